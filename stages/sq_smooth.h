/* seamquad: quad mesh smoothing on a triangle surface with Ceres (see
 * docs/smooth.md).
 *
 * Moves the vertices of a closed quad mesh so that corner angles approach 90
 * degrees and edge lengths become locally uniform, keeping every vertex on
 * the input triangle surface (each vertex ends as a closest point: a
 * barycentric combination of one surface triangle's corners) and the
 * connectivity unchanged. Folded input quads are untangled first; after
 * that no accepted step folds a quad (robust fold test, sq_quad_fold_margin).
 * Where the quads would cut off a sharp point of the surface, a quad vertex
 * is held on it (pin_threshold). */
#ifndef SQ_SMOOTH_H
#define SQ_SMOOTH_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Quality of a quad mesh, with the referee's formulas (check_quad.py [6]). */
typedef struct sq_quad_quality {
    uint32_t nq;
    double angle_min_deg, angle_max_deg;
    double angle_mean_dev_deg;  /* mean |corner angle - 90| over all corners  */
    double sjac_min, sjac_mean; /* scaled Jacobian per quad (min over corners) */
    double edge_ratio_mean, edge_ratio_max; /* longest / shortest edge of a quad */
    uint32_t folded;            /* both triangulations fold by > 90 degrees    */
    double fold_margin_min;     /* min over quads of sq_quad_fold_margin       */
} sq_quad_quality;

/* Fold margin of quad (p0, p1, p2, p3): the larger, over its two
 * triangulations (02 and 13), of the cosine of the angle between the two
 * triangle normals; -1 when a triangle is degenerate. The referee calls a
 * quad folded when both cosines are negative, i.e. when this is < 0. */
double sq_quad_fold_margin(const double *p0, const double *p1, const double *p2, const double *p3);

/* The unit normal of triangle (a, b, c), (b - a) x (c - a) normalized,
 * into n (left as it is when the cross product is zero); returns 1 when
 * it has a direction, 0 when the triangle is too thin for one (the cross
 * product below 1e-10 of the longest side squared: rounding decides it). */
int sq_triangle_unit_normal(const double *a, const double *b, const double *c, double n[3]);

/* Turn margin of quad p[0..3] against the unit surface normals n[k] at its
 * corners (a quad turned over on the surface: sq_extract.h): the largest
 * over the corners of the cosine between the corner's normal (of the
 * triangle of the corner and its two neighbours) and n[k], a corner below
 * 1e-6 of the quad's largest counting 0 (its direction is rounding
 * noise): < 0 exactly when every corner faces away from its n[k]. */
double sq_quad_turn_margin(const double *const p[4], const double *const n[4]);

/* The turn margin that decides "turned over" (extract's check, the
 * smoother's acceptance, the repair): the larger of the margins against
 * the interpolated unit vertex normals `smooth` and the holding
 * triangles' own normals `flat` (smooth's where a triangle is too thin to
 * have one): a quad is turned when every corner faces away from both. */
double sq_quad_turn_margin_either(const double *const p[4], const double *const smooth[4],
                                  const double *const flat[4]);

void sq_quad_quality_compute(const double *pos, uint32_t nq, const uint32_t *quads,
                             sq_quad_quality *q);

/* The same without the corner angles (angle_* fields left at 180, 0 and
 * 0): every other field identical to sq_quad_quality_compute's, at a
 * fraction of the cost (no atan2). */
void sq_quad_quality_compute_shapes(const double *pos, uint32_t nq, const uint32_t *quads,
                                    sq_quad_quality *q);

/* The referee's size figures of quad (p0, p1, p2, p3) (check_quad.py
 * [3]): its area (the mean of its two triangulations') and its shortest
 * edge. */
void sq_quad_size(const double *p0, const double *p1, const double *p2, const double *p3, double *area,
                  double *shortest_edge);

/* The quads around each vertex of a quad mesh (sq_quad_star.c): those of
 * vertex v are quad[off[v] .. off[v + 1]), and next[k] is the corner after
 * v in quad[k], so that next lists every edge neighbour of v once where
 * the mesh is closed and manifold. */
typedef struct sq_quad_star {
    uint32_t *off;  /* nv + 1 */
    uint32_t *quad; /* 4 nq   */
    uint32_t *next; /* 4 nq   */
} sq_quad_star;

/* SQ_ERR_NOMEM or SQ_OK; S is zeroed on failure. */
sq_status sq_quad_star_build(uint32_t nv, uint32_t nq, const uint32_t *quads, sq_quad_star *S, sq_error *err);
void sq_quad_star_free(sq_quad_star *S);

/* The smallest sq_quad_fold_margin of the quads around v (2 if none). */
double sq_quad_star_worst_margin(const sq_quad_star *S, const double *pos, const uint32_t *quads, uint32_t v);

typedef struct sq_smooth_options {
    int iterations;          /* outer iterations: optimize, re-project (10)       */
    int solver_iterations;   /* Levenberg-Marquardt iterations per outer one (5)  */
    int linear_iterations;   /* conjugate-gradient iterations per LM step (10)    */
    int untangle_solver_iterations; /* the same two while untangling (20, 500)    */
    int untangle_linear_iterations;
    int untangle_iterations; /* outer iterations allowed for untangling (30)      */
    double angle_weight;     /* weight of the corner-angle residuals (1)          */
    double length_weight;    /* weight of the edge-length residuals (1)           */
    double untangle_weight;  /* weight of the untangling residuals (4)            */
    double barrier_weight;   /* weight of the fold-margin log barrier (0.1)       */
    double fold_margin;      /* keep every quad's fold margin >= min(this, half   */
                             /* its margin after untangling) (0.01)               */
    double untangle_target;  /* untangle until every fold margin >= this (1e-3)   */
    double pin_threshold;    /* fidelity pins (docs/smooth.md, "Fidelity"): a     */
                             /* surface vertex that the quads miss by more than  */
                             /* this times the local edge length (and by half    */
                             /* the widest gap) gets a quad vertex held on it    */
                             /* (0.3; 0: no pins)                                */
    double function_tolerance, gradient_tolerance, parameter_tolerance; /* Ceres  */
    double trust_region_radius; /* Levenberg-Marquardt's first trust region in  */
                             /* each solve (1e4, as Ceres')                      */
    double cautious_trust_region_radius; /* instead, once a quick step failed */
                             /* or stalled early, before going thorough (1: a    */
                             /* first damping equal to the normal equations'     */
                             /* diagonal; docs/smooth.md, "Trust region")        */
    double stop_tolerance;   /* stop when an outer iteration lowers the energy by */
                             /* less than this, relative (1e-4)                   */
    double thorough_stop_tolerance; /* the same for thorough iterations (1e-3):  */
                             /* each costs several quick ones                    */
    int num_threads;         /* Ceres threads (1)                                 */
    /* optional progress report (the library never prints) */
    void (*progress)(void *user, const char *phase, int iteration, double energy, uint32_t folded);
    void *progress_user;
} sq_smooth_options;

typedef struct sq_smooth_stats {
    sq_quad_quality before;      /* the input as given                         */
    sq_quad_quality projected;   /* after projecting it onto the surface       */
    sq_quad_quality untangled;   /* after untangling                           */
    sq_quad_quality after;       /* the result                                 */
    double dist_before_rel;      /* max vertex-to-surface distance / diagonal  */
    double dist_after_rel;
    int untangle_iterations, iterations;
    long solver_iterations;      /* Ceres iterations, all outer iterations      */
    long solver_rejected;        /* Ceres steps rejected (any reason)           */
    long fold_rejections;        /* trial states that would fold a quad         */
    int backtracks;              /* halvings of a step after re-projection      */
    int steps_rejected;          /* outer steps rejected whole (fold / quality) */
    int retries;                 /* damped retries after a rejected step        */
    uint32_t pinned;             /* quad vertices held on surface vertices      */
    int cautious;                /* 1: a quick step failed or stalled: the later */
                                 /* ones from cautious_trust_region_radius      */
    int thorough;                /* 1: the quick steps failed at once or stalled */
                                 /* early; the later ones used untangling's      */
                                 /* bounds (docs/smooth.md)                      */
    double energy_before, energy_after; /* smoothing energy (sum of squares)   */
    double seconds;
    char linear_solver[48];
    char stop_reason[160];
} sq_smooth_stats;

void sq_smooth_options_default(sq_smooth_options *o);

/* Smooths the quad mesh (nv vertices pos: 3*nv, updated in place; nq quads:
 * 4*nq indices, closed and validated by the caller) on the triangle surface
 * (snv vertices spos, snt triangles stri). On failure pos keeps the last
 * accepted state. SQ_ERR_SOLVER when untangling leaves a folded quad. */
sq_status sq_smooth_quads(uint32_t snv, const double *spos, uint32_t snt, const uint32_t *stri,
                          uint32_t nv, double *pos, uint32_t nq, const uint32_t *quads,
                          const sq_smooth_options *opt, sq_smooth_stats *stats, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
