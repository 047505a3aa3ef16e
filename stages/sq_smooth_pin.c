/* seamquad: where the quads miss the surface, for the smoother's fidelity
 * pins (docs/smooth.md, "Fidelity").
 *
 * Every vertex of the quads lies on the surface, but their faces are
 * chords: where the surface turns sharply (a horn's tip, a crease, a corner
 * of a coarse input) a surface vertex can lie far from the quad surface,
 * and smoothing, which flattens the quads there, slides their vertices off
 * such points and widens the gap. This file finds those surface vertices
 * and, for each, the quad vertex to move onto it.
 *
 * The quad surface is the referee's (check_quad.py): each quad split along
 * its shorter diagonal. Cost: a tree over 2 nq triangles and one
 * nearest-point query per surface vertex. */
#include <math.h>
#include <stdlib.h>

#include "sq_closest_point.h"
#include "sq_smooth_internal.h"

#define PIN_SHARE_OF_WORST 0.5 /* only gaps above this share of the largest one */

sq_status sq_smooth_find_pins(uint32_t snv, const double *spos, uint32_t nv, const double *pos, uint32_t nq,
                              const uint32_t *quads, const double *h, double theta, uint32_t *pin_v,
                              uint32_t *pin_s, uint32_t *npin, sq_error *err)
{
    *npin = 0;
    uint32_t *tri = malloc(6 * (size_t)(nq ? nq : 1) * sizeof(uint32_t));
    double *d2 = malloc(((size_t)snv + 1) * sizeof(double));
    uint32_t *hit_tri = malloc(((size_t)snv + 1) * sizeof(uint32_t));
    if (!tri || !d2 || !hit_tri) {
        free(tri), free(d2), free(hit_tri);
        return sq_error_set(err, SQ_ERR_NOMEM, "smooth: out of memory for the fidelity pins");
    }
    for (uint32_t q = 0; q < nq; q++) {
        const uint32_t *f = quads + 4 * (size_t)q;
        const double *p0 = pos + 3 * (size_t)f[0], *p1 = pos + 3 * (size_t)f[1], *p2 = pos + 3 * (size_t)f[2],
                     *p3 = pos + 3 * (size_t)f[3];
        double d02 = 0.0, d13 = 0.0;
        for (int k = 0; k < 3; k++) d02 += (p2[k] - p0[k]) * (p2[k] - p0[k]), d13 += (p3[k] - p1[k]) * (p3[k] - p1[k]);
        uint32_t *t = tri + 6 * (size_t)q;
        if (d02 <= d13)
            t[0] = f[0], t[1] = f[1], t[2] = f[2], t[3] = f[0], t[4] = f[2], t[5] = f[3];
        else
            t[0] = f[0], t[1] = f[1], t[2] = f[3], t[3] = f[1], t[4] = f[2], t[5] = f[3];
    }
    sq_cp_tree tree;
    sq_status st = sq_cp_tree_build(nv, pos, 2 * nq, tri, &tree, err);
    if (st != SQ_OK) {
        free(tri), free(d2), free(hit_tri);
        return st;
    }
    double worst2 = 0.0;
    for (uint32_t i = 0; i < snv; i++) {
        sq_cp_hit hit;
        sq_cp_tree_query(&tree, spos + 3 * (size_t)i, &hit);
        d2[i] = hit.dist2, hit_tri[i] = hit.tri;
        if (hit.dist2 > worst2) worst2 = hit.dist2;
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < snv; i++) {
        if (!(d2[i] > PIN_SHARE_OF_WORST * PIN_SHARE_OF_WORST * worst2)) continue;
        /* the corner of the nearest quad triangle nearest to the surface vertex */
        const double *p = spos + 3 * (size_t)i;
        const uint32_t *t = tri + 3 * (size_t)hit_tri[i];
        uint32_t best = t[0];
        double bd = INFINITY;
        for (int k = 0; k < 3; k++) {
            const double *x = pos + 3 * (size_t)t[k];
            double d = (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) + (x[2] - p[2]) * (x[2] - p[2]);
            if (d < bd) bd = d, best = t[k];
        }
        if (!(sqrt(d2[i]) > theta * h[best])) continue;
        pin_v[n] = best, pin_s[n] = i;
        n++;
    }
    sq_cp_tree_free(&tree);
    free(tri), free(d2), free(hit_tri);
    *npin = n;
    return SQ_OK;
}
