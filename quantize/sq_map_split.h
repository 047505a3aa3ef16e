/* seamquad: a map's triangles split along iso-line chords.
 *
 * Quantization re-embeds every T-mesh face on its own, so no triangle may
 * straddle an arc. Given chords (pieces of iso-lines u = c or v = c in the
 * chart of one mesh face, c exact), this step cuts every face by the full
 * lines of its chords (a line cuts the whole triangle; beyond a chord's
 * extent the cut only refines a T-mesh face), and splits every mesh edge
 * where a line of either neighbour crosses it, so the result is a
 * conforming triangle mesh: each triangle inside one input face, each on
 * one side of every chord.
 *
 * Exactness: which side of a line a point lies on is decided exactly: at
 * mesh vertices and at line-line crossings (exact double points) by
 * comparison, at the crossing of a line with a mesh edge by sq_orient2d
 * against the crossing point of the two lines. Computed coordinates (the
 * free coordinate of an edge crossing, cell centres) are used for positions
 * only, never for decisions, and are flagged as inexact.
 *
 * Cells are convex polygons; a cell whose sides hold extra points (edge
 * crossings of the neighbour's lines, or crossings on a line) gets a centre
 * vertex and a fan, any other cell a fan from its first corner.
 *
 * Cost: per face O(lines x cell vertices); memory linear in the output. */
#ifndef SQ_MAP_SPLIT_H
#define SQ_MAP_SPLIT_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_chord {
    uint32_t face;  /* the mesh face whose chart holds the chord             */
    uint8_t axis;   /* 0: the line u = c (the chord runs along v);            */
                    /* 1: the line v = c (it runs along u)                    */
    double c;       /* exact                                                  */
    double lo, hi;  /* the chord's extent along the line (the other           */
                    /* coordinate); -INFINITY / INFINITY: to the face's edge  */
} sq_chord;

enum {
    SQ_SPLIT_U_EXACT = 1, /* the corner's u coordinate is exact              */
    SQ_SPLIT_V_EXACT = 2  /* its v coordinate is exact                       */
};

typedef struct sq_split {
    sq_mesh mesh;        /* the triangles as a halfedge mesh (halfedge 3t+i  */
                         /* runs from corner i of triangle t to corner i+1)  */
    uint32_t nv, nt;
    uint32_t nv_input;   /* the first nv_input vertices are the map's own     */
    double *pos;         /* 3 nv                                              */
    uint32_t *tri;       /* 3 nt, counterclockwise                            */
    uint32_t *tri_face;  /* nt: the mesh face holding the triangle            */
    double *uv;          /* 6 nt: corner UVs in the chart of tri_face         */
    uint8_t *uv_exact;   /* 3 nt: SQ_SPLIT_U_EXACT | SQ_SPLIT_V_EXACT          */
    uint8_t *on_chord;   /* 3 nt: 1 where the edge from corner i to i+1 lies  */
                         /* on a chord (on the same undirected edge, both     */
                         /* sides agree)                                      */
} sq_split;

sq_status sq_map_split(const sq_map *M, const sq_chord *chords, uint32_t n_chords, sq_split *out,
                       sq_error *err);

void sq_split_free(sq_split *S);

#ifdef __cplusplus
}
#endif
#endif
