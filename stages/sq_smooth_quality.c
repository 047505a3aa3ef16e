/* seamquad: quad quality measures and the fold margin (same formulas as the
 * referee tools/check_quad.py, sections [3] and [6]). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "sq_smooth.h"

static void sub3(const double *a, const double *b, double *o) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double cos_normals(const double *n, const double *m)
{
    double a = sqrt(dot3(n, n)), b = sqrt(dot3(m, m));
    if (!(a > 0.0) || !(b > 0.0)) return -1.0;
    return dot3(n, m) / (a * b);
}

double sq_quad_fold_margin(const double *p0, const double *p1, const double *p2, const double *p3)
{
    double e0[3], e1[3], d02[3], d03[3], d13[3], n012[3], n023[3], n013[3], n123[3];
    sub3(p1, p0, e0), sub3(p2, p1, e1), sub3(p2, p0, d02), sub3(p3, p0, d03), sub3(p3, p1, d13);
    cross3(e0, d02, n012), cross3(d02, d03, n023), cross3(e0, d03, n013), cross3(e1, d13, n123);
    double c1 = cos_normals(n012, n023), c2 = cos_normals(n013, n123);
    return c1 > c2 ? c1 : c2;
}

int sq_triangle_unit_normal(const double *a, const double *b, const double *c, double n[3])
{
    double e1[3], e2[3], e3[3], x[3];
    sub3(b, a, e1), sub3(c, a, e2), sub3(c, b, e3), cross3(e1, e2, x);
    double l = sqrt(dot3(x, x)), longest = fmax(fmax(dot3(e1, e1), dot3(e2, e2)), dot3(e3, e3));
    if (l > 0.0) n[0] = x[0] / l, n[1] = x[1] / l, n[2] = x[2] / l;
    return l > 1e-10 * longest;
}

double sq_quad_turn_margin(const double *const p[4], const double *const n[4])
{
    double c[4][3], l[4], lmax = 0.0;
    for (int k = 0; k < 4; k++) {
        double e1[3], e2[3];
        sub3(p[(k + 1) % 4], p[k], e1), sub3(p[(k + 3) % 4], p[k], e2), cross3(e1, e2, c[k]);
        l[k] = sqrt(c[k][0] * c[k][0] + c[k][1] * c[k][1] + c[k][2] * c[k][2]);
        if (l[k] > lmax) lmax = l[k];
    }
    double best = -1.0;
    for (int k = 0; k < 4; k++) {
        /* a corner a millionth of the largest has no direction to speak of */
        double cs = l[k] > 1e-6 * lmax ? (c[k][0] * n[k][0] + c[k][1] * n[k][1] + c[k][2] * n[k][2]) / l[k] : 0.0;
        if (cs > best) best = cs;
    }
    return best;
}

void sq_quad_size(const double *p0, const double *p1, const double *p2, const double *p3, double *area,
                  double *shortest_edge)
{
    const double *p[4] = {p0, p1, p2, p3};
    double e[4][3], d02[3], d03[3], d13[3], n012[3], n023[3], n013[3], n123[3];
    for (int k = 0; k < 4; k++) sub3(p[(k + 1) % 4], p[k], e[k]);
    sub3(p2, p0, d02), sub3(p3, p0, d03), sub3(p3, p1, d13);
    cross3(e[0], d02, n012), cross3(d02, d03, n023), cross3(e[0], d03, n013), cross3(e[1], d13, n123);
    *area = 0.25 * (sqrt(dot3(n012, n012)) + sqrt(dot3(n023, n023)) + sqrt(dot3(n013, n013)) +
                    sqrt(dot3(n123, n123)));
    *shortest_edge = fmin(fmin(sqrt(dot3(e[0], e[0])), sqrt(dot3(e[1], e[1]))),
                          fmin(sqrt(dot3(e[2], e[2])), sqrt(dot3(e[3], e[3]))));
}

/* Both: the angles (atan2 per corner, most of the cost) only when asked;
 * every other figure is computed the same way either way. */
static void quality(const double *pos, uint32_t nq, const uint32_t *quads, int angles, sq_quad_quality *q)
{
    memset(q, 0, sizeof *q);
    q->nq = nq;
    q->angle_min_deg = 180.0, q->angle_max_deg = 0.0;
    q->sjac_min = DBL_MAX, q->edge_ratio_max = 0.0, q->fold_margin_min = DBL_MAX;
    double sum_dev = 0.0, sum_sj = 0.0, sum_er = 0.0;
    uint32_t measured = 0;
    for (uint32_t f = 0; f < nq; f++) {
        const double *P[4];
        for (int k = 0; k < 4; k++) P[k] = pos + 3 * (size_t)quads[4 * (size_t)f + k];
        double m = sq_quad_fold_margin(P[0], P[1], P[2], P[3]);
        if (m < q->fold_margin_min) q->fold_margin_min = m;
        double e0[3], e1[3], d02[3], d03[3], d13[3], n012[3], n023[3], n013[3], n123[3];
        sub3(P[1], P[0], e0), sub3(P[2], P[1], e1), sub3(P[2], P[0], d02), sub3(P[3], P[0], d03),
            sub3(P[3], P[1], d13);
        cross3(e0, d02, n012), cross3(d02, d03, n023), cross3(e0, d03, n013), cross3(e1, d13, n123);
        if (dot3(n012, n023) < 0.0 && dot3(n013, n123) < 0.0) q->folded++;
        double E[4][3], L[4];
        for (int k = 0; k < 4; k++) {
            sub3(P[(k + 1) % 4], P[k], E[k]);
            L[k] = sqrt(dot3(E[k], E[k]));
        }
        double lmin = fmin(fmin(L[0], L[1]), fmin(L[2], L[3]));
        double lmax = fmax(fmax(L[0], L[1]), fmax(L[2], L[3]));
        if (!(lmin > 0.0)) continue;
        double nvec[3];
        cross3(d02, d13, nvec);
        double nn = sqrt(dot3(nvec, nvec)), qsj = DBL_MAX;
        for (int k = 0; k < 4; k++) {
            const double *u = E[k], *w = E[(k + 3) % 4];
            double c[3];
            cross3(u, w, c);
            c[0] = -c[0], c[1] = -c[1], c[2] = -c[2];
            if (angles) {
                double ang = atan2(sqrt(dot3(c, c)), -dot3(u, w)) * (180.0 / 3.14159265358979323846);
                if (ang < q->angle_min_deg) q->angle_min_deg = ang;
                if (ang > q->angle_max_deg) q->angle_max_deg = ang;
                sum_dev += fabs(ang - 90.0);
            }
            double j = nn > 0.0 ? dot3(c, nvec) / (L[k] * L[(k + 3) % 4] * nn) : 0.0;
            if (j < qsj) qsj = j;
        }
        sum_sj += qsj;
        if (qsj < q->sjac_min) q->sjac_min = qsj;
        double er = lmax / lmin;
        sum_er += er;
        if (er > q->edge_ratio_max) q->edge_ratio_max = er;
        measured++;
    }
    if (measured) {
        q->angle_mean_dev_deg = sum_dev / (4.0 * measured);
        q->sjac_mean = sum_sj / measured;
        q->edge_ratio_mean = sum_er / measured;
    }
}

void sq_quad_quality_compute(const double *pos, uint32_t nq, const uint32_t *quads, sq_quad_quality *q)
{
    quality(pos, nq, quads, 1, q);
}

void sq_quad_quality_compute_shapes(const double *pos, uint32_t nq, const uint32_t *quads, sq_quad_quality *q)
{
    quality(pos, nq, quads, 0, q);
}

double sq_quad_turn_margin_either(const double *const p[4], const double *const smooth[4],
                                  const double *const flat[4])
{
    return fmax(sq_quad_turn_margin(p, smooth), sq_quad_turn_margin(p, flat));
}
