/* seamquad: the cut surface laid out in the unit disk (seed 9.2, first
 * paragraph): boundary on the circle by arc length, interior by a Tutte
 * map with mean-value weights (positive, so the layout is an embedding in
 * exact arithmetic; it is only a guide, so floating point suffices). */
#include <math.h>
#include <stdlib.h>

#include "sq_guide.h"
#include "sq_guide_internal.h"
#include "sq_mean_value.h"
#include "sq_sparse.h"

static double vdist(const double *p, const double *q)
{
    double x = p[0] - q[0], y = p[1] - q[1], z = p[2] - q[2];
    return sqrt(x * x + y * y + z * z);
}

uint32_t sq_guide_inner_index(const sq_mesh *m, const sq_cut_graph *G, uint32_t *idx)
{
    for (uint32_t v = 0; v < m->nv; v++) idx[v] = 0;
    for (uint32_t h = 0; h < m->nh; h++)
        if (G->he_cut[h]) idx[m->he_vert[h]] = SQ_NONE;
    uint32_t n = 0;
    for (uint32_t v = 0; v < m->nv; v++)
        if (idx[v] != SQ_NONE) idx[v] = n++;
    return n;
}

double sq_guide_walk_lengths(const sq_mesh *m, const sq_cut_graph *G, uint32_t *walk_of, double *len)
{
    const uint32_t nb = G->side_off[G->pattern.k];
    for (uint32_t h = 0; h < m->nh; h++) walk_of[h] = SQ_NONE;
    double total = 0;
    for (uint32_t j = 0; j < nb; j++) {
        uint32_t h = G->side_he[j];
        walk_of[h] = j;
        len[j] = total;
        total += vdist(m->pos + 3 * m->he_vert[h], m->pos + 3 * m->he_vert[m->he_next[h]]);
    }
    return total;
}

uint32_t sq_guide_sector_walk(const sq_mesh *m, const sq_cut_graph *G, const uint32_t *walk_of, uint32_t h)
{
    uint32_t s = h, guard = 0;
    while (!G->he_cut[s] && guard++ < m->nh) s = m->he_next[m->he_twin[s]];
    return G->he_cut[s] ? walk_of[s] : SQ_NONE;
}

sq_status sq_guide_surface_disk(const sq_mesh *m, const sq_cut_graph *G, double *v_xy,
                                double *corner_angle, sq_error *err)
{
    const uint32_t k = G->pattern.k, nb = G->side_off[k];
    uint32_t *walk_of = malloc((size_t)m->nh * sizeof *walk_of);
    uint32_t *idx = malloc((size_t)m->nv * sizeof *idx);
    double *ang = malloc(((size_t)nb + 1) * sizeof *ang);
    uint32_t *ri = NULL, *cj = NULL;
    double *val = NULL, *rhs = NULL, *x = NULL;
    sq_lu *lu = NULL;
    sq_status st = SQ_OK;
    if (!walk_of || !idx || !ang) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (nb < 2) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "guidance: the cut graph has no boundary walk");
        goto done;
    }
    /* the boundary walk by arc length, counterclockwise from angle 0 */
    double total = sq_guide_walk_lengths(m, G, walk_of, ang);
    if (!(total > 0)) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "guidance: the cut graph has zero length");
        goto done;
    }
    for (uint32_t j = 0; j < nb; j++) ang[j] *= 2 * SQ_GUIDE_PI / total;
    for (uint32_t s = 0; s < k; s++) corner_angle[s] = ang[G->side_off[s]];

    /* unknowns: vertices off the cut */
    uint32_t n = sq_guide_inner_index(m, G, idx);
    size_t cap = 2 * (size_t)m->nh + 1, nnz = 0; /* two entries per halfedge */
    ri = malloc(cap * sizeof *ri), cj = malloc(cap * sizeof *cj), val = malloc(cap * sizeof *val);
    rhs = calloc(2 * (size_t)n + 2, sizeof *rhs), x = malloc((2 * (size_t)n + 2) * sizeof *x);
    if (!ri || !cj || !val || !rhs || !x) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* one row per vertex off the cut: sum_w wt (x_v - x_w) = 0, where a
     * neighbour on the cut contributes the circle point of the sector that
     * holds the edge (the cut halfedge met turning clockwise from w->v) */
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t v = m->he_vert[h];
        if (idx[v] == SQ_NONE) continue;
        uint32_t t = m->he_twin[h], w = m->he_vert[t];
        uint32_t a = m->he_vert[m->he_next[m->he_next[h]]];
        uint32_t b = m->he_vert[m->he_next[m->he_next[t]]];
        const double *pv = m->pos + 3 * v, *pw = m->pos + 3 * w;
        double wt = sq_mean_value_weight(pv, pw, m->pos + 3 * a, m->pos + 3 * b);
        ri[nnz] = idx[v], cj[nnz] = idx[v], val[nnz++] = wt;
        if (idx[w] != SQ_NONE) {
            ri[nnz] = idx[v], cj[nnz] = idx[w], val[nnz++] = -wt;
            continue;
        }
        uint32_t j = sq_guide_sector_walk(m, G, walk_of, t);
        if (j == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "guidance: vertex %u on the cut has no sector", w);
            goto done;
        }
        rhs[idx[v]] += wt * cos(ang[j]);
        rhs[n + idx[v]] += wt * sin(ang[j]);
    }
    if (n > 0) {
        st = sq_lu_factor(n, nnz, ri, cj, val, &lu, err);
        if (st == SQ_OK) st = sq_lu_solve(lu, 2, rhs, x, err);
        if (st) goto done;
    }
    for (uint32_t v = 0; v < m->nv; v++) {
        v_xy[2 * v] = idx[v] == SQ_NONE ? NAN : x[idx[v]];
        v_xy[2 * v + 1] = idx[v] == SQ_NONE ? NAN : x[n + idx[v]];
    }
done:
    if (lu) sq_lu_free(lu);
    free(walk_of);
    free(idx);
    free(ang);
    free(ri);
    free(cj);
    free(val);
    free(rhs);
    free(x);
    return st;
}
