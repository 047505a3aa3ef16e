/* seamquad: a seamless map on the input mesh from seam rotations alone
 * (sq_map_from_rotations.h: what, why, limits). */
#include "sq_map_from_rotations.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_map_internal.h"
#include "sq_map_untangle.h"

typedef struct build {
    const sq_mesh *m;   /* the input                                         */
    sq_soup soup;       /* m's positions and triangles (corners from f_he)   */
    uint32_t *hm;       /* 3 nf: m's halfedge of the map's halfedge 3f + c   */
    sq_map S;           /* the map's structure: its own mesh, rotations      */
    uint8_t *seam;      /* 3 nf                                              */
    sq_uv_basis B;
    sq_sd_face *F;
    double *phi;        /* nf: the field's direction in f's frame, quarter turns */
} build;

/* The soup of m with corners from f_he[f] on, and the map's mesh from it
 * (halfedge 3f + c), with hm to m's halfedges. */
static sq_status make_mesh(build *X, sq_error *err)
{
    const sq_mesh *m = X->m;
    X->soup.nv = m->nv;
    X->soup.pos = m->pos;
    X->soup.nf = m->nf;
    X->soup.face_off = malloc(((size_t)m->nf + 1) * sizeof *X->soup.face_off);
    X->soup.face_idx = sq_mesh_triangles(m);
    X->hm = malloc(3 * (size_t)m->nf * sizeof *X->hm);
    if (!X->soup.face_off || !X->soup.face_idx || !X->hm)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map of %u faces)", m->nf);
    for (uint32_t f = 0; f <= m->nf; f++) X->soup.face_off[f] = 3 * f;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) X->hm[3 * (size_t)f + c] = h;
    }
    sq_error e2;
    sq_status st = sq_mesh_from_soup(&X->soup, SQ_MESH_SKIP_DEGENERATE, &X->S.mesh, &e2);
    if (st == SQ_ERR_NOMEM) return sq_error_set(err, st, "%s", e2.msg);
    if (st) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_map_from_rotations: %s", e2.msg);
    return SQ_OK;
}

/* Step 1: integer rotations on a face tree's gauge; the seams. 0 and why
 * when turn is not a connection with integer loop sums. */
static sq_status rotations(build *X, const double *turn, sq_rotation_map_report *rep, int *ok, sq_error *err)
{
    const sq_mesh *mc = &X->S.mesh;
    const int32_t *val = X->S.valence;
    uint32_t nf = mc->nf, nh = mc->nh, nv = mc->nv;
    double *phi = X->phi;
    uint32_t *queue = malloc((size_t)(nf > nv ? nf : nv) * sizeof *queue);
    uint8_t *seen = calloc(nf, 1);
    uint32_t *deg = calloc(nv, sizeof *deg);
    *ok = 0;
    sq_status st = SQ_OK;
    if (!phi || !queue || !seen || !deg) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (rotations)");
        goto done;
    }
    for (uint32_t h = 0; h < nh; h++) X->seam[h] = 1;
    uint32_t qh = 0, qn = 0;
    queue[qn++] = 0, seen[0] = 1, phi[0] = 0;
    while (qh < qn) {
        uint32_t f = queue[qh++];
        for (uint32_t c = 0; c < 3; c++) {
            uint32_t h = 3 * f + c, t = mc->he_twin[h], g = mc->he_face[t];
            if (seen[g]) continue;
            seen[g] = 1;
            phi[g] = phi[f] + turn[X->hm[h]];
            X->seam[h] = X->seam[t] = 0;
            queue[qn++] = g;
        }
    }
    for (uint32_t h = 0; h < nh; h++) {
        double x = turn[X->hm[h]] + phi[mc->he_face[h]] - phi[mc->he_face[mc->he_twin[h]]];
        double k = nearbyint(x);
        if (fabs(x - k) > 1e-4) {
            snprintf(rep->why, sizeof rep->why, "the transport is not integer around the loop of edge (%u, %u): %g",
                     mc->he_vert[h], sq_map_dst(mc, h), x);
            goto done;
        }
        X->S.he_rot[h] = X->seam[h] ? (uint8_t)(((long)k % 4 + 4) % 4) : 0;
    }
    /* dangling seams at regular vertices go (their rotation must be 0) */
    for (uint32_t h = 0; h < nh; h++) deg[mc->he_vert[h]] += X->seam[h];
    qh = qn = 0;
    for (uint32_t v = 0; v < nv; v++)
        if (deg[v] == 1 && val[v] == 4) queue[qn++] = v;
    while (qh < qn) {
        uint32_t v = queue[qh++], h0 = mc->v_he[v], h = h0;
        if (deg[v] != 1) continue;
        while (!X->seam[h]) {
            h = sq_map_rotate_out(mc, h);
            if (h == h0) break;
        }
        if (X->S.he_rot[h] != 0) {
            snprintf(rep->why, sizeof rep->why, "the transport turns around regular vertex %u", v);
            goto done;
        }
        uint32_t t = mc->he_twin[h], w = mc->he_vert[t];
        X->seam[h] = X->seam[t] = 0;
        deg[v]--, deg[w]--;
        if (deg[w] == 1 && val[w] == 4) queue[qn++] = w;
    }
    for (uint32_t h = 0; h < nh; h++) rep->seam_edges += X->seam[h];
    rep->seam_edges /= 2;
    *ok = 1;
done:
    free(queue), free(seen), free(deg);
    return st;
}

/* The conformal scale the cones ask for (Ben-Chen, Gotsman and Bunin
 * 2008, "Conformal flattening by curvature prescription and metric
 * scaling", linearized): L u = K_target - K, L the cotangent Laplacian, K
 * the angle defect, K_target = 2 pi - valence pi/2; per face exp(mean u),
 * scaled to keep the total area. scale: nf, out. */
static sq_status cone_scale(const build *X, double *scale, sq_error *err)
{
    const sq_mesh *mc = &X->S.mesh;
    uint32_t nv = mc->nv, nh = mc->nh;
    size_t cap = 3 * (size_t)nh + nv;
    uint32_t *r = malloc(cap * sizeof *r), *c = malloc(cap * sizeof *c);
    double *v = malloc(cap * sizeof *v), *b = calloc(nv, sizeof *b), *u = malloc((size_t)nv * sizeof *u);
    double *dg = calloc(nv, sizeof *dg);
    sq_spd *fac = NULL;
    sq_status st = SQ_OK;
    if (!r || !c || !v || !b || !u || !dg) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (cone scale)");
        goto done;
    }
    size_t n = 0;
    for (uint32_t v0 = 0; v0 < nv; v0++) b[v0] = -X->S.valence[v0] * 1.57079632679489661923;
    for (uint32_t h = 0; h < nh; h++) {
        /* the corner opposite h's edge, and h's origin corner's angle */
        uint32_t nx = mc->he_next[h], pv = mc->he_next[nx];
        uint32_t a0 = mc->he_vert[h], a1 = mc->he_vert[nx], o = mc->he_vert[pv];
        const double *P0 = mc->pos + 3 * (size_t)a0, *P1 = mc->pos + 3 * (size_t)a1, *PO = mc->pos + 3 * (size_t)o;
        double e1[3], e2[3], f1[3], f2[3];
        for (int k = 0; k < 3; k++) e1[k] = P0[k] - PO[k], e2[k] = P1[k] - PO[k], f1[k] = P1[k] - P0[k], f2[k] = PO[k] - P0[k];
        double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double crn = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        double dot = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
        double w = crn > 0 ? 0.5 * dot / crn : 0.0;
        double fdot = f1[0] * f2[0] + f1[1] * f2[1] + f1[2] * f2[2];
        b[a0] += atan2(crn, fdot); /* crn: the same face's doubled area */
        uint32_t hi = a0 > a1 ? a0 : a1, lo = a0 > a1 ? a1 : a0;
        r[n] = a0, c[n] = a0, v[n++] = w;
        r[n] = a1, c[n] = a1, v[n++] = w;
        r[n] = hi, c[n] = lo, v[n++] = -w;
        dg[a0] += w, dg[a1] += w;
    }
    double mean = 0;
    for (uint32_t k = 0; k < nv; k++) mean += dg[k];
    mean = nv ? mean / nv : 1;
    for (uint32_t k = 0; k < nv; k++) r[n] = c[n] = k, v[n++] = 1e-8 * mean;
    if ((st = sq_spd_factor(nv, n, r, c, v, &fac, err))) goto done;
    if ((st = sq_spd_solve(fac, 1, b, u, err))) goto done;
    double A = 0, As = 0;
    for (uint32_t f = 0; f < mc->nf; f++) {
        double m3 = (u[mc->he_vert[3 * f]] + u[mc->he_vert[3 * f + 1]] + u[mc->he_vert[3 * f + 2]]) / 3;
        scale[f] = exp(m3);
        A += X->F[f].area, As += X->F[f].area * scale[f] * scale[f];
    }
    double k = As > 0 && isfinite(As) ? sqrt(A / As) : 1;
    for (uint32_t f = 0; f < mc->nf; f++) scale[f] = isfinite(scale[f] * k) ? scale[f] * k : 1;
done:
    sq_spd_free(fac);
    free(r), free(c), free(v), free(b), free(u), free(dg);
    return st;
}

/* Step 2: the seamless map closest to the field's frames scaled by the
 * cones' conformal scale: sum over faces of area |J - s_f R(-theta_f)|^2,
 * theta_f = phi_f pi/2 (the field's direction in f's frame goes to the u
 * axis), s_f from cone_scale. A linear least-squares problem in the basis:
 * one Newton step from z = 0 solves it, in S (sq_zsys_init of the map's
 * mesh and basis; step 3 goes on with it). z: nz, out. */
static sq_status field_aligned(build *X, sq_zsys *S, double *z, sq_error *err)
{
    const sq_mesh *mc = &X->S.mesh;
    const sq_uv_basis *B = &X->B;
    uint32_t nz = B->nz;
    double *uv = malloc(B->ncoord * sizeof *uv), *gz = malloc(((size_t)nz + 1) * sizeof *gz);
    double *scale = NULL;
    sq_status st = SQ_OK;
    if (!uv || !gz) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (field-aligned map)");
        goto done;
    }
    scale = malloc((size_t)mc->nf * sizeof *scale);
    if (!scale) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (field-aligned map)");
        goto done;
    }
    for (uint32_t f = 0; f < mc->nf; f++) scale[f] = 1;
    if ((st = cone_scale(X, scale, err))) goto done;
    memset(z, 0, nz * sizeof *z);
    sq_uv_basis_eval(B, z, uv);
    sq_zsys_zero(S, gz);
    for (uint32_t f = 0; f < mc->nf; f++) {
        const sq_sd_face *F = &X->F[f];
        if (F->area == 0) continue;
        double th = X->phi[f] * 1.57079632679489661923, ct = scale[f] * cos(th), sn = scale[f] * sin(th);
        double T[4] = {ct, sn, -sn, ct}, J[4], g[6], H[36];
        double fu[6];
        sq_face_uv(mc, uv, f, fu);
        sq_sd_jacobian(F, fu, J);
        for (int c1 = 0; c1 < 3; c1++)
            for (int a1 = 0; a1 < 2; a1++) {
                g[2 * c1 + a1] = 2 * F->area * (F->G[c1][0] * (J[2 * a1] - T[2 * a1]) + F->G[c1][1] * (J[2 * a1 + 1] - T[2 * a1 + 1]));
                for (int c2 = 0; c2 < 3; c2++)
                    for (int a2 = 0; a2 < 2; a2++)
                        H[(2 * c1 + a1) * 6 + 2 * c2 + a2] =
                            a1 == a2 ? 2 * F->area * (F->G[c1][0] * F->G[c2][0] + F->G[c1][1] * F->G[c2][1]) : 0.0;
            }
        sq_zsys_add_face(S, f, g, H, gz);
    }
    st = sq_zsys_solve(S, NULL, gz, z, err);
done:
    free(uv), free(gz), free(scale);
    return st;
}

/* Scales z so that the map's signed area is the surface's (1). */
static int normalize_area(const build *X, double *z)
{
    const sq_mesh *mc = &X->S.mesh;
    double *uv = malloc(X->B.ncoord * sizeof *uv);
    if (!uv) return 0;
    sq_uv_basis_eval(&X->B, z, uv);
    double A = 0;
    for (uint32_t f = 0; f < mc->nf; f++) {
        double p[6];
        sq_face_uv(mc, uv, f, p);
        A += 0.5 * ((p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]));
    }
    free(uv);
    if (!(A > 0) || !isfinite(A)) return 0;
    double k = 1 / sqrt(A);
    for (uint32_t i = 0; i < X->B.nz; i++) z[i] *= k;
    return 1;
}

/* Step 4: the soup with one UV per wedge (corners around a vertex joined
 * by non-seam edges), read back as an exact map. */
static sq_status finish(build *X, const double *uv, const int32_t *valence, sq_map *out,
                        sq_rotation_map_report *rep, sq_error *err)
{
    const sq_mesh *mc = &X->S.mesh;
    uint32_t nh = mc->nh;
    uint32_t *vt = malloc((size_t)nh * sizeof *vt);
    double *uvs = malloc(2 * (size_t)nh * sizeof *uvs);
    if (!vt || !uvs) {
        free(vt), free(uvs);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map soup)");
    }
    uint32_t n = 0;
    for (uint32_t v = 0; v < mc->nv; v++) {
        /* start right after a seam (crossing from h to rotate_out(h)
         * crosses the edge prev(h)), if there is one */
        uint32_t h0 = mc->v_he[v], start = h0, h = h0;
        do {
            uint32_t g = sq_map_rotate_out(mc, h);
            if (X->seam[sq_map_prev(mc, h)]) {
                start = g;
                break;
            }
            h = g;
        } while (h != h0);
        uint32_t id = n++;
        h = start;
        uvs[2 * (size_t)id] = uv[2 * (size_t)h], uvs[2 * (size_t)id + 1] = uv[2 * (size_t)h + 1];
        for (;;) {
            vt[h] = id;
            int crossing = X->seam[sq_map_prev(mc, h)];
            h = sq_map_rotate_out(mc, h);
            if (h == start) break;
            if (crossing) {
                id = n++;
                uvs[2 * (size_t)id] = uv[2 * (size_t)h], uvs[2 * (size_t)id + 1] = uv[2 * (size_t)h + 1];
            }
        }
    }
    sq_soup s = X->soup;
    s.nuv = n;
    s.uv = uvs;
    s.face_uv = vt;
    sq_error e2;
    sq_status st = sq_map_from_soup(&s, X->m, valence, 1e-9, 0, out, NULL, &e2);
    if (st == SQ_ERR_NOMEM) st = sq_error_set(err, st, "%s", e2.msg);
    else if (st) {
        snprintf(rep->why, sizeof rep->why, "the untangled map fails the exact check: %.150s", e2.msg);
        st = SQ_OK;
    } else
        rep->valid = 1;
    free(vt), free(uvs);
    return st;
}

sq_status sq_map_from_rotations(const sq_mesh *m, const int32_t *valence, const double *turn,
                                const sq_rotation_map_options *opt, sq_map *out,
                                sq_rotation_map_report *rep_out, sq_error *err)
{
    sq_rotation_map_report rep_local, *rep = rep_out ? rep_out : &rep_local;
    memset(rep, 0, sizeof *rep);
    memset(out, 0, sizeof *out);
    if (!m || !valence || !turn || !m->nf)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_map_from_rotations: NULL argument or empty mesh");
    double t0 = sq_now();
    uint32_t max_it = opt && opt->max_iterations ? opt->max_iterations : 300;
    build X;
    memset(&X, 0, sizeof X);
    X.m = m;
    double *z = NULL, *uv = NULL;
    sq_zsys S; /* the Newton system of steps 2 and 3 */
    memset(&S, 0, sizeof S);
    sq_status st = make_mesh(&X, err);
    if (st) goto done;
    const sq_mesh *mc = &X.S.mesh;
    X.S.he_uv = calloc(2 * (size_t)mc->nh, sizeof *X.S.he_uv);
    X.S.he_t = calloc(2 * (size_t)mc->nh, sizeof *X.S.he_t);
    X.S.he_rot = calloc(mc->nh, 1);
    X.S.valence = malloc((size_t)mc->nv * sizeof *X.S.valence);
    X.seam = calloc(mc->nh, 1);
    X.F = calloc(mc->nf, sizeof *X.F);
    X.phi = malloc((size_t)mc->nf * sizeof *X.phi);
    if (!X.phi || !X.S.he_uv || !X.S.he_t || !X.S.he_rot || !X.S.valence || !X.seam || !X.F) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map of %u faces)", m->nf);
        goto done;
    }
    memcpy(X.S.valence, valence, (size_t)mc->nv * sizeof *valence);
    int ok;
    if ((st = rotations(&X, turn, rep, &ok, err)) || !ok) goto done;
    if ((st = sq_uv_basis_free_translations_seams(&X.S, X.seam, &X.B, err))) goto done;
    /* the surface at area 1 */
    double area = sq_sd_surface_area(mc);
    if (!(area > 0)) {
        snprintf(rep->why, sizeof rep->why, "the surface has no area");
        goto done;
    }
    sq_sd_surface(mc, 1 / sqrt(area), X.F);
    z = malloc(((size_t)X.B.nz + 1) * sizeof *z);
    uv = malloc(X.B.ncoord * sizeof *uv);
    if (!z || !uv) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map of %u faces)", m->nf);
        goto done;
    }
    double t1 = sq_now();
    if ((st = sq_zsys_init(&S, mc, &X.B, err))) goto done;
    if ((st = field_aligned(&X, &S, z, err))) goto done;
    if (!normalize_area(&X, z)) {
        snprintf(rep->why, sizeof rep->why, "the conformal map has no positive area");
        goto done;
    }
    rep->seconds_fit = sq_now() - t1;
    t1 = sq_now();
    sq_untangle_result ur;
    if ((st = sq_map_untangle(mc, &X.B, X.F, &S, z, max_it, &ur, err))) goto done;
    rep->seconds_untangle = sq_now() - t1;
    rep->flipped_start = ur.flipped_before;
    rep->flipped_after = ur.flipped_after;
    rep->iterations = ur.iterations;
    rep->rounds = ur.rounds;
    if (ur.flipped_after) {
        snprintf(rep->why, sizeof rep->why, "%u triangles still flipped after %u untangling iterations",
                 ur.flipped_after, ur.iterations);
        goto done;
    }
    sq_uv_basis_eval(&X.B, z, uv);
    st = finish(&X, uv, valence, out, rep, err);
done:
    rep->seconds = sq_now() - t0;
    sq_zsys_free(&S);
    free(z), free(uv);
    sq_uv_basis_free(&X.B);
    sq_map_free(&X.S);
    free(X.seam), free(X.F), free(X.hm), free(X.phi);
    free(X.soup.face_off), free(X.soup.face_idx);
    return st;
}
