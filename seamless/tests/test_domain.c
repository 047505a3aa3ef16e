/* Property tests of the combinatorial seamless domain (seed 5-6): random
 * admissible cone multisets per genus; after padding and gluing all
 * identified sides, Q must close into a simple quad mesh of the input genus
 * whose irregular vertices are exactly the cones (sq_domain_verify, which
 * uses the input validator of core/). Bounded in CI; SQ_LONG_TESTS=1 runs
 * 10x more cases. Also: the clear errors for inadmissible cone sets. */
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
#include "sq_pattern.h"

/* Sanitizer builds run about 10x slower: a smaller sample there. */
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static void run_genus(uint32_t genus, uint32_t cases)
{
    int32_t v[4096];
    uint64_t quads0 = 0, added = 0;
    double worst = 0;
    for (uint32_t c = 0; c < cases; c++) {
        uint32_t n = random_cones(genus, v, 4096);
        sq_domain D;
        sq_error err;
        clock_t t0 = clock();
        if (sq_domain_build(genus, v, n, NULL, &D, &err))
            fail_msg("genus %u case %u (%u cones): %s", genus, c, n, err.msg);
        if (sq_domain_verify(&D, v, n, &err))
            fail_msg("genus %u case %u: verify: %s", genus, c, err.msg);
        double t = (double)(clock() - t0) / CLOCKS_PER_SEC;
        if (t > worst) worst = t;
        assert_int_equal(D.k, 8 * genus - 4);
        assert_int_equal(D.refine, 1);
        quads0 += D.quads_unpadded;
        added += D.quads_added;
        sq_domain_free(&D);
    }
    print_message("genus %2u: %4u cases, mean quads %llu + %llu padding, worst %.3f s\n", genus,
                  cases, (unsigned long long)(quads0 / cases), (unsigned long long)(added / cases),
                  worst);
}

static void test_genus_2_to_10(void **state)
{
    (void)state;
    rng_state = 20260522;
    for (uint32_t g = 2; g <= 10; g++) run_genus(g, long_mode() ? 1000 : SANITIZED ? 15 : 100);
}

static void test_genus_11_to_30(void **state)
{
    (void)state;
    rng_state = 7;
    for (uint32_t g = 11; g <= 30; g++) {
        if (SANITIZED && !long_mode() && g % 5) continue;
        run_genus(g, long_mode() ? 100 : SANITIZED ? 1 : 4);
    }
}

static void test_shared_cone_sets(void **state)
{
    (void)state;
    /* the cone multisets of the Table-1 models in ../shared/data */
    static const struct {
        const char *name;
        uint32_t genus;
        uint32_t n[23]; /* n[k] = cones of valence k */
    } sets[] = {
        {"helmet", 3, {[3] = 6, [5] = 1, [7] = 1, [22] = 1}},
        {"genus3", 3, {[3] = 3, [5] = 19}},
        {"holes3", 3, {[3] = 4, [5] = 20}},
        {"block", 3, {[3] = 15, [5] = 31}},
        {"fertility", 4, {[3] = 18, [5] = 42}},
        {"elephant", 3, {[3] = 54, [5] = 59, [6] = 4, [7] = 1}},
        {"cup", 2, {[5] = 6, [6] = 1}},
        {"eight", 2, {[5] = 8}},
        {"femur", 2, {[3] = 17, [5] = 11, [6] = 5, [8] = 1}},
        {"sculpt", 2, {[3] = 11, [5] = 19}},
    };
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
        int32_t v[512];
        uint32_t n = 0;
        for (uint32_t k = 0; k < 23; k++)
            for (uint32_t i = 0; i < sets[s].n[k]; i++) v[n++] = (int32_t)k;
        sq_domain D;
        sq_error err;
        if (sq_domain_build(sets[s].genus, v, n, NULL, &D, &err))
            fail_msg("%s: %s", sets[s].name, err.msg);
        if (sq_domain_verify(&D, v, n, &err)) fail_msg("%s: verify: %s", sets[s].name, err.msg);
        print_message("%-10s genus %u, %3u cones: %5llu + %5llu quads (%.1f ms)\n", sets[s].name,
                      sets[s].genus, n, (unsigned long long)D.quads_unpadded,
                      (unsigned long long)D.quads_added, 1e3 * D.seconds);
        sq_domain_free(&D);
    }
}

/* The pattern is an input (the surface stage computes it from its cut
 * graph): random valid patterns that pass the rank test must work too. */
static void test_random_patterns(void **state)
{
    (void)state;
    rng_state = 99;
    uint64_t pstate = 12345;
    uint32_t built = 0, skipped = 0;
    for (uint32_t g = 2; g <= 8; g++) {
        for (uint32_t c = 0; c < (SANITIZED ? 3u : 20u); c++) {
            sq_pattern pat;
            sq_pattern_init(&pat);
            sq_error err;
            assert_int_equal(sq_pattern_random(g, &pstate, &pat, &err), SQ_OK);
            if (sq_pattern_rank(&pat) < 2) {
                skipped++; /* needs a slide (seed 6.4) */
                sq_pattern_free(&pat);
                continue;
            }
            int32_t v[1024];
            uint32_t n = random_cones(g, v, 1024);
            sq_domain_options opt = {&pat, SQ_NONE, NULL, 0, 0};
            sq_domain D;
            if (sq_domain_build(g, v, n, &opt, &D, &err))
                fail_msg("genus %u random pattern %u: %s", g, c, err.msg);
            if (sq_domain_verify(&D, v, n, &err))
                fail_msg("genus %u random pattern %u: verify: %s", g, c, err.msg);
            for (uint32_t i = 0; i < D.k; i++) assert_int_equal(D.pattern.partner[i], pat.partner[i]);
            built++;
            sq_domain_free(&D);
            sq_pattern_free(&pat);
        }
    }
    print_message("random patterns: %u domains built and verified, %u rank-deficient skipped\n",
                  built, skipped);
    assert_true(built > 0);
}

static void expect_error(uint32_t genus, const int32_t *v, uint32_t n, sq_status code,
                         const char *sub)
{
    sq_domain D;
    sq_error err;
    sq_error_clear(&err);
    sq_status st = sq_domain_build(genus, v, n, NULL, &D, &err);
    if (st != code || !strstr(err.msg, sub))
        fail_msg("expected %s with '%s', got %s: %s", sq_status_name(code), sub,
                 sq_status_name(st), err.msg);
}

static void test_errors(void **state)
{
    (void)state;
    int32_t gb[] = {3, 5, 5};
    expect_error(2, gb, 3, SQ_ERR_GAUSS_BONNET, "Gauss-Bonnet");
    int32_t v1[] = {1, 5, 5, 5, 5, 5, 5, 5, 5, 5};
    expect_error(2, v1, 10, SQ_ERR_UNREALIZABLE, "valence 1");
    int32_t t35[] = {3, 5};
    expect_error(1, t35, 2, SQ_ERR_UNREALIZABLE, "Jucovic");
    /* a pattern of the wrong genus */
    sq_pattern pat;
    sq_pattern_init(&pat);
    sq_error err;
    assert_int_equal(sq_pattern_canonical(3, &pat, &err), SQ_OK);
    sq_domain_options opt = {&pat, SQ_NONE, NULL, 0, 0};
    int32_t g2[] = {6, 6, 6, 6};
    sq_domain D;
    assert_int_equal(sq_domain_build(2, g2, 4, &opt, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "sides"));
    sq_pattern_free(&pat);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_shared_cone_sets),
        cmocka_unit_test(test_random_patterns),
        cmocka_unit_test(test_genus_2_to_10),
        cmocka_unit_test(test_genus_11_to_30),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
