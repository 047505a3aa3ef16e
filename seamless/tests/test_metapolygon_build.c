/* Valence orders (seed 5.2 Prop. 5.1, seed 9.2), building Q_(n) with
 * explicit glue-edge choices (seed 5.2, Algorithm 1's interface), and the
 * subdivision into a quad mesh (seed 5.4). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "mp_test_util.h"
#include "sq_metapolygon.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_valence_order.h"

/* ---- valence orders ---------------------------------------------------- */

static void test_check_sequence(void **state)
{
    (void)state;
    sq_error err;
    uint32_t bad;
    uint32_t ok[] = {5, 3, 3, 3, 3};
    assert_int_equal(sq_valence_check_sequence(ok, 5, &bad, &err), SQ_OK);
    assert_int_equal(bad, 5);
    uint32_t no[] = {3, 3, 3, 3, 5}; /* prefix sums -1 -2 -3 -4: bad at 3 */
    assert_int_equal(sq_valence_check_sequence(no, 5, &bad, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(bad, 3);
    assert_non_null(strstr(err.msg, "position 3"));
    uint32_t late[] = {3, 3, 3, 5, 5}; /* -1 -2 -3 -2 -1 */
    assert_int_equal(sq_valence_check_sequence(late, 5, &bad, &err), SQ_OK);
}

static void test_order_admissible(void **state)
{
    (void)state;
    sq_error err;
    uint32_t v[] = {3, 3, 3, 3, 3, 3, 5, 7, 22}; /* helmet: excess 16 */
    uint32_t out[9];
    assert_int_equal(sq_valence_excess(v, 9), 16);
    assert_int_equal(sq_valence_order_admissible(v, 9, out, &err), SQ_OK);
    uint32_t expect[] = {5, 7, 22, 3, 3, 3, 3, 3, 3};
    assert_memory_equal(out, expect, sizeof expect);
    assert_int_equal(sq_valence_check_sequence(out, 9, NULL, NULL), SQ_OK);

    /* total excess <= -4: not one metapolygon (genus 0 needs pieces) */
    uint32_t sphere[] = {3, 3, 3, 3, 3, 3, 3, 3};
    assert_int_equal(sq_valence_order_admissible(sphere, 8, out, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "-8"));
    assert_int_equal(sq_valence_order_greedy(sphere, 8, out, &err), SQ_ERR_ARGUMENT);
    uint32_t minus4[] = {2, 2};
    assert_int_equal(sq_valence_order_admissible(minus4, 2, out, &err), SQ_ERR_ARGUMENT);
    uint32_t minus3[] = {2, 3};
    assert_int_equal(sq_valence_order_admissible(minus3, 2, out, &err), SQ_OK);
    /* invalid values */
    uint32_t four[] = {5, 4};
    assert_int_equal(sq_valence_order_admissible(four, 2, out, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "position 1"));
    uint32_t one[] = {5, 5, 1};
    assert_int_equal(sq_valence_order_greedy(one, 3, out, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "valence 1"));
    /* empty multiset: excess 0 */
    assert_int_equal(sq_valence_order_admissible(NULL, 0, NULL, &err), SQ_OK);
}

static void test_order_greedy(void **state)
{
    (void)state;
    uint32_t pref[] = {2, 2, 3, 6, 5, 3};
    uint32_t out[6];
    assert_int_equal(sq_valence_order_greedy(pref, 6, out, NULL), SQ_OK);
    uint32_t expect[] = {2, 6, 2, 3, 5, 3};
    assert_memory_equal(out, expect, sizeof expect);
    /* an already admissible order is kept */
    uint32_t fine[] = {3, 5, 3, 3, 6, 2};
    assert_int_equal(sq_valence_order_greedy(fine, 6, out, NULL), SQ_OK);
    assert_memory_equal(out, fine, sizeof fine);

    /* random preferred orders: admissible, a permutation, and valences
     * <= 4 keep their relative order (only > 4 move forward) */
    rng r = {7};
    for (uint32_t t = 0; t < 2000; t++) {
        uint32_t v[256], o[256];
        int64_t target = (int64_t)rng_below(&r, 40) - 3;
        uint32_t n = random_valences(&r, target, 30, v, 256);
        assert_true(n > 0 || target == 0);
        assert_int_equal(sq_valence_order_greedy(v, n, o, NULL), SQ_OK);
        assert_int_equal(sq_valence_check_sequence(o, n, NULL, NULL), SQ_OK);
        uint32_t j = 0;
        for (uint32_t a = 0; a < n; a++) {
            if (v[a] > 4) continue;
            while (j < n && o[j] > 4) j++;
            assert_true(j < n);
            assert_int_equal(o[j], v[a]);
            j++;
        }
        uint32_t s1[256], s2[256];
        memcpy(s1, v, n * sizeof *v);
        memcpy(s2, o, n * sizeof *o);
        qsort(s1, n, sizeof *s1, cmp_u32);
        qsort(s2, n, sizeof *s2, cmp_u32);
        assert_memory_equal(s1, s2, n * sizeof *s1);
    }
}

/* ---- build --------------------------------------------------------------- */

typedef struct choice_log {
    rng r;
    uint32_t n;
    uint32_t he[256];
    int fail_at;
} choice_log;

/* A stand-in for geometric guidance: a random boundary edge, logged. */
static sq_status random_chooser(void *user, const sq_metapolygon *P, uint32_t step,
                                uint32_t valence, uint32_t *glue_he, sq_error *err)
{
    (void)valence;
    choice_log *L = user;
    if ((int)step == L->fail_at) return sq_error_set(err, SQ_ERR_SOLVER, "embedding failed");
    uint32_t h = P->bnd_he;
    for (uint32_t t = rng_below(&L->r, P->nbnd); t > 0; t--) h = P->he_next[h];
    L->he[step] = h;
    L->n = step + 1;
    *glue_he = h;
    return SQ_OK;
}

static void test_build_explicit_choices(void **state)
{
    (void)state;
    uint32_t seq[] = {6, 5, 3, 7, 2, 3, 3, 5, 2, 3};
    sq_metapolygon A, B;
    sq_metapolygon_init(&A);
    sq_metapolygon_init(&B);
    choice_log L = {{99}, 0, {0}, -1};
    sq_build_options opt = {NULL, random_chooser, &L};
    sq_build_stats st;
    assert_int_equal(sq_metapolygon_build(&A, seq, 10, &opt, &st, NULL), SQ_OK);
    assert_int_equal(st.corners, 4 + sq_valence_excess(seq, 10));
    assert_int_equal(st.quads, sq_metapolygon_count_quads(&A));
    assert_int_equal(st.quads, st.quads_step2 + st.quads_step3);
    /* the same choices as an array give the same mesh, index for index */
    L.he[0] = SQ_NONE;
    sq_build_options arr = {L.he, NULL, NULL};
    assert_int_equal(sq_metapolygon_build(&B, seq, 10, &arr, NULL, NULL), SQ_OK);
    assert_int_equal(A.nh, B.nh);
    assert_memory_equal(A.he_next, B.he_next, A.nh * sizeof(uint32_t));
    assert_memory_equal(A.he_vert, B.he_vert, A.nh * sizeof(uint32_t));
    sq_metapolygon_free(&B);

    /* array entries SQ_NONE fall back to the default: all-SQ_NONE equals no
     * options at all */
    uint32_t none[10];
    for (int j = 0; j < 10; j++) none[j] = SQ_NONE;
    sq_metapolygon C, D;
    sq_metapolygon_init(&C);
    sq_metapolygon_init(&D);
    sq_build_options nopt = {none, NULL, NULL};
    assert_int_equal(sq_metapolygon_build(&C, seq, 10, &nopt, NULL, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_build(&D, seq, 10, NULL, NULL, NULL), SQ_OK);
    assert_int_equal(C.nh, D.nh);
    assert_memory_equal(C.he_next, D.he_next, C.nh * sizeof(uint32_t));
    sq_metapolygon_free(&C);
    sq_metapolygon_free(&D);
    sq_metapolygon_free(&A);
}

static void test_build_errors(void **state)
{
    (void)state;
    sq_error err;
    sq_metapolygon P;
    sq_metapolygon_init(&P);
    uint32_t bad[] = {3, 3, 3, 3, 5};
    assert_int_equal(sq_metapolygon_build(&P, bad, 5, NULL, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "position 3"));
    assert_int_equal(P.nf, 0);

    uint32_t seq[] = {5, 3, 5};
    uint32_t first[] = {0, SQ_NONE, SQ_NONE};
    sq_build_options o1 = {first, NULL, NULL};
    assert_int_equal(sq_metapolygon_build(&P, seq, 3, &o1, NULL, &err), SQ_ERR_ARGUMENT);

    choice_log L = {{1}, 0, {0}, 2};
    sq_build_options o2 = {NULL, random_chooser, &L};
    assert_int_equal(sq_metapolygon_build(&P, seq, 3, &o2, NULL, &err), SQ_ERR_SOLVER);
    assert_non_null(strstr(err.msg, "step 2"));
    assert_non_null(strstr(err.msg, "embedding failed"));
    sq_metapolygon_free(&P);

    /* an interior halfedge as glue edge */
    uint32_t inner[] = {SQ_NONE, 0, SQ_NONE};
    sq_build_options o3 = {inner, NULL, NULL};
    assert_int_equal(sq_metapolygon_build(&P, seq, 3, &o3, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "step 1"));
    sq_metapolygon_free(&P);

    /* non-empty input */
    assert_int_equal(sq_metapolygon_make_grid(&P, 1, 1, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_build(&P, seq, 3, NULL, NULL, &err), SQ_ERR_ARGUMENT);
    sq_metapolygon_free(&P);

    /* n = 0: Q_(0) is empty */
    assert_int_equal(sq_metapolygon_build(&P, NULL, 0, NULL, NULL, &err), SQ_OK);
    assert_int_equal(P.nf, 0);
}

/* ---- subdivision ----------------------------------------------------------- */

/* Checks Q against P and the seed 5.4 claims with the independent checker;
 * returns the number of quads. */
static uint32_t check_subdivision(const sq_metapolygon *P, const sq_mp_quads *Q)
{
    sq_error err;
    sq_status st = sq_metapolygon_validate(&Q->mesh, 0, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    uint32_t *quads = quads_of(Q);
    quad_report R = check_quad_disk(Q->mesh.nv, Q->mesh.nf, quads);
    if (!R.ok) print_error("%s\n", R.why);
    assert_true(R.ok);
    /* one quad per face corner; interior vertex valences */
    uint64_t corners_of_faces = 0;
    for (uint32_t f = 0; f < P->nf; f++) corners_of_faces += P->f_valence[f];
    assert_int_equal(Q->mesh.nf, corners_of_faces);
    uint32_t irregular = 0;
    for (uint32_t v = 0; v < Q->mesh.nv; v++) {
        if (R.on_boundary[v]) {
            assert_true(R.valence[v] == 1 || R.valence[v] == 2);
            assert_int_equal(R.valence[v] == 1, Q->v_corner[v]);
            continue;
        }
        if (R.valence[v] != 4) {
            irregular++;
            assert_int_equal(Q->v_origin_kind[v], SQ_MP_ORIGIN_FACE);
            assert_int_equal(P->f_valence[Q->v_origin[v]], R.valence[v]);
        }
    }
    assert_int_equal(irregular, sq_metapolygon_irregular(P, 0, NULL));
    /* sides: doubled metapolygon sides, runs of the boundary */
    uint32_t len[512];
    uint32_t k = sq_metapolygon_nonflat(P, 512, NULL, NULL, len);
    assert_int_equal(Q->ncorner, k);
    uint64_t total = 0;
    for (uint32_t s = 0; s < k; s++) {
        assert_true(Q->side_len[s] >= 2 && Q->side_len[s] % 2 == 0);
        assert_int_equal(Q->side_len[s], 2 * len[s]);
        assert_true(Q->v_corner[Q->bnd_vert[Q->corner_pos[s]]]);
        for (uint32_t j = 1; j < Q->side_len[s]; j++)
            assert_false(Q->v_corner[Q->bnd_vert[(Q->corner_pos[s] + j) % Q->nbnd]]);
        total += Q->side_len[s];
    }
    assert_int_equal(total, Q->nbnd);
    assert_int_equal(R.n_boundary_verts, Q->nbnd);
    for (uint32_t j = 0; j < Q->nbnd; j++) {
        assert_int_equal(Q->mesh.he_vert[Q->bnd_he[j]], Q->bnd_vert[j]);
        assert_int_equal(Q->mesh.he_next[Q->bnd_he[j]], Q->bnd_he[(j + 1) % Q->nbnd]);
    }
    quad_report_free(&R);
    free(quads);
    return Q->mesh.nf;
}

static void test_subdivide_small(void **state)
{
    (void)state;
    for (uint32_t i = 2; i <= 7; i++) {
        if (i == 4) continue;
        sq_metapolygon P;
        sq_metapolygon_init(&P);
        assert_int_equal(sq_metapolygon_extend(&P, i, SQ_NONE, NULL, NULL), SQ_OK);
        sq_mp_quads Q;
        assert_int_equal(sq_metapolygon_subdivide(&P, &Q, NULL), SQ_OK);
        assert_int_equal(check_subdivision(&P, &Q), i);
        assert_int_equal(Q.mesh.nv, i + i + 1);
        assert_int_equal(Q.ncorner, i);
        sq_mp_quads_free(&Q);
        sq_metapolygon_free(&P);
    }
    sq_metapolygon P;
    sq_metapolygon_init(&P);
    assert_int_equal(sq_metapolygon_make_grid(&P, 2, 3, NULL), SQ_OK);
    sq_mp_quads Q;
    assert_int_equal(sq_metapolygon_subdivide(&P, &Q, NULL), SQ_OK);
    assert_int_equal(check_subdivision(&P, &Q), 24);
    assert_int_equal(Q.mesh.nv, 7 * 5);
    sq_mp_quads_free(&Q);
    /* refuses a concave vertex */
    uint32_t len[4], he[4];
    sq_metapolygon_nonflat(&P, 4, NULL, he, len);
    uint32_t h = len[0] > 1 ? P.he_next[he[0]] : P.he_next[he[1]];
    assert_int_equal(sq_metapolygon_glue_polygon(&P, h, 1, 1, NULL, NULL, NULL, NULL), SQ_OK);
    sq_error err;
    assert_int_equal(sq_metapolygon_subdivide(&P, &Q, &err), SQ_ERR_ARGUMENT);
    sq_metapolygon_free(&P);
    sq_metapolygon_init(&P);
    assert_int_equal(sq_metapolygon_subdivide(&P, &Q, &err), SQ_ERR_ARGUMENT);
}

/* The cone sets of two of the seed's Table 1 models (genus 3, meta-20-gons):
 * built with the default glue edge; sizes reported. */
static void build_example(const char *name, const uint32_t *cones, uint32_t n,
                          int descending)
{
    uint32_t seq[64];
    assert_int_equal(sq_valence_order_admissible(cones, n, seq, NULL), SQ_OK);
    if (descending) { /* positives by decreasing valence, then negatives */
        uint32_t npos = 0;
        while (npos < n && seq[npos] > 4) npos++;
        qsort(seq, npos, sizeof *seq, cmp_u32);
        for (uint32_t a = 0, b = npos - 1; npos && a < b; a++, b--) {
            uint32_t t = seq[a];
            seq[a] = seq[b];
            seq[b] = t;
        }
    }
    sq_metapolygon P;
    sq_metapolygon_init(&P);
    sq_build_stats st;
    assert_int_equal(sq_metapolygon_build(&P, seq, n, NULL, &st, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_validate(&P, SQ_MP_CHECK_METAPOLYGON, NULL), SQ_OK);
    assert_int_equal(st.corners, 20);
    sq_mp_quads Q;
    assert_int_equal(sq_metapolygon_subdivide(&P, &Q, NULL), SQ_OK);
    uint32_t nq = check_subdivision(&P, &Q);
    print_message("%-7s %s order: metapolygon %u faces (%llu 4-gons), subdivided %u quads, "
                  "boundary %u quad edges\n",
                  name, descending ? "descending" : "input     ", P.nf,
                  (unsigned long long)st.quads, nq, Q.nbnd);
    sq_mp_quads_free(&Q);
    sq_metapolygon_free(&P);
    if (descending) return;
    /* for scale: random glue edges on the same sequence */
    choice_log L = {{2024}, 0, {0}, -1};
    sq_build_options opt = {NULL, random_chooser, &L};
    uint64_t sum = 0, max = 0;
    for (int t = 0; t < 200; t++) {
        sq_metapolygon_init(&P);
        assert_int_equal(sq_metapolygon_build(&P, seq, n, &opt, &st, NULL), SQ_OK);
        uint64_t quads = 0;
        for (uint32_t f = 0; f < P.nf; f++) quads += P.f_valence[f];
        sum += quads;
        if (quads > max) max = quads;
        sq_metapolygon_free(&P);
    }
    print_message("%-7s random glue edges: subdivided quads mean %.1f, max %llu (200 runs)\n",
                  name, sum / 200.0, (unsigned long long)max);
}

static void test_examples_table1(void **state)
{
    (void)state;
    uint32_t helmet[] = {3, 3, 3, 3, 3, 3, 5, 7, 22};
    uint32_t genus3[22];
    for (int j = 0; j < 3; j++) genus3[j] = 3;
    for (int j = 3; j < 22; j++) genus3[j] = 5;
    build_example("helmet", helmet, 9, 0);
    build_example("helmet", helmet, 9, 1);
    build_example("genus3", genus3, 22, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_check_sequence),
        cmocka_unit_test(test_order_admissible),
        cmocka_unit_test(test_order_greedy),
        cmocka_unit_test(test_build_explicit_choices),
        cmocka_unit_test(test_build_errors),
        cmocka_unit_test(test_subdivide_small),
        cmocka_unit_test(test_examples_table1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
