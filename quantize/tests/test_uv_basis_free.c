/* Tests of the free-translation basis (quantize/sq_uv_basis_free.c,
 * sq_uv_basis_free_translations) on:
 *  - the published maps of shared/data/mpz, made exact by sq_map_read;
 *  - integer-grid maps made by quantization (sq_quantize) from two of them
 *    (refined meshes, long seams, integer translations);
 *  - hand-made maps: flat tori (trivial holonomy: one more dimension), the
 *    cube's net, and the cube with every face its own chart (all corners at
 *    cones, no free vertex: a curve translation is pinned in every chart).
 * Properties, for every map:
 *  1. well-formed rows (columns in range and increasing);
 *  2. c + P z0 reproduces the map within 1e-12 of its UV diameter;
 *  3. for random z near z0 the map is seamless with the input's rotations:
 *     on every edge the translation read at both ends agrees (1e-9 diam),
 *     corners across a non-seam edge are equal bit for bit, and the seams'
 *     translations did move (they are free);
 *  4. completeness: 2M, (0.6 - 0.8i) M (a rotation and scaling: the
 *     rotations commute with it) and c + P z for a random z are fitted by
 *     least squares (normal equations, CHOLMOD) with a translation per
 *     chart as extra unknowns (the pinned gauge), to a residual below 1e-9
 *     diam, and the random z is recovered with zero translations (P and
 *     the charts' translations are independent: no gauge left);
 *  5. dimension: when every chart is a disk, nz = 2 (nv + 2 genus - 2 + K),
 *     K = 1 iff the rotations have trivial holonomy (a translation
 *     surface), else 0: the complex dimension of the flat structures with
 *     these cones (2 genus + cones - 2, or - 1 for translation surfaces),
 *     plus every other vertex's point, less the translation; computed here
 *     from the mesh, not from the basis's construction;
 *  6. bad input: a map failing sq_map_check (a flipped triangle, a
 *     transition broken by one ulp) is refused with SQ_ERR_ARGUMENT and the
 *     check's message; NULL arguments likewise.
 * SQ_LONG_TESTS=1 also quantizes every mpz model. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "sq_map.h"
#include "sq_quantize.h"
#include "sq_sparse.h"
#include "sq_test_soup.h"
#include "sq_union_find.h"
#include "sq_uv_basis.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static const char *MODELS[] = {"block",         "cup",    "eight",  "elk",    "fandisk", "femur",
                               "fertility_tri", "genus3", "helmet", "holes3", "homer",   "knot1",
                               "rocker_arm",    "sculpt", "trim-star", "twirl"};
#define NMODELS (sizeof MODELS / sizeof MODELS[0])

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* deterministic uniform numbers in [-1, 1] */
static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}


static int is_seam(const sq_map *M, uint32_t h)
{
    return M->he_rot[h] != 0 || M->he_t[2 * h] != 0 || M->he_t[2 * h + 1] != 0;
}

static double uv_diam(const sq_map *M)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t h = 0; h < M->mesh.nh; h++)
        for (int a = 0; a < 2; a++)
            lo[a] = fmin(lo[a], M->he_uv[2 * h + a]), hi[a] = fmax(hi[a], M->he_uv[2 * h + a]);
    return hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

/* ---- the dimension, from the mesh and the rotations alone ----------------- */

typedef struct topo {
    uint32_t charts;
    uint32_t *chart; /* nf: chart index of the face (caller frees) */
    int all_disks;
    int trivial_holonomy;
    int64_t genus;
} topo;

static topo topology(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    topo T = {0, NULL, 1, 1, sq_mesh_genus(m)};
    uint32_t *fc = malloc(m->nf * sizeof *fc), *wc = malloc(m->nh * sizeof *wc);
    int64_t *chi = calloc(m->nf, sizeof *chi);
    assert_non_null(fc), assert_non_null(wc), assert_non_null(chi);
    /* charts: faces across non-seam edges; wedges: corners across them */
    sq_uf_init(fc, m->nf);
    sq_uf_init(wc, m->nh);
    for (uint32_t h = 0; h < m->nh; h++) {
        if (is_seam(M, h)) continue;
        uint32_t g = m->he_twin[h];
        sq_uf_union(fc, m->he_face[h], m->he_face[g]);
        sq_uf_union(wc, h, m->he_next[g]); /* corner at h's origin */
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t C = sq_uf_find(fc, f);
        T.charts += C == f;
        chi[C] += 1;
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t C = sq_uf_find(fc, m->he_face[h]);
        if (sq_uf_find(wc, h) == h) chi[C] += 1;                     /* a wedge   */
        if (is_seam(M, h) || h < m->he_twin[h]) chi[C] -= 1;         /* an edge   */
    }
    T.chart = malloc(m->nf * sizeof *T.chart);
    assert_non_null(T.chart);
    for (uint32_t f = 0, k = 0; f < m->nf; f++) {
        if (sq_uf_find(fc, f) != f) continue;
        if (chi[f] != 1) T.all_disks = 0;
        chi[f] = k++; /* from now on: the chart's index */
    }
    for (uint32_t f = 0; f < m->nf; f++) T.chart[f] = (uint32_t)chi[sq_uf_find(fc, f)];
    /* holonomy: s(face) in Z4 with s(twin's face) = s(face) + rot */
    int *s = malloc(m->nf * sizeof *s);
    uint32_t *queue = malloc(m->nf * sizeof *queue), nq = 0;
    assert_non_null(s), assert_non_null(queue);
    for (uint32_t f = 0; f < m->nf; f++) s[f] = -1;
    s[0] = 0;
    queue[nq++] = 0;
    for (uint32_t q = 0; q < nq; q++) {
        uint32_t f = queue[q], h = m->f_he[f];
        for (int k = 0; k < 3; k++, h = m->he_next[h]) {
            uint32_t g = m->he_face[m->he_twin[h]];
            int want = (s[f] + M->he_rot[h]) & 3;
            if (s[g] < 0) s[g] = want, queue[nq++] = g;
            else if (s[g] != want) T.trivial_holonomy = 0;
        }
    }
    free(s), free(queue), free(fc), free(wc), free(chi);
    return T;
}

/* ---- checks ------------------------------------------------------------------ */

/* every edge: the translation read at both ends agrees; non-seam edges:
 * equal corners. Returns the largest change of a seam translation from
 * M's. */
static double check_seamless(const sq_map *M, const double *uv, double tol, const char *what)
{
    const sq_mesh *m = &M->mesh;
    double moved = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t g = m->he_twin[h];
        const double *fa = uv + 2 * h, *fb = uv + 2 * m->he_next[h];
        const double *ga = uv + 2 * m->he_next[g], *gb = uv + 2 * g;
        if (!is_seam(M, h)) {
            if (fa[0] != ga[0] || fa[1] != ga[1] || fb[0] != gb[0] || fb[1] != gb[1])
                fail_msg("%s: edge (%u, %u) is no seam but its corners differ", what, m->he_vert[h],
                         m->he_vert[g]);
            continue;
        }
        double ra[2], rb[2];
        sq_map_rotate(M->he_rot[h], fa, ra);
        sq_map_rotate(M->he_rot[h], fb, rb);
        double ta[2] = {ga[0] - ra[0], ga[1] - ra[1]}, tb[2] = {gb[0] - rb[0], gb[1] - rb[1]};
        double d = hypot(ta[0] - tb[0], ta[1] - tb[1]);
        if (!(d <= tol))
            fail_msg("%s: edge (%u, %u): translations %g apart at its ends (tolerance %g)", what,
                     m->he_vert[h], m->he_vert[g], d, tol);
        moved = fmax(moved, hypot(ta[0] - M->he_t[2 * h], ta[1] - M->he_t[2 * h + 1]));
    }
    return moved;
}

/* Least squares: c + P z + (a translation per chart) = target; returns the
 * largest residual and the solution in z (nz + 2 charts: P's unknowns,
 * then the translations). */
static double fit(const sq_uv_basis *B, const sq_mesh *m, const topo *T, const double *target,
                  double *z)
{
    uint32_t n = B->nz + 2 * T->charts;
    size_t cap = 0;
    for (uint32_t k = 0; k < B->ncoord; k++) {
        size_t len = B->row_off[k + 1] - B->row_off[k] + 1;
        cap += len * (len + 1) / 2;
    }
    uint32_t *ri = malloc(cap * sizeof *ri), *ci = malloc(cap * sizeof *ci);
    double *v = malloc(cap * sizeof *v), *rhs = calloc(n, sizeof *rhs);
    assert_non_null(ri), assert_non_null(ci), assert_non_null(v), assert_non_null(rhs);
    size_t nnz = 0;
    uint32_t cols[4096];
    double vals[4096];
    for (uint32_t k = 0; k < B->ncoord; k++) {
        uint32_t len = 0;
        for (uint32_t j = B->row_off[k]; j < B->row_off[k + 1]; j++) {
            assert_true(len < 4095);
            cols[len] = B->col[j], vals[len++] = B->val[j];
        }
        cols[len] = B->nz + 2 * T->chart[m->he_face[k / 2]] + (k & 1), vals[len++] = 1.0;
        double b = target[k] - B->c[k];
        for (uint32_t a = 0; a < len; a++) {
            rhs[cols[a]] += vals[a] * b;
            for (uint32_t c = 0; c <= a; c++) {
                uint32_t i = cols[a], j = cols[c];
                ri[nnz] = i > j ? i : j, ci[nnz] = i > j ? j : i, v[nnz++] = vals[a] * vals[c];
            }
        }
    }
    sq_spd *F;
    sq_error err;
    if (sq_spd_factor(n, nnz, ri, ci, v, &F, &err)) fail_msg("normal equations: %s", err.msg);
    if (sq_spd_solve(F, 1, rhs, z, &err)) fail_msg("normal equations: %s", err.msg);
    sq_spd_free(F);
    double *uv = malloc(B->ncoord * sizeof *uv), worst = 0;
    assert_non_null(uv);
    sq_uv_basis_eval(B, z, uv);
    for (uint32_t k = 0; k < B->ncoord; k++)
        worst = fmax(worst, fabs(uv[k] + z[B->nz + 2 * T->chart[m->he_face[k / 2]] + (k & 1)] - target[k]));
    free(uv), free(ri), free(ci), free(v), free(rhs);
    return worst;
}

/* All properties of the basis of map M. */
static void check_basis(const sq_map *M, const char *name, int64_t expect_nz)
{
    const sq_mesh *m = &M->mesh;
    sq_uv_basis B;
    sq_error err;
    double t0 = now();
    sq_status st = sq_uv_basis_free_translations(M, &B, &err);
    double secs = now() - t0;
    if (st) fail_msg("%s: %s", name, err.msg);
    double diam = uv_diam(M);
    /* 1. rows */
    assert_int_equal(B.ncoord, 2 * m->nh);
    assert_int_equal(B.row_off[0], 0);
    uint32_t longest = 0;
    for (uint32_t k = 0; k < B.ncoord; k++) {
        assert_true(B.row_off[k] <= B.row_off[k + 1]);
        if (B.row_off[k + 1] - B.row_off[k] > longest) longest = B.row_off[k + 1] - B.row_off[k];
        for (uint32_t j = B.row_off[k]; j < B.row_off[k + 1]; j++) {
            assert_true(B.col[j] < B.nz);
            assert_true(isfinite(B.val[j]) && B.val[j] != 0);
            if (j > B.row_off[k]) assert_true(B.col[j] > B.col[j - 1]);
        }
        assert_true(isfinite(B.c[k]));
    }
    /* 5. dimension */
    topo T = topology(M);
    int64_t formula = 2 * ((int64_t)m->nv + 2 * T.genus - 2 + T.trivial_holonomy);
    if (T.all_disks) assert_int_equal(B.nz, formula);
    if (expect_nz >= 0) assert_int_equal(B.nz, expect_nz);
    /* 2. z0 */
    double *uv = malloc(B.ncoord * sizeof *uv), *target = malloc(B.ncoord * sizeof *target);
    double *z = malloc((B.nz + 2 * T.charts) * sizeof *z), *zr = malloc((B.nz + 1) * sizeof *zr);
    assert_non_null(uv), assert_non_null(target), assert_non_null(z), assert_non_null(zr);
    sq_uv_basis_eval(&B, B.z0, uv);
    double e0 = 0;
    for (uint32_t k = 0; k < B.ncoord; k++) e0 = fmax(e0, fabs(uv[k] - M->he_uv[k]));
    if (!(e0 <= 1e-12 * diam)) fail_msg("%s: z0 reproduces the map within %g (diameter %g)", name, e0, diam);
    check_seamless(M, uv, 1e-12 * diam, name);
    /* 3. random z near z0 */
    uint64_t seed = 12345;
    for (uint32_t j = 0; j < B.nz; j++) zr[j] = B.z0[j] + 1e-3 * diam * rnd(&seed);
    sq_uv_basis_eval(&B, zr, uv);
    double moved = check_seamless(M, uv, 1e-9 * diam, name);
    /* 4. completeness: 2M, lambda M, a random member */
    double r2, rl, rr, zerr = 0;
    for (uint32_t k = 0; k < B.ncoord; k++) target[k] = 2 * M->he_uv[k];
    r2 = fit(&B, m, &T, target, z);
    for (uint32_t h = 0; h < m->nh; h++) {
        double x = M->he_uv[2 * h], y = M->he_uv[2 * h + 1];
        target[2 * h] = 0.6 * x + 0.8 * y, target[2 * h + 1] = -0.8 * x + 0.6 * y;
    }
    rl = fit(&B, m, &T, target, z);
    for (uint32_t j = 0; j < B.nz; j++) zr[j] = B.z0[j] + 0.1 * diam * rnd(&seed);
    sq_uv_basis_eval(&B, zr, target);
    rr = fit(&B, m, &T, target, z);
    for (uint32_t j = 0; j < B.nz; j++) zerr = fmax(zerr, fabs(z[j] - zr[j]));
    for (uint32_t j = B.nz; j < B.nz + 2 * T.charts; j++) zerr = fmax(zerr, fabs(z[j]));
    print_message("%-14s nv %6u genus %d charts %5u%s%s nz %6u nnz %8u (longest row %u) %.3f s | "
                  "z0 %.1e, seams moved %.1e, fits %.1e %.1e %.1e, z recovered %.1e (x diam)\n",
                  name, m->nv, (int)T.genus, T.charts, T.all_disks ? "" : " (not all disks)",
                  T.trivial_holonomy ? " translation" : "", B.nz, B.row_off[B.ncoord], longest,
                  secs, e0 / diam, moved / diam, r2 / diam, rl / diam, rr / diam, zerr / diam);
    assert_true(moved > 1e-5 * diam);
    if (!(r2 <= 1e-9 * diam && rl <= 1e-9 * diam && rr <= 1e-9 * diam))
        fail_msg("%s: a member of the space is not fitted: residuals %g %g %g (diameter %g)", name,
                 r2, rl, rr, diam);
    if (!(zerr <= 1e-7 * diam)) fail_msg("%s: random z recovered within %g only", name, zerr);
    free(uv), free(target), free(z), free(zr), free(T.chart);
    sq_uv_basis_free(&B);
}

static void read_mpz(const char *name, sq_map *M)
{
    char path[512];
    sq_error err;
    snprintf(path, sizeof path, "%s/data/mpz/%s.obj", SQ_SHARED_DIR, name);
    if (sq_map_read(path, NULL, NULL, 1e-9, 0, M, NULL, &err)) fail_msg("%s: %s", name, err.msg);
}

/* ---- hand-made maps ------------------------------------------------------------ */

static void b_map(soup_builder *b, sq_map *M)
{
    sq_error err;
    if (sq_map_from_soup(&b->s, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT, M, NULL, &err))
        fail_msg("hand-made map: %s", err.msg);
    sq_soup_free(&b->s);
}

/* flat torus: N x N unit squares, the plane modulo (N, 0) and (skew, N) */
static void make_torus(int N, int skew, sq_map *M)
{
    soup_builder b;
    memset(&b, 0, sizeof b);
    for (int a = 0; a < N; a++)
        for (int c = 0; c < N; c++) {
            int ga[4] = {a, a + 1, a + 1, a}, gb[4] = {c, c, c + 1, c + 1};
            uint32_t cv[4], cu[4];
            for (int k = 0; k < 4; k++) {
                int i = ((ga[k] - (gb[k] == N ? skew : 0)) % N + N) % N, j = gb[k] % N;
                double s = 2 * 3.14159265358979323846 * i / N, t = 2 * 3.14159265358979323846 * j / N;
                double p[3] = {(2 + cos(t)) * cos(s), (2 + cos(t)) * sin(s), sin(t)}, uv[2] = {ga[k], gb[k]};
                cv[k] = sb_vertex(&b, p), cu[k] = sb_uv(&b, uv);
            }
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int k = 0; k < 2; k++) {
                uint32_t v[3] = {cv[tri[k][0]], cv[tri[k][1]], cv[tri[k][2]]};
                uint32_t t[3] = {cu[tri[k][0]], cu[tri[k][1]], cu[tri[k][2]]};
                sb_tri(&b, v, t);
            }
        }
    b_map(&b, M);
}

/* the unit cube's net, each face an n x n grid (8 cones of valence 3) */
static void make_cube(int n, sq_map *M)
{
    static const struct {
        int nx, ny, o[3], u[3], v[3];
    } face[6] = {
        {1, 1, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},  {1, 2, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
        {1, 0, {0, 1, 0}, {1, 0, 0}, {0, -1, 0}}, {0, 1, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
        {2, 1, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {3, 1, {1, 1, 0}, {-1, 0, 0}, {0, 0, 1}},
    };
    soup_builder b;
    memset(&b, 0, sizeof b);
    for (int q = 0; q < 6; q++)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                int si[4] = {i, i + 1, i + 1, i}, sj[4] = {j, j, j + 1, j + 1};
                uint32_t cv[4], cu[4];
                for (int c = 0; c < 4; c++) {
                    double p[3], uv[2] = {n * face[q].nx + si[c], n * face[q].ny + sj[c]};
                    for (int k = 0; k < 3; k++)
                        p[k] = (double)(n * face[q].o[k] + si[c] * face[q].u[k] + sj[c] * face[q].v[k]) / n;
                    cv[c] = sb_vertex(&b, p), cu[c] = sb_uv(&b, uv);
                }
                static const int ta[2][3] = {{0, 1, 2}, {0, 2, 3}};
                for (int k = 0; k < 2; k++) {
                    uint32_t v[3] = {cv[ta[k][0]], cv[ta[k][1]], cv[ta[k][2]]};
                    uint32_t t[3] = {cu[ta[k][0]], cu[ta[k][1]], cu[ta[k][2]]};
                    sb_tri(&b, v, t);
                }
            }
    b_map(&b, M);
}

/* M with every face in its own chart: rotated by r_f quarter turns and
 * moved by an integer t_f (M's UVs are integers: sums stay exact) */
static void rechart(const sq_map *M, sq_map *out)
{
    const sq_mesh *m = &M->mesh;
    soup_builder b;
    memset(&b, 0, sizeof b);
    sq_soup *s = &b.s;
    s->nv = m->nv, s->nf = m->nf, s->nuv = 3 * m->nf;
    s->pos = malloc(3 * (size_t)m->nv * sizeof *s->pos);
    s->face_off = malloc(((size_t)m->nf + 1) * sizeof *s->face_off);
    s->face_idx = malloc(3 * (size_t)m->nf * sizeof *s->face_idx);
    s->face_uv = malloc(3 * (size_t)m->nf * sizeof *s->face_uv);
    s->uv = malloc(6 * (size_t)m->nf * sizeof *s->uv);
    assert_non_null(s->pos), assert_non_null(s->face_off), assert_non_null(s->face_idx);
    assert_non_null(s->face_uv), assert_non_null(s->uv);
    memcpy(s->pos, m->pos, 3 * (size_t)m->nv * sizeof *s->pos);
    for (uint32_t f = 0; f < m->nf; f++) {
        s->face_off[f] = 3 * f;
        int r = (int)((f * 2654435761u) >> 7) & 3;
        double t[2] = {(double)((int)(f % 13) - 6), (double)((int)(f % 7) - 3)};
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) {
            double q[2];
            sq_map_rotate(r, M->he_uv + 2 * (size_t)h, q);
            s->face_idx[3 * f + c] = m->he_vert[h];
            s->face_uv[3 * f + c] = 3 * f + (uint32_t)c;
            s->uv[2 * (3 * f + c)] = q[0] + t[0], s->uv[2 * (3 * f + c) + 1] = q[1] + t[1];
        }
    }
    s->face_off[m->nf] = 3 * m->nf;
    b_map(&b, out);
}

/* ---- tests ------------------------------------------------------------------------ */

static void test_published_maps(void **state)
{
    (void)state;
    for (size_t i = 0; i < NMODELS; i++) {
        sq_map M;
        read_mpz(MODELS[i], &M);
        topo T = topology(&M);
        /* the published maps are cut into one disk; their cones make the
         * holonomy nontrivial: nz = 2 (nv + 2 genus - 2) */
        assert_int_equal(T.charts, 1);
        assert_true(T.all_disks);
        assert_false(T.trivial_holonomy);
        free(T.chart);
        check_basis(&M, MODELS[i], 2 * ((int64_t)M.mesh.nv + 2 * T.genus - 2));
        sq_map_free(&M);
    }
}

static void test_quantized_maps(void **state)
{
    (void)state;
    int lng = getenv("SQ_LONG_TESTS") != NULL;
    /* homer's has a chart whose corners are all at cones (a curve's
     * translation pinned) */
    static const char *some[] = {"eight", "knot1", "homer"};
    size_t n = lng ? NMODELS : sizeof some / sizeof some[0];
    for (size_t i = 0; i < n; i++) {
        const char *name = lng ? MODELS[i] : some[i];
        sq_map M, igm;
        sq_error err;
        read_mpz(name, &M);
        sq_quantize_options opt = {1000, 0, SQ_TARGETS_MAP, 0, 0};
        if (sq_quantize(&M, &opt, &igm, NULL, &err)) fail_msg("quantize %s: %s", name, err.msg);
        char label[64];
        snprintf(label, sizeof label, "%s (igm)", name);
        check_basis(&igm, label, -1);
        sq_map_free(&igm);
        sq_map_free(&M);
    }
}

static void test_hand_made(void **state)
{
    (void)state;
    sq_map M, R;
    /* flat tori: trivial holonomy, nz = 2 (nv + 1): the points and the
     * lattice's shape and size, less the translation */
    make_torus(4, 0, &M);
    check_basis(&M, "torus 4", 2 * (16 + 1));
    sq_map_free(&M);
    make_torus(5, 2, &M);
    check_basis(&M, "torus 5 skew 2", 2 * (25 + 1));
    sq_map_free(&M);
    /* the cube: 8 cones of valence 3, genus 0: nz = 2 (nv - 2) */
    for (int n = 1; n <= 3; n++) {
        char label[64];
        make_cube(n, &M);
        uint32_t nv = 6 * n * n + 2;
        assert_int_equal(M.mesh.nv, nv);
        snprintf(label, sizeof label, "cube %d", n);
        check_basis(&M, label, 2 * ((int64_t)nv - 2));
        /* every face its own chart: the same space up to the charts'
         * translations (one pinned each; at n = 1 every corner is a cone,
         * so each chart pins a curve's translation) */
        rechart(&M, &R);
        snprintf(label, sizeof label, "cube %d, charts", n);
        check_basis(&R, label, 2 * ((int64_t)nv - 2));
        sq_map_free(&R);
        sq_map_free(&M);
    }
}

static void test_bad_input(void **state)
{
    (void)state;
    sq_map M;
    sq_uv_basis B;
    sq_error err;
    read_mpz("eight", &M);
    assert_int_equal(sq_uv_basis_free_translations(NULL, &B, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_uv_basis_free_translations(&M, NULL, &err), SQ_ERR_ARGUMENT);
    /* a flipped triangle: two corners of face 10 swap their UVs */
    uint32_t h = M.mesh.f_he[10], n = M.mesh.he_next[h];
    double keep[2] = {M.he_uv[2 * h], M.he_uv[2 * h + 1]};
    memcpy(M.he_uv + 2 * h, M.he_uv + 2 * n, 2 * sizeof(double));
    memcpy(M.he_uv + 2 * n, keep, 2 * sizeof(double));
    assert_int_equal(sq_uv_basis_free_translations(&M, &B, &err), SQ_ERR_ARGUMENT);
    if (!strstr(err.msg, "not a valid exact seamless map") || !strstr(err.msg, "face 10"))
        fail_msg("unexpected message: %s", err.msg);
    memcpy(M.he_uv + 2 * n, M.he_uv + 2 * h, 2 * sizeof(double));
    memcpy(M.he_uv + 2 * h, keep, 2 * sizeof(double));
    assert_int_equal(sq_uv_basis_free_translations(&M, &B, &err), SQ_OK);
    sq_uv_basis_free(&B);
    /* a seam's translation off by one ulp: no longer exact */
    uint32_t s = 0;
    while (!is_seam(&M, s)) s++;
    M.he_t[2 * s] = nextafter(M.he_t[2 * s], INFINITY);
    assert_int_equal(sq_uv_basis_free_translations(&M, &B, &err), SQ_ERR_ARGUMENT);
    if (!strstr(err.msg, "not a valid exact seamless map") || !strstr(err.msg, "exactly"))
        fail_msg("unexpected message: %s", err.msg);
    sq_map_free(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_made),
        cmocka_unit_test(test_published_maps),
        cmocka_unit_test(test_quantized_maps),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
