/* seamquad: quads turned over on the surface (sq_extract.h). */
#include <math.h>

#include "sq_extract.h"
#include "sq_smooth.h"

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

/* Triangle f's unit normal, or n left as it is where the triangle is too
 * thin for its cross product to have a direction (below 1e-10 of its
 * longest side squared: rounding decides it). */
static void face_normal_if_defined(const sq_mesh *m, uint32_t f, double n[3])
{
    uint32_t h = m->f_he[f];
    const double *a = m->pos + 3 * (size_t)m->he_vert[h], *b = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]],
                 *c = m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]];
    double e1[3], e2[3], e3[3], x[3];
    sub3(b, a, e1), sub3(c, a, e2), sub3(c, b, e3), cross3(e1, e2, x);
    double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), s = 0.0;
    const double *e[3] = {e1, e2, e3};
    for (int k = 0; k < 3; k++) s = fmax(s, e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2]);
    if (l > 1e-10 * s) n[0] = x[0] / l, n[1] = x[1] / l, n[2] = x[2] / l;
}

double sq_quad_turn_margin_on(const sq_mesh *m, const double *vn, const double *const p[4], const uint32_t face[4],
                              const double *const bary[4])
{
    double smooth[4][3], flat[4][3];
    const double *ns[4], *nf[4];
    for (int k = 0; k < 4; k++) {
        sq_mesh_normal_at(m, vn, face[k], bary[k], smooth[k]);
        flat[k][0] = smooth[k][0], flat[k][1] = smooth[k][1], flat[k][2] = smooth[k][2];
        face_normal_if_defined(m, face[k], flat[k]);
        ns[k] = smooth[k], nf[k] = flat[k];
    }
    return fmax(sq_quad_turn_margin(p, ns), sq_quad_turn_margin(p, nf));
}

sq_status sq_quad_mesh_count_turned(const sq_quad_mesh *Q, const sq_mesh *m, const double *vn,
                                    const uint32_t *vert_face, const double *vert_bary, uint32_t *count,
                                    uint32_t *first, uint8_t *flags, sq_error *err)
{
    (void)err;
    uint32_t n = 0;
    if (first) *first = UINT32_MAX;
    for (uint32_t f = 0; f < Q->nq; f++) {
        const uint32_t *q = Q->quad + 4 * (size_t)f;
        const double *p[4], *b[4];
        uint32_t face[4];
        for (int k = 0; k < 4; k++)
            p[k] = Q->pos + 3 * (size_t)q[k], b[k] = vert_bary + 3 * (size_t)q[k], face[k] = vert_face[q[k]];
        int t = sq_quad_turn_margin_on(m, vn, p, face, b) < 0.0;
        if (flags) flags[f] = (uint8_t)t;
        if (t && !n++ && first) *first = f;
    }
    *count = n;
    return SQ_OK;
}
