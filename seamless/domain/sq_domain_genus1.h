/* seamquad: internals of the genus-1 domain (seed 6.2, 6.3; docs/domain.md,
 * "Genus 1"). Shared by sq_domain_genus1*.c and the tests; not installed.
 *
 * The torus is built from two pieces: a meta-6-gon (cones of total excess
 * +2) and a meta-2-gon (total excess -2), whose 8 sides pair up into a torus
 * with two regular branch points. */
#ifndef SQ_DOMAIN_GENUS1_H
#define SQ_DOMAIN_GENUS1_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_metapolygon.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of sides over all pieces handled by the enumeration. */
#define SQ_G1_MAX_SIDES 12u

/* Side-pairing patterns of several pieces (seed 6.2, 6.3). Piece p has
 * k[p] >= 1 sides, numbered consecutively over the pieces (piece 0 first);
 * within a piece side s runs from corner s to corner next(s) in boundary
 * order, corner s being shared with the previous side of the piece. A
 * pairing glues side i forward to side partner[i] backward (corner i ~
 * corner next(partner[i]), corner next(i) ~ corner partner[i]).
 *
 * Enumerates every fixed-point-free involution of the n = sum k[p] sides
 * (n even, n <= SQ_G1_MAX_SIDES) whose corners fall into classes of exactly
 * four (each a regular point of four right angles) and whose pieces are
 * connected by the pairs. With F = npieces faces, E = n/2 edges and V = n/4
 * vertices the glued surface has Euler characteristic npieces - n/4: a
 * torus for two pieces with 8 sides.
 *
 * out (cap * n entries, may be NULL) receives the partner arrays one after
 * another; glue (cap entries, may be NULL) a side i of piece 0 whose pair
 * joins piece 0 to piece 1 and whose two ends lie in different corner
 * classes (gluing that pair first leaves two straight corners in different
 * classes), or UINT32_MAX when there is none. Returns the total number of
 * patterns (may exceed cap). */
uint32_t sq_g1_patterns(uint32_t npieces, const uint32_t *k, uint32_t cap, uint32_t *out,
                        uint32_t *glue);

/* Builds the quad disk Q (initialized, empty) from nf quads over vertices
 * 0..nv-1, each quad counterclockwise (4 vertex ids per quad, quad[4f+c]).
 * Quad f gets halfedges 4f..4f+3 (4f+c leaves quad[4f+c]); boundary
 * halfedges follow. Twins by matching, one boundary loop (clockwise, the
 * sq_metapolygon convention), v_he of a boundary vertex its outgoing
 * boundary halfedge. Returns SQ_ERR_INTERNAL if the quads do not form a
 * manifold disk (then checked by sq_metapolygon_validate). */
sq_status sq_g1_quads_to_disk(uint32_t nv, uint32_t nf, const uint32_t *quad, sq_metapolygon *Q,
                              sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
