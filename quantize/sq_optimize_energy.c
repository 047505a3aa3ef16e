/* seamquad: the symmetric Dirichlet energy of one triangle, its gradient
 * and its Hessian made positive semidefinite (sq_optimize_internal.h); the
 * mean conformal ratio of a map (sq_optimize.h).
 *
 * A triangle with corners p0, p1, p2 on the surface gets a 2D frame:
 * x1 = (|e1|, 0), x2 = (e1.e2 / |e1|, |e1 x e2| / |e1|), e_i = p_i - p0.
 * With X = [x1 x2] and the map's edge vectors U = [u1 - u0, u2 - u0], the
 * Jacobian is J = U X^-1 = uv G, uv the 2x3 matrix of corners and
 * G = D X^-1 (D: 3x2 with rows (-1,-1), (1,0), (0,1)).
 *
 * psi(J) = |J|^2 + |J^-1|^2 = f (1 + d^-2), f = |J|^2, d = det J (in 2D,
 * |J^-1|^2 = |J|^2 / d^2). With g = vec J, c = vec cof(J) (the gradient of
 * d) and Hd the constant Hessian of d:
 *   dpsi  = 2 (1 + d^-2) g - 2 f d^-3 c
 *   d2psi = 2 (1 + d^-2) I - 4 d^-3 (g c^T + c g^T) + 6 f d^-4 c c^T
 *           - 2 f d^-3 Hd
 * The 4x4 Hessian is made positive semidefinite by clamping its only
 * eigenvalue that can be negative, the twist's, to zero (in closed form,
 * sq_sd_grad_hess), then pulled back to the 6 corner coordinates through
 * G. Cost: a few hundred flops per triangle. */
#include <math.h>
#include <string.h>

#include "sq_optimize.h"
#include "sq_optimize_internal.h"

int sq_sd_prepare(const double *p0, const double *p1, const double *p2, double scale,
                  sq_sd_face *F)
{
    double e1[3], e2[3], cr[3];
    for (int i = 0; i < 3; i++) e1[i] = (p1[i] - p0[i]) * scale, e2[i] = (p2[i] - p0[i]) * scale;
    cr[0] = e1[1] * e2[2] - e1[2] * e2[1];
    cr[1] = e1[2] * e2[0] - e1[0] * e2[2];
    cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    double a2 = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    memset(F, 0, sizeof *F);
    if (!(l1 > 0) || !(a2 > 0) || !isfinite(a2)) return 0;
    double x1 = l1, x2x = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1, x2y = a2 / l1;
    /* X = [[x1, x2x], [0, x2y]], X^-1 = [[1/x1, -x2x/(x1 x2y)], [0, 1/x2y]] */
    double Xi[2][2] = {{1.0 / x1, -x2x / (x1 * x2y)}, {0.0, 1.0 / x2y}};
    static const double D[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    for (int c = 0; c < 3; c++)
        for (int b = 0; b < 2; b++) F->G[c][b] = D[c][0] * Xi[0][b] + D[c][1] * Xi[1][b];
    F->area = 0.5 * a2;
    if (!isfinite(F->G[0][0] + F->G[0][1] + F->G[1][0] + F->G[1][1] + F->G[2][0] + F->G[2][1])) {
        memset(F, 0, sizeof *F);
        return 0;
    }
    return 1;
}

static int face_frame(const sq_mesh *m, uint32_t f, double scale, sq_sd_face *F)
{
    uint32_t hc[3];
    sq_face_corners(m, f, hc);
    const double *P = m->pos;
    return sq_sd_prepare(P + 3 * (size_t)m->he_vert[hc[0]], P + 3 * (size_t)m->he_vert[hc[1]],
                         P + 3 * (size_t)m->he_vert[hc[2]], scale, F);
}

double sq_sd_surface_area(const sq_mesh *m)
{
    double a = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        sq_sd_face F;
        if (face_frame(m, f, 1.0, &F)) a += F.area;
    }
    return a;
}

void sq_sd_surface(const sq_mesh *m, double scale, sq_sd_face *F) { sq_sd_surface_scaled(m, scale, NULL, F); }

void sq_sd_surface_scaled(const sq_mesh *m, double scale, const double *face_scale, sq_sd_face *F)
{
    for (uint32_t f = 0; f < m->nf; f++) face_frame(m, f, face_scale ? scale * face_scale[f] : scale, &F[f]);
}

static void jacobian(const sq_sd_face *F, const double uv[6], double J[4])
{
    /* J[a][b] = sum_c uv[c][a] G[c][b]; vec order (00, 01, 10, 11) */
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            J[2 * a + b] = uv[a] * F->G[0][b] + uv[2 + a] * F->G[1][b] + uv[4 + a] * F->G[2][b];
}

double sq_sd_psi(const sq_sd_face *F, const double uv[6])
{
    if (F->area == 0) return 0.0;
    double J[4];
    jacobian(F, uv, J);
    double d = J[0] * J[3] - J[1] * J[2];
    if (!(d > 0)) return INFINITY;
    double f = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3];
    return f * (1.0 + 1.0 / (d * d));
}

double sq_sd_grad_hess(const sq_sd_face *F, const double uv[6], double weight, double g[6],
                       double H[36])
{
    memset(g, 0, 6 * sizeof *g);
    memset(H, 0, 36 * sizeof *H);
    if (F->area == 0) return 0.0;
    double J[4];
    jacobian(F, uv, J);
    double d = J[0] * J[3] - J[1] * J[2];
    if (!(d > 0)) return INFINITY;
    double f = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3];
    double id = 1.0 / d, id2 = id * id, id3 = id2 * id, id4 = id2 * id2;
    double c[4] = {J[3], -J[2], -J[1], J[0]};
    double dpsi[4], A[4][4];
    for (int i = 0; i < 4; i++) dpsi[i] = 2 * (1 + id2) * J[i] - 2 * f * id3 * c[i];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            A[i][j] = (i == j ? 2 * (1 + id2) : 0) - 4 * id3 * (J[i] * c[j] + c[i] * J[j]) +
                      6 * f * id4 * c[i] * c[j];
    /* Hd: d = J0 J3 - J1 J2 */
    A[0][3] -= 2 * f * id3, A[3][0] -= 2 * f * id3;
    A[1][2] += 2 * f * id3, A[2][1] += 2 * f * id3;
    /* Projection onto the positive semidefinite matrices, analytically:
     * psi is isotropic, so its Hessian's eigenvectors are two scaling
     * modes, a flip and a twist (Smith, de Goes and Kim 2019). With
     * psi = sum_i s_i^2 + s_i^-2 the scaling eigenvalues 2 + 6 s_i^-4 and
     * the flip's 2 + 2 (s1^2 + s1 s2 + s2^2) / (s1 s2)^3 are positive; only
     * the twist's, (psi_1 + psi_2) / (s1 + s2) = 2 - 2 (f - d) / d^3, can be
     * negative. Its eigenvector is J's rotation part turned by 90 degrees:
     * vec(Rot(a + pi/2)) / sqrt(2), a = atan2(J10 - J01, J00 + J11). So the
     * projection adds -lambda t t^T where lambda < 0. */
    double P[4][4];
    memcpy(P, A, sizeof P);
    double lambda = 2.0 - 2.0 * (f - d) * id3;
    if (lambda < 0) {
        double e = 0.5 * (J[0] + J[3]), h = 0.5 * (J[2] - J[1]), r = hypot(e, h);
        double c = e / r, sn = h / r;
        const double k = 0.70710678118654752440; /* 1 / sqrt(2) */
        double t[4] = {-sn * k, -c * k, c * k, -sn * k};
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) P[i][j] -= lambda * t[i] * t[j];
    }
    sq_sd_pullback(F, dpsi, P, weight * F->area, g, H);
    return f * (1.0 + id2);
}

void sq_sd_pullback(const sq_sd_face *F, const double dJ[4], const double P[4][4], double s, double g[6],
                    double H[36])
{
    /* coordinate (c, a) is uv index 2c + a; dJ[2a+b]/duv[2c+a] = G[c][b] */
    for (int cc = 0; cc < 3; cc++)
        for (int a = 0; a < 2; a++) {
            int k = 2 * cc + a;
            g[k] = s * (dJ[2 * a] * F->G[cc][0] + dJ[2 * a + 1] * F->G[cc][1]);
        }
    for (int c1 = 0; c1 < 3; c1++)
        for (int a1 = 0; a1 < 2; a1++)
            for (int c2 = 0; c2 < 3; c2++)
                for (int a2 = 0; a2 < 2; a2++) {
                    double h = 0;
                    for (int b1 = 0; b1 < 2; b1++)
                        for (int b2 = 0; b2 < 2; b2++)
                            h += P[2 * a1 + b1][2 * a2 + b2] * F->G[c1][b1] * F->G[c2][b2];
                    H[(2 * c1 + a1) * 6 + 2 * c2 + a2] = s * h;
                }
}

void sq_sd_jacobian(const sq_sd_face *F, const double uv[6], double J[4]) { jacobian(F, uv, J); }

/* t in [0, 1] with 2 cosh(2 t l1) + 2 cosh(2 t l2) = K (the energy of the
 * map over the reference, below), by bisection: the function rises with t */
static double reference_t(double l1, double l2, double K)
{
    if (2 * cosh(2 * l1) + 2 * cosh(2 * l2) <= K) return 1.0;
    double lo = 0, hi = 1;
    for (int it = 0; it < 40; it++) {
        double mid = 0.5 * (lo + hi);
        if (2 * cosh(2 * mid * l1) + 2 * cosh(2 * mid * l2) <= K) lo = mid;
        else hi = mid;
    }
    return lo;
}

double sq_sd_reference(const sq_sd_face *F, const double uv[6], double K, sq_sd_face *R)
{
    *R = *F;
    if (F->area == 0) return 1.0;
    double J[4];
    jacobian(F, uv, J);
    double det = J[0] * J[3] - J[1] * J[2];
    if (!(det > 0)) return 1.0;
    /* J = Rot(phi) diag(s1, s2) Rot(theta) (closed-form 2x2 SVD; s2 from
     * the determinant, which keeps its relative precision when s2 << s1) */
    double e = 0.5 * (J[0] + J[3]), f = 0.5 * (J[0] - J[3]);
    double g = 0.5 * (J[2] + J[1]), h = 0.5 * (J[2] - J[1]);
    double s1 = hypot(e, h) + hypot(f, g), s2 = det / s1;
    double a1 = atan2(g, f), a2 = atan2(h, e);
    double theta = 0.5 * (a2 - a1), phi = 0.5 * (a2 + a1);
    double l1 = log(s1), l2 = log(s2);
    if (!isfinite(l1) || !isfinite(l2)) return 1.0;
    double t = reference_t(l1, l2, K);
    if (t >= 1.0) return 1.0;
    /* the reference's Jacobian from the surface's frame: Rot(phi)
     * diag(r1, r2) Rot(theta), r = s^(1 - t); G_ref = G Rinv with
     * Rinv = Rot(-theta) diag(1/r1, 1/r2) Rot(-phi) */
    double ir1 = exp(-(1 - t) * l1), ir2 = exp(-(1 - t) * l2);
    double ct = cos(theta), st = sin(theta), cp = cos(phi), sp = sin(phi);
    /* Rot(-theta) = [[ct, st], [-st, ct]], Rot(-phi) = [[cp, sp], [-sp, cp]] */
    double M[2][2] = {{ct * ir1, st * ir2}, {-st * ir1, ct * ir2}};
    double Ri[2][2] = {{M[0][0] * cp - M[0][1] * sp, M[0][0] * sp + M[0][1] * cp},
                       {M[1][0] * cp - M[1][1] * sp, M[1][0] * sp + M[1][1] * cp}};
    for (int c = 0; c < 3; c++)
        for (int b = 0; b < 2; b++) R->G[c][b] = F->G[c][0] * Ri[0][b] + F->G[c][1] * Ri[1][b];
    if (!isfinite(R->G[0][0] + R->G[0][1] + R->G[1][0] + R->G[1][1] + R->G[2][0] + R->G[2][1])) {
        *R = *F;
        return 1.0;
    }
    return t;
}

double sq_sd_max_step(const double uv[6], const double duv[6])
{
    double u1 = uv[2] - uv[0], v1 = uv[3] - uv[1], u2 = uv[4] - uv[0], v2 = uv[5] - uv[1];
    double du1 = duv[2] - duv[0], dv1 = duv[3] - duv[1], du2 = duv[4] - duv[0],
           dv2 = duv[5] - duv[1];
    /* det(alpha) = a alpha^2 + b alpha + c */
    double c = u1 * v2 - v1 * u2;
    double b = u1 * dv2 + du1 * v2 - v1 * du2 - dv1 * u2;
    double a = du1 * dv2 - dv1 * du2;
    double t = INFINITY;
    if (fabs(a) <= 1e-14 * (fabs(b) + fabs(c))) {
        if (b < 0) t = -c / b;
    } else {
        double disc = b * b - 4 * a * c;
        if (disc >= 0) {
            double sq = sqrt(disc);
            double q = -0.5 * (b + (b >= 0 ? sq : -sq));
            double r1 = q / a, r2 = q != 0 ? c / q : INFINITY;
            if (r1 > 0) t = fmin(t, r1);
            if (r2 > 0) t = fmin(t, r2);
        }
    }
    return t;
}

/* a*d - b*c with the rounding of b*c compensated (Kahan) */
static double det2(double a, double b, double c, double d)
{
    double w = b * c;
    double e = fma(-b, c, w);
    double f = fma(a, d, -w);
    return f + e;
}

/* sq_optimize_internal.h. The corners are taken relative to the first; the
 * determinant is the UV cross product (FMA-compensated) times det X^-1, so
 * a triangle of width 1e-93 is measured right. */
double sq_sd_log_stretch(const sq_sd_face *F, const double uv[6])
{
    double du1 = uv[2] - uv[0], dv1 = uv[3] - uv[1], du2 = uv[4] - uv[0], dv2 = uv[5] - uv[1];
    /* J[a][b] = sum_c uv[c][a] G[c][b], with corner 0 at the origin */
    double J00 = du1 * F->G[1][0] + du2 * F->G[2][0], J01 = du1 * F->G[1][1] + du2 * F->G[2][1];
    double J10 = dv1 * F->G[1][0] + dv2 * F->G[2][0], J11 = dv1 * F->G[1][1] + dv2 * F->G[2][1];
    double cross = det2(du1, du2, dv1, dv2);
    double dxi = det2(F->G[1][0], F->G[1][1], F->G[2][0], F->G[2][1]);
    double det = cross * dxi;
    double E = 0.5 * (J00 + J11), Fh = 0.5 * (J00 - J11), Gh = 0.5 * (J10 + J01), H = 0.5 * (J10 - J01);
    double s1 = hypot(E, H) + hypot(Fh, Gh);
    if (!(det > 0) || !(s1 > 0) || !isfinite(s1)) return 1000.0;
    double s2 = det / s1;
    if (!(s2 > 0)) return 1000.0;
    return fmax(log(s1), -log(s2));
}

double sq_map_conformal_mean(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    double sum = 0, area = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h[3] = {m->f_he[f], 0, 0};
        h[1] = m->he_next[h[0]];
        h[2] = m->he_next[h[1]];
        const double *p0 = m->pos + 3 * (size_t)m->he_vert[h[0]];
        const double *p1 = m->pos + 3 * (size_t)m->he_vert[h[1]];
        const double *p2 = m->pos + 3 * (size_t)m->he_vert[h[2]];
        double e1[3], e2[3];
        for (int i = 0; i < 3; i++) e1[i] = p1[i] - p0[i], e2[i] = p2[i] - p0[i];
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        double a2 = sqrt(cx * cx + cy * cy + cz * cz), l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        if (!(a2 > 0) || !(l1 > 0)) continue;
        /* the surface triangle in a 2D frame: x1 = (l1, 0), x2 = (a, b) */
        double a = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1, b = a2 / l1;
        const double *u0 = M->he_uv + 2 * (size_t)h[0], *u1 = M->he_uv + 2 * (size_t)h[1],
                     *u2 = M->he_uv + 2 * (size_t)h[2];
        double du1[2] = {u1[0] - u0[0], u1[1] - u0[1]}, du2[2] = {u2[0] - u0[0], u2[1] - u0[1]};
        /* J = [du1 du2] X^-1, X = [[l1, a], [0, b]] */
        double J00 = du1[0] / l1, J10 = du1[1] / l1;
        double J01 = (du2[0] - a * J00) / b, J11 = (du2[1] - a * J10) / b;
        double fro = J00 * J00 + J01 * J01 + J10 * J10 + J11 * J11, det = J00 * J11 - J01 * J10;
        if (!(det > 0)) continue;
        double d = sqrt(fmax(fro * fro - 4 * det * det, 0.0));
        double s1 = sqrt(0.5 * (fro + d)), s2 = det / s1;
        sum += 0.5 * a2 * (s1 / s2);
        area += 0.5 * a2;
    }
    return area > 0 ? sum / area : INFINITY;
}
