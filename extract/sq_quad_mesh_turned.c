/* seamquad: quads turned over on the surface (sq_extract.h). */
#include <math.h>
#include <stdlib.h>

#include "sq_extract.h"

static void sub3(const double *a, const double *b, double *d)
{
    d[0] = a[0] - b[0], d[1] = a[1] - b[1], d[2] = a[2] - b[2];
}

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

double sq_quad_turn_margin(const double *const p[4], const double *const n[4])
{
    double c[4][3], l[4], lmax = 0.0;
    for (int k = 0; k < 4; k++) {
        double e1[3], e2[3];
        sub3(p[(k + 1) % 4], p[k], e1), sub3(p[(k + 3) % 4], p[k], e2), cross3(e1, e2, c[k]);
        l[k] = sqrt(c[k][0] * c[k][0] + c[k][1] * c[k][1] + c[k][2] * c[k][2]);
        if (l[k] > lmax) lmax = l[k];
    }
    double best = -1.0;
    for (int k = 0; k < 4; k++) {
        /* a corner a millionth of the largest has no direction to speak of */
        double cs = l[k] > 1e-6 * lmax ? (c[k][0] * n[k][0] + c[k][1] * n[k][1] + c[k][2] * n[k][2]) / l[k] : 0.0;
        if (cs > best) best = cs;
    }
    return best;
}

sq_status sq_quad_mesh_count_turned(const sq_quad_mesh *Q, const sq_mesh *m, const double *vn,
                                    const uint32_t *vert_face, const double *vert_bary, uint32_t *count,
                                    uint32_t *first, uint8_t *flags, sq_error *err)
{
    uint32_t n = 0;
    if (first) *first = UINT32_MAX;
    double *qn = malloc(3 * ((size_t)Q->nv + 1) * sizeof *qn);
    if (!qn) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (turned quads)");
    for (uint32_t v = 0; v < Q->nv; v++) sq_mesh_normal_at(m, vn, vert_face[v], vert_bary + 3 * (size_t)v, qn + 3 * (size_t)v);
    for (uint32_t f = 0; f < Q->nq; f++) {
        const uint32_t *q = Q->quad + 4 * (size_t)f;
        const double *p[4], *nk[4];
        for (int k = 0; k < 4; k++) p[k] = Q->pos + 3 * (size_t)q[k], nk[k] = qn + 3 * (size_t)q[k];
        int t = sq_quad_turn_margin(p, nk) < 0.0;
        if (flags) flags[f] = (uint8_t)t;
        if (t && !n++ && first) *first = f;
    }
    free(qn);
    *count = n;
    return SQ_OK;
}
