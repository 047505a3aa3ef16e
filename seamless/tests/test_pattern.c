/* Tests for side-pairing patterns (seamless/domain/sq_pattern.h): corner classes,
 * genus, the 4-corner condition, handle insertion, canonical and random
 * patterns, and the genus-2 census of seamless-notes 7. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_pattern.h"

static uint64_t rng_next(uint64_t *s) /* splitmix64 */
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint32_t long_factor(void)
{
    const char *e = getenv("SQ_LONG_TESTS");
    return (e && e[0] == '1') ? 100u : 1u;
}

static void set_pattern(sq_pattern *p, uint32_t k, const uint32_t *partner)
{
    assert_int_equal(sq_pattern_alloc(p, k, NULL), SQ_OK);
    memcpy(p->partner, partner, k * sizeof *partner);
}

/* Every class of a valid pattern without straight corners has 4 corners,
 * checked independently of the validator. */
static void assert_four_corner_classes(const sq_pattern *p)
{
    uint32_t *cls = malloc(p->k * sizeof *cls), *cnt = calloc(p->k, sizeof *cnt);
    assert_non_null(cls);
    assert_non_null(cnt);
    const uint32_t V = sq_pattern_corner_classes(p, cls);
    for (uint32_t i = 0; i < p->k; ++i) {
        assert_true(cls[i] < V);
        cnt[cls[i]]++;
    }
    for (uint32_t v = 0; v < V; ++v)
        assert_int_equal(cnt[v], 4);
    free(cls);
    free(cnt);
}

static void test_torus(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    sq_error err;
    assert_int_equal(sq_pattern_torus(&p, &err), SQ_OK);
    sq_pattern_info info;
    assert_int_equal(sq_pattern_validate(&p, &info, &err), SQ_OK);
    assert_int_equal(info.classes, 1);
    assert_int_equal(info.genus, 1);
    assert_int_equal(info.rank, 0);
    assert_int_equal(info.translations, 2);
    /* all three fixed-point-free involutions of 4 sides: only a b a^-1 b^-1
     * is a closed surface with one regular branch point */
    static const uint32_t inv[3][4] = {{1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
    uint32_t ok = 0;
    for (int t = 0; t < 3; ++t) {
        set_pattern(&p, 4, inv[t]);
        if (sq_pattern_validate(&p, &info, &err) == SQ_OK) {
            ++ok;
            assert_int_equal(p.partner[0], 2);
        } else {
            /* the other two are spheres: 3 classes of angle 1, 1 and 2 */
            assert_int_equal(err.code, SQ_ERR_ARGUMENT);
            assert_non_null(strstr(err.msg, "total angle"));
        }
    }
    assert_int_equal(ok, 1);
    sq_pattern_free(&p);
}

static void test_invalid(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    sq_error err;
    static const uint32_t fixed[4] = {0, 2, 1, 3};
    set_pattern(&p, 4, fixed);
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "side 0 is paired with itself"));
    static const uint32_t notinv[4] = {1, 2, 3, 0};
    set_pattern(&p, 4, notinv);
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "pairs with"));
    static const uint32_t range[4] = {9, 3, 0, 1};
    set_pattern(&p, 4, range);
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "out of range"));
    assert_int_equal(sq_pattern_alloc(&p, 3, NULL), SQ_OK);
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    /* a genus-2 octagon a b a^-1 b^-1 c d c^-1 d^-1: one branch point of
     * 8 corners (720 degrees): a cone, not a regular point */
    static const uint32_t oct[8] = {2, 3, 0, 1, 6, 7, 4, 5};
    set_pattern(&p, 8, oct);
    sq_pattern_info info;
    assert_int_equal(sq_pattern_validate(&p, &info, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(info.classes, 1);
    assert_non_null(strstr(err.msg, "8 x 90"));
    sq_pattern_free(&p);
}

/* Degree-3 branch points (seamless-notes 1, 7): the torus hexagon
 * a b c a^-1 b^-1 c^-1 has two classes of 3 corners; with one straight
 * corner in each it is valid, without it is not. */
static void test_straight_corners(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    sq_error err;
    static const uint32_t hex[6] = {3, 4, 5, 0, 1, 2};
    set_pattern(&p, 6, hex);
    uint32_t cls[6];
    assert_int_equal(sq_pattern_corner_classes(&p, cls), 2);
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "3 x 90"));
    /* one straight corner per class */
    uint32_t c0 = 0, c1 = 0;
    for (uint32_t i = 0; i < 6; ++i)
        if (cls[i] != cls[0])
            c1 = i;
    p.straight[c0] = 1;
    p.straight[c1] = 1;
    sq_pattern_info info;
    assert_int_equal(sq_pattern_validate(&p, &info, &err), SQ_OK);
    assert_int_equal(info.genus, 1);
    assert_int_equal(info.classes, 2);
    /* directions skip the straight corners */
    uint32_t turns = 0;
    for (uint32_t i = 1; i < 6; ++i)
        turns += !p.straight[i];
    assert_int_equal(sq_pattern_side_direction(&p, 5), turns & 3u);
    /* two straight corners in one class: 2 + 2 + 1 = 5 quarter turns */
    memset(p.straight, 0, 6);
    uint32_t n = 0;
    for (uint32_t i = 0; i < 6 && n < 2; ++i)
        if (cls[i] == cls[0]) {
            p.straight[i] = 1;
            ++n;
        }
    assert_int_equal(sq_pattern_validate(&p, NULL, &err), SQ_ERR_ARGUMENT);
    sq_pattern_free(&p);
}

/* All fixed-point-free involutions of 12 sides (11!! = 10395): the genus-2
 * patterns with three 4-corner branch points, and how many pass the rank
 * test (seamless-notes 7 claims 45 and 30). */
static uint32_t g2_count, g2_rank[3];

static void enumerate(sq_pattern *p, uint32_t *used)
{
    uint32_t a = 0;
    while (a < 12 && used[a])
        ++a;
    if (a == 12) {
        sq_pattern_info info;
        if (sq_pattern_validate(p, &info, NULL) == SQ_OK) {
            assert_int_equal(info.genus, 2);
            assert_int_equal(info.classes, 3);
            assert_four_corner_classes(p);
            ++g2_count;
            g2_rank[info.rank]++;
        } else {
            assert_true(info.classes != 3 || info.rank <= 2);
        }
        return;
    }
    used[a] = 1;
    for (uint32_t b = a + 1; b < 12; ++b) {
        if (used[b])
            continue;
        used[b] = 1;
        p->partner[a] = b;
        p->partner[b] = a;
        enumerate(p, used);
        used[b] = 0;
    }
    used[a] = 0;
}

static void test_genus2_census(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    assert_int_equal(sq_pattern_alloc(&p, 12, NULL), SQ_OK);
    uint32_t used[12] = {0};
    g2_count = 0;
    memset(g2_rank, 0, sizeof g2_rank);
    enumerate(&p, used);
    printf("genus-2 census: %u patterns with three 4-corner branch points; rank 0: %u, "
           "rank 1: %u, rank 2 (padding alone suffices): %u\n",
           g2_count, g2_rank[0], g2_rank[1], g2_rank[2]);
    assert_int_equal(g2_count, 45);
    assert_int_equal(g2_rank[2], 30);
    assert_int_equal(g2_rank[0], 9);
    assert_int_equal(g2_rank[1], 6);
    sq_pattern_free(&p);
}

/* Every handle rule at every side of every genus-2 pattern gives a valid
 * genus-3 pattern with 4-corner classes. */
static void g2_insert_all(sq_pattern *p, uint32_t *used, uint32_t *nvalid)
{
    uint32_t a = 0;
    while (a < 12 && used[a])
        ++a;
    if (a == 12) {
        if (sq_pattern_validate(p, NULL, NULL) != SQ_OK)
            return;
        ++*nvalid;
        sq_pattern q;
        sq_pattern_init(&q);
        for (uint32_t side = 0; side < 12; ++side)
            for (uint32_t rule = 0; rule < SQ_PATTERN_HANDLE_RULES; ++rule) {
                sq_error err;
                assert_int_equal(sq_pattern_insert_handle(p, side, rule, &q, &err), SQ_OK);
                sq_pattern_info info;
                assert_int_equal(sq_pattern_validate(&q, &info, &err), SQ_OK);
                assert_int_equal(info.genus, 3);
                assert_int_equal(q.k, 20);
                assert_four_corner_classes(&q);
            }
        sq_pattern_free(&q);
        return;
    }
    used[a] = 1;
    for (uint32_t b = a + 1; b < 12; ++b) {
        if (used[b])
            continue;
        used[b] = 1;
        p->partner[a] = b;
        p->partner[b] = a;
        g2_insert_all(p, used, nvalid);
        used[b] = 0;
    }
    used[a] = 0;
}

static void test_handle_insertion(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    assert_int_equal(sq_pattern_alloc(&p, 12, NULL), SQ_OK);
    uint32_t used[12] = {0}, nvalid = 0;
    g2_insert_all(&p, used, &nvalid);
    assert_int_equal(nvalid, 45);
    /* bad arguments */
    sq_pattern q;
    sq_pattern_init(&q);
    sq_error err;
    assert_int_equal(sq_pattern_torus(&p, NULL), SQ_OK);
    assert_int_equal(sq_pattern_insert_handle(&p, 4, 0, &q, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_pattern_insert_handle(&p, 0, SQ_PATTERN_HANDLE_RULES, &q, &err),
                     SQ_ERR_ARGUMENT);
    assert_int_equal(sq_pattern_insert_handle(&p, 0, 0, &p, &err), SQ_ERR_ARGUMENT);
    sq_pattern_free(&p);
    sq_pattern_free(&q);
}

static void test_canonical(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    sq_error err;
    for (uint32_t g = 1; g <= 30; ++g) {
        assert_int_equal(sq_pattern_canonical(g, &p, &err), SQ_OK);
        assert_int_equal(p.k, 8 * g - 4);
        sq_pattern_info info;
        assert_int_equal(sq_pattern_validate(&p, &info, &err), SQ_OK);
        assert_int_equal(info.genus, g);
        assert_int_equal(info.classes, 2 * g - 1);
        assert_four_corner_classes(&p);
        if (g >= 2)
            assert_int_equal(sq_pattern_rank(&p), 2);
        else
            assert_int_equal(sq_pattern_rank(&p), 0);
    }
    /* deterministic: the genus-3 pattern (cross-checked with an independent
     * script when the rules were derived) */
    static const uint32_t g3[20] = {18, 3,  16, 1,  14, 8, 9, 13, 5, 6,
                                    12, 19, 10, 7,  4,  17, 2, 15, 0, 11};
    assert_int_equal(sq_pattern_canonical(3, &p, &err), SQ_OK);
    assert_memory_equal(p.partner, g3, sizeof g3);
    assert_int_equal(sq_pattern_canonical(0, &p, &err), SQ_ERR_ARGUMENT);
    sq_pattern_free(&p);
}

static void test_random(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    sq_error err;
    uint64_t base = 0x5eed0001, seed = rng_next(&base);
    const uint32_t reps = 4 * long_factor();
    uint32_t pass[31] = {0}, total[31] = {0};
    for (uint32_t rep = 0; rep < reps; ++rep)
        for (uint32_t g = 1; g <= 30; ++g) {
            assert_int_equal(sq_pattern_random(g, &seed, &p, &err), SQ_OK);
            sq_pattern_info info;
            assert_int_equal(sq_pattern_validate(&p, &info, &err), SQ_OK);
            assert_int_equal(info.genus, g);
            assert_int_equal(p.k, 8 * g - 4);
            assert_four_corner_classes(&p);
            total[g]++;
            pass[g] += info.rank == 2;
        }
    printf("random patterns passing the rank test:");
    for (uint32_t g = 2; g <= 30; g += 4)
        printf(" g=%u %u/%u", g, pass[g], total[g]);
    printf("\n");
    sq_pattern_free(&p);
}

static void test_closure(void **state)
{
    (void)state;
    sq_pattern p;
    sq_pattern_init(&p);
    assert_int_equal(sq_pattern_torus(&p, NULL), SQ_OK);
    const int64_t rect[4] = {3, 5, 3, 5}, skew[4] = {4, 2, 2, 4};
    int64_t x, y;
    sq_pattern_closure(&p, rect, &x, &y);
    assert_true(x == 0 && y == 0);
    sq_pattern_closure(&p, skew, &x, &y);
    assert_true(x == 2 && y == -2);
    sq_pattern_free(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torus),           cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_straight_corners), cmocka_unit_test(test_genus2_census),
        cmocka_unit_test(test_handle_insertion), cmocka_unit_test(test_canonical),
        cmocka_unit_test(test_random),          cmocka_unit_test(test_closure),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
