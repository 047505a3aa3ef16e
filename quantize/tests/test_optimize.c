/* Tests of the distortion optimizer (quantize/sq_optimize*.c,
 * sq_uv_basis.c):
 *  - the per-triangle energy: 4 at an isometry with zero gradient; the
 *    gradient matches central differences of psi; the projected Hessian is
 *    symmetric positive semidefinite and equals the numerical projection
 *    (central differences of the gradient, Jacobi eigen-decomposition,
 *    negative eigenvalues set to zero); the largest safe step degenerates the
 *    triangle exactly there;
 *  - the fixed-transition basis reproduces the map at z0 and keeps every
 *    seam for any z;
 *  - integer-grid maps quantized from published maps (eight, holes3,
 *    sculpt at 1K quads; every model with SQ_LONG_TESTS): optimized with
 *    fixed transitions, the map is still an integer-grid map (sq_map_check
 *    with SQ_MAP_REQUIRE_INTEGER), with the same rotations, translations
 *    and cone points bit for bit, a lower mean energy (recomputed here
 *    independently of the report), and it extracts into a quad mesh with
 *    the same quad count;
 *  - optimizing the result again never makes it worse;
 *  - param's map of eight quantized at 1K: its triangles thinner than
 *    rounding are held, the rest optimized; still an integer-grid map with
 *    the same transitions and quad count;
 *  - a map failing sq_map_check is refused;
 *  - progressive references: the map's energy over a triangle's reference
 *    is the bound K where the reference is not the surface's own, and the
 *    map over it is a pure stretch (a symmetric Jacobian); a triangle within
 *    K keeps its surface shape; on param's map of knot1 (mean energy 2e6),
 *    10 iterations with references end at less than half the energy of 10
 *    without, and the map is still exact with the same rotations;
 *  - step 0, the relaxation, on param's map of fandisk: its thinnest
 *    triangle (1e-93 of its longest side squared) widens by more than 50
 *    orders of magnitude, with the transitions and the cones' corners bit
 *    for bit;
 *  - free translations where the snapped result is refused
 *    (sq_optimize_map_free_or_fixed): on param's map of fandisk, 12
 *    iterations include a round with the transitions fixed; the map is
 *    exact, with the same rotations and cones, and its mean conformal ratio
 *    lower;
 *  - quantization's step 0 (sq_quantize_prepare, through
 *    sq_optimize_map_free_or_fixed): the published map of knot1 (mean
 *    conformal ratio 1.32) and param's (559) both come out exact, with the
 *    same rotations and cones, param's below the published map's ratio;
 *    param's, quantized at 20K quads, extracts into a quad mesh with no
 *    quad folded or turned over after untangling (param's map as it is
 *    leaves one upside down);
 *  - face_scale: knot1's published map with half its faces drawn toward
 *    twice the surface's size: their UV area per area grows more than
 *    twofold against the others', the map valid with its rotations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "sq_test_model.h"

#include "sq_extract.h"
#include "sq_map.h"
#include "sq_optimize.h"
#include "sq_optimize_internal.h"
#include "sq_param.h"
#include "sq_predicates.h"
#include "sq_quantize.h"
#include "sq_uv_basis.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static double rnd(void) /* in [-1, 1) */
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) / 4503599627370496.0 - 1.0;
}

static void test_energy_isometry(void **state)
{
    (void)state;
    double p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, p2[3] = {0.3, 0.8, 0};
    sq_sd_face F;
    assert_int_equal(sq_sd_prepare(p0, p1, p2, 1.0, &F), 1);
    /* the same triangle rotated by 30 degrees and moved */
    double c = cos(0.5236), s = sin(0.5236), uv[6];
    const double *P[3] = {p0, p1, p2};
    for (int k = 0; k < 3; k++) {
        uv[2 * k] = c * P[k][0] - s * P[k][1] + 5;
        uv[2 * k + 1] = s * P[k][0] + c * P[k][1] - 2;
    }
    assert_true(fabs(sq_sd_psi(&F, uv) - 4.0) < 1e-12);
    double g[6], H[36];
    sq_sd_grad_hess(&F, uv, 1.0, g, H);
    for (int k = 0; k < 6; k++) assert_true(fabs(g[k]) < 1e-12);
    /* flipped: infinite */
    double fl[6] = {uv[0], uv[1], uv[4], uv[5], uv[2], uv[3]};
    assert_true(isinf(sq_sd_psi(&F, fl)));
}

/* eigenvalues of a symmetric 6x6 matrix are >= -tol: by trying to
 * Cholesky-factor H + tol I */
static int psd6(const double H[36], double tol)
{
    double L[36] = {0};
    for (int i = 0; i < 6; i++)
        for (int j = 0; j <= i; j++) {
            double s = H[i * 6 + j] + (i == j ? tol : 0);
            for (int k = 0; k < j; k++) s -= L[i * 6 + k] * L[j * 6 + k];
            if (i == j) {
                if (!(s > 0)) return 0;
                L[i * 6 + i] = sqrt(s);
            } else {
                L[i * 6 + j] = s / L[j * 6 + j];
            }
        }
    return 1;
}

static void test_energy_derivatives(void **state)
{
    (void)state;
    int tried = 0;
    for (int trial = 0; trial < 200; trial++) {
        double p[3][3], uv[6];
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++) p[k][i] = rnd();
        for (int k = 0; k < 6; k++) uv[k] = rnd();
        sq_sd_face F;
        if (!sq_sd_prepare(p[0], p[1], p[2], 1.0, &F)) continue;
        if (!isfinite(sq_sd_psi(&F, uv))) continue;
        double g[6], H[36];
        double psi = sq_sd_grad_hess(&F, uv, 1.0, g, H);
        if (psi > 1e4) continue; /* keep central differences accurate */
        tried++;
        for (int k = 0; k < 6; k++) {
            double h = 1e-6, a[6], b[6];
            memcpy(a, uv, sizeof a);
            memcpy(b, uv, sizeof b);
            a[k] += h;
            b[k] -= h;
            double fd = F.area * (sq_sd_psi(&F, a) - sq_sd_psi(&F, b)) / (2 * h);
            assert_true(fabs(fd - g[k]) <= 1e-4 * (1 + fabs(g[k])));
        }
        double hmax = 0;
        for (int k = 0; k < 36; k++) {
            assert_true(fabs(H[k] - H[(k % 6) * 6 + k / 6]) <= 1e-9 * (1 + fabs(H[k])));
            hmax = fmax(hmax, fabs(H[k]));
        }
        assert_true(psd6(H, 1e-9 * hmax + 1e-12));
    }
    assert_true(tried >= 50);
}

static void test_max_step(void **state)
{
    (void)state;
    int tried = 0;
    for (int trial = 0; trial < 500; trial++) {
        double uv[6], d[6];
        for (int k = 0; k < 6; k++) uv[k] = rnd(), d[k] = 3 * rnd();
        if (sq_orient2d(uv, uv + 2, uv + 4) <= 0) continue;
        double a = sq_sd_max_step(uv, d);
        if (!isfinite(a)) continue;
        tried++;
        /* positive just before, zero (to rounding) at a */
        double t[6], scale = 0;
        for (int k = 0; k < 6; k++) t[k] = uv[k] + 0.999 * a * d[k], scale = fmax(scale, fabs(uv[k]) + fabs(a * d[k]));
        assert_true(sq_orient2d(t, t + 2, t + 4) >= 0);
        for (int k = 0; k < 6; k++) t[k] = uv[k] + a * d[k];
        double det = (t[2] - t[0]) * (t[5] - t[1]) - (t[3] - t[1]) * (t[4] - t[0]);
        assert_true(fabs(det) <= 1e-9 * scale * scale);
    }
    assert_true(tried >= 50);
}

static void quantized(const char *name, double quads, model *md, sq_map *igm)
{
    sq_error err;
    sq_map M;
    load(name, md);
    if (sq_map_from_soup(&md->soup, &md->mesh, md->valence, 1e-9, 0, &M, NULL, &err))
        fail_msg("%s: %s", name, err.msg);
    sq_quantize_options qo = {quads, 0, SQ_TARGETS_MAP, 0, 0};
    if (sq_quantize(&M, &qo, igm, NULL, &err)) fail_msg("%s: %s", name, err.msg);
    sq_map_free(&M);
}

static void test_basis_fixed(void **state)
{
    (void)state;
    model md;
    sq_map igm;
    quantized("eight", 1000, &md, &igm);
    sq_uv_basis B;
    sq_error err;
    assert_int_equal(sq_uv_basis_fixed_transitions(&igm, &B, &err), SQ_OK);
    const sq_mesh *m = &igm.mesh;
    double *uv = malloc(2 * (size_t)m->nh * sizeof *uv), *z = malloc(B.nz * sizeof *z);
    assert_non_null(uv);
    assert_non_null(z);
    sq_uv_basis_eval(&B, B.z0, uv);
    for (uint32_t k = 0; k < 2 * m->nh; k++) assert_true(fabs(uv[k] - igm.he_uv[k]) <= 1e-12 * (1 + fabs(uv[k])));
    for (uint32_t i = 0; i < B.nz; i++) z[i] = B.z0[i] + 0.1 * rnd();
    sq_uv_basis_eval(&B, z, uv);
    /* every edge: the twin's corners are the transition of this side's */
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t g = m->he_twin[h];
        uint32_t ends[2][2] = {{h, m->he_next[g]}, {m->he_next[h], g}};
        for (int e = 0; e < 2; e++) {
            double Rp[2];
            sq_map_rotate(igm.he_rot[h], uv + 2 * (size_t)ends[e][0], Rp);
            for (int a = 0; a < 2; a++)
                assert_true(fabs(Rp[a] + igm.he_t[2 * (size_t)h + a] - uv[2 * (size_t)ends[e][1] + a]) <= 1e-9);
        }
    }
    free(uv);
    free(z);
    sq_uv_basis_free(&B);
    sq_map_free(&igm);
    unload(&md);
}

static double mean_energy_here(const sq_map *M)
{
    /* independent of sq_optimize_energy's bookkeeping: surface scaled to
     * the map's area, then the area mean of psi */
    const sq_mesh *m = &M->mesh;
    double a3 = 0, auv = 0, sum = 0, area = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h0 = m->f_he[f], h1 = m->he_next[h0], h2 = m->he_next[h1];
        const double *u0 = M->he_uv + 2 * (size_t)h0, *u1 = M->he_uv + 2 * (size_t)h1,
                     *u2 = M->he_uv + 2 * (size_t)h2;
        auv += 0.5 * ((u1[0] - u0[0]) * (u2[1] - u0[1]) - (u1[1] - u0[1]) * (u2[0] - u0[0]));
        const double *p0 = m->pos + 3 * (size_t)m->he_vert[h0], *p1 = m->pos + 3 * (size_t)m->he_vert[h1],
                     *p2 = m->pos + 3 * (size_t)m->he_vert[h2];
        double e1[3], e2[3];
        for (int i = 0; i < 3; i++) e1[i] = p1[i] - p0[i], e2[i] = p2[i] - p0[i];
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        a3 += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    double s = sqrt(auv / a3);
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h0 = m->f_he[f], h1 = m->he_next[h0], h2 = m->he_next[h1];
        double uv[6];
        uint32_t hc[3] = {h0, h1, h2};
        for (int k = 0; k < 3; k++) uv[2 * k] = M->he_uv[2 * (size_t)hc[k]], uv[2 * k + 1] = M->he_uv[2 * (size_t)hc[k] + 1];
        sq_sd_face F;
        if (!sq_sd_prepare(m->pos + 3 * (size_t)m->he_vert[h0], m->pos + 3 * (size_t)m->he_vert[h1],
                           m->pos + 3 * (size_t)m->he_vert[h2], s, &F))
            continue;
        sum += F.area * sq_sd_psi(&F, uv);
        area += F.area;
    }
    return sum / area;
}

static void optimize_igm(const char *name, double quads)
{
    model md;
    sq_map igm;
    sq_error err;
    quantized(name, quads, &md, &igm);
    const sq_mesh *m = &igm.mesh;
    uint8_t *rot = malloc(m->nh);
    double *t = malloc(2 * (size_t)m->nh * sizeof *t), *cone_uv = malloc(2 * (size_t)m->nh * sizeof *cone_uv);
    assert_non_null(rot);
    assert_non_null(t);
    assert_non_null(cone_uv);
    memcpy(rot, igm.he_rot, m->nh);
    memcpy(t, igm.he_t, 2 * (size_t)m->nh * sizeof *t);
    memcpy(cone_uv, igm.he_uv, 2 * (size_t)m->nh * sizeof *cone_uv);
    double before = mean_energy_here(&igm);
    sq_quad_mesh q0;
    assert_int_equal(sq_extract(&igm, &q0, NULL, &err), SQ_OK);

    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
    opt.max_iterations = 20;
    sq_optimize_report rep;
    if (sq_optimize_map(&igm, &opt, &rep, &err)) fail_msg("%s: %s", name, err.msg);
    print_message("%s %.0f: energy %.4g -> %.4g (worst %.4g -> %.4g), %u iterations, %.2f s: %s\n", name,
                  quads, rep.energy_before, rep.energy_after, rep.max_energy_before, rep.max_energy_after,
                  rep.iterations, rep.seconds, rep.why);
    assert_int_equal(rep.changed, 1);
    if (sq_map_check(&igm, SQ_MAP_REQUIRE_INTEGER, &err)) fail_msg("%s: %s", name, err.msg);
    assert_memory_equal(rot, igm.he_rot, m->nh);
    for (uint32_t k = 0; k < 2 * m->nh; k++) assert_true(t[k] == igm.he_t[k]); /* -0 == 0 */
    for (uint32_t h = 0; h < m->nh; h++)
        if (igm.valence[m->he_vert[h]] != 4) {
            assert_true(igm.he_uv[2 * (size_t)h] == cone_uv[2 * (size_t)h]);
            assert_true(igm.he_uv[2 * (size_t)h + 1] == cone_uv[2 * (size_t)h + 1]);
        }
    double after = mean_energy_here(&igm);
    assert_true(after < before);
    assert_true(fabs(after - rep.energy_after) <= 1e-9 * after);

    sq_quad_mesh q1;
    assert_int_equal(sq_extract(&igm, &q1, NULL, &err), SQ_OK);
    assert_int_equal(q1.nq, q0.nq);
    sq_quad_mesh_free(&q0);
    sq_quad_mesh_free(&q1);

    /* again: never worse */
    sq_optimize_report rep2;
    assert_int_equal(sq_optimize_map(&igm, &opt, &rep2, &err), SQ_OK);
    assert_true(mean_energy_here(&igm) <= after * (1 + 1e-12));
    if (sq_map_check(&igm, SQ_MAP_REQUIRE_INTEGER, &err)) fail_msg("%s: %s", name, err.msg);

    free(rot);
    free(t);
    free(cone_uv);
    sq_map_free(&igm);
    unload(&md);
}

static void test_optimize_igm(void **state)
{
    (void)state;
    if (getenv("SQ_LONG_TESTS")) {
        static const char *all[] = {"block", "cup", "eight", "elk", "fandisk", "femur", "fertility_tri",
                                    "genus3", "helmet", "holes3", "homer", "knot1", "rocker_arm",
                                    "sculpt", "trim-star"};
        for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) optimize_igm(all[i], 1000);
    } else {
        optimize_igm("eight", 1000);
        optimize_igm("holes3", 1000);
        optimize_igm("sculpt", 1000);
    }
}

static void test_refuses_bad_map(void **state)
{
    (void)state;
    model md;
    sq_map igm;
    sq_error err;
    quantized("eight", 1000, &md, &igm);
    /* fold the first triangle: swap two corners' UVs */
    uint32_t h0 = igm.mesh.f_he[0], h1 = igm.mesh.he_next[h0];
    double tmp[2] = {igm.he_uv[2 * h0], igm.he_uv[2 * h0 + 1]};
    igm.he_uv[2 * h0] = igm.he_uv[2 * h1];
    igm.he_uv[2 * h0 + 1] = igm.he_uv[2 * h1 + 1];
    igm.he_uv[2 * h1] = tmp[0];
    igm.he_uv[2 * h1 + 1] = tmp[1];
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    assert_int_not_equal(sq_optimize_map(&igm, &opt, NULL, &err), SQ_OK);
    assert_non_null(strstr(err.msg, "face"));
    sq_map_free(&igm);
    unload(&md);
}

/* param's map of eight (exact, integer, a refinement with triangles far
 * below rounding) with the given cone tree, quantized: the optimizer holds
 * the triangles it cannot move (among them any of infinite energy: the
 * integer-grid map of the default tree has triangles flat in 3D), lowers
 * the energy of the rest or keeps it, and the result is an integer-grid
 * map with the same transitions that extracts into as many quads. With the
 * surface tree, 10 iterations lower it. */
static void param_igm_case(const model *md, int tree, int must_lower)
{
    sq_error err;
    sq_param P;
    sq_param_init(&P);
    sq_param_options po;
    sq_param_options_default(&po);
    po.tree = tree;
    if (sq_param_build(&md->mesh, md->valence, &po, &P, NULL, &err)) fail_msg("param: %s", err.msg);
    char path[256];
    snprintf(path, sizeof path, "/tmp/sq_test_optimize_%d.obj", (int)getpid());
    if (sq_param_write_obj(path, &P, &err)) fail_msg("%s", err.msg);
    sq_map M, igm;
    if (sq_map_read(path, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, NULL, &err))
        fail_msg("param map read back: %s", err.msg);
    unlink(path);
    sq_param_free(&P);
    sq_quantize_options qo = {1000, 0, SQ_TARGETS_MAP, 0, 0};
    if (sq_quantize(&M, &qo, &igm, NULL, &err)) fail_msg("quantize: %s", err.msg);
    const sq_mesh *m = &igm.mesh;
    uint8_t *rot = malloc(m->nh);
    double *t = malloc(2 * (size_t)m->nh * sizeof *t);
    assert_non_null(rot);
    assert_non_null(t);
    memcpy(rot, igm.he_rot, m->nh);
    memcpy(t, igm.he_t, 2 * (size_t)m->nh * sizeof *t);
    sq_quad_mesh q0, q1;
    assert_int_equal(sq_extract(&igm, &q0, NULL, &err), SQ_OK);
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
    opt.max_iterations = 10;
    sq_optimize_report rep;
    if (sq_optimize_map(&igm, &opt, &rep, &err)) fail_msg("%s", err.msg);
    print_message("param eight (tree %s) 1000: %u held, energy %.4g -> %.4g, %u iterations: %s\n",
                  tree == SQ_TREE_SURFACE ? "surface" : "auto", rep.held_triangles, rep.energy_before,
                  rep.energy_after, rep.iterations, rep.why);
    assert_true(rep.held_triangles > 0);
    assert_true(isfinite(rep.energy_before) && rep.energy_after <= rep.energy_before);
    if (must_lower) {
        assert_int_equal(rep.changed, 1);
        assert_true(rep.energy_after < rep.energy_before);
    }
    if (sq_map_check(&igm, SQ_MAP_REQUIRE_INTEGER, &err)) fail_msg("%s", err.msg);
    assert_memory_equal(rot, igm.he_rot, m->nh);
    for (uint32_t k = 0; k < 2 * m->nh; k++) assert_true(t[k] == igm.he_t[k]);
    assert_int_equal(sq_extract(&igm, &q1, NULL, &err), SQ_OK);
    assert_int_equal(q1.nq, q0.nq);
    sq_quad_mesh_free(&q0);
    sq_quad_mesh_free(&q1);
    free(rot);
    free(t);
    sq_map_free(&igm);
    sq_map_free(&M);
}

static void test_param_igm(void **state)
{
    (void)state;
    model md;
    load("eight", &md);
    param_igm_case(&md, SQ_TREE_SURFACE, 1);
    param_igm_case(&md, SQ_TREE_AUTO, 0);
    unload(&md);
}

/* Eigen-decomposition of a symmetric 4x4 matrix by cyclic Jacobi rotations
 * (the reference for the optimizer's closed-form projection) */
static void jacobi4(double A[4][4], double w[4], double V[4][4])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) V[i][j] = i == j;
    for (int sweep = 0; sweep < 60; sweep++) {
        for (int p = 0; p < 3; p++)
            for (int q = p + 1; q < 4; q++) {
                if (A[p][q] == 0) continue;
                double th = (A[q][q] - A[p][p]) / (2 * A[p][q]);
                double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1));
                double c = 1 / sqrt(t * t + 1), sn = t * c;
                for (int k = 0; k < 4; k++) {
                    double a = A[k][p], b = A[k][q];
                    A[k][p] = c * a - sn * b, A[k][q] = sn * a + c * b;
                }
                for (int k = 0; k < 4; k++) {
                    double a = A[p][k], b = A[q][k];
                    A[p][k] = c * a - sn * b, A[q][k] = sn * a + c * b;
                }
                for (int k = 0; k < 4; k++) {
                    double a = V[k][p], b = V[k][q];
                    V[k][p] = c * a - sn * b, V[k][q] = sn * a + c * b;
                }
            }
    }
    for (int i = 0; i < 4; i++) w[i] = A[i][i];
}

/* The closed-form projection of the Hessian (sq_sd_grad_hess) against a
 * numerical one: on the unit right triangle with corner 0 at the origin the
 * UVs of corners 1 and 2 are J's columns, so the 4x4 block of H for them is
 * the projected Hessian in J (area 1/2 times it). The exact Hessian comes
 * from central differences of the analytic gradient, its projection from
 * Jacobi rotations with negative eigenvalues set to 0. */
static void test_hessian_projection(void **state)
{
    (void)state;
    double p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, p2[3] = {0, 1, 0};
    sq_sd_face F;
    assert_int_equal(sq_sd_prepare(p0, p1, p2, 1.0, &F), 1);
    /* uv index 2..5 <-> J entries 00, 10, 01, 11 (vec order 0, 2, 1, 3) */
    static const int vj[4] = {0, 2, 1, 3};
    int negative = 0, tried = 0;
    for (int trial = 0; trial < 400; trial++) {
        double uv[6] = {0, 0, 1 + 0.8 * rnd(), 0.8 * rnd(), 0.8 * rnd(), 1 + 0.8 * rnd()};
        if (trial % 3 == 0) uv[3] *= 0.1, uv[4] *= 3; /* more anisotropic */
        if (!isfinite(sq_sd_psi(&F, uv)) || sq_sd_psi(&F, uv) > 1e3) continue;
        tried++;
        double g[6], H[36], A[4][4];
        sq_sd_grad_hess(&F, uv, 1.0, g, H);
        for (int i = 0; i < 4; i++) {
            double a[6], b[6], ga[6], gb[6], Ha[36];
            memcpy(a, uv, sizeof a), memcpy(b, uv, sizeof b);
            double h = 1e-6;
            a[2 + i] += h, b[2 + i] -= h;
            sq_sd_grad_hess(&F, a, 1.0, ga, Ha);
            sq_sd_grad_hess(&F, b, 1.0, gb, Ha);
            for (int j = 0; j < 4; j++) A[vj[i]][vj[j]] = (ga[2 + j] - gb[2 + j]) / (2 * h) / F.area;
        }
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < i; j++) A[i][j] = A[j][i] = 0.5 * (A[i][j] + A[j][i]);
        double w[4], V[4][4];
        jacobi4(A, w, V);
        double scale = 0;
        for (int k = 0; k < 4; k++) {
            if (w[k] < 0) negative++;
            scale = fmax(scale, fabs(w[k]));
        }
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double ref = 0;
                for (int k = 0; k < 4; k++)
                    if (w[k] > 0) ref += V[vj[i]][k] * w[k] * V[vj[j]][k];
                double got = H[(2 + i) * 6 + 2 + j] / F.area;
                if (!(fabs(got - ref) <= 1e-5 * scale))
                    fail_msg("projected Hessian entry (%d, %d): %.10g, numerically %.10g (scale %g)", i, j, got, ref, scale);
            }
    }
    /* both cases occur: some Hessians needed the projection, most not */
    assert_true(tried > 200 && negative > 10);
}

/* J of the map uv over the face F (as sq_optimize_energy.c computes it) */
static void face_jacobian(const sq_sd_face *F, const double uv[6], double J[4])
{
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            J[2 * a + b] = uv[a] * F->G[0][b] + uv[2 + a] * F->G[1][b] + uv[4 + a] * F->G[2][b];
}

static void test_reference(void **state)
{
    (void)state;
    int bounded = 0, kept = 0;
    for (int trial = 0; trial < 2000; trial++) {
        double p[3][3], uv[6];
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++) p[k][i] = rnd();
        /* corners from 1e-6 to 1 in size, so energies from 4 to 1e12 */
        double sc = pow(10.0, -6.0 * (0.5 * rnd() + 0.5));
        for (int k = 0; k < 6; k++) uv[k] = (k % 2 ? sc : 1.0) * rnd();
        sq_sd_face F, R;
        if (!sq_sd_prepare(p[0], p[1], p[2], 1.0, &F)) continue;
        double psi = sq_sd_psi(&F, uv);
        if (!isfinite(psi)) continue;
        double K = trial % 2 ? 16.0 : 1000.0;
        double t = sq_sd_reference(&F, uv, K, &R);
        assert_true(t >= 0 && t <= 1);
        assert_true(R.area == F.area);
        if (psi <= K) {
            assert_true(t == 1.0);
            assert_memory_equal(&R, &F, sizeof R);
            kept++;
            continue;
        }
        assert_true(t < 1.0);
        double pr = sq_sd_psi(&R, uv);
        if (!(fabs(pr - K) <= 1e-6 * K)) fail_msg("energy over the reference %.17g, bound %g (t %g)", pr, K, t);
        double J[4];
        face_jacobian(&R, uv, J);
        double nj = sqrt(J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3]);
        /* to the precision of the SVD's angles, which falls with the
         * triangle's anisotropy (about sqrt(psi)) */
        if (!(fabs(J[1] - J[2]) <= 1e-12 * sqrt(psi) * nj)) fail_msg("not a pure stretch: %g %g (norm %g, psi %g, t %g)", J[1], J[2], nj, psi, t);
        assert_true(J[0] > 0 && J[3] > 0);
        bounded++;
    }
    assert_true(bounded > 500 && kept > 50);
}

/* param's map of md written to a temporary OBJ named by tag (path gets
 * its name; the caller unlinks it) */
static void write_param_map(const model *md, const char *tag, char *path, size_t cap)
{
    sq_error err;
    sq_param P;
    sq_param_init(&P);
    if (sq_param_build(&md->mesh, md->valence, NULL, &P, NULL, &err)) fail_msg("param: %s", err.msg);
    snprintf(path, cap, "/tmp/sq_test_optimize_%s_%d.obj", tag, (int)getpid());
    if (sq_param_write_obj(path, &P, &err)) fail_msg("%s", err.msg);
    sq_param_free(&P);
}

/* param's map of md, read back exact (through a temporary OBJ) */
static void read_param_map(const model *md, const char *tag, sq_map *M)
{
    char path[256];
    sq_error err;
    write_param_map(md, tag, path, sizeof path);
    if (sq_map_read(path, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT, M, NULL, &err))
        fail_msg("param map read back: %s", err.msg);
    unlink(path);
}

static void test_progressive_param(void **state)
{
    (void)state;
    model md;
    sq_error err;
    load("knot1", &md);
    char path[256];
    write_param_map(&md, "p", path, sizeof path);
    sq_map M[2];
    sq_optimize_report rep[2];
    for (int k = 0; k < 2; k++) {
        if (sq_map_read(path, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT, &M[k], NULL, &err))
            fail_msg("param map read back: %s", err.msg);
        sq_optimize_options opt;
        memset(&opt, 0, sizeof opt);
        opt.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
        opt.max_iterations = 10;
        opt.reference_bound = k == 0 ? 0 : INFINITY;
        opt.relax_bound = INFINITY; /* the iterations alone, from the same start */
        if (sq_optimize_map(&M[k], &opt, &rep[k], &err)) fail_msg("%s", err.msg);
        print_message("knot1 param, references %s: energy %.4g -> %.4g in %u iterations (%u with references)\n",
                      k ? "off" : "on", rep[k].energy_before, rep[k].energy_after, rep[k].iterations,
                      rep[k].reference_iterations);
        assert_int_equal(rep[k].changed, 1);
        if (sq_map_check(&M[k], 0, &err)) fail_msg("%s", err.msg);
    }
    unlink(path);
    assert_true(rep[0].reference_iterations > 0 && rep[1].reference_iterations == 0);
    assert_true(rep[0].energy_before == rep[1].energy_before);
    assert_true(rep[0].energy_after < 0.5 * rep[1].energy_after);
    assert_memory_equal(M[0].he_rot, M[1].he_rot, M[0].mesh.nh);
    sq_map_free(&M[0]);
    sq_map_free(&M[1]);
    unload(&md);
}

/* the thinnest UV triangle, 2 area / (longest side)^2 (scale-free) */
static double thinnest(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    double thin = INFINITY;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        const double *a = M->he_uv + 2 * (size_t)h, *b = M->he_uv + 2 * (size_t)m->he_next[h];
        const double *c = M->he_uv + 2 * (size_t)m->he_next[m->he_next[h]];
        double l = fmax(fmax(hypot(b[0] - a[0], b[1] - a[1]), hypot(c[0] - b[0], c[1] - b[1])),
                        hypot(a[0] - c[0], a[1] - c[1]));
        /* (b - a) x (c - a) with the product's rounding compensated */
        double p = (c[0] - a[0]) * (b[1] - a[1]);
        double e = fma(c[0] - a[0], b[1] - a[1], -p);
        double cross = fma(b[0] - a[0], c[1] - a[1], -p) - e;
        thin = fmin(thin, cross / (l * l));
    }
    return thin;
}

/* Step 0 (sq_optimize_relax.c) on param's map of fandisk, whose slivers
 * (1e-93 wide) Newton's rounded steps cannot move: one iteration with fixed
 * transitions; the thinnest triangle must widen by more than 50 orders of
 * magnitude, the worst stretch the report gives likewise, and the map stay
 * exact with the same transitions and the cones where they were. */
static void test_relax_param(void **state)
{
    (void)state;
    model md;
    sq_error err;
    load("fandisk", &md);
    sq_map M;
    read_param_map(&md, "r", &M);
    const sq_mesh *m = &M.mesh;
    double *uv0 = malloc(2 * (size_t)m->nh * sizeof *uv0), *t0 = malloc(2 * (size_t)m->nh * sizeof *t0);
    uint8_t *rot0 = malloc(m->nh);
    assert_non_null(uv0);
    assert_non_null(t0);
    assert_non_null(rot0);
    memcpy(uv0, M.he_uv, 2 * (size_t)m->nh * sizeof *uv0);
    memcpy(t0, M.he_t, 2 * (size_t)m->nh * sizeof *t0);
    memcpy(rot0, M.he_rot, m->nh);
    double thin0 = thinnest(&M);
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
    opt.max_iterations = 1;
    sq_optimize_report rep;
    if (sq_optimize_map(&M, &opt, &rep, &err)) fail_msg("%s", err.msg);
    double thin1 = thinnest(&M);
    print_message("fandisk param: %u relaxation moves, worst stretch %.3g -> %.3g, thinnest triangle "
                  "%.3g -> %.3g\n",
                  rep.relax_moves, rep.relax_stretch_before, rep.relax_stretch_after, thin0, thin1);
    assert_true(rep.relax_moves > 0 && rep.changed);
    assert_true(thin0 > 0 && thin0 < 1e-80);
    assert_true(thin1 > 1e50 * thin0);
    assert_true(rep.relax_stretch_before > 1e50 * rep.relax_stretch_after);
    if (sq_map_check(&M, 0, &err)) fail_msg("%s", err.msg);
    assert_memory_equal(rot0, M.he_rot, m->nh);
    for (uint32_t k = 0; k < 2 * m->nh; k++) assert_true(t0[k] == M.he_t[k]);
    for (uint32_t h = 0; h < m->nh; h++)
        if (M.valence[m->he_vert[h]] != 4) {
            assert_true(M.he_uv[2 * (size_t)h] == uv0[2 * (size_t)h]);
            assert_true(M.he_uv[2 * (size_t)h + 1] == uv0[2 * (size_t)h + 1]);
        }
    free(uv0);
    free(t0);
    free(rot0);
    sq_map_free(&M);
    unload(&md);
}

static void test_free_or_fixed(void **state)
{
    (void)state;
    model md;
    sq_error err;
    load("fandisk", &md);
    sq_map M;
    read_param_map(&md, "f", &M);
    uint8_t *rot = malloc(M.mesh.nh);
    assert_non_null(rot);
    memcpy(rot, M.he_rot, M.mesh.nh);
    double before = sq_map_conformal_mean(&M);
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
    opt.max_iterations = 12;
    sq_optimize_report rep;
    if (sq_optimize_map_free_or_fixed(&M, &opt, &rep, &err)) fail_msg("%s", err.msg);
    double after = sq_map_conformal_mean(&M);
    print_message("fandisk param, free or fixed: mean conformal ratio %.4g -> %.4g, %u iterations in %u runs "
                  "(%u with fixed transitions): %s\n",
                  before, after, rep.iterations, rep.rounds, rep.fixed_rounds, rep.why);
    assert_true(rep.fixed_rounds >= 1 && rep.rounds > rep.fixed_rounds && rep.changed);
    assert_true(rep.iterations > 0 && rep.iterations <= 12);
    assert_true(after < before);
    if (sq_map_check(&M, 0, &err)) fail_msg("%s", err.msg);
    assert_memory_equal(rot, M.he_rot, M.mesh.nh);
    for (uint32_t v = 0; v < md.mesh.nv; v++) assert_int_equal(M.valence[v], md.valence[v]);
    free(rot);
    sq_map_free(&M);
    unload(&md);
}

/* the quad mesh of M at `quads`: its quads still folded or turned over
 * after untangling */
static uint32_t bad_quads_after_untangling(const sq_map *M, double quads)
{
    sq_quantize_options qo = {quads, 0, SQ_TARGETS_MAP, 1, 0};
    sq_map igm;
    sq_quad_mesh Q;
    sq_untangle_stats us;
    sq_error err;
    if (sq_quantize(M, &qo, &igm, NULL, &err)) fail_msg("quantize: %s", err.msg);
    if (sq_extract(&igm, &Q, NULL, &err)) fail_msg("extract: %s", err.msg);
    if (sq_extract_untangle(&igm, &Q, &us, &err)) fail_msg("untangle: %s", err.msg);
    sq_quad_mesh_free(&Q);
    sq_map_free(&igm);
    return us.folded_after;
}

/* M prepared (sq_quantize_prepare): exact, the same rotations and cones,
 * a lower mean conformal ratio; returns that ratio */
static double prepared(const char *what, sq_map *M)
{
    sq_error err;
    uint8_t *rot = malloc(M->mesh.nh);
    int32_t *val = malloc(M->mesh.nv * sizeof *val);
    assert_non_null(rot);
    assert_non_null(val);
    memcpy(rot, M->he_rot, M->mesh.nh);
    memcpy(val, M->valence, M->mesh.nv * sizeof *val);
    sq_quantize_prepare_report pr;
    if (sq_quantize_prepare(M, NULL, &pr, &err)) fail_msg("%s: %s", what, err.msg);
    print_message("%s: mean conformal ratio %.4g -> %.4g, %u iterations in %u runs (%u with fixed "
                  "transitions): %s\n",
                  what, pr.conformal_before, pr.conformal_after, pr.optimize.iterations, pr.optimize.rounds,
                  pr.optimize.fixed_rounds, pr.optimize.why);
    assert_true(pr.conformal_after < pr.conformal_before);
    assert_true(pr.conformal_after == sq_map_conformal_mean(M));
    if (sq_map_check(M, 0, &err)) fail_msg("%s: %s", what, err.msg);
    assert_memory_equal(rot, M->he_rot, M->mesh.nh);
    assert_memory_equal(val, M->valence, M->mesh.nv * sizeof *val);
    free(rot);
    free(val);
    return pr.conformal_after;
}

/* The model and its published map (the vt of its OBJ), exact. */
static void load_published(const char *name, model *md, sq_map *M)
{
    sq_error err;
    load(name, md);
    if (sq_map_from_soup(&md->soup, &md->mesh, md->valence, 1e-9, 0, M, NULL, &err))
        fail_msg("%s: published map: %s", name, err.msg);
}

/* UV area over 3D area, summed over the faces with (or without) mark */
static double uv_per_area(const sq_map *M, const uint8_t *mark, int want)
{
    const sq_mesh *m = &M->mesh;
    double uv = 0, a3 = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        if (mark[f] != want) continue;
        uint32_t h = m->f_he[f];
        const uint32_t h1 = m->he_next[h], h2 = m->he_next[h1];
        const double *a = M->he_uv + 2 * (size_t)h, *b = M->he_uv + 2 * (size_t)h1, *c = M->he_uv + 2 * (size_t)h2;
        uv += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        a3 += sq_mesh_face_area(m, f);
    }
    return uv / a3;
}

/* face_scale: knot1's published map with the faces on one side of a plane
 * drawn toward twice the surface's size: their UV area per surface area
 * must grow against the others' by more than 2 (4 where nothing resists),
 * the map stay valid with the same rotations and cones. */
static void test_face_scale(void **state)
{
    (void)state;
    model md;
    sq_error err;
    sq_map M;
    load_published("knot1", &md, &M);
    const sq_mesh *m = &M.mesh;
    double *scale = malloc((size_t)m->nf * sizeof *scale);
    uint8_t *mark = malloc(m->nf);
    uint8_t *rot = malloc(m->nh);
    assert_true(scale && mark && rot);
    memcpy(rot, M.he_rot, m->nh);
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t v = 0; v < m->nv; v++) lo = fmin(lo, m->pos[3 * (size_t)v]), hi = fmax(hi, m->pos[3 * (size_t)v]);
    for (uint32_t f = 0; f < m->nf; f++) {
        const double x = m->pos[3 * (size_t)m->he_vert[m->f_he[f]]];
        mark[f] = x < 0.5 * (lo + hi);
        scale[f] = mark[f] ? 2.0 : 1.0;
    }
    const double before = uv_per_area(&M, mark, 1) / uv_per_area(&M, mark, 0);
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
    opt.max_iterations = 50;
    opt.face_scale = scale;
    opt.keep_last = 1;
    sq_optimize_report rep;
    if (sq_optimize_map(&M, &opt, &rep, &err)) fail_msg("%s", err.msg);
    const double after = uv_per_area(&M, mark, 1) / uv_per_area(&M, mark, 0);
    print_message("knot1 published, half the faces at twice the size: UV area per area, those over the others, "
                  "%.3f -> %.3f in %u iterations\n", before, after, rep.iterations);
    assert_true(rep.changed && after > 2 * before);
    if (sq_map_check(&M, 0, &err)) fail_msg("%s", err.msg);
    assert_memory_equal(rot, M.he_rot, m->nh);
    for (uint32_t v = 0; v < m->nv; v++) assert_int_equal(M.valence[v], md.valence[v]);
    free(scale), free(mark), free(rot);
    sq_map_free(&M);
    unload(&md);
}

static void test_quantize_prepare(void **state)
{
    (void)state;
    model md;
    sq_map pub;
    load_published("knot1", &md, &pub);
    double published = sq_map_conformal_mean(&pub);
    assert_true(published > 1.3 && published < 1.35);
    prepared("knot1 published", &pub);
    sq_map_free(&pub);
    /* param's map (param is deterministic: the same map twice) */
    sq_map M, raw;
    read_param_map(&md, "q", &M);
    read_param_map(&md, "q", &raw);
    assert_memory_equal(M.he_uv, raw.he_uv, 2 * (size_t)M.mesh.nh * sizeof *M.he_uv);
    assert_true(sq_map_conformal_mean(&M) > 100);
    assert_true(prepared("knot1 param", &M) < published);
    uint32_t bad_raw = bad_quads_after_untangling(&raw, 20000), bad = bad_quads_after_untangling(&M, 20000);
    print_message("knot1 param at 20K quads: %u quads folded or turned over after untangling from the map as "
                  "it is, %u from the prepared map\n", bad_raw, bad);
    assert_int_equal(bad, 0);
    sq_map_free(&M);
    sq_map_free(&raw);
    unload(&md);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_energy_isometry),  cmocka_unit_test(test_energy_derivatives),
        cmocka_unit_test(test_max_step),         cmocka_unit_test(test_basis_fixed),
        cmocka_unit_test(test_optimize_igm),     cmocka_unit_test(test_refuses_bad_map),
        cmocka_unit_test(test_param_igm),        cmocka_unit_test(test_reference),
        cmocka_unit_test(test_hessian_projection),
        cmocka_unit_test(test_progressive_param), cmocka_unit_test(test_relax_param),
        cmocka_unit_test(test_free_or_fixed),    cmocka_unit_test(test_quantize_prepare),
        cmocka_unit_test(test_face_scale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
