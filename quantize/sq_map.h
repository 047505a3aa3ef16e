/* seamquad: a seamless map on a closed triangle mesh, with exact transitions.
 *
 * A map gives every corner of every triangle a UV point in that triangle's
 * chart. Across each edge the two charts differ by a transition: a rotation
 * by r * 90 degrees (r in 0..3, counterclockwise) followed by a translation
 * t. For halfedge h in face f with twin h' in face g, a point p in f's chart
 * has the coordinates R^r p + t in g's chart, where r = he_rot[h] and
 * t = he_t[2h .. 2h+1]; the twin stores the inverse. Interior edges (same UV
 * on both sides) have r = 0, t = (0, 0).
 *
 * An exact map (sq_map_check) satisfies, with no tolerance:
 *  - the transitions map the edge's two corners of one side onto those of
 *    the other side exactly (every double computed exactly: rotations only
 *    swap and negate, and the translations are chosen so the sums are exact);
 *  - every UV triangle has positive orientation (exact predicate);
 *  - the UV angle sum at vertex v is valence[v] * pi/2 (valence 4: regular).
 *
 * Layout: flat arrays indexed by the halfedges of `mesh` (sq_mesh.h), caller
 * frees with sq_map_free. The mesh is owned by the map. */
#ifndef SQ_MAP_H
#define SQ_MAP_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_map {
    sq_mesh mesh;        /* the triangle mesh (owned)                          */
    double *he_uv;       /* 2 nh: UV of halfedge h's origin corner, in the     */
                         /* chart of face he_face[h]                           */
    uint8_t *he_rot;     /* nh: r of the transition from h's face to its twin's */
    double *he_t;        /* 2 nh: t of that transition                         */
    int32_t *valence;    /* nv: angle sum / (pi/2); 4 at regular vertices      */
} sq_map;

/* R^r p: rotation of p by r * 90 degrees counterclockwise (exact). */
static inline void sq_map_rotate(int r, const double p[2], double out[2])
{
    double x = p[0], y = p[1];
    switch (r & 3) {
    case 0: out[0] = x;  out[1] = y;  break;
    case 1: out[0] = -y; out[1] = x;  break;
    case 2: out[0] = -x; out[1] = -y; break;
    default: out[0] = y; out[1] = -x; break;
    }
}

enum {
    /* sq_map_from_soup: refuse any seam that is not exact (no snapping) */
    SQ_MAP_REQUIRE_EXACT = 1u << 0,
    /* sq_map_check / sq_map_from_soup: also require an integer grid map:
     * integer translations and every cone on an integer point */
    SQ_MAP_REQUIRE_INTEGER = 1u << 1,
    /* sq_map_from_soup: accept triangles whose 3D corners are exactly
     * collinear (a refinement may hold slivers thinner than rounding, as
     * quantization's split makes; the map itself is checked in UV) */
    SQ_MAP_ALLOW_FLAT_3D = 1u << 2
};

/* What sq_map_from_soup found and changed. */
typedef struct sq_map_report {
    uint32_t seam_edges;     /* edges whose two sides differ                  */
    uint32_t seam_curves;    /* maximal seam chains between nodes             */
    uint32_t cones;          /* vertices of valence != 4                      */
    double max_seam_error;   /* largest seam mismatch before snapping, in     */
                             /* units of the UV bounding-box diagonal         */
    double grid;             /* the dyadic grid the UVs were snapped to (0:   */
                             /* the input was exact and left unchanged)       */
    uint32_t moved_uv;       /* UV values changed by the snapping             */
} sq_map_report;

/* Builds the map of a soup with `vt` on every corner (a triangle mesh read
 * by sq_read_mesh). The positions and faces must form a closed, connected,
 * oriented manifold (sq_mesh_from_soup's checks); every edge's two sides
 * must differ by a rotation by a multiple of 90 degrees plus a translation
 * within tol * (UV bounding-box diagonal); a seam curve (a chain of seam
 * edges between nodes: cones and vertices on three or more seam edges) must
 * use one transition. Unless SQ_MAP_REQUIRE_EXACT, the UVs are then snapped
 * to a dyadic grid so that every transition holds exactly (one translation
 * per seam curve, consistent around every vertex); the result must pass
 * sq_map_check, else the map is refused with the first bad triangle or seam
 * named (never repaired silently). `input` (may be NULL): the mesh the map
 * must belong to (same vertex count, positions and faces). valence (may be
 * NULL): the cones the map must have (angle sums). rep may be NULL. */
sq_status sq_map_from_soup(const sq_soup *soup, const sq_mesh *input, const int32_t *valence,
                           double tol, unsigned flags, sq_map *out, sq_map_report *rep,
                           sq_error *err);

/* Reads an OBJ with vt (sq_read_mesh) and calls sq_map_from_soup. */
sq_status sq_map_read(const char *path, const sq_mesh *input, const int32_t *valence, double tol,
                      unsigned flags, sq_map *out, sq_map_report *rep, sq_error *err);

/* Exact check of the invariants listed at the top (and, with
 * SQ_MAP_REQUIRE_INTEGER, integer translations and cone points). The first
 * violation is named (face, vertex, edge; 0-based). */
sq_status sq_map_check(const sq_map *M, unsigned flags, sq_error *err);

/* Writes the map as OBJ: v, vt (one per distinct UV of a vertex) and
 * f v/vt lines, faces in the mesh's order (atomic, see sq_io.h). */
sq_status sq_map_write_obj(const char *path, const sq_map *M, sq_error *err);

/* A deep copy of M (out is overwritten; free it with sq_map_free). */
sq_status sq_map_copy(const sq_map *M, sq_map *out, sq_error *err);

void sq_map_free(sq_map *M);

#ifdef __cplusplus
}
#endif
#endif
