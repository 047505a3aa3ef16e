/* seamquad: the shapes of a quad mesh's quads, judged as the referee
 * judges them (sq_extract.h, step 6). */
#include <stdlib.h>

#include "sq_extract.h"
#include "sq_smooth.h"

sq_status sq_quad_mesh_check_shapes(const sq_quad_mesh *Q, const sq_mesh *m, const uint32_t *vert_face,
                                    const double *vert_bary, double diag, sq_quad_shapes *out, sq_error *err)
{
    sq_quad_shapes s = {0, 0, 0, 0, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};
    double eps_len = 1e-12 * diag, eps_area = 1e-12 * diag * diag;
    for (uint32_t f = 0; f < Q->nq; f++) {
        const uint32_t *q = Q->quad + 4 * (size_t)f;
        const double *p[4];
        for (int k = 0; k < 4; k++) p[k] = Q->pos + 3 * (size_t)q[k];
        double area, lmin;
        sq_quad_size(p[0], p[1], p[2], p[3], &area, &lmin);
        if (!(lmin > eps_len)) {
            if (!s.short_edge++) s.first_short_edge = f;
        } else if (!(area > eps_area)) {
            if (!s.tiny++) s.first_tiny = f;
        }
        if (sq_quad_fold_margin(p[0], p[1], p[2], p[3]) < 0.0 && !s.folded++) s.first_folded = f;
    }
    if (m && vert_face && vert_bary) {
        double *vn = sq_mesh_vertex_normals(m);
        if (!vn) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (turned quads)");
        sq_status st =
            sq_quad_mesh_count_turned(Q, m, vn, vert_face, vert_bary, &s.turned, &s.first_turned, NULL, err);
        free(vn);
        if (st) return st;
    }
    if (out) *out = s;
    if (s.short_edge)
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "%u quad%s an edge of length <= 1e-12 of the diagonal (two grid "
                            "points at one place on the surface), first: quad %u; %u folded, %u of "
                            "area <= 1e-12 diagonal^2: the map is too distorted at this grid size",
                            s.short_edge, s.short_edge == 1 ? " has" : "s have", s.first_short_edge + 1, s.folded, s.tiny);
    if (s.tiny)
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "%u quad%s an area <= 1e-12 of the squared diagonal, first: quad %u; "
                            "%u folded: the map is too distorted at this grid size",
                            s.tiny, s.tiny == 1 ? " has" : "s have", s.first_tiny + 1, s.folded);
    if (s.folded)
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "%u quad%s folded over the surface (both triangulations bent by more "
                            "than 90 degrees), first: quad %u: the map is too distorted at this grid "
                            "size",
                            s.folded, s.folded == 1 ? " is" : "s are", s.first_folded + 1);
    if (s.turned)
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "%u quad%s turned over on the surface (every corner facing away from it: "
                            "a flipped face), first: quad %u: the map is too distorted at this "
                            "grid size",
                            s.turned, s.turned == 1 ? " is" : "s are", s.first_turned + 1);
    return SQ_OK;
}
