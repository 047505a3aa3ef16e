/* seamquad: param's result as an exact sq_map (sq_remesh.h, stage 3), and
 * the conformal ratio of a map.
 *
 * The soup is param's own arrays (sq_param_soup: positions, triangles, UV
 * corners), read without copying; sq_map_from_soup with SQ_MAP_REQUIRE_EXACT checks that
 * every seam is exact as param promises (nothing is snapped), that the
 * first vertices are the input's and that the angle sums are the cones. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_remesh.h"

sq_status sq_remesh_param_map(const sq_param *P, const sq_mesh *m, const int32_t *valence,
                              sq_map *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (!P || !m || !P->nf) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_remesh_param_map: no map");
    sq_soup s;
    sq_status st = sq_param_soup(P, &s, err);
    if (st) return st;
    st = sq_map_from_soup(&s, m, valence, 0, SQ_MAP_REQUIRE_EXACT, out, NULL, err);
    free(s.face_off);
    return st;
}

double sq_remesh_conformal_mean(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    double sum = 0, area = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h[3] = {m->f_he[f], 0, 0};
        h[1] = m->he_next[h[0]];
        h[2] = m->he_next[h[1]];
        const double *p0 = m->pos + 3 * (size_t)m->he_vert[h[0]];
        const double *p1 = m->pos + 3 * (size_t)m->he_vert[h[1]];
        const double *p2 = m->pos + 3 * (size_t)m->he_vert[h[2]];
        double e1[3], e2[3];
        for (int i = 0; i < 3; i++) e1[i] = p1[i] - p0[i], e2[i] = p2[i] - p0[i];
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        double a2 = sqrt(cx * cx + cy * cy + cz * cz), l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        if (!(a2 > 0) || !(l1 > 0)) continue;
        /* the surface triangle in a 2D frame: x1 = (l1, 0), x2 = (a, b) */
        double a = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1, b = a2 / l1;
        const double *u0 = M->he_uv + 2 * (size_t)h[0], *u1 = M->he_uv + 2 * (size_t)h[1],
                     *u2 = M->he_uv + 2 * (size_t)h[2];
        double du1[2] = {u1[0] - u0[0], u1[1] - u0[1]}, du2[2] = {u2[0] - u0[0], u2[1] - u0[1]};
        /* J = [du1 du2] X^-1, X = [[l1, a], [0, b]] */
        double J00 = du1[0] / l1, J10 = du1[1] / l1;
        double J01 = (du2[0] - a * J00) / b, J11 = (du2[1] - a * J10) / b;
        double fro = J00 * J00 + J01 * J01 + J10 * J10 + J11 * J11, det = J00 * J11 - J01 * J10;
        if (!(det > 0)) continue;
        double d = sqrt(fmax(fro * fro - 4 * det * det, 0.0));
        double s1 = sqrt(0.5 * (fro + d)), s2 = det / s1;
        sum += 0.5 * a2 * (s1 / s2);
        area += 0.5 * a2;
    }
    return area > 0 ? sum / area : INFINITY;
}
