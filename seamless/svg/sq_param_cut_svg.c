/* seamquad: a picture of the cut on the surface (issue 4, outputs): the
 * input mesh in three orthographic views (front, side, and from the
 * (1, 1, 1) direction), shaded by a light from the viewer's upper left
 * and drawn back to front, with
 * the seams of the map (the cut graph and the cone tree: he_cut 1) on it,
 * the cones by valence and the seams' branch points. A seam segment is
 * drawn after the triangles up to half its length in front of it, so
 * nearer parts of the surface hide it as they hide the surface; cones and branch points are
 * drawn on top (also where hidden: no depth test for points). The library
 * never prints or exits. */
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

#define VIEW 420.0   /* pixels per view                                  */
#define GAP 20.0
#define TOP 40.0
#define LEGEND 44.0

typedef struct item {
    double depth;
    uint32_t index;  /* an input face, or nf_in + a seam halfedge of P   */
} item;

static int item_cmp(const void *x, const void *y)
{
    const item *a = x, *b = y;
    return a->depth < b->depth ? -1 : a->depth > b->depth ? 1 : (a->index > b->index) - (a->index < b->index);
}

/* View k: screen right r, screen up u, towards the viewer d. */
#define R2 0.70710678118654752
#define R3 0.57735026918962576
#define R6 0.40824829046386302
static const double AXES[3][3][3] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},                          /* front: along -z   */
    {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},                         /* side: along -x    */
    {{R2, 0, -R2}, {-R6, 2 * R6, -R6}, {R3, R3, R3}},           /* along -(1, 1, 1)  */
};
static const char *VIEW_NAME[3] = {"front (x right, y up)", "side (-z right, y up)",
                                   "from (1, 1, 1) (y up)"};

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The corner positions of input face f. */
static void face_corners(const sq_mesh *m, uint32_t f, const double **p0, const double **p1, const double **p2)
{
    uint32_t h = m->f_he[f];
    *p0 = m->pos + 3 * (size_t)m->he_vert[h];
    *p1 = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
    *p2 = m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]];
}

sq_status sq_param_write_cut_svg(const char *path, const sq_mesh *m, const sq_param *P, sq_error *err)
{
    if (!path || !m || !P) return sq_error_set(err, SQ_ERR_ARGUMENT, "cut SVG: NULL argument");
    if (!P->he_cut || P->nv_input != m->nv || P->nv < P->nv_input)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cut SVG: the map is not of this mesh (%u input vertices, the mesh has %u)",
                            P->nv_input, m->nv);
    /* the seams, each edge once (from its lower vertex) */
    uint32_t nseam = 0;
    for (uint32_t k = 0; k < 3 * P->nf; k++) {
        uint32_t a = P->tri[k], b = P->tri[sq_param_corner_next(k)];
        if (P->he_cut[k] == 1 && a < b) nseam++;
    }
    const uint32_t n = m->nf + nseam;
    item *it = malloc(((size_t)n + 1) * sizeof *it);
    uint32_t *seam = malloc(((size_t)nseam + 1) * sizeof *seam);
    uint32_t *deg = calloc((size_t)P->nv + 1, sizeof *deg);
    double *nrm = malloc(3 * ((size_t)m->nf + 1) * sizeof *nrm);
    if (!it || !seam || !deg || !nrm) {
        free(it), free(seam), free(deg), free(nrm);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    nseam = 0;
    for (uint32_t k = 0; k < 3 * P->nf; k++) {
        uint32_t a = P->tri[k], b = P->tri[sq_param_corner_next(k)];
        if (P->he_cut[k] == 1 && a < b) seam[nseam++] = k, deg[a]++, deg[b]++;
    }
    /* the bounding box's extent (a depth offset for the seams) */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m->nv; v++)
        for (int d = 0; d < 3; d++) {
            double x = m->pos[3 * (size_t)v + d];
            lo[d] = x < lo[d] ? x : lo[d], hi[d] = x > hi[d] ? x : hi[d];
        }
    double ext = 0;
    for (int d = 0; d < 3; d++) ext = hi[d] - lo[d] > ext ? hi[d] - lo[d] : ext;
    /* each view centred on its projected box; one scale that fits them all */
    double cr[3], cu[3], big = 0;
    for (int k = 0; k < 3; k++) {
        double r0 = INFINITY, r1 = -INFINITY, u0 = INFINITY, u1 = -INFINITY;
        for (uint32_t v = 0; v < m->nv; v++) {
            const double *p = m->pos + 3 * (size_t)v;
            double x = dot(p, AXES[k][0]), y = dot(p, AXES[k][1]);
            r0 = x < r0 ? x : r0, r1 = x > r1 ? x : r1, u0 = y < u0 ? y : u0, u1 = y > u1 ? y : u1;
        }
        cr[k] = (r0 + r1) / 2, cu[k] = (u0 + u1) / 2;
        big = r1 - r0 > big ? r1 - r0 : big, big = u1 - u0 > big ? u1 - u0 : big;
    }
    const double s = (VIEW - 2 * GAP) / (big > 0 ? big : 1);
    for (uint32_t f = 0; f < m->nf; f++) {
        const double *p0, *p1, *p2;
        face_corners(m, f, &p0, &p1, &p2);
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double *q = nrm + 3 * (size_t)f;
        q[0] = e1[1] * e2[2] - e1[2] * e2[1], q[1] = e1[2] * e2[0] - e1[0] * e2[2], q[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double l = sqrt(dot(q, q));
        if (l > 0) q[0] /= l, q[1] /= l, q[2] /= l;
    }
    uint32_t ncone = 0, nbranch = 0;
    for (uint32_t v = 0; v < P->nv_input; v++) ncone += P->valence && P->valence[v] != 4;
    for (uint32_t v = 0; v < P->nv; v++) nbranch += deg[v] >= 3;
    const double W = 3 * VIEW, H = TOP + VIEW + LEGEND;
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) goto done;
    FILE *out = af.fp;
    fprintf(out, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                 "font-family=\"sans-serif\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            W, H, W, H);
    fprintf(out, "<text x=\"%.0f\" y=\"22\" font-size=\"13\">The cut on the surface: %" PRIu32 " triangles, %" PRIu32
                 " seam edges (cut graph and cone tree), %" PRIu32 " cones, %" PRIu32 " branch points</text>\n",
            GAP, m->nf, nseam, ncone, nbranch);
    for (int k = 0; k < 3 && !ferror(out); k++) {
        const double *r = AXES[k][0], *u = AXES[k][1], *d = AXES[k][2];
        const double x0 = k * VIEW + VIEW / 2, y0 = TOP + VIEW / 2;
        /* light from the viewer's upper left, so that faces at the same
         * angle to the view still differ */
        double light[3];
        for (int i = 0; i < 3; i++) light[i] = 0.8 * d[i] + 0.45 * u[i] - 0.4 * r[i];
        {
            double l = sqrt(dot(light, light));
            for (int i = 0; i < 3; i++) light[i] /= l;
        }
#define PX(p) (x0 + s * (dot(p, r) - cr[k]))
#define PY(p) (y0 - s * (dot(p, u) - cu[k]))
        for (uint32_t f = 0; f < m->nf; f++) {
            const double *p0, *p1, *p2;
            face_corners(m, f, &p0, &p1, &p2);
            it[f] = (item){(dot(p0, d) + dot(p1, d) + dot(p2, d)) / 3, f};
        }
        for (uint32_t i = 0; i < nseam; i++) {
            uint32_t e = seam[i];
            const double *a = P->pos + 3 * (size_t)P->tri[e], *b = P->pos + 3 * (size_t)P->tri[sq_param_corner_next(e)];
            /* in front of the triangles around it (their centroids lie
             * within about an edge length of its midpoint), behind the
             * surface further in front */
            double len = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            it[m->nf + i] = (item){(dot(a, d) + dot(b, d)) / 2 + 0.5 * len + 1e-6 * ext, m->nf + i};
        }
        qsort(it, n, sizeof *it, item_cmp);
        fprintf(out, "<g stroke-linejoin=\"round\">\n");
        for (uint32_t i = 0; i < n && !ferror(out); i++) {
            uint32_t x = it[i].index;
            if (x < m->nf) {
                const double *p0, *p1, *p2;
                face_corners(m, x, &p0, &p1, &p2);
                int g = (int)(70 + 170 * fabs(dot(nrm + 3 * (size_t)x, light)));
                fprintf(out, "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fz\" fill=\"#%02x%02x%02x\" stroke=\"#%02x%02x%02x\" "
                             "stroke-width=\"1\"/>\n",
                        PX(p0), PY(p0), PX(p1), PY(p1), PX(p2), PY(p2), g, g, g, g, g, g);
            } else {
                uint32_t e = seam[x - m->nf];
                const double *a = P->pos + 3 * (size_t)P->tri[e], *b = P->pos + 3 * (size_t)P->tri[sq_param_corner_next(e)];
                fprintf(out, "<path d=\"M%.1f %.1fL%.1f %.1f\" stroke=\"#d7191c\" stroke-width=\"1.6\" "
                             "stroke-linecap=\"round\"/>\n",
                        PX(a), PY(a), PX(b), PY(b));
            }
        }
        fprintf(out, "</g>\n<g stroke=\"black\" stroke-width=\"0.5\">\n");
        for (uint32_t v = 0; v < P->nv && !ferror(out); v++) {
            const double *p = P->pos + 3 * (size_t)v;
            if (v < P->nv_input && P->valence && P->valence[v] != 4)
                fprintf(out, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"><title>cone vertex %" PRIu32
                             ", valence %" PRId32 "</title></circle>\n",
                        PX(p), PY(p), sq_param_valence_colour(P->valence[v]), v, P->valence[v]);
            else if (deg[v] >= 3)
                fprintf(out, "<rect x=\"%.1f\" y=\"%.1f\" width=\"5\" height=\"5\" fill=\"black\"><title>branch "
                             "vertex %" PRIu32 " (%" PRIu32 " seam edges)</title></rect>\n",
                        PX(p) - 2.5, PY(p) - 2.5, v, deg[v]);
        }
        fprintf(out, "</g>\n<text x=\"%.0f\" y=\"%.0f\" font-size=\"11\">%s</text>\n", k * VIEW + GAP, TOP + VIEW - 4,
                VIEW_NAME[k]);
#undef PX
#undef PY
    }
    fprintf(out, "<text x=\"%.0f\" y=\"%.0f\" font-size=\"11\">grey: the input triangles, lighter where they face "
                 "the viewer; red: seams (the cut graph and the cone tree, where the map's two sides meet), hidden "
                 "where the surface is in front</text>\n",
            GAP, H - LEGEND + 16);
    fprintf(out, "<text x=\"%.0f\" y=\"%.0f\" font-size=\"11\">dots: cones by valence (as in the UV picture); "
                 "black squares: branch points of the seams; both drawn on top, also where hidden</text>\n",
            GAP, H - LEGEND + 32);
    fprintf(out, "</svg>\n");
    st = sq_atomic_commit(&af, err);
done:
    free(it), free(seam), free(deg), free(nrm);
    return st;
}
