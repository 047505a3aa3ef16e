/* seamquad: param's map, optimized and simplified (`seamquad param
 * --optimize on`, stage 4 of `seamquad remesh`).
 *
 * param's maps are valid (exact seams, every triangle positive, exactly
 * the cones) but refined 3 to 39 times and far from conformal. These two
 * calls turn param's result into an exact sq_map and lower its distortion
 * in rounds: a few optimizer iterations (rotations kept, translations
 * free), then param's own simplification on the optimized UVs, which can
 * remove far more of the added vertices once the map is less distorted
 * (docs/param.md, step 10). The seams' rotations and the
 * cones never change; the translations do not stay integer (quantize
 * makes them integer again). */
#ifndef SQ_PARAM_OPTIMIZE_H
#define SQ_PARAM_OPTIMIZE_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"
#include "sq_mesh.h"
#include "sq_optimize.h"
#include "sq_param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The budget of `param --optimize on` and of remesh (SQ_REMESH_ITERATIONS,
 * where it is measured): the rounds stop sooner where they converge. */
#define SQ_PARAM_OPTIMIZE_ITERATIONS 600u

/* What the rounds did. */
typedef struct sq_param_optimize_report {
    uint32_t iterations;           /* optimizer iterations, all rounds       */
    uint32_t reference_iterations; /* of them, with progressive references   */
    uint32_t rounds;               /* simplifications run                    */
    uint32_t fixed_rounds;         /* rounds run with the translations fixed */
                                   /* (free ones failed the exact check)     */
    uint32_t removed;              /* vertices they removed                  */
    uint32_t faces_before, faces_after;
    double conformal_before, conformal_after; /* area-weighted mean          */
                                   /* sigma1/sigma2 (the referee's figure)   */
    char why[160];                 /* why the last optimizer run stopped     */
} sq_param_optimize_report;

/* param's result P (built on m, whose cones are `valence`) as an exact map
 * of a refinement of m (its first vertices are m's), checked by
 * sq_map_check: nothing is snapped, a seam that is not exact fails
 * (sq_param_map.c). */
sq_status sq_param_map(const sq_param *P, const sq_mesh *m, const int32_t *valence, sq_map *out,
                       sq_error *err);

/* P's map optimized (base: the optimizer's options; its max_iterations is
 * ignored) for at most `budget` iterations in all, in rounds each followed
 * by sq_param_simplify on P with the optimized UVs (sq_param_optimize.c).
 * P is simplified in place and holds the final UVs; *M gets the final map
 * (exact, sq_map_check passes; the caller frees it with sq_map_free). */
sq_status sq_param_optimize(const sq_mesh *m, const int32_t *valence, sq_param *P,
                            const sq_optimize_options *base, uint32_t budget, sq_map *M,
                            sq_param_optimize_report *rep, sq_error *err);

#ifdef __cplusplus
}
#endif

#endif
