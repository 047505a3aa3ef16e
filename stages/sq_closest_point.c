/* seamquad: bounding-volume hierarchy over triangles and exact nearest-point
 * queries (branch and bound: visit the nearer child first, prune every node
 * whose box is farther than the best distance found so far). */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "sq_closest_point.h"

#define LEAF_SIZE 4
#define STACK_MAX 128

typedef struct keyed keyed;

typedef struct build_ctx {
    sq_cp_tree *t;
    double *centroid; /* 3*nt */
    keyed *scratch;   /* nt   */
} build_ctx;

static void node_bounds(const sq_cp_tree *t, sq_cp_node *n)
{
    for (int k = 0; k < 3; k++) n->lo[k] = DBL_MAX, n->hi[k] = -DBL_MAX;
    for (uint32_t i = n->first; i < n->first + n->count; i++) {
        const double *c = t->corner + 9 * (size_t)t->tri_order[i];
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                if (c[3 * j + k] < n->lo[k]) n->lo[k] = c[3 * j + k];
                if (c[3 * j + k] > n->hi[k]) n->hi[k] = c[3 * j + k];
            }
    }
}

typedef struct keyed {
    double key;
    uint32_t tri;
} keyed;

static int cmp_keyed(const void *x, const void *y)
{
    const keyed *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return a->tri < b->tri ? -1 : a->tri > b->tri;
}

/* Sorts tri_order[first, first+count) by centroid coordinate `axis` and
 * returns the size of the left half. */
static uint32_t split_median(build_ctx *b, uint32_t first, uint32_t count, int axis)
{
    uint32_t *o = b->t->tri_order + first;
    for (uint32_t i = 0; i < count; i++) {
        b->scratch[i].key = b->centroid[3 * (size_t)o[i] + axis];
        b->scratch[i].tri = o[i];
    }
    qsort(b->scratch, count, sizeof(keyed), cmp_keyed);
    for (uint32_t i = 0; i < count; i++) o[i] = b->scratch[i].tri;
    return count / 2;
}

static void build_node(build_ctx *b, uint32_t ni)
{
    sq_cp_tree *t = b->t;
    sq_cp_node *n = &t->node[ni];
    node_bounds(t, n);
    if (n->count <= LEAF_SIZE) return;
    double clo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, chi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    for (uint32_t i = n->first; i < n->first + n->count; i++)
        for (int k = 0; k < 3; k++) {
            double c = b->centroid[3 * (size_t)t->tri_order[i] + k];
            if (c < clo[k]) clo[k] = c;
            if (c > chi[k]) chi[k] = c;
        }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
    uint32_t first = n->first, count = n->count;
    uint32_t nl = split_median(b, first, count, axis);
    uint32_t left = t->nnode;
    t->nnode += 2;
    n = &t->node[ni]; /* (array does not move: allocated for the worst case) */
    n->first = left;
    n->count = 0;
    t->node[left].first = first, t->node[left].count = nl;
    t->node[left + 1].first = first + nl, t->node[left + 1].count = count - nl;
    build_node(b, left);
    build_node(b, left + 1);
}

sq_status sq_cp_tree_build(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri,
                           sq_cp_tree *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (nt == 0 || !pos || !tri)
        return sq_error_set(err, SQ_ERR_EMPTY, "closest point: no triangles to build a tree on");
    for (size_t i = 0; i < 3 * (size_t)nt; i++)
        if (tri[i] >= nv)
            return sq_error_set(err, SQ_ERR_INDEX, "closest point: triangle %zu uses vertex %u of %u",
                                i / 3, tri[i], nv);
    out->nt = nt;
    out->corner = malloc(9 * (size_t)nt * sizeof(double));
    out->tri_order = malloc((size_t)nt * sizeof(uint32_t));
    out->node = malloc(2 * (size_t)nt * sizeof(sq_cp_node));
    double *centroid = malloc(3 * (size_t)nt * sizeof(double));
    keyed *scratch = malloc((size_t)nt * sizeof(keyed));
    if (!out->corner || !out->tri_order || !out->node || !centroid || !scratch) {
        free(centroid);
        free(scratch);
        sq_cp_tree_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "closest point: out of memory for %u triangles", nt);
    }
    for (uint32_t f = 0; f < nt; f++) {
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) out->corner[9 * (size_t)f + 3 * j + k] = pos[3 * (size_t)tri[3 * (size_t)f + j] + k];
        for (int k = 0; k < 3; k++)
            centroid[3 * (size_t)f + k] = (out->corner[9 * (size_t)f + k] + out->corner[9 * (size_t)f + 3 + k] +
                                           out->corner[9 * (size_t)f + 6 + k]) / 3.0;
        out->tri_order[f] = f;
    }
    build_ctx b = {out, centroid, scratch};
    out->nnode = 1;
    out->node[0].first = 0, out->node[0].count = nt;
    build_node(&b, 0);
    free(centroid);
    free(scratch);
    return SQ_OK;
}

void sq_cp_tree_free(sq_cp_tree *t)
{
    if (!t) return;
    free(t->corner);
    free(t->tri_order);
    free(t->node);
    memset(t, 0, sizeof *t);
}

static double box_dist2(const sq_cp_node *n, const double p[3])
{
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double d = p[k] < n->lo[k] ? n->lo[k] - p[k] : p[k] > n->hi[k] ? p[k] - n->hi[k] : 0.0;
        d2 += d * d;
    }
    return d2;
}

static void test_tri(const sq_cp_tree *t, uint32_t f, const double p[3], sq_cp_hit *hit)
{
    const double *c = t->corner + 9 * (size_t)f;
    double bary[3], q[3];
    sq_closest_point_triangle(p, c, c + 3, c + 6, bary, q);
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) d2 += (q[k] - p[k]) * (q[k] - p[k]);
    if (d2 < hit->dist2 || (d2 == hit->dist2 && f < hit->tri)) {
        hit->dist2 = d2;
        hit->tri = f;
        memcpy(hit->bary, bary, sizeof bary);
        memcpy(hit->point, q, sizeof q);
    }
}

void sq_cp_tree_query(const sq_cp_tree *t, const double p[3], sq_cp_hit *hit)
{
    hit->dist2 = DBL_MAX;
    hit->tri = UINT32_MAX;
    /* depth <= 2 log2(nt) (median splits), far below STACK_MAX */
    uint32_t stack[STACK_MAX];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const sq_cp_node *n = &t->node[stack[--sp]];
        if (box_dist2(n, p) > hit->dist2) continue;
        if (n->count > 0) {
            for (uint32_t i = n->first; i < n->first + n->count; i++) test_tri(t, t->tri_order[i], p, hit);
            continue;
        }
        uint32_t l = n->first, r = n->first + 1;
        double dl = box_dist2(&t->node[l], p), dr = box_dist2(&t->node[r], p);
        if (sp + 2 > STACK_MAX) { /* cannot happen for median splits; stay correct anyway */
            for (uint32_t i = 0; i < t->nt; i++) test_tri(t, i, p, hit);
            return;
        }
        if (dl <= dr) stack[sp++] = r, stack[sp++] = l;
        else stack[sp++] = l, stack[sp++] = r;
    }
}
