#include "sq_disk_layout.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_sparse.h"

sq_status sq_disk_layout_tutte(const sq_metapolygon *P, uint32_t start, double *xy,
                               sq_error *err)
{
    if (P->nf == 0 || P->bnd_he == SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cannot lay out an empty disk");
    if (start == SQ_NONE) start = P->bnd_he;
    if (P->he_face[start] != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "layout start %u is not a boundary halfedge",
                            start);
    /* boundary: clockwise on the unit circle */
    uint32_t h = start, t = 0;
    do {
        uint32_t v = P->he_vert[h];
        double a = -6.283185307179586 * (double)t / (double)P->nbnd;
        xy[2 * v] = cos(a);
        xy[2 * v + 1] = sin(a);
        t++;
        h = P->he_next[h];
    } while (h != start);
    assert(t == P->nbnd);
    return sq_disk_layout_tutte_fixed(P, xy, err);
}

/* Every vertex with idx[v] != SQ_NONE (numbered 0 .. ni-1) to the average
 * of its neighbours, the others fixed at xy: one sparse SPD solve. The
 * edges: with faces_only 0, every halfedge out of a free vertex (a disk:
 * each edge once per end); with 1, every face halfedge from both ends (a
 * cut sphere: each edge twice, the cut edge too, so uniform weights). */
static sq_status tutte_solve(const sq_metapolygon *P, const uint32_t *idx, uint32_t ni, int faces_only, double *xy,
                             sq_error *err)
{
    if (ni == 0) return SQ_OK;
    size_t cap = 4 * (size_t)P->nh + 1, nnz = 0;
    uint32_t *ri = malloc(cap * sizeof *ri), *ci = malloc(cap * sizeof *ci);
    double *val = malloc(cap * sizeof *val);
    double *rhs = calloc(2 * (size_t)ni, sizeof *rhs), *sol = malloc(2 * (size_t)ni * sizeof *sol);
    sq_status st = SQ_OK;
    if (!ri || !ci || !val || !rhs || !sol) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t e = 0; st == SQ_OK && e < P->nh; e++) {
        if (faces_only && P->he_face[e] == SQ_NONE) continue;
        const uint32_t end[2] = {P->he_vert[e], P->he_vert[P->he_next[e]]};
        for (int s = 0; s < (faces_only ? 2 : 1); s++) {
            uint32_t a = end[s], b = end[1 - s];
            if (idx[a] == SQ_NONE) continue;
            ri[nnz] = idx[a], ci[nnz] = idx[a], val[nnz++] = 1.0;
            if (idx[b] != SQ_NONE) {
                ri[nnz] = idx[a], ci[nnz] = idx[b], val[nnz++] = -1.0;
            } else {
                rhs[idx[a]] += xy[2 * b];
                rhs[ni + idx[a]] += xy[2 * b + 1];
            }
        }
    }
    if (st == SQ_OK) {
        sq_spd *f = NULL;
        st = sq_spd_factor(ni, nnz, ri, ci, val, &f, err);
        if (st == SQ_OK) st = sq_spd_solve(f, 2, rhs, sol, err);
        sq_spd_free(f);
    }
    for (uint32_t v = 0; st == SQ_OK && v < P->nv; v++)
        if (idx[v] != SQ_NONE) xy[2 * v] = sol[idx[v]], xy[2 * v + 1] = sol[ni + idx[v]];
    free(ri), free(ci), free(val), free(rhs), free(sol);
    return st;
}

sq_status sq_disk_layout_tutte_fixed(const sq_metapolygon *P, double *xy, sq_error *err)
{
    const uint32_t nv = P->nv;
    uint32_t *idx = malloc(((size_t)nv + 1) * sizeof *idx); /* interior index or SQ_NONE */
    if (!idx) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t v = 0; v < nv; v++) idx[v] = 0;
    for (uint32_t h = 0; h < P->nh; h++)
        if (P->he_face[h] == SQ_NONE) idx[P->he_vert[h]] = SQ_NONE;
    uint32_t ni = 0;
    for (uint32_t v = 0; v < nv; v++)
        if (idx[v] != SQ_NONE) idx[v] = ni++;
    /* uniform Laplacian over the interior: L x = sum of boundary neighbours */
    sq_status st = tutte_solve(P, idx, ni, 0, xy, err);
    free(idx);
    return st;
}

sq_status sq_disk_layout_sphere(const sq_metapolygon *P, uint32_t outer, double *xy, sq_error *err)
{
    if (outer >= P->nf || P->nbnd > 2)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sphere layout: face %u of %u, boundary of %u halfedges", outer,
                            P->nf, P->nbnd);
    const uint32_t nv = P->nv;
    uint32_t *idx = malloc(((size_t)nv + 1) * sizeof *idx); /* free index or SQ_NONE */
    if (!idx) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t v = 0; v < nv; v++) idx[v] = 0;
    /* the outer face clockwise on the circle */
    uint32_t h0 = SQ_NONE, deg = 0;
    for (uint32_t h = 0; h < P->nh; h++)
        if (P->he_face[h] == outer) h0 = h, deg++;
    uint32_t h = h0, t = 0;
    do {
        uint32_t v = P->he_vert[h];
        double a = 0.785398163397448 - 6.283185307179586 * (double)t / (double)deg;
        xy[2 * v] = cos(a), xy[2 * v + 1] = sin(a);
        idx[v] = SQ_NONE;
        t++;
        h = P->he_next[h];
    } while (h != h0);
    uint32_t ni = 0;
    for (uint32_t v = 0; v < nv; v++)
        if (idx[v] != SQ_NONE) idx[v] = ni++;
    sq_status st = tutte_solve(P, idx, ni, 1, xy, err);
    free(idx);
    return st;
}
