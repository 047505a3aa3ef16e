/* seamquad: matching the domain's cones to the surface's cones by position
 * in the two disk layouts (seed 9.2). Per valence: greedy by increasing
 * distance, then pairwise exchanges while the total squared distance
 * drops (each exchange strictly lowers it, so the loop ends). */
#include <stdlib.h>

#include "sq_guide.h"

typedef struct pair {
    double d;
    uint32_t a, b;
} pair;

static int cmp_pair(const void *x, const void *y)
{
    const pair *p = x, *q = y;
    if (p->d != q->d) return p->d < q->d ? -1 : 1;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

static double d2(const double *p, const double *q)
{
    double x = p[0] - q[0], y = p[1] - q[1];
    return x * x + y * y;
}

sq_status sq_guide_match(uint32_t n, const double *a_xy, const int32_t *a_val, const double *b_xy,
                         const int32_t *b_val, uint32_t *a_to_b, sq_error *err)
{
    size_t np = 0;
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < n; j++) np += a_val[i] == b_val[j];
    pair *p = malloc((np + 1) * sizeof *p);
    uint8_t *used = calloc((size_t)n + 1, 1);
    if (!p || !used) {
        free(p);
        free(used);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    np = 0;
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < n; j++)
            if (a_val[i] == b_val[j]) p[np++] = (pair){d2(a_xy + 2 * i, b_xy + 2 * j), i, j};
    qsort(p, np, sizeof *p, cmp_pair);
    for (uint32_t i = 0; i < n; i++) a_to_b[i] = SQ_NONE;
    for (size_t e = 0; e < np; e++)
        if (a_to_b[p[e].a] == SQ_NONE && !used[p[e].b]) a_to_b[p[e].a] = p[e].b, used[p[e].b] = 1;
    free(p);
    free(used);
    for (uint32_t i = 0; i < n; i++)
        if (a_to_b[i] == SQ_NONE)
            return sq_error_set(err, SQ_ERR_ARGUMENT, "guidance: no cone of valence %d left for cone %u",
                                a_val[i], i);
    for (int improved = 1, rounds = 0; improved && rounds < 100; rounds++) {
        improved = 0;
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t j = i + 1; j < n; j++) {
                if (a_val[i] != a_val[j]) continue;
                const double *bi = b_xy + 2 * a_to_b[i], *bj = b_xy + 2 * a_to_b[j];
                double now = d2(a_xy + 2 * i, bi) + d2(a_xy + 2 * j, bj);
                double swp = d2(a_xy + 2 * i, bj) + d2(a_xy + 2 * j, bi);
                if (swp < now) {
                    uint32_t t = a_to_b[i];
                    a_to_b[i] = a_to_b[j], a_to_b[j] = t;
                    improved = 1;
                }
            }
    }
    return SQ_OK;
}
