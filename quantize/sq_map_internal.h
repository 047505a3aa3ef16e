/* seamquad: helpers shared by the sq_map files (not a public header). */
#ifndef SQ_MAP_INTERNAL_H
#define SQ_MAP_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "sq_map.h"

#define SQ_MAP_HALF_PI 1.57079632679489661923

static inline uint32_t sq_map_prev(const sq_mesh *m, uint32_t h) { return m->he_next[m->he_next[h]]; }
static inline uint32_t sq_map_dst(const sq_mesh *m, uint32_t h) { return m->he_vert[m->he_next[h]]; }

/* The next halfedge out of the same vertex, counterclockwise: across the
 * edge prev(h), whose transition maps h's chart to the new halfedge's. */
static inline uint32_t sq_map_rotate_out(const sq_mesh *m, uint32_t h)
{
    return m->he_twin[sq_map_prev(m, h)];
}

/* TwoSum (Knuth): s = fl(a + b), e = (a + b) - s exactly. */
static inline void sq_map_two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* out = R^r p + t; 1 iff every addition was exact. */
static inline int sq_map_apply(int r, const double t[2], const double p[2], double out[2])
{
    double q[2], e0, e1;
    sq_map_rotate(r, p, q);
    sq_map_two_sum(q[0], t[0], &out[0], &e0);
    sq_map_two_sum(q[1], t[1], &out[1], &e1);
    return e0 == 0.0 && e1 == 0.0;
}

/* The inverse transition of (r, t): (-r, -R^{-r} t), exact. */
static inline void sq_map_inverse(int r, const double t[2], int *ri, double ti[2])
{
    double q[2];
    *ri = (4 - (r & 3)) & 3;
    sq_map_rotate(*ri, t, q);
    ti[0] = -q[0];
    ti[1] = -q[1];
}

/* Interior angle at corner b of the UV triangle (a, b, c). */
static inline double sq_map_corner_angle(const double *a, const double *b, const double *c)
{
    double ux = a[0] - b[0], uy = a[1] - b[1], vx = c[0] - b[0], vy = c[1] - b[1];
    return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy);
}

/* UV angle sums per vertex (nv doubles, caller-allocated). */
void sq_map_angle_sums(const sq_mesh *m, const double *he_uv, double *sum);

/* Snaps the map to a dyadic grid so that every transition holds exactly
 * (sq_map_snap.c). he_rot must hold the rotations, he_t the estimated
 * translations; seam[e] marks halfedges whose sides differ. */
sq_status sq_map_snap(sq_map *M, const uint8_t *seam, double tol_abs, sq_map_report *rep,
                      sq_error *err);

#endif
