/* seamquad: principal curvature crosses per face, the alignment source of
 * the curvature-aligned cross field (sq_cross_field.h).
 *
 * Shape operator: the edge-based estimate of Cohen-Steiner and Morvan
 * (2003): at vertex v, S_v = (1 / A_v) sum over edges e at v of
 * beta_e |e| (e^ e^T), beta_e the signed dihedral angle of e and A_v a third
 * of the one-ring's area. Face f uses the mean of its three corners' S_v,
 * restricted to its plane: the 2x2 matrix [[a, b], [b, c]] in f's frame.
 * Its principal directions are those of (a - c) + 2 i b = |k1 - k2|
 * exp(2 i theta); the cross of both directions is exp(4 i theta), and we
 * weight it by the anisotropy |k1 - k2|:
 *     q_f = z^2 / |z|,   z = (a - c) + 2 i b.
 * The sign convention of beta cancels in z^2, and so does the choice
 * between the two principal directions (perpendicular ones give the same
 * cross). Curvatures are scaled by sqrt(total area), so q does not depend on
 * the mesh's units. */
#include "sq_cross_field.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cross_field_frames.h"

sq_status sq_cross_field_curvature(const sq_mesh *m, double *q, sq_error *err)
{
    if (!q) return sq_error_set(err, SQ_ERR_ARGUMENT, "curvature: output array is NULL");
    sq_cross_field_frames fr;
    sq_status st = sq_cross_field_frames_build(m, &fr, err);
    if (st) return st;
    double *tensor = calloc(6 * (size_t)m->nv, sizeof *tensor); /* xx yy zz xy xz yz */
    double *varea = calloc((size_t)m->nv, sizeof *varea);
    if (!tensor || !varea) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "curvature: out of memory (%u vertices)", m->nv);
        goto done;
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        varea[m->he_vert[h]] += fr.area[m->he_face[h]] / 3.0; /* unit total area */
        uint32_t t = m->he_twin[h];
        if (t < h) continue;
        uint32_t va = m->he_vert[h], vb = m->he_vert[t];
        const double *pa = m->pos + 3 * (size_t)va, *pb = m->pos + 3 * (size_t)vb;
        double e[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (!(len > 0)) continue;
        for (int k = 0; k < 3; k++) e[k] /= len;
        const double *nf = fr.n + 3 * (size_t)m->he_face[h], *ng = fr.n + 3 * (size_t)m->he_face[t];
        double cx[3] = {nf[1] * ng[2] - nf[2] * ng[1], nf[2] * ng[0] - nf[0] * ng[2],
                        nf[0] * ng[1] - nf[1] * ng[0]};
        double beta = atan2(cx[0] * e[0] + cx[1] * e[1] + cx[2] * e[2],
                            nf[0] * ng[0] + nf[1] * ng[1] + nf[2] * ng[2]);
        /* edge length in unit-area units */
        double c = beta * len / sqrt(fr.total_area);
        double add[6] = {c * e[0] * e[0], c * e[1] * e[1], c * e[2] * e[2],
                         c * e[0] * e[1], c * e[0] * e[2], c * e[1] * e[2]};
        for (int k = 0; k < 6; k++) {
            tensor[6 * (size_t)va + k] += add[k];
            tensor[6 * (size_t)vb + k] += add[k];
        }
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        double s[6] = {0, 0, 0, 0, 0, 0};
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) {
            uint32_t v = m->he_vert[h];
            /* varea > 0: every vertex has a face of positive area */
            for (int k = 0; k < 6; k++) s[k] += tensor[6 * (size_t)v + k] / (3.0 * varea[v]);
        }
        const double *e1 = fr.e1 + 3 * (size_t)f, *e2 = fr.e2 + 3 * (size_t)f;
        double se1[3] = {s[0] * e1[0] + s[3] * e1[1] + s[4] * e1[2],
                         s[3] * e1[0] + s[1] * e1[1] + s[5] * e1[2],
                         s[4] * e1[0] + s[5] * e1[1] + s[2] * e1[2]};
        double se2[3] = {s[0] * e2[0] + s[3] * e2[1] + s[4] * e2[2],
                         s[3] * e2[0] + s[1] * e2[1] + s[5] * e2[2],
                         s[4] * e2[0] + s[5] * e2[1] + s[2] * e2[2]};
        double a = e1[0] * se1[0] + e1[1] * se1[1] + e1[2] * se1[2];
        double b = e2[0] * se1[0] + e2[1] * se1[1] + e2[2] * se1[2];
        double cc = e2[0] * se2[0] + e2[1] * se2[1] + e2[2] * se2[2];
        double zr = a - cc, zi = 2 * b, r = hypot(zr, zi);
        if (r > 0 && isfinite(r)) {
            q[2 * f] = (zr * zr - zi * zi) / r;
            q[2 * f + 1] = 2 * zr * zi / r;
        } else {
            q[2 * f] = q[2 * f + 1] = 0;
        }
    }
done:
    free(tensor);
    free(varea);
    sq_cross_field_frames_free(&fr);
    return st;
}
