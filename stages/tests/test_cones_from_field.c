/* Tests of cones from a cross field (stages/sq_cross_field.h) on the real
 * meshes of ../shared/data: Gauss-Bonnet exact, every valence >= 2,
 * realizable, a sensible cone count (compared with the mpz/ cone files),
 * a cone file that reads back identically; and the repair rules on their
 * own. Counts are printed for the record (docs/cones_from_field.md). */
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

#include "sq_cones.h"
#include "sq_cross_field.h"
#include "sq_io.h"
#include "sq_mesh.h"

static const char *shared_dir(void)
{
    const char *s = getenv("SQ_SHARED_DIR");
    return s && *s ? s : SQ_SHARED_DIR;
}

/* Closed meshes without cones (MANIFEST.tsv; quads/ and the open cid/ ones
 * are left out on purpose). */
static const char *const plain_meshes[] = {
    "libigl/3holes.off", "libigl/bumpy.off", "libigl/bunny.off", "libigl/cheburashka.off",
    "libigl/decimated-knight.off", "libigl/fertility.off", "avaxman/Kitten.off",
    "avaxman/botijo.off", "avaxman/rocker-arm2500.off", "gpjs/torus.obj",
    "gpjs/double-torus.obj", "odedstein/fish_low_resolution.obj",
    "odedstein/skull_low_resolution.obj", "odedstein/spot_low_resolution.obj",
    "odedstein/torus.obj", "nvdiffrec/bob_tri.obj", "vmas/chair.off", "vmas/neptune.off",
    "vmas/pinion.off", "cggs/rolling_stage.off", "cid/elephant.obj",
};

static const char *const mpz_meshes[] = {
    "block", "cup", "eight", "elk", "fandisk", "femur", "fertility_tri", "genus3",
    "helmet", "holes3", "homer", "knot1", "rocker_arm", "sculpt", "trim-star", "twirl",
};

static int load(const char *rel, sq_soup *soup, sq_mesh *mesh)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/data/%s", shared_dir(), rel);
    sq_error err;
    memset(soup, 0, sizeof *soup);
    memset(mesh, 0, sizeof *mesh);
    if (sq_read_mesh(path, soup, &err) != SQ_OK) {
        print_error("cannot read %s: %s\n", path, err.msg);
        return 0;
    }
    if (sq_mesh_from_soup(soup, 0, mesh, &err) != SQ_OK) {
        print_error("invalid mesh %s: %s\n", path, err.msg);
        sq_soup_free(soup);
        return 0;
    }
    return 1;
}

/* Everything a cone set from a field must satisfy; returns the cone count. */
static uint32_t check_cones(const char *name, const sq_mesh *m, const int32_t *valence,
                            const sq_cones_from_field_stats *st)
{
    int64_t sum = 0;
    uint32_t cones = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        sum += 4 - (int64_t)valence[v];
        cones += valence[v] != 4;
        if (valence[v] < 2) fail_msg("%s: vertex %u has valence %d", name, v, (int)valence[v]);
    }
    assert_int_equal(sum, 4 * sq_mesh_euler(m));
    sq_error err;
    assert_int_equal(sq_cones_check_gauss_bonnet(m->nv, valence, sq_mesh_euler(m), &err), SQ_OK);
    if (sq_cones_check_realizable(m->nv, valence, sq_mesh_genus(m), &err) != SQ_OK)
        fail_msg("%s: not realizable: %s", name, err.msg);
    assert_int_equal(cones, st->cones);
    /* a field's singularities are a handful per handle and feature, never
     * a sizeable fraction of the vertices */
    if (cones > 20 + m->nv / 20) fail_msg("%s: %u cones on %u vertices", name, cones, m->nv);
    return cones;
}

static void print_row(const char *name, const sq_mesh *m, const char *align, uint32_t cones,
                      const int32_t *valence, const sq_cones_from_field_stats *st, int theirs)
{
    uint32_t hist[16];
    sq_cones_histogram(m->nv, valence, hist, 16);
    printf("  %-34s %-9s g=%lld F=%-6u raw=%-4u cancelled=%-4u moved=%-2u cones=%-4u", name,
           align, (long long)sq_mesh_genus(m), m->nf, st->raw_singularities, st->cancelled,
           st->moved_units, cones);
    if (theirs >= 0) printf(" mpz=%-4d", theirs);
    printf(" [");
    for (uint32_t k = 0; k < 16; k++)
        if (k != 4 && hist[k]) printf(" %u:%u", k, hist[k]);
    printf(" ] %.2fs\n", st->t_total);
}

static void test_plain_meshes(void **state)
{
    (void)state;
    printf("closed meshes without cones:\n");
    for (size_t i = 0; i < sizeof plain_meshes / sizeof *plain_meshes; i++) {
        sq_soup soup;
        sq_mesh m;
        assert_true(load(plain_meshes[i], &soup, &m));
        int32_t *valence = malloc((size_t)m.nv * sizeof *valence);
        assert_non_null(valence);
        for (int a = 0; a < 2; a++) {
            sq_cones_from_field_options opt;
            sq_cones_from_field_default_options(&opt);
            opt.field.align = a ? SQ_FIELD_SMOOTH : SQ_FIELD_CURVATURE;
            /* the big meshes once (default alignment): they are slow under ASan */
            if (a && m.nf > 60000) continue;
            sq_cones_from_field_stats st;
            sq_error err;
            if (sq_cones_from_field(&m, &opt, valence, &st, &err) != SQ_OK)
                fail_msg("%s: %s", plain_meshes[i], err.msg);
            uint32_t cones = check_cones(plain_meshes[i], &m, valence, &st);
            print_row(plain_meshes[i], &m, a ? "smooth" : "curvature", cones, valence, &st, -1);
        }
        free(valence);
        sq_mesh_free(&m);
        sq_soup_free(&soup);
    }
}

static void test_mpz_meshes(void **state)
{
    (void)state;
    printf("mpz meshes (their cone files come from curvature-aligned parametrizations):\n");
    for (size_t i = 0; i < sizeof mpz_meshes / sizeof *mpz_meshes; i++) {
        char rel[256], cpath[4096];
        snprintf(rel, sizeof rel, "mpz/%s.obj", mpz_meshes[i]);
        snprintf(cpath, sizeof cpath, "%s/data/mpz/%s_Th_hat", shared_dir(), mpz_meshes[i]);
        sq_soup soup;
        sq_mesh m;
        assert_true(load(rel, &soup, &m));
        int32_t *theirs = malloc((size_t)m.nv * sizeof *theirs);
        int32_t *valence = malloc((size_t)m.nv * sizeof *valence);
        assert_non_null(theirs);
        assert_non_null(valence);
        sq_cone_format fmt;
        sq_error err;
        assert_int_equal(sq_cones_read(cpath, m.nv, theirs, &fmt, &err), SQ_OK);
        uint32_t ntheirs = 0;
        for (uint32_t v = 0; v < m.nv; v++) ntheirs += theirs[v] != 4;
        sq_cones_from_field_stats st;
        if (sq_cones_from_field(&m, NULL, valence, &st, &err) != SQ_OK)
            fail_msg("%s: %s", rel, err.msg);
        uint32_t cones = check_cones(rel, &m, valence, &st);
        print_row(rel, &m, "curvature", cones, valence, &st, (int)ntheirs);
        if (cones >= 5 * ntheirs + 20)
            fail_msg("%s: %u cones, theirs %u", rel, cones, ntheirs);
        free(theirs);
        free(valence);
        sq_mesh_free(&m);
        sq_soup_free(&soup);
    }
}

/* The written file reads back as the same valences, in both formats, and
 * a failed write leaves nothing behind. */
static void test_write_roundtrip(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh m;
    assert_true(load("libigl/bumpy.off", &soup, &m));
    int32_t *valence = malloc((size_t)m.nv * sizeof *valence);
    int32_t *back = malloc((size_t)m.nv * sizeof *back);
    assert_non_null(valence);
    assert_non_null(back);
    sq_error err;
    assert_int_equal(sq_cones_from_field(&m, NULL, valence, NULL, &err), SQ_OK);
    char dir[] = "/tmp/sq_cones_test_XXXXXX";
    assert_non_null(mkdtemp(dir));
    for (int list = 0; list < 2; list++) {
        char path[256];
        snprintf(path, sizeof path, "%s/bumpy%s", dir, list ? ".cones" : "_Th_hat");
        assert_int_equal(sq_cones_from_field_write(path, m.nv, valence, list, &err), SQ_OK);
        sq_cone_format fmt;
        assert_int_equal(sq_cones_read(path, m.nv, back, &fmt, &err), SQ_OK);
        assert_int_equal(fmt, list ? SQ_CONES_LIST : SQ_CONES_TH_HAT);
        assert_memory_equal(back, valence, (size_t)m.nv * sizeof *back);
        unlink(path);
    }
    char bad[300];
    snprintf(bad, sizeof bad, "%s/no/such/dir/x.cones", dir);
    assert_int_equal(sq_cones_from_field_write(bad, m.nv, valence, 1, &err), SQ_ERR_IO);
    assert_int_equal(rmdir(dir), 0); /* empty: no temporary file left */
    free(valence);
    free(back);
    sq_mesh_free(&m);
    sq_soup_free(&soup);
}

/* The repair rules on hand-made valences over a real mesh. */
static void test_repair_rules(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh m;
    assert_true(load("odedstein/torus.obj", &soup, &m)); /* genus 1 */
    int32_t *val = malloc((size_t)m.nv * sizeof *val);
    assert_non_null(val);
    sq_error err;
    uint32_t moved;
    int cancelled;
    /* lone 3-5 pair on a torus: cancelled */
    for (uint32_t v = 0; v < m.nv; v++) val[v] = 4;
    val[0] = 3;
    val[m.nv / 2] = 5;
    assert_int_equal(sq_cones_from_field_repair(&m, val, &moved, &cancelled, &err), SQ_OK);
    assert_int_equal(cancelled, 1);
    assert_int_equal(moved, 0);
    for (uint32_t v = 0; v < m.nv; v++) assert_int_equal(val[v], 4);
    /* valence 0 at one vertex, two valence-6 elsewhere: two quarter turns
     * move, the result is admissible and keeps Gauss-Bonnet */
    for (uint32_t v = 0; v < m.nv; v++) val[v] = 4;
    val[5] = 0;
    val[100] = 6;
    val[1000] = 6;
    assert_int_equal(sq_cones_from_field_repair(&m, val, &moved, &cancelled, &err), SQ_OK);
    assert_int_equal(moved, 2);
    assert_int_equal(cancelled, 0);
    assert_int_equal(val[5], 2);
    assert_int_equal(sq_cones_check_realizable(m.nv, val, 1, &err), SQ_OK);
    /* not Gauss-Bonnet: refused */
    val[7] = 3;
    assert_int_equal(sq_cones_from_field_repair(&m, val, NULL, NULL, &err), SQ_ERR_GAUSS_BONNET);
    /* cancellation: a 3 next to a 5 cancels within radius, not beyond */
    for (uint32_t v = 0; v < m.nv; v++) val[v] = 4;
    uint32_t a = 0, b = m.he_vert[m.he_next[m.v_he[0]]];
    val[a] = 3;
    val[b] = 5;
    uint32_t nc;
    assert_int_equal(sq_cones_from_field_cancel(&m, val, 1e-12, &nc, &err), SQ_OK);
    assert_int_equal(nc, 0);
    assert_int_equal(sq_cones_from_field_cancel(&m, val, 1e30, &nc, &err), SQ_OK);
    assert_int_equal(nc, 1);
    assert_int_equal(val[a], 4);
    assert_int_equal(val[b], 4);
    assert_int_equal(sq_cones_from_field_cancel(&m, val, -1, &nc, &err), SQ_ERR_ARGUMENT);
    free(val);
    sq_mesh_free(&m);
    sq_soup_free(&soup);
}

/* Field indices alone (no repair) already satisfy Gauss-Bonnet exactly,
 * and a rotated copy of the field (every direction turned by the same
 * angle in its face) has the same indices. */
static void test_indices_exact(void **state)
{
    (void)state;
    const char *meshes[] = {"libigl/decimated-knight.off", "gpjs/double-torus.obj",
                            "mpz/helmet.obj"};
    for (size_t i = 0; i < 3; i++) {
        sq_soup soup;
        sq_mesh m;
        assert_true(load(meshes[i], &soup, &m));
        double *u = malloc(2 * (size_t)m.nf * sizeof *u);
        int32_t *idx = malloc((size_t)m.nv * sizeof *idx), *idx2 = malloc((size_t)m.nv * sizeof *idx2);
        assert_true(u && idx && idx2);
        sq_error err;
        assert_int_equal(sq_cross_field(&m, NULL, u, NULL, &err), SQ_OK);
        for (uint32_t f = 0; f < m.nf; f++)
            assert_true(fabs(hypot(u[2 * f], u[2 * f + 1]) - 1) < 1e-12);
        assert_int_equal(sq_cross_field_indices(&m, u, idx, &err), SQ_OK);
        int64_t s = 0;
        for (uint32_t v = 0; v < m.nv; v++) s += idx[v];
        assert_int_equal(s, 4 * sq_mesh_euler(&m));
        double c = cos(0.3), sn = sin(0.3);
        for (uint32_t f = 0; f < m.nf; f++) {
            double x = u[2 * f], y = u[2 * f + 1];
            u[2 * f] = c * x - sn * y;
            u[2 * f + 1] = sn * x + c * y;
        }
        assert_int_equal(sq_cross_field_indices(&m, u, idx2, &err), SQ_OK);
        assert_memory_equal(idx, idx2, (size_t)m.nv * sizeof *idx);
        free(u);
        free(idx);
        free(idx2);
        sq_mesh_free(&m);
        sq_soup_free(&soup);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_indices_exact),
        cmocka_unit_test(test_repair_rules),
        cmocka_unit_test(test_write_roundtrip),
        cmocka_unit_test(test_mpz_meshes),
        cmocka_unit_test(test_plain_meshes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
