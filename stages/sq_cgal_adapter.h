/* seamquad: the CGAL adapter (stages/adapter_cgal.cpp), a thin extern "C"
 * wrapper around CGAL's Polygon Mesh Processing (Debian libcgal-dev).
 *
 * It only hands out what CGAL computes: the pairs of triangles of a closed
 * triangle mesh that intersect beyond what they share (a common edge or
 * vertex), decided with exact predicates (CGAL's filtered exact
 * predicates; under valgrind their floating-point filters are unreliable,
 * the sanitizer build uses ASan instead). */
#ifndef SQ_CGAL_ADAPTER_H
#define SQ_CGAL_ADAPTER_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The number of intersecting triangle pairs of the mesh (pos: 3 nv, tri:
 * 3 nt vertex indices; an oriented manifold, closed or not) in *pairs, and
 * the first min(cap, *pairs) pairs found in list (2 triangle indices each;
 * list may be NULL). SQ_ERR_ARGUMENT if CGAL cannot build the mesh (not
 * manifold). */
sq_status sq_cgal_self_intersections(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri,
                                     uint64_t *pairs, uint32_t *list, uint32_t cap, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
