/* seamquad: the quad mesh of a metapolygon, seed 5.4.
 *
 * Every k-gon is split into k quads around a new centre vertex, through new
 * edge-midpoint vertices. A face of valence i != 4 becomes an interior
 * vertex of valence i (a cone of curvature (4 - i) pi/2); every other
 * interior vertex has valence 4; metapolygon corners stay corners (one
 * quad) and every other boundary vertex is flat (two quads). A metapolygon
 * side of l edges becomes a run of 2l quad edges. Combinatorial only: no
 * positions. */
#ifndef SQ_METAPOLYGON_SUBDIVIDE_H
#define SQ_METAPOLYGON_SUBDIVIDE_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_metapolygon.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a quad-mesh vertex comes from. */
typedef enum sq_mp_origin {
    SQ_MP_ORIGIN_VERTEX = 0, /* a metapolygon vertex                       */
    SQ_MP_ORIGIN_EDGE = 1,   /* midpoint of an edge (index: its smaller     */
                             /* halfedge)                                   */
    SQ_MP_ORIGIN_FACE = 2    /* centre of a face                            */
} sq_mp_origin;

typedef struct sq_mp_quads {
    /* The quad mesh, in the halfedge layout of sq_metapolygon (all faces
     * 4-gons). Quad q has interior halfedges 4q .. 4q+3, so its vertices are
     * he_vert[4q + c], c = 0..3, counterclockwise; boundary halfedges
     * follow from 4*nf on. */
    sq_metapolygon mesh;
    uint8_t *v_origin_kind;  /* nv: sq_mp_origin                          */
    uint32_t *v_origin;      /* nv: vertex, halfedge or face index in P    */
    uint32_t *f_origin;      /* nf: metapolygon halfedge whose origin      */
                             /* corner (of its face) the quad covers       */
    uint8_t *v_corner;       /* nv: 1 for a metapolygon corner             */
    /* Boundary in boundary (clockwise) order, starting at corner 0. */
    uint32_t nbnd;
    uint32_t *bnd_vert;      /* nbnd: boundary vertices                    */
    uint32_t *bnd_he;        /* nbnd: boundary halfedge leaving bnd_vert[j] */
    /* Sides: side j runs over bnd_vert[corner_pos[j] .. corner_pos[j] +
     * side_len[j]] (indices mod nbnd, both ends included), from corner j to
     * corner j+1. */
    uint32_t ncorner;
    uint32_t *corner_pos;    /* ncorner                                    */
    uint32_t *side_len;      /* ncorner: length in quad edges (even, >= 2) */
} sq_mp_quads;

/* Seed 5.4: subdivides the metapolygon P (non-empty, no concave boundary
 * vertex) into out, which must be zeroed or freed. */
sq_status sq_metapolygon_subdivide(const sq_metapolygon *P, sq_mp_quads *out, sq_error *err);

/* Frees every array and zeroes Q. Safe on a zeroed Q. */
void sq_mp_quads_free(sq_mp_quads *Q);

#ifdef __cplusplus
}
#endif
#endif
