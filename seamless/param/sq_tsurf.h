/* seamquad: an editable triangle surface with cut edges, for the surface
 * side of compatible cutting (seed 7, [SAPH04]) and the interior map
 * (seed 8).
 *
 * Halfedge arrays with explicit next pointers; faces are counterclockwise
 * triangles. The surface only grows: sq_tsurf_split_edge appends one vertex,
 * two faces and six halfedges, and every existing halfedge keeps its index,
 * its origin and its direction (a split halfedge keeps its first half), so
 * halfedges stored by callers stay valid as names of "the edge leaving v in
 * this direction".
 *
 * A cut edge has both halfedges marked (kind != 0). The surface cut along
 * its cut edges falls into regions; the corners of a region at a vertex v
 * form sectors. A sector is named by the cut halfedge h leaving v on its
 * clockwise side: the faces counterclockwise from face(h) up to, not across,
 * the next cut edge around v.
 *
 * The library never prints or exits. */
#ifndef SQ_TSURF_H
#define SQ_TSURF_H

#include <math.h>
#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SQ_TS_UNCUT = 0,
    SQ_TS_SEAM = 1,  /* cut graph and cone tree: a seam of the map */
    SQ_TS_CHORD = 2  /* a cell boundary inside the domain (no seam) */
};

typedef struct sq_tsurf {
    uint32_t nv, nf, nh;
    uint32_t cap_v, cap_f, cap_h;
    uint32_t nv_input;
    double *pos;       /* 3 cap_v                                        */
    uint32_t *vert;    /* cap_h: origin vertex                           */
    uint32_t *next;    /* cap_h                                          */
    uint32_t *twin;    /* cap_h                                          */
    uint32_t *f_he;    /* cap_f: a halfedge of the face                  */
    uint32_t *forig;   /* cap_f: the input face holding the face         */
    uint32_t *face;    /* cap_h: the face of the halfedge                */
    uint32_t *v_he;    /* cap_v: an outgoing halfedge                    */
    uint8_t *kind;     /* cap_h: SQ_TS_*                                 */
    uint32_t *label;   /* cap_h: caller's label of a cut halfedge        */
                       /* (SQ_NONE when uncut)                           */
    uint32_t *v_ncut;  /* cap_v: cut edges at the vertex                 */
    int32_t *valence;  /* cap_v: prescribed valence (4 = regular)        */
    double *hvec;      /* 2 cap_h or NULL: for a flat surface (Q         */
                       /* triangulated, sq_qtri.h), each halfedge's      */
                       /* vector in its face's frame; sq_tsurf_split_edge */
                       /* keeps it exact (halves and sums of dyadics)    */
} sq_tsurf;

static inline uint32_t sq_ts_next(const sq_tsurf *S, uint32_t h) { return S->next[h]; }
static inline uint32_t sq_ts_prev(const sq_tsurf *S, uint32_t h) { return S->next[S->next[h]]; }
static inline uint32_t sq_ts_head(const sq_tsurf *S, uint32_t h) { return S->vert[S->next[h]]; }
/* Euclidean distance between vertices a and b */
static inline double sq_ts_dist(const sq_tsurf *S, uint32_t a, uint32_t b)
{
    double x = S->pos[3 * a] - S->pos[3 * b], y = S->pos[3 * a + 1] - S->pos[3 * b + 1],
           z = S->pos[3 * a + 2] - S->pos[3 * b + 2];
    return sqrt(x * x + y * y + z * z);
}
/* next outgoing halfedge of the same origin, counterclockwise / clockwise */
static inline uint32_t sq_ts_ccw(const sq_tsurf *S, uint32_t h) { return S->twin[sq_ts_prev(S, h)]; }
static inline uint32_t sq_ts_cw(const sq_tsurf *S, uint32_t h) { return S->next[S->twin[h]]; }
/* the halfedge from a to b, SQ_NONE if they are not adjacent */
static inline uint32_t sq_ts_find(const sq_tsurf *S, uint32_t a, uint32_t b)
{
    uint32_t h0 = S->v_he[a], h = h0;
    do {
        if (S->vert[S->next[h]] == b) return h;
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    return SQ_NONE;
}

void sq_tsurf_init(sq_tsurf *S);
void sq_tsurf_free(sq_tsurf *S);
/* dst (initialized; its old content freed) becomes a deep copy of src.
 * -1 when out of memory (dst left empty). */
int sq_tsurf_copy(sq_tsurf *dst, const sq_tsurf *src);

/* Copies a closed triangle mesh (faces must be triangles; face f keeps its
 * index, and its halfedges are 3f, 3f+1, 3f+2 from m->f_he[f] on). valence: nv entries or NULL (all 4). he_map (m->nh entries, may
 * be NULL) receives the halfedge of S for every halfedge of m. */
sq_status sq_tsurf_from_mesh(const sq_mesh *m, const int32_t *valence, sq_tsurf *S,
                             uint32_t *he_map, sq_error *err);

/* Splits the edge of halfedge h at parameter t in (0, 1) from its origin:
 * the new vertex is (1 - t) origin + t head; both adjacent faces are split
 * in two. Cut state and labels are inherited by both halves. Returns the new
 * vertex, SQ_NONE when out of memory. */
uint32_t sq_tsurf_split_edge(sq_tsurf *S, uint32_t h, double t);

/* Marks the edge of h cut with the given kind; label of h and of its twin. */
void sq_tsurf_cut_edge(sq_tsurf *S, uint32_t h, uint8_t kind, uint32_t label_h,
                       uint32_t label_twin);

/* The sector holding the corner of face(h) at h's origin: the cut halfedge
 * reached by turning clockwise from h (h itself if cut); SQ_NONE if the
 * vertex has no cut edge. */
uint32_t sq_tsurf_sector_of(const sq_tsurf *S, uint32_t h);

/* Next cut halfedge after the cut halfedge h along the boundary of its
 * region, the region on the left (counterclockwise around the region). */
uint32_t sq_tsurf_next_boundary(const sq_tsurf *S, uint32_t h);

/* Splits, at their midpoints, every uncut edge whose two end vertices are
 * both on the cut (chords of a region), and, when `cones` is set, every
 * uncut edge joining a cone (valence != 4, not on the cut) to another cone
 * or to a vertex on the cut. Afterwards the vertices off the cut of every
 * region with any are connected, and no cone blocks a path to another.
 * Returns the number of splits, or -1 when out of memory. */
int64_t sq_tsurf_split_blocking(sq_tsurf *S, int cones);

/* Local Steiner splits so that a route can leave (or enter) a vertex:
 * sq_tsurf_open_sector splits the edges strictly inside sector(h) whose
 * other end is on the cut or a cone (or, for a one-face sector, its
 * opposite edge); sq_tsurf_open_vertex does the same around a vertex off
 * the cut. Return the number of splits, -1 when out of memory. */
int64_t sq_tsurf_open_sector(sq_tsurf *S, uint32_t h);
int64_t sq_tsurf_open_vertex(sq_tsurf *S, uint32_t v);

/* Route kinds for sq_tsurf_route. */
typedef enum sq_route_target {
    SQ_ROUTE_CONE,   /* any input vertex off the cut with valence ==        */
                     /* target_valence and cone_free[v] set (cone_free has  */
                     /* nv_input entries; valence 4 names one regular input */
                     /* vertex, e.g. where a tree should branch)            */
    SQ_ROUTE_FREE,   /* a vertex off the cut, not a cone, reached at a       */
                     /* distance >= target_length (or the farthest one)      */
    SQ_ROUTE_SECTOR  /* the origin of target_sector, entered through an     */
                     /* edge strictly inside that sector                    */
} sq_route_target;

/* Shortest path (Euclidean edge lengths) leaving the origin of the cut
 * halfedge `start` through an edge strictly inside sector(start), running
 * through vertices off the cut that are not cones, ending at a target.
 * Where edges between blocked vertices (on the cut or cones) wall regions
 * off, the path may cross such an edge at its midpoint, which then becomes
 * a Steiner vertex (split), so a path exists whenever the target lies in
 * the start's region. The path's halfedges (start to end) are appended to
 * *path (realloc'd; *npath updated). */
sq_status sq_tsurf_route(sq_tsurf *S, uint32_t start, sq_route_target kind,
                         int32_t target_valence, const uint8_t *cone_free, double target_length,
                         uint32_t target_sector, uint32_t **path, uint32_t *npath, sq_error *err);

/* The same targets, routed through faces: the path crosses uncut edges of
 * the region and every crossed edge is split at its midpoint (a Steiner
 * vertex), so the path touches no existing vertex but its two ends. Always
 * finds a route when the target lies in the start's region. Modifies S. */
sq_status sq_tsurf_route_faces(sq_tsurf *S, uint32_t start, sq_route_target kind,
                               int32_t target_valence, const uint8_t *cone_free,
                               double target_length, uint32_t target_sector, uint32_t **path,
                               uint32_t *npath, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
