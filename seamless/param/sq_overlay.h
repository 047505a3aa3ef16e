/* seamquad: common refinement (overlay) of two triangulations of one
 * polygon, for the interior map of the surface parametrization (seed 8;
 * seamless-notes 5: "overlay" of two bijective maps onto a convex disk).
 *
 * A and B triangulate the same polygon in the plane (in sq_param: the cut
 * surface and the domain Omega, both mapped bijectively onto the unit disk
 * with the same boundary points). Their boundary vertices are shared: the
 * same ids, the same points, the same boundary edges. Every piece of the
 * overlay is the intersection of a triangle of A and a triangle of B, a
 * convex polygon, cut into triangles by a fan. So every output triangle
 * lies in one triangle of A (it is a piece of the surface) and in one
 * triangle of B (the affine map of that triangle gives its UVs).
 *
 * The combinatorics is decided by exact orientation tests on the given
 * doubles only (never on computed crossing points): which vertices lie in
 * which triangle, which edges cross, and in which order along an edge.
 * Shared boundary vertices are decided by the angular order of the edges
 * of both fans there. Exactly collinear triples that the input's sharing
 * does not explain (a vertex of one mesh on an edge of the other) are
 * reported as SQ_ERR_SOLVER "degenerate"; the caller perturbs and retries.
 *
 * Vertex ids: [0, nbnd) the shared boundary, [nbnd, na) A's interior,
 * [na, nv) B's interior. Overlay vertex id nv + k is crossing k.
 * Neither A nor B may have an interior edge joining two boundary vertices
 * (a dividing edge), and the polygon must be convex at every boundary
 * vertex (angles below pi), as on a circle.
 *
 * The library never prints or exits. */
#ifndef SQ_OVERLAY_H
#define SQ_OVERLAY_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_overlay_mesh {
    uint32_t nf;
    const uint32_t *tri;  /* 3 nf vertex ids, counterclockwise            */
    const uint32_t *twin; /* 3 nf: the halfedge 3 g + j opposite halfedge  */
                          /* 3 f + i (corner i to i + 1); SQ_NONE on the   */
                          /* boundary                                      */
} sq_overlay_mesh;

typedef struct sq_overlay {
    uint32_t nx;       /* crossings (overlay vertex nv + k)                 */
    uint32_t *x_ha;    /* nx: the A halfedge 3 f + i crossed, and ...       */
    uint32_t *x_hb;    /* nx: ... the B halfedge 3 g + j crossing it        */
    double *x_ta;      /* nx: parameter along x_ha (0 at its corner i)      */
    double *x_tb;      /* nx: parameter along x_hb                          */
    uint32_t *loc;     /* nv: the face of the other mesh holding vertex v   */
                       /* strictly inside (A's interior vertices: a face of */
                       /* B; B's interior vertices: a face of A); SQ_NONE   */
                       /* for boundary vertices                             */
    double *bary;      /* 3 nv: barycentric coordinates in that face        */
    uint32_t ntri, cap_tri;
    uint32_t *tri;     /* 3 ntri: overlay vertex ids, counterclockwise      */
    uint32_t *tri_fa;  /* ntri: the face of A holding it                    */
    uint32_t *tri_fb;  /* ntri: the face of B holding it                    */
    uint64_t expected; /* crossings expected from the sample walk (set by   */
                       /* sq_overlay_build_threads, also when it fails; 0   */
                       /* when B is too small to sample)                    */
} sq_overlay;

void sq_overlay_init(sq_overlay *X);
void sq_overlay_free(sq_overlay *X);

/* Builds the overlay of A and B (xy: 2 nv disk positions). Both must be
 * embeddings (every triangle positively oriented, checked here exactly).
 * SQ_ERR_SOLVER: not an embedding, a degenerate configuration (see
 * above), or more than max_crossings crossings (0: no limit); SQ_ERR_INTERNAL: inconsistent input; SQ_ERR_NOMEM. */
sq_status sq_overlay_build(uint32_t nbnd, uint32_t na, uint32_t nv, const double *xy,
                           const sq_overlay_mesh *A, const sq_overlay_mesh *B, uint64_t max_crossings,
                           sq_overlay *out, sq_error *err);

/* The same, B's faces walked in two ranges (in two threads when threads >
 * 1); the result does not depend on threads and is the one of a single
 * walk over B's faces in order. The crossing budget applies to each range
 * alone (the second counting the crossings it shares with the first) and
 * to the whole. cancel (may be NULL): once it is set (by another thread),
 * the walk stops within 64 of B's faces with SQ_ERR_SOLVER "cancelled".
 * Before the walk (with one thread or two alike), every 16th of B's faces
 * is walked alone, a sample of the work: out->expected = 8 times the
 * sample's crossings (each edge of B has two faces; within 6% of the
 * count on the shared models' overlays: ratios 7.6 to 8.5). Where, with
 * max_expected not 0, it exceeds max_crossings by more than a quarter or
 * max_expected itself (UINT64_MAX: the budget alone), the call fails at
 * once with SQ_ERR_SOLVER ("expected"), about 1/16 of the walk's time
 * instead of the walk up to its budget. sq_overlay_build is this with
 * max_expected 0, one thread: the sample only splits the walk. */
sq_status sq_overlay_build_threads(uint32_t nbnd, uint32_t na, uint32_t nv, const double *xy,
                                   const sq_overlay_mesh *A, const sq_overlay_mesh *B, uint64_t max_crossings,
                                   uint64_t max_expected, uint32_t threads, const _Atomic int *cancel,
                                   sq_overlay *out, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
