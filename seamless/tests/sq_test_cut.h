/* seamquad tests: an independent check of a surface cut (shared by
 * test_cut_graph.c and test_cut_low_genus.c): the mesh cut open along the
 * marked edges, rebuilt as a soup, its Euler characteristic and boundary
 * loops. Include after <cmocka.h> (it asserts). */
#ifndef SQ_TEST_CUT_H
#define SQ_TEST_CUT_H

#include <stdint.h>
#include <stdlib.h>

#include "sq_mesh.h"

typedef struct pair {
    uint32_t a, b;
} pair;

static int pair_cmp(const void *x, const void *y)
{
    const pair *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : (p->b > q->b);
}

/* Cuts the mesh along he_cut by giving every wedge at a vertex its own
 * copy (wedges found by rotating around each vertex through the faces),
 * then counts the cut soup's vertices, edges, boundary edges and boundary
 * loops. Returns the Euler characteristic; *loops the boundary loops. */
static int64_t cut_soup_euler(const sq_mesh *m, const uint8_t *cut, uint32_t *loops)
{
    uint32_t *copy = malloc(m->nh * sizeof *copy); /* new vertex of the corner at origin(h) */
    uint32_t nv2 = 0;
    for (uint32_t h = 0; h < m->nh; ++h)
        copy[h] = UINT32_MAX;
    for (uint32_t v = 0; v < m->nv; ++v) {
        /* Rotating h -> next(twin(h)) crosses the edge of h into the next
         * face; start just after crossing a cut edge, if there is one, and
         * open a new copy at every cut edge crossed. */
        uint32_t s = m->v_he[v], h = s;
        do {
            if (cut[h]) {
                s = m->he_next[m->he_twin[h]];
                break;
            }
            h = m->he_next[m->he_twin[h]];
        } while (h != m->v_he[v]);
        h = s;
        uint32_t id = nv2++;
        do {
            copy[h] = id;
            const uint32_t crossed = h;
            h = m->he_next[m->he_twin[h]];
            if (h != s && cut[crossed])
                id = nv2++;
        } while (h != s);
    }
    /* faces of the cut soup: corner h of face f -> copy[h] */
    pair *e = malloc(m->nh * sizeof *e);
    for (uint32_t h = 0; h < m->nh; ++h) {
        const uint32_t a = copy[h], b = copy[m->he_next[h]];
        e[h].a = a < b ? a : b;
        e[h].b = a < b ? b : a;
    }
    qsort(e, m->nh, sizeof *e, pair_cmp);
    uint32_t ne = 0, nbd = 0;
    for (uint32_t i = 0; i < m->nh;) {
        uint32_t j = i;
        while (j < m->nh && e[j].a == e[i].a && e[j].b == e[i].b)
            ++j;
        ++ne;
        nbd += (j - i == 1);
        i = j;
    }
    /* boundary loops: directed boundary edges copy[h] -> copy[next h] for
     * halfedges of cut edges; follow successor by vertex */
    uint32_t *succ = malloc(nv2 * sizeof *succ);
    for (uint32_t i = 0; i < nv2; ++i)
        succ[i] = UINT32_MAX;
    uint32_t nb = 0;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (cut[h]) {
            assert_int_equal(succ[copy[h]], UINT32_MAX); /* disk: one out-edge each */
            succ[copy[h]] = copy[m->he_next[h]];
            ++nb;
        }
    assert_int_equal(nb, nbd);
    uint8_t *seen = calloc(nv2, 1);
    *loops = 0;
    for (uint32_t i = 0; i < nv2; ++i) {
        if (succ[i] == UINT32_MAX || seen[i])
            continue;
        ++*loops;
        for (uint32_t x = i; !seen[x]; x = succ[x]) {
            seen[x] = 1;
            assert_int_not_equal(succ[x], UINT32_MAX);
        }
    }
    free(seen);
    free(succ);
    free(e);
    free(copy);
    return (int64_t)nv2 - ne + m->nf;
}

#endif
