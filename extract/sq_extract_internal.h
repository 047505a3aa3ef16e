/* seamquad: the grid points of an integer-grid map and the helpers shared
 * by the extract steps (not a public header; sq_extract.h is).
 *
 * A grid point has outgoing directions ("slots"), stored flat: the slots of
 * point p are slot_off[p] .. slot_off[p+1]-1, counterclockwise around p.
 * Slot s is the axis direction slot_dir[s] (0: +u, 1: +v, 2: -u, 3: -v) in
 * the chart of face he_face[slot_he[s]]. At a point inside an edge or face
 * the four slots are the four axis directions of the point's own chart (the
 * face of its halfedge, or the face itself), in order. At a mesh vertex v,
 * slot_he[s] is the corner halfedge (he_vert[h] = v) whose corner holds the
 * direction: each corner h, from h's edge (included) counterclockwise to
 * the edge of prev(h) (excluded, it starts the next corner), holds the axis
 * directions of its face's chart in that range; at a vertex of valence k
 * there are exactly k. */
#ifndef SQ_EXTRACT_INTERNAL_H
#define SQ_EXTRACT_INTERNAL_H

#include <stdint.h>

#include "sq_extract.h"
#include "sq_map.h"

/* UV coordinates must stay below this magnitude, so that integer points,
 * their neighbours and every transition of them are exact doubles and fit
 * in int64. */
#define SQ_EXTRACT_MAX_UV 1099511627776.0 /* 2^40 */

/* At most this many grid points (and slots: 4 per point, more at cones). */
#define SQ_EXTRACT_MAX_POINTS 200000000u

typedef struct sq_grid {
    uint32_t n;                    /* grid points                                 */
    uint32_t nvert, nedge, nface;  /* by kind, stored in this order               */
    uint8_t *kind;                 /* n: sq_grid_kind                             */
    uint32_t *elem;                /* n: vertex, halfedge (h < twin) or face      */
    double *uv;                    /* 2n: UV in the chart of the point's face:    */
                                   /* he_face[v_he[v]], he_face[h], or the face   */
    uint32_t nslot;
    uint32_t *slot_off;            /* n+1                                         */
    uint32_t *slot_point;          /* nslot: the point of each slot               */
    uint32_t *slot_he;             /* nslot: the halfedge whose face's chart has  */
                                   /* the direction                              */
    uint8_t *slot_dir;             /* nslot: axis direction 0..3 in that chart    */
    uint32_t *vert_point;          /* mesh nv: grid point at the vertex, or SQ_NONE */
    uint32_t hmask;                /* hash of edge and face points: size - 1      */
    uint32_t *htab;                /* point index or SQ_NONE                      */
} sq_grid;

/* p + the unit step of axis direction d (0..3); exact for integer p. */
static inline void sq_grid_step(const double p[2], int d, double out[2])
{
    out[0] = p[0] + (d == 0 ? 1.0 : d == 2 ? -1.0 : 0.0);
    out[1] = p[1] + (d == 1 ? 1.0 : d == 3 ? -1.0 : 0.0);
}

/* Axis direction of a vector with exactly one nonzero coordinate, or -1. */
static inline int sq_grid_dir_of(double du, double dv)
{
    if (dv == 0.0 && du > 0.0) return 0;
    if (du == 0.0 && dv > 0.0) return 1;
    if (dv == 0.0 && du < 0.0) return 2;
    if (du == 0.0 && dv < 0.0) return 3;
    return -1;
}

static inline uint32_t sq_grid_prev(const sq_mesh *m, uint32_t h) { return m->he_next[m->he_next[h]]; }

/* Step 1 (sq_extract_points.c): every integer point of the map, once, with
 * its slots; checks that every cone is one and has as many directions as
 * its valence. */
sq_status sq_grid_build(const sq_map *M, sq_grid *G, sq_error *err);

/* The edge or face point of that kind and element at uv (in the element's
 * chart), or SQ_NONE. */
uint32_t sq_grid_find(const sq_grid *G, sq_grid_kind kind, uint32_t elem, const double uv[2]);

void sq_grid_free(sq_grid *G);

/* "grid point 12 (inside face 3, UV (4, 5))" into buf; returns buf. */
const char *sq_grid_describe(const sq_grid *G, uint32_t p, char *buf, size_t n);

/* Step 2 (sq_extract_trace.c): follows slot s as the unit segment from its
 * point to the next grid point; *to is the slot of the arrival point that
 * points back along the segment. *steps counts the faces, edges and
 * vertices crossed. */
sq_status sq_grid_trace(const sq_map *M, const sq_grid *G, uint32_t s, uint32_t *to,
                        uint32_t *steps, sq_error *err);

/* Step 3 (sq_extract_quads.c): the quads from the traced slots (to[s] for
 * every slot); fills out->nq, quad, valence and the counts of stats. */
sq_status sq_grid_quads(const sq_map *M, const sq_grid *G, const uint32_t *to, sq_quad_mesh *out,
                        sq_extract_stats *stats, sq_error *err);

/* Step 4 (sq_extract_positions.c): out->nv, pos, kind, elem, uv, loc_face,
 * loc_bary of every grid point. */
sq_status sq_grid_positions(const sq_map *M, const sq_grid *G, sq_quad_mesh *out, sq_error *err);

#endif
