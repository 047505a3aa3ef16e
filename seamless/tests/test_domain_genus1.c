/* Tests of the genus-1 (torus) domain: two pieces, a meta-6-gon and a
 * meta-2-gon (seed 6.2, 6.3; docs/domain.md, "Genus 1").
 *
 * 1. The configuration itself: exhaustive enumeration of the two-piece side
 *    pairings (which piece sizes admit a torus with two regular branch
 *    points at all), and the padding feasibility of the chosen one, by the
 *    exact solver, over random side lengths and over the real pieces of
 *    random cone multisets with random splits (seamless-notes 7 asks for
 *    this before a configuration is built).
 * 2. sq_domain_build + sq_domain_verify on fixed sets (the cone multisets of
 *    the shared genus-1 meshes) and on random admissible multisets (300 in
 *    CI, 100x with SQ_LONG_TESTS=1), plus extra structural checks of Q.
 * 3. The Jucovic-Trenkler exception {3, 5} and argument errors. */
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
#include "sq_domain_genus1.h"
#include "sq_domain_internal.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_padding.h"
#include "sq_pattern.h"
#include "sq_valence_order.h"

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

/* A random torus multiset (total excess 0): valences 2..8, sometimes 22,
 * never exactly {3, 5}. */
static uint32_t random_torus_cones(int32_t *v, uint32_t cap)
{
    for (;;) {
        uint32_t n = 0;
        int64_t excess = 0;
        uint32_t start = 1 + rnd(rnd(4) == 0 ? 40 : 8); /* cones placed freely */
        while (n < start && n + 1 < cap) {
            int32_t k = rnd(30) == 0 ? 22 : 2 + (int32_t)rnd(7);
            if (k == 4) continue;
            v[n++] = k;
            excess += k - 4;
        }
        while (excess != 0 && n < cap) { /* then close up */
            int32_t k;
            if (excess < 0)
                k = 4 + (int32_t)(-excess >= 4 ? 1 + rnd(4) : 1 + rnd((uint32_t)-excess));
            else k = excess >= 2 && rnd(2) ? 2 : 3;
            v[n++] = k;
            excess += k - 4;
        }
        if (excess != 0 || n < 2) continue;
        if (n == 2 && v[0] + v[1] == 8 && (v[0] == 3 || v[0] == 5)) continue; /* {3, 5} */
        return n;
    }
}

/* ---- 1. the configuration -------------------------------------------------- */

static uint32_t class_count(uint32_t np, const uint32_t *k, const uint32_t *partner)
{
    uint32_t parent[SQ_G1_MAX_SIDES], next[SQ_G1_MAX_SIDES], n = 0;
    for (uint32_t p = 0; p < np; p++)
        for (uint32_t s = 0; s < k[p]; s++, n++) next[n] = n - s + (s + 1) % k[p];
    for (uint32_t i = 0; i < n; i++) parent[i] = i;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a[2] = {i, next[i]}, b[2] = {next[partner[i]], partner[i]};
        for (int t = 0; t < 2; t++) {
            uint32_t x = a[t], y = b[t];
            while (parent[x] != x) x = parent[x];
            while (parent[y] != y) y = parent[y];
            if (x != y) parent[x] = y;
        }
    }
    uint32_t c = 0;
    for (uint32_t i = 0; i < n; i++) c += parent[i] == i;
    return c;
}

static void test_pattern_enumeration(void **state)
{
    (void)state;
    uint32_t out[105 * 8], glue[105];
    /* one piece of 4 sides: only the torus a b a^-1 b^-1 */
    uint32_t k4[1] = {4};
    assert_int_equal(sq_g1_patterns(1, k4, 105, out, NULL), 1);
    sq_pattern torus;
    sq_pattern_init(&torus);
    assert_int_equal(sq_pattern_torus(&torus, NULL), SQ_OK);
    assert_memory_equal(out, torus.partner, 4 * sizeof(uint32_t));
    sq_pattern_free(&torus);

    /* two pieces, 8 sides: (6, 2) has 6 patterns, every one with a pair
     * joining the pieces whose ends lie in different classes; (5, 3) and
     * (3, 5) have none (Jucovic-Trenkler: excess +-1 splits cannot work);
     * (7, 1) has some, but no usable glue pair; (4, 4) would need two
     * meta-4-gons, each with padding invariants. */
    struct {
        uint32_t k[2], total;
        int usable;
    } cases[] = {{{6, 2}, 6, 1}, {{2, 6}, 6, 1}, {{5, 3}, 0, 0}, {{3, 5}, 0, 0}, {{7, 1}, 7, 0}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        uint32_t n = sq_g1_patterns(2, cases[c].k, 105, out, glue);
        print_message("pieces (%u, %u): %u of 105 pairings close into a torus with two regular "
                      "branch points\n",
                      cases[c].k[0], cases[c].k[1], n);
        assert_int_equal(n, cases[c].total);
        for (uint32_t p = 0; p < n; p++) {
            const uint32_t *q = out + 8 * p;
            assert_int_equal(class_count(2, cases[c].k, q), 2);
            for (uint32_t i = 0; i < 8; i++) {
                assert_true(q[i] < 8 && q[i] != i);
                assert_int_equal(q[q[i]], i);
            }
            if (cases[c].usable) {
                assert_true(glue[p] < cases[c].k[0]);
                assert_true(q[glue[p]] >= cases[c].k[0]);
            } else {
                assert_int_equal(glue[p], UINT32_MAX);
            }
            if (cases[c].k[0] == 6) { /* H's other sides pair with their opposites */
                uint32_t opposite = 0;
                for (uint32_t i = 0; i < 6; i++) opposite += q[i] < 6 && q[i] == (i + 3) % 6;
                assert_int_equal(opposite, 4);
            }
        }
    }
    uint32_t k44[2] = {4, 4};
    print_message("pieces (4, 4): %u patterns (not used: meta-4-gons keep closure vectors)\n",
                  sq_g1_patterns(2, k44, 105, NULL, NULL));
}

/* Exact padding solve of (6, 2) pattern p for side lengths Lh, Lt. */
static int solve62(const uint32_t *partner, const int64_t *Lh, const int64_t *Lt, uint64_t *d,
                   int64_t *w, uint64_t *added)
{
    sq_pad_system S;
    sq_pad_system_init(&S);
    assert_int_equal(sq_pad_system_add_piece(&S, 6, Lh, NULL, NULL), SQ_OK);
    assert_int_equal(sq_pad_system_add_piece(&S, 2, Lt, NULL, NULL), SQ_OK);
    for (uint32_t i = 0; i < 8; i++) {
        if (partner[i] < i) continue;
        uint32_t side[2] = {i, partner[i]};
        int32_t coef[2] = {1, -1};
        assert_int_equal(sq_pad_system_add_constraint(&S, 2, side, coef, NULL), SQ_OK);
    }
    sq_pad_result res;
    memset(&res, 0, sizeof res);
    res.w = w;
    int64_t fl[8];
    res.final_length = fl;
    int ok = sq_pad_solve(&S, NULL, &res, NULL) == SQ_OK && res.outcome == SQ_PAD_SOLVED;
    if (ok) {
        *d = res.d;
        *added = res.added_quads;
        for (uint32_t i = 0; i < 8; i++) {
            assert_true(w[i] >= 0);
            assert_int_equal(fl[i], fl[partner[i]]);
        }
    }
    sq_pad_system_free(&S);
    return ok;
}

static void test_configuration_random_lengths(void **state)
{
    (void)state;
    rng_state = 11;
    static const uint32_t K[2] = {6, 2};
    uint32_t pat[6 * 8];
    assert_int_equal(sq_g1_patterns(2, K, 6, pat, NULL), 6);
    const uint32_t trials = long_mode() ? 20000 : SANITIZED ? 100 : 1000;
    uint32_t solved = 0, integral = 0, tried = 0;
    for (uint32_t t = 0; t < trials; t++) {
        int64_t Lh[6], Lt[2];
        /* subdivided metapolygons have even side lengths */
        for (int i = 0; i < 6; i++) Lh[i] = 2 + 2 * (int64_t)rnd(t % 3 ? 6 : 40);
        for (int i = 0; i < 2; i++) Lt[i] = 2 + 2 * (int64_t)rnd(t % 3 ? 6 : 40);
        for (uint32_t p = 0; p < 6; p++) {
            uint64_t d = 0, added = 0;
            int64_t w[8];
            tried++;
            if (solve62(pat + 8 * p, Lh, Lt, &d, w, &added)) {
                solved++;
                integral += d == 1;
            }
        }
    }
    print_message("random even side lengths: %u of %u (meta-6-gon, meta-2-gon, pattern) "
                  "systems feasible, %u without refinement\n",
                  solved, tried, integral);
    assert_int_equal(solved, tried);
    assert_int_equal(integral, tried);
}

/* The real pieces of random cone multisets, split at random into a group
 * of excess -2 and one of +2: every (split, pattern) must be feasible. */
static void test_configuration_random_cones(void **state)
{
    (void)state;
    rng_state = 12;
    static const uint32_t K[2] = {6, 2};
    uint32_t pat[6 * 8];
    assert_int_equal(sq_g1_patterns(2, K, 6, pat, NULL), 6);
    const uint32_t sets = long_mode() ? 20000 : SANITIZED ? 30 : 400;
    uint32_t tried = 0, solved = 0, with_split = 0;
    for (uint32_t s = 0; s < sets; s++) {
        int32_t v[256];
        uint32_t n = random_torus_cones(v, 256), perm[256];
        /* random subset of excess -2: shuffle, take a prefix landing on -2 */
        int found = 0;
        for (uint32_t attempt = 0; attempt <= 20 && !found; attempt++) {
            for (uint32_t i = 0; i < n; i++) perm[i] = i;
            for (uint32_t i = n; i > 1; i--) {
                uint32_t j = rnd(i), x = perm[i - 1];
                perm[i - 1] = perm[j], perm[j] = x;
            }
            if (attempt == 20) { /* last resort: a 2 first, else two 3s */
                int32_t want = 3;
                uint32_t front = 0, need = 2;
                for (uint32_t i = 0; i < n; i++)
                    if (v[i] == 2) want = 2, need = 1;
                for (uint32_t i = 0; i < n; i++) perm[i] = i;
                for (uint32_t i = 0; i < n && front < need; i++)
                    if (v[perm[i]] == want) {
                        uint32_t x = perm[front];
                        perm[front] = perm[i], perm[i] = x, front++;
                    }
            }
            int64_t sum = 0;
            for (uint32_t m = 0; m + 1 < n && !found; m++) {
                sum += v[perm[m]] - 4;
                if (sum != -2) continue;
                found = 1;
                uint32_t grp[2][256], cnt[2] = {0, 0};
                for (uint32_t i = 0; i < n; i++) {
                    int in_t = 0;
                    for (uint32_t j = 0; j <= m; j++) in_t |= perm[j] == i;
                    grp[in_t][cnt[in_t]++] = (uint32_t)v[i];
                }
                sq_mp_quads sub[2];
                int64_t L[2][6];
                for (int p = 0; p < 2; p++) {
                    uint32_t ord[256];
                    sq_metapolygon P;
                    sq_metapolygon_init(&P);
                    memset(&sub[p], 0, sizeof sub[p]);
                    assert_int_equal(sq_valence_order_admissible(grp[p], cnt[p], ord, NULL), SQ_OK);
                    assert_int_equal(sq_metapolygon_build(&P, ord, cnt[p], NULL, NULL, NULL),
                                     SQ_OK);
                    assert_int_equal(sq_metapolygon_subdivide(&P, &sub[p], NULL), SQ_OK);
                    assert_int_equal(sub[p].ncorner, K[p]);
                    for (uint32_t j = 0; j < K[p]; j++) L[p][j] = sub[p].side_len[j];
                    sq_mp_quads_free(&sub[p]);
                    sq_metapolygon_free(&P);
                }
                for (uint32_t p = 0; p < 6; p++) {
                    uint64_t d = 0, added = 0;
                    int64_t w[8];
                    tried++;
                    solved += solve62(pat + 8 * p, L[0], L[1], &d, w, &added) && d == 1;
                }
            }
        }
        assert_true(found); /* every torus set but {3, 5} has such a subset */
        with_split++;
    }
    print_message("random torus cone sets: %u of %u have a split of excess -2/+2; %u of %u "
                  "(split, pattern) padding systems feasible, integral\n",
                  with_split, sets, solved, tried);
    assert_int_equal(solved, tried);
}

/* ---- 2. building -------------------------------------------------------------- */

static uint64_t built_quads, built_count;

static void build_and_check(const int32_t *v, uint32_t n, const char *name)
{
    sq_domain D;
    sq_error err;
    if (sq_domain_build(1, v, n, NULL, &D, &err)) fail_msg("%s (%u cones): %s", name, n, err.msg);
    if (sq_domain_verify(&D, v, n, &err)) fail_msg("%s: verify: %s", name, err.msg);
    uint32_t nirr = 0;
    for (uint32_t i = 0; i < n; i++) nirr += v[i] != 4;
    const sq_metapolygon *Q = &D.quads;
    assert_int_equal(sq_metapolygon_validate(Q, 0, &err), SQ_OK);
    assert_true(sq_domain_glued_is_simple(&D));
    assert_int_equal(D.genus, 1);
    assert_int_equal(D.refine, 1);
    assert_int_equal(D.quads_unpadded + D.quads_added, Q->nf);
    assert_true(D.nf_unpadded <= D.quads_unpadded);
    sq_pattern_info info;
    assert_int_equal(sq_pattern_validate(&D.pattern, &info, &err), SQ_OK);
    assert_int_equal(info.genus, 1);
    assert_int_equal(D.pattern.k, D.k);
    uint32_t nstraight = 0, ncorner = 0;
    for (uint32_t i = 0; i < D.k; i++) nstraight += D.pattern.straight[i];
    for (uint32_t v2 = 0; v2 < Q->nv; v2++) ncorner += Q->v_nface[v2] == 1;
    if (nirr == 0) {
        assert_int_equal(D.k, 4);
        assert_int_equal(nstraight, 0);
        assert_int_equal(Q->nf, 9);
    } else {
        assert_int_equal(D.k, 6);
        assert_int_equal(nstraight, 2);
        assert_int_equal(ncorner, 4);
        /* the two straight corners lie in different classes (two right
         * corners and one straight each) */
        uint32_t cls[6];
        assert_int_equal(sq_pattern_corner_classes(&D.pattern, cls), 2);
        uint32_t a = SQ_NONE, b = SQ_NONE;
        for (uint32_t i = 0; i < 6; i++)
            if (D.pattern.straight[i]) {
                if (a == SQ_NONE) a = cls[i];
                else b = cls[i];
            }
        assert_int_not_equal(a, b);
        /* D.meta: the meta-6-gon, a valid metapolygon; its quads first */
        assert_int_equal(sq_metapolygon_validate(&D.meta, SQ_MP_CHECK_METAPOLYGON, &err), SQ_OK);
        assert_int_equal(sq_metapolygon_count_corners(&D.meta), 6);
        uint64_t meta_quads = 0;
        for (uint32_t f = 0; f < D.meta.nf; f++) meta_quads += D.meta.f_valence[f];
        assert_int_equal(meta_quads, D.nf_unpadded);
        for (uint32_t f = 0; f < D.nf_unpadded; f++) assert_true(D.f_meta_face[f] < D.meta.nf);
        /* the construction order is a permutation of the cones */
        uint32_t cnt[64] = {0}, want[64] = {0};
        for (uint32_t i = 0; i < D.ncones; i++) cnt[D.order[i] < 63 ? D.order[i] : 63]++;
        for (uint32_t i = 0; i < n; i++)
            if (v[i] != 4) want[v[i] < 63 ? v[i] : 63]++;
        assert_memory_equal(cnt, want, sizeof cnt);
    }
    built_quads += Q->nf;
    built_count++;
    sq_domain_free(&D);
}

static void test_fixed_sets(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        uint32_t n[23]; /* n[k] = cones of valence k */
    } sets[] = {
        {"no cones", {0}},
        {"only 4s", {[4] = 3}},
        {"3,3,5,5", {[3] = 2, [5] = 2}},
        {"2,6", {[2] = 1, [6] = 1}},
        {"2,2,6,6", {[2] = 2, [6] = 2}},
        {"3,3,3,3,8", {[3] = 4, [8] = 1}},
        {"22 + 9x2", {[2] = 9, [22] = 1}},
        {"2,2,3,6,7", {[2] = 2, [3] = 1, [6] = 1, [7] = 1}},
        {"7,3,3,3", {[3] = 3, [7] = 1}},
        {"mpz/elk", {[3] = 37, [5] = 23, [6] = 7}},
        {"mpz/knot1", {[3] = 6, [5] = 6}},
        {"mpz/rocker_arm", {[2] = 1, [3] = 16, [5] = 18}},
        {"mpz/trim-star", {[3] = 30, [5] = 22, [6] = 4}},
    };
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
        int32_t v[256];
        uint32_t n = 0;
        for (uint32_t k = 0; k < 23; k++)
            for (uint32_t i = 0; i < sets[s].n[k]; i++) v[n++] = (int32_t)k;
        uint64_t before = built_quads;
        build_and_check(v, n, sets[s].name);
        print_message("%-15s %3u cones: %6llu quads\n", sets[s].name, n,
                      (unsigned long long)(built_quads - before));
    }
}

static void test_random_sets(void **state)
{
    (void)state;
    rng_state = 20260601;
    const uint32_t cases = long_mode() ? 30000 : 300;
    built_quads = built_count = 0;
    char name[64];
    for (uint32_t c = 0; c < cases; c++) {
        int32_t v[256];
        uint32_t n = random_torus_cones(v, 256);
        snprintf(name, sizeof name, "random case %u", c);
        build_and_check(v, n, name);
    }
    print_message("%u random torus cone sets built and verified, mean %.1f quads\n", cases,
                  (double)built_quads / (double)built_count);
}

/* ---- 3. errors -------------------------------------------------------------------- */

static void test_errors(void **state)
{
    (void)state;
    sq_domain D;
    sq_error err;
    int32_t t35[] = {3, 5};
    assert_int_equal(sq_domain_build(1, t35, 2, NULL, &D, &err), SQ_ERR_UNREALIZABLE);
    assert_non_null(strstr(err.msg, "Jucovic"));
    /* the builder itself also finds no split for {3, 5} */
    uint32_t irr[] = {3, 5};
    sq_domain_init(&D);
    D.genus = 1;
    D.ncones = 2;
    D.order = calloc(3, sizeof *D.order);
    assert_non_null(D.order);
    assert_int_equal(sq_domain_build_genus1(irr, 2, NULL, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "excess -2"));
    sq_domain_free(&D);
    /* a pattern is refused when there are cones; a bad offset too */
    sq_pattern torus;
    sq_pattern_init(&torus);
    assert_int_equal(sq_pattern_torus(&torus, NULL), SQ_OK);
    sq_domain_options opt = {&torus, SQ_NONE, NULL, 0, 0};
    int32_t v[] = {2, 6};
    assert_int_equal(sq_domain_build(1, v, 2, &opt, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "two pieces"));
    /* without cones the torus pattern is accepted */
    assert_int_equal(sq_domain_build(1, NULL, 0, &opt, &D, &err), SQ_OK);
    assert_int_equal(sq_domain_verify(&D, NULL, 0, &err), SQ_OK);
    sq_domain_free(&D);
    sq_pattern_free(&torus);
    sq_domain_options bad = {NULL, 6, NULL, 0, 0};
    assert_int_equal(sq_domain_build(1, v, 2, &bad, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "offset"));
    /* every fixed offset (pattern) works on its own */
    for (uint32_t o = 0; o < 6; o++) {
        sq_domain_options fix = {NULL, o, NULL, 0, 0};
        int32_t w[] = {3, 3, 5, 5, 2, 6};
        if (sq_domain_build(1, w, 6, &fix, &D, &err)) fail_msg("offset %u: %s", o, err.msg);
        assert_int_equal(D.offset, o);
        if (sq_domain_verify(&D, w, 6, &err)) fail_msg("offset %u: verify: %s", o, err.msg);
        sq_domain_free(&D);
    }
}

/* Seed 9.2 for the two pieces (sq_domain_options.g1_split with
 * keep_order, as guided `param` builds them): the caller's split and
 * orders are kept, H's irregular faces follow its order, T's cones are the
 * cones of Q outside H's subdivision, every pairing works; a split of the
 * wrong excess or size is refused. */
static void test_given_split(void **state)
{
    (void)state;
    sq_error err;
    const uint32_t cases = SANITIZED ? 60 : 300;
    uint32_t built = 0;
    for (uint32_t c = 0; c < cases; c++) {
        int32_t v[128], w[128];
        uint32_t n = random_torus_cones(v, 128), nh = 0, nt = 0;
        /* T: a valence-2 cone, else two valence-3 cones (as param picks) */
        uint32_t t2 = SQ_NONE, t3a = SQ_NONE, t3b = SQ_NONE;
        for (uint32_t i = 0; i < n; i++) {
            if (v[i] == 2 && t2 == SQ_NONE) t2 = i;
            if (v[i] == 3) {
                if (t3a == SQ_NONE) t3a = i;
                else if (t3b == SQ_NONE) t3b = i;
            }
        }
        uint32_t hv[128];
        for (uint32_t i = 0; i < n; i++) {
            int in_t = t2 != SQ_NONE ? i == t2 : (i == t3a || i == t3b);
            if (!in_t) hv[nh++] = (uint32_t)v[i];
        }
        nt = n - nh;
        if (nt == 0 || nh == 0) continue;
        uint32_t ho[128];
        if (sq_valence_order_admissible(hv, nh, ho, &err)) fail_msg("case %u: %s", c, err.msg);
        for (uint32_t i = 0; i < nh; i++) w[i] = (int32_t)ho[i];
        for (uint32_t i = 0; i < nt; i++) w[nh + i] = t2 != SQ_NONE ? 2 : 3;
        for (uint32_t o = 0; o < 6; o += (c % 3 ? 6 : 1)) {
            sq_domain_options opt = {NULL, c % 3 ? SQ_NONE : o, NULL, 1, nt};
            sq_domain D;
            if (sq_domain_build(1, w, n, &opt, &D, &err)) fail_msg("case %u offset %u: %s", c, o, err.msg);
            if (sq_domain_verify(&D, w, n, &err)) fail_msg("case %u: verify: %s", c, err.msg);
            assert_true(sq_domain_glued_is_simple(&D));
            for (uint32_t i = 0; i < n; i++) assert_int_equal(D.order[i], (uint32_t)w[i]);
            uint32_t j = 0;
            for (uint32_t f = 0; f < D.meta.nf; f++)
                if (D.meta.f_valence[f] != 4) assert_int_equal(D.meta.f_valence[f], (uint32_t)w[j++]);
            assert_int_equal(j, nh);
            /* T's cones: the irregular vertices of Q outside H's quads */
            const sq_metapolygon *Q = &D.quads;
            uint32_t tcount = 0;
            for (uint32_t x = 0; x < Q->nv; x++) {
                uint32_t f = Q->he_face[Q->v_he[x]];
                if (Q->v_nface[x] == 4 || f == SQ_NONE || f < D.nf_unpadded) continue;
                int bnd = 0;
                for (uint32_t h = 0; h < Q->nh; h++) bnd |= Q->he_face[h] == SQ_NONE && Q->he_vert[h] == x;
                if (bnd) continue;
                assert_int_equal(Q->v_nface[x], (uint32_t)w[nh]);
                tcount++;
            }
            assert_int_equal(tcount, nt);
            sq_domain_free(&D);
            built++;
        }
    }
    assert_true(built >= cases / 2);
    /* a given T of excess != -2, or holding every cone, is refused */
    int32_t bad[] = {3, 5, 5, 3, 3, 5};
    sq_domain_options o1 = {NULL, SQ_NONE, NULL, 1, 1};
    sq_domain D;
    assert_int_equal(sq_domain_build(1, bad, 6, &o1, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "excess"));
    sq_domain_options o7 = {NULL, SQ_NONE, NULL, 1, 6};
    assert_int_equal(sq_domain_build(1, bad, 6, &o7, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "split"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pattern_enumeration),
        cmocka_unit_test(test_configuration_random_lengths),
        cmocka_unit_test(test_configuration_random_cones),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_given_split),
        cmocka_unit_test(test_fixed_sets),
        cmocka_unit_test(test_random_sets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
