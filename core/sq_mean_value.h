/* seamquad: the mean-value weight of Floater (2003), shared by every Tutte
 * map of a triangle surface (the interior map of sq_param_interior.c, the disk
 * layout of sq_guide_surface_disk.c, quantization's patch fallback in
 * sq_patch_embed.c). Positive for every non-degenerate pair of triangles,
 * so Tutte's theorem applies. */
#ifndef SQ_MEAN_VALUE_H
#define SQ_MEAN_VALUE_H

#include <math.h>

/* tan(angle at p between p->a and p->b, halved) */
static inline double sq_half_tan(const double *p, const double *a, const double *b)
{
    double u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, w[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double cs = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / (lu * lw);
    if (!(cs < 1)) cs = 1;
    if (!(cs > -1)) cs = -1;
    return tan(0.5 * acos(cs));
}

/* Weight of edge v-w in v's row: (tan(alpha/2) + tan(beta/2)) / |v - w|,
 * alpha and beta the angles at v of the triangles (v, w, a) and (v, w, b)
 * on the edge's two sides. Not positive or not finite (a degenerate
 * triangle): 1e-12, which keeps the row diagonally dominant. */
static inline double sq_mean_value_weight(const double *v, const double *w, const double *a, const double *b)
{
    double d[3] = {w[0] - v[0], w[1] - v[1], w[2] - v[2]};
    double wt = (sq_half_tan(v, w, a) + sq_half_tan(v, w, b)) / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return wt > 0 && isfinite(wt) ? wt : 1e-12;
}

#endif
