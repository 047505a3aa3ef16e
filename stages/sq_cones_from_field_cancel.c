/* seamquad: cancelling nearby singularities of opposite sign (used by
 * sq_cones_from_field; see sq_cross_field.h and docs/cones_from_field.md).
 *
 * A face-based field puts a singularity at nearly every vertex whose angle
 * defect is large, and on noisy or sliver-ridden meshes such vertices come
 * in tight +/- pairs (a spike next to a dent): cones a quad mesh neither
 * needs nor wants. Rule, in passes until a pass changes nothing:
 *   for every vertex v of positive index (valence < 4), the nearest vertex
 *   w of negative index (valence > 4) by shortest-path length along edges,
 *   if that length is <= radius; the pairs are applied in order of length
 *   (ties: smaller v, then smaller w), each while v still has positive and
 *   w negative index: index_v -= 1, index_w += 1 (valence_v += 1,
 *   valence_w -= 1).
 * The sum of indices is unchanged (Gauss-Bonnet), no valence leaves the
 * range between the pair's old values (so no valence <= 1 is created), and
 * every step lowers sum |index| by 2, so the passes end. */
#include "sq_cross_field.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct heap_item {
    double d;
    uint32_t v;
} heap_item;

typedef struct cancel_work {
    double *dist;      /* nv, valid where stamp matches */
    uint32_t *stamp;   /* nv */
    uint32_t cur;
    heap_item *heap;   /* capacity nh + 1: one push per edge relaxation */
    size_t nheap;
} cancel_work;

static void heap_push(cancel_work *w, double d, uint32_t v)
{
    size_t i = w->nheap++;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (w->heap[p].d <= d) break;
        w->heap[i] = w->heap[p];
        i = p;
    }
    w->heap[i].d = d;
    w->heap[i].v = v;
}

static heap_item heap_pop(cancel_work *w)
{
    heap_item top = w->heap[0], last = w->heap[--w->nheap];
    size_t i = 0, n = w->nheap;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && w->heap[c + 1].d < w->heap[c].d) c++;
        if (last.d <= w->heap[c].d) break;
        w->heap[i] = w->heap[c];
        i = c;
    }
    if (n) w->heap[i] = last;
    return top;
}

static double edge_length(const sq_mesh *m, uint32_t a, uint32_t b)
{
    const double *p = m->pos + 3 * (size_t)a, *q = m->pos + 3 * (size_t)b;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2]));
}

/* Nearest vertex of valence > 4 within radius of v (Dijkstra), or
 * UINT32_MAX; its distance in *dist_out. Ties: smaller index. */
static uint32_t nearest_negative(const sq_mesh *m, const int32_t *valence, uint32_t v,
                                 double radius, cancel_work *w, double *dist_out)
{
    w->cur++;
    w->nheap = 0;
    w->stamp[v] = w->cur;
    w->dist[v] = 0;
    heap_push(w, 0, v);
    uint32_t best = UINT32_MAX;
    double bestd = HUGE_VAL;
    while (w->nheap) {
        heap_item it = heap_pop(w);
        if (it.d > w->dist[it.v]) continue; /* stale entry */
        if (it.d > bestd) break;
        if (valence[it.v] > 4) {
            if (it.d < bestd || (it.d == bestd && it.v < best)) {
                best = it.v;
                bestd = it.d;
            }
            continue;
        }
        uint32_t h0 = m->v_he[it.v], h = h0;
        do {
            uint32_t b = m->he_vert[m->he_next[h]];
            double nd = it.d + edge_length(m, it.v, b);
            if (nd <= radius && (w->stamp[b] != w->cur || nd < w->dist[b])) {
                w->stamp[b] = w->cur;
                w->dist[b] = nd;
                assert(w->nheap < (size_t)m->nh + 1);
                heap_push(w, nd, b);
            }
            h = m->he_twin[m->he_next[m->he_next[h]]];
        } while (h != h0);
    }
    *dist_out = bestd;
    return best;
}

typedef struct pair {
    double d;
    uint32_t v, w;
} pair;

static int pair_cmp(const void *a, const void *b)
{
    const pair *x = a, *y = b;
    if (x->d != y->d) return x->d < y->d ? -1 : 1;
    if (x->v != y->v) return x->v < y->v ? -1 : 1;
    return (x->w > y->w) - (x->w < y->w);
}

sq_status sq_cones_from_field_cancel(const sq_mesh *m, int32_t *valence, double radius,
                                     uint32_t *cancelled, sq_error *err)
{
    if (cancelled) *cancelled = 0;
    if (!(radius >= 0) || !isfinite(radius))
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cone cancellation: radius must be finite and >= 0 (got %g)", radius);
    if (radius == 0) return SQ_OK;
    cancel_work w;
    memset(&w, 0, sizeof w);
    w.dist = malloc((size_t)m->nv * sizeof *w.dist);
    w.stamp = calloc(m->nv, sizeof *w.stamp);
    w.heap = malloc(((size_t)m->nh + 1) * sizeof *w.heap);
    pair *pairs = malloc((size_t)m->nv * sizeof *pairs);
    sq_status st = SQ_OK;
    if (!w.dist || !w.stamp || !w.heap || !pairs) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cone cancellation: out of memory");
        goto done;
    }
    uint32_t total = 0;
    for (;;) {
        size_t np = 0;
        for (uint32_t v = 0; v < m->nv; v++) {
            if (valence[v] >= 4) continue;
            double d;
            uint32_t u = nearest_negative(m, valence, v, radius, &w, &d);
            if (u == UINT32_MAX) continue;
            pairs[np].d = d;
            pairs[np].v = v;
            pairs[np].w = u;
            np++;
        }
        if (np == 0) break;
        qsort(pairs, np, sizeof *pairs, pair_cmp);
        uint32_t applied = 0;
        for (size_t i = 0; i < np; i++) {
            uint32_t v = pairs[i].v, u = pairs[i].w;
            if (valence[v] >= 4 || valence[u] <= 4) continue;
            valence[v] += 1;
            valence[u] -= 1;
            applied++;
        }
        total += applied;
        if (!applied) break;
    }
    if (cancelled) *cancelled = total;
done:
    free(w.dist);
    free(w.stamp);
    free(w.heap);
    free(pairs);
    return st;
}
