/* seamquad: the 3D side of a parametrization's check (sq_param.h,
 * sq_param_verify_refinement): the map's mesh must be a refinement of the
 * input mesh, so that every quad vertex later placed on it lies on the
 * input surface.
 *
 * With the input face of every map triangle known (P->tri_in), the test is
 * local and needs no search: every corner of triangle f must lie in input
 * triangle tri_in[f] (an input vertex must be one of its corners, exactly;
 * an added vertex within REFINEMENT_TOLERANCE of it), and f must face the
 * same way. A triangle is convex, so a triangle whose corners lie in it
 * lies in it. Cost: one point-triangle distance per corner, O(faces). */
#include <inttypes.h>
#include <math.h>
#include <string.h>

#include "sq_param.h"

/* Distance of an added vertex from its input triangle, relative to the
 * input's bounding-box diagonal, above which the map is not a refinement
 * (the referee, check_param.py, allows 1e-9). param places added vertices
 * as barycentric combinations of their input face's or edge's corners:
 * on the 15 mpz cone files, and with needles of area 1e-12 of the
 * diagonal's square, the worst lie 3e-17 to 6e-16 off. */
#define REFINEMENT_TOLERANCE 1e-12

static void cross3(const double *a, const double *b, const double *c, double n[3])
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
}

static double dot3(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

/* Distance from p to segment ab. */
static double segment_distance(const double *p, const double *a, const double *b)
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double l2 = dot3(ab, ab), t = l2 > 0 ? fmin(fmax(dot3(ap, ab) / l2, 0.0), 1.0) : 0.0;
    return hypot(hypot(ap[0] - t * ab[0], ap[1] - t * ab[1]), ap[2] - t * ab[2]);
}

/* Distance from p to triangle abc: to its plane where p projects inside
 * it, else to its nearest side. Written for needles (the input may have
 * triangles of area 1e-12 of the diagonal's square), where closed forms
 * through the triangle's Gram matrix lose every digit: the sides'
 * distances need no normal, and where a thin triangle's inside test
 * rounds wrongly, p is within rounding of a side anyway. Not the
 * smoother's closest point (stages/sq_closest_point_triangle.c): that one
 * must return a point as a barycentric combination of the corners, whose
 * weights on a needle carry the normal's relative error (2e-12 of the
 * diagonal on mpz/eight with needles of 1e-9 of their length), while the
 * distance to the plane of a point in the corners' span does not. */
static double triangle_distance(const double *p, const double *a, const double *b, const double *c)
{
    double d = fmin(segment_distance(p, a, b), fmin(segment_distance(p, b, c), segment_distance(p, c, a)));
    double n[3];
    cross3(a, b, c, n);
    const double nn = sqrt(dot3(n, n));
    if (!(nn > 0)) return d;
    const double *corner[3] = {a, b, c};
    for (int k = 0; k < 3; k++) {
        const double *x = corner[k], *y = corner[(k + 1) % 3];
        double e[3];
        cross3(x, y, p, e); /* (y - x) x (p - x) */
        if (dot3(e, n) < 0) return d;
    }
    const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    return fmin(d, fabs(dot3(ap, n)) / nn);
}

sq_status sq_param_verify_refinement(const sq_param *P, const sq_mesh *m, double *max_dist,
                                     sq_error *err)
{
    static const char *who = "refinement check";
    if (max_dist) *max_dist = 0;
    if (!P || !m) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL argument", who);
    if (!P->tri_in)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: the map has no input faces (tri_in)", who);
    if (P->nv_input != m->nv || P->nv < P->nv_input)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: the map has %" PRIu32 " input vertices, the mesh %" PRIu32, who,
                            P->nv_input, m->nv);
    if (memcmp(P->pos, m->pos, 3 * (size_t)m->nv * sizeof *m->pos) != 0) {
        uint32_t v = 0;
        while (memcmp(P->pos + 3 * (size_t)v, m->pos + 3 * (size_t)v, 3 * sizeof *m->pos) == 0) v++;
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: input vertex %" PRIu32 " moved (%.17g %.17g %.17g, input %.17g "
                            "%.17g %.17g)",
                            who, v, P->pos[3 * (size_t)v], P->pos[3 * (size_t)v + 1],
                            P->pos[3 * (size_t)v + 2], m->pos[3 * (size_t)v], m->pos[3 * (size_t)v + 1],
                            m->pos[3 * (size_t)v + 2]);
    }
    const double diag = sq_bbox_diagonal(m->nv, m->pos);
    const double tol = REFINEMENT_TOLERANCE * diag;
    double worst = 0;
    for (uint32_t f = 0; f < P->nf; f++) {
        const uint32_t F = P->tri_in[f];
        if (F >= m->nf)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: face %" PRIu32 " names input face %" PRIu32 " of %" PRIu32, who, f,
                                F, m->nf);
        const uint32_t h0 = m->f_he[F];
        const uint32_t c[3] = {m->he_vert[h0], m->he_vert[m->he_next[h0]],
                               m->he_vert[m->he_next[m->he_next[h0]]]};
        const double *a = m->pos + 3 * (size_t)c[0], *b = m->pos + 3 * (size_t)c[1],
                     *cc = m->pos + 3 * (size_t)c[2];
        for (int k = 0; k < 3; k++) {
            const uint32_t v = P->tri[3 * (size_t)f + k];
            if (v >= P->nv)
                return sq_error_set(err, SQ_ERR_INTERNAL, "%s: face %" PRIu32 " names vertex %" PRIu32
                                    " of %" PRIu32, who, f, v, P->nv);
            if (v < P->nv_input) {
                if (v != c[0] && v != c[1] && v != c[2])
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "%s: face %" PRIu32 " has input vertex %" PRIu32
                                        ", which is not a corner of its input face %" PRIu32
                                        " (%" PRIu32 " %" PRIu32 " %" PRIu32 ")",
                                        who, f, v, F, c[0], c[1], c[2]);
                continue;
            }
            const double d = triangle_distance(P->pos + 3 * (size_t)v, a, b, cc);
            if (!(d <= tol))
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "%s: added vertex %" PRIu32 " of face %" PRIu32
                                    " lies %.3g of the diagonal off its input face %" PRIu32
                                    " (allowed %.0e): not a refinement of the input",
                                    who, v, f, d / diag, F, REFINEMENT_TOLERANCE);
            if (d > worst) worst = d;
        }
        /* the same side up, unless the triangle is too small to have one */
        double n[3], N[3];
        cross3(P->pos + 3 * (size_t)P->tri[3 * (size_t)f], P->pos + 3 * (size_t)P->tri[3 * (size_t)f + 1],
               P->pos + 3 * (size_t)P->tri[3 * (size_t)f + 2], n);
        cross3(a, b, cc, N);
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 1e-12 * diag * diag && !(n[0] * N[0] + n[1] * N[1] + n[2] * N[2] > 0))
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: face %" PRIu32 " faces the other way than its input face %" PRIu32,
                                who, f, F);
    }
    if (max_dist) *max_dist = diag > 0 ? worst / diag : worst;
    return SQ_OK;
}
