/* seamquad: a map optimized with its translations free, with rounds of
 * fixed transitions where the free result cannot be made exact
 * (sq_optimize.h, sq_optimize_map_free_or_fixed).
 *
 * With free translations, sq_optimize_map's result is snapped to a dyadic
 * grid and checked exactly; a triangle far thinner than the grid (param's
 * maps hold them, down to 1e-16 of the map's size after step 0) can come
 * out of the snap flat or flipped, and the run's iterations are then
 * discarded (step 0's moves stay: they are exact). With fixed transitions
 * every iterate is exact as it is (only the vertices on seams are rounded,
 * to a grid on which the transitions are exact sums), and the iterations
 * widen the slivers. So:
 *  1. one free run of the whole budget; if its result is kept, that is all
 *     (the published maps, and most of param's);
 *  2. else a round of FIXED_ROUND iterations with the transitions fixed,
 *     then free rounds again, FIXED_ROUND iterations first and twice as
 *     many after each kept one; a refused free round is followed by a
 *     fixed round again.
 * Every round but the last keeps its last iterate (keep_last: progressive
 * references, restarted by every round, can raise the energy against the
 * surface over a few iterations); the rounds double so that restarts stay
 * few. It ends when the budget (the iterations of refused runs included)
 * is spent or a round ends early (converged, stalled, refused). Measured
 * on param's map of fandisk (mean conformal ratio 1.3e88; its free run is
 * refused): one fixed run after it stalls at 3e9, the rounds reach 1.12.
 * The map handed back passes sq_map_check (sq_optimize_map never returns
 * one that does not). */
#include <stdio.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_optimize.h"

/* the iterations of a fixed round, and of the first free round after it
 * (remesh's rounds: sq_param_optimize.c) */
#define FIXED_ROUND 5u

/* r's figures added to the rounds' report */
static void add_round(sq_optimize_report *rep, const sq_optimize_report *r)
{
    if (rep->rounds++ == 0) {
        rep->energy_before = r->energy_before;
        rep->max_energy_before = r->max_energy_before;
        rep->relax_stretch_before = r->relax_stretch_before;
        rep->held_triangles = r->held_triangles;
        rep->unknowns = r->unknowns;
    }
    rep->energy_after = r->energy_after;
    rep->max_energy_after = r->max_energy_after;
    rep->relax_moves += r->relax_moves;
    rep->relax_stretch_after = r->relax_stretch_after;
    rep->changed |= r->changed;
    rep->iterate_kept = r->iterate_kept;
    rep->seconds_basis += r->seconds_basis;
    rep->seconds_solve += r->seconds_solve;
    memcpy(rep->why, r->why, sizeof rep->why);
}

sq_status sq_optimize_map_free_or_fixed(sq_map *M, const sq_optimize_options *opt, sq_optimize_report *rep,
                                        sq_error *err)
{
    sq_optimize_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!M || !opt || opt->basis != SQ_OPTIMIZE_FREE_TRANSLATIONS)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_optimize_map_free_or_fixed: a map and free translations");
    double t0 = sq_now();
    uint32_t budget = opt->max_iterations ? opt->max_iterations : 100, spent = 0, size = budget;
    snprintf(rep->why, sizeof rep->why, "no iteration");
    while (spent < budget) {
        sq_optimize_options o = *opt;
        o.progress_base = opt->progress_base + rep->iterations;
        o.max_iterations = size < budget - spent ? size : budget - spent;
        o.keep_last = opt->keep_last || o.max_iterations < budget - spent;
        sq_optimize_report r;
        sq_status st = sq_optimize_map(M, &o, &r, err);
        if (st) return st;
        add_round(rep, &r);
        spent += r.iterations;
        if (r.iterate_kept) {
            rep->iterations += r.iterations;
            rep->reference_iterations += r.reference_iterations;
            if (r.iterations < o.max_iterations) break;
            size = 2 * size < size ? size : 2 * size;
            continue;
        }
        o.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
        if (o.max_iterations > FIXED_ROUND) o.max_iterations = FIXED_ROUND;
        o.progress_base = opt->progress_base + rep->iterations;
        if ((st = sq_optimize_map(M, &o, &r, err))) return st;
        add_round(rep, &r);
        rep->fixed_rounds++;
        spent += r.iterations;
        rep->iterations += r.iterations;
        rep->reference_iterations += r.reference_iterations;
        if (r.iterations < o.max_iterations) break;
        size = FIXED_ROUND;
    }
    rep->seconds = sq_now() - t0;
    return SQ_OK;
}
