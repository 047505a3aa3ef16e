/* seamquad: a seamless map from a soup with vt (sq_map.h).
 *
 * Steps: every corner has a UV; the positions and faces form a valid closed
 * mesh (sq_mesh_from_soup); the map belongs to `input` (its first vertices
 * are the input's, at the same positions); every UV triangle is positive
 * (exact predicate, before anything is changed: a fold is refused, never
 * repaired); every edge's two sides differ by a rotation by r * 90 degrees
 * plus a translation within tol * diagonal; angle sums are multiples of
 * pi/2 and match the cones given. A map whose transitions are exact is
 * kept as it is; otherwise it is refused (SQ_MAP_REQUIRE_EXACT) or snapped
 * to a dyadic grid (sq_map_snap.c). The result passes sq_map_check. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_map_internal.h"
#include "sq_predicates.h"

void sq_map_free(sq_map *M)
{
    if (!M) return;
    sq_mesh_free(&M->mesh);
    free(M->he_uv);
    free(M->he_rot);
    free(M->he_t);
    free(M->valence);
    memset(M, 0, sizeof *M);
}

static void *dup(const void *p, size_t n)
{
    void *q = malloc(n ? n : 1);
    if (q && n) memcpy(q, p, n);
    return q;
}

sq_status sq_map_copy(const sq_map *M, sq_map *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    const sq_mesh *m = &M->mesh;
    size_t nh = m->nh, nv = m->nv, nf = m->nf;
    out->mesh.nv = m->nv, out->mesh.nf = m->nf, out->mesh.nh = m->nh;
    out->mesh.pos = dup(m->pos, 3 * nv * sizeof *m->pos);
    out->mesh.he_next = dup(m->he_next, nh * sizeof *m->he_next);
    out->mesh.he_twin = dup(m->he_twin, nh * sizeof *m->he_twin);
    out->mesh.he_vert = dup(m->he_vert, nh * sizeof *m->he_vert);
    out->mesh.he_face = dup(m->he_face, nh * sizeof *m->he_face);
    out->mesh.v_he = dup(m->v_he, nv * sizeof *m->v_he);
    out->mesh.f_he = dup(m->f_he, nf * sizeof *m->f_he);
    out->he_uv = dup(M->he_uv, 2 * nh * sizeof *M->he_uv);
    out->he_rot = dup(M->he_rot, nh * sizeof *M->he_rot);
    out->he_t = dup(M->he_t, 2 * nh * sizeof *M->he_t);
    out->valence = dup(M->valence, nv * sizeof *M->valence);
    if (!out->mesh.pos || !out->mesh.he_next || !out->mesh.he_twin || !out->mesh.he_vert || !out->mesh.he_face ||
        !out->mesh.v_he || !out->mesh.f_he || !out->he_uv || !out->he_rot || !out->he_t || !out->valence) {
        sq_map_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (copy of a map of %u faces)", m->nf);
    }
    return SQ_OK;
}

void sq_map_angle_sums(const sq_mesh *m, const double *he_uv, double *sum)
{
    memset(sum, 0, m->nv * sizeof *sum);
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t n = m->he_next[h], p = sq_map_prev(m, h);
        sum[m->he_vert[h]] +=
            sq_map_corner_angle(he_uv + 2 * (size_t)p, he_uv + 2 * (size_t)h, he_uv + 2 * (size_t)n);
    }
}

static const char *face_where(const sq_soup *s, uint32_t f, char *buf, size_t n)
{
    sq_soup_where_face(s, f, buf, n);
    if (!buf[0]) snprintf(buf, n, "%s", s->path ? s->path : "the map");
    return buf;
}

/* The map's vertices must start with the input's, at the same positions
 * (a refinement keeps them first, as param writes its maps). */
static sq_status check_input(const sq_soup *soup, const sq_mesh *m, const sq_mesh *input,
                             sq_error *err)
{
    const char *file = soup->path ? soup->path : "the map";
    if (m->nv < input->nv)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: not a map of the input mesh: it has %u vertices, the input %u",
                            file, m->nv, input->nv);
    if (m->nv == input->nv && m->nf != input->nf)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: not a map of the input mesh: %u faces on the input's %u "
                            "vertices, the input has %u",
                            file, m->nf, m->nv, input->nf);
    for (uint32_t v = 0; v < input->nv; v++) {
        const double *a = m->pos + 3 * (size_t)v, *b = input->pos + 3 * (size_t)v;
        if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]) {
            char where[256];
            sq_soup_where_vertex(soup, v, where, sizeof where);
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: not a map of the input mesh: vertex %u is at (%.17g, %.17g, "
                                "%.17g), the input's vertex %u at (%.17g, %.17g, %.17g)",
                                where[0] ? where : file, v, a[0], a[1], a[2], v, b[0], b[1], b[2]);
        }
    }
    return SQ_OK;
}

/* Every UV triangle positive, decided exactly on the input's doubles. */
static sq_status check_orientation(const sq_soup *soup, const sq_map *M, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint32_t bad = 0, first = UINT32_MAX;
    int first_sign = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f], n = m->he_next[h], p = m->he_next[n];
        int s = sq_orient2d(M->he_uv + 2 * (size_t)h, M->he_uv + 2 * (size_t)n,
                            M->he_uv + 2 * (size_t)p);
        if (s > 0) continue;
        if (!bad++) first = f, first_sign = s;
    }
    if (!bad) return SQ_OK;
    char where[256];
    return sq_error_set(err, SQ_ERR_DEGENERATE,
                        "%s: the UV triangle of face %u is %s (exact orientation test); %u "
                        "flipped or zero-area UV triangles in all: the map is not locally "
                        "injective and is refused (nothing is repaired)",
                        face_where(soup, first, where, sizeof where), first,
                        first_sign < 0 ? "flipped" : "of zero area", bad);
}

/* Rotation and translation of every edge; seam[h] = 1 where the sides
 * differ. The translation stored is qa - R pa (estimated; exact or snapped
 * later); the mismatch at the other end is measured. */
static sq_status edge_transitions(const sq_soup *soup, sq_map *M, uint8_t *seam, double tol_abs,
                                  double *max_err, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    *max_err = 0.0;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t g = m->he_twin[h];
        if (g < h) continue;
        const double *pa = M->he_uv + 2 * (size_t)h, *pb = M->he_uv + 2 * (size_t)m->he_next[h];
        const double *qb = M->he_uv + 2 * (size_t)g, *qa = M->he_uv + 2 * (size_t)m->he_next[g];
        if (pa[0] == qa[0] && pa[1] == qa[1] && pb[0] == qb[0] && pb[1] == qb[1]) {
            M->he_rot[h] = M->he_rot[g] = 0;
            M->he_t[2 * (size_t)h] = M->he_t[2 * (size_t)h + 1] = 0.0;
            M->he_t[2 * (size_t)g] = M->he_t[2 * (size_t)g + 1] = 0.0;
            continue;
        }
        seam[h] = seam[g] = 1;
        double d[2] = {pb[0] - pa[0], pb[1] - pa[1]}, e[2] = {qb[0] - qa[0], qb[1] - qa[1]};
        int best = 0;
        double best_d = INFINITY;
        for (int r = 0; r < 4; r++) {
            double Rd[2];
            sq_map_rotate(r, d, Rd);
            double dd = hypot(Rd[0] - e[0], Rd[1] - e[1]);
            if (dd < best_d) best_d = dd, best = r;
        }
        double Ra[2], Rb[2], t[2];
        sq_map_rotate(best, pa, Ra);
        sq_map_rotate(best, pb, Rb);
        t[0] = qa[0] - Ra[0];
        t[1] = qa[1] - Ra[1];
        double mis = hypot(Rb[0] + t[0] - qb[0], Rb[1] + t[1] - qb[1]);
        if (mis > *max_err) *max_err = mis;
        if (!(mis <= tol_abs)) {
            char where[256];
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: the two sides of edge (%u, %u) (face %u) are not related by "
                                "a rotation by a multiple of 90 degrees plus a translation: the "
                                "best one misses by %.3g (tolerance %.3g)",
                                face_where(soup, m->he_face[h], where, sizeof where),
                                m->he_vert[h], m->he_vert[m->he_next[h]], m->he_face[h], mis,
                                tol_abs);
        }
        M->he_rot[h] = (uint8_t)best;
        M->he_t[2 * (size_t)h] = t[0];
        M->he_t[2 * (size_t)h + 1] = t[1];
        int ri;
        double ti[2];
        sq_map_inverse(best, t, &ri, ti);
        M->he_rot[g] = (uint8_t)ri;
        M->he_t[2 * (size_t)g] = ti[0];
        M->he_t[2 * (size_t)g + 1] = ti[1];
    }
    return SQ_OK;
}

/* Exactness of the transitions as given (SQ_MAP_REQUIRE_EXACT). */
static sq_status require_exact(const sq_soup *soup, sq_map *M, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t g = m->he_twin[h];
        const double *pa = M->he_uv + 2 * (size_t)h, *pb = M->he_uv + 2 * (size_t)m->he_next[h];
        const double *qb = M->he_uv + 2 * (size_t)g, *qa = M->he_uv + 2 * (size_t)m->he_next[g];
        int r = M->he_rot[h];
        double Ra[2], t[2], e0, e1, xa[2], xb[2];
        sq_map_rotate(r, pa, Ra);
        sq_map_two_sum(qa[0], -Ra[0], &t[0], &e0);
        sq_map_two_sum(qa[1], -Ra[1], &t[1], &e1);
        int ok = e0 == 0.0 && e1 == 0.0 && sq_map_apply(r, t, pa, xa) && sq_map_apply(r, t, pb, xb) &&
                 xa[0] == qa[0] && xa[1] == qa[1] && xb[0] == qb[0] && xb[1] == qb[1];
        if (!ok) {
            char where[256];
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: the seam at edge (%u, %u) (face %u) is not exact: its two "
                                "sides differ by a rotation by %d x 90 degrees plus a translation "
                                "only up to rounding (an exact map is required here)",
                                face_where(soup, m->he_face[h], where, sizeof where),
                                m->he_vert[h], m->he_vert[m->he_next[h]], m->he_face[h], r);
        }
        M->he_t[2 * (size_t)h] = t[0];
        M->he_t[2 * (size_t)h + 1] = t[1];
    }
    return SQ_OK;
}

/* Valences from the angle sums; the cones given must match. */
static sq_status angle_valences(const sq_soup *soup, sq_map *M, const int32_t *valence,
                                uint32_t n_valence, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    double *sum = malloc((m->nv ? m->nv : 1) * sizeof *sum);
    if (!sum) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (angle sums)");
    sq_map_angle_sums(m, M->he_uv, sum);
    sq_status st = SQ_OK;
    for (uint32_t v = 0; v < m->nv && !st; v++) {
        double k = sum[v] / SQ_MAP_HALF_PI;
        long kr = lround(k);
        char where[256];
        sq_soup_where_vertex(soup, v, where, sizeof where);
        if (kr < 1 || fabs(k - (double)kr) > 1e-6 * (double)kr)
            st = sq_error_set(err, SQ_ERR_CONE_VALUE,
                              "%s: vertex %u: the UV angle sum %.12g is not a multiple of pi/2 "
                              "(%.9g x pi/2): not a seamless map",
                              where[0] ? where : "map", v, sum[v], k);
        else if (valence && (v < n_valence ? valence[v] : 4) != kr)
            st = sq_error_set(err, SQ_ERR_CONE_VALUE,
                              "%s: vertex %u: the map's angle sum is %ld x pi/2 (valence %ld) but "
                              "the cones say valence %d: the map does not have these cones",
                              where[0] ? where : "map", v, kr, kr,
                              v < n_valence ? valence[v] : 4);
        else
            M->valence[v] = (int32_t)kr;
    }
    free(sum);
    return st;
}

sq_status sq_map_from_soup(const sq_soup *soup, const sq_mesh *input, const int32_t *valence,
                           double tol, unsigned flags, sq_map *out, sq_map_report *rep,
                           sq_error *err)
{
    sq_map_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!soup || !out) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_map_from_soup: NULL argument");
    memset(out, 0, sizeof *out);
    const char *file = soup->path ? soup->path : "the map";
    if (!soup->face_uv || !soup->nuv)
        return sq_error_set(err, SQ_ERR_PARSE,
                            "%s: no texture coordinates (vt): a map gives every face corner a UV "
                            "point ('f v/vt' corners)",
                            file);
    for (uint32_t f = 0; f < soup->nf; f++)
        for (uint32_t c = soup->face_off[f]; c < soup->face_off[f + 1]; c++)
            if (soup->face_uv[c] == SQ_NONE) {
                char where[256];
                return sq_error_set(err, SQ_ERR_PARSE,
                                    "%s: face %u has a corner without vt: a map gives every face "
                                    "corner a UV point",
                                    face_where(soup, f, where, sizeof where), f);
            }
    sq_status st = sq_mesh_from_soup(soup, (flags & SQ_MAP_ALLOW_FLAT_3D) ? SQ_MESH_SKIP_DEGENERATE : 0,
                                     &out->mesh, err);
    if (st) return st;
    sq_mesh *m = &out->mesh;
    if (input && (st = check_input(soup, m, input, err))) goto fail;
    out->he_uv = malloc(2 * (size_t)m->nh * sizeof *out->he_uv);
    out->he_rot = calloc(m->nh, 1);
    out->he_t = calloc(2 * (size_t)m->nh, sizeof *out->he_t);
    out->valence = malloc(m->nv * sizeof *out->valence);
    uint8_t *seam = calloc(m->nh, 1);
    if (!out->he_uv || !out->he_rot || !out->he_t || !out->valence || !seam) {
        free(seam);
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map of %u faces)", m->nf);
        goto fail;
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t h = 0; h < m->nh; h++) {
        const double *uv = soup->uv + 2 * (size_t)soup->face_uv[h];
        if (!isfinite(uv[0]) || !isfinite(uv[1])) {
            char where[256];
            free(seam);
            st = sq_error_set(err, SQ_ERR_NOT_FINITE, "%s: face %u has a UV that is not finite",
                              face_where(soup, m->he_face[h], where, sizeof where), m->he_face[h]);
            goto fail;
        }
        out->he_uv[2 * (size_t)h] = uv[0];
        out->he_uv[2 * (size_t)h + 1] = uv[1];
        for (int i = 0; i < 2; i++) lo[i] = fmin(lo[i], uv[i]), hi[i] = fmax(hi[i], uv[i]);
    }
    double diag = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if ((st = check_orientation(soup, out, err))) {
        free(seam);
        goto fail;
    }
    double max_err = 0.0;
    st = edge_transitions(soup, out, seam, (tol > 0 ? tol : 1e-9) * diag, &max_err, err);
    if (!st) st = angle_valences(soup, out, valence, input ? input->nv : m->nv, err);
    if (!st) {
        rep->max_seam_error = diag > 0 ? max_err / diag : 0.0;
        for (uint32_t h = 0; h < m->nh; h++) rep->seam_edges += seam[h];
        rep->seam_edges /= 2;
        for (uint32_t v = 0; v < m->nv; v++) rep->cones += out->valence[v] != 4;
        /* an exact map (param's) is kept as it is; otherwise snapped */
        sq_error exact_err;
        st = require_exact(soup, out, (flags & SQ_MAP_REQUIRE_EXACT) ? err : &exact_err);
        if (st && !(flags & SQ_MAP_REQUIRE_EXACT))
            st = sq_map_snap(out, seam, (tol > 0 ? tol : 1e-9) * diag, rep, err);
    }
    free(seam);
    if (!st) st = sq_map_check(out, flags & SQ_MAP_REQUIRE_INTEGER, err);
    if (st) goto fail;
    return SQ_OK;
fail:
    sq_map_free(out);
    return st;
}

sq_status sq_map_read(const char *path, const sq_mesh *input, const int32_t *valence, double tol,
                      unsigned flags, sq_map *out, sq_map_report *rep, sq_error *err)
{
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    if (out) memset(out, 0, sizeof *out);
    sq_status st = sq_read_mesh(path, &soup, err);
    if (!st) st = sq_map_from_soup(&soup, input, valence, tol, flags, out, rep, err);
    sq_soup_free(&soup);
    return st;
}
