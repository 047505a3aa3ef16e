/* seamquad: the stages of remesh between themselves (private to stages/,
 * not installed; sq_remesh.h is the public API). */
#ifndef SQ_REMESH_INTERNAL_H
#define SQ_REMESH_INTERNAL_H

#include "sq_remesh.h"

/* The quads' intersecting triangle pairs (CGAL), each quad split along its
 * shorter diagonal as the referee splits it: the count in *pairs and the
 * first min(cap, *pairs) pairs as quad indices in list (may be NULL)
 * (sq_remesh_repair.c). */
sq_status sq_remesh_quad_intersections(const sq_quad_mesh *Q, uint64_t *pairs, uint32_t *list, uint32_t cap,
                                       sq_error *err);

/* Stage 8's repair (sq_remesh_repair.c): the vertices of intersecting
 * quads and, round by round, their rings (cones excepted) relaxed on m's
 * surface; Q->pos ends with the fewest pairs found (*pairs), after
 * *rounds rounds (at most 20). Connectivity unchanged; no move folds a
 * quad that was not folded. */
sq_status sq_remesh_repair_intersections(const sq_mesh *m, sq_quad_mesh *Q, uint64_t *pairs, uint32_t *rounds,
                                         sq_error *err);

/* The magnified layouts (sq_remesh_magnify.c). sq_remesh_intersecting_points:
 * the centroids of the quads of Q's intersecting triangle pairs appended
 * to pts (3 per point, *npts of at most cap). sq_remesh_magnify_map: M
 * optimized again from where it is, drawn toward `factor` times the
 * surface's size around the points (each face's reference triangle
 * scaled by 1 + (factor - 1) exp(-(d / radius)^2), d the distance from its
 * centroid to the nearest point; sq_optimize_options.face_scale), its last
 * iterate kept (its energy is against the magnified surface); base gives
 * the basis and the budget. Cost: faces times points, and the optimizer. */
sq_status sq_remesh_intersecting_points(const sq_quad_mesh *Q, double *pts, uint32_t *npts, uint32_t cap,
                                        sq_error *err);
sq_status sq_remesh_magnify_map(sq_map *M, const double *pts, uint32_t npts, double radius, double factor,
                                const sq_optimize_options *base, sq_error *err);

#endif
