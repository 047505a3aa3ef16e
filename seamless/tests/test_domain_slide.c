/* Property tests of one slide (seed 6.4, 9.3; seamless-notes 3, 7;
 * docs/domain.md "Sliding"): for side-pairing patterns that fail the rank
 * test, split the subdivided metapolygon along a straight edge sequence,
 * pad both pieces exactly, slide them back together, and check the result
 * with sq_domain_verify (corners, equal pair lengths, closed simple mesh of
 * the right genus whose irregular vertices are exactly the cones).
 *
 * - the 6 rank-1 genus-2 patterns (from the 10395 pairings of 12 sides),
 *   with random cone sets: a slide must always exist and verify;
 * - the 9 rank-0 genus-2 patterns: a slide adds one direction only, so it
 *   fails with a clear message unless the closure vector happens to lie on
 *   that direction; what happens is counted and every success verified;
 * - random rank-1 patterns of genus 3..6 (sq_pattern_random).
 * SQ_LONG_TESTS=1 runs 20 times more cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "sq_test_random.h"

#include "sq_domain.h"
#include "sq_domain_slide.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_padding.h"
#include "sq_pattern.h"
#include "sq_valence_order.h"

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static uint32_t scale(uint32_t n)
{
    return long_mode() ? 20 * n : SANITIZED ? (n + 4) / 5 : n;
}

/* The state in which sq_domain_build (sq_domain.c) would call the slide:
 * admissible order, metapolygon, subdivision, pattern (seed 5.1-5.4). */
static sq_status prepare(uint32_t genus, const int32_t *val, uint32_t n, const sq_pattern *pat,
                         sq_domain *D, uint32_t *corner_v, uint32_t *len, sq_error *err)
{
    sq_domain_init(D);
    D->genus = genus;
    uint32_t irr[512], m = 0;
    for (uint32_t i = 0; i < n; i++)
        if (val[i] != 4) irr[m++] = (uint32_t)val[i];
    D->ncones = m;
    D->order = malloc(((size_t)m + 1) * sizeof *D->order);
    if (!D->order) return SQ_ERR_NOMEM;
    sq_status st = sq_valence_order_admissible(irr, m, D->order, err);
    if (!st) st = sq_metapolygon_build(&D->meta, D->order, m, NULL, NULL, err);
    if (st) return st;
    sq_mp_quads sub;
    st = sq_metapolygon_subdivide(&D->meta, &sub, err);
    if (st) return st;
    const uint32_t k = sub.ncorner;
    assert_int_equal(k, 8 * genus - 4);
    D->k = k;
    D->quads_unpadded = D->nf_unpadded = sub.mesh.nf;
    D->f_meta_face = malloc((size_t)sub.mesh.nf * sizeof *D->f_meta_face);
    D->corner_vert = malloc((size_t)k * sizeof *D->corner_vert);
    D->side_len = malloc((size_t)k * sizeof *D->side_len);
    D->padding = malloc((size_t)k * sizeof *D->padding);
    assert_non_null(D->f_meta_face);
    assert_non_null(D->corner_vert);
    assert_non_null(D->side_len);
    assert_non_null(D->padding);
    for (uint32_t f = 0; f < sub.mesh.nf; f++) D->f_meta_face[f] = D->meta.he_face[sub.f_origin[f]];
    for (uint32_t j = 0; j < k; j++) {
        corner_v[j] = sub.bnd_vert[sub.corner_pos[j]];
        len[j] = sub.side_len[j];
    }
    D->quads = sub.mesh;
    sq_metapolygon_init(&sub.mesh);
    sq_mp_quads_free(&sub);
    return sq_pattern_copy(&D->pattern, pat, err);
}

/* 1 if padding alone (any offset) equalizes the pattern: the lead's path. */
static int padding_alone(const sq_pattern *pat, const uint32_t *len)
{
    const uint32_t k = pat->k;
    int64_t L[64], w[64];
    for (uint32_t o = 0; o < k; o++) {
        for (uint32_t i = 0; i < k; i++) L[i] = len[(i + o) % k];
        sq_pad_result res;
        memset(&res, 0, sizeof res);
        res.w = w;
        sq_pad_options popt = {SQ_PAD_OPT_NO_DESCENT, 0};
        if (sq_pad_solve_pattern(pat, L, &popt, &res, NULL) == SQ_OK) return 1;
    }
    return 0;
}

typedef struct tally {
    uint32_t cases, built, infeasible, alone, needed, needed_built;
    uint64_t seqs, valid, feasible, quads0, added;
    int64_t max_shift;
    double seconds, worst;
} tally;

/* Builds with a slide; on success verifies everything. Returns the status
 * of sq_domain_slide_build. */
static sq_status run_case(uint32_t genus, const sq_pattern *pat, const int32_t *val, uint32_t n,
                          tally *T, int *alone_out, sq_error *err)
{
    sq_domain D;
    uint32_t corner_v[64], len[64];
    assert_int_equal(prepare(genus, val, n, pat, &D, corner_v, len, err), SQ_OK);
    T->cases++;
    const int alone = padding_alone(pat, len);
    T->alone += (uint32_t)alone;
    T->needed += !alone;
    sq_slide_info info;
    clock_t t0 = clock();
    sq_status st = sq_domain_slide_build(&D, corner_v, len, SQ_NONE, &info, err);
    double sec = (double)(clock() - t0) / CLOCKS_PER_SEC;
    T->seconds += sec;
    if (sec > T->worst) T->worst = sec;
    T->seqs += info.sequences;
    T->valid += info.valid;
    T->feasible += info.feasible;
    if (st == SQ_OK) {
        sq_error e2;
        if (sq_domain_verify(&D, val, n, &e2))
            fail_msg("genus %u: slide built but verify failed: %s", genus, e2.msg);
        assert_true(info.valid > 0 && info.feasible > 0);
        assert_true(info.corners[0] % 4 != 0 && info.corners[1] % 4 != 0);
        assert_int_equal(info.corners[0] + info.corners[1], D.k + 4);
        assert_true(info.start_side < D.k && info.end_side < D.k);
        assert_true(info.length >= 1);
        /* the seam's ends are flat points of Q, not corners */
        assert_int_equal(D.quads.v_nface[info.seam_start], 2);
        assert_int_equal(D.quads.v_nface[info.seam_end], 2);
        for (uint32_t i = 0; i < D.k; i++) assert_true(D.corner_vert[i] != info.seam_start);
        for (uint32_t i = 0; i < D.k + 2; i++) assert_true(D.padding[i] >= 0);
        assert_int_equal(D.refine, 1);
        assert_int_equal(D.quads_unpadded + D.quads_added, D.quads.nf);
        T->built++;
        T->needed_built += !alone;
        T->quads0 += D.quads_unpadded;
        T->added += D.quads_added;
        int64_t s = info.shift < 0 ? -info.shift : info.shift;
        if (s > T->max_shift) T->max_shift = s;
    } else {
        T->infeasible++;
    }
    sq_domain_free(&D);
    if (alone_out) *alone_out = alone;
    return st;
}

static void print_tally(const char *what, const tally *T)
{
    print_message("%s: %u cases, slide built and verified %u, infeasible %u; padding alone "
                  "works in %u, fails in %u (of which the slide rescued %u); per case: %.1f "
                  "straight sequences, %.1f valid, %.1f feasible (sequence, offset); mean "
                  "quads %.0f + %.0f; max |t| %lld; slide search %.3f s mean, %.3f s worst\n",
                  what, T->cases, T->built, T->infeasible, T->alone, T->needed, T->needed_built,
                  T->cases ? (double)T->seqs / T->cases : 0.0,
                  T->cases ? (double)T->valid / T->cases : 0.0,
                  T->cases ? (double)T->feasible / T->cases : 0.0,
                  T->built ? (double)T->quads0 / T->built : 0.0,
                  T->built ? (double)T->added / T->built : 0.0, (long long)T->max_shift,
                  T->cases ? T->seconds / T->cases : 0.0, T->worst);
}

/* ---- the genus-2 patterns ------------------------------------------------ */

static sq_pattern g2[2][16]; /* [rank 0 / rank 1][index] */
static uint32_t g2n[2];

static void pairings(uint32_t *partner, uint32_t k)
{
    uint32_t i = 0;
    while (i < k && partner[i] != UINT32_MAX) i++;
    if (i == k) {
        sq_pattern p;
        sq_pattern_init(&p);
        assert_int_equal(sq_pattern_alloc(&p, k, NULL), SQ_OK);
        memcpy(p.partner, partner, k * sizeof *partner);
        sq_pattern_info info;
        if (sq_pattern_validate(&p, &info, NULL) == SQ_OK && info.rank < 2) {
            assert_true(g2n[info.rank] < 16);
            g2[info.rank][g2n[info.rank]++] = p;
        } else {
            sq_pattern_free(&p);
        }
        return;
    }
    for (uint32_t j = i + 1; j < k; j++) {
        if (partner[j] != UINT32_MAX) continue;
        partner[i] = j, partner[j] = i;
        pairings(partner, k);
        partner[i] = partner[j] = UINT32_MAX;
    }
}

static int setup_g2(void **state)
{
    (void)state;
    uint32_t partner[12];
    for (uint32_t i = 0; i < 12; i++) partner[i] = UINT32_MAX;
    g2n[0] = g2n[1] = 0;
    pairings(partner, 12);
    return 0;
}

static int teardown_g2(void **state)
{
    (void)state;
    for (uint32_t r = 0; r < 2; r++)
        for (uint32_t i = 0; i < g2n[r]; i++) sq_pattern_free(&g2[r][i]);
    return 0;
}

static void test_genus2_census(void **state)
{
    (void)state;
    /* docs/padding.md: 9 of rank 0 and 6 of rank 1 among the 45 */
    assert_int_equal(g2n[0], 9);
    assert_int_equal(g2n[1], 6);
}

static void test_genus2_rank1(void **state)
{
    (void)state;
    rng_state = 20260601;
    tally T;
    memset(&T, 0, sizeof T);
    const uint32_t per = scale(50);
    for (uint32_t p = 0; p < g2n[1]; p++) {
        for (uint32_t c = 0; c < per; c++) {
            int32_t v[256];
            uint32_t n = random_cones(2, v, 256);
            sq_error err;
            int alone;
            /* the slide is only needed (and called by sq_domain_build) when
             * padding alone fails; then it must succeed */
            if (run_case(2, &g2[1][p], v, n, &T, &alone, &err) != SQ_OK && !alone)
                fail_msg("rank-1 genus-2 pattern %u, case %u (%u cones): %s", p, c, n, err.msg);
        }
    }
    print_tally("genus 2, rank 1", &T);
    assert_int_equal(T.needed_built, T.needed);
    assert_true(T.needed > 0);
}

static void test_genus2_rank0(void **state)
{
    (void)state;
    rng_state = 99;
    tally T;
    memset(&T, 0, sizeof T);
    const uint32_t per = scale(10);
    for (uint32_t p = 0; p < g2n[0]; p++) {
        for (uint32_t c = 0; c < per; c++) {
            int32_t v[256];
            uint32_t n = random_cones(2, v, 256);
            sq_error err;
            sq_status st = run_case(2, &g2[0][p], v, n, &T, NULL, &err);
            if (st != SQ_OK) {
                /* a clear message naming the reason, not a crash */
                assert_int_equal(st, SQ_ERR_ARGUMENT);
                assert_non_null(strstr(err.msg, "rank 0"));
                assert_non_null(strstr(err.msg, "translation"));
            }
        }
    }
    print_tally("genus 2, rank 0", &T);
    assert_true(T.infeasible > 0);
}

/* All cones of valence 8 (multiples of 4): every straight sequence leaves
 * each piece cones of excess 0 mod 4, so no slide is valid (seed 6.4: "no
 * split is necessary"); the closure vector is then zero and padding alone
 * equalizes every pattern (seamless-notes 7), which the lead's path does. */
static void test_genus2_valence8(void **state)
{
    (void)state;
    const int32_t v[2] = {8, 8};
    tally T;
    memset(&T, 0, sizeof T);
    for (uint32_t r = 0; r < 2; r++)
        for (uint32_t p = 0; p < g2n[r]; p++) {
            sq_error err;
            int alone;
            sq_status st = run_case(2, &g2[r][p], v, 2, &T, &alone, &err);
            assert_int_equal(st, SQ_ERR_ARGUMENT);
            assert_true(alone);
        }
    print_tally("genus 2, {8, 8}, rank 0 and 1", &T);
    assert_int_equal(T.valid, 0);
}

/* ---- higher genus ---------------------------------------------------------- */

/* sq_pattern_random never yields rank 1 (its handle insertions start from
 * the torus: 0 of 100000 at each genus 2..6, only ranks 0 and 2), so
 * rank-1 patterns of genus g are grown from the 6 rank-1 genus-2 ones by
 * g - 2 random handle insertions (sq_pattern_insert_handle), keeping rank 1
 * (half of the children of a rank-1 pattern have rank 1), then a random
 * cyclic relabelling. */
static void random_rank1(uint32_t genus, sq_pattern *out)
{
    sq_pattern cur;
    sq_pattern_init(&cur);
    assert_int_equal(sq_pattern_copy(&cur, &g2[1][rnd(g2n[1])], NULL), SQ_OK);
    for (uint32_t g = 2; g < genus;) {
        sq_pattern q;
        sq_pattern_init(&q);
        assert_int_equal(sq_pattern_insert_handle(&cur, rnd(cur.k), rnd(SQ_PATTERN_HANDLE_RULES),
                                                  &q, NULL),
                         SQ_OK);
        if (sq_pattern_rank(&q) != 1) {
            sq_pattern_free(&q);
            continue;
        }
        sq_pattern_free(&cur);
        cur = q;
        g++;
    }
    const uint32_t k = cur.k, r = rnd(k);
    assert_int_equal(sq_pattern_alloc(out, k, NULL), SQ_OK);
    for (uint32_t i = 0; i < k; i++) out->partner[i] = (cur.partner[(i + r) % k] + k - r) % k;
    sq_pattern_free(&cur);
    sq_pattern_info info;
    assert_int_equal(sq_pattern_validate(out, &info, NULL), SQ_OK);
    assert_int_equal(info.genus, genus);
    assert_int_equal(info.rank, 1);
}

static void test_rank1_genus3_to_6(void **state)
{
    (void)state;
    rng_state = 4242;
    for (uint32_t g = 3; g <= 6; g++) {
        tally T;
        memset(&T, 0, sizeof T);
        const uint32_t cases = scale(g <= 4 ? 20 : 8);
        for (uint32_t c = 0; c < cases; c++) {
            sq_pattern pat;
            sq_pattern_init(&pat);
            random_rank1(g, &pat);
            int32_t v[512];
            uint32_t n = random_cones(g, v, 512);
            sq_error err;
            int alone;
            if (run_case(g, &pat, v, n, &T, &alone, &err) != SQ_OK && !alone)
                fail_msg("rank-1 genus-%u pattern, case %u (%u cones): %s", g, c, n, err.msg);
            sq_pattern_free(&pat);
        }
        char what[32];
        snprintf(what, sizeof what, "genus %u, rank 1", g);
        print_tally(what, &T);
        assert_int_equal(T.needed_built, T.needed);
    }
}

/* Arguments: a wrong state is an error, not a crash. */
static void test_bad_arguments(void **state)
{
    (void)state;
    sq_domain D;
    sq_domain_init(&D);
    uint32_t cv[4] = {0}, len[4] = {0};
    sq_error err;
    assert_int_equal(sq_domain_slide_build(&D, cv, len, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    sq_domain_free(&D);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_genus2_census),
        cmocka_unit_test(test_genus2_rank1),
        cmocka_unit_test(test_genus2_rank0),
        cmocka_unit_test(test_genus2_valence8),
        cmocka_unit_test(test_rank1_genus3_to_6),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, setup_g2, teardown_g2);
}
