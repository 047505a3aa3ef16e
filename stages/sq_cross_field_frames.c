/* seamquad: face frames and the face-to-face connection (see
 * sq_cross_field_frames.h). */
#include "sq_cross_field_frames.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void sub3(const double *a, const double *b, double *out)
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static void cross3(const double *a, const double *b, double *out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void sq_cross_field_frames_free(sq_cross_field_frames *fr)
{
    if (!fr) return;
    free(fr->e1);
    free(fr->e2);
    free(fr->n);
    free(fr->area);
    free(fr->rot);
    memset(fr, 0, sizeof *fr);
}

/* Angle of the vector of halfedge h in the frame of its face. */
static double halfedge_angle(const sq_mesh *m, const sq_cross_field_frames *fr, uint32_t h)
{
    uint32_t f = m->he_face[h];
    double d[3];
    sub3(m->pos + 3 * (size_t)m->he_vert[m->he_next[h]], m->pos + 3 * (size_t)m->he_vert[h], d);
    return atan2(dot3(d, fr->e2 + 3 * (size_t)f), dot3(d, fr->e1 + 3 * (size_t)f));
}

sq_status sq_cross_field_frames_build(const sq_mesh *m, sq_cross_field_frames *fr,
                                      sq_error *err)
{
    memset(fr, 0, sizeof *fr);
    if (!m || m->nf == 0 || m->nh != 3 * m->nf)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cross field: needs a non-empty closed triangle mesh");
    fr->nf = m->nf;
    fr->nh = m->nh;
    fr->e1 = malloc(3 * (size_t)m->nf * sizeof(double));
    fr->e2 = malloc(3 * (size_t)m->nf * sizeof(double));
    fr->n = malloc(3 * (size_t)m->nf * sizeof(double));
    fr->area = malloc((size_t)m->nf * sizeof(double));
    fr->rot = malloc((size_t)m->nh * sizeof(double));
    if (!fr->e1 || !fr->e2 || !fr->n || !fr->area || !fr->rot) {
        sq_cross_field_frames_free(fr);
        return sq_error_set(err, SQ_ERR_NOMEM, "cross field: out of memory (%u faces)", m->nf);
    }
    double total = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        const double *p0 = m->pos + 3 * (size_t)m->he_vert[h];
        const double *p1 = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
        const double *p2 = m->pos + 3 * (size_t)m->he_vert[sq_cross_field_prev(m, h)];
        double a[3], b[3], nn[3];
        sub3(p1, p0, a);
        sub3(p2, p0, b);
        cross3(a, b, nn);
        double la = sqrt(dot3(a, a)), ln = sqrt(dot3(nn, nn));
        /* sq_mesh_from_soup rejects exactly collinear corners, but a
         * product can still underflow for absurdly small coordinates */
        if (!(la > 0) || !(ln > 0) || !isfinite(ln))
            return sq_cross_field_frames_free(fr),
                   sq_error_set(err, SQ_ERR_DEGENERATE,
                                "cross field: face %u has no usable normal (its area "
                                "underflows); rescale the mesh",
                                f);
        double *e1 = fr->e1 + 3 * (size_t)f, *e2 = fr->e2 + 3 * (size_t)f,
               *n = fr->n + 3 * (size_t)f;
        for (int k = 0; k < 3; k++) {
            e1[k] = a[k] / la;
            n[k] = nn[k] / ln;
        }
        cross3(n, e1, e2);
        fr->area[f] = 0.5 * ln;
        total += 0.5 * ln;
    }
    fr->total_area = total;
    for (uint32_t f = 0; f < m->nf; f++) fr->area[f] /= total;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t t = m->he_twin[h];
        if (t < h) continue;
        /* The edge vector of h is minus that of t: its angle in t's face is
         * angle(t) + pi, so the transport f -> g adds angle(t) + pi - angle(h). */
        double r = halfedge_angle(m, fr, t) + SQ_CROSS_FIELD_PI - halfedge_angle(m, fr, h);
        fr->rot[h] = 4.0 * r;
        fr->rot[t] = -fr->rot[h];
    }
    return SQ_OK;
}
