/* seamquad: helpers shared by the sq_guide_* files (not a public API). */
#ifndef SQ_GUIDE_INTERNAL_H
#define SQ_GUIDE_INTERNAL_H

#include <stdint.h>

#include "sq_cut_internal.h"
#include "sq_mesh.h"

/* Whether the tree vertex x may end a path arriving from its neighbour u. */
typedef int (*sq_guide_end_fn)(void *user, uint32_t x, uint32_t u);

/* One path of the surface cone tree (seed 9.4): Dijkstra (Euclidean edge
 * lengths) from s through vertices that are neither blocked nor on the
 * tree (owner[v] != SQ_NONE) to the nearest tree vertex, arriving by an
 * edge that end_ok accepts (end_ok may be NULL: any). dist must be
 * INFINITY everywhere on entry; the vertices it touches are listed in
 * touched (*nt of them) for the caller to reset. Returns the tree vertex
 * reached (par[] leads back to s), SQ_NONE when none is, or SQ_NONE with
 * *nomem set. */
uint32_t sq_guide_surface_path(const sq_mesh *m, const uint8_t *blocked, const uint32_t *owner,
                               sq_guide_end_fn end_ok, void *user, uint32_t s, double *dist,
                               uint32_t *par, uint32_t *touched, uint32_t *nt, sq_cut_heap *heap,
                               int *nomem);

#endif
