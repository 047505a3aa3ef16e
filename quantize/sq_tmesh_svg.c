/* seamquad: SVG of a T-mesh over the UV layout of its map (sq_tmesh.h).
 *
 * Every mesh triangle is drawn in its own chart (grey; inner edges only
 * below a size limit), every arc as the polyline of its pieces in their
 * charts (one colour per arc from a small palette, so neighbouring arcs
 * differ; an arc crossing a seam jumps with the layout), cones as red dots
 * and the other nodes (T-junctions) as small blue ones, each copy of a
 * vertex node at every corner of the vertex. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sq_io.h"
#include "sq_tmesh_internal.h"

#define SVG_SIZE 900.0
#define SVG_MARGIN 20.0
#define SVG_TOP 30.0
#define SVG_MAX_FACES_FOR_EDGES 20000u

typedef struct frame {
    double s, x0, y1;
} frame;

static double sx(const frame *F, const double *p) { return SVG_MARGIN + (p[0] - F->x0) * F->s; }
static double sy(const frame *F, const double *p) { return SVG_TOP + SVG_MARGIN + (F->y1 - p[1]) * F->s; }

static void end_uv(const sq_map *M, const sq_tmesh_piece *P, const sq_tmesh_end *e, double out[2])
{
    if (e->kind == SQ_TMESH_AT_VERTEX) {
        uint32_t h = sq_tmesh_corner(M, P->face, e->id);
        if (h != TM_NONE) {
            out[0] = tm_uv(M, h)[0], out[1] = tm_uv(M, h)[1];
            return;
        }
    }
    out[tm_rc(P->dir)] = e->s, out[tm_cc(P->dir)] = P->c;
}

sq_status sq_tmesh_write_svg(const char *path, const sq_map *M, const sq_tmesh *T, sq_error *err)
{
    static const char *palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b",
                                    "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#d62728"};
    const sq_mesh *m = &M->mesh;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t h = 0; h < m->nh; h++)
        for (int k = 0; k < 2; k++) lo[k] = fmin(lo[k], tm_uv(M, h)[k]), hi[k] = fmax(hi[k], tm_uv(M, h)[k]);
    double w = hi[0] - lo[0], hh = hi[1] - lo[1], big = w > hh ? w : hh;
    frame F = {SVG_SIZE / (big > 0 ? big : 1), lo[0], hi[1]};
    double W = 2 * SVG_MARGIN + w * F.s, H = SVG_TOP + 2 * SVG_MARGIN + hh * F.s;
    if (W < 600) W = 600;
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *f = af.fp;
    uint32_t cones = 0;
    for (uint32_t n = 0; n < T->n_nodes; n++)
        cones += T->nodes[n].kind == SQ_TMESH_AT_VERTEX && T->nodes[n].valence != 4;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
               "font-family=\"sans-serif\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            W, H, W, H);
    fprintf(f, "<text x=\"%.0f\" y=\"20\" font-size=\"13\">T-mesh: %u nodes (%u cones), %u arcs, %u faces over the "
               "UV layout (%u triangles)</text>\n",
            SVG_MARGIN, T->n_nodes, cones, T->n_arcs, T->n_faces, m->nf);
    fprintf(f, "<path fill=\"none\" stroke=\"#c8c8c8\" stroke-width=\"0.3\" d=\"");
    for (uint32_t h = 0; h < m->nh && !ferror(f); h++) {
        /* all edges of small maps; seams (either side) of large ones */
        const double *a = tm_uv(M, h), *b = tm_uv(M, tm_next(M, h));
        uint32_t t = m->he_twin[h];
        int seam = M->he_rot[h] != 0 || M->he_t[2 * h] != 0 || M->he_t[2 * h + 1] != 0;
        if (!seam && (m->nf > SVG_MAX_FACES_FOR_EDGES || t < h)) continue;
        fprintf(f, "M%.2f %.2fL%.2f %.2f", sx(&F, a), sy(&F, a), sx(&F, b), sy(&F, b));
    }
    fprintf(f, "\"/>\n<g fill=\"none\" stroke-width=\"1.4\" stroke-linecap=\"round\">\n");
    for (uint32_t a = 0; a < T->n_arcs && !ferror(f); a++) {
        const sq_tmesh_arc *A = &T->arcs[a];
        fprintf(f, "<path stroke=\"%s\" d=\"", palette[a % (sizeof palette / sizeof *palette)]);
        for (uint32_t i = 0; i < A->piece_count; i++) {
            const sq_tmesh_piece *P = &T->pieces[A->piece_off + i];
            double p[2], q[2];
            end_uv(M, P, &P->from, p);
            end_uv(M, P, &P->to, q);
            fprintf(f, "M%.2f %.2fL%.2f %.2f", sx(&F, p), sy(&F, p), sx(&F, q), sy(&F, q));
        }
        fprintf(f, "\"><title>arc %u: nodes %u to %u, length %.6g (%.4g on the surface)</title></path>\n", a,
                A->node[0], A->node[1], A->length, A->length3d);
    }
    fprintf(f, "</g>\n<g stroke=\"black\" stroke-width=\"0.4\">\n");
    for (uint32_t n = 0; n < T->n_nodes && !ferror(f); n++) {
        const sq_tmesh_node *N = &T->nodes[n];
        int cone = N->kind == SQ_TMESH_AT_VERTEX && N->valence != 4;
        if (N->kind == SQ_TMESH_AT_VERTEX) {
            /* one dot per distinct corner UV of the vertex */
            uint32_t h0 = m->v_he[N->id], h = h0, guard = 0;
            do {
                const double *p = tm_uv(M, h);
                fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%s\" fill=\"%s\"><title>node %u: vertex %u, valence "
                           "%d</title></circle>\n",
                        sx(&F, p), sy(&F, p), cone ? "3.5" : "2", cone ? "#d62728" : "#1f4fd0", n, N->id,
                        N->valence);
                h = m->he_twin[tm_prev(M, h)];
            } while (h != h0 && ++guard < 64);
        } else {
            double p[2] = {N->uv[0], N->uv[1]};
            fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2\" fill=\"#1f4fd0\"><title>node %u: %s %u, "
                       "(%.6g, %.6g)</title></circle>\n",
                    sx(&F, p), sy(&F, p), n, N->kind == SQ_TMESH_ON_EDGE ? "on edge" : "in face", N->id, p[0], p[1]);
        }
    }
    fprintf(f, "</g>\n</svg>\n");
    return sq_atomic_commit(&af, err);
}
