/* seamquad: the surface cone tree copied exactly into Q (seed 9.4, "Cone
 * Cuts"; seed 7, compatible cuts).
 *
 * Seed 9.4 replicates the surface paths in Q "as discrete geodesic paths".
 * For the two cut disks to be compatible it is not enough that each path
 * ends near the same place: the trees must be the same plane tree, with the
 * same cyclic order of edges at every node and the root on the same side.
 * Then the surface needs no routing at all: every segment of Q's tree is
 * the surface tree's own path between the two corresponding nodes, and no
 * Steiner vertex is added for the tree.
 *
 * The tree is grown in Q in the surface's step order. Each path ends where
 * its surface path ended: at the copy of a node (a cone or an earlier
 * attachment vertex), or at a new node inside the copy of the segment the
 * surface path ended in; and it arrives in the same sector: turning
 * counterclockwise from the path's last edge, the first tree edge met is
 * the copy of the one met on the surface. Inserting every edge at the same
 * place of the same cyclic orders gives the same plane tree by induction.
 * The root path leaves its cone in the surface root path's sector and ends
 * on the side of Q that stands for the surface root's side. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_guide.h"
#include "sq_guide_internal.h"
#include "sq_omega.h"

/* The neighbour among cand[0..ncand) met first when turning
 * counterclockwise around x from its neighbour `from` (SQ_NONE: none, or
 * `from` is not a neighbour). Turning clockwise is next(twin(h)) in both
 * the mesh and Q, so the answer is the last candidate met clockwise. */
static uint32_t ccw_first(const uint32_t *v_he, const uint32_t *next, const uint32_t *twin,
                          const uint32_t *vert, uint32_t x, uint32_t from, const uint32_t *cand,
                          uint32_t ncand)
{
    uint32_t h0 = v_he[x], h = h0, start = SQ_NONE;
    do {
        if (vert[next[h]] == from) start = h;
        h = next[twin[h]];
    } while (h != h0 && start == SQ_NONE);
    if (start == SQ_NONE) return SQ_NONE;
    uint32_t last = SQ_NONE;
    for (h = next[twin[start]]; h != start; h = next[twin[h]]) {
        uint32_t w = vert[next[h]];
        for (uint32_t i = 0; i < ncand; i++)
            if (cand[i] == w) last = w;
    }
    return last;
}

/* Q's tree neighbours of y (at most 64). */
static uint32_t q_tree_nbrs(const sq_metapolygon *Q, const uint8_t *qtree, uint32_t y, uint32_t *out)
{
    uint32_t n = 0, h0 = Q->v_he[y], h = h0;
    do {
        if (qtree[h] && n < 64) out[n++] = Q->he_vert[Q->he_next[h]];
        h = Q->he_next[Q->he_twin[h]];
    } while (h != h0);
    return n;
}

/* Extra cost of entering v: next to a tree vertex, a cone or Q's boundary.
 * Paths that hug the tree, cones or the boundary wall off the sectors and
 * sides later paths must reach; this keeps a lane free where there is room. */
enum { HUG_COST = 4 };

static uint32_t hug_cost(const sq_metapolygon *Q, const uint8_t *bnd, const uint32_t *qowner, uint32_t v)
{
    uint32_t h0 = Q->v_he[v], h = h0;
    do {
        uint32_t w = Q->he_vert[Q->he_next[h]];
        if (bnd[w] || Q->v_nface[w] != 4 || qowner[w] != SQ_NONE) return HUG_COST;
        h = Q->he_next[Q->he_twin[h]];
    } while (h != h0);
    return 0;
}

typedef struct replica {
    const sq_metapolygon *Q;
    const sq_mesh *m;
    uint32_t n;
    /* surface paths: spath[soff[j] .. soff[j+1]) from cone j to its end */
    uint32_t *soff, *spath;
    uint32_t *sowner, *sidx; /* m->nv: path and index of a tree vertex (not */
                             /* its end); SQ_NONE off the tree             */
    uint32_t *node_q;        /* m->nv: Q copy of a surface node            */
    uint32_t *qoff, *qpath;  /* the same for Q's paths, grown step by step */
    uint32_t nq;
    uint32_t *qowner, *qidx; /* Q->nv */
    uint8_t *qtree;          /* Q->nh: tree halfedges (both directions)    */
    uint32_t *qv, *spath_cone; /* n: Q and surface cone of each path, in build order */
    uint32_t *step;          /* n: the step of each path (path 0: the root) */
    uint32_t *tree_next, *att_s, *att_q;
} replica;

/* The Q vertex next to the copy of surface node x along the copy of the
 * tree edge x -> nb (nb a tree neighbour of x at this step); SQ_NONE when
 * nb is not one. */
static uint32_t q_neighbour(const replica *R, uint32_t x, uint32_t nb, uint32_t jmax)
{
    uint32_t p = R->sowner[x];
    if (p != SQ_NONE) {
        uint32_t i = R->sidx[x], qi = R->node_q[x] != SQ_NONE ? R->qidx[R->node_q[x]] : SQ_NONE;
        if (qi == SQ_NONE) return SQ_NONE;
        const uint32_t *sp = R->spath + R->soff[p], *qp = R->qpath + R->qoff[p];
        uint32_t qlen = R->qoff[p + 1] - R->qoff[p];
        if (i > 0 && sp[i - 1] == nb) return qp[qi - 1];
        if (i + 1 < R->soff[p + 1] - R->soff[p] && sp[i + 1] == nb) return qi + 1 < qlen ? qp[qi + 1] : SQ_NONE;
    }
    /* paths that end at x */
    for (uint32_t j = 1; j < jmax; j++) {
        uint32_t len = R->soff[j + 1] - R->soff[j];
        if (len < 2 || R->spath[R->soff[j] + len - 1] != x) continue;
        if (R->spath[R->soff[j] + len - 2] == nb) return R->qpath[R->qoff[j + 1] - 2];
    }
    return SQ_NONE;
}

/* The surface tree neighbours of x before step j (paths 0 .. j-1). */
static uint32_t s_tree_nbrs(const replica *R, uint32_t x, uint32_t j, uint32_t *out)
{
    uint32_t n = 0, p = R->sowner[x];
    if (p != SQ_NONE && p < j) {
        uint32_t i = R->sidx[x], len = R->soff[p + 1] - R->soff[p];
        if (i > 0) out[n++] = R->spath[R->soff[p] + i - 1];
        if (i + 1 < len) out[n++] = R->spath[R->soff[p] + i + 1];
    }
    for (uint32_t q = 1; q < j && n < 64; q++) {
        uint32_t len = R->soff[q + 1] - R->soff[q];
        if (len >= 2 && R->spath[R->soff[q] + len - 1] == x) out[n++] = R->spath[R->soff[q] + len - 2];
    }
    return n;
}

/* Which surface ends Q can copy at step j: the Q vertices reachable from
 * qv[j] (region[v] == j), and for every arrival at a surface tree vertex
 * whether Q has a free neighbour of the copy in that sector (a node) or of
 * some inner vertex of the segment's copy on that side. */
typedef struct end_ctx {
    const replica *R;
    uint32_t j;
    const uint32_t *forbid, *region;
    uint32_t *seg_stamp; /* per spath index of a segment's first node */
    uint8_t *seg_val;    /* bit 0/1: up side known/ok, bit 2/3: down side */
} end_ctx;

/* Whether a free neighbour w of Q vertex y in the region lies in the
 * sector whose first tree neighbour counterclockwise is lab (among nb). */
static int q_sector_open(const replica *R, const uint32_t *region, uint32_t j, uint32_t y, uint32_t lab,
                         const uint32_t *nb, uint32_t nnb)
{
    const sq_metapolygon *Q = R->Q;
    uint32_t h0 = Q->v_he[y], h = h0;
    do {
        uint32_t w = Q->he_vert[Q->he_next[h]];
        int interior = Q->he_face[h] != SQ_NONE && Q->he_face[Q->he_twin[h]] != SQ_NONE;
        h = Q->he_next[Q->he_twin[h]];
        if (!interior || region[w] != j) continue;
        if (!nnb || ccw_first(Q->v_he, Q->he_next, Q->he_twin, Q->he_vert, y, w, nb, nnb) == lab) return 1;
    } while (h != h0);
    return 0;
}

static int end_ok_(void *user, uint32_t x, uint32_t u);
static int end_ok(void *user, uint32_t x, uint32_t u)
{
    int r = end_ok_(user, x, u);
    return r;
}
static int end_ok_(void *user, uint32_t x, uint32_t u)
{
    end_ctx *E = user;
    const replica *R = E->R;
    const sq_mesh *m = R->m;
    if (E->forbid[x] == E->j) return 0;
    uint32_t cand[64], qcand[64];
    uint32_t nc = s_tree_nbrs(R, x, E->j, cand);
    uint32_t label = nc ? ccw_first(m->v_he, m->he_next, m->he_twin, m->he_vert, x, u, cand, nc) : SQ_NONE;
    if (nc && label == SQ_NONE) return 0;
    if (R->node_q[x] != SQ_NONE) {
        uint32_t y = R->node_q[x];
        uint32_t lq = label != SQ_NONE ? q_neighbour(R, x, label, E->j) : SQ_NONE;
        if (label != SQ_NONE && lq == SQ_NONE) return 0;
        return q_sector_open(R, E->region, E->j, y, lq, qcand, q_tree_nbrs(R->Q, R->qtree, y, qcand));
    }
    /* inside a segment of path p: the answer is the segment's, per side */
    uint32_t p = R->sowner[x], i = R->sidx[x], plen = R->soff[p + 1] - R->soff[p];
    const uint32_t *sp = R->spath + R->soff[p];
    uint32_t a = i, b = i;
    while (a > 0 && R->node_q[sp[a]] == SQ_NONE) a--;
    while (b + 1 < plen && R->node_q[sp[b]] == SQ_NONE) b++;
    int up = label == sp[i - 1];
    uint8_t known = up ? 1 : 4, ok = up ? 2 : 8;
    uint32_t key = R->soff[p] + a;
    if (E->seg_stamp[key] != E->j) E->seg_stamp[key] = E->j, E->seg_val[key] = 0;
    if (E->seg_val[key] & known) return (E->seg_val[key] & ok) != 0;
    uint32_t qlen = R->qoff[p + 1] - R->qoff[p];
    uint32_t q0 = a == 0 ? 0 : R->qidx[R->node_q[sp[a]]];
    uint32_t q1 = b + 1 == plen ? qlen - 1 : R->qidx[R->node_q[sp[b]]];
    const uint32_t *qp = R->qpath + R->qoff[p];
    int res = 0;
    for (uint32_t qi = q0 + 1; qi < q1 && !res; qi++) {
        uint32_t two[2] = {qp[qi - 1], qp[qi + 1]};
        res = q_sector_open(R, E->region, E->j, qp[qi], up ? qp[qi - 1] : qp[qi + 1], two, 2);
    }
    E->seg_val[key] |= known | (res ? ok : 0);
    return res;
}

/* The free region of Q around qv[j]: region[w] = j for the interior
 * vertices of Q reached from it through interior edges and free regular
 * vertices (no boundary, no tree); queue: scratch. */
static void mark_region(const replica *R, uint32_t j, const uint8_t *bnd, uint32_t *region, uint32_t *queue)
{
    const sq_metapolygon *Q = R->Q;
    uint32_t qh = 0, qt = 0;
    region[R->qv[j]] = j, queue[qt++] = R->qv[j];
    while (qh < qt) {
        uint32_t v = queue[qh++], h0 = Q->v_he[v], h = h0;
        do {
            uint32_t w = Q->he_vert[Q->he_next[h]];
            int interior = Q->he_face[h] != SQ_NONE && Q->he_face[Q->he_twin[h]] != SQ_NONE;
            h = Q->he_next[Q->he_twin[h]];
            if (!interior || region[w] == j || bnd[w] || Q->v_nface[w] != 4 || R->qowner[w] != SQ_NONE) continue;
            region[w] = j, queue[qt++] = w;
        } while (h != h0);
    }
}

/* Seed 9.4 on both disks at once. Step j: the surface path from cone j to
 * the nearest tree vertex x (sq_guide_surface_path), then Q's path from
 * qv[j] to the copy of x (or into the copy of x's segment) in the same
 * sector. Where Q's grid has no room for that (the sector at a node holds
 * no free edge of Q, the segment's copy has no inner vertex, or the place
 * is walled off), x (or x's whole segment) is forbidden as an end for this
 * step and the surface path is chosen again. */
static sq_status grow_step(replica *R, uint32_t j, const uint8_t *sblocked, double *sdist, uint32_t *spar,
                           uint32_t *stouched, uint32_t *forbid, uint32_t *region, uint32_t *seg_stamp,
                           uint8_t *seg_val, sq_cut_heap *heap, sq_cut_heap *qheap,
                           const uint8_t *bnd,
                           uint32_t *dist, uint32_t *par, uint32_t *queue, uint32_t **edges_io,
                           uint32_t *ne, sq_error *err)
{
    const sq_mesh *m = R->m;
    const sq_metapolygon *Q = R->Q;
    uint32_t cand[64], qcand[64];
    mark_region(R, j, bnd, region, queue);
    for (uint32_t tries = 0; tries < 256; tries++) {
        uint32_t nt = 0;
        int nomem = 0;
        end_ctx E = {R, j, forbid, region, seg_stamp, seg_val};
        uint32_t x = sq_guide_surface_path(m, sblocked, R->sowner, end_ok, &E, R->spath_cone[j], sdist, spar,
                                           stouched, &nt, heap, &nomem);
        /* the surface path cone .. x, reversed from par */
        uint32_t len = 0;
        if (x != SQ_NONE)
            for (uint32_t y = x; y != SQ_NONE; y = spar[y]) len++;
        uint32_t *sp = R->spath + R->soff[j];
        if (x != SQ_NONE) {
            uint32_t i = len;
            for (uint32_t y = x; y != SQ_NONE; y = spar[y]) sp[--i] = y;
        }
        for (uint32_t i = 0; i < nt; i++) sdist[stouched[i]] = INFINITY;
        if (nomem) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        if (x == SQ_NONE)
            return sq_error_set(err, SQ_ERR_SOLVER, "cone tree pair: step %u reaches no allowed tree vertex", j);
        R->soff[j + 1] = R->soff[j] + len;
        uint32_t u = sp[len - 2];
        /* the surface sector: first tree neighbour counterclockwise */
        uint32_t nc = s_tree_nbrs(R, x, j, cand);
        uint32_t label = nc ? ccw_first(m->v_he, m->he_next, m->he_twin, m->he_vert, x, u, cand, nc) : SQ_NONE;
        if (nc && label == SQ_NONE)
            return sq_error_set(err, SQ_ERR_INTERNAL, "cone tree pair: step %u has no sector", j);
        uint32_t want_q = R->node_q[x], p = SQ_NONE, q0 = 0, q1 = 0, a = 0, b = 0, label_q = SQ_NONE;
        double want_pos = 0;
        if (want_q == SQ_NONE) {
            /* inside a segment of path p, between the nodes sp[a], sp[b] */
            p = R->sowner[x];
            uint32_t i = R->sidx[x], plen = R->soff[p + 1] - R->soff[p];
            const uint32_t *pp = R->spath + R->soff[p];
            a = b = i;
            while (a > 0 && R->node_q[pp[a]] == SQ_NONE) a--;
            while (b + 1 < plen && R->node_q[pp[b]] == SQ_NONE) b++;
            uint32_t qlen = R->qoff[p + 1] - R->qoff[p];
            q0 = a == 0 ? 0 : R->qidx[R->node_q[pp[a]]];
            q1 = b + 1 == plen ? qlen - 1 : R->qidx[R->node_q[pp[b]]];
            want_pos = (double)q0 + (double)(q1 - q0) * (double)(i - a) / (double)(b - a);
        } else if (label != SQ_NONE) {
            label_q = q_neighbour(R, x, label, j);
            if (label_q == SQ_NONE)
                return sq_error_set(err, SQ_ERR_INTERNAL, "cone tree pair: step %u: no copy of its sector", j);
        }
        /* Dijkstra in Q from qv[j] through free interior vertices (unit
         * edges, HUG_COST more next to the tree, cones and the boundary) */
        uint32_t s = R->qv[j];
        double best_cost = INFINITY;
        uint32_t best = SQ_NONE, best_from = SQ_NONE, qt = 0;
        dist[s] = 0, par[s] = SQ_NONE, queue[qt++] = s;
        qheap->n = 0;
        if (!sq_cut_heap_push(qheap, 0, s)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        double dv;
        uint32_t v;
        if (want_q != SQ_NONE || q1 > q0 + 1)
            while (sq_cut_heap_pop(qheap, &dv, &v)) {
                if (dv > (double)dist[v]) continue;
                if (dv + 1 > best_cost) break;
                uint32_t h0 = Q->v_he[v], h = h0;
                do {
                    uint32_t w = Q->he_vert[Q->he_next[h]];
                    int interior = Q->he_face[h] != SQ_NONE && Q->he_face[Q->he_twin[h]] != SQ_NONE;
                    h = Q->he_next[Q->he_twin[h]];
                    if (!interior || w == s) continue;
                    double cost = INFINITY;
                    if (want_q != SQ_NONE) {
                        if (w == want_q) {
                            uint32_t qn = q_tree_nbrs(Q, R->qtree, w, qcand);
                            if (!qn || ccw_first(Q->v_he, Q->he_next, Q->he_twin, Q->he_vert, w, v, qcand, qn) == label_q)
                                cost = dv + 1;
                        }
                    } else if (R->qowner[w] == p && R->qidx[w] > q0 && R->qidx[w] < q1) {
                        const uint32_t *qp = R->qpath + R->qoff[p], *pp = R->spath + R->soff[p];
                        uint32_t qi = R->qidx[w], i = R->sidx[x];
                        uint32_t lab_q = label == pp[i - 1] ? qp[qi - 1] : label == pp[i + 1] ? qp[qi + 1] : SQ_NONE;
                        uint32_t two[2] = {qp[qi - 1], qp[qi + 1]};
                        if (lab_q != SQ_NONE &&
                            ccw_first(Q->v_he, Q->he_next, Q->he_twin, Q->he_vert, w, v, two, 2) == lab_q)
                            cost = dv + 1 + fabs((double)qi - want_pos);
                    }
                    if (isfinite(cost)) {
                        if (cost < best_cost) best_cost = cost, best = w, best_from = v;
                        continue;
                    }
                    if (bnd[w] || Q->v_nface[w] != 4 || R->qowner[w] != SQ_NONE) continue;
                    uint32_t nd = (uint32_t)dv + 1 + hug_cost(Q, bnd, R->qowner, w);
                    if (nd >= dist[w]) continue;
                    if (dist[w] == UINT32_MAX) queue[qt++] = w;
                    dist[w] = nd, par[w] = v;
                    if (!sq_cut_heap_push(qheap, nd, w)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                } while (h != h0);
            }
        if (best == SQ_NONE) {
            for (uint32_t i = 0; i < qt; i++) dist[queue[i]] = UINT32_MAX;
            /* no room in Q: not this end again */
            if (want_q != SQ_NONE) {
                forbid[x] = j;
            } else {
                const uint32_t *pp = R->spath + R->soff[p];
                for (uint32_t i = a + 1; i < b; i++) forbid[pp[i]] = j;
            }
            continue;
        }
        /* accept: the surface path joins the tree */
        for (uint32_t i = 0; i + 1 < len; i++) {
            R->sowner[sp[i]] = j, R->sidx[sp[i]] = i;
            R->tree_next[sp[i]] = sp[i + 1];
        }
        /* Q's path s .. best_from, best */
        uint32_t qlen = 2;
        for (uint32_t y = best_from; par[y] != SQ_NONE; y = par[y]) qlen++;
        R->qoff[j] = R->nq, R->qoff[j + 1] = R->nq + qlen;
        uint32_t i = qlen - 1, prev = best;
        R->qpath[R->nq + i] = best;
        for (uint32_t y = best_from; y != SQ_NONE; prev = y, y = par[y]) {
            i--;
            uint32_t h0 = Q->v_he[y], h = h0;
            while (Q->he_vert[Q->he_next[h]] != prev) {
                h = Q->he_next[Q->he_twin[h]];
                if (h == h0) break;
            }
            (*edges_io)[(*ne)++] = h;
            R->qtree[h] = R->qtree[Q->he_twin[h]] = 1;
            R->qpath[R->nq + i] = y;
            R->qowner[y] = j, R->qidx[y] = i;
        }
        for (uint32_t k = 0; k < qt; k++) dist[queue[k]] = UINT32_MAX;
        R->nq += qlen;
        if (R->node_q[x] == SQ_NONE) R->node_q[x] = best;
        R->att_s[R->step[j]] = x, R->att_q[R->step[j]] = best;
        return SQ_OK;
    }
    return sq_error_set(err, SQ_ERR_SOLVER, "cone tree pair: step %u finds no place in Q", j);
}

static void replica_free(replica *R)
{
    free(R->soff), free(R->step), free(R->qv), free(R->spath_cone), free(R->qoff), free(R->spath);
    free(R->sowner), free(R->sidx), free(R->node_q), free(R->qowner), free(R->qidx), free(R->qtree);
    free(R->qpath);
}

/* Q's root path: breadth-first from the root cone s to the boundary vertex
 * standing for the surface root (the cheapest by rcost), through free
 * regular interior vertices; its edges appended to edges (*ne), the path
 * recorded as R's path 0; *qroot_out: its end on Q's boundary. dist
 * (UINT32_MAX outside a search), par, queue: scratch. */
static sq_status q_root_path(replica *R, uint32_t s, const uint8_t *bnd, const double *rcost, uint32_t *dist,
                             uint32_t *par, uint32_t *queue, uint32_t *edges, uint32_t *ne, uint32_t *qroot_out,
                             sq_error *err)
{
    const sq_metapolygon *Q = R->Q;
    uint32_t qh = 0, qt = 0, best_from = SQ_NONE, qroot = SQ_NONE;
    double best_cost = INFINITY;
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
            if (bnd[w]) {
                if (Q->v_nface[w] == 2 && isfinite(rcost[w]) && (double)dist[v] + 1 + rcost[w] < best_cost)
                    best_cost = (double)dist[v] + 1 + rcost[w], qroot = w, best_from = v;
                continue;
            }
            if (dist[w] != UINT32_MAX || Q->v_nface[w] != 4) continue;
            dist[w] = dist[v] + 1, par[w] = v, queue[qt++] = w;
        } while (h != h0);
    }
    uint32_t qlen = qroot != SQ_NONE ? dist[best_from] + 2 : 0;
    for (uint32_t k = 0; k < qt; k++) dist[queue[k]] = UINT32_MAX;
    if (qroot == SQ_NONE) return sq_error_set(err, SQ_ERR_SOLVER, "cone tree pair: the root cone cannot reach its side of Q");
    for (uint32_t y = best_from, k = qlen - 1, prev = qroot; y != SQ_NONE; prev = y, y = par[y]) {
        uint32_t h0 = Q->v_he[y], h = h0;
        while (Q->he_vert[Q->he_next[h]] != prev) {
            h = Q->he_next[Q->he_twin[h]];
            if (h == h0) break;
        }
        edges[(*ne)++] = h;
        R->qtree[h] = R->qtree[Q->he_twin[h]] = 1;
        R->qpath[--k] = y;
        R->qowner[y] = 0, R->qidx[y] = k;
    }
    R->qpath[qlen - 1] = qroot;
    R->qoff[0] = 0, R->qoff[1] = R->nq = qlen;
    *qroot_out = qroot;
    return SQ_OK;
}

sq_status sq_guide_tree_pair(const sq_metapolygon *Q, const uint32_t *qv, const sq_mesh *m, const sq_cut_graph *G,
                             const uint32_t *cone, uint32_t n, uint32_t root_step, sq_guide_root_cost_fn root_cost,
                             void *user, uint32_t *tree_next, uint32_t *att_vertex, uint32_t *att_qvertex,
                             sq_guide_root *root, sq_cone_tree *T, sq_error *err)
{
    if (n == 0 || root_step >= n) return sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree pair: no cones or root step");
    replica R;
    memset(&R, 0, sizeof R);
    R.Q = Q, R.m = m, R.n = n, R.tree_next = tree_next;
    R.att_s = att_vertex, R.att_q = att_qvertex;
    size_t nv1 = (size_t)m->nv + 1, qv1 = (size_t)Q->nv + 1;
    R.soff = malloc(((size_t)n + 1) * sizeof *R.soff);
    R.step = malloc(((size_t)n + 1) * sizeof *R.step);
    R.qv = malloc(((size_t)n + 1) * sizeof *R.qv);
    R.spath_cone = malloc(((size_t)n + 1) * sizeof *R.spath_cone);
    R.qoff = malloc(((size_t)n + 1) * sizeof *R.qoff);
    R.spath = malloc((nv1 + n) * sizeof *R.spath);
    R.sowner = malloc(nv1 * sizeof *R.sowner);
    R.sidx = malloc(nv1 * sizeof *R.sidx);
    R.node_q = malloc(nv1 * sizeof *R.node_q);
    R.qowner = malloc(qv1 * sizeof *R.qowner);
    R.qidx = malloc(qv1 * sizeof *R.qidx);
    R.qtree = calloc((size_t)Q->nh + 1, 1);
    R.qpath = malloc((qv1 + n) * sizeof *R.qpath);
    uint8_t *sblocked = calloc(nv1, 1), *bnd = calloc(qv1, 1);
    double *sdist = malloc(nv1 * sizeof *sdist), *rcost = malloc(qv1 * sizeof *rcost);
    uint32_t *spar = malloc(nv1 * sizeof *spar), *stouched = malloc(nv1 * sizeof *stouched);
    uint32_t *forbid = malloc(nv1 * sizeof *forbid), *rnext = malloc(nv1 * sizeof *rnext);
    uint32_t *region = malloc(qv1 * sizeof *region), *seg_stamp = malloc((nv1 + n) * sizeof *seg_stamp);
    uint8_t *seg_val = malloc(nv1 + n);
    uint32_t *dist = malloc(qv1 * sizeof *dist), *par = malloc(qv1 * sizeof *par);
    uint32_t *queue = malloc(qv1 * sizeof *queue), *edges = malloc(qv1 * sizeof *edges);
    sq_cut_heap heap, qheap;
    memset(&heap, 0, sizeof heap);
    memset(&qheap, 0, sizeof qheap);
    sq_status st = SQ_OK;
    uint32_t ne = 0, qroot = SQ_NONE;
    if (!R.soff || !R.step || !R.qv || !R.spath_cone || !R.qoff || !R.spath || !R.sowner || !R.sidx || !R.node_q || !R.qowner || !R.qidx ||
        !R.qtree || !R.qpath || !sblocked || !bnd || !sdist || !rcost || !spar || !stouched || !forbid || !region || !seg_stamp || !seg_val ||
        !rnext || !dist || !par || !queue || !edges || !sq_cut_heap_init(&heap, 64) ||
        !sq_cut_heap_init(&qheap, 64)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) bnd[Q->he_vert[h]] = 1;
    for (uint32_t j = 0; j < n; j++)
        if (qv[j] >= Q->nv || bnd[qv[j]] || Q->v_nface[qv[j]] == 4) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree pair: step %u has no interior cone of Q", j);
            goto done;
        }
    for (uint32_t h = 0; h < m->nh; h++)
        if (G->he_cut[h]) sblocked[m->he_vert[h]] = 1;
    for (uint32_t j = 0; j < n; j++) sblocked[cone[j]] = 1;
    for (uint32_t v = 0; v < m->nv; v++) {
        R.sowner[v] = R.node_q[v] = tree_next[v] = forbid[v] = rnext[v] = SQ_NONE;
        sdist[v] = INFINITY;
    }
    for (uint32_t v = 0; v < Q->nv; v++) R.qowner[v] = region[v] = SQ_NONE, dist[v] = UINT32_MAX;
    for (uint32_t k = 0; k < nv1 + n; k++) seg_stamp[k] = SQ_NONE;
    /* path 0 is the root path (seed 9.4: from the cone nearest the circle
     * to the nearest side), then every other step in order */
    for (uint32_t t = 0, j = 0; j < n; j++)
        if (j != root_step) R.step[++t] = j;
    R.step[0] = root_step;
    for (uint32_t t = 0; t < n; t++) R.spath_cone[t] = cone[R.step[t]], R.qv[t] = qv[R.step[t]];
    for (uint32_t j = 0; j < n; j++) R.node_q[cone[j]] = qv[j];
    for (uint32_t j = 0; j < n; j++) att_vertex[j] = att_qvertex[j] = SQ_NONE;
    root->step = root_step, root->side = SQ_NONE;
    st = sq_guide_surface_root(m, G, n, cone, tree_next, rnext, root, err);
    if (st == SQ_OK && root->vertex == SQ_NONE)
        st = sq_error_set(err, SQ_ERR_SOLVER, "cone tree pair: the root cone reaches no side");
    if (st == SQ_OK) st = root_cost(user, root, rcost);
    if (st) goto done;
    {
        /* the surface root path, cone .. side vertex */
        uint32_t len = 1;
        for (uint32_t x = root->vertex; x != cone[root_step] && len <= m->nv; x = rnext[x]) len++;
        uint32_t i = len;
        for (uint32_t x = root->vertex; i > 0; x = rnext[x]) R.spath[--i] = x;
        R.soff[0] = 0, R.soff[1] = len;
        for (i = 0; i + 1 < len; i++) {
            R.sowner[R.spath[i]] = 0, R.sidx[R.spath[i]] = i;
            tree_next[R.spath[i]] = R.spath[i + 1];
        }
        st = q_root_path(&R, qv[root_step], bnd, rcost, dist, par, queue, edges, &ne, &qroot, err);
        if (st) goto done;
        R.node_q[root->vertex] = qroot;
    }
    for (uint32_t t = 1; t < n && st == SQ_OK; t++)
        st = grow_step(&R, t, sblocked, sdist, spar, stouched, forbid, region, seg_stamp, seg_val, &heap, &qheap, bnd, dist, par, queue, &edges, &ne, err);
    if (st) goto done;
    st = sq_cone_tree_from_edges(Q, qroot, edges, ne, T, err);
done:
    replica_free(&R);
    free(sblocked);
    free(bnd);
    free(sdist);
    free(rcost);
    free(spar);
    free(stouched);
    free(forbid);
    free(region);
    free(seg_stamp);
    free(seg_val);
    free(rnext);
    free(dist);
    free(par);
    free(queue);
    free(edges);
    sq_cut_heap_free(&heap);
    sq_cut_heap_free(&qheap);
    return st;
}
