/* seamquad: a planar picture of a combinatorial disk (Tutte embedding).
 *
 * Boundary vertices go to the unit circle, spaced evenly in boundary order;
 * every interior vertex goes to the average of its neighbours (uniform
 * weights, one sparse SPD solve). This is the layout of seed Fig. 8 (c, d):
 * it only serves pictures and coordinates of combinatorial outputs, never a
 * decision of the construction. */
#ifndef SQ_DISK_LAYOUT_H
#define SQ_DISK_LAYOUT_H

#include "sq_error.h"
#include "sq_metapolygon.h"

#ifdef __cplusplus
extern "C" {
#endif

/* xy: 2*P->nv doubles (caller-owned). start: a boundary halfedge whose
 * origin goes to angle 0 (SQ_NONE: P->bnd_he). The boundary runs clockwise
 * around the disk (sq_metapolygon convention), so it is laid out clockwise
 * and faces come out counterclockwise. */
sq_status sq_disk_layout_tutte(const sq_metapolygon *P, uint32_t start, double *xy,
                               sq_error *err);

/* The same interior solve with the boundary vertices' positions taken from
 * xy as the caller set them (any convex placement gives an embedding). */
sq_status sq_disk_layout_tutte_fixed(const sq_metapolygon *P, double *xy, sq_error *err);

/* A sphere cut along one edge (a disk whose boundary loop has at most two
 * halfedges, as the genus-0 domain is; its Tutte layout would put every
 * vertex on one segment): face `outer`'s vertices go to the unit circle,
 * clockwise and evenly spaced, every other vertex to the average of its
 * neighbours on the sphere (the cut edge counted as one edge). Face
 * `outer` is then the unbounded face of a planar drawing of the sphere. */
sq_status sq_disk_layout_sphere(const sq_metapolygon *P, uint32_t outer, double *xy, sq_error *err);

/* The outer face the pictures of a genus-0 domain use: the last face (a
 * padding quad, away from the cones). */
static inline uint32_t sq_disk_layout_sphere_outer(const sq_metapolygon *P) { return P->nf ? P->nf - 1 : 0; }

#ifdef __cplusplus
}
#endif
#endif
