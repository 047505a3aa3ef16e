/* seamquad: helpers shared by the sq_guide_* files (not a public API). */
#ifndef SQ_GUIDE_INTERNAL_H
#define SQ_GUIDE_INTERNAL_H

#include <stdint.h>

#include "sq_cut_internal.h"
#include "sq_mesh.h"

/* The vertices off G's cut numbered 0, 1, ... in idx (m->nv entries;
 * SQ_NONE on the cut); returns their count (sq_guide_surface_disk.c). */
uint32_t sq_guide_inner_index(const sq_mesh *m, const sq_cut_graph *G, uint32_t *idx);

/* G's boundary walk (G->side_he, counterclockwise around the cut disk):
 * walk_of[h] = j for its j-th halfedge, SQ_NONE for the others (m->nh
 * entries); len[j] the walk's arc length before it (nb entries). Returns
 * the total length (sq_guide_surface_disk.c). */
double sq_guide_walk_lengths(const sq_mesh *m, const sq_cut_graph *G, uint32_t *walk_of, double *len);

/* The walk index of the sector that holds the origin of halfedge h on the
 * cut: the first cut halfedge met turning clockwise from h (h itself if it
 * is one); SQ_NONE if none is on the walk (sq_guide_surface_disk.c). */
uint32_t sq_guide_sector_walk(const sq_mesh *m, const sq_cut_graph *G, const uint32_t *walk_of, uint32_t h);

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
