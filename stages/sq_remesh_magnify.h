/* seamquad: the magnified layouts of remesh (private to stages/, not
 * installed). */
#ifndef SQ_REMESH_MAGNIFY_H
#define SQ_REMESH_MAGNIFY_H

#include "sq_remesh.h"

/* The magnified layouts (sq_remesh_magnify.c). sq_remesh_intersecting_points:
 * the centroids of the quads of Q's intersecting triangle pairs appended
 * to pts (3 per point, *npts of at most cap). sq_remesh_magnify_map: M
 * optimized again from where it is, drawn toward `factor` times the
 * surface's size around the points (each face's reference triangle
 * scaled by 1 + (factor - 1) exp(-(d / radius)^2), d the distance from its
 * centroid to the nearest point; sq_optimize_options.face_scale), its last
 * iterate kept (its energy is against the magnified surface); base gives
 * the basis and the budget. Cost: faces times points, and the optimizer.
 * sq_remesh_surface_area: the area of m's triangles. */
sq_status sq_remesh_intersecting_points(const sq_quad_mesh *Q, double *pts, uint32_t *npts, uint32_t cap,
                                        sq_error *err);
sq_status sq_remesh_magnify_map(sq_map *M, const double *pts, uint32_t npts, double radius, double factor,
                                const sq_optimize_options *base, sq_error *err);
double sq_remesh_surface_area(const sq_mesh *m);

#endif
