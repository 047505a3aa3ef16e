/* Tests of sq_quantize (quantize/sq_quantize*.c) end to end on the
 * published maps of shared/data/mpz, made exact:
 *  - every model at 1K quads in CI (1K, 5K and 20K with SQ_LONG_TESTS): an
 *    integer-grid map that passes sq_map_check with SQ_MAP_REQUIRE_INTEGER,
 *    a refinement of the map (its first vertices are the map's), the cones
 *    of the *_Th_hat file with their angles, a quad count (UV area) within
 *    5% of the request wherever the request is at least the reported
 *    minimum; extracted (sq_extract) into a quad mesh with as many quads,
 *    whose irregular vertices are exactly the cones (valence k for a cone
 *    of angle k pi/2) and whose Euler characteristic is the mesh's; after
 *    sq_extract_untangle no quad is folded, every vertex is still a
 *    barycentric combination of its face's corners, cones unmoved;
 *  - an integer-grid map quantized with chords along its own integer lines
 *    and the map's lengths as targets gives back its own quad count (param
 *    cannot run here, so the map is the published eight scaled by
 *    quantization itself);
 *  - bad requests: no options, 0 quads, more than 1e8, a negative edge
 *    length: refused without output. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_test_model.h"

#include "sq_cones.h"
#include "sq_extract.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_quantize.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static const char *MODELS[] = {"block", "cup",    "eight", "elk",        "fandisk", "femur",     "fertility_tri",
                               "genus3", "helmet", "holes3", "homer", "knot1", "rocker_arm", "sculpt",
                               "trim-star"};
#define NMODELS (sizeof MODELS / sizeof MODELS[0])

static void load_map(const char *name, sq_map *M)
{
    model md;
    sq_error err;
    load(name, &md);
    sq_status st = sq_map_from_soup(&md.soup, &md.mesh, md.valence, 1e-9, 0, M, NULL, &err);
    if (st) fail_msg("%s: %s", name, err.msg);
    unload(&md);
}

static double uv_area(const sq_map *M)
{
    double a = 0;
    for (uint32_t f = 0; f < M->mesh.nf; f++) {
        uint32_t h = M->mesh.f_he[f], n = M->mesh.he_next[h], p = M->mesh.he_next[n];
        const double *x = M->he_uv + 2 * h, *y = M->he_uv + 2 * n, *z = M->he_uv + 2 * p;
        a += 0.5 * ((y[0] - x[0]) * (z[1] - x[1]) - (y[1] - x[1]) * (z[0] - x[0]));
    }
    return a;
}

static void check_result(const char *name, const sq_map *M, const sq_map *igm, double asked,
                         const sq_quantize_stats *st)
{
    sq_error err;
    if (sq_map_check(igm, SQ_MAP_REQUIRE_INTEGER, &err)) fail_msg("%s: %s", name, err.msg);
    assert_true(igm->mesh.nv >= M->mesh.nv);
    for (uint32_t v = 0; v < M->mesh.nv; v++) {
        assert_memory_equal(igm->mesh.pos + 3 * v, M->mesh.pos + 3 * v, 3 * sizeof(double));
        assert_int_equal(igm->valence[v], M->valence[v]);
    }
    for (uint32_t v = M->mesh.nv; v < igm->mesh.nv; v++) assert_int_equal(igm->valence[v], 4);
    double area = uv_area(igm);
    assert_true(fabs(area - st->quads) < 1e-6 * st->quads);
    if (asked >= st->min_quads && !(fabs(st->quads - asked) <= 0.05 * asked))
        fail_msg("%s: %.0f quads for %.0f asked (minimum %.0f)", name, st->quads, asked, st->min_quads);
    /* the quad mesh */
    sq_quad_mesh Q;
    sq_extract_stats xs;
    sq_status s = sq_extract(igm, &Q, &xs, &err);
    if (s) fail_msg("%s at %.0f: extract: %s", name, asked, err.msg);
    assert_int_equal((double)Q.nq, st->quads);
    uint32_t cones = 0, irregular = 0;
    for (uint32_t v = 0; v < M->mesh.nv; v++) cones += M->valence[v] != 4;
    for (uint32_t p = 0; p < Q.nv; p++) {
        if (Q.valence[p] == 4) continue;
        irregular++;
        /* an irregular quad vertex sits at a cone of that valence */
        assert_int_equal(Q.kind[p], SQ_GRID_VERTEX);
        assert_true(Q.elem[p] < M->mesh.nv);
        assert_int_equal(Q.valence[p], M->valence[Q.elem[p]]);
    }
    assert_int_equal(irregular, cones);
    /* Euler characteristic: V - E + F, E = 2 F for a closed quad mesh */
    int64_t chi = (int64_t)Q.nv - (int64_t)Q.nq;
    assert_int_equal(chi, sq_mesh_euler(&M->mesh));
    /* step 5: no folded quad left, every vertex still on the surface (its
     * position the barycentric combination of its face's corners), cones
     * where they were */
    sq_untangle_stats us;
    assert_int_equal(sq_extract_untangle(igm, &Q, &us, &err), SQ_OK);
    if (us.folded_after) fail_msg("%s at %.0f: %u of %u folded quads left", name, asked, us.folded_after, us.folded_before);
    for (uint32_t p = 0; p < Q.nv; p++) {
        uint32_t h = igm->mesh.f_he[Q.loc_face[p]];
        double x[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++, h = igm->mesh.he_next[h])
            for (int i = 0; i < 3; i++) x[i] += Q.loc_bary[3 * p + k] * igm->mesh.pos[3 * igm->mesh.he_vert[h] + i];
        for (int i = 0; i < 3; i++) assert_true(fabs(x[i] - Q.pos[3 * p + i]) <= 1e-9);
        if (Q.valence[p] != 4)
            assert_memory_equal(Q.pos + 3 * p, igm->mesh.pos + 3 * Q.elem[p], 3 * sizeof(double));
    }
    sq_quad_mesh_free(&Q);
}

static void test_published_maps(void **state)
{
    (void)state;
    int lng = getenv("SQ_LONG_TESTS") != NULL;
    const double sizes[] = {1000, 5000, 20000};
    for (size_t i = 0; i < NMODELS; i++) {
        sq_map M;
        load_map(MODELS[i], &M);
        for (int k = 0; k < (lng ? 3 : 1); k++) {
            sq_quantize_options opt = {sizes[k], 0, SQ_TARGETS_MAP, 0, 0};
            sq_quantize_stats st;
            sq_map igm;
            sq_error err;
            sq_status s = sq_quantize(&M, &opt, &igm, &st, &err);
            if (s) fail_msg("%s at %.0f: %s", MODELS[i], sizes[k], err.msg);
            assert_true(st.faces > 0 && st.arcs > st.faces && st.min_quads >= 1);
            check_result(MODELS[i], &M, &igm, sizes[k], &st);
            sq_map_free(&igm);
        }
        sq_map_free(&M);
    }
}

/* An integer-grid map's own integer lines as chords, its lengths as
 * targets: the same quad count back. The integer-grid map is quantization's
 * own output for eight. */
static void test_integer_map_reproduced(void **state)
{
    (void)state;
    sq_map M, igm, again;
    load_map("eight", &M);
    sq_quantize_options opt = {400, 0, SQ_TARGETS_MAP, 0, 0};
    sq_quantize_stats st;
    sq_error err;
    assert_int_equal(sq_quantize(&M, &opt, &igm, &st, &err), SQ_OK);
    double quads = st.quads;
    uint32_t cap = 1024, n = 0;
    sq_chord *ch = malloc(cap * sizeof *ch);
    for (uint32_t f = 0; f < igm.mesh.nf; f++) {
        uint32_t h = igm.mesh.f_he[f];
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int c = 0; c < 3; c++, h = igm.mesh.he_next[h])
            for (int a = 0; a < 2; a++)
                lo[a] = fmin(lo[a], igm.he_uv[2 * h + a]), hi[a] = fmax(hi[a], igm.he_uv[2 * h + a]);
        for (int a = 0; a < 2; a++)
            for (double c = ceil(lo[a]); c <= hi[a]; c += 1) {
                if (n == cap) cap *= 2, ch = realloc(ch, cap * sizeof *ch);
                ch[n++] = (sq_chord){f, (uint8_t)a, c, -INFINITY, INFINITY};
            }
    }
    sq_quantize_options same = {quads, 0, SQ_TARGETS_MAP, 0, 0};
    sq_status s = sq_quantize_chords(&igm, ch, n, &same, &again, &st, &err);
    if (s) fail_msg("%s", err.msg);
    assert_int_equal(st.faces, (uint32_t)quads); /* every unit square a face */
    assert_true(st.quads == quads);
    assert_int_equal(sq_map_check(&again, SQ_MAP_REQUIRE_INTEGER, &err), SQ_OK);
    free(ch);
    sq_map_free(&again);
    sq_map_free(&igm);
    sq_map_free(&M);
}

static void test_bad_requests(void **state)
{
    (void)state;
    sq_map M, igm;
    load_map("knot1", &M);
    sq_error err;
    const sq_quantize_options bad[] = {{0, 0, SQ_TARGETS_MAP, 0, 0}, {-5, 0, SQ_TARGETS_MAP, 0, 0}, {2e8, 0, SQ_TARGETS_MAP, 0, 0},
                                       {0, -1, SQ_TARGETS_MAP, 0, 0}, {100, 0, 7, 0, 0}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(sq_quantize(&M, &bad[k], &igm, NULL, &err), SQ_ERR_ARGUMENT);
        assert_non_null(strstr(err.msg, "quantize"));
    }
    assert_int_equal(sq_quantize(&M, NULL, &igm, NULL, &err), SQ_ERR_ARGUMENT);
    /* below the minimum: the minimum is built and reported */
    sq_quantize_options tiny = {1, 0, SQ_TARGETS_MAP, 0, 0};
    sq_quantize_stats st;
    assert_int_equal(sq_quantize(&M, &tiny, &igm, &st, &err), SQ_OK);
    assert_true(st.min_quads > 1 && st.quads == st.min_quads);
    sq_map_free(&igm);
    sq_map_free(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_published_maps),
        cmocka_unit_test(test_integer_map_reproduced),
        cmocka_unit_test(test_bad_requests),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
