/* seamquad: the cut surface laid out with little length distortion, for
 * guidance (seed 9.2: "a low-distortion map of the cut surface ... onto the
 * unit disk"; sq_guide.h).
 *
 * The Tutte layout of sq_guide_surface_disk keeps the boundary on the
 * circle and squeezes whatever lies far from the cut (an elephant's trunk
 * and legs) into a small part of the disk, so their cones crowd together
 * there. Here the boundary is freed and a few local-global iterations of
 * as-rigid-as-possible flattening (one rotation per triangle, then one
 * sparse solve for all positions with the factorization kept) bring every
 * triangle near an isometric copy of itself. The result is moved and
 * scaled into the unit disk (centroid at the origin, the farthest point
 * just inside the circle). Only a guide: floating point, and overlaps are
 * allowed (Algorithm 1 only reads positions). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_guide.h"
#include "sq_guide_internal.h"
#include "sq_sparse.h"

sq_status sq_guide_surface_arap(const sq_mesh *m, const sq_cut_graph *G, uint32_t iters, double *v_xy,
                                double *corner_angle, sq_error *err)
{
    const uint32_t k = G->pattern.k, nb = G->side_off[k], nf = m->nf;
    sq_status st = sq_guide_surface_disk(m, G, v_xy, corner_angle, err);
    if (st) return st;
    uint32_t *walk_of = malloc((size_t)m->nh * sizeof *walk_of), *idx = malloc((size_t)m->nv * sizeof *idx);
    uint32_t *cid = malloc(3 * (size_t)nf * sizeof *cid);
    double *ref = malloc(6 * (size_t)nf * sizeof *ref), *cot = malloc(3 * (size_t)nf * sizeof *cot);
    uint32_t *ri = malloc(12 * (size_t)nf * sizeof *ri + 8), *cj = malloc(12 * (size_t)nf * sizeof *cj + 8);
    double *val = malloc(12 * (size_t)nf * sizeof *val + 8);
    double *u = NULL, *rhs = NULL;
    sq_spd *chol = NULL;
    if (!walk_of || !idx || !cid || !ref || !cot || !ri || !cj || !val) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    const uint32_t nin = sq_guide_inner_index(m, G, idx), N = nin + nb;
    u = malloc(2 * (size_t)N * sizeof *u), rhs = malloc(2 * (size_t)N * sizeof *rhs);
    if (!u || !rhs) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* start: the Tutte layout, the boundary copies on the circle */
    for (uint32_t v = 0; v < m->nv; v++)
        if (idx[v] != SQ_NONE) u[idx[v]] = v_xy[2 * v], u[N + idx[v]] = v_xy[2 * v + 1];
    {
        double *len = malloc(((size_t)nb + 1) * sizeof *len);
        if (!len) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
        const double total = sq_guide_walk_lengths(m, G, walk_of, len);
        for (uint32_t j = 0; j < nb; j++) {
            double a = 2 * SQ_GUIDE_PI * len[j] / total;
            u[nin + j] = cos(a), u[N + nin + j] = sin(a);
        }
        free(len);
    }
    /* corners: an inner vertex, or the copy of the sector holding it (the
     * cut halfedge met turning clockwise) */
    for (uint32_t f = 0; f < nf && st == SQ_OK; f++) {
        uint32_t h = m->f_he[f];
        for (int i = 0; i < 3; i++, h = m->he_next[h]) {
            uint32_t v = m->he_vert[h];
            if (idx[v] != SQ_NONE) {
                cid[3 * f + (uint32_t)i] = idx[v];
                continue;
            }
            uint32_t j = sq_guide_sector_walk(m, G, walk_of, h);
            if (j == SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "guidance: vertex %u on the cut has no sector", v);
                break;
            }
            cid[3 * f + (uint32_t)i] = nin + j;
        }
    }
    if (st) goto done;
    /* each triangle isometric in its plane; cotangent weights (clamped: a
     * guide needs no exact Dirichlet energy, and positive weights keep the
     * system definite) */
    size_t nnz = 0;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t h = m->f_he[f];
        const double *p0 = m->pos + 3 * m->he_vert[h], *p1 = m->pos + 3 * m->he_vert[m->he_next[h]],
                     *p2 = m->pos + 3 * m->he_vert[m->he_next[m->he_next[h]]];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        double d = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / (l1 > 0 ? l1 : 1);
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
        double hgt = sqrt(cx * cx + cy * cy + cz * cz) / (l1 > 0 ? l1 : 1);
        double *r = ref + 6 * f;
        r[0] = 0, r[1] = 0, r[2] = l1, r[3] = 0, r[4] = d, r[5] = hgt;
        for (int i = 0; i < 3; i++) {
            /* the angle at corner i, opposite edge (i+1, i+2) */
            const double *a = r + 2 * i, *b = r + 2 * ((i + 1) % 3), *c = r + 2 * ((i + 2) % 3);
            double ux = b[0] - a[0], uy = b[1] - a[1], wx = c[0] - a[0], wy = c[1] - a[1];
            double cr = fabs(ux * wy - uy * wx), dt = ux * wx + uy * wy;
            double ct = cr > 0 ? dt / cr : 100;
            ct = ct < 0.01 ? 0.01 : ct > 100 ? 100 : ct;
            cot[3 * f + (uint32_t)i] = ct;
            uint32_t vi = cid[3 * f + (uint32_t)(i + 1) % 3], vj = cid[3 * f + (uint32_t)(i + 2) % 3];
            ri[nnz] = vi, cj[nnz] = vi, val[nnz++] = ct;
            ri[nnz] = vj, cj[nnz] = vj, val[nnz++] = ct;
            ri[nnz] = vi, cj[nnz] = vj, val[nnz++] = -ct;
            ri[nnz] = vj, cj[nnz] = vi, val[nnz++] = -ct;
        }
    }
    /* one point pinned (translation) */
    const double pin = 1e6;
    const double pin_x = u[0], pin_y = u[N];
    ri[nnz] = 0, cj[nnz] = 0, val[nnz++] = pin;
    st = sq_spd_factor(N, nnz, ri, cj, val, &chol, err);
    if (st) goto done;
    for (uint32_t it = 0; it < iters && st == SQ_OK; it++) {
        memset(rhs, 0, 2 * (size_t)N * sizeof *rhs);
        for (uint32_t f = 0; f < nf; f++) {
            const double *r = ref + 6 * f;
            const uint32_t *c = cid + 3 * f;
            double m00 = 0, m01 = 0, m10 = 0, m11 = 0;
            for (int i = 0; i < 3; i++) {
                uint32_t a = (uint32_t)(i + 1) % 3, b = (uint32_t)(i + 2) % 3;
                double w = cot[3 * f + (uint32_t)i];
                double rx = r[2 * a] - r[2 * b], ry = r[2 * a + 1] - r[2 * b + 1];
                double ux = u[c[a]] - u[c[b]], uy = u[N + c[a]] - u[N + c[b]];
                m00 += w * rx * ux, m01 += w * rx * uy, m10 += w * ry * ux, m11 += w * ry * uy;
            }
            double th = atan2(m01 - m10, m00 + m11), cs = cos(th), sn = sin(th);
            for (int i = 0; i < 3; i++) {
                uint32_t a = (uint32_t)(i + 1) % 3, b = (uint32_t)(i + 2) % 3;
                double w = cot[3 * f + (uint32_t)i];
                double rx = r[2 * a] - r[2 * b], ry = r[2 * a + 1] - r[2 * b + 1];
                double qx = cs * rx - sn * ry, qy = sn * rx + cs * ry;
                rhs[c[a]] += w * qx, rhs[N + c[a]] += w * qy;
                rhs[c[b]] -= w * qx, rhs[N + c[b]] -= w * qy;
            }
        }
        rhs[0] += pin * pin_x, rhs[N] += pin * pin_y;
        st = sq_spd_solve(chol, 2, rhs, u, err);
    }
    if (st) goto done;
    /* into the unit disk */
    double mx = 0, my = 0, rmax = 0;
    for (uint32_t i = 0; i < N; i++) mx += u[i], my += u[N + i];
    mx /= N, my /= N;
    for (uint32_t i = 0; i < N; i++) rmax = fmax(rmax, hypot(u[i] - mx, u[N + i] - my));
    double s = rmax > 0 ? 0.999 / rmax : 1;
    for (uint32_t v = 0; v < m->nv; v++) {
        if (idx[v] == SQ_NONE) continue;
        v_xy[2 * v] = (u[idx[v]] - mx) * s, v_xy[2 * v + 1] = (u[N + idx[v]] - my) * s;
    }
    for (uint32_t q = 0; q < k; q++) {
        uint32_t j = nin + G->side_off[q];
        double a = atan2(u[N + j] - my, u[j] - mx);
        corner_angle[q] = a < 0 ? a + 2 * SQ_GUIDE_PI : a;
    }
done:
    if (chol) sq_spd_free(chol);
    free(walk_of), free(idx), free(cid), free(ref), free(cot), free(ri), free(cj), free(val), free(u), free(rhs);
    return st;
}
