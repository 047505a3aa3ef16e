/* seamquad: SVG picture of a seamless domain (seed Fig. 3, 7, 8).
 *
 * Left: the metapolygon P, faces coloured by valence, corners marked.
 * Right: the padded quad disk Q in a Tutte layout with its boundary on a
 * circle (seed Fig. 8 c, d): quads subdividing P coloured by the valence of
 * their metapolygon face, padding quads green, every side drawn in the
 * colour of its pair with its length, corners and cones marked. */
#include "sq_domain.h"
#include "sq_seamless_svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sq_disk_layout.h"
#include "sq_io.h"

#define PANEL 480.0
#define MARGIN 40.0

static const char *valence_fill(uint32_t k)
{
    switch (k) {
    case 2: return "#b2182b";
    case 3: return "#ef8a62";
    case 4: return "#f4f4f4";
    case 5: return "#67a9cf";
    case 6: return "#2166ac";
    case 7: return "#5e3c99";
    default: return k < 4 ? "#67001f" : "#053061";
    }
}

static const char *pair_colour(uint32_t p)
{
    static const char *c[] = {"#e41a1c", "#377eb8", "#4daf4a", "#984ea3", "#ff7f00",
                              "#a65628", "#f781bf", "#999999", "#66c2a5", "#fc8d62",
                              "#8da0cb", "#e78ac3", "#a6d854", "#e5c494"};
    return c[p % (sizeof c / sizeof c[0])];
}

static void pt(FILE *f, const double *xy, uint32_t v, double ox)
{
    fprintf(f, "%.2f,%.2f ", ox + MARGIN + (xy[2 * v] + 1) * 0.5 * PANEL,
            MARGIN + (1 - xy[2 * v + 1]) * 0.5 * PANEL);
}

static void face_poly(FILE *f, const sq_metapolygon *P, const double *xy, uint32_t face,
                      double ox, const char *fill, const char *stroke, double width)
{
    fprintf(f, "<polygon points=\"");
    uint32_t h0 = P->f_he[face], h = h0;
    do {
        pt(f, xy, P->he_vert[h], ox);
        h = P->he_next[h];
    } while (h != h0);
    fprintf(f, "\" fill=\"%s\" stroke=\"%s\" stroke-width=\"%.2f\"/>\n", fill, stroke, width);
}

static void dot(FILE *f, const double *xy, uint32_t v, double ox, double r, const char *fill)
{
    fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.1f\" fill=\"%s\" stroke=\"black\" "
               "stroke-width=\"0.5\"/>\n",
            ox + MARGIN + (xy[2 * v] + 1) * 0.5 * PANEL, MARGIN + (1 - xy[2 * v + 1]) * 0.5 * PANEL,
            r, fill);
}

sq_status sq_domain_write_svg(const sq_domain *D, const double *qxy_given, const char *path,
                              sq_error *err)
{
    const sq_metapolygon *P = &D->meta, *Q = &D->quads;
    double *pxy = malloc(2 * (size_t)P->nv * sizeof *pxy);
    double *qxy_own = qxy_given ? NULL : malloc(2 * (size_t)Q->nv * sizeof *qxy_own);
    const double *qxy = qxy_given ? qxy_given : qxy_own;
    uint32_t *pair = malloc((size_t)D->k * sizeof *pair);
    if (!pxy || !qxy || !pair) {
        free(pxy), free(qxy_own), free(pair);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    sq_status st = sq_disk_layout_tutte(P, SQ_NONE, pxy, err);
    /* genus 0: Q is the sphere cut along one edge, drawn as a planar map
     * of the sphere with one quad as the unbounded face (not drawn) */
    const int sphere = Q->nbnd <= 2;
    const uint32_t outer = sphere ? sq_disk_layout_sphere_outer(Q) : SQ_NONE;
    if (st == SQ_OK && qxy_own)
        st = sphere ? sq_disk_layout_sphere(Q, outer, qxy_own, err)
                    : sq_disk_layout_tutte(Q, Q->v_he[D->corner_vert[0]], qxy_own, err);
    sq_atomic_file af;
    if (st == SQ_OK) st = sq_atomic_open(&af, path, err);
    if (st) {
        free(pxy), free(qxy_own), free(pair);
        return st;
    }
    FILE *f = af.fp;
    double W = 2 * (PANEL + 2 * MARGIN), H = PANEL + 2 * MARGIN + 40;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n",
            W, H, W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    fprintf(f, "<text x=\"%.0f\" y=\"22\" font-size=\"15\">metapolygon P: %u faces, %u "
               "corners</text>\n",
            MARGIN, P->nf, D->k);
    fprintf(f, "<text x=\"%.0f\" y=\"22\" font-size=\"15\">padded disk Q: %llu + %llu "
               "quads, genus %u%s</text>\n",
            PANEL + 3 * MARGIN, (unsigned long long)D->quads_unpadded,
            (unsigned long long)D->quads_added, D->genus,
            sphere ? " (a sphere cut along one edge: one quad is the outer face)" : "");

    /* left panel: P */
    fprintf(f, "<g>\n");
    for (uint32_t face = 0; face < P->nf; face++)
        face_poly(f, P, pxy, face, 0, valence_fill(P->f_valence[face]), "black", 0.6);
    for (uint32_t v = 0; v < P->nv; v++)
        if (P->v_nface[v] == 1 && P->he_face[P->v_he[v]] == SQ_NONE) dot(f, pxy, v, 0, 4, "#ffd700");
    fprintf(f, "</g>\n");

    /* right panel: Q */
    const double ox = PANEL + 2 * MARGIN;
    double width = Q->nf > 20000 ? 0.05 : Q->nf > 2000 ? 0.15 : 0.4;
    fprintf(f, "<g>\n");
    for (uint32_t face = 0; face < Q->nf; face++) {
        if (face == outer) continue;
        /* faces: the first piece's subdivision (by valence), the other
         * pieces' subdivision (genus 0 and 1, light blue), padding (green) */
        const char *fill = face < D->nf_unpadded ? valence_fill(P->f_valence[D->f_meta_face[face]])
                           : face < D->quads_unpadded ? "#c6dbef"
                                                      : "#b8e186";
        face_poly(f, Q, qxy, face, ox, fill, "#555555", width);
    }
    /* sides by pair */
    uint32_t np = 0;
    for (uint32_t i = 0; i < D->k; i++) pair[i] = SQ_NONE;
    for (uint32_t i = 0; i < D->k; i++)
        if (pair[i] == SQ_NONE) pair[i] = pair[D->pattern.partner[i]] = np++;
    for (uint32_t i = 0; i < D->k; i++) {
        uint32_t h = Q->v_he[D->corner_vert[i]];
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"3\" points=\"",
                pair_colour(pair[i]));
        for (uint32_t t = 0; t <= D->side_len[i]; t++) {
            pt(f, qxy, Q->he_vert[h], ox);
            h = Q->he_next[h];
        }
        fprintf(f, "\"/>\n");
        /* label: side index, pair and length, outside the circle */
        uint32_t mid = D->corner_vert[i];
        h = Q->v_he[mid];
        for (uint32_t t = 0; t < D->side_len[i] / 2; t++) h = Q->he_next[h];
        mid = Q->he_vert[h];
        double x = qxy[2 * mid] * 1.1, y = qxy[2 * mid + 1] * 1.1;
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" text-anchor=\"middle\" "
                   "fill=\"%s\">%u:%u</text>\n",
                ox + MARGIN + (x + 1) * 0.5 * PANEL, MARGIN + (1 - y) * 0.5 * PANEL,
                pair_colour(pair[i]), i, D->side_len[i]);
    }
    for (uint32_t i = 0; i < D->k; i++) dot(f, qxy, D->corner_vert[i], ox, 4, "#ffd700");
    /* cones: interior vertices of valence != 4 */
    for (uint32_t v = 0; v < Q->nv; v++) {
        if (Q->he_face[Q->v_he[v]] == SQ_NONE || Q->v_nface[v] == 4) continue;
        dot(f, qxy, v, ox, 3.5, valence_fill(Q->v_nface[v]));
    }
    fprintf(f, "</g>\n");
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" font-size=\"12\">faces by valence: 2, 3 warm; 4 "
               "grey; 5, 6, 7 cool; other pieces light blue. Sides labelled side:length, one "
               "colour per pair; yellow: corners; dots: cones; green: padding</text>\n",
            MARGIN, H - 14);
    fprintf(f, "</svg>\n");
    free(pxy), free(qxy_own), free(pair);
    return sq_atomic_commit(&af, err);
}
