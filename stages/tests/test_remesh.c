/* Tests of the pipeline driver (stages/sq_remesh.h) on examples/cube.obj and
 * mpz/eight:
 *  - cones from the cross field and given cones: a closed pure-quad mesh
 *    whose every vertex has valence 4 except the cones (each with its
 *    valence), Euler characteristic V - E + F equal to the input's, the
 *    quad count within 5% of the target, no folded quad left, no two of
 *    its triangles intersecting (the verify stage's count), every stage
 *    timed, the progress reported from 0 to 1 in order;
 *  - the kept maps: by default the map on the mesh itself (exact, the
 *    input's faces, mean conformal ratio below 1.3 before and after the
 *    optimizer); with SQ_REMESH_PARAM_ALWAYS param's map exact (integer), the
 *    optimized map exact and less distorted, the integer-grid map exact and
 *    integer;
 *  - bad arguments and unrealizable cones fail with the stage named and
 *    nothing returned. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_remesh.h"

#ifndef SQ_SOURCE_DIR
#define SQ_SOURCE_DIR "."
#endif

static const char *shared_dir(void)
{
    const char *s = getenv("SQ_SHARED_DIR");
    return s && *s ? s : SQ_SHARED_DIR;
}

static void load(const char *path, sq_soup *soup, sq_mesh *mesh)
{
    sq_error err;
    memset(soup, 0, sizeof *soup);
    memset(mesh, 0, sizeof *mesh);
    if (sq_read_mesh(path, soup, &err) || sq_mesh_from_soup(soup, 0, mesh, &err))
        fail_msg("%s: %s", path, err.msg);
}

typedef struct progress_log {
    double last;
    int calls, backwards;
} progress_log;

static void on_progress(void *user, const char *stage, double fraction)
{
    (void)stage;
    progress_log *p = user;
    if (fraction < p->last - 1e-12 || fraction < 0 || fraction > 1 + 1e-12) p->backwards++, print_message("progress %s %.17g after %.17g\n", stage, fraction, p->last);
    p->last = fraction;
    p->calls++;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* The quad mesh's structure: valences, Euler characteristic, closedness
 * (every directed edge once, its twin once). */
static void check_quads(const sq_mesh *m, const sq_remesh_result *R, double target)
{
    const sq_quad_mesh *Q = &R->quads;
    assert_true(Q->nq > 0);
    assert_true(fabs((double)Q->nq - target) <= 0.05 * target);
    int32_t *val = calloc(Q->nv, sizeof *val);
    assert_non_null(val);
    for (uint32_t q = 0; q < 4 * Q->nq; q++) val[Q->quad[q]]++;
    uint32_t cones = 0;
    for (uint32_t v = 0; v < m->nv; v++) cones += R->valence[v] != 4;
    uint32_t irregular = 0;
    for (uint32_t v = 0; v < Q->nv; v++) {
        assert_int_equal(val[v], Q->valence[v]);
        if (val[v] != 4) irregular++;
    }
    assert_int_equal(irregular, cones);
    /* every input cone is a quad vertex of its valence (a grid point at the
     * mesh vertex) */
    for (uint32_t v = 0; v < Q->nv; v++)
        if (Q->kind[v] == SQ_GRID_VERTEX && Q->elem[v] < m->nv) assert_int_equal(val[v], R->valence[Q->elem[v]]);
    /* closed: 4 nq directed edges, each with its reverse */
    uint64_t n = 4 * (uint64_t)Q->nq;
    uint64_t *key = malloc(n * sizeof *key);
    assert_non_null(key);
    for (uint32_t q = 0; q < Q->nq; q++)
        for (int c = 0; c < 4; c++)
            key[4 * q + c] = (uint64_t)Q->quad[4 * q + c] << 32 | Q->quad[4 * q + (c + 1) % 4];
    qsort(key, n, sizeof *key, cmp_u64);
    for (uint64_t i = 0; i < n; i++) {
        assert_true(i == 0 || key[i] != key[i - 1]); /* each directed edge once */
        uint64_t rev = key[i] << 32 | key[i] >> 32;
        assert_non_null(bsearch(&rev, key, n, sizeof *key, cmp_u64));
    }
    int64_t chi = (int64_t)Q->nv - (int64_t)(n / 2) + Q->nq;
    assert_int_equal(chi, sq_mesh_euler(m));
    free(key);
    free(val);
}

static void test_cube_field(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh mesh;
    load(SQ_SOURCE_DIR "/examples/cube.obj", &soup, &mesh);
    sq_remesh_options opt;
    memset(&opt, 0, sizeof opt);
    opt.quads = 600;
    progress_log log = {0, 0, 0};
    opt.progress = on_progress;
    opt.user = &log;
    sq_remesh_result R;
    sq_remesh_stats st;
    sq_error err;
    if (sq_remesh(&mesh, NULL, &opt, &R, &st, &err)) fail_msg("%s: %s", st.stage, err.msg);
    assert_true(st.cones_from_field);
    assert_int_equal(st.cones, 8);
    check_quads(&mesh, &R, 600);
    assert_int_equal(st.untangle.folded_after, 0);
    assert_int_equal(st.self_intersections, 0);
    assert_true(st.input_self_intersections == -1);
    assert_true(st.optimize.conformal_after <= st.optimize.conformal_before);
    assert_true(log.calls >= 6 && log.backwards == 0 && fabs(log.last - 1) < 1e-12);
    assert_true(st.t_total >= st.t_param + st.t_optimize + st.t_quantize);
    /* maps are not kept unless asked */
    assert_null(R.map.he_uv);
    assert_null(R.igm.he_uv);
    sq_remesh_result_free(&R);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static void test_eight_kept_maps(void **state)
{
    (void)state;
    char path[4096];
    sq_soup soup;
    sq_mesh mesh;
    sq_error err;
    snprintf(path, sizeof path, "%s/data/mpz/eight.obj", shared_dir());
    load(path, &soup, &mesh);
    int32_t *val = malloc(mesh.nv * sizeof *val);
    assert_non_null(val);
    snprintf(path, sizeof path, "%s/data/mpz/eight_Th_hat", shared_dir());
    if (sq_cones_read(path, mesh.nv, val, NULL, &err)) fail_msg("%s", err.msg);
    sq_remesh_options opt;
    memset(&opt, 0, sizeof opt);
    opt.quads = 2000;
    opt.keep_maps = 1;
    sq_remesh_result R;
    sq_remesh_stats st;
    /* by default the map on the mesh itself: no added vertex, the field's
     * rotations, low distortion before any optimization */
    if (sq_remesh(&mesh, val, &opt, &R, &st, &err)) fail_msg("%s: %s", st.stage, err.msg);
    assert_true(st.map_from_rotations && st.rotations.valid);
    check_quads(&mesh, &R, 2000);
    assert_int_equal(sq_map_check(&R.map, 0, &err), SQ_OK);
    assert_int_equal(R.map.mesh.nf, mesh.nf);
    assert_int_equal(R.optimized.mesh.nf, mesh.nf);
    assert_int_equal(sq_map_check(&R.igm, SQ_MAP_REQUIRE_INTEGER, &err), SQ_OK);
    print_message("eight, map on the mesh: conformal %.4g -> %.4g, %u iterations\n", st.optimize.conformal_before,
                  st.optimize.conformal_after, st.optimize.iterations);
    assert_true(st.optimize.conformal_before < 1.3 && st.optimize.conformal_after < 1.3);
    assert_int_equal(st.param.faces_out, 0); /* param did not run */
    sq_remesh_result_free(&R);
    /* param's map when asked */
    opt.param = SQ_REMESH_PARAM_ALWAYS;
    if (sq_remesh(&mesh, val, &opt, &R, &st, &err)) fail_msg("%s: %s", st.stage, err.msg);
    assert_false(st.map_from_rotations);
    assert_false(st.cones_from_field);
    assert_memory_equal(R.valence, val, mesh.nv * sizeof *val);
    check_quads(&mesh, &R, 2000);
    assert_int_equal(sq_map_check(&R.map, SQ_MAP_REQUIRE_INTEGER, &err), SQ_OK);
    assert_int_equal(sq_map_check(&R.optimized, 0, &err), SQ_OK);
    assert_int_equal(sq_map_check(&R.igm, SQ_MAP_REQUIRE_INTEGER, &err), SQ_OK);
    /* eight's rotations allow a good map: the measured 27.7 -> 1.23 */
    print_message("eight: conformal %.4g -> %.4g (%.4g recomputed), faces %u -> %u in %u rounds\n",
                  st.optimize.conformal_before, st.optimize.conformal_after,
                  sq_map_conformal_mean(&R.optimized), st.optimize.faces_before, st.optimize.faces_after,
                  st.optimize.rounds);
    assert_true(st.optimize.conformal_before > 10 && st.optimize.conformal_after < 1.5);
    assert_true(fabs(sq_map_conformal_mean(&R.optimized) - st.optimize.conformal_after) < 1e-12);
    /* the rounds' simplification: fewer faces, param's map kept as it was */
    assert_true(st.optimize.rounds >= 1 && st.optimize.removed > 0);
    assert_int_equal(st.optimize.faces_after, R.optimized.mesh.nf);
    assert_int_equal(st.optimize.faces_before, R.map.mesh.nf);
    assert_int_equal(st.optimize.faces_before - st.optimize.faces_after, 2 * st.optimize.removed);
    sq_remesh_result_free(&R);
    free(val);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static void test_failures(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh mesh;
    load(SQ_SOURCE_DIR "/examples/cube.obj", &soup, &mesh);
    sq_remesh_options opt;
    memset(&opt, 0, sizeof opt);
    sq_remesh_result R;
    sq_remesh_stats st;
    sq_error err;
    opt.quads = 100, opt.edge_length = 0.1;
    assert_int_equal(sq_remesh(&mesh, NULL, &opt, &R, &st, &err), SQ_ERR_ARGUMENT);
    assert_null(R.quads.quad);
    assert_null(R.valence);
    opt.edge_length = 0;
    int32_t *val = malloc(mesh.nv * sizeof *val);
    assert_non_null(val);
    for (uint32_t v = 0; v < mesh.nv; v++) val[v] = 4;
    /* genus 0 needs sum (4 - k) = 8: one valence 1 (3) and five valence 3 */
    val[0] = 1;
    for (uint32_t v = 1; v <= 5; v++) val[v] = 3;
    sq_status s = sq_remesh(&mesh, val, &opt, &R, &st, &err);
    assert_int_equal(s, SQ_ERR_UNREALIZABLE);
    assert_string_equal(st.stage, "cones");
    assert_non_null(strstr(err.msg, "valence 1"));
    assert_null(R.quads.quad);
    assert_null(R.valence);
    /* Gauss-Bonnet */
    val[0] = 4;
    s = sq_remesh(&mesh, val, &opt, &R, &st, &err);
    assert_int_equal(s, SQ_ERR_GAUSS_BONNET);
    assert_string_equal(st.stage, "cones");
    free(val);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube_field),
        cmocka_unit_test(test_eight_kept_maps),
        cmocka_unit_test(test_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
