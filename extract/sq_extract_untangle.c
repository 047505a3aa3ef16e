/* seamquad: folded quads relaxed on the surface (sq_extract.h, step 5).
 *
 * A quad extracted from a map is folded in 3D (in both triangulations the
 * two triangle normals differ by more than 90 degrees, the referee's test)
 * where the map is strongly distorted at the scale of one quad: around the
 * cones of published maps, whose 1-rings carry most of their distortion.
 * The connectivity is right; the positions are not. Each round moves every
 * vertex of a folded quad that is not a cone towards the mean of its edge
 * neighbours (else the mean of its quads' corners, else one neighbour,
 * else the point that makes one of its quads a parallelogram),
 * projected back onto the surface (the nearest point of the map's mesh: a
 * barycentric combination of one triangle's corners), with the step
 * halved until the worst fold margin (sq_quad_fold_margin) of the quads
 * around the vertex rises; a move that does not raise it is not made. Rounds without progress widen the moved set by one ring; at most
 * SQ_UNTANGLE_ROUNDS rounds. Cones never move, every vertex stays on the
 * surface, the connectivity is untouched.
 *
 * Cost: one closest-point tree over the map's triangles, then work
 * proportional to the folded quads' neighbourhoods. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_closest_point.h"
#include "sq_extract.h"
#include "sq_smooth.h"

#define SQ_UNTANGLE_ROUNDS 60

static int folded(const sq_quad_mesh *Q, uint32_t f)
{
    const uint32_t *q = Q->quad + 4 * (size_t)f;
    return sq_quad_fold_margin(Q->pos + 3 * (size_t)q[0], Q->pos + 3 * (size_t)q[1], Q->pos + 3 * (size_t)q[2],
                               Q->pos + 3 * (size_t)q[3]) < 0.0;
}

sq_status sq_extract_untangle(const sq_map *M, sq_quad_mesh *Q, sq_untangle_stats *stats, sq_error *err)
{
    sq_untangle_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    const sq_mesh *m = &M->mesh;
    uint32_t nv = Q->nv, nq = Q->nq;
    for (uint32_t f = 0; f < nq; f++) stats->folded_before += folded(Q, f);
    stats->folded_after = stats->folded_before;
    if (!stats->folded_before) return SQ_OK;
    uint32_t *tri = sq_mesh_triangles(m);
    uint8_t *mark = calloc(nv, 1), *next = calloc(nv, 1);
    sq_quad_star S = {NULL, NULL, NULL};
    sq_cp_tree tree;
    memset(&tree, 0, sizeof tree);
    sq_status st = SQ_OK;
    if (!tri || !mark || !next) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (untangling %u quads)", nq);
        goto done;
    }
    if ((st = sq_cp_tree_build(m->nv, m->pos, m->nf, tri, &tree, err))) goto done;
    /* quads around each vertex; edge neighbours (S.next: each quad edge
     * once from each side, the mesh being closed and manifold) */
    if ((st = sq_quad_star_build(nv, nq, Q->quad, &S, err))) goto done;
    for (uint32_t f = 0; f < nq; f++)
        if (folded(Q, f))
            for (int k = 0; k < 4; k++) mark[Q->quad[4 * (size_t)f + k]] = 1;
    for (int round = 0; round < SQ_UNTANGLE_ROUNDS; round++) {
        uint32_t moved = 0;
        for (uint32_t v = 0; v < nv; v++) {
            if (!mark[v] || Q->valence[v] != 4) continue;
            double cur = sq_quad_star_worst_margin(&S, Q->pos, Q->quad, v), old[3];
            if (cur >= 0.5) continue;
            memcpy(old, Q->pos + 3 * (size_t)v, sizeof old);
            /* candidate targets: the mean of the edge neighbours, the mean
             * of the quads' corners around v, then each edge neighbour */
            uint32_t o = S.off[v], deg = S.off[v + 1] - o, ncand = 2 + 2 * deg;
            double best = cur, best_p[3] = {0, 0, 0}, best_bary[3] = {0, 0, 0};
            uint32_t best_tri = UINT32_MAX;
            for (uint32_t c = 0; c < ncand; c++) {
                double tgt[3] = {0, 0, 0};
                if (c == 0) {
                    for (uint32_t k = o; k < o + deg; k++)
                        for (int i = 0; i < 3; i++) tgt[i] += Q->pos[3 * (size_t)S.next[k] + i] / deg;
                } else if (c == 1) {
                    uint32_t n = 0;
                    for (uint32_t k = o; k < o + deg; k++)
                        for (int j = 0; j < 4; j++, n++)
                            for (int i = 0; i < 3; i++) tgt[i] += Q->pos[3 * (size_t)Q->quad[4 * (size_t)S.quad[k] + j] + i];
                    for (int i = 0; i < 3; i++) tgt[i] /= n;
                } else if (c < 2 + deg) {
                    memcpy(tgt, Q->pos + 3 * (size_t)S.next[o + c - 2], sizeof tgt);
                } else { /* the corner that makes quad k a parallelogram */
                    const uint32_t *q = Q->quad + 4 * (size_t)S.quad[o + c - 2 - deg];
                    int j = 0;
                    while (q[j] != v) j++;
                    for (int i = 0; i < 3; i++)
                        tgt[i] = Q->pos[3 * (size_t)q[(j + 1) % 4] + i] + Q->pos[3 * (size_t)q[(j + 3) % 4] + i] -
                                 Q->pos[3 * (size_t)q[(j + 2) % 4] + i];
                }
                for (double step = c < 2 ? 1.0 : 0.5; step > 1.0 / 64; step *= 0.5) {
                    double p[3];
                    for (int i = 0; i < 3; i++) p[i] = old[i] + step * (tgt[i] - old[i]);
                    sq_cp_hit hit;
                    sq_cp_tree_query(&tree, p, &hit);
                    memcpy(Q->pos + 3 * (size_t)v, hit.point, sizeof hit.point);
                    double w = sq_quad_star_worst_margin(&S, Q->pos, Q->quad, v);
                    memcpy(Q->pos + 3 * (size_t)v, old, sizeof old);
                    if (w > best) {
                        best = w, best_tri = hit.tri;
                        memcpy(best_p, hit.point, sizeof best_p);
                        memcpy(best_bary, hit.bary, sizeof best_bary);
                        break;
                    }
                }
                if (best_tri != UINT32_MAX && c == 0) break; /* the plain mean did it */
            }
            if (best_tri == UINT32_MAX) continue;
            memcpy(Q->pos + 3 * (size_t)v, best_p, sizeof best_p);
            Q->loc_face[v] = best_tri;
            memcpy(Q->loc_bary + 3 * (size_t)v, best_bary, sizeof best_bary);
            /* the map's UV there (no longer an integer point) */
            uint32_t h = m->f_he[best_tri];
            double uv[2] = {0, 0};
            for (int k = 0; k < 3; k++, h = m->he_next[h])
                for (int i = 0; i < 2; i++) uv[i] += best_bary[k] * M->he_uv[2 * (size_t)h + i];
            Q->uv[2 * (size_t)v] = uv[0], Q->uv[2 * (size_t)v + 1] = uv[1];
            moved++;
        }
        stats->moves += moved;
        stats->rounds = (uint32_t)round + 1;
        /* the quads still folded mark their vertices; no progress: a ring more */
        uint32_t still = 0;
        memset(next, 0, nv);
        for (uint32_t f = 0; f < nq; f++)
            if (folded(Q, f)) {
                still++;
                for (int k = 0; k < 4; k++) next[Q->quad[4 * (size_t)f + k]] = 1;
            }
        stats->folded_after = still;
        if (!still) break;
        if (!moved)
            for (uint32_t v = 0; v < nv; v++)
                if (mark[v])
                    for (uint32_t k = S.off[v]; k < S.off[v + 1]; k++) next[S.next[k]] = 1;
        uint8_t *t = mark;
        mark = next, next = t;
    }
done:
    sq_cp_tree_free(&tree);
    sq_quad_star_free(&S);
    free(tri), free(mark), free(next);
    return st;
}
