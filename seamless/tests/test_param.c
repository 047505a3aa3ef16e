/* seamquad: end-to-end tests of sq_param_build (seed 7, 8) on the shared
 * cone files, checked by our own verifier and by the independent referee
 * (../shared/tools/check_param.py).
 *
 * What must hold (docs/param.md, "Results"):
 * - mpz/eight (seed 1) and mpz/cup (seed 3, with the seed 9.2 guidance and
 *   the seed 9.4 tree that are the default for genus >= 2; without them the
 *   same cut fails): seamless
 *   integer-grid maps that the referee passes with --integer and
 *   sq_param_verify passes with SQ_PARAM_VERIFY_INTEGER; retries with the
 *   next seed (attempts) find cup's;
 * - every other cone model: the compatible cut is found (never an internal
 *   error), and the run ends either with a valid map or with SQ_ERR_SOLVER
 *   (interior map not injective in doubles, or the Steiner budget); where
 *   the map is returned for diagnosis (allow_flips), the referee's topology,
 *   refinement and integer seam checks pass: only injectivity may fail. */
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

#include "sq_cone_connection.h"
#include "sq_cut_graph.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_predicates.h"
#include "sq_test_mesh.h"
#include "sq_seamless_svg.h"

typedef struct model {
    sq_mesh m;
    int32_t *val;
    char mesh_path[512], cone_path[512];
} model;

static void load(model *M, const char *rel)
{
    memset(M, 0, sizeof *M);
    snprintf(M->mesh_path, sizeof M->mesh_path, "%s/data/%s.obj", SQ_SHARED_DIR, rel);
    snprintf(M->cone_path, sizeof M->cone_path, "%s/data/%s_Th_hat", SQ_SHARED_DIR, rel);
    sq_test_read_mesh(&M->m, M->mesh_path);
    M->val = sq_test_read_valence(M->cone_path, M->m.nv);
}

static void unload(model *M)
{
    sq_mesh_free(&M->m);
    free(M->val);
}

static char *referee(const model *M, const char *obj, int *rc);

/* Writes P to a temporary OBJ and fails unless the referee passes it. */
static void assert_referee_passes(const model *M, const sq_param *P, const char *name)
{
    sq_error err = {0};
    char obj[] = "/tmp/sq_test_param_XXXXXX";
    int fd = mkstemp(obj);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(sq_param_write_obj(obj, P, &err), SQ_OK);
    int rc;
    char *out = referee(M, obj, &rc);
    remove(obj);
    assert_non_null(out);
    if (rc != 0) fail_msg("%s: referee:\n%s", name, out);
    assert_non_null(strstr(out, "check_param: PASS"));
    free(out);
}

/* Runs the referee; returns its output (caller frees) and exit code. */
static char *referee(const model *M, const char *obj, int *rc)
{
    char cmd[2048], out[600];
    snprintf(out, sizeof out, "%s.ref", obj);
    snprintf(cmd, sizeof cmd, "python3 %s/tools/check_param.py %s %s %s --integer > %s 2>&1", SQ_SHARED_DIR,
             M->mesh_path, M->cone_path, obj, out);
    int r = system(cmd);
    *rc = WIFEXITED(r) ? WEXITSTATUS(r) : -1;
    FILE *f = fopen(out, "rb");
    if (!f) return NULL;
    char *buf = calloc(1, 1 << 16);
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    buf[n] = 0;
    fclose(f);
    remove(out);
    return buf;
}

/* mpz/eight with the default options, with the cells only and with the
 * overlay only (step 7'): all three pass; the default keeps the overlay's
 * map, which is far less distorted than the cells' */
static void test_eight_passes(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/eight");
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    sq_error err = {0};
    sq_status s = sq_param_build(&M.m, M.val, NULL, &P, &st, &err);
    if (s) fail_msg("eight: %s", err.msg);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    /* input vertices kept first, bit for bit */
    assert_true(P.nv_input == M.m.nv && P.nv >= P.nv_input);
    assert_memory_equal(P.pos, M.m.pos, 3 * (size_t)M.m.nv * sizeof(double));
    assert_int_equal(st.genus, 2);
    assert_int_equal(st.ncones, 8);
    /* the default (SQ_TREE_AUTO): tree qtri's first attempt passes, with
     * the overlay */
    assert_true(st.attempts == 1 && st.tree_qtri && !st.fallback && st.overlay == 1);
    assert_true(st.chords == 0 && st.cells == 0 && st.rounds == 0);
    assert_referee_passes(&M, &P, "eight");
    /* the surface tree with the cells alone: a map too, far more distorted */
    sq_param Pc;
    sq_param_init(&Pc);
    sq_param_stats sc;
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.interior = SQ_INTERIOR_CELLS;
    s = sq_param_build(&M.m, M.val, &opt, &Pc, &sc, &err);
    if (s) fail_msg("eight, cells: %s", err.msg);
    assert_int_equal(sc.overlay, 0);
    assert_int_equal(sc.cells, sc.chords + 1);
    assert_int_equal(sq_param_verify(&Pc, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    assert_true(st.conformal_mean > 1 && 100 * st.conformal_mean < sc.conformal_mean);
    printf("  eight: overlay %u faces, conformal mean %.3g; cells %u faces, %.3g\n", st.faces_out,
           st.conformal_mean, sc.faces_out, sc.conformal_mean);
    /* tree qtri alone: the same map as the default's */
    sq_param Po;
    sq_param_init(&Po);
    sq_param_stats so;
    opt.interior = SQ_INTERIOR_AUTO, opt.tree = SQ_TREE_QTRI;
    s = sq_param_build(&M.m, M.val, &opt, &Po, &so, &err);
    if (s) fail_msg("eight, tree qtri: %s", err.msg);
    assert_true(so.overlay == 1 && so.tree_qtri && !so.fallback && Po.nf == P.nf && Po.nv == P.nv);
    assert_memory_equal(Po.uv, P.uv, 2 * (size_t)P.nuv * sizeof(double));
    sq_param_free(&Po);
    /* the surface tree with the overlay: a map, less distorted than the
     * cells' */
    sq_param_init(&Po);
    opt.interior = SQ_INTERIOR_OVERLAY, opt.tree = SQ_TREE_AUTO;
    s = sq_param_build(&M.m, M.val, &opt, &Po, &so, &err);
    if (s) fail_msg("eight, overlay: %s", err.msg);
    assert_true(so.overlay == 1 && !so.tree_qtri && so.surface_tree);
    assert_true(100 * so.conformal_mean < sc.conformal_mean);
    assert_referee_passes(&M, &Po, "eight (the surface tree, overlay)");
    sq_param_free(&Po);
    sq_param_free(&Pc);
    sq_param_free(&P);
    unload(&M);
}

/* mpz/cup (genus 2), without refinement rounds (step 7c, see
 * test_refine): with seed 9.2 guidance and the seed 9.4 tree (the default
 * for genus >= 2) cut-graph seed 9 gives a map the referee passes; the
 * same cut without guidance does not (flips in doubles); seed 8 fails with
 * guidance too, so two attempts from seed 8 find seed 9 */
static void test_cup_guided(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/cup");
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.interior = SQ_INTERIOR_CELLS; /* what this test is about */
    opt.seed = 9;
    opt.refine = 0;
    sq_error err = {0};
    sq_status s = sq_param_build(&M.m, M.val, &opt, &P, &st, &err);
    if (s) fail_msg("cup seed 9: %s", err.msg);
    assert_true(st.guided && st.attempts == 1 && st.seed_used == 9);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    assert_referee_passes(&M, &P, "cup");
    sq_param_free(&P);
    /* unguided, same cut: not injective in doubles */
    opt.guidance = SQ_GUIDE_OFF;
    s = sq_param_build(&M.m, M.val, &opt, &P, &st, &err);
    assert_int_equal(s, SQ_ERR_SOLVER);
    assert_non_null(strstr(err.msg, "not injective in floating point"));
    assert_false(st.guided);
    assert_null(P.pos);
    /* guided, seed 8 then 9 */
    opt.guidance = SQ_GUIDE_AUTO;
    opt.seed = 8;
    opt.attempts = 2;
    s = sq_param_build(&M.m, M.val, &opt, &P, &st, &err);
    if (s) fail_msg("cup seeds 8-9: %s", err.msg);
    assert_true(st.attempts == 2 && st.seed_used == 9 && st.surface_tree);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    sq_param_free(&P);
    unload(&M);
}

/* P and Q the same map, bit for bit */
static void assert_same_map(const sq_param *P, const sq_param *Q)
{
    assert_true(P->nv == Q->nv && P->nf == Q->nf && P->nuv == Q->nuv);
    assert_memory_equal(P->pos, Q->pos, 3 * (size_t)P->nv * sizeof *P->pos);
    assert_memory_equal(P->tri, Q->tri, 3 * (size_t)P->nf * sizeof *P->tri);
    assert_memory_equal(P->uv, Q->uv, 2 * (size_t)P->nuv * sizeof *P->uv);
    assert_memory_equal(P->tri_uv, Q->tri_uv, 3 * (size_t)P->nf * sizeof *P->tri_uv);
}

/* Attempts in threads (sq_param_options.threads) give the result of one
 * after another: mpz/cup from seed 8 without rounds passes at attempt 2
 * (seed 9) with 1, 2 and 3 threads, the same map to the bit; with a
 * Steiner budget of 1 every attempt fails, and the last one's error and
 * seed are reported. */
static void test_threads(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/cup");
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.interior = SQ_INTERIOR_CELLS; /* what this test is about */
    opt.seed = 8, opt.attempts = 3, opt.refine = 0;
    sq_param P1, P;
    sq_param_init(&P1);
    sq_param_stats s1, st;
    sq_error err = {0};
    opt.threads = 1;
    if (sq_param_build(&M.m, M.val, &opt, &P1, &s1, &err)) fail_msg("cup, 1 thread: %s", err.msg);
    assert_true(s1.attempts == 2 && s1.seed_used == 9);
    for (uint32_t t = 2; t <= 3; t++) {
        opt.threads = t;
        sq_param_init(&P);
        if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("cup, %u threads: %s", t, err.msg);
        assert_true(st.attempts == s1.attempts && st.seed_used == s1.seed_used && st.faces_out == s1.faces_out);
        assert_same_map(&P, &P1);
        sq_param_free(&P);
    }
    sq_param_free(&P1);
    /* every attempt over the budget */
    opt.max_steiner = 1;
    char msg1[sizeof err.msg];
    opt.threads = 1;
    assert_int_equal(sq_param_build(&M.m, M.val, &opt, &P, &s1, &err), SQ_ERR_SOLVER);
    memcpy(msg1, err.msg, sizeof msg1);
    opt.threads = 2;
    assert_int_equal(sq_param_build(&M.m, M.val, &opt, &P, &st, &err), SQ_ERR_SOLVER);
    assert_true(st.attempts == 3 && s1.attempts == 3 && st.seed_used == 10 && s1.seed_used == 10);
    assert_string_equal(err.msg, msg1);
    assert_null(P.pos);
    unload(&M);
}

/* sq_param_build with 1 thread (into P1, s1) and with 2 (into P, st): the
 * same map bit for bit, the same attempt and seed */
static void build_1_and_2_threads(const model *M, sq_param_options *opt, const char *name, sq_param *P1,
                                  sq_param_stats *s1, sq_param *P, sq_param_stats *st)
{
    sq_error err = {0};
    sq_param_init(P1), sq_param_init(P);
    opt->threads = 1;
    if (sq_param_build(&M->m, M->val, opt, P1, s1, &err)) fail_msg("%s, 1 thread: %s", name, err.msg);
    opt->threads = 2;
    if (sq_param_build(&M->m, M->val, opt, P, st, &err)) fail_msg("%s, 2 threads: %s", name, err.msg);
    assert_true(st->attempts == s1->attempts && st->seed_used == s1->seed_used);
    assert_same_map(P, P1);
}

/* The attempts as one ordered list (sq_param_attempts.c): mpz/eight with
 * an overlay budget of 1 crossing fails tree qtri's 4 attempts and passes
 * at the surface tree's first (attempt 5, seed 1: the fallback, the cells'
 * map), which with two threads runs once qtri's have failed;
 * with 1 and 2 threads the same map to the bit. With budgets of 1 Steiner
 * vertex and 1 crossing every attempt fails (qtri three times, surface
 * three times): the same message with 1 and 2 threads, naming each
 * kind. */
static void test_fallback_threads(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/eight");
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.attempts = 16, opt.max_crossings = 1;
    sq_param P1, P;
    sq_param_stats s1, st;
    sq_error err = {0};
    build_1_and_2_threads(&M, &opt, "eight", &P1, &s1, &P, &st);
    assert_true(s1.attempts == 5 && s1.seed_used == 1 && s1.fallback && !s1.tree_qtri && !s1.overlay);
    assert_true(st.fallback && !st.tree_qtri);
    assert_referee_passes(&M, &P, "eight (fallback, 2 threads)");
    sq_param_free(&P);
    sq_param_free(&P1);
    opt.attempts = 3, opt.max_steiner = 1, opt.max_crossings = 1;
    char msg1[sizeof err.msg];
    opt.threads = 1;
    assert_int_equal(sq_param_build(&M.m, M.val, &opt, &P, &s1, &err), SQ_ERR_SOLVER);
    memcpy(msg1, err.msg, sizeof msg1);
    opt.threads = 2;
    assert_int_equal(sq_param_build(&M.m, M.val, &opt, &P, &st, &err), SQ_ERR_SOLVER);
    assert_string_equal(err.msg, msg1);
    assert_non_null(strstr(err.msg, "(tree qtri, 3 attempts); the fallback ("));
    assert_non_null(strstr(err.msg, "3 attempts) failed too"));
    assert_true(st.attempts == 6 && s1.attempts == 6);
    assert_null(P.pos);
    unload(&M);
}

static double tri_area(const double *p, const double *q, const double *r)
{
    double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Tree qtri where the cut walls a cone in (sq_param_split_walls):
 * mpz/femur's cut graph (seed 1) walls a cone in (every seed does). The
 * split mesh keeps the input's vertices and its genus, puts each new
 * vertex at the exact midpoint of a non-cut edge between two blocked
 * vertices, covers every input face by its own pieces, keeps the cut;
 * after it no edge but a cut edge joins two blocked vertices. Then the
 * whole attempt with --tree qtri passes there, the map named on the input
 * (its vertices first, its faces), and the referee agrees. */
static void test_split_walls(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/femur");
    const sq_mesh *m = &M.m;
    uint8_t *cone = calloc(m->nv, 1);
    assert_non_null(cone);
    for (uint32_t v = 0; v < m->nv; v++) cone[v] = M.val[v] != 4;
    sq_cut_options copt;
    sq_cut_options_default(&copt);
    copt.seed = 1;
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_error err = {0};
    assert_int_equal(sq_cut_graph_build(m, cone, &copt, &G, NULL, &err), SQ_OK);
    { /* steered as param steers it (docs/holonomy.md) */
        double *turn = malloc((size_t)m->nh * sizeof *turn);
        assert_non_null(turn);
        assert_int_equal(sq_cone_connection(m, M.val, turn, NULL, &err), SQ_OK);
        assert_int_equal(sq_cut_graph_steer(m, M.val, turn, &G, NULL, &err), SQ_OK);
        free(turn);
    }
    sq_mesh m2;
    int32_t *val2;
    uint32_t *fparent, n;
    uint8_t *cut2;
    assert_int_equal(sq_param_split_walls(m, M.val, G.he_cut, &m2, &val2, &fparent, &cut2, &n, &err), SQ_OK);
    assert_true(n > 0);
    assert_int_equal(m2.nv, m->nv + n);
    assert_true(sq_mesh_euler(&m2) == sq_mesh_euler(m));
    assert_memory_equal(m2.pos, m->pos, 3 * (size_t)m->nv * sizeof *m->pos);
    uint8_t *blocked = calloc(m2.nv, 1);
    assert_non_null(blocked);
    for (uint32_t v = 0; v < m2.nv; v++) blocked[v] = val2[v] != 4;
    uint32_t ncut = 0, ncut2 = 0;
    for (uint32_t h = 0; h < m->nh; h++) ncut += G.he_cut[h];
    for (uint32_t h = 0; h < m2.nh; h++) {
        ncut2 += cut2[h];
        if (cut2[h]) blocked[m2.he_vert[h]] = 1;
    }
    assert_int_equal(ncut2, ncut);
    for (uint32_t v = 0; v < m->nv; v++) assert_int_equal(val2[v], M.val[v]);
    /* every midpoint: free, exactly between two blocked input vertices
     * that share a non-cut edge of the input */
    for (uint32_t v = m->nv; v < m2.nv; v++) {
        assert_int_equal(val2[v], 4);
        assert_false(blocked[v]);
        int found = 0;
        uint32_t h0 = m2.v_he[v], h = h0;
        do {
            uint32_t a = m2.he_vert[m2.he_next[h]];
            uint32_t g0 = m2.v_he[v], g = g0;
            do {
                uint32_t b = m2.he_vert[m2.he_next[g]];
                if (a < b && a < m->nv && b < m->nv && blocked[a] && blocked[b]) {
                    int mid = 1;
                    for (int d = 0; d < 3; d++)
                        mid &= m2.pos[3 * (size_t)v + d] == 0.5 * (m->pos[3 * (size_t)a + d] + m->pos[3 * (size_t)b + d]);
                    uint32_t e0 = m->v_he[a], e = e0;
                    do {
                        if (mid && m->he_vert[m->he_next[e]] == b && !G.he_cut[e]) found = 1;
                        e = m->he_next[m->he_twin[e]];
                    } while (e != e0);
                }
                g = m2.he_next[m2.he_twin[g]];
            } while (g != g0);
            h = m2.he_next[m2.he_twin[h]];
        } while (h != h0);
        if (!found) fail_msg("midpoint %u: not between two blocked vertices of a non-cut input edge", v);
    }
    /* no edge but a cut edge between two blocked vertices */
    for (uint32_t h = 0; h < m2.nh; h++)
        if (blocked[m2.he_vert[h]] && blocked[m2.he_vert[m2.he_twin[h]]] && !cut2[h])
            fail_msg("edge %u-%u joins two blocked vertices", m2.he_vert[h], m2.he_vert[m2.he_twin[h]]);
    /* each input face covered by its pieces */
    double *area = calloc(m->nf, sizeof *area);
    assert_non_null(area);
    for (uint32_t f = 0; f < m2.nf; f++) {
        uint32_t h = m2.f_he[f];
        assert_true(fparent[f] < m->nf);
        area[fparent[f]] += tri_area(m2.pos + 3 * (size_t)m2.he_vert[h], m2.pos + 3 * (size_t)m2.he_vert[m2.he_next[h]],
                                     m2.pos + 3 * (size_t)m2.he_vert[m2.he_next[m2.he_next[h]]]);
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        double a = tri_area(m->pos + 3 * (size_t)m->he_vert[h], m->pos + 3 * (size_t)m->he_vert[m->he_next[h]],
                            m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]]);
        assert_true(fabs(area[f] - a) <= 1e-12 * a);
    }
    free(area), free(blocked);
    sq_mesh_free(&m2);
    free(val2), free(fparent), free(cut2);
    sq_cut_graph_free(&G);
    free(cone);
    /* the whole attempt: the fallback's choices at seed 1 */
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.tree = SQ_TREE_QTRI, opt.attempts = 1, opt.seed = 1;
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    if (sq_param_build(m, M.val, &opt, &P, &st, &err)) fail_msg("femur, tree qtri: %s", err.msg);
    assert_int_equal(st.wall_splits, n);
    assert_int_equal(P.nv_input, m->nv);
    assert_memory_equal(P.pos, m->pos, 3 * (size_t)m->nv * sizeof *m->pos);
    for (uint32_t f = 0; f < P.nf; f++) assert_true(P.tri_in[f] < m->nf);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    assert_referee_passes(&M, &P, "femur (tree qtri, walls split)");
    sq_param_free(&P);
    unload(&M);
}

/* sq_param_verify_refinement (which sq_param_build runs on every map it
 * returns, the cells' of test_eight_passes too): eight's map refines the
 * input, added vertices within rounding of their input faces; a vertex
 * moved off its face, a moved input vertex, a face given another input
 * face, and a face turned over are each refused, named. */
static void test_refinement_check(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/eight");
    sq_error err = {0};
    sq_param P;
    sq_param_init(&P);
    if (sq_param_build(&M.m, M.val, NULL, &P, NULL, &err)) fail_msg("eight: %s", err.msg);
    double dist = 1;
    assert_int_equal(sq_param_verify_refinement(&P, &M.m, &dist, &err), SQ_OK);
    assert_true(dist >= 0 && dist < 1e-14);
    assert_true(P.nv > P.nv_input);
    /* an added vertex lifted off its input face along the normal */
    uint32_t f = 0;
    while (f < P.nf && P.tri[3 * (size_t)f] < P.nv_input && P.tri[3 * (size_t)f + 1] < P.nv_input &&
           P.tri[3 * (size_t)f + 2] < P.nv_input)
        f++;
    assert_true(f < P.nf);
    uint32_t v = P.tri[3 * (size_t)f];
    for (int k = 1; v < P.nv_input; k++) v = P.tri[3 * (size_t)f + k];
    double keep[3];
    memcpy(keep, P.pos + 3 * (size_t)v, sizeof keep);
    const uint32_t h0 = M.m.f_he[P.tri_in[f]];
    const double *a = M.m.pos + 3 * (size_t)M.m.he_vert[h0];
    const double *b = M.m.pos + 3 * (size_t)M.m.he_vert[M.m.he_next[h0]];
    const double *c = M.m.pos + 3 * (size_t)M.m.he_vert[M.m.he_next[M.m.he_next[h0]]];
    double n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                   (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                   (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) P.pos[3 * (size_t)v + k] += 1e-6 * n[k] / len;
    assert_int_equal(sq_param_verify_refinement(&P, &M.m, NULL, &err), SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "added vertex"));
    assert_non_null(strstr(err.msg, "not a refinement"));
    memcpy(P.pos + 3 * (size_t)v, keep, sizeof keep);
    /* an input vertex moved */
    P.pos[1] += 1e-12;
    assert_int_equal(sq_param_verify_refinement(&P, &M.m, NULL, &err), SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "input vertex 0 moved"));
    P.pos[1] = M.m.pos[1];
    /* the face given an input face far away */
    const uint32_t F = P.tri_in[f];
    P.tri_in[f] = (F + M.m.nf / 2) % M.m.nf;
    assert_int_equal(sq_param_verify_refinement(&P, &M.m, NULL, &err), SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "its input face"));
    P.tri_in[f] = F;
    /* the face turned over */
    uint32_t t = P.tri[3 * (size_t)f + 1];
    P.tri[3 * (size_t)f + 1] = P.tri[3 * (size_t)f + 2], P.tri[3 * (size_t)f + 2] = t;
    if (sq_param_verify_refinement(&P, &M.m, NULL, &err) == SQ_OK)
        fail_msg("eight: a face turned over passed");
    assert_non_null(strstr(err.msg, "the other way"));
    P.tri[3 * (size_t)f + 2] = P.tri[3 * (size_t)f + 1], P.tri[3 * (size_t)f + 1] = t;
    assert_int_equal(sq_param_verify_refinement(&P, &M.m, NULL, &err), SQ_OK);
    assert_int_equal(sq_param_verify_refinement(NULL, &M.m, NULL, &err), SQ_ERR_ARGUMENT);
    sq_param_free(&P);
    unload(&M);
}

/* Needles (issue: param's output left the input surface next to needles
 * and caps): mpz/eight with 300 edges split at 1e-9 to 1e-6 of their
 * length, both triangles of each split edge cut in two at the new vertex,
 * so each split makes two needles of area down to 1e-9 of their
 * neighbours'. param's map must refine it within rounding (the refinement
 * check at 1e-12 of the diagonal runs inside sq_param_build; its largest
 * distance is reported) and pass the referee. */
static void test_needles(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/eight");
    const sq_mesh *m = &M.m;
    const uint32_t nsplit = 300;
    sq_soup S;
    memset(&S, 0, sizeof S);
    S.nv = m->nv + nsplit, S.nf = m->nf + 2 * nsplit;
    S.pos = malloc(3 * (size_t)S.nv * sizeof *S.pos);
    S.face_off = malloc(((size_t)S.nf + 1) * sizeof *S.face_off);
    S.face_idx = malloc(3 * (size_t)S.nf * sizeof *S.face_idx);
    uint8_t *touched = calloc(m->nf, 1);
    assert_true(S.pos && S.face_off && S.face_idx && touched);
    memcpy(S.pos, m->pos, 3 * (size_t)m->nv * sizeof *S.pos);
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        for (int k = 0; k < 3; k++, h = m->he_next[h]) S.face_idx[3 * (size_t)f + k] = m->he_vert[h];
    }
    /* halfedge h of face f is its corner k's outgoing side; split the
     * sides of untouched face pairs, a deterministic pseudo-random choice */
    uint64_t rng = 88172645463325252ull;
    uint32_t nv = m->nv, nf = m->nf, done = 0;
    for (uint32_t tries = 0; done < nsplit && tries < 100000; tries++) {
        rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
        const uint32_t h = (uint32_t)(rng % m->nh), t = m->he_twin[h];
        const uint32_t f = m->he_face[h], g = m->he_face[t];
        if (touched[f] || touched[g]) continue;
        touched[f] = touched[g] = 1;
        const uint32_t a = m->he_vert[h], b = m->he_vert[t];
        const double frac = pow(10.0, -9.0 + 3.0 * (double)(rng >> 11) / 9007199254740992.0);
        for (int d = 0; d < 3; d++)
            S.pos[3 * (size_t)nv + d] = m->pos[3 * (size_t)a + d] + frac * (m->pos[3 * (size_t)b + d] - m->pos[3 * (size_t)a + d]);
        /* each of the two faces (x, y, c) with side x -> y on the edge
         * becomes (x, n, c) and (n, y, c) */
        const uint32_t face[2] = {f, g};
        for (int s2 = 0; s2 < 2; s2++) {
            uint32_t *F = S.face_idx + 3 * (size_t)face[s2];
            int k = 0;
            while (!((F[k] == a && F[(k + 1) % 3] == b) || (F[k] == b && F[(k + 1) % 3] == a))) k++;
            const uint32_t x = F[k], y = F[(k + 1) % 3], c = F[(k + 2) % 3];
            F[0] = x, F[1] = nv, F[2] = c;
            uint32_t *G = S.face_idx + 3 * (size_t)nf++;
            G[0] = nv, G[1] = y, G[2] = c;
        }
        nv++, done++;
    }
    assert_int_equal(done, nsplit);
    for (uint32_t f = 0; f <= S.nf; f++) S.face_off[f] = 3 * f;
    model N;
    memset(&N, 0, sizeof N);
    sq_error err = {0};
    if (sq_mesh_from_soup(&S, 0, &N.m, &err)) fail_msg("eight with needles: %s", err.msg);
    N.val = malloc((size_t)S.nv * sizeof *N.val);
    assert_non_null(N.val);
    for (uint32_t v = 0; v < S.nv; v++) N.val[v] = v < m->nv ? M.val[v] : 4;
    /* the files the referee reads */
    strcpy(N.mesh_path, "/tmp/sq_test_needles_XXXXXX");
    int fd = mkstemp(N.mesh_path);
    assert_true(fd >= 0);
    FILE *o = fdopen(fd, "w");
    for (uint32_t v = 0; v < S.nv; v++)
        fprintf(o, "v %.17g %.17g %.17g\n", S.pos[3 * (size_t)v], S.pos[3 * (size_t)v + 1], S.pos[3 * (size_t)v + 2]);
    for (uint32_t f = 0; f < S.nf; f++)
        fprintf(o, "f %u %u %u\n", S.face_idx[3 * (size_t)f] + 1, S.face_idx[3 * (size_t)f + 1] + 1,
                S.face_idx[3 * (size_t)f + 2] + 1);
    fclose(o);
    snprintf(N.cone_path, sizeof N.cone_path, "%.500s.cones", N.mesh_path);
    o = fopen(N.cone_path, "w");
    assert_non_null(o);
    for (uint32_t v = 0; v < S.nv; v++) fprintf(o, "%.17g\n", N.val[v] * (2 * atan(1.0)));
    fclose(o);
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    if (sq_param_build(&N.m, N.val, NULL, &P, &st, &err)) fail_msg("eight with needles: %s", err.msg);
    assert_true(st.refinement_max_dist < 1e-14);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    assert_referee_passes(&N, &P, "eight with 300 needle pairs");
    printf("  eight with 300 needle pairs: %u faces, farthest added vertex %.2g of the diagonal\n", P.nf,
           st.refinement_max_dist);
    remove(N.mesh_path), remove(N.cone_path);
    sq_param_free(&P);
    unload(&N);
    free(S.pos), free(S.face_off), free(S.face_idx), free(touched);
    unload(&M);
}

/* Domain variants (sq_param_build_once, tree qtri): with a gate every
 * domain misses, the attempt builds `variants` domains (Algorithm 1's ties
 * broken another way each time) and keeps the one whose overlay expects
 * the fewest crossings, so the result expects no more than the first
 * domain alone (and fewer on mpz/holes3, whose variants 2 to 6 all expect
 * fewer: 53,984 to 64,760 against 64,864), and a gate nothing misses
 * gives the first domain's map, bit for bit. */
static void test_domain_variants(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/holes3");
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.tree = SQ_TREE_QTRI, opt.attempts = 1, opt.seed = 1;
    sq_param P0, P;
    sq_param_stats s0, st;
    sq_error err = {0};
    sq_param_init(&P0), sq_param_init(&P);
    opt.variants = 1; /* the first domain only */
    if (sq_param_build(&M.m, M.val, &opt, &P0, &s0, &err)) fail_msg("holes3, one domain: %s", err.msg);
    assert_int_equal(s0.domain_variant, 0);
    assert_true(s0.crossings_expected > 0);
    opt.variants = 4, opt.variant_gate = 1000000; /* nothing misses it */
    if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("holes3, high gate: %s", err.msg);
    assert_int_equal(st.domain_variant, 0);
    assert_true(P.nf == P0.nf && P.nv == P0.nv && P.nuv == P0.nuv);
    assert_memory_equal(P.tri, P0.tri, 3 * (size_t)P.nf * sizeof *P.tri);
    assert_memory_equal(P.uv, P0.uv, 2 * (size_t)P.nuv * sizeof *P.uv);
    sq_param_free(&P);
    opt.variant_gate = 1; /* every domain misses it */
    uint64_t last = s0.crossings_expected;
    for (uint32_t k = 2; k <= 4; k += 2) {
        opt.variants = k;
        if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("holes3, %u variants: %s", k, err.msg);
        assert_true(st.domain_variant < k);
        assert_true(st.crossings_expected <= last); /* more domains, never worse */
        last = st.crossings_expected;
        assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
        if (k == 4) assert_referee_passes(&M, &P, "holes3 (the best of 4 domain variants)");
        sq_param_free(&P);
    }
    assert_true(last < s0.crossings_expected);
    sq_param_free(&P0);
    unload(&M);
}

static const char *models[] = {"mpz/block",   "mpz/cup",        "mpz/elk",      "mpz/fandisk",
                               "mpz/femur",   "mpz/fertility_tri", "mpz/genus3", "mpz/helmet",
                               "mpz/holes3",  "mpz/homer",      "mpz/knot1",    "mpz/rocker_arm",
                               "mpz/sculpt",  "mpz/trim-star",  "cid/elephant"};

/* Under the sanitizers only the models whose maps the referee reads in CI
 * (the plain build runs all 15; the rest cost about 150 s of ASan time and
 * end at the Steiner budget or at the referee's size limit). */
static int sanitizer_subset(const char *name)
{
#if defined(__SANITIZE_ADDRESS__)
    static const char *keep[] = {"mpz/cup", "mpz/helmet", "mpz/holes3", "mpz/knot1"};
    for (size_t i = 0; i < sizeof keep / sizeof *keep; i++)
        if (!strcmp(name, keep[i])) return 1;
    return 0;
#else
    (void)name;
    return 1;
#endif
}

static void test_all_models_compatible(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof models / sizeof *models; i++) {
        if (!sanitizer_subset(models[i])) continue;
        model M;
        load(&M, models[i]);
        sq_param P;
        sq_param_init(&P);
        sq_param_stats st;
        sq_param_options opt;
        sq_param_options_default(&opt);
        opt.interior = SQ_INTERIOR_CELLS;
        opt.allow_flips = 1;
        sq_error err = {0};
        sq_status s = sq_param_build(&M.m, M.val, &opt, &P, &st, &err);
        if (s != SQ_OK && s != SQ_ERR_SOLVER) fail_msg("%s: status %d: %s", models[i], s, err.msg);
        if (s == SQ_ERR_SOLVER) {
            assert_non_null(strstr(err.msg, "Steiner vertices were needed"));
            printf("  %-18s Steiner budget exceeded\n", models[i]);
            unload(&M);
            continue;
        }
        if (st.faces_out > 120000) { /* keep the referee's cost in CI small */
            printf("  %-18s %u faces: referee skipped (size)\n", models[i], st.faces_out);
            sq_param_free(&P);
            unload(&M);
            continue;
        }
        char obj[] = "/tmp/sq_test_param_XXXXXX";
        int fd = mkstemp(obj);
        assert_true(fd >= 0);
        close(fd);
        assert_int_equal(sq_param_write_obj(obj, &P, &err), SQ_OK);
        int rc;
        char *out = referee(&M, obj, &rc);
        remove(obj);
        assert_non_null(out);
        /* topology, refinement and exact integer seams hold everywhere */
        if (!strstr(out, "[a] topology: PASS") || !strstr(out, "[b] refinement: PASS") ||
            !strstr(out, "[d] seamlessness: PASS"))
            fail_msg("%s: referee:\n%s", models[i], out);
        const char *last = strstr(out, "check_param:");
        const char *l2;
        while (last && (l2 = strstr(last + 1, "check_param:"))) last = l2;
        printf("  %-18s %u faces, %u cells: %.90s\n", models[i], st.faces_out, st.cells, last ? last : "");
        free(out);
        sq_param_free(&P);
        unload(&M);
    }
}

/* Seed 9.1: cones that touch. On gpjs/torus.obj, (a) the one-ring of
 * vertex 7 made cones (valences 3, 5, 3, 5, 3, 5 around it: vertex 7 is
 * walled in) and (b) a whole meridian of 48 adjacent cones (3, 5, ...: a
 * ring around the tube that every loop of the torus crosses). The cut graph
 * fails on the input for want of an edge split; the edges between two
 * cones are split at their midpoints (6, 48), the map is built on that mesh
 * and expressed on the input: its vertices first, bit for bit, every face
 * in its input face (sq_param_verify_refinement, run by sq_param_build),
 * and the referee passes it with the cone file. Under the sanitizers (a)
 * only. */
static void ring_of_cones(const char *name, const uint32_t *ring, uint32_t n)
{
    model M;
    memset(&M, 0, sizeof M);
    snprintf(M.mesh_path, sizeof M.mesh_path, "%s/data/gpjs/torus.obj", SQ_SHARED_DIR);
    sq_test_read_mesh(&M.m, M.mesh_path);
    M.val = malloc(M.m.nv * sizeof *M.val);
    for (uint32_t v = 0; v < M.m.nv; v++) M.val[v] = 4;
    for (uint32_t i = 0; i < n; i++) M.val[ring[i]] = i % 2 ? 5 : 3;
    /* the cone file, for the referee */
    snprintf(M.cone_path, sizeof M.cone_path, "/tmp/sq_test_ring_XXXXXX");
    int fd = mkstemp(M.cone_path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    for (uint32_t v = 0; v < M.m.nv; v++) fprintf(f, "%.17g\n", M.val[v] * 1.5707963267948966);
    fclose(f);
    sq_param_options opt;
    sq_param_options_default(&opt);
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    sq_error err = {0};
    if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("%s: %s", name, err.msg);
    assert_true(st.cut_needs_split);
    assert_int_equal(st.cone_splits, n); /* the ring's edges: consecutive cones */
    assert_int_equal(P.nv_input, M.m.nv);
    assert_int_equal(st.verts_in, M.m.nv);
    assert_memory_equal(P.pos, M.m.pos, 3 * (size_t)M.m.nv * sizeof *P.pos);
    for (uint32_t t = 0; t < P.nf; t++) assert_true(P.tri_in[t] < M.m.nf);
    assert_referee_passes(&M, &P, name);
    printf("  %s: %u edges between cones split, %u faces, %u Steiner vertices\n", name, st.cone_splits, P.nf,
           st.steiner);
    sq_param_free(&P);
    remove(M.cone_path);
    unload(&M);
}

static void test_cones_touching(void **state)
{
    (void)state;
    /* vertex 7's one-ring, in order around it */
    const uint32_t wall[] = {54, 55, 8, 3799, 3798, 6};
    ring_of_cones("torus, vertex 7 walled in", wall, 6);
#if !defined(__SANITIZE_ADDRESS__)
    uint32_t meridian[48]; /* vertices 0..47: the tube's circle at angle 0 */
    for (uint32_t i = 0; i < 48; i++) meridian[i] = i;
    ring_of_cones("torus, a meridian of 48 cones", meridian, 48);
#endif
}

/* Step 7c: mpz/helmet (genus 2, a valence-22 cone) at seed 1 leaves
 * thousands of flipped or flat triangles without refinement; with it the
 * cells holding them are halved until the map passes the referee, on the
 * same cut graph (one attempt). */
static void test_refine(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/helmet");
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st0, st;
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.interior = SQ_INTERIOR_CELLS; /* what this test is about */
    assert_int_equal(opt.refine, SQ_PARAM_REFINE);
    opt.refine = 0;
    sq_error err = {0};
    assert_int_equal(sq_param_build(&M.m, M.val, &opt, &P, &st0, &err), SQ_ERR_SOLVER);
    assert_non_null(strstr(err.msg, "not injective in floating point"));
    assert_null(P.pos);
    assert_true(st0.rounds == 0 && st0.cells_refined == 0);
    opt.refine = SQ_PARAM_REFINE;
    sq_status s = sq_param_build(&M.m, M.val, &opt, &P, &st, &err);
    if (s) fail_msg("helmet, refined: %s", err.msg);
    assert_true(st.attempts == 1 && st.seed_used == 1);
    assert_true(st.rounds >= 1 && st.rounds <= SQ_PARAM_REFINE && st.cells_refined >= st.rounds);
    assert_true(st.cells > st0.cells);
    assert_int_equal(st.cells, st.chords + 1);
    assert_int_equal(sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    assert_referee_passes(&M, &P, "helmet");
    sq_param_free(&P);
    unload(&M);
}

/* sq_param_bad_cells: on a map with flips (mpz/holes3 seed 1, kept with
 * allow_flips) every bad triangle lies in a reported cell, each cell's
 * rectangle has positive size and its boundary runs along its four sides;
 * on a valid map (eight) there is none */
static void test_bad_cells(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/holes3");
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.interior = SQ_INTERIOR_CELLS; /* what this test is about */
    opt.seed = 1;
    opt.refine = 0; /* the flips as Tutte's map leaves them */
    opt.allow_flips = 1;
    sq_error err = {0};
    if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("holes3 seed 1: %s", err.msg);
    uint32_t bad = 0;
    for (uint32_t f = 0; f < P.nf; f++)
        bad += sq_orient2d(P.uv + 2 * P.tri_uv[3 * f], P.uv + 2 * P.tri_uv[3 * f + 1], P.uv + 2 * P.tri_uv[3 * f + 2]) <= 0;
    assert_true(bad > 0); /* if this seed ever passes, pick another failing one */
    sq_param_cell cells[64];
    uint32_t n = 0;
    assert_int_equal(sq_param_bad_cells(&P, cells, 64, &n, &err), SQ_OK);
    assert_true(n >= 1 && n <= 64);
    uint32_t sum = 0;
    for (uint32_t i = 0; i < n; i++) {
        assert_true(cells[i].bad >= 1 && cells[i].bad <= cells[i].faces);
        if (i) assert_true(cells[i].bad <= cells[i - 1].bad);
        assert_true(cells[i].umax > cells[i].umin && cells[i].vmax > cells[i].vmin);
        /* Omega's cells are integer rectangles */
        assert_true(cells[i].umin == floor(cells[i].umin) && cells[i].vmax == floor(cells[i].vmax));
        assert_true(cells[i].runs >= 4);
        for (int k = 0; k < 4; k++) assert_true(cells[i].side_len[k] > 0);
        sum += cells[i].bad;
    }
    assert_int_equal(sum, bad);
    char path[] = "/tmp/sq_test_cells_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(sq_param_write_cells_svg(path, &P, cells, n, &err), SQ_OK);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    char buf[256] = {0};
    assert_true(fread(buf, 1, sizeof buf - 1, fp) > 0);
    fclose(fp);
    unlink(path);
    assert_non_null(strstr(buf, "<svg"));
    sq_param_free(&P);
    /* a valid map has no bad cell */
    unload(&M);
    load(&M, "mpz/eight");
    opt.seed = 1;
    opt.allow_flips = 0;
    if (sq_param_build(&M.m, M.val, &opt, &P, &st, &err)) fail_msg("eight: %s", err.msg);
    assert_int_equal(sq_param_bad_cells(&P, cells, 64, &n, &err), SQ_OK);
    assert_int_equal(n, 0);
    sq_param_free(&P);
    unload(&M);
}

static void test_rejects_bad_cones(void **state)
{
    (void)state;
    model M;
    load(&M, "mpz/eight");
    sq_param P;
    sq_param_init(&P);
    sq_error err = {0};
    /* Gauss-Bonnet: one cone removed */
    for (uint32_t v = 0; v < M.m.nv; v++)
        if (M.val[v] != 4) {
            M.val[v] = 4;
            break;
        }
    assert_int_equal(sq_param_build(&M.m, M.val, NULL, &P, NULL, &err), SQ_ERR_GAUSS_BONNET);
    assert_null(P.pos);
    unload(&M);
}

int main(void)
{
    /* SQ_TEST_FILTER=test_name (a cmocka pattern) runs only the tests it matches */
    if (getenv("SQ_TEST_FILTER")) cmocka_set_test_filter(getenv("SQ_TEST_FILTER"));
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eight_passes),
        cmocka_unit_test(test_refinement_check),
        cmocka_unit_test(test_needles),
        cmocka_unit_test(test_cup_guided),
        cmocka_unit_test(test_threads),
        cmocka_unit_test(test_fallback_threads),
        cmocka_unit_test(test_split_walls),
        cmocka_unit_test(test_domain_variants),
        cmocka_unit_test(test_all_models_compatible),
        cmocka_unit_test(test_refine),
        cmocka_unit_test(test_bad_cells),
        cmocka_unit_test(test_rejects_bad_cones),
        cmocka_unit_test(test_cones_touching),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
