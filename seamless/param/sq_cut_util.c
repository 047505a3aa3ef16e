/* seamquad: helpers of the cut graph (see sq_cut_internal.h). */
#include "sq_cut_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

double sq_cut_he_length(const sq_mesh *m, uint32_t h)
{
    const double *a = m->pos + 3 * (size_t)m->he_vert[h];
    const double *b = m->pos + 3 * (size_t)sq_cut_dest(m, h);
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

int sq_cut_heap_init(sq_cut_heap *q, uint32_t cap)
{
    q->n = 0;
    q->cap = cap ? cap : 16;
    q->key = malloc((size_t)q->cap * sizeof *q->key);
    q->val = malloc((size_t)q->cap * sizeof *q->val);
    if (!q->key || !q->val) {
        sq_cut_heap_free(q);
        return 0;
    }
    return 1;
}

void sq_cut_heap_free(sq_cut_heap *q)
{
    free(q->key);
    free(q->val);
    memset(q, 0, sizeof *q);
}

int sq_cut_heap_push(sq_cut_heap *q, double key, uint32_t val)
{
    if (q->n == q->cap) {
        const uint32_t cap = q->cap * 2;
        double *k = realloc(q->key, (size_t)cap * sizeof *k);
        if (!k)
            return 0;
        q->key = k;
        uint32_t *v = realloc(q->val, (size_t)cap * sizeof *v);
        if (!v)
            return 0;
        q->val = v;
        q->cap = cap;
    }
    uint32_t i = q->n++;
    while (i > 0) {
        const uint32_t p = (i - 1) / 2;
        if (q->key[p] <= key)
            break;
        q->key[i] = q->key[p];
        q->val[i] = q->val[p];
        i = p;
    }
    q->key[i] = key;
    q->val[i] = val;
    return 1;
}

int sq_cut_heap_pop(sq_cut_heap *q, double *key, uint32_t *val)
{
    if (q->n == 0)
        return 0;
    *key = q->key[0];
    *val = q->val[0];
    const double k = q->key[--q->n];
    const uint32_t v = q->val[q->n];
    uint32_t i = 0;
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= q->n)
            break;
        if (c + 1 < q->n && q->key[c + 1] < q->key[c])
            ++c;
        if (k <= q->key[c])
            break;
        q->key[i] = q->key[c];
        q->val[i] = q->val[c];
        i = c;
    }
    q->key[i] = k;
    q->val[i] = v;
    return 1;
}

uint32_t sq_cut_face_regions(const sq_mesh *m, const uint8_t *cut, uint32_t *scratch)
{
    uint32_t *seen = scratch, *stack = scratch + m->nf;
    memset(seen, 0, (size_t)m->nf * sizeof *seen);
    uint32_t regions = 0;
    for (uint32_t f0 = 0; f0 < m->nf; ++f0) {
        if (seen[f0])
            continue;
        ++regions;
        uint32_t top = 0;
        stack[top++] = f0;
        seen[f0] = 1;
        while (top) {
            const uint32_t f = stack[--top];
            const uint32_t h0 = m->f_he[f];
            uint32_t h = h0;
            do {
                if (!cut[h]) {
                    const uint32_t g = m->he_face[m->he_twin[h]];
                    if (!seen[g]) {
                        seen[g] = 1;
                        stack[top++] = g;
                    }
                }
                h = m->he_next[h];
            } while (h != h0);
        }
    }
    return regions;
}

uint32_t sq_cut_boundary_loops(const sq_mesh *m, const uint8_t *cut, uint8_t *scratch)
{
    memset(scratch, 0, m->nh);
    uint32_t loops = 0;
    for (uint32_t h0 = 0; h0 < m->nh; ++h0) {
        if (!cut[h0] || scratch[h0])
            continue;
        ++loops;
        uint32_t h = h0;
        do {
            if (scratch[h])
                return UINT32_MAX; /* entered a loop in its middle */
            scratch[h] = 1;
            h = sq_cut_boundary_next(m, cut, h);
        } while (h != h0);
    }
    return loops;
}

/* An edge joining two cones, preferably in the ring around `near` (for the
 * message when cones block a loop or path). */
void sq_cut_find_cone_edge(const sq_mesh *m, const uint8_t *cone, uint32_t near, uint32_t *a, uint32_t *b)
{
    *a = *b = SQ_NONE;
    if (!cone)
        return;
    if (near != SQ_NONE) { /* a cone-cone edge in the ring around `near` */
        const uint32_t h0 = m->v_he[near];
        uint32_t h = h0;
        do {
            const uint32_t n = m->he_next[h];
            const uint32_t p = m->he_vert[n], q = sq_cut_dest(m, n);
            if (cone[p] && cone[q]) {
                *a = p;
                *b = q;
                return;
            }
            h = sq_cut_rot(m, h);
        } while (h != h0);
    }
    for (uint32_t h = 0; h < m->nh; ++h) {
        const uint32_t p = m->he_vert[h], q = sq_cut_dest(m, h);
        if (p < q && cone[p] && cone[q]) {
            *a = p;
            *b = q;
            return;
        }
    }
}
