/* seamquad: one slide (seed 6.4, 9.3; seamless-notes 3, 7), for genus >= 2
 * patterns that fail the rank test. Internal to seamless/; not installed.
 *
 * The subdivided metapolygon Q is split along a combinatorially straight
 * sequence of interior edges (boundary to boundary, straight through every
 * valence-4 vertex, through no cone, without self-intersection) into two
 * pieces whose corner counts c1, c2 (the two ends count as corners of both)
 * are not multiples of 4. Each piece is padded (seed 6.1) with zero padding
 * on its split side; the original sides cut by the ends are two sub-sides
 * whose final lengths add up to their partner's; both split sides must end
 * equally long. The pieces are then glued back along the split sides,
 * which shifts one against the other by t edges (the slide). Every
 * (sequence, side correspondence) pair is solved exactly (sq_pad_solve) and
 * the one with the fewest quads whose closed mesh is simple wins (seed 9.3).
 * docs/domain.md, "Sliding", has the details and the numbers. */
#ifndef SQ_DOMAIN_SLIDE_H
#define SQ_DOMAIN_SLIDE_H

#include <stdint.h>

#include "sq_domain.h"
#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What the slide search found and chose (for --json). Positions refer to
 * the unpadded subdivided metapolygon (the D->quads given on entry). */
typedef struct sq_slide_info {
    uint32_t sequences;     /* straight sequences, each counted once         */
    uint32_t valid;         /* of which c1 mod 4 != 0 (seed 6.4)             */
    uint32_t feasible;      /* (valid sequence, offset) pairs with a         */
                            /* nonnegative integral padding, d = 1           */
    uint32_t start_vertex;  /* chosen sequence: its first boundary vertex in */
    uint32_t end_vertex;    /* the unpadded Q (earlier in boundary order from */
                            /* metapolygon corner 0) and its last            */
    uint32_t start_side;    /* metapolygon side holding start_vertex, and the */
    uint32_t start_pos;     /* number of quad edges from that side's first   */
    uint32_t end_side;      /* corner to it; likewise for end_vertex         */
    uint32_t end_pos;
    uint32_t length;        /* edges of the sequence                         */
    uint32_t corners[2];    /* c1 (the piece after start_vertex in boundary  */
                            /* order), c2                                    */
    int64_t shift;          /* t = w_a1 - w_a2 at the start end: layers on   */
                            /* the sub-side leaving start_vertex minus those */
                            /* on the sub-side entering it                   */
    uint32_t seam_start;    /* the seam's end vertices in the final Q (flat) */
    uint32_t seam_end;
} sq_slide_info;

/* Seed 6.4 / 9.3: builds D by one slide. Preconditions (as sq_domain_build
 * holds them after subdivision when no offset is feasible without a
 * slide): D->genus >= 2, D->k = 8g-4, D->pattern valid with k sides,
 * D->quads the unpadded subdivided metapolygon with D->nf_unpadded =
 * D->quads_unpadded = its quad count and D->f_meta_face filled;
 * corner_v[j] / len[j] are the vertex and length of metapolygon side j
 * (boundary order). fixed_offset: SQ_NONE searches every offset (at most 40,
 * spread evenly), else only that one.
 *
 * On success D->quads is the padded, slid disk; corner_vert, side_len,
 * offset, refine (= 1), quads_added and offsets_feasible (offsets with a
 * feasible slide) are set, and D->padding is reallocated to k + 2 entries:
 * padding[i] = layers on the (first) sub-side that starts at corner i of
 * Q, padding[k] = layers on the sub-side that starts at the seam's start,
 * padding[k + 1] = on the one that starts at its end. info may be NULL.
 * When no slide is feasible: SQ_ERR_ARGUMENT with a message giving the
 * counts and the pattern's rank (rank 0: one slide adds one direction and
 * generally cannot help, seamless-notes 7). On failure D is left for the
 * caller to free. */
sq_status sq_domain_slide_build(sq_domain *D, const uint32_t *corner_v, const uint32_t *len,
                                uint32_t fixed_offset, sq_slide_info *info, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
