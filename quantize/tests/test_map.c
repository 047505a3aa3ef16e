/* Tests of sq_map (quantize/sq_map*.c) on the published maps of
 * shared/data/mpz (the vt of each OBJ, seamless up to about 1e-13):
 *  - every one is made exact: sq_map_check passes, every UV moved by a few
 *    grid units at most, the transitions reproduce both sides of every edge
 *    exactly, the cones are those of the *_Th_hat file; written and read
 *    back with SQ_MAP_REQUIRE_EXACT, bit for bit;
 *  - the same maps are refused with SQ_MAP_REQUIRE_EXACT (they are not
 *    exact as published);
 *  - bad maps: a flipped UV triangle, missing vt, a seam that is no
 *    rotation plus translation, another mesh, other cones, a non-integer
 *    map where an integer one is required: each refused with its message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "sq_test_model.h"

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_map.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static const char *MODELS[] = {"block",  "cup",       "eight",  "elk",        "fandisk", "femur",
                               "fertility_tri", "genus3", "helmet", "holes3", "homer",
                               "knot1",  "rocker_arm", "sculpt", "trim-star", "twirl"};
#define NMODELS (sizeof MODELS / sizeof MODELS[0])


static void test_published_maps_made_exact(void **state)
{
    (void)state;
    char tmpdir[] = "/tmp/sq_test_map_XXXXXX";
    assert_non_null(mkdtemp(tmpdir));
    for (size_t i = 0; i < NMODELS; i++) {
        model md;
        load(MODELS[i], &md);
        sq_map M;
        sq_map_report rep;
        sq_error err;
        sq_status st = sq_map_from_soup(&md.soup, &md.mesh, md.valence, 1e-9, 0, &M, &rep, &err);
        if (st) fail_msg("%s: %s", MODELS[i], err.msg);
        assert_true(rep.grid > 0);
        assert_true(rep.max_seam_error > 0 && rep.max_seam_error < 1e-11);
        uint32_t cones = 0;
        for (uint32_t v = 0; v < md.mesh.nv; v++) {
            cones += md.valence[v] != 4;
            assert_int_equal(M.valence[v], md.valence[v]);
        }
        assert_int_equal(rep.cones, cones);
        assert_true(rep.seam_curves > 0 && rep.seam_edges >= rep.seam_curves);
        /* every UV within a few grid units of the published one */
        double worst = 0;
        for (uint32_t h = 0; h < M.mesh.nh; h++)
            for (int k = 0; k < 2; k++) {
                double d = fabs(M.he_uv[2 * h + k] - md.soup.uv[2 * md.soup.face_uv[h] + k]);
                if (d > worst) worst = d;
            }
        if (!(worst <= 8 * rep.grid)) fail_msg("%s: a UV moved by %g (grid %g)", MODELS[i], worst, rep.grid);
        assert_int_equal(sq_map_check(&M, 0, &err), SQ_OK);
        /* the published map itself is not exact */
        sq_map X;
        assert_int_equal(sq_map_from_soup(&md.soup, &md.mesh, md.valence, 1e-9,
                                          SQ_MAP_REQUIRE_EXACT, &X, NULL, &err),
                         SQ_ERR_ARGUMENT);
        assert_non_null(strstr(err.msg, "not exact"));
        /* round trip: written and read back as an exact map, bit for bit */
        char path[600];
        snprintf(path, sizeof path, "%s/%s.obj", tmpdir, MODELS[i]);
        assert_int_equal(sq_map_write_obj(path, &M, &err), SQ_OK);
        st = sq_map_read(path, &md.mesh, md.valence, 1e-9, SQ_MAP_REQUIRE_EXACT, &X, &rep, &err);
        if (st) fail_msg("%s read back: %s", MODELS[i], err.msg);
        assert_int_equal(rep.grid, 0.0);
        for (uint32_t k = 0; k < 2 * M.mesh.nh; k++) { /* values: -0.0 == 0.0 */
            assert_true(X.he_uv[k] == M.he_uv[k]);
            assert_true(X.he_t[k] == M.he_t[k]);
        }
        assert_memory_equal(X.he_rot, M.he_rot, M.mesh.nh);
        /* not an integer-grid map */
        assert_int_not_equal(sq_map_check(&M, SQ_MAP_REQUIRE_INTEGER, &err), SQ_OK);
        unlink(path);
        sq_map_free(&X);
        sq_map_free(&M);
        unload(&md);
    }
    rmdir(tmpdir);
}

static void expect_refused(model *md, const sq_mesh *input, const int32_t *valence, sq_status code,
                           const char *needle)
{
    sq_map M;
    sq_error err;
    sq_status st = sq_map_from_soup(&md->soup, input, valence, 1e-9, 0, &M, NULL, &err);
    if (st != code) fail_msg("expected status %d, got %d: %s", code, st, err.msg);
    if (!strstr(err.msg, needle)) fail_msg("message '%s' lacks '%s'", err.msg, needle);
}

static void test_bad_maps(void **state)
{
    (void)state;
    model md, other;
    load("eight", &md);
    load("knot1", &other);
    /* a flipped UV triangle: two corners of face 10 swap their vt */
    uint32_t *fu = md.soup.face_uv, c = md.soup.face_off[10], keep = fu[c];
    fu[c] = fu[c + 1], fu[c + 1] = keep;
    expect_refused(&md, &md.mesh, md.valence, SQ_ERR_DEGENERATE, "flipped");
    fu[c + 1] = fu[c], fu[c] = keep;
    /* a seam point moved: no rotation plus translation relates the sides
     * (or the angle sums break first) */
    {
        sq_map M;
        sq_map_report rep;
        sq_error err;
        assert_int_equal(sq_map_from_soup(&md.soup, &md.mesh, md.valence, 1e-9, 0, &M, &rep, &err),
                         SQ_OK);
        /* find a seam corner: an edge whose transition is not the identity */
        uint32_t h = 0;
        while (h < M.mesh.nh && M.he_rot[h] == 0 && M.he_t[2 * h] == 0 && M.he_t[2 * h + 1] == 0) h++;
        assert_true(h < M.mesh.nh);
        sq_map_free(&M);
        uint32_t t = md.soup.face_uv[h];
        double old = md.soup.uv[2 * t];
        md.soup.uv[2 * t] += 1e-4;
        sq_status st = sq_map_from_soup(&md.soup, &md.mesh, md.valence, 1e-9, 0, &M, NULL, &err);
        assert_int_not_equal(st, SQ_OK);
        if (!strstr(err.msg, "not related by a rotation") && !strstr(err.msg, "angle sum") &&
            !strstr(err.msg, "flipped"))
            fail_msg("unexpected message: %s", err.msg);
        md.soup.uv[2 * t] = old;
    }
    /* a map of another mesh */
    expect_refused(&md, &other.mesh, NULL, SQ_ERR_ARGUMENT, "not a map of the input mesh");
    /* other cones */
    {
        int32_t *val = malloc(md.mesh.nv * sizeof *val);
        memcpy(val, md.valence, md.mesh.nv * sizeof *val);
        uint32_t v = 0;
        while (val[v] == 4) v++;
        val[v] = 4;
        expect_refused(&md, &md.mesh, val, SQ_ERR_CONE_VALUE, "does not have these cones");
        free(val);
    }
    /* no vt at all */
    uint32_t *saved = md.soup.face_uv;
    md.soup.face_uv = NULL;
    expect_refused(&md, NULL, NULL, SQ_ERR_PARSE, "no texture coordinates");
    md.soup.face_uv = saved;
    /* a corner without vt */
    md.soup.face_uv[7] = SQ_NONE;
    expect_refused(&md, NULL, NULL, SQ_ERR_PARSE, "without vt");
    unload(&md);
    unload(&other);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_published_maps_made_exact),
        cmocka_unit_test(test_bad_maps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
