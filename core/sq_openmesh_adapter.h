/* seamquad: OpenMesh adapter (C API over core/adapter_openmesh.cpp).
 *
 * Test-only: reads a mesh file with OpenMesh's own readers so that a test
 * can cross-check our hand-written readers (tests/openmesh_crosscheck.c).
 * The product never reads user input through OpenMesh, because OpenMesh
 * alters input without an error: its importer gives every face that cannot
 * be added to its halfedge structure (non-manifold edge or vertex) fresh
 * copies of its vertices, drops faces with out-of-range indices, and its OBJ
 * reader removes repeated corners from a face. Messages that OpenMesh itself
 * writes go to its own log stream (stderr); this adapter does not touch it.
 *
 * Everything returned is in OpenMesh's order: vertices in handle order,
 * faces in handle order, and the corners of a face as OpenMesh's
 * face-vertex circulator visits them (it may start at another corner than
 * the file's face line). The mesh type is a polygon mesh with double
 * coordinates, so faces are never triangulated and nothing is lost in the
 * mesh itself; what a reader keeps of the file's digits is its own affair. */
#ifndef SQ_OPENMESH_ADAPTER_H
#define SQ_OPENMESH_ADAPTER_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_om_mesh {
    uint32_t nv;           /* vertices, including any OpenMesh added      */
    double *pos;           /* 3*nv                                        */
    uint32_t nf;           /* faces                                       */
    uint32_t *face_off;    /* nf+1 offsets into face_idx                  */
    uint32_t *face_idx;    /* face_off[nf] 0-based vertex indices         */
    /* OpenMesh's own record of what it changed: its importer flags as
     * "fixed non-manifold" the vertices it created and the faces it
     * re-attached to them when a face could not be added as given. */
    uint8_t *vert_fixed;   /* nv: 1 if OpenMesh created this vertex copy  */
    uint8_t *face_fixed;   /* nf: 1 if OpenMesh re-attached this face     */
    uint32_t n_vert_fixed; /* number of 1s in vert_fixed                  */
    uint32_t n_face_fixed; /* number of 1s in face_fixed                  */
    /* Texture coordinates kept by OpenMesh (only with SQ_OM_READ_TEXCOORDS
     * and only when the file has them): one (u, v) per face corner, same
     * layout as face_idx. NULL otherwise. */
    double *corner_uv;     /* 2*face_off[nf]                              */
} sq_om_mesh;

enum {
    /* Ask OpenMesh to read texture coordinates as well (OBJ `vt`): vertex
     * and per-halfedge (face corner) texture coordinates are requested
     * before reading, as an application that wants the UVs would do. */
    SQ_OM_READ_TEXCOORDS = 1u << 0
};

/* Reads `path` (OBJ, OFF or PLY, chosen by OpenMesh from the extension)
 * with OpenMesh::IO::read_mesh into `out`, which is zeroed first. On
 * failure `out` is left zeroed and err (may be NULL) names the problem.
 * No C++ exception leaves this function. */
sq_status sq_openmesh_read(const char *path, unsigned flags, sq_om_mesh *out, sq_error *err);

/* Frees every array of `m` and zeroes it. Safe on a zeroed struct. */
void sq_om_mesh_free(sq_om_mesh *m);

#ifdef __cplusplus
}
#endif
#endif
