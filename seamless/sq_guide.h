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

#include <stdint.h>

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_metapolygon.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SQ_GUIDE_PI 3.14159265358979323846

/* Layout of the cut surface of m along G in the unit disk (seed 9.2: "a map
 * ... of the cut surface onto the unit disk"). The boundary walk of G (disk
 * on the left) runs counterclockwise around the circle, by arc length,
 * starting at angle 0 at G's corner 0. v_xy (2 m->nv, caller-owned)
 * receives the position of every vertex off the cut, NaN for vertices on
 * the cut; corner_angle (G->pattern.k, caller-owned) the angle of every
 * corner of G in [0, 2 pi). */
sq_status sq_guide_surface_disk(const sq_mesh *m, const sq_cut_graph *G, double *v_xy,
                                double *corner_angle, sq_error *err);

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
    /* the chooser's cache (zero-initialize; sq_guide_glue_free): above 5000
     * faces the layout is recomputed only when the metapolygon has grown by
     * a quarter, new vertices placed at their neighbours' average between */
    double *xy;
    uint32_t cap, nv_laid, nf_laid;
} sq_guide_glue;

void sq_guide_glue_free(sq_guide_glue *G);

sq_status sq_guide_glue_chooser(void *user, const sq_metapolygon *P, uint32_t step, uint32_t valence,
                                uint32_t *glue_he, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
