/* seamquad: private parts of the rectangle cells of Omega (sq_omega_cells.c,
 * sq_omega_cells_verify.c), shared with their tests. */
#ifndef SQ_OMEGA_CELLS_INTERNAL_H
#define SQ_OMEGA_CELLS_INTERNAL_H

#include "sq_omega_cells.h"

/* Independent check of C against O (everything sq_omega_cells_build
 * promises, recomputed from the chord list, f_cell and cell_box alone):
 * - chords: contiguous halfedge runs (he_off), interior edges of O->cut,
 *   each edge on one chord only, he_chord equal to the union of the chords;
 *   every chord straight (one unit direction in the layout), starting on
 *   the boundary, every vertex strictly inside it interior and on no
 *   earlier chord, ending on the boundary or on an earlier chord;
 * - start_sector / end_sector: a face halfedge leaving the chord's start /
 *   end vertex along a boundary edge or an earlier chord, from which the
 *   chord's own edge is reached counterclockwise before any other boundary
 *   edge or earlier chord (the sector the chord was shot into / arrived in);
 * - sectors: at every vertex, at most two quads between consecutive
 *   boundary or chord edges;
 * - cells: f_cell is constant across every edge that is not a chord and
 *   differs across every chord; each cell is one connected set of quads;
 *   its quads tile cell_box exactly (count = area, each unit square of the
 *   box covered once, none outside) and every boundary or chord edge of its
 *   quads lies on the box's boundary.
 * SQ_ERR_INTERNAL names the first violation. */
sq_status sq_omega_cells_verify(const sq_omega *O, const sq_omega_cells *C, sq_error *err);

#endif
