/* seamquad: exact check of a seamless map (sq_map.h, sq_map_check).
 *
 * Orientation by the exact predicate; transitions by exact additions
 * (TwoSum: a sum is exact iff its rounding error is zero, and the stored
 * translation must reproduce both corners of the edge exactly); each twin
 * stores the inverse; angle sums are the valences' multiples of pi/2 (angles
 * are transcendental: relative tolerance 1e-6, as the referee uses); with
 * SQ_MAP_REQUIRE_INTEGER integer translations and cone points. */
#include <math.h>
#include <stdlib.h>

#include "sq_map_internal.h"
#include "sq_predicates.h"

static sq_status check_edges(const sq_map *M, unsigned flags, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t g = m->he_twin[h];
        int r = M->he_rot[h];
        const double *t = M->he_t + 2 * (size_t)h;
        const double *pa = M->he_uv + 2 * (size_t)h, *pb = M->he_uv + 2 * (size_t)m->he_next[h];
        const double *qb = M->he_uv + 2 * (size_t)g, *qa = M->he_uv + 2 * (size_t)m->he_next[g];
        double xa[2], xb[2], ti[2];
        int ri;
        uint32_t a = m->he_vert[h], b = sq_map_dst(m, h);
        if (r > 3 || !isfinite(t[0]) || !isfinite(t[1]))
            return sq_error_set(err, SQ_ERR_INTERNAL, "map: edge (%u, %u): bad transition", a, b);
        if (!sq_map_apply(r, t, pa, xa) || !sq_map_apply(r, t, pb, xb) || xa[0] != qa[0] ||
            xa[1] != qa[1] || xb[0] != qb[0] || xb[1] != qb[1])
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "map: edge (%u, %u) (face %u): the transition (rotation %d x 90 "
                                "degrees, translation (%.17g, %.17g)) does not map one side onto "
                                "the other exactly",
                                a, b, m->he_face[h], r, t[0], t[1]);
        sq_map_inverse(r, t, &ri, ti);
        if (M->he_rot[g] != ri || M->he_t[2 * (size_t)g] != ti[0] ||
            M->he_t[2 * (size_t)g + 1] != ti[1])
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "map: edge (%u, %u): the two sides do not store inverse transitions",
                                a, b);
        if ((flags & SQ_MAP_REQUIRE_INTEGER) && (floor(t[0]) != t[0] || floor(t[1]) != t[1]))
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "map: edge (%u, %u) (face %u): the seam's translation (%.17g, "
                                "%.17g) is not integer: not an integer-grid map",
                                a, b, m->he_face[h], t[0], t[1]);
    }
    return SQ_OK;
}

sq_status sq_map_check(const sq_map *M, unsigned flags, sq_error *err)
{
    if (!M || !M->he_uv || !M->he_rot || !M->he_t || !M->valence)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_map_check: incomplete map");
    const sq_mesh *m = &M->mesh;
    uint32_t bad = 0, first = 0;
    int first_sign = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f], n = m->he_next[h], p = m->he_next[n];
        int s = sq_orient2d(M->he_uv + 2 * (size_t)h, M->he_uv + 2 * (size_t)n,
                            M->he_uv + 2 * (size_t)p);
        if (s <= 0 && !bad++) first = f, first_sign = s;
    }
    if (bad)
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "map: the UV triangle of face %u is %s (exact orientation test); %u "
                            "such triangles in all",
                            first, first_sign < 0 ? "flipped" : "of zero area", bad);
    sq_status st = check_edges(M, flags, err);
    if (st) return st;
    double *sum = malloc((m->nv ? m->nv : 1) * sizeof *sum);
    if (!sum) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (angle sums)");
    sq_map_angle_sums(m, M->he_uv, sum);
    for (uint32_t v = 0; v < m->nv && !st; v++) {
        double want = M->valence[v] * SQ_MAP_HALF_PI;
        if (!(fabs(sum[v] - want) <= 1e-6 * want))
            st = sq_error_set(err, SQ_ERR_CONE_VALUE,
                              "map: vertex %u: UV angle sum %.12g, expected %d x pi/2", v, sum[v],
                              M->valence[v]);
    }
    free(sum);
    if (st || !(flags & SQ_MAP_REQUIRE_INTEGER)) return st;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t v = m->he_vert[h];
        const double *p = M->he_uv + 2 * (size_t)h;
        if (M->valence[v] != 4 && (floor(p[0]) != p[0] || floor(p[1]) != p[1]))
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "map: cone vertex %u (valence %d) is at UV (%.17g, %.17g), not on "
                                "an integer point: not an integer-grid map",
                                v, M->valence[v], p[0], p[1]);
    }
    return SQ_OK;
}
