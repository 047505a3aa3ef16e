/* seamquad: g disjoint non-separating loops (seed 9.1).
 *
 * Rounds of: tree-cotree candidates from sampled base points, sorted by
 * length; greedily keep each candidate that is vertex-disjoint from the
 * loops kept so far and keeps the surface connected when cut along all of
 * them (face flood fill). Kept loops' vertices are then blocked like cones
 * for the next round, whose cotree treats each side strip of a kept loop
 * as a hole; the leftover loops then form a basis on the capped remainder
 * of genus g - k, one of which is non-separating, so every round makes
 * progress and at most g rounds are needed (a few spare rounds absorb
 * combinatorially narrow regions). */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"
#include "sq_cut_tree_cotree.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

void sq_cut_options_default(sq_cut_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->base_points = 8;
    opt->seed = 0x5eed5eedu;
    opt->max_tries = 64;
}

void sq_cut_loops_init(sq_cut_loops *L) { memset(L, 0, sizeof *L); }

void sq_cut_loops_free(sq_cut_loops *L)
{
    if (!L)
        return;
    free(L->loop_off);
    free(L->loop_he);
    free(L->loop_len);
    memset(L, 0, sizeof *L);
}

static void stats_fail(sq_cut_stats *s, sq_cut_failure f, uint32_t a, uint32_t b)
{
    if (s) {
        s->failure = f;
        s->where[0] = a;
        s->where[1] = b;
    }
}

static int by_len(const void *a, const void *b)
{
    const sq_cut_cand *x = a, *y = b;
    if (x->len != y->len)
        return x->len < y->len ? -1 : 1;
    return x->off < y->off ? -1 : (x->off > y->off);
}

/* Appends candidate c (its halfedges he) to pool p; 0: out of memory. */
static int pool_append(sq_cut_pool *p, const sq_cut_cand *c, const uint32_t *he)
{
    if (p->n == p->cap || p->nhe + c->n > p->hecap) {
        const uint32_t cap = p->cap ? 2 * p->cap : 8;
        uint32_t hecap = p->hecap ? p->hecap : 1024;
        while (hecap < p->nhe + c->n)
            hecap *= 2;
        sq_cut_cand *nc = realloc(p->c, (size_t)cap * sizeof *nc);
        if (nc)
            p->c = nc, p->cap = cap;
        uint32_t *nh = realloc(p->he, (size_t)hecap * sizeof *nh);
        if (nh)
            p->he = nh, p->hecap = hecap;
        if (!nc || !nh)
            return 0;
    }
    p->c[p->n] = *c;
    p->c[p->n].off = p->nhe;
    memcpy(p->he + p->nhe, he, (size_t)c->n * sizeof *he);
    p->nhe += c->n;
    p->n++;
    return 1;
}

/* out: the loops kept (genus g), in the order they were kept. */
static sq_status loops_output(const sq_cut_pool *keep, uint32_t g, sq_cut_loops *out, sq_error *err)
{
    const uint32_t nkept = keep->n;
    out->genus = g;
    out->nloops = nkept;
    out->loop_off = malloc(((size_t)nkept + 1) * sizeof *out->loop_off);
    out->loop_he = malloc(((size_t)keep->nhe + 1) * sizeof *out->loop_he);
    out->loop_len = malloc(((size_t)nkept + 1) * sizeof *out->loop_len);
    if (!out->loop_off || !out->loop_he || !out->loop_len)
        return sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (loops)");
    out->loop_off[0] = 0;
    for (uint32_t i = 0; i < nkept; ++i) {
        out->loop_off[i + 1] = out->loop_off[i] + keep->c[i].n;
        out->loop_len[i] = keep->c[i].len;
    }
    memcpy(out->loop_he, keep->he, (size_t)keep->nhe * sizeof *keep->he);
    return SQ_OK;
}

sq_status sq_cut_loops_find(const sq_mesh *m, const uint8_t *cone, const sq_cut_options *opt_in,
                            sq_cut_loops *out, sq_cut_stats *stats, sq_error *err)
{
    sq_cut_options opt;
    if (opt_in)
        opt = *opt_in;
    else
        sq_cut_options_default(&opt);
    if (opt.base_points == 0)
        opt.base_points = 1;
    if (stats)
        memset(stats, 0, sizeof *stats);
    sq_cut_loops_free(out);
    const int64_t genus = sq_mesh_genus(m);
    if (genus < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cut graph: genus %lld; the loop cut needs genus >= 1",
                            (long long)genus);
    const uint32_t g = (uint32_t)genus;

    sq_status st = SQ_OK;
    uint8_t *blocked = calloc(m->nv, 1);
    uint8_t *cut = calloc(m->nh, 1);
    uint32_t *scratch = malloc(2 * (size_t)m->nf * sizeof *scratch);
    sq_cut_pool keep = {0}, pool = {0};
    sq_cut_tc_ws ws;
    int ws_ok = sq_cut_tc_ws_init(&ws, m);
    if (!blocked || !cut || !scratch || !ws_ok) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (%u vertices)", m->nv);
        goto done;
    }
    uint32_t nfree = 0;
    for (uint32_t v = 0; v < m->nv; ++v) {
        blocked[v] = cone && cone[v];
        nfree += !blocked[v];
    }
    if (nfree == 0) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "cut graph: every vertex is a cone");
        goto done;
    }
    uint64_t rng = opt.seed;
    uint32_t nkept = 0, idle = 0;
    for (uint32_t round = 0; nkept < g; ++round) {
        if (stats)
            stats->rounds = round + 1;
        pool.n = pool.nhe = 0;
        for (uint32_t b = 0; b < opt.base_points; ++b) {
            uint32_t base = SQ_NONE;
            for (uint32_t t = 0; t < 64 && base == SQ_NONE; ++t) {
                const uint32_t v = (uint32_t)(sq_cut_splitmix(&rng) % m->nv);
                if (!blocked[v])
                    base = v;
            }
            if (base == SQ_NONE)
                for (uint32_t v = 0; v < m->nv && base == SQ_NONE; ++v)
                    if (!blocked[v])
                        base = v;
            if (base == SQ_NONE)
                break;
            uint32_t left, unreached;
            st = sq_cut_tree_cotree(m, blocked, cut, base, &ws, &pool, &left, &unreached, err);
            if (st != SQ_OK)
                goto done;
            if (round == 0 && b == 0) {
                /* Only cones are blocked: a missed vertex is walled in by
                 * cones, and a wrong leftover count means a ring of
                 * adjacent cones is not a disk. Both need edge splits. */
                if (unreached != SQ_NONE || left != 2 * g) {
                    uint32_t a, c;
                    sq_cut_find_cone_edge(m, cone ? cone : blocked, unreached, &a, &c);
                    stats_fail(stats, SQ_CUT_FAIL_NEEDS_SPLIT, a, c);
                    if (unreached != SQ_NONE)
                        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                                          "cut graph: vertex %u is walled in by cones (e.g. "
                                          "cone edge %u-%u); the cut needs an edge split "
                                          "(Steiner vertex, seed 9.1; sq_param_build makes it)",
                                          unreached, a, c);
                    else
                        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                                          "cut graph: adjacent cones (e.g. edge %u-%u) form a "
                                          "ring that blocks loops (%u tree-cotree generators, "
                                          "expected %u); the cut needs an edge split (Steiner "
                                          "vertex, seed 9.1; sq_param_build makes it)",
                                          a, c, left, 2 * g);
                    goto done;
                }
            }
        }
        qsort(pool.c, pool.n, sizeof *pool.c, by_len);
        uint32_t gained = 0;
        for (uint32_t i = 0; i < pool.n && nkept < g; ++i) {
            const sq_cut_cand *c = &pool.c[i];
            const uint32_t *he = pool.he + c->off;
            if (stats)
                stats->candidates++;
            uint32_t k = 0;
            for (; k < c->n; ++k)
                if (blocked[m->he_vert[he[k]]])
                    break;
            if (k < c->n)
                continue; /* touches a loop kept in this round */
            for (k = 0; k < c->n; ++k) {
                cut[he[k]] = 1;
                cut[m->he_twin[he[k]]] = 1;
            }
            if (sq_cut_face_regions(m, cut, scratch) != 1) {
                for (k = 0; k < c->n; ++k) {
                    cut[he[k]] = 0;
                    cut[m->he_twin[he[k]]] = 0;
                }
                continue; /* separating */
            }
            for (k = 0; k < c->n; ++k)
                blocked[m->he_vert[he[k]]] = 1;
            if (!pool_append(&keep, c, he)) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (loops)");
                goto done;
            }
            ++nkept;
            ++gained;
        }
        idle = gained ? 0 : idle + 1;
        if (idle >= 3) {
            stats_fail(stats, SQ_CUT_FAIL_NO_LOOP, SQ_NONE, SQ_NONE);
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "cut graph: found only %u of %u disjoint non-separating loops; "
                              "the remaining handles are too narrow between the chosen loops "
                              "and cones (an edge split would be needed)",
                              nkept, g);
            goto done;
        }
    }

    st = loops_output(&keep, g, out, err);
    if (st == SQ_OK) st = sq_cut_loops_check(m, cone, out, err);
    if (st != SQ_OK && st != SQ_ERR_NOMEM) stats_fail(stats, SQ_CUT_FAIL_CHECK, SQ_NONE, SQ_NONE);
    if (st != SQ_OK) sq_cut_loops_free(out);
done:
    if (ws_ok)
        sq_cut_tc_ws_free(&ws);
    sq_cut_pool_free(&pool);
    sq_cut_pool_free(&keep);
    free(blocked);
    free(cut);
    free(scratch);
    return st;
}

sq_status sq_cut_loops_check(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L,
                             sq_error *err)
{
    sq_status st = SQ_OK;
    uint32_t *owner = malloc((size_t)m->nv * sizeof *owner);
    uint8_t *cut = calloc(m->nh, 1);
    uint8_t *seen = malloc(m->nh);
    uint32_t *scratch = malloc(2 * (size_t)m->nf * sizeof *scratch);
    if (!owner || !cut || !seen || !scratch) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (loop check)");
        goto done;
    }
    for (uint32_t v = 0; v < m->nv; ++v)
        owner[v] = SQ_NONE;
    for (uint32_t i = 0; i < L->nloops; ++i) {
        const uint32_t a = L->loop_off[i], b = L->loop_off[i + 1];
        if (b - a < 3) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: loop %u has %u edges", i, b - a);
            goto done;
        }
        for (uint32_t k = a; k < b; ++k) {
            const uint32_t h = L->loop_he[k], nx = L->loop_he[k + 1 < b ? k + 1 : a];
            const uint32_t v = m->he_vert[h];
            if (sq_cut_dest(m, h) != m->he_vert[nx]) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: loop %u is not closed at "
                                  "vertex %u", i, sq_cut_dest(m, h));
                goto done;
            }
            if (cone && cone[v]) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: loop %u passes cone %u", i, v);
                goto done;
            }
            if (owner[v] != SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "cut graph: vertex %u is on loop %u and loop %u "
                                  "(loops must be simple and disjoint)", v, owner[v], i);
                goto done;
            }
            owner[v] = i;
            cut[h] = cut[m->he_twin[h]] = 1;
        }
    }
    /* Cutting along the loops duplicates as many vertices as edges, so the
     * Euler characteristic is unchanged; connected with 2n boundary loops
     * means genus g - n. */
    const uint32_t regions = sq_cut_face_regions(m, cut, scratch);
    const uint32_t bl = sq_cut_boundary_loops(m, cut, seen);
    if (regions != 1 || bl != 2 * L->nloops) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "cut graph: cutting along %u loops gives %u components and %u "
                          "boundary loops (expected 1 and %u)",
                          L->nloops, regions, bl, 2 * L->nloops);
        goto done;
    }
done:
    free(owner);
    free(cut);
    free(seen);
    free(scratch);
    return st;
}
