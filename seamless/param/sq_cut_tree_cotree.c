/* seamquad: tree-cotree candidate loops (seed 9.1). See sq_cut_tree_cotree.h.
 *
 * The seed replaces the short-handle-loop method of [DFW13] by the
 * tree-cotree algorithm of [EW05], modified to avoid singular vertices:
 * here a cone (or a vertex of an already chosen loop) is removed from the
 * primal graph and its star is merged into one dual node, so the loops
 * live on the surface with those stars as holes. */
#include "sq_cut_tree_cotree.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sq_cut_tc_ws_init(sq_cut_tc_ws *ws, const sq_mesh *m)
{
    memset(ws, 0, sizeof *ws);
    ws->dist = malloc((size_t)m->nv * sizeof *ws->dist);
    ws->par = malloc((size_t)m->nv * sizeof *ws->par);
    ws->stamp = calloc(m->nv, sizeof *ws->stamp);
    ws->fparent = malloc((size_t)m->nf * sizeof *ws->fparent);
    ws->edges = malloc((size_t)(m->nh / 2 + 1) * sizeof *ws->edges);
    if (!ws->dist || !ws->par || !ws->stamp || !ws->fparent || !ws->edges ||
        !sq_cut_heap_init(&ws->heap, m->nv + 16)) {
        sq_cut_tc_ws_free(ws);
        return 0;
    }
    return 1;
}

void sq_cut_tc_ws_free(sq_cut_tc_ws *ws)
{
    free(ws->dist);
    free(ws->par);
    free(ws->stamp);
    free(ws->fparent);
    free(ws->edges);
    sq_cut_heap_free(&ws->heap);
    memset(ws, 0, sizeof *ws);
}

void sq_cut_pool_free(sq_cut_pool *p)
{
    free(p->c);
    free(p->he);
    memset(p, 0, sizeof *p);
}

static int pool_reserve(sq_cut_pool *p, uint32_t more_he)
{
    if (p->n == p->cap) {
        const uint32_t cap = p->cap ? 2 * p->cap : 64;
        sq_cut_cand *c = realloc(p->c, (size_t)cap * sizeof *c);
        if (!c)
            return 0;
        p->c = c;
        p->cap = cap;
    }
    if (p->nhe + more_he > p->hecap) {
        uint32_t cap = p->hecap ? 2 * p->hecap : 4096;
        while (cap < p->nhe + more_he)
            cap *= 2;
        uint32_t *he = realloc(p->he, (size_t)cap * sizeof *he);
        if (!he)
            return 0;
        p->he = he;
        p->hecap = cap;
    }
    return 1;
}

static int by_weight_desc(const void *a, const void *b)
{
    const sq_cut_edge_w *x = a, *y = b;
    if (x->w != y->w)
        return x->w < y->w ? 1 : -1;
    return x->h < y->h ? -1 : (x->h > y->h);
}

/* Appends the loop closed by non-tree edge h (u -> v): lca => u, h,
 * v => lca. */
static sq_status add_loop(const sq_mesh *m, sq_cut_tc_ws *ws, sq_cut_pool *pool, uint32_t h,
                          double len, sq_error *err)
{
    const uint32_t u = m->he_vert[h], v = sq_cut_dest(m, h);
    const uint32_t st = ++ws->stamp_now;
    uint32_t nu = 0, nvv = 0;
    for (uint32_t x = u;; x = m->he_vert[ws->par[x]]) {
        ws->stamp[x] = st;
        if (ws->par[x] == SQ_NONE)
            break;
    }
    uint32_t lca = v;
    while (ws->stamp[lca] != st) {
        assert(ws->par[lca] != SQ_NONE);
        lca = m->he_vert[ws->par[lca]];
        ++nvv;
    }
    for (uint32_t x = u; x != lca; x = m->he_vert[ws->par[x]])
        ++nu;
    if (!pool_reserve(pool, nu + nvv + 1))
        return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory for candidate loops");
    sq_cut_cand *c = &pool->c[pool->n++];
    c->off = pool->nhe;
    c->n = nu + nvv + 1;
    c->len = ws->dist[u] + ws->dist[v] + len - 2.0 * ws->dist[lca];
    uint32_t *out = pool->he + c->off;
    /* lca => u: the tree halfedges from u upwards, reversed in place */
    uint32_t i = nu;
    for (uint32_t x = u; x != lca; x = m->he_vert[ws->par[x]])
        out[--i] = ws->par[x];
    out[nu] = h;
    i = nu + 1;
    for (uint32_t x = v; x != lca; x = m->he_vert[ws->par[x]])
        out[i++] = m->he_twin[ws->par[x]];
    pool->nhe += c->n;
#ifndef NDEBUG
    for (uint32_t k = 0; k < c->n; ++k)
        assert(sq_cut_dest(m, out[k]) == m->he_vert[out[(k + 1) % c->n]]);
#endif
    return SQ_OK;
}

sq_status sq_cut_tree_cotree(const sq_mesh *m, const uint8_t *blocked, const uint8_t *cut,
                             uint32_t base, sq_cut_tc_ws *ws, sq_cut_pool *pool,
                             uint32_t *leftover, uint32_t *unreached, sq_error *err)
{
    assert(!blocked[base]);
    /* 1. Shortest-path tree (Dijkstra) over unblocked vertices. */
    for (uint32_t v = 0; v < m->nv; ++v) {
        ws->dist[v] = INFINITY;
        ws->par[v] = SQ_NONE;
    }
    ws->dist[base] = 0.0;
    ws->heap.n = 0;
    if (!sq_cut_heap_push(&ws->heap, 0.0, base))
        return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (Dijkstra)");
    double d;
    uint32_t x;
    while (sq_cut_heap_pop(&ws->heap, &d, &x)) {
        if (d > ws->dist[x])
            continue;
        const uint32_t h0 = m->v_he[x];
        uint32_t h = h0;
        do {
            const uint32_t y = sq_cut_dest(m, h);
            if (!blocked[y]) {
                const double nd = d + sq_cut_he_length(m, h);
                if (nd < ws->dist[y]) {
                    ws->dist[y] = nd;
                    ws->par[y] = h;
                    if (!sq_cut_heap_push(&ws->heap, nd, y))
                        return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (Dijkstra)");
                }
            }
            h = sq_cut_rot(m, h);
        } while (h != h0);
    }
    *unreached = SQ_NONE;
    for (uint32_t v = 0; v < m->nv; ++v)
        if (!blocked[v] && ws->dist[v] == INFINITY) {
            *unreached = v;
            break;
        }

    /* 2. Dual: merge faces across uncut edges at holes, then collect the
     * remaining non-tree edges with their loop lengths. */
    for (uint32_t f = 0; f < m->nf; ++f)
        ws->fparent[f] = f;
    uint32_t ne = 0;
    for (uint32_t h = 0; h < m->nh; ++h) {
        const uint32_t t = m->he_twin[h];
        if (t < h || (cut && cut[h]))
            continue;
        const uint32_t u = m->he_vert[h], v = m->he_vert[t];
        if (ws->dist[u] == INFINITY || ws->dist[v] == INFINITY) {
            sq_uf_union(ws->fparent, m->he_face[h], m->he_face[t]);
            continue;
        }
        if (ws->par[v] == h || ws->par[u] == t)
            continue; /* tree edge */
        ws->edges[ne].w = ws->dist[u] + ws->dist[v] + sq_cut_he_length(m, h);
        ws->edges[ne].h = h;
        ++ne;
    }
    /* 3. Cotree: maximum spanning tree by Kruskal; leftovers close loops. */
    qsort(ws->edges, ne, sizeof *ws->edges, by_weight_desc);
    uint32_t left = 0;
    for (uint32_t i = 0; i < ne; ++i) {
        const uint32_t h = ws->edges[i].h;
        if (sq_uf_union(ws->fparent, m->he_face[h], m->he_face[m->he_twin[h]]))
            continue;
        ++left;
        const uint32_t u = m->he_vert[h], v = sq_cut_dest(m, h);
        const double len = ws->edges[i].w - ws->dist[u] - ws->dist[v];
        sq_status st = add_loop(m, ws, pool, h, len, err);
        if (st != SQ_OK)
            return st;
    }
    *leftover = left;
    return SQ_OK;
}
