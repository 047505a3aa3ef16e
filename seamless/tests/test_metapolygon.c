/* Metapolygon data structure and extension E(P, i): seed 5.1 (Def. 5.1 -
 * 5.4, Theorem 5.5, every case of Figure 4) and the 4-gon counts of
 * seed 5.3. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "mp_test_util.h"
#include "sq_metapolygon.h"

static void assert_valid(const sq_metapolygon *P, unsigned flags)
{
    sq_error err;
    sq_error_clear(&err);
    sq_status st = sq_metapolygon_validate(P, flags, &err);
    if (st != SQ_OK) print_error("validate: %s\n", err.msg);
    assert_int_equal(st, SQ_OK);
}

/* The side lengths of P in C(P) order; n returned. */
static uint32_t sides_of(const sq_metapolygon *P, uint32_t *len, uint32_t cap)
{
    uint32_t n = sq_metapolygon_nonflat(P, cap, NULL, NULL, len);
    assert_true(n <= cap);
    return n;
}

/* P's side lengths equal `expect` up to a cyclic rotation. */
static void assert_sides(const sq_metapolygon *P, const uint32_t *expect, uint32_t n)
{
    uint32_t len[64];
    uint32_t k = sides_of(P, len, 64);
    assert_int_equal(k, n);
    for (uint32_t r = 0; r < n; r++) {
        uint32_t j = 0;
        while (j < n && len[(r + j) % n] == expect[j]) j++;
        if (j == n) return;
    }
    char buf[256] = "";
    for (uint32_t j = 0; j < k; j++)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%u ", len[j]);
    print_error("side lengths: %s\n", buf);
    fail_msg("side lengths differ from the expected cyclic sequence");
}

/* The first halfedge of a side of length l, and its position-th edge. */
static uint32_t edge_on_side(const sq_metapolygon *P, uint32_t l, uint32_t position)
{
    uint32_t he[64], len[64];
    uint32_t k = sq_metapolygon_nonflat(P, 64, NULL, he, len);
    for (uint32_t s = 0; s < k && s < 64; s++) {
        if (len[s] != l) continue;
        uint32_t h = he[s];
        for (uint32_t p = 0; p < position; p++) h = P->he_next[h];
        return h;
    }
    fail_msg("no side of length %u", l);
    return SQ_NONE;
}

static void grid(sq_metapolygon *P, uint32_t rows, uint32_t cols)
{
    sq_metapolygon_init(P);
    assert_int_equal(sq_metapolygon_make_grid(P, rows, cols, NULL), SQ_OK);
    assert_valid(P, SQ_MP_CHECK_METAPOLYGON);
}

/* ---- data structure ------------------------------------------------------ */

static void test_empty_and_single_polygons(void **state)
{
    (void)state;
    sq_metapolygon P;
    sq_metapolygon_init(&P);
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
    assert_int_equal(sq_metapolygon_count_corners(&P), 0);
    assert_int_equal(sq_metapolygon_nonflat(&P, 0, NULL, NULL, NULL), 0);
    assert_int_equal(sq_metapolygon_excess(&P), 0);
    for (uint32_t i = 2; i <= 9; i++) {
        if (i == 4) continue;
        sq_metapolygon_init(&P);
        sq_extend_stats es;
        assert_int_equal(sq_metapolygon_extend(&P, i, SQ_NONE, &es, NULL), SQ_OK);
        assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
        assert_int_equal(P.nf, 1);
        assert_int_equal(P.f_valence[0], i);
        assert_int_equal(sq_metapolygon_count_corners(&P), i); /* k + i - 4, k = 4 */
        assert_int_equal(sq_metapolygon_excess(&P), (int64_t)i - 4);
        uint32_t ones[16];
        for (uint32_t j = 0; j < i; j++) ones[j] = 1;
        assert_sides(&P, ones, i);
        for (uint32_t v = 0; v < P.nv; v++)
            assert_int_equal(sq_metapolygon_vertex_kind(&P, v), SQ_MP_CORNER);
        sq_metapolygon_free(&P);
    }
}

/* A 2-gon: two edges between the same two vertices. */
static void test_two_gon_edges_not_endpoints(void **state)
{
    (void)state;
    sq_metapolygon P;
    sq_metapolygon_init(&P);
    assert_int_equal(sq_metapolygon_extend(&P, 2, SQ_NONE, NULL, NULL), SQ_OK);
    assert_int_equal(P.nv, 2);
    assert_int_equal(P.nh, 4);
    assert_int_equal(P.nbnd, 2);
    /* both boundary halfedges join the same two vertices, in opposite
     * directions, and are distinct edges */
    uint32_t b0 = P.bnd_he, b1 = P.he_next[b0];
    assert_int_not_equal(b0, b1);
    assert_int_equal(P.he_vert[b0], P.he_vert[P.he_next[b1]]);
    assert_int_not_equal(P.he_twin[b0], b1);
    /* a 3-gon on a 2-gon: the meta-1-gon of seed 5.2 */
    assert_int_equal(sq_metapolygon_extend(&P, 3, b0, NULL, NULL), SQ_OK);
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
    assert_int_equal(sq_metapolygon_count_corners(&P), 1);
    uint32_t three[] = {3};
    assert_sides(&P, three, 1);
    sq_metapolygon_free(&P);
}

static void test_grid_and_copy(void **state)
{
    (void)state;
    sq_metapolygon P, Q;
    grid(&P, 3, 5);
    assert_int_equal(P.nf, 15);
    assert_int_equal(P.nv, 24);
    assert_int_equal(sq_metapolygon_count_quads(&P), 15);
    assert_int_equal(sq_metapolygon_irregular(&P, 0, NULL), 0);
    uint32_t s[] = {5, 3, 5, 3};
    assert_sides(&P, s, 4);
    uint32_t kinds[5] = {0};
    for (uint32_t v = 0; v < P.nv; v++) kinds[sq_metapolygon_vertex_kind(&P, v)]++;
    assert_int_equal(kinds[SQ_MP_INTERIOR], 2 * 4);
    assert_int_equal(kinds[SQ_MP_CORNER], 4);
    assert_int_equal(kinds[SQ_MP_FLAT], 2 * (2 + 4));
    sq_metapolygon_init(&Q);
    assert_int_equal(sq_metapolygon_copy(&Q, &P, NULL), SQ_OK);
    sq_metapolygon_free(&P);
    assert_valid(&Q, SQ_MP_CHECK_METAPOLYGON);
    assert_sides(&Q, s, 4);
    sq_metapolygon_free(&Q);
}

/* Seed 6.1: padding a side of l edges by m layers adds m to both
 * neighbouring sides (one-sided grid). */
static void test_one_sided_grid_padding(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 3);
    uint32_t h = edge_on_side(&P, 3, 0);
    assert_int_equal(sq_metapolygon_glue_grid(&P, h, 4, 3, 1, NULL), SQ_OK);
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
    assert_int_equal(P.nf, 6 + 12);
    uint32_t s[] = {3, 6, 3, 6};
    assert_sides(&P, s, 4);
    sq_metapolygon_free(&P);
}

static void test_validate_catches_corruption(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 2);
    sq_error err;
    P.v_nface[0]++;
    assert_int_equal(sq_metapolygon_validate(&P, 0, &err), SQ_ERR_INTERNAL);
    P.v_nface[0]--;
    uint32_t t = P.he_next[0];
    P.he_next[0] = P.he_next[t];
    assert_int_equal(sq_metapolygon_validate(&P, 0, &err), SQ_ERR_INTERNAL);
    P.he_next[0] = t;
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
    /* an interior vertex of valence 4 is fine; glue a triangle to get a
     * concave vertex and check the Def. 5.1 flag */
    uint32_t h = edge_on_side(&P, 2, 1);
    assert_int_equal(sq_metapolygon_glue_polygon(&P, h, 1, 1, NULL, NULL, NULL, NULL), SQ_OK);
    assert_valid(&P, 0);
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON | SQ_MP_CHECK_ALLOW_CONCAVE);
    assert_int_equal(sq_metapolygon_validate(&P, SQ_MP_CHECK_METAPOLYGON, &err),
                     SQ_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "Def. 5.1"));
    /* extension refuses a non-metapolygon */
    assert_int_equal(sq_metapolygon_extend(&P, 5, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    sq_metapolygon_free(&P);
}

/* ---- Def. 5.4 preconditions ---------------------------------------------- */

static void test_preconditions(void **state)
{
    (void)state;
    sq_error err;
    sq_metapolygon P;
    grid(&P, 1, 1);
    uint32_t nf = P.nf, nh = P.nh;
    assert_int_equal(sq_metapolygon_extend(&P, 4, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "4-gon"));
    assert_int_equal(sq_metapolygon_extend(&P, 1, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_metapolygon_extend(&P, 0, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_metapolygon_extend(&P, 5, 0, NULL, &err), SQ_ERR_ARGUMENT); /* interior */
    assert_non_null(strstr(err.msg, "not a boundary halfedge"));
    assert_int_equal(sq_metapolygon_extend(&P, 5, 999, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(P.nf, nf);
    assert_int_equal(P.nh, nh);
    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
    sq_metapolygon_free(&P);

    /* empty: a glue edge makes no sense */
    sq_metapolygon_init(&P);
    assert_int_equal(sq_metapolygon_extend(&P, 5, 0, NULL, &err), SQ_ERR_ARGUMENT);
    /* meta-2-gon (a 2-gon): i > max(1, 4-2) = 2 */
    assert_int_equal(sq_metapolygon_extend(&P, 2, SQ_NONE, NULL, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_extend(&P, 2, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "meta-2-gon"));
    /* meta-1-gon: i > 3, i != 4 */
    assert_int_equal(sq_metapolygon_extend(&P, 3, SQ_NONE, NULL, NULL), SQ_OK);
    assert_int_equal(sq_metapolygon_count_corners(&P), 1);
    assert_int_equal(sq_metapolygon_extend(&P, 3, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_metapolygon_extend(&P, 2, SQ_NONE, NULL, &err), SQ_ERR_ARGUMENT);
    uint32_t b;
    assert_int_equal(sq_metapolygon_default_glue_edge(&P, 3, &b, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_metapolygon_predict_quads(&P, 3, P.bnd_he), UINT64_MAX);
    assert_int_equal(sq_metapolygon_extend(&P, 5, SQ_NONE, NULL, &err), SQ_OK);
    sq_metapolygon_free(&P);
}

/* ---- Figure 4 -------------------------------------------------------------- */

typedef struct fig4_expect {
    uint32_t concave, grids2, grids3;
    uint64_t quads2, quads3;
    uint32_t corners;
} fig4_expect;

static void extend_and_check(sq_metapolygon *P, uint32_t i, uint32_t h, fig4_expect e)
{
    uint32_t nf0 = P->nf;
    uint32_t irr0 = sq_metapolygon_irregular(P, 0, NULL);
    uint64_t predicted = sq_metapolygon_predict_quads(P, i, h);
    sq_extend_stats es;
    sq_error err;
    sq_status st = sq_metapolygon_extend(P, i, h, &es, &err);
    if (st != SQ_OK) print_error("%s\n", err.msg);
    assert_int_equal(st, SQ_OK);
    assert_valid(P, SQ_MP_CHECK_METAPOLYGON);
    assert_int_equal(es.glue_he, h);
    assert_int_equal(es.concave, e.concave);
    assert_int_equal(es.grids_step2, e.grids2);
    assert_int_equal(es.grids_step3, e.grids3);
    assert_int_equal(es.quads_step2, e.quads2);
    assert_int_equal(es.quads_step3, e.quads3);
    assert_int_equal(predicted, e.quads2 + e.quads3);
    assert_int_equal(P->nf, nf0 + 1 + e.quads2 + e.quads3);
    assert_int_equal(sq_metapolygon_count_corners(P), e.corners);
    /* I(Q) = I(P) + {i}: the i-gon is the only new irregular face */
    assert_int_equal(sq_metapolygon_irregular(P, 0, NULL), irr0 + 1);
    assert_int_equal(P->f_valence[es.face], i);
    for (uint32_t f = nf0; f < P->nf; f++)
        if (f != es.face) assert_int_equal(P->f_valence[f], 4);
}

/* (b) i-gon on a corner-corner edge: no concave vertex, no fill. */
static void test_fig4_b_corner_corner(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 1, 1);
    extend_and_check(&P, 5, P.bnd_he, (fig4_expect){0, 0, 0, 0, 0, 5});
    uint32_t s5[] = {1, 2, 1, 1, 2};
    assert_sides(&P, s5, 5);
    sq_metapolygon_free(&P);

    grid(&P, 1, 1);
    extend_and_check(&P, 2, P.bnd_he, (fig4_expect){0, 0, 0, 0, 0, 2});
    uint32_t s2[] = {1, 3};
    assert_sides(&P, s2, 2);
    sq_metapolygon_free(&P);

    grid(&P, 1, 1);
    extend_and_check(&P, 3, P.bnd_he, (fig4_expect){0, 0, 0, 0, 0, 3});
    uint32_t s3[] = {1, 2, 2};
    assert_sides(&P, s3, 3);
    sq_metapolygon_free(&P);
}

/* (c) 2-gon on a flat-flat edge with d(v0,v1) = d(v2,v3): one step-2 grid
 * of d(v1,v2) x d(v0,v1) = 1 x 1, which closes the side. */
static void test_fig4_c_two_gon_centred(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 3); /* sides 3 2 3 2 */
    extend_and_check(&P, 2, edge_on_side(&P, 3, 1), (fig4_expect){2, 1, 0, 1, 0, 2});
    uint32_t s[] = {3, 5};
    assert_sides(&P, s, 2);
    assert_int_equal(P.nf, 8);
    sq_metapolygon_free(&P);

    grid(&P, 4, 5); /* centred on a side of 5: x = 2, (l-1)/2 = 2 quads */
    extend_and_check(&P, 2, edge_on_side(&P, 5, 2), (fig4_expect){2, 1, 0, 2, 0, 2});
    uint32_t s2[] = {5, 4 + 1 + 4};
    assert_sides(&P, s2, 2);
    sq_metapolygon_free(&P);
}

/* (d) i-gon on a flat-corner edge: one concave vertex, one step-3 grid of
 * 1 x (l-1). */
static void test_fig4_d_flat_corner(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 3);
    extend_and_check(&P, 3, edge_on_side(&P, 3, 0), (fig4_expect){1, 0, 1, 0, 2, 3});
    uint32_t s3[] = {3, 3, 5};
    assert_sides(&P, s3, 3);
    sq_metapolygon_free(&P);

    grid(&P, 2, 3);
    extend_and_check(&P, 5, edge_on_side(&P, 3, 0), (fig4_expect){1, 0, 1, 0, 2, 5});
    uint32_t s5[] = {3, 1, 3, 3, 3};
    assert_sides(&P, s5, 5);
    sq_metapolygon_free(&P);

    /* the corner at the other end of the edge */
    grid(&P, 2, 3);
    extend_and_check(&P, 6, edge_on_side(&P, 3, 2), (fig4_expect){1, 0, 1, 0, 2, 6});
    sq_metapolygon_free(&P);
}

/* (e) 2-gon on a flat-flat edge with d(v0,v1) != d(v2,v3): a step-2 grid
 * leaves one concave vertex, filled by a step-3 grid. */
static void test_fig4_e_two_gon_off_centre(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 4); /* l = 4, l' = 2, x = 1: 1 + (4-2-1)(2+1) = 4 */
    extend_and_check(&P, 2, edge_on_side(&P, 4, 1), (fig4_expect){2, 1, 1, 1, 3, 2});
    uint32_t s[] = {5, 5};
    assert_sides(&P, s, 2);
    sq_metapolygon_free(&P);

    /* mirrored: x = 1 from the other corner */
    grid(&P, 2, 4);
    extend_and_check(&P, 2, edge_on_side(&P, 4, 2), (fig4_expect){2, 1, 1, 1, 3, 2});
    assert_sides(&P, s, 2);
    sq_metapolygon_free(&P);

    /* l = 7, l' = 3, x = 2: step 2 adds 1 x 2, step 3 (3+1) x (7-4-1) */
    grid(&P, 3, 7);
    extend_and_check(&P, 2, edge_on_side(&P, 7, 2), (fig4_expect){2, 1, 1, 2, 8, 2});
    sq_metapolygon_free(&P);
}

/* (f) i != 2 on a flat-flat edge: two separated concave vertices, two
 * step-3 grids. */
static void test_fig4_f_flat_flat(void **state)
{
    (void)state;
    sq_metapolygon P;
    grid(&P, 2, 3); /* i = 3, x = 1: 1 + 2*1 */
    extend_and_check(&P, 3, edge_on_side(&P, 3, 1), (fig4_expect){2, 0, 2, 0, 3, 3});
    uint32_t s3[] = {4, 4, 3};
    assert_sides(&P, s3, 3);
    sq_metapolygon_free(&P);

    grid(&P, 2, 3); /* i = 5: l - 1 = 2 */
    extend_and_check(&P, 5, edge_on_side(&P, 3, 1), (fig4_expect){2, 0, 2, 0, 2, 5});
    sq_metapolygon_free(&P);

    grid(&P, 3, 6); /* i = 8 anywhere inside a side of 6: 5 */
    extend_and_check(&P, 8, edge_on_side(&P, 6, 3), (fig4_expect){2, 0, 2, 0, 5, 8});
    sq_metapolygon_free(&P);
}

/* Seed 5.3 formulas, l = side length, x = distance to the nearest corner,
 * l' = the other side at that corner; a rows x cols grid has sides
 * l = cols and l' = rows around it. */
static void test_four_gon_counts_formulas(void **state)
{
    (void)state;
    uint32_t checked = 0;
    for (uint32_t l = 1; l <= 9; l++) {
        for (uint32_t lp = 1; lp <= 7; lp++) {
            for (uint32_t p = 0; p < l; p++) {
                uint64_t x = p < l - 1 - p ? p : l - 1 - p;
                uint32_t vals[] = {2, 3, 5, 6, 7, 11};
                for (uint32_t vi = 0; vi < 6; vi++) {
                    uint32_t i = vals[vi];
                    uint64_t expect = i > 4  ? l - 1
                                    : i == 3 ? x + (x + 1) * (l - x - 1)
                                             : x + (l - 2 * x - 1) * (lp + 1);
                    sq_metapolygon P;
                    grid(&P, lp, l);
                    uint32_t h = edge_on_side(&P, l, p);
                    assert_int_equal(sq_metapolygon_predict_quads(&P, i, h), expect);
                    sq_extend_stats es;
                    assert_int_equal(sq_metapolygon_extend(&P, i, h, &es, NULL), SQ_OK);
                    assert_int_equal(es.quads_step2 + es.quads_step3, expect);
                    assert_int_equal(sq_metapolygon_count_corners(&P), i);
                    assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
                    sq_metapolygon_free(&P);
                    checked++;
                }
            }
        }
    }
    /* the minima of seed 5.3: i = 3 at a corner (x = 0): l - 1; i = 2
     * centred: (l-1)/2 for odd l, l/2 + l' for even l */
    for (uint32_t l = 1; l <= 12; l++) {
        for (uint32_t lp = 1; lp <= 12; lp++) {
            uint64_t x = (l - 1) / 2;
            uint64_t c2 = x + (l - 2 * x - 1) * (lp + 1);
            assert_int_equal(c2, l % 2 ? (l - 1) / 2 : l / 2 + lp);
            uint64_t best3 = UINT64_MAX, best2 = UINT64_MAX;
            for (uint64_t y = 0; y <= (l - 1) / 2; y++) {
                uint64_t q3 = y + (y + 1) * (l - y - 1), q2 = y + (l - 2 * y - 1) * (lp + 1);
                if (q3 < best3) best3 = q3;
                if (q2 < best2) best2 = q2;
            }
            assert_int_equal(best3, l - 1);
            assert_int_equal(best2, c2);
        }
    }
    print_message("seed 5.3 counts checked on %u glue edges\n", checked);
}

/* On a meta-1-gon the side's two ends are one corner: E adds l 4-gons, one
 * more than seed 5.3's l - 1 (documented in sq_metapolygon.h). */
static void test_meta_one_gon_count(void **state)
{
    (void)state;
    for (uint32_t pos = 0; pos < 3; pos++) {
        sq_metapolygon P;
        sq_metapolygon_init(&P);
        assert_int_equal(sq_metapolygon_extend(&P, 2, SQ_NONE, NULL, NULL), SQ_OK);
        assert_int_equal(sq_metapolygon_extend(&P, 3, SQ_NONE, NULL, NULL), SQ_OK);
        uint32_t h = edge_on_side(&P, 3, pos);
        assert_int_equal(sq_metapolygon_predict_quads(&P, 5, h), 3);
        sq_extend_stats es;
        assert_int_equal(sq_metapolygon_extend(&P, 5, h, &es, NULL), SQ_OK);
        assert_int_equal(es.quads_step2 + es.quads_step3, 3);
        assert_int_equal(sq_metapolygon_count_corners(&P), 2);
        assert_valid(&P, SQ_MP_CHECK_METAPOLYGON);
        sq_metapolygon_free(&P);
    }
}

/* The default edge is the cheapest of all boundary edges by the exact
 * count, on metapolygons grown by random extensions. */
static void test_default_edge_is_cheapest_and_prediction_exact(void **state)
{
    (void)state;
    rng r = {42};
    uint32_t edges_checked = 0;
    for (uint32_t trial = 0; trial < 40; trial++) {
        sq_metapolygon P;
        sq_metapolygon_init(&P);
        uint32_t first = 5 + rng_below(&r, 4);
        assert_int_equal(sq_metapolygon_extend(&P, first, SQ_NONE, NULL, NULL), SQ_OK);
        uint32_t steps = 1 + rng_below(&r, 5);
        for (uint32_t s = 0; s < steps; s++) {
            uint32_t k = sq_metapolygon_count_corners(&P);
            uint32_t i = 2 + rng_below(&r, 7);
            if (i == 4 || (int)i <= 4 - (int)k) i = 5;
            uint32_t h = P.bnd_he;
            for (uint32_t t = rng_below(&r, P.nbnd); t > 0; t--) h = P.he_next[h];
            assert_int_equal(sq_metapolygon_extend(&P, i, h, NULL, NULL), SQ_OK);
        }
        uint32_t k = sq_metapolygon_count_corners(&P);
        uint32_t vals[] = {2, 3, 5, 6, 9};
        for (uint32_t vi = 0; vi < 5; vi++) {
            uint32_t i = vals[vi];
            if ((int)i <= 4 - (int)k) continue;
            uint32_t def;
            assert_int_equal(sq_metapolygon_default_glue_edge(&P, i, &def, NULL), SQ_OK);
            uint64_t def_cost = sq_metapolygon_predict_quads(&P, i, def);
            uint32_t h = P.bnd_he;
            do {
                uint64_t pred = sq_metapolygon_predict_quads(&P, i, h);
                assert_true(pred >= def_cost);
                sq_metapolygon Q;
                sq_metapolygon_init(&Q);
                assert_int_equal(sq_metapolygon_copy(&Q, &P, NULL), SQ_OK);
                sq_extend_stats es;
                assert_int_equal(sq_metapolygon_extend(&Q, i, h, &es, NULL), SQ_OK);
                assert_int_equal(es.quads_step2 + es.quads_step3, pred);
                assert_int_equal(Q.nf, P.nf + 1 + pred);
                sq_metapolygon_free(&Q);
                edges_checked++;
                h = P.he_next[h];
            } while (h != P.bnd_he);
        }
        sq_metapolygon_free(&P);
    }
    print_message("prediction == extension on %u (metapolygon, valence, edge) triples\n",
                  edges_checked);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_empty_and_single_polygons),
        cmocka_unit_test(test_two_gon_edges_not_endpoints),
        cmocka_unit_test(test_grid_and_copy),
        cmocka_unit_test(test_one_sided_grid_padding),
        cmocka_unit_test(test_validate_catches_corruption),
        cmocka_unit_test(test_preconditions),
        cmocka_unit_test(test_fig4_b_corner_corner),
        cmocka_unit_test(test_fig4_c_two_gon_centred),
        cmocka_unit_test(test_fig4_d_flat_corner),
        cmocka_unit_test(test_fig4_e_two_gon_off_centre),
        cmocka_unit_test(test_fig4_f_flat_flat),
        cmocka_unit_test(test_four_gon_counts_formulas),
        cmocka_unit_test(test_meta_one_gon_count),
        cmocka_unit_test(test_default_edge_is_cheapest_and_prediction_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
