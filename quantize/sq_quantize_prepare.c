/* seamquad: step 0 of quantization, the map's distortion lowered first
 * (sq_quantize.h, sq_quantize_prepare).
 *
 * Quantization follows the map: the T-mesh's arcs get integer lengths
 * close to their lengths in the map, and each T-mesh face is re-embedded
 * onto its integer rectangle by the map's own shape. Where the map is far
 * from conformal at the scale of one quad, so are the quads, and where it
 * is extremely so (param's maps: mean conformal ratio 27 to 1e88,
 * triangles stretched by up to 1e92) quads come out folded or upside down
 * on the surface, which extract refuses; step 5 (the integer-grid map
 * optimized with its transitions fixed) cannot undo a layout made from
 * such a map. So the map is optimized first, its rotations and cones kept
 * and its translations free (sq_optimize_map_free_or_fixed: where the free
 * result cannot be made exact, rounds with the transitions fixed).
 *
 * Measured (bench/README.md): param's maps of fandisk at 5K and 20K quads
 * and of knot1 at 20K gave quads that extract refused; prepared, all pass
 * the referee (knot1's map 559 -> 1.19, below the published map's 1.32;
 * fandisk's 1.3e88 -> 1.12). On the published maps of the 15 mpz models
 * the quads' mean |angle - 90| falls on 10 of 15 at 1K and 11 of 15 at
 * 5K (medians 11.52 -> 11.38 and 7.32 -> 6.88 degrees; helmet 20.41 ->
 * 14.85 at 1K). Cost: the optimizer's, 0.02 to 3.6 s on the published
 * maps, minutes on param's largest (its refinement is not undone here:
 * remesh, which has param's structure, simplifies between rounds). */
#include <string.h>

#include "sq_quantize.h"

sq_status sq_quantize_prepare(sq_map *M, const sq_quantize_prepare_options *opt,
                              sq_quantize_prepare_report *rep, sq_error *err)
{
    sq_quantize_prepare_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!M) return sq_error_set(err, SQ_ERR_ARGUMENT, "quantize: step 0 needs a map");
    rep->conformal_before = rep->conformal_after = sq_map_conformal_mean(M);
    sq_optimize_options oo;
    memset(&oo, 0, sizeof oo);
    oo.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
    oo.max_iterations = opt && opt->iterations ? opt->iterations : SQ_QUANTIZE_PREPARE_ITERATIONS;
    if (opt) oo.progress = opt->progress, oo.user = opt->user;
    sq_status st = sq_optimize_map_free_or_fixed(M, &oo, &rep->optimize, err);
    if (st) return st;
    rep->conformal_after = sq_map_conformal_mean(M);
    return SQ_OK;
}
