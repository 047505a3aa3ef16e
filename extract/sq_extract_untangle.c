/* seamquad: folded and turned quads relaxed on the surface (sq_extract.h,
 * step 5).
 *
 * A quad extracted from a map is folded in 3D (in both triangulations the
 * two triangle normals differ by more than 90 degrees, the referee's test)
 * or turned over (every corner facing away from the surface:
 * sq_quad_turn_margin) where the map is strongly distorted at the scale of
 * one quad: around the cones of published maps, whose 1-rings carry most
 * of their distortion, and throughout param's maps. The connectivity is
 * right; the positions are not. Each round moves every vertex of such a
 * quad that is not a cone towards the mean of its edge neighbours (else
 * the mean of its quads' corners, else one neighbour, else the point that
 * makes one of its quads a parallelogram, else its mirror image across the
 * diagonal of one of its quads that it does not touch: the first half of
 * turning an upside-down quad back), projected back onto the surface (the
 * nearest point of the map's mesh: a barycentric combination of one
 * triangle's corners), with the step halved until the quads around the
 * vertex are better off: a higher worst margin (per quad the smaller of
 * its fold and turn margins), or the worst no lower, no more bad quads and
 * less badness in sum. No move brings two corners of a quad within 1e-9
 * of the diagonal, or its area below 1e-18 of the diagonal's square.
 * Rounds without progress widen the moved set by one ring; at most
 * SQ_UNTANGLE_ROUNDS rounds. The moves are greedy and where they get stuck
 * depends on which mirror images are offered (move_vertex's strategies),
 * so where quads are left bad the rounds start again from the extracted
 * positions with the other strategies, and the result with the fewest bad
 * quads is kept. Cones never move, every vertex stays on the surface, the
 * connectivity is untouched.
 *
 * Cost: the map's vertex normals and one closest-point tree over its
 * triangles, then work proportional to the bad quads' neighbourhoods, up
 * to three times where quads stay bad. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_closest_point.h"
#include "sq_extract.h"
#include "sq_smooth.h"

#define SQ_UNTANGLE_ROUNDS 60

/* Quad f's turn margin on the map's mesh (sq_quad_turn_margin_on at each
 * corner's loc_face and loc_bary; vn: the mesh's vertex normals). */
static double turn_margin(const sq_map *M, const sq_quad_mesh *Q, const double *vn, uint32_t f)
{
    const uint32_t *q = Q->quad + 4 * (size_t)f;
    const double *p[4], *b[4];
    uint32_t face[4];
    for (int k = 0; k < 4; k++)
        p[k] = Q->pos + 3 * (size_t)q[k], face[k] = Q->loc_face[q[k]], b[k] = Q->loc_bary + 3 * (size_t)q[k];
    return sq_quad_turn_margin_on(&M->mesh, vn, p, face, b);
}

/* The smaller of quad f's fold margin and its turn margin: negative where
 * the quad is folded or turned over. */
static double quad_margin(const sq_map *M, const sq_quad_mesh *Q, const double *vn, double min_edge, uint32_t f)
{
    const uint32_t *q = Q->quad + 4 * (size_t)f;
    const double *p0 = Q->pos + 3 * (size_t)q[0], *p1 = Q->pos + 3 * (size_t)q[1], *p2 = Q->pos + 3 * (size_t)q[2],
                 *p3 = Q->pos + 3 * (size_t)q[3];
    double area, lmin;
    sq_quad_size(p0, p1, p2, p3, &area, &lmin);
    /* two corners (nearly) at one place, or a quad (nearly) without area:
     * worse than any fold */
    if (!(lmin > min_edge) || !(area > min_edge * min_edge)) return -2.0;
    double a = sq_quad_fold_margin(p0, p1, p2, p3), b = turn_margin(M, Q, vn, f);
    return a < b ? a : b;
}

/* The quads around v judged together: the worst margin, how many are
 * negative (folded or turned), and the sum of their negative parts. */
typedef struct star_score {
    double worst, neg_sum;
    uint32_t neg;
} star_score;

static star_score star_margin(const sq_map *M, const sq_quad_star *S, const sq_quad_mesh *Q, const double *vn,
                              double min_edge, uint32_t v)
{
    star_score r = {2.0, 0.0, 0};
    for (uint32_t k = S->off[v]; k < S->off[v + 1]; k++) {
        double x = quad_margin(M, Q, vn, min_edge, S->quad[k]);
        if (x < r.worst) r.worst = x;
        if (x < 0.0) r.neg++, r.neg_sum -= x;
    }
    return r;
}

/* a better than b: a higher worst margin; or, with no lower worst margin
 * and no more bad quads, less badness in sum (a move that unfolds one of
 * two bad quads around v without touching the worst) */
static int star_better(star_score a, star_score b)
{
    if (a.worst > b.worst) return 1;
    return a.worst >= b.worst && a.neg <= b.neg && a.neg_sum < b.neg_sum * (1.0 - 1e-9);
}

/* Vertex v moved to the surface point `hit`: locate sets pos, loc_face
 * and loc_bary (enough to judge the move), place also the map's UV there
 * (no longer an integer point). */
static void locate(sq_quad_mesh *Q, uint32_t v, const sq_cp_hit *hit)
{
    memcpy(Q->pos + 3 * (size_t)v, hit->point, sizeof hit->point);
    Q->loc_face[v] = hit->tri;
    memcpy(Q->loc_bary + 3 * (size_t)v, hit->bary, sizeof hit->bary);
}

static void place(const sq_map *M, sq_quad_mesh *Q, uint32_t v, const sq_cp_hit *hit)
{
    const sq_mesh *m = &M->mesh;
    locate(Q, v, hit);
    uint32_t h = m->f_he[hit->tri];
    double uv[2] = {0, 0};
    for (int k = 0; k < 3; k++, h = m->he_next[h])
        for (int i = 0; i < 2; i++) uv[i] += hit->bary[k] * M->he_uv[2 * (size_t)h + i];
    Q->uv[2 * (size_t)v] = uv[0], Q->uv[2 * (size_t)v + 1] = uv[1];
}

/* One move of vertex v (the targets and the test in the header); 1 when
 * it moved. The mirror images are taken across the far diagonal of, by
 * strategy: 0, any quad around v, only when no other target helps; 1, a
 * turned quad, always; 2, a bad quad, only when no other target helps. */
static int move_vertex(const sq_map *M, sq_quad_mesh *Q, const sq_quad_star *S, const sq_cp_tree *tree,
                       const double *vn, double min_edge, uint32_t v, int strategy)
{
    star_score cur = star_margin(M, S, Q, vn, min_edge, v);
    if (cur.worst >= 0.5) return 0;
    sq_cp_hit now, best_hit; /* v's place, the best move's */
    memcpy(now.point, Q->pos + 3 * (size_t)v, sizeof now.point);
    now.tri = Q->loc_face[v];
    memcpy(now.bary, Q->loc_bary + 3 * (size_t)v, sizeof now.bary);
    const double *old = now.point;
    /* candidate targets: the mean of the edge neighbours, the mean
     * of the quads' corners around v, then each edge neighbour */
    uint32_t o = S->off[v], deg = S->off[v + 1] - o, ncand = 2 + 3 * deg;
    star_score best = cur;
    int found = 0;
    for (uint32_t c = 0; c < ncand; c++) {
        double tgt[3] = {0, 0, 0};
        if (c == 0) {
            for (uint32_t k = o; k < o + deg; k++)
                for (int i = 0; i < 3; i++) tgt[i] += Q->pos[3 * (size_t)S->next[k] + i] / deg;
        } else if (c == 1) {
            uint32_t n = 0;
            for (uint32_t k = o; k < o + deg; k++)
                for (int j = 0; j < 4; j++, n++)
                    for (int i = 0; i < 3; i++) tgt[i] += Q->pos[3 * (size_t)Q->quad[4 * (size_t)S->quad[k] + j] + i];
            for (int i = 0; i < 3; i++) tgt[i] /= n;
        } else if (c < 2 + deg) {
            memcpy(tgt, Q->pos + 3 * (size_t)S->next[o + c - 2], sizeof tgt);
        } else if (c < 2 + 2 * deg) { /* the corner that makes quad k a parallelogram */
            const uint32_t *q = Q->quad + 4 * (size_t)S->quad[o + c - 2 - deg];
            int j = 0;
            while (q[j] != v) j++;
            for (int i = 0; i < 3; i++)
                tgt[i] = Q->pos[3 * (size_t)q[(j + 1) % 4] + i] + Q->pos[3 * (size_t)q[(j + 3) % 4] + i] -
                         Q->pos[3 * (size_t)q[(j + 2) % 4] + i];
        } else { /* v mirrored across the diagonal of quad k that it does not touch: turns
                  * its half of a quad lying upside down (a bow tie, which the next moves
                  * of the other corners undo) */
            uint32_t f = S->quad[o + c - 2 - 2 * deg];
            if (strategy == 1 && turn_margin(M, Q, vn, f) >= 0.0) continue;
            if (strategy == 2 && quad_margin(M, Q, vn, min_edge, f) >= 0.0) continue;
            const uint32_t *q = Q->quad + 4 * (size_t)f;
            int j = 0;
            while (q[j] != v) j++;
            const double *a = Q->pos + 3 * (size_t)q[(j + 1) % 4], *b = Q->pos + 3 * (size_t)q[(j + 3) % 4];
            double d[3], w[3], dd = 0, t = 0;
            for (int i = 0; i < 3; i++) d[i] = b[i] - a[i], w[i] = old[i] - a[i], dd += d[i] * d[i], t += w[i] * d[i];
            t = dd > 0 ? t / dd : 0;
            for (int i = 0; i < 3; i++) tgt[i] = 2 * (a[i] + t * d[i]) - old[i];
        }
        for (double step = c < 2 || c >= 2 + 2 * deg ? 1.0 : 0.5; step > 1.0 / 64; step *= 0.5) {
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = old[i] + step * (tgt[i] - old[i]);
            sq_cp_hit hit;
            sq_cp_tree_query(tree, p, &hit);
            locate(Q, v, &hit);
            star_score w = star_margin(M, S, Q, vn, min_edge, v);
            locate(Q, v, &now);
            if (star_better(w, best)) {
                best = w, best_hit = hit, found = 1;
                break;
            }
        }
        if (found && c == 0) break; /* the plain mean did it */
        if (found && strategy != 1 && c == 1 + 2 * deg) break; /* mirrors: a last resort */
    }
    if (!found) return 0;
    place(M, Q, v, &best_hit);
    return 1;
}

/* Rounds of moves (header) with the given strategy (move_vertex), from
 * the bad quads' vertices; stats->moves, rounds, folded_after updated. */
static void untangle_rounds(const sq_map *M, sq_quad_mesh *Q, const sq_quad_star *S, const sq_cp_tree *tree,
                            const double *vn, double min_edge, int strategy, uint8_t *mark, uint8_t *next,
                            sq_untangle_stats *stats)
{
    uint32_t nv = Q->nv, nq = Q->nq;
    memset(mark, 0, nv);
    for (uint32_t f = 0; f < nq; f++)
        if (quad_margin(M, Q, vn, min_edge, f) < 0.0)
            for (int k = 0; k < 4; k++) mark[Q->quad[4 * (size_t)f + k]] = 1;
    for (int round = 0; round < SQ_UNTANGLE_ROUNDS; round++) {
        uint32_t moved = 0;
        for (uint32_t v = 0; v < nv; v++) {
            if (!mark[v] || Q->valence[v] != 4) continue;
            moved += (uint32_t)move_vertex(M, Q, S, tree, vn, min_edge, v, strategy);
        }
        stats->moves += moved;
        stats->rounds = (uint32_t)round + 1;
        /* the quads still folded mark their vertices; no progress: a ring more */
        uint32_t still = 0;
        memset(next, 0, nv);
        for (uint32_t f = 0; f < nq; f++)
            if (quad_margin(M, Q, vn, min_edge, f) < 0.0) {
                still++;
                for (int k = 0; k < 4; k++) next[Q->quad[4 * (size_t)f + k]] = 1;
            }
        stats->folded_after = still;
        if (!still) break;
        if (!moved)
            for (uint32_t v = 0; v < nv; v++)
                if (mark[v])
                    for (uint32_t k = S->off[v]; k < S->off[v + 1]; k++) next[S->next[k]] = 1;
        uint8_t *t = mark;
        mark = next, next = t;
    }
}

/* Where Q's vertices are (pos, loc_face, loc_bary), saved and put back
 * (place recomputes their UVs). */
typedef struct saved_places {
    double *pos, *bary;
    uint32_t *face;
} saved_places;

static void save_places(const sq_quad_mesh *Q, saved_places *s)
{
    memcpy(s->pos, Q->pos, 3 * (size_t)Q->nv * sizeof *s->pos);
    memcpy(s->bary, Q->loc_bary, 3 * (size_t)Q->nv * sizeof *s->bary);
    memcpy(s->face, Q->loc_face, (size_t)Q->nv * sizeof *s->face);
}

static void restore_places(const sq_map *M, sq_quad_mesh *Q, const saved_places *s)
{
    for (uint32_t v = 0; v < Q->nv; v++) {
        sq_cp_hit hit;
        memcpy(hit.point, s->pos + 3 * (size_t)v, sizeof hit.point);
        memcpy(hit.bary, s->bary + 3 * (size_t)v, sizeof hit.bary);
        hit.tri = s->face[v];
        place(M, Q, v, &hit);
    }
}

sq_status sq_extract_untangle(const sq_map *M, sq_quad_mesh *Q, sq_untangle_stats *stats, sq_error *err)
{
    sq_untangle_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    const sq_mesh *m = &M->mesh;
    uint32_t nv = Q->nv, nq = Q->nq;
    double *vn = sq_mesh_vertex_normals(m);
    /* edges the moves may not shorten below: 1e-9 of the diagonal (step 6
     * refuses 1e-12) */
    double min_edge = 1e-9 * sq_bbox_diagonal(m->nv, m->pos);
    if (!vn) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (untangling %u quads)", nq);
    for (uint32_t f = 0; f < nq; f++) stats->folded_before += quad_margin(M, Q, vn, min_edge, f) < 0.0;
    stats->folded_after = stats->folded_before;
    if (!stats->folded_before) {
        free(vn);
        return SQ_OK;
    }
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
    /* strategy 0, then, where quads are left bad, 1 and 2 from the same
     * start (the moves are greedy, and which one gets stuck differs from
     * map to map): the result with the fewest bad quads is kept */
    size_t n3 = 3 * (size_t)nv;
    double *buf = malloc(4 * n3 * sizeof *buf);
    uint32_t *faces = malloc(2 * (size_t)nv * sizeof *faces);
    if (!buf || !faces) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (untangling %u quads)", nq);
        free(buf), free(faces);
        goto done;
    }
    saved_places start = {buf, buf + n3, faces}, best = {buf + 2 * n3, buf + 3 * n3, faces + nv};
    save_places(Q, &start);
    sq_untangle_stats s0 = *stats;
    untangle_rounds(M, Q, &S, &tree, vn, min_edge, 0, mark, next, &s0);
    for (int strategy = 1; strategy < 3 && s0.folded_after; strategy++) {
        sq_untangle_stats s1 = *stats;
        save_places(Q, &best);
        restore_places(M, Q, &start);
        untangle_rounds(M, Q, &S, &tree, vn, min_edge, strategy, mark, next, &s1);
        if (s1.folded_after < s0.folded_after) s0 = s1;
        else restore_places(M, Q, &best);
    }
    *stats = s0;
    free(buf), free(faces);
done:
    sq_cp_tree_free(&tree);
    sq_quad_star_free(&S);
    free(tri), free(mark), free(next), free(vn);
    return st;
}
