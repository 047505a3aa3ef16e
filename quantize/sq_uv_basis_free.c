/* seamquad: the seamless maps with the rotations of a given map and free
 * translations, as an affine function of free unknowns (sq_uv_basis.h,
 * sq_uv_basis_free_translations).
 *
 * What: the space V of corner UVs such that across every seam edge the two
 * sides differ by the input's rotation R = i^r (a point is a complex number)
 * and SOME translation, and across every other edge they are equal. One
 * seam curve (a chain of seam edges between nodes, as in sq_map_snap.c)
 * then shares one translation, and around every vertex the transitions
 * compose to a map that fixes the vertex's point. The optimizer moves in V
 * before quantization (issue 24). The input must pass sq_map_check (else
 * SQ_ERR_ARGUMENT with its message).
 *
 * Construction (complex-linear: a complex unknown is a real pair, and a
 * complex coefficient a + ib gives the entries a, -b / b, a):
 *  - Wedges: the corners around a vertex joined by non-seam edges (one UV
 *    each). Unknowns: the wedge of every vertex on no seam; inside a curve,
 *    the wedge on the curve's own side (A); the translation t_c of every
 *    curve (A's chart to B's: B = R_c A + t_c); one wedge w_1 of every node
 *    whose transitions compose to a rotation R_v = I.
 *  - The B wedge inside a curve is R_c A + t_c (sparse).
 *  - At a node the wedges follow each other across the curves' ends:
 *    w_{j+1} = u_j w_j + s_j t_{c_j} (u_j, s_j units: the transition or its
 *    inverse). Going round gives w_1 = R_v w_1 + T_v(t). If R_v != I (a cone
 *    of valence 1, 2 or 3 mod 4) w_1 is the fixed point (1 - R_v)^-1 T_v.
 *    If R_v = I the curves' translations must satisfy T_v(t) = 0.
 *  - These node conditions are solved on a spanning tree of each component
 *    of the graph of nodes and curves, rooted at a node with R_v != I when
 *    there is one (sq_map_snap.c's tree): from the leaves, each node with
 *    R_v = I gives the translation of the curve to its parent (met once
 *    there: a unit coefficient) in terms of the others. Every coefficient
 *    so far is a Gaussian integer, computed exactly. A root with R_v = I
 *    leaves one condition on the remaining translations, with Gaussian
 *    integer coefficients too, so whether it vanishes identically is
 *    decided exactly (it does on a translation surface and at a closed
 *    chain's node); if not, it gives the curve with the largest
 *    coefficient. No rank is decided with a tolerance; a final pass checks
 *    that every node condition vanishes for all unknowns.
 *  - Gauge: translating one chart (faces joined by non-seam edges) changes
 *    no triangle's edge vectors; these are the only such directions in V,
 *    so they span the Hessian's null space for an energy that is definite
 *    on each triangle's edge vectors (Dirichlet), and no other linear
 *    gauge is left. One unknown per chart is pinned (kept constant at the
 *    input's value): the wedge of a vertex on no seam if the chart has one,
 *    else one inside a curve, else a node's w_1. A chart with none (every
 *    corner at a cone, as when each face is its own chart) pins a curve
 *    translation, chosen on the gain graph of such charts so that the
 *    pinned columns are independent: forests grown from curves that reach
 *    other charts, else a spanning tree plus an edge closing an unbalanced
 *    cycle.
 *    Not pinned: an energy invariant under rotation (symmetric Dirichlet)
 *    or scaling keeps the symmetry x -> p + a (x - p) (a complex, p the
 *    pinned point), which stays in V; at a critical point its Hessian is
 *    singular along i (x - p) (and along x - p if scale-invariant).
 *
 * Dimension: nz = 2 (nv - nodes + curves + K - charts), K the number of
 * roots whose condition vanishes. If every chart is a disk this is
 * 2 (nv + 2 genus - 2 + h), h = 1 for a translation surface (trivial
 * holonomy), else 0: the complex dimension of the flat metrics with these
 * cones and holonomy (2 genus + cones - 2 + h), plus the other vertices'
 * points, less the translation.
 *
 * Guarantees: every z gives a map with the input's rotations whose two
 * sides agree on every edge up to the rounding of the sums (corners of one
 * wedge: bit for bit, same row); every map of V, after one translation per
 * chart, is c + P z for exactly one z; z0 gives the input (up to
 * rounding). Rows list their columns in increasing order.
 *
 * Cost: O(halfedges) plus the curve translations' expressions (each: the
 * free translations of its subtree, which stops at cones; the B wedges of
 * a curve and a node's wedges repeat them). Time and memory are linear in
 * the entries; the published maps take at most 65 entries per row. */
#include "sq_uv_basis.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"
#include "sq_union_find.h"

#define NONE UINT32_MAX

/* ---- complex numbers (a UV point; rotations are units i^r) --------------- */

typedef struct cx {
    double re, im;
} cx;

static cx cx_make(double re, double im)
{
    cx z = {re, im};
    return z;
}
static cx cx_unit(int r)
{
    static const double c[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    return cx_make(c[r & 3][0], c[r & 3][1]);
}
static cx cx_mul(cx a, cx b)
{
    return cx_make(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}
static cx cx_add(cx a, cx b) { return cx_make(a.re + b.re, a.im + b.im); }
static cx cx_neg(cx a) { return cx_make(-a.re, -a.im); }
static cx cx_inv(cx a)
{
    double d = a.re * a.re + a.im * a.im;
    return cx_make(a.re / d, -a.im / d);
}
static double cx_norm2(cx a) { return a.re * a.re + a.im * a.im; }

/* ---- expressions: sparse complex combinations of the raw unknowns --------- */

typedef struct span {
    size_t off;
    uint32_t len;
} span;

typedef struct pool {
    uint32_t *col;
    cx *coef;
    size_t n, cap;
} pool;

/* sparse accumulator over the raw unknowns */
typedef struct spa {
    cx *acc;
    uint8_t *on;
    uint32_t *list;
    uint32_t n;
} spa;

/* one crossing of a seam edge while walking around a node: from wedge j to
 * wedge j+1, x -> i^rot x + s t_curve */
typedef struct crossing {
    uint32_t curve;
    int rot;
    cx s;
} crossing;

typedef struct ctx {
    const sq_map *M;
    const sq_mesh *m;
    const uint8_t *seam_in; /* nh or NULL: the seams given (not from M's      */
                        /* transitions, which are then starting values only)  */
    uint8_t *seam;      /* nh: the edge's sides differ                        */
    uint32_t *deg;      /* nv: seam edges at the vertex                       */
    uint8_t *rtot;      /* nv: rotation of the transitions around it          */
    uint8_t *node;      /* nv                                                 */
    uint32_t *v_start;  /* nv: first corner of the walk (a seam follows)      */
    uint32_t *wedge;    /* nh: wedge of the corner                            */
    uint32_t nw;
    uint32_t *w_he;     /* nw: a corner of the wedge                          */
    uint8_t *w_kind;    /* nw: 0 dependent; free: 1 no seam, 2 curve, 3 node  */
    uint32_t *w_col;    /* nw: raw unknown of a free wedge, else NONE         */
    span *w_expr;       /* nw                                                 */
    uint32_t *he_curve; /* nh: curve of the edge, NONE if not a seam          */
    int8_t *he_dir;     /* nh: +1 on the curve's own side, -1 on the other    */
    uint32_t nc;
    uint32_t *c_he;     /* nc: first own halfedge                             */
    uint32_t *c_end;    /* 2 nc                                               */
    uint8_t *c_dep;     /* nc: translation given by an expression             */
    uint8_t *c_done;    /* nc: expression computed                            */
    uint32_t *c_col;    /* nc: raw unknown of a free translation, else NONE   */
    span *c_expr;       /* nc                                                 */
    uint32_t nraw;
    cx *raw_val;        /* nraw: the input's value                            */
    uint32_t *raw_curve;/* nraw: the curve of a translation unknown, or NONE  */
    uint8_t *raw_dead;  /* nraw: eliminated after all (a root's condition)    */
    uint8_t *raw_pin;   /* nraw                                               */
    crossing *cr;       /* max degree: scratch of a node walk                 */
    uint32_t *cw;       /* max degree: wedges of a node walk                  */
    int *cpre;          /* max degree + 1: prefix sums of the rotations       */
    pool P;
    spa S;
} ctx;

static int pool_push(pool *P, uint32_t col, cx a)
{
    if (P->n == P->cap) {
        size_t cap = P->cap ? 2 * P->cap : 1024;
        uint32_t *c = realloc(P->col, cap * sizeof *c);
        if (!c) return -1;
        P->col = c;
        cx *k = realloc(P->coef, cap * sizeof *k);
        if (!k) return -1;
        P->coef = k;
        P->cap = cap;
    }
    P->col[P->n] = col;
    P->coef[P->n] = a;
    P->n++;
    return 0;
}

static void spa_add(spa *S, uint32_t col, cx a)
{
    if (!S->on[col]) {
        S->on[col] = 1;
        S->acc[col] = a;
        S->list[S->n++] = col;
    } else {
        S->acc[col] = cx_add(S->acc[col], a);
    }
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Appends the accumulated combination (columns increasing, exact zeros
 * dropped) to the pool and clears the accumulator. */
static int spa_flush(ctx *X, span *out)
{
    spa *S = &X->S;
    qsort(S->list, S->n, sizeof *S->list, cmp_u32);
    out->off = X->P.n;
    out->len = 0;
    int bad = 0;
    for (uint32_t k = 0; k < S->n; k++) {
        uint32_t col = S->list[k];
        cx a = S->acc[col];
        S->on[col] = 0;
        if (bad || (a.re == 0.0 && a.im == 0.0)) continue;
        if (pool_push(&X->P, col, a)) bad = 1;
        else out->len++;
    }
    S->n = 0;
    return bad ? -1 : 0;
}

/* a * t_c */
static void add_curve(ctx *X, uint32_t c, cx a)
{
    if (X->c_col[c] != NONE) {
        spa_add(&X->S, X->c_col[c], a);
        return;
    }
    assert(X->c_done[c]);
    span e = X->c_expr[c];
    for (uint32_t k = 0; k < e.len; k++)
        spa_add(&X->S, X->P.col[e.off + k], cx_mul(a, X->P.coef[e.off + k]));
}

/* The crossings around node v, from the chart of its first corner: cr[j]
 * leads from wedge cw[j] to wedge cw[j+1] (cw[d] = cw[0]); cpre[j] the
 * rotation accumulated before crossing j. Returns d = deg[v]. */
static uint32_t node_walk(ctx *X, uint32_t v)
{
    const sq_mesh *m = X->m;
    uint32_t h0 = X->v_start[v], h = h0, d = 0;
    X->cw[0] = X->wedge[h0];
    X->cpre[0] = 0;
    do {
        uint32_t n = sq_map_rotate_out(m, h);
        if (X->seam[n]) {
            uint32_t e = sq_map_prev(m, h);
            crossing *C = &X->cr[d];
            C->curve = X->he_curve[e];
            C->rot = X->M->he_rot[e];
            /* own side: x -> R x + t; other side: the inverse,
             * x -> R^-1 x - R^-1 t with R^-1 = i^he_rot[e] */
            C->s = X->he_dir[e] > 0 ? cx_make(1, 0) : cx_neg(cx_unit(C->rot));
            X->cpre[d + 1] = (X->cpre[d] + C->rot) & 3;
            d++;
            if (n != h0) X->cw[d] = X->wedge[n];
        }
        h = n;
    } while (h != h0);
    assert(d == X->deg[v]);
    return d;
}

/* coefficient of t_{cr[k]} in the composite from wedge 0 to wedge j (k < j) */
static cx walk_coef(const ctx *X, uint32_t k, uint32_t j)
{
    return cx_mul(cx_unit(X->cpre[j] - X->cpre[k + 1]), X->cr[k].s);
}

/* ---- steps ------------------------------------------------------------------ */

/* Seams, seam degrees, rotations around vertices, nodes, wedges. */
static void find_wedges(ctx *X)
{
    const sq_map *M = X->M;
    const sq_mesh *m = X->m;
    for (uint32_t h = 0; h < m->nh; h++) {
        X->seam[h] = X->seam_in ? X->seam_in[h] != 0
                                : M->he_rot[h] != 0 || M->he_t[2 * (size_t)h] != 0.0 ||
                                      M->he_t[2 * (size_t)h + 1] != 0.0;
        X->deg[m->he_vert[h]] += X->seam[h];
    }
    X->nw = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], h = h0, start = h0;
        int r = 0;
        do {
            r += M->he_rot[sq_map_prev(m, h)];
            if (X->seam[h] && start == h0 && !X->seam[h0]) start = h;
            h = sq_map_rotate_out(m, h);
        } while (h != h0);
        X->rtot[v] = (uint8_t)(r & 3);
        X->node[v] = X->deg[v] > 0 && (X->deg[v] != 2 || X->rtot[v] != 0 || M->valence[v] != 4);
        X->v_start[v] = start;
        h = start;
        do {
            if (h == start || X->seam[h]) X->w_he[X->nw++] = h;
            X->wedge[h] = X->nw - 1;
            h = sq_map_rotate_out(m, h);
        } while (h != start);
    }
}

/* Seam curves, as sq_map_snap.c walks them: from nodes, then closed chains
 * (one of whose vertices becomes a node). */
static sq_status find_curves(ctx *X, sq_error *err)
{
    const sq_map *M = X->M;
    const sq_mesh *m = X->m;
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t h0 = 0; h0 < m->nh; h0++) {
            if (!X->seam[h0] || X->he_curve[h0] != NONE) continue;
            uint32_t a = m->he_vert[h0];
            if (pass == 0 && !X->node[a]) continue;
            if (pass == 1) X->node[a] = 1; /* closed chain: deg 2, R = I */
            uint32_t c = X->nc++, h = h0;
            X->c_he[c] = h0;
            X->c_end[2 * (size_t)c] = a;
            for (;;) {
                uint32_t g = m->he_twin[h];
                X->he_curve[h] = X->he_curve[g] = c;
                X->he_dir[h] = 1;
                X->he_dir[g] = -1;
                const double *t = M->he_t + 2 * (size_t)h, *t0 = M->he_t + 2 * (size_t)h0;
                if (M->he_rot[h] != M->he_rot[h0] || (!X->seam_in && (t[0] != t0[0] || t[1] != t0[1])))
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "free-translation basis: the seam curve from vertex %u "
                                        "changes its transition at edge (%u, %u)",
                                        a, m->he_vert[h], sq_map_dst(m, h));
                uint32_t b = sq_map_dst(m, h);
                if (X->node[b]) {
                    X->c_end[2 * (size_t)c + 1] = b;
                    break;
                }
                uint32_t n = m->he_next[h], k = n, next = NONE;
                do {
                    if (X->seam[k] && k != g) next = k;
                    k = sq_map_rotate_out(m, k);
                } while (k != n);
                if (next == NONE || X->he_curve[next] != NONE)
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "free-translation basis: vertex %u has two seam edges but "
                                        "its chain does not continue",
                                        b);
                h = next;
            }
        }
    return SQ_OK;
}

/* Spanning trees of the graph of nodes and curves (roots with R != I
 * first); order[] lists the nodes by component, parents first. */
static sq_status node_trees(ctx *X, uint32_t *order, uint32_t *parent, uint32_t *comp_off,
                            uint32_t *ncomp, uint32_t *norder, sq_error *err)
{
    const sq_mesh *m = X->m;
    uint32_t nv = m->nv;
    uint32_t *adj_off = calloc((size_t)nv + 1, sizeof *adj_off);
    uint32_t *adj = malloc((2 * (size_t)X->nc + 1) * sizeof *adj);
    uint8_t *seen = calloc((size_t)nv + 1, 1);
    if (!adj_off || !adj || !seen) {
        free(adj_off), free(adj), free(seen);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam node trees)");
    }
    for (uint32_t c = 0; c < X->nc; c++) {
        uint32_t a = X->c_end[2 * (size_t)c], b = X->c_end[2 * (size_t)c + 1];
        if (a != b) adj_off[a + 1]++, adj_off[b + 1]++;
    }
    for (uint32_t v = 0; v < nv; v++) adj_off[v + 1] += adj_off[v];
    for (uint32_t c = 0; c < X->nc; c++) { /* fill, then shift back */
        uint32_t a = X->c_end[2 * (size_t)c], b = X->c_end[2 * (size_t)c + 1];
        if (a != b) adj[adj_off[a]++] = c, adj[adj_off[b]++] = c;
    }
    for (uint32_t v = nv; v > 0; v--) adj_off[v] = adj_off[v - 1];
    adj_off[0] = 0;
    uint32_t no = 0, nk = 0;
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t v0 = 0; v0 < nv; v0++) {
            if (!X->node[v0] || seen[v0] || (pass == 0 && X->rtot[v0] == 0)) continue;
            uint32_t head = no;
            comp_off[nk++] = no;
            seen[v0] = 1;
            parent[v0] = NONE;
            order[no++] = v0;
            while (head < no) {
                uint32_t v = order[head++];
                for (uint32_t k = adj_off[v]; k < adj_off[v + 1]; k++) {
                    uint32_t c = adj[k];
                    uint32_t w = X->c_end[2 * (size_t)c] == v ? X->c_end[2 * (size_t)c + 1]
                                                              : X->c_end[2 * (size_t)c];
                    if (seen[w]) continue;
                    seen[w] = 1;
                    parent[w] = c;
                    order[no++] = w;
                }
            }
        }
    comp_off[nk] = no;
    *ncomp = nk;
    *norder = no;
    free(adj_off);
    free(adj);
    free(seen);
    return SQ_OK;
}

/* The free unknowns before the conditions at roots: free wedges, then the
 * translations of the curves no tree condition gives. */
static sq_status raw_unknowns(ctx *X, sq_error *err)
{
    const sq_map *M = X->M;
    const sq_mesh *m = X->m;
    uint32_t n = 0;
    for (uint32_t w = 0; w < X->nw; w++) X->w_col[w] = NONE;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t w = X->wedge[X->v_start[v]];
        if (X->deg[v] == 0) X->w_kind[w] = 1;
        else if (X->node[v] && X->rtot[v] == 0) X->w_kind[w] = 3;
    }
    for (uint32_t c = 0; c < X->nc; c++)
        for (uint32_t h = X->c_he[c];;) { /* inside vertices: the own side */
            if (X->node[sq_map_dst(m, h)]) break;
            X->w_kind[X->wedge[m->he_next[h]]] = 2;
            uint32_t k = m->he_next[h], g = m->he_twin[h];
            while (!(X->seam[k] && k != g)) k = sq_map_rotate_out(m, k);
            h = k;
        }
    for (uint32_t w = 0; w < X->nw; w++)
        if (X->w_kind[w]) X->w_col[w] = n++;
    for (uint32_t c = 0; c < X->nc; c++) X->c_col[c] = X->c_dep[c] ? NONE : n++;
    X->nraw = n;
    size_t sz = (size_t)n + 1;
    X->raw_val = malloc(sz * sizeof *X->raw_val);
    X->raw_curve = malloc(sz * sizeof *X->raw_curve);
    X->raw_dead = calloc(sz, 1);
    X->raw_pin = calloc(sz, 1);
    X->S.acc = malloc(sz * sizeof *X->S.acc);
    X->S.on = calloc(sz, 1);
    X->S.list = malloc(sz * sizeof *X->S.list);
    if (!X->raw_val || !X->raw_curve || !X->raw_dead || !X->raw_pin || !X->S.acc || !X->S.on ||
        !X->S.list)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (%u basis unknowns)", n);
    for (uint32_t w = 0; w < X->nw; w++)
        if (X->w_col[w] != NONE) {
            const double *p = M->he_uv + 2 * (size_t)X->w_he[w];
            X->raw_val[X->w_col[w]] = cx_make(p[0], p[1]);
            X->raw_curve[X->w_col[w]] = NONE;
        }
    for (uint32_t c = 0; c < X->nc; c++)
        if (X->c_col[c] != NONE) {
            const double *t = M->he_t + 2 * (size_t)X->c_he[c];
            X->raw_val[X->c_col[c]] = cx_make(t[0], t[1]);
            X->raw_curve[X->c_col[c]] = c;
        }
    return SQ_OK;
}

/* Tree conditions, leaves first: at a node with R = I (not a root), the
 * composite translation vanishes; solved for its parent curve's t. */
static sq_status solve_trees(ctx *X, const uint32_t *order, const uint32_t *parent, uint32_t norder,
                             sq_error *err)
{
    for (uint32_t i = norder; i-- > 0;) {
        uint32_t v = order[i], p = parent[v];
        if (p == NONE || X->rtot[v] != 0) continue;
        uint32_t d = node_walk(X, v), kp = NONE;
        for (uint32_t k = 0; k < d; k++)
            if (X->cr[k].curve == p) {
                assert(kp == NONE); /* the parent curve ends here once */
                kp = k;
            }
        assert(kp != NONE);
        cx inv = cx_neg(cx_inv(walk_coef(X, kp, d))); /* a unit: exact */
        for (uint32_t k = 0; k < d; k++)
            if (k != kp) add_curve(X, X->cr[k].curve, cx_mul(inv, walk_coef(X, k, d)));
        if (spa_flush(X, &X->c_expr[p]))
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam curve translations)");
        X->c_done[p] = 1;
    }
    return SQ_OK;
}

/* A root with R = I: its condition on the remaining translations, if not
 * identically zero, gives the curve with the largest coefficient; the
 * component's tree translations that used it are rewritten. */
static sq_status solve_root(ctx *X, uint32_t r, const uint32_t *order, const uint32_t *parent,
                            uint32_t lo, uint32_t hi, sq_error *err)
{
    uint32_t d = node_walk(X, r);
    span E;
    for (uint32_t k = 0; k < d; k++) add_curve(X, X->cr[k].curve, walk_coef(X, k, d));
    if (spa_flush(X, &E)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam nodes)");
    if (!E.len) return SQ_OK;
    uint32_t best = 0;
    for (uint32_t k = 1; k < E.len; k++)
        if (cx_norm2(X->P.coef[E.off + k]) > cx_norm2(X->P.coef[E.off + best])) best = k;
    uint32_t col = X->P.col[E.off + best], c = X->raw_curve[col];
    assert(c != NONE); /* only translations enter a node's condition */
    cx inv = cx_neg(cx_inv(X->P.coef[E.off + best]));
    for (uint32_t k = 0; k < E.len; k++)
        if (k != best) spa_add(&X->S, X->P.col[E.off + k], cx_mul(inv, X->P.coef[E.off + k]));
    if (spa_flush(X, &X->c_expr[c]))
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam curve translations)");
    X->c_col[c] = NONE;
    X->c_dep[c] = X->c_done[c] = 1;
    X->raw_dead[col] = 1;
    /* the component's tree translations that used t_c */
    for (uint32_t i = lo; i < hi; i++) {
        uint32_t p = parent[order[i]];
        if (p == NONE || !X->c_dep[p] || p == c) continue;
        span e = X->c_expr[p];
        int uses = 0;
        for (uint32_t k = 0; k < e.len && !uses; k++) uses = X->P.col[e.off + k] == col;
        if (!uses) continue;
        for (uint32_t k = 0; k < e.len; k++) {
            uint32_t j = X->P.col[e.off + k];
            if (j == col) add_curve(X, c, X->P.coef[e.off + k]);
            else spa_add(&X->S, j, X->P.coef[e.off + k]);
        }
        if (spa_flush(X, &X->c_expr[p]))
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam curve translations)");
    }
    return SQ_OK;
}

/* Every node condition with R = I must now vanish identically (exactly in
 * the tree's Gaussian integers; up to rounding where a root's condition was
 * divided): a check of the elimination, not a tolerance that decides it. */
static sq_status verify_nodes(ctx *X, sq_error *err)
{
    const sq_mesh *m = X->m;
    for (uint32_t v = 0; v < m->nv; v++) {
        if (!X->node[v] || X->rtot[v] != 0) continue;
        uint32_t d = node_walk(X, v);
        for (uint32_t k = 0; k < d; k++) add_curve(X, X->cr[k].curve, walk_coef(X, k, d));
        double worst = 0;
        for (uint32_t k = 0; k < X->S.n; k++) {
            uint32_t col = X->S.list[k];
            double a = cx_norm2(X->S.acc[col]);
            worst = a > worst ? a : worst;
            X->S.on[col] = 0;
        }
        X->S.n = 0;
        if (!(worst <= 1e-18))
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "free-translation basis: the seams around vertex %u do not close "
                                "for every translation (coefficient %.3g)",
                                v, sqrt(worst));
    }
    return SQ_OK;
}

/* Every wedge's expression. */
static sq_status wedge_exprs(ctx *X, sq_error *err)
{
    const sq_mesh *m = X->m;
    for (uint32_t w = 0; w < X->nw; w++)
        if (X->w_kind[w] == 1 || X->w_kind[w] == 2) {
            spa_add(&X->S, X->w_col[w], cx_make(1, 0));
            if (spa_flush(X, &X->w_expr[w])) goto oom;
        }
    /* inside curves: B = R A + t */
    for (uint32_t c = 0; c < X->nc; c++) {
        int r = X->M->he_rot[X->c_he[c]];
        for (uint32_t h = X->c_he[c];;) {
            if (X->node[sq_map_dst(m, h)]) break;
            uint32_t A = X->wedge[m->he_next[h]], B = X->wedge[m->he_twin[h]];
            assert(X->w_kind[A] == 2 && X->w_kind[B] == 0);
            spa_add(&X->S, X->w_col[A], cx_unit(r));
            add_curve(X, c, cx_make(1, 0));
            if (spa_flush(X, &X->w_expr[B])) goto oom;
            uint32_t k = m->he_next[h], g = m->he_twin[h];
            while (!(X->seam[k] && k != g)) k = sq_map_rotate_out(m, k);
            h = k;
        }
    }
    /* nodes: w_j = rho_j w_1 + tau_j */
    for (uint32_t v = 0; v < m->nv; v++) {
        if (!X->node[v]) continue;
        uint32_t d = node_walk(X, v);
        cx kappa = cx_make(0, 0); /* cone: w_1 = kappa T */
        if (X->rtot[v] != 0) kappa = cx_inv(cx_add(cx_make(1, 0), cx_neg(cx_unit(X->rtot[v]))));
        for (uint32_t j = 0; j < d; j++) {
            cx rho = cx_unit(X->cpre[j]);
            if (X->rtot[v] == 0) {
                spa_add(&X->S, X->w_col[X->cw[0]], rho);
            } else {
                for (uint32_t k = 0; k < d; k++)
                    add_curve(X, X->cr[k].curve, cx_mul(cx_mul(rho, kappa), walk_coef(X, k, d)));
            }
            for (uint32_t k = 0; k < j; k++) add_curve(X, X->cr[k].curve, walk_coef(X, k, j));
            if (spa_flush(X, &X->w_expr[X->cw[j]])) goto oom;
        }
    }
    return SQ_OK;
oom:
    return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (basis rows)");
}

/* One pinned unknown per chart (see the top). */
static sq_status pin_charts(ctx *X, sq_error *err)
{
    const sq_mesh *m = X->m;
    sq_status st = SQ_OK;
    uint32_t nf = m->nf, K = 0, nq = 0;
    size_t sz = (size_t)nf + 1;
    uint32_t *chart = malloc(sz * sizeof *chart); /* face -> chart index      */
    uint32_t *wpin = malloc(sz * sizeof *wpin);   /* chart -> free wedge      */
    uint32_t *cpin = malloc(sz * sizeof *cpin);   /* chart -> pinned curve    */
    uint32_t *queue = malloc(sz * sizeof *queue);
    cx *pot = malloc(sz * sizeof *pot);
    uint32_t *eoff = calloc(sz + 1, sizeof *eoff);
    uint32_t *elist = malloc((2 * (size_t)X->nc + 1) * sizeof *elist);
    if (!chart || !wpin || !cpin || !queue || !pot || !eoff || !elist) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (charts)");
        goto done;
    }
    sq_uf_init(chart, nf);
    for (uint32_t h = 0; h < m->nh; h++)
        if (!X->seam[h]) sq_uf_union(chart, m->he_face[h], m->he_face[m->he_twin[h]]);
    for (uint32_t f = 0; f < nf; f++) chart[f] = sq_uf_find(chart, f);
    for (uint32_t f = 0; f < nf; f++) /* a root is its set's smallest face */
        chart[f] = chart[f] == f ? K++ : chart[chart[f]];
    for (uint32_t C = 0; C < K; C++) wpin[C] = cpin[C] = NONE;
    /* a free wedge per chart, by preference of kind */
    for (uint32_t w = 0; w < X->nw; w++) {
        if (!X->w_kind[w]) continue;
        uint32_t C = chart[m->he_face[X->w_he[w]]];
        if (wpin[C] == NONE || X->w_kind[w] < X->w_kind[wpin[C]]) wpin[C] = w;
    }
    uint32_t lacking = 0;
    for (uint32_t C = 0; C < K; C++) {
        if (wpin[C] != NONE) X->raw_pin[X->w_col[wpin[C]]] = 1;
        else lacking++;
    }
    if (!lacking) goto done;
    /* Charts without a free wedge (all corners at cones): a free curve
     * translation moves with chart C's translation tau by +tau if C is its
     * B side, -R_c tau if its A side. Roots: curves that touch one such
     * chart only (or loop on one with R_c != I); edges: curves between two */
#define SIDE_A(c) chart[m->he_face[X->c_he[c]]]
#define SIDE_B(c) chart[m->he_face[m->he_twin[X->c_he[c]]]]
#define LACKS(C) (wpin[C] == NONE)
    for (uint32_t c = 0; c < X->nc; c++) {
        if (X->c_col[c] == NONE) continue;
        uint32_t A = SIDE_A(c), B = SIDE_B(c), root = NONE;
        if (A == B) {
            if (LACKS(A) && X->M->he_rot[X->c_he[c]] != 0) root = A;
        } else if (LACKS(A) != LACKS(B)) {
            root = LACKS(A) ? A : B;
        } else if (LACKS(A)) {
            eoff[A + 2]++, eoff[B + 2]++;
        }
        if (root != NONE && cpin[root] == NONE) cpin[root] = c, queue[nq++] = root;
    }
    for (uint32_t C = 0; C < K; C++) eoff[C + 2] += eoff[C + 1];
    for (uint32_t c = 0; c < X->nc; c++) {
        if (X->c_col[c] == NONE) continue;
        uint32_t A = SIDE_A(c), B = SIDE_B(c);
        if (A != B && LACKS(A) && LACKS(B)) elist[eoff[A + 1]++] = c, elist[eoff[B + 1]++] = c;
    }
    /* eoff[C] .. eoff[C+1]: chart C's edges. Forests grown from the roots
     * (pass 0); each remaining component: a spanning tree with potentials
     * y_B = R_c y_A and one edge that breaks them (pass 1). Either way the
     * pinned columns, ordered as reached, are triangular or unicyclic and
     * unbalanced: independent. */
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t C0 = 0; C0 < (pass ? K : 1); C0++) {
            uint32_t start = 0;
            if (pass == 1) {
                if (!LACKS(C0) || cpin[C0] != NONE) continue;
                start = nq;
                queue[nq++] = C0;
                pot[C0] = cx_make(1, 0);
            }
            for (uint32_t head = start; head < nq; head++) {
                uint32_t C = queue[head];
                for (uint32_t k = eoff[C]; k < eoff[C + 1]; k++) {
                    uint32_t c = elist[k], A = SIDE_A(c), B = SIDE_B(c), D = A == C ? B : A;
                    if (cpin[D] != NONE || (pass == 1 && D == C0)) continue;
                    cpin[D] = c;
                    if (pass == 1) {
                        cx R = cx_unit(X->M->he_rot[X->c_he[c]]);
                        pot[D] = D == B ? cx_mul(R, pot[C]) : cx_mul(cx_inv(R), pot[C]);
                    }
                    queue[nq++] = D;
                }
            }
            if (pass == 0) continue;
            for (uint32_t q = start; q < nq && cpin[C0] == NONE; q++)
                for (uint32_t k = eoff[queue[q]]; k < eoff[queue[q] + 1]; k++) {
                    uint32_t c = elist[k];
                    cx y = cx_mul(cx_unit(X->M->he_rot[X->c_he[c]]), pot[SIDE_A(c)]);
                    if (y.re != pot[SIDE_B(c)].re || y.im != pot[SIDE_B(c)].im) {
                        cpin[C0] = c;
                        break;
                    }
                }
            if (cpin[C0] == NONE) {
                uint32_t f = 0;
                while (chart[f] != C0) f++;
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "free-translation basis: the translation of the chart of face "
                                  "%u cannot be pinned (no free unknown moves it alone)",
                                  f);
                goto done;
            }
        }
    for (uint32_t C = 0; C < K; C++)
        if (LACKS(C)) {
            assert(cpin[C] != NONE && !X->raw_pin[X->c_col[cpin[C]]]);
            X->raw_pin[X->c_col[cpin[C]]] = 1;
        }
#undef SIDE_A
#undef SIDE_B
#undef LACKS
done:
    free(chart);
    free(wpin);
    free(cpin);
    free(queue);
    free(pot);
    free(eoff);
    free(elist);
    return st;
}

/* he_uv rows from the wedges' expressions, pinned unknowns as constants. */
static sq_status emit(ctx *X, sq_uv_basis *out, sq_error *err)
{
    const sq_mesh *m = X->m;
    uint32_t *fcol = malloc(((size_t)X->nraw + 1) * sizeof *fcol);
    if (!fcol) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (basis columns)");
    uint32_t nz = 0;
    for (uint32_t j = 0; j < X->nraw; j++) fcol[j] = X->raw_dead[j] || X->raw_pin[j] ? NONE : nz++;
    out->nz = 2 * nz;
    out->ncoord = 2 * m->nh;
    size_t nnz = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        span e = X->w_expr[X->wedge[h]];
        for (uint32_t k = 0; k < e.len; k++) {
            cx a = X->P.coef[e.off + k];
            if (fcol[X->P.col[e.off + k]] != NONE) nnz += 2 * ((a.re != 0.0) + (a.im != 0.0));
        }
    }
    if (nnz > UINT32_MAX) {
        free(fcol);
        return sq_error_set(err, SQ_ERR_NOMEM,
                            "free-translation basis: %zu entries, more than 2^32", nnz);
    }
    out->row_off = malloc(((size_t)out->ncoord + 1) * sizeof *out->row_off);
    out->col = malloc((nnz + 1) * sizeof *out->col);
    out->val = malloc((nnz + 1) * sizeof *out->val);
    out->c = malloc(((size_t)out->ncoord + 1) * sizeof *out->c);
    out->z0 = malloc(((size_t)out->nz + 1) * sizeof *out->z0);
    if (!out->row_off || !out->col || !out->val || !out->c || !out->z0) {
        free(fcol);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (basis of %u halfedges)", m->nh);
    }
    for (uint32_t j = 0; j < X->nraw; j++)
        if (fcol[j] != NONE) {
            out->z0[2 * (size_t)fcol[j]] = X->raw_val[j].re;
            out->z0[2 * (size_t)fcol[j] + 1] = X->raw_val[j].im;
        }
    uint32_t n = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        span e = X->w_expr[X->wedge[h]];
        cx c0 = cx_make(0, 0);
        for (int axis = 0; axis < 2; axis++) {
            out->row_off[2 * (size_t)h + axis] = n;
            for (uint32_t k = 0; k < e.len; k++) {
                uint32_t j = X->P.col[e.off + k];
                cx a = X->P.coef[e.off + k];
                assert(!X->raw_dead[j]);
                if (fcol[j] == NONE) {
                    if (axis == 0) c0 = cx_add(c0, cx_mul(a, X->raw_val[j]));
                    continue;
                }
                /* re: a.re x - a.im y; im: a.im x + a.re y */
                double vx = axis == 0 ? a.re : a.im, vy = axis == 0 ? -a.im : a.re;
                if (vx != 0.0) out->col[n] = 2 * fcol[j], out->val[n++] = vx;
                if (vy != 0.0) out->col[n] = 2 * fcol[j] + 1, out->val[n++] = vy;
            }
        }
        out->c[2 * (size_t)h] = c0.re;
        out->c[2 * (size_t)h + 1] = c0.im;
    }
    out->row_off[out->ncoord] = n;
    assert(n == nnz);
    free(fcol);
    return SQ_OK;
}

static sq_status build(const sq_map *M, const uint8_t *seam_in, sq_uv_basis *out, sq_error *err);

sq_status sq_uv_basis_free_translations(const sq_map *M, sq_uv_basis *out, sq_error *err)
{
    if (!M || !out)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_uv_basis_free_translations: NULL argument");
    memset(out, 0, sizeof *out);
    sq_error tmp;
    if (sq_map_check(M, 0, &tmp))
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "sq_uv_basis_free_translations: the map is not a valid exact seamless "
                            "map: %s",
                            tmp.msg);
    return build(M, NULL, out, err);
}

sq_status sq_uv_basis_free_translations_seams(const sq_map *M, const uint8_t *seam, sq_uv_basis *out,
                                              sq_error *err)
{
    if (!M || !seam || !out)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_uv_basis_free_translations_seams: NULL argument");
    memset(out, 0, sizeof *out);
    return build(M, seam, out, err);
}

static sq_status build(const sq_map *M, const uint8_t *seam_in, sq_uv_basis *out, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    if (m->nh > UINT32_MAX / 2 - 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "sq_uv_basis_free_translations: %u halfedges, too many for 32-bit rows",
                            m->nh);
    ctx X;
    memset(&X, 0, sizeof X);
    X.M = M;
    X.m = m;
    X.seam_in = seam_in;
    size_t nh = m->nh, nv = m->nv;
    X.seam = malloc(nh + 1);
    X.deg = calloc(nv + 1, sizeof *X.deg);
    X.rtot = malloc(nv + 1);
    X.node = malloc(nv + 1);
    X.v_start = malloc((nv + 1) * sizeof *X.v_start);
    X.wedge = malloc((nh + 1) * sizeof *X.wedge);
    X.w_he = malloc((nh + 1) * sizeof *X.w_he);
    X.w_kind = calloc(nh + 1, 1);
    X.w_col = malloc((nh + 1) * sizeof *X.w_col);
    X.w_expr = calloc(nh + 1, sizeof *X.w_expr);
    X.he_curve = malloc((nh + 1) * sizeof *X.he_curve);
    X.he_dir = calloc(nh + 1, 1);
    X.c_he = malloc((nh / 2 + 1) * sizeof *X.c_he);
    X.c_end = malloc((nh + 2) * sizeof *X.c_end);
    X.c_dep = calloc(nh / 2 + 1, 1);
    X.c_done = calloc(nh / 2 + 1, 1);
    X.c_col = malloc((nh / 2 + 1) * sizeof *X.c_col);
    X.c_expr = calloc(nh / 2 + 1, sizeof *X.c_expr);
    uint32_t *order = malloc((nv + 1) * sizeof *order);
    uint32_t *parent = malloc((nv + 1) * sizeof *parent);
    uint32_t *comp_off = malloc((nv + 2) * sizeof *comp_off);
    sq_status st = SQ_OK;
    if (!X.seam || !X.deg || !X.rtot || !X.node || !X.v_start || !X.wedge || !X.w_he || !X.w_kind ||
        !X.w_col || !X.w_expr || !X.he_curve || !X.he_dir || !X.c_he || !X.c_end || !X.c_dep ||
        !X.c_done || !X.c_col || !X.c_expr || !order || !parent || !comp_off) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (basis of %u halfedges)", m->nh);
        goto done;
    }
    for (size_t h = 0; h < nh; h++) X.he_curve[h] = NONE;
    find_wedges(&X);
    if ((st = find_curves(&X, err))) goto done;
    uint32_t maxdeg = 1;
    for (size_t v = 0; v < nv; v++) maxdeg = X.deg[v] > maxdeg ? X.deg[v] : maxdeg;
    X.cr = malloc(((size_t)maxdeg + 1) * sizeof *X.cr);
    X.cw = malloc(((size_t)maxdeg + 1) * sizeof *X.cw);
    X.cpre = malloc(((size_t)maxdeg + 2) * sizeof *X.cpre);
    if (!X.cr || !X.cw || !X.cpre) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam nodes)");
        goto done;
    }
    uint32_t ncomp = 0, norder = 0;
    if ((st = node_trees(&X, order, parent, comp_off, &ncomp, &norder, err))) goto done;
    for (uint32_t i = 0; i < norder; i++) {
        uint32_t v = order[i];
        if (parent[v] != NONE && X.rtot[v] == 0) X.c_dep[parent[v]] = 1;
    }
    if ((st = raw_unknowns(&X, err))) goto done;
    if ((st = solve_trees(&X, order, parent, norder, err))) goto done;
    for (uint32_t k = 0; k < ncomp; k++) {
        uint32_t r = order[comp_off[k]];
        if (X.rtot[r] != 0) continue;
        if ((st = solve_root(&X, r, order, parent, comp_off[k], comp_off[k + 1], err))) goto done;
    }
    if ((st = verify_nodes(&X, err))) goto done;
    if ((st = wedge_exprs(&X, err))) goto done;
    if ((st = pin_charts(&X, err))) goto done;
    st = emit(&X, out, err);
done:
    if (st) sq_uv_basis_free(out);
    free(X.seam);
    free(X.deg);
    free(X.rtot);
    free(X.node);
    free(X.v_start);
    free(X.wedge);
    free(X.w_he);
    free(X.w_kind);
    free(X.w_col);
    free(X.w_expr);
    free(X.he_curve);
    free(X.he_dir);
    free(X.c_he);
    free(X.c_end);
    free(X.c_dep);
    free(X.c_done);
    free(X.c_col);
    free(X.c_expr);
    free(X.raw_val);
    free(X.raw_curve);
    free(X.raw_dead);
    free(X.raw_pin);
    free(X.cr);
    free(X.cw);
    free(X.cpre);
    free(X.P.col);
    free(X.P.coef);
    free(X.S.acc);
    free(X.S.on);
    free(X.S.list);
    free(order);
    free(parent);
    free(comp_off);
    return st;
}
