/* seamquad: integer arc lengths of a T-mesh (quantization; the method, why
 * its constraints are exact and how close its cost is to the optimum are in
 * docs/quantize_lengths.md).
 *
 * A T-mesh (the surface cut along the separatrices traced from the cones of
 * a seamless map) has rectangular faces. Each face has four sides,
 * counterclockwise bottom (0), right (1), top (2), left (3); each side is a
 * sequence of arcs, and every arc lies on exactly two sides (possibly of
 * one face). Integer lengths L >= min_length make an integer-grid map when,
 * for every face f,
 *
 *     sum L(side 0 of f) = sum L(side 2 of f),
 *     sum L(side 1 of f) = sum L(side 3 of f).
 *
 * sq_tmesh_lengths returns such lengths (always exactly: they are checked
 * before returning) with a small weighted deviation sum_a w_a |L_a - t_a|
 * from real targets t_a, computed by min-cost flows on the double cover of
 * the constraints' bi-directed graph (LEMON, sq_mcf.h), together with a
 * lower bound on the cost of every integer solution: where the two meet
 * (stats.cost == stats.lower_bound: on every test mesh but one, which is
 * 0.03% above) the result is proven optimal.
 *
 * Costs: one solve is a min-cost flow on 4 n_faces nodes and at most
 * 6 n_arcs arcs; a call makes 1 solve when the relaxation is integral (the
 * usual case for targets that nearly meet the constraints), else 2 to
 * 3 + 2 SQ_TMESH_MAX_ROUNDS. Measured: 21K arcs, 0.07-0.11 s CPU for one
 * solve. */
#ifndef SQ_TMESH_LENGTHS_H
#define SQ_TMESH_LENGTHS_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest accepted target and min_length (flows and int64 costs stay far
 * from overflow below it). */
#define SQ_TMESH_MAX_LENGTH 1.0e7

/* Most improvement rounds after the first split solve (see the doc). */
#define SQ_TMESH_MAX_ROUNDS 8

typedef struct sq_tmesh_sides {
    uint32_t n_faces, n_arcs;
    const uint32_t *side_off;  /* 4 n_faces + 1 offsets: side s of face f holds
                                  side_arc[side_off[4f+s] .. side_off[4f+s+1]-1];
                                  sides 0..3 counterclockwise: bottom, right, top, left */
    const uint32_t *side_arc;  /* arc indices; each arc appears exactly twice overall */
    const double *target;      /* n_arcs: desired length (> 0, finite) */
    const double *weight;      /* n_arcs, or NULL for all 1 (each >= 0, finite) */
    int64_t min_length;        /* smallest allowed length (>= 1) */
    const int64_t *min_arc;    /* n_arcs or NULL: a larger smallest length for
                                  some arcs (the larger of the two counts) */
} sq_tmesh_sides;

typedef struct sq_tmesh_lengths_stats {
    double cost;             /* sum_a w_a |L_a - t_a| of the result (t: the  */
                             /* targets the result was solved for; for the   */
                             /* smallest layout of for_quads, T's targets)   */
    double lower_bound;      /* no integer solution costs less (the          */
                             /* relaxation with costs interpolated between   */
                             /* the integers; up to the 2^-20 resolution of  */
                             /* the integer weights): cost == lower_bound    */
                             /* proves the result optimal                    */
    uint32_t half_arcs;      /* arcs where the relaxation is half-integral   */
                             /* (0: its solution was integral and returned)  */
    double rounding_cost;    /* the same for max(min_length, round(t_a))     */
    int rounding_feasible;   /* 1 when that rounding meets every constraint  */
    double quads;            /* sum_f L(f, side 0) * L(f, side 1)            */
    uint32_t solves;         /* min-cost flow solves made                    */
    uint32_t improvements;   /* rounds that lowered the cost (see the doc)   */
    uint32_t network_nodes;  /* size of one network                          */
    uint32_t network_arcs;
    /* sq_tmesh_lengths_for_quads only (0 otherwise): */
    double target_scale;     /* factor applied to the targets (0: the        */
                             /* smallest layout, with lower_bound and the    */
                             /* rounding fields 0)                           */
    double min_quads;        /* quads of the solution for vanishing targets: */
                             /* the fewest the constraints allow (up to the  */
                             /* method's approximation)                      */
} sq_tmesh_lengths_stats;

/* Integer lengths length[0 .. n_arcs-1] (caller-owned) for T. stats may be
 * NULL. Errors, naming the face, side or arc: SQ_ERR_EMPTY (no face or no
 * arc); SQ_ERR_INDEX (a side names an arc >= n_arcs); SQ_ERR_ARGUMENT (an
 * arc not on exactly two sides, an empty side, an arc twice on one side,
 * which would force length 0, a target not finite, <= 0 or above
 * SQ_TMESH_MAX_LENGTH, a weight negative or not finite, min_length out of
 * range); SQ_ERR_UNREALIZABLE (no lengths >= min_length satisfy the
 * constraints); SQ_ERR_NOMEM; SQ_ERR_INTERNAL (a result failed the final
 * check: a bug). */
sq_status sq_tmesh_lengths(const sq_tmesh_sides *T, int64_t *length,
                           sq_tmesh_lengths_stats *stats, sq_error *err);

/* Like sq_tmesh_lengths with the targets scaled by one factor, chosen (a few
 * solves) so that the quad count sum_f L(f,0) L(f,1) comes within 5% of
 * n_quads where it can; where the count jumps over that band at one scale
 * (arcs of equal targets rounding together), a second search scales each
 * arc's target by its own fixed factor within 4% of the first. When n_quads is below the smallest reachable count
 * (stats->min_quads) the result is that smallest layout; otherwise the
 * closest count found is returned, in stats->quads. */
sq_status sq_tmesh_lengths_for_quads(const sq_tmesh_sides *T, double n_quads, int64_t *length,
                                     sq_tmesh_lengths_stats *stats, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
