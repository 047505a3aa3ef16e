/* seamquad: the cone tree chosen on the surface and replicated in Q
 * (seed 9.4, "Cone Cuts").
 *
 * Seed 9.4: "On the input mesh M^c we connect the singularities by
 * discrete, boundary-avoiding shortest paths in radial order, as determined
 * by the unit disk embedding, starting from the center of the disk ... On
 * the quad mesh Q these paths are replicated as discrete geodesic paths
 * using Dijkstra's algorithm". Q's tree (along quad edges, so that Omega
 * keeps integer corners) follows the surface tree's structure: every cone
 * joins the same path of the tree, near the same fraction of its length,
 * so the compatible cut on the surface (which replays Q's tree) finds its
 * targets where the surface tree had them and does not wind around the
 * surface. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cut_internal.h"
#include "sq_guide.h"
#include "sq_guide_internal.h"
#include "sq_omega.h"

/* ---- the surface tree ------------------------------------------------- */

/* The side of the path a -> x -> b on which x's neighbour y lies (x's
 * outgoing halfedges: x_he, turned clockwise by next(twin(h)) in both Q and
 * the mesh, whose faces are counterclockwise): SQ_GUIDE_RIGHT when turning
 * clockwise from x->b reaches x->y before x->a, SQ_GUIDE_LEFT when after,
 * 0 when b, a or y is not a neighbour. */
static uint8_t side_of(uint32_t x_he, const uint32_t *next, const uint32_t *twin, const uint32_t *vert,
                       uint32_t b, uint32_t a, uint32_t y)
{
    uint32_t h = x_he, guard = 0;
    while (vert[next[h]] != b) {
        h = next[twin[h]];
        if (h == x_he || ++guard > 1000000) return 0;
    }
    for (uint32_t g = next[twin[h]]; g != h; g = next[twin[g]]) {
        if (vert[next[g]] == y) return SQ_GUIDE_RIGHT;
        if (vert[next[g]] == a) return SQ_GUIDE_LEFT;
    }
    return 0;
}

static double edge_len(const sq_mesh *m, uint32_t a, uint32_t b)
{
    const double *p = m->pos + 3 * a, *q = m->pos + 3 * b;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

uint32_t sq_guide_surface_path(const sq_mesh *m, const uint8_t *blocked, const uint32_t *owner,
                               sq_guide_end_fn end_ok, void *user, uint32_t s, double *dist,
                               uint32_t *par, uint32_t *touched, uint32_t *nt, sq_cut_heap *heap,
                               int *nomem)
{
    dist[s] = 0, par[s] = SQ_NONE, touched[(*nt)++] = s;
    heap->n = 0;
    if (!sq_cut_heap_push(heap, 0, s)) {
        *nomem = 1;
        return SQ_NONE;
    }
    double d;
    uint32_t v;
    while (sq_cut_heap_pop(heap, &d, &v)) {
        if (d > dist[v]) continue;
        if (v != s && owner[v] != SQ_NONE) return v;
        if (v != s && blocked[v]) continue;
        uint32_t h0 = m->v_he[v], h = h0;
        do {
            uint32_t w = m->he_vert[m->he_next[h]];
            int end = owner[w] != SQ_NONE && (!end_ok || end_ok(user, w, v));
            if (end || (owner[w] == SQ_NONE && !blocked[w])) {
                double nd = d + edge_len(m, v, w);
                if (nd < dist[w]) {
                    if (dist[w] == INFINITY) touched[(*nt)++] = w;
                    dist[w] = nd, par[w] = v;
                    if (!sq_cut_heap_push(heap, nd, w)) {
                        *nomem = 1;
                        return SQ_NONE;
                    }
                }
            }
            h = m->he_next[m->he_twin[h]];
        } while (h != h0);
    }
    return SQ_NONE;
}

sq_status sq_guide_surface_tree(const sq_mesh *m, const sq_cut_graph *G, uint32_t n, const uint32_t *cone,
                                uint32_t *att_step, double *att_frac, uint8_t *att_side, uint32_t *att_vertex,
                                uint32_t *tree_next, sq_error *err)
{
    if (n == 0) return SQ_OK;
    size_t nv1 = (size_t)m->nv + 1;
    uint8_t *blocked = calloc(nv1, 1);     /* on the cut or a cone           */
    uint32_t *owner = malloc(nv1 * sizeof *owner); /* tree vertex: its step */
    double *arc = malloc(nv1 * sizeof *arc);       /* ... and arc length    */
    double *dist = malloc(nv1 * sizeof *dist);
    uint32_t *par = malloc(nv1 * sizeof *par), *touched = malloc(nv1 * sizeof *touched);
    double *plen = calloc((size_t)n, sizeof *plen); /* length of path j */
    uint32_t *ta = malloc(nv1 * sizeof *ta), *tb = malloc(nv1 * sizeof *tb); /* path neighbours */
    sq_cut_heap heap;
    memset(&heap, 0, sizeof heap);
    sq_status st = SQ_OK;
    if (!blocked || !owner || !arc || !dist || !par || !touched || !plen || !ta || !tb || !sq_cut_heap_init(&heap, 64)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < m->nh; h++)
        if (G->he_cut[h]) blocked[m->he_vert[h]] = 1;
    for (uint32_t j = 0; j < n; j++) blocked[cone[j]] = 1;
    for (uint32_t v = 0; v < m->nv; v++) owner[v] = SQ_NONE, dist[v] = INFINITY;
    if (tree_next)
        for (uint32_t v = 0; v < m->nv; v++) tree_next[v] = SQ_NONE;
    owner[cone[0]] = 0, arc[cone[0]] = 0;
    att_step[0] = SQ_NONE, att_frac[0] = 0, att_side[0] = 0;
    if (att_vertex) att_vertex[0] = SQ_NONE;
    for (uint32_t j = 1; j < n && st == SQ_OK; j++) {
        /* Dijkstra from cone j through free vertices to the first tree
         * vertex; tree vertices are ends, never passed through */
        uint32_t nt = 0, s = cone[j];
        if (owner[s] != SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "surface tree: cone %u already on the tree", s);
            break;
        }
        int nomem = 0;
        uint32_t hit = sq_guide_surface_path(m, blocked, owner, NULL, NULL, s, dist, par, touched, &nt, &heap, &nomem);
        if (nomem) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        if (st == SQ_OK && hit == SQ_NONE) {
            /* walled in by the cut and other cones (the surface stage
             * splits edges there): no preference for this cone */
            att_step[j] = SQ_NONE, att_frac[j] = 0, att_side[j] = 0;
            if (att_vertex) att_vertex[j] = SQ_NONE;
        } else if (st == SQ_OK) {
            /* the path cone j .. hit; its vertices up to, not including,
             * hit are owned by step j, at their arc length from cone j */
            for (uint32_t x = par[hit], prev = hit; x != SQ_NONE; prev = x, x = par[x])
                owner[x] = j, arc[x] = dist[x], ta[x] = par[x], tb[x] = prev;
            if (tree_next)
                for (uint32_t x = par[hit], prev = hit; x != SQ_NONE; prev = x, x = par[x]) tree_next[x] = prev;
            plen[j] = dist[hit];
            uint32_t p = owner[hit];
            att_step[j] = p;
            if (att_vertex) att_vertex[j] = hit;
            att_frac[j] = plen[p] > 0 ? arc[hit] / plen[p] : 0;
            /* which side of path p the path arrives from (not at a cone) */
            att_side[j] = arc[hit] > 0 ? side_of(m->v_he[hit], m->he_next, m->he_twin, m->he_vert, tb[hit],
                                                 ta[hit], par[hit])
                                       : 0;
        }
        for (uint32_t i = 0; i < nt; i++) dist[touched[i]] = INFINITY;
    }
done:
    free(blocked);
    free(owner);
    free(arc);
    free(dist);
    free(par);
    free(touched);
    free(plen);
    free(ta);
    free(tb);
    sq_cut_heap_free(&heap);
    return st;
}

/* ---- the same tree in Q ------------------------------------------------ */

sq_status sq_cone_tree_guided(const sq_metapolygon *Q, uint32_t n, const uint32_t *qv, const uint32_t *att_step,
                              const double *att_frac, const uint8_t *att_side, uint32_t root_step,
                              const double *root_cost, uint32_t *att_qvertex, uint32_t *att_qstep, double *att_qfrac, sq_cone_tree *T,
                              sq_error *err)
{
    if (n == 0 || root_step >= n) return sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: no cones or no root step");
    size_t nv1 = (size_t)Q->nv + 1;
    uint8_t *bnd = calloc(nv1, 1);
    uint32_t *owner = malloc(nv1 * sizeof *owner); /* tree vertex: its step  */
    uint32_t *pos = malloc(nv1 * sizeof *pos);     /* ... index on its path */
    uint32_t *ta = malloc(nv1 * sizeof *ta), *tb = malloc(nv1 * sizeof *tb); /* path neighbours */
    uint32_t *plen = calloc((size_t)n, sizeof *plen); /* edges of path j    */
    uint32_t *dist = malloc(nv1 * sizeof *dist), *par = malloc(nv1 * sizeof *par);
    uint32_t *queue = malloc(nv1 * sizeof *queue), *edges = malloc(nv1 * sizeof *edges);
    sq_status st = SQ_OK;
    uint32_t ne = 0, root = SQ_NONE;
    if (!bnd || !owner || !pos || !ta || !tb || !plen || !dist || !par || !queue || !edges) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) bnd[Q->he_vert[h]] = 1;
    for (uint32_t v = 0; v < Q->nv; v++) owner[v] = SQ_NONE, dist[v] = UINT32_MAX;
    for (uint32_t j = 0; j < n; j++)
        if (qv[j] >= Q->nv || bnd[qv[j]] || Q->v_nface[qv[j]] == 4) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: step %u has no interior cone of Q", j);
            goto done;
        }
    owner[qv[0]] = 0, pos[qv[0]] = 0, ta[qv[0]] = tb[qv[0]] = SQ_NONE;
    if (att_qvertex) att_qvertex[0] = SQ_NONE;
    if (att_qstep) att_qstep[0] = SQ_NONE;
    if (att_qfrac) att_qfrac[0] = 0;
    /* steps 1 .. n-1, then the root path from the cone of root_step */
    for (uint32_t j = 1; j <= n && st == SQ_OK; j++) {
        const int to_root = j == n;
        uint32_t s = to_root ? qv[root_step] : qv[j];
        /* a path of the tree (on the surface tree's side of it) when the
         * surface joined one, else anywhere */
        uint32_t want = to_root ? SQ_NONE : att_step[j];
        uint8_t side = to_root || !att_side ? 0 : att_side[j];
        uint32_t best = SQ_NONE, best_from = SQ_NONE, qt = 0;
        if (!to_root && owner[s] != SQ_NONE) {
            /* an earlier path ran through this cone: it is joined there */
            if (att_qvertex) att_qvertex[j] = s;
            if (att_qstep) att_qstep[j] = owner[s];
            if (att_qfrac) att_qfrac[j] = plen[owner[s]] ? (double)pos[s] / plen[owner[s]] : 0;
            continue;
        }
        for (int pass = 0; pass < 4 && best == SQ_NONE; pass++) {
            if (pass == 1) side = 0;          /* then either side      */
            if (pass == 2) want = SQ_NONE;    /* then any tree vertex  */
            if (pass > 0 && to_root) break;
            /* pass 3: also through cones not yet on the tree (as
             * sq_cone_tree_shortest does); they join the tree there */
            const int through_cones = pass == 3;
            double best_cost = INFINITY;
            for (uint32_t i = 0; i < qt; i++) dist[queue[i]] = UINT32_MAX;
            uint32_t qh = 0;
            qt = 0;
            /* breadth-first from s through free interior vertices (neither
             * cones nor on the tree) over interior edges; every edge into
             * an end is a candidate, ends are not passed through */
            dist[s] = 0, par[s] = SQ_NONE, queue[qt++] = s;
            while (qh < qt) {
                uint32_t v = queue[qh++];
                if ((double)dist[v] + 1 > best_cost) break;
                uint32_t h0 = Q->v_he[v], h = h0;
                do {
                    uint32_t w = Q->he_vert[Q->he_next[h]];
                    int interior = Q->he_face[h] != SQ_NONE && Q->he_face[Q->he_twin[h]] != SQ_NONE;
                    h = Q->he_next[Q->he_twin[h]];
                    if (!interior || w == s) continue;
                    if (to_root ? bnd[w] : owner[w] != SQ_NONE) {
                        double cost = INFINITY;
                        if (to_root && Q->v_nface[w] == 2) cost = (double)dist[v] + 1 + (root_cost ? root_cost[w] : 0);
                        if (!to_root && want == SQ_NONE) cost = (double)dist[v] + 1;
                        if (!to_root && want != SQ_NONE && owner[w] == want) {
                            cost = (double)dist[v] + 1 + fabs((double)pos[w] - att_frac[j] * (double)plen[want]);
                            if (side && pos[w] > 0 &&
                                side_of(Q->v_he[w], Q->he_next, Q->he_twin, Q->he_vert, tb[w], ta[w], v) != side)
                                cost = INFINITY;
                        }
                        if (cost < best_cost) best_cost = cost, best = w, best_from = v;
                        continue;
                    }
                    if (dist[w] != UINT32_MAX || bnd[w] || (Q->v_nface[w] != 4 && !through_cones) ||
                        owner[w] != SQ_NONE)
                        continue;
                    dist[w] = dist[v] + 1, par[w] = v, queue[qt++] = w;
                } while (h != h0);
            }
        }
        if (best == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_SOLVER, to_root ? "cone tree: the cone of step %u cannot reach Q's boundary"
                                                          : "cone tree: the cone of step %u cannot reach the tree",
                              to_root ? root_step : j);
        } else {
            /* record the path's edges and its vertices' places */
            uint32_t len = dist[best_from] + 1, prev = best;
            for (uint32_t y = best_from; y != SQ_NONE; prev = y, y = par[y]) {
                uint32_t h0 = Q->v_he[y], h = h0;
                while (Q->he_vert[Q->he_next[h]] != prev) {
                    h = Q->he_next[Q->he_twin[h]];
                    if (h == h0) break;
                }
                edges[ne++] = h;
                if (!to_root) owner[y] = j, pos[y] = dist[y], ta[y] = par[y], tb[y] = prev;
            }
            if (!to_root) plen[j] = len;
            else root = best;
            if (!to_root && att_qvertex) att_qvertex[j] = best;
            if (!to_root && att_qstep) att_qstep[j] = owner[best];
            if (!to_root && att_qfrac) att_qfrac[j] = plen[owner[best]] ? (double)pos[best] / plen[owner[best]] : 0;
        }
        for (uint32_t i = 0; i < qt; i++) dist[queue[i]] = UINT32_MAX;
    }
    if (st == SQ_OK) st = sq_cone_tree_from_edges(Q, root, edges, ne, T, err);
done:
    free(bnd);
    free(owner);
    free(pos);
    free(ta);
    free(tb);
    free(plen);
    free(dist);
    free(par);
    free(queue);
    free(edges);
    return st;
}

/* ---- the root path on the surface ---------------------------------------- */

/* 1 when y lies in the sector of the cut disk at the origin of the side
 * halfedge h (from h counterclockwise to the incoming side halfedge, whose
 * origin is a). */
static int in_left_sector(const sq_mesh *m, uint32_t h, uint32_t a, uint32_t y)
{
    uint32_t g = h;
    for (uint32_t guard = 0; guard < m->nh; guard++) {
        uint32_t pg = g;
        while (m->he_next[pg] != g) pg = m->he_next[pg];
        g = m->he_twin[pg]; /* counterclockwise: twin(prev(g)) */
        uint32_t w = m->he_vert[m->he_next[g]];
        if (w == y) return 1;
        if (w == a || g == h) return 0;
    }
    return 0;
}

sq_status sq_guide_surface_root(const sq_mesh *m, const sq_cut_graph *G, uint32_t n, const uint32_t *cone,
                                const uint32_t *tree_next, uint32_t *path_next, sq_guide_root *root,
                                sq_error *err)
{
    root->vertex = root->index = SQ_NONE;
    uint32_t want_side = root->side;
    root->side = SQ_NONE;
    if (root->step >= n) return sq_error_set(err, SQ_ERR_ARGUMENT, "surface root: no step %u", root->step);
    size_t nv1 = (size_t)m->nv + 1;
    uint8_t *blocked = calloc(nv1, 1);  /* cut, cones, tree: not passed */
    uint32_t *side_e = malloc(nv1 * sizeof *side_e); /* an end: side halfedge slot */
    double *dist = malloc(nv1 * sizeof *dist);
    uint32_t *par = malloc(nv1 * sizeof *par), *from = malloc(nv1 * sizeof *from);
    sq_cut_heap heap;
    memset(&heap, 0, sizeof heap);
    sq_status st = SQ_OK;
    if (!blocked || !side_e || !dist || !par || !from || !sq_cut_heap_init(&heap, 64)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < m->nv; v++) {
        blocked[v] = tree_next[v] != SQ_NONE;
        side_e[v] = SQ_NONE, dist[v] = INFINITY;
    }
    for (uint32_t j = 0; j < n; j++) blocked[cone[j]] = 1;
    for (uint32_t h = 0; h < m->nh; h++)
        if (G->he_cut[h]) blocked[m->he_vert[h]] = 1;
    /* ends: the inner vertices of the wanted side (any side: SQ_NONE);
     * a vertex inside two sides keeps the first, checked again below */
    for (uint32_t sd = 0; sd < G->pattern.k; sd++) {
        if (want_side != SQ_NONE && sd != want_side) continue;
        for (uint32_t e = G->side_off[sd] + 1; e < G->side_off[sd + 1]; e++) {
            uint32_t v = m->he_vert[G->side_he[e]];
            if (side_e[v] == SQ_NONE) side_e[v] = e;
        }
    }
    /* seed 9.4: Dijkstra from the cone through free vertices to the first
     * side vertex entered from the cut disk's side of that side */
    uint32_t s = cone[root->step], hit = SQ_NONE;
    dist[s] = 0, par[s] = SQ_NONE;
    if (!sq_cut_heap_push(&heap, 0, s)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    double d;
    uint32_t v;
    while (st == SQ_OK && hit == SQ_NONE && sq_cut_heap_pop(&heap, &d, &v)) {
        if (d > dist[v]) continue;
        if (v != s && blocked[v]) {
            if (side_e[v] != SQ_NONE && par[v] != SQ_NONE) hit = v; /* the nearest end */
            continue;
        }
        uint32_t h0 = m->v_he[v], h = h0;
        do {
            uint32_t w = m->he_vert[m->he_next[h]];
            double nd = d + edge_len(m, v, w);
            if (side_e[w] != SQ_NONE && nd < dist[w]) {
                /* an end if v lies in the sector of some wanted side at w */
                for (uint32_t sd = 0; sd < G->pattern.k; sd++) {
                    if (want_side != SQ_NONE && sd != want_side) continue;
                    for (uint32_t e = G->side_off[sd] + 1; e < G->side_off[sd + 1]; e++)
                        if (m->he_vert[G->side_he[e]] == w &&
                            in_left_sector(m, G->side_he[e], m->he_vert[G->side_he[e - 1]], v)) {
                            dist[w] = nd, par[w] = v, from[w] = sd, side_e[w] = e;
                            if (!sq_cut_heap_push(&heap, nd, w)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                        }
                }
            } else if (!blocked[w] && nd < dist[w]) {
                dist[w] = nd, par[w] = v;
                if (!sq_cut_heap_push(&heap, nd, w)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            }
            h = m->he_next[m->he_twin[h]];
        } while (h != h0 && st == SQ_OK);
    }
    if (st == SQ_OK && hit != SQ_NONE) {
        root->vertex = hit, root->side = from[hit];
        root->index = side_e[hit] - G->side_off[from[hit]];
        if (path_next)
            for (uint32_t x = hit; par[x] != SQ_NONE; x = par[x]) path_next[x] = par[x];
    }
done:
    free(blocked);
    free(side_e);
    free(dist);
    free(par);
    free(from);
    sq_cut_heap_free(&heap);
    return st;
}
