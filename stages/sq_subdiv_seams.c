/* seamquad: continuity report across the borders of the Catmull-Clark
 * B-spline patches: the gap between neighbouring patches (must be ~0) and
 * the jump of the normal (zero where both patches are regular B-spline
 * patches of the exact surface, nonzero next to the B-spline end caps that
 * approximate the surface at extraordinary vertices). */
#include <math.h>
#include <string.h>

#include "sq_osd_adapter.h"
#include "sq_subdiv.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The patch of face f other than `not` whose closed domain holds (u, v). */
static uint32_t find_patch(const sq_subdiv *s, uint32_t f, double u, double v, uint32_t not)
{
    for (uint32_t k = s->face_first[f]; k < s->face_first[f + 1]; k++) {
        uint32_t q = s->face_patch[k];
        const double *d = s->patch_dom + 4 * (size_t)q;
        if (q != not && u >= d[0] && u <= d[2] && v >= d[1] && v <= d[3]) return q;
    }
    return UINT32_MAX;
}

static void side_param(uint32_t k, double t, double *u, double *v)
{
    switch (k) {
    case 0: *u = t; *v = 0.0; break;
    case 1: *u = 1.0; *v = t; break;
    case 2: *u = 1.0 - t; *v = 1.0; break;
    default: *u = 0.0; *v = 1.0 - t; break;
    }
}

static void unit_normal(const double a[3], const double b[3], double n[3])
{
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) {
        n[0] /= l;
        n[1] /= l;
        n[2] /= l;
    }
}

sq_status sq_subdiv_seam_report(const sq_subdiv *s, const sq_mesh *m, uint32_t samples,
                                sq_subdiv_seams *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (samples < 1 || samples > 1000)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%u samples per patch side outside 1..1000",
                            samples);
    if (m->nf != s->nf) return sq_error_set(err, SQ_ERR_ARGUMENT, "mesh and surface differ");
    const double finest = ldexp(1.0, -s->isolation);
    double sum = 0.0;
    for (uint32_t p = 0; p < s->np; p++) {
        const uint32_t f = s->patch_face[p];
        const double *d = s->patch_dom + 4 * (size_t)p;
        const int p_cap = d[2] - d[0] <= finest;
        for (uint32_t side = 0; side < 4; side++) {
            for (uint32_t a = 0; a <= samples; a++) {
                double t = (double)a / samples, u, v;
                /* the side of the patch, corner `side` to corner side+1 */
                side_param(side, t, &u, &v);
                u = d[0] + u * (d[2] - d[0]);
                v = d[1] + v * (d[3] - d[1]);
                /* where the neighbour is: across the base edge, or inside f */
                int on_edge = (side == 0 && v == 0.0) || (side == 1 && u == 1.0) ||
                              (side == 2 && v == 1.0) || (side == 3 && u == 0.0);
                uint32_t g = f, q;
                double u2 = u, v2 = v;
                if (on_edge) {
                    double tb = side == 0 ? u : side == 1 ? v : side == 2 ? 1.0 - u : 1.0 - v;
                    uint32_t h = m->he_twin[4 * f + side];
                    g = m->he_face[h];
                    side_param(h - 4 * g, 1.0 - tb, &u2, &v2);
                    q = find_patch(s, g, u2, v2, UINT32_MAX);
                } else {
                    q = find_patch(s, f, u, v, p);
                }
                if (q == UINT32_MAX)
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "no patch across the border of patch %u at (%g, %g) "
                                        "of face %u",
                                        p, u, v, f);
                double P[3], Pu[3], Pv[3], Q[3], Qu[3], Qv[3], n1[3], n2[3];
                sq_osd_eval(s->osd, f, p, u, v, P, Pu, Pv);
                sq_osd_eval(s->osd, g, q, u2, v2, Q, Qu, Qv);
                double gap = sqrt((P[0] - Q[0]) * (P[0] - Q[0]) + (P[1] - Q[1]) * (P[1] - Q[1]) +
                                  (P[2] - Q[2]) * (P[2] - Q[2]));
                unit_normal(Pu, Pv, n1);
                unit_normal(Qu, Qv, n2);
                double c = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
                double cx = n1[1] * n2[2] - n1[2] * n2[1], cy = n1[2] * n2[0] - n1[0] * n2[2],
                       cz = n1[0] * n2[1] - n1[1] * n2[0];
                double ang = atan2(sqrt(cx * cx + cy * cy + cz * cz), c) * (180.0 / M_PI);
                const double *dq = s->patch_dom + 4 * (size_t)q;
                int q_cap = dq[2] - dq[0] <= finest;
                if (gap > out->max_gap) out->max_gap = gap;
                if (ang > out->max_normal_deg) out->max_normal_deg = ang;
                if (!p_cap && !q_cap && ang > out->max_normal_regular_deg)
                    out->max_normal_regular_deg = ang;
                sum += ang;
                out->points++;
            }
        }
    }
    out->mean_normal_deg = out->points ? sum / (double)out->points : 0.0;
    out->max_gap_rel = s->bbox_diag > 0 ? out->max_gap / s->bbox_diag : out->max_gap;
    return SQ_OK;
}
