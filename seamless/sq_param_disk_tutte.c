/* seamquad: Tutte's map of an open triangulated disk (step 7', the
 * overlay's two disk maps; sq_param.c). */
#include <stdlib.h>

#include "sq_mean_value.h"
#include "sq_param_internal.h"
#include "sq_sparse.h"

/* sq_param_pair_twins sorts the halfedges by their vertex pair */
typedef struct edge_key {
    uint64_t key;
    uint32_t h;
} edge_key;

static int edge_key_cmp(const void *x, const void *y)
{
    const edge_key *a = x, *b = y;
    return a->key < b->key ? -1 : a->key > b->key ? 1 : (a->h > b->h) - (a->h < b->h);
}

int sq_param_pair_twins(uint32_t nf, const uint32_t *tri, uint32_t *twin)
{
    size_t nh = 3 * (size_t)nf;
    edge_key *k = malloc(nh * sizeof *k);
    if (!k) return -1;
    for (size_t h = 0; h < nh; h++) {
        uint32_t a = tri[h], b = tri[sq_param_corner_next((uint32_t)h)];
        k[h].key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
        k[h].h = (uint32_t)h;
        twin[h] = SQ_NONE;
    }
    qsort(k, nh, sizeof *k, edge_key_cmp);
    int r = 0;
    for (size_t i = 0; i < nh && !r;) {
        size_t j = i + 1;
        while (j < nh && k[j].key == k[i].key) j++;
        if (j - i > 2) r = -2;
        if (j - i == 2) {
            uint32_t h = k[i].h, g = k[i + 1].h;
            if (tri[h] == tri[g]) r = -2;
            twin[h] = g, twin[g] = h;
        }
        i = j;
    }
    free(k);
    return r;
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
