/* seamquad tests: loading the real meshes and cone files of ../shared/data
 * (SQ_SHARED_DIR) shared by the tests of seamless/ (include after cmocka.h).
 * Every failure fails the test with the library's message, which names the
 * file (and line, vertex or face). */
#ifndef SQ_TEST_MESH_H
#define SQ_TEST_MESH_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_mesh.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

/* buf = SQ_SHARED_DIR/data/rel; a path that does not fit fails the test. */
static inline void sq_test_data_path(char *buf, size_t cap, const char *rel)
{
    const int n = snprintf(buf, cap, "%s/data/%s", SQ_SHARED_DIR, rel);
    if (n < 0 || (size_t)n >= cap) fail_msg("path too long: %s/data/%s", SQ_SHARED_DIR, rel);
}

/* Reads the mesh file at path into the halfedge mesh *m (sq_mesh_free). */
static inline void sq_test_read_mesh(sq_mesh *m, const char *path)
{
    sq_error err;
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    memset(m, 0, sizeof *m);
    if (sq_read_mesh(path, &soup, &err) != SQ_OK) fail_msg("reading mesh: %s", err.msg);
    const sq_status st = sq_mesh_from_soup(&soup, 0, m, &err);
    sq_soup_free(&soup);
    if (st != SQ_OK) fail_msg("building halfedge mesh of %s: %s", path, err.msg);
}

/* Reads the cone file at path (Th_hat or cone list) for a mesh of nv
 * vertices: nv per-vertex valences, caller frees. */
static inline int32_t *sq_test_read_valence(const char *path, uint32_t nv)
{
    sq_error err;
    sq_cone_format fmt;
    int32_t *val = malloc(nv * sizeof *val);
    assert_non_null(val);
    if (sq_cones_read(path, nv, val, &fmt, &err) != SQ_OK) fail_msg("reading cones: %s", err.msg);
    return val;
}

/* The same, by path relative to SQ_SHARED_DIR/data ("mpz/eight.obj"). */
static inline void sq_test_load_mesh(sq_mesh *m, const char *rel)
{
    char path[1024];
    sq_test_data_path(path, sizeof path, rel);
    sq_test_read_mesh(m, path);
}

static inline int32_t *sq_test_load_valence(const char *rel, uint32_t nv)
{
    char path[1024];
    sq_test_data_path(path, sizeof path, rel);
    return sq_test_read_valence(path, nv);
}

#endif
