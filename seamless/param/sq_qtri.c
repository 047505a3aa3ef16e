/* seamquad: Q triangulated and glued, the surface tree copied into it
 * (sq_qtri.h; seed 9.4). */
#include "sq_qtri.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_edge_hash.h"
#include "sq_predicates.h"
#include "sq_soup.h"

void sq_qtri_init(sq_qtri *T)
{
    memset(T, 0, sizeof *T);
    sq_tsurf_init(&T->S);
    T->root = T->root_side = T->root_he = T->root_pos = SQ_NONE;
}

void sq_qtri_free(sq_qtri *T)
{
    sq_tsurf_free(&T->S);
    free(T->closed_of);
    free(T->tree_next);
    free(T->tree_step);
    free(T->cone);
    free(T->att);
    sq_qtri_init(T);
}

/* tree_next and tree_step cover every vertex of S */
static int ensure_cap(sq_qtri *T)
{
    if (T->cap_v >= T->S.nv) return 0;
    uint32_t c = T->S.cap_v > T->S.nv ? T->S.cap_v : T->S.nv;
    uint32_t *a = realloc(T->tree_next, (size_t)c * sizeof *a);
    if (!a) return -1;
    T->tree_next = a;
    uint32_t *b = realloc(T->tree_step, (size_t)c * sizeof *b);
    if (!b) return -1;
    T->tree_step = b;
    for (uint32_t v = T->cap_v; v < c; v++) T->tree_next[v] = T->tree_step[v] = SQ_NONE;
    T->cap_v = c;
    return 0;
}

/* The interior halfedge of Q between a and b (either direction). */
static uint32_t q_inner_he(const sq_metapolygon *Q, uint32_t a, uint32_t b)
{
    for (int r = 0; r < 2; r++) {
        uint32_t x = r ? b : a, y = r ? a : b, h0 = Q->v_he[x], h = h0;
        do {
            if (Q->he_vert[Q->he_next[h]] == y && Q->he_face[h] != SQ_NONE) return h;
            h = Q->he_next[Q->he_twin[h]];
        } while (h != h0);
    }
    return SQ_NONE;
}

/* The halfedge of S in quad f's triangles from vertex a to vertex b. */
static uint32_t s_he_in_quad(const sq_tsurf *S, uint32_t f, uint32_t a, uint32_t b)
{
    for (uint32_t t = 2 * f; t < 2 * f + 2; t++)
        for (uint32_t e = 3 * t; e < 3 * t + 3; e++)
            if (S->vert[e] == a && sq_ts_head(S, e) == b) return e;
    return SQ_NONE;
}

/* the two triangles of a quad along diagonal c0-c2 (0) or c1-c3 (1) */
static const int quad_tri[2][2][3] = {{{0, 1, 2}, {0, 2, 3}}, {{1, 2, 3}, {1, 3, 0}}};

/* adds the undirected edge a-b to E; returns 1 if it was there already */
static int edge_set_add(sq_edge_hash *E, uint32_t a, uint32_t b)
{
    size_t i = sq_edge_hash_slot(E, a < b ? a : b, a < b ? b : a);
    if (E->val[i] != SQ_NONE) return 1;
    E->val[i] = 1;
    return 0;
}

sq_status sq_qtri_build(const sq_domain *D, const double *xy, sq_qtri *T, sq_error *err)
{
    const sq_metapolygon *Q = &D->quads;
    sq_qtri_free(T);
    sq_soup quads, tris;
    memset(&quads, 0, sizeof quads);
    memset(&tris, 0, sizeof tris);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    int32_t *val = NULL;
    uint32_t *side = NULL;
    uint8_t *diag = NULL;
    sq_edge_hash es = {0, NULL, NULL};
    T->nq = Q->nv;
    T->closed_of = malloc(((size_t)Q->nv + 1) * sizeof *T->closed_of);
    if (!T->closed_of) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
    sq_status st = sq_domain_glue(D, xy, &quads, T->closed_of, err);
    if (st) goto done;
    tris.nv = quads.nv, tris.pos = quads.pos, quads.pos = NULL;
    tris.nf = 2 * quads.nf;
    tris.face_off = malloc(((size_t)tris.nf + 1) * sizeof *tris.face_off);
    tris.face_idx = malloc(3 * (size_t)tris.nf * sizeof *tris.face_idx);
    val = calloc((size_t)quads.nv + 1, sizeof *val);
    if (!tris.face_off || !tris.face_idx || !val) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
        goto done;
    }
    /* quad (c0 c1 c2 c3) -> (c0 c1 c2), (c0 c2 c3), or along the other
     * diagonal where c0-c2 is an edge already (two quads around a cone of
     * valence 2 share two sides; their diagonals may join the same pair) */
    diag = calloc((size_t)quads.nf + 1, 1);
    if (!diag || sq_edge_hash_init(&es, 6 * (size_t)quads.nf + 16)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
        goto done;
    }
    for (uint32_t f = 0; f < quads.nf; f++)
        for (int i = 0; i < 4; i++)
            edge_set_add(&es, quads.face_idx[quads.face_off[f] + (uint32_t)i],
                         quads.face_idx[quads.face_off[f] + (uint32_t)(i + 1) % 4]);
    for (uint32_t f = 0; f < quads.nf; f++) {
        const uint32_t *c = quads.face_idx + quads.face_off[f];
        if (edge_set_add(&es, c[0], c[2])) {
            diag[f] = 1;
            if (edge_set_add(&es, c[1], c[3])) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "Q triangulated: both diagonals of quad %u are edges", f);
                goto done;
            }
        }
        const int(*tri)[3] = quad_tri[diag[f]];
        for (int s = 0; s < 2; s++) {
            uint32_t t = 2 * f + (uint32_t)s;
            tris.face_off[t] = 3 * t;
            for (int i = 0; i < 3; i++) tris.face_idx[3 * t + (uint32_t)i] = c[tri[s][i]];
        }
        for (int i = 0; i < 4; i++) val[c[i]]++;
    }
    tris.face_off[tris.nf] = 3 * tris.nf;
    st = sq_mesh_from_soup(&tris, SQ_MESH_SKIP_DEGENERATE, &mesh, err);
    if (st) {
        char why[sizeof err->msg];
        memcpy(why, err ? err->msg : "", err ? sizeof why : 1);
        st = sq_error_set(err, SQ_ERR_INTERNAL, "Q triangulated and glued is not a simple closed mesh: %s", why);
        goto done;
    }
    st = sq_tsurf_from_mesh(&mesh, val, &T->S, NULL, err);
    if (st) goto done;
    sq_tsurf *S = &T->S;
    S->hvec = malloc(2 * (size_t)S->cap_h * sizeof *S->hvec);
    if (!S->hvec) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
        goto done;
    }
    /* exact vectors in each quad's frame */
    static const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (uint32_t t = 0; t < S->nf; t++) {
        const uint32_t *c = quads.face_idx + quads.face_off[t / 2];
        const int *ti = quad_tri[diag[t / 2]][t % 2];
        for (uint32_t e = 3 * t; e < 3 * t + 3; e++) {
            int k = 0;
            while (k < 3 && c[ti[k]] != S->vert[e]) k++;
            if (k == 3 || c[ti[(k + 1) % 3]] != sq_ts_head(S, e)) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "Q triangulated: face %u does not match quad %u", t, t / 2);
                goto done;
            }
            for (int q = 0; q < 2; q++) S->hvec[2 * e + (uint32_t)q] = corner[ti[(k + 1) % 3]][q] - corner[ti[k]][q];
        }
    }
    /* Q's boundary is a cut; each halfedge is labelled with the side of Q
     * whose face it lies in */
    uint32_t maxlen = 0;
    for (uint32_t i = 0; i < D->k; i++) maxlen = D->side_len[i] > maxlen ? D->side_len[i] : maxlen;
    side = malloc(((size_t)maxlen + 1) * sizeof *side);
    if (!side) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
        goto done;
    }
    for (uint32_t i = 0; i < D->k; i++) {
        sq_domain_side_vertices(D, i, side);
        for (uint32_t t = 0; t < D->side_len[i]; t++) {
            uint32_t qh = q_inner_he(Q, side[t], side[t + 1]);
            uint32_t e = qh == SQ_NONE ? SQ_NONE
                                       : s_he_in_quad(S, Q->he_face[qh], T->closed_of[Q->he_vert[qh]],
                                                      T->closed_of[Q->he_vert[Q->he_next[qh]]]);
            if (e == SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "Q triangulated: edge %u of side %u not found", t, i);
                goto done;
            }
            sq_tsurf_cut_edge(S, e, SQ_TS_SEAM, i, D->pattern.partner[i]);
        }
    }
    if (ensure_cap(T)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Q triangulated)");
done:
    sq_soup_free(&quads);
    sq_soup_free(&tris);
    sq_mesh_free(&mesh);
    free(val);
    free(side);
    free(diag);
    sq_edge_hash_free(&es);
    if (st) sq_qtri_free(T);
    return st;
}

/* ---- the copy of the surface tree -------------------------------------- */

typedef struct rep {
    sq_qtri *T;
    const sq_mesh *m;
    const uint32_t *next; /* the surface tree */
    uint32_t *step_of;    /* m->nv: the surface path holding each tree vertex */
    uint32_t *snode;      /* m->nv: the copy in S of each surface node       */
    uint32_t *list;       /* m->nv + 1: scratch                              */
    sq_error *err;
} rep;

/* The tree neighbour of x (a surface node) met first turning clockwise
 * from its neighbour u, among the edges of paths before step j; SQ_NONE if
 * there is none. */
static uint32_t surface_cw_first(const rep *R, uint32_t x, uint32_t u, uint32_t j)
{
    const sq_mesh *m = R->m;
    uint32_t h0 = m->v_he[x], h = h0, hu = SQ_NONE;
    do {
        if (m->he_vert[m->he_next[h]] == u) hu = h;
        h = m->he_next[m->he_twin[h]];
    } while (h != h0 && hu == SQ_NONE);
    if (hu == SQ_NONE) return SQ_NONE;
    for (h = m->he_next[m->he_twin[hu]]; h != hu; h = m->he_next[m->he_twin[h]]) {
        uint32_t w = m->he_vert[m->he_next[h]];
        if (R->next[x] == w && R->step_of[x] < j) return w;
        if (R->next[w] == x && R->step_of[w] < j) return w;
    }
    return SQ_NONE;
}

/* The copy in S of the tree neighbour w of the surface node x. */
static uint32_t copy_neighbour(const rep *R, uint32_t x, uint32_t w)
{
    const sq_qtri *T = R->T;
    uint32_t xc = R->snode[x];
    if (R->next[x] == w) return T->tree_next[xc];
    const sq_tsurf *S = &T->S;
    uint32_t h0 = S->v_he[xc], h = h0;
    do {
        uint32_t y = sq_ts_head(S, h);
        if (T->tree_next[y] == xc && T->tree_step[y] == R->step_of[w]) return y;
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    return SQ_NONE;
}

/* x lies inside surface path p (not a node): a new node of S inside the
 * copy of x's segment, at about the same fraction of it. */
static sq_status new_node(rep *R, uint32_t x, uint32_t p, const uint32_t *cone, const uint32_t *att)
{
    sq_qtri *T = R->T;
    uint32_t n = 0, ix = SQ_NONE, lim = R->m->nv;
    for (uint32_t y = cone[p]; n <= lim; y = R->next[y]) {
        R->list[n] = y;
        if (y == x) ix = n;
        n++;
        if (y == att[p]) break;
    }
    if (ix == SQ_NONE || ix == 0 || ix + 1 >= n)
        return sq_error_set(R->err, SQ_ERR_INTERNAL, "tree copy: vertex %u is not inside path %u", x, p);
    uint32_t ia = ix, ib = ix;
    while (R->snode[R->list[ia]] == SQ_NONE) ia--;
    while (R->snode[R->list[ib]] == SQ_NONE) ib++;
    uint32_t a = R->snode[R->list[ia]], b = R->snode[R->list[ib]];
    /* the copy of the segment a .. b */
    uint32_t L = 0;
    for (uint32_t y = a; y != b; y = T->tree_next[y]) {
        uint32_t z = T->tree_next[y];
        if (z == SQ_NONE || (z != b && T->tree_step[z] != p) || L > T->S.nv)
            return sq_error_set(R->err, SQ_ERR_INTERNAL, "tree copy: segment of path %u broken", p);
        L++;
    }
    if (L == 1) {
        uint32_t h = sq_ts_find(&T->S, a, b);
        uint32_t mv = h == SQ_NONE ? SQ_NONE : sq_tsurf_split_edge(&T->S, h, 0.5);
        if (mv == SQ_NONE || ensure_cap(T)) return sq_error_set(R->err, SQ_ERR_NOMEM, "out of memory (tree copy)");
        T->tree_next[a] = mv, T->tree_next[mv] = b, T->tree_step[mv] = p;
        T->splits++;
        R->snode[x] = mv;
        return SQ_OK;
    }
    long k = lround((double)(ix - ia) / (double)(ib - ia) * (double)L);
    if (k < 1) k = 1;
    if (k > (long)L - 1) k = (long)L - 1;
    uint32_t y = a;
    for (long i = 0; i < k; i++) y = T->tree_next[y];
    R->snode[x] = y;
    return SQ_OK;
}

/* Marks the route's edges as tree edges of step j; each vertex after the
 * first points back along the route. */
static void mark_path(sq_qtri *T, const uint32_t *path, uint32_t np, uint32_t j)
{
    for (uint32_t i = 0; i < np; i++) {
        uint32_t a = T->S.vert[path[i]], b = sq_ts_head(&T->S, path[i]);
        sq_tsurf_cut_edge(&T->S, path[i], SQ_TS_SEAM, SQ_NONE, SQ_NONE);
        T->tree_next[b] = a, T->tree_step[b] = j;
    }
}

/* Step 1 from cone 0, which has no tree edge yet: a shortest path in edges
 * through vertices off the cut that are not cones. */
static sq_status first_path(sq_qtri *T, uint32_t from, uint32_t to, uint32_t **path, uint32_t *np, sq_error *err)
{
    const sq_tsurf *S = &T->S;
    uint32_t *pred = malloc((size_t)S->nv * sizeof *pred), *q = malloc((size_t)S->nv * sizeof *q);
    if (!pred || !q) {
        free(pred), free(q);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (tree copy)");
    }
    for (uint32_t v = 0; v < S->nv; v++) pred[v] = SQ_NONE;
    uint32_t nq = 0;
    q[nq++] = from, pred[from] = S->v_he[from];
    for (uint32_t i = 0; i < nq && pred[to] == SQ_NONE; i++) {
        uint32_t v = q[i], h0 = S->v_he[v], h = h0;
        if (v != from && (S->v_ncut[v] || S->valence[v] != 4)) continue;
        do {
            uint32_t w = sq_ts_head(S, h);
            if (pred[w] == SQ_NONE) pred[w] = h, q[nq++] = w;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
    }
    sq_status st = SQ_OK;
    if (pred[to] == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: no first path between Q's cones %u and %u", from, to);
    } else {
        uint32_t n = 0;
        for (uint32_t v = to; v != from; v = S->vert[pred[v]]) n++;
        uint32_t *p = realloc(*path, ((size_t)n + 1) * sizeof *p);
        if (!p) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (tree copy)");
        } else {
            *path = p, *np = n;
            for (uint32_t v = to; v != from; v = S->vert[pred[v]]) p[--n] = pred[v];
        }
    }
    free(pred), free(q);
    return st;
}

/* The root of Q: the inner vertex of side q_root_side at about the
 * surface root's fraction of its side (root->index of the surface side's
 * length in G), and the halfedge of S leaving it along that side. */
static sq_status place_root(sq_qtri *T, const sq_domain *D, const sq_cut_graph *G, const sq_guide_root *root,
                            uint32_t q_root_side, sq_error *err)
{
    const sq_tsurf *S = &T->S;
    const sq_metapolygon *Q = &D->quads;
    uint32_t L = D->side_len[q_root_side];
    uint32_t Ls = G->side_off[root->side + 1] - G->side_off[root->side];
    if (L < 2) return sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: side %u of Q has no inner vertex", q_root_side);
    uint32_t *side = malloc(((size_t)L + 1) * sizeof *side);
    if (!side) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (tree copy)");
    sq_domain_side_vertices(D, q_root_side, side);
    long iq = lround((double)root->index / (double)(Ls ? Ls : 1) * (double)L);
    iq = iq < 1 ? 1 : iq > (long)L - 1 ? (long)L - 1 : iq;
    uint32_t v = side[iq], e = SQ_NONE;
    for (int d = -1; d <= 1 && e == SQ_NONE; d += 2) {
        uint32_t w = side[iq + d], qh = q_inner_he(Q, v, w);
        if (qh != SQ_NONE && Q->he_vert[qh] == v)
            e = s_he_in_quad(S, Q->he_face[qh], T->closed_of[v], T->closed_of[w]);
    }
    free(side);
    if (e == SQ_NONE) return sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: no root halfedge on side %u", q_root_side);
    T->root = T->closed_of[v], T->root_side = q_root_side, T->root_he = e, T->root_pos = (uint32_t)iq;
    return SQ_OK;
}

sq_status sq_qtri_replicate(sq_qtri *T, const sq_domain *D, const sq_mesh *m, const sq_cut_graph *G,
                            uint32_t n, const uint32_t *cone, const uint32_t *qcone,
                            const uint32_t *tree_next, const uint32_t *att_vertex,
                            const sq_guide_root *root, uint32_t q_root_side, sq_error *err)
{
    sq_tsurf *S = &T->S;
    if (n == 0) return SQ_OK;
    if (!root || root->vertex == SQ_NONE || root->step >= n)
        return sq_error_set(err, SQ_ERR_SOLVER, "tree copy: the surface tree has no root path");
    rep R = {T, m, tree_next, malloc((size_t)m->nv * sizeof(uint32_t)), malloc((size_t)m->nv * sizeof(uint32_t)),
             malloc(((size_t)m->nv + 1) * sizeof(uint32_t)), err};
    uint32_t *path = NULL, np = 0;
    uint8_t *cone_free = calloc(S->nv_input, 1);
    T->cone = malloc((size_t)n * sizeof *T->cone);
    T->att = malloc((size_t)n * sizeof *T->att);
    T->n = n;
    sq_status st = SQ_OK;
    if (!R.step_of || !R.snode || !R.list || !cone_free || !T->cone || !T->att || ensure_cap(T)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (tree copy)");
        goto done;
    }
    for (uint32_t v = 0; v < m->nv; v++) R.step_of[v] = R.snode[v] = SQ_NONE;
    for (uint32_t j = 0; j < n; j++) {
        T->cone[j] = T->closed_of[qcone[j]];
        T->att[j] = SQ_NONE;
        if (j && att_vertex[j] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_SOLVER, "tree copy: the surface tree does not join cone %u (step %u)",
                              cone[j], j);
            goto done;
        }
        uint32_t x = cone[j], steps = 0;
        if (j == 0) R.step_of[x] = 0;
        for (; j && x != att_vertex[j] && x != SQ_NONE && steps <= m->nv; x = tree_next[x], steps++)
            R.step_of[x] = j;
        if (j && x != att_vertex[j]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: surface path %u does not reach its end", j);
            goto done;
        }
    }
    {
        uint32_t x = root->vertex, steps = 0;
        for (; x != cone[root->step] && x != SQ_NONE && steps <= m->nv; x = tree_next[x], steps++) R.step_of[x] = n;
        if (x != cone[root->step]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: the surface root path does not reach its cone");
            goto done;
        }
    }
    st = place_root(T, D, G, root, q_root_side, err);
    if (st) goto done;
    R.snode[cone[0]] = T->cone[0];
    T->tree_step[T->cone[0]] = 0;
    for (uint32_t j = 1; j <= n && st == SQ_OK; j++) {
        const int is_root = j == n;
        uint32_t x = is_root ? cone[root->step] : att_vertex[j], u = SQ_NONE;
        uint32_t y = is_root ? root->vertex : cone[j], steps = 0;
        for (; y != x && steps <= m->nv; y = tree_next[y], steps++) u = y;
        if (u == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: surface path %u is empty", j);
            break;
        }
        if (R.snode[x] == SQ_NONE) {
            st = new_node(&R, x, R.step_of[x], cone, att_vertex);
            if (st) break;
        }
        uint32_t xc = R.snode[x], w = surface_cw_first(&R, x, u, j);
        np = 0;
        if (w == SQ_NONE) {
            if (j != 1 || is_root) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: step %u ends at a vertex off the tree", j);
                break;
            }
            st = first_path(T, T->cone[1], xc, &path, &np, err);
            if (st == SQ_OK) {
                /* walked from cone 1 to cone 0: reverse it for mark_path,
                 * which points every vertex back towards the first */
                for (uint32_t i = 0; i < np; i++) path[i] = S->twin[path[i]];
                for (uint32_t i = 0; i < np / 2; i++) {
                    uint32_t t = path[i];
                    path[i] = path[np - 1 - i], path[np - 1 - i] = t;
                }
            }
        } else {
            uint32_t wc = copy_neighbour(&R, x, w);
            uint32_t start = wc == SQ_NONE ? SQ_NONE : sq_ts_find(S, xc, wc);
            if (start == SQ_NONE || !S->kind[start]) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: step %u: no copy of the sector's tree edge", j);
                break;
            }
            uint32_t nv0 = S->nv;
            /* along Q's edges where there is room, through edge midpoints
             * where earlier paths wall the way (sq_tsurf_route); through
             * faces where that finds nothing */
            if (!is_root) cone_free[T->cone[j]] = 1;
            for (int faces = 0; faces < 2; faces++) {
                if (faces && st != SQ_ERR_INTERNAL) break;
                np = 0;
                st = (faces ? sq_tsurf_route_faces : sq_tsurf_route)(
                    S, start, is_root ? SQ_ROUTE_SECTOR : SQ_ROUTE_CONE, is_root ? 0 : S->valence[T->cone[j]],
                    cone_free, 0, is_root ? T->root_he : SQ_NONE, &path, &np, err);
            }
            if (!is_root) cone_free[T->cone[j]] = 0;
            T->splits += S->nv - nv0;
            if (st == SQ_OK && T->max_faces && S->nf > T->max_faces)
                st = sq_error_set(err, SQ_ERR_SOLVER,
                                  "tree qtri: the tree's paths split Q triangulated into %u triangles (%llu "
                                  "Steiner vertices) by step %u of %u, more than the memory limit allows (%llu; --max-memory)",
                                  S->nf, (unsigned long long)T->splits, j, n, (unsigned long long)T->max_faces);
            if (st == SQ_ERR_INTERNAL && err) { /* name the step */
                char why[sizeof err->msg];
                memcpy(why, err->msg, sizeof why);
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: step %u of %u: %s", j, n, why);
            }
        }
        if (st) break;
        if (ensure_cap(T)) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (tree copy)");
            break;
        }
        uint32_t end = np ? sq_ts_head(S, path[np - 1]) : SQ_NONE;
        if (end != (is_root ? T->root : T->cone[j])) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tree copy: step %u ends at vertex %u of Q", j, end);
            break;
        }
        mark_path(T, path, np, j);
        if (!is_root) {
            R.snode[cone[j]] = T->cone[j];
            T->att[j] = xc;
        }
    }
done:
    free(R.step_of), free(R.snode), free(R.list);
    free(path), free(cone_free);
    return st;
}

/* ---- Omega's layout ----------------------------------------------------- */

/* v turned by k x 90 degrees counterclockwise (exact) */
static void rot90(uint8_t k, const double v[2], double out[2])
{
    double x = v[0], y = v[1];
    for (uint8_t i = 0; i < (k & 3); i++) {
        double t = x;
        x = -y, y = t;
    }
    out[0] = x, out[1] = y;
}

/* lays out face f with its halfedge h's origin at P and rotation k */
static void place_face(const sq_tsurf *S, uint32_t h, const double P[2], uint8_t k, double *cxy)
{
    double p[2] = {P[0], P[1]};
    for (int i = 0; i < 3; i++, h = S->next[h]) {
        cxy[2 * h] = p[0], cxy[2 * h + 1] = p[1];
        double d[2];
        rot90(k, S->hvec + 2 * h, d);
        p[0] += d[0], p[1] += d[1];
    }
}

sq_status sq_qtri_layout(const sq_qtri *T, double *cxy, sq_error *err)
{
    const sq_tsurf *S = &T->S;
    uint32_t *queue = malloc(((size_t)S->nf + 1) * sizeof *queue);
    uint8_t *seen = calloc((size_t)S->nf + 1, 1);
    sq_status st = SQ_OK;
    if (!queue || !seen) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Omega layout)");
        goto done;
    }
    const double origin[2] = {0, 0};
    uint32_t nq = 0;
    place_face(S, S->f_he[0], origin, 0, cxy);
    seen[0] = 1, queue[nq++] = 0;
    for (uint32_t i = 0; i < nq && st == SQ_OK; i++) {
        uint32_t f = queue[i], h = S->f_he[f];
        for (int e = 0; e < 3; e++, h = S->next[h]) {
            if (S->kind[h]) continue;
            uint32_t t = S->twin[h], g = S->face[t], hn = S->next[h];
            const double *A = cxy + 2 * h, *B = cxy + 2 * hn; /* h: A -> B */
            if (seen[g]) {
                /* closing: g's copies of B and A */
                const double *gb = cxy + 2 * t, *ga = cxy + 2 * S->next[t];
                if (gb[0] != B[0] || gb[1] != B[1] || ga[0] != A[0] || ga[1] != A[1])
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega layout: edge %u-%u does not close", S->vert[h],
                                      S->vert[hn]);
                continue;
            }
            /* the turn of g's frame that maps its vector of t onto A - B */
            double want[2] = {A[0] - B[0], A[1] - B[1]}, d[2];
            uint8_t k = 0;
            for (; k < 4; k++) {
                rot90(k, S->hvec + 2 * t, d);
                if (d[0] == want[0] && d[1] == want[1]) break;
            }
            if (k == 4) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega layout: edge %u-%u is no 90-degree turn of its twin",
                                  S->vert[h], S->vert[hn]);
                break;
            }
            place_face(S, t, B, k, cxy);
            seen[g] = 1, queue[nq++] = g;
        }
    }
    if (st == SQ_OK && nq != S->nf)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega layout: %u of %u faces reached (the cut is no disk)", nq, S->nf);
    for (uint32_t f = 0; f < S->nf && st == SQ_OK; f++) {
        uint32_t h = S->f_he[f];
        if (sq_orient2d(cxy + 2 * h, cxy + 2 * S->next[h], cxy + 2 * S->next[S->next[h]]) <= 0)
            st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega layout: face %u is not positively oriented", f);
    }
done:
    free(queue), free(seen);
    return st;
}

int sq_qtri_transition(const sq_qtri *T, const double *cxy, uint32_t h, uint8_t *rot, double t[2])
{
    const sq_tsurf *S = &T->S;
    uint32_t g = S->twin[h];
    /* h: a -> b in its face, g: b -> a in the other */
    const double *a = cxy + 2 * h, *b = cxy + 2 * S->next[h];
    const double *b2 = cxy + 2 * g, *a2 = cxy + 2 * S->next[g];
    double u[2] = {b[0] - a[0], b[1] - a[1]}, w[2] = {b2[0] - a2[0], b2[1] - a2[1]}, d[2];
    for (uint8_t k = 0; k < 4; k++) {
        rot90(k, u, d);
        if (d[0] != w[0] || d[1] != w[1]) continue;
        double ra[2];
        rot90(k, a, ra);
        t[0] = a2[0] - ra[0], t[1] = a2[1] - ra[1];
        double rb[2];
        rot90(k, b, rb);
        if (rb[0] + t[0] != b2[0] || rb[1] + t[1] != b2[1]) return 0;
        *rot = k;
        return 1;
    }
    return 0;
}
