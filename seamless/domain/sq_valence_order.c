/* seamquad: admissible valence orders, seed 5.2 (Prop. 5.1) and seed 9.2
 * (greedy reordering). */
#include "sq_valence_order.h"

#include <assert.h>
#include <stdlib.h>

int64_t sq_valence_excess(const uint32_t *valences, uint32_t n)
{
    int64_t e = 0;
    for (uint32_t j = 0; j < n; j++) e += (int64_t)valences[j] - 4;
    return e;
}

/* Every valence is a valid extension valence: l > 1 (Def. 5.4) and l != 4
 * (a 4-gon is not irregular). */
static sq_status check_values(const uint32_t *valences, uint32_t n, uint32_t *bad,
                              sq_error *err)
{
    for (uint32_t j = 0; j < n; j++) {
        if (valences[j] < 2) {
            if (bad) *bad = j;
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "valence %u at position %u: metapolygon construction needs "
                                "valences >= 2 (a cone of angle %u*pi/2 is not supported)",
                                valences[j], j, valences[j]);
        }
        if (valences[j] == 4) {
            if (bad) *bad = j;
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "valence 4 at position %u is regular, not a cone", j);
        }
    }
    return SQ_OK;
}

static sq_status check_total(const uint32_t *valences, uint32_t n, sq_error *err)
{
    int64_t e = sq_valence_excess(valences, n);
    if (e <= -4)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "total excess %lld of %u valences is <= -4: no single metapolygon "
                            "has them (Prop. 5.1); genus 0 (excess -8) needs four pieces "
                            "(seed 6.5)",
                            (long long)e, n);
    return SQ_OK;
}

/* Seed 5.2, Prop. 5.1: every prefix sum of e(l) > -4. */
sq_status sq_valence_check_sequence(const uint32_t *valences, uint32_t n, uint32_t *bad,
                                    sq_error *err)
{
    if (bad) *bad = n;
    sq_status st = check_values(valences, n, bad, err);
    if (st != SQ_OK) return st;
    int64_t prefix = 0;
    for (uint32_t j = 0; j < n; j++) {
        prefix += (int64_t)valences[j] - 4;
        if (prefix <= -4) {
            if (bad) *bad = j;
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "valence sequence not admissible (Prop. 5.1): the prefix sum "
                                "of excess reaches %lld at position %u (valence %u)",
                                (long long)prefix, j, valences[j]);
        }
    }
    return SQ_OK;
}

/* Seed 5.2: non-negative excess first, then negative, stable. */
sq_status sq_valence_order_admissible(const uint32_t *valences, uint32_t n, uint32_t *out,
                                      sq_error *err)
{
    sq_status st = check_values(valences, n, NULL, err);
    if (st == SQ_OK) st = check_total(valences, n, err);
    if (st != SQ_OK) return st;
    uint32_t *tmp = malloc((size_t)(n ? n : 1) * sizeof *tmp);
    if (!tmp) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory ordering %u valences", n);
    uint32_t m = 0;
    for (uint32_t j = 0; j < n; j++)
        if (valences[j] > 4) tmp[m++] = valences[j];
    for (uint32_t j = 0; j < n; j++)
        if (valences[j] < 4) tmp[m++] = valences[j];
    assert(m == n);
    for (uint32_t j = 0; j < n; j++) out[j] = tmp[j];
    free(tmp);
    assert(sq_valence_check_sequence(out, n, NULL, NULL) == SQ_OK);
    return SQ_OK;
}

/* Seed 9.2: "reordered greedily by moving valences greater than 4 towards
 * the front wherever necessary". Success: if the next preferred valence l
 * does not fit, e(l) < 0; were no valence > 4 left after it, everything
 * left would have negative excess and the total would be at most
 * prefix + e(l) <= -4. */
sq_status sq_valence_order_greedy_index(const uint32_t *preferred, uint32_t n, uint32_t *index,
                                        sq_error *err)
{
    sq_status st = check_values(preferred, n, NULL, err);
    if (st == SQ_OK) st = check_total(preferred, n, err);
    if (st != SQ_OK) return st;
    uint8_t *used = calloc(n ? n : 1, 1);
    if (!used) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory ordering %u valences", n);
    int64_t prefix = 0;
    uint32_t m = 0, pull = 0; /* pull: scan position for the next valence > 4 */
    for (uint32_t j = 0; j < n; j++) {
        if (used[j]) continue;
        int64_t e = (int64_t)preferred[j] - 4;
        while (prefix + e <= -4) {
            if (pull <= j) pull = j + 1;
            while (pull < n && (used[pull] || preferred[pull] < 4)) pull++;
            if (pull == n) { /* impossible after check_total */
                free(used);
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "greedy valence order found no valence > 4 to move forward");
            }
            used[pull] = 1;
            index[m++] = pull;
            prefix += (int64_t)preferred[pull] - 4;
        }
        used[j] = 1;
        index[m++] = j;
        prefix += e;
    }
    assert(m == n);
    free(used);
    return SQ_OK;
}

sq_status sq_valence_order_greedy(const uint32_t *preferred, uint32_t n, uint32_t *out,
                                  sq_error *err)
{
    uint32_t *index = malloc((n ? n : 1) * sizeof *index);
    if (!index) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory ordering %u valences", n);
    sq_status st = sq_valence_order_greedy_index(preferred, n, index, err);
    for (uint32_t i = 0; st == SQ_OK && i < n; i++) out[i] = preferred[index[i]];
    free(index);
    assert(st != SQ_OK || sq_valence_check_sequence(out, n, NULL, NULL) == SQ_OK);
    return st;
}
