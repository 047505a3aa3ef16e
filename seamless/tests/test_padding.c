/* Tests for the exact padding solve (seamless/domain/sq_padding.h, seed 6.3):
 * hand examples, explicit quad counts, every canonical pattern of genus
 * 2..30 with random lengths, the rank test of seamless-notes 7 against the
 * solver, brute force on small general systems, and the LP lower bound. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_metapolygon.h"
#include "sq_padding.h"
#include "sq_padding_internal.h"
#include "sq_pattern.h"

static uint64_t rng_next(uint64_t *s) /* splitmix64 */
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint32_t below(uint64_t *s, uint32_t n) { return (uint32_t)(rng_next(s) % n); }

static uint32_t long_factor(void)
{
    const char *e = getenv("SQ_LONG_TESTS");
    return (e && e[0] == '1') ? 100u : 1u;
}

/* ---- independent checks ------------------------------------------------- */

/* Explicit sequential padding of one cyclic piece (seed 6.1): pad side 0,
 * then 1, ..., each time gluing w_s layers on the side's CURRENT length
 * and lengthening its two neighbours; returns the quads glued. */
static uint64_t sequential_quads(uint32_t k, const int64_t *L, uint64_t d, const int64_t *w)
{
    int64_t *cur = malloc(k * sizeof *cur);
    assert_non_null(cur);
    for (uint32_t i = 0; i < k; ++i)
        cur[i] = L[i] * (int64_t)d;
    uint64_t q = 0;
    for (uint32_t s = 0; s < k; ++s) {
        q += (uint64_t)w[s] * (uint64_t)cur[s];
        cur[(s + k - 1) % k] += w[s];
        cur[(s + 1) % k] += w[s];
    }
    free(cur);
    return q;
}

/* w >= 0 and identified sides equal, recomputed from w and L only. */
static void check_pattern_solution(const sq_pattern *p, const int64_t *L, const sq_pad_result *r)
{
    const uint32_t k = p->k;
    for (uint32_t i = 0; i < k; ++i) {
        assert_true(r->w[i] >= 0);
        const int64_t len = L[i] * (int64_t)r->d + r->w[(i + k - 1) % k] + r->w[(i + 1) % k];
        assert_int_equal(len, r->final_length[i]);
    }
    for (uint32_t i = 0; i < k; ++i)
        assert_int_equal(r->final_length[i], r->final_length[p->partner[i]]);
    assert_int_equal(r->added_quads, sequential_quads(k, L, r->d, r->w));
    assert_true(r->added_quads <= r->start_quads);
}

/* Is V in the span of the u_p (seamless-notes 7)? */
static int closure_in_span(const sq_pattern *p, const int64_t *L)
{
    static const int64_t dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
    int64_t vx, vy;
    sq_pattern_closure(p, L, &vx, &vy);
    const uint32_t rank = sq_pattern_rank(p);
    if (rank == 2)
        return 1;
    if (rank == 0)
        return vx == 0 && vy == 0;
    for (uint32_t i = 0; i < p->k; ++i) {
        const uint32_t j = p->partner[i], a = i & 3u, b = j & 3u;
        const int64_t ux = dx[a] + dx[b], uy = dy[a] + dy[b];
        if (ux || uy)
            return ux * vy - uy * vx == 0;
    }
    return 0;
}

/* ---- hand examples ----------------------------------------------------- */

static sq_status solve_sys(const sq_pad_system *S, const sq_pad_options *o, sq_pad_result *r,
                           int64_t *w, int64_t *fl, sq_error *err)
{
    memset(r, 0, sizeof *r);
    r->w = w;
    r->final_length = fl;
    return sq_pad_solve(S, o, r, err);
}

/* A 3 x 5 grid (sides 3, 5, 3, 5) made square: L'_0 = L'_1 needs
 * w1 + w3 - w0 - w2 = 2; the cheapest is one strip of 2 x 5 (10 quads). */
static void test_hand_square(void **state)
{
    (void)state;
    sq_pad_system S;
    sq_pad_system_init(&S);
    const int64_t L[4] = {3, 5, 3, 5};
    assert_int_equal(sq_pad_system_add_piece(&S, 4, L, NULL, NULL), SQ_OK);
    const uint32_t sd[2] = {0, 1};
    const int32_t cf[2] = {1, -1};
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, NULL), SQ_OK);
    sq_pad_result r;
    int64_t w[4], fl[4];
    sq_error err;
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_OK);
    assert_int_equal(r.outcome, SQ_PAD_SOLVED);
    assert_int_equal(r.d, 1);
    assert_int_equal(r.added_quads, 10);
    assert_int_equal(fl[0], fl[1]);
    assert_int_equal(w[1] + w[3] - w[0] - w[2], 2);
    /* forced zero padding on sides 1 and 3 (as on split sides): then
     * -w0 - w2 = 2, no nonnegative solution */
    sq_pad_system_free(&S);
    const uint8_t fz[4] = {0, SQ_PAD_ZERO, 0, SQ_PAD_ZERO};
    assert_int_equal(sq_pad_system_add_piece(&S, 4, L, fz, NULL), SQ_OK);
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, NULL), SQ_OK);
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(r.outcome, SQ_PAD_INFEASIBLE_NONNEGATIVE);
    assert_non_null(strstr(err.msg, "w >= 0"));
    /* ... but L'_1 = L'_0 (the other way round) is fine: pad 0 and 2 */
    sq_pad_system_free(&S);
    const int64_t L2[4] = {5, 3, 5, 3};
    assert_int_equal(sq_pad_system_add_piece(&S, 4, L2, fz, NULL), SQ_OK);
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, NULL), SQ_OK);
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_OK);
    assert_int_equal(r.used_shift, 0);
    assert_int_equal(w[1], 0);
    assert_int_equal(w[3], 0);
    assert_int_equal(w[0] + w[2], 2);
    assert_int_equal(r.added_quads, 10);
    sq_pad_system_free(&S);
}

/* Denominators: sides 0 and 2 unpadded, 2 L'_0 = L'_1 with L = (2, 5, 2, 5)
 * gives w1 + w3 = 1/2, so a 2 x 2 refinement is needed (seed 6.3). */
static void test_hand_refine(void **state)
{
    (void)state;
    sq_pad_system S;
    sq_pad_system_init(&S);
    const int64_t L[4] = {2, 5, 2, 5};
    const uint8_t fz[4] = {SQ_PAD_ZERO, 0, SQ_PAD_ZERO, 0};
    assert_int_equal(sq_pad_system_add_piece(&S, 4, L, fz, NULL), SQ_OK);
    const uint32_t sd[2] = {0, 1};
    const int32_t cf[2] = {2, -1};
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, NULL), SQ_OK);
    sq_pad_result r;
    int64_t w[4], fl[4];
    sq_error err;
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_OK);
    assert_int_equal(r.d, 2);
    assert_int_equal(r.rational_den, 2);
    assert_int_equal(w[1] + w[3], 1);
    assert_int_equal(2 * fl[0], fl[1]);
    assert_int_equal(r.added_quads, 10); /* one strip of 1 x 10 */
    /* the seed's own rule (refine by the basic solution's denominators)
     * agrees here */
    const sq_pad_options o = {SQ_PAD_OPT_NO_INTEGRAL_SEARCH, 0};
    assert_int_equal(solve_sys(&S, &o, &r, w, fl, &err), SQ_OK);
    assert_int_equal(r.d, 2);
    assert_int_equal(2 * fl[0], fl[1]);
    sq_pad_system_free(&S);
}

/* Straight corner: a piece whose first "side" is two collinear parts
 * (corner 1 straight): both parts get the same padding and do not
 * lengthen each other. */
static void test_hand_straight(void **state)
{
    (void)state;
    sq_pad_system S;
    sq_pad_system_init(&S);
    /* rectangle 4 x 3 with its bottom split 2 + 2 */
    const int64_t L[5] = {2, 2, 3, 4, 3};
    const uint8_t fl5[5] = {0, SQ_PAD_STRAIGHT_START, 0, 0, 0};
    assert_int_equal(sq_pad_system_add_piece(&S, 5, L, fl5, NULL), SQ_OK);
    /* make the left side (4) as long as the right side (3) + 2 */
    const uint32_t sd[2] = {2, 4};
    const int32_t cf[2] = {1, -1};
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, NULL), SQ_OK);
    const uint32_t sd2[2] = {0, 2};
    const int32_t cf2[2] = {3, -1}; /* 3 L'_0 = L'_2 */
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd2, cf2, NULL), SQ_OK);
    sq_pad_result r;
    int64_t w[5], fl[5];
    sq_error err;
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_OK);
    assert_int_equal(w[0], w[1]);
    assert_int_equal(fl[0], L[0] * (int64_t)r.d + w[4]);
    assert_int_equal(fl[1], L[1] * (int64_t)r.d + w[2]);
    assert_int_equal(fl[2], fl[4]);
    assert_int_equal(3 * fl[0], fl[2]);
    assert_true(w[3] > 0);
    sq_pad_system_free(&S);
}

static void test_torus(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    assert_int_equal(sq_pattern_torus(&p, NULL), SQ_OK);
    sq_pad_result r;
    int64_t w[4], fl[4];
    memset(&r, 0, sizeof r);
    r.w = w;
    r.final_length = fl;
    sq_error err;
    const int64_t rect[4] = {2, 6, 2, 6};
    assert_int_equal(sq_pad_solve_pattern(&p, rect, NULL, &r, &err), SQ_OK);
    assert_int_equal(r.added_quads, 0);
    /* Jucovic-Trenkler: the torus with one valence-3 and one valence-5 cone
     * has the meta-4-gon E(E(0, 5), 3) with sides (4, 2, 2, 4)
     * (seamless-notes 7): closure (2, -2), not equalizable */
    const int64_t jt[4] = {4, 2, 2, 4};
    assert_int_equal(sq_pad_solve_pattern(&p, jt, NULL, &r, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(r.outcome, SQ_PAD_INFEASIBLE_INVARIANT);
    assert_non_null(strstr(err.msg, "closure vector"));
    assert_non_null(strstr(err.msg, "(2, -2)"));
    /* the general solver names the invariant itself */
    sq_pad_system S;
    sq_pad_system_init(&S);
    assert_int_equal(sq_pad_system_from_pattern(&S, &p, jt, NULL), SQ_OK);
    assert_int_equal(sq_pad_solve(&S, NULL, &r, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "invariant"));
    sq_pad_system_free(&S);
    sq_pattern_free(&p);
}

/* The quad-count formula against explicit constructions on rectangles:
 * the padded rectangle's area, and gluing grids with the metapolygon code
 * (sq_metapolygon_glue_grid, the operation of seed 6.1) and counting faces. */
static uint32_t find_side_start(const sq_metapolygon *P, uint32_t corner_v)
{
    return P->v_he[corner_v];
}

static uint32_t walk(const sq_metapolygon *P, uint32_t v, uint32_t steps)
{
    uint32_t h = P->v_he[v];
    for (uint32_t i = 0; i < steps; ++i)
        h = P->he_next[h];
    return P->he_vert[h];
}

static void test_quads_explicit(void **state)
{
    (void)state;
    uint64_t seed = 0xabc;
    const uint32_t reps = 30 * long_factor();
    sq_pad_system S;
    for (uint32_t rep = 0; rep < reps; ++rep) {
        const int64_t C = 1 + below(&seed, 6), R = 1 + below(&seed, 6);
        int64_t w[4];
        for (int s = 0; s < 4; ++s)
            w[s] = below(&seed, 4);
        /* sides: 0 = cols, 1 = rows, 2 = cols, 3 = rows */
        const int64_t L[4] = {C, R, C, R};
        sq_pad_system_init(&S);
        assert_int_equal(sq_pad_system_add_piece(&S, 4, L, NULL, NULL), SQ_OK);
        uint64_t q;
        assert_int_equal(sq_pad_added_quads(&S, 1, w, &q, NULL), SQ_OK);
        const uint64_t area = (uint64_t)((C + w[1] + w[3]) * (R + w[0] + w[2]) - C * R);
        assert_int_equal(q, area);
        assert_int_equal(q, sequential_quads(4, L, 1, w));
        /* the real thing: a metapolygon grid padded side by side */
        sq_metapolygon P;
        sq_metapolygon_init(&P);
        assert_int_equal(sq_metapolygon_make_grid(&P, (uint32_t)R, (uint32_t)C, NULL), SQ_OK);
        uint32_t n = sq_metapolygon_nonflat(&P, 0, NULL, NULL, NULL);
        assert_int_equal(n, 4);
        uint32_t cv[4], dist[4];
        sq_metapolygon_nonflat(&P, 4, cv, NULL, dist);
        /* number our sides like the grid's: side j from corner j */
        int64_t len[4];
        for (int j = 0; j < 4; ++j)
            len[j] = dist[j];
        int64_t ww[4];
        for (int j = 0; j < 4; ++j) /* map w to the grid's side lengths */
            ww[j] = w[j];
        const uint32_t f0 = P.nf;
        for (uint32_t s = 0; s < 4; ++s) {
            if (ww[s] == 0)
                continue;
            const uint32_t prev = (s + 3) % 4, next = (s + 1) % 4;
            assert_int_equal(sq_metapolygon_glue_grid(&P, find_side_start(&P, cv[s]),
                                                      (uint32_t)ww[s], (uint32_t)len[s], 1, NULL),
                             SQ_OK);
            cv[s] = walk(&P, cv[prev], (uint32_t)(len[prev] + ww[s]));
            cv[next] = walk(&P, cv[s], (uint32_t)len[s]);
            len[prev] += ww[s];
            len[next] += ww[s];
        }
        uint64_t q2;
        assert_int_equal(sq_pad_added_quads(&S, 1, ww, &q2, NULL), SQ_OK);
        const int64_t L0[4] = {(int64_t)dist[0], (int64_t)dist[1], (int64_t)dist[2],
                               (int64_t)dist[3]};
        assert_int_equal(P.nf - f0, sequential_quads(4, L0, 1, ww));
        assert_int_equal(sq_metapolygon_validate(&P, SQ_MP_CHECK_METAPOLYGON, NULL), SQ_OK);
        assert_int_equal(sq_metapolygon_count_corners(&P), 4);
        sq_metapolygon_free(&P);
        sq_pad_system_free(&S);
    }
}

/* Every canonical pattern g = 2..30 with random lengths: even ones (real
 * subdivided metapolygons) and arbitrary ones (parity issues). */
static void test_canonical_random_lengths(void **state)
{
    (void)state;
    uint64_t seed = 0x1234;
    const uint32_t reps = 3 * long_factor();
    sq_pattern p;
    sq_pattern_init(&p);
    uint64_t dhist[2][5] = {{0}}, rhist[2][5] = {{0}}, runs[2] = {0};
    double gain = 0;
    for (uint32_t g = 2; g <= 30; ++g) {
        assert_int_equal(sq_pattern_canonical(g, &p, NULL), SQ_OK);
        const uint32_t k = p.k;
        int64_t *L = malloc(k * sizeof *L), *w = malloc(k * sizeof *w),
                *fl = malloc(k * sizeof *fl);
        for (uint32_t rep = 0; rep < reps; ++rep)
            for (int even = 0; even < 2; ++even) {
                const uint32_t span = rep % 3 == 2 ? 200 : 12;
                for (uint32_t i = 0; i < k; ++i)
                    L[i] = even ? 2 + 2 * (int64_t)below(&seed, span)
                                : 2 + (int64_t)below(&seed, 2 * span);
                sq_pad_result r;
                memset(&r, 0, sizeof r);
                r.w = w;
                r.final_length = fl;
                sq_error err;
                assert_int_equal(sq_pad_solve_pattern(&p, L, NULL, &r, &err), SQ_OK);
                assert_int_equal(r.outcome, SQ_PAD_SOLVED);
                assert_true(r.used_shift);
                assert_int_equal(r.rank, k / 2); /* pairs independent when rank 2 */
                check_pattern_solution(&p, L, &r);
                dhist[even][r.d < 4 ? r.d : 4]++;
                rhist[even][r.rational_den < 4 ? r.rational_den : 4]++;
                runs[even]++;
                if (r.start_quads)
                    gain += (double)r.added_quads / (double)r.start_quads;
            }
        free(L);
        free(w);
        free(fl);
    }
    printf("canonical g=2..30: refinement d (lattice search) for even lengths: d=1 %llu, d=2 "
           "%llu, d=3 %llu, d>3 %llu of %llu; arbitrary lengths: d=1 %llu, d=2 %llu, d=3 %llu, "
           "d>3 %llu of %llu\n",
           (unsigned long long)dhist[1][1], (unsigned long long)dhist[1][2],
           (unsigned long long)dhist[1][3], (unsigned long long)dhist[1][4],
           (unsigned long long)runs[1], (unsigned long long)dhist[0][1],
           (unsigned long long)dhist[0][2], (unsigned long long)dhist[0][3],
           (unsigned long long)dhist[0][4], (unsigned long long)runs[0]);
    printf("  basic rational solution's denominator (seed 6.3's d): even: 1 %llu, 2 %llu, >2 "
           "%llu; arbitrary: 1 %llu, 2 %llu, >2 %llu; descent keeps %.3f of the shifted start\n",
           (unsigned long long)rhist[1][1], (unsigned long long)rhist[1][2],
           (unsigned long long)(rhist[1][3] + rhist[1][4]), (unsigned long long)rhist[0][1],
           (unsigned long long)rhist[0][2], (unsigned long long)(rhist[0][3] + rhist[0][4]),
           gain / (double)(runs[0] + runs[1]));
    assert_int_equal(dhist[1][1], runs[1]); /* even lengths never needed refinement */
    sq_pattern_free(&p);
}

/* The rank test against the exact solver, both directions: feasible iff
 * the closure vector lies in span{u_p} (always, when rank 2). Patterns:
 * all 45 genus-2 ones, and random ones for g = 1..12. */
static uint64_t agree_stats[3][2]; /* [rank][solved] */

static void rank_check(const sq_pattern *p, uint64_t *seed, uint32_t trials)
{
    const uint32_t k = p->k;
    int64_t *L = malloc(k * sizeof *L), *w = malloc(k * sizeof *w), *fl = malloc(k * sizeof *fl);
    const uint32_t rank = sq_pattern_rank(p);
    for (uint32_t t = 0; t < trials; ++t) {
        for (uint32_t i = 0; i < k; ++i)
            L[i] = 2 + (int64_t)below(seed, t % 2 ? 40 : 8);
        sq_pad_result r;
        memset(&r, 0, sizeof r);
        r.w = w;
        r.final_length = fl;
        sq_error err;
        const sq_status st = sq_pad_solve_pattern(p, L, NULL, &r, &err);
        const int expect = closure_in_span(p, L);
        if (expect) {
            assert_int_equal(st, SQ_OK);
            check_pattern_solution(p, L, &r);
        } else {
            assert_int_equal(st, SQ_ERR_ARGUMENT);
            assert_int_equal(r.outcome, SQ_PAD_INFEASIBLE_INVARIANT);
        }
        agree_stats[rank][st == SQ_OK]++;
    }
    free(L);
    free(w);
    free(fl);
}

static void g2_walk(sq_pattern *p, uint32_t *used, uint64_t *seed, uint32_t trials)
{
    uint32_t a = 0;
    while (a < 12 && used[a])
        ++a;
    if (a == 12) {
        if (sq_pattern_validate(p, NULL, NULL) == SQ_OK)
            rank_check(p, seed, trials);
        return;
    }
    used[a] = 1;
    for (uint32_t b = a + 1; b < 12; ++b) {
        if (used[b])
            continue;
        used[b] = 1;
        p->partner[a] = b;
        p->partner[b] = a;
        g2_walk(p, used, seed, trials);
        used[b] = 0;
    }
    used[a] = 0;
}

static void test_rank_agreement(void **state)
{
    (void)state;
    memset(agree_stats, 0, sizeof agree_stats);
    uint64_t seed = 0x77;
    sq_pattern p;
    sq_pattern_init(&p);
    assert_int_equal(sq_pattern_alloc(&p, 12, NULL), SQ_OK);
    uint32_t used[12] = {0};
    g2_walk(&p, used, &seed, 20 * long_factor());
    for (uint32_t rep = 0; rep < 10 * long_factor(); ++rep)
        for (uint32_t g = 1; g <= 12; ++g) {
            assert_int_equal(sq_pattern_random(g, &seed, &p, NULL), SQ_OK);
            rank_check(&p, &seed, 4);
        }
    printf("rank test vs exact solver (random lengths): rank 2: %llu solved, %llu failed; "
           "rank 1: %llu solved (closure on the line), %llu infeasible; rank 0: %llu solved "
           "(closure 0), %llu infeasible\n",
           (unsigned long long)agree_stats[2][1], (unsigned long long)agree_stats[2][0],
           (unsigned long long)agree_stats[1][1], (unsigned long long)agree_stats[1][0],
           (unsigned long long)agree_stats[0][1], (unsigned long long)agree_stats[0][0]);
    assert_int_equal(agree_stats[2][0], 0);
    assert_true(agree_stats[1][0] > 0 && agree_stats[0][0] > 0);
    sq_pattern_free(&p);
}

/* Brute force on small general systems (one or two pieces, random pair
 * constraints, some forced zeros): the solver is feasible iff a
 * nonnegative integral solution exists in the box (or it found one beyond
 * it, or needed a refinement), and its count is never below the box
 * optimum; how often it equals the optimum is reported. */
static void test_brute_force(void **state)
{
    (void)state;
    uint64_t seed = 0xb0b;
    const uint32_t reps = 150 * long_factor();
    uint32_t optimal = 0, compared = 0, infeasible = 0, refined = 0, needless = 0;
    for (uint32_t rep = 0; rep < reps; ++rep) {
        sq_pad_system S;
        sq_pad_system_init(&S);
        const uint32_t pieces = 1 + (rep % 3 == 0);
        int64_t L[8];
        uint8_t F[8];
        uint32_t n = 0;
        for (uint32_t pc = 0; pc < pieces; ++pc) {
            const uint32_t m = pieces == 1 ? 4 + below(&seed, 3) : 4;
            for (uint32_t i = 0; i < m; ++i) {
                L[n + i] = 1 + below(&seed, 6);
                F[n + i] = below(&seed, 6) == 0 ? SQ_PAD_ZERO : 0;
            }
            assert_int_equal(sq_pad_system_add_piece(&S, m, L + n, F + n, NULL), SQ_OK);
            n += m;
        }
        const uint32_t ncon = 1 + below(&seed, 3);
        for (uint32_t c = 0; c < ncon; ++c) {
            uint32_t sd[3] = {below(&seed, n), below(&seed, n), below(&seed, n)};
            int32_t cf[3] = {1, -1, below(&seed, 3) == 0 ? 1 : -1};
            const uint32_t nt = below(&seed, 4) == 0 ? 3 : 2; /* sometimes a sum */
            if (sd[0] == sd[1])
                continue;
            assert_int_equal(sq_pad_system_add_constraint(&S, nt, sd, cf, NULL), SQ_OK);
        }
        if (S.ncon == 0) {
            sq_pad_system_free(&S);
            continue;
        }
        int64_t w[8], fl[8];
        sq_pad_result r;
        sq_error err;
        const sq_status st = solve_sys(&S, NULL, &r, w, fl, &err);
        /* brute force over w in [0, B]^n at refinement 1 */
        const int64_t B = n > 6 ? 3 : 5;
        int64_t x[8] = {0}, best = -1;
        for (;;) {
            int ok = 1;
            for (uint32_t s = 0; s < n && ok; ++s)
                ok = !(F[s] & SQ_PAD_ZERO) || x[s] == 0;
            if (ok) {
                int64_t f[8];
                assert_int_equal(sq_pad_final_lengths(&S, 1, x, f, NULL), SQ_OK);
                for (uint32_t c = 0; c < S.ncon && ok; ++c) {
                    int64_t sum = 0;
                    for (uint32_t t = S.con_first[c]; t < S.con_first[c + 1]; ++t)
                        sum += S.term_coef[t] * f[S.term_side[t]];
                    ok = sum == 0;
                }
                if (ok) {
                    uint64_t q;
                    assert_int_equal(sq_pad_added_quads(&S, 1, x, &q, NULL), SQ_OK);
                    if (best < 0 || (int64_t)q < best)
                        best = (int64_t)q;
                }
            }
            uint32_t s = 0;
            while (s < n && x[s] == B)
                x[s++] = 0;
            if (s == n)
                break;
            x[s]++;
        }
        if (st != SQ_OK) {
            assert_int_equal(st, SQ_ERR_ARGUMENT);
            assert_true(r.outcome != SQ_PAD_SOLVED);
            assert_true(best < 0); /* nothing in the box either */
            ++infeasible;
        } else {
            for (uint32_t c = 0; c < S.ncon; ++c) {
                int64_t sum = 0;
                for (uint32_t t = S.con_first[c]; t < S.con_first[c + 1]; ++t)
                    sum += S.term_coef[t] * fl[S.term_side[t]];
                assert_int_equal(sum, 0);
            }
            for (uint32_t s = 0; s < n; ++s)
                assert_true(w[s] >= 0 && (!(F[s] & SQ_PAD_ZERO) || w[s] == 0));
            if (r.d > 1) {
                ++refined;
                /* the repair descent is a heuristic: a refinement although
                 * an integral point exists is possible, but must be rare */
                needless += best >= 0;
            } else if (best >= 0) {
                int inside = 1;
                for (uint32_t s = 0; s < n; ++s)
                    inside &= w[s] <= B;
                if (inside) /* the box optimum is a true lower bound there */
                    assert_true((int64_t)r.added_quads >= best);
                ++compared;
                optimal += (int64_t)r.added_quads <= best;
            }
        }
        sq_pad_system_free(&S);
    }
    printf("brute force on %u small systems: %u infeasible (agreed), %u refined (%u of them "
           "although an integral point exists), solver optimal in %u of %u compared\n",
           reps, infeasible, refined, needless, optimal, compared);
    assert_true(compared > reps / 4);
    assert_true(needless * 100 <= reps);
}

/* The exact LP lower bound min sum L_s w_s (corner squares dropped) against
 * the solver's count, default and with the LP start, for small genus. */
static void test_lp_bound(void **state)
{
    (void)state;
    uint64_t seed = 0x1f;
    sq_pattern p;
    sq_pattern_init(&p);
    double ratio[2] = {0, 0};
    uint32_t runs = 0, lp_better = 0;
    for (uint32_t g = 2; g <= 5; ++g)
        for (uint32_t rep = 0; rep < 5 * long_factor(); ++rep) {
            if (rep == 0)
                assert_int_equal(sq_pattern_canonical(g, &p, NULL), SQ_OK);
            else {
                do
                    assert_int_equal(sq_pattern_random(g, &seed, &p, NULL), SQ_OK);
                while (sq_pattern_rank(&p) != 2);
            }
            const uint32_t k = p.k;
            int64_t L[36], w[36], fl[36];
            for (uint32_t i = 0; i < k; ++i)
                L[i] = 2 + 2 * (int64_t)below(&seed, 15);
            sq_pad_result r0, r1;
            const sq_pad_options o = {SQ_PAD_OPT_NO_LP_START, 0};
            memset(&r0, 0, sizeof r0);
            r0.w = w;
            r0.final_length = fl;
            assert_int_equal(sq_pad_solve_pattern(&p, L, &o, &r0, NULL), SQ_OK);
            memset(&r1, 0, sizeof r1);
            r1.w = w;
            r1.final_length = fl;
            assert_int_equal(sq_pad_solve_pattern(&p, L, NULL, &r1, NULL), SQ_OK);
            check_pattern_solution(&p, L, &r1);
            assert_true(r1.added_quads <= r0.added_quads);
            lp_better += r1.added_quads < r0.added_quads;
            /* the bound: exact LP through the internal solver */
            sq_pad_system S;
            sq_pad_system_init(&S);
            assert_int_equal(sq_pad_system_from_pattern(&S, &p, L, NULL), SQ_OK);
            const uint32_t m = S.ncon, n = k;
            mpz_t *M = malloc(m * n * sizeof *M), *rhs = malloc(m * sizeof *rhs),
                  *cost = malloc(n * sizeof *cost);
            mpq_t *v = malloc(n * sizeof *v);
            for (uint32_t i = 0; i < m * n; ++i)
                mpz_init(M[i]);
            for (uint32_t i = 0; i < m; ++i) {
                const uint32_t a = S.term_side[2 * i], b = S.term_side[2 * i + 1];
                mpz_add_ui(M[i * n + (a + k - 1) % k], M[i * n + (a + k - 1) % k], 1);
                mpz_add_ui(M[i * n + (a + 1) % k], M[i * n + (a + 1) % k], 1);
                mpz_sub_ui(M[i * n + (b + k - 1) % k], M[i * n + (b + k - 1) % k], 1);
                mpz_sub_ui(M[i * n + (b + 1) % k], M[i * n + (b + 1) % k], 1);
                mpz_init_set_si(rhs[i], (long)(L[b] - L[a]));
            }
            for (uint32_t s = 0; s < n; ++s) {
                mpz_init_set_si(cost[s], (long)L[s]);
                mpq_init(v[s]);
            }
            int feas = 0;
            assert_int_equal(sq_padding_lp(m, n, M, rhs, cost, &feas, v, NULL), SQ_OK);
            assert_true(feas);
            mpq_t obj, t;
            mpq_init(obj);
            mpq_init(t);
            for (uint32_t s = 0; s < n; ++s) {
                mpq_set_z(t, cost[s]);
                mpq_mul(t, t, v[s]);
                mpq_add(obj, obj, t);
            }
            const double bound = mpq_get_d(obj);
            assert_true(r0.d == 1 && r1.d == 1);
            assert_true((double)r1.added_quads >= bound - 1e-9);
            if (bound > 0) {
                ratio[0] += (double)r0.added_quads / bound;
                ratio[1] += (double)r1.added_quads / bound;
            }
            ++runs;
            mpq_clear(obj);
            mpq_clear(t);
            for (uint32_t i = 0; i < m * n; ++i)
                mpz_clear(M[i]);
            for (uint32_t i = 0; i < m; ++i)
                mpz_clear(rhs[i]);
            for (uint32_t s = 0; s < n; ++s) {
                mpz_clear(cost[s]);
                mpq_clear(v[s]);
            }
            free(M);
            free(rhs);
            free(cost);
            free(v);
            sq_pad_system_free(&S);
        }
    printf("quads / LP lower bound (g=2..5, %u runs): shift start only %.3f, default (shift "
           "and LP starts) %.3f; LP start better in %u\n",
           runs, ratio[0] / runs, ratio[1] / runs, lp_better);
    sq_pattern_free(&p);
}

static void test_bad_systems(void **state)
{
    (void)state;
    sq_pad_system S;
    sq_pad_system_init(&S);
    sq_error err;
    const int64_t L1[1] = {3}, Ln[3] = {3, -1, 2};
    assert_int_equal(sq_pad_system_add_piece(&S, 1, L1, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_pad_system_add_piece(&S, 3, Ln, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "negative"));
    const int64_t L[3] = {3, 3, 3};
    assert_int_equal(sq_pad_system_add_piece(&S, 3, L, NULL, &err), SQ_OK);
    const uint32_t sd[2] = {0, 7};
    const int32_t cf[2] = {1, -1}, cz[2] = {1, 0};
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cz, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_pad_system_add_constraint(&S, 2, sd, cf, &err), SQ_OK);
    sq_pad_result r;
    int64_t w[3], fl[3];
    assert_int_equal(solve_sys(&S, NULL, &r, w, fl, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "side 7"));
    sq_pad_system_free(&S);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_square),
        cmocka_unit_test(test_hand_refine),
        cmocka_unit_test(test_hand_straight),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_quads_explicit),
        cmocka_unit_test(test_canonical_random_lengths),
        cmocka_unit_test(test_rank_agreement),
        cmocka_unit_test(test_brute_force),
        cmocka_unit_test(test_lp_bound),
        cmocka_unit_test(test_bad_systems),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
