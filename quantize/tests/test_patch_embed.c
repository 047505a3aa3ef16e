/* Tests of sq_patch_embed on rectangles triangulated from jittered grids:
 * the boundary vertices keep their prescribed images exactly, every
 * triangle is positive (exact predicate), the sweep is used where the
 * integer sides are close to proportional and reproduces a uniform scaling
 * exactly there; Tutte's map (the fallback) on strongly sheared
 * boundaries (the bottom's vertices pushed left, the top's right) is valid
 * too.
 * 300 random patches (3000 with SQ_LONG_TESTS). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_patch_embed.h"
#include "sq_predicates.h"

typedef struct gen {
    uint32_t nx, ny, nv, nt;
    double *uv, *out;
    uint32_t *tri;
    uint8_t *fixed;
    sq_patch P;
} gen;

static uint64_t rng_state = 88172645463325252ull;
static double frand(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* Boundary image of a side point at relative position x in [0, 1]:
 * a monotone map of [0, 1] onto [0, n] given by `shear` (0: linear; > 0
 * pushes points toward 0, < 0 toward n). */
static double side_image(double x, double n, double shear)
{
    double y = shear >= 0 ? pow(x, 1.0 + shear) : 1.0 - pow(1.0 - x, 1.0 - shear);
    return y * n;
}

static void make(gen *G, uint32_t nx, uint32_t ny, double W, double H, int64_t a, int64_t b,
                 double shear_bottom, double shear_top, double jitter)
{
    memset(G, 0, sizeof *G);
    G->nx = nx, G->ny = ny;
    G->nv = (nx + 1) * (ny + 1);
    G->nt = 2 * nx * ny;
    G->uv = malloc(2 * G->nv * sizeof *G->uv);
    G->out = malloc(2 * G->nv * sizeof *G->out);
    G->tri = malloc(3 * G->nt * sizeof *G->tri);
    G->fixed = calloc(G->nv, 1);
    assert_non_null(G->uv), assert_non_null(G->out), assert_non_null(G->tri), assert_non_null(G->fixed);
    for (uint32_t j = 0; j <= ny; j++)
        for (uint32_t i = 0; i <= nx; i++) {
            uint32_t v = j * (nx + 1) + i;
            double x = (double)i / nx, y = (double)j / ny;
            int bi = i == 0 || i == nx, bj = j == 0 || j == ny;
            if (!bi) x += jitter * (frand() - 0.5) / nx;
            if (!bj) y += jitter * (frand() - 0.5) / ny;
            G->uv[2 * v] = i == nx ? W : x * W;
            G->uv[2 * v + 1] = j == ny ? H : y * H;
            if (i == 0) G->uv[2 * v] = 0.0;
            if (j == 0) G->uv[2 * v + 1] = 0.0;
            G->fixed[v] = (uint8_t)((j == 0 ? SQ_PATCH_BOTTOM : 0) | (i == nx ? SQ_PATCH_RIGHT : 0) |
                                    (j == ny ? SQ_PATCH_TOP : 0) | (i == 0 ? SQ_PATCH_LEFT : 0));
            if (!G->fixed[v]) continue;
            /* images: bottom/top by their shear, left/right linear */
            double s = j == 0 ? side_image(x, (double)a, shear_bottom)
                              : j == ny ? side_image(x, (double)a, shear_top) : (i == 0 ? 0.0 : (double)a);
            double t = i == 0 || i == nx ? side_image(y, (double)b, 0.0) : (j == 0 ? 0.0 : (double)b);
            if (i == 0) s = 0.0;
            if (i == nx) s = (double)a;
            if (j == 0) t = 0.0;
            if (j == ny) t = (double)b;
            G->out[2 * v] = s, G->out[2 * v + 1] = t;
        }
    uint32_t t = 0;
    for (uint32_t j = 0; j < ny; j++)
        for (uint32_t i = 0; i < nx; i++) {
            uint32_t v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
            uint32_t *c = G->tri + 3 * t;
            if ((i + j) & 1) {
                c[0] = v00, c[1] = v10, c[2] = v11, c[3] = v00, c[4] = v11, c[5] = v01;
            } else {
                c[0] = v00, c[1] = v10, c[2] = v01, c[3] = v10, c[4] = v11, c[5] = v01;
            }
            t += 2;
        }
    /* the input must be a valid map */
    for (uint32_t k = 0; k < G->nt; k++) {
        const uint32_t *c = G->tri + 3 * k;
        assert_true(sq_orient2d(G->uv + 2 * c[0], G->uv + 2 * c[1], G->uv + 2 * c[2]) > 0);
    }
    G->P = (sq_patch){G->nv, G->nt, G->uv, G->tri, W, H, a, b, G->fixed, NULL};
}

static void release(gen *G)
{
    free(G->uv), free(G->out), free(G->tri), free(G->fixed);
}

static int embed_and_check(gen *G)
{
    double *want = malloc(2 * G->nv * sizeof *want);
    assert_non_null(want);
    memcpy(want, G->out, 2 * G->nv * sizeof *want);
    int method = 0;
    sq_error err;
    sq_status st = sq_patch_embed(&G->P, G->out, &method, &err);
    if (st) fail_msg("%s", err.msg);
    for (uint32_t v = 0; v < G->nv; v++)
        if (G->fixed[v]) {
            assert_true(G->out[2 * v] == want[2 * v]);
            assert_true(G->out[2 * v + 1] == want[2 * v + 1]);
        } else {
            assert_true(G->out[2 * v] > 0 && G->out[2 * v] < (double)G->P.a);
            assert_true(G->out[2 * v + 1] > 0 && G->out[2 * v + 1] < (double)G->P.b);
        }
    for (uint32_t k = 0; k < G->nt; k++) {
        const uint32_t *c = G->tri + 3 * k;
        assert_true(sq_orient2d(G->out + 2 * c[0], G->out + 2 * c[1], G->out + 2 * c[2]) > 0);
    }
    free(want);
    return method;
}

static void test_uniform_scaling_is_exact(void **state)
{
    (void)state;
    gen G;
    /* W = 2.5, H = 1.25 onto 20 x 10: a scaling by 8 (exact in binary) */
    make(&G, 12, 7, 2.5, 1.25, 20, 10, 0.0, 0.0, 0.8);
    assert_int_equal(embed_and_check(&G), SQ_PATCH_SWEEP);
    for (uint32_t v = 0; v < G.nv; v++) {
        assert_true(fabs(G.out[2 * v] - 8.0 * G.uv[2 * v]) <= 1e-12);
        assert_true(fabs(G.out[2 * v + 1] - 8.0 * G.uv[2 * v + 1]) <= 1e-12);
    }
    release(&G);
}

/* The fallback on its own: Tutte's map of strongly sheared patches keeps
 * the boundary and gives positive triangles. */
static void test_tutte(void **state)
{
    (void)state;
    for (int k = 0; k < 50; k++) {
        gen G;
        make(&G, 1 + k % 9, 1 + (k * 7) % 13, 0.5 + k, 10.0 / (1 + k), 1 + k % 5, 1 + k % 7,
             k % 2 ? 6.0 : -6.0, k % 3 ? -6.0 : 6.0, 0.5);
        double *want = malloc(2 * G.nv * sizeof *want);
        assert_non_null(want);
        memcpy(want, G.out, 2 * G.nv * sizeof *want);
        sq_error err;
        assert_int_equal(sq_patch_embed_tutte(&G.P, G.out, &err), SQ_OK);
        for (uint32_t v = 0; v < G.nv; v++)
            if (G.fixed[v]) assert_true(G.out[2 * v] == want[2 * v] && G.out[2 * v + 1] == want[2 * v + 1]);
        for (uint32_t t = 0; t < G.nt; t++) {
            const uint32_t *c = G.tri + 3 * t;
            assert_true(sq_orient2d(G.out + 2 * c[0], G.out + 2 * c[1], G.out + 2 * c[2]) > 0);
        }
        free(want);
        release(&G);
    }
}

static void test_random_patches(void **state)
{
    (void)state;
    uint32_t n = getenv("SQ_LONG_TESTS") ? 3000 : 300, tutte = 0;
    for (uint32_t k = 0; k < n; k++) {
        gen G;
        uint32_t nx = 1 + (uint32_t)(frand() * 12), ny = 1 + (uint32_t)(frand() * 12);
        double W = 0.1 + 5 * frand(), H = 0.1 + 5 * frand();
        int64_t a = 1 + (int64_t)(frand() * 30), b = 1 + (int64_t)(frand() * 30);
        double sb = 4 * (frand() - 0.5), stp = 4 * (frand() - 0.5);
        make(&G, nx, ny, W, H, a, b, sb, stp, 0.5 * frand());
        tutte += embed_and_check(&G) == SQ_PATCH_TUTTE;
        release(&G);
    }
    assert_true(tutte < n); /* the sweep serves most patches */
}

static void test_bad_patch(void **state)
{
    (void)state;
    gen G;
    make(&G, 2, 2, 1.0, 1.0, 0, 3, 0.0, 0.0, 0.0);
    sq_error err;
    assert_int_equal(sq_patch_embed(&G.P, G.out, NULL, &err), SQ_ERR_ARGUMENT);
    release(&G);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform_scaling_is_exact),
        cmocka_unit_test(test_tutte),
        cmocka_unit_test(test_random_patches),
        cmocka_unit_test(test_bad_patch),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
