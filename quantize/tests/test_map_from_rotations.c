/* Tests of the map on the input mesh from seam rotations
 * (quantize/sq_map_from_rotations.c, sq_map_untangle.c):
 *  1. on mpz models with their cones and the field's rotations
 *     (sq_cone_connection): the map is valid (it passed sq_map_from_soup's
 *     exact checks inside; sq_map_check again here), it is a map of the
 *     input mesh itself (same vertices, positions and faces, no vertex
 *     added), its rotations are the field's around every loop (the per-edge
 *     difference integrates to a potential mod 4 on a face tree), its angle
 *     sums are the cones, and its mean conformal ratio is low (at most 1.6:
 *     the published maps of these models are at 1.16 to 2.65);
 *  2. untangling: a valid map with unknowns pushed until triangles flip is
 *     untangled back to every triangle positive (the flips counted before);
 *  3. a model where no valid map comes out (helmet: coarse, 1,644 faces for
 *     124 cones) returns no map and says why, or a valid one: never an
 *     invalid map;
 *  4. bad arguments. */
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
#include "sq_map_from_rotations.h"
#include "sq_map_untangle.h"
#include "sq_optimize.h"
#include "sq_uv_basis.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static const char *shared_dir(void)
{
    const char *s = getenv("SQ_SHARED_DIR");
    return s && *s ? s : SQ_SHARED_DIR;
}

typedef struct model {
    sq_soup soup;
    sq_mesh m;
    int32_t *val;
    double *turn;
} model;

static void load(const char *name, model *X)
{
    char path[512], cpath[512];
    snprintf(path, sizeof path, "%s/data/mpz/%s.obj", shared_dir(), name);
    snprintf(cpath, sizeof cpath, "%s/data/mpz/%s_Th_hat", shared_dir(), name);
    sq_error err;
    memset(X, 0, sizeof *X);
    if (sq_read_mesh(path, &X->soup, &err) || sq_mesh_from_soup(&X->soup, 0, &X->m, &err)) fail_msg("%s", err.msg);
    X->val = malloc((size_t)X->m.nv * sizeof *X->val);
    X->turn = malloc((size_t)X->m.nh * sizeof *X->turn);
    assert_true(X->val && X->turn);
    if (sq_cones_read(cpath, X->m.nv, X->val, NULL, &err)) fail_msg("%s", err.msg);
    if (sq_cone_connection(&X->m, X->val, X->turn, NULL, &err)) fail_msg("%s: %s", name, err.msg);
}

static void unload(model *X)
{
    free(X->val), free(X->turn);
    sq_mesh_free(&X->m);
    sq_soup_free(&X->soup);
}

/* The halfedge of m in face f at corner c (corners from f_he[f] on). */
static uint32_t corner_he(const sq_mesh *m, uint32_t f, uint32_t c)
{
    uint32_t h = m->f_he[f];
    while (c--) h = m->he_next[h];
    return h;
}

/* Edges whose fundamental loop (face tree by BFS) turns differently in the
 * map and in the transport: 0 when the rotations agree around every loop. */
static uint32_t loop_disagreements(const sq_map *M, const sq_mesh *m, const double *turn)
{
    const sq_mesh *mc = &M->mesh;
    double *phi = malloc((size_t)mc->nf * sizeof *phi);
    uint32_t *queue = malloc((size_t)mc->nf * sizeof *queue);
    uint8_t *seen = calloc(mc->nf, 1);
    assert_true(phi && queue && seen);
    uint32_t qh = 0, qn = 0;
    queue[qn++] = 0, seen[0] = 1, phi[0] = 0;
    while (qh < qn) {
        uint32_t f = queue[qh++];
        for (uint32_t c = 0; c < 3; c++) {
            uint32_t h = 3 * f + c, g = mc->he_face[mc->he_twin[h]];
            if (seen[g]) continue;
            seen[g] = 1;
            phi[g] = phi[f] + turn[corner_he(m, f, c)] - M->he_rot[h];
            queue[qn++] = g;
        }
    }
    assert_int_equal(qn, mc->nf);
    uint32_t bad = 0;
    for (uint32_t h = 0; h < mc->nh; h++) {
        uint32_t f = h / 3, g = mc->he_face[mc->he_twin[h]];
        double d = (phi[f] + turn[corner_he(m, f, h % 3)] - M->he_rot[h] - phi[g]) / 4.0;
        d -= nearbyint(d);
        if (fabs(d) > 1e-6) bad++;
    }
    free(phi), free(queue), free(seen);
    return bad;
}

static void test_models(void **state)
{
    (void)state;
    static const char *models[] = {"eight", "knot1", "sculpt", "genus3", "femur", "homer"};
    for (size_t i = 0; i < sizeof models / sizeof *models; i++) {
        model X;
        load(models[i], &X);
        sq_map M;
        sq_rotation_map_report rep;
        sq_error err;
        if (sq_map_from_rotations(&X.m, X.val, X.turn, NULL, &M, &rep, &err)) fail_msg("%s: %s", models[i], err.msg);
        if (!rep.valid) fail_msg("%s: no valid map: %s", models[i], rep.why);
        if (sq_map_check(&M, 0, &err)) fail_msg("%s: %s", models[i], err.msg);
        /* the input mesh itself, faces in its order, corners from f_he */
        assert_int_equal(M.mesh.nv, X.m.nv);
        assert_int_equal(M.mesh.nf, X.m.nf);
        for (uint32_t v = 0; v < X.m.nv; v++)
            assert_memory_equal(M.mesh.pos + 3 * (size_t)v, X.m.pos + 3 * (size_t)v, 3 * sizeof(double));
        for (uint32_t f = 0; f < X.m.nf; f++)
            for (uint32_t c = 0; c < 3; c++)
                assert_int_equal(M.mesh.he_vert[3 * f + c], X.m.he_vert[corner_he(&X.m, f, c)]);
        for (uint32_t v = 0; v < X.m.nv; v++) assert_int_equal(M.valence[v], X.val[v]);
        const uint32_t bad = loop_disagreements(&M, &X.m, X.turn);
        const double conf = sq_map_conformal_mean(&M);
        print_message("%-8s seams %u, flipped %u -> %u in %u iterations, mean conformal ratio %.3f, "
                      "loops off the field %u (%.2f s)\n",
                      models[i], rep.seam_edges, rep.flipped_start, rep.flipped_after, rep.iterations, conf,
                      bad, rep.seconds);
        assert_int_equal(bad, 0);
        assert_true(conf < 1.6);
        sq_map_free(&M);
        unload(&X);
    }
}

static uint32_t flipped(const sq_mesh *m, const double *uv)
{
    uint32_t n = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        const double *p = uv + 6 * (size_t)f;
        if (!((p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]) > 0)) n++;
    }
    return n;
}

static void test_untangle_pushed(void **state)
{
    (void)state;
    model X;
    load("eight", &X);
    sq_map M;
    sq_rotation_map_report rep;
    sq_error err;
    if (sq_map_from_rotations(&X.m, X.val, X.turn, NULL, &M, &rep, &err) || !rep.valid)
        fail_msg("eight: %s %s", err.msg, rep.why);
    sq_uv_basis B;
    if (sq_uv_basis_free_translations(&M, &B, &err)) fail_msg("%s", err.msg);
    sq_sd_face *F = calloc(M.mesh.nf, sizeof *F);
    double *z = malloc(B.nz * sizeof *z), *uv = malloc(B.ncoord * sizeof *uv);
    assert_true(F && z && uv);
    sq_sd_surface(&M.mesh, 1 / sqrt(sq_sd_surface_area(&M.mesh)), F); /* area 1, as sq_map_from_rotations */
    /* every 40th unknown pushed by a tenth of the map's width: flips */
    memcpy(z, B.z0, B.nz * sizeof *z);
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t i = 0; i < B.nz; i++) lo = fmin(lo, z[i]), hi = fmax(hi, z[i]);
    for (uint32_t i = 0; i < B.nz; i += 40) z[i] += 0.1 * (hi - lo) * ((i / 40) % 2 ? 1 : -1);
    sq_uv_basis_eval(&B, z, uv);
    const uint32_t before = flipped(&M.mesh, uv);
    sq_untangle_result res;
    if (sq_map_untangle(&M.mesh, &B, F, NULL, z, 300, &res, &err)) fail_msg("%s", err.msg);
    sq_uv_basis_eval(&B, z, uv);
    print_message("eight pushed: %u flipped -> %u after %u iterations (%u values of eps)\n", before,
                  flipped(&M.mesh, uv), res.iterations, res.rounds);
    assert_true(before > 10);
    assert_int_equal(res.flipped_before, before);
    assert_int_equal(flipped(&M.mesh, uv), 0);
    assert_int_equal(res.flipped_after, 0);
    free(F), free(z), free(uv);
    sq_uv_basis_free(&B);
    sq_map_free(&M);
    unload(&X);
}

static void test_never_invalid(void **state)
{
    (void)state;
    model X;
    load("helmet", &X);
    sq_map M;
    sq_rotation_map_report rep;
    sq_error err;
    if (sq_map_from_rotations(&X.m, X.val, X.turn, NULL, &M, &rep, &err)) fail_msg("%s", err.msg);
    print_message("helmet: valid %d, flipped %u -> %u: %s\n", rep.valid, rep.flipped_start, rep.flipped_after,
                  rep.why);
    if (rep.valid) {
        if (sq_map_check(&M, 0, &err)) fail_msg("%s", err.msg);
    } else {
        assert_int_equal(M.mesh.nv, 0);
        assert_true(rep.why[0] != 0);
    }
    sq_map_free(&M);
    unload(&X);
}

static void test_bad_arguments(void **state)
{
    (void)state;
    model X;
    load("knot1", &X);
    sq_map M;
    sq_rotation_map_report rep;
    sq_error err;
    assert_int_equal(sq_map_from_rotations(NULL, X.val, X.turn, NULL, &M, &rep, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_map_from_rotations(&X.m, NULL, X.turn, NULL, &M, &rep, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_map_from_rotations(&X.m, X.val, NULL, NULL, &M, &rep, &err), SQ_ERR_ARGUMENT);
    /* a transport that is not integer around a loop: no map, a reason */
    for (uint32_t h = 0; h < X.m.nh; h++)
        if (h < X.m.he_twin[h] && (h % 7) == 3) X.turn[h] += 0.3, X.turn[X.m.he_twin[h]] -= 0.3;
    if (sq_map_from_rotations(&X.m, X.val, X.turn, NULL, &M, &rep, &err)) fail_msg("%s", err.msg);
    assert_int_equal(rep.valid, 0);
    assert_non_null(strstr(rep.why, "not integer"));
    assert_int_equal(M.mesh.nv, 0);
    unload(&X);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_models),
        cmocka_unit_test(test_untangle_pushed),
        cmocka_unit_test(test_never_invalid),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
