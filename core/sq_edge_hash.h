/* seamquad: a hash map from directed edges (a, b) of 32-bit vertex ids to
 * 32-bit values (open addressing, linear probing; sized at init for n keys
 * at most, so it is at most half full). Header-only: the triangulated Q
 * (sq_qtri.c) and Omega's coarsening (sq_qtri_omega.c) both find edges by
 * their ends. An undirected edge is the key (min, max). */
#ifndef SQ_EDGE_HASH_H
#define SQ_EDGE_HASH_H

#include <stdint.h>
#include <stdlib.h>

#include "sq_soup.h" /* SQ_NONE */

typedef struct sq_edge_hash {
    size_t cap;    /* a power of two, >= 2 n                 */
    uint64_t *key; /* cap: (a << 32 | b), UINT64_MAX: empty  */
    uint32_t *val; /* cap: SQ_NONE until set                 */
} sq_edge_hash;

/* -1 when out of memory (H left empty). */
static inline int sq_edge_hash_init(sq_edge_hash *H, size_t n)
{
    H->cap = 16;
    while (H->cap < 2 * n) H->cap *= 2;
    H->key = malloc(H->cap * sizeof *H->key);
    H->val = malloc(H->cap * sizeof *H->val);
    if (!H->key || !H->val) {
        free(H->key), free(H->val);
        H->key = NULL, H->val = NULL, H->cap = 0;
        return -1;
    }
    for (size_t i = 0; i < H->cap; i++) H->key[i] = UINT64_MAX, H->val[i] = SQ_NONE;
    return 0;
}

static inline void sq_edge_hash_free(sq_edge_hash *H)
{
    free(H->key), free(H->val);
    H->key = NULL, H->val = NULL, H->cap = 0;
}

/* The slot of (a, b): the one holding it, else the empty one claimed for
 * it (its value SQ_NONE). */
static inline size_t sq_edge_hash_slot(sq_edge_hash *H, uint32_t a, uint32_t b)
{
    uint64_t k = (uint64_t)a << 32 | b;
    size_t i = (size_t)((k * 0x9e3779b97f4a7c15ull) >> 20) & (H->cap - 1);
    while (H->key[i] != UINT64_MAX && H->key[i] != k) i = (i + 1) & (H->cap - 1);
    H->key[i] = k;
    return i;
}

#endif
