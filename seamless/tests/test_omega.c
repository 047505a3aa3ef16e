/* Tests of the flat domain Omega (seed 7; seed 3, Fig. 2): for the cone
 * multisets of the shared Table-1 models and random admissible multisets
 * (genus 2..6), build Q, the cone tree, cut and lay out, then check
 * exactly: Omega_c is a disk (Euler characteristic 1, one boundary loop),
 * every quad is a counterclockwise unit square placed consistently from
 * every neighbour, every side pair and tree segment has one seamless
 * transition (rotation by k x 90 degrees plus an integer translation) on
 * every vertex, every cone lies on the boundary with copies adding up to
 * its valence, every other glued point (corner classes included) has 360
 * degrees. Also: trees given by the caller, bad trees rejected, and the
 * verifier catching corrupted layouts. SQ_LONG_TESTS=1 runs 10x more. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_test_random.h"

#include "sq_domain.h"
#include "sq_omega.h"
#include "sq_seamless_svg.h"

typedef struct case_stats {
    uint64_t quads, tree_edges, segments, cones, bbox;
} case_stats;

/* Independent counts on a built Omega, beyond sq_omega_verify. */
static void check_counts(const sq_domain *D, const sq_cone_tree *T, const sq_omega *O,
                         const int32_t *val, uint32_t n)
{
    const sq_metapolygon *Q = &D->quads, *C = &O->cut;
    /* Euler characteristic 1: V - E + F; every edge has two halfedges (a
     * boundary edge: its face side and its boundary side) */
    assert_int_equal(C->nh % 2, 0);
    int64_t E = (int64_t)C->nh / 2;
    assert_int_equal((int64_t)C->nv - E + (int64_t)C->nf, 1);
    /* one boundary loop through all boundary halfedges */
    uint32_t len = 0, h = C->bnd_he;
    do {
        assert_true(C->he_face[h] == SQ_NONE);
        len++;
        h = C->he_next[h];
    } while (h != C->bnd_he && len <= C->nh);
    assert_int_equal(len, C->nbnd);
    assert_int_equal(C->nbnd, Q->nbnd + 2 * T->nedges);
    /* every cone: only boundary copies, angles adding up to its valence;
     * the valences of Q's cones are the input multiset (valence 4 dropped) */
    uint32_t *angle = malloc(C->nv * sizeof *angle), *sum = calloc(Q->nv, sizeof *sum);
    uint8_t *inner = calloc(Q->nv, 1), *onb = calloc(C->nv, 1);
    uint32_t hist[64] = {0}, want[64] = {0};
    assert_non_null(angle), assert_non_null(sum), assert_non_null(inner), assert_non_null(onb);
    assert_int_equal(sq_omega_angles(D, O, angle, NULL, NULL), SQ_OK);
    for (uint32_t b = 0; b < C->nh; b++)
        if (C->he_face[b] == SQ_NONE) onb[C->he_vert[b]] = 1;
    for (uint32_t v = 0; v < Q->nv; v++) inner[v] = 1;
    for (uint32_t b = 0; b < Q->nh; b++)
        if (Q->he_face[b] == SQ_NONE) inner[Q->he_vert[b]] = 0;
    for (uint32_t w = 0; w < C->nv; w++) {
        uint32_t v = O->v_qvert[w];
        sum[v] += angle[w];
        if (inner[v] && Q->v_nface[v] != 4) assert_true(onb[w]);
    }
    for (uint32_t v = 0; v < Q->nv; v++)
        if (inner[v] && Q->v_nface[v] != 4) {
            assert_int_equal(sum[v], Q->v_nface[v]);
            hist[Q->v_nface[v] < 63 ? Q->v_nface[v] : 63]++;
        }
    for (uint32_t i = 0; i < n; i++)
        if (val[i] != 4) want[val[i] < 63 ? val[i] : 63]++;
    assert_memory_equal(hist, want, sizeof hist);
    /* every cone is a tree node */
    uint32_t cone_nodes = 0;
    for (uint32_t i = 0; i < T->nverts; i++)
        if (T->node[i] & SQ_TREE_CONE) cone_nodes++;
    uint32_t ncones = 0;
    for (uint32_t k = 0; k < 64; k++) ncones += want[k];
    assert_int_equal(cone_nodes, ncones);
    free(angle), free(sum), free(inner), free(onb);
}

static void run_case(uint32_t genus, const int32_t *val, uint32_t n, const char *svg,
                     case_stats *cs, const char *name)
{
    sq_domain D;
    sq_cone_tree T;
    sq_omega O;
    sq_error err;
    sq_cone_tree_init(&T);
    sq_omega_init(&O);
    if (sq_domain_build(genus, val, n, NULL, &D, &err)) fail_msg("%s: domain: %s", name, err.msg);
    if (sq_cone_tree_shortest(&D.quads, SQ_NONE, &T, &err)) fail_msg("%s: tree: %s", name, err.msg);
    if (sq_omega_build(&D, &T, &O, &err)) fail_msg("%s: omega: %s", name, err.msg);
    if (sq_omega_verify(&D, &T, &O, &err)) fail_msg("%s: verify: %s", name, err.msg);
    check_counts(&D, &T, &O, val, n);
    if (svg && sq_omega_write_svg(&D, &T, &O, svg, &err)) fail_msg("%s: svg: %s", name, err.msg);
    if (cs) {
        cs->quads += D.quads.nf;
        cs->tree_edges += T.nedges;
        cs->segments += T.nseg;
        cs->cones += n;
        int64_t w = O.xmax - O.xmin, h = O.ymax - O.ymin;
        cs->bbox += (uint64_t)(w > h ? w : h);
    }
    sq_omega_free(&O);
    sq_cone_tree_free(&T);
    sq_domain_free(&D);
}

static uint32_t expand(const uint32_t *count, uint32_t kmax, int32_t *v)
{
    uint32_t n = 0;
    for (uint32_t k = 0; k <= kmax; k++)
        for (uint32_t c = 0; c < count[k]; c++) v[n++] = (int32_t)k;
    return n;
}

static void test_shared_cone_sets(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        uint32_t genus;
        uint32_t n[23];
    } sets[] = {
        {"helmet", 3, {[3] = 6, [5] = 1, [7] = 1, [22] = 1}},
        {"genus3", 3, {[3] = 3, [5] = 19}},
        {"elephant", 3, {[3] = 54, [5] = 59, [6] = 4, [7] = 1}},
        {"fertility", 4, {[3] = 18, [5] = 42}},
    };
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
        int32_t v[512];
        uint32_t n = expand(sets[s].n, 22, v);
        case_stats cs = {0};
        char svg[256];
        snprintf(svg, sizeof svg, "test_omega_%s.svg", sets[s].name);
        run_case(sets[s].genus, v, n, svg, &cs, sets[s].name);
        print_message("%-9s: %6llu quads, tree %4llu edges / %3llu segments, Omega %llu wide\n",
                      sets[s].name, (unsigned long long)cs.quads,
                      (unsigned long long)cs.tree_edges, (unsigned long long)cs.segments,
                      (unsigned long long)cs.bbox);
        remove(svg);
    }
}

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static void test_random_genus_2_to_6(void **state)
{
    (void)state;
    rng_state = 20260601;
    uint32_t per = long_mode() ? 200 : SANITIZED ? 6 : 20;
    for (uint32_t g = 2; g <= 6; g++) {
        case_stats cs = {0};
        for (uint32_t c = 0; c < per; c++) {
            int32_t v[1024];
            uint32_t n = random_cones(g, v, 1024);
            char name[64];
            snprintf(name, sizeof name, "genus %u case %u", g, c);
            run_case(g, v, n, NULL, &cs, name);
        }
        print_message("genus %u: %u cases, mean %llu quads, %llu tree edges, %llu segments\n", g,
                      per, (unsigned long long)(cs.quads / per),
                      (unsigned long long)(cs.tree_edges / per),
                      (unsigned long long)(cs.segments / per));
    }
}

/* Genus 0 and 1 domains (seed 6.5, 6.2) when their builders succeed. */
static void test_low_genus(void **state)
{
    (void)state;
    static const int32_t cube[] = {3, 3, 3, 3, 3, 3, 3, 3};
    static const int32_t g0b[] = {2, 2, 3, 3, 3, 5, 3, 3};
    static const int32_t torus[] = {3, 3, 5, 5};
    static const int32_t torus2[] = {2, 6, 3, 5, 3, 5};
    struct {
        uint32_t genus;
        const int32_t *v;
        uint32_t n;
    } cases[] = {{0, cube, 8}, {0, g0b, 8}, {1, torus, 4}, {1, torus2, 6}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        sq_domain D;
        sq_error err;
        if (sq_domain_build(cases[c].genus, cases[c].v, cases[c].n, NULL, &D, &err)) {
            print_message("genus %u case %zu: domain not built (%s), skipped\n", cases[c].genus,
                          c, err.msg);
            continue;
        }
        sq_domain_free(&D);
        char name[32];
        snprintf(name, sizeof name, "low genus case %zu", c);
        run_case(cases[c].genus, cases[c].v, cases[c].n, NULL, NULL, name);
    }
}

/* A tree given by the caller: the shortest-path tree's edges, shuffled and
 * with flipped halfedges, give the same tree; bad trees are rejected. */
static void test_tree_input(void **state)
{
    (void)state;
    static const uint32_t helmet[23] = {[3] = 6, [5] = 1, [7] = 1, [22] = 1};
    int32_t v[64];
    uint32_t n = expand(helmet, 22, v);
    sq_domain D;
    sq_cone_tree T, U;
    sq_omega O;
    sq_error err;
    sq_cone_tree_init(&T);
    sq_cone_tree_init(&U);
    sq_omega_init(&O);
    assert_int_equal(sq_domain_build(3, v, n, NULL, &D, &err), SQ_OK);
    const sq_metapolygon *Q = &D.quads;
    assert_int_equal(sq_cone_tree_shortest(Q, SQ_NONE, &T, &err), SQ_OK);
    assert_true(T.nedges > 0);
    assert_int_equal(T.nverts, T.nedges + 1);
    assert_int_equal(T.vert[0], T.root);
    assert_true(T.node[0] & SQ_TREE_ROOT);
    /* root: a flat boundary vertex with one tree edge */
    assert_int_equal(Q->v_nface[T.root], 2);
    assert_int_equal(T.rot_off[1] - T.rot_off[0], 1);
    /* rotation system: interior vertices start with the edge to the parent */
    for (uint32_t i = 1; i < T.nverts; i++) {
        uint32_t first = T.rot_he[T.rot_off[i]];
        assert_int_equal(Q->he_vert[first], T.vert[i]);
    }
    for (uint32_t e = 0; e < T.nedges; e++)
        assert_int_equal(T.vert[e + 1], Q->he_vert[Q->he_twin[T.he[e]]]);

    uint32_t *edges = malloc(T.nedges * sizeof *edges);
    assert_non_null(edges);
    for (uint32_t e = 0; e < T.nedges; e++)
        edges[T.nedges - 1 - e] = (e & 1) ? Q->he_twin[T.he[e]] : T.he[e];
    assert_int_equal(sq_cone_tree_from_edges(Q, T.root, edges, T.nedges, &U, &err), SQ_OK);
    assert_int_equal(U.nedges, T.nedges);
    assert_int_equal(U.nseg, T.nseg);
    assert_memory_equal(U.he, T.he, T.nedges * sizeof *T.he);
    assert_memory_equal(U.rot_he, T.rot_he, 2 * T.nedges * sizeof *T.rot_he);
    assert_int_equal(sq_omega_build(&D, &U, &O, &err), SQ_OK);
    assert_int_equal(sq_omega_verify(&D, &U, &O, &err), SQ_OK);
    assert_int_equal(O.root_side < D.k, 1);
    {
        uint32_t *sv = malloc((D.side_len[O.root_side] + 1) * sizeof *sv);
        sq_domain_side_vertices(&D, O.root_side, sv);
        assert_int_equal(sv[O.root_pos], T.root);
        free(sv);
    }

    /* a missing edge: some cone (or subtree) is cut off */
    assert_int_equal(sq_cone_tree_from_edges(Q, T.root, edges, T.nedges - 1, &U, &err),
                     SQ_ERR_ARGUMENT);
    /* an edge listed twice */
    edges[0] = Q->he_twin[edges[1]];
    assert_int_equal(sq_cone_tree_from_edges(Q, T.root, edges, T.nedges, &U, &err),
                     SQ_ERR_ARGUMENT);
    /* a boundary edge */
    edges[0] = Q->bnd_he;
    assert_int_equal(sq_cone_tree_from_edges(Q, T.root, edges, T.nedges, &U, &err),
                     SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "not an interior edge"));
    /* the root inside Q */
    assert_int_equal(sq_cone_tree_from_edges(Q, T.vert[T.nverts - 1], T.he, T.nedges, &U, &err),
                     SQ_ERR_ARGUMENT);
    /* no edges at all: the cones are missing */
    assert_int_equal(sq_cone_tree_from_edges(Q, T.root, NULL, 0, &U, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "cone vertex"));
    /* a cycle: add an interior edge between two tree vertices not in T */
    {
        uint8_t *intree = calloc(Q->nv, 1);
        uint8_t *tedge = calloc(Q->nh, 1);
        for (uint32_t i = 0; i < T.nverts; i++) intree[T.vert[i]] = 1;
        for (uint32_t e = 0; e < T.nedges; e++) tedge[T.he[e]] = tedge[Q->he_twin[T.he[e]]] = 1;
        uint32_t extra = SQ_NONE;
        for (uint32_t h = 0; h < Q->nh && extra == SQ_NONE; h++)
            if (!tedge[h] && intree[Q->he_vert[h]] && intree[Q->he_vert[Q->he_twin[h]]] &&
                Q->he_face[h] != SQ_NONE && Q->he_face[Q->he_twin[h]] != SQ_NONE &&
                Q->he_vert[h] != T.root && Q->he_vert[Q->he_twin[h]] != T.root)
                extra = h;
        if (extra != SQ_NONE) {
            uint32_t *cyc = malloc((T.nedges + 1) * sizeof *cyc);
            memcpy(cyc, T.he, T.nedges * sizeof *cyc);
            cyc[T.nedges] = extra;
            assert_int_equal(sq_cone_tree_from_edges(Q, T.root, cyc, T.nedges + 1, &U, &err),
                             SQ_ERR_ARGUMENT);
            free(cyc);
        }
        free(intree), free(tedge);
    }
    /* a caller's root: another flat boundary vertex */
    {
        uint32_t h = Q->bnd_he, root = SQ_NONE;
        do {
            uint32_t r = Q->he_vert[h];
            if (Q->v_nface[r] == 2 && r != T.root) root = r;
            h = Q->he_next[h];
        } while (h != Q->bnd_he);
        assert_true(root != SQ_NONE);
        assert_int_equal(sq_cone_tree_shortest(Q, root, &U, &err), SQ_OK);
        assert_int_equal(U.root, root);
        assert_int_equal(sq_omega_build(&D, &U, &O, &err), SQ_OK);
        assert_int_equal(sq_omega_verify(&D, &U, &O, &err), SQ_OK);
        /* an interior vertex is no root */
        assert_int_equal(sq_cone_tree_shortest(Q, T.vert[1], &U, &err), SQ_ERR_ARGUMENT);
    }
    free(edges);
    sq_omega_free(&O);
    sq_cone_tree_free(&T);
    sq_cone_tree_free(&U);
    sq_domain_free(&D);
}

/* The verifier is not vacuous: corrupt one thing at a time. */
static void test_verify_catches(void **state)
{
    (void)state;
    static const uint32_t genus3[23] = {[3] = 3, [5] = 19};
    int32_t v[64];
    uint32_t n = expand(genus3, 22, v);
    sq_domain D;
    sq_cone_tree T;
    sq_omega O;
    sq_error err;
    sq_cone_tree_init(&T);
    sq_omega_init(&O);
    assert_int_equal(sq_domain_build(3, v, n, NULL, &D, &err), SQ_OK);
    assert_int_equal(sq_cone_tree_shortest(&D.quads, SQ_NONE, &T, &err), SQ_OK);
    assert_int_equal(sq_omega_build(&D, &T, &O, &err), SQ_OK);
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_OK);
    const sq_metapolygon *C = &O.cut;

    /* move one boundary vertex by one unit */
    uint32_t w = C->he_vert[C->bnd_he];
    O.xy[2 * w] += 1;
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    O.xy[2 * w] -= 1;
    /* move an interior vertex */
    for (w = 0; w < C->nv; w++)
        if (C->he_face[C->v_he[w]] != SQ_NONE) break;
    assert_true(w < C->nv);
    O.xy[2 * w + 1] += 1;
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    O.xy[2 * w + 1] -= 1;
    /* mirror the layout: every face clockwise */
    for (uint32_t u = 0; u < C->nv; u++) O.xy[2 * u] = -O.xy[2 * u];
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    for (uint32_t u = 0; u < C->nv; u++) O.xy[2 * u] = -O.xy[2 * u];
    /* a wrong translation on a side, then on a tree segment */
    O.label_t[0] += 1;
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    O.label_t[0] -= 1;
    O.label_rot[O.k] ^= 2u;
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    O.label_rot[O.k] ^= 2u;
    /* restored: valid again */
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_OK);
    /* a label swapped on one boundary edge */
    uint32_t b = C->bnd_he, l = O.he_label[b];
    O.he_label[b] = O.label_partner[l];
    assert_int_equal(sq_omega_verify(&D, &T, &O, &err), SQ_ERR_INTERNAL);
    O.he_label[b] = l;
    sq_omega_free(&O);
    sq_cone_tree_free(&T);
    sq_domain_free(&D);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tree_input),
        cmocka_unit_test(test_verify_catches),
        cmocka_unit_test(test_shared_cone_sets),
        cmocka_unit_test(test_random_genus_2_to_6),
        cmocka_unit_test(test_low_genus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
