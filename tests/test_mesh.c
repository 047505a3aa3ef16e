/* Unit tests of halfedge construction and validation (core/sq_mesh.c) on
 * small soups built in memory. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_mesh.h"

/* A soup over caller arrays (not owned: never sq_soup_free it). */
static sq_soup make_soup(uint32_t nv, double *pos, uint32_t nf, uint32_t deg, uint32_t *idx,
                         uint32_t *off)
{
    sq_soup s;
    memset(&s, 0, sizeof s);
    s.nv = nv;
    s.pos = pos;
    s.nf = nf;
    for (uint32_t f = 0; f <= nf; f++) off[f] = f * deg;
    s.face_off = off;
    s.face_idx = idx;
    return s;
}

static double tet_pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint32_t tet_idx[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static sq_status build(sq_soup *s, unsigned flags, sq_mesh *m, sq_error *err)
{
    sq_status st = sq_mesh_from_soup(s, flags, m, err);
    if (st == SQ_OK) {
        /* structural invariants of every valid mesh */
        for (uint32_t h = 0; h < m->nh; h++) {
            assert_int_equal(m->he_twin[m->he_twin[h]], h);
            assert_int_not_equal(m->he_twin[h], h);
            assert_int_equal(m->he_vert[m->he_twin[h]], m->he_vert[m->he_next[h]]);
            assert_int_equal(m->he_face[m->he_next[h]], m->he_face[h]);
        }
        for (uint32_t v = 0; v < m->nv; v++) assert_int_equal(m->he_vert[m->v_he[v]], v);
        for (uint32_t f = 0; f < m->nf; f++) assert_int_equal(m->he_face[m->f_he[f]], f);
    }
    return st;
}

static void test_tetrahedron(void **state)
{
    (void)state;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    sq_soup s = make_soup(4, tet_pos, 4, 3, idx, off);
    sq_mesh m;
    sq_error err;
    assert_int_equal(build(&s, 0, &m, &err), SQ_OK);
    assert_int_equal(m.nh, 12);
    assert_int_equal(sq_mesh_euler(&m), 2);
    assert_int_equal(sq_mesh_genus(&m), 0);
    for (uint32_t v = 0; v < 4; v++) assert_int_equal(sq_mesh_vertex_valence(&m, v), 3);
    /* three right triangles of area 1/2 and one equilateral of side sqrt 2 */
    assert_true(fabs(sq_mesh_area(&m) - (1.5 + sqrt(3.0) / 2)) < 1e-15);
    sq_mesh_free(&m);
}

/* n x k torus grid, genus 1 */
static void torus_soup(uint32_t n, uint32_t k, double **pos, uint32_t **idx, uint32_t **off,
                       sq_soup *s)
{
    *pos = malloc(3 * n * k * sizeof **pos);
    *idx = malloc(6 * n * k * sizeof **idx);
    *off = malloc((2 * n * k + 1) * sizeof **off);
    for (uint32_t i = 0; i < n; i++) {
        for (uint32_t j = 0; j < k; j++) {
            double u = 6.283185307179586 * i / n, v = 6.283185307179586 * j / k;
            double *p = *pos + 3 * (i * k + j);
            p[0] = (2 + cos(v)) * cos(u);
            p[1] = (2 + cos(v)) * sin(u);
            p[2] = sin(v);
            uint32_t a = i * k + j, b = ((i + 1) % n) * k + j;
            uint32_t c = ((i + 1) % n) * k + (j + 1) % k, d = i * k + (j + 1) % k;
            uint32_t *t = *idx + 6 * (i * k + j);
            t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
        }
    }
    *s = make_soup(n * k, *pos, 2 * n * k, 3, *idx, *off);
}

static void test_torus_genus(void **state)
{
    (void)state;
    double *pos;
    uint32_t *idx, *off;
    sq_soup s;
    torus_soup(9, 5, &pos, &idx, &off, &s);
    sq_mesh m;
    sq_error err;
    assert_int_equal(build(&s, 0, &m, &err), SQ_OK);
    assert_int_equal(sq_mesh_euler(&m), 0);
    assert_int_equal(sq_mesh_genus(&m), 1);
    sq_mesh_free(&m);
    free(pos), free(idx), free(off);
}

static void expect_error(sq_soup *s, unsigned flags, sq_status code, const char *substring)
{
    sq_mesh m;
    sq_error err;
    sq_error_clear(&err);
    sq_status st = build(s, flags, &m, &err);
    if (st != code || !strstr(err.msg, substring))
        fail_msg("expected %s containing '%s', got %s: %s", sq_status_name(code), substring,
                 sq_status_name(st), err.msg);
}

static void test_flipped_face(void **state)
{
    (void)state;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    idx[10] = 3, idx[11] = 2; /* face 3 = (1, 3, 2) */
    sq_soup s = make_soup(4, tet_pos, 4, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_ORIENTATION, "inconsistent orientation");
}

static void test_open(void **state)
{
    (void)state;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    sq_soup s = make_soup(4, tet_pos, 3, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_BOUNDARY, "3 boundary edges in total");
}

static void test_nan(void **state)
{
    (void)state;
    double pos[12];
    memcpy(pos, tet_pos, sizeof pos);
    pos[7] = NAN;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    sq_soup s = make_soup(4, pos, 4, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_NOT_FINITE, "vertex 2 has a non-finite coordinate");
    pos[7] = INFINITY;
    expect_error(&s, 0, SQ_ERR_NOT_FINITE, "vertex 2");
}

static void test_index_and_repeat(void **state)
{
    (void)state;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    idx[4] = 7;
    sq_soup s = make_soup(4, tet_pos, 4, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_INDEX, "face 1 uses vertex 7, but there are only 4 vertices");
    memcpy(idx, tet_idx, sizeof idx);
    idx[5] = 0;
    expect_error(&s, 0, SQ_ERR_REPEATED_VERTEX, "face 1 uses vertex 0 twice");
}

static void test_unreferenced(void **state)
{
    (void)state;
    double pos[15];
    memcpy(pos, tet_pos, sizeof tet_pos);
    pos[12] = pos[13] = pos[14] = 5;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    sq_soup s = make_soup(5, pos, 4, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_UNREFERENCED, "vertex 4 is not used by any face");
}

static void test_polygon(void **state)
{
    (void)state;
    /* unit cube of quads */
    double pos[24];
    for (int i = 0; i < 8; i++) {
        pos[3 * i] = i >> 2 & 1, pos[3 * i + 1] = i >> 1 & 1, pos[3 * i + 2] = i & 1;
    }
    uint32_t idx[] = {0, 1, 3, 2, 4, 6, 7, 5, 0, 4, 5, 1, 2, 3, 7, 6, 0, 2, 6, 4, 1, 5, 7, 3};
    uint32_t off[7];
    sq_soup s = make_soup(8, pos, 6, 4, idx, off);
    expect_error(&s, 0, SQ_ERR_POLYGON, "face 0 is a polygon with 4 vertices");
    sq_mesh m;
    sq_error err;
    assert_int_equal(build(&s, SQ_MESH_ALLOW_POLYGONS, &m, &err), SQ_OK);
    assert_int_equal(sq_mesh_genus(&m), 0);
    assert_int_equal(m.nh, 24);
    sq_mesh_free(&m);
}

static void test_two_components_and_bowtie(void **state)
{
    (void)state;
    double pos[24];
    uint32_t idx[24], off[9];
    memcpy(pos, tet_pos, sizeof tet_pos);
    for (int i = 0; i < 12; i++) pos[12 + i] = tet_pos[i] + (i % 3 == 0 ? 5 : 0);
    for (int i = 0; i < 12; i++) idx[i] = tet_idx[i], idx[12 + i] = tet_idx[i] + 4;
    sq_soup s = make_soup(8, pos, 8, 3, idx, off);
    expect_error(&s, 0, SQ_ERR_COMPONENTS, "2 connected components");
    /* glue vertex 4 onto vertex 0: a bow-tie (vertex 4 then unused: drop it
     * by renumbering the second tetrahedron onto 0, 5, 6, 7) */
    for (int i = 12; i < 24; i++)
        if (idx[i] == 4) idx[i] = 0;
    pos[12] = pos[13] = pos[14] = 0; /* vertex 4 unused now */
    expect_error(&s, 0, SQ_ERR_UNREFERENCED, "vertex 4");
    /* move vertex 7 into slot 4 so every vertex is used again */
    for (int i = 12; i < 24; i++)
        if (idx[i] == 7) idx[i] = 4;
    s.nv = 7;
    expect_error(&s, 0, SQ_ERR_NONMANIFOLD_VERTEX, "non-manifold vertex 0");
}

static void test_nonmanifold_edge(void **state)
{
    (void)state;
    /* three triangles around edge (0, 1) plus caps: a "book" of three
     * tetrahedra sharing edge (0,1) is enough to see the edge with 6 faces */
    double pos[18] = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
    uint32_t idx[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
    uint32_t off[4];
    sq_soup s = make_soup(6, pos, 3, 3, idx, off);
    s.nv = 5;
    expect_error(&s, 0, SQ_ERR_NONMANIFOLD_EDGE, "non-manifold edge (0, 1): shared by 3 faces");
}

/* Octahedron with one face replaced by a fan around an extra vertex p placed
 * on (or next to) the segment between two of its corners. */
static sq_status split_octahedron(double px, double py, double pz, sq_error *err)
{
    double pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, px, py, pz};
    /* faces (outward): split face (0, 2, 4) at p=6 into (0,2,6),(2,4,6),(4,0,6) */
    uint32_t idx[] = {0, 2, 6, 2, 4, 6, 4, 0, 6, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                      2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    uint32_t off[11];
    sq_soup s = make_soup(7, pos, 10, 3, idx, off);
    sq_mesh m;
    sq_status st = sq_mesh_from_soup(&s, 0, &m, err);
    if (st == SQ_OK) sq_mesh_free(&m);
    return st;
}

static void test_degenerate_exact(void **state)
{
    (void)state;
    sq_error err;
    /* p exactly on segment (0,2): (0.5, 0.5, 0) - face (0, 2, 6) collinear */
    sq_error_clear(&err);
    assert_int_equal(split_octahedron(0.5, 0.5, 0, &err), SQ_ERR_DEGENERATE);
    assert_non_null(strstr(err.msg, "degenerate face 0"));
    /* 0.6 is not a dyadic number, but 1 - 0.6 is exact (Sterbenz), so
     * (0.6, 1 - 0.6, 0) is exactly on the segment; one ulp less is not */
    double x = 0.6, y = 1.0 - x;
    assert_int_equal(split_octahedron(x, y, 0, &err), SQ_ERR_DEGENERATE);
    assert_int_equal(split_octahedron(x, nextafter(y, 0), 0, &err), SQ_OK);
    /* nearly degenerate: 1e-16 of the bounding box off the segment: valid */
    assert_int_equal(split_octahedron(0.5, 0.5, 1e-16, &err), SQ_OK);
    assert_int_equal(split_octahedron(0.5, 0.5 + 0x1p-52, 0, &err), SQ_OK);
}

static void test_empty(void **state)
{
    (void)state;
    uint32_t off[1] = {0};
    sq_soup s;
    memset(&s, 0, sizeof s);
    s.face_off = off;
    expect_error(&s, 0, SQ_ERR_EMPTY, "no vertices");
    s.nv = 4;
    s.pos = tet_pos;
    expect_error(&s, 0, SQ_ERR_EMPTY, "no faces");
}

static void test_provenance(void **state)
{
    (void)state;
    uint32_t idx[12], off[5];
    memcpy(idx, tet_idx, sizeof idx);
    idx[10] = 3, idx[11] = 2;
    sq_soup s = make_soup(4, tet_pos, 4, 3, idx, off);
    uint32_t vl[4] = {2, 3, 4, 5}, fl[4] = {7, 8, 9, 10};
    char path[] = "mesh.obj";
    s.vert_line = vl;
    s.face_line = fl;
    s.path = path;
    expect_error(&s, 0, SQ_ERR_ORIENTATION, "mesh.obj: inconsistent orientation: faces 0 (line 7) and 3 (line 10)");
    s.nf = 3;
    expect_error(&s, 0, SQ_ERR_BOUNDARY, "mesh.obj:");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tetrahedron),
        cmocka_unit_test(test_torus_genus),
        cmocka_unit_test(test_flipped_face),
        cmocka_unit_test(test_open),
        cmocka_unit_test(test_nan),
        cmocka_unit_test(test_index_and_repeat),
        cmocka_unit_test(test_unreferenced),
        cmocka_unit_test(test_polygon),
        cmocka_unit_test(test_two_components_and_bowtie),
        cmocka_unit_test(test_nonmanifold_edge),
        cmocka_unit_test(test_degenerate_exact),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_provenance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
