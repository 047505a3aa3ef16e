/* Tests of quad smoothing (stages/sq_smooth.h) and its closest-point BVH
 * (stages/sq_closest_point.h) on the shared meshes.
 *
 * CI runs a bounded sample (a few meshes, few iterations); SQ_LONG=1 runs
 * every input of docs/smooth.md with the default iteration count. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_closest_point.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_smooth.h"
#include "sq_smooth_internal.h"

static const char *shared_dir(void)
{
    const char *d = getenv("SQ_SHARED_DIR");
    return d && *d ? d : SQ_SHARED_DIR;
}

static int long_mode(void)
{
    const char *l = getenv("SQ_LONG");
    return l && *l && strcmp(l, "0");
}

static void load(const char *rel, sq_soup *s, unsigned flags)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/data/%s", shared_dir(), rel);
    sq_error err;
    sq_mesh m;
    memset(s, 0, sizeof *s);
    sq_status st = sq_read_mesh(path, s, &err);
    if (st != SQ_OK) fail_msg("%s: %s", path, err.msg);
    st = sq_mesh_from_soup(s, flags, &m, &err);
    if (st != SQ_OK) fail_msg("%s: %s", path, err.msg);
    sq_mesh_free(&m);
}

static double diag_of(const sq_soup *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < s->nv; v++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], s->pos[3 * v + k]), hi[k] = fmax(hi[k], s->pos[3 * v + k]);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* ---- closest point: the BVH agrees exactly with a brute-force scan ---- */
static void test_closest_point_matches_brute_force(void **state)
{
    (void)state;
    sq_soup s;
    load("libigl/bunny.off", &s, 0);
    sq_cp_tree t;
    sq_error err;
    assert_int_equal(sq_cp_tree_build(s.nv, s.pos, s.nf, s.face_idx, &t, &err), SQ_OK);
    double d = diag_of(&s);
    uint64_t rng = 12345;
    for (int i = 0; i < 300; i++) {
        double p[3];
        uint32_t v = (uint32_t)((rng = rng * 6364136223846793005ull + 1442695040888963407ull) >> 33) % s.nv;
        for (int k = 0; k < 3; k++) {
            rng = rng * 6364136223846793005ull + 1442695040888963407ull;
            p[k] = s.pos[3 * v + k] + 0.05 * d * ((double)(rng >> 11) / 9007199254740992.0 - 0.5);
        }
        sq_cp_hit hit;
        sq_cp_tree_query(&t, p, &hit);
        double best = INFINITY;
        for (uint32_t f = 0; f < s.nf; f++) {
            const uint32_t *c = s.face_idx + 3 * f;
            double bary[3], q[3];
            sq_closest_point_triangle(p, s.pos + 3 * c[0], s.pos + 3 * c[1], s.pos + 3 * c[2], bary, q);
            double d2 = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
            if (d2 < best) best = d2;
        }
        assert_true(hit.dist2 == best);
        assert_true(hit.bary[0] >= 0 && hit.bary[1] >= 0 && hit.bary[2] >= 0);
        assert_true(fabs(hit.bary[0] + hit.bary[1] + hit.bary[2] - 1.0) < 1e-12);
    }
    sq_cp_tree_free(&t);
    sq_soup_free(&s);
}

/* ---- closest point on needles: points on a side are their own closest
 * point, within rounding, for triangles of height 1e-6 .. 1e-12 of their
 * length (the inputs' needles); and off the plane, the projection is as
 * near as a side's point ---- */
static void test_closest_point_needles(void **state)
{
    (void)state;
    const double a[3] = {0.1, 0.2, 0.3}, b[3] = {1.1, 0.7, 0.2};
    double worst = 0;
    for (int e = 6; e <= 12; e++) {
        const double h = pow(10.0, -e);
        const double c[3] = {0.4 + 0.2 * h, 0.35 - h, 0.27 + 0.7 * h}; /* near side ab */
        const double *corner[3] = {a, b, c};
        for (int i = 1; i < 100; i++) {
            const double t = i / 100.0;
            for (int k = 0; k < 3; k++) {
                const double *x = corner[k], *y = corner[(k + 1) % 3];
                double p[3], bary[3], q[3];
                for (int d = 0; d < 3; d++) p[d] = x[d] + t * (y[d] - x[d]);
                sq_closest_point_triangle(p, a, b, c, bary, q);
                const double dist = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                         (p[2] - q[2]) * (p[2] - q[2]));
                if (dist > worst) worst = dist;
                assert_true(bary[0] >= 0 && bary[1] >= 0 && bary[2] >= 0);
                assert_true(fabs(bary[0] + bary[1] + bary[2] - 1.0) < 1e-12);
            }
        }
    }
    assert_true(worst < 1e-14);
}

static void test_fold_margin(void **state)
{
    (void)state;
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {1, 1, 0}, d[3] = {0, 1, 0};
    assert_true(fabs(sq_quad_fold_margin(a, b, c, d) - 1.0) < 1e-15);
    /* bow-tie: corners c and d swapped folds both triangulations */
    assert_true(sq_quad_fold_margin(a, b, d, c) < 0.0);
    /* degenerate: a repeated point counts as folded */
    assert_true(sq_quad_fold_margin(a, b, b, d) == -1.0);
    /* non-convex dart: one triangulation folds, the other does not */
    double e[3] = {0.4, 0.4, 0};
    assert_true(sq_quad_fold_margin(a, b, e, d) > 0.0);
}

/* Catmull-Clark-style split: every triangle becomes three quads (corner,
 * edge midpoints, centroid). Vertices: input, then one per edge, then one
 * per face. */
static void split_triangles(const sq_soup *s, uint32_t *nv_out, double **pos_out, uint32_t *nq_out, uint32_t **q_out)
{
    sq_mesh m;
    sq_error err;
    assert_int_equal(sq_mesh_from_soup(s, 0, &m, &err), SQ_OK);
    uint32_t *edge = malloc(m.nh * sizeof(uint32_t)), ne = 0;
    for (uint32_t h = 0; h < m.nh; h++)
        if (h < m.he_twin[h]) edge[h] = edge[m.he_twin[h]] = ne++;
    uint32_t nv = s->nv + ne + s->nf, nq = 3 * s->nf;
    double *pos = malloc(3 * (size_t)nv * sizeof(double));
    uint32_t *q = malloc(4 * (size_t)nq * sizeof(uint32_t));
    memcpy(pos, s->pos, 3 * (size_t)s->nv * sizeof(double));
    for (uint32_t h = 0; h < m.nh; h++) {
        uint32_t a = m.he_vert[h], b = m.he_vert[m.he_next[h]];
        for (int k = 0; k < 3; k++) pos[3 * (s->nv + edge[h]) + k] = 0.5 * (s->pos[3 * a + k] + s->pos[3 * b + k]);
    }
    for (uint32_t f = 0; f < s->nf; f++) {
        uint32_t g = s->nv + ne + f;
        for (int k = 0; k < 3; k++)
            pos[3 * g + k] = (s->pos[3 * s->face_idx[3 * f] + k] + s->pos[3 * s->face_idx[3 * f + 1] + k] +
                              s->pos[3 * s->face_idx[3 * f + 2] + k]) / 3.0;
        for (uint32_t j = 0; j < 3; j++) { /* halfedge 3f+j starts at corner j */
            uint32_t h = 3 * f + j, hp = 3 * f + (j + 2) % 3;
            uint32_t *o = q + 4 * (3 * f + j);
            o[0] = s->face_idx[3 * f + j], o[1] = s->nv + edge[h], o[2] = g, o[3] = s->nv + edge[hp];
        }
    }
    free(edge);
    sq_mesh_free(&m);
    *nv_out = nv, *pos_out = pos, *nq_out = nq, *q_out = q;
}

/* Smooths and asserts the properties: quality improves (mean
 * |corner angle - 90| decreases), every vertex on the surface within 1e-9
 * of the diagonal (checked with a fresh BVH), no folded quad, connectivity
 * unchanged. */
static void smooth_and_check_pins(const sq_soup *surf, uint32_t nv, double *pos, uint32_t nq,
                                  const uint32_t *quads, int iterations, double pin_threshold, const char *name,
                                  sq_smooth_stats *stats_out)
{
    uint32_t *q0 = malloc(4 * (size_t)nq * sizeof(uint32_t));
    memcpy(q0, quads, 4 * (size_t)nq * sizeof(uint32_t));
    sq_smooth_options o;
    sq_smooth_options_default(&o);
    o.iterations = long_mode() ? 10 : iterations;
    o.pin_threshold = pin_threshold;
    sq_smooth_stats st;
    sq_error err;
    sq_status rc = sq_smooth_quads(surf->nv, surf->pos, surf->nf, surf->face_idx, nv, pos, nq, quads, &o, &st, &err);
    if (rc != SQ_OK) fail_msg("%s: %s", name, err.msg);
    print_message("%s: %u quads, mean|a-90| %.3f -> %.3f deg, min sJ %.4f -> %.4f, edge ratio %.4f -> %.4f, "
                  "folded %u -> %u, dist %.2g -> %.2g, %d+%d iterations, %d backtracks, %d retries, %.1f s (%s)\n",
                  name, nq, st.before.angle_mean_dev_deg, st.after.angle_mean_dev_deg, st.before.sjac_min,
                  st.after.sjac_min, st.before.edge_ratio_mean, st.after.edge_ratio_mean, st.before.folded,
                  st.after.folded, st.dist_before_rel, st.dist_after_rel, st.untangle_iterations, st.iterations,
                  st.backtracks, st.retries, st.seconds, st.stop_reason);
    assert_memory_equal(q0, quads, 4 * (size_t)nq * sizeof(uint32_t));
    assert_true(st.after.angle_mean_dev_deg < st.before.angle_mean_dev_deg);
    /* the acceptance test (docs/smooth.md): from the untangled state on, no
     * measure gets worse and the mean angle deviation improves */
    assert_true(st.after.angle_mean_dev_deg < st.untangled.angle_mean_dev_deg);
    assert_true(st.after.sjac_min >= st.untangled.sjac_min);
    assert_true(st.after.edge_ratio_mean <= st.untangled.edge_ratio_mean);
    assert_true(st.iterations >= 1);
    assert_int_equal(st.after.folded, 0);
    assert_true(st.after.fold_margin_min > 0.0);
    /* independent check of the surface distance */
    sq_cp_tree t;
    assert_int_equal(sq_cp_tree_build(surf->nv, surf->pos, surf->nf, surf->face_idx, &t, &err), SQ_OK);
    double d = diag_of(surf), worst = 0.0;
    for (uint32_t v = 0; v < nv; v++) {
        sq_cp_hit hit;
        sq_cp_tree_query(&t, pos + 3 * (size_t)v, &hit);
        worst = fmax(worst, sqrt(hit.dist2) / d);
    }
    assert_true(worst <= 1e-9);
    sq_cp_tree_free(&t);
    free(q0);
    if (stats_out) *stats_out = st;
}

static void smooth_and_check(const sq_soup *surf, uint32_t nv, double *pos, uint32_t nq, const uint32_t *quads,
                             int iterations, const char *name)
{
    sq_smooth_options o;
    sq_smooth_options_default(&o);
    smooth_and_check_pins(surf, nv, pos, nq, quads, iterations, o.pin_threshold, name, NULL);
}

/* The widest gap between a surface vertex and the quad surface (each quad
 * split along its shorter diagonal, as the referee does), over the
 * diagonal: a BVH over the quads' triangles, built here (the BVH equals a
 * brute-force scan: test_closest_point_matches_brute_force). */
static double widest_gap(const sq_soup *surf, uint32_t nv, const double *pos, uint32_t nq, const uint32_t *quads)
{
    uint32_t *tri = malloc(6 * (size_t)nq * sizeof(uint32_t));
    assert_non_null(tri);
    for (uint32_t q = 0; q < nq; q++) {
        const uint32_t *f = quads + 4 * (size_t)q;
        const double *x[4] = {pos + 3 * (size_t)f[0], pos + 3 * (size_t)f[1], pos + 3 * (size_t)f[2],
                              pos + 3 * (size_t)f[3]};
        double d02 = 0.0, d13 = 0.0;
        for (int k = 0; k < 3; k++)
            d02 += (x[2][k] - x[0][k]) * (x[2][k] - x[0][k]), d13 += (x[3][k] - x[1][k]) * (x[3][k] - x[1][k]);
        const int t[2][6] = {{0, 1, 2, 0, 2, 3}, {0, 1, 3, 1, 2, 3}};
        for (int j = 0; j < 6; j++) tri[6 * (size_t)q + j] = f[t[d02 > d13][j]];
    }
    sq_cp_tree tree;
    sq_error err;
    assert_int_equal(sq_cp_tree_build(nv, pos, 2 * nq, tri, &tree, &err), SQ_OK);
    double worst = 0.0;
    for (uint32_t i = 0; i < surf->nv; i++) {
        sq_cp_hit hit;
        sq_cp_tree_query(&tree, surf->pos + 3 * (size_t)i, &hit);
        worst = fmax(worst, sqrt(hit.dist2));
    }
    sq_cp_tree_free(&tree);
    free(tri);
    return worst / diag_of(surf);
}

static void run_split(const char *rel, int iterations)
{
    sq_soup s;
    load(rel, &s, 0);
    uint32_t nv, nq, *quads;
    double *pos;
    split_triangles(&s, &nv, &pos, &nq, &quads);
    smooth_and_check(&s, nv, pos, nq, quads, iterations, rel);
    free(pos), free(quads);
    sq_soup_free(&s);
}

static void run_quads(const char *quads_rel, const char *surf_rel, int iterations)
{
    sq_soup s, q;
    load(surf_rel, &s, 0);
    load(quads_rel, &q, SQ_MESH_ALLOW_POLYGONS);
    assert_int_equal(q.face_off[q.nf], 4 * q.nf);
    smooth_and_check(&s, q.nv, q.pos, q.nf, q.face_idx, iterations, quads_rel);
    sq_soup_free(&s);
    sq_soup_free(&q);
}

static void test_split_helmet(void **state) { (void)state; run_split("mpz/helmet.obj", 5); }
static void test_split_double_torus(void **state)
{
    (void)state;
#ifdef __SANITIZE_ADDRESS__
    if (!long_mode()) skip(); /* 18K quads: too slow under ASan */
#endif
    run_split("gpjs/double-torus.obj", 1);
}
static void test_split_bunny_long(void **state)
{
    (void)state;
    if (!long_mode()) skip();
    run_split("libigl/bunny.off", 10);
}

/* folded input: 3 folded quads, vertices up to 5e-3 of the diagonal off */
static void test_elephant_untangle(void **state)
{
    (void)state;
    run_quads("quads/elephant_quadriflow5k.obj", "cid/elephant.obj", 3);
}

static void test_3holes(void **state)
{
    (void)state;
    run_quads("quads/3holes_quadriflow5k.obj", "libigl/3holes.off", 3);
}

/* Fidelity pins (docs/smooth.md, "Fidelity"): on QuadriFlow's bunny the
 * pinned run closes the widest surface-to-quads gap further than the run
 * without pins, every pinned vertex sits exactly on a surface vertex, and
 * the quality promise holds for both (smooth_and_check_pins). */
static void test_pins_close_the_gap(void **state)
{
    (void)state;
    sq_soup s, q0, q1;
    load("libigl/bunny.off", &s, 0);
    load("quads/bunny_quadriflow5k.obj", &q0, SQ_MESH_ALLOW_POLYGONS);
    load("quads/bunny_quadriflow5k.obj", &q1, SQ_MESH_ALLOW_POLYGONS);
    sq_smooth_stats off, on;
    smooth_and_check_pins(&s, q0.nv, q0.pos, q0.nf, q0.face_idx, 4, 0.0, "bunny, no pins", &off);
    smooth_and_check_pins(&s, q1.nv, q1.pos, q1.nf, q1.face_idx, 4, 0.3, "bunny, pins", &on);
    assert_int_equal(off.pinned, 0);
    assert_true(on.pinned > 0);
    uint32_t on_vertex = 0;
    for (uint32_t v = 0; v < q1.nv; v++)
        for (uint32_t i = 0; i < s.nv; i++)
            if (!memcmp(q1.pos + 3 * (size_t)v, s.pos + 3 * (size_t)i, 3 * sizeof(double))) {
                on_vertex++;
                break;
            }
    assert_true(on_vertex >= on.pinned);
    double g0 = widest_gap(&s, q0.nv, q0.pos, q0.nf, q0.face_idx);
    double g1 = widest_gap(&s, q1.nv, q1.pos, q1.nf, q1.face_idx);
    print_message("bunny: widest gap %.5f without pins, %.5f with %u pins\n", g0, g1, on.pinned);
    assert_true(g1 < g0);
    sq_soup_free(&s), sq_soup_free(&q0), sq_soup_free(&q1);
}

static void test_quads_long(void **state)
{
    (void)state;
    if (!long_mode()) skip();
    run_quads("quads/fertility_quadriflow5k.obj", "libigl/fertility.off", 10);
    run_quads("quads/bunny_quadriflow5k.obj", "libigl/bunny.off", 10);
    run_quads("quads/botijo_quadriflow5k.obj", "avaxman/botijo.off", 10);
}

/* ---- a corner's angle stays on its branch during a solve ------------- */

/* A quad whose corner 0 is 2 degrees wide (a sliver corner, as quantize's
 * bent quads on femur have): moving corner 3 across corner 0's other edge
 * makes that corner -2 degrees. With the branch of the solve's start
 * (base_angle) the angle residual moves by about 4 degrees, continuously;
 * without it, it jumps by 360 degrees (the wrap into (0, 360)), which made
 * Levenberg-Marquardt reject most steps on such quads. */
static void test_angle_branch_continuity(void **state)
{
    (void)state;
    const double deg = 3.14159265358979323846 / 180.0;
    uint32_t quad[4] = {0, 1, 2, 3};
    double h[4] = {1, 1, 1, 1}, normal[3] = {0, 0, 1}, threshold = -INFINITY, frame[36];
    for (int k = 0; k < 4; k++) {
        double f[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(frame + 9 * k, f, sizeof f);
    }
    /* counterclockwise: corner 0 at the origin, corner 1 along +x, corner 3
     * at +2 degrees from it */
    double base[12] = {0, 0, 0, 1, 0, 0, 2, 1, 0, cos(2 * deg), sin(2 * deg), 0};
    sq_smooth_ctx c;
    memset(&c, 0, sizeof c);
    c.nv = 4, c.nq = 1, c.quads = quad, c.base = base, c.frame = frame, c.h = h;
    c.ref_normal = normal, c.threshold = &threshold;
    c.wa = 1.0, c.wl = 1.0, c.wb = 0.0;
    const double *x[4] = {base, base + 3, base + 6, base + 9};
    double r0[SQ_SMOOTH_MAX_RES], r1[SQ_SMOOTH_MAX_RES], r2[SQ_SMOOTH_MAX_RES];
    assert_int_equal(sq_smooth_quad_residuals(&c, 0, x, r0), 1);
    double branch[4];
    for (int k = 0; k < 4; k++) branch[k] = r0[k] + 0.5 * 3.14159265358979323846;
    assert_true(fabs(branch[0] - 2 * deg) < 1e-12);
    double moved[12];
    memcpy(moved, base, sizeof moved);
    moved[9] = cos(-2 * deg), moved[10] = sin(-2 * deg); /* corner 0 now -2 degrees */
    const double *y[4] = {moved, moved + 3, moved + 6, moved + 9};
    assert_int_equal(sq_smooth_quad_residuals(&c, 0, y, r1), 1); /* no branch: wraps */
    c.base_angle = branch;
    assert_int_equal(sq_smooth_quad_residuals(&c, 0, y, r2), 1);
    print_message("corner 0: residual %.2f deg at the start, %.2f wrapped, %.2f on the branch\n", r0[0] / deg,
                  r1[0] / deg, r2[0] / deg);
    assert_true(fabs(r1[0] - r0[0] - 356 * deg) < 1e-9);
    assert_true(fabs(r2[0] - r0[0] + 4 * deg) < 1e-9);
}

/* ---- the residuals' derivatives agree with central differences -------- */

/* One quad's residual callback, its Jacobian against central differences
 * in the parameters, on 200 random quads around a square: mildly and
 * strongly skewed, with the barrier off and active, with and without the
 * untangling terms. */
static void test_residual_derivatives(void **state)
{
    (void)state;
    uint32_t quad[4] = {0, 1, 2, 3};
    unsigned seed = 7;
    int barrier_seen = 0;
    for (int t = 0; t < 200; t++) {
        double base[12], frame[36], h[4] = {1, 1, 1, 1}, normal[3] = {0, 0, 1};
        double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, skew = t < 100 ? 0.15 : 0.45;
        for (int k = 0; k < 4; k++) {
            base[3 * k] = sq[k][0] + skew * ((double)rand_r(&seed) / RAND_MAX - 0.5);
            base[3 * k + 1] = sq[k][1] + skew * ((double)rand_r(&seed) / RAND_MAX - 0.5);
            /* half the quads a saddle bent enough for the barrier to act */
            double amp = t % 4 < 2 ? 0.1 * ((double)rand_r(&seed) / RAND_MAX - 0.5)
                                   : 0.4 + 0.4 * (double)rand_r(&seed) / RAND_MAX;
            base[3 * k + 2] = k % 2 ? -amp : amp;
            double a = 6.28318 * rand_r(&seed) / RAND_MAX; /* tangent frame turned by a */
            double f[9] = {cos(a), sin(a), 0, -sin(a), cos(a), 0, 0, 0, 1};
            memcpy(frame + 9 * k, f, sizeof f);
            h[k] = 0.5 + (double)rand_r(&seed) / RAND_MAX;
        }
        unsigned char untangle = (unsigned char)(t % 2);
        double threshold = t % 4 < 2 ? -INFINITY : -0.9, target[4], ideal[4];
        sq_smooth_targets(4, 1, quad, target, ideal);
        sq_smooth_ctx c;
        memset(&c, 0, sizeof c);
        c.nv = 4, c.nq = 1, c.quads = quad, c.base = base, c.frame = frame, c.h = h;
        c.ref_normal = normal, c.untangle = &untangle, c.threshold = &threshold;
        c.target = target, c.ideal_log = ideal;
        c.wa = 1.0, c.wl = 0.7, c.wu = 4.0, c.wb = 0.1;
        double ab[4][2], *param[4];
        for (int k = 0; k < 4; k++) {
            ab[k][0] = 0.05 * ((double)rand_r(&seed) / RAND_MAX - 0.5);
            ab[k][1] = 0.05 * ((double)rand_r(&seed) / RAND_MAX - 0.5);
            param[k] = ab[k];
        }
        double r[SQ_SMOOTH_MAX_RES], J[4][2 * SQ_SMOOTH_MAX_RES], *jac[4] = {J[0], J[1], J[2], J[3]};
        if (!sq_smooth_residual_cb(&c, 0, (const double *const *)param, r, jac)) continue;
        uint32_t nr = sq_smooth_residual_count(&c, 0);
        barrier_seen += r[8] != 0.0;
        for (int k = 0; k < 4; k++)
            for (int d = 0; d < 2; d++) {
                double rp[SQ_SMOOTH_MAX_RES], rm[SQ_SMOOTH_MAX_RES], x0 = ab[k][d], eps = 1e-6;
                ab[k][d] = x0 + eps;
                int okp = sq_smooth_residual_cb(&c, 0, (const double *const *)param, rp, NULL);
                ab[k][d] = x0 - eps;
                int okm = sq_smooth_residual_cb(&c, 0, (const double *const *)param, rm, NULL);
                ab[k][d] = x0;
                if (!okp || !okm) continue;
                for (uint32_t i = 0; i < nr; i++) {
                    double num = (rp[i] - rm[i]) / (2 * eps), an = J[k][2 * i + d];
                    if (fabs(num - an) > 1e-5 * fmax(1.0, fabs(num)))
                        fail_msg("quad %d residual %u by vertex %d coordinate %d: analytic %.9g, numeric %.9g", t,
                                 i, k, d, an, num);
                }
            }
    }
    assert_true(barrier_seen > 0); /* the numeric part was exercised too */
}

static void test_rejects_bad_arguments(void **state)
{
    (void)state;
    double tp[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t tri[3] = {0, 1, 2}, quad[4] = {0, 1, 2, 7};
    double qp[12] = {0};
    sq_smooth_stats st;
    sq_error err;
    assert_int_equal(sq_smooth_quads(3, tp, 1, tri, 4, qp, 1, quad, NULL, &st, &err), SQ_ERR_INDEX);
    assert_non_null(strstr(err.msg, "vertex 7"));
    assert_int_equal(sq_smooth_quads(3, tp, 1, tri, 4, qp, 0, quad, NULL, &st, &err), SQ_ERR_EMPTY);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fold_margin),
        cmocka_unit_test(test_residual_derivatives),
        cmocka_unit_test(test_angle_branch_continuity),
        cmocka_unit_test(test_rejects_bad_arguments),
        cmocka_unit_test(test_closest_point_matches_brute_force),
        cmocka_unit_test(test_closest_point_needles),
        cmocka_unit_test(test_split_helmet),
        cmocka_unit_test(test_split_double_torus),
        cmocka_unit_test(test_elephant_untangle),
        cmocka_unit_test(test_3holes),
        cmocka_unit_test(test_pins_close_the_gap),
        cmocka_unit_test(test_split_bunny_long),
        cmocka_unit_test(test_quads_long),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
