/* seamquad: helpers shared by the sq_cut_* files (not a public API).
 * Binary min-heap with lazy deletion, union-find, edge lengths, the
 * rotation of outgoing halfedges around a vertex, and the two topological
 * counts used by every check: connected face regions and boundary loops of
 * the mesh cut along marked edges. */
#ifndef SQ_CUT_INTERNAL_H
#define SQ_CUT_INTERNAL_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_union_find.h"

/* Next outgoing halfedge around the origin of c, clockwise (into the face
 * on the right of c). The faces swept from c up to the next cut halfedge
 * form the wedge (corner of the cut surface) that starts at c. */
static inline uint32_t sq_cut_rot(const sq_mesh *m, uint32_t c)
{
    return m->he_next[m->he_twin[c]];
}

static inline uint32_t sq_cut_dest(const sq_mesh *m, uint32_t h)
{
    return m->he_vert[m->he_next[h]];
}

double sq_cut_he_length(const sq_mesh *m, uint32_t h);

typedef struct sq_cut_heap {
    uint32_t n, cap;
    double *key;
    uint32_t *val;
} sq_cut_heap;

int sq_cut_heap_init(sq_cut_heap *q, uint32_t cap); /* 0 on failure */
void sq_cut_heap_free(sq_cut_heap *q);
int sq_cut_heap_push(sq_cut_heap *q, double key, uint32_t val); /* 0: no memory */
/* Pops the minimum into *key, *val; returns 0 when empty. */
int sq_cut_heap_pop(sq_cut_heap *q, double *key, uint32_t *val);

/* Number of connected face regions when faces may not cross halfedges with
 * cut[h] != 0. scratch: nf + nf entries (uint32). */
uint32_t sq_cut_face_regions(const sq_mesh *m, const uint8_t *cut, uint32_t *scratch);

/* Number of boundary loops of the mesh cut along cut[] (each cut edge gives
 * two boundary halfedges; the walk keeps the cut surface on its left).
 * scratch: nh bytes. Returns UINT32_MAX if the walk is inconsistent. */
uint32_t sq_cut_boundary_loops(const sq_mesh *m, const uint8_t *cut, uint8_t *scratch);

/* Next boundary halfedge after boundary halfedge h (cut[h] set) on the cut
 * surface: sweep the wedge at the head of h to the next cut halfedge. */
static inline uint32_t sq_cut_boundary_next(const sq_mesh *m, const uint8_t *cut, uint32_t h)
{
    uint32_t c = m->he_next[h];
    while (!cut[c])
        c = sq_cut_rot(m, c);
    return c;
}

static inline uint64_t sq_cut_splitmix(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* An edge joining two cones (a, b; SQ_NONE if none), preferably in the ring
 * around `near` (SQ_NONE: anywhere); for messages (sq_cut_util.c). */
void sq_cut_find_cone_edge(const sq_mesh *m, const uint8_t *cone, uint32_t near, uint32_t *a,
                           uint32_t *b);

#endif
