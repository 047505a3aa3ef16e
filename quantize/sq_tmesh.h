/* seamquad: the T-mesh of a seamless map (docs/tmesh.md).
 *
 * From every cone of an exact seamless map (sq_map.h) the iso-lines leaving
 * it along the axis directions (its separatrices: a cone of valence k has k
 * of them, one per quarter turn of its angle sum) are traced together, in
 * order of the parametric distance travelled, until each hits a cone or a
 * trace (the motorcycle graph of Quantized Global Parametrization, Campen,
 * Bommes, Kobbelt 2015). The traces cut the surface into T-mesh faces, each
 * a rectangle of the map with 4 convex corners at cones or T-junctions and
 * no cone inside. Every decision is exact: a trace is the line u = c or
 * v = c of a face's chart with c an exact double, and its passage through
 * triangles, vertices and edges and its meetings with other traces are
 * decided by exact comparisons and sq_orient2d, never by computed
 * intersection points.
 *
 * Nodes are the cones, the T-junctions (where a trace ends on another) and
 * the vertices where traces end; arcs are the pieces of traces between
 * consecutive nodes. Faces list their 4 sides as arcs in order, for the
 * integer-length solver. */
#ifndef SQ_TMESH_H
#define SQ_TMESH_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a node or a piece end lies on the mesh. */
enum {
    SQ_TMESH_AT_VERTEX = 0, /* a mesh vertex                                  */
    SQ_TMESH_ON_EDGE = 1,   /* inside a mesh edge                             */
    SQ_TMESH_IN_FACE = 2    /* inside a mesh face                             */
};

typedef struct sq_tmesh_node {
    uint8_t kind;    /* SQ_TMESH_AT_VERTEX, _ON_EDGE or _IN_FACE              */
    uint8_t exact;   /* uv holds the point exactly (always, for a node that  */
                     /* passes sq_tmesh_build's checks)                      */
    int32_t valence; /* quarter turns around the node: the map's valence at */
                     /* a vertex (cone iff != 4), 4 elsewhere                */
    uint32_t id;     /* the vertex; for ON_EDGE the halfedge (the smaller   */
                     /* of the pair); for IN_FACE the face                   */
    double uv[2];    /* the point in the chart of face he_face[id] (ON_EDGE), */
                     /* face id (IN_FACE), face he_face[v_he[id]] (vertex)   */
    uint32_t degree; /* arc ends at the node (a cone of valence k: k)       */
} sq_tmesh_node;

/* One end of a piece (the part of an arc inside one mesh face). */
typedef struct sq_tmesh_end {
    uint8_t kind;  /* SQ_TMESH_AT_VERTEX: id = the vertex; SQ_TMESH_ON_EDGE: */
                   /* id = the halfedge of the piece's face it crosses (the */
                   /* point is the piece's line on that edge); IN_FACE: a   */
                   /* node inside the face (id = the face)                  */
    uint8_t exact; /* s is exact (vertices and nodes; edge crossings are    */
                   /* rounded)                                              */
    uint32_t id;
    double s;      /* coordinate along the line: u for a line v = c, v for  */
                   /* a line u = c, in the piece's face's chart             */
} sq_tmesh_end;

/* A piece of an arc: the segment of the iso-line v = c (dir 0 or 2) or
 * u = c (dir 1 or 3) of one mesh face's chart, run in direction dir (0: +u,
 * 1: +v, 2: -u, 3: -v), from `from` to `to`. A piece along a mesh edge has
 * he = the halfedge of `face` on that edge (`face` is either of the edge's
 * two faces; the piece may run either way along he), else he = UINT32_MAX.
 * Consecutive pieces of an arc meet at a vertex or on an edge (the same
 * edge, seen from its two faces). */
typedef struct sq_tmesh_piece {
    uint32_t face;
    uint32_t he;
    uint8_t dir;
    double c;      /* exact */
    sq_tmesh_end from, to;
} sq_tmesh_piece;

typedef struct sq_tmesh_arc {
    uint32_t node[2];    /* tail, head                                      */
    uint32_t slot[2];    /* the direction the arc leaves each end node by:  */
                         /* at a vertex the index of its axis ray (0 ..     */
                         /* valence-1, counterclockwise from the first ray  */
                         /* of the corner of halfedge v_he[v]), elsewhere   */
                         /* 0..3 (+u, +v, -u, -v) in the node's chart       */
    double length;       /* parametric length (exact at integer maps)       */
    double length3d;     /* length on the surface                           */
    uint32_t piece_off;  /* pieces piece_off .. piece_off + piece_count - 1, */
    uint32_t piece_count;/* from tail to head                               */
} sq_tmesh_arc;

typedef struct sq_tmesh {
    uint32_t n_nodes, n_arcs, n_faces, n_pieces;
    sq_tmesh_node *nodes;
    sq_tmesh_arc *arcs;
    sq_tmesh_piece *pieces;
    /* Side s (0 bottom, 1 right, 2 top, 3 left, counterclockwise) of face f
     * is side_arc[side_off[4f+s] .. side_off[4f+s+1]-1], arcs in the order
     * the side runs (counterclockwise around the face); side_rev[i] = 1
     * where the arc is run from head to tail. The bottom runs along +u of
     * the face's chart (the chart of the mesh face at its lower-left corner)
     * from the lower-left corner; where seams inside the face rotate the
     * charts so that no side's first piece runs along +u of its own face's
     * chart, side 0 is the first side found. Every arc lies on exactly two
     * sides, once in each direction. */
    uint32_t *side_off;  /* 4 n_faces + 1 */
    uint32_t *side_arc;
    uint8_t *side_rev;
    double *width;       /* n_faces: bottom (= top) length                  */
    double *height;      /* n_faces: right (= left) length                  */
    double uv_area;      /* the map's UV area (= sum of width * height)     */
} sq_tmesh;

typedef struct sq_tmesh_stats {
    uint32_t cones;
    uint32_t traces;         /* separatrices started (sum of cone valences; */
                             /* 4 from vertex 0 of a map without cones)     */
    uint32_t empty_traces;   /* met by a trace along their ray at the start */
    uint32_t steps;          /* trace pieces added                          */
    uint32_t vertex_passes;  /* traces continued straight through a vertex  */
    uint32_t edge_pieces;    /* pieces running along mesh edges             */
    uint32_t t_junctions;    /* traces ended on another trace               */
    uint32_t meets;          /* pairs of traces met head-on (one arc)       */
    uint32_t overtaken;      /* traces cut back to a crossing that the     */
                             /* crossing trace reached first               */
    uint32_t nodes, arcs, faces;
    double max_side_mismatch;/* largest |bottom - top|, |right - left|      */
    double area_error;       /* |sum of face areas - UV area| / UV area     */
    double seconds;
} sq_tmesh_stats;

/* Builds the T-mesh of the exact map M. A map without cones (a flat torus)
 * gets the four rays of vertex 0 traced as if it were a cone (a node of
 * degree 4). Refused with a message naming the element: a transition whose
 * sum is not exact on a trace, traces that do not end (more than the step
 * budget), and any broken result (checked by sq_tmesh_verify before
 * returning). stats may be NULL. */
sq_status sq_tmesh_build(const sq_map *M, sq_tmesh *out, sq_tmesh_stats *stats, sq_error *err);

/* Independent check of T against its map: every face a disk with exactly
 * 4 convex corners and no reflex one, Euler's formula, every arc on two
 * sides, opposite sides of equal length (1e-9 relative to the map's size),
 * the faces' areas summing to the UV area (1e-9 relative), every cone of
 * valence k at the end of exactly k arcs, one per ray, and every other node
 * with at least 3 arcs. stats (may be NULL) receives the measured errors. */
sq_status sq_tmesh_verify(const sq_map *M, const sq_tmesh *T, sq_tmesh_stats *stats, sq_error *err);

/* SVG of the traces over the UV layout of M: every triangle in its chart,
 * one colour per arc (from a palette), cones red, other nodes blue
 * (atomic, see sq_io.h). */
sq_status sq_tmesh_write_svg(const char *path, const sq_map *M, const sq_tmesh *T, sq_error *err);

void sq_tmesh_free(sq_tmesh *T);

#ifdef __cplusplus
}
#endif
#endif
