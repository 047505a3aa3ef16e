/* Seam rotations (docs/holonomy.md) on real maps:
 *  - the smooth cross field's rotations (sq_cone_connection) are those of
 *    the published field-aligned maps of ../shared/data/mpz (the `vt` of
 *    the OBJ files) around every loop, on the eight models where the
 *    issue's measurements found the published rotations best;
 *  - param's maps, built on the steered cut graph, have the field's
 *    rotations around every loop: on mpz/holes3, cup, sculpt, block and
 *    knot1 (genus 1: steered after the domain's alignment, which decides
 *    its straight corners), whose unsteered maps had other rotations (min
 *    Ec/Ed 10 to 28 times the published map's, ../shared/tools/holonomy).
 * Two maps have the same rotations around every loop iff, with a face
 * tree, the per-edge difference of their transition rotations sums to 0
 * mod 4 over every edge's fundamental loop; this is checked edge by edge. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_cone_connection.h"
#include "sq_cones.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_mesh.h"
#include "sq_param.h"
#include "sq_remesh.h"
#include "sq_remesh_internal.h"
#include "sq_test_potentials.h"

static const char *shared_dir(void)
{
    const char *s = getenv("SQ_SHARED_DIR");
    return s && *s ? s : SQ_SHARED_DIR;
}

/* Edges whose fundamental loop (in a face tree) turns differently in the
 * map (he_rot) and in the connection (turn). 0: same rotations around
 * every loop. */
static uint32_t rotation_disagreements(const sq_map *M, const double *turn)
{
    const sq_mesh *m = &M->mesh;
    double *phi = malloc((size_t)m->nf * sizeof *phi), *diff = malloc((size_t)m->nh * sizeof *diff);
    assert_true(phi && diff);
    for (uint32_t h = 0; h < m->nh; ++h) diff[h] = turn[h] - (double)M->he_rot[h];
    sq_test_face_potentials(m, diff, phi);
    uint32_t bad = 0;
    for (uint32_t h = 0; h < m->nh; ++h) {
        if (h > m->he_twin[h]) continue;
        double d = (phi[m->he_face[h]] + diff[h] - phi[m->he_face[m->he_twin[h]]]) / 4.0;
        d -= nearbyint(d);
        if (fabs(d) > 1e-6) ++bad;
    }
    free(phi), free(diff);
    return bad;
}

static uint32_t map_vs_field(const sq_map *M, const char *what)
{
    double *turn = malloc((size_t)M->mesh.nh * sizeof *turn);
    assert_non_null(turn);
    sq_error err;
    if (sq_cone_connection(&M->mesh, M->valence, turn, NULL, &err)) fail_msg("%s: %s", what, err.msg);
    const uint32_t bad = rotation_disagreements(M, turn);
    free(turn);
    return bad;
}

static void test_field_matches_published(void **state)
{
    (void)state;
    static const char *models[] = {"eight", "trim-star", "holes3", "cup", "sculpt", "knot1", "block", "femur"};
    for (size_t i = 0; i < sizeof models / sizeof *models; ++i) {
        char path[512];
        snprintf(path, sizeof path, "%s/data/mpz/%s.obj", shared_dir(), models[i]);
        sq_map M;
        sq_error err;
        if (sq_map_read(path, NULL, NULL, 1e-9, 0, &M, NULL, &err)) fail_msg("%s: %s", models[i], err.msg);
        const uint32_t bad = map_vs_field(&M, models[i]);
        print_message("%-10s published map vs field: %u edges whose loop turns differently\n", models[i], bad);
        if (bad) fail_msg("%s: the field's rotations differ from the published map's", models[i]);
        sq_map_free(&M);
    }
}

static void test_param_has_field_rotations(void **state)
{
    (void)state;
    static const char *models[] = {"holes3", "cup", "sculpt", "block", "knot1"};
    for (size_t i = 0; i < sizeof models / sizeof *models; ++i) {
        char path[512], cpath[512];
        snprintf(path, sizeof path, "%s/data/mpz/%s.obj", shared_dir(), models[i]);
        snprintf(cpath, sizeof cpath, "%s/data/mpz/%s_Th_hat", shared_dir(), models[i]);
        sq_soup soup;
        sq_mesh m;
        sq_error err;
        memset(&soup, 0, sizeof soup);
        if (sq_read_mesh(path, &soup, &err) || sq_mesh_from_soup(&soup, 0, &m, &err)) fail_msg("%s", err.msg);
        int32_t *val = malloc((size_t)m.nv * sizeof *val);
        assert_non_null(val);
        if (sq_cones_read(cpath, m.nv, val, NULL, &err)) fail_msg("%s", err.msg);
        sq_param_options po;
        sq_param_options_default(&po);
        sq_param P;
        sq_param_stats ps;
        if (sq_param_build(&m, val, &po, &P, &ps, &err)) fail_msg("%s: param: %s", models[i], err.msg);
        sq_map M;
        if (sq_param_map(&P, &m, val, &M, &err)) fail_msg("%s: map: %s", models[i], err.msg);
        const uint32_t bad = map_vs_field(&M, models[i]);
        print_message("%-10s param: mismatch %u -> %u (%u reroutes); map vs field: %u edges\n", models[i],
                      ps.rot_mismatch_before, ps.rot_mismatch_after, ps.rot_reroutes, bad);
        assert_int_equal(ps.rot_mismatch_after, 0);
        if (bad) fail_msg("%s: param's map does not have the field's rotations", models[i]);
        sq_map_free(&M);
        sq_param_free(&P);
        free(val);
        sq_mesh_free(&m);
        sq_soup_free(&soup);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_field_matches_published),
        cmocka_unit_test(test_param_has_field_rotations),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
