/* Cut graphs of genus 0 and 1 (seed 6.5, seed 6.2, seed 7 "Low Genus
 * Special Cases") and the side correspondence with the domain Q, on real
 * meshes of ../shared/data:
 *  - the mesh cut along the graph (vertices duplicated per wedge, counted
 *    independently of the library) is one disk with one boundary loop;
 *  - no cone on the cut; branch points of degree 1 (genus 0), 3 (genus 1
 *    with cones, theta graph) or 4 (genus 1 without cones: two loops);
 *  - the boundary word validates with the right genus, sides pair up as
 *    reverses, corner classes sit at one branch vertex each;
 *  - sq_cut_graph_domain_offset finds the rotation against the pattern of
 *    the domain sq_domain_build builds for the mesh's cone valences;
 *  - genus >= 2: sq_domain_build accepts the reversed (clockwise) word of
 *    sq_cut_graph_build and offset 0 matches;
 *  - cones that wall every path off are reported as needing an edge split. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_mesh.h"
#include "sq_pattern.h"
#include "sq_test_mesh.h"
#include "sq_test_cut.h"

typedef struct model {
    sq_mesh m;
    uint8_t *cone;  /* NULL without a cone file */
    uint32_t ncones;
    int32_t *val;   /* ncones valences (!= 4), file order */
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
        M->val = malloc((M->m.nv + 1) * sizeof *M->val);
        assert_non_null(M->cone);
        assert_non_null(M->val);
        for (uint32_t v = 0; v < M->m.nv; ++v)
            if (val[v] != 4) {
                M->cone[v] = 1;
                M->val[M->ncones++] = val[v];
            }
        free(val);
    }
}

static void unload(model *M)
{
    sq_mesh_free(&M->m);
    free(M->cone);
    free(M->val);
}


static uint32_t mesh_dest(const sq_mesh *m, uint32_t h) { return m->he_vert[m->he_next[h]]; }

static void word_string(const sq_pattern *p, char *buf, size_t cap)
{
    size_t n = 0;
    n += (size_t)snprintf(buf + n, cap - n, "{");
    for (uint32_t i = 0; i < p->k && n < cap; ++i)
        n += (size_t)snprintf(buf + n, cap - n, "%s%u%s", i ? "," : "", p->partner[i],
                              p->straight && p->straight[i] ? "*" : "");
    if (n < cap)
        snprintf(buf + n, cap - n, "}");
}

/* All properties of a low-genus cut graph: bdeg = degree of the branch
 * points, np their number. */
static void check_graph(const model *M, const sq_cut_graph *G, uint32_t g, uint32_t bdeg,
                        uint32_t np_want)
{
    const sq_mesh *m = &M->m;
    uint32_t *deg = calloc(m->nv, sizeof *deg);
    for (uint32_t h = 0; h < m->nh; ++h) {
        assert_int_equal(G->he_cut[h], G->he_cut[m->he_twin[h]]);
        if (G->he_cut[h])
            deg[m->he_vert[h]]++;
    }
    uint32_t np = 0, ends = 0, ncut = 0;
    for (uint32_t v = 0; v < m->nv; ++v) {
        if (!deg[v])
            continue;
        if (M->cone)
            assert_false(M->cone[v]); /* no cone on the cut */
        assert_true(deg[v] == 2 || deg[v] == bdeg);
        ncut += deg[v];
        if (deg[v] == bdeg)
            ++np, ends += bdeg;
    }
    const uint32_t nbr = ends / 2;
    assert_int_equal(np, np_want);
    assert_int_equal(G->npoints, np);
    assert_int_equal(G->nbranches, nbr);
    assert_int_equal(G->ncut_edges, ncut / 2);
    for (uint32_t i = 0; i < np; ++i)
        assert_int_equal(deg[G->point_vertex[i]], bdeg);
    if (g == 0)
        assert_true(G->ncut_edges >= 2);
    uint32_t loops;
    assert_int_equal(cut_soup_euler(m, G->he_cut, &loops), 1);
    assert_int_equal(loops, 1);
    const uint32_t k = G->pattern.k;
    assert_int_equal(k, 2 * nbr);
    assert_int_equal(G->side_off[0], 0);
    assert_int_equal(G->side_off[k], 2 * G->ncut_edges);
    double len = 0.0;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t j = G->pattern.partner[i];
        assert_true(j < k && j != i);
        assert_int_equal(G->pattern.partner[j], i);
        const uint32_t a = G->side_off[i], b = G->side_off[i + 1];
        const uint32_t c = G->side_off[j], d = G->side_off[j + 1];
        assert_true(b > a);
        assert_int_equal(b - a, d - c);
        for (uint32_t t = 0; t < b - a; ++t) {
            assert_int_equal(G->side_he[c + t], m->he_twin[G->side_he[b - 1 - t]]);
            const uint32_t h = G->side_he[a + t];
            const uint32_t p = m->he_vert[h], q = m->he_vert[m->he_next[h]];
            const double *x = m->pos + 3 * (size_t)p, *y = m->pos + 3 * (size_t)q;
            len += 0.5 * sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                              (x[2] - y[2]) * (x[2] - y[2]));
            if (t > 0)
                assert_int_equal(deg[p], 2); /* inside a side: no branch point */
        }
        assert_int_equal(deg[G->corner_vertex[i]], bdeg);
        assert_int_equal(m->he_vert[G->side_he[a]], G->corner_vertex[i]);
    }
    assert_true(fabs(len - G->length) <= 1e-9 * (1.0 + len));
    uint32_t *cls = malloc(k * sizeof *cls), *cnt = calloc(k, sizeof *cnt);
    const uint32_t V = sq_pattern_corner_classes(&G->pattern, cls);
    assert_int_equal(V, np);
    for (uint32_t i = 0; i < k; ++i) {
        cnt[cls[i]]++;
        for (uint32_t j = 0; j < k; ++j)
            if (cls[j] == cls[i])
                assert_int_equal(G->corner_vertex[j], G->corner_vertex[i]);
    }
    for (uint32_t c = 0; c < V; ++c)
        assert_int_equal(cnt[c], bdeg);
    sq_error err;
    if (g >= 1) {
        sq_pattern_info info;
        if (sq_pattern_validate(&G->pattern, &info, &err) != SQ_OK)
            fail_msg("%s", err.msg);
        assert_int_equal(info.genus, g);
    } else {
        assert_int_equal(k, 2);
        assert_int_equal(G->pattern.partner[0], 1);
    }
    assert_int_equal(sq_pattern_rank(&G->pattern), G->rank);
    /* the library's own check agrees */
    if (sq_cut_graph_check(m, M->cone, G, &err) != SQ_OK)
        fail_msg("%s", err.msg);
    free(cls);
    free(cnt);
    free(deg);
}

/* Q side j = clockwise surface side (j + r) mod k: the pairings agree. */
static void check_offset(const sq_cut_graph *G, const sq_pattern *q, uint32_t r)
{
    const uint32_t k = G->pattern.k;
    assert_int_equal(q->k, k);
    assert_true(r < k);
    for (uint32_t j = 0; j < k; ++j) {
        /* clockwise side s = counterclockwise side k-1-s, backward */
        const uint32_t s = (j + r) % k, ccw = k - 1 - s;
        const uint32_t pc = G->pattern.partner[ccw];
        const uint32_t ps = k - 1 - pc; /* its partner, clockwise */
        assert_int_equal(ps, (q->partner[j] + r) % k);
    }
}

/* Cut, check, build the domain for the mesh's valences (stand-in when the
 * mesh has none but the genus needs cones), find and check the offset. */
static void run_model(const char *rel, const char *cones, uint32_t g)
{
    model M;
    load(&M, rel, cones);
    assert_int_equal(sq_mesh_genus(&M.m), g);
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_cut_stats stats;
    sq_error err;
    const double t0 = now();
    sq_status st = sq_cut_graph_build_low_genus(&M.m, M.cone, NULL, &G, &stats, &err);
    const double t1 = now();
    if (st != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    assert_int_equal(G.genus, g);
    assert_int_equal(stats.failure, SQ_CUT_FAIL_NONE);
    uint32_t bdeg, np;
    if (g == 0)
        bdeg = 1, np = 2;
    else if (M.ncones > 0)
        bdeg = 3, np = 2;
    else
        bdeg = 4, np = 1;
    check_graph(&M, &G, g, bdeg, np);
    /* the domain */
    static const int32_t cube[8] = {3, 3, 3, 3, 3, 3, 3, 3};
    const int32_t *val = M.val;
    uint32_t nval = M.ncones;
    if (g == 0 && nval == 0)
        val = cube, nval = 8; /* the sphere needs cones; Q's pattern is {1, 0} anyway */
    sq_domain D;
    const double t2 = now();
    if (sq_domain_build(g, val, nval, NULL, &D, &err) != SQ_OK)
        fail_msg("%s: domain: %s", rel, err.msg);
    const double t3 = now();
    uint32_t r = SQ_NONE;
    if (sq_cut_graph_domain_offset(&G, &D.pattern, &r, &err) != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    check_offset(&G, &D.pattern, r);
    sq_pattern cw;
    sq_pattern_init(&cw);
    assert_int_equal(sq_pattern_reversed(&G.pattern, &cw, &err), SQ_OK);
    int straight_ok = 1;
    for (uint32_t j = 0; j < D.k; ++j)
        straight_ok &= cw.straight[(j + r) % D.k] == D.pattern.straight[j];
    if (g == 1 && M.ncones > 0)
        assert_true(straight_ok); /* the theta word carries one straight corner per class */
    char ccw_s[128], cw_s[128], q_s[128];
    word_string(&G.pattern, ccw_s, sizeof ccw_s);
    word_string(&cw, cw_s, sizeof cw_s);
    word_string(&D.pattern, q_s, sizeof q_s);
    print_message("%-24s g=%u F=%u cones=%u: %u points (deg %u), %u branches, %u cut edges, "
                  "length %.3g; ccw %s cw %s; Q %s (%llu quads) offset %u%s; cut %.3f s, "
                  "domain %.3f s\n",
                  rel, g, M.m.nf, M.ncones, G.npoints, bdeg, G.nbranches, G.ncut_edges,
                  G.length, ccw_s, cw_s, q_s,
                  (unsigned long long)(D.quads_unpadded + D.quads_added), r,
                  straight_ok ? " (straight corners match)" : "", t1 - t0, t3 - t2);
    sq_pattern_free(&cw);
    sq_domain_free(&D);
    sq_cut_graph_free(&G);
    unload(&M);
}

/* genus 0: the seed moves the slit (retries of sq_param_build get other
 * cuts); every one is a valid cut graph, seed 1 keeps the unseeded one */
static void test_genus0_seeds(void **s)
{
    (void)s;
    model M;
    load(&M, "mpz/fandisk.obj", "mpz/fandisk_Th_hat");
    sq_cut_graph G[6];
    sq_error err;
    for (uint32_t i = 0; i < 6; ++i) {
        sq_cut_graph_init(&G[i]);
        sq_cut_options opt;
        sq_cut_options_default(&opt);
        opt.seed = i + 1;
        if (sq_cut_graph_build_low_genus(&M.m, M.cone, &opt, &G[i], NULL, &err) != SQ_OK)
            fail_msg("seed %u: %s", i + 1, err.msg);
        check_graph(&M, &G[i], 0, 1, 2);
    }
    sq_cut_graph H;
    sq_cut_graph_init(&H);
    assert_int_equal(sq_cut_graph_build_low_genus(&M.m, M.cone, NULL, &H, NULL, &err), SQ_OK);
    assert_memory_equal(H.he_cut, G[0].he_cut, M.m.nh);
    uint32_t distinct = 0;
    for (uint32_t i = 0; i < 6; ++i) {
        int fresh = 1;
        for (uint32_t j = 0; j < i && fresh; ++j) fresh = memcmp(G[i].he_cut, G[j].he_cut, M.m.nh) != 0;
        distinct += fresh;
    }
    assert_true(distinct >= 5);
    for (uint32_t i = 0; i < 6; ++i) sq_cut_graph_free(&G[i]);
    sq_cut_graph_free(&H);
    unload(&M);
}

static void test_fandisk(void **s) { (void)s; run_model("mpz/fandisk.obj", "mpz/fandisk_Th_hat", 0); }
static void test_homer(void **s) { (void)s; run_model("mpz/homer.obj", "mpz/homer_Th_hat", 0); }
static void test_bunny(void **s) { (void)s; run_model("libigl/bunny.off", NULL, 0); }
static void test_knight(void **s) { (void)s; run_model("libigl/decimated-knight.off", NULL, 0); }
static void test_elk(void **s) { (void)s; run_model("mpz/elk.obj", "mpz/elk_Th_hat", 1); }
static void test_knot1(void **s) { (void)s; run_model("mpz/knot1.obj", "mpz/knot1_Th_hat", 1); }
static void test_rocker_arm(void **s)
{
    (void)s;
    run_model("mpz/rocker_arm.obj", "mpz/rocker_arm_Th_hat", 1);
}
static void test_trim_star(void **s)
{
    (void)s;
    run_model("mpz/trim-star.obj", "mpz/trim-star_Th_hat", 1);
}
static void test_torus(void **s) { (void)s; run_model("gpjs/torus.obj", NULL, 1); }
static void test_kitten(void **s) { (void)s; run_model("avaxman/Kitten.off", NULL, 1); }

/* Genus >= 2: the domain built with the clockwise (reversed) word of the
 * hole-chain cut graph matches it at offset 0. */
static void run_high(const char *rel, const char *cones)
{
    model M;
    load(&M, rel, cones);
    const int64_t g = sq_mesh_genus(&M.m);
    assert_true(g >= 2);
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_error err;
    if (sq_cut_graph_build_low_genus(&M.m, M.cone, NULL, &G, NULL, &err) != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    assert_int_equal(G.genus, (uint32_t)g);
    assert_int_equal(G.pattern.k, 8 * (uint32_t)g - 4);
    if (sq_cut_graph_check(&M.m, M.cone, &G, &err) != SQ_OK)
        fail_msg("%s", err.msg);
    uint32_t loops;
    assert_int_equal(cut_soup_euler(&M.m, G.he_cut, &loops), 1);
    assert_int_equal(loops, 1);
    sq_pattern cw;
    sq_pattern_init(&cw);
    assert_int_equal(sq_pattern_reversed(&G.pattern, &cw, &err), SQ_OK);
    sq_pattern_info a, b;
    assert_int_equal(sq_pattern_validate(&G.pattern, &a, &err), SQ_OK);
    assert_int_equal(sq_pattern_validate(&cw, &b, &err), SQ_OK);
    assert_int_equal(a.genus, b.genus);
    assert_int_equal(a.rank, b.rank); /* walking direction keeps the rank */
    /* reversing twice gives the word back */
    sq_pattern back;
    sq_pattern_init(&back);
    assert_int_equal(sq_pattern_reversed(&cw, &back, &err), SQ_OK);
    assert_memory_equal(back.partner, G.pattern.partner, G.pattern.k * sizeof *back.partner);
    sq_domain_options opt;
    memset(&opt, 0, sizeof opt);
    opt.pattern = &cw;
    opt.offset = SQ_NONE;
    sq_domain D;
    const double t0 = now();
    if (sq_domain_build((uint32_t)g, M.val, M.ncones, &opt, &D, &err) != SQ_OK)
        fail_msg("%s: domain with the reversed word: %s", rel, err.msg);
    const double t1 = now();
    if (sq_domain_verify(&D, M.val, M.ncones, &err) != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    uint32_t r = SQ_NONE;
    if (sq_cut_graph_domain_offset(&G, &D.pattern, &r, &err) != SQ_OK)
        fail_msg("%s: %s", rel, err.msg);
    assert_int_equal(r, 0);
    check_offset(&G, &D.pattern, r);
    char cw_s[256];
    word_string(&cw, cw_s, sizeof cw_s);
    print_message("%-24s g=%lld cones=%u: cw %s rank %u; Q %llu quads%s, offset 0; domain "
                  "%.3f s\n",
                  rel, (long long)g, M.ncones, cw_s, b.rank,
                  (unsigned long long)(D.quads_unpadded + D.quads_added),
                  D.slid ? " (slid)" : "", t1 - t0);
    sq_domain_free(&D);
    sq_pattern_free(&back);
    sq_pattern_free(&cw);
    sq_cut_graph_free(&G);
    unload(&M);
}

static void test_eight(void **s) { (void)s; run_high("mpz/eight.obj", "mpz/eight_Th_hat"); }
static void test_genus3(void **s) { (void)s; run_high("mpz/genus3.obj", "mpz/genus3_Th_hat"); }
static void test_elephant(void **s) { (void)s; run_high("cid/elephant.obj", "cid/elephant_Th_hat"); }

/* sq_pattern_reversed and the offset on hand-made words. */
static void test_reversed_and_offset(void **s)
{
    (void)s;
    sq_error err;
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    G.genus = 1;
    assert_int_equal(sq_pattern_alloc(&G.pattern, 6, &err), SQ_OK);
    for (uint32_t i = 0; i < 6; ++i)
        G.pattern.partner[i] = (i + 3) % 6;
    G.pattern.straight[0] = G.pattern.straight[1] = 1; /* what the theta graph marks */
    sq_pattern cw;
    sq_pattern_init(&cw);
    assert_int_equal(sq_pattern_reversed(&G.pattern, &cw, &err), SQ_OK);
    for (uint32_t i = 0; i < 6; ++i)
        assert_int_equal(cw.partner[i], (i + 3) % 6);
    /* clockwise corner j = counterclockwise corner (6 - j) mod 6 */
    const uint8_t want[6] = {1, 0, 0, 0, 0, 1};
    assert_memory_equal(cw.straight, want, 6);
    /* Q of genus 1: straight corners 0 and 5 -> offset 0 honours them */
    sq_pattern q;
    sq_pattern_init(&q);
    assert_int_equal(sq_pattern_alloc(&q, 6, &err), SQ_OK);
    for (uint32_t i = 0; i < 6; ++i)
        q.partner[i] = (i + 3) % 6;
    q.straight[0] = q.straight[5] = 1;
    uint32_t r = 99;
    assert_int_equal(sq_cut_graph_domain_offset(&G, &q, &r, &err), SQ_OK);
    assert_int_equal(r, 0);
    /* straight corners elsewhere: partners still match, r honours straight */
    memset(q.straight, 0, 6);
    q.straight[2] = q.straight[1] = 1;
    assert_int_equal(sq_cut_graph_domain_offset(&G, &q, &r, &err), SQ_OK);
    for (uint32_t j = 0; j < 6; ++j)
        assert_int_equal(cw.straight[(j + r) % 6], q.straight[j]);
    /* a genus-2 word: offset found is a true rotation; a wrong pairing fails */
    sq_pattern p2;
    sq_pattern_init(&p2);
    assert_int_equal(sq_pattern_canonical(2, &p2, &err), SQ_OK);
    sq_cut_graph H;
    sq_cut_graph_init(&H);
    H.genus = 2;
    assert_int_equal(sq_pattern_reversed(&p2, &H.pattern, &err), SQ_OK); /* H ccw, p2 cw */
    for (uint32_t rot = 0; rot < 12; ++rot) {
        sq_pattern qq;
        sq_pattern_init(&qq);
        assert_int_equal(sq_pattern_alloc(&qq, 12, &err), SQ_OK);
        /* Q side j = p2 side (j + rot) */
        for (uint32_t j = 0; j < 12; ++j)
            qq.partner[j] = (p2.partner[(j + rot) % 12] + 12 - rot) % 12;
        assert_int_equal(sq_cut_graph_domain_offset(&H, &qq, &r, &err), SQ_OK);
        check_offset(&H, &qq, r);
        sq_pattern_free(&qq);
    }
    sq_pattern_free(&q);
    assert_int_equal(sq_pattern_alloc(&q, 12, &err), SQ_OK);
    for (uint32_t j = 0; j < 12; ++j)
        q.partner[j] = 11 - j; /* a nested pairing: genus 0, never a rotation of p2 */
    assert_int_equal(sq_cut_graph_domain_offset(&H, &q, &r, &err), SQ_ERR_ARGUMENT);
    sq_pattern_free(&q);
    assert_int_equal(sq_pattern_alloc(&q, 4, &err), SQ_OK);
    assert_int_equal(sq_cut_graph_domain_offset(&H, &q, &r, &err), SQ_ERR_ARGUMENT);
    sq_pattern_free(&q);
    sq_pattern_free(&p2);
    sq_pattern_free(&cw);
    sq_cut_graph_free(&H);
    sq_cut_graph_free(&G);
}

/* Genus 0: every vertex a cone except one edge's ends: no 2-edge path. */
static void test_genus0_needs_split(void **s)
{
    (void)s;
    model M;
    load(&M, "libigl/decimated-knight.off", NULL);
    const sq_mesh *m = &M.m;
    uint8_t *cone = malloc(m->nv);
    memset(cone, 1, m->nv);
    const uint32_t v = 5, w = mesh_dest(m, m->v_he[v]);
    cone[v] = cone[w] = 0;
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_cut_stats stats;
    sq_error err;
    assert_int_equal(sq_cut_graph_build_low_genus(m, cone, NULL, &G, &stats, &err),
                     SQ_ERR_ARGUMENT);
    assert_int_equal(stats.failure, SQ_CUT_FAIL_NEEDS_SPLIT);
    assert_non_null(strstr(err.msg, "edge split"));
    assert_true(cone[stats.where[0]] && cone[stats.where[1]]);
    assert_null(G.he_cut);
    /* one more free vertex next to v (not adjacent to w) opens a path */
    uint32_t h = m->v_he[v], x = SQ_NONE;
    do {
        const uint32_t y = mesh_dest(m, h);
        int adj = 0;
        uint32_t t = m->v_he[w];
        do {
            adj |= mesh_dest(m, t) == y;
            t = m->he_next[m->he_twin[t]];
        } while (t != m->v_he[w]);
        if (y != w && !adj)
            x = y;
        h = m->he_next[m->he_twin[h]];
    } while (h != m->v_he[v] && x == SQ_NONE);
    assert_int_not_equal(x, SQ_NONE);
    cone[x] = 0;
    M.cone = cone;
    assert_int_equal(sq_cut_graph_build_low_genus(m, cone, NULL, &G, &stats, &err), SQ_OK);
    check_graph(&M, &G, 0, 1, 2);
    assert_int_equal(G.ncut_edges, 2);
    sq_cut_graph_free(&G);
    unload(&M); /* frees cone */
}

/* Genus 1 with cones walling a vertex in: reported as needing a split. */
static void test_genus1_needs_split(void **s)
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
    assert_int_equal(sq_cut_graph_build_low_genus(m, cone, NULL, &G, &stats, &err),
                     SQ_ERR_ARGUMENT);
    assert_int_equal(stats.failure, SQ_CUT_FAIL_NEEDS_SPLIT);
    assert_non_null(strstr(err.msg, "edge split"));
    assert_true(cone[stats.where[0]] && cone[stats.where[1]]);
    assert_null(G.he_cut);
    free(cone);
    unload(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reversed_and_offset),
        cmocka_unit_test(test_fandisk),
        cmocka_unit_test(test_genus0_seeds),
        cmocka_unit_test(test_homer),
        cmocka_unit_test(test_bunny),
        cmocka_unit_test(test_knight),
        cmocka_unit_test(test_elk),
        cmocka_unit_test(test_knot1),
        cmocka_unit_test(test_rocker_arm),
        cmocka_unit_test(test_trim_star),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_kitten),
        cmocka_unit_test(test_eight),
        cmocka_unit_test(test_genus3),
        cmocka_unit_test(test_elephant),
        cmocka_unit_test(test_genus0_needs_split),
        cmocka_unit_test(test_genus1_needs_split),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
