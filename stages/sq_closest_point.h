/* seamquad: closest point on a triangle mesh (a bounding-volume hierarchy in
 * C; see docs/smooth.md).
 *
 * The tree copies the triangles' corner coordinates, so the caller's arrays
 * may be freed after sq_cp_tree_build. A query returns the exact nearest
 * triangle (ties broken by the lower triangle index) and the closest point
 * as a barycentric combination of that triangle's corners, so the point lies
 * on the surface up to the rounding of one affine combination. */
#ifndef SQ_CLOSEST_POINT_H
#define SQ_CLOSEST_POINT_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_cp_node {
    double lo[3], hi[3];  /* bounding box of the node's triangles          */
    uint32_t first;       /* leaf: first slot in tri_order; inner: left child */
    uint32_t count;       /* leaf: number of triangles; inner: 0 (right = left + 1) */
} sq_cp_node;

typedef struct sq_cp_tree {
    uint32_t nt;          /* triangles                                      */
    double *corner;       /* 9*nt: the three corners of each triangle       */
    uint32_t *tri_order;  /* nt: triangles in leaf order                    */
    sq_cp_node *node;     /* nnode nodes, node 0 is the root                */
    uint32_t nnode;
} sq_cp_tree;

typedef struct sq_cp_hit {
    double point[3];      /* closest point on the surface                   */
    double bary[3];       /* its barycentric coordinates in triangle `tri`  */
    double dist2;         /* squared distance from the query point          */
    uint32_t tri;         /* index of the nearest triangle                  */
} sq_cp_hit;

/* Builds the tree over nt triangles (tri: 3*nt indices into pos: 3*nv). */
sq_status sq_cp_tree_build(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri,
                           sq_cp_tree *out, sq_error *err);

void sq_cp_tree_free(sq_cp_tree *t);

/* Nearest point of the triangle mesh to p. */
void sq_cp_tree_query(const sq_cp_tree *t, const double p[3], sq_cp_hit *hit);

/* Closest point of triangle (a, b, c) to p: barycentrics in bary, the
 * point in q (exact at a corner or on a side's endpoints; accurate on
 * needles, sq_closest_point_triangle.c). */
void sq_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double bary[3], double q[3]);

#ifdef __cplusplus
}
#endif
#endif
