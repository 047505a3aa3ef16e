/* Tests of sq_map_split:
 *  - a flat torus of 5 x 3 (4 x 4 cells of 1.25 x 0.75, two triangles each,
 *    embedded as a torus of revolution), an integer-grid map: cut along
 *    every integer line it falls into exactly 15 unit squares (components
 *    across edges off the chords), with the UV area kept; cut along only
 *    u = 0, u = 2 and v = 0 (loops), into 2 components; a chord of finite
 *    extent between two lines marks only the edges within it;
 *  - the published maps of mpz/eight and mpz/helmet made exact, cut by
 *    lines every 1/16 in every face's chart (not continued across seams):
 *    the split is a closed manifold, each face's UV area is kept, and no
 *    triangle crosses a line of its face (exact test at its exact corners). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_io.h"
#include "sq_map.h"
#include "sq_map_split.h"
#include "sq_union_find.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static void torus_map(sq_map *M)
{
    enum { NX = 4, NY = 4 };
    sq_soup s;
    memset(&s, 0, sizeof s);
    s.nv = NX * NY;
    s.pos = malloc(3 * s.nv * sizeof *s.pos);
    s.nuv = (NX + 1) * (NY + 1);
    s.uv = malloc(2 * s.nuv * sizeof *s.uv);
    s.nf = 2 * NX * NY;
    s.face_off = malloc((s.nf + 1) * sizeof *s.face_off);
    s.face_idx = malloc(3 * s.nf * sizeof *s.face_idx);
    s.face_uv = malloc(3 * s.nf * sizeof *s.face_uv);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            double a = 6.283185307179586 * i / NX, b = 6.283185307179586 * j / NY + 0.3;
            double *p = s.pos + 3 * (j * NX + i);
            p[0] = (3 + cos(b)) * cos(a), p[1] = (3 + cos(b)) * sin(a), p[2] = sin(b);
        }
    for (int j = 0; j <= NY; j++)
        for (int i = 0; i <= NX; i++) s.uv[2 * (j * (NX + 1) + i)] = 1.25 * i, s.uv[2 * (j * (NX + 1) + i) + 1] = 0.75 * j;
    uint32_t f = 0;
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            uint32_t v00 = j * NX + i, v10 = j * NX + (i + 1) % NX, v01 = ((j + 1) % NY) * NX + i,
                     v11 = ((j + 1) % NY) * NX + (i + 1) % NX;
            uint32_t t00 = j * (NX + 1) + i, t10 = t00 + 1, t01 = t00 + NX + 1, t11 = t01 + 1;
            uint32_t V[6] = {v00, v10, v11, v00, v11, v01}, T[6] = {t00, t10, t11, t00, t11, t01};
            for (int k = 0; k < 6; k++) s.face_idx[3 * f + k] = V[k], s.face_uv[3 * f + k] = T[k];
            f += 2;
        }
    for (uint32_t k = 0; k <= s.nf; k++) s.face_off[k] = 3 * k;
    sq_error err;
    sq_status st = sq_map_from_soup(&s, NULL, NULL, 1e-9, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER,
                                    M, NULL, &err);
    if (st) fail_msg("%s", err.msg);
    sq_soup_free(&s);
}

/* Chords of every line c = k * step in every face's chart. */
static sq_chord *grid_chords(const sq_map *M, double step, uint32_t *n)
{
    uint32_t cap = 64, k = 0;
    sq_chord *ch = malloc(cap * sizeof *ch);
    for (uint32_t f = 0; f < M->mesh.nf; f++) {
        uint32_t h = M->mesh.f_he[f];
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int i = 0; i < 3; i++, h = M->mesh.he_next[h])
            for (int a = 0; a < 2; a++)
                lo[a] = fmin(lo[a], M->he_uv[2 * h + a]), hi[a] = fmax(hi[a], M->he_uv[2 * h + a]);
        for (int a = 0; a < 2; a++)
            for (double c = ceil(lo[a] / step) * step; c <= hi[a]; c += step) {
                if (k == cap) cap *= 2, ch = realloc(ch, cap * sizeof *ch);
                ch[k++] = (sq_chord){f, (uint8_t)a, c, -INFINITY, INFINITY};
            }
    }
    *n = k;
    return ch;
}

static uint32_t components(const sq_split *S)
{
    uint32_t *par = malloc(S->nt * sizeof *par), n = 0;
    for (uint32_t t = 0; t < S->nt; t++) par[t] = t;
    for (uint32_t h = 0; h < S->mesh.nh; h++)
        if (!S->on_chord[h]) sq_uf_union(par, h / 3, S->mesh.he_twin[h] / 3);
    for (uint32_t t = 0; t < S->nt; t++) n += sq_uf_find(par, t) == t;
    free(par);
    return n;
}

static double tri_area(const double *p)
{
    return 0.5 * ((p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]));
}

/* UV area per input face kept; no triangle on both sides of a line. */
static void check_split(const sq_map *M, const sq_split *S, const sq_chord *ch, uint32_t n)
{
    double *area = calloc(M->mesh.nf, sizeof *area);
    for (uint32_t t = 0; t < S->nt; t++) area[S->tri_face[t]] += tri_area(S->uv + 6 * t);
    for (uint32_t f = 0; f < M->mesh.nf; f++) {
        uint32_t h = M->mesh.f_he[f];
        double p[6];
        for (int i = 0; i < 3; i++, h = M->mesh.he_next[h]) p[2 * i] = M->he_uv[2 * h], p[2 * i + 1] = M->he_uv[2 * h + 1];
        double a = tri_area(p);
        if (!(fabs(area[f] - a) <= 1e-9 * a)) fail_msg("face %u: area %.17g split into %.17g", f, a, area[f]);
    }
    free(area);
    for (uint32_t k = 0; k < n; k++)
        for (uint32_t t = 0; t < S->nt; t++) {
            if (S->tri_face[t] != ch[k].face) continue;
            int lo = 0, hi = 0;
            for (int i = 0; i < 3; i++) {
                int exact = S->uv_exact[3 * t + i] & (ch[k].axis ? SQ_SPLIT_V_EXACT : SQ_SPLIT_U_EXACT);
                if (!exact) continue;
                double x = S->uv[6 * t + 2 * i + ch[k].axis];
                lo |= x < ch[k].c, hi |= x > ch[k].c;
            }
            if (lo && hi) fail_msg("triangle %u crosses the line %s = %g of face %u", t, ch[k].axis ? "v" : "u", ch[k].c, ch[k].face);
        }
}

static void test_torus_unit_squares(void **state)
{
    (void)state;
    sq_map M;
    torus_map(&M);
    uint32_t n;
    sq_chord *ch = grid_chords(&M, 1.0, &n);
    sq_split S;
    sq_error err;
    assert_int_equal(sq_map_split(&M, ch, n, &S, &err), SQ_OK);
    assert_int_equal(components(&S), 15);
    check_split(&M, &S, ch, n);
    sq_split_free(&S);
    /* only the loops u = 0, u = 2, v = 0 as chords: 2 components */
    uint32_t m = 0;
    for (uint32_t k = 0; k < n; k++)
        if ((ch[k].axis == 0 && (ch[k].c == 0 || ch[k].c == 2 || ch[k].c == 5)) ||
            (ch[k].axis == 1 && (ch[k].c == 0 || ch[k].c == 3)))
            ch[m++] = ch[k];
    assert_int_equal(sq_map_split(&M, ch, m, &S, &err), SQ_OK);
    assert_int_equal(components(&S), 2);
    /* a chord of finite extent, ending on two full lines: v = 1 only for
     * u in [0, 1], with u = 0 and u = 1 as chords: the edges on v = 1 are
     * marked there and nowhere else (1 unit, counted from both sides) */
    sq_split_free(&S);
    free(ch);
    ch = grid_chords(&M, 1.0, &n);
    m = 0;
    for (uint32_t k = 0; k < n; k++) {
        if (ch[k].axis == 1 && ch[k].c == 1) ch[m] = ch[k], ch[m].lo = 0.0, ch[m].hi = 1.0, m++;
        else if (ch[k].axis == 0 && (ch[k].c == 0 || ch[k].c == 1 || ch[k].c == 5)) ch[m++] = ch[k];
    }
    assert_int_equal(sq_map_split(&M, ch, m, &S, &err), SQ_OK);
    double len = 0;
    for (uint32_t h = 0; h < S.mesh.nh; h++)
        if (S.on_chord[h]) {
            uint32_t t = h / 3, i = h % 3;
            const double *p = S.uv + 6 * t + 2 * i, *q = S.uv + 6 * t + 2 * ((i + 1) % 3);
            if (p[0] == q[0]) continue; /* on u = 0 or u = 1 */
            assert_true(p[1] == 1.0 && q[1] == 1.0);
            assert_true(fmin(p[0], q[0]) >= 0.0 && fmax(p[0], q[0]) <= 1.0);
            len += fabs(q[0] - p[0]);
        }
    assert_true(fabs(len - 2.0) < 1e-12);
    /* the strip 0 < u < 1 and the rest: the short chord cuts nothing off */
    assert_int_equal(components(&S), 2);
    sq_split_free(&S);
    free(ch);
    sq_map_free(&M);
}

static void test_published_maps(void **state)
{
    (void)state;
    const char *models[] = {"eight", "helmet"};
    for (int i = 0; i < 2; i++) {
        char path[512];
        sq_error err;
        sq_map M;
        snprintf(path, sizeof path, "%s/data/mpz/%s.obj", SQ_SHARED_DIR, models[i]);
        assert_int_equal(sq_map_read(path, NULL, NULL, 1e-9, 0, &M, NULL, &err), SQ_OK);
        uint32_t n;
        sq_chord *ch = grid_chords(&M, 1.0 / 16, &n);
        sq_split S;
        sq_status st = sq_map_split(&M, ch, n, &S, &err);
        if (st) fail_msg("%s: %s", models[i], err.msg);
        assert_true(S.nt > M.mesh.nf);
        check_split(&M, &S, ch, n);
        sq_split_free(&S);
        free(ch);
        sq_map_free(&M);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torus_unit_squares),
        cmocka_unit_test(test_published_maps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
