/* seamquad: shared internals of the T-mesh (sq_tmesh_*.c; docs/tmesh.md).
 *
 * Tracing (sq_tmesh_trace.c) produces traces as sequences of pieces (one
 * per mesh face crossed or mesh edge run along), the nodes where traces
 * stop, and marks: the positions on traces where a node lies. Assembly
 * (sq_tmesh_build.c) splits the traces at their marks into arcs and walks
 * the faces. */
#ifndef SQ_TMESH_INTERNAL_H
#define SQ_TMESH_INTERNAL_H

#include <stdlib.h>

#include <stdint.h>

#include "sq_map.h"
#include "sq_tmesh.h"

#define TM_NONE UINT32_MAX
#define TM_MAX_RAYS 64

/* Piece ends. */
enum { TM_END_VERTEX = 0, TM_END_EDGE = 1, TM_END_POINT = 2 };

/* Trace states and stop reasons. */
enum { TM_AT_VERTEX = 0, TM_AT_EDGE = 1, TM_STOPPED = 2 };
enum { TM_STOP_CONE = 0, TM_STOP_ON_TRACE = 1, TM_STOP_MEET = 2 };

/* An axis ray at a vertex: direction dir of the chart of he_face[h], h
 * leaving the vertex, inside the corner of h (along h itself iff on_edge). */
typedef struct tm_ray {
    uint32_t h;
    uint8_t dir, on_edge;
} tm_ray;

typedef struct tm_piece {
    uint32_t trace, k;      /* the k-th piece of its trace                 */
    uint32_t face, he;      /* he: the halfedge of face run along, or NONE */
    uint8_t dir;
    uint8_t start_kind;     /* TM_END_VERTEX or TM_END_EDGE                */
    uint8_t end_kind;       /* TM_END_VERTEX, _EDGE or _POINT (truncated)  */
    uint8_t s1_exact;
    uint32_t start_id;      /* VERTEX: the vertex; EDGE: halfedge of face  */
    uint32_t end_id;
    double c;               /* the line in face's chart (exact)            */
    double c2;              /* along an edge: the line in the twin's chart */
    double s0, s1;          /* coordinate along the line at start and end  */
    double b;               /* parametric distance tau = sigma s + b       */
} tm_piece;

/* A node at position (k, at_end ? end of piece k : s inside piece k) of a
 * trace. */
typedef struct tm_mark {
    uint32_t trace, k;
    uint8_t at_end;
    double s;
    uint32_t node;
} tm_mark;

/* has_sum: a head-on meeting of two traces at a point known only in
 * floating point (on an edge or inside a face); sum = the sum of the two
 * traces' tau there (exact at integer maps, though the point is not) */
typedef struct tm_node {
    uint8_t kind, exact, has_sum;
    double sum;
    uint32_t id;            /* vertex, canonical halfedge or face          */
    double uv[2];
} tm_node;

typedef struct tm_trace {
    uint32_t cone, ray;
    uint8_t state, reason;
    uint32_t n;             /* pieces                                      */
    uint32_t last;          /* last piece or NONE                          */
    uint32_t end_node;      /* node where it stopped                       */
    double tau;             /* parametric distance travelled               */
} tm_trace;

typedef struct tm_traces {
    uint32_t n_traces;
    tm_trace *traces;
    uint32_t n_pieces, cap_pieces;
    tm_piece *pieces;
    uint32_t n_marks, cap_marks;
    tm_mark *marks;
    uint32_t n_nodes, cap_nodes;
    tm_node *nodes;
    uint32_t *vnode;        /* nv: node at the vertex or NONE              */
    uint32_t cones, empty_traces, vertex_passes, edge_pieces, t_junctions, meets, overtaken;
} tm_traces;

static inline const double *tm_uv(const sq_map *M, uint32_t h) { return M->he_uv + 2 * (size_t)h; }
static inline uint32_t tm_next(const sq_map *M, uint32_t h) { return M->mesh.he_next[h]; }
static inline uint32_t tm_prev(const sq_map *M, uint32_t h)
{
    return M->mesh.he_next[M->mesh.he_next[h]];
}
/* index of the coordinate running along direction d, and of the constant */
static inline int tm_rc(int d) { return d & 1; }
static inline int tm_cc(int d) { return (d & 1) ^ 1; }
static inline int tm_sigma(int d) { return d < 2 ? 1 : -1; }

/* The axis rays at v, counterclockwise from the corner of v_he[v]; returns
 * their count (the valence) or -1 if more than max. */
int sq_tmesh_vertex_rays(const sq_map *M, uint32_t v, tm_ray *rays, int max);
/* Index of the ray at v = origin(h) in direction d of h's face's chart,
 * d inside h's corner or on its edges; -1 if none. */
int sq_tmesh_find_ray(const sq_map *M, uint32_t h, int d);
/* The halfedge of face f leaving vertex v, or NONE. */
uint32_t sq_tmesh_corner(const sq_map *M, uint32_t f, uint32_t v);
/* p' = R^r p + t across halfedge h (from he_face[h] to its twin's face);
 * 0 if a sum is not exact. */
int sq_tmesh_transform(const sq_map *M, uint32_t h, const double p[2], double out[2]);

/* Traces the separatrices of every cone (sq_tmesh_trace.c). */
sq_status sq_tmesh_trace(const sq_map *M, tm_traces *T, sq_error *err);
void sq_tmesh_traces_free(tm_traces *T);

/* Grows *p (capacity *cap elements of size bytes) to hold need elements,
 * doubling; 0 when out of memory (then *p is unchanged). */
static inline int grow(void **p, uint32_t *cap, uint32_t need, size_t size)
{
    if (need <= *cap) return 1;
    uint32_t c = *cap ? *cap : 64;
    while (c < need) c = c > UINT32_MAX / 2 ? need : 2 * c;
    void *q = realloc(*p, (size_t)c * size);
    if (!q) return 0;
    *p = q, *cap = c;
    return 1;
}

#endif
