/* seamquad: tests of sq_param_simplify (seamless/param/sq_param_simplify.c) on
 * real maps: mpz/eight (the overlay's map, step 7') and mpz/genus3 (the
 * cells' map, steps 6-7), each built with SQ_SIMPLIFY_OFF and with the
 * default (simplified). The simplified map must:
 *  - pass sq_param_verify (integer grid map) and the referee;
 *  - keep the input vertices first, bit for bit; its added vertices and
 *    its UV points must be subsequences of the unsimplified map's (nothing
 *    moves, orders are kept);
 *  - have every triangle inside its input face (tri_in), oriented like it,
 *    and the triangles of each input face must add up to its area (no
 *    overlap, no gap); the UV area must be the unsimplified map's;
 *  - keep the seam edges' count, have fewer faces, and a worst conformal
 *    ratio no larger;
 *  - be a fixed point: simplifying it again removes nothing.
 * Its picture of the cut on the surface (sq_param_write_cut_svg) shows
 * every cone in each of its three views. Bad calls (no tri_in, another
 * mesh) are refused. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "sq_param.h"
#include "sq_test_mesh.h"
#include "sq_seamless_svg.h"

static void sub(const double *a, const double *b, double *r)
{
    r[0] = a[0] - b[0], r[1] = a[1] - b[1], r[2] = a[2] - b[2];
}
static void crs(const double *a, const double *b, double *r)
{
    r[0] = a[1] * b[2] - a[2] * b[1], r[1] = a[2] * b[0] - a[0] * b[2], r[2] = a[0] * b[1] - a[1] * b[0];
}
static double dt(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void input_face(const sq_mesh *m, uint32_t f, const double **p)
{
    uint32_t h = m->f_he[f];
    for (int i = 0; i < 3; i++, h = m->he_next[h]) p[i] = m->pos + 3 * (size_t)m->he_vert[h];
}

static double uv_area(const sq_param *P)
{
    double a = 0;
    for (uint32_t f = 0; f < P->nf; f++) {
        const double *u = P->uv + 2 * (size_t)P->tri_uv[3 * f], *v = P->uv + 2 * (size_t)P->tri_uv[3 * f + 1],
                     *w = P->uv + 2 * (size_t)P->tri_uv[3 * f + 2];
        a += 0.5 * ((v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0]));
    }
    return a;
}

/* 1 iff the n2 items of b (size each) appear in a (n1 items) in order */
static int subsequence(const void *a, size_t n1, const void *b, size_t n2, size_t size)
{
    size_t i = 0;
    for (size_t k = 0; k < n2; k++) {
        while (i < n1 && memcmp((const char *)a + i * size, (const char *)b + k * size, size)) i++;
        if (i == n1) return 0;
        i++;
    }
    return 1;
}

static void referee_passes(const char *mesh, const char *cones, const sq_param *P)
{
    sq_error err = {0};
    char obj[] = "/tmp/sq_test_simplify_XXXXXX";
    int fd = mkstemp(obj);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(sq_param_write_obj(obj, P, &err), SQ_OK);
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "python3 %s/tools/check_param.py %s %s %s --integer > %s.ref 2>&1", SQ_SHARED_DIR,
             mesh, cones, obj, obj);
    int r = system(cmd);
    char ref[600];
    snprintf(ref, sizeof ref, "%s.ref", obj);
    FILE *f = fopen(ref, "rb");
    char buf[4096] = {0};
    if (f) {
        size_t n = fread(buf, 1, sizeof buf - 1, f);
        buf[n] = 0;
        fclose(f);
    }
    remove(obj), remove(ref);
    if (!WIFEXITED(r) || WEXITSTATUS(r) != 0) fail_msg("referee:\n%s", buf);
    assert_non_null(strstr(buf, "check_param: PASS"));
}

static void check_model(const char *rel, int want_overlay)
{
    char mesh[512], cones[512];
    snprintf(mesh, sizeof mesh, "%s/data/%s.obj", SQ_SHARED_DIR, rel);
    snprintf(cones, sizeof cones, "%s/data/%s_Th_hat", SQ_SHARED_DIR, rel);
    sq_mesh m;
    sq_test_read_mesh(&m, mesh);
    int32_t *val = sq_test_read_valence(cones, m.nv);
    sq_param A, B;
    sq_param_init(&A), sq_param_init(&B);
    sq_param_stats sa, sb;
    sq_error err = {0};
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.attempts = 4;
    opt.tree = SQ_TREE_SURFACE; /* genus3: the cells' map (tree qtri's is an overlay) */
    opt.simplify = SQ_SIMPLIFY_OFF;
    if (sq_param_build(&m, val, &opt, &A, &sa, &err)) fail_msg("%s, unsimplified: %s", rel, err.msg);
    opt.simplify = SQ_SIMPLIFY_ON;
    opt.threads = 1;
    if (sq_param_build(&m, val, &opt, &B, &sb, &err)) fail_msg("%s, simplified: %s", rel, err.msg);
    /* the same simplification in two threads (the input's faces in two
     * halves, then the vertices between them): the same map to the bit */
    {
        sq_param C;
        sq_param_init(&C);
        opt.simplify = SQ_SIMPLIFY_OFF;
        if (sq_param_build(&m, val, &opt, &C, NULL, &err)) fail_msg("%s, unsimplified again: %s", rel, err.msg);
        uint32_t removed = 0;
        assert_int_equal(sq_param_simplify_threads(&m, &C, 2, &removed, &err), SQ_OK);
        assert_int_equal(removed, sb.simplified);
        assert_true(C.nv == B.nv && C.nf == B.nf && C.nuv == B.nuv);
        assert_memory_equal(C.pos, B.pos, 3 * (size_t)B.nv * sizeof *B.pos);
        assert_memory_equal(C.tri, B.tri, 3 * (size_t)B.nf * sizeof *B.tri);
        assert_memory_equal(C.uv, B.uv, 2 * (size_t)B.nuv * sizeof *B.uv);
        assert_memory_equal(C.tri_uv, B.tri_uv, 3 * (size_t)B.nf * sizeof *B.tri_uv);
        assert_memory_equal(C.tri_in, B.tri_in, (size_t)B.nf * sizeof *B.tri_in);
        sq_param_free(&C);
    }
    assert_int_equal(sa.overlay, want_overlay);
    assert_int_equal(sb.overlay, want_overlay);
    assert_int_equal(sa.simplified, 0);
    assert_true(sa.seed_used == sb.seed_used && sb.faces_unsimplified == A.nf && sb.faces_out == B.nf);
    assert_int_equal(sq_param_verify(&B, SQ_PARAM_VERIFY_INTEGER, &err), SQ_OK);
    /* fewer faces, as many vertices fewer as removed (two faces each) */
    assert_true(B.nf < A.nf);
    assert_int_equal(A.nv - B.nv, sb.simplified);
    assert_int_equal(A.nf - B.nf, 2 * sb.simplified);
    printf("  %s: %u -> %u faces (%u vertices removed), conformal mean %.4g -> %.4g, max %.4g -> %.4g\n", rel,
           A.nf, B.nf, sb.simplified, sa.conformal_mean, sb.conformal_mean, sa.conformal_max, sb.conformal_max);
    /* nothing moves: input vertices bit for bit, the rest and the UVs are
     * subsequences of the unsimplified map's */
    assert_int_equal(B.nv_input, m.nv);
    assert_memory_equal(B.pos, m.pos, 3 * (size_t)m.nv * sizeof(double));
    assert_true(subsequence(A.pos + 3 * (size_t)m.nv, A.nv - m.nv, B.pos + 3 * (size_t)m.nv, B.nv - m.nv,
                            3 * sizeof(double)));
    assert_true(subsequence(A.uv, A.nuv, B.uv, B.nuv, 2 * sizeof(double)));
    /* a refinement of the input: each triangle in its input face, oriented
     * like it; per input face the areas add up */
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (uint32_t v = 0; v < m.nv; v++)
        for (int d = 0; d < 3; d++)
            lo[d] = fmin(lo[d], m.pos[3 * v + d]), hi[d] = fmax(hi[d], m.pos[3 * v + d]);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double *farea = calloc(m.nf, sizeof *farea);
    assert_non_null(farea);
    assert_non_null(B.tri_in);
    for (uint32_t t = 0; t < B.nf; t++) {
        uint32_t f = B.tri_in[t];
        assert_true(f < m.nf);
        const double *q[3], *p[3];
        input_face(&m, f, q);
        for (int i = 0; i < 3; i++) p[i] = B.pos + 3 * (size_t)B.tri[3 * t + i];
        double e1[3], e2[3], n[3], g1[3], g2[3], nt[3];
        sub(q[1], q[0], e1), sub(q[2], q[0], e2), crs(e1, e2, n);
        double nn = sqrt(dt(n, n));
        for (int i = 0; i < 3; i++) {
            /* in the plane, and inside the triangle (barycentric >= 0) */
            double x[3];
            sub(p[i], q[0], x);
            if (fabs(dt(x, n)) / nn > 1e-9 * diag) fail_msg("%s: face %u off its input face %u", rel, t, f);
            for (int k = 0; k < 3; k++) {
                double a[3], b[3], c[3];
                sub(q[(k + 1) % 3], q[k], a), sub(p[i], q[k], b), crs(a, b, c);
                if (dt(c, n) / nn < -1e-9 * diag * sqrt(dt(a, a)))
                    fail_msg("%s: face %u leaves its input face %u", rel, t, f);
            }
        }
        sub(p[1], p[0], g1), sub(p[2], p[0], g2), crs(g1, g2, nt);
        assert_true(dt(nt, n) > 0);
        farea[f] += 0.5 * sqrt(dt(nt, nt));
    }
    for (uint32_t f = 0; f < m.nf; f++) {
        const double *q[3];
        input_face(&m, f, q);
        double e1[3], e2[3], n[3];
        sub(q[1], q[0], e1), sub(q[2], q[0], e2), crs(e1, e2, n);
        double a = 0.5 * sqrt(dt(n, n));
        if (fabs(farea[f] - a) > 1e-9 * a)
            fail_msg("%s: input face %u has area %.17g, its triangles %.17g", rel, f, a, farea[f]);
    }
    free(farea);
    double ua = uv_area(&A), ub = uv_area(&B);
    assert_true(fabs(ua - ub) <= 1e-9 * ua);
    assert_int_equal(sa.seam_edges, sb.seam_edges);
    assert_true(sb.conformal_max <= sa.conformal_max * (1 + 1e-9));
    /* a fixed point */
    uint32_t again = 1;
    assert_int_equal(sq_param_simplify(&m, &B, &again, &err), SQ_OK);
    assert_int_equal(again, 0);
    referee_passes(mesh, cones, &B);
    /* the cut on the surface (sq_param_write_cut_svg): three views, every
     * cone once per view */
    {
        char svg[] = "/tmp/sq_test_cut_svg_XXXXXX";
        int fd = mkstemp(svg);
        assert_true(fd >= 0);
        close(fd);
        assert_int_equal(sq_param_write_cut_svg(svg, &m, &B, &err), SQ_OK);
        FILE *f = fopen(svg, "rb");
        assert_non_null(f);
        char line[4096];
        uint32_t circles = 0, seams = 0;
        while (fgets(line, sizeof line, f)) circles += strstr(line, "<circle") != NULL, seams += strstr(line, "#d7191c") != NULL;
        fclose(f);
        remove(svg);
        assert_int_equal(circles, 3 * sb.ncones);
        assert_true(seams >= 3 * sb.seam_edges / 2);
    }
    /* bad calls: another mesh, no input faces */
    sq_mesh other;
    sq_test_load_mesh(&other, "mpz/knot1.obj");
    assert_int_equal(sq_param_write_cut_svg("/tmp/sq_test_never.svg", &other, &B, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_param_simplify(&other, &B, NULL, &err), SQ_ERR_ARGUMENT);
    free(B.tri_in);
    B.tri_in = NULL;
    assert_int_equal(sq_param_simplify(&m, &B, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "tri_in"));
    sq_mesh_free(&other);
    sq_param_free(&A), sq_param_free(&B);
    sq_mesh_free(&m);
    free(val);
}

static void test_eight_overlay(void **state)
{
    (void)state;
    check_model("mpz/eight", 1);
}

static void test_genus3_cells(void **state)
{
    (void)state;
    check_model("mpz/genus3", 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eight_overlay),
        cmocka_unit_test(test_genus3_cells),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
