/* seamquad: quads turned over on the surface (sq_extract.h). */

#include "sq_extract.h"
#include "sq_smooth.h"

/* Triangle f's unit normal, or n left as it is where the triangle is too
 * thin to have one (sq_triangle_unit_normal). */
static void face_normal_if_defined(const sq_mesh *m, uint32_t f, double n[3])
{
    uint32_t h = m->f_he[f];
    const double *a = m->pos + 3 * (size_t)m->he_vert[h], *b = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]],
                 *c = m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]];
    double x[3];
    if (sq_triangle_unit_normal(a, b, c, x)) n[0] = x[0], n[1] = x[1], n[2] = x[2];
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
    return sq_quad_turn_margin_either(p, ns, nf);
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
