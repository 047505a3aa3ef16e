/* seamquad: geometric guidance (seed 9.2) for the surface parametrization.
 *
 * The combinatorial construction is correct for any correspondence between
 * the surface's cones and the domain's irregular vertices; geometry only
 * decides which correspondence (seed 4: "technically an arbitrary choice
 * suffices"). A correspondence unrelated to the surface makes the cone tree
 * wind across the surface and the interior map squeeze cells below double
 * precision. Here both disks are laid out in the unit disk with their
 * boundary corners at the same angles, and each domain cone is matched to
 * the surface cone of the same valence nearest to it:
 *   - sq_guide_surface_disk: the cut surface M^c (a disk) by a mean-value
 *     Tutte map with its boundary on the unit circle by arc length;
 *   - sq_guide_domain_disk: the quad disk Q by a uniform Tutte map with its
 *     corners at given angles and its boundary evenly spaced between them;
 *   - sq_guide_match: per valence, the assignment of least total squared
 *     distance found by a greedy start and pairwise exchanges.
 *
 * The library never prints or exits. */
#ifndef SQ_GUIDE_H
#define SQ_GUIDE_H

#include <stdatomic.h>
#include <stdint.h>

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_metapolygon.h"
#include "sq_omega.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SQ_GUIDE_PI 3.14159265358979323846
enum { SQ_GUIDE_LEFT = 1, SQ_GUIDE_RIGHT = 2 };

/* Layout of the cut surface of m along G in the unit disk (seed 9.2: "a map
 * ... of the cut surface onto the unit disk"). The boundary walk of G (disk
 * on the left) runs counterclockwise around the circle, by arc length,
 * starting at angle 0 at G's corner 0. v_xy (2 m->nv, caller-owned)
 * receives the position of every vertex off the cut, NaN for vertices on
 * the cut; corner_angle (G->pattern.k, caller-owned) the angle of every
 * corner of G in [0, 2 pi). */
sq_status sq_guide_surface_disk(const sq_mesh *m, const sq_cut_graph *G, double *v_xy,
                                double *corner_angle, sq_error *err);

/* The same outputs from a layout with little length distortion
 * (sq_guide_surface_arap.c): from sq_guide_surface_disk's, the boundary
 * freed and `iters` as-rigid-as-possible iterations (one rotation per
 * triangle, one sparse solve), then moved and scaled into the unit disk
 * (centroid at the origin, farthest point at radius 0.999). corner_angle:
 * each corner's direction from the centroid, in [0, 2 pi), in general no
 * longer increasing with the corner's index. */
sq_status sq_guide_surface_arap(const sq_mesh *m, const sq_cut_graph *G, uint32_t iters, double *v_xy,
                                double *corner_angle, sq_error *err);
#define SQ_GUIDE_ARAP_ITERS 30

/* Layout of D's quad disk Q in the unit disk: corner i of Q at angle
 * corner_angle[i]; Q's boundary runs clockwise (decreasing angle) from
 * corner i to corner i + 1, its vertices evenly spaced; interior vertices
 * by a uniform Tutte map. q_xy: 2 Q->nv, caller-owned (boundary vertices
 * get their circle positions). */
sq_status sq_guide_domain_disk(const sq_domain *D, const double *corner_angle, double *q_xy,
                               sq_error *err);

/* Matches n points a (positions a_xy, labels a_val) to n points b of the
 * same labels: a_to_b[i] is the b matched to a[i], each b used once, the
 * labels equal. Per label, the greedy assignment by increasing distance,
 * improved by exchanging pairs while the total squared distance drops.
 * SQ_ERR_ARGUMENT when the label multisets differ. */
sq_status sq_guide_match(uint32_t n, const double *a_xy, const int32_t *a_val, const double *b_xy,
                         const int32_t *b_val, uint32_t *a_to_b, sq_error *err);

/* Seed 9.2: the order in which the metapolygon construction takes the n
 * cones (valence[i], disk position xy[2i..2i+1]): by distance from the
 * disk centre, valences > 4 moved forward where the prefix condition of
 * seed 5.1 needs them (sq_valence_order_greedy_index). order: n indices.
 * SQ_ERR_ARGUMENT when no order is admissible (total excess <= -4, or a
 * valence below 2 or equal to 4). */
sq_status sq_guide_cone_order(uint32_t n, const int32_t *valence, const double *xy, uint32_t *order,
                              sq_error *err);

/* Layout of the metapolygon P (seed 9.2, Algorithm 1 line 3): every face
 * near a similar copy of its regular polygon, and for j < npinned either
 * the barycentre of the j-th irregular face (faces of valence != 4 in index
 * order; pin_vert NULL) or vertex pin_vert[j] at c[2j..2j+1] (least
 * squares, weight 10 against 1 per face edge). xy: 2 P->nv, caller-owned. */
sq_status sq_guide_metapolygon_layout(const sq_metapolygon *P, const double *c, uint32_t npinned,
                                      const uint32_t *pin_vert, double *xy, sq_error *err);

/* sq_glue_chooser of Algorithm 1 (lines 3-5): user points to an
 * sq_guide_glue (not const: it holds a cache); the boundary edge closest to c[step] in the layout pinned
 * at c[0 .. step-1], among the edges where extension by `valence` is
 * allowed. Each choice is also stored in chosen[step] (when not NULL), so
 * that the same metapolygon can be rebuilt without layouts
 * (sq_build_options.glue_he). */
typedef struct sq_guide_glue {
    const double *c;  /* 2 per step: singularity positions in construction order */
    uint32_t *chosen; /* optional, one per step (entry 0 stays as it was)        */
    /* optional: once it holds non-zero, the chooser fails with
     * SQ_ERR_SOLVER (another attempt passed: sq_param_attempts.c) */
    const _Atomic int *cancel;
    /* which of the boundary edges tied for nearest (distances within a
     * relative 1e-9) is taken: 0 the first in index order; v > 0 the
     * least of a hash of (edge, v), so every v gives another domain where
     * ties occur (sq_param's domain variants) */
    uint32_t variant;
    /* the chooser's cache (zero-initialize; sq_guide_glue_free): above 5000
     * faces the layout is recomputed only when the metapolygon has grown by
     * a quarter, new vertices placed at their neighbours' average between */
    double *xy;
    uint32_t cap, nv_laid, nf_laid;
} sq_guide_glue;

void sq_guide_glue_free(sq_guide_glue *G);

sq_status sq_guide_glue_chooser(void *user, const sq_metapolygon *P, uint32_t step, uint32_t valence,
                                uint32_t *glue_he, sq_error *err);

/* Seed 9.4 on the surface (sq_guide_tree.c): the n cones cone[0..n), in
 * radial order (seed 9.2's step order), joined one by one to the tree
 * grown from cone[0], each by a shortest path (Euclidean edge lengths)
 * through vertices that are neither on G's cut nor cones, ending at the
 * first tree vertex it reaches. For j >= 1, att_step[j] = p: that vertex
 * lies on path p (the path of step p, from cone[p]; p = 0 is cone[0]
 * alone), at the fraction att_frac[j] in [0, 1) of its length from
 * cone[p] (0: the cone itself), arriving from its side att_side[j]
 * (SQ_GUIDE_LEFT or SQ_GUIDE_RIGHT of path p walked from cone[p]; 0 at a
 * cone). A cone walled in by the cut and other cones gets att_step[j] =
 * SQ_NONE (no preference). att_step[0] = SQ_NONE. att_vertex (may be
 * NULL): the vertex of m each path ends at (SQ_NONE where none).
 * tree_next (m->nv, may be NULL): the tree as a forest rooted at cone[0]:
 * for every tree vertex but cone[0] its neighbour along its path towards
 * the path's end; SQ_NONE elsewhere. */
sq_status sq_guide_surface_tree(const sq_mesh *m, const sq_cut_graph *G, uint32_t n, const uint32_t *cone,
                                uint32_t *att_step, double *att_frac, uint8_t *att_side, uint32_t *att_vertex,
                                uint32_t *tree_next, sq_error *err);

/* The root path of the surface tree (seed 9.4: "the singularity closest to
 * the boundary of the unit disk is connected to the closest boundary point
 * by a shortest path"): from cone[step] through vertices neither on the
 * cut, cones nor on the tree (tree_next from sq_guide_surface_tree) to the
 * nearest inner vertex of a side of G (of side `side` only, unless that is
 * SQ_NONE), entered from the cut disk's side of it. Out: vertex, side and
 * index (side_he[side_off[side] + index] leaves vertex); SQ_NONE when no
 * such vertex is reached. path_next (may be NULL; may be tree_next itself
 * to attach the path to the tree): every vertex of the path but the cone
 * gets its neighbour towards the cone. */
typedef struct sq_guide_root {
    uint32_t step, side; /* in (side: SQ_NONE for any); side also out */
    uint32_t vertex, index;
} sq_guide_root;

sq_status sq_guide_surface_root(const sq_mesh *m, const sq_cut_graph *G, uint32_t n, const uint32_t *cone,
                                const uint32_t *tree_next, uint32_t *path_next, sq_guide_root *root,
                                sq_error *err);

/* The same tree in Q (seed 9.4: the surface paths "replicated as discrete
 * geodesic paths"): qv[j] is the cone of Q standing for step j. In step
 * order, qv[j] is joined by a breadth-first shortest path (interior edges;
 * through interior vertices of Q that are neither cones nor on the tree)
 * to a vertex of Q's path att_step[j], arriving from side att_side[j] of
 * it (att_side may be NULL), the one minimizing edges plus the distance
 * from the fraction att_frac[j] of that path (where that is blocked: from
 * either side, then to any tree vertex); finally
 * qv[root_step] is joined to the flat boundary vertex of Q, the root,
 * that minimizes edges plus root_cost (Q->nv, may be NULL). att_qvertex, att_qstep, att_qfrac (each may be NULL): the vertex
 * of Q each path ends at, the step whose path holds it and its fraction of
 * that path's length (in edges).
 * T is replaced (sq_cone_tree_from_edges). SQ_ERR_SOLVER when a
 * path is blocked in Q (the caller may fall back to
 * sq_cone_tree_shortest). */
sq_status sq_cone_tree_guided(const sq_metapolygon *Q, uint32_t n, const uint32_t *qv, const uint32_t *att_step,
                              const double *att_frac, const uint8_t *att_side, uint32_t root_step,
                              const double *root_cost, uint32_t *att_qvertex, uint32_t *att_qstep, double *att_qfrac, sq_cone_tree *T,
                              sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
