/* Step 3 of the extraction: the quads of the traced grid edges.
 *
 * Every slot s (an outgoing direction of a grid point) has been traced to
 * to[s], the slot of its end point pointing back. A grid edge is the pair
 * {s, to[s]}: to[to[s]] = s must hold, or the two traces of one edge
 * disagree.
 *
 * The quad on the left of the directed edge s = (p -> q): at q, arriving
 * through slot j = to[s] (the direction back to p), turning left by 90
 * degrees is the next slot clockwise from j, j - 1 (slots run
 * counterclockwise). Four such steps must come back to s. The corners of a
 * quad at q are thus pairs of consecutive slots (j - 1, j), so a point with
 * k slots gets exactly k quad corners in one fan: when every slot is in
 * exactly one quad, the mesh is closed, manifold, oriented like the map
 * (the face lies left of its edges in every chart) and each point has the
 * valence of its slots.
 *
 * Checked at the end: the Euler characteristic is the map's, the quad
 * count is the map's UV area (each quad is a unit square of the grid), and
 * the mesh is connected.
 *
 * A valid integer-grid map can still be too coarse for a quad mesh (a grid
 * edge from a point back to itself, two grid edges between the same two
 * points, a quad through one point twice, as on a 1 x 1 torus): refused
 * with SQ_ERR_DEGENERATE naming the grid point. Everything else that does
 * not fit is a broken invariant (SQ_ERR_INTERNAL). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_extract_internal.h"
#include "sq_union_find.h"

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The slot that turns left after arriving through slot t. */
static uint32_t turn_left(const sq_grid *G, uint32_t t)
{
    uint32_t q = G->slot_point[t], o = G->slot_off[q], k = G->slot_off[q + 1] - o;
    return o + (t - o + k - 1) % k;
}

sq_status sq_grid_quads(const sq_map *M, const sq_grid *G, const uint32_t *to, sq_quad_mesh *out,
                        sq_extract_stats *stats, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint32_t S = G->nslot;
    char a[160];
    for (uint32_t s = 0; s < S; s++)
        if (to[s] >= S)
            return sq_error_set(err, SQ_ERR_INTERNAL, "grid direction %u traced to %u of %u", s,
                                to[s], S);
    for (uint32_t s = 0; s < S; s++) {
        if (to[to[s]] != s) {
            char b[160], c[160];
            uint32_t t = to[s];
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "the grid edge from %s in direction %u ends at %s, whose "
                                "direction %u back along it ends at %s",
                                sq_grid_describe(G, G->slot_point[s], a, sizeof a),
                                (unsigned)G->slot_dir[s], sq_grid_describe(G, G->slot_point[t], b, sizeof b),
                                (unsigned)G->slot_dir[t],
                                sq_grid_describe(G, G->slot_point[to[t]], c, sizeof c));
        }
        if (G->slot_point[to[s]] == G->slot_point[s])
            return sq_error_set(err, SQ_ERR_DEGENERATE,
                                "the grid edge from %s in direction %u comes back to its own point: "
                                "the map is too coarse for a quad mesh there",
                                sq_grid_describe(G, G->slot_point[s], a, sizeof a),
                                (unsigned)G->slot_dir[s]);
    }
    if (S % 4)
        return sq_error_set(err, SQ_ERR_INTERNAL, "%u grid directions: not a multiple of 4", S);

    /* no two edges between the same two points */
    uint64_t *key = malloc((size_t)(S / 2 + 1) * sizeof *key);
    if (!key) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid edges)");
    uint32_t ne = 0;
    for (uint32_t s = 0; s < S; s++) {
        uint32_t p = G->slot_point[s], q = G->slot_point[to[s]];
        if (p < q) key[ne++] = (uint64_t)p << 32 | q;
    }
    qsort(key, ne, sizeof *key, cmp_u64);
    for (uint32_t i = 1; i < ne; i++) {
        if (key[i] != key[i - 1]) continue;
        char b[160];
        uint32_t p = (uint32_t)(key[i] >> 32), q = (uint32_t)key[i];
        free(key);
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "two grid edges join %s and %s: the quad mesh would not be manifold "
                            "(the map is too coarse there)",
                            sq_grid_describe(G, p, a, sizeof a), sq_grid_describe(G, q, b, sizeof b));
    }
    free(key);

    uint32_t nq = S / 4;
    uint8_t *used = calloc(S ? S : 1, 1);
    out->quad = malloc(4 * (size_t)(nq ? nq : 1) * sizeof *out->quad);
    out->valence = malloc((size_t)G->n * sizeof *out->valence);
    if (!used || !out->quad || !out->valence) {
        free(used);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quads)");
    }
    uint32_t f = 0;
    for (uint32_t s0 = 0; s0 < S; s0++) {
        if (used[s0]) continue;
        uint32_t s = s0;
        for (int k = 0; k < 4; k++) {
            if (used[s] || f == nq) {
                free(used);
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "the quad left of the grid edge from %s in direction %u "
                                    "meets a direction used by another quad after %d edges",
                                    sq_grid_describe(G, G->slot_point[s0], a, sizeof a),
                                    (unsigned)G->slot_dir[s0], k);
            }
            used[s] = 1;
            out->quad[4 * (size_t)f + k] = G->slot_point[s];
            s = turn_left(G, to[s]);
        }
        if (s != s0) {
            free(used);
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "the face left of the grid edge from %s in direction %u does not "
                                "close after 4 edges",
                                sq_grid_describe(G, G->slot_point[s0], a, sizeof a),
                                (unsigned)G->slot_dir[s0]);
        }
        const uint32_t *v = out->quad + 4 * (size_t)f;
        for (int i = 0; i < 4; i++)
            for (int j = i + 1; j < 4; j++)
                if (v[i] == v[j]) {
                    free(used);
                    return sq_error_set(err, SQ_ERR_DEGENERATE,
                                        "quad %u has %s twice: the map is too coarse there", f,
                                        sq_grid_describe(G, v[i], a, sizeof a));
                }
        f++;
    }
    free(used);
    if (f != nq)
        return sq_error_set(err, SQ_ERR_INTERNAL, "%u quads from %u grid directions", f, S);

    int64_t chi_map = (int64_t)m->nv - m->nh / 2 + m->nf;
    int64_t chi = (int64_t)G->n - S / 2 + nq;
    if (chi != chi_map)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "the quad mesh has Euler characteristic %lld, the map's mesh %lld",
                            (long long)chi, (long long)chi_map);
    /* each quad is a unit square of the grid: together they cover the UV
     * area (summed in doubles: far closer than 1/2 to the integer) */
    double area = 0.0;
    for (uint32_t g = 0; g < m->nf; g++) {
        uint32_t h0 = m->f_he[g], h1 = m->he_next[h0], h2 = m->he_next[h1];
        const double *a0 = M->he_uv + 2 * (size_t)h0, *a1 = M->he_uv + 2 * (size_t)h1,
                     *a2 = M->he_uv + 2 * (size_t)h2;
        area += 0.5 * ((a1[0] - a0[0]) * (a2[1] - a0[1]) - (a1[1] - a0[1]) * (a2[0] - a0[0]));
    }
    if (!(area > nq - 0.5 && area < nq + 0.5))
        return sq_error_set(err, SQ_ERR_INTERNAL, "%u quads, but the map's UV area is %.17g", nq,
                            area);
    /* one component, as the map's connected mesh */
    uint32_t *parent = malloc((size_t)G->n * sizeof *parent), comps = G->n;
    if (!parent) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quads)");
    sq_uf_init(parent, G->n);
    for (uint32_t s = 0; s < S; s++)
        comps -= (uint32_t)sq_uf_union(parent, G->slot_point[s], G->slot_point[to[s]]);
    free(parent);
    if (comps != 1)
        return sq_error_set(err, SQ_ERR_INTERNAL, "the quad mesh has %u components", comps);
    uint32_t irregular = 0;
    for (uint32_t p = 0; p < G->n; p++) {
        out->valence[p] = (int32_t)(G->slot_off[p + 1] - G->slot_off[p]);
        irregular += out->valence[p] != 4;
    }
    out->nq = nq;
    if (stats) {
        stats->quads = nq;
        stats->edges = S / 2;
        stats->irregular = irregular;
    }
    return SQ_OK;
}
