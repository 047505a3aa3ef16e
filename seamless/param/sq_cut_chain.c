/* seamquad: the hole chain of 2g - 1 paths between loop sides (seed 7,
 * seed 9.1; seamless-notes 6, the variant L1+, L2+, L2-, ..., Lg+, Lg-,
 * L1-).
 *
 * After cutting along g loops the surface is a sphere with 2g holes (the
 * two sides of each loop). The chain visits them in the order
 *   L1+ -> Li+ -> Li- -> Lj+ -> Lj- -> ... -> L1-
 * with one shortest path per step, so the holes and paths form a tree and
 * the complement is a disk. Branch points: p1 on L1 (one path on each
 * side), and on every other loop a_i (two paths on the + side) and b_i
 * (two paths on the - side): 2g - 1 points of degree 4; branches: 2g - 1
 * loop arcs and 2g - 1 paths, 4g - 2 in all.
 *
 * Paths are found on the cut surface: a path starts in a given wedge
 * (corner of the cut surface: the fan of faces at a cut vertex between two
 * consecutive cut edges, named by its first outgoing cut halfedge in
 * clockwise order, see sq_cut_rot), runs through vertices that are neither
 * cones nor on the cut, and ends in one of the target wedges. Wedges
 * decide the side of a loop and the sector at a branch point; the rotation
 * bits choose the sector at a_i and b_i (sq_cut_graph.h). The next loop
 * is whichever unvisited loop the path from the current hole reaches
 * first. For genus 1 the single path runs from p1 on L1+ to p1 on L1-:
 * the two-loop graph a b a^-1 b^-1. */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct chain_ws {
    double *dist;      /* nv */
    uint32_t *par;     /* nv: path halfedge into v */
    uint32_t *vstamp;  /* nv: dist valid iff vstamp == run */
    uint32_t *tstamp;  /* nh: interior halfedge of a target wedge */
    uint32_t run;
    uint32_t *cutdeg;  /* nv */
    uint32_t *path;    /* nv: the last path found, halfedges in order */
    uint8_t *reserved; /* nv: kept free for the last path (p1's - fan) */
    uint32_t *near;    /* nv: number of neighbours on the cut */
    double penalty;    /* extra cost of entering a vertex next to the cut */
    uint8_t reserve_tag; /* 1 while reserved vertices are excluded, else 2 */
    uint32_t npath;
    sq_cut_heap heap;
} chain_ws;

enum { KEEP_ANY = 0, KEEP_FIRST = 1, KEEP_SECOND = 2 };

static int is_free(const chain_ws *w, const uint8_t *cone, uint32_t v)
{
    return w->cutdeg[v] == 0 && !(cone && cone[v]) && w->reserved[v] != w->reserve_tag;
}

/* Shortest path from any source wedge to any target wedge (wedges named by
 * their first cut halfedge). Result in w->path; *len its length. Returns
 * 0 when no path exists. */
static int find_path(const sq_mesh *m, const uint8_t *cone, const uint8_t *cut, chain_ws *w,
                     const uint32_t *src, uint32_t ns, const uint32_t *tgt, uint32_t nt,
                     uint32_t keep, double *len, int *nomem)
{
    const uint32_t run = ++w->run;
    for (uint32_t i = 0; i < nt; ++i) {
        /* Arriving by interior halfedge c_j of wedge c_0 .. c_k splits it
         * into c_0 .. c_j and c_j .. c_k; the sub-wedge the next path
         * leaves from must keep an interior halfedge: KEEP_FIRST needs
         * j >= 2, KEEP_SECOND needs j <= k - 2. */
        const uint32_t c1 = sq_cut_rot(m, tgt[i]);
        for (uint32_t c = c1; !cut[c]; c = sq_cut_rot(m, c)) {
            if (keep == KEEP_FIRST && c == c1)
                continue;
            if (keep == KEEP_SECOND && cut[sq_cut_rot(m, c)])
                continue;
            w->tstamp[c] = run;
        }
    }
    double best = INFINITY;
    uint32_t arrive = SQ_NONE;
    w->heap.n = 0;
    for (uint32_t i = 0; i < ns; ++i) {
        assert(cut[src[i]]);
        for (uint32_t c = sq_cut_rot(m, src[i]); !cut[c]; c = sq_cut_rot(m, c)) {
            const uint32_t y = sq_cut_dest(m, c);
            double l = sq_cut_he_length(m, c);
            if (is_free(w, cone, y)) {
                if (w->near[y])
                    l += w->penalty;
                if (w->vstamp[y] != run || l < w->dist[y]) {
                    w->vstamp[y] = run;
                    w->dist[y] = l;
                    w->par[y] = c;
                    if (!sq_cut_heap_push(&w->heap, l, y))
                        return *nomem = 1, 0;
                }
            } else if (w->tstamp[m->he_twin[c]] == run && l < best) {
                best = l;
                arrive = c;
            }
        }
    }
    double d;
    uint32_t x;
    while (sq_cut_heap_pop(&w->heap, &d, &x)) {
        if (d > w->dist[x])
            continue;
        if (d >= best)
            break;
        const uint32_t h0 = m->v_he[x];
        uint32_t h = h0;
        do {
            const uint32_t y = sq_cut_dest(m, h);
            double nd = d + sq_cut_he_length(m, h);
            if (is_free(w, cone, y)) {
                if (w->near[y])
                    nd += w->penalty;
                if (w->vstamp[y] != run || nd < w->dist[y]) {
                    w->vstamp[y] = run;
                    w->dist[y] = nd;
                    w->par[y] = h;
                    if (!sq_cut_heap_push(&w->heap, nd, y))
                        return *nomem = 1, 0;
                }
            } else if (w->tstamp[m->he_twin[h]] == run && nd < best) {
                best = nd;
                arrive = h;
            }
            h = sq_cut_rot(m, h);
        } while (h != h0);
    }
    if (arrive == SQ_NONE)
        return 0;
    uint32_t n = 0;
    for (uint32_t h = arrive;; h = w->par[m->he_vert[h]]) {
        w->path[n++] = h;
        if (!is_free(w, cone, m->he_vert[h]))
            break;
    }
    for (uint32_t i = 0; i < n / 2; ++i) {
        const uint32_t t = w->path[i];
        w->path[i] = w->path[n - 1 - i];
        w->path[n - 1 - i] = t;
    }
    w->npath = n;
    *len = best; /* with penalties */
    return 1;
}

/* Vertex v joins the cut: its neighbours are now next to the cut. */
static void touch(const sq_mesh *m, chain_ws *w, uint32_t v)
{
    if (w->cutdeg[v]++ > 0)
        return;
    const uint32_t h0 = m->v_he[v];
    uint32_t h = h0;
    do {
        w->near[sq_cut_dest(m, h)]++;
        h = sq_cut_rot(m, h);
    } while (h != h0);
}

/* Cuts along the last path found; returns its Euclidean length. */
static double commit_path(const sq_mesh *m, uint8_t *cut, chain_ws *w)
{
    double len = 0.0;
    for (uint32_t i = 0; i < w->npath; ++i) {
        const uint32_t h = w->path[i];
        assert(!cut[h]);
        cut[h] = cut[m->he_twin[h]] = 1;
        touch(m, w, m->he_vert[h]);
        touch(m, w, sq_cut_dest(m, h));
        len += sq_cut_he_length(m, h);
    }
    return len;
}

#define PENALTY_EDGES 3.0

static int bit(uint64_t bits, uint32_t i) { return i < 64 ? (int)((bits >> i) & 1u) : 0; }

/* Genus 1: p1 on L1+ to p1 on L1-, the shortest of evenly spaced p1
 * (seed 7); the path cut, its length added to *length. */
static sq_status torus_path(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L, const uint32_t *plus,
                            const uint32_t *minus, uint8_t *cut, chain_ws *w, double *length, sq_cut_stats *stats,
                            sq_error *err)
{
    double len;
    int nomem = 0;
    const uint32_t a = L->loop_off[0], n = L->loop_off[1] - a;
    const uint32_t samples = n < 16 ? n : 16;
    double best = INFINITY;
    uint32_t best_v = SQ_NONE;
    for (uint32_t s = 0; s < samples; ++s) {
        const uint32_t v = m->he_vert[L->loop_he[a + (uint32_t)((uint64_t)s * n / samples)]];
        if (find_path(m, cone, cut, w, &plus[v], 1, &minus[v], 1, KEEP_ANY, &len,
                      &nomem) &&
            len < best) {
            best = len;
            best_v = v;
        }
        if (nomem)
            break;
    }
    if (!nomem && best_v != SQ_NONE &&
        !find_path(m, cone, cut, w, &plus[best_v], 1, &minus[best_v], 1, KEEP_ANY,
                   &len, &nomem))
        best_v = SQ_NONE;
    if (nomem) return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (chain)");
    if (best_v == SQ_NONE) {
        if (stats)
            stats->failure = SQ_CUT_FAIL_NO_PATH, stats->where[0] = stats->where[1] = SQ_NONE;
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cut graph: no cone-free path crosses the loop of the torus "
                            "(cones wall it in; an edge split would be needed)");
    }
    *length += commit_path(m, cut, w);
    return SQ_OK;
}

/* Genus >= 2: the 2g - 1 paths of the hole chain (seed 7, [CSZZ19]), from
 * L1+ to the + side of the nearest other loop, across each loop from its +
 * to its - side, and back to p1 on L1-, each in the sector the rotation
 * bits choose; the paths cut, their lengths added to *length. tg (the
 * loops' vertices), visited (g): scratch. */
static sq_status chain_paths(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L, uint64_t rotation,
                             const uint32_t *plus, const uint32_t *minus, const uint32_t *loop_of, uint32_t *tg,
                             uint8_t *visited, uint8_t *cut, chain_ws *w, double *length, sq_cut_stats *stats,
                             sq_error *err)
{
    const uint32_t g = L->nloops;
    double len;
    int nomem = 0;
    uint32_t ns = 0, nt;
    for (uint32_t k = L->loop_off[0]; k < L->loop_off[1]; ++k)
        tg[ns++] = plus[m->he_vert[L->loop_he[k]]];
    visited[0] = 1;
    uint32_t *src = malloc((size_t)ns * sizeof *src);
    if (!src) return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (chain)");
    memcpy(src, tg, (size_t)ns * sizeof *src);
    uint32_t p1 = SQ_NONE, from = SQ_NONE; /* from: start wedge of the next path */
    const char *what = NULL;
    for (uint32_t step = 0; step < 2 * g - 1; ++step) {
        const uint32_t *s = step == 0 ? src : &from;
        const uint32_t nsrc = step == 0 ? ns : 1;
        uint32_t arrive_loop = SQ_NONE, on_minus = 0, exclude = SQ_NONE;
        nt = 0;
        if (step % 2 == 1) {
            /* a_i (+) to b_i (-) on the same loop, b_i != a_i */
            arrive_loop = loop_of[m->he_vert[from]];
            exclude = m->he_vert[from];
            for (uint32_t k = L->loop_off[arrive_loop]; k < L->loop_off[arrive_loop + 1]; ++k) {
                const uint32_t v = m->he_vert[L->loop_he[k]];
                if (v != exclude)
                    tg[nt++] = minus[v];
            }
            on_minus = 1;
            what = "from the + to the - side of a loop";
        } else if (step == 2 * g - 2) {
            tg[nt++] = minus[p1]; /* back to p1 on L1- */
            what = "back to the first loop's - side";
        } else {
            for (uint32_t i = 1; i < g; ++i)
                if (!visited[i])
                    for (uint32_t k = L->loop_off[i]; k < L->loop_off[i + 1]; ++k)
                        tg[nt++] = plus[m->he_vert[L->loop_he[k]]];
            what = "to the + side of the next loop";
        }
        if (step == 2 * g - 2)
            w->reserve_tag = 2; /* the last path may use p1's fan */
        const uint32_t keep = step == 2 * g - 2 ? KEEP_ANY
                              : bit(rotation, step) ? KEEP_SECOND : KEEP_FIRST;
        if (!find_path(m, cone, cut, w, s, nsrc, tg, nt, keep, &len, &nomem)) {
            free(src);
            if (nomem) return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (chain)");
            const uint32_t v = m->he_vert[s[0]];
            if (stats)
                stats->failure = SQ_CUT_FAIL_NO_PATH, stats->where[0] = v,
                stats->where[1] = SQ_NONE;
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "cut graph: chain path %u of %u (%s) from vertex %u has no "
                                "route avoiding cones and the cut (a narrow passage; an "
                                "edge split would be needed)",
                                step + 1, 2 * g - 1, what, v);
        }
        const uint32_t first = w->path[0], last = w->path[w->npath - 1];
        const uint32_t y = sq_cut_dest(m, last);
        if (step == 0) {
            /* Keep the fan of p1 on the - side free for the last path:
             * later paths could otherwise wall it in. */
            p1 = m->he_vert[first];
            for (uint32_t c = sq_cut_rot(m, minus[p1]); !cut[c]; c = sq_cut_rot(m, c))
                w->reserved[sq_cut_dest(m, c)] = 1;
        }
        *length += commit_path(m, cut, w);
        if (step == 2 * g - 2)
            break;
        /* The next path leaves y on the same side as this one arrived,
         * in the sector chosen by the rotation bit (seamless-notes 6). */
        const uint32_t q = m->he_twin[last];
        const uint32_t bi = step; /* a_2, b_2, a_3, b_3, ... */
        const uint32_t side_start = on_minus ? minus[y] : plus[y];
        from = bit(rotation, bi) ? q : side_start;
        if (step % 2 == 0) {
            assert(loop_of[y] != SQ_NONE && !visited[loop_of[y]]);
            visited[loop_of[y]] = 1;
        }
    }
    free(src);
    return SQ_OK;
}

sq_status sq_cut_chain(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L,
                       uint64_t rotation, uint64_t flip, sq_cut_graph *out,
                       sq_cut_stats *stats, sq_error *err)
{
    sq_cut_graph_free(out);
    if (stats)
        stats->failure = SQ_CUT_FAIL_NONE;
    const uint32_t g = L->nloops;
    if (g < 1 || g != L->genus)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cut graph: %u loops for genus %u", g,
                            L->genus);
    sq_status st = SQ_OK;
    chain_ws w;
    memset(&w, 0, sizeof w);
    uint32_t *plus = malloc((size_t)m->nv * sizeof *plus);   /* + wedge start */
    uint32_t *minus = malloc((size_t)m->nv * sizeof *minus); /* - wedge start */
    uint32_t *loop_of = malloc((size_t)m->nv * sizeof *loop_of);
    uint32_t *tg = malloc(((size_t)L->loop_off[g] + 1) * sizeof *tg);
    uint8_t *visited = calloc(g, 1);
    out->he_cut = calloc(m->nh, 1);
    w.dist = malloc((size_t)m->nv * sizeof *w.dist);
    w.par = malloc((size_t)m->nv * sizeof *w.par);
    w.vstamp = calloc(m->nv, sizeof *w.vstamp);
    w.tstamp = calloc(m->nh, sizeof *w.tstamp);
    w.cutdeg = calloc(m->nv, sizeof *w.cutdeg);
    w.path = malloc((size_t)m->nv * sizeof *w.path);
    w.reserved = calloc(m->nv, 1);
    w.near = calloc(m->nv, sizeof *w.near);
    w.reserve_tag = 1;
    int heap_ok = sq_cut_heap_init(&w.heap, 1024);
    if (!plus || !minus || !loop_of || !tg || !visited || !out->he_cut || !w.dist || !w.par ||
        !w.vstamp || !w.tstamp || !w.cutdeg || !w.path || !w.reserved || !w.near ||
        !heap_ok) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (chain)");
        goto done;
    }
    uint8_t *cut = out->he_cut;
    out->genus = g;
    out->rotation = rotation;
    out->flip = flip;
    for (uint32_t v = 0; v < m->nv; ++v)
        plus[v] = minus[v] = loop_of[v] = SQ_NONE;
    /* Entering a vertex next to the cut costs PENALTY_EDGES mean edge
     * lengths extra: paths then keep a free vertex between themselves and
     * other cut curves where they can, which keeps the cut surface's free
     * vertices connected (no pockets between a path and a loop). */
    double mean = 0.0;
    for (uint32_t h = 0; h < m->nh; ++h)
        mean += sq_cut_he_length(m, h);
    w.penalty = PENALTY_EDGES * mean / (double)m->nh;
    /* Loops: their edges are cut; at loop vertex v with loop halfedges
     * h_in (into v) and h_out (out of v), the wedge starting at
     * twin(h_in) lies on the left of the loop (+), the one starting at
     * h_out on the right (-); a flipped loop swaps them. */
    for (uint32_t i = 0; i < g; ++i) {
        const uint32_t a = L->loop_off[i], b = L->loop_off[i + 1];
        for (uint32_t k = a; k < b; ++k) {
            const uint32_t h_in = L->loop_he[k == a ? b - 1 : k - 1], h_out = L->loop_he[k];
            const uint32_t v = m->he_vert[h_out];
            assert(sq_cut_dest(m, h_in) == v);
            plus[v] = bit(flip, i) ? h_out : m->he_twin[h_in];
            minus[v] = bit(flip, i) ? m->he_twin[h_in] : h_out;
            loop_of[v] = i;
            cut[h_out] = cut[m->he_twin[h_out]] = 1;
            touch(m, &w, v);
            w.cutdeg[v]++;
            out->length += sq_cut_he_length(m, h_out);
        }
    }
    sq_status sp = g == 1 ? torus_path(m, cone, L, plus, minus, cut, &w, &out->length, stats, err)
                          : chain_paths(m, cone, L, rotation, plus, minus, loop_of, tg, visited, cut, &w,
                                        &out->length, stats, err);
    if (sp) {
        st = sp;
        goto done;
    }
    st = sq_cut_boundary_word(m, out, err);
    if (st == SQ_OK)
        st = sq_cut_graph_check(m, cone, out, err);
    if (st != SQ_OK && stats && st != SQ_ERR_NOMEM)
        stats->failure = SQ_CUT_FAIL_CHECK;
done:
    if (st != SQ_OK)
        sq_cut_graph_free(out);
    free(plus);
    free(minus);
    free(loop_of);
    free(tg);
    free(visited);
    free(w.dist);
    free(w.par);
    free(w.vstamp);
    free(w.tstamp);
    free(w.cutdeg);
    free(w.path);
    free(w.reserved);
    free(w.near);
    if (heap_ok)
        sq_cut_heap_free(&w.heap);
    return st;
}
