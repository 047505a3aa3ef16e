/* seamquad: untangling a seamless map in the basis of its seamless maps
 * (sq_map_from_rotations.h, step 3).
 *
 * Energy (Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov 2021,
 * "Foldover-free maps in 50 lines of code"): per triangle, with J its
 * Jacobian from the surface and d = det J,
 *     f_eps(J) = ((1 - L) |J|^2 + L (d^2 + 1)) / chi(d, eps),
 *     chi(d, eps) = (d + sqrt(eps^2 + d^2)) / 2,
 * area-weighted over the surface (scaled to area 1, the map to the same
 * area). chi is positive for every d, so f_eps is finite on flipped
 * triangles and large there when eps is small; as eps -> 0 it becomes
 * the barrier |J|^2 / d + (d + 1/d) of the valid maps. For each eps a few
 * projected Newton steps (4x4 Hessians in J made positive semidefinite by
 * Jacobi's eigenvalue method, pulled back through the basis, CHOLMOD) with
 * an Armijo line search; then eps follows the paper's rule from the worst
 * determinant D and the last relative decrease sigma:
 *     mu = (1 - sigma) chi(D, eps),  eps = 2 sqrt(mu (mu - D)) if D < mu.
 * The energy does not see angle sums: a vertex may end winding around
 * twice or a cone once less (the caller's exact check refuses such a
 * map). Holding each vertex at its count once reached was measured and
 * lost more maps than it saved (12 of 15 mpz models valid against 13:
 * femur's untangling passes through wrong counts). It stops as soon as
 * every triangle is positive in doubles (checked after every step; the
 * caller checks exactly), or after max_iterations Newton steps.
 *
 * Cost per step: O(faces) for the Hessians and one sparse Cholesky. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_untangle.h"

#define AREA_WEIGHT 0.5      /* L: the area term's share                 */
#define STEPS_PER_EPS 8u     /* Newton steps before eps is updated       */
#define ARMIJO 1e-4
/* the first eps, times the worst determinant's magnitude (the map's area
 * is the surface's, so 1 is a typical determinant). Small: a large eps
 * lets many triangles turn over on the way and come back around a vertex
 * the other way (winding twice, an angle sum off by 2 pi). Measured on the
 * 15 mpz models from the field-aligned start: 0.02, 0.005 and 0.001 give
 * 13 valid maps, 0.1 and 0.5 give 11. */
#define EPS_START 0.02

/* chi(d, eps), accurate for d << 0 too */
static double chi(double d, double eps)
{
    double s = sqrt(eps * eps + d * d);
    return d >= 0 ? 0.5 * (d + s) : 0.5 * eps * eps / (s - d);
}

static double face_energy(const sq_sd_face *F, const double uv[6], double eps)
{
    double J[4];
    sq_sd_jacobian(F, uv, J);
    double d = J[0] * J[3] - J[1] * J[2];
    double n2 = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3];
    return ((1 - AREA_WEIGHT) * n2 + AREA_WEIGHT * (d * d + 1)) / chi(d, eps);
}

/* A := its projection onto the positive semidefinite matrices (Jacobi). */
static void project_psd4(double A[4][4])
{
    double V[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = 0, on = 0;
        for (int p = 0; p < 4; p++)
            for (int q = 0; q < 4; q++) *(p == q ? &on : &off) += A[p][q] * A[p][q];
        if (off <= 1e-30 * on || off == 0) break;
        for (int p = 0; p < 3; p++)
            for (int q = p + 1; q < 4; q++) {
                if (A[p][q] == 0) continue;
                double th = (A[q][q] - A[p][p]) / (2 * A[p][q]);
                double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1));
                double c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 4; k++) { /* columns p, q */
                    double x = A[k][p], y = A[k][q];
                    A[k][p] = c * x - s * y, A[k][q] = s * x + c * y;
                }
                for (int k = 0; k < 4; k++) { /* rows p, q */
                    double x = A[p][k], y = A[q][k];
                    A[p][k] = c * x - s * y, A[q][k] = s * x + c * y;
                }
                for (int k = 0; k < 4; k++) {
                    double x = V[k][p], y = V[k][q];
                    V[k][p] = c * x - s * y, V[k][q] = s * x + c * y;
                }
            }
    }
    double lam[4];
    for (int i = 0; i < 4; i++) lam[i] = A[i][i] > 0 ? A[i][i] : 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += V[i][k] * lam[k] * V[j][k];
            A[i][j] = s;
        }
}

/* f_eps's gradient and projected Hessian in the corners, times the area. */
static void face_grad_hess(const sq_sd_face *F, const double uv[6], double eps, double g[6], double H[36])
{
    double J[4];
    sq_sd_jacobian(F, uv, J);
    const double L = AREA_WEIGHT;
    double d = J[0] * J[3] - J[1] * J[2];
    double n2 = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3];
    double c[4] = {J[3], -J[2], -J[1], J[0]}; /* d's gradient */
    double s = sqrt(eps * eps + d * d), x = chi(d, eps);
    double x1 = x / s, x2 = 0.5 * eps * eps / (s * s * s); /* chi', chi'' */
    double N = (1 - L) * n2 + L * (d * d + 1);
    double NJ[4], dJ[4], A[4][4];
    for (int i = 0; i < 4; i++) NJ[i] = 2 * (1 - L) * J[i] + 2 * L * d * c[i];
    for (int i = 0; i < 4; i++) dJ[i] = NJ[i] / x - N * x1 * c[i] / (x * x);
    double ccoef = N * (2 * x1 * x1 / (x * x * x) - x2 / (x * x));
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            A[i][j] = ((i == j ? 2 * (1 - L) : 0) + 2 * L * c[i] * c[j]) / x -
                      x1 * (NJ[i] * c[j] + c[i] * NJ[j]) / (x * x) + ccoef * c[i] * c[j];
    /* d's Hessian Hd (entries 03, 30: 1; 12, 21: -1), in N_JJ and chi's term */
    double hd = 2 * L * d / x - N * x1 / (x * x);
    A[0][3] += hd, A[3][0] += hd, A[1][2] -= hd, A[2][1] -= hd;
    project_psd4(A);
    sq_sd_pullback(F, dJ, (const double(*)[4])A, F->area, g, H);
}

static double total_energy(const sq_mesh *m, const sq_sd_face *F, const double *he_uv, double eps)
{
    double E = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        if (F[f].area == 0) continue;
        double uv[6];
        sq_face_uv(m, he_uv, f, uv);
        E += F[f].area * face_energy(&F[f], uv, eps);
    }
    return E;
}

/* the smallest determinant of J, and the triangles with det <= 0 */
static double min_det(const sq_mesh *m, const sq_sd_face *F, const double *he_uv, uint32_t *bad)
{
    double dmin = INFINITY;
    *bad = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        if (F[f].area == 0) continue;
        double uv[6], J[4];
        sq_face_uv(m, he_uv, f, uv);
        sq_sd_jacobian(&F[f], uv, J);
        double d = J[0] * J[3] - J[1] * J[2];
        if (!(d > 0)) ++*bad;
        if (d < dmin) dmin = d;
    }
    return dmin;
}

sq_status sq_map_untangle(const sq_mesh *m, const sq_uv_basis *B, const sq_sd_face *F, sq_zsys *S, double *z,
                          uint32_t max_iterations, sq_untangle_result *res, sq_error *err)
{
    memset(res, 0, sizeof *res);
    const uint32_t nz = B->nz;
    double *uv = malloc(B->ncoord * sizeof *uv), *trial = malloc(B->ncoord * sizeof *trial);
    double *gz = malloc(((size_t)nz + 1) * sizeof *gz), *d = malloc(((size_t)nz + 1) * sizeof *d);
    double *zt = malloc(((size_t)nz + 1) * sizeof *zt);
    sq_zsys own;
    memset(&own, 0, sizeof own);
    sq_status st = SQ_OK;
    if (!uv || !trial || !gz || !d || !zt) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (untangling)");
        goto done;
    }
    if (!S) {
        if ((st = sq_zsys_init(&own, m, B, err))) goto done;
        S = &own;
    }
    sq_uv_basis_eval(B, z, uv);
    uint32_t bad;
    double dmin = min_det(m, F, uv, &bad);
    res->flipped_before = bad;
    double eps = EPS_START * fmax(fabs(dmin), 1e-3);
    while (bad && res->iterations < max_iterations) {
        res->rounds++;
        double e_start = total_energy(m, F, uv, eps), e = e_start;
        for (uint32_t k = 0; k < STEPS_PER_EPS && res->iterations < max_iterations; k++) {
            sq_zsys_zero(S, gz);
            for (uint32_t f = 0; f < m->nf; f++) {
                if (F[f].area == 0) continue;
                double fu[6], g[6], H[36];
                sq_face_uv(m, uv, f, fu);
                face_grad_hess(&F[f], fu, eps, g, H);
                sq_zsys_add_face(S, f, g, H, gz);
            }
            if ((st = sq_zsys_solve(S, NULL, gz, d, err))) goto done;
            double slope = 0;
            for (uint32_t i = 0; i < nz; i++) slope += gz[i] * d[i];
            if (!(slope < 0)) break;
            double a = 1, et = INFINITY;
            for (int cut = 0; cut < 40; cut++, a *= 0.5) {
                for (uint32_t i = 0; i < nz; i++) zt[i] = z[i] + a * d[i];
                sq_uv_basis_eval(B, zt, trial);
                et = total_energy(m, F, trial, eps);
                if (et <= e + ARMIJO * a * slope) break;
            }
            if (!(et < e)) break;
            memcpy(z, zt, nz * sizeof *z);
            memcpy(uv, trial, B->ncoord * sizeof *uv);
            res->iterations++;
            double gain = (e - et) / e;
            e = et;
            if (gain < 1e-6) break;
            dmin = min_det(m, F, uv, &bad);
            if (!bad) break; /* done: no step more than needed */
        }
        dmin = min_det(m, F, uv, &bad);
        if (!bad) break;
        double sigma = fmax(1 - e / e_start, 0.1);
        double mu = (1 - sigma) * chi(dmin, eps);
        eps = dmin < mu ? 2 * sqrt(mu * (mu - dmin)) : 1e-13;
        if (!(eps > 0)) eps = 1e-13;
    }
    res->flipped_after = bad;
    res->eps = eps;
done:
    sq_zsys_free(&own);
    free(uv), free(trial), free(gz), free(d), free(zt);
    return st;
}
