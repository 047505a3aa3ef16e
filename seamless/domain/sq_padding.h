/* seamquad: the padding equation system of seed 6.3, solved exactly.
 *
 * Discrete padding (seed 6.1): gluing w_s layers of quads along side s of a
 * (subdivided) metapolygon adds w_s edges to its two neighbouring sides.
 * The padding numbers that make identified sides equally long solve one
 * small linear system A w = b (seed 6.3); they must be nonnegative integers.
 *
 * General form (seamless-notes 3), so that splits/sliding (seed 6.4) and
 * several pieces (seed 6.2: genus 1 and 2) use the same solver:
 * - pieces, each a cyclic list of sides in boundary order with integer
 *   lengths L_s >= 0 (the quad edges on the side);
 * - per side, flags: SQ_PAD_ZERO forces w_s = 0 (a split side, seed 6.4);
 *   SQ_PAD_STRAIGHT_START marks the corner at the start of s (between the
 *   previous side of its piece and s) as straight (180 degrees: both sides
 *   lie on one metapolygon side, so they get the same padding, neither
 *   lengthens the other, and no corner square is added there);
 * - the final length of s is L'_s = d L_s + w_p [if the corner between the
 *   previous side p and s is a right angle] + w_n [likewise for the next
 *   side n], d the refinement factor (1 unless needed, see below);
 * - constraints: sum_t coef_t L'_{side_t} = 0, e.g. L'_i - L'_j = 0 for an
 *   identified pair, or L'_{a1} + L'_{a2} - L'_j = 0 for a side split in
 *   two whose twin is whole.
 *
 * The solver (sq_pad_solve, docs/padding.md):
 * 1. exact rational Gaussian elimination (GMP mpq): rank, feasibility over
 *    Q and, if infeasible, the violated invariant of the lengths;
 * 2. integral solution via a column Hermite normal form (GMP mpz): an
 *    integral w exists iff the pivot unknowns come out integral; otherwise
 *    d = lcm of their denominators is the smallest refinement (d x d
 *    subdivision of every quad scales all lengths by d, seed 6.3);
 * 3. nonnegativity: if (1 on every unforced side) is a null vector (one
 *    piece, no forced zeros, no straight corners next to forced zeros:
 *    padding every side once adds 2 to every side, seamless-notes 3), w is
 *    shifted by a multiple of it; otherwise an exact simplex (mpq, Bland's
 *    rule) decides whether a nonnegative solution exists and gives a
 *    vertex; a fractional vertex is made integral by further refinement;
 * 4. objective (seed 9.3): the number of added quads,
 *    sum_s w_s L_s + sum_{right corners (p, s)} w_p w_s, is decreased by a
 *    steepest descent over integral null-space moves that keep w >= 0,
 *    from the shifted point and from the exact LP vertex when that is
 *    integral; the better result is kept (heuristic, not a proven optimum;
 *    see docs/padding.md).
 *
 * Infeasibility is not a library failure: sq_pad_solve sets res->outcome
 * and returns SQ_ERR_ARGUMENT with a message naming the violated invariant
 * (for patterns: the closure vector); callers that search over options
 * (slides, side offsets, seed 9.3) test res->outcome. */
#ifndef SQ_PADDING_H
#define SQ_PADDING_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_pattern.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SQ_PAD_ZERO = 1u << 0,           /* w_s = 0 (split side, seed 6.4)          */
    SQ_PAD_STRAIGHT_START = 1u << 1  /* corner at the start of s is straight   */
};

typedef struct sq_pad_system {
    uint32_t npieces, nsides, ncon, nterms;
    uint32_t cap_pieces, cap_sides, cap_con, cap_terms;
    uint32_t *piece_first; /* npieces + 1: sides of piece p are               */
                           /* piece_first[p] .. piece_first[p+1]-1, in order  */
    int64_t *length;       /* nsides: L_s >= 0                                 */
    uint8_t *flags;        /* nsides: SQ_PAD_* bits                            */
    uint32_t *con_first;   /* ncon + 1: terms of constraint c                  */
    uint32_t *term_side;   /* nterms                                           */
    int32_t *term_coef;    /* nterms, nonzero                                  */
} sq_pad_system;

void sq_pad_system_init(sq_pad_system *S);
void sq_pad_system_free(sq_pad_system *S);

/* Appends a piece of n >= 2 sides (lengths >= 0; flags may be NULL). The
 * new sides get the next n side indices. */
sq_status sq_pad_system_add_piece(sq_pad_system *S, uint32_t n, const int64_t *length,
                                  const uint8_t *flags, sq_error *err);

/* Appends the constraint sum_t coef[t] * L'_{side[t]} = 0 (n >= 1 terms). */
sq_status sq_pad_system_add_constraint(sq_pad_system *S, uint32_t n, const uint32_t *side,
                                       const int32_t *coef, sq_error *err);

/* One piece with the pattern's k sides (straight corners become
 * SQ_PAD_STRAIGHT_START) and L'_i = L'_partner(i) for every pair. The
 * pattern must be valid (checked). S must be empty. */
sq_status sq_pad_system_from_pattern(sq_pad_system *S, const sq_pattern *pat,
                                     const int64_t *length, sq_error *err);

typedef enum sq_pad_outcome {
    SQ_PAD_SOLVED = 0,
    SQ_PAD_INFEASIBLE_INVARIANT,  /* no rational solution: the lengths violate */
                                  /* an invariant of padding                    */
    SQ_PAD_INFEASIBLE_NONNEGATIVE /* rational solutions, none with all w >= 0  */
} sq_pad_outcome;

enum {
    SQ_PAD_OPT_NO_DESCENT = 1u << 0, /* return the first feasible point        */
    SQ_PAD_OPT_NO_LP_START = 1u << 1,/* skip the second start from an exact LP */
                                     /* vertex (min sum (L_s + 1) w_s) when the */
                                     /* shift already gives a feasible point    */
    SQ_PAD_OPT_NO_INTEGRAL_SEARCH = 1u << 2 /* refine by the seed's d (lcm of  */
                                     /* the basic rational solution) instead of */
                                     /* looking for an integral point first     */
};

typedef struct sq_pad_options {
    unsigned flags;
    uint32_t max_descent_steps; /* 0: default (100000) */
} sq_pad_options;

typedef struct sq_pad_result {
    sq_pad_outcome outcome;
    uint32_t rank;          /* rank of the equations in w                      */
    uint32_t equations;     /* rows: constraints + forced zeros + straight ties */
    uint64_t rational_den;  /* lcm of denominators of the basic rational       */
                            /* solution (free unknowns 0): seed 6.3's d        */
    uint64_t d;             /* refinement used: all lengths were scaled by d   */
    int used_shift;         /* nonnegativity by the all-ones shift             */
    int used_lp;            /* the returned w descends from the LP vertex      */
    uint64_t start_quads;   /* added quads at the first feasible point         */
    uint64_t added_quads;   /* added quads of w (in refined units)             */
    uint32_t descent_steps;
    /* caller-owned output arrays of nsides entries each (may be NULL): */
    int64_t *w;             /* padding numbers, >= 0, 0 on SQ_PAD_ZERO sides   */
    int64_t *final_length;  /* L'_s = d L_s + padding from the neighbours      */
} sq_pad_result;

/* Solves the padding system (see above). On success res->outcome is
 * SQ_PAD_SOLVED and the outputs satisfy every constraint exactly. Returns
 * SQ_ERR_ARGUMENT for a malformed system or when infeasible (then
 * res->outcome says which), SQ_ERR_NOMEM, or SQ_ERR_INTERNAL if a number
 * does not fit 64 bits. opt may be NULL. */
sq_status sq_pad_solve(const sq_pad_system *S, const sq_pad_options *opt, sq_pad_result *res,
                       sq_error *err);

/* Pattern front end: one piece, pairs equal. On infeasibility the message
 * gives the closure vector V = sum_i L_i w^{t(i)} and the rank of the u_p
 * (seamless-notes 7). */
sq_status sq_pad_solve_pattern(const sq_pattern *pat, const int64_t *length,
                               const sq_pad_options *opt, sq_pad_result *res, sq_error *err);

/* Final lengths for padding w with refinement d (nsides entries). Returns
 * SQ_ERR_INTERNAL on 64-bit overflow. */
sq_status sq_pad_final_lengths(const sq_pad_system *S, uint64_t d, const int64_t *w,
                               int64_t *final_length, sq_error *err);

/* Added quads of simultaneous padding (seed 9.3): strips w_s * d L_s plus a
 * w_p * w_s square at every right-angle corner. Exact (GMP); SQ_ERR_INTERNAL
 * if the count does not fit 64 bits. */
sq_status sq_pad_added_quads(const sq_pad_system *S, uint64_t d, const int64_t *w,
                             uint64_t *quads, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
