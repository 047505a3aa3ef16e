/* seamquad: halfedge mesh as flat index arrays.
 *
 * Halfedge h runs from vertex he_vert[h] to vertex he_vert[he_next[h]] and
 * lies in face he_face[h]; he_twin[h] is the opposite halfedge (always valid:
 * meshes here are closed). For a mesh built from a soup, the halfedges of
 * face f are face_off[f] .. face_off[f+1]-1 in the soup's corner order, so
 * halfedge c starts at corner c. */
#ifndef SQ_MESH_H
#define SQ_MESH_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_mesh {
    uint32_t nv, nf, nh;
    double *pos;          /* 3*nv                                   */
    uint32_t *he_next;    /* nh                                     */
    uint32_t *he_twin;    /* nh                                     */
    uint32_t *he_vert;    /* nh: origin vertex                      */
    uint32_t *he_face;    /* nh                                     */
    uint32_t *v_he;       /* nv: one outgoing halfedge              */
    uint32_t *f_he;       /* nf: first halfedge of the face         */
} sq_mesh;

enum {
    /* accept faces of any valence >= 3 (quad meshes); default: triangles */
    SQ_MESH_ALLOW_POLYGONS = 1u << 0,
    /* skip the exact collinearity test of triangles */
    SQ_MESH_SKIP_DEGENERATE = 1u << 1
};

/* Validates the soup and builds the halfedge mesh. Checks, in this order:
 * non-empty; finite coordinates; face valence; indices in range; no
 * repeated vertex in a face; every vertex used; edge-manifold; consistent
 * orientation; closed; vertex-manifold; one connected component; no
 * triangle with exactly collinear corners (exact predicate). The first
 * violation is returned with a message naming the element and its file and
 * line; the message also counts further violations of the same kind. */
sq_status sq_mesh_from_soup(const sq_soup *soup, unsigned flags, sq_mesh *out, sq_error *err);

void sq_mesh_free(sq_mesh *m);

/* Euler characteristic V - E + F (E = nh/2). */
int64_t sq_mesh_euler(const sq_mesh *m);

/* Genus of a closed orientable connected mesh: (2 - chi)/2. */
int64_t sq_mesh_genus(const sq_mesh *m);

/* Number of faces around vertex v (its valence). */
uint32_t sq_mesh_vertex_valence(const sq_mesh *m, uint32_t v);

/* The area of face f of a triangle mesh (its first three corners from
 * f_he[f]); sq_mesh_area: the sum over m's faces. */
double sq_mesh_face_area(const sq_mesh *m, uint32_t f);
double sq_mesh_area(const sq_mesh *m);

/* The length of the diagonal of the bounding box of nv points (3 nv
 * coordinates): the scale the referees' tolerances are relative to. */
double sq_bbox_diagonal(uint32_t nv, const double *pos);

/* The triangles of the triangle mesh m as 3 nf vertex indices, each face's
 * corners from f_he[f] on (malloc'ed; NULL when out of memory). */
uint32_t *sq_mesh_triangles(const sq_mesh *m);

/* Area-weighted vertex normals of the triangles tri (3 nt): vn (3 nv,
 * overwritten) receives at each vertex the sum of its triangles' cross
 * products (b - a) x (c - a), twice their areas times their unit normals;
 * not normalized. */
void sq_area_weighted_normals(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri, double *vn);

/* The same for a triangle mesh, each normalized (3 nv, malloc'ed; NULL
 * when out of memory); sq_mesh_normal_at: their interpolation by the
 * barycentric coordinates bary in face f (for the corners from f_he[f]
 * on), normalized: the surface's smooth normal there, which a sliver
 * triangle's own (noise) normal does not decide. */
double *sq_mesh_vertex_normals(const sq_mesh *m);
void sq_mesh_normal_at(const sq_mesh *m, const double *vn, uint32_t f, const double bary[3], double n[3]);

#ifdef __cplusplus
}
#endif
#endif
