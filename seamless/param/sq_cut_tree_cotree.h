/* seamquad: tree-cotree candidate loops from one base vertex (seed 9.1,
 * after Erickson-Whittlesey's greedy homotopy generators). Internal. */
#ifndef SQ_CUT_TREE_COTREE_H
#define SQ_CUT_TREE_COTREE_H

#include <stdint.h>

#include "sq_cut_internal.h"

typedef struct sq_cut_cand {
    double len;
    uint32_t off, n; /* halfedges pool->he[off .. off+n-1], closed loop */
} sq_cut_cand;

typedef struct sq_cut_pool {
    uint32_t n, cap;
    sq_cut_cand *c;
    uint32_t nhe, hecap;
    uint32_t *he;
} sq_cut_pool;

typedef struct sq_cut_edge_w {
    double w;
    uint32_t h;
} sq_cut_edge_w;

typedef struct sq_cut_tc_ws {
    double *dist;       /* nv */
    uint32_t *par;      /* nv: tree halfedge into v, SQ_NONE at the base */
    uint32_t *stamp;    /* nv: LCA marks */
    uint32_t stamp_now;
    uint32_t *fparent;  /* nf: union-find over faces */
    sq_cut_edge_w *edges; /* nh / 2 */
    sq_cut_heap heap;
} sq_cut_tc_ws;

int sq_cut_tc_ws_init(sq_cut_tc_ws *ws, const sq_mesh *m);
void sq_cut_tc_ws_free(sq_cut_tc_ws *ws);
void sq_cut_pool_free(sq_cut_pool *p);

/* Shortest-path tree from `base` over vertices with !blocked[v]; cotree:
 * maximum spanning tree (weight: length of the edge's loop) of the dual
 * graph, where faces are first merged across every uncut edge with a
 * blocked or unreached endpoint (cone stars and loop strips act as single
 * faces, i.e. holes), and never across cut[] edges. Each leftover edge
 * closes one simple loop through the tree, appended to pool. *leftover
 * receives their number; *unreached the first unblocked vertex the tree
 * misses (SQ_NONE if none). Returns SQ_ERR_NOMEM or SQ_OK. */
sq_status sq_cut_tree_cotree(const sq_mesh *m, const uint8_t *blocked, const uint8_t *cut,
                             uint32_t base, sq_cut_tc_ws *ws, sq_cut_pool *pool,
                             uint32_t *leftover, uint32_t *unreached, sq_error *err);

#endif
