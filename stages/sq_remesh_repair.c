/* seamquad: stage 8 of the pipeline (sq_remesh.h): the quads' surface
 * tested for self-intersection (CGAL), and where it passes through itself
 * but the input does not, the quads around the intersections relaxed on
 * the surface until it no longer does.
 *
 * The intersections left after smoothing are local: around a cone of high
 * valence on a saddle (mpz/homer's valence-6 cones) or across a thin part,
 * two or three quads whose triangles (each quad split along its shorter
 * diagonal) cut each other, every vertex on the surface. The repair moves
 * the vertices of the quads involved, cones included, towards the mean of
 * their edge neighbours (at a sharp tip, libigl/decimated-knight's ears,
 * the quads around a valence-3 cone cut each other until the cone moves;
 * the referee matches irregular vertices to cones by count, not by
 * place), projected back onto the input (closest point),
 * each move halved until no quad around the vertex is folded or turned
 * over on the surface that was not (sq_quad_fold_margin,
 * sq_quad_turn_margin_on with the surface at the corners' closest
 * points); after each round the whole test runs again. A
 * round that does not lower the count widens the moved set by a ring. The
 * positions with the fewest pairs are kept; the caller fails the run if
 * any is left. Cost: one CGAL test per round (0.04 s at 5K quads). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cgal_adapter.h"
#include "sq_closest_point.h"
#include "sq_edge_hash.h"
#include "sq_remesh.h"
#include "sq_remesh_internal.h"

#define REPAIR_ROUNDS 20u
#define REPAIR_LIST 65536u

typedef struct tri_key {
    uint32_t v[3]; /* sorted corners */
    uint32_t quad;
} tri_key;

static int cmp_tri_key(const void *a, const void *b)
{
    const tri_key *x = a, *y = b;
    for (int i = 0; i < 3; i++)
        if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
    return (x->quad > y->quad) - (x->quad < y->quad);
}

/* The quads' intersecting triangle pairs, each quad split along its
 * shorter diagonal (as the referee splits them), or along the other where
 * the shorter one is already an edge of the quads or another quad's
 * diagonal: two quads that share two opposite corners (beside a cone of
 * high valence: mpz/helmet's) would otherwise give one edge four
 * triangles, which the test cannot take. Two triangles of the referee's
 * split with the same three corners count as one more pair each (two
 * quads around a cone of valence 2, both split along the diagonal that
 * does not touch it: mpz/rocker_arm's at 1K quads); the test of the
 * other split cannot see them. */
sq_status sq_remesh_quad_intersections(const sq_quad_mesh *Q, uint64_t *pairs, uint32_t *list, uint32_t cap,
                                       sq_error *err)
{
    uint32_t *tri = malloc(6 * ((size_t)Q->nq + 1) * sizeof *tri);
    tri_key *keys = malloc(2 * ((size_t)Q->nq + 1) * sizeof *keys);
    sq_edge_hash H;
    if (!tri || !keys || sq_edge_hash_init(&H, 4 * (size_t)Q->nq) != 0) { /* edges, both diagonals */
        free(tri), free(keys);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (self-intersection test)");
    }
    for (size_t i = 0; i < 4 * (size_t)Q->nq; i++) {
        const uint32_t a = Q->quad[i], b = Q->quad[i % 4 == 3 ? i - 3 : i + 1];
        H.val[sq_edge_hash_slot(&H, a < b ? a : b, a < b ? b : a)] = 1;
    }
    for (uint32_t q = 0; q < Q->nq; q++) {
        const uint32_t *c = Q->quad + 4 * (size_t)q;
        double d02 = 0, d13 = 0;
        for (int i = 0; i < 3; i++) {
            double a = Q->pos[3 * (size_t)c[2] + i] - Q->pos[3 * (size_t)c[0] + i];
            double b = Q->pos[3 * (size_t)c[3] + i] - Q->pos[3 * (size_t)c[1] + i];
            d02 += a * a, d13 += b * b;
        }
        int k = d02 <= d13 ? 0 : 1; /* the diagonal from corner k to k + 2 */
        for (int j = 0; j < 2; j++) { /* the referee's triangles */
            uint32_t a = c[k], b = c[(k + 1 + 2 * j) % 4], d = c[(k + 2) % 4];
            uint32_t lo = a < b ? (a < d ? a : d) : (b < d ? b : d), hi = a > b ? (a > d ? a : d) : (b > d ? b : d);
            tri_key *K = keys + 2 * (size_t)q + j;
            K->v[0] = lo, K->v[1] = a + b + d - lo - hi, K->v[2] = hi, K->quad = q;
        }
        size_t slot[2];
        for (int j = 0; j < 2; j++) {
            const uint32_t a = c[j], b = c[j + 2];
            slot[j] = sq_edge_hash_slot(&H, a < b ? a : b, a < b ? b : a);
        }
        /* both taken: the shorter, and the test names the triangle */
        if (H.val[slot[k]] != SQ_NONE && H.val[slot[1 - k]] == SQ_NONE) k = 1 - k;
        H.val[slot[k]] = 1;
        uint32_t *t = tri + 6 * (size_t)q;
        t[0] = c[k], t[1] = c[k + 1], t[2] = c[(k + 2) % 4];
        t[3] = c[k], t[4] = c[(k + 2) % 4], t[5] = c[(k + 3) % 4];
    }
    sq_edge_hash_free(&H);
    sq_status st = sq_cgal_self_intersections(Q->nv, Q->pos, 2 * Q->nq, tri, pairs, list, cap, err);
    if (list) /* triangles 2q and 2q + 1 are quad q's */
        for (uint64_t k = 0; k < 2 * (*pairs < cap ? *pairs : cap); k++) list[k] /= 2;
    if (!st) {
        qsort(keys, 2 * (size_t)Q->nq, sizeof *keys, cmp_tri_key);
        for (size_t i = 0; i + 1 < 2 * (size_t)Q->nq; i++) {
            if (memcmp(keys[i].v, keys[i + 1].v, sizeof keys[i].v) != 0) continue;
            if (list && *pairs < cap)
                list[2 * *pairs] = keys[i].quad, list[2 * *pairs + 1] = keys[i + 1].quad;
            ++*pairs;
        }
    }
    free(tri);
    free(keys);
    return st;
}

/* The smallest turn margin (sq_quad_turn_margin_on: < 0 for a quad turned
 * over on the surface) of the quads around v, each corner located at its
 * closest point on m. */
static double star_worst_turn(const sq_quad_star *S, const sq_quad_mesh *Q, const sq_cp_tree *tree,
                              const sq_mesh *m, const double *vn, uint32_t v)
{
    double worst = INFINITY;
    for (uint32_t k = S->off[v]; k < S->off[v + 1]; k++) {
        const uint32_t *q = Q->quad + 4 * (size_t)S->quad[k];
        const double *p[4], *b[4];
        uint32_t face[4];
        sq_cp_hit hit[4];
        for (int c = 0; c < 4; c++) {
            p[c] = Q->pos + 3 * (size_t)q[c];
            sq_cp_tree_query(tree, p[c], &hit[c]);
            face[c] = hit[c].tri, b[c] = hit[c].bary;
        }
        worst = fmin(worst, sq_quad_turn_margin_on(m, vn, p, face, b));
    }
    return worst;
}

sq_status sq_remesh_repair_intersections(const sq_mesh *m, sq_quad_mesh *Q, uint64_t *pairs, uint32_t *rounds,
                                         sq_error *err)
{
    uint32_t nv = Q->nv, nq = Q->nq;
    *rounds = 0;
    uint32_t *list = malloc(2 * (size_t)REPAIR_LIST * sizeof *list), *tri = NULL;
    uint8_t *mark = calloc((size_t)nv + 1, 1), *grow = calloc((size_t)nv + 1, 1);
    double *best = malloc(3 * ((size_t)nv + 1) * sizeof *best), *vn = NULL;
    sq_quad_star S = {NULL, NULL, NULL};
    sq_cp_tree tree;
    memset(&tree, 0, sizeof tree);
    sq_status st = SQ_OK;
    if (!list || !mark || !grow || !best) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (intersection repair)");
        goto done;
    }
    if ((st = sq_remesh_quad_intersections(Q, pairs, list, REPAIR_LIST, err)) || !*pairs) goto done;
    if (!(tri = sq_mesh_triangles(m)) || !(vn = sq_mesh_vertex_normals(m))) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (intersection repair)");
        goto done;
    }
    if ((st = sq_cp_tree_build(m->nv, m->pos, m->nf, tri, &tree, err))) goto done;
    /* quads around each vertex, and every edge neighbour once (S.next) */
    if ((st = sq_quad_star_build(nv, nq, Q->quad, &S, err))) goto done;
    uint64_t best_pairs = *pairs;
    memcpy(best, Q->pos, 3 * (size_t)nv * sizeof *best);
    uint32_t ring = 0;
    while (*rounds < REPAIR_ROUNDS && *pairs) {
        memset(mark, 0, nv);
        uint64_t listed = *pairs < REPAIR_LIST ? *pairs : REPAIR_LIST;
        for (uint64_t k = 0; k < 2 * listed; k++)
            for (int c = 0; c < 4; c++) mark[Q->quad[4 * (size_t)list[k] + c]] = 1;
        for (uint32_t r = 0; r < ring; r++) {
            memcpy(grow, mark, nv);
            for (uint32_t v = 0; v < nv; v++)
                if (mark[v])
                    for (uint32_t k = S.off[v]; k < S.off[v + 1]; k++) grow[S.next[k]] = 1;
            memcpy(mark, grow, nv);
        }
        for (uint32_t v = 0; v < nv; v++) {
            if (!mark[v]) continue;
            double *p = Q->pos + 3 * (size_t)v, old[3], tgt[3] = {0, 0, 0};
            memcpy(old, p, sizeof old);
            uint32_t deg = S.off[v + 1] - S.off[v];
            for (uint32_t k = S.off[v]; k < S.off[v + 1]; k++)
                for (int i = 0; i < 3; i++) tgt[i] += Q->pos[3 * (size_t)S.next[k] + i] / deg;
            double before = sq_quad_star_worst_margin(&S, Q->pos, Q->quad, v);
            double turn_before = star_worst_turn(&S, Q, &tree, m, vn, v);
            int moved = 0;
            for (double step = 1.0; step > 1.0 / 16 && !moved; step *= 0.5) {
                double x[3];
                for (int i = 0; i < 3; i++) x[i] = old[i] + step * (tgt[i] - old[i]);
                sq_cp_hit hit;
                sq_cp_tree_query(&tree, x, &hit);
                memcpy(p, hit.point, sizeof old);
                double after = sq_quad_star_worst_margin(&S, Q->pos, Q->quad, v);
                moved = after >= 0.0 || after >= before;
                if (moved) {
                    double turn = star_worst_turn(&S, Q, &tree, m, vn, v);
                    moved = turn >= 0.0 || turn >= turn_before;
                }
            }
            if (!moved) memcpy(p, old, sizeof old);
        }
        ++*rounds;
        if ((st = sq_remesh_quad_intersections(Q, pairs, list, REPAIR_LIST, err))) goto done;
        if (*pairs < best_pairs) {
            best_pairs = *pairs;
            memcpy(best, Q->pos, 3 * (size_t)nv * sizeof *best);
        } else {
            ring++;
        }
    }
    memcpy(Q->pos, best, 3 * (size_t)nv * sizeof *best);
    *pairs = best_pairs;
done:
    sq_cp_tree_free(&tree);
    sq_quad_star_free(&S);
    free(list), free(tri), free(mark), free(grow), free(best), free(vn);
    return st;
}
