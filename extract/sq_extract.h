/* seamquad: the quad mesh of an integer-grid map (extract stage).
 *
 * Input: an integer-grid map M (sq_map.h, valid for sq_map_check with
 * SQ_MAP_REQUIRE_INTEGER): every UV triangle strictly positive, every
 * transition a rotation by a multiple of 90 degrees plus an integer
 * translation, exactly, and every cone on an integer point.
 *
 * Output: the closed, pure-quad mesh whose vertices are the integer points
 * of the map and whose edges are the unit segments of the integer grid
 * traced on the surface. Its irregular vertices are exactly the cones (a
 * cone of valence k is a quad vertex of valence k), and every vertex lies
 * on the triangle mesh of M (a point of one of its triangles).
 *
 * Steps (one file each; docs/extract.md):
 *  1. grid points (sq_extract_points.c): the integer points of the map, each
 *     once: at mesh vertices, strictly inside edges, strictly inside faces,
 *     with their outgoing grid directions (4, or k at a cone of valence k);
 *  2. tracing (sq_extract_trace.c): every outgoing direction is followed as
 *     the unit segment P -> P + d across triangles and charts to the grid
 *     point at its end, and the direction it arrives from;
 *  3. quads (sq_extract_quads.c): each directed grid edge has one quad on
 *     its left, found by turning left at each end; every (point, direction)
 *     must belong to exactly one quad and the two traces of an edge must
 *     agree;
 *  4. positions (sq_extract_positions.c): 3D positions by barycentric
 *     interpolation in the triangle, edge or vertex holding each point.
 *
 * Every decision is an exact orientation test (sq_orient2d) or a comparison
 * of doubles that are integers or UV corners: no tolerance anywhere. A map
 * too coarse for a quad mesh (a grid edge from a point back to itself, two
 * grid edges between the same points, a quad through one point twice) is
 * refused with SQ_ERR_DEGENERATE naming the grid point; an inconsistency
 * (a bug) is SQ_ERR_INTERNAL naming the grid point, its direction and the
 * face. No partial mesh is ever returned.
 *
 * The library never prints or exits. */
#ifndef SQ_EXTRACT_H
#define SQ_EXTRACT_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a grid point lies on the map's triangle mesh. */
typedef enum sq_grid_kind {
    SQ_GRID_VERTEX = 0, /* at a mesh vertex (element: the vertex)                  */
    SQ_GRID_EDGE = 1,   /* strictly inside an edge (element: the edge's halfedge   */
                        /* h < twin(h), whose face's chart gives the UV)           */
    SQ_GRID_FACE = 2    /* strictly inside a face (element: the face)              */
} sq_grid_kind;

typedef struct sq_extract_stats {
    uint32_t vertex_points;  /* grid points at mesh vertices                       */
    uint32_t edge_points;    /* grid points strictly inside mesh edges             */
    uint32_t face_points;    /* grid points strictly inside mesh faces             */
    uint32_t quads;
    uint32_t edges;          /* quad mesh edges (= 2 quads)                        */
    uint32_t irregular;      /* quad vertices of valence != 4 (= the cones)        */
    uint64_t trace_steps;    /* faces, edges and vertices crossed by all traces    */
    uint32_t max_trace_steps;/* the longest trace of one unit segment              */
    double t_check;          /* seconds: sq_map_check of the input                 */
    double t_points, t_trace, t_quads, t_positions, t_total; /* seconds, per step  */
} sq_extract_stats;

/* The result. Arrays are owned by the struct (sq_quad_mesh_free). Vertex
 * order: grid points at mesh vertices (by vertex), then inside edges (by
 * halfedge), then inside faces (by face; within an edge or face in
 * increasing coordinate order of its chart). Quads are counterclockwise
 * (the orientation of the triangle mesh), ordered by their first vertex
 * (each quad starts at its lowest direction slot). */
typedef struct sq_quad_mesh {
    uint32_t nv, nq;
    double *pos;         /* 3 nv: position on the map's triangle mesh              */
    uint32_t *quad;      /* 4 nq: vertex indices, counterclockwise                 */
    int32_t *valence;    /* nv: quads around the vertex                            */
    uint8_t *kind;       /* nv: sq_grid_kind                                       */
    uint32_t *elem;      /* nv: the vertex, halfedge or face of that kind          */
    double *uv;          /* 2 nv: integer UV in the chart of loc_face              */
    uint32_t *loc_face;  /* nv: a face of the map's mesh holding the point         */
    double *loc_bary;    /* 3 nv: barycentric coordinates in loc_face, for the     */
                         /* corners at the origins of f_he[f], next, next-next     */
} sq_quad_mesh;

/* Builds the quad mesh of the integer-grid map M. The map is checked first
 * (sq_map_check with SQ_MAP_REQUIRE_INTEGER: errors name its face, vertex
 * or edge); UV coordinates must stay below 2^40 in magnitude and the grid
 * below 2*10^8 points (SQ_ERR_ARGUMENT). On success: only quads, closed,
 * manifold, oriented as the map, connected, the map's Euler
 * characteristic, valence 4 except at the cones (valence[v] of the map),
 * quad count = UV area.
 * out is overwritten (not freed: free a previous result first); on failure
 * it is left empty. stats may be NULL. */
sq_status sq_extract(const sq_map *M, sq_quad_mesh *out, sq_extract_stats *stats,
                     sq_error *err);

/* Frees every array and zeroes the struct. Safe on a zeroed struct. */
void sq_quad_mesh_free(sq_quad_mesh *q);

/* Writes the quads of Q as OBJ: `v` and `f` lines, atomically (sq_write_obj:
 * on failure nothing is left at path). */
sq_status sq_quad_mesh_write_obj(const char *path, const sq_quad_mesh *Q, sq_error *err);

typedef struct sq_untangle_stats {
    uint32_t folded_before, folded_after; /* quads folded in 3D (the referee's */
                                          /* test: both triangulations) or    */
                                          /* turned over on the surface       */
    uint32_t rounds, moves;
} sq_untangle_stats;

/* Step 5 (sq_extract_untangle.c): the vertices of folded or turned quads,
 * cones excepted, relaxed towards their neighbours' mean and projected back
 * onto the map's mesh, each move kept only where it raises the worst fold
 * or turn margin around the vertex. Connectivity unchanged; moved vertices keep
 * lying on the surface (loc_face, loc_bary and uv updated: uv is then the
 * map's value there, no longer integer). Folds may remain (stats say how
 * many); the call fails only for lack of memory. */
sq_status sq_extract_untangle(const sq_map *M, sq_quad_mesh *Q, sq_untangle_stats *stats, sq_error *err);

/* What the referee (check_quad.py, degeneracy) rejects in a quad mesh's
 * geometry, counted; first_* are 0-based quad indices (UINT32_MAX: none). */
typedef struct sq_quad_shapes {
    uint32_t short_edge;  /* quads with an edge <= 1e-12 diag long             */
    uint32_t tiny;        /* other quads of area <= 1e-12 diag^2 (the mean of   */
                          /* their two triangulations' areas)                  */
    uint32_t folded;      /* both triangulations bent by more than 90 degrees   */
                          /* (sq_quad_fold_margin < 0)                         */
    uint32_t turned;      /* turned over on the surface (sq_quad_turn_margin    */
                          /* < 0; not a referee test: a flipped face)           */
    uint32_t first_short_edge, first_tiny, first_folded, first_turned;
} sq_quad_shapes;

/* Step 6 (sq_quad_mesh_check_shapes.c): every quad of Q judged against
 * diag (the input's bounding-box diagonal), and where m, vert_face and
 * vert_bary are given (vertex v of Q in face vert_face[v] of the triangle
 * mesh m, sq_quad_mesh_count_turned), none turned over on it. SQ_ERR_DEGENERATE when any count is non-zero, the
 * message naming the first quad (1-based, as in the OBJ); out (may be
 * NULL) receives the counts either way. O(nq). */
sq_status sq_quad_mesh_check_shapes(const sq_quad_mesh *Q, const sq_mesh *m, const uint32_t *vert_face,
                                    const double *vert_bary, double diag, sq_quad_shapes *out, sq_error *err);

/* Turned over on the surface: a quad whose every corner (the triangle of
 * the corner and its two quad neighbours) faces away from the surface
 * there. Such a quad need not be folded in the referee's sense (its two
 * triangulations may agree) but lies upside down: a flipped face. (A quad
 * with only some corners facing away is non-convex or twisted, a matter
 * of quality: its scaled Jacobian is <= 0.) A corner faces the surface
 * when it agrees with either of two normals there: the normal of the
 * triangle of m that holds it (skipped where that triangle is too thin to
 * have one), or the interpolation of m's vertex normals vn
 * (sq_mesh_vertex_normals, sq_mesh_normal_at in core/sq_mesh.h). The
 * first decides on a coarse mesh with sharp features, where vertex
 * normals can lean more than 90 degrees from a triangle they belong to
 * (libigl/decimated-knight); the second on a refinement's slivers, whose
 * own normal is noise.
 * sq_quad_turn_margin (stages/sq_smooth.h) measures it against one normal
 * per corner; sq_quad_turn_margin_on: the larger of the margins with the two normals
 * of m at the corners, corner k at barycentric bary[k] in face[k] of m:
 * < 0 exactly when the quad is turned.
 * sq_quad_mesh_count_turned: the turned quads of Q on the triangle mesh m,
 * vertex v at barycentric vert_bary[3v..] in face vert_face[v] of m;
 * *first (may be NULL) the first (0-based, UINT32_MAX: none), flags (nq,
 * may be NULL) 1 at each. O(nq). */
double sq_quad_turn_margin_on(const sq_mesh *m, const double *vn, const double *const p[4], const uint32_t face[4],
                              const double *const bary[4]);
sq_status sq_quad_mesh_count_turned(const sq_quad_mesh *Q, const sq_mesh *m, const double *vn,
                                    const uint32_t *vert_face, const double *vert_bary, uint32_t *count,
                                    uint32_t *first, uint8_t *flags, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
