/* seamquad: the output of an attempt (sq_param_steps.h): P from the cut
 * and refined surface and its UVs, every UV triangle's orientation checked
 * exactly, and the map's distortion statistics. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_steps.h"
#include "sq_predicates.h"

/* Distortion of the map (stats): per triangle the singular values s1 >= s2
 * of the linear map from the 3D triangle to its UV triangle; symmetric
 * Dirichlet s1^2 + s2^2 + s1^-2 + s2^-2 after the global scale that
 * minimizes its area-weighted sum, and the conformal ratio s1 / s2. */
void sq_param_distortion(const sq_param *P, sq_param_stats *stats)
{
    /* per face: 3D area, s1^2 + s2^2, s1^-2 + s2^-2 */
    double *t = malloc(3 * (size_t)P->nf * sizeof *t);
    if (!t) return; /* statistics only */
    double A = 0, B = 0, W = 0, cmean = 0, cmax = 0;
    for (uint32_t f = 0; f < P->nf; f++) {
        t[3 * f] = 0;
        const double *p0 = P->pos + 3 * P->tri[3 * f], *p1 = P->pos + 3 * P->tri[3 * f + 1],
                     *p2 = P->pos + 3 * P->tri[3 * f + 2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        double x2 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
        double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double y2 = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / l1;
        double area = 0.5 * l1 * y2;
        if (!(area > 0)) continue;
        const double *u0 = P->uv + 2 * P->tri_uv[3 * f], *u1 = P->uv + 2 * P->tri_uv[3 * f + 1],
                     *u2 = P->uv + 2 * P->tri_uv[3 * f + 2];
        /* J = [u1-u0, u2-u0] * inv([[l1, x2], [0, y2]]) */
        double a = u1[0] - u0[0], b = u2[0] - u0[0], c = u1[1] - u0[1], d = u2[1] - u0[1];
        double j11 = a / l1, j12 = (b - a * x2 / l1) / y2, j21 = c / l1, j22 = (d - c * x2 / l1) / y2;
        double fro = j11 * j11 + j12 * j12 + j21 * j21 + j22 * j22, det = j11 * j22 - j12 * j21;
        double disc = sqrt(fmax(fro * fro - 4 * det * det, 0));
        double s1 = sqrt(0.5 * (fro + disc)), s2 = fabs(det) / s1; /* no cancellation */
        if (!(s2 > 0)) continue;
        t[3 * f] = area, t[3 * f + 1] = s1 * s1 + s2 * s2, t[3 * f + 2] = 1 / (s1 * s1) + 1 / (s2 * s2);
        A += area * t[3 * f + 1], B += area * t[3 * f + 2], W += area;
        cmean += area * s1 / s2;
        if (s1 / s2 > cmax) cmax = s1 / s2;
    }
    if (W > 0 && A > 0 && B > 0) {
        /* the scale a^2 = sqrt(B / A) minimizes sum area (a^2 p + q / a^2) */
        double a2 = sqrt(B / A), dmax = 0;
        for (uint32_t f = 0; f < P->nf; f++)
            if (t[3 * f] > 0 && a2 * t[3 * f + 1] + t[3 * f + 2] / a2 > dmax) dmax = a2 * t[3 * f + 1] + t[3 * f + 2] / a2;
        stats->sym_dirichlet_mean = (a2 * A + B / a2) / W, stats->sym_dirichlet_max = dmax;
        stats->conformal_mean = cmean / W, stats->conformal_max = cmax;
    }
    free(t);
}

sq_status sq_param_assemble(ctx *c, const uint32_t *v_uv, const int32_t *valence, sq_param *P,
                            sq_param_stats *stats)
{
    sq_tsurf *S = &c->S;
    P->nv = S->nv, P->nf = S->nf, P->nv_input = S->nv_input;
    P->pos = malloc(3 * (size_t)S->nv * sizeof *P->pos);
    P->tri = malloc(3 * (size_t)S->nf * sizeof *P->tri);
    P->tri_uv = malloc(3 * (size_t)S->nf * sizeof *P->tri_uv);
    P->he_seam = malloc(3 * (size_t)S->nf);
    P->he_cut = malloc(3 * (size_t)S->nf);
    P->tri_in = malloc((size_t)S->nf * sizeof *P->tri_in);
    P->valence = malloc((size_t)S->nv_input * sizeof *P->valence);
    if (!P->pos || !P->tri || !P->tri_uv || !P->he_seam || !P->he_cut || !P->tri_in || !P->valence)
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    memcpy(P->tri_in, S->forig, (size_t)S->nf * sizeof *P->tri_in);
    memcpy(P->pos, S->pos, 3 * (size_t)S->nv * sizeof *P->pos);
    memcpy(P->valence, valence, (size_t)S->nv_input * sizeof *P->valence);
    /* corner 3f + i of the output is halfedge ch[3f + i] of S */
    uint32_t *ch = malloc(3 * (size_t)S->nf * sizeof *ch);
    if (!ch) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t f = 0; f < S->nf; f++) {
        uint32_t h = S->f_he[f];
        for (uint32_t i = 0; i < 3; i++, h = S->next[h]) ch[3 * f + i] = h, P->tri[3 * f + i] = S->vert[h];
    }
    sq_status st = SQ_OK;
    for (uint32_t k = 0; k < 3 * S->nf; k++) {
        uint32_t h = ch[k];
        uint32_t v = S->vert[h];
        uint32_t u = corner_uv(c, v_uv, h);
        if (u == SQ_NONE) {
            st = sq_error_set(c->err, SQ_ERR_INTERNAL, "corner %u of face %u (vertex %u) has no UV", k % 3,
                              k / 3, v);
            break;
        }
        P->tri_uv[k] = u;
    }
    if (st) {
        free(ch);
        return st;
    }
    /* compact the UV array to the used entries */
    uint32_t *newi = malloc((size_t)c->nuv * sizeof *newi);
    uint32_t *corner_of = malloc((size_t)S->nh * sizeof *corner_of);
    if (!newi || !corner_of) {
        free(ch), free(newi), free(corner_of);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t k = 0; k < 3 * S->nf; k++) corner_of[ch[k]] = k;
    for (uint32_t i = 0; i < c->nuv; i++) newi[i] = SQ_NONE;
    uint32_t nu = 0;
    for (uint32_t h = 0; h < 3 * S->nf; h++)
        if (newi[P->tri_uv[h]] == SQ_NONE) newi[P->tri_uv[h]] = nu++;
    P->uv = malloc(2 * (size_t)nu * sizeof *P->uv);
    if (!P->uv) {
        free(ch), free(newi), free(corner_of);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t i = 0; i < c->nuv; i++)
        if (newi[i] != SQ_NONE) P->uv[2 * newi[i]] = c->uv[2 * i], P->uv[2 * newi[i] + 1] = c->uv[2 * i + 1];
    for (uint32_t h = 0; h < 3 * S->nf; h++) P->tri_uv[h] = newi[P->tri_uv[h]];
    free(newi);
    P->nuv = nu;
    uint32_t seams = 0;
    for (uint32_t k = 0; k < 3 * S->nf; k++) {
        uint32_t h = ch[k], g = S->twin[h];
        uint32_t kh = k, khn = corner_of[S->next[h]], kg = corner_of[g], kgn = corner_of[S->next[g]];
        int seam = P->tri_uv[kh] != P->tri_uv[kgn] || P->tri_uv[khn] != P->tri_uv[kg];
        P->he_seam[k] = (uint8_t)seam;
        P->he_cut[k] = S->kind[h];
        if (seam && h < g) seams++;
    }
    free(ch);
    free(corner_of);
    /* exact orientation of every UV triangle */
    uint32_t bad = 0, first = SQ_NONE;
    for (uint32_t f = 0; f < S->nf; f++) {
        const double *a = P->uv + 2 * P->tri_uv[3 * f], *b = P->uv + 2 * P->tri_uv[3 * f + 1],
                     *d = P->uv + 2 * P->tri_uv[3 * f + 2];
        if (sq_orient2d(a, b, d) <= 0) {
            if (first == SQ_NONE) first = f;
            bad++;
        }
    }
    if (stats) {
        stats->verts_out = S->nv, stats->faces_out = S->nf;
        stats->steiner = S->nv - S->nv_input;
        stats->nuv = nu;
        stats->seam_edges = seams;
    }
    if (stats && !bad && !distortion_later(c)) sq_param_distortion(P, stats);
    if (bad && !c->keep_flips)
        return sq_error_set(c->err, SQ_ERR_SOLVER,
                            "the interior map is not injective in floating point: %u of %u UV "
                            "triangles are not positively oriented (first: face %u); Tutte's map "
                            "squeezes narrow parts of a cell below double precision (docs/param.md, "
                            "Limits)",
                            bad, S->nf, first);
    return SQ_OK;
}
