/* seamquad: the smoothing objective (docs/smooth.md): per quad, its four
 * signed corner angles minus 90 degrees (radians), the logs of its four edge
 * lengths over their geometric mean (0 when equal), and for quads being untangled a hinge on the
 * alignment of each of its four triangles with the surface normal; and a
 * log barrier keeping its fold margin above its threshold. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "sq_smooth_internal.h"

#define UNTANGLE_COS 0.2 /* untangling pushes triangle normals within ~78 deg of the surface's */
#define SQ_PI 3.14159265358979323846
#define BARRIER_START 0.5 /* fold margin (cosine) below which the barrier acts */

static void sub3(const double *a, const double *b, double *o) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

uint32_t sq_smooth_residual_count(const sq_smooth_ctx *c, uint32_t q)
{
    return c->untangle && c->untangle[q] ? 13 : 9;
}

/* Log barrier on the fold margin m above the quad's threshold t: 0 for
 * m >= BARRIER_START, growing without bound as m falls to t. It lets the
 * solver see the no-fold constraint coming instead of only hitting it. */
static int barrier_term(double m, double t, double *r)
{
    if (t == -INFINITY || m >= BARRIER_START) {
        *r = 0.0;
        return 1;
    }
    if (!(m > t)) return 0;
    *r = -log((m - t) / (BARRIER_START - t));
    return 1;
}

/* hinge: how far triangle (a, b, d)'s normal is from facing along n */
static double untangle_term(const double *a, const double *b, const double *d, const double *n)
{
    double u[3], v[3], t[3];
    sub3(b, a, u), sub3(d, a, v), cross3(u, v, t);
    double len = sqrt(dot3(t, t));
    double cosv = len > 0.0 ? dot3(t, n) / len : 0.0;
    return cosv < UNTANGLE_COS ? UNTANGLE_COS - cosv : 0.0;
}

void sq_smooth_corner_angles(const double *const x[4], const double n[3], double theta[4])
{
    for (int k = 0; k < 4; k++) {
        double u[3], w[3], cr[3]; /* corner k: from the edge to k+1 to the edge to k-1 */
        sub3(x[(k + 1) % 4], x[k], u), sub3(x[(k + 3) % 4], x[k], w), cross3(u, w, cr);
        double th = atan2(dot3(cr, n), dot3(u, w));
        theta[k] = th < 0.0 ? th + 2.0 * SQ_PI : th;
    }
}

int sq_smooth_quad_residuals(const sq_smooth_ctx *c, uint32_t q, const double *const x[4], double *r)
{
    /* Scale-invariant residuals: signed corner angles (radians, 0 at 90
     * degrees, in (0, 360) degrees measured around the surface normal, so a
     * reflex corner is penalized and the gradient does not vanish at 0 or
     * 180 degrees as a cosine's does) and log(edge length / geometric mean
     * of the quad's four edges) (unbounded as an edge collapses). */
    double e[4][3], len[4], lmean = 0.0;
    const double *n = c->ref_normal + 3 * (size_t)q;
    for (int k = 0; k < 4; k++) {
        sub3(x[(k + 1) % 4], x[k], e[k]);
        len[k] = sqrt(dot3(e[k], e[k]));
        if (!(len[k] > 0.0)) return 0;
        lmean += 0.25 * log(len[k]);
    }
    double theta[4];
    sq_smooth_corner_angles(x, n, theta);
    for (int k = 0; k < 4; k++) {
        double th = theta[k];
        if (c->base_angle) { /* the branch nearest the angle at the solve's start */
            double b = c->base_angle[4 * (size_t)q + k];
            if (th > b + SQ_PI) th -= 2.0 * SQ_PI;
            else if (th < b - SQ_PI) th += 2.0 * SQ_PI;
        }
        r[k] = c->wa * (th - (c->target ? c->target[4 * (size_t)q + k] : 0.5 * SQ_PI));
        r[4 + k] = c->wl * (log(len[k]) - lmean - (c->ideal_log ? c->ideal_log[4 * (size_t)q + k] : 0.0));
    }
    double b;
    if (!barrier_term(sq_quad_fold_margin(x[0], x[1], x[2], x[3]), c->threshold[q], &b)) return 0;
    r[8] = c->wb * b;
    if (c->untangle && c->untangle[q]) {
        const double *n = c->ref_normal + 3 * (size_t)q;
        r[9] = c->wu * untangle_term(x[0], x[1], x[2], n);
        r[10] = c->wu * untangle_term(x[0], x[2], x[3], n);
        r[11] = c->wu * untangle_term(x[0], x[1], x[3], n);
        r[12] = c->wu * untangle_term(x[1], x[2], x[3], n);
    }
    return 1;
}

double sq_smooth_energy(const sq_smooth_ctx *c, const double *pos)
{
    double sum = 0.0, r[SQ_SMOOTH_MAX_RES];
    for (uint32_t q = 0; q < c->nq; q++) {
        const double *x[4];
        for (int k = 0; k < 4; k++) x[k] = pos + 3 * (size_t)c->quads[4 * (size_t)q + k];
        if (!sq_smooth_quad_residuals(c, q, x, r)) return INFINITY;
        for (uint32_t i = 0; i < sq_smooth_residual_count(c, q); i++) sum += r[i] * r[i];
    }
    return sum;
}

static void tangent_position(const sq_smooth_ctx *c, uint32_t v, const double *ab, double *x)
{
    const double *p = c->base + 3 * (size_t)v, *f = c->frame + 9 * (size_t)v;
    double s = c->h[v];
    for (int k = 0; k < 3; k++) x[k] = p[k] + s * (ab[0] * f[k] + ab[1] * f[3 + k]);
}

/* Derivatives of the quad's angle and length residuals (r[0..7]) by its
 * corner positions: G[i][3 k + d] = d r_i / d x_k[d]. Corner k's angle
 * theta = atan2(Y, X), X = u.w, Y = (u x w).n (u = x_{k+1} - x_k, w =
 * x_{k-1} - x_k, n fixed): d theta = (X dY - Y dX) / (X^2 + Y^2), with
 * dX = du.w + u.dw and dY = du.(w x n) + dw.(n x u). Edge k's log length
 * L_k = log |e_k| has gradient e_k / |e_k|^2 at x_{k+1} and its opposite at
 * x_k; residual 4 + k is L_k minus the mean of the four. */
static void shape_gradient(const sq_smooth_ctx *c, uint32_t q, const double *const x[4], double G[8][12])
{
    const double *n = c->ref_normal + 3 * (size_t)q;
    double e[4][3], gl[4][3];
    memset(G, 0, 8 * sizeof G[0]);
    for (int k = 0; k < 4; k++) {
        sub3(x[(k + 1) % 4], x[k], e[k]);
        double l2 = dot3(e[k], e[k]);
        for (int d = 0; d < 3; d++) gl[k][d] = e[k][d] / l2;
    }
    for (int k = 0; k < 4; k++) {
        int kn = (k + 1) % 4, kp = (k + 3) % 4;
        const double *u = e[k];
        double w[3] = {-e[kp][0], -e[kp][1], -e[kp][2]}, cr[3], wn[3], nu[3];
        cross3(u, w, cr);
        double X = dot3(u, w), Y = dot3(cr, n), s = c->wa / (X * X + Y * Y);
        cross3(w, n, wn);
        cross3(n, u, nu);
        for (int d = 0; d < 3; d++) {
            double gn = s * (X * wn[d] - Y * w[d]); /* by x_{k+1} */
            double gp = s * (X * nu[d] - Y * u[d]); /* by x_{k-1} */
            G[k][3 * kn + d] += gn;
            G[k][3 * kp + d] += gp;
            G[k][3 * k + d] -= gn + gp;
        }
        /* length residual k: grad L_k - mean_j grad L_j */
        for (int j = 0; j < 4; j++) {
            double a = c->wl * ((j == k) - 0.25);
            int jn = (j + 1) % 4;
            for (int d = 0; d < 3; d++) {
                G[4 + k][3 * jn + d] += a * gl[j][d];
                G[4 + k][3 * j + d] -= a * gl[j][d];
            }
        }
    }
}

int sq_smooth_residual_cb(void *user, uint32_t q, const double *const *param, double *r, double **jac)
{
    const sq_smooth_ctx *c = user;
    if (q >= c->nq) { /* damping block of vertex q - nq */
        r[0] = c->damping * param[0][0], r[1] = c->damping * param[0][1];
        if (jac && jac[0]) jac[0][0] = c->damping, jac[0][1] = 0.0, jac[0][2] = 0.0, jac[0][3] = c->damping;
        return 1;
    }
    double xs[4][3];
    const double *x[4];
    for (int k = 0; k < 4; k++) {
        tangent_position(c, c->quads[4 * (size_t)q + k], param[k], xs[k]);
        x[k] = xs[k];
    }
    if (!sq_smooth_quad_residuals(c, q, x, r)) return 0;
    if (!jac) return 1;
    uint32_t nr = sq_smooth_residual_count(c, q);
    double G[8][12];
    shape_gradient(c, q, x, G);
    for (int k = 0; k < 4; k++) {
        if (!jac[k]) continue;
        uint32_t v = c->quads[4 * (size_t)q + k];
        const double *f = c->frame + 9 * (size_t)v;
        double h = c->h[v];
        for (int i = 0; i < 8; i++) {
            jac[k][2 * i] = h * dot3(G[i] + 3 * k, f);
            jac[k][2 * i + 1] = h * dot3(G[i] + 3 * k, f + 3);
        }
        for (uint32_t i = 8; i < nr; i++) jac[k][2 * i] = jac[k][2 * i + 1] = 0.0;
    }
    /* The barrier and untangling residuals act only near a fold or while
     * untangling: there, central differences in the parameters (Ceres'
     * relative step); a side where the residuals are undefined (the margin
     * at its threshold) gives a one-sided difference. */
    if (nr == 9 && r[8] == 0.0) return 1;
    for (int k = 0; k < 4; k++) {
        if (!jac[k]) continue;
        for (int d = 0; d < 2; d++) {
            double ab[2] = {param[k][0], param[k][1]}, rp[SQ_SMOOTH_MAX_RES], rm[SQ_SMOOTH_MAX_RES];
            double eps = 1e-6 * fmax(1.0, fabs(ab[d])), x0 = ab[d];
            ab[d] = x0 + eps;
            tangent_position(c, c->quads[4 * (size_t)q + k], ab, xs[k]);
            int okp = sq_smooth_quad_residuals(c, q, x, rp);
            ab[d] = x0 - eps;
            tangent_position(c, c->quads[4 * (size_t)q + k], ab, xs[k]);
            int okm = sq_smooth_quad_residuals(c, q, x, rm);
            tangent_position(c, c->quads[4 * (size_t)q + k], param[k], xs[k]);
            for (uint32_t i = 8; i < nr; i++)
                jac[k][2 * i + d] = okp && okm ? (rp[i] - rm[i]) / (2 * eps)
                                  : okp        ? (rp[i] - r[i]) / eps
                                  : okm        ? (r[i] - rm[i]) / eps
                                               : 0.0;
        }
    }
    return 1;
}

int sq_smooth_feasible_cb(void *user, uint32_t con, const double *const *param)
{
    sq_smooth_ctx *c = user;
    uint32_t q = c->con_quad[con];
    double xs[4][3];
    for (int k = 0; k < 4; k++) tangent_position(c, c->quads[4 * (size_t)q + k], param[k], xs[k]);
    if (sq_quad_fold_margin(xs[0], xs[1], xs[2], xs[3]) >= c->threshold[q]) return 1;
    c->fold_rejections++;
    return 0;
}

/* Ideal edge lengths of a planar quad with interior angles a[0..3] (sum
 * 2 pi): edge k runs from corner k to k+1 with direction phi_k, phi_{k+1} =
 * phi_k + pi - a[k+1]. Closing the polygon, sum_k l_k (cos phi_k, sin
 * phi_k) = 0, is 2 linear equations in the 4 lengths; the lengths closest
 * to (1, 1, 1, 1) are l = 1 - D^T (D D^T)^-1 D 1 (D: the 2x4 direction
 * matrix). A square gives (1, 1, 1, 1); the split's kite (60, 90, 120, 90
 * degrees) gives edges in ratio sqrt(3). Returns 0 when the shape is
 * unusable (D D^T singular or a length below 0.2). */
static int ideal_lengths(const double a[4], double l[4])
{
    double phi = 0.0, D[2][4];
    for (int k = 0; k < 4; k++) {
        D[0][k] = cos(phi), D[1][k] = sin(phi);
        phi += SQ_PI - a[(k + 1) % 4];
    }
    double M00 = 0, M01 = 0, M11 = 0, d0 = 0, d1 = 0;
    for (int k = 0; k < 4; k++) {
        M00 += D[0][k] * D[0][k], M01 += D[0][k] * D[1][k], M11 += D[1][k] * D[1][k];
        d0 += D[0][k], d1 += D[1][k];
    }
    double det = M00 * M11 - M01 * M01;
    if (!(det > 1e-9)) return 0;
    double y0 = (M11 * d0 - M01 * d1) / det, y1 = (M00 * d1 - M01 * d0) / det;
    for (int k = 0; k < 4; k++) {
        l[k] = 1.0 - (D[0][k] * y0 + D[1][k] * y1);
        if (!(l[k] >= 0.2)) return 0;
    }
    return 1;
}

void sq_smooth_targets(uint32_t nv, uint32_t nq, const uint32_t *quads, double *target, double *ideal_log)
{
    uint32_t *val = calloc(nv ? nv : 1, sizeof(uint32_t));
    for (size_t i = 0; val && i < 4 * (size_t)nq; i++) val[quads[i]]++;
    for (uint32_t q = 0; q < nq; q++) {
        double a[4], sum = 0.0, l[4];
        for (int k = 0; k < 4; k++) {
            uint32_t k_v = val ? val[quads[4 * (size_t)q + k]] : 4;
            a[k] = 2.0 * SQ_PI / (double)(k_v ? k_v : 4);
            target[4 * (size_t)q + k] = a[k];
            sum += a[k];
        }
        for (int k = 0; k < 4; k++) a[k] *= 2.0 * SQ_PI / sum;
        double lm = 0.0;
        if (!ideal_lengths(a, l)) l[0] = l[1] = l[2] = l[3] = 1.0;
        for (int k = 0; k < 4; k++) lm += 0.25 * log(l[k]);
        for (int k = 0; k < 4; k++) ideal_log[4 * (size_t)q + k] = log(l[k]) - lm;
    }
    free(val);
}
