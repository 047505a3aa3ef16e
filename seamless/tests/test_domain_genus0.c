/* Tests of the genus-0 domain (seed 6.5, seamless/domain/sq_domain_genus0.c):
 * hand cases (cube, four 2s, octahedron-like, the cone multisets of
 * mpz/homer and mpz/fandisk) and random admissible multisets (300 in CI,
 * 100x with SQ_LONG_TESTS=1). Each result must pass sq_domain_verify (the
 * glued mesh is a closed simple sphere whose irregular vertices are exactly
 * the cones), be a disk cut along one edge between two regular vertices,
 * and use no fewer quads than the four meta-2-gons plus the minimal padding
 * predicted here independently from the pieces rebuilt with the public API
 * (and exactly that many in most cases). The quad count is compared with
 * the seed's n x n refinement (and with an lcm variant of it). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_domain.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_valence_order.h"

static uint64_t rng_state = 0x9e0c0de5eedull;

static uint64_t rng(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static uint32_t rnd(uint32_t n) { return (uint32_t)(rng() % n); }

static int long_mode(void)
{
    const char *s = getenv("SQ_LONG_TESTS");
    return s && *s && strcmp(s, "0");
}

/* ---- an independent model of the construction ------------------------- */

/* One group's meta-2-gon, rebuilt with the public API. */
typedef struct piece {
    uint64_t quads, len[2];
} piece;

static uint64_t gcd64(uint64_t a, uint64_t b)
{
    while (b) {
        uint64_t t = a % b;
        a = b, b = t;
    }
    return a;
}

static const int pairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};

/* Splits D->order (the four groups, each an admissible order of excess -2)
 * at the running excess sums -2, -4, -6 and rebuilds the four meta-2-gons. */
static void rebuild_pieces(const sq_domain *D, piece pc[4])
{
    uint32_t start = 0, g = 0;
    int64_t sum = 0;
    for (uint32_t i = 0; i < D->ncones; i++) {
        sum += (int64_t)D->order[i] - 4;
        if (sum != -2 * (int64_t)(g + 1)) continue;
        uint32_t m = i + 1 - start;
        assert_true(g < 4);
        /* each group is itself admissible (seed 5.2) */
        assert_int_equal(sq_valence_check_sequence(D->order + start, m, NULL, NULL), SQ_OK);
        sq_metapolygon P;
        sq_metapolygon_init(&P);
        sq_error err;
        if (sq_metapolygon_build(&P, D->order + start, m, NULL, NULL, &err))
            fail_msg("group %u: %s", g, err.msg);
        sq_mp_quads sub;
        memset(&sub, 0, sizeof sub);
        if (sq_metapolygon_subdivide(&P, &sub, &err)) fail_msg("group %u: %s", g, err.msg);
        assert_int_equal(sub.ncorner, 2); /* a meta-2-gon */
        pc[g].quads = sub.mesh.nf;
        pc[g].len[0] = sub.side_len[0];
        pc[g].len[1] = sub.side_len[1];
        assert_true(pc[g].len[0] % 2 == 0 && pc[g].len[1] % 2 == 0);
        if (g == 0) assert_int_equal(P.nf, D->meta.nf); /* D->meta is group 0 */
        sq_mp_quads_free(&sub);
        sq_metapolygon_free(&P);
        start = i + 1;
        g++;
    }
    assert_int_equal(g, 4);
    assert_int_equal(start, D->ncones);
}

/* Minimal padding over the 3 pairings and 16 side choices: per pair, pad
 * the shorter A side's piece on its B side by half the difference, then
 * the shorter pair's perimeter by half the difference (cost per layer: the
 * pair's A length). Also the seed's refinement: pieces of a pair glued by
 * refining each by the other's A length (m x m, n x n), then the two
 * meta-0-gons refined by each other's perimeter; and the lcm variant
 * (refine by lcm / own length). Doubles: refinement overflows quickly. */
static void model(const piece pc[4], uint64_t *pad_min, double *naive, double *naive_lcm)
{
    *pad_min = UINT64_MAX;
    *naive = *naive_lcm = 1e300;
    for (int id = 0; id < 48; id++) {
        uint64_t A[4], B[4], q[4];
        for (int j = 0; j < 4; j++) {
            const piece *p = &pc[pairings[id / 16][j]];
            int a = (id >> j) & 1;
            A[j] = p->len[a], B[j] = p->len[1 - a], q[j] = p->quads;
        }
        uint64_t added = 0, per[2], la[2];
        double nq[2], nper[2], lq[2], lper[2];
        for (int k = 0; k < 2; k++) {
            int j0 = 2 * k, j1 = 2 * k + 1;
            la[k] = A[j0] > A[j1] ? A[j0] : A[j1];
            added += (la[k] - A[j0]) / 2 * B[j0] + (la[k] - A[j1]) / 2 * B[j1];
            per[k] = B[j0] + B[j1];
            double m = (double)A[j0], n = (double)A[j1];
            nq[k] = (double)q[j0] * n * n + (double)q[j1] * m * m;
            nper[k] = (double)B[j0] * n + (double)B[j1] * m;
            uint64_t l = A[j0] / gcd64(A[j0], A[j1]) * A[j1];
            double r0 = (double)(l / A[j0]), r1 = (double)(l / A[j1]);
            lq[k] = (double)q[j0] * r0 * r0 + (double)q[j1] * r1 * r1;
            lper[k] = (double)B[j0] * r0 + (double)B[j1] * r1;
        }
        added += per[0] < per[1] ? (per[1] - per[0]) / 2 * la[0] : (per[0] - per[1]) / 2 * la[1];
        if (added < *pad_min) *pad_min = added;
        double nv = nq[0] * nper[1] * nper[1] + nq[1] * nper[0] * nper[0];
        if (nv < *naive) *naive = nv;
        uint64_t p0 = (uint64_t)lper[0], p1 = (uint64_t)lper[1];
        uint64_t l = p0 / gcd64(p0, p1) * p1;
        double r0 = (double)(l / p0), r1 = (double)(l / p1);
        double lv = lq[0] * r0 * r0 + lq[1] * r1 * r1;
        if (lv < *naive_lcm) *naive_lcm = lv;
    }
}

typedef struct stats {
    uint32_t cases, minimal, le_lcm;
    double quads, naive, naive_lcm, log_ratio;
} stats;

/* Builds, verifies and checks one genus-0 case; returns the quad count. */
static uint32_t check_case(const int32_t *v, uint32_t n, stats *S, const char *name)
{
    sq_domain D;
    sq_error err;
    if (sq_domain_build(0, v, n, NULL, &D, &err)) fail_msg("%s (%u cones): %s", name, n, err.msg);
    if (sq_domain_verify(&D, v, n, &err)) fail_msg("%s: verify: %s", name, err.msg);
    const sq_metapolygon *Q = &D.quads;
    /* S cut along one edge: a disk with a boundary loop of two halfedges,
     * both ends with their four quads (regular, not cones) */
    assert_int_equal(D.genus, 0);
    assert_int_equal(D.k, 2);
    assert_int_equal(Q->nbnd, 2);
    assert_int_equal(D.pattern.partner[0], 1);
    assert_int_equal(D.pattern.partner[1], 0);
    assert_int_equal(D.side_len[0], 1);
    assert_int_equal(D.side_len[1], 1);
    assert_true(D.corner_vert[0] != D.corner_vert[1]);
    assert_int_equal(Q->v_nface[D.corner_vert[0]], 4);
    assert_int_equal(Q->v_nface[D.corner_vert[1]], 4);
    assert_int_equal(sq_metapolygon_validate(Q, 0, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_count_quads(Q), Q->nf);
    assert_int_equal(D.quads_unpadded + D.quads_added, Q->nf);
    assert_int_equal(D.refine, 1);
    /* the faces that index D->meta (the SVG dereferences them) */
    assert_true(D.nf_unpadded <= D.quads_unpadded);
    for (uint32_t f = 0; f < D.nf_unpadded; f++) assert_true(D.f_meta_face[f] < D.meta.nf);
    {
        uint64_t sum_val = 0; /* seed 5.4: a k-gon becomes k quads */
        for (uint32_t f = 0; f < D.meta.nf; f++) sum_val += D.meta.f_valence[f];
        assert_int_equal(sum_val, D.nf_unpadded);
    }
    assert_int_equal(D.padding[0], 0);
    assert_int_equal(D.padding[1], 0);
    for (int i = 2; i < 10; i++) assert_true(D.padding[i] >= 0);
    /* the order is the four groups; their pieces rebuilt independently */
    piece pc[4];
    rebuild_pieces(&D, pc);
    uint64_t sub = 0;
    for (int g = 0; g < 4; g++) sub += pc[g].quads;
    assert_int_equal(sub, D.quads_unpadded);
    uint64_t pad_min;
    double naive, naive_lcm;
    model(pc, &pad_min, &naive, &naive_lcm);
    assert_true(D.quads_added >= pad_min);
    if (D.quads_added == pad_min) S->minimal++;
    S->cases++;
    S->quads += Q->nf;
    S->naive += naive;
    S->naive_lcm += naive_lcm;
    S->log_ratio += log(naive / (double)Q->nf);
    assert_true(naive_lcm <= naive);
    S->le_lcm += (double)Q->nf <= naive_lcm;
    uint32_t nq = Q->nf;
    sq_domain_free(&D);
    return nq;
}

static void report(const char *what, const stats *S)
{
    printf("# %s: %u cases, mean quads %.1f (minimal padding in %u); seed n x n refinement: "
           "mean %.4g quads, geometric mean ratio %.4g; lcm refinement: mean %.4g (ours not "
           "larger in %u)\n",
           what, S->cases, S->quads / S->cases, S->minimal, S->naive / S->cases,
           exp(S->log_ratio / S->cases), S->naive_lcm / S->cases, S->le_lcm);
}

/* ---- hand cases --------------------------------------------------------- */

static uint32_t multiset(int32_t *v, const uint32_t (*spec)[2], uint32_t nspec)
{
    uint32_t n = 0;
    for (uint32_t s = 0; s < nspec; s++)
        for (uint32_t c = 0; c < spec[s][1]; c++) v[n++] = (int32_t)spec[s][0];
    return n;
}

static void test_hand_cases(void **state)
{
    (void)state;
    stats S;
    memset(&S, 0, sizeof S);
    int32_t v[256];
    /* cube: four {3,3} meta-2-gons (two triangles, sides 4, 4 after
     * subdivision), no padding: the cube with every face split 2 x 2 */
    static const uint32_t cube[][2] = {{3, 8}};
    uint32_t n = multiset(v, cube, 1);
    assert_int_equal(check_case(v, n, &S, "cube"), 24);
    /* four 2-gons of two quads each: 8 quads */
    static const int32_t twos[] = {2, 2, 2, 2};
    assert_int_equal(check_case(twos, 4, &S, "2,2,2,2"), 8);
    static const int32_t c5[] = {2, 2, 2, 3, 3};
    check_case(c5, 5, &S, "2,2,2,3,3");
    static const int32_t c6[] = {6, 2, 2, 2, 2, 2};
    check_case(c6, 6, &S, "6,2,2,2,2,2");
    /* the same with valence-4 entries, which are ignored */
    static const int32_t c6b[] = {4, 6, 2, 4, 2, 2, 2, 2};
    check_case(c6b, 8, &S, "4,6,2,4,2,2,2,2");
    static const uint32_t homer[][2] = {{3, 51}, {5, 22}, {6, 7}, {7, 1}, {8, 1}};
    n = multiset(v, homer, 5);
    uint32_t qh = check_case(v, n, &S, "homer");
    static const uint32_t fandisk[][2] = {{3, 25}, {5, 17}};
    n = multiset(v, fandisk, 2);
    uint32_t qf = check_case(v, n, &S, "fandisk");
    static const int32_t big[] = {22, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3};
    check_case(big, sizeof big / sizeof big[0], &S, "22 + 2s + 3s");
    printf("# homer %u quads, fandisk %u quads\n", qh, qf);
    report("hand cases", &S);
}

/* Input order does not matter for validity: shuffled cube and homer. */
static void test_shuffled(void **state)
{
    (void)state;
    stats S;
    memset(&S, 0, sizeof S);
    static const uint32_t homer[][2] = {{3, 51}, {5, 22}, {6, 7}, {7, 1}, {8, 1}};
    int32_t v[128];
    uint32_t n = multiset(v, homer, 5);
    for (int r = 0; r < 10; r++) {
        for (uint32_t i = n; i > 1; i--) {
            uint32_t j = rnd(i);
            int32_t t = v[i - 1];
            v[i - 1] = v[j], v[j] = t;
        }
        check_case(v, n, &S, "shuffled homer");
    }
    report("shuffled homer", &S);
}

/* ---- errors ------------------------------------------------------------- */

static void test_errors(void **state)
{
    (void)state;
    sq_domain D;
    sq_error err;
    /* Gauss-Bonnet: excess -6 is not a sphere */
    static const int32_t bad[] = {3, 3, 3, 3, 3, 3};
    assert_int_not_equal(sq_domain_build(0, bad, 6, NULL, &D, &err), SQ_OK);
    /* valence 1 is not allowed */
    static const int32_t one[] = {1, 3, 3, 3, 3, 3};
    assert_int_not_equal(sq_domain_build(0, one, 6, NULL, &D, &err), SQ_OK);
    /* a pattern does not apply to the sphere */
    sq_pattern pat;
    sq_pattern_init(&pat);
    assert_int_equal(sq_pattern_torus(&pat, NULL), SQ_OK);
    sq_domain_options opt = {&pat, SQ_NONE, NULL, 0, 0};
    static const int32_t cube[] = {3, 3, 3, 3, 3, 3, 3, 3};
    assert_int_equal(sq_domain_build(0, cube, 8, &opt, &D, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "genus 0"));
    sq_pattern_free(&pat);
    /* verify rejects a wrong cone list */
    assert_int_equal(sq_domain_build(0, cube, 8, NULL, &D, &err), SQ_OK);
    static const int32_t other[] = {2, 2, 2, 2};
    assert_int_not_equal(sq_domain_verify(&D, other, 4, &err), SQ_OK);
    sq_domain_free(&D);
}

/* ---- random multisets ---------------------------------------------------- */

/* Valences 2..8 (sometimes 22) with total excess -8: some positives, then
 * 2s and 3s until the sum is reached. */
static uint32_t random_cones(int32_t *v, uint32_t cap)
{
    uint32_t n = 0;
    int64_t excess = 0;
    uint32_t npos = rnd(3) == 0 ? 0 : rnd(12);
    for (uint32_t i = 0; i < npos && n + 64 < cap; i++) {
        int32_t k = rnd(40) == 0 ? 22 : 5 + (int32_t)rnd(4);
        v[n++] = k;
        excess += k - 4;
    }
    uint32_t bias = rnd(4); /* share of 2s among the negative cones */
    while (excess != -8 && n < cap) {
        int32_t k = excess - -8 >= 2 && rnd(4) < bias ? 2 : 3;
        v[n++] = k;
        excess += k - 4;
    }
    assert_true(excess == -8);
    /* shuffle */
    for (uint32_t i = n; i > 1; i--) {
        uint32_t j = rnd(i);
        int32_t t = v[i - 1];
        v[i - 1] = v[j], v[j] = t;
    }
    return n;
}

static void test_random(void **state)
{
    (void)state;
    const uint32_t cases = long_mode() ? 30000 : 300;
    stats S;
    memset(&S, 0, sizeof S);
    int32_t v[512];
    char name[64];
    for (uint32_t c = 0; c < cases; c++) {
        uint32_t n = random_cones(v, 512);
        snprintf(name, sizeof name, "random case %u", c);
        check_case(v, n, &S, name);
    }
    report("random", &S);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_cases),
        cmocka_unit_test(test_shuffled),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_random),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
