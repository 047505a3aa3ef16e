/* seamquad: side-pairing patterns of a cut disk (seed 6, 7).
 *
 * Cutting a closed genus-g surface along a graph with 4g-2 branches gives a
 * disk with k = 8g-4 sides (seed 6, "Assume we cut the surface..."). A
 * pattern records which sides are two sides of the same branch:
 *
 * - Sides 0..k-1 follow the disk boundary; corner i sits between side i-1
 *   and side i, so side i runs from corner i to corner i+1 (indices mod k).
 * - partner[i] = j: side i, traversed forward, is glued to side j traversed
 *   backward (orientation-reversing gluing, the surface is orientable). So
 *   corner i ~ corner j+1 and corner i+1 ~ corner j.
 * - After all gluings the corners fall into classes: the branch points.
 *   Each corner of a metapolygon is a right angle (seed 5, Def. 5.1); a
 *   corner may instead be marked straight (a flat point on a metapolygon
 *   side, 180 degrees; seamless-notes 1, 7: degree-3 branch points). A class
 *   is a regular point iff its angles add to 360 degrees (seed 3,
 *   condition (1); seed 8, "Boundary Map"): four right corners, or two
 *   right and one straight.
 * - Euler: V - E + F with F = 1 face (the disk), E = k/2 branches, V =
 *   number of classes, so genus g = (1 + k/2 - V) / 2.
 *
 * The rank test (seamless-notes 7): with w = e^{i pi/2} and side i pointing
 * in direction w^{t(i)} (t(i) = number of right-angle corners among corners
 * 1..i; t(i) = i without straight corners), pair p = (i, j) contributes
 * u_p = w^{t(i)} + w^{t(j)}. Padding alone (one piece, no split) equalizes
 * every choice of side lengths iff the u_p span the plane (rank 2);
 * docs/padding.md gives the argument and the numerical verification.
 *
 * The library never prints or exits; fallible functions return an
 * sq_status and fill the caller's sq_error (which may be NULL). */
#ifndef SQ_PATTERN_H
#define SQ_PATTERN_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_pattern {
    uint32_t k;          /* number of sides (= number of corners)          */
    uint32_t *partner;   /* k entries: side i glues reversed to partner[i] */
    uint8_t *straight;   /* k entries: 1 if corner i is straight (180 deg), */
                         /* 0 for a right-angle corner                      */
} sq_pattern;

/* Zeroes pat (no arrays). */
void sq_pattern_init(sq_pattern *pat);

/* Frees the arrays and zeroes pat. Safe on a zeroed pat. */
void sq_pattern_free(sq_pattern *pat);

/* (Re)allocates pat for k sides: partner[i] = SQ_NONE-like UINT32_MAX,
 * straight[i] = 0. */
sq_status sq_pattern_alloc(sq_pattern *pat, uint32_t k, sq_error *err);

/* Deep copy. dst must be initialized. */
sq_status sq_pattern_copy(sq_pattern *dst, const sq_pattern *src, sq_error *err);

/* The same boundary word read the other way round (clockwise instead of
 * counterclockwise, or back): side j of out is side k-1-j of in traversed
 * backward, so out->partner[j] = k-1-in->partner[k-1-j], and corner j of
 * out is corner (k-j) mod k of in: out->straight[j] = in->straight[(k-j)
 * mod k]. Validity, genus and rank are unchanged. out must be initialized
 * and differ from in. (sq_cut_graph.h: the surface's word runs with the
 * disk on the left, the domain Q's sides with the disk on the right.) */
sq_status sq_pattern_reversed(const sq_pattern *in, sq_pattern *out, sq_error *err);

/* Corner classes after gluing (union-find over the rules corner i ~ corner
 * partner[i]+1, corner i+1 ~ corner partner[i]). class_of (k entries,
 * optional) receives class ids 0..V-1 numbered by first corner; returns V.
 * partner must be an involution (checked by sq_pattern_validate; here it
 * is only asserted). */
uint32_t sq_pattern_corner_classes(const sq_pattern *pat, uint32_t *class_of);

typedef struct sq_pattern_info {
    uint32_t classes;      /* V: branch points                          */
    uint32_t genus;        /* (1 + k/2 - V) / 2                         */
    uint32_t rank;         /* rank of the u_p: 0, 1 or 2                 */
    uint32_t translations; /* pairs with u_p = 0 (pure translations)     */
    uint32_t half_turns;   /* pairs whose sides point the same way       */
    uint32_t quarter_turns;/* pairs glued by a 90-degree rotation        */
} sq_pattern_info;

/* Checks the pattern: k >= 2 even, partner a fixed-point-free involution,
 * every corner class a regular point (angles add to 360 degrees: four
 * right corners or two right and one straight), and an integral genus.
 * Fills info (optional) also when a check fails, as far as computed.
 * SQ_ERR_ARGUMENT names the first offending side, corner or class. */
sq_status sq_pattern_validate(const sq_pattern *pat, sq_pattern_info *info, sq_error *err);

/* Direction of side i as a multiple of 90 degrees (0..3): the number of
 * right-angle corners among corners 1..i, mod 4. */
uint32_t sq_pattern_side_direction(const sq_pattern *pat, uint32_t side);

/* The rank test of seamless-notes 7: rank (0, 1, 2) of {u_p}. Exact
 * integer arithmetic (u_p has coordinates in {-2..2}). */
uint32_t sq_pattern_rank(const sq_pattern *pat);

/* Closure vector V = sum_i L_i w^{t(i)} of side lengths L (k entries):
 * the padding invariant of seamless-notes 2. Exact. */
void sq_pattern_closure(const sq_pattern *pat, const int64_t *length, int64_t *vx,
                        int64_t *vy);

/* The genus-1 pattern a b a^-1 b^-1: partner = (2, 3, 0, 1). */
sq_status sq_pattern_torus(sq_pattern *pat, sq_error *err);

/* Handle insertion: the pattern of genus g+1 obtained from pat (genus g)
 * by subdividing the branch of side `side` into three (two new branch
 * points x, y) and adding two new branches e, f between x and y, whose
 * four sides are inserted into the four new corners as described by
 * `rule` (0 .. SQ_PATTERN_HANDLE_RULES-1; see sq_pattern.c). Every rule
 * keeps all old corner classes and makes x and y classes of four right
 * corners, so validity and genus g+1 follow (docs/padding.md); the result
 * is validated anyway. out must be initialized and differ from pat.
 * Straight corners are not supported here (SQ_ERR_ARGUMENT). */
#define SQ_PATTERN_HANDLE_RULES 48u
sq_status sq_pattern_insert_handle(const sq_pattern *pat, uint32_t side, uint32_t rule,
                                   sq_pattern *out, sq_error *err);

/* Canonical pattern of genus g >= 1: g = 1 is the torus (rank 0: padding
 * alone cannot equalize it); for g >= 2 the torus with one handle inserted
 * by rule 4 at side 0, then g-2 handles by rule 0 at side 0. Valid, genus
 * g, and for every g >= 2 it passes the rank test (checked on return:
 * SQ_ERR_INTERNAL otherwise). */
sq_status sq_pattern_canonical(uint32_t genus, sq_pattern *pat, sq_error *err);

/* A random valid pattern of genus g >= 1: the torus, then g-1 handle
 * insertions at random sides with random rules, then a random cyclic
 * relabelling of the sides. *state is a splitmix64 state (advanced).
 * The rank test may fail (use sq_pattern_rank). O(g^2). */
sq_status sq_pattern_random(uint32_t genus, uint64_t *state, sq_pattern *pat, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
