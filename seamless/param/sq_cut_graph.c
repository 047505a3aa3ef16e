/* seamquad: the cut graph driver and its verification (seed 7, seed 9.1).
 * Loops once (sq_cut_loops_find), then the hole chain for successive
 * rotation/flip choices until the boundary word passes the rank test of
 * seamless-notes 7. */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

void sq_cut_graph_init(sq_cut_graph *G)
{
    memset(G, 0, sizeof *G);
    sq_pattern_init(&G->pattern);
}

void sq_cut_graph_free(sq_cut_graph *G)
{
    if (!G)
        return;
    free(G->he_cut);
    free(G->point_vertex);
    free(G->side_off);
    free(G->side_he);
    free(G->corner_vertex);
    sq_pattern_free(&G->pattern);
    sq_cut_graph_init(G);
}

sq_status sq_cut_graph_check(const sq_mesh *m, const uint8_t *cone, const sq_cut_graph *G,
                             sq_error *err)
{
    const uint32_t g = G->genus;
    sq_status st = SQ_OK;
    uint32_t *deg = calloc(m->nv, sizeof *deg);
    uint32_t *corner = malloc((size_t)m->nh * sizeof *corner);
    uint32_t *scratch = malloc(2 * (size_t)m->nf * sizeof *scratch);
    uint8_t *seen = malloc(m->nh);
    uint32_t *cls = malloc(((size_t)G->pattern.k + 1) * sizeof *cls);
    uint32_t *cnt = calloc((size_t)G->pattern.k + 1, sizeof *cnt);
    uint32_t *cv = malloc(((size_t)G->pattern.k + 1) * sizeof *cv);
    if (!deg || !corner || !scratch || !seen || !cls || !cnt || !cv) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (check)");
        goto done;
    }
    uint32_t ncut = 0;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (G->he_cut[h]) {
            deg[m->he_vert[h]]++;
            ncut += h < m->he_twin[h];
        }
    /* Branch points: degree 4 (hole chain, genus >= 1), 3 (theta graph,
     * genus 1) or 1 (one path, genus 0); all of one degree. */
    uint32_t np = 0, degsum = 0, bdeg = 0;
    for (uint32_t v = 0; v < m->nv; ++v) {
        if (!deg[v])
            continue;
        if (cone && cone[v]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: cone vertex %u is on the cut", v);
            goto done;
        }
        if (deg[v] == 2)
            continue;
        const int allowed = g == 0 ? deg[v] == 1 : g == 1 ? deg[v] == 3 || deg[v] == 4
                                                          : deg[v] == 4;
        if (!allowed || (bdeg && deg[v] != bdeg)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: vertex %u has cut degree %u (genus %u: 2 or %s "
                              "expected)",
                              v, deg[v], g, g == 0 ? "1" : g == 1 ? "one of 3 and 4" : "4");
            goto done;
        }
        bdeg = deg[v];
        ++np;
        degsum += deg[v];
    }
    const uint32_t want_np = g == 0 ? 2 : (g == 1 && bdeg == 3) ? 2 : 2 * g - 1;
    const uint32_t want_br = want_np * (bdeg ? bdeg : 4) / 2;
    if (np != want_np || degsum / 2 != want_br) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "cut graph: %u branch points and %u branches (expected %u and %u)", np,
                          degsum / 2, want_np, want_br);
        goto done;
    }
    /* The cut surface: corners (halfedges, each the corner at its origin)
     * joined across uncut edges are its vertices. */
    for (uint32_t h = 0; h < m->nh; ++h)
        corner[h] = h;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (!G->he_cut[h])
            sq_uf_union(corner, h, sq_cut_rot(m, h));
    int64_t vc = 0;
    for (uint32_t h = 0; h < m->nh; ++h)
        vc += sq_uf_find(corner, h) == h;
    const int64_t chi = vc - ((int64_t)m->nh / 2 + ncut) + m->nf;
    const uint32_t regions = sq_cut_face_regions(m, G->he_cut, scratch);
    const uint32_t bl = sq_cut_boundary_loops(m, G->he_cut, seen);
    if (chi != 1 || regions != 1 || bl != 1) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "cut graph: the cut surface is not a disk (Euler characteristic "
                          "%lld, %u components, %u boundary loops)",
                          (long long)chi, regions, bl);
        goto done;
    }
    /* The pattern: k = 2 * branches sides; genus g; one corner class per
     * branch point. Genus 0 has one right corner per class, which is not a
     * regular point of a metapolygon (sq_pattern_validate refuses it; the
     * domain's genus-0 Q is a closed sphere cut along one edge, seed 6.5),
     * so only its pairing and Euler characteristic are checked. */
    const uint32_t k = G->pattern.k;
    if (k != 2 * want_br) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: %u sides (expected %u)", k,
                          2 * want_br);
        goto done;
    }
    if (g == 0) {
        if (G->pattern.partner[0] != 1 || G->pattern.partner[1] != 0) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: genus 0 sides do not pair as {1, 0}");
            goto done;
        }
    } else {
        sq_pattern_info info;
        st = sq_pattern_validate(&G->pattern, &info, err);
        if (st != SQ_OK)
            goto done;
        if (info.genus != g || info.classes != want_np) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: pattern of genus %u with %u corner classes (expected "
                              "%u and %u)", info.genus, info.classes, g, want_np);
            goto done;
        }
    }
    const uint32_t V = sq_pattern_corner_classes(&G->pattern, cls);
    for (uint32_t c = 0; c < V; ++c)
        cv[c] = SQ_NONE;
    for (uint32_t i = 0; i < k; ++i) {
        cnt[cls[i]]++;
        if (cv[cls[i]] == SQ_NONE)
            cv[cls[i]] = G->corner_vertex[i];
        if (cv[cls[i]] != G->corner_vertex[i]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: corner %u (vertex %u) is glued to vertex %u", i,
                              G->corner_vertex[i], cv[cls[i]]);
            goto done;
        }
    }
    if (V != want_np) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: %u corner classes (expected %u)", V,
                          want_np);
        goto done;
    }
    for (uint32_t c = 0; c < V; ++c)
        if (cnt[c] != deg[cv[c]]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: branch vertex %u has %u corners (expected %u)", cv[c],
                              cnt[c], deg[cv[c]]);
            goto done;
        }
done:
    free(deg);
    free(corner);
    free(scratch);
    free(seen);
    free(cls);
    free(cnt);
    free(cv);
    return st;
}

sq_status sq_cut_graph_build(const sq_mesh *m, const uint8_t *cone, const sq_cut_options *opt_in,
                             sq_cut_graph *out, sq_cut_stats *stats, sq_error *err)
{
    sq_cut_options opt;
    if (opt_in)
        opt = *opt_in;
    else
        sq_cut_options_default(&opt);
    if (opt.max_tries == 0)
        opt.max_tries = 1;
    sq_cut_graph_free(out);
    sq_cut_loops L;
    sq_cut_loops_init(&L);
    sq_status st = sq_cut_loops_find(m, cone, &opt, &L, stats, err);
    if (st != SQ_OK)
        return st;
    const uint32_t g = L.genus;
    const uint32_t nb = 2 * (g - 1); /* rotation bits a_2, b_2, ..., a_g, b_g */
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    uint32_t tries = 0;
    int have = 0;
    for (uint32_t t = 0; t < opt.max_tries; ++t) {
        uint64_t rot = opt.rotation, flip = opt.flip;
        if (nb >= 64) {
            rot ^= t;
        } else {
            rot ^= (uint64_t)t & ((1ull << nb) - 1);
            flip ^= nb ? (uint64_t)t >> nb : (uint64_t)t;
        }
        ++tries;
        sq_status s = sq_cut_chain(m, cone, &L, rot, flip, &G, stats, err);
        if (s == SQ_ERR_NOMEM) {
            st = s;
            break;
        }
        if (s != SQ_OK) {
            st = s;
            continue; /* another choice may route */
        }
        sq_cut_graph_free(out);
        *out = G;
        sq_cut_graph_init(&G);
        have = 1;
        st = SQ_OK;
        if (g == 1 || out->rank == 2)
            break; /* genus 1 is rank 0 for every choice */
    }
    sq_cut_graph_free(&G);
    if (have) {
        out->tries = tries;
        st = SQ_OK;
        sq_error_clear(err);
        if (stats)
            stats->failure = SQ_CUT_FAIL_NONE;
    }
    sq_cut_loops_free(&L);
    return st;
}
