/* seamquad: Tutte's map of an open triangulated disk (step 7', the
 * overlay's two disk maps; sq_param_overlay.c). */
#include <pthread.h>
#include <stdlib.h>

#include "sq_mean_value.h"
#include "sq_param_internal.h"
#include "sq_sparse.h"

/* Pairs the halfedges of buckets [v0, v1) (start[v]: the end of bucket v,
 * bucket by smaller vertex); returns 0 or -2 (see sq_param_pair_twins). */
typedef struct pair_job {
    const uint32_t *tri, *start, *bucket;
    uint32_t *twin;
    uint32_t v0, v1;
    int r;
} pair_job;

static void *pair_buckets(void *arg)
{
    pair_job *J = arg;
    const uint32_t *tri = J->tri, *start = J->start, *bucket = J->bucket;
    int r = 0;
    for (uint32_t v = J->v0, begin = v ? start[v - 1] : 0; v < J->v1; begin = start[v++])
        for (uint32_t i = begin; i < start[v]; i++) {
            uint32_t h = bucket[i], a = tri[h], b = tri[sq_param_corner_next(h)], hi = a < b ? b : a;
            uint32_t same = 0, other = SQ_NONE;
            for (uint32_t k = begin; k < start[v]; k++) {
                uint32_t g = bucket[k];
                if (g == h) continue;
                uint32_t c = tri[g], d = tri[sq_param_corner_next(g)];
                if ((c < d ? d : c) != hi) continue;
                same++;
                if (c == b && d == a) other = g;
                else r = -2; /* two halfedges in one direction */
            }
            if (same > 1) r = -2; /* an edge with more than two halfedges */
            if (same == 1 && other != SQ_NONE) J->twin[h] = other;
        }
    J->r = r;
    return NULL;
}

int sq_param_pair_twins(uint32_t nf, const uint32_t *tri, uint32_t *twin)
{
    return sq_param_pair_twins_threads(nf, tri, twin, 1);
}

int sq_param_pair_twins_threads(uint32_t nf, const uint32_t *tri, uint32_t *twin, uint32_t threads)
{
    /* halfedges bucketed by their smaller vertex (a counting sort), then
     * paired within each bucket by the larger one (the buckets split
     * between two threads where asked: each writes its own halfedges'
     * twins, the same result) */
    size_t nh = 3 * (size_t)nf;
    uint32_t nv = 0;
    for (size_t h = 0; h < nh; h++)
        if (tri[h] >= nv) nv = tri[h] + 1;
    uint32_t *start = calloc((size_t)nv + 1, sizeof *start), *bucket = malloc((nh ? nh : 1) * sizeof *bucket);
    if (!start || !bucket) {
        free(start), free(bucket);
        return -1;
    }
    for (size_t h = 0; h < nh; h++) {
        uint32_t a = tri[h], b = tri[sq_param_corner_next((uint32_t)h)];
        start[(a < b ? a : b) + 1]++;
        twin[h] = SQ_NONE;
    }
    for (uint32_t v = 0; v < nv; v++) start[v + 1] += start[v];
    for (size_t h = 0; h < nh; h++) {
        uint32_t a = tri[h], b = tri[sq_param_corner_next((uint32_t)h)];
        bucket[start[a < b ? a : b]++] = (uint32_t)h;
    }
    /* start[v] is now the end of bucket v */
    uint32_t split = threads > 1 ? 0 : nv; /* the first bucket ending past half the halfedges */
    while (split < nv && start[split] < nh / 2) split++;
    pair_job J[2] = {{tri, start, bucket, twin, 0, split, 0}, {tri, start, bucket, twin, split, nv, 0}};
    pthread_t th;
    int helper = split < nv && pthread_create(&th, NULL, pair_buckets, &J[1]) == 0;
    pair_buckets(&J[0]);
    if (helper) pthread_join(th, NULL);
    else if (split < nv) pair_buckets(&J[1]);
    free(start), free(bucket);
    return J[0].r ? J[0].r : J[1].r;
}

/* Tutte's map of one mesh (nf triangles tri, twins twin) onto the disk:
 * its interior vertices [first, first + n) at the mean-value-weighted mean
 * of their neighbours (one UMFPACK solve), the other vertices fixed at
 * their xy. p3: a 3D position per vertex id, for the weights. */
sq_status sq_param_disk_tutte(uint32_t nf, const uint32_t *tri, const uint32_t *twin, uint32_t first,
                              uint32_t n, const double *p3, double *xy, sq_error *err)
{
    if (!n) return SQ_OK;
    size_t nh = 3 * (size_t)nf, nnz = 0;
    uint32_t *ri = malloc((nh + n) * sizeof *ri), *cj = malloc((nh + n) * sizeof *cj);
    double *val = malloc((nh + n) * sizeof *val), *rhs = calloc(2 * (size_t)n, sizeof *rhs),
           *diag = calloc(n, sizeof *diag), *x = malloc(2 * (size_t)n * sizeof *x);
    sq_lu *lu = NULL;
    sq_status st = SQ_OK;
    if (!ri || !cj || !val || !rhs || !diag || !x) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (size_t h = 0; h < nh; h++) {
        uint32_t v = tri[h];
        if (v < first || v >= first + n) continue;
        uint32_t hn = sq_param_corner_next((uint32_t)h), hp = sq_param_corner_prev((uint32_t)h);
        uint32_t w = tri[hn], a = tri[hp], t = twin[h];
        if (t == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "disk map: interior vertex %u on a boundary edge", v);
            goto done;
        }
        uint32_t b = tri[sq_param_corner_prev(t)];
        double wt = sq_mean_value_weight(p3 + 3 * (size_t)v, p3 + 3 * (size_t)w, p3 + 3 * (size_t)a,
                                         p3 + 3 * (size_t)b);
        diag[v - first] += wt;
        if (w >= first && w < first + n) {
            ri[nnz] = v - first, cj[nnz] = w - first, val[nnz] = -wt, nnz++;
        } else {
            rhs[v - first] += wt * xy[2 * (size_t)w];
            rhs[n + v - first] += wt * xy[2 * (size_t)w + 1];
        }
    }
    for (uint32_t i = 0; i < n; i++) ri[nnz] = i, cj[nnz] = i, val[nnz] = diag[i], nnz++;
    st = sq_lu_factor(n, nnz, ri, cj, val, &lu, err);
    if (st == SQ_OK) st = sq_lu_solve(lu, 2, rhs, x, err);
    if (st) goto done;
    for (uint32_t i = 0; i < n; i++) xy[2 * ((size_t)first + i)] = x[i], xy[2 * ((size_t)first + i) + 1] = x[n + i];
done:
    if (lu) sq_lu_free(lu);
    free(ri), free(cj), free(val), free(rhs), free(diag), free(x);
    return st;
}
