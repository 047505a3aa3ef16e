/* seamquad: the cone tree in Q (seed 7, "Compatible Cutting"; seed 9.4).
 *
 * Seed 7: "In the quad mesh Q, we compute a discrete (edge-based) spanning
 * tree of all singularities and one arbitrary flat boundary vertex, within
 * the set of non-boundary edges." The tree must also touch Q's boundary
 * only at its root: a second boundary vertex on it would cut Q apart.
 *
 * Rotations around a vertex, with counterclockwise faces (sq_metapolygon.h):
 * for an outgoing halfedge h, next(twin(h)) is the next outgoing halfedge
 * clockwise, twin(prev(h)) the next one counterclockwise. The clockwise
 * step also walks through a boundary vertex (from its outgoing boundary
 * halfedge around its fan of faces and back), so it visits every outgoing
 * halfedge of any vertex exactly once. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"

void sq_cone_tree_init(sq_cone_tree *T) { memset(T, 0, sizeof *T); }

void sq_cone_tree_free(sq_cone_tree *T)
{
    free(T->he);
    free(T->vert);
    free(T->node);
    free(T->rot_off);
    free(T->rot_he);
    free(T->seg_off);
    free(T->seg_he);
    sq_cone_tree_init(T);
}

static uint32_t head(const sq_metapolygon *Q, uint32_t h) { return Q->he_vert[Q->he_next[h]]; }

/* Marks the vertices on Q's boundary loop; returns 0 if the loop is
 * broken (never for a valid Q). */
static int mark_boundary(const sq_metapolygon *Q, uint8_t *on_bnd)
{
    memset(on_bnd, 0, Q->nv);
    if (Q->bnd_he == SQ_NONE) return 1;
    uint32_t h = Q->bnd_he, steps = 0;
    do {
        if (h >= Q->nh || Q->he_face[h] != SQ_NONE || ++steps > Q->nh) return 0;
        on_bnd[Q->he_vert[h]] = 1;
        h = Q->he_next[h];
    } while (h != Q->bnd_he);
    return 1;
}

static int is_cone(const sq_metapolygon *Q, const uint8_t *on_bnd, uint32_t v)
{
    return !on_bnd[v] && Q->v_nface[v] != 4;
}

/* The tree halfedges leaving v in counterclockwise order, starting with
 * `first` (for an interior vertex: the halfedge towards the parent); for a
 * boundary vertex (first == SQ_NONE) starting at the twin of the incoming
 * boundary halfedge, ending with the outgoing one. Returns the count. */
static uint32_t rotation(const sq_metapolygon *Q, const uint8_t *tmark, uint32_t v,
                         uint32_t first, uint32_t *out)
{
    /* collect clockwise from `start`, then reverse (keeping start first
     * for an interior vertex) */
    uint32_t start = first == SQ_NONE ? Q->v_he[v] : first;
    uint32_t n = 0, h = start;
    do {
        if (tmark[h]) out[n++] = h;
        h = Q->he_next[Q->he_twin[h]];
    } while (h != start);
    if (first == SQ_NONE) {
        /* clockwise from the outgoing boundary halfedge = counterclockwise
         * order reversed, ending at the twin of the incoming one */
        for (uint32_t i = 0; i < n / 2; i++) {
            uint32_t t = out[i];
            out[i] = out[n - 1 - i];
            out[n - 1 - i] = t;
        }
    } else {
        /* out = [first, c1, c2, ...] clockwise -> [first, ..., c2, c1] */
        for (uint32_t i = 1, j = n - 1; i < j; i++, j--) {
            uint32_t t = out[i];
            out[i] = out[j];
            out[j] = t;
        }
    }
    return n;
}

sq_status sq_cone_tree_from_edges(const sq_metapolygon *Q, uint32_t root, const uint32_t *he,
                                  uint32_t n, sq_cone_tree *T, sq_error *err)
{
    sq_cone_tree_free(T);
    if (root >= Q->nv)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: root %u is not a vertex of Q (%u)",
                            root, Q->nv);
    if (n >= Q->nv)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cone tree: %u edges cannot form a tree on %u vertices", n, Q->nv);
    sq_status st = SQ_OK;
    uint8_t *on_bnd = malloc(Q->nv ? Q->nv : 1);
    uint8_t *tmark = calloc(Q->nh ? Q->nh : 1, 1);
    uint32_t *tid = malloc((Q->nv ? Q->nv : 1) * sizeof *tid);
    uint32_t *stack = malloc((2 * (size_t)n + 1) * sizeof *stack);
    T->he = malloc((n ? n : 1) * sizeof *T->he);
    T->vert = malloc(((size_t)n + 1) * sizeof *T->vert);
    T->node = calloc((size_t)n + 1, 1);
    T->rot_off = malloc(((size_t)n + 2) * sizeof *T->rot_off);
    T->rot_he = malloc((2 * (size_t)n + 1) * sizeof *T->rot_he);
    T->seg_off = malloc(((size_t)n + 2) * sizeof *T->seg_off);
    T->seg_he = malloc((n ? n : 1) * sizeof *T->seg_he);
    if (!on_bnd || !tmark || !tid || !stack || !T->he || !T->vert || !T->node || !T->rot_off ||
        !T->rot_he || !T->seg_off || !T->seg_he) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (!mark_boundary(Q, on_bnd)) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: Q has no valid boundary loop");
        goto done;
    }
    if (!on_bnd[root]) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "cone tree: root %u is not on the boundary of Q", root);
        goto done;
    }
    for (uint32_t e = 0; e < n; e++) {
        uint32_t h = he[e];
        if (h >= Q->nh || Q->he_face[h] == SQ_NONE || Q->he_face[Q->he_twin[h]] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cone tree: edge %u (halfedge %u) is not an interior edge of Q", e,
                              h);
            goto done;
        }
        if (tmark[h]) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cone tree: edge %u (halfedge %u) is listed twice", e, h);
            goto done;
        }
        tmark[h] = tmark[Q->he_twin[h]] = 1;
    }
    for (uint32_t v = 0; v < Q->nv; v++) tid[v] = SQ_NONE;

    /* depth-first from the root in rotation order: vertices and edges in
     * preorder, the rotation system written as vertices are numbered */
    uint32_t nv = 0, ne = 0, nr = 0, sp = 0;
    tid[root] = nv;
    T->vert[nv] = root;
    T->rot_off[nv] = nr;
    nr += rotation(Q, tmark, root, SQ_NONE, T->rot_he + nr);
    nv++;
    for (uint32_t i = T->rot_off[0]; i < nr; i++) stack[sp++] = T->rot_he[nr - 1 - i];
    while (sp) {
        uint32_t h = stack[--sp], w = head(Q, h);
        if (tid[w] != SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cone tree: the edges contain a cycle (through vertex %u of Q)", w);
            goto done;
        }
        if (on_bnd[w]) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cone tree: vertex %u of Q is on Q's boundary but not the root "
                              "%u (the cut would split Q)",
                              w, root);
            goto done;
        }
        T->he[ne++] = h;
        tid[w] = nv;
        T->vert[nv] = w;
        T->rot_off[nv] = nr;
        uint32_t deg = rotation(Q, tmark, w, Q->he_twin[h], T->rot_he + nr);
        nr += deg;
        nv++;
        for (uint32_t i = deg; i-- > 1;) stack[sp++] = T->rot_he[T->rot_off[nv - 1] + i];
    }
    T->rot_off[nv] = nr;
    if (ne != n) {
        for (uint32_t e = 0; e < n; e++)
            if (tid[Q->he_vert[he[e]]] == SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_ARGUMENT,
                                  "cone tree: edge %u (halfedge %u) is not connected to the root "
                                  "%u",
                                  e, he[e], root);
                goto done;
            }
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: edges not connected to the root");
        goto done;
    }
    for (uint32_t v = 0; v < Q->nv; v++)
        if (is_cone(Q, on_bnd, v) && tid[v] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cone tree: cone vertex %u of Q (valence %u) is not on the tree", v,
                              Q->v_nface[v]);
            goto done;
        }
    T->root = root;
    T->nedges = n;
    T->nverts = nv;

    /* nodes: root, cones, branch vertices, leaves */
    for (uint32_t i = 0; i < nv; i++) {
        uint32_t v = T->vert[i], deg = T->rot_off[i + 1] - T->rot_off[i];
        uint8_t f = 0;
        if (i == 0) f |= SQ_TREE_ROOT;
        if (is_cone(Q, on_bnd, v)) f |= SQ_TREE_CONE;
        if (deg >= 3) f |= SQ_TREE_BRANCH;
        if (deg == 1 && i != 0) f |= SQ_TREE_LEAF;
        T->node[i] = f;
    }
    /* segments: from every node along each child edge to the next node */
    uint32_t ns = 0, nsh = 0;
    for (uint32_t i = 0; i < nv; i++) {
        if (!T->node[i]) continue;
        for (uint32_t r = T->rot_off[i] + (i ? 1 : 0); r < T->rot_off[i + 1]; r++) {
            T->seg_off[ns++] = nsh;
            uint32_t h = T->rot_he[r];
            for (;;) {
                T->seg_he[nsh++] = h;
                uint32_t j = tid[head(Q, h)];
                if (T->node[j]) break;
                /* a regular degree-2 vertex: rotation = [parent, child] */
                h = T->rot_he[T->rot_off[j] + 1];
            }
        }
    }
    T->seg_off[ns] = nsh;
    T->nseg = ns;
    if (nsh != n) st = sq_error_set(err, SQ_ERR_INTERNAL, "cone tree: segments cover %u of %u "
                                                          "edges", nsh, n);
done:
    free(on_bnd);
    free(tmark);
    free(tid);
    free(stack);
    if (st) sq_cone_tree_free(T);
    return st;
}

/* Breadth-first relaxation from the vertices in queue[0..nq) (distance 0
 * already set): unit edge lengths, through interior vertices of Q only.
 * dist[] only decreases; par[w] is the halfedge by which w was reached. */
static void relax(const sq_metapolygon *Q, const uint8_t *on_bnd, uint32_t *dist, uint32_t *par,
                  uint32_t *queue, uint32_t nq)
{
    for (uint32_t qi = 0; qi < nq; qi++) {
        uint32_t u = queue[qi], h0 = Q->v_he[u], h = h0;
        do {
            uint32_t w = head(Q, h);
            if (!on_bnd[w] && dist[u] + 1 < dist[w]) {
                dist[w] = dist[u] + 1;
                par[w] = h;
                queue[nq++] = w;
            }
            h = Q->he_next[Q->he_twin[h]];
        } while (h != h0);
    }
}

/* Shortest paths from the tree (in_tree) over interior vertices, and among
 * them the ones with the fewest turns: every turn of the tree gives Omega a
 * reflex corner, hence a chord of sq_omega_cells, and a grid BFS alone
 * returns staircases. Breadth-first by layers of equal distance; the states
 * are halfedges h entering head(h) on a shortest path, with st_turn[h] the
 * fewest turns of a shortest path ending with h and st_par[h] the state
 * before it (SQ_NONE: h leaves the tree). A path goes straight through a
 * regular interior vertex when it leaves by the edge opposite the one it
 * came in by; at the tree itself no turn is counted. Per vertex: dist
 * (UINT32_MAX - 1 if unreachable), vturn and vbest (the best state entering
 * it; ties: the first found). */
static void straight_paths(const sq_metapolygon *Q, const uint8_t *on_bnd,
                           const uint8_t *in_tree, uint32_t *dist, uint32_t *vturn,
                           uint32_t *vbest, uint32_t *st_turn, uint32_t *st_par, uint32_t *queue)
{
    uint32_t nq = 0;
    for (uint32_t v = 0; v < Q->nv; v++) {
        dist[v] = in_tree[v] ? 0 : UINT32_MAX - 1;
        vturn[v] = UINT32_MAX;
        vbest[v] = SQ_NONE;
        if (in_tree[v]) queue[nq++] = v;
    }
    for (uint32_t h = 0; h < Q->nh; h++) st_turn[h] = UINT32_MAX;
    /* FIFO order visits the layers in turn, so every state entering u is
     * final before u's own edges are relaxed */
    for (uint32_t qi = 0; qi < nq; qi++) {
        uint32_t u = queue[qi], h0 = Q->v_he[u], h = h0;
        int regular = !on_bnd[u] && Q->v_nface[u] == 4;
        do {
            uint32_t w = head(Q, h);
            if (!on_bnd[w] && dist[w] >= dist[u] + 1) {
                if (dist[w] > dist[u] + 1) {
                    dist[w] = dist[u] + 1;
                    queue[nq++] = w;
                }
                uint32_t t = 0, p = SQ_NONE;
                if (dist[u] > 0) {
                    t = vturn[u] + 1;
                    p = vbest[u];
                    if (regular) {
                        /* the state entering u in h's direction */
                        uint32_t a = Q->he_twin[Q->he_next[Q->he_twin[Q->he_next[Q->he_twin[h]]]]];
                        if (st_turn[a] < t) t = st_turn[a], p = a;
                    }
                }
                st_turn[h] = t;
                st_par[h] = p;
                if (t < vturn[w]) vturn[w] = t, vbest[w] = h;
            }
            h = Q->he_next[Q->he_twin[h]];
        } while (h != h0);
    }
}

sq_status sq_cone_tree_shortest(const sq_metapolygon *Q, uint32_t root, sq_cone_tree *T,
                                sq_error *err)
{
    if (root != SQ_NONE && root >= Q->nv)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: root %u is not a vertex of Q (%u)",
                            root, Q->nv);
    size_t nv1 = Q->nv ? Q->nv : 1;
    uint8_t *on_bnd = malloc(nv1);
    uint8_t *in_tree = calloc(nv1, 1);
    uint32_t *dist = malloc(nv1 * sizeof *dist);
    uint32_t *par = malloc(nv1 * sizeof *par);
    uint32_t *queue = malloc(nv1 * sizeof *queue);
    uint32_t *cones = malloc(nv1 * sizeof *cones);
    uint32_t *edges = malloc(nv1 * sizeof *edges);
    size_t nh1 = Q->nh ? Q->nh : 1;
    uint32_t *vturn = malloc(nv1 * sizeof *vturn);
    uint32_t *vbest = malloc(nv1 * sizeof *vbest);
    uint32_t *st_turn = malloc(nh1 * sizeof *st_turn);
    uint32_t *st_par = malloc(nh1 * sizeof *st_par);
    sq_status st = SQ_OK;
    if (!on_bnd || !in_tree || !dist || !par || !queue || !cones || !edges || !vturn || !vbest ||
        !st_turn || !st_par) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (!mark_boundary(Q, on_bnd) || Q->bnd_he == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "cone tree: Q has no valid boundary loop");
        goto done;
    }
    if (root != SQ_NONE && !on_bnd[root]) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "cone tree: root %u is not on the boundary of Q", root);
        goto done;
    }
    uint32_t nc = 0;
    for (uint32_t v = 0; v < Q->nv; v++)
        if (is_cone(Q, on_bnd, v)) cones[nc++] = v;

    if (root == SQ_NONE) {
        /* distance of every interior vertex to the nearest cone */
        for (uint32_t v = 0; v < Q->nv; v++) dist[v] = UINT32_MAX - 1;
        for (uint32_t c = 0; c < nc; c++) dist[cones[c]] = 0;
        memcpy(queue, cones, nc * sizeof *queue);
        relax(Q, on_bnd, dist, par, queue, nc);
        /* pass 0: flat boundary vertices; pass 1: any with an interior
         * neighbour (the genus-0 slit has no flat boundary vertex) */
        for (int pass = 0; pass < 2 && root == SQ_NONE; pass++) {
            uint32_t best = UINT32_MAX, h = Q->bnd_he;
            do {
                uint32_t v = Q->he_vert[h];
                if (pass == 1 || Q->v_nface[v] == 2) {
                    uint32_t g = h;
                    do {
                        uint32_t w = head(Q, g);
                        uint32_t d = on_bnd[w] ? UINT32_MAX : nc ? dist[w] : 0;
                        if (d < UINT32_MAX - 1 && d < best) best = d, root = v;
                        g = Q->he_next[Q->he_twin[g]];
                    } while (g != h);
                }
                h = Q->he_next[h];
            } while (h != Q->bnd_he);
        }
        if (root == SQ_NONE) {
            if (nc) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "cone tree: no boundary vertex of Q reaches a cone through "
                                  "interior vertices");
                goto done;
            }
            root = Q->he_vert[Q->bnd_he];
        }
    }

    /* seed 9.4: join the nearest cone to the tree by a shortest path; among
     * shortest paths the one with the fewest turns (straight_paths,
     * recomputed from the whole tree after each join) */
    in_tree[root] = 1;
    uint32_t ne = 0, left = nc;
    while (left) {
        straight_paths(Q, on_bnd, in_tree, dist, vturn, vbest, st_turn, st_par, queue);
        uint32_t best = SQ_NONE;
        for (uint32_t c = 0; c < nc; c++)
            if (!in_tree[cones[c]] && (best == SQ_NONE || dist[cones[c]] < dist[best]))
                best = cones[c];
        if (dist[best] >= UINT32_MAX - 1) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cone tree: cone vertex %u of Q (valence %u) cannot be reached "
                              "from the root %u through interior vertices",
                              best, Q->v_nface[best], root);
            goto done;
        }
        for (uint32_t w = best, h = vbest[best]; !in_tree[w]; h = st_par[h]) {
            if (h == SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "cone tree: broken shortest path at vertex %u of Q", w);
                goto done;
            }
            edges[ne++] = h;
            in_tree[w] = 1;
            if (is_cone(Q, on_bnd, w)) left--;
            w = Q->he_vert[h];
        }
    }
    st = sq_cone_tree_from_edges(Q, root, edges, ne, T, err);
done:
    free(on_bnd);
    free(in_tree);
    free(dist);
    free(par);
    free(queue);
    free(cones);
    free(edges);
    free(vturn);
    free(vbest);
    free(st_turn);
    free(st_par);
    return st;
}
