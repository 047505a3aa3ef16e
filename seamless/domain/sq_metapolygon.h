/* seamquad: metapolygons, the combinatorial polygon disks of seed 5.
 *
 * An sq_metapolygon is a polygon mesh of disk topology stored as flat
 * halfedge arrays. Faces may have any valence >= 2: a 2-gon is a face with
 * two edges between the same two vertices, so an edge is never identified
 * by its endpoints, only by its halfedges.
 *
 * Conventions
 * - Halfedge h runs from he_vert[h] to he_vert[he_next[h]].
 * - Faces are counterclockwise: a face lies to the left of its halfedges.
 * - Boundary halfedges have he_face == SQ_NONE. Their he_next links form the
 *   single boundary loop, which therefore runs clockwise around the disk
 *   (the disk lies to the right). "Clockwise" in seed 5.1 (the order of
 *   C(P) and the distance d(v, w)) means "along he_next of boundary
 *   halfedges" here.
 * - v_he[v] is an outgoing halfedge of v; for a boundary vertex it is the
 *   outgoing boundary halfedge.
 * - v_nface[v] is the valence of Def. 5.1: the number of incident faces.
 * - Arrays only grow by appending: indices of existing vertices, faces and
 *   halfedges never change, so a caller may keep them across extensions.
 *
 * The container itself does not require the conditions of Def. 5.1 (the
 * subdivided quad mesh of seed 5.4 uses it too, and extension passes through
 * states with concave vertices); sq_metapolygon_validate checks them on
 * request.
 *
 * The library never prints or exits: fallible functions return an sq_status
 * and fill the caller's sq_error (which may be NULL). */
#ifndef SQ_METAPOLYGON_H
#define SQ_METAPOLYGON_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_soup.h" /* SQ_NONE */

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_metapolygon {
    uint32_t nv, nf, nh;            /* counts in use                          */
    uint32_t cap_v, cap_f, cap_h;   /* allocated lengths of the arrays        */
    uint32_t *he_next;              /* cap_h                                   */
    uint32_t *he_twin;              /* cap_h                                   */
    uint32_t *he_vert;              /* cap_h: origin vertex                    */
    uint32_t *he_face;              /* cap_h: SQ_NONE on the boundary          */
    uint32_t *v_he;                 /* cap_v                                   */
    uint32_t *v_nface;              /* cap_v: incident faces (Def. 5.1)        */
    uint32_t *f_he;                 /* cap_f: first halfedge of the face       */
    uint32_t *f_valence;            /* cap_f: number of edges of the face      */
    uint32_t bnd_he;                /* a boundary halfedge, SQ_NONE when empty */
    uint32_t nbnd;                  /* number of boundary halfedges            */
} sq_metapolygon;

/* Boundary vertex classes of Def. 5.1 (by number of incident faces). */
typedef enum sq_mp_vertex_kind {
    SQ_MP_INTERIOR = 0, /* not on the boundary                         */
    SQ_MP_CORNER = 1,   /* boundary vertex with 1 incident face         */
    SQ_MP_FLAT = 2,     /* boundary vertex with 2 incident faces        */
    SQ_MP_CONCAVE = 3,  /* boundary vertex with 3 incident faces        */
    SQ_MP_OVERFULL = 4  /* boundary vertex with 4+ faces: never valid   */
} sq_mp_vertex_kind;

/* ---- storage (sq_metapolygon.c) --------------------------------------- */

/* Zeroes P: the empty metapolygon (seed 5: regular, treated as a meta-4-gon
 * by extension). */
void sq_metapolygon_init(sq_metapolygon *P);

/* Frees every array and zeroes P. Safe on a zeroed P. */
void sq_metapolygon_free(sq_metapolygon *P);

/* Makes room for `more_v` vertices, `more_f` faces and `more_h` halfedges
 * beyond the current counts (capacity grows geometrically). */
sq_status sq_metapolygon_reserve(sq_metapolygon *P, uint64_t more_v, uint64_t more_f,
                                 uint64_t more_h, sq_error *err);

/* Deep copy of src into dst (dst must be initialized; its arrays are
 * replaced). */
sq_status sq_metapolygon_copy(sq_metapolygon *dst, const sq_metapolygon *src, sq_error *err);

/* ---- editing primitives (sq_metapolygon.c) ----------------------------- */

/* Adds a free-standing k-gon (k >= 2) to an EMPTY P (seed Def. 5.4 step 1,
 * "if P is empty, P' will be just the i-gon"). */
sq_status sq_metapolygon_add_polygon(sq_metapolygon *P, uint32_t k, uint32_t *face,
                                     sq_error *err);

/* Glues a new face along the n_glued consecutive boundary halfedges that
 * start at boundary halfedge h (in boundary order), closing it with
 * n_new_verts new vertices, so the face has n_glued + n_new_verts + 1 edges.
 * Examples: (1, i-2) glues an i-gon to one edge (seed Def. 5.4 step 1);
 * (2, 1) and (3, 0) glue a quad into a concave notch (grid filling).
 * Optional outputs: the new face, and the new boundary halfedges leaving the
 * run's first vertex (first_bnd) and entering its last vertex (last_bnd). */
sq_status sq_metapolygon_glue_polygon(sq_metapolygon *P, uint32_t h, uint32_t n_glued,
                                      uint32_t n_new_verts, uint32_t *face,
                                      uint32_t *first_bnd, uint32_t *last_bnd,
                                      sq_error *err);

/* The boundary halfedge whose successor is boundary halfedge h (found by
 * turning around h's origin, O(valence)). */
uint32_t sq_metapolygon_boundary_prev(const sq_metapolygon *P, uint32_t h);

/* ---- queries (sq_metapolygon.c) ---------------------------------------- */

sq_mp_vertex_kind sq_metapolygon_vertex_kind(const sq_metapolygon *P, uint32_t v);

/* Number of corner vertices (boundary vertices with one face), Def. 5.2. */
uint32_t sq_metapolygon_count_corners(const sq_metapolygon *P);

/* C(P) of seed 5.1: the cyclic sequence of non-flat boundary vertices in
 * boundary (clockwise) order, starting at the first one at or after the
 * origin of P->bnd_he. For entry j it stores, in the arrays that are not
 * NULL: vert[j]; out_he[j], the boundary halfedge leaving vert[j]; and
 * dist[j] = d(vert[j], vert[j+1 mod n]), the number of boundary edges
 * between them (for a metapolygon: the side lengths). Fills at most cap
 * entries and returns the total number n (call with cap 0 to size arrays).
 * Returns 0 when every boundary vertex is flat (a meta-0-gon) or P is
 * empty. */
uint32_t sq_metapolygon_nonflat(const sq_metapolygon *P, uint32_t cap, uint32_t *vert,
                                uint32_t *out_he, uint32_t *dist);

/* I(P) of seed 5.1: valences of the faces with valence != 4, in face index
 * order. Fills at most cap entries; returns the total number. */
uint32_t sq_metapolygon_irregular(const sq_metapolygon *P, uint32_t cap, uint32_t *valence);

/* e(P) of Def. 5.3: sum over faces of (valence - 4). */
int64_t sq_metapolygon_excess(const sq_metapolygon *P);

/* Number of faces of valence 4. */
uint32_t sq_metapolygon_count_quads(const sq_metapolygon *P);

enum {
    /* Def. 5.1: interior vertices have valence 4, boundary ones 1 or 2 */
    SQ_MP_CHECK_METAPOLYGON = 1u << 0,
    /* with SQ_MP_CHECK_METAPOLYGON: also accept concave (3) boundary
     * vertices, the intermediate states of Def. 5.4 */
    SQ_MP_CHECK_ALLOW_CONCAVE = 1u << 1
};

/* Full structural check, O(size): twin/next/face consistency, faces of
 * valence >= 2 without repeated vertices, stored valences, one boundary
 * loop through every boundary vertex once, manifold vertices, Euler
 * characteristic 1 (a disk), plus the Def. 5.1 valence conditions when
 * flagged. Returns SQ_ERR_INTERNAL naming the first violation. */
sq_status sq_metapolygon_validate(const sq_metapolygon *P, unsigned flags, sq_error *err);

/* ---- regular grids (sq_metapolygon_grid.c) ----------------------------- */

/* Makes P (must be empty) a rows x cols grid of 4-gons: a meta-4-gon with
 * sides rows, cols, rows, cols. */
sq_status sq_metapolygon_make_grid(sq_metapolygon *P, uint32_t rows, uint32_t cols,
                                   sq_error *err);

/* Glues a regular rows x cols grid of 4-gons onto the boundary with 1, 2 or
 * 3 of its sides (seed Def. 5.4 steps 2 and 3; seed 6.1 padding).
 * - sides == 1: h is the first of `cols` consecutive boundary halfedges; the
 *   grid stacks `rows` layers on them.
 * - sides == 2: h is the boundary halfedge entering the vertex that becomes
 *   the grid corner; the grid covers the `rows` boundary edges ending with h
 *   and the `cols` edges after it (seed step 3).
 * - sides == 3: as 2, plus the `rows` boundary edges after those (seed
 *   step 2).
 * Adds exactly rows*cols faces, all 4-gons, with explicit integer loops. */
sq_status sq_metapolygon_glue_grid(sq_metapolygon *P, uint32_t h, uint32_t rows,
                                   uint32_t cols, uint32_t sides, sq_error *err);

/* ---- extension E(P, i) (sq_metapolygon_extend.c) ----------------------- */

typedef struct sq_extend_stats {
    uint32_t face;         /* index of the glued i-gon                     */
    uint32_t glue_he;      /* boundary halfedge it was glued to (SQ_NONE   */
                           /* when P was empty)                            */
    uint32_t concave;      /* m: concave vertices after step 1 (0..2)      */
    uint32_t grids_step2;  /* grids glued in step 2 (0 or 1)               */
    uint32_t grids_step3;  /* grids glued in step 3 (0..2)                 */
    uint64_t quads_step2;  /* 4-gons added in step 2                       */
    uint64_t quads_step3;  /* 4-gons added in step 3                       */
} sq_extend_stats;

/* Seed 5.1, Def. 5.4: replaces the meta-k-gon P by E(P, i), a
 * meta-(k+i-4)-gon with I(E(P,i)) = I(P) + {i} (Theorem 5.5).
 * glue_he is the boundary halfedge for step 1, or SQ_NONE for the default
 * choice (sq_metapolygon_default_glue_edge); it must be SQ_NONE when P is
 * empty. Preconditions (checked, SQ_ERR_ARGUMENT): P is empty or a
 * metapolygon with k > 0 corners (an empty P counts as k = 4), and
 * i > max(1, 4 - k), i != 4. stats may be NULL. After an argument error P
 * is unchanged; after SQ_ERR_NOMEM (or SQ_ERR_INTERNAL, a bug) it is a valid
 * polygon disk but possibly not a metapolygon, and should be freed. */
sq_status sq_metapolygon_extend(sq_metapolygon *P, uint32_t i, uint32_t glue_he,
                                sq_extend_stats *stats, sq_error *err);

/* ---- glue-edge choice (sq_metapolygon_glue.c) -------------------------- */

/* Seed 5.3: number of 4-gons that E(P, i) adds when gluing to boundary
 * halfedge glue_he of the metapolygon P (exact; used by the default choice
 * and checked against sq_metapolygon_extend by the tests):
 *   i > 4: l - 1 (l: length of the side holding glue_he);
 *   i = 3: x + (x+1)(l-x-1), x = edges between glue_he and its nearest
 *          corner;
 *   i = 2: x + (l-2x-1)(l'+1), l' = length of the other side at that corner.
 * The seed's formulas assume the side's two end corners differ; on a
 * meta-1-gon (one corner, only i > 4 allowed) the count is l.
 * Returns UINT64_MAX if the arguments violate Def. 5.4's preconditions. */
uint64_t sq_metapolygon_predict_quads(const sq_metapolygon *P, uint32_t i, uint32_t glue_he);

/* Default glue edge for E(P, i) when no geometric guidance is given (seed
 * 5.3): the edge minimizing the predicted 4-gon count. Within a side that
 * is, for i > 4 and i = 3, the side's first edge (incident to its starting
 * corner); for i = 2, the edge centred between the two corners (for an even
 * side, the one of the two central edges whose nearest corner has the
 * shorter other side). Among sides the cheapest wins (for i != 2: the
 * shortest side), ties going to the first in C(P) order. SQ_NONE for an
 * empty P. */
sq_status sq_metapolygon_default_glue_edge(const sq_metapolygon *P, uint32_t i,
                                           uint32_t *glue_he, sq_error *err);

/* ---- Q_(n) from a valence sequence (sq_metapolygon_build.c) ------------ */

/* Glue-edge chooser for step `step` (0-based) of the build, which glues a
 * `valence`-gon to P (non-empty, as P is empty only at step 0, where no
 * choice exists). Set *glue_he to a boundary halfedge of P, or to SQ_NONE
 * for the default. This is where geometric guidance plugs in (seed 9.2,
 * Algorithm 1: the boundary edge closest to the next singularity). */
typedef sq_status (*sq_glue_chooser)(void *user, const sq_metapolygon *P, uint32_t step,
                                     uint32_t valence, uint32_t *glue_he, sq_error *err);

typedef struct sq_build_options {
    /* optional: n entries; entry s is the glue halfedge for step s, or
     * SQ_NONE for "ask the chooser / use the default". Entry 0 must be
     * SQ_NONE. */
    const uint32_t *glue_he;
    sq_glue_chooser chooser; /* optional, consulted when glue_he is NULL or */
    void *chooser_user;      /* its entry is SQ_NONE                       */
} sq_build_options;

typedef struct sq_build_stats {
    uint64_t quads;         /* 4-gons in the result                        */
    uint64_t quads_step2;   /* of which added in steps 2 / 3 of Def. 5.4    */
    uint64_t quads_step3;
    uint32_t corners;       /* k of the resulting meta-k-gon               */
} sq_build_stats;

/* Seed 5.2, Prop. 5.1: Q_(n) by Q_(i) = E(Q_(i-1), l_(i-1)), Q_(0) empty.
 * The sequence must be admissible (every l > 1, l != 4, every prefix sum of
 * e(l) = l - 4 greater than -4): otherwise SQ_ERR_ARGUMENT naming the first
 * bad position (sq_valence_order_admissible / sq_valence_order_greedy make
 * one). P must be empty on entry. opt and stats may be NULL. */
sq_status sq_metapolygon_build(sq_metapolygon *P, const uint32_t *valences, uint32_t n,
                               const sq_build_options *opt, sq_build_stats *stats,
                               sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
