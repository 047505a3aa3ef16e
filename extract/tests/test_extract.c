/* Tests of the extract stage (extract/sq_extract.h).
 *
 * Maps with a known answer, built here:
 *  - the unit cube, each face its own chart (a unit square, two triangles):
 *    8 cones of valence 3, seams with every rotation; scaled by k it must
 *    give the k x k grid on every face: 6 k^2 quads, no fold, vertices on
 *    the faces at multiples of 1/k;
 *  - a torus of revolution, a 24 x 12 grid of vertices with UV (a i, b j):
 *    a = b = 1 gives back the grid itself; a = 3/4, b = 1/2 puts grid lines
 *    through vertices, along edges and across faces (18 x 6 quads); then the
 *    same map with every face's chart moved by its own rotation and integer
 *    translation (seams everywhere) must give the same quads.
 * Maps of the shared meshes built in-process by sq_param (mpz/eight,
 * mpz/knot1, mpz/holes3), scaled by k = 1, 2, 3: the quad count equals the
 * UV area, which equals the combinatorial domain's quad count times k^2.
 *
 * Every result is checked independently of the library's own checks: each
 * directed edge once and its reverse once (closed, manifold, oriented), no
 * repeated vertex, Euler characteristic, valence 4 except at the cones,
 * which have their valence, positions equal to their barycentric location.
 * Refused maps: a flipped UV triangle, a non-integer translation, a cone
 * off the integer grid, maps too coarse for a quad mesh (tori of 2 x 1
 * and 16 x 2 units: an edge from a point to itself, two edges between the
 * same points); the result stays empty.
 * Random tori (vertices moved by multiples of 1/16, charts moved at random;
 * 40 runs, 400 with SQ_LONG_TESTS=1) must give their UV area in quads. */
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
#include "sq_extract.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_mesh.h"
#include "sq_param.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

/* ---- maps built by hand ------------------------------------------------ */

/* The map of nv positions and nf triangles with one UV per corner (6 nf
 * doubles), through the soup reader's path (sq_map_from_soup). */
static sq_status map_of_corners(uint32_t nv, const double *pos, uint32_t nf, const uint32_t *tri,
                                const double *corner_uv, unsigned flags, sq_map *M, sq_error *err)
{
    sq_soup s;
    memset(&s, 0, sizeof s);
    s.nv = nv;
    s.pos = (double *)pos;
    s.nf = nf;
    s.face_off = malloc(((size_t)nf + 1) * sizeof *s.face_off);
    s.face_uv = malloc(3 * (size_t)nf * sizeof *s.face_uv);
    assert_non_null(s.face_off), assert_non_null(s.face_uv);
    for (uint32_t f = 0; f <= nf; f++) s.face_off[f] = 3 * f;
    for (uint32_t c = 0; c < 3 * nf; c++) s.face_uv[c] = c;
    s.face_idx = (uint32_t *)tri;
    s.nuv = 3 * nf;
    s.uv = (double *)corner_uv;
    sq_status st = sq_map_from_soup(&s, NULL, NULL, 1e-9, flags, M, NULL, err);
    free(s.face_off), free(s.face_uv);
    return st;
}

/* The unit cube; each face a unit square in its own chart. */
static sq_status cube_map(double k, unsigned flags, sq_map *M, sq_error *err)
{
    static const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    static const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    double pos[24], uv[6 * 12];
    uint32_t tri[36];
    for (int v = 0; v < 8; v++) pos[3 * v] = v & 1, pos[3 * v + 1] = (v >> 1) & 1, pos[3 * v + 2] = (v >> 2) & 1;
    for (int f = 0; f < 6; f++) {
        static const int split[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (int t = 0; t < 2; t++)
            for (int c = 0; c < 3; c++) {
                int i = split[t][c], corner = 3 * (2 * f + t) + c;
                tri[corner] = quads[f][i];
                /* each face in its own place of the plane, k times the unit square */
                uv[2 * corner] = k * (sq[i][0] + 3 * f);
                uv[2 * corner + 1] = k * sq[i][1];
            }
    }
    return map_of_corners(8, pos, 12, tri, uv, flags, M, err);
}

/* A torus of revolution: n x m vertices, UV (a i, b j) plus, with jitter,
 * an offset per vertex of -jitter, 0 or +jitter in each coordinate (the
 * same in every chart: the transitions stay translations by (n a, 0) and
 * (0, m b)); then (when shuffle) each face's chart moved by R^r + t of its
 * own. seed picks the offsets and the moves. */
static sq_status torus_map_jitter(uint32_t n, uint32_t m, double a, double b, double jitter,
                                  int shuffle, uint64_t seed, unsigned flags, sq_map *M,
                                  sq_error *err)
{
    uint32_t nv = n * m, nf = 2 * n * m;
    double *pos = malloc(3 * (size_t)nv * sizeof *pos), *uv = malloc(6 * (size_t)nf * sizeof *uv);
    uint32_t *tri = malloc(3 * (size_t)nf * sizeof *tri);
    assert_non_null(pos), assert_non_null(uv), assert_non_null(tri);
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < m; j++) {
            double p = 2 * 3.14159265358979323846 * i / n, q = 2 * 3.14159265358979323846 * j / m;
            double *x = pos + 3 * (size_t)(i * m + j);
            x[0] = (3 + cos(q)) * cos(p), x[1] = (3 + cos(q)) * sin(p), x[2] = sin(q);
        }
    uint64_t rng = seed;
    double *off = malloc(2 * (size_t)nv * sizeof *off);
    assert_non_null(off);
    for (uint32_t v = 0; v < 2 * nv; v++) {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        off[v] = jitter * (double)((int)(rng >> 61) % 3 - 1);
    }
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < m; j++) {
            static const uint32_t di[2][3] = {{0, 1, 1}, {0, 1, 0}}, dj[2][3] = {{0, 0, 1}, {0, 1, 1}};
            for (int t = 0; t < 2; t++) {
                uint32_t f = 2 * (i * m + j) + t;
                rng = rng * 6364136223846793005ull + 1442695040888963407ull;
                int r = shuffle ? (int)(rng >> 60) & 3 : 0;
                double tu = shuffle ? (double)((int)(rng >> 40 & 15) - 8) : 0.0;
                double tv = shuffle ? (double)((int)(rng >> 20 & 15) - 8) : 0.0;
                for (int c = 0; c < 3; c++) {
                    uint32_t ii = i + di[t][c], jj = j + dj[t][c];
                    tri[3 * f + c] = (ii % n) * m + jj % m;
                    uint32_t w = tri[3 * f + c];
                    double p[2] = {a * ii + off[2 * w], b * jj + off[2 * w + 1]}, o[2];
                    sq_map_rotate(r, p, o);
                    uv[6 * f + 2 * c] = o[0] + tu;
                    uv[6 * f + 2 * c + 1] = o[1] + tv;
                }
            }
        }
    sq_status st = map_of_corners(nv, pos, nf, tri, uv, flags, M, err);
    free(pos), free(uv), free(tri), free(off);
    return st;
}

static sq_status torus_map(uint32_t n, uint32_t m, double a, double b, int shuffle, unsigned flags,
                           sq_map *M, sq_error *err)
{
    return torus_map_jitter(n, m, a, b, 0.0, shuffle, 12345, flags, M, err);
}

static void scale_map(sq_map *M, double k)
{
    for (size_t i = 0; i < 2 * (size_t)M->mesh.nh; i++) M->he_uv[i] *= k, M->he_t[i] *= k;
}

/* ---- independent checks of a result ------------------------------------ */

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static double uv_area(const sq_map *M)
{
    double area = 0.0;
    for (uint32_t f = 0; f < M->mesh.nf; f++) {
        uint32_t h0 = M->mesh.f_he[f], h1 = M->mesh.he_next[h0], h2 = M->mesh.he_next[h1];
        const double *a = M->he_uv + 2 * (size_t)h0, *b = M->he_uv + 2 * (size_t)h1,
                     *c = M->he_uv + 2 * (size_t)h2;
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    return area;
}

/* Quads folded as the referee counts them: both triangulations bend by
 * more than 90 degrees. */
static uint32_t folded_quads(const sq_quad_mesh *Q)
{
    uint32_t folded = 0;
    for (uint32_t f = 0; f < Q->nq; f++) {
        const double *x[4];
        for (int i = 0; i < 4; i++) x[i] = Q->pos + 3 * (size_t)Q->quad[4 * f + i];
        int bent = 0;
        for (int d = 0; d < 2; d++) {
            double n[2][3];
            for (int t = 0; t < 2; t++) {
                const double *p = x[(d + 2 * t) % 4], *q = x[(d + 2 * t + 1) % 4], *r = x[(d + 2 * t + 2) % 4];
                double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
                n[t][0] = u[1] * w[2] - u[2] * w[1];
                n[t][1] = u[2] * w[0] - u[0] * w[2];
                n[t][2] = u[0] * w[1] - u[1] * w[0];
            }
            bent += n[0][0] * n[1][0] + n[0][1] * n[1][1] + n[0][2] * n[1][2] < 0;
        }
        folded += bent == 2;
    }
    return folded;
}

/* What every extraction must satisfy; nq_expected 0: not known. */
static void check_result(const sq_map *M, const sq_quad_mesh *Q, const sq_extract_stats *st,
                         uint32_t nq_expected)
{
    const sq_mesh *m = &M->mesh;
    if (nq_expected) assert_int_equal(Q->nq, nq_expected);
    /* every unit square of the grid once: the quads cover the UV area */
    assert_true(fabs(uv_area(M) - Q->nq) <= 1e-9 * Q->nq);
    assert_int_equal(st->quads, Q->nq);
    assert_int_equal(st->vertex_points + st->edge_points + st->face_points, Q->nv);

    /* each directed edge once, its reverse once; no repeated vertex */
    size_t ne = 4 * (size_t)Q->nq;
    uint64_t *e = malloc(ne * sizeof *e), *r = malloc(ne * sizeof *r);
    uint32_t *deg = calloc(Q->nv, sizeof *deg);
    assert_non_null(e), assert_non_null(r), assert_non_null(deg);
    for (uint32_t f = 0; f < Q->nq; f++)
        for (int i = 0; i < 4; i++) {
            uint32_t a = Q->quad[4 * f + i], b = Q->quad[4 * f + (i + 1) % 4];
            assert_true(a < Q->nv);
            for (int j = i + 1; j < 4; j++) assert_int_not_equal(a, Q->quad[4 * f + j]);
            e[4 * f + i] = (uint64_t)a << 32 | b;
            r[4 * f + i] = (uint64_t)b << 32 | a;
            deg[a]++;
        }
    qsort(e, ne, sizeof *e, cmp_u64);
    qsort(r, ne, sizeof *r, cmp_u64);
    for (size_t i = 0; i < ne; i++) {
        if (i) assert_true(e[i] != e[i - 1]);
        assert_true(e[i] == r[i]);
    }
    free(e), free(r);
    int64_t chi = (int64_t)Q->nv - (int64_t)ne / 2 + Q->nq;
    assert_int_equal(chi, (int64_t)m->nv - m->nh / 2 + m->nf);
    assert_int_equal(st->edges, ne / 2);

    /* valences: 4, except at the cones, which are grid points */
    uint32_t irregular = 0, cones = 0;
    for (uint32_t v = 0; v < m->nv; v++) cones += M->valence[v] != 4;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m->nv; v++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], m->pos[3 * v + k]), hi[k] = fmax(hi[k], m->pos[3 * v + k]);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    for (uint32_t p = 0; p < Q->nv; p++) {
        assert_int_equal(deg[p], (uint32_t)Q->valence[p]);
        irregular += deg[p] != 4;
        if (Q->kind[p] == SQ_GRID_VERTEX) {
            assert_int_equal(Q->valence[p], M->valence[Q->elem[p]]);
            assert_memory_equal(Q->pos + 3 * (size_t)p, m->pos + 3 * (size_t)Q->elem[p], 3 * sizeof(double));
        } else {
            assert_int_equal(Q->valence[p], 4);
        }
        assert_true(floor(Q->uv[2 * p]) == Q->uv[2 * p] && floor(Q->uv[2 * p + 1]) == Q->uv[2 * p + 1]);
        /* the position is the barycentric combination of its face */
        uint32_t f = Q->loc_face[p], h = m->f_he[f];
        assert_true(f < m->nf);
        double x[3] = {0, 0, 0}, sum = 0;
        for (int i = 0; i < 3; i++, h = m->he_next[h]) {
            double w = Q->loc_bary[3 * (size_t)p + i];
            assert_true(w >= 0.0 && w <= 1.0);
            sum += w;
            for (int k = 0; k < 3; k++) x[k] += w * m->pos[3 * (size_t)m->he_vert[h] + k];
        }
        assert_true(fabs(sum - 1.0) < 1e-12);
        for (int k = 0; k < 3; k++) assert_true(fabs(x[k] - Q->pos[3 * (size_t)p + k]) <= 1e-12 * diag);
    }
    for (uint32_t v = 0; v < m->nv; v++) {
        if (M->valence[v] == 4) continue;
        int found = 0;
        for (uint32_t p = 0; p < st->vertex_points; p++) found |= Q->kind[p] == SQ_GRID_VERTEX && Q->elem[p] == v;
        assert_true(found);
    }
    assert_int_equal(irregular, cones);
    assert_int_equal(st->irregular, cones);
    free(deg);
}

/* ---- tests --------------------------------------------------------------- */

static void test_cube(void **state)
{
    (void)state;
    for (int k = 1; k <= 5; k++) {
        sq_map M;
        sq_error err;
        sq_quad_mesh Q;
        memset(&Q, 0, sizeof Q);
        sq_extract_stats st;
        assert_int_equal(cube_map(k, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, &err), SQ_OK);
        sq_status s = sq_extract(&M, &Q, &st, &err);
        if (s) fprintf(stderr, "cube k=%d: %s\n", k, err.msg);
        assert_int_equal(s, SQ_OK);
        check_result(&M, &Q, &st, 6 * k * k);
        assert_int_equal(st.irregular, 8);
        assert_int_equal(st.vertex_points, 8);
        assert_int_equal(st.edge_points, 12 * (k - 1) + 6 * (k - 1)); /* cube edges and diagonals */
        assert_int_equal(folded_quads(&Q), 0);
        /* every vertex on a face of the cube, at multiples of 1/k */
        for (uint32_t p = 0; p < Q.nv; p++) {
            int on_face = 0;
            for (int c = 0; c < 3; c++) {
                double x = Q.pos[3 * p + c];
                assert_true(fabs(x * k - round(x * k)) < 1e-9);
                on_face |= x == 0.0 || x == 1.0;
            }
            assert_true(on_face);
        }
        sq_quad_mesh_free(&Q);
        sq_map_free(&M);
    }
}

static void test_torus(void **state)
{
    (void)state;
    static const struct {
        double a, b;
        int shuffle;
        uint32_t nq;
    } cases[] = {{1, 1, 0, 24 * 12}, {1, 1, 1, 24 * 12}, {0.75, 0.5, 0, 18 * 6},
                 {0.75, 0.5, 1, 18 * 6}, {0.375, 1.25, 0, 9 * 15}, {0.375, 1.25, 1, 9 * 15}};
    uint32_t ncases = sizeof cases / sizeof cases[0];
    sq_quad_mesh ref; /* the case before, without seams */
    memset(&ref, 0, sizeof ref);
    for (uint32_t c = 0; c < ncases; c++) {
        sq_map M;
        sq_error err;
        sq_quad_mesh Q;
        sq_extract_stats st;
        memset(&Q, 0, sizeof Q);
        assert_int_equal(torus_map(24, 12, cases[c].a, cases[c].b, cases[c].shuffle,
                                   SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, &err),
                         SQ_OK);
        sq_status s = sq_extract(&M, &Q, &st, &err);
        if (s) fprintf(stderr, "torus case %u: %s\n", c, err.msg);
        assert_int_equal(s, SQ_OK);
        check_result(&M, &Q, &st, cases[c].nq);
        assert_int_equal(folded_quads(&Q), 0);
        if (cases[c].a == 1 && cases[c].b == 1) { /* the grid itself */
            assert_int_equal(Q.nv, 24 * 12);
            assert_int_equal(st.vertex_points, 24 * 12);
        }
        if (cases[c].shuffle) {
            /* the same points on the same elements as without the seams */
            assert_int_equal(Q.nv, ref.nv);
            for (uint32_t p = 0; p < Q.nv; p++) {
                uint32_t q = 0;
                while (q < ref.nv &&
                       !(ref.kind[q] == Q.kind[p] && ref.elem[q] == Q.elem[p] &&
                         fabs(ref.pos[3 * q] - Q.pos[3 * p]) < 1e-12 &&
                         fabs(ref.pos[3 * q + 1] - Q.pos[3 * p + 1]) < 1e-12 &&
                         fabs(ref.pos[3 * q + 2] - Q.pos[3 * p + 2]) < 1e-12))
                    q++;
                assert_true(q < ref.nv);
            }
            sq_quad_mesh_free(&Q);
        } else {
            sq_quad_mesh_free(&ref);
            ref = Q;
        }
        sq_map_free(&M);
    }
    sq_quad_mesh_free(&ref);
}

/* Random tori: vertices moved by multiples of 1/16 (so that grid lines run
 * through vertices and along edges often), charts moved at random; the
 * quad count must be the UV area, n a m b, and every check must hold. */
static void test_torus_random(void **state)
{
    (void)state;
    static const double scales[][2] = {{0.5, 0.5}, {0.75, 0.5}, {1.0, 0.375}, {1.5, 1.25}};
    uint32_t runs = getenv("SQ_LONG_TESTS") ? 400 : 40, through_vertices = 0, skipped = 0;
    for (uint32_t r = 0; r < runs; r++) {
        const double *sc = scales[r % 4];
        double jitter = (r / 4) % 2 ? 0.0625 : 0.125;
        if (jitter * 4 > fmin(sc[0], sc[1])) jitter = 0.0625;
        sq_map M;
        sq_error err;
        sq_quad_mesh Q;
        sq_extract_stats st;
        memset(&Q, 0, sizeof Q);
        sq_status s = torus_map_jitter(16, 8, sc[0], sc[1], jitter, (int)(r % 3 != 0), 7 + r,
                                       SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, &err);
        if (s == SQ_ERR_DEGENERATE) { /* the moves flattened a UV triangle: not a map */
            skipped++;
            continue;
        }
        assert_int_equal(s, SQ_OK);
        s = sq_extract(&M, &Q, &st, &err);
        if (s) fprintf(stderr, "random torus %u: %s\n", r, err.msg);
        assert_int_equal(s, SQ_OK);
        check_result(&M, &Q, &st, (uint32_t)lround(16 * sc[0] * 8 * sc[1]));
        through_vertices += st.vertex_points;
        sq_quad_mesh_free(&Q);
        sq_map_free(&M);
    }
    assert_true(skipped * 10 < runs);
    assert_true(through_vertices > runs); /* the degenerate cases did occur */
}

/* sq_param's map of a shared mesh with its cones, as an sq_map. */
static void param_map(const char *name, sq_mesh *mesh, int32_t **valence, sq_map *M,
                      uint64_t *domain_quads)
{
    char path[1024], cones[1024];
    snprintf(path, sizeof path, "%s/data/mpz/%s.obj", SQ_SHARED_DIR, name);
    snprintf(cones, sizeof cones, "%s/data/mpz/%s_Th_hat", SQ_SHARED_DIR, name);
    sq_soup soup;
    sq_error err;
    memset(&soup, 0, sizeof soup);
    assert_int_equal(sq_read_mesh(path, &soup, &err), SQ_OK);
    assert_int_equal(sq_mesh_from_soup(&soup, 0, mesh, &err), SQ_OK);
    sq_soup_free(&soup);
    *valence = malloc(mesh->nv * sizeof **valence);
    assert_non_null(*valence);
    assert_int_equal(sq_cones_read(cones, mesh->nv, *valence, NULL, &err), SQ_OK);
    sq_param_options opt;
    sq_param_options_default(&opt);
    sq_param P;
    sq_param_init(&P);
    sq_param_stats ps;
    sq_status s = sq_param_build(mesh, *valence, &opt, &P, &ps, &err);
    if (s) fprintf(stderr, "param %s: %s\n", name, err.msg);
    assert_int_equal(s, SQ_OK);
    *domain_quads = ps.quads_unpadded + ps.quads_added;
    sq_soup ms;
    memset(&ms, 0, sizeof ms);
    ms.nv = P.nv, ms.pos = P.pos, ms.nf = P.nf, ms.face_idx = P.tri, ms.nuv = P.nuv, ms.uv = P.uv;
    ms.face_uv = P.tri_uv;
    ms.face_off = malloc(((size_t)P.nf + 1) * sizeof *ms.face_off);
    assert_non_null(ms.face_off);
    for (uint32_t f = 0; f <= P.nf; f++) ms.face_off[f] = 3 * f;
    s = sq_map_from_soup(&ms, mesh, *valence, 1e-9, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, M,
                         NULL, &err);
    if (s) fprintf(stderr, "map of %s: %s\n", name, err.msg);
    assert_int_equal(s, SQ_OK);
    free(ms.face_off);
    sq_param_free(&P);
}

static void run_param_model(const char *name, int kmax)
{
    sq_mesh mesh;
    int32_t *valence;
    sq_map M;
    uint64_t domain_quads;
    param_map(name, &mesh, &valence, &M, &domain_quads);
    size_t n2 = 2 * (size_t)M.mesh.nh;
    double *uv0 = malloc(n2 * sizeof *uv0), *t0 = malloc(n2 * sizeof *t0);
    assert_non_null(uv0), assert_non_null(t0);
    memcpy(uv0, M.he_uv, n2 * sizeof *uv0);
    memcpy(t0, M.he_t, n2 * sizeof *t0);
    for (int k = 1; k <= kmax; k++) {
        sq_quad_mesh Q;
        sq_extract_stats st;
        sq_error err;
        memset(&Q, 0, sizeof Q);
        /* k times the map: another integer-grid map, k^2 times the quads */
        memcpy(M.he_uv, uv0, n2 * sizeof *uv0);
        memcpy(M.he_t, t0, n2 * sizeof *t0);
        scale_map(&M, k);
        sq_status s = sq_extract(&M, &Q, &st, &err);
        if (s) fprintf(stderr, "%s k=%d: %s\n", name, k, err.msg);
        assert_int_equal(s, SQ_OK);
        check_result(&M, &Q, &st, (uint32_t)(domain_quads * k * k));
        /* the cones of the input are the irregular vertices, with their valences */
        for (uint32_t v = 0; v < mesh.nv; v++)
            if (valence[v] != 4) {
                uint32_t p = 0;
                while (p < Q.nv && !(Q.kind[p] == SQ_GRID_VERTEX && Q.elem[p] == v)) p++;
                assert_true(p < Q.nv);
                assert_int_equal(Q.valence[p], valence[v]);
            }
        printf("%s k=%d: %u quads (%u + %u + %u points), %u irregular, %u folded, %llu trace steps, %.3f s\n",
               name, k, Q.nq, st.vertex_points, st.edge_points, st.face_points, st.irregular,
               folded_quads(&Q), (unsigned long long)st.trace_steps, st.t_total);
        sq_quad_mesh_free(&Q);
    }
    free(uv0), free(t0);
    sq_map_free(&M);
    free(valence);
    sq_mesh_free(&mesh);
}

static void test_param_eight(void **state)
{
    (void)state;
    run_param_model("eight", 3);
}

static void test_param_knot1(void **state)
{
    (void)state;
    run_param_model("knot1", 2);
}

static void test_param_holes3(void **state)
{
    (void)state;
    run_param_model("holes3", 2);
}

static void test_refused(void **state)
{
    (void)state;
    sq_map M;
    sq_error err;
    sq_quad_mesh Q;
    memset(&Q, 0, sizeof Q);

    /* a flipped UV triangle: the map's own check names the face */
    assert_int_equal(cube_map(2, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, &err), SQ_OK);
    uint32_t h = M.mesh.f_he[5];
    double *a = M.he_uv + 2 * (size_t)h, *b = M.he_uv + 2 * (size_t)M.mesh.he_next[h],
           *c = M.he_uv + 2 * (size_t)M.mesh.he_next[M.mesh.he_next[h]];
    a[0] = b[0] + c[0] - a[0]; /* mirrored across the opposite edge */
    a[1] = b[1] + c[1] - a[1];
    assert_int_not_equal(sq_extract(&M, &Q, NULL, &err), SQ_OK);
    assert_non_null(strstr(err.msg, "face"));
    assert_int_equal(Q.nq, 0);
    assert_null(Q.quad);
    sq_map_free(&M);

    /* cones at half-integers */
    assert_int_equal(cube_map(1.5, SQ_MAP_REQUIRE_EXACT, &M, &err), SQ_OK);
    assert_int_not_equal(sq_extract(&M, &Q, NULL, &err), SQ_OK);
    assert_null(Q.quad);
    sq_map_free(&M);

    /* a non-integer translation (24 * 0.6875 = 16.5), no cone */
    assert_int_equal(torus_map(24, 12, 0.6875, 0.5, 0, SQ_MAP_REQUIRE_EXACT, &M, &err), SQ_OK);
    assert_int_not_equal(sq_extract(&M, &Q, NULL, &err), SQ_OK);
    assert_null(Q.quad);
    sq_map_free(&M);

    /* a torus 2 x 1 units: the grid edge in v returns to its own point */
    assert_int_equal(torus_map(16, 8, 0.125, 0.125, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER,
                               &M, &err),
                     SQ_OK);
    sq_status s = sq_extract(&M, &Q, NULL, &err);
    assert_int_equal(s, SQ_ERR_DEGENERATE);
    assert_non_null(strstr(err.msg, "comes back to its own point"));
    assert_null(Q.quad);
    sq_map_free(&M);

    /* a torus 16 x 2 units: two grid edges join the same two points */
    assert_int_equal(torus_map(16, 8, 1.0, 0.25, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER,
                               &M, &err),
                     SQ_OK);
    s = sq_extract(&M, &Q, NULL, &err);
    assert_int_equal(s, SQ_ERR_DEGENERATE);
    assert_non_null(strstr(err.msg, "two grid edges join"));
    assert_null(Q.quad);
    sq_map_free(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_torus_random),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_param_eight),
        cmocka_unit_test(test_param_knot1),
        cmocka_unit_test(test_param_holes3),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
