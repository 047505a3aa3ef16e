/* Property tests of the graded fans (sq_param_grade_fans, sq_param_fans.c)
 * on random disks: a convex polygon in a tilted plane whose sides are cut
 * into random numbers of random pieces, every piece joined to one inner
 * apex (a fan per side, each side its own "input face"), plus sides that
 * share an input face and bend (a fan that must be split at the bend), and
 * sides too short to grade. Checked independently of the construction:
 * every triangle positively oriented in the plane (exact predicate on the
 * projected doubles), the areas add up to the polygon's, the result is a
 * manifold disk (sq_param_pair_twins) with exactly the old boundary edges,
 * the faces not in a graded fan kept first and unchanged, every new vertex
 * strictly inside its fan's triangle (apex, first, last base point) and in
 * the plane, the apex's fans down to two triangles each, and the Tutte map
 * of the result onto the disk an embedding. Seeded; SQ_LONG_TESTS=1 runs
 * many more disks. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_param_internal.h"
#include "sq_predicates.h"
#include "sq_test_random.h"

#define TEST_PI 3.14159265358979323846

static double urand(void) { return (double)(rng() >> 11) * (1.0 / 9007199254740992.0); }

/* the plane z = 0.3 x - 0.7 y + 2: 3D point of (x, y) */
static void lift(double x, double y, double *p) { p[0] = x, p[1] = y, p[2] = 0.3 * x - 0.7 * y + 2; }

typedef struct disk {
    uint32_t nbl, nv, nf, nsides;
    uint32_t *tri, *fin, *twin;
    double *p3;
    uint32_t *side_first; /* nsides + 1: boundary id of each side's corner */
    double area;
} disk;

/* A convex polygon of `sides` corners on an ellipse, side s cut into
 * pieces[s] pieces at random parameters, one apex near the centre; face
 * ids: side s's fan is input face fin_of[s]. */
static void make_disk(disk *D, uint32_t sides, const uint32_t *pieces, const uint32_t *fin_of)
{
    uint32_t nbl = 0;
    for (uint32_t s = 0; s < sides; s++) nbl += pieces[s];
    D->nbl = nbl, D->nv = nbl + 1, D->nf = nbl, D->nsides = sides;
    D->p3 = malloc(3 * (size_t)D->nv * sizeof *D->p3);
    D->tri = malloc(3 * (size_t)D->nf * sizeof *D->tri);
    D->fin = malloc((size_t)D->nf * sizeof *D->fin);
    D->twin = malloc(3 * (size_t)D->nf * sizeof *D->twin);
    D->side_first = malloc(((size_t)sides + 1) * sizeof *D->side_first);
    assert_non_null(D->p3), assert_non_null(D->tri), assert_non_null(D->fin), assert_non_null(D->twin);
    double cx[64], cy[64], a = 1 + urand(), b = 0.5 + urand();
    /* consecutive corners less than 1.3 * 2 pi / 3 apart: every side at
     * least 0.1 from the centre, where the apex is (within 0.015) */
    for (uint32_t s = 0; s < sides; s++) {
        double t = 2 * TEST_PI * (s + 0.35 + 0.3 * urand()) / sides;
        cx[s] = a * cos(t), cy[s] = b * sin(t);
    }
    /* boundary ids counterclockwise, side by side */
    uint32_t id = 0;
    for (uint32_t s = 0; s < sides; s++) {
        D->side_first[s] = id;
        uint32_t n = pieces[s];
        double u[1024];
        u[0] = 0;
        for (uint32_t k = 1; k < n; k++) u[k] = urand();
        for (uint32_t k = 1; k < n; k++) /* sorted, distinct */
            for (uint32_t j = k; j > 1 && u[j - 1] > u[j]; j--) {
                double x = u[j];
                u[j] = u[j - 1], u[j - 1] = x;
            }
        for (uint32_t k = 0; k < n; k++) {
            double t = k == 0 ? 0 : 0.02 + 0.96 * u[k];
            uint32_t s1 = (s + 1) % sides;
            lift(cx[s] + t * (cx[s1] - cx[s]), cy[s] + t * (cy[s1] - cy[s]), D->p3 + 3 * (size_t)id);
            id++;
        }
    }
    D->side_first[sides] = nbl;
    uint32_t apex = nbl;
    lift(0.01 * urand(), 0.01 * urand(), D->p3 + 3 * (size_t)apex);
    D->area = 0;
    for (uint32_t s = 0, f = 0; s < sides; s++)
        for (uint32_t k = D->side_first[s]; k < D->side_first[s + 1]; k++, f++) {
            uint32_t k1 = (k + 1) % nbl;
            D->tri[3 * f] = k, D->tri[3 * f + 1] = k1, D->tri[3 * f + 2] = apex;
            D->fin[f] = fin_of[s];
            const double *p = D->p3 + 3 * (size_t)k, *q = D->p3 + 3 * (size_t)k1, *c = D->p3 + 3 * (size_t)apex;
            D->area += 0.5 * ((q[0] - p[0]) * (c[1] - p[1]) - (q[1] - p[1]) * (c[0] - p[0]));
            assert_true(sq_orient2d(p, q, c) > 0); /* a valid disk to start from */
        }
    assert_int_equal(sq_param_pair_twins(D->nf, D->tri, D->twin), 0);
}

static void free_disk(disk *D)
{
    free(D->p3), free(D->tri), free(D->fin), free(D->twin), free(D->side_first);
    memset(D, 0, sizeof *D);
}

static double xy_of(const disk *D, uint32_t v, int d) { return D->p3[3 * (size_t)v + d]; }

/* one random disk through the pass, every property checked */
static void check_one(uint32_t sides, int with_bend)
{
    uint32_t pieces[64], fin_of[64];
    for (uint32_t s = 0; s < sides; s++) {
        uint32_t r = (uint32_t)(rng() % 4);
        pieces[s] = r == 0 ? 1 + (uint32_t)(rng() % (SQ_FAN_MIN_RUN - 1)) : 1 + (uint32_t)(rng() % 300);
        fin_of[s] = s;
    }
    if (with_bend && sides >= 3) fin_of[1] = fin_of[0]; /* sides 0 and 1: one input face, a bend */
    disk D;
    make_disk(&D, sides, pieces, fin_of);
    const uint32_t nf0 = D.nf, nv0 = D.nv, nbl = D.nbl, apex = nbl;
    uint32_t *tri0 = malloc(3 * (size_t)nf0 * sizeof *tri0), *fin0 = malloc((size_t)nf0 * sizeof *fin0);
    memcpy(tri0, D.tri, 3 * (size_t)nf0 * sizeof *tri0);
    memcpy(fin0, D.fin, (size_t)nf0 * sizeof *fin0);
    sq_error err;
    sq_error_clear(&err);
    uint32_t added = 0;
    assert_int_equal(sq_param_grade_fans(nbl, SQ_FAN_MIN_RUN, D.twin, &D.nf, &D.tri, &D.fin, &D.nv, &D.p3, &added, &err),
                     SQ_OK);
    assert_int_equal(D.nv, nv0 + added);
    /* which sides were graded: those of at least SQ_FAN_MIN_RUN pieces
     * (a bent pair: each of its straight parts on its own) */
    uint32_t graded_faces = 0, expect_apex = 0;
    for (uint32_t s = 0; s < sides; s++) {
        if (pieces[s] >= SQ_FAN_MIN_RUN) graded_faces += pieces[s], expect_apex += 2;
        else expect_apex += pieces[s];
    }
    if (graded_faces == 0) {
        assert_int_equal(added, 0);
        assert_int_equal(D.nf, nf0);
        assert_memory_equal(D.tri, tri0, 3 * (size_t)nf0 * sizeof *tri0);
    } else {
        assert_true(added > 0);
    }
    /* the kept faces first, unchanged, in their order */
    uint32_t kept = nf0 - graded_faces, j = 0;
    for (uint32_t f = 0; f < nf0; f++) {
        uint32_t s = 0;
        while (s + 1 < sides && D.side_first[s + 1] <= tri0[3 * f]) s++;
        if (pieces[s] >= SQ_FAN_MIN_RUN) continue;
        assert_memory_equal(D.tri + 3 * (size_t)j, tri0 + 3 * (size_t)f, 3 * sizeof *tri0);
        assert_int_equal(D.fin[j], fin0[f]);
        j++;
    }
    assert_int_equal(j, kept);
    /* positively oriented in the plane, areas adding up, in the plane */
    double area = 0;
    for (uint32_t f = 0; f < D.nf; f++) {
        const uint32_t *t = D.tri + 3 * (size_t)f;
        double a[2] = {xy_of(&D, t[0], 0), xy_of(&D, t[0], 1)}, b[2] = {xy_of(&D, t[1], 0), xy_of(&D, t[1], 1)},
               c[2] = {xy_of(&D, t[2], 0), xy_of(&D, t[2], 1)};
        assert_true(sq_orient2d(a, b, c) > 0);
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    assert_true(fabs(area - D.area) <= 1e-12 * D.area);
    for (uint32_t v = nv0; v < D.nv; v++) {
        const double *p = D.p3 + 3 * (size_t)v;
        assert_true(fabs(p[2] - (0.3 * p[0] - 0.7 * p[1] + 2)) <= 1e-12);
    }
    /* a manifold disk with the old boundary */
    uint32_t *tw = malloc(3 * (size_t)D.nf * sizeof *tw);
    assert_int_equal(sq_param_pair_twins(D.nf, D.tri, tw), 0);
    uint32_t nbnd = 0;
    for (uint32_t h = 0; h < 3 * D.nf; h++)
        if (tw[h] == SQ_NONE) {
            uint32_t a = D.tri[h], b = D.tri[sq_param_corner_next(h)];
            assert_true(a < nbl && b == (a + 1) % nbl);
            nbnd++;
        }
    assert_int_equal(nbnd, nbl);
    /* the new vertices inside their fans' triangles, the fans' faces
     * keeping their input face */
    for (uint32_t f = kept; f < D.nf; f++) {
        const uint32_t *t = D.tri + 3 * (size_t)f;
        for (int k = 0; k < 3; k++) {
            if (t[k] < nv0) continue;
            uint32_t s = 0;
            while (s < sides && fin_of[s] != D.fin[f]) s++;
            assert_true(s < sides);
            /* the fan of side s (or of the bent pair's second side) */
            int inside = 0;
            for (uint32_t s2 = s; s2 < sides && fin_of[s2] == D.fin[f] && !inside; s2++) {
                uint32_t p0 = D.side_first[s2], pk = (D.side_first[s2 + 1]) % nbl;
                double A[2] = {xy_of(&D, apex, 0), xy_of(&D, apex, 1)}, P0[2] = {xy_of(&D, p0, 0), xy_of(&D, p0, 1)},
                       PK[2] = {xy_of(&D, pk, 0), xy_of(&D, pk, 1)}, X[2] = {xy_of(&D, t[k], 0), xy_of(&D, t[k], 1)};
                inside = sq_orient2d(P0, PK, X) > 0 && sq_orient2d(PK, A, X) > 0 && sq_orient2d(A, P0, X) > 0;
            }
            assert_true(inside);
        }
    }
    /* the apex: two triangles per graded fan, its others as they were */
    uint32_t at_apex = 0;
    for (uint32_t h = 0; h < 3 * D.nf; h++) at_apex += D.tri[h] == apex;
    assert_int_equal(at_apex, expect_apex);
    /* Tutte's map of the result: an embedding */
    double *xy = malloc(2 * (size_t)D.nv * sizeof *xy);
    for (uint32_t i = 0; i < nbl; i++) {
        double t = 2 * TEST_PI * i / nbl;
        xy[2 * i] = cos(t), xy[2 * i + 1] = sin(t);
    }
    assert_int_equal(sq_param_disk_tutte(D.nf, D.tri, tw, nbl, D.nv - nbl, D.p3, xy, &err), SQ_OK);
    for (uint32_t f = 0; f < D.nf; f++) {
        const uint32_t *t = D.tri + 3 * (size_t)f;
        assert_true(sq_orient2d(xy + 2 * (size_t)t[0], xy + 2 * (size_t)t[1], xy + 2 * (size_t)t[2]) > 0);
    }
    free(xy), free(tw), free(tri0), free(fin0);
    free_disk(&D);
}

static void test_random_disks(void **state)
{
    (void)state;
    rng_state = 20261127;
    uint32_t n = long_mode() ? 2000 : 60;
    for (uint32_t i = 0; i < n; i++) check_one(3 + (uint32_t)(rng() % 10), (int)(rng() % 2));
}

/* a fan below the threshold and nothing else: nothing changes */
static void test_short_fans_kept(void **state)
{
    (void)state;
    uint32_t pieces[4] = {1, 2, SQ_FAN_MIN_RUN - 1, 1}, fin_of[4] = {0, 1, 2, 3};
    rng_state = 7;
    disk D;
    make_disk(&D, 4, pieces, fin_of);
    uint32_t nf = D.nf, nv = D.nv, added = 5;
    sq_error err;
    sq_error_clear(&err);
    assert_int_equal(sq_param_grade_fans(D.nbl, SQ_FAN_MIN_RUN, D.twin, &D.nf, &D.tri, &D.fin, &D.nv, &D.p3, &added, &err),
                     SQ_OK);
    assert_int_equal(added, 0);
    assert_int_equal(D.nf, nf);
    assert_int_equal(D.nv, nv);
    free_disk(&D);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_disks),
        cmocka_unit_test(test_short_fans_kept),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
