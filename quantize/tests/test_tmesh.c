/* Tests of the T-mesh (quantize/sq_tmesh_*.c):
 *  - the cube laid out as its cross-shaped net, each face an n x n grid of
 *    unit squares (two triangles each), n = 1..4: 8 cones of valence 3
 *    whose separatrices run along mesh edges (the cube's edges), pass
 *    through regular vertices when n > 1 and meet head-on (or reach the
 *    other cone before its trace left): exactly 8 nodes, 12 arcs of
 *    length n and 6 faces n x n; also with every third square split along
 *    its other diagonal;
 *  - the same maps with every face in its own chart (rotated by a multiple
 *    of 90 degrees, moved where exact): every edge a seam; valid, same area
 *  - flat tori (no cones): the rays of vertex 0 traced; a square torus
 *    gives one node, two loops, one face; a skewed one a T-junction;
 *  - param's integer grid maps of real models (sq_param_build, written as
 *    OBJ and read back exactly by sq_map_read): every node on the integer
 *    grid, every arc of integer length, every face an integer rectangle,
 *    the faces' areas summing to the domain's quad count (eight: 188);
 *  - published maps (shared/data/mpz) made exact by sq_map_read's snapping:
 *    the T-mesh passes sq_tmesh_verify, area = UV area;
 *  - the integer-length solver (sq_tmesh_lengths) accepts the faces' sides:
 *    on param's map it returns the arcs' own integer lengths;
 *  - sq_tmesh_verify rejects corrupted T-meshes (a wrong width, swapped
 *    arcs, a reversed arc, a wrong slot, a wrong length, an inexact node, a
 *    dropped face, a wrong degree, pieces that do not join);
 *  - the SVG is written. */
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
#include "sq_test_soup.h"

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_param.h"
#include "sq_tmesh.h"
#include "sq_tmesh_lengths.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

/* ---- maps built by hand --------------------------------------------------- */

/* The unit cube's net, each face an n x n grid; square (i, j) of a face is
 * split along its diagonal from (i, j) unless flip(i, j), then along the
 * other one. UVs: net square (nx, ny) scaled by n. */
static void make_cube(soup_builder *b, int n, int flip_mode)
{
    static const struct {
        int nx, ny, o[3], u[3], v[3];
    } face[6] = {
        {1, 1, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},  {1, 2, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
        {1, 0, {0, 1, 0}, {1, 0, 0}, {0, -1, 0}}, {0, 1, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
        {2, 1, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {3, 1, {1, 1, 0}, {-1, 0, 0}, {0, 0, 1}},
    };
    memset(b, 0, sizeof *b);
    for (int q = 0; q < 6; q++)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                int si[4] = {i, i + 1, i + 1, i}, sj[4] = {j, j, j + 1, j + 1};
                uint32_t cv[4], cu[4];
                for (int c = 0; c < 4; c++) {
                    double p[3], uv[2] = {n * face[q].nx + si[c], n * face[q].ny + sj[c]};
                    for (int k = 0; k < 3; k++)
                        p[k] = (double)(n * face[q].o[k] + si[c] * face[q].u[k] + sj[c] * face[q].v[k]) / n;
                    cv[c] = sb_vertex(b, p);
                    cu[c] = sb_uv(b, uv);
                }
                int flip = flip_mode && ((i + 2 * j + q) % 3 == 0);
                static const int ta[2][3] = {{0, 1, 2}, {0, 2, 3}}, tb[2][3] = {{0, 1, 3}, {1, 2, 3}};
                for (int k = 0; k < 2; k++) {
                    uint32_t v[3], t[3];
                    for (int c = 0; c < 3; c++) {
                        int x = flip ? tb[k][c] : ta[k][c];
                        v[c] = cv[x], t[c] = cu[x];
                    }
                    sb_tri(b, v, t);
                }
            }
}

/* flat torus, N x N unit squares, no cones: the plane modulo the lattice
 * of (N, 0) and (skew, N); grid point (a, b), 0 <= a, b <= N, is vertex
 * (a - skew [b = N]) mod N, b mod N */
static void make_torus(soup_builder *b, int N, int skew)
{
    memset(b, 0, sizeof *b);
    for (int a = 0; a < N; a++)
        for (int c = 0; c < N; c++) {
            int ga[4] = {a, a + 1, a + 1, a}, gb[4] = {c, c, c + 1, c + 1};
            uint32_t cv[4], cu[4];
            for (int k = 0; k < 4; k++) {
                int i = ((ga[k] - (gb[k] == N ? skew : 0)) % N + N) % N, j = gb[k] % N;
                double s = 2 * 3.14159265358979323846 * i / N, t = 2 * 3.14159265358979323846 * j / N;
                double p[3] = {(2 + cos(t)) * cos(s), (2 + cos(t)) * sin(s), sin(t)}, uv[2] = {ga[k], gb[k]};
                cv[k] = sb_vertex(b, p), cu[k] = sb_uv(b, uv);
            }
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int k = 0; k < 2; k++) {
                uint32_t v[3] = {cv[tri[k][0]], cv[tri[k][1]], cv[tri[k][2]]};
                uint32_t t[3] = {cu[tri[k][0]], cu[tri[k][1]], cu[tri[k][2]]};
                sb_tri(b, v, t);
            }
        }
}

/* ---- checks shared by the tests -------------------------------------------- */

/* Properties every T-mesh of an integer grid map has, beyond
 * sq_tmesh_verify: integer node points, arc lengths and face sizes. */
static void check_integer(const sq_tmesh *T, double expect_area)
{
    double area = 0;
    for (uint32_t n = 0; n < T->n_nodes; n++) {
        assert_true(T->nodes[n].exact);
        assert_true(T->nodes[n].uv[0] == floor(T->nodes[n].uv[0]));
        assert_true(T->nodes[n].uv[1] == floor(T->nodes[n].uv[1]));
    }
    for (uint32_t a = 0; a < T->n_arcs; a++) {
        if (T->arcs[a].length != floor(T->arcs[a].length))
            print_message("arc %u: length %.17g, %u pieces, nodes %u %u\n", a, T->arcs[a].length,
                          T->arcs[a].piece_count, T->arcs[a].node[0], T->arcs[a].node[1]);
        assert_true(T->arcs[a].length >= 1 && T->arcs[a].length == floor(T->arcs[a].length));
        assert_true(T->arcs[a].length3d > 0);
    }
    for (uint32_t f = 0; f < T->n_faces; f++) {
        assert_true(T->width[f] >= 1 && T->width[f] == floor(T->width[f]));
        assert_true(T->height[f] >= 1 && T->height[f] == floor(T->height[f]));
        area += T->width[f] * T->height[f];
    }
    if (expect_area > 0) assert_true(area == expect_area);
}

static void check_cones(const sq_map *M, const sq_tmesh *T)
{
    uint32_t cones = 0;
    for (uint32_t v = 0; v < M->mesh.nv; v++) cones += M->valence[v] != 4;
    uint32_t found = 0;
    for (uint32_t n = 0; n < T->n_nodes; n++) {
        const sq_tmesh_node *N = &T->nodes[n];
        if (N->kind != SQ_TMESH_AT_VERTEX || M->valence[N->id] == 4) continue;
        found++;
        assert_int_equal(N->degree, (uint32_t)M->valence[N->id]);
    }
    assert_int_equal(found, cones);
}

/* ---- tests ------------------------------------------------------------------ */

static void cube_case(int n, int flip)
{
    soup_builder b;
    make_cube(&b, n, flip);
    sq_map M;
    sq_error err;
    sq_status st = sq_map_from_soup(&b.s, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, NULL,
                                    &err);
    if (st) fail_msg("cube map: %s", err.msg);
    sq_tmesh T;
    sq_tmesh_stats stats;
    st = sq_tmesh_build(&M, &T, &stats, &err);
    if (st) fail_msg("cube n=%d flip=%d: %s", n, flip, err.msg);
    assert_int_equal(T.n_nodes, 8);
    assert_int_equal(T.n_arcs, 12);
    assert_int_equal(T.n_faces, 6);
    assert_int_equal(stats.cones, 8);
    assert_int_equal(stats.traces, 24);
    /* every cube edge: two traces head-on, or one reaching the other's cone
     * before it left */
    assert_int_equal(stats.meets + stats.empty_traces, 12);
    for (uint32_t a = 0; a < T.n_arcs; a++) assert_true(T.arcs[a].length == n);
    for (uint32_t a = 0; a < T.n_arcs; a++) assert_true(fabs(T.arcs[a].length3d - 1) < 1e-12);
    for (uint32_t f = 0; f < T.n_faces; f++) {
        assert_true(T.width[f] == n && T.height[f] == n);
        for (int s = 0; s < 4; s++) assert_int_equal(T.side_off[4 * f + s + 1] - T.side_off[4 * f + s], 1);
    }
    check_integer(&T, 6.0 * n * n);
    check_cones(&M, &T);
    if (n > 1) assert_true(stats.vertex_passes > 0);
    sq_tmesh_free(&T);
    sq_map_free(&M);
    sq_soup_free(&b.s);
}

static void test_cube(void **state)
{
    (void)state;
    cube_case(1, 0);
    cube_case(2, 0);
    cube_case(3, 0);
    cube_case(3, 1);
    cube_case(4, 1);
}

/* Flat tori: no cones, so the four rays of vertex 0 are traced. The square
 * torus closes them into two loops through vertex 0: one node, two arcs,
 * one N x N face. On the skewed one the vertical trace winds and ends on
 * the horizontal loop. */
static void torus_case(int N, int skew, uint32_t nodes, uint32_t arcs, uint32_t faces)
{
    soup_builder b;
    make_torus(&b, N, skew);
    sq_map M;
    sq_error err;
    sq_status st = sq_map_from_soup(&b.s, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, &M, NULL,
                                    &err);
    if (st) fail_msg("torus map: %s", err.msg);
    sq_tmesh T;
    sq_tmesh_stats stats;
    st = sq_tmesh_build(&M, &T, &stats, &err);
    if (st) fail_msg("torus %d skew %d: %s", N, skew, err.msg);
    print_message("torus %d skew %d: %u nodes, %u arcs, %u faces\n", N, skew, T.n_nodes, T.n_arcs, T.n_faces);
    assert_int_equal(stats.cones, 0);
    assert_int_equal(stats.traces, 4);
    assert_int_equal(T.n_nodes, nodes);
    assert_int_equal(T.n_arcs, arcs);
    assert_int_equal(T.n_faces, faces);
    uint32_t seed = 0;
    for (uint32_t n = 0; n < T.n_nodes; n++)
        if (T.nodes[n].kind == SQ_TMESH_AT_VERTEX && T.nodes[n].id == 0) seed++, assert_int_equal(T.nodes[n].degree, 4);
    assert_int_equal(seed, 1);
    check_integer(&T, (double)N * N);
    sq_tmesh_free(&T);
    sq_map_free(&M);
    sq_soup_free(&b.s);
}

static void test_torus(void **state)
{
    (void)state;
    torus_case(4, 0, 1, 2, 1);
    torus_case(5, 0, 1, 2, 1);
    /* skew 1: the horizontal rays close into a loop; the vertical ones,
     * traced together, wind and end on it at two T-junctions: 3 nodes,
     * 5 arcs (the loop in 3), 2 faces */
    torus_case(4, 1, 3, 5, 2);
}

/* ---- param's maps ------------------------------------------------------------ */

typedef struct tmpdir {
    char path[256];
} tmpdir;

static void tmp_make(tmpdir *t)
{
    snprintf(t->path, sizeof t->path, "/tmp/sq_test_tmesh.XXXXXX");
    assert_non_null(mkdtemp(t->path));
}

static void tmp_remove(tmpdir *t, const char *file)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", t->path, file);
    unlink(p);
}


/* param's map of model `name`: built, written, read back exact */
static void param_map(const char *name, tmpdir *td, sq_map *M, uint64_t *quads)
{
    model md;
    load(name, &md);
    sq_param P;
    sq_param_stats ps;
    sq_error err;
    sq_param_init(&P);
    if (sq_param_build(&md.mesh, md.valence, NULL, &P, &ps, &err)) fail_msg("param %s: %s", name, err.msg);
    *quads = ps.quads_unpadded + ps.quads_added;
    char path[512];
    snprintf(path, sizeof path, "%s/%s_p.obj", td->path, name);
    if (sq_param_write_obj(path, &P, &err)) fail_msg("%s", err.msg);
    if (sq_map_read(path, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER, M, NULL, &err))
        fail_msg("param map of %s read back: %s", name, err.msg);
    unlink(path);
    sq_param_free(&P);
    unload(&md);
}

static void param_case(const char *name, int svg)
{
    tmpdir td;
    tmp_make(&td);
    sq_map M;
    uint64_t quads;
    param_map(name, &td, &M, &quads);
    sq_tmesh T;
    sq_tmesh_stats stats;
    sq_error err;
    if (sq_tmesh_build(&M, &T, &stats, &err)) fail_msg("tmesh of %s: %s", name, err.msg);
    print_message("%-10s %u cones: %u nodes, %u arcs, %u faces; %u steps (%u along edges, %u vertex passes), %u "
                  "T-junctions, %u meets, %u overtaken; area %g = %llu quads; %.3f s\n",
                  name, stats.cones, T.n_nodes, T.n_arcs, T.n_faces, stats.steps, stats.edge_pieces,
                  stats.vertex_passes, stats.t_junctions, stats.meets, stats.overtaken, T.uv_area, (unsigned long long)quads,
                  stats.seconds);
    check_integer(&T, (double)quads);
    check_cones(&M, &T);
    assert_true(fabs(T.uv_area - (double)quads) <= 1e-9 * (double)quads);
    if (svg) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s_tmesh.svg", td.path, name);
        if (sq_tmesh_write_svg(path, &M, &T, &err)) fail_msg("%s", err.msg);
        FILE *f = fopen(path, "rb");
        assert_non_null(f);
        char buf[64] = {0};
        assert_true(fread(buf, 1, 4, f) == 4);
        fclose(f);
        assert_memory_equal(buf, "<svg", 4);
        unlink(path);
    }
    sq_tmesh_free(&T);
    sq_map_free(&M);
    tmp_remove(&td, "");
    rmdir(td.path);
}

static void test_param_eight(void **state)
{
    (void)state;
    param_case("eight", 1);
}

/* The integer-length solver (sq_tmesh_lengths.h) takes the faces' sides as
 * they are: on param's map the arcs' own lengths are integers meeting
 * every constraint, so the solver returns them unchanged (cost 0); on a
 * published map, targets = lengths scaled to a few units give a feasible
 * integer layout. */
static void lengths_case(const sq_map *M, double scale, int exact)
{
    sq_tmesh T;
    sq_error err;
    if (sq_tmesh_build(M, &T, NULL, &err)) fail_msg("%s", err.msg);
    double *target = malloc(T.n_arcs * sizeof *target);
    int64_t *L = malloc(T.n_arcs * sizeof *L);
    assert_non_null(target), assert_non_null(L);
    double mean = 0;
    for (uint32_t a = 0; a < T.n_arcs; a++) mean += T.arcs[a].length / T.n_arcs;
    if (!exact) scale /= mean; /* a mean target of `scale` units */
    for (uint32_t a = 0; a < T.n_arcs; a++) target[a] = T.arcs[a].length * scale;
    sq_tmesh_sides S = {T.n_faces, T.n_arcs, T.side_off, T.side_arc, target, NULL, 1, NULL};
    sq_tmesh_lengths_stats ls;
    if (sq_tmesh_lengths(&S, L, &ls, &err)) fail_msg("lengths: %s", err.msg);
    if (exact)
        for (uint32_t a = 0; a < T.n_arcs; a++) assert_true((double)L[a] == T.arcs[a].length);
    for (uint32_t f = 0; f < T.n_faces; f++) {
        int64_t side[4] = {0, 0, 0, 0};
        for (int s = 0; s < 4; s++)
            for (uint32_t i = T.side_off[4 * f + s]; i < T.side_off[4 * f + s + 1]; i++) side[s] += L[T.side_arc[i]];
        assert_true(side[0] == side[2] && side[1] == side[3] && side[0] >= 1 && side[1] >= 1);
    }
    free(target), free(L);
    sq_tmesh_free(&T);
}

static void test_lengths(void **state)
{
    (void)state;
    tmpdir td;
    tmp_make(&td);
    sq_map M;
    uint64_t quads;
    param_map("eight", &td, &M, &quads);
    lengths_case(&M, 1, 1);
    sq_map_free(&M);
    rmdir(td.path);

    model md;
    load("block", &md);
    char path[512];
    sq_error err;
    snprintf(path, sizeof path, "%s/data/mpz/block.obj", SQ_SHARED_DIR);
    if (sq_map_read(path, &md.mesh, md.valence, 0, 0, &M, NULL, &err)) fail_msg("%s", err.msg);
    lengths_case(&M, 3, 0);
    sq_map_free(&M);
    unload(&md);
}

static const char *ALL[] = {"block",  "cup",    "eight",  "elk",    "fandisk",    "femur",
                            "fertility_tri", "genus3", "helmet", "holes3", "homer",
                            "knot1",  "rocker_arm", "sculpt", "trim-star", "twirl"};
#define NALL (sizeof ALL / sizeof ALL[0])
/* the models sq_param_build maps with its default options (homer needs
 * more Steiner vertices, twirl has a cone of valence 1) */
static const char *PARAM_ALL[] = {"block", "cup",    "eight",  "elk",        "fandisk", "femur", "fertility_tri",
                                  "genus3", "helmet", "holes3", "knot1", "rocker_arm", "sculpt",  "trim-star"};
#define NPARAM_ALL (sizeof PARAM_ALL / sizeof PARAM_ALL[0])

static int long_tests(void)
{
    const char *e = getenv("SQ_LONG_TESTS");
    return e && *e && strcmp(e, "0") != 0;
}

/* a few cheap models in CI; all with SQ_LONG_TESTS=1 */
static void test_param_models(void **state)
{
    (void)state;
    static const char *names[] = {"cup", "knot1", "block"};
    if (long_tests())
        for (size_t i = 0; i < NPARAM_ALL; i++) param_case(PARAM_ALL[i], 0);
    else
        for (size_t i = 0; i < sizeof names / sizeof *names; i++) param_case(names[i], 0);
}

/* ---- the same maps in other charts ---------------------------------------- */

/* M with every face in its own chart: its UVs rotated by r_f quarter turns
 * and, when `move` (all UVs integer, so the sums stay exact), moved by an
 * integer t_f: every edge is a seam with a rotation and a translation (the
 * transitions recomputed by sq_map_from_soup) */
static void rechart(const sq_map *M, int move, sq_map *out)
{
    const sq_mesh *m = &M->mesh;
    sq_soup s;
    memset(&s, 0, sizeof s);
    s.nv = m->nv, s.nf = m->nf, s.nuv = 3 * m->nf;
    s.pos = malloc(3 * (size_t)m->nv * sizeof *s.pos);
    s.face_off = malloc(((size_t)m->nf + 1) * sizeof *s.face_off);
    s.face_idx = malloc(3 * (size_t)m->nf * sizeof *s.face_idx);
    s.face_uv = malloc(3 * (size_t)m->nf * sizeof *s.face_uv);
    s.uv = malloc(6 * (size_t)m->nf * sizeof *s.uv);
    assert_non_null(s.pos), assert_non_null(s.face_off), assert_non_null(s.face_idx);
    assert_non_null(s.face_uv), assert_non_null(s.uv);
    memcpy(s.pos, m->pos, 3 * (size_t)m->nv * sizeof *s.pos);
    for (uint32_t f = 0; f < m->nf; f++) {
        s.face_off[f] = 3 * f;
        int r = (int)((f * 2654435761u) >> 7) & 3;
        double t[2] = {move ? (double)((int)(f % 13) - 6) : 0, move ? (double)((int)(f % 7) - 3) : 0};
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) {
            double q[2];
            sq_map_rotate(r, M->he_uv + 2 * (size_t)h, q);
            s.face_idx[3 * f + c] = m->he_vert[h];
            s.face_uv[3 * f + c] = 3 * f + (uint32_t)c;
            s.uv[2 * (3 * f + c)] = q[0] + t[0], s.uv[2 * (3 * f + c) + 1] = q[1] + t[1];
        }
    }
    s.face_off[m->nf] = 3 * m->nf;
    sq_error err;
    if (sq_map_from_soup(&s, m, M->valence, 0, SQ_MAP_REQUIRE_EXACT, out, NULL, &err))
        fail_msg("recharted map: %s", err.msg);
    sq_soup_free(&s);
}

static void rechart_case(const sq_map *M, int move, double area)
{
    sq_map R;
    rechart(M, move, &R);
    sq_tmesh T, U;
    sq_tmesh_stats a, b;
    sq_error err;
    if (sq_tmesh_build(M, &T, &a, &err)) fail_msg("%s", err.msg);
    if (sq_tmesh_build(&R, &U, &b, &err)) fail_msg("recharted: %s", err.msg);
    print_message("one chart per face: %u/%u nodes, %u/%u arcs, %u/%u faces\n", T.n_nodes, U.n_nodes, T.n_arcs,
                  U.n_arcs, T.n_faces, U.n_faces);
    if (area > 0) check_integer(&U, area);
    check_cones(&R, &U);
    assert_int_equal(a.traces, b.traces);
    sq_tmesh_free(&T);
    sq_tmesh_free(&U);
    sq_map_free(&R);
}

static void test_rechart(void **state)
{
    (void)state;
    soup_builder b;
    make_cube(&b, 3, 1);
    sq_map M;
    sq_error err;
    if (sq_map_from_soup(&b.s, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT, &M, NULL, &err)) fail_msg("%s", err.msg);
    rechart_case(&M, 1, 54);
    sq_map_free(&M);
    sq_soup_free(&b.s);

    tmpdir td;
    tmp_make(&td);
    uint64_t quads;
    param_map("eight", &td, &M, &quads);
    rechart_case(&M, 0, (double)quads);
    sq_map_free(&M);
    rmdir(td.path);

    /* a published map, snapped to its dyadic grid */
    model md;
    load("cup", &md);
    char path[512];
    snprintf(path, sizeof path, "%s/data/mpz/cup.obj", SQ_SHARED_DIR);
    if (sq_map_read(path, &md.mesh, md.valence, 0, 0, &M, NULL, &err)) fail_msg("%s", err.msg);
    rechart_case(&M, 0, 0);
    sq_map_free(&M);
    unload(&md);
}

/* ---- the published maps, snapped exact ------------------------------------- */

static void published_case(const char *name)
{
    char path[512];
    sq_error err;
    model md;
    load(name, &md);
    snprintf(path, sizeof path, "%s/data/mpz/%s.obj", SQ_SHARED_DIR, name);
    sq_map M;
    if (sq_map_read(path, &md.mesh, md.valence, 0, 0, &M, NULL, &err)) fail_msg("%s: %s", name, err.msg);
    sq_tmesh T;
    sq_tmesh_stats stats;
    if (sq_tmesh_build(&M, &T, &stats, &err)) fail_msg("tmesh of published %s: %s", name, err.msg);
    print_message("%-10s published: %u cones: %u nodes, %u arcs, %u faces; %u steps, %u T-junctions, %u meets, %u overtaken; "
                  "side mismatch %.3g, area error %.3g; %.3f s\n",
                  name, stats.cones, T.n_nodes, T.n_arcs, T.n_faces, stats.steps, stats.t_junctions, stats.meets, stats.overtaken,
                  stats.max_side_mismatch, stats.area_error, stats.seconds);
    check_cones(&M, &T);
    assert_true(stats.area_error <= 1e-9);
    sq_tmesh_free(&T);
    sq_map_free(&M);
    unload(&md);
}

static void test_published(void **state)
{
    (void)state;
    static const char *names[] = {"eight", "block", "cup"};
    if (long_tests())
        for (size_t i = 0; i < NALL; i++) published_case(ALL[i]);
    else
        for (size_t i = 0; i < sizeof names / sizeof *names; i++) published_case(names[i]);
}

/* ---- the check rejects broken T-meshes ------------------------------------- */

static void expect_reject(const sq_map *M, const sq_tmesh *T, const char *what)
{
    sq_error err;
    sq_status st = sq_tmesh_verify(M, T, NULL, &err);
    if (st != SQ_ERR_INTERNAL) fail_msg("corruption '%s' accepted", what);
}

static void test_verify_rejects(void **state)
{
    (void)state;
    soup_builder b;
    make_cube(&b, 2, 1);
    sq_map M;
    sq_error err;
    if (sq_map_from_soup(&b.s, NULL, NULL, 0, SQ_MAP_REQUIRE_EXACT, &M, NULL, &err)) fail_msg("%s", err.msg);
    sq_tmesh T;
    if (sq_tmesh_build(&M, &T, NULL, &err)) fail_msg("%s", err.msg);
    assert_int_equal(sq_tmesh_verify(&M, &T, NULL, &err), SQ_OK);

    double w = T.width[0];
    T.width[0] = w + 1;
    expect_reject(&M, &T, "width");
    T.width[0] = w;

    uint32_t a0 = T.side_arc[0], a1 = T.side_arc[1];
    T.side_arc[0] = a1, T.side_arc[1] = a0;
    expect_reject(&M, &T, "sides swapped");
    T.side_arc[0] = a0, T.side_arc[1] = a1;

    T.side_rev[0] ^= 1;
    expect_reject(&M, &T, "arc direction");
    T.side_rev[0] ^= 1;

    uint32_t s = T.arcs[0].slot[0];
    T.arcs[0].slot[0] = (s + 1) % (uint32_t)T.nodes[T.arcs[0].node[0]].valence;
    expect_reject(&M, &T, "slot");
    T.arcs[0].slot[0] = s;

    double len = T.arcs[3].length;
    T.arcs[3].length = len + 0.5;
    expect_reject(&M, &T, "arc length");
    T.arcs[3].length = len;

    T.nodes[1].exact = 0;
    expect_reject(&M, &T, "inexact node");
    T.nodes[1].exact = 1;

    T.n_faces--;
    expect_reject(&M, &T, "a face dropped");
    T.n_faces++;

    uint32_t dg = T.nodes[2].degree;
    T.nodes[2].degree = dg + 1;
    expect_reject(&M, &T, "node degree");
    T.nodes[2].degree = dg;

    assert_int_equal(T.arcs[5].piece_count, 2); /* a cube edge: two mesh edges */
    sq_tmesh_piece pc = T.pieces[T.arcs[5].piece_off + 1];
    T.pieces[T.arcs[5].piece_off + 1].from.id = (pc.from.id + 1) % M.mesh.nv;
    expect_reject(&M, &T, "pieces broken");
    T.pieces[T.arcs[5].piece_off + 1] = pc;

    assert_int_equal(sq_tmesh_verify(&M, &T, NULL, &err), SQ_OK);
    sq_tmesh_free(&T);
    sq_map_free(&M);
    sq_soup_free(&b.s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_verify_rejects),
        cmocka_unit_test(test_param_eight),
        cmocka_unit_test(test_rechart),
        cmocka_unit_test(test_lengths),
        cmocka_unit_test(test_param_models),
        cmocka_unit_test(test_published),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
