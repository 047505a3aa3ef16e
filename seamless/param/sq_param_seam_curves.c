/* seamquad: what the check (sq_param_io.c) and the picture of a
 * parametrization (svg/sq_param_svg.c) both read from it: the arrays'
 * ranges, and its seam curves: maximal chains of seam edges through
 * vertices with exactly two seam edges that are not cones, or closed loops
 * of such vertices (as the referee, shared/tools/check_param.py, defines
 * them). */
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_internal.h"

/* Arguments and index ranges; a message naming the first bad element. */
sq_status sq_param_check_arrays(const sq_param *P, const char *who, sq_error *err)
{
    if (!P) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL parametrization", who);
    if (!P->nv || !P->nf || !P->nuv)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: empty parametrization (%" PRIu32 " vertices, %" PRIu32
                            " faces, %" PRIu32 " UV points)",
                            who, P->nv, P->nf, P->nuv);
    if (!P->pos || !P->tri || !P->tri_uv || !P->uv)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL array in the parametrization", who);
    if (P->nv_input > P->nv)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: nv_input %" PRIu32 " exceeds the %" PRIu32 " vertices", who,
                            P->nv_input, P->nv);
    if (P->nf > UINT32_MAX / 3)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: too many faces", who);
    for (uint32_t c = 0; c < 3 * P->nf; c++) {
        if (P->tri[c] >= P->nv)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: face %" PRIu32 " uses vertex %" PRIu32 ", but there are %" PRIu32
                                " vertices",
                                who, c / 3, P->tri[c], P->nv);
        if (P->tri_uv[c] >= P->nuv)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: face %" PRIu32 " uses UV point %" PRIu32 ", but there are %" PRIu32
                                " UV points",
                                who, c / 3, P->tri_uv[c], P->nuv);
    }
    for (uint32_t t = 0; t < P->nuv; t++)
        if (!isfinite(P->uv[2 * (size_t)t]) || !isfinite(P->uv[2 * (size_t)t + 1]))
            return sq_error_set(err, SQ_ERR_INTERNAL, "%s: UV point %" PRIu32 " is not finite (%g, %g)",
                                who, t, P->uv[2 * (size_t)t], P->uv[2 * (size_t)t + 1]);
    return SQ_OK;
}

void sq_param_seam_curves_free(sq_param_seam_curves *C)
{
    free(C->curve), free(C->dir), free(C->first), free(C->sdeg);
    memset(C, 0, sizeof *C);
}

int sq_param_seam_node(const sq_param_seam_curves *C, const sq_param *P, uint32_t v)
{
    return C->sdeg[v] != 2 || sq_param_is_cone(P, v);
}

/* The other seam halfedge out of the vertex v where halfedge `in` ends (v
 * has two seam edges and is not a cone), or SQ_NONE. */
uint32_t sq_param_seam_next_out(const sq_mesh *m, const sq_param_seam_curves *C, uint32_t in)
{
    uint32_t back = m->he_twin[in], h = back;
    do {
        h = m->he_next[m->he_twin[h]];
        if (h != back && C->curve[h] != SQ_NONE) return h;
    } while (h != back);
    return SQ_NONE;
}

/* While the curves are found, C->curve[h] is SQ_NONE for a non-seam edge
 * and SQ_NONE - 1 for a seam edge not yet on a curve. */
sq_status sq_param_seam_curves_find(const sq_mesh *m, const sq_param *P, sq_param_seam_curves *C, sq_error *err)
{
    memset(C, 0, sizeof *C);
    C->curve = malloc((size_t)m->nh * sizeof *C->curve);
    C->dir = calloc(m->nh ? m->nh : 1, 1);
    C->sdeg = calloc(m->nv ? m->nv : 1, sizeof *C->sdeg);
    uint32_t cap = 64;
    C->first = malloc(cap * sizeof *C->first);
    if (!C->curve || !C->dir || !C->sdeg || !C->first) {
        sq_param_seam_curves_free(C);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    const uint32_t UNSET = SQ_NONE - 1;
    for (uint32_t h = 0; h < m->nh; h++) {
        C->curve[h] = sq_param_is_seam(m, P, h) ? UNSET : SQ_NONE;
        if (C->curve[h] == UNSET && h < m->he_twin[h]) {
            C->sdeg[m->he_vert[h]]++;
            C->sdeg[sq_param_he_dst(m, h)]++;
        }
    }
    /* open curves from every node, then closed loops */
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t h0 = 0; h0 < m->nh; h0++) {
            if (C->curve[h0] != UNSET) continue;
            if (pass == 0 && !sq_param_seam_node(C, P, m->he_vert[h0])) continue;
            if (C->n == cap) {
                uint32_t *t = realloc(C->first, 2 * (size_t)cap * sizeof *t);
                if (!t) {
                    sq_param_seam_curves_free(C);
                    return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                }
                C->first = t;
                cap *= 2;
            }
            uint32_t id = C->n++;
            C->first[id] = h0;
            uint32_t h = h0;
            for (;;) {
                C->curve[h] = C->curve[m->he_twin[h]] = id;
                C->dir[h] = 1;
                uint32_t y = sq_param_he_dst(m, h);
                if (sq_param_seam_node(C, P, y)) break;
                uint32_t g = sq_param_seam_next_out(m, C, h);
                if (g == SQ_NONE || C->curve[g] != UNSET) break; /* a loop closed */
                h = g;
            }
        }
    }
    return SQ_OK;
}
