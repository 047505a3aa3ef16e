/* Tests of sq_mcf_solve (the LEMON adapter), with each algorithm:
 * hand-computed optima, infeasible, unbounded and malformed networks, and
 * small random networks against exhaustive enumeration of every integral
 * flow. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "sq_mcf.h"

/* Every test runs with each of the three algorithms. */
static int method = SQ_MCF_NETWORK_SIMPLEX;

/* Two sources (3 and 2 units) and two sinks (4 and 1): with x = flow 0->3,
 * the cost is (3-x) + 4x + 3(1+x) + 2(1-x) = 8 + 4x, so x = 0, cost 8. */
static void test_transport(void **state)
{
    (void)state;
    const uint32_t tail[] = {0, 0, 1, 1}, head[] = {2, 3, 2, 3};
    const int64_t cost[] = {1, 4, 3, 2}, supply[] = {3, 2, -4, -1};
    sq_mcf_problem p = {.method = method, .n_nodes = 4, .n_arcs = 4, .supply = supply, .tail = tail, .head = head, .cost = cost};
    int64_t flow[4], total = -1;
    assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_OPTIMAL);
    assert_int_equal(total, 8);
    assert_int_equal(flow[0], 3);
    assert_int_equal(flow[1], 0);
    assert_int_equal(flow[2], 1);
    assert_int_equal(flow[3], 1);
}

/* A circulation: the negative cycle 0->1->2->0 (costs -2, -1, +1) runs at
 * its capacity 5 (cost -10); the arc 2->3 with lower bound 2 forces 2 units
 * around 2->3->0 (cost 2*7 + 2*0), and 0->1 then still carries only 5. */
static void test_circulation_bounds(void **state)
{
    (void)state;
    const uint32_t tail[] = {0, 1, 2, 2, 3}, head[] = {1, 2, 0, 3, 0};
    const int64_t cost[] = {-2, -1, 1, 7, 0};
    const int64_t lower[] = {0, 0, 0, 2, 0};
    int64_t upper[] = {5, SQ_MCF_INF, SQ_MCF_INF, 4, SQ_MCF_INF};
    sq_mcf_problem p = {.method = method, .n_nodes = 4, .n_arcs = 5, .tail = tail, .head = head, .lower = lower,
                        .upper = upper, .cost = cost};
    int64_t flow[5], total = 0;
    if (method != SQ_MCF_NETWORK_SIMPLEX) {
        /* the scaling methods refuse the uncapacitated arc of cost -1 */
        assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_UNBOUNDED);
        upper[1] = 100;
    }
    assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_OPTIMAL);
    assert_int_equal(flow[0], 5);
    assert_int_equal(flow[1], 5);
    assert_int_equal(flow[3], 2);
    assert_int_equal(flow[4], 2);
    assert_int_equal(flow[2], 3);
    assert_int_equal(total, -10 - 5 + 3 + 14);
}

/* A self-loop of negative cost fills to its capacity; parallel arcs are
 * used cheapest first (a convex cost as a bundle). */
static void test_loop_and_parallel(void **state)
{
    (void)state;
    /* loop at 0 (cost -3, cap 4); 0->1 twice: cost 1 cap 2, cost 5 cap inf;
     * 3 units must go from 0 to 1 */
    const uint32_t tail[] = {0, 0, 0}, head[] = {0, 1, 1};
    const int64_t cost[] = {-3, 1, 5}, upper[] = {4, 2, SQ_MCF_INF}, supply[] = {3, -3};
    sq_mcf_problem p = {.method = method, .n_nodes = 2, .n_arcs = 3, .supply = supply, .tail = tail, .head = head,
                        .upper = upper, .cost = cost};
    int64_t flow[3], total = 0;
    assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_OPTIMAL);
    assert_int_equal(flow[0], 4);
    assert_int_equal(flow[1], 2);
    assert_int_equal(flow[2], 1);
    assert_int_equal(total, -12 + 2 + 5);
}

static void test_infeasible(void **state)
{
    (void)state;
    /* 5 units through an arc of capacity 3 */
    const uint32_t tail[] = {0}, head[] = {1};
    const int64_t cost[] = {1}, upper[] = {3}, supply[] = {5, -5};
    sq_mcf_problem p = {.method = method, .n_nodes = 2, .n_arcs = 1, .supply = supply, .tail = tail, .head = head,
                        .upper = upper, .cost = cost};
    int64_t flow[1] = {-7}, total = -7;
    assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_INFEASIBLE);
    assert_int_equal(flow[0], -7);
    assert_int_equal(total, -7);
    /* a lower bound that cannot be returned: 0->1 at least 1, no way back */
    const int64_t lower[] = {1};
    sq_mcf_problem q = {.method = method, .n_nodes = 2, .n_arcs = 1, .tail = tail, .head = head, .lower = lower, .cost = cost};
    assert_int_equal(sq_mcf_solve(&q, flow, NULL), SQ_MCF_INFEASIBLE);
}

static void test_unbounded(void **state)
{
    (void)state;
    /* the cycle 0->1->0 costs -1 per unit and has no capacity limit */
    const uint32_t tail[] = {0, 1}, head[] = {1, 0};
    const int64_t cost[] = {2, -3};
    sq_mcf_problem p = {.method = method, .n_nodes = 2, .n_arcs = 2, .tail = tail, .head = head, .cost = cost};
    int64_t flow[2];
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_UNBOUNDED);
    /* the same cycle with a capacity is bounded: 6 units, cost -6 (the
     * scaling methods need the bound on the negative arc itself) */
    int64_t upper[] = {6, SQ_MCF_INF};
    if (method != SQ_MCF_NETWORK_SIMPLEX) {
        upper[0] = SQ_MCF_INF;
        upper[1] = 6;
    }
    p.upper = upper;
    int64_t total = 0;
    assert_int_equal(sq_mcf_solve(&p, flow, &total), SQ_MCF_OPTIMAL);
    assert_int_equal(total, -6);
}

static void test_bad_input(void **state)
{
    (void)state;
    const uint32_t tail[] = {0}, head[] = {2};
    const int64_t cost[] = {1};
    int64_t flow[1];
    sq_mcf_problem p = {.method = method, .n_nodes = 2, .n_arcs = 1, .tail = tail, .head = head, .cost = cost};
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_BAD_INPUT);  /* head out of range */
    const uint32_t head1[] = {1};
    p.head = head1;
    const int64_t lower[] = {3}, upper[] = {2};
    p.lower = lower;
    p.upper = upper;
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_BAD_INPUT);  /* lower > upper */
    p.lower = NULL;
    const int64_t supply[] = {1, 0};
    p.supply = supply;
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_BAD_INPUT);  /* supplies sum to 1 */
    assert_int_equal(sq_mcf_solve(NULL, flow, NULL), SQ_MCF_BAD_INPUT);
    p.supply = NULL;
    p.cost = NULL;
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_BAD_INPUT);
    p.cost = cost;
    p.method = 7;
    assert_int_equal(sq_mcf_solve(&p, flow, NULL), SQ_MCF_BAD_INPUT);  /* unknown method */
    /* an empty network is trivially optimal */
    sq_mcf_problem e = {0};
    int64_t total = 9;
    assert_int_equal(sq_mcf_solve(&e, NULL, &total), SQ_MCF_OPTIMAL);
    assert_int_equal(total, 0);
    assert_string_equal(sq_mcf_status_name(SQ_MCF_INFEASIBLE), "infeasible");
}

/* Small random networks (4 nodes, 5 arcs, capacities <= 3, random lower
 * bounds and supplies) against the best of all 4^5 integral flows. */
static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rnd(uint32_t n)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state % n);
}

static void test_random_vs_enumeration(void **state)
{
    (void)state;
    enum { N = 4, A = 5 };
    int optimal = 0, infeasible = 0;
    for (int trial = 0; trial < 400; trial++) {
        uint32_t tail[A], head[A];
        int64_t cost[A], lower[A], upper[A], supply[N] = {0};
        for (int a = 0; a < A; a++) {
            tail[a] = rnd(N);
            head[a] = rnd(N);
            cost[a] = (int64_t)rnd(11) - 5;
            upper[a] = rnd(4);
            lower[a] = rnd(3) == 0 ? rnd((uint32_t)upper[a] + 1) : 0;
        }
        for (int k = 0; k < 2; k++) {  /* move a unit or two of supply around */
            uint32_t s = rnd(N), d = rnd(N), amount = rnd(3);
            supply[s] += amount;
            supply[d] -= amount;
        }
        /* enumeration */
        int64_t best = INT64_MAX;
        for (uint32_t code = 0; code < 1024; code++) {
            int64_t f[A], bal[N] = {0}, c = 0;
            int ok = 1;
            for (int a = 0; a < A; a++) {
                f[a] = (code >> (2 * a)) & 3;
                if (f[a] < lower[a] || f[a] > upper[a]) ok = 0;
                bal[tail[a]] += f[a];
                bal[head[a]] -= f[a];
                c += cost[a] * f[a];
            }
            for (int n = 0; n < N; n++)
                if (bal[n] != supply[n]) ok = 0;
            if (ok && c < best) best = c;
        }
        sq_mcf_problem p = {.method = method, .n_nodes = N, .n_arcs = A, .supply = supply, .tail = tail, .head = head,
                            .lower = lower, .upper = upper, .cost = cost};
        int64_t flow[A], total = 0;
        sq_mcf_status st = sq_mcf_solve(&p, flow, &total);
        if (best == INT64_MAX) {
            assert_int_equal(st, SQ_MCF_INFEASIBLE);
            infeasible++;
            continue;
        }
        assert_int_equal(st, SQ_MCF_OPTIMAL);
        assert_int_equal(total, best);
        int64_t bal[N] = {0}, c = 0;
        for (int a = 0; a < A; a++) {
            assert_true(flow[a] >= lower[a] && flow[a] <= upper[a]);
            bal[tail[a]] += flow[a];
            bal[head[a]] -= flow[a];
            c += cost[a] * flow[a];
        }
        for (int n = 0; n < N; n++) assert_int_equal(bal[n], supply[n]);
        assert_int_equal(c, best);
        optimal++;
    }
    assert_true(optimal > 50 && infeasible > 50);  /* both kinds were exercised */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_transport),
        cmocka_unit_test(test_circulation_bounds),
        cmocka_unit_test(test_loop_and_parallel),
        cmocka_unit_test(test_infeasible),
        cmocka_unit_test(test_unbounded),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_random_vs_enumeration),
    };
    int failed = 0;
    const sq_mcf_method methods[] = {SQ_MCF_NETWORK_SIMPLEX, SQ_MCF_CAPACITY_SCALING, SQ_MCF_COST_SCALING};
    for (int i = 0; i < 3; i++) {
        method = methods[i];
        failed += cmocka_run_group_tests(tests, NULL, NULL);
    }
    return failed;
}
