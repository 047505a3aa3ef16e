/* seamquad: orderings of cone valences for metapolygon construction
 * (seed 5.2, Prop. 5.1; seed 9.2).
 *
 * A valence l is the number of edges of an irregular metapolygon face, and
 * of a cone's quad-mesh vertex; its excess is e(l) = l - 4 (Def. 5.3). A
 * sequence is admissible when every l > 1, l != 4, and every prefix sum of
 * e(l) is greater than -4: then extension builds Q_(n) step by step
 * (Prop. 5.1). A multiset can be ordered admissibly iff its total excess is
 * greater than -4; genus 0 (total -8) needs several pieces (seed 6.5). */
#ifndef SQ_VALENCE_ORDER_H
#define SQ_VALENCE_ORDER_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sum of e(l) = l - 4. */
int64_t sq_valence_excess(const uint32_t *valences, uint32_t n);

/* Checks the sequence is admissible (Prop. 5.1). On failure returns
 * SQ_ERR_ARGUMENT naming the first bad position; *bad (if not NULL) gets it
 * (n when the sequence is admissible). */
sq_status sq_valence_check_sequence(const uint32_t *valences, uint32_t n, uint32_t *bad,
                                    sq_error *err);

/* Seed 5.2 (note after Prop. 5.1): an admissible order of the multiset:
 * every valence with e >= 0, then every one with e < 0, each group in
 * input order. SQ_ERR_ARGUMENT for a valence < 2 or == 4, or total excess
 * <= -4. out has n entries (may equal valences). */
sq_status sq_valence_order_admissible(const uint32_t *valences, uint32_t n, uint32_t *out,
                                      sq_error *err);

/* Seed 9.2: keeps a preferred order (e.g. singularities sorted by distance
 * from the disk centre) and only moves valences > 4 forward where the
 * prefix condition needs them: whenever the next preferred valence would
 * bring the prefix sum to -4 or below, the earliest later valence > 4 is
 * taken first, as often as needed. Succeeds for every multiset with total
 * excess > -4. Errors as for sq_valence_order_admissible. out has n
 * entries and must not alias preferred. */
sq_status sq_valence_order_greedy(const uint32_t *preferred, uint32_t n, uint32_t *out,
                                  sq_error *err);

/* The same order as positions: index[i] is the position in `preferred` of
 * the i-th valence taken (n entries), so that callers can carry what
 * stands behind each valence (a cone vertex) along. */
sq_status sq_valence_order_greedy_index(const uint32_t *preferred, uint32_t n, uint32_t *index,
                                        sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
