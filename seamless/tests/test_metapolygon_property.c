/* Property tests of the whole seed-5 pipeline on random cone sets:
 * valences -> admissible order (seed 9.2 greedy) -> Q_(n) (seed 5.2) with
 * random or default glue edges -> quad mesh (seed 5.4), checked by an
 * independent quad-mesh checker. Bounded in CI; SQ_LONG_TESTS=1 runs 100x
 * more. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "mp_test_util.h"
#include "sq_metapolygon.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_valence_order.h"

#define MAXV 1024

typedef struct chooser_state {
    rng r;
    int random;              /* random edge, else the default edge      */
    uint64_t predicted;      /* sum of seed 5.3 counts of the choices    */
    int prediction_failed;
} chooser_state;

static sq_status chooser(void *user, const sq_metapolygon *P, uint32_t step, uint32_t valence,
                         uint32_t *glue_he, sq_error *err)
{
    (void)step;
    chooser_state *S = user;
    uint32_t h;
    if (S->random) {
        h = P->bnd_he;
        for (uint32_t t = rng_below(&S->r, P->nbnd); t > 0; t--) h = P->he_next[h];
    } else {
        sq_status st = sq_metapolygon_default_glue_edge(P, valence, &h, err);
        if (st != SQ_OK) return st;
    }
    uint64_t q = sq_metapolygon_predict_quads(P, valence, h);
    if (q == UINT64_MAX) S->prediction_failed = 1;
    S->predicted += q;
    *glue_he = h;
    return SQ_OK;
}

typedef struct outcome {
    uint64_t quads_meta;   /* 4-gons of the metapolygon      */
    uint64_t quads_sub;    /* quads after subdivision        */
} outcome;

/* Builds, subdivides and checks everything for one valence multiset. */
static outcome run_one(const uint32_t *cones, uint32_t n, rng *r, int random_glue)
{
    outcome o = {0, 0};
    uint32_t seq[MAXV];
    sq_error err;
    sq_status st = sq_valence_order_greedy(cones, n, seq, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    int64_t excess = sq_valence_excess(seq, n);

    sq_metapolygon P;
    sq_metapolygon_init(&P);
    chooser_state S = {{rng_next(r)}, random_glue, 0, 0};
    sq_build_options opt = {NULL, chooser, &S};
    sq_build_stats bs;
    st = sq_metapolygon_build(&P, seq, n, &opt, &bs, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    if (n == 0) { /* Q_(0) is the empty metapolygon */
        assert_int_equal(P.nf, 0);
        return o;
    }
    st = sq_metapolygon_validate(&P, SQ_MP_CHECK_METAPOLYGON, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    /* Theorem 5.5 / Prop. 5.1: a meta-(4 + excess)-gon with I = the cones */
    assert_int_equal(bs.corners, 4 + excess);
    assert_int_equal(sq_metapolygon_excess(&P), excess);
    assert_false(S.prediction_failed);
    assert_int_equal(S.predicted, bs.quads); /* seed 5.3 counts, step by step */
    uint32_t irr[MAXV], want[MAXV];
    assert_int_equal(sq_metapolygon_irregular(&P, MAXV, irr), n);

    sq_mp_quads Q;
    st = sq_metapolygon_subdivide(&P, &Q, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    uint32_t *quads = quads_of(&Q);
    quad_report R = check_quad_disk(Q.mesh.nv, Q.mesh.nf, quads);
    if (!R.ok) print_error("quad mesh: %s\n", R.why);
    assert_true(R.ok);
    assert_int_equal(R.euler, 1);
    assert_int_equal(R.n_boundary_loops, 1);
    /* interior vertices: valence != 4 exactly at the cones */
    uint32_t nirr = 0, ncorner = 0;
    for (uint32_t v = 0; v < Q.mesh.nv; v++) {
        if (R.on_boundary[v]) {
            assert_true(R.valence[v] == 1 || R.valence[v] == 2);
            ncorner += R.valence[v] == 1;
            assert_int_equal(R.valence[v] == 1, Q.v_corner[v]);
        } else if (R.valence[v] != 4) {
            assert_true(nirr < MAXV);
            irr[nirr++] = R.valence[v];
        }
    }
    assert_int_equal(nirr, n);
    memcpy(want, cones, n * sizeof *cones);
    qsort(irr, n, sizeof *irr, cmp_u32);
    qsort(want, n, sizeof *want, cmp_u32);
    assert_memory_equal(irr, want, n * sizeof *irr);
    assert_int_equal(ncorner, 4 + excess);
    assert_int_equal(Q.ncorner, ncorner);
    uint64_t total = 0;
    for (uint32_t s = 0; s < Q.ncorner; s++) {
        assert_true(Q.side_len[s] >= 2 && Q.side_len[s] % 2 == 0);
        /* the side is a boundary run between consecutive corners */
        assert_int_equal(R.valence[Q.bnd_vert[Q.corner_pos[s]]], 1);
        for (uint32_t j = 1; j < Q.side_len[s]; j++)
            assert_int_equal(R.valence[Q.bnd_vert[(Q.corner_pos[s] + j) % Q.nbnd]], 2);
        total += Q.side_len[s];
    }
    assert_int_equal(total, R.n_boundary_verts);
    o.quads_meta = bs.quads;
    o.quads_sub = Q.mesh.nf;
    quad_report_free(&R);
    free(quads);
    sq_mp_quads_free(&Q);
    sq_metapolygon_free(&P);
    return o;
}

static uint32_t scale(uint32_t n)
{
    return long_tests() ? 100 * n : n;
}

/* Genus 1..30: total excess 8g - 8 (Gauss-Bonnet, seed 6); every other
 * run glues to random edges, the others to the default edge. */
static void test_random_genus(void **state)
{
    (void)state;
    rng r = {0x5eed0001};
    uint32_t runs = scale(1500);
    uint64_t max_quads = 0;
    for (uint32_t t = 0; t < runs; t++) {
        int random_glue = t % 2;
        uint32_t g = 1 + rng_below(&r, 30);
        uint32_t cones[MAXV];
        uint32_t n = random_valences(&r, 8 * (int64_t)g - 8, 2 * g + 4, cones, MAXV);
        assert_true(n > 0 || g == 1);
        outcome o = run_one(cones, n, &r, random_glue);
        if (o.quads_sub > max_quads) max_quads = o.quads_sub;
    }
    print_message("%u random cone sets of genus 1..30 passed (largest: %llu quads)\n", runs,
                  (unsigned long long)max_quads);
}

/* Any total excess > -4 (one metapolygon, Prop. 5.1). */
static void test_random_excess(void **state)
{
    (void)state;
    rng r = {0x5eed0002};
    uint32_t runs = scale(1000);
    for (uint32_t t = 0; t < runs; t++) {
        int64_t target = (int64_t)rng_below(&r, 44) - 3;
        uint32_t cones[MAXV];
        uint32_t n = random_valences(&r, target, 12, cones, MAXV);
        run_one(cones, n, &r, (int)rng_below(&r, 2));
    }
    print_message("%u random cone sets with excess -3..40 passed\n", runs);
}

/* The default glue edge against random edges on the same sequences. */
static void test_default_beats_random(void **state)
{
    (void)state;
    rng r = {0x5eed0003};
    uint32_t runs = scale(300);
    double sum_def = 0, sum_rnd = 0;
    uint32_t def_wins = 0, ties = 0;
    for (uint32_t t = 0; t < runs; t++) {
        uint32_t g = 1 + rng_below(&r, 6);
        uint32_t cones[MAXV];
        uint32_t n = random_valences(&r, 8 * (int64_t)g - 8, 2 * g + 4, cones, MAXV);
        outcome d = run_one(cones, n, &r, 0);
        outcome x = run_one(cones, n, &r, 1);
        sum_def += (double)d.quads_meta;
        sum_rnd += (double)x.quads_meta;
        def_wins += d.quads_meta < x.quads_meta;
        ties += d.quads_meta == x.quads_meta;
    }
    print_message("genus 1..6, %u cone sets: mean 4-gons default %.1f, random %.1f; default "
                  "smaller in %u, equal in %u\n",
                  runs, sum_def / runs, sum_rnd / runs, def_wins, ties);
    assert_true(sum_def <= sum_rnd);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_genus),
        cmocka_unit_test(test_random_excess),
        cmocka_unit_test(test_default_beats_random),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
