/* seamquad: the picture of a seamless parametrization (sq_param.h,
 * sq_param_write_svg): the UV layout, seams in one colour per seam curve,
 * cones coloured by valence. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_param.h"
#include "sq_seamless_svg.h"
#include "sq_param_internal.h"

static const double *UV(const sq_param *P, uint32_t t) { return P->uv + 2 * (size_t)t; }

#define SVG_SIZE 1000.0
#define SVG_MARGIN 20.0
#define SVG_TOP 34.0
#define SVG_LEGEND 46.0
#define SVG_MAX_FACES_FOR_EDGES 200000u

static const char *curve_colour(uint32_t i)
{
    static const char *c[] = {"#e41a1c", "#377eb8", "#4daf4a", "#984ea3", "#ff7f00", "#a65628",
                              "#f781bf", "#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e",
                              "#e6ab02", "#17becf"};
    return c[i % (sizeof c / sizeof c[0])];
}

const char *sq_param_valence_colour(int32_t k)
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

typedef struct svg_frame {
    double s, u0, v1;
} svg_frame;

static double SX(const svg_frame *F, const double *p) { return SVG_MARGIN + (p[0] - F->u0) * F->s; }
static double SY(const svg_frame *F, const double *p)
{
    return SVG_TOP + SVG_MARGIN + (F->v1 - p[1]) * F->s;
}

sq_status sq_param_write_svg(const char *path, const sq_param *P, sq_error *err)
{
    if (!path) return sq_error_set(err, SQ_ERR_ARGUMENT, "parametrization SVG: NULL path");
    sq_status st = sq_param_check_arrays(P, path, err);
    if (st) return st;
    sq_mesh m;
    st = sq_param_mesh(P, path, &m, err);
    if (st) return st;
    sq_param_seam_curves C;
    uint8_t *seen = NULL;
    st = sq_param_seam_curves_find(&m, P, &C, err);
    if (st) {
        sq_mesh_free(&m);
        return st;
    }
    seen = calloc(P->nuv, 1);
    if (!seen) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t c = 0; c < m.nh; c++) {
        const double *p = UV(P, P->tri_uv[c]);
        for (int k = 0; k < 2; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
    }
    double w = hi[0] - lo[0], h = hi[1] - lo[1], big = w > h ? w : h;
    svg_frame F = {SVG_SIZE / (big > 0 ? big : 1), lo[0], hi[1]};
    double W = 2 * SVG_MARGIN + w * F.s, H = SVG_TOP + 2 * SVG_MARGIN + h * F.s + SVG_LEGEND;
    if (W < 760) W = 760;
    uint32_t nseam = 0, ncone = 0, hist[9] = {0};
    for (uint32_t e = 0; e < m.nh; e++)
        if (C.curve[e] != SQ_NONE && e < m.he_twin[e]) nseam++;
    if (P->valence)
        for (uint32_t v = 0; v < P->nv_input; v++)
            if (P->valence[v] != 4) {
                ncone++;
                hist[P->valence[v] < 1 ? 0 : P->valence[v] < 8 ? P->valence[v] : 8]++;
            }
    int edges = P->nf <= SVG_MAX_FACES_FOR_EDGES;

    sq_atomic_file af;
    st = sq_atomic_open(&af, path, err);
    if (st) goto done;
    FILE *f = af.fp;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n",
            W, H, W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    fprintf(f, "<text x=\"%.0f\" y=\"22\" font-size=\"13\">UV layout: %" PRIu32 " triangles, %" PRIu32
               " UV points, %" PRIu32 " seam edges in %" PRIu32 " seam curves, %" PRIu32
               " cones; %.6g x %.6g grid units%s</text>\n",
            SVG_MARGIN, P->nf, P->nuv, nseam, C.n, ncone, w, h,
            edges ? "" : " (inner edges not drawn: too many faces)");
    /* inner edges: one thin path, each edge once */
    if (edges) {
        fprintf(f, "<path fill=\"none\" stroke=\"#b0b0b0\" stroke-width=\"0.25\" d=\"");
        for (uint32_t e = 0; e < m.nh && !ferror(f); e++) {
            if (C.curve[e] != SQ_NONE || e > m.he_twin[e]) continue;
            const double *a = UV(P, P->tri_uv[e]), *b = UV(P, P->tri_uv[m.he_next[e]]);
            fprintf(f, "M%.2f %.2fL%.2f %.2f", SX(&F, a), SY(&F, a), SX(&F, b), SY(&F, b));
        }
        fprintf(f, "\"/>\n");
    }
    /* seams: both sides of a curve in the curve's colour */
    fprintf(f, "<g fill=\"none\" stroke-width=\"1.6\" stroke-linecap=\"round\">\n");
    for (uint32_t i = 0; i < C.n && !ferror(f); i++) {
        fprintf(f, "<path stroke=\"%s\" d=\"", curve_colour(i));
        for (int side = 0; side < 2; side++) {
            uint32_t h0 = C.first[i], hh = h0, steps = 0;
            for (;;) {
                uint32_t e = side ? m.he_twin[hh] : hh;
                const double *a = UV(P, P->tri_uv[e]), *b = UV(P, P->tri_uv[m.he_next[e]]);
                fprintf(f, "M%.2f %.2fL%.2f %.2f", SX(&F, a), SY(&F, a), SX(&F, b), SY(&F, b));
                if (++steps > m.nh) break;
                uint32_t y = sq_param_he_dst(&m, hh);
                if (sq_param_seam_node(&C, P, y)) break;
                uint32_t g = sq_param_seam_next_out(&m, &C, hh);
                if (g == SQ_NONE || g == h0 || C.curve[g] != i || !C.dir[g]) break;
                hh = g;
            }
        }
        fprintf(f, "\"><title>seam curve %" PRIu32 " from vertex %" PRIu32 "</title></path>\n", i,
                m.he_vert[C.first[i]]);
    }
    fprintf(f, "</g>\n<g stroke=\"black\" stroke-width=\"0.5\">\n");
    for (uint32_t c = 0; c < m.nh && !ferror(f); c++) {
        uint32_t v = P->tri[c], t = P->tri_uv[c];
        if (!sq_param_is_cone(P, v) || seen[t]) continue;
        seen[t] = 1;
        const double *p = UV(P, t);
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"><title>cone vertex %" PRIu32
                   ", valence %" PRId32 ", at (%.6g, %.6g)</title></circle>\n",
                SX(&F, p), SY(&F, p), sq_param_valence_colour(P->valence[v]), v, P->valence[v], p[0], p[1]);
    }
    fprintf(f, "</g>\n");
    /* legend */
    double x = SVG_MARGIN, y = H - SVG_LEGEND + 14;
    fprintf(f, "<g font-size=\"11\">\n");
    for (int32_t k = 1; k <= 8; k++) {
        if (!hist[k] || k == 4) continue;
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"%s\" stroke=\"black\" "
                   "stroke-width=\"0.5\"/><text x=\"%.0f\" y=\"%.0f\">valence %s%" PRId32
                   ": %" PRIu32 "</text>\n",
                x + 4, y - 4, sq_param_valence_colour(k), x + 12, y, k == 8 ? "&gt;=" : "", k, hist[k]);
        x += 110;
    }
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\">grey: triangles; coloured: seams, one colour per seam "
               "curve, the same on both of its sides (the two copies are related by a rotation "
               "by k x 90 degrees plus a translation); dots: UV copies of cones</text>\n",
            SVG_MARGIN, y + 20);
    fprintf(f, "</g>\n</svg>\n");
    st = sq_atomic_commit(&af, err);
done:
    free(seen);
    sq_param_seam_curves_free(&C);
    sq_mesh_free(&m);
    return st;
}
