/* seamquad: integer singularity index of a face-based cross field at every
 * vertex (sq_cross_field.h; the derivation is in docs/cones_from_field.md).
 *
 * Per edge (halfedge h < twin t, faces f = face(h), g = face(t)), with
 * psi = arg u (4 times a field angle) and rot[h] the connection:
 *     raw_h = psi_g - psi_f - rot[h],   p_h = -round(raw_h / 2 pi),
 * so delta_h = raw_h + 2 pi p_h in [-pi, pi] is the field's turn across the
 * edge, measured against parallel transport. p_t = -p_h by definition (not
 * recomputed), so the period jumps are exactly antisymmetric.
 * Around vertex v, counter-clockwise through its faces, the crossings add
 * up to P_v = sum p and R_v = sum rot, and with the angle defect K_v:
 *     R_v = 4 K_v + 8 pi m_v   for an integer m_v   (holonomy of the loop),
 *     index_v = P_v - 4 m_v                         (quarter turns).
 * The only floating-point step is rounding (R_v - 4 K_v) / 8 pi to m_v;
 * it is checked to be within 1e-6 of an integer. Sum over v of P_v is 0
 * (each edge is crossed once each way) and sum of m_v is -chi (sum of R_v
 * is 0 and sum of K_v is 2 pi chi), so sum of index_v = 4 chi exactly; it
 * is verified in integers anyway. */
#include "sq_cross_field.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

#include "sq_cross_field_frames.h"

/* Corner angle at the origin of h in its face. */
static double corner_angle(const sq_mesh *m, uint32_t h)
{
    const double *p = m->pos + 3 * (size_t)m->he_vert[h];
    const double *a = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
    const double *b = m->pos + 3 * (size_t)m->he_vert[sq_cross_field_prev(m, h)];
    double u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]};
    double w[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
}

sq_status sq_cross_field_indices(const sq_mesh *m, const double *u, int32_t *index,
                                 sq_error *err)
{
    const double pi = SQ_CROSS_FIELD_PI;
    if (!u || !index) return sq_error_set(err, SQ_ERR_ARGUMENT, "field index: NULL array");
    sq_cross_field_frames fr;
    sq_status st = sq_cross_field_frames_build(m, &fr, err);
    if (st) return st;
    int32_t *jump = malloc((size_t)m->nh * sizeof *jump);
    if (!jump) {
        sq_cross_field_frames_free(&fr);
        return sq_error_set(err, SQ_ERR_NOMEM, "field index: out of memory (%u edges)",
                            m->nh / 2);
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t t = m->he_twin[h];
        if (t < h) continue;
        uint32_t f = m->he_face[h], g = m->he_face[t];
        double psi_f = atan2(u[2 * f + 1], u[2 * f]), psi_g = atan2(u[2 * g + 1], u[2 * g]);
        double raw = psi_g - psi_f - fr.rot[h];
        /* |raw| < 3 pi + |rot| is small, so the rounded value fits an int */
        jump[h] = -(int32_t)lround(raw / (2 * pi));
        jump[t] = -jump[h];
    }
    int64_t total = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], h = h0;
        int64_t p = 0;
        double r = 0, angles = 0;
        uint32_t guard = 0;
        do {
            /* h leaves v in face f; the next face counter-clockwise around v
             * is across prev(h), which enters v */
            uint32_t x = sq_cross_field_prev(m, h);
            angles += corner_angle(m, h);
            p += jump[x];
            r += fr.rot[x];
            h = m->he_twin[x];
            assert(m->he_vert[h] == v);
            if (++guard > m->nh) break;
        } while (h != h0);
        if (guard > m->nh) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "field index: the faces around vertex %u do not close", v);
            goto done;
        }
        double defect = 2 * pi - angles;
        double mreal = (r - 4 * defect) / (8 * pi);
        double mr = nearbyint(mreal);
        if (!(fabs(mreal - mr) < 1e-6) || fabs(mr) > 1e6) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "field index: the holonomy around vertex %u is not a multiple of "
                              "2 pi (off by %g turns): a bug in the connection",
                              v, mreal - mr);
            goto done;
        }
        int64_t idx = p - 4 * (int64_t)mr;
        if (idx < -1000000 || idx > 1000000) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "field index: index %lld at vertex %u",
                              (long long)idx, v);
            goto done;
        }
        index[v] = (int32_t)idx;
        total += idx;
    }
    int64_t chi = sq_mesh_euler(m);
    assert(total == 4 * chi);
    if (total != 4 * chi)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "field index: indices sum to %lld quarter turns, but 4*chi = %lld",
                          (long long)total, (long long)(4 * chi));
done:
    free(jump);
    sq_cross_field_frames_free(&fr);
    return st;
}
