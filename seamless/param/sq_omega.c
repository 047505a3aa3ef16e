/* seamquad: the flat domain Omega: storage, the build driver and angles
 * (seed 7; seed 3, Fig. 2 d). */
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"

void sq_omega_init(sq_omega *O)
{
    memset(O, 0, sizeof *O);
    sq_metapolygon_init(&O->cut);
    O->root_side = O->root_pos = SQ_NONE;
}

void sq_omega_free(sq_omega *O)
{
    sq_metapolygon_free(&O->cut);
    free(O->v_qvert);
    free(O->he_qhe);
    free(O->he_label);
    free(O->he_partner);
    free(O->xy);
    free(O->f_dir);
    free(O->label_partner);
    free(O->label_side);
    free(O->label_rot);
    free(O->label_t);
    sq_omega_init(O);
}

sq_status sq_omega_build(const sq_domain *D, const sq_cone_tree *T, sq_omega *O,
                         sq_error *err)
{
    sq_status st = sq_omega_cut(D, T, O, err);
    if (st == SQ_OK) st = sq_omega_layout(D, O, err);
    if (st) sq_omega_free(O);
    return st;
}

static uint32_t uf_find(uint32_t *p, uint32_t x)
{
    while (p[x] != x) {
        p[x] = p[p[x]];
        x = p[x];
    }
    return x;
}

/* Seed 3, condition (1); seed 8 "Boundary Map": the angle of a glued point
 * is the sum over its copies; 4 quarter turns except at a cone. */
sq_status sq_omega_angles(const sq_domain *D, const sq_omega *O, uint32_t *angle,
                          uint32_t *point_angle, sq_error *err)
{
    const sq_metapolygon *Q = &D->quads, *C = &O->cut;
    for (uint32_t w = 0; w < C->nv; w++) angle[w] = C->v_nface[w];
    if (!point_angle) return SQ_OK;
    uint32_t *parent = malloc((Q->nv ? Q->nv : 1) * sizeof *parent);
    uint32_t *sum = calloc(Q->nv ? Q->nv : 1, sizeof *sum);
    if (!parent || !sum) {
        free(parent), free(sum);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t v = 0; v < Q->nv; v++) parent[v] = v;
    /* side i forward glues to side partner[i] backward */
    for (uint32_t i = 0; i < D->k; i++) {
        uint32_t j = D->pattern.partner[i], L = D->side_len[i];
        uint32_t hi = Q->v_he[D->corner_vert[i]];
        uint32_t hj = Q->v_he[D->corner_vert[(j + 1) % D->k]]; /* side j's end */
        for (uint32_t t = 0; t <= L; t++) {
            uint32_t a = uf_find(parent, Q->he_vert[hi]), b = uf_find(parent, Q->he_vert[hj]);
            if (a != b) parent[a < b ? b : a] = a < b ? a : b;
            if (t == L) break;
            hi = Q->he_next[hi];
            hj = sq_metapolygon_boundary_prev(Q, hj);
        }
    }
    for (uint32_t w = 0; w < C->nv; w++) sum[uf_find(parent, O->v_qvert[w])] += angle[w];
    for (uint32_t v = 0; v < Q->nv; v++) point_angle[v] = sum[uf_find(parent, v)];
    free(parent), free(sum);
    return SQ_OK;
}
