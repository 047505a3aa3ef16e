/* seamquad: steering the cut graph so that the map's seam rotations around
 * the handles are those of a smooth cross field with the same cones
 * (docs/holonomy.md).
 *
 * Why the cut graph decides them. The domain D of the seed is a disk with
 * 8g - 4 straight sides and a right angle at every corner (seed 6, 8
 * "Boundary Map"); the map sends the cut disk M^c onto it side by side and
 * cones onto cones. Take the loop that starts just inside side j, follows
 * the boundary forward (disk on the left) to side i = partner(j) and
 * crosses the cut there: in D it runs along the boundary through no cone,
 * so its rotation is fixed by the corners it passes, t(j) - t(i) + 2
 * quarter turns (t = sq_pattern_side_direction). On the surface the same
 * loop hugs the cut graph; the field's rotation around it depends on which
 * cones the cut graph passes on which side. Where the two differ, no map
 * built on this cut graph has the field's rotations.
 *
 * The fix moves branches across cones: a segment of a branch b is
 * replaced by a detour inside the cut disk, on the side of one of b's two
 * sides s, around a cone; b keeps its ends, so the rotation system and the
 * pattern stay the same, and the region between the segment and the
 * detour (with its cones) moves to the other side of the branch. The mismatch is
 * a homomorphism from the cycles of the cut graph to Z4; with a spanning
 * tree of the branch graph it is one value per non-tree branch (Z4
 * linear system, solved mod 2 and lifted), and each accepted reroute must
 * lower the sum of these values' distances from 0.
 *
 * Genus >= 1 (genus 0 has no handle). The domain's corner angles are read
 * from G's pattern: right angles for genus >= 2; for genus 1's theta graph
 * the caller marks the corners the domain makes straight, and the marks
 * follow the corners when a reroute renumbers them. */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the mismatch ------------------------------------------------------- */

/* GF(2) solve of A x = r (rows n, cols c, row-major bytes); x gets one
 * solution (free variables 0). work: n (c + 1) bytes; pivcol: n entries.
 * Returns 0 if inconsistent. */
static int solve_gf2(uint32_t n, uint32_t c, const uint8_t *A, const uint8_t *r, uint8_t *x,
                     uint8_t *work, uint32_t *pivcol)
{
    const uint32_t w = c + 1;
    uint8_t *M = work;
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < c; ++j) M[i * w + j] = A[i * c + j] & 1u;
        M[i * w + c] = r[i] & 1u;
    }
    uint32_t row = 0;
    for (uint32_t j = 0; j < c && row < n; ++j) {
        uint32_t p = row;
        while (p < n && !M[p * w + j]) ++p;
        if (p == n) continue;
        for (uint32_t t = 0; t < w; ++t) {
            const uint8_t s = M[p * w + t];
            M[p * w + t] = M[row * w + t], M[row * w + t] = s;
        }
        for (uint32_t i = 0; i < n; ++i)
            if (i != row && M[i * w + j])
                for (uint32_t t = 0; t < w; ++t) M[i * w + t] ^= M[row * w + t];
        pivcol[row++] = j;
    }
    for (uint32_t i = row; i < n; ++i)
        if (M[i * w + c]) return 0;
    memset(x, 0, c);
    for (uint32_t i = 0; i < row; ++i) x[pivcol[i]] = M[i * w + c];
    return 1;
}

typedef struct mismatch {
    uint32_t npairs, nfree;   /* side pairs (branches); non-tree branches  */
    uint32_t *pair_side;      /* npairs: the side i < partner[i]            */
    uint32_t *free_pair;      /* nfree: pair index of each non-tree branch  */
    uint8_t *y;               /* nfree: the rotation each must gain, 0..3   */
    uint32_t norm;            /* sum of min(y, 4 - y)                        */
    uint32_t wrong_loops;     /* side pairs whose loop rotates wrongly       */
} mismatch;

static void mismatch_free(mismatch *M)
{
    free(M->pair_side), free(M->free_pair), free(M->y);
    memset(M, 0, sizeof *M);
}

/* The mismatch of G against the connection turn. Returns 0 when the Z4
 * system has no solution (it always has one when turn is a connection
 * with integer rotations; a failure means a bug) or on out of memory. */
/* A name for the branch of side i that survives renumbering: its lowest
 * edge (canonical halfedge). */
static uint32_t branch_id(const sq_mesh *m, const sq_cut_graph *G, uint32_t i)
{
    uint32_t id = UINT32_MAX;
    for (uint32_t n = G->side_off[i]; n < G->side_off[i + 1]; ++n) {
        const uint32_t h = G->side_he[n], e = h < m->he_twin[h] ? h : m->he_twin[h];
        if (e < id) id = e;
    }
    return id;
}

/* blocked (nh entries or NULL): branches (by branch_id) that no detour
 * could move, taken into the spanning tree first */
static int compute_mismatch(const sq_mesh *m, const sq_cut_graph *G, const double *turn,
                            const uint8_t *blocked, mismatch *out)
{
    const sq_pattern *P = &G->pattern;
    const uint32_t k = P->k, B = G->side_off[k], np = k / 2;
    memset(out, 0, sizeof *out);
    double *pre = malloc(((size_t)B + 1) * sizeof *pre);
    uint32_t *cls = malloc((size_t)k * sizeof *cls), *pair_of = malloc((size_t)k * sizeof *pair_of);
    uint32_t *comp = malloc((size_t)k * sizeof *comp);
    uint8_t *intree = calloc(np, 1), *rhs = calloc(np + 1, 1), *A = calloc((size_t)np * np, 1);
    uint8_t *x0 = calloc(np + 1, 1), *x1 = calloc(np + 1, 1), *r2 = calloc(np + 1, 1);
    uint8_t *work = malloc((size_t)np * (np + 2));
    uint32_t *piv = malloc(((size_t)np + 1) * sizeof *piv);
    int32_t *Ai = calloc((size_t)np * np, sizeof *Ai);
    out->pair_side = malloc((size_t)np * sizeof *out->pair_side);
    out->free_pair = malloc((size_t)np * sizeof *out->free_pair);
    out->y = calloc(np + 1, 1);
    int ok = 0;
    if (!pre || !cls || !pair_of || !comp || !intree || !rhs || !A || !x0 || !x1 || !r2 || !work || !piv ||
        !Ai || !out->pair_side || !out->free_pair || !out->y)
        goto done;
    /* rotation of the field along the boundary walk: crossings between
     * consecutive boundary halfedges (the wedge at their common vertex) */
    pre[0] = 0.0;
    for (uint32_t n = 0; n < B; ++n) {
        double s = 0.0;
        for (uint32_t c = m->he_next[G->side_he[n]]; !G->he_cut[c]; c = sq_cut_rot(m, c)) s += turn[c];
        pre[n + 1] = pre[n] + s;
    }
    uint32_t p = 0;
    for (uint32_t i = 0; i < k; ++i)
        if (i < P->partner[i]) pair_of[i] = pair_of[P->partner[i]] = p, out->pair_side[p++] = i;
    assert(p == np);
    out->npairs = np;
    /* spanning tree of the branch graph (corner classes, branches) */
    sq_pattern_corner_classes(P, cls);
    for (uint32_t i = 0; i < k; ++i) comp[i] = cls[i];
    /* into the tree first: branches no detour could move, then short ones
     * (a branch of one edge has no inner vertex to leave from); ties by
     * branch_id, so the tree does not change when a reroute renumbers the
     * sides */
    uint32_t *order = malloc((size_t)np * sizeof *order);
    uint32_t *bid = malloc((size_t)np * sizeof *bid);
    if (!order || !bid) {
        free(order), free(bid);
        goto done;
    }
    for (uint32_t q = 0; q < np; ++q) order[q] = q, bid[q] = branch_id(m, G, out->pair_side[q]);
    for (uint32_t a = 1; a < np; ++a) /* insertion sort */
        for (uint32_t b = a; b > 0; --b) {
            const uint32_t qx = order[b - 1], qy = order[b];
            const uint32_t x = out->pair_side[qx], y = out->pair_side[qy];
            const int bx = blocked && blocked[bid[qx]], by = blocked && blocked[bid[qy]];
            const uint32_t lx = G->side_off[x + 1] - G->side_off[x], ly = G->side_off[y + 1] - G->side_off[y];
            if (bx > by || (bx == by && (lx < ly || (lx == ly && bid[qx] <= bid[qy])))) break;
            order[b - 1] = qy, order[b] = qx;
        }
    free(bid);
    for (uint32_t oq = 0; oq < np; ++oq) {
        const uint32_t q = order[oq];
        const uint32_t i = out->pair_side[q];
        const uint32_t a = comp[cls[i]], b = comp[cls[(i + 1) % k]];
        if (a == b) continue;
        intree[q] = 1;
        for (uint32_t t = 0; t < k; ++t)
            if (comp[t] == b) comp[t] = a;
    }
    free(order);
    uint32_t nfree = 0;
    for (uint32_t q = 0; q < np; ++q)
        if (!intree[q]) out->free_pair[nfree++] = q;
    out->nfree = nfree;
    /* per side pair: the map's rotation t(j) - t(i) + 2 and the field's */
    for (uint32_t q = 0; q < np; ++q) {
        const uint32_t i = out->pair_side[q], j = P->partner[i];
        const uint32_t hi = G->side_he[G->side_off[i]], pos_q = G->side_off[j + 1] - 1;
        assert(G->side_he[pos_q] == m->he_twin[hi]);
        const double f = (pre[B] - pre[pos_q]) + pre[G->side_off[i]] + turn[hi];
        const long field = ((long)nearbyint(f) % 4 + 4) % 4;
        const long want = ((long)sq_pattern_side_direction(P, j) - (long)sq_pattern_side_direction(P, i) + 6) % 4;
        rhs[q] = (uint8_t)((want - field + 4) % 4);
        if (rhs[q]) out->wrong_loops++;
        /* the loop's cycle: sides j+1 .. i-1 (forward, cyclic) */
        for (uint32_t s = (j + 1) % k; s != i; s = (s + 1) % k) {
            const uint32_t b = pair_of[s];
            Ai[(size_t)q * np + b] += s < P->partner[s] ? 1 : -1;
        }
    }
    for (uint32_t q = 0; q < np; ++q)
        for (uint32_t t = 0; t < nfree; ++t)
            A[(size_t)q * nfree + t] = (uint8_t)(((Ai[(size_t)q * np + out->free_pair[t]] % 4) + 4) % 4);
    /* A y = rhs (mod 4): y = x0 + 2 x1 */
    if (!solve_gf2(np, nfree, A, rhs, x0, work, piv)) goto done;
    for (uint32_t q = 0; q < np; ++q) {
        int s = rhs[q];
        for (uint32_t t = 0; t < nfree; ++t) s -= A[(size_t)q * nfree + t] * x0[t];
        s = ((s % 4) + 4) % 4;
        assert(!(s & 1));
        r2[q] = (uint8_t)(s / 2);
    }
    if (!solve_gf2(np, nfree, A, r2, x1, work, piv)) goto done;
    out->norm = 0;
    for (uint32_t t = 0; t < nfree; ++t) {
        out->y[t] = (uint8_t)((x0[t] + 2 * x1[t]) % 4);
        out->norm += out->y[t] <= 2 ? out->y[t] : 4u - out->y[t];
    }
    for (uint32_t q = 0; q < np; ++q) { /* the lifted solution must hold mod 4 */
        int s = 0;
        for (uint32_t t = 0; t < nfree; ++t) s += A[(size_t)q * nfree + t] * out->y[t];
        if ((s - rhs[q]) % 4) goto done;
    }
    ok = 1;
done:
    free(pre), free(cls), free(pair_of), free(comp), free(intree), free(rhs), free(A);
    free(x0), free(x1), free(r2), free(work), free(piv), free(Ai);
    if (!ok) mismatch_free(out);
    return ok;
}

/* ---- rerouting a branch -------------------------------------------------- */

/* A branch b is moved across a cone c by a detour: a simple path through
 * free vertices (neither cones nor on the cut) that leaves side s of b at
 * an inner vertex x and rejoins it at a later inner vertex y, going around
 * c; the segment of b between x and y is replaced by the detour. The
 * branch keeps its two ends, so the rotation system and the pattern are
 * unchanged; the faces between the segment and the detour (with their
 * cones) move to the other side of b. Candidates: one shortest-path forest
 * over free vertices grown from side s's inner vertices; around a cone c,
 * the ring edge (a, b) whose two tree paths reach the side at different
 * vertices gives the detour x ~> a -> b ~> y. */

#define PENALTY_EDGES 3.0
#define NEAR_CONES 16 /* the cones tried per side, nearest first */

/* Shortest paths from side vertices side_he lo..hi: dist, the halfedge
 * into v (par) and the side_he index n of the vertex the path starts at
 * (src), grown on demand (forest_grow) and resumable: the vertices settled
 * so far are those of the whole forest, whatever the stops. dist, par and
 * src of v hold only where vis[v] == stamp (fdist: INFINITY elsewhere), so
 * a new forest costs no pass over the vertices. */
typedef struct forest {
    double *dist;
    uint32_t *par, *src;
    uint32_t *vis;  /* nv: stamp where dist, par, src are set */
    uint32_t *done; /* nv: stamp where settled                */
    uint32_t stamp, lo, hi;
    int live;       /* lo, hi grown on the current cut         */
    sq_cut_heap heap;
} forest;

static double fdist(const forest *F, uint32_t v)
{
    return F->vis[v] == F->stamp ? F->dist[v] : INFINITY;
}

typedef struct steer_ws {
    const sq_mesh *m;
    const uint8_t *cone;
    uint8_t *cut;           /* nh: the current cut                           */
    uint32_t *cutdeg, *near;/* nv                                            */
    uint32_t *route;        /* nv: the detour, halfedges x -> y              */
    uint32_t *mark;         /* nv: stamps                                    */
    uint32_t *fstack;       /* nf                                            */
    uint32_t *fmark;        /* nf: stamps                                    */
    uint32_t stamp;
    double penalty;
    double *len;            /* nh: edge lengths (sq_cut_he_length)           */
} steer_ws;

static int is_free(const steer_ws *w, uint32_t v)
{
    return w->cutdeg[v] == 0 && !(w->cone && w->cone[v]);
}

/* Marks cone c's free ring vertices not yet settled in F (stamp ring),
 * counting them in *left. */
static void mark_ring(steer_ws *w, const forest *F, uint32_t c, uint32_t ring, uint32_t *left)
{
    const sq_mesh *m = w->m;
    const uint32_t h0 = m->v_he[c];
    uint32_t h = h0;
    do {
        const uint32_t a = sq_cut_dest(m, h);
        if (is_free(w, a) && w->mark[a] != ring && F->done[a] != F->stamp) w->mark[a] = ring, ++*left;
        h = sq_cut_rot(m, h);
    } while (h != h0);
}

/* dist[y] := d through halfedge h from side vertex n where shorter. */
static int relax(forest *F, uint32_t y, double d, uint32_t h, uint32_t n)
{
    if (!(d < fdist(F, y))) return 1;
    F->vis[y] = F->stamp, F->dist[y] = d, F->par[y] = h, F->src[y] = n;
    return sq_cut_heap_push(&F->heap, d, y);
}

/* F := the forest of side_he lo..hi with nothing settled: the first step
 * from each inner vertex of the side, through the wedge on the disk's
 * side. 0: out of memory. */
static int forest_start(steer_ws *w, const sq_cut_graph *G, uint32_t lo, uint32_t hi, forest *F)
{
    const sq_mesh *m = w->m;
    if (++F->stamp == 0) { /* wrapped: every stamp void */
        memset(F->vis, 0, (size_t)m->nv * sizeof *F->vis);
        memset(F->done, 0, (size_t)m->nv * sizeof *F->done);
        F->stamp = 1;
    }
    F->lo = lo, F->hi = hi, F->live = 1;
    F->heap.n = 0;
    const uint32_t B = G->side_off[G->pattern.k];
    for (uint32_t n = lo; n <= hi; ++n) {
        /* the wedge at the n-th vertex of the walk, between side_he[n-1]
         * (into it) and side_he[n]: inner vertices, and the two corners
         * (in the sector next to side s) */
        for (uint32_t c = m->he_next[G->side_he[(n + B - 1) % B]]; !w->cut[c]; c = sq_cut_rot(m, c)) {
            const uint32_t y = sq_cut_dest(m, c);
            if (is_free(w, y) && !relax(F, y, w->len[c] + (w->near[y] ? w->penalty : 0.0), c, n)) return 0;
        }
    }
    return 1;
}

/* Grows F over free vertices (Dijkstra) until every vertex the caller
 * reads is settled:
 *  - stop a cone: the free vertices of its ring;
 *  - stop SQ_NONE (F just started): NEAR_CONES cones seen (a free ring
 *    vertex settled), every cone as near as the last of them, and the
 *    free rings of the cones seen: what nearest_cones and cone_detours
 *    read.
 * Or until every reachable vertex is settled. 0: out of memory. */
static int forest_grow(steer_ws *w, forest *F, uint32_t stop)
{
    const sq_mesh *m = w->m;
    uint32_t left = 0, nseen = 0; /* ring vertices to settle; cones seen */
    const uint32_t ring = ++w->stamp, seen = ++w->stamp;
    double dlim = INFINITY; /* the distance of the NEAR_CONES-th cone seen */
    if (stop != SQ_NONE) {
        mark_ring(w, F, stop, ring, &left);
        if (left == 0) return 1;
    }
    double d;
    uint32_t x;
    while (sq_cut_heap_pop(&F->heap, &d, &x)) {
        if (d > fdist(F, x)) continue;
        F->done[x] = F->stamp;
        if (w->mark[x] == ring) w->mark[x] = 0, --left;
        const uint32_t h0 = m->v_he[x];
        uint32_t h = h0;
        do {
            const uint32_t y = sq_cut_dest(m, h);
            if (is_free(w, y)) {
                if (!relax(F, y, d + w->len[h] + (w->near[y] ? w->penalty : 0.0), h, F->src[x])) return 0;
            } else if (stop == SQ_NONE && d <= dlim && w->cone[y] && w->mark[y] != seen) {
                w->mark[y] = seen;
                mark_ring(w, F, y, ring, &left);
                if (++nseen == NEAR_CONES) dlim = d;
            }
            h = sq_cut_rot(m, h);
        } while (h != h0);
        if (left > 0) continue;
        if (stop != SQ_NONE) break;
        /* near: no cone left as near as the last one seen */
        if (nseen >= NEAR_CONES && (F->heap.n == 0 || F->heap.key[0] > dlim)) break;
    }
    return 1;
}

/* The detour through ring edge ab (halfedge a -> b) into w->route: the
 * path of forest A to a, then ab, then forest Bf's path from b, run from
 * the earlier of the two side vertices to the later; *na, *nb their
 * side_he indices. Returns the number of halfedges, 0 if the two paths
 * meet or start at the same vertex. */
static uint32_t build_detour(steer_ws *w, const forest *A, const forest *Bf, uint32_t ab,
                             uint32_t *na, uint32_t *nb)
{
    const sq_mesh *m = w->m;
    const uint32_t a = m->he_vert[ab], b = sq_cut_dest(m, ab);
    if (A->src[a] == Bf->src[b]) return 0;
    const uint32_t st = ++w->stamp;
    uint32_t n = 0;
    for (uint32_t x = a;;) { /* x_a ~> a, collected backwards */
        const uint32_t h = A->par[x];
        w->route[n++] = h;
        w->mark[x] = st;
        x = m->he_vert[h];
        if (!is_free(w, x)) break;
    }
    for (uint32_t i = 0; i < n / 2; ++i) {
        const uint32_t t = w->route[i];
        w->route[i] = w->route[n - 1 - i], w->route[n - 1 - i] = t;
    }
    w->route[n++] = ab;
    for (uint32_t x = b;;) { /* b ~> x_b */
        if (w->mark[x] == st) return 0;
        w->mark[x] = st;
        const uint32_t h = m->he_twin[Bf->par[x]];
        w->route[n++] = h;
        x = sq_cut_dest(m, h);
        if (!is_free(w, x)) break;
    }
    *na = A->src[a], *nb = Bf->src[b];
    if (*na > *nb) { /* run from the earlier side vertex */
        for (uint32_t i = 0; i < n / 2; ++i) {
            const uint32_t t = w->route[i];
            w->route[i] = m->he_twin[w->route[n - 1 - i]], w->route[n - 1 - i] = m->he_twin[t];
        }
        if (n & 1) w->route[n / 2] = m->he_twin[w->route[n / 2]];
        const uint32_t t = *na;
        *na = *nb, *nb = t;
    }
    return n;
}

/* Index sum (4 - valence) of the cones between the segment side_he[na ..
 * nb-1] and the detour: faces flood-filled from the segment's faces
 * without crossing the cut or the detour. *bad: the fill reached another
 * cut edge (the detour does not close the region off). */
static long region_index(steer_ws *w, const sq_cut_graph *G, uint32_t na, uint32_t nb,
                         const int32_t *valence, uint32_t nroute, int *bad)
{
    const sq_mesh *m = w->m;
    const uint32_t st = ++w->stamp;
    for (uint32_t i = 0; i < nroute; ++i) w->cut[w->route[i]] = w->cut[m->he_twin[w->route[i]]] = 2;
    for (uint32_t n = na; n < nb; ++n) w->cut[G->side_he[n]] = 3;
    uint32_t sp = 0;
    for (uint32_t n = na; n < nb; ++n) {
        const uint32_t f = m->he_face[G->side_he[n]];
        if (w->fmark[f] != st) w->fmark[f] = st, w->fstack[sp++] = f;
    }
    *bad = 0;
    long idx = 0;
    while (sp) {
        const uint32_t f = w->fstack[--sp];
        const uint32_t h0 = m->f_he[f];
        uint32_t h = h0;
        do {
            const uint32_t v = m->he_vert[h];
            if (w->cone && w->cone[v] && w->mark[v] != st) w->mark[v] = st, idx += 4 - valence[v];
            if (!w->cut[h]) {
                const uint32_t g = m->he_face[m->he_twin[h]];
                if (w->fmark[g] != st) w->fmark[g] = st, w->fstack[sp++] = g;
            } else if (w->cut[h] == 1)
                *bad = 1;
            h = m->he_next[h];
        } while (h != h0);
    }
    for (uint32_t i = 0; i < nroute; ++i) w->cut[w->route[i]] = w->cut[m->he_twin[w->route[i]]] = 0;
    for (uint32_t n = na; n < nb; ++n) w->cut[G->side_he[n]] = 1;
    return idx;
}

static void ws_recount(steer_ws *w)
{
    const sq_mesh *m = w->m;
    memset(w->cutdeg, 0, (size_t)m->nv * sizeof *w->cutdeg);
    memset(w->near, 0, (size_t)m->nv * sizeof *w->near);
    for (uint32_t h = 0; h < m->nh; ++h)
        if (w->cut[h]) w->cutdeg[m->he_vert[h]]++;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (w->cutdeg[m->he_vert[h]]) w->near[sq_cut_dest(m, h)]++;
}

/* G with the segment side_he[na .. nb-1] of side s replaced by the detour
 * (n halfedges); the boundary word redone (not the check: the caller
 * checks the detour it keeps). The new word may
 * start elsewhere: its corner (i + *shift) mod k is G's corner i, whose
 * straight flag it gets. */
static sq_status apply_detour(const sq_mesh *m, const sq_cut_graph *G, uint32_t s, uint32_t na, uint32_t nb,
                              const uint32_t *route, uint32_t n, sq_cut_graph *out, uint32_t *shift, sq_error *err)
{
    sq_cut_graph_init(out);
    out->he_cut = malloc(m->nh);
    if (!out->he_cut) return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (steer)");
    memcpy(out->he_cut, G->he_cut, m->nh);
    double len = G->length;
    for (uint32_t i = na; i < nb; ++i) {
        const uint32_t h = G->side_he[i];
        out->he_cut[h] = out->he_cut[m->he_twin[h]] = 0;
        len -= sq_cut_he_length(m, h);
    }
    for (uint32_t i = 0; i < n; ++i) {
        out->he_cut[route[i]] = out->he_cut[m->he_twin[route[i]]] = 1;
        len += sq_cut_he_length(m, route[i]);
    }
    out->genus = G->genus;
    out->length = len;
    out->rotation = G->rotation, out->flip = G->flip, out->tries = G->tries;
    sq_status st = sq_cut_boundary_word(m, out, err);
    if (st == SQ_OK) out->rank = sq_pattern_rank(&out->pattern);
    const uint32_t k = G->pattern.k;
    if (st == SQ_OK && out->pattern.k != k)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: a detour changed the number of sides");
    if (st) return st;
    /* a side the detour left alone: its first halfedge names it in both */
    uint32_t i = 0;
    while (i == s || i == G->pattern.partner[s]) ++i;
    const uint32_t h = G->side_he[G->side_off[i]];
    uint32_t j = 0;
    while (j < k && out->side_he[out->side_off[j]] != h) ++j;
    if (j == k) return sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: a side moved by a detour it did not touch");
    *shift = (j + k - i) % k;
    for (uint32_t c = 0; c < k; ++c) out->pattern.straight[(c + *shift) % k] = G->pattern.straight[c];
    return SQ_OK;
}

typedef struct near_entry {
    uint32_t c;
    double d;
} near_entry;

static int near_cmp(const void *a, const void *b)
{
    const near_entry *p = a, *q = b;
    if (p->d != q->d) return p->d < q->d ? -1 : 1;
    return p->c < q->c ? -1 : p->c > q->c; /* ties by index: the same order on every libc */
}

typedef struct route_cand {
    uint32_t ab;  /* the ring edge a -> b the detour crosses */
    int pass;     /* 0: one forest; 1: before / after the nearest vertex */
    long q;       /* index sum of the cones moved            */
    double len;   /* detour length with penalties           */
} route_cand;


/* The cones next to a free vertex that F reaches (F: from one side of the
 * cut), nearest first, at most NEAR_CONES of them, into near_cone;
 * returns their count. */
static uint32_t nearest_cones(const steer_ws *w, const forest *F, near_entry *near_cone)
{
    const sq_mesh *m = w->m;
    uint32_t nnear = 0;
    for (uint32_t c = 0; c < m->nv; ++c) {
        if (!w->cone[c]) continue;
        double d = INFINITY;
        const uint32_t h0 = m->v_he[c];
        uint32_t h = h0;
        do {
            const uint32_t a = sq_cut_dest(m, h);
            if (is_free(w, a) && fdist(F, a) < d) d = fdist(F, a);
            h = sq_cut_rot(m, h);
        } while (h != h0);
        if (isfinite(d)) near_cone[nnear].c = c, near_cone[nnear++].d = d;
    }
    qsort(near_cone, nnear, sizeof *near_cone, near_cmp);
    return nnear > NEAR_CONES ? NEAR_CONES : nnear;
}

/* Detours of the side lo..hi through cone c's ring edges that move a cone
 * index not a multiple of 4 across the cut: per index the shortest, at
 * most 4, into cand (*nc). Both halves from the whole side (F[0]); if c is
 * seen from one side vertex x0 only, the halves from before and after x0
 * (F[1], F[2]). 0: out of memory. */
static int cone_detours(steer_ws *w, const sq_cut_graph *G, const int32_t *valence, forest *F, uint32_t c,
                        uint32_t lo, uint32_t hi, route_cand *cand, uint32_t *nc_out)
{
    uint32_t nc = 0, x0 = SQ_NONE;
    const sq_mesh *m = w->m;
    for (int pass = 0; pass < 2 && nc == 0; ++pass) {
        const forest *A = &F[0], *Bf = &F[0];
        if (pass == 1) {
            if (x0 == SQ_NONE || x0 <= lo || x0 >= hi) break;
            /* the halves, resumed where they are of this x0 on this cut */
            if (!(F[1].live && F[1].lo == lo && F[1].hi == x0) && !forest_start(w, G, lo, x0, &F[1])) return 0;
            if (!(F[2].live && F[2].lo == x0 + 1 && F[2].hi == hi) && !forest_start(w, G, x0 + 1, hi, &F[2]))
                return 0;
            if (!forest_grow(w, &F[1], c) || !forest_grow(w, &F[2], c)) return 0;
            A = &F[1], Bf = &F[2];
        }
        const uint32_t h0 = m->v_he[c];
        uint32_t h = h0;
        do {
            const uint32_t ring = m->he_next[h];
            h = sq_cut_rot(m, h);
            for (int dir = 0; dir < 2; ++dir) {
                const uint32_t ab = dir ? m->he_twin[ring] : ring;
                const uint32_t a = m->he_vert[ab], b = sq_cut_dest(m, ab);
                if (!is_free(w, a) || !is_free(w, b) || !isfinite(fdist(A, a)) || !isfinite(fdist(Bf, b)))
                    continue;
                if (pass == 0 && x0 == SQ_NONE) x0 = A->src[a];
                uint32_t na, nb;
                const uint32_t n = build_detour(w, A, Bf, ab, &na, &nb);
                if (!n) continue;
                int bad = 0;
                const long q = region_index(w, G, na, nb, valence, n, &bad);
                if (bad || q % 4 == 0) continue;
                const double len = fdist(A, a) + fdist(Bf, b) + w->len[ab];
                uint32_t dup = nc;
                for (uint32_t x = 0; x < nc; ++x)
                    if (cand[x].q == q) dup = x;
                if (dup < nc && len >= cand[dup].len) continue;
                if (dup == nc) {
                    if (nc == 4) continue;
                    ++nc;
                }
                cand[dup].ab = ab, cand[dup].len = len, cand[dup].q = q;
                cand[dup].pass = pass;
            }
        } while (h != h0);
    }
    *nc_out = nc;
    return 1;
}

/* Each candidate detour applied to a copy of G's side s; the one that lowers
 * the mismatch (below norm) the most, then the shortest, replaces *best
 * (*best_norm, *best_len, *best_shift: its mismatch, length and corner
 * shift). */
static void pick_detour(steer_ws *w, const sq_cut_graph *G, const double *turn, const uint8_t *blocked,
                        const forest *F, uint32_t s, const route_cand *cand, uint32_t nc, uint32_t norm,
                        sq_cut_graph *best, uint32_t *best_norm, double *best_len, uint32_t *best_shift)
{
    const sq_mesh *m = w->m;
    const uint8_t *cone = w->cone;
    for (uint32_t x = 0; x < nc; ++x) {
        const forest *A = cand[x].pass ? &F[1] : &F[0], *Bf = cand[x].pass ? &F[2] : &F[0];
        uint32_t na, nb;
        const uint32_t n = build_detour(w, A, Bf, cand[x].ab, &na, &nb);
        sq_cut_graph cg;
        sq_error e2;
        uint32_t d = 0;
        if (!n || apply_detour(m, G, s, na, nb, w->route, n, &cg, &d, &e2) != SQ_OK) {
            if (n) sq_cut_graph_free(&cg);
            continue;
        }
        mismatch M2;
        if (!compute_mismatch(m, &cg, turn, blocked, &M2)) {
            sq_cut_graph_free(&cg);
            continue;
        }
        const uint32_t nn = M2.norm;
        mismatch_free(&M2);
        /* the graph's check (linear in the mesh) only for a detour that
         * would win: the same choice as checking every one first */
        if (nn < norm && (nn < *best_norm || (nn == *best_norm && cand[x].len < *best_len)) &&
            sq_cut_graph_check(m, cone, &cg, &e2) == SQ_OK) {
            *best_norm = nn, *best_len = cand[x].len, *best_shift = d;
            sq_cut_graph_free(best);
            *best = cg;
        } else
            sq_cut_graph_free(&cg);
}
}

/* G back to the cut it came with (he_cut0, straight0, length). */
static sq_status restore_cut(const sq_mesh *m, sq_cut_graph *G, const uint8_t *he_cut0, const uint8_t *straight0,
                             double length, sq_error *err)
{
    memcpy(G->he_cut, he_cut0, m->nh);
    G->length = length;
    sq_status st = sq_cut_boundary_word(m, G, err);
    if (st) return st;
    G->rank = sq_pattern_rank(&G->pattern);
    memcpy(G->pattern.straight, straight0, G->pattern.k);
    return SQ_OK;
}

/* One round's search: every non-tree branch that must change, on both of
 * its sides; per side the detours around the nearest cones; the lowest
 * mismatch, then the shortest detour, into *best (pick_detour). 0 when out
 * of memory. */
static int best_detour(steer_ws *w, const sq_cut_graph *G, const int32_t *valence, const double *turn,
                       const uint8_t *blocked, const mismatch *M, forest F[3], near_entry *near_cone,
                       sq_cut_graph *best, uint32_t *best_norm, double *best_len, uint32_t *best_shift)
{
    route_cand cand[4];
    for (uint32_t t = 0; t < M->nfree; ++t) {
        if (!M->y[t]) continue;
        const uint32_t i = M->pair_side[M->free_pair[t]];
        const uint32_t sides[2] = {i, G->pattern.partner[i]};
        for (int si = 0; si < 2; ++si) {
            const uint32_t s = sides[si], lo = G->side_off[s], hi = G->side_off[s + 1];
            if (!forest_start(w, G, lo, hi, &F[0]) || !forest_grow(w, &F[0], SQ_NONE)) return 0;
            const uint32_t nnear = nearest_cones(w, &F[0], near_cone);
            for (uint32_t ci = 0; ci < nnear; ++ci) {
                const uint32_t c = near_cone[ci].c;
                uint32_t nc = 0;
                if (!cone_detours(w, G, valence, F, c, lo, hi, cand, &nc)) return 0;
                pick_detour(w, G, turn, blocked, F, s, cand, nc, M->norm, best, best_norm, best_len,
                            best_shift);
            }
        }
    }
    return 1;
}

sq_status sq_cut_graph_steer(const sq_mesh *m, const int32_t *valence, const double *turn,
                             sq_cut_graph *G, sq_cut_steer_stats *stats, sq_error *err)
{
    sq_cut_steer_stats S;
    memset(&S, 0, sizeof S);
    S.length_before = S.length_after = G->length;
    if (stats) *stats = S;
    if (G->genus < 1) return SQ_OK;
    sq_status st = SQ_OK;
    steer_ws w;
    memset(&w, 0, sizeof w);
    w.m = m;
    uint32_t ncones = 0;
    for (uint32_t v = 0; v < m->nv; ++v) ncones += valence[v] != 4;
    uint8_t *cone = calloc(m->nv, 1);
    w.cone = cone;
    w.cut = malloc(m->nh);
    w.cutdeg = malloc((size_t)m->nv * sizeof *w.cutdeg);
    w.near = malloc((size_t)m->nv * sizeof *w.near);
    w.len = malloc((size_t)m->nh * sizeof *w.len);
    forest F[3];
    memset(F, 0, sizeof F);
    int fok = 1;
    for (int f = 0; f < 3; ++f) {
        F[f].dist = malloc((size_t)m->nv * sizeof *F[f].dist);
        F[f].par = malloc((size_t)m->nv * sizeof *F[f].par);
        F[f].src = malloc((size_t)m->nv * sizeof *F[f].src);
        F[f].vis = calloc(m->nv, sizeof *F[f].vis);
        F[f].done = calloc(m->nv, sizeof *F[f].done);
        fok = fok && F[f].dist && F[f].par && F[f].src && F[f].vis && F[f].done &&
              sq_cut_heap_init(&F[f].heap, m->nv + 16);
    }
    near_entry *near_cone = malloc(((size_t)ncones + 1) * sizeof *near_cone);
    w.route = malloc(((size_t)m->nv + 2) * sizeof *w.route);
    w.mark = calloc(m->nv, sizeof *w.mark);
    w.fstack = malloc((size_t)m->nf * sizeof *w.fstack);
    w.fmark = calloc(m->nf, sizeof *w.fmark);
    uint8_t *blocked = calloc(m->nh, 1);
    uint8_t *he_cut0 = malloc(m->nh), *straight0 = malloc(G->pattern.k + 1);
    if (he_cut0) memcpy(he_cut0, G->he_cut, m->nh);
    if (straight0) memcpy(straight0, G->pattern.straight, G->pattern.k);
    mismatch M;
    memset(&M, 0, sizeof M);
    if (!cone || !blocked || !he_cut0 || !straight0 || !w.cut || !w.cutdeg || !w.near || !w.len || !fok ||
        !near_cone || !w.route || !w.mark || !w.fstack || !w.fmark) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (steer)");
        goto done;
    }
    double mean = 0.0;
    for (uint32_t h = 0; h < m->nh; ++h) mean += w.len[h] = sq_cut_he_length(m, h);
    w.penalty = PENALTY_EDGES * mean / m->nh;
    for (uint32_t v = 0; v < m->nv; ++v) cone[v] = valence[v] != 4;
    if (!compute_mismatch(m, G, turn, blocked, &M)) {
        /* no Z4 solution (the corner angles given do not fit the graph)
         * or no memory for it: G is left as it is, the mismatch unknown */
        S.norm_before = S.norm_after = UINT32_MAX;
        if (stats) *stats = S;
        goto done;
    }
    S.norm_before = M.norm;
    S.wrong_loops_before = M.wrong_loops;
    for (uint32_t round = 0; M.norm > 0 && round < 6 * G->genus; ++round) {
        /* the best detour of the round (best_detour) */
        uint32_t best_norm = M.norm, best_shift = 0;
        double best_len = INFINITY;
        sq_cut_graph best;
        sq_cut_graph_init(&best);
        /* G's cut and the counts next to it, once per round (the
         * candidates below leave w.cut as they found it) */
        memcpy(w.cut, G->he_cut, m->nh);
        ws_recount(&w);
        F[1].live = F[2].live = 0;
        if (!best_detour(&w, G, valence, turn, blocked, &M, F, near_cone, &best, &best_norm, &best_len,
                         &best_shift))
            goto nomem;
        if (best_norm >= M.norm) {
            sq_cut_graph_free(&best);
            /* no detour moves these branches: put them into the tree, so
             * that other branches carry the change, while that is new */
            uint32_t added = 0;
            for (uint32_t t = 0; t < M.nfree; ++t) {
                const uint32_t id = branch_id(m, G, M.pair_side[M.free_pair[t]]);
                if (M.y[t] && !blocked[id]) blocked[id] = 1, ++added;
            }
            if (!added) break;
            mismatch_free(&M);
            if (!compute_mismatch(m, G, turn, blocked, &M)) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the rotation mismatch has no Z4 solution");
                goto done;
            }
            continue;
        }
        sq_cut_graph_free(G);
        *G = best;
        S.reroutes++;
        S.corner_shift = (S.corner_shift + best_shift) % G->pattern.k;
        mismatch_free(&M);
        if (!compute_mismatch(m, G, turn, blocked, &M)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the rotation mismatch has no Z4 solution");
            goto done;
        }
    }
    goto finish;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (steer)");
    goto done;
finish:
    mismatch_free(&M);
    if (!compute_mismatch(m, G, turn, NULL, &M)) { /* the canonical tree's norm */
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the rotation mismatch has no Z4 solution");
        goto done;
    }
    if (M.norm > S.norm_before) {
        /* the detours' trees disagreed with the canonical one: worse than
         * the input by its measure, so the input is kept */
        st = restore_cut(m, G, he_cut0, straight0, S.length_before, err);
        if (st) goto done;
        S.reroutes = 0, S.corner_shift = 0;
        mismatch_free(&M);
        if (!compute_mismatch(m, G, turn, NULL, &M)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the rotation mismatch has no Z4 solution");
            goto done;
        }
    }
    S.norm_after = M.norm;
    S.wrong_loops_after = M.wrong_loops;
    S.length_after = G->length;
    if (stats) *stats = S;
done:
    mismatch_free(&M);
    free(cone), free(blocked), free(he_cut0), free(straight0), free(w.cut), free(w.cutdeg), free(w.near), free(w.len), free(near_cone);
    for (int f = 0; f < 3; ++f) {
        free(F[f].dist), free(F[f].par), free(F[f].src), free(F[f].vis), free(F[f].done);
        sq_cut_heap_free(&F[f].heap);
    }
    free(w.route), free(w.mark), free(w.fstack), free(w.fmark);
    return st;
}

sq_status sq_cut_graph_rotation_mismatch(const sq_mesh *m, const sq_cut_graph *G,
                                         const double *turn, uint32_t *norm, uint32_t *wrong_loops,
                                         sq_error *err)
{
    mismatch M;
    if (!compute_mismatch(m, G, turn, NULL, &M))
        return sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the rotation mismatch has no Z4 solution");
    if (norm) *norm = M.norm;
    if (wrong_loops) *wrong_loops = M.wrong_loops;
    mismatch_free(&M);
    return SQ_OK;
}
