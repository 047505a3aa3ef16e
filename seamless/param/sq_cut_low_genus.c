/* seamquad: cut graphs for genus 0 and 1 (seed 6.5, seed 7 "Low Genus
 * Special Cases", seed 6.2, seed 9.1), and the side correspondence between
 * a cut graph's boundary word and the domain Q's pattern.
 *
 * Genus 0 (seed 6.5: "Cutting along one edge of this mesh yields a disk";
 * seed 7: "For genus 0 a trivial one-segment cut graph is sufficient"): one
 * shortest path of at least 2 edges between two non-cone vertices through
 * non-cone vertices. Its ends are degree-1 branch points; the disk has
 * k = 2 sides, partner {1, 0}, matching sq_domain_genus0.c.
 *
 * Genus 1 with cones (seed 6.2 with two pieces; docs/domain.md "Genus 1"):
 * Q is a 6-gon with opposite sides glued (partner {3, 4, 5, 0, 1, 2}) and
 * one straight corner in each of its two corner classes. The matching cut
 * graph is a theta graph: a shortest cone-free non-separating loop L
 * (sq_cut_loops_find, seed 9.1) and a shortest cone-free path P in M cut
 * along L from the + side of L to the - side, with ends x != y on L. Cut
 * along L the surface is an annulus; P joins its two boundary circles, so
 * the complement is a disk. x and y have degree 3; the branches are the two
 * arcs of L between them and P; the word is a b c a^-1 b^-1 c^-1.
 *
 * Genus 1 without cones, genus >= 2: sq_cut_graph_build (the two-loop graph
 * a b a^-1 b^-1 for genus 1, the hole chain for genus >= 2). */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void stats_fail(sq_cut_stats *s, sq_cut_failure f, uint32_t a, uint32_t b)
{
    if (s) {
        s->failure = f;
        s->where[0] = a;
        s->where[1] = b;
    }
}

static int is_cone(const uint8_t *cone, uint32_t v) { return cone && cone[v]; }

/* Boundary word, length and the checks; genus already set in G. */
static sq_status finish(const sq_mesh *m, const uint8_t *cone, sq_cut_graph *G,
                        sq_cut_stats *stats, sq_error *err)
{
    G->length = 0.0;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (G->he_cut[h] && h < m->he_twin[h])
            G->length += sq_cut_he_length(m, h);
    sq_status st = sq_cut_boundary_word(m, G, err);
    if (st == SQ_OK)
        st = sq_cut_graph_check(m, cone, G, err);
    if (st != SQ_OK && st != SQ_ERR_NOMEM)
        stats_fail(stats, SQ_CUT_FAIL_CHECK, SQ_NONE, SQ_NONE);
    G->tries = 1;
    return st;
}

/* ---- genus 0: one path ------------------------------------------------- */

static sq_status build_genus0(const sq_mesh *m, const uint8_t *cone, uint64_t seed,
                              sq_cut_graph *out, sq_cut_stats *stats, sq_error *err)
{
    sq_status st = SQ_OK;
    double *dist = malloc((size_t)m->nv * sizeof *dist);
    uint32_t *par = malloc((size_t)m->nv * sizeof *par);
    uint32_t *seen = calloc(m->nv, sizeof *seen); /* Dijkstra run that reached v */
    uint8_t *ring = calloc(m->nv, 1);
    sq_cut_heap heap;
    const int heap_ok = sq_cut_heap_init(&heap, 256);
    out->he_cut = calloc(m->nh, 1);
    if (!dist || !par || !seen || !ring || !heap_ok || !out->he_cut) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (genus 0)");
        goto done;
    }
    out->genus = 0;
    /* Start at the first non-cone vertex (in index order from `first`,
     * below) from which some non-cone vertex outside its 1-ring is
     * reachable through non-cone vertices; the end is the nearest such
     * vertex, so the shortest path has >= 2 edges. A run that fails stays
     * inside the closed 1-ring of its start, so trying every start is cheap;
     * another start in the same component may still succeed (u's neighbours
     * see u's other neighbours as outside their own 1-ring). */
    uint32_t u = SQ_NONE, w = SQ_NONE, walled = SQ_NONE, run = 0;
    /* seed 1 scans from vertex 0; other seeds from a vertex spread over the
     * index range (a prime stride), so that retries get other slits */
    const uint32_t first = (uint32_t)(((seed ? seed - 1 : 0) % m->nv) * 7919u % m->nv);
    for (uint32_t i = 0; i < m->nv && w == SQ_NONE; ++i) {
        const uint32_t s = (first + i) % m->nv;
        if (is_cone(cone, s))
            continue;
        ++run;
        u = s;
        uint32_t h = m->v_he[s];
        do {
            ring[sq_cut_dest(m, h)] = 1;
            h = sq_cut_rot(m, h);
        } while (h != m->v_he[s]);
        heap.n = 0;
        dist[s] = 0.0;
        par[s] = SQ_NONE;
        seen[s] = run;
        if (!sq_cut_heap_push(&heap, 0.0, s)) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (genus 0)");
            goto done;
        }
        double d;
        uint32_t x;
        while (sq_cut_heap_pop(&heap, &d, &x)) {
            if (d > dist[x])
                continue;
            if (x != s && !ring[x]) {
                w = x;
                break;
            }
            const uint32_t h0 = m->v_he[x];
            h = h0;
            do {
                const uint32_t y = sq_cut_dest(m, h);
                const double nd = d + sq_cut_he_length(m, h);
                if (!is_cone(cone, y) && (seen[y] != run || nd < dist[y])) {
                    seen[y] = run;
                    dist[y] = nd;
                    par[y] = h;
                    if (!sq_cut_heap_push(&heap, nd, y)) {
                        st = sq_error_set(err, SQ_ERR_NOMEM,
                                          "cut graph: out of memory (genus 0)");
                        goto done;
                    }
                }
                h = sq_cut_rot(m, h);
            } while (h != h0);
        }
        h = m->v_he[s];
        do {
            ring[sq_cut_dest(m, h)] = 0;
            h = sq_cut_rot(m, h);
        } while (h != m->v_he[s]);
        if (w == SQ_NONE && walled == SQ_NONE)
            walled = s;
    }
    if (w == SQ_NONE) {
        uint32_t a, b;
        sq_cut_find_cone_edge(m, cone, walled, &a, &b);
        stats_fail(stats, SQ_CUT_FAIL_NEEDS_SPLIT, a, b);
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "cut graph: no path of 2 edges avoids the cones (non-cone vertex %u "
                          "is walled in, e.g. by cone edge %u-%u); the cut needs an edge "
                          "split (Steiner vertex, seed 9.1; sq_param_build makes it)",
                          walled, a, b);
        goto done;
    }
    for (uint32_t x = w; x != u; x = m->he_vert[par[x]]) {
        const uint32_t h = par[x];
        out->he_cut[h] = out->he_cut[m->he_twin[h]] = 1;
    }
    st = finish(m, cone, out, stats, err);
done:
    free(dist);
    free(par);
    free(seen);
    free(ring);
    if (heap_ok)
        sq_cut_heap_free(&heap);
    return st;
}

/* ---- genus 1 with cones: the theta graph -------------------------------- */

/* Dijkstra labels with distinct sources: every vertex keeps at most two
 * settled labels, from different loop vertices. A shortest path from some
 * x to a target y != x has, at each of its vertices, a label among the two
 * best of distinct sources (otherwise both better sources give paths at
 * least as short, one of them from a source != y), so two labels per
 * vertex find the shortest path with distinct ends exactly. */
typedef struct theta_cand {
    double d;
    uint32_t v, src, he, parent; /* he: halfedge into v; parent: label */
} theta_cand;

typedef struct theta_ws {
    theta_cand *cand;
    uint32_t ncand, capcand;
    uint32_t *lab_src, *lab_he, *lab_par; /* 2 nv labels */
    uint32_t nlab;
    uint32_t *vlab;                       /* 2 nv: labels of v (slot 0, 1) */
    uint8_t *nset;                        /* nv: settled labels at v */
    sq_cut_heap heap;
} theta_ws;

static int push_cand(theta_ws *w, double d, uint32_t v, uint32_t src, uint32_t he,
                     uint32_t parent)
{
    if (w->ncand == w->capcand) {
        const uint32_t cap = w->capcand ? 2 * w->capcand : 1024;
        theta_cand *c = realloc(w->cand, (size_t)cap * sizeof *c);
        if (!c)
            return 0;
        w->cand = c;
        w->capcand = cap;
    }
    w->cand[w->ncand] = (theta_cand){d, v, src, he, parent};
    if (!sq_cut_heap_push(&w->heap, d, w->ncand))
        return 0;
    w->ncand++;
    return 1;
}

/* Shortest path through free vertices (neither cone nor on L) from an
 * interior halfedge of the + wedge at some x on L to an interior halfedge
 * of the - wedge at some y != x on L. plus/minus: wedge starts (SQ_NONE off
 * L). Fills path (halfedges from x to y), *npath. Returns 0 if there is
 * none, -1 when out of memory. */
static int theta_path(const sq_mesh *m, const uint8_t *cone, const uint8_t *cut,
                      const uint32_t *plus, const uint32_t *minus, const uint32_t *loop_v,
                      uint32_t nloop, uint32_t *path, uint32_t *npath)
{
    theta_ws w;
    memset(&w, 0, sizeof w);
    int ret = -1;
    uint8_t *target = calloc(m->nh, 1); /* interior halfedges of - wedges */
    w.lab_src = malloc(2 * (size_t)m->nv * sizeof *w.lab_src);
    w.lab_he = malloc(2 * (size_t)m->nv * sizeof *w.lab_he);
    w.lab_par = malloc(2 * (size_t)m->nv * sizeof *w.lab_par);
    w.vlab = malloc(2 * (size_t)m->nv * sizeof *w.vlab);
    w.nset = calloc(m->nv, 1);
    const int heap_ok = sq_cut_heap_init(&w.heap, 1024);
    if (!target || !w.lab_src || !w.lab_he || !w.lab_par || !w.vlab || !w.nset || !heap_ok)
        goto done;
    for (uint32_t i = 0; i < nloop; ++i) {
        const uint32_t y = loop_v[i];
        for (uint32_t c = sq_cut_rot(m, minus[y]); !cut[c]; c = sq_cut_rot(m, c))
            target[c] = 1;
    }
    double best = INFINITY;
    uint32_t best_lab = SQ_NONE, best_he = SQ_NONE;
    /* sources: out of the + wedges */
    for (uint32_t i = 0; i < nloop; ++i) {
        const uint32_t x = loop_v[i];
        for (uint32_t c = sq_cut_rot(m, plus[x]); !cut[c]; c = sq_cut_rot(m, c)) {
            const uint32_t y = sq_cut_dest(m, c);
            const double l = sq_cut_he_length(m, c);
            if (!is_cone(cone, y) && plus[y] == SQ_NONE) {
                if (!push_cand(&w, l, y, x, c, SQ_NONE))
                    goto done;
            } else if (target[m->he_twin[c]] && y != x && l < best) {
                best = l; /* one edge straight across */
                best_lab = SQ_NONE;
                best_he = c;
            }
        }
    }
    double d;
    uint32_t ci;
    while (sq_cut_heap_pop(&w.heap, &d, &ci)) {
        if (d >= best)
            break;
        const theta_cand c = w.cand[ci];
        if (w.nset[c.v] == 2 || (w.nset[c.v] == 1 && w.lab_src[w.vlab[2 * c.v]] == c.src))
            continue;
        const uint32_t lab = w.nlab++;
        w.lab_src[lab] = c.src;
        w.lab_he[lab] = c.he;
        w.lab_par[lab] = c.parent;
        w.vlab[2 * c.v + w.nset[c.v]++] = lab;
        const uint32_t h0 = m->v_he[c.v];
        uint32_t h = h0;
        do {
            const uint32_t y = sq_cut_dest(m, h);
            const double nd = d + sq_cut_he_length(m, h);
            if (!is_cone(cone, y) && plus[y] == SQ_NONE) {
                if (w.nset[y] < 2 && !push_cand(&w, nd, y, c.src, h, lab))
                    goto done;
            } else if (target[m->he_twin[h]] && y != c.src && nd < best) {
                best = nd;
                best_lab = lab;
                best_he = h;
            }
            h = sq_cut_rot(m, h);
        } while (h != h0);
    }
    if (best_he == SQ_NONE) {
        ret = 0;
        goto done;
    }
    uint32_t n = 0;
    path[n++] = best_he;
    for (uint32_t l = best_lab; l != SQ_NONE; l = w.lab_par[l])
        path[n++] = w.lab_he[l];
    for (uint32_t i = 0; i < n / 2; ++i) {
        const uint32_t t = path[i];
        path[i] = path[n - 1 - i];
        path[n - 1 - i] = t;
    }
    *npath = n;
    ret = 1;
done:
    free(target);
    free(w.cand);
    free(w.lab_src);
    free(w.lab_he);
    free(w.lab_par);
    free(w.vlab);
    free(w.nset);
    if (heap_ok)
        sq_cut_heap_free(&w.heap);
    return ret;
}

static sq_status build_theta(const sq_mesh *m, const uint8_t *cone, const sq_cut_options *opt,
                             sq_cut_graph *out, sq_cut_stats *stats, sq_error *err)
{
    sq_cut_loops L;
    sq_cut_loops_init(&L);
    sq_status st = sq_cut_loops_find(m, cone, opt, &L, stats, err);
    if (st != SQ_OK)
        return st;
    assert(L.nloops == 1);
    const uint32_t a = L.loop_off[0], n = L.loop_off[1] - a;
    uint32_t *plus = malloc((size_t)m->nv * sizeof *plus);
    uint32_t *minus = malloc((size_t)m->nv * sizeof *minus);
    uint32_t *loop_v = malloc((size_t)n * sizeof *loop_v);
    uint32_t *path = malloc((size_t)m->nv * sizeof *path);
    out->he_cut = calloc(m->nh, 1);
    if (!plus || !minus || !loop_v || !path || !out->he_cut) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (theta graph)");
        goto done;
    }
    out->genus = 1;
    for (uint32_t v = 0; v < m->nv; ++v)
        plus[v] = minus[v] = SQ_NONE;
    /* At loop vertex v with loop halfedges h_in (into v) and h_out: the
     * wedge starting at twin(h_in) is the + side (left of L), the wedge
     * starting at h_out the - side (as in sq_cut_chain). */
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t h_in = L.loop_he[a + (k + n - 1) % n], h_out = L.loop_he[a + k];
        const uint32_t v = m->he_vert[h_out];
        plus[v] = m->he_twin[h_in];
        minus[v] = h_out;
        loop_v[k] = v;
        out->he_cut[h_out] = out->he_cut[m->he_twin[h_out]] = 1;
    }
    uint32_t np = 0;
    const int r = theta_path(m, cone, out->he_cut, plus, minus, loop_v, n, path, &np);
    if (r < 0) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (theta graph)");
        goto done;
    }
    if (r == 0) {
        uint32_t p, q;
        sq_cut_find_cone_edge(m, cone, SQ_NONE, &p, &q);
        stats_fail(stats, SQ_CUT_FAIL_NEEDS_SPLIT, p, q);
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "cut graph: no cone-free path crosses the loop of the torus from "
                          "one side to the other (adjacent cones wall it off, e.g. edge "
                          "%u-%u); the cut needs an edge split (Steiner vertex, seed 9.1; "
                          "sq_param_build makes it)",
                          p, q);
        goto done;
    }
    for (uint32_t i = 0; i < np; ++i) {
        assert(!out->he_cut[path[i]]);
        out->he_cut[path[i]] = out->he_cut[m->he_twin[path[i]]] = 1;
    }
    st = finish(m, cone, out, stats, err);
done:
    free(plus);
    free(minus);
    free(loop_v);
    free(path);
    sq_cut_loops_free(&L);
    return st;
}

sq_status sq_cut_graph_build_low_genus(const sq_mesh *m, const uint8_t *cone,
                                       const sq_cut_options *opt, sq_cut_graph *out,
                                       sq_cut_stats *stats, sq_error *err)
{
    sq_cut_graph_free(out);
    if (stats)
        memset(stats, 0, sizeof *stats);
    const int64_t genus = sq_mesh_genus(m);
    if (genus < 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cut graph: Euler characteristic %lld is not that of a closed "
                            "connected orientable surface",
                            (long long)sq_mesh_euler(m));
    int any_cone = 0;
    for (uint32_t v = 0; cone && v < m->nv && !any_cone; ++v)
        any_cone = cone[v] != 0;
    if (genus >= 2 || (genus == 1 && !any_cone))
        return sq_cut_graph_build(m, cone, opt, out, stats, err);
    sq_status st = genus == 0 ? build_genus0(m, cone, opt ? opt->seed : 1, out, stats, err)
                              : build_theta(m, cone, opt, out, stats, err);
    if (st != SQ_OK)
        sq_cut_graph_free(out);
    return st;
}

/* ---- side correspondence with Q ----------------------------------------- */

int sq_cut_graph_shift_pairs(const sq_pattern *cw, const sq_pattern *q, uint32_t r)
{
    const uint32_t k = q->k;
    for (uint32_t j = 0; j < k; ++j)
        if (cw->partner[(j + r) % k] != (q->partner[j] + r) % k)
            return 0;
    return 1;
}

sq_status sq_cut_graph_domain_offset(const sq_cut_graph *G, const sq_pattern *q, uint32_t *offset,
                                     sq_error *err)
{
    const uint32_t k = G->pattern.k;
    if (!q || q->k != k || !q->partner)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cut graph: the surface word has %u sides, the domain's pattern %u",
                            k, q ? q->k : 0);
    sq_pattern cw;
    sq_pattern_init(&cw);
    sq_status st = sq_pattern_reversed(&G->pattern, &cw, err);
    if (st != SQ_OK)
        return st;
    uint32_t first = SQ_NONE, with_straight = SQ_NONE;
    for (uint32_t r = 0; r < k && with_straight == SQ_NONE; ++r) {
        if (!sq_cut_graph_shift_pairs(&cw, q, r))
            continue;
        int straight_ok = 1;
        for (uint32_t j = 0; j < k; ++j)
            straight_ok &= cw.straight[(j + r) % k] == (q->straight ? q->straight[j] : 0);
        if (first == SQ_NONE)
            first = r;
        if (straight_ok)
            with_straight = r;
    }
    sq_pattern_free(&cw);
    if (first == SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cut graph: no rotation of the surface's clockwise boundary word "
                            "(%u sides, genus %u) has the domain's side pairing",
                            k, G->genus);
    *offset = with_straight != SQ_NONE ? with_straight : first;
    return SQ_OK;
}
