/* seamquad: union-find over 0..n-1 in a caller-owned parent array.
 *
 * Initialise parent[i] = i. Roots are the smallest index of their set, so
 * class numbering by first member is stable. Path halving keeps finds short;
 * without union by rank the worst case is O(log n) amortized per operation,
 * ample for the small and medium sets of the combinatorics. */
#ifndef SQ_UNION_FIND_H
#define SQ_UNION_FIND_H

#include <stdint.h>

static inline uint32_t sq_uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

/* Merges the sets of a and b; returns 1 if they were different sets. */
static inline int sq_uf_union(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = sq_uf_find(parent, a);
    b = sq_uf_find(parent, b);
    if (a == b) return 0;
    if (a < b) parent[b] = a;
    else parent[a] = b;
    return 1;
}

static inline void sq_uf_init(uint32_t *parent, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) parent[i] = i;
}

#endif
