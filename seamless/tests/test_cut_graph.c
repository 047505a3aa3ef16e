/* The cut graph on the surface (seed 7, seed 9.1): loops, hole chain and
 * boundary word on real meshes of ../shared/data, checked independently:
 * the mesh is cut by duplicating vertices along the graph and the result
 * must be one disk; the pattern must glue back to genus g. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "sq_cut_graph.h"
#include "sq_mesh.h"
#include "sq_pattern.h"
#include "sq_test_mesh.h"
#include "sq_test_cut.h"

typedef struct model {
    sq_mesh m;
    uint8_t *cone; /* NULL without a cone file */
    uint32_t ncones;
} model;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void load(model *M, const char *rel, const char *cones_rel)
{
    memset(M, 0, sizeof *M);
    sq_test_load_mesh(&M->m, rel);
    if (cones_rel) {
        int32_t *val = sq_test_load_valence(cones_rel, M->m.nv);
        M->cone = calloc(M->m.nv, 1);
        assert_non_null(M->cone);
        for (uint32_t v = 0; v < M->m.nv; ++v)
            if (val[v] != 4) {
                M->cone[v] = 1;
                M->ncones++;
            }
        free(val);
    }
}

static void unload(model *M)
{
    sq_mesh_free(&M->m);
    free(M->cone);
}


/* All properties of a built cut graph. */
static void check_graph(const model *M, const sq_cut_graph *G, uint32_t g)
{
    const sq_mesh *m = &M->m;
    uint32_t *deg = calloc(m->nv, sizeof *deg);
    for (uint32_t h = 0; h < m->nh; ++h) {
        assert_int_equal(G->he_cut[h], G->he_cut[m->he_twin[h]]);
        if (G->he_cut[h])
            deg[m->he_vert[h]]++;
    }
    uint32_t np = 0, ends = 0;
    for (uint32_t v = 0; v < m->nv; ++v) {
        if (!deg[v])
            continue;
        if (M->cone)
            assert_false(M->cone[v]); /* no cone on the cut */
        assert_true(deg[v] == 2 || deg[v] == 4);
        if (deg[v] == 4)
            ++np, ends += 4;
    }
    assert_int_equal(np, 2 * g - 1);
    assert_int_equal(ends / 2, 4 * g - 2); /* branches */
    assert_int_equal(G->npoints, 2 * g - 1);
    assert_int_equal(G->nbranches, 4 * g - 2);
    uint32_t loops;
    assert_int_equal(cut_soup_euler(m, G->he_cut, &loops), 1);
    assert_int_equal(loops, 1);
    /* pattern: sides pair up as reverses with equal halfedge counts */
    const uint32_t k = G->pattern.k;
    assert_int_equal(k, 8 * g - 4);
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t j = G->pattern.partner[i];
        assert_true(j < k && j != i);
        assert_int_equal(G->pattern.partner[j], i);
        const uint32_t a = G->side_off[i], b = G->side_off[i + 1];
        const uint32_t c = G->side_off[j], d = G->side_off[j + 1];
        assert_int_equal(b - a, d - c);
        for (uint32_t t = 0; t < b - a; ++t)
            assert_int_equal(G->side_he[c + t], m->he_twin[G->side_he[b - 1 - t]]);
        assert_int_equal(deg[G->corner_vertex[i]], 4);
        assert_int_equal(m->he_vert[G->side_he[a]], G->corner_vertex[i]);
    }
    uint32_t *cls = malloc(k * sizeof *cls), *cnt = calloc(k, sizeof *cnt);
    const uint32_t V = sq_pattern_corner_classes(&G->pattern, cls);
    assert_int_equal(V, 2 * g - 1);
    for (uint32_t i = 0; i < k; ++i)
        cnt[cls[i]]++;
    for (uint32_t c = 0; c < V; ++c)
        assert_int_equal(cnt[c], 4);
    sq_pattern_info info;
    sq_error err;
    assert_int_equal(sq_pattern_validate(&G->pattern, &info, &err), SQ_OK);
    assert_int_equal(info.genus, g);
    assert_int_equal(sq_pattern_rank(&G->pattern), G->rank);
    free(cls);
    free(cnt);
    free(deg);
}

static void run_model(const char *rel, const char *cones, uint32_t g)
{
    model M;
    load(&M, rel, cones);
    assert_int_equal(sq_mesh_genus(&M.m), g);
    sq_cut_options opt;
    sq_cut_options_default(&opt);
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_cut_stats stats;
    sq_error err;
    const double t0 = now();
    sq_status st = sq_cut_graph_build(&M.m, M.cone, &opt, &G, &stats, &err);
    const double t1 = now();
    if (st != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    check_graph(&M, &G, g);
    print_message("%-22s g=%u F=%u cones=%u: %u loops (%u rounds, %u candidates), %u branch "
                  "points, %u branches, %u sides, cut %u edges, rank %u (%s, %u tries), "
                  "%.3f s\n",
                  rel, g, M.m.nf, M.ncones, g, stats.rounds, stats.candidates, G.npoints,
                  G.nbranches, G.pattern.k, G.ncut_edges, G.rank,
                  G.rank == 2 ? "pass" : "fail", G.tries, t1 - t0);
    if (g >= 2)
        assert_int_equal(G.rank, 2);
    else
        assert_int_equal(G.rank, 0); /* a b a^-1 b^-1: all translations */
    sq_cut_graph_free(&G);
    unload(&M);
}

static void test_torus(void **s) { (void)s; run_model("gpjs/torus.obj", NULL, 1); }
static void test_double_torus(void **s) { (void)s; run_model("gpjs/double-torus.obj", NULL, 2); }
static void test_eight(void **s) { (void)s; run_model("mpz/eight.obj", "mpz/eight_Th_hat", 2); }
static void test_genus3(void **s) { (void)s; run_model("mpz/genus3.obj", "mpz/genus3_Th_hat", 3); }
static void test_helmet(void **s) { (void)s; run_model("mpz/helmet.obj", "mpz/helmet_Th_hat", 3); }
static void test_fertility(void **s) { (void)s; run_model("libigl/fertility.off", NULL, 4); }
static void test_botijo(void **s) { (void)s; run_model("avaxman/botijo.off", NULL, 5); }
static void test_rolling_stage(void **s) { (void)s; run_model("cggs/rolling_stage.off", NULL, 7); }

/* Every rotation/flip choice on the eight: each graph is a valid disk cut;
 * count how many pass the rank test. */
static void test_all_choices(void **s)
{
    (void)s;
    model M;
    load(&M, "mpz/eight.obj", "mpz/eight_Th_hat");
    sq_cut_loops L;
    sq_cut_loops_init(&L);
    sq_error err;
    assert_int_equal(sq_cut_loops_find(&M.m, M.cone, NULL, &L, NULL, &err), SQ_OK);
    assert_int_equal(L.nloops, 2);
    assert_int_equal(sq_cut_loops_check(&M.m, M.cone, &L, &err), SQ_OK);
    uint32_t pass = 0, built = 0;
    for (uint32_t rot = 0; rot < 4; ++rot)
        for (uint32_t flip = 0; flip < 4; ++flip) {
            sq_cut_graph G;
            sq_cut_graph_init(&G);
            if (sq_cut_chain(&M.m, M.cone, &L, rot, flip, &G, NULL, &err) != SQ_OK)
                fail_msg("rotation %u flip %u: %s", rot, flip, err.msg);
            check_graph(&M, &G, 2);
            ++built;
            pass += G.rank == 2;
            sq_cut_graph_free(&G);
        }
    print_message("eight: %u of %u rotation/flip choices pass the rank test\n", pass, built);
    assert_int_equal(built, 16);
    assert_true(pass >= 1);
    sq_cut_loops_free(&L);
    unload(&M);
}

/* Fertility (genus 4): the first 32 rotation/flip choices all route and
 * all give valid disk cuts; most pass the rank test. */
static void test_choices_fertility(void **s)
{
    (void)s;
    model M;
    load(&M, "libigl/fertility.off", NULL);
    sq_cut_loops L;
    sq_cut_loops_init(&L);
    sq_error err;
    assert_int_equal(sq_cut_loops_find(&M.m, NULL, NULL, &L, NULL, &err), SQ_OK);
    uint32_t pass = 0;
    for (uint32_t t = 0; t < 32; ++t) {
        sq_cut_graph G;
        sq_cut_graph_init(&G);
        if (sq_cut_chain(&M.m, NULL, &L, t & 63u, 0, &G, NULL, &err) != SQ_OK)
            fail_msg("rotation %u: %s", t, err.msg);
        check_graph(&M, &G, 4);
        pass += G.rank == 2;
        sq_cut_graph_free(&G);
    }
    print_message("fertility: %u of 32 rotation choices pass the rank test\n", pass);
    assert_true(pass >= 1);
    sq_cut_loops_free(&L);
    unload(&M);
}

/* The loop check rejects a repeated loop, and a contractible one. */
static void test_loops_check_rejects(void **s)
{
    (void)s;
    model M;
    load(&M, "gpjs/double-torus.obj", NULL);
    sq_cut_loops L;
    sq_cut_loops_init(&L);
    sq_error err;
    assert_int_equal(sq_cut_loops_find(&M.m, NULL, NULL, &L, NULL, &err), SQ_OK);
    assert_int_equal(sq_cut_loops_check(&M.m, NULL, &L, &err), SQ_OK);
    /* loop 1 := loop 0 */
    sq_cut_loops bad;
    const uint32_t n0 = L.loop_off[1];
    bad.genus = 2;
    bad.nloops = 2;
    uint32_t off[3] = {0, n0, 2 * n0};
    bad.loop_off = off;
    bad.loop_he = malloc(2 * n0 * sizeof *bad.loop_he);
    memcpy(bad.loop_he, L.loop_he, n0 * sizeof *bad.loop_he);
    memcpy(bad.loop_he + n0, L.loop_he, n0 * sizeof *bad.loop_he);
    assert_int_equal(sq_cut_loops_check(&M.m, NULL, &bad, &err), SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "disjoint"));
    /* one loop around a vertex's link: separates */
    const sq_mesh *m = &M.m;
    uint32_t ring[64], nr = 0, h0 = m->v_he[0], h = h0;
    do {
        ring[nr++] = m->he_next[h]; /* edge opposite vertex 0, in its face */
        h = m->he_next[m->he_twin[h]];
    } while (h != h0 && nr < 64);
    bad.nloops = 1;
    bad.genus = 2;
    uint32_t off1[2] = {0, nr};
    bad.loop_off = off1;
    memcpy(bad.loop_he, ring, nr * sizeof *ring);
    /* ring halfedges must run head to tail: reverse order if needed */
    if (m->he_vert[m->he_next[ring[0]]] != m->he_vert[ring[1]])
        for (uint32_t i = 0; i < nr; ++i)
            bad.loop_he[i] = ring[nr - 1 - i];
    assert_int_equal(sq_cut_loops_check(&M.m, NULL, &bad, &err), SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "components"));
    free(bad.loop_he);
    sq_cut_loops_free(&L);
    unload(&M);
}

/* A vertex whose neighbours are all cones cannot be reached: the cut needs
 * an edge split, reported as such. */
static void test_walled_in_needs_split(void **s)
{
    (void)s;
    model M;
    load(&M, "gpjs/torus.obj", NULL);
    const sq_mesh *m = &M.m;
    uint8_t *cone = calloc(m->nv, 1);
    const uint32_t v = 7, h0 = m->v_he[v];
    uint32_t h = h0;
    do {
        cone[m->he_vert[m->he_next[h]]] = 1;
        h = m->he_next[m->he_twin[h]];
    } while (h != h0);
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_cut_stats stats;
    sq_error err;
    assert_int_equal(sq_cut_graph_build(m, cone, NULL, &G, &stats, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(stats.failure, SQ_CUT_FAIL_NEEDS_SPLIT);
    assert_non_null(strstr(err.msg, "edge split"));
    assert_true(cone[stats.where[0]] && cone[stats.where[1]]);
    assert_null(G.he_cut);
    free(cone);
    unload(&M);
}

/* Genus 0 is rejected with a clear message. */
static void test_genus0_rejected(void **s)
{
    (void)s;
    model M;
    load(&M, "libigl/bunny.off", NULL);
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_error err;
    assert_int_equal(sq_cut_graph_build(&M.m, NULL, NULL, &G, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "genus"));
    unload(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_double_torus),
        cmocka_unit_test(test_eight),
        cmocka_unit_test(test_genus3),
        cmocka_unit_test(test_helmet),
        cmocka_unit_test(test_fertility),
        cmocka_unit_test(test_botijo),
        cmocka_unit_test(test_rolling_stage),
        cmocka_unit_test(test_all_choices),
        cmocka_unit_test(test_choices_fertility),
        cmocka_unit_test(test_loops_check_rejects),
        cmocka_unit_test(test_walled_in_needs_split),
        cmocka_unit_test(test_genus0_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
