/* seamquad: the quads around each vertex of a quad mesh (sq_smooth.h), as
 * extract's untangling and remesh's intersection repair walk them. */
#include <stdlib.h>
#include <string.h>

#include "sq_smooth.h"

sq_status sq_quad_star_build(uint32_t nv, uint32_t nq, const uint32_t *quads, sq_quad_star *S, sq_error *err)
{
    S->off = calloc((size_t)nv + 1, sizeof *S->off);
    S->quad = malloc(4 * ((size_t)nq + 1) * sizeof *S->quad);
    S->next = malloc(4 * ((size_t)nq + 1) * sizeof *S->next);
    uint32_t *fill = malloc(((size_t)nv + 1) * sizeof *fill);
    if (!S->off || !S->quad || !S->next || !fill) {
        free(fill);
        sq_quad_star_free(S);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (the quads around %u vertices)", nv);
    }
    for (size_t i = 0; i < 4 * (size_t)nq; i++) S->off[quads[i] + 1]++;
    for (uint32_t v = 0; v < nv; v++) S->off[v + 1] += S->off[v];
    memcpy(fill, S->off, (size_t)nv * sizeof *fill);
    for (uint32_t f = 0; f < nq; f++)
        for (int k = 0; k < 4; k++) {
            uint32_t v = quads[4 * (size_t)f + k], slot = fill[v]++;
            S->quad[slot] = f;
            S->next[slot] = quads[4 * (size_t)f + (k + 1) % 4];
        }
    free(fill);
    return SQ_OK;
}

void sq_quad_star_free(sq_quad_star *S)
{
    free(S->off), free(S->quad), free(S->next);
    memset(S, 0, sizeof *S);
}

double sq_quad_star_worst_margin(const sq_quad_star *S, const double *pos, const uint32_t *quads, uint32_t v)
{
    double w = 2.0;
    for (uint32_t k = S->off[v]; k < S->off[v + 1]; k++) {
        const uint32_t *q = quads + 4 * (size_t)S->quad[k];
        double x = sq_quad_fold_margin(pos + 3 * (size_t)q[0], pos + 3 * (size_t)q[1], pos + 3 * (size_t)q[2],
                                       pos + 3 * (size_t)q[3]);
        if (x < w) w = x;
    }
    return w;
}
