/* seamquad: distortion optimization of a seamless map that keeps its seams,
 * cones and injectivity (docs/optimize.md).
 *
 * Energy: the symmetric Dirichlet energy, the area-weighted mean over the
 * triangles of |J|^2 + |J^-1|^2 (J: the triangle's Jacobian from the
 * surface to the map; 4 for an isometry, infinite for a degenerate or
 * flipped triangle). The surface is scaled so that its area equals the
 * map's, so the energy measures shape, not size.
 *
 * Unknowns: an affine basis of the seamless maps with the input's rotations
 * (sq_uv_basis.h): every iterate is seamless by construction.
 *
 * Method: projected Newton (per-triangle Hessians made positive
 * semidefinite by their eigen-decomposition, solved with CHOLMOD). Each step
 * is first limited to the largest one that keeps every triangle's
 * orientation (a quadratic per triangle), then shortened until the energy
 * decreases enough (Armijo), and accepted only if the exact orientation
 * test (sq_orient2d) finds every triangle positive.
 *
 * The result is exactly seamless (with fixed transitions every iterate is;
 * with free translations it is snapped to a dyadic grid) and checked
 * exactly (sq_map_check, with SQ_MAP_REQUIRE_INTEGER for an integer-grid
 * map); if that fails, or the energy did not decrease, the map is left
 * unchanged and the report says why. The map is never made invalid.
 * Triangles too distorted or too thin to move are held where they are
 * (rep->held_triangles). */
#ifndef SQ_OPTIMIZE_H
#define SQ_OPTIMIZE_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    /* rotations and translations kept, cones fixed: an integer-grid map
     * stays one (after quantization) */
    SQ_OPTIMIZE_FIXED_TRANSITIONS = 0,
    /* rotations kept, translations free (before quantization) */
    SQ_OPTIMIZE_FREE_TRANSLATIONS = 1
};

#define SQ_OPTIMIZE_REFERENCE_BOUND 1000.0

typedef struct sq_optimize_options {
    int basis;                /* SQ_OPTIMIZE_FIXED_TRANSITIONS or _FREE_TRANSLATIONS */
    uint32_t max_iterations;  /* 0: 100                                              */
    double tolerance;         /* stop when an iteration lowers the energy by less    */
                              /* than this fraction; 0: 1e-4                         */
    /* progressive references while a triangle's energy exceeds this bound
     * (sq_optimize.c, PROG_PATIENCE): 0 gives SQ_OPTIMIZE_REFERENCE_BOUND;
     * INFINITY (or any value <= 4) turns them off */
    double reference_bound;
    /* step 0 (sq_optimize_relax.c) moves the vertices beside triangles
     * stretched by more than this: 0 gives 100 without references, 1e4
     * with them (sq_optimize.c, RELAX_BOUND); INFINITY skips step 0 */
    double relax_bound;
    /* 1: the last iterate is returned (if it passes the exact check) even
     * when its energy against the surface is above the input's, as it may
     * be after a few iterations with progressive references; for callers
     * that run the optimizer in rounds (sq_param_optimize). Default 0:
     * never worse. */
    int keep_last;
    /* NULL, or per face of the map a factor on its reference triangle:
     * the map is drawn toward that many times the surface's size there,
     * so that a layout at a given quad count puts its square as many
     * quads on the face (sq_remesh's magnified layouts) */
    const double *face_scale;
    /* called after every iteration (may be NULL): a progress hook; the
     * iteration it gets is counted from progress_base + 1 (callers that
     * run the optimizer in rounds count across them) */
    void (*progress)(void *user, uint32_t iteration, double energy, double step);
    void *user;
    uint32_t progress_base;
} sq_optimize_options;

typedef struct sq_optimize_report {
    uint32_t iterations;      /* accepted Newton steps                               */
    uint32_t unknowns;        /* real unknowns of the basis                          */
    uint32_t held_triangles;  /* not positive in doubles at the start: held in place */
    uint32_t reference_iterations; /* of the iterations, those against progressive   */
                              /* references                                         */
    double energy_before;     /* area-weighted mean symmetric Dirichlet energy over  */
                              /* the triangles not held (a sliver weighs at least    */
                              /* 1e-12 of the mean; sq_optimize.c)                   */
    double energy_after;
    double max_energy_before; /* of the worst triangle                               */
    double max_energy_after;
    uint32_t relax_moves;     /* step 0: local moves of vertices beside extreme      */
                              /* triangles (sq_optimize_relax.c)                     */
    double relax_stretch_before; /* the largest stretch max(s1, 1/s2) of a triangle  */
    double relax_stretch_after;  /* before and after step 0                          */
    int changed;              /* 1 if M was changed (step 0 or the iterations)       */
    int iterate_kept;         /* 1 if the iterations' (last round's) map is M: it    */
                              /* passed the exact check and lowered the energy       */
    uint32_t rounds;          /* sq_optimize_map_free_or_fixed: the runs made, and   */
    uint32_t fixed_rounds;    /* of them those with the transitions fixed            */
    char why[160];            /* why the optimization stopped, or was not applied    */
    double seconds_basis, seconds_solve, seconds;
} sq_optimize_report;

/* Optimizes the exact map M in place (it must pass sq_map_check; with
 * SQ_OPTIMIZE_FIXED_TRANSITIONS and an integer-grid M, the result is one
 * too). rep may be NULL. An error is returned only for bad arguments, lack
 * of memory or a solver failure; an optimization that cannot improve the
 * map leaves it unchanged with rep->changed = 0. */
sq_status sq_optimize_map(sq_map *M, const sq_optimize_options *opt, sq_optimize_report *rep,
                          sq_error *err);

/* sq_optimize_map with free translations (opt->basis must be
 * SQ_OPTIMIZE_FREE_TRANSLATIONS) for opt->max_iterations; where its result
 * cannot be made exact (the iterations are discarded), rounds with the
 * transitions fixed and free again (sq_optimize_free.c). rep sums the
 * rounds: iterations kept, step 0's moves; energies and worst stretch
 * before the first round and after the last (each as its round measured
 * it); `why` the last round's. One round is sq_optimize_map's report. */
sq_status sq_optimize_map_free_or_fixed(sq_map *M, const sq_optimize_options *opt, sq_optimize_report *rep,
                                        sq_error *err);
/* The energy of M without optimizing it: mean and max (either may be
 * NULL). Triangles of zero area on the surface are left out. */
void sq_optimize_energy(const sq_map *M, double *mean, double *max);
/* The area-weighted mean conformal ratio sigma1/sigma2 of M (the referee's
 * figure; triangles of zero area on the surface, or not positive in the
 * map, left out; INFINITY if none is left). */
double sq_map_conformal_mean(const sq_map *M);

#ifdef __cplusplus
}
#endif
#endif
