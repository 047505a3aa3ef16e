/* seamquad: independent check and output of a seamless parametrization
 * (sq_param.h): sq_param_verify, sq_param_write_obj (the picture:
 * svg/sq_param_svg.c).
 *
 * The check shares no code with the construction (sq_param.c and its step
 * files, sq_param_steps.h): it rebuilds the halfedge mesh from P->tri with
 * the core validator, then decides every property on the stored doubles,
 * exactly where the issue asks for exactness (seed 7-9; issue 4 (a)-(c)):
 *  - orientation: sq_orient2d (exact predicate) on every UV triangle;
 *  - seams: the two UV copies (p_a, p_b) and (q_a, q_b) of an edge are
 *    related by q = R p + t with R a rotation by r x 90 degrees iff
 *    q_a - R p_a = q_b - R p_b as real numbers, i.e. iff
 *    q_a + R p_b = q_b + R p_a. Both sides are sums of two doubles (R only
 *    swaps and negates coordinates), compared exactly as (sum, error) pairs
 *    of TwoSum: fl(a + b) depends only on the real sum and the error term
 *    is exact, so two pairs are equal iff the real sums are. No tolerance.
 *    The translation t = q_a - R p_a is integer iff its TwoSum pair is made
 *    of integers;
 *  - one transition per seam curve: a seam curve is a maximal chain of
 *    seam edges through vertices with exactly two seam edges that are not
 *    cones (as the referee, shared/tools/check_param.py, defines it), or a
 *    closed loop of such vertices; every edge of a curve, walked in one
 *    direction, must carry the rotation and the (exact) translation of its
 *    first edge;
 *  - angle sums: valence * pi/2 at input vertices, 2 pi at added ones,
 *    relative tolerance 1e-9 (angles are transcendental: this is the one
 *    check that cannot be exact).
 * The library never prints or exits: the first violation is returned as
 * SQ_ERR_INTERNAL with a message naming it (0-based face, vertex, edge) and
 * how many violations of that kind there are. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_predicates.h"

#define HALF_PI 1.57079632679489661923
#define ANGLE_RTOL 1e-9

/* ---- exact helpers ------------------------------------------------------ */

/* TwoSum (Knuth): s = fl(a + b), e = (a + b) - s exactly (finite inputs
 * without overflow). */
static void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* 1 iff a + b == c + d as real numbers. */
static int sums_equal(double a, double b, double c, double d)
{
    double s1, e1, s2, e2;
    two_sum(a, b, &s1, &e1);
    two_sum(c, d, &s2, &e2);
    return s1 == s2 && e1 == e2;
}

/* 1 iff a + b is an integer (exactly). */
static int sum_integral(double a, double b)
{
    double s, e;
    two_sum(a, b, &s, &e);
    return floor(s) == s && floor(e) == e;
}

/* R_r p for the rotation by r x 90 degrees (counterclockwise). */
static void rot(int r, const double *p, double *out)
{
    switch (r & 3) {
    case 0: out[0] = p[0], out[1] = p[1]; break;
    case 1: out[0] = -p[1], out[1] = p[0]; break;
    case 2: out[0] = -p[0], out[1] = -p[1]; break;
    default: out[0] = p[1], out[1] = -p[0]; break;
    }
}

/* 1 iff q_a - R p_a == q_b - R p_b exactly (the same translation at both
 * points). */
static int same_translation(int r, const double *pa, const double *qa, const double *pb,
                            const double *qb)
{
    double Ra[2], Rb[2];
    rot(r, pa, Ra);
    rot(r, pb, Rb);
    return sums_equal(qa[0], Rb[0], qb[0], Ra[0]) && sums_equal(qa[1], Rb[1], qb[1], Ra[1]);
}

/* ---- the mesh of P ------------------------------------------------------- */

sq_status sq_param_soup(const sq_param *P, sq_soup *s, sq_error *err)
{
    memset(s, 0, sizeof *s);
    uint32_t *off = malloc(((size_t)P->nf + 1) * sizeof *off);
    if (!off) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (soup of %" PRIu32 " faces)", P->nf);
    for (uint32_t f = 0; f <= P->nf; f++) off[f] = 3 * f;
    s->nv = P->nv;
    s->pos = P->pos;
    s->nf = P->nf;
    s->face_off = off;
    s->face_idx = P->tri;
    s->nuv = P->nuv;
    s->uv = P->uv;
    s->face_uv = P->tri_uv;
    return SQ_OK;
}

sq_status sq_param_mesh(const sq_param *P, const char *who, sq_mesh *m, sq_error *err)
{
    memset(m, 0, sizeof *m);
    sq_soup s;
    if (sq_param_soup(P, &s, err)) return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    /* the mesh only: no UVs */
    s.nuv = 0, s.uv = NULL, s.face_uv = NULL;
    sq_error e2;
    sq_status st = sq_mesh_from_soup(&s, SQ_MESH_SKIP_DEGENERATE, m, &e2);
    free(s.face_off);
    if (st == SQ_ERR_NOMEM) return sq_error_set(err, st, "%s: out of memory", who);
    if (st) return sq_error_set(err, SQ_ERR_INTERNAL, "%s: the mesh is not a valid closed surface: %s", who, e2.msg);
    return SQ_OK;
}

static const double *UV(const sq_param *P, uint32_t t) { return P->uv + 2 * (size_t)t; }

/* The transition of directed seam halfedge g (from x to y, left face =
 * g's face): UV copies p (left) and q (right) at x and y, and the rotation
 * r with q = R_r p + t exactly; -1 if there is none. */
typedef struct transition {
    const double *px, *py, *qx, *qy;
    int r;
} transition;

static transition edge_transition(const sq_mesh *m, const sq_param *P, uint32_t g)
{
    uint32_t t = m->he_twin[g];
    transition T;
    T.px = UV(P, P->tri_uv[g]);
    T.py = UV(P, P->tri_uv[m->he_next[g]]);
    T.qx = UV(P, P->tri_uv[m->he_next[t]]);
    T.qy = UV(P, P->tri_uv[t]);
    T.r = -1;
    for (int r = 0; r < 4; r++)
        if (same_translation(r, T.px, T.qx, T.py, T.qy)) {
            T.r = r;
            break;
        }
    return T;
}

/* Smallest |(q_y - q_x) - R (p_y - p_x)| over the rotations (for messages). */
static double best_residual(const transition *T, int *best_r)
{
    double d[2] = {T->py[0] - T->px[0], T->py[1] - T->px[1]};
    double e[2] = {T->qy[0] - T->qx[0], T->qy[1] - T->qx[1]};
    double best = INFINITY;
    for (int r = 0; r < 4; r++) {
        double Rd[2];
        rot(r, d, Rd);
        double res = hypot(e[0] - Rd[0], e[1] - Rd[1]);
        if (res < best) best = res, *best_r = r;
    }
    return best;
}

/* ---- verify ------------------------------------------------------------- */

static double corner_angle(const double *a, const double *b, const double *c)
{
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

/* every UV point belongs to one vertex (owner: nuv scratch) */
static sq_status check_uv_owners(const sq_param *P, const sq_mesh *m, uint32_t *owner, const char *who,
                                 sq_error *err)
{
    for (uint32_t t = 0; t < P->nuv; t++) owner[t] = SQ_NONE;
    for (uint32_t c = 0; c < m->nh; c++) {
        uint32_t t = P->tri_uv[c], v = P->tri[c];
        if (owner[t] == SQ_NONE) owner[t] = v;
        else if (owner[t] != v)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: UV point %" PRIu32 " is used by vertex %" PRIu32
                                " and by vertex %" PRIu32 " (face %" PRIu32 "); a UV point belongs to one vertex",
                                who, t, owner[t], v, c / 3);
    }
    return SQ_OK;
}

/* (a) orientation, exactly */
static sq_status check_orientation(const sq_param *P, const char *who, sq_error *err)
{
    uint32_t nflip = 0, nzero = 0, first = SQ_NONE;
    int first_sign = 0;
    for (uint32_t f = 0; f < P->nf; f++) {
        const uint32_t *t = P->tri_uv + 3 * (size_t)f;
        int s = sq_orient2d(UV(P, t[0]), UV(P, t[1]), UV(P, t[2]));
        if (s > 0) continue;
        if (s < 0) nflip++;
        else nzero++;
        if (first == SQ_NONE) first = f, first_sign = s;
    }
    if (first != SQ_NONE) {
        const uint32_t *v = P->tri + 3 * (size_t)first;
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: face %" PRIu32 " (vertices %" PRIu32 ", %" PRIu32 ", %" PRIu32
                            ") is %s in UV (exact orientation test); %" PRIu32
                            " flipped and %" PRIu32 " zero-area UV triangles in all",
                            who, first, v[0], v[1], v[2],
                            first_sign < 0 ? "flipped (clockwise)" : "degenerate (zero area)", nflip,
                            nzero);
    }
    return SQ_OK;
}

/* he_seam agrees with the UV indices */
static sq_status check_he_seam(const sq_param *P, const sq_mesh *m, const char *who, sq_error *err)
{
    if (P->he_seam)
        for (uint32_t h = 0; h < m->nh; h++)
            if (!P->he_seam[h] != !sq_param_is_seam(m, P, h))
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "%s: he_seam of face %" PRIu32 ", corner %" PRIu32
                                    " says %s, but edge (%" PRIu32 ", %" PRIu32 ") %s",
                                    who, h / 3, h % 3, P->he_seam[h] ? "seam" : "no seam", m->he_vert[h],
                                    sq_param_he_dst(m, h),
                                    P->he_seam[h] ? "has the same UV points on both sides"
                                                  : "has different UV points on its two sides");
    return SQ_OK;
}

/* (b) every seam edge: rotation by k x 90 degrees plus a translation,
 * exactly; integer translations with SQ_PARAM_VERIFY_INTEGER */
static sq_status check_seam_edges(const sq_param *P, const sq_mesh *m, int integer, const char *who,
                                  sq_error *err)
{
    uint32_t nbad = 0, nnonint = 0, bad = SQ_NONE, nonint = SQ_NONE;
    for (uint32_t h = 0; h < m->nh; h++) {
        if (h > m->he_twin[h] || !sq_param_is_seam(m, P, h)) continue;
        transition T = edge_transition(m, P, h);
        if (T.r < 0) {
            if (!nbad++) bad = h;
            continue;
        }
        if (integer) {
            double Rp[2];
            rot(T.r, T.px, Rp);
            if (!sum_integral(T.qx[0], -Rp[0]) || !sum_integral(T.qx[1], -Rp[1]))
                if (!nnonint++) nonint = h;
        }
    }
    if (nbad) {
        transition T = edge_transition(m, P, bad);
        int r = 0;
        double res = best_residual(&T, &r);
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: seam edge (%" PRIu32 ", %" PRIu32 ") between faces %" PRIu32
                            " and %" PRIu32
                            ": its two UV copies are not related exactly by a rotation by a "
                            "multiple of 90 degrees plus a translation (closest: rotation by %d "
                            "degrees, off by %.3g); %" PRIu32 " such seam edges in all",
                            who, m->he_vert[bad], sq_param_he_dst(m, bad), bad / 3, m->he_twin[bad] / 3,
                            90 * r, res, nbad);
    }
    if (nnonint) {
        transition T = edge_transition(m, P, nonint);
        double Rp[2];
        rot(T.r, T.px, Rp);
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: seam edge (%" PRIu32 ", %" PRIu32 ") between faces %" PRIu32
                            " and %" PRIu32 ": translation (%.17g, %.17g) of its transition "
                            "(rotation by %d degrees) is not integer; %" PRIu32
                            " such seam edges in all (an integer grid map needs integer "
                            "translations)",
                            who, m->he_vert[nonint], sq_param_he_dst(m, nonint), nonint / 3,
                            m->he_twin[nonint] / 3, T.qx[0] - Rp[0], T.qx[1] - Rp[1], 90 * T.r,
                            nnonint);
    }
    return SQ_OK;
}

/* (b') one transition per seam curve (C from find_curves) */
static sq_status check_curve_transitions(const sq_param *P, const sq_mesh *m, const sq_param_seam_curves *C,
                                         const char *who, sq_error *err)
{
    for (uint32_t i = 0; i < C->n; i++) {
        uint32_t h0 = C->first[i];
        transition T0 = edge_transition(m, P, h0);
        uint32_t h = h0, len = 0;
        for (;;) {
            len++;
            if (h != h0) {
                transition T = edge_transition(m, P, h);
                if (T.r != T0.r || !same_translation(T0.r, T0.px, T0.qx, T.px, T.qx))
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "%s: seam curve %" PRIu32 " from vertex %" PRIu32
                                        " has two transitions: edge (%" PRIu32 ", %" PRIu32
                                        ") (edge %" PRIu32 " along the curve) has rotation %d "
                                        "degrees%s, its first edge (%" PRIu32 ", %" PRIu32
                                        ") rotation %d degrees; a seam curve has one transition",
                                        who, i, m->he_vert[h0], m->he_vert[h], sq_param_he_dst(m, h), len - 1,
                                        90 * T.r, T.r == T0.r ? " and another translation" : "",
                                        m->he_vert[h0], sq_param_he_dst(m, h0), 90 * T0.r);
            }
            uint32_t y = sq_param_he_dst(m, h);
            if (sq_param_seam_node(C, P, y)) break;
            uint32_t g = sq_param_seam_next_out(m, C, h);
            if (g == SQ_NONE || g == h0 || C->curve[g] != i || !C->dir[g]) break;
            h = g;
        }
    }
    return SQ_OK;
}

/* integer grid map: cones at integer points */
static sq_status check_integer_cones(const sq_param *P, const sq_mesh *m, const char *who, sq_error *err)
{
    for (uint32_t c = 0; c < m->nh; c++) {
        uint32_t v = P->tri[c];
        if (!sq_param_is_cone(P, v)) continue;
        const double *p = UV(P, P->tri_uv[c]);
        if (floor(p[0]) != p[0] || floor(p[1]) != p[1])
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "%s: cone vertex %" PRIu32 " (valence %" PRId32
                                ") has UV point %" PRIu32 " = (%.17g, %.17g), not an integer "
                                "point (face %" PRIu32 "); an integer grid map puts cones on "
                                "the grid",
                                who, v, P->valence[v], P->tri_uv[c], p[0], p[1], c / 3);
    }
    return SQ_OK;
}

/* (c) angle sums (angle: nv zeroed scratch) */
static sq_status check_angle_sums(const sq_param *P, double *angle, const char *who, sq_error *err)
{
    for (uint32_t f = 0; f < P->nf; f++) {
        const uint32_t *t = P->tri_uv + 3 * (size_t)f;
        for (int k = 0; k < 3; k++)
            angle[P->tri[3 * (size_t)f + k]] +=
                corner_angle(UV(P, t[k]), UV(P, t[(k + 1) % 3]), UV(P, t[(k + 2) % 3]));
    }
    uint32_t nbad = 0, bad = SQ_NONE;
    for (uint32_t v = 0; v < P->nv; v++) {
        int32_t k = P->valence && v < P->nv_input ? P->valence[v] : 4;
        double want = k * HALF_PI;
        if (!(fabs(angle[v] - want) <= ANGLE_RTOL * want))
            if (!nbad++) bad = v;
    }
    if (nbad) {
        int32_t k = P->valence && bad < P->nv_input ? P->valence[bad] : 4;
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "%s: vertex %" PRIu32 " (%s) has UV angle sum %.17g = %.6f x pi/2, "
                            "expected %" PRId32 " x pi/2 (%s); %" PRIu32
                            " vertices with a wrong angle sum in all",
                            who, bad, bad < P->nv_input ? "input vertex" : "added vertex",
                            angle[bad], angle[bad] / HALF_PI, k,
                            bad < P->nv_input ? (k == 4 ? "regular" : "its cone") : "added vertices are regular",
                            nbad);
    }
    return SQ_OK;
}

sq_status sq_param_verify(const sq_param *P, unsigned flags, sq_error *err)
{
    static const char *who = "parametrization check";
    sq_status st = sq_param_check_arrays(P, who, err);
    if (st) return st;
    if (P->valence)
        for (uint32_t v = 0; v < P->nv_input; v++)
            if (P->valence[v] < 1)
                return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: vertex %" PRIu32 " has valence %" PRId32,
                                    who, v, P->valence[v]);
    sq_mesh m;
    st = sq_param_mesh(P, who, &m, err);
    if (st) return st;
    uint32_t *owner = NULL;
    double *angle = NULL;
    sq_param_seam_curves C;
    memset(&C, 0, sizeof C);
    const int integer = (flags & SQ_PARAM_VERIFY_INTEGER) != 0;

    owner = malloc((size_t)P->nuv * sizeof *owner);
    if (!owner) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if ((st = check_uv_owners(P, &m, owner, who, err)) || (st = check_orientation(P, who, err)) ||
        (st = check_he_seam(P, &m, who, err)) || (st = check_seam_edges(P, &m, integer, who, err)))
        goto done;
    st = sq_param_seam_curves_find(&m, P, &C, err);
    if (st) goto done;
    if ((st = check_curve_transitions(P, &m, &C, who, err)))
        goto done;
    if (integer && (st = check_integer_cones(P, &m, who, err)))
        goto done;
    angle = calloc(P->nv, sizeof *angle);
    if (!angle) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if ((st = check_angle_sums(P, angle, who, err)))
        goto done;
    st = SQ_OK;
done:
    free(owner);
    free(angle);
    sq_param_seam_curves_free(&C);
    sq_mesh_free(&m);
    if (st == SQ_OK) sq_error_clear(err);
    return st;
}

/* ---- OBJ ---------------------------------------------------------------- */

sq_status sq_param_write_obj(const char *path, const sq_param *P, sq_error *err)
{
    if (!path) return sq_error_set(err, SQ_ERR_ARGUMENT, "parametrization OBJ: NULL path");
    sq_status st = sq_param_check_arrays(P, path, err);
    if (st) return st;
    uint32_t *off = malloc(((size_t)P->nf + 1) * sizeof *off);
    if (!off) return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", path);
    for (uint32_t f = 0; f <= P->nf; f++) off[f] = 3 * f;
    /* v (%.17g), vt (%.17g), f a/ta b/tb c/tc, 1-based, through an atomic
     * file: doubles round-trip exactly */
    st = sq_write_obj(path, P->nv, P->pos, P->nf, off, P->tri, P->nuv, P->uv, P->tri_uv, err);
    free(off);
    return st;
}
