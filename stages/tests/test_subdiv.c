/* Tests of the Catmull-Clark surface (stages/sq_subdiv.h): limit mesh, seam
 * report, STEP and IGES export, the last two checked by an independent CAD
 * kernel (OpenCASCADE, stages/tests/occt_check.cpp) on a cube and on the
 * QuadriFlow quad meshes of ../shared/data/quads. */
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

#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_osd_adapter.h"
#include "sq_subdiv.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static const char *shared_dir(void)
{
    const char *s = getenv("SQ_SHARED_DIR");
    return s && *s ? s : SQ_SHARED_DIR;
}

/* The cube [-1,1]^3 as 6 outward quads. */
static void cube_soup(sq_soup *s)
{
    static const double P[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    static const uint32_t F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    memset(s, 0, sizeof *s);
    s->nv = 8;
    s->nf = 6;
    s->pos = malloc(sizeof P);
    s->face_off = malloc(7 * sizeof(uint32_t));
    s->face_idx = malloc(24 * sizeof(uint32_t));
    assert_non_null(s->pos);
    assert_non_null(s->face_off);
    assert_non_null(s->face_idx);
    memcpy(s->pos, P, sizeof P);
    for (uint32_t f = 0; f <= 6; f++) s->face_off[f] = 4 * f;
    memcpy(s->face_idx, F, sizeof F);
}

static void load_quads(const char *name, sq_soup *soup, sq_mesh *mesh)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/data/quads/%s", shared_dir(), name);
    sq_error err;
    sq_status st = sq_read_mesh(path, soup, &err);
    if (st) fail_msg("%s: %s", path, err.msg);
    st = sq_mesh_from_soup(soup, SQ_MESH_ALLOW_POLYGONS, mesh, &err);
    if (st) fail_msg("%s: %s", path, err.msg);
}

/* Limit mesh: watertight closed quad mesh (Euler characteristic of the
 * input), unit normals, base vertices at the same limit point at every
 * level, and points close to the control mesh's hull. */
static void check_limit_mesh(const sq_subdiv *s, const sq_mesh *m, int level)
{
    sq_limit_mesh lm, lm0;
    sq_error err;
    assert_int_equal(sq_subdiv_limit_mesh(s, m, level, &lm, &err), SQ_OK);
    assert_int_equal(sq_subdiv_limit_mesh(s, m, 0, &lm0, &err), SQ_OK);
    uint32_t n = 1u << level;
    assert_int_equal(lm.nq, m->nf * n * n);
    /* every undirected edge used exactly twice, in opposite directions */
    sq_soup ls = {0};
    ls.nv = lm.nv;
    ls.pos = lm.pos;
    ls.nf = lm.nq;
    ls.face_idx = lm.quads;
    ls.face_off = malloc(((size_t)lm.nq + 1) * sizeof(uint32_t));
    assert_non_null(ls.face_off);
    for (uint32_t q = 0; q <= lm.nq; q++) ls.face_off[q] = 4 * q;
    sq_mesh lmesh;
    sq_status st = sq_mesh_from_soup(&ls, SQ_MESH_ALLOW_POLYGONS, &lmesh, &err);
    if (st) fail_msg("limit mesh invalid: %s", err.msg);
    assert_int_equal(sq_mesh_euler(&lmesh), sq_mesh_euler(m));
    sq_mesh_free(&lmesh);
    free(ls.face_off);
    for (uint32_t v = 0; v < lm.nv; v++) {
        const double *nn = lm.nrm + 3 * (size_t)v;
        double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        assert_true(fabs(l - 1.0) < 1e-9);
        for (int c = 0; c < 3; c++) assert_true(isfinite(lm.pos[3 * (size_t)v + c]));
    }
    for (uint32_t v = 0; v < m->nv; v++)
        for (int c = 0; c < 3; c++)
            assert_true(lm.pos[3 * (size_t)v + c] == lm0.pos[3 * (size_t)v + c]);
    sq_limit_mesh_free(&lm);
    sq_limit_mesh_free(&lm0);
}

/* Writes the STEP and IGES files and the reference samples (OpenSubdiv's
 * evaluation of each patch at its own parameters), runs the OpenCASCADE
 * checker on both and asserts: valid shape, one B-spline face per patch,
 * samples on the limit surface within 1e-9 of the bounding-box diagonal. */
static void check_cad(const sq_subdiv *s, const char *tag, int with_step)
{
#ifndef SQ_OCCT_CHECK
    (void)s;
    (void)tag;
    (void)with_step;
    fail_msg("built without the OpenCASCADE checker");
#else
    char dir[] = "/tmp/sq_subdiv_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char step[256], iges[256], samples[256], cmd[2048];
    snprintf(step, sizeof step, "%s/%s.step", dir, tag);
    snprintf(iges, sizeof iges, "%s/%s.igs", dir, tag);
    snprintf(samples, sizeof samples, "%s/%s.samples", dir, tag);
    sq_error err;
    assert_int_equal(sq_cad_write_step(step, tag, s->np, s->cv, s->bbox_diag, &err), SQ_OK);
    assert_int_equal(sq_cad_write_iges(iges, tag, s->np, s->cv, s->bbox_diag, &err), SQ_OK);
    FILE *fp = fopen(samples, "w");
    assert_non_null(fp);
    static const double T[5] = {0.0, 0.25, 0.5, 0.8, 1.0};
    for (uint32_t p = 0; p < s->np; p++) {
        const double *d = s->patch_dom + 4 * (size_t)p;
        for (int b = 0; b < 5; b++)
            for (int a = 0; a < 5; a++) {
                double P[3];
                sq_osd_eval(s->osd, s->patch_face[p], p, d[0] + T[a] * (d[2] - d[0]),
                            d[1] + T[b] * (d[3] - d[1]), P, NULL, NULL);
                fprintf(fp, "%u %.17g %.17g %.17g %.17g %.17g\n", p, T[a], T[b], P[0], P[1], P[2]);
            }
    }
    assert_int_equal(fclose(fp), 0);
    const char *files[2] = {step, iges};
    for (int k = with_step ? 0 : 1; k < 2; k++) {
        snprintf(cmd, sizeof cmd, "ASAN_OPTIONS=detect_leaks=0 '%s' '%s' '%s'", SQ_OCCT_CHECK,
                 files[k], samples);
        FILE *pp = popen(cmd, "r");
        assert_non_null(pp);
        char fmt[16] = "", line[512];
        unsigned long faces = 0, nsamp = 0, badidx = 1;
        int valid = 0, bspline = 0;
        double dev = INFINITY;
        int got = 0;
        while (fgets(line, sizeof line, pp))
            if (!strncmp(line, "format ", 7))
                got = sscanf(line, "format %15s faces %lu valid %d bspline %d samples %lu bad_index %lu "
                             "max_dev %lf",
                             fmt, &faces, &valid, &bspline, &nsamp, &badidx, &dev);
        int rc = pclose(pp);
        printf("%s %s: %lu faces (%u patches), valid %d, %d B-spline, %lu samples, max deviation "
               "%.3e (%.3e of the diagonal)\n",
               tag, fmt, faces, s->np, valid, bspline, nsamp, dev, dev / s->bbox_diag);
        assert_int_equal(got, 7);
        assert_int_equal(rc, 0);
        assert_int_equal(faces, s->np);
        assert_int_equal(valid, 1);
        assert_int_equal(bspline, (int)s->np);
        assert_int_equal(nsamp, 25 * (unsigned long)s->np);
        assert_int_equal(badidx, 0);
        assert_true(dev <= 1e-9 * s->bbox_diag);
    }
    unlink(step);
    unlink(iges);
    unlink(samples);
    rmdir(dir);
#endif
}

static void check_seams(const sq_subdiv *s, const sq_mesh *m, const char *tag)
{
    sq_subdiv_seams r;
    sq_error err;
    assert_int_equal(sq_subdiv_seam_report(s, m, 8, &r, &err), SQ_OK);
    printf("%s: %u patches, gap max %.3e (rel %.3e), normal jump max %.4f deg, mean %.5f deg, "
           "away from end caps %.3e deg\n",
           tag, s->np, r.max_gap, r.max_gap_rel, r.max_normal_deg, r.mean_normal_deg,
           r.max_normal_regular_deg);
    assert_true(r.points == (uint64_t)s->np * 4 * 9);
    assert_true(r.max_gap_rel < 1e-12);
    assert_true(r.max_normal_regular_deg < 1e-6);
    assert_true(r.max_normal_deg < 10.0);
}

static void test_cube(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh mesh;
    sq_subdiv s;
    sq_error err;
    cube_soup(&soup);
    assert_int_equal(sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &mesh, &err), SQ_OK);
    assert_int_equal(sq_subdiv_build(&mesh, 4, &s, &err), SQ_OK);
    /* every face touches 4 valence-3 vertices: isolated to level 4 */
    assert_true(s.np > 6 * 4 * 4);
    /* the surface is symmetric: the limit point of face centres lies on the
     * axes, at the same distance for all six faces; corners likewise */
    double c0[3], r0 = 0;
    for (uint32_t f = 0; f < 6; f++) {
        double P[3], N[3];
        sq_subdiv_eval(&s, f, 0.5, 0.5, P, N);
        double r = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
        if (f == 0) {
            r0 = r;
            memcpy(c0, P, sizeof c0);
        }
        assert_true(fabs(r - r0) < 1e-12);
        /* normal = the axis direction = P/|P| */
        for (int c = 0; c < 3; c++) assert_true(fabs(N[c] - P[c] / r) < 1e-12);
        assert_true(r < 1.0 && r > 0.5);
    }
    /* the corners: the exact limit of a valence-n vertex of a quad mesh is
     * (n^2 v + 4 sum e + sum d) / (n (n + 5)) (e: edge neighbours, d:
     * diagonal neighbours); for the cube corner (1,1,1), per coordinate
     * (9*1 + 4*(1+1-1) + (1-1-1)) / 24 = 1/2. OpenSubdiv's B-spline end
     * caps interpolate the limit point at the extraordinary vertex. */
    for (uint32_t f = 0; f < 6; f++)
        for (int k = 0; k < 4; k++) {
            double P[3];
            sq_subdiv_eval(&s, f, k == 1 || k == 2, k >= 2, P, NULL);
            for (int c = 0; c < 3; c++) assert_true(fabs(fabs(P[c]) - 0.5) < 1e-14);
        }
    check_limit_mesh(&s, &mesh, 3);
    check_seams(&s, &mesh, "cube");
    check_cad(&s, "cube", 1);
    sq_subdiv_free(&s);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

/* OpenCASCADE's STEP reader needs about a minute for 6K faces: the STEP
 * check runs on one real mesh, the IGES check on all. */
static void run_quads(const char *name, int isolation, int with_step)
{
    sq_soup soup = {0};
    sq_mesh mesh = {0};
    sq_subdiv s;
    sq_error err;
    load_quads(name, &soup, &mesh);
    assert_int_equal(sq_subdiv_build(&mesh, isolation, &s, &err), SQ_OK);
    assert_true(s.np >= mesh.nf);
    check_limit_mesh(&s, &mesh, 2);
    check_seams(&s, &mesh, name);
    check_cad(&s, name, with_step);
    sq_subdiv_free(&s);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static void test_bunny(void **state)
{
    (void)state;
#ifdef __SANITIZE_ADDRESS__
    /* OpenCASCADE's minute on the STEP file is not our code: the sanitizer
     * build checks the STEP writer on the cube, the bunny's IGES here */
    run_quads("bunny_quadriflow5k.obj", 3, 0);
#else
    run_quads("bunny_quadriflow5k.obj", 3, 1);
#endif
}

static void test_3holes(void **state)
{
    (void)state;
    run_quads("3holes_quadriflow5k.obj", 2, 0);
}

/* One Catmull-Clark step of a quad mesh: 4x the quads, same Euler
 * characteristic, a valid closed mesh, and the same limit surface. */
static void test_refine(void **state)
{
    (void)state;
    sq_soup soup, ref;
    sq_mesh mesh, rmesh;
    sq_subdiv s, rs;
    sq_error err;
    cube_soup(&soup);
    assert_int_equal(sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &mesh, &err), SQ_OK);
    assert_int_equal(sq_subdiv_refine(&soup, 1, &ref, &err), SQ_OK);
    assert_int_equal(ref.nf, 24);
    assert_int_equal(ref.nv, 26);
    assert_int_equal(sq_mesh_from_soup(&ref, SQ_MESH_ALLOW_POLYGONS, &rmesh, &err), SQ_OK);
    assert_int_equal(sq_mesh_euler(&rmesh), 2);
    assert_int_equal(sq_subdiv_build(&mesh, 6, &s, &err), SQ_OK);
    assert_int_equal(sq_subdiv_build(&rmesh, 5, &rs, &err), SQ_OK);
    /* the refined mesh's vertex 0..7 are the cube corners: same limit */
    double a[3], b[3];
    sq_subdiv_eval(&s, 0, 0.0, 0.0, a, NULL);
    for (uint32_t v = 0; v < 8; v++) {
        uint32_t h = rmesh.v_he[v], f = rmesh.he_face[h], k = h - 4 * f;
        static const double U[4] = {0, 1, 1, 0}, V[4] = {0, 0, 1, 1};
        sq_subdiv_eval(&rs, f, U[k], V[k], b, NULL);
        for (int c = 0; c < 3; c++) assert_true(fabs(fabs(a[c]) - fabs(b[c])) < 1e-12);
    }
    sq_subdiv_free(&s);
    sq_subdiv_free(&rs);
    sq_mesh_free(&mesh);
    sq_mesh_free(&rmesh);
    sq_soup_free(&soup);
    sq_soup_free(&ref);
}

/* Errors: non-quad input, bad levels, unwritable output leaves no file. */
static void test_errors(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh mesh;
    sq_subdiv s;
    sq_limit_mesh lm;
    sq_error err;
    cube_soup(&soup);
    assert_int_equal(sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &mesh, &err), SQ_OK);
    assert_int_equal(sq_subdiv_build(&mesh, 0, &s, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_subdiv_build(&mesh, 11, &s, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_subdiv_build(&mesh, 2, &s, &err), SQ_OK);
    assert_int_equal(sq_subdiv_limit_mesh(&s, &mesh, 9, &lm, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_subdiv_limit_mesh(&s, &mesh, -1, &lm, &err), SQ_ERR_ARGUMENT);
    const char *bad = "/nonexistent-dir/x.step";
    assert_int_equal(sq_cad_write_step(bad, "x", s.np, s.cv, 1.0, &err), SQ_ERR_IO);
    assert_int_equal(sq_cad_write_iges("/nonexistent-dir/x.igs", "x", s.np, s.cv, 1.0, &err),
                     SQ_ERR_IO);
    assert_int_equal(sq_cad_write_step("/tmp/x.step", "x", 0, s.cv, 1.0, &err), SQ_ERR_EMPTY);
    assert_int_equal(access(bad, F_OK), -1);
    sq_subdiv_free(&s);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    /* a triangle mesh (tetrahedron) is refused with a message */
    static const double tp[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tf[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    sq_soup t = {0};
    t.nv = 4;
    t.nf = 4;
    t.pos = malloc(sizeof tp);
    t.face_off = malloc(5 * sizeof(uint32_t));
    t.face_idx = malloc(sizeof tf);
    memcpy(t.pos, tp, sizeof tp);
    memcpy(t.face_idx, tf, sizeof tf);
    for (uint32_t f = 0; f <= 4; f++) t.face_off[f] = 3 * f;
    assert_int_equal(sq_mesh_from_soup(&t, 0, &mesh, &err), SQ_OK);
    assert_int_equal(sq_subdiv_build(&mesh, 2, &s, &err), SQ_ERR_POLYGON);
    assert_non_null(strstr(err.msg, "quad"));
    sq_mesh_free(&mesh);
    sq_soup_free(&t);
}

/* The real-number format of STEP and IGES. */
static void test_real_format(void **state)
{
    (void)state;
    char b[32];
    assert_string_equal(sq_cad_real(1.0, b), "1.");
    assert_string_equal(sq_cad_real(-3.0, b), "-3.");
    assert_string_equal(sq_cad_real(0.5, b), "0.5");
    assert_string_equal(sq_cad_real(1e-7, b), "9.9999999999999995E-08");
    assert_string_equal(sq_cad_real(1e20, b), "1.E+20");
    assert_string_equal(sq_cad_real(-0.0, b), "0.");
    assert_true(strtod(sq_cad_real(0.1, b), NULL) == 0.1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_real_format), cmocka_unit_test(test_errors),
        cmocka_unit_test(test_cube),        cmocka_unit_test(test_refine),
        cmocka_unit_test(test_bunny),       cmocka_unit_test(test_3holes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
