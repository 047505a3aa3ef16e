/* seamquad: SVG picture of the flat domain Omega (seed Fig. 1 centre,
 * Fig. 2 d, Fig. 11): the exact integer layout, quads light, the boundary
 * polygon with Q's sides in one colour per identified pair and both sides
 * of the cone tree highlighted, cone copies coloured by valence, branch
 * points (copies of Q's corners: the corner classes) and the root marked.
 * Omega may overlap itself (weakly self-overlapping, seed 3): quads are
 * drawn translucent so overlaps show. */
#include <stdio.h>
#include <stdlib.h>

#include "sq_io.h"
#include "sq_omega.h"
#include "sq_seamless_svg.h"

#define SIZE 900.0
#define MARGIN 30.0
#define TITLE 30.0

static const char *pair_colour(uint32_t p)
{
    static const char *c[] = {"#1f78b4", "#33a02c", "#6a3d9a", "#b15928", "#a6cee3",
                              "#b2df8a", "#cab2d6", "#fdbf6f", "#66c2a5", "#8da0cb",
                              "#a6d854", "#e5c494", "#377eb8", "#4daf4a"};
    return c[p % (sizeof c / sizeof c[0])];
}

static const char *valence_fill(uint32_t k)
{
    switch (k) {
    case 2: return "#b2182b";
    case 3: return "#ef8a62";
    case 5: return "#67a9cf";
    case 6: return "#2166ac";
    case 7: return "#5e3c99";
    default: return k < 4 ? "#67001f" : "#053061";
    }
}

typedef struct frame {
    double s, x0, y1;
} frame;

static double X(const frame *F, int64_t x) { return MARGIN + (double)(x - F->x0) * F->s; }
static double Y(const frame *F, int64_t y) { return TITLE + MARGIN + (double)(F->y1 - y) * F->s; }

sq_status sq_omega_write_svg(const sq_domain *D, const sq_cone_tree *T, const sq_omega *O,
                             const char *path, sq_error *err)
{
    const sq_metapolygon *Q = &D->quads, *C = &O->cut;
    if (!O->xy) return sq_error_set(err, SQ_ERR_ARGUMENT, "omega svg: Omega is not laid out");
    uint8_t *kind = calloc(Q->nv ? Q->nv : 1, 1); /* 1 corner, 2 cone, 4 root */
    if (!kind) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t i = 0; i < D->k; i++) kind[D->corner_vert[i]] |= 1;
    for (uint32_t i = 0; i < T->nverts; i++)
        if (T->node[i] & SQ_TREE_CONE) kind[T->vert[i]] |= 2;
    if (T->root < Q->nv) kind[T->root] |= 4;

    double w = (double)(O->xmax - O->xmin), h = (double)(O->ymax - O->ymin);
    frame F;
    F.s = SIZE / (w > h ? (w > 0 ? w : 1) : (h > 0 ? h : 1));
    if (F.s > 40) F.s = 40;
    F.x0 = (double)O->xmin;
    F.y1 = (double)O->ymax;
    double W = 2 * MARGIN + w * F.s, H = TITLE + 2 * MARGIN + h * F.s + 20;
    if (W < 720) W = 720;

    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) {
        free(kind);
        return st;
    }
    FILE *f = af.fp;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n",
            W, H, W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    fprintf(f, "<text x=\"%.0f\" y=\"22\" font-size=\"13\">Omega: %u quads, genus %u, %u sides, "
               "cone tree %u edges / %u segments, %lld x %lld</text>\n",
            MARGIN, C->nf, D->genus, D->k, T->nedges, T->nseg,
            (long long)(O->xmax - O->xmin), (long long)(O->ymax - O->ymin));

    double lw = F.s > 8 ? 0.5 : 0.2;
    fprintf(f, "<g fill=\"#c6dbef\" fill-opacity=\"0.45\" stroke=\"#9e9e9e\" "
               "stroke-width=\"%.2f\">\n",
            lw);
    for (uint32_t face = 0; face < C->nf; face++) {
        uint32_t e = C->f_he[face];
        fprintf(f, "<polygon points=\"");
        for (uint32_t i = 0; i < C->f_valence[face]; i++, e = C->he_next[e]) {
            uint32_t v = C->he_vert[e];
            fprintf(f, "%.2f,%.2f ", X(&F, O->xy[2 * v]), Y(&F, O->xy[2 * v + 1]));
        }
        fprintf(f, "\"/>\n");
    }
    fprintf(f, "</g>\n<g stroke-linecap=\"round\">\n");
    for (uint32_t b = 0; b < C->nh; b++) {
        if (C->he_face[b] != SQ_NONE) continue;
        uint32_t l = O->he_label[b], a = C->he_vert[b], z = C->he_vert[C->he_next[b]];
        const char *col;
        double sw;
        uint32_t side = O->label_side[l];
        if (side != SQ_NONE) {
            uint32_t j = D->pattern.partner[side];
            col = pair_colour(side < j ? side : j);
            sw = 2.5;
        } else {
            col = "#e7298a"; /* the cone tree, both sides */
            sw = 3.0;
        }
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" "
                   "stroke-width=\"%.1f\"/>\n",
                X(&F, O->xy[2 * a]), Y(&F, O->xy[2 * a + 1]), X(&F, O->xy[2 * z]),
                Y(&F, O->xy[2 * z + 1]), col, sw);
    }
    fprintf(f, "</g>\n<g stroke=\"black\" stroke-width=\"0.6\">\n");
    for (uint32_t v = 0; v < C->nv; v++) {
        uint32_t q = O->v_qvert[v];
        double x = X(&F, O->xy[2 * v]), y = Y(&F, O->xy[2 * v + 1]);
        if (kind[q] & 2)
            fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4.5\" fill=\"%s\"><title>cone %u, "
                       "valence %u, copy angle %u x 90</title></circle>\n",
                    x, y, valence_fill(Q->v_nface[q]), q, Q->v_nface[q], C->v_nface[v]);
        if (kind[q] & 1)
            fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"7\" height=\"7\" fill=\"#ffd700\">"
                       "<title>branch point (corner of Q, vertex %u)</title></rect>\n",
                    x - 3.5, y - 3.5, q);
        if (kind[q] & 4)
            fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"#1b9e77\"><title>tree "
                       "root (vertex %u)</title></circle>\n",
                    x, y, q);
    }
    fprintf(f, "</g>\n");
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" font-size=\"10\">sides: one colour per identified "
               "pair; magenta: both sides of the cone tree; dots: cone copies (warm: valence "
               "&lt; 4, cool: &gt; 4); yellow: branch points; green: root</text>\n",
            MARGIN, H - 8);
    fprintf(f, "</svg>\n");
    free(kind);
    return sq_atomic_commit(&af, err);
}
