/* seamquad: a seamless map on the input mesh itself, from seam rotations
 * alone (docs/optimize.md, "A map on the input mesh").
 *
 * param's maps are valid by construction but refine the input 10 to 35
 * times and start far from conformal; the optimizer then spends most of
 * its time on added vertices. This builds a map with no added vertex:
 *  1. rotations: the transport `turn` of a cross field with the cones
 *     (sq_cone_connection: an angle per halfedge whose sum around every
 *     loop is an integer number of quarter turns) made integer per edge by
 *     a face spanning tree; the edges off the tree, less the dangling ones
 *     at regular vertices, are the seams (a cut graph);
 *  2. the seamless map closest to the field: among the maps with these
 *     rotations and free translations (sq_uv_basis.h), the least-squares
 *     fit of every triangle's Jacobian to the field's frame there (the
 *     tree's integrated transport) scaled by the conformal factor the cones
 *     ask for (the linearized curvature prescription of Ben-Chen, Gotsman
 *     and Bunin 2008: one Laplace solve); one sparse Cholesky;
 *  3. untangling (sq_map_untangle.c): the foldover-free energy of Garanzha
 *     et al. 2021, "Foldover-free maps in 50 lines of code", minimized by
 *     projected Newton while its regularization shrinks, until every
 *     triangle is positive;
 *  4. the result snapped to a dyadic grid and checked exactly
 *     (sq_map_from_soup: positive triangles by the exact predicate, exact
 *     transitions, angle sums equal to the cones).
 * Nothing guarantees step 3 succeeds (a coarse mesh may have no valid map
 * with these rotations, or the untangling may stall); then no map is
 * returned and rep->why says why: callers keep the map of the seed's
 * construction as the fallback.
 *
 * Cost: one sparse Cholesky for step 2, one per untangling iteration (the
 * input's size, about twice its vertex count unknowns). */
#ifndef SQ_MAP_FROM_ROTATIONS_H
#define SQ_MAP_FROM_ROTATIONS_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"
#include "sq_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_rotation_map_options {
    uint32_t max_iterations; /* untangling Newton iterations (0: 300)            */
} sq_rotation_map_options;

typedef struct sq_rotation_map_report {
    int valid;                 /* 1: out holds a map that passed every check   */
    uint32_t seam_edges;       /* edges of the cut graph                       */
    uint32_t flipped_start;    /* triangles not positive in the field fit (step 2) */
    uint32_t iterations;       /* untangling Newton iterations                 */
    uint32_t rounds;           /* values of the regularization epsilon         */
    uint32_t flipped_after;    /* triangles not positive after untangling      */
    double seconds_fit, seconds_untangle, seconds;
    char why[200];             /* why no map was returned                      */
} sq_rotation_map_report;

/* m: closed triangle mesh; valence: nv cone valences (4 regular); turn: nh
 * transport angles in quarter turns (sq_cone_connection's convention: from
 * face(h) into face(twin(h)), turn[twin(h)] = -turn[h], integer sums
 * around loops, 4 - valence around a vertex). On success rep->valid = 1
 * and out is an exact map of m (its faces in m's order, corners from
 * f_he[f] on; rotations kept, translations free). Otherwise out is zeroed
 * and rep->why says why. Errors only for bad arguments, memory or a solver
 * failure. opt may be NULL. */
sq_status sq_map_from_rotations(const sq_mesh *m, const int32_t *valence, const double *turn,
                                const sq_rotation_map_options *opt, sq_map *out,
                                sq_rotation_map_report *rep, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
