/* seamquad: the per-triangle energy of the optimizer (sq_optimize_energy.c;
 * not a public header). */
#ifndef SQ_OPTIMIZE_INTERNAL_H
#define SQ_OPTIMIZE_INTERNAL_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"
#include "sq_sparse.h"
#include "sq_uv_basis.h"

typedef struct sq_sd_face {
    double area;     /* on the (scaled) surface; 0: left out of the energy */
    double G[3][2];  /* J = uv G (uv: the 2x3 matrix of corners)           */
} sq_sd_face;

/* The frame of the triangle p0 p1 p2 scaled by `scale`; 0 (and area 0) if
 * it is degenerate in doubles. */
int sq_sd_prepare(const double *p0, const double *p1, const double *p2, double scale,
                  sq_sd_face *F);

/* The halfedges of face f, its first (f_he[f]) first: the corners in F's
 * order; sq_face_uv: their UVs in he_uv (u0 v0 u1 v1 u2 v2). */
static inline void sq_face_corners(const sq_mesh *m, uint32_t f, uint32_t hc[3])
{
    hc[0] = m->f_he[f];
    hc[1] = m->he_next[hc[0]];
    hc[2] = m->he_next[hc[1]];
}

static inline void sq_face_uv(const sq_mesh *m, const double *he_uv, uint32_t f, double uv[6])
{
    uint32_t hc[3];
    sq_face_corners(m, f, hc);
    for (int c = 0; c < 3; c++)
        uv[2 * c] = he_uv[2 * (size_t)hc[c]], uv[2 * c + 1] = he_uv[2 * (size_t)hc[c] + 1];
}

/* sq_sd_surface_area: the total area of m's triangles (those that
 * sq_sd_prepare takes); sq_sd_surface: their frames (F: nf, corners from
 * f_he[f] on) with the surface scaled by `scale`. */
double sq_sd_surface_area(const sq_mesh *m);
void sq_sd_surface(const sq_mesh *m, double scale, sq_sd_face *F);
/* sq_sd_surface with face f's triangle scaled by scale * face_scale[f]
 * (face_scale NULL: by scale alone). */
void sq_sd_surface_scaled(const sq_mesh *m, double scale, const double *face_scale, sq_sd_face *F);

/* psi = |J|^2 + |J^-1|^2 of the corners uv (u0 v0 u1 v1 u2 v2); INFINITY
 * if the map's triangle is not positive in doubles; 0 if area is 0. */
double sq_sd_psi(const sq_sd_face *F, const double uv[6]);

/* psi, and weight * area * its gradient and projected Hessian (row-major
 * 6x6) in the corner coordinates. */
double sq_sd_grad_hess(const sq_sd_face *F, const double uv[6], double weight, double g[6],
                       double H[36]);

/* J (vec order 00, 01, 10, 11) of the corners uv against F. */
void sq_sd_jacobian(const sq_sd_face *F, const double uv[6], double J[4]);

/* A per-triangle function of J with gradient dJ and Hessian P (4x4, in
 * J's vec order) pulled back to the corner coordinates, times s: g (6) and
 * H (row-major 6x6). */
void sq_sd_pullback(const sq_sd_face *F, const double dJ[4], const double P[4][4], double s, double g[6],
                    double H[36]);

/* The progressive reference of F at the corners uv (Liu et al. 2018,
 * "Progressive Parameterizations"): with J = U diag(s1, s2) V^T the map's
 * Jacobian, the triangle whose Jacobian from the surface is
 * U diag(s1^(1-t), s2^(1-t)) V^T, t in [0, 1] the largest for which the map's
 * energy over it, sum s_i^(2t) + s_i^(-2t), is at most K. t = 1 (returned)
 * gives F itself; R keeps F's area. */
double sq_sd_reference(const sq_sd_face *F, const double uv[6], double K, sq_sd_face *R);

/* The smallest alpha > 0 at which the triangle uv + alpha duv degenerates
 * (INFINITY if none). */
double sq_sd_max_step(const double uv[6], const double duv[6]);

/* The log of the worst stretch max(s1, 1/s2) of the triangle uv (corners in
 * F's order; s1 >= s2 the singular values of J). A triangle whose
 * determinant rounds to zero or below (it may be positive exactly) gets
 * 1000, beyond any double's. */
double sq_sd_log_stretch(const sq_sd_face *F, const double uv[6]);

/* sq_optimize_relax.c: the vertices (not cones) beside triangles stretched
 * by more than `bound` (max(s1, 1/s2) against F) moved to lower the worst
 * stretch of their triangles, every move checked exactly; those on a seam
 * only if grid > 0 (their first corner rounded to it, the others by the
 * transitions, every sum exact). he_uv (the map's corners) is changed
 * in place and stays an exact map with the same transitions. */
typedef struct sq_relax_report {
    uint64_t moves, tries;
    double worst_before, worst_after; /* the largest stretch over the map */
} sq_relax_report;

sq_status sq_optimize_relax(const sq_map *M, const sq_sd_face *F, double bound, double grid,
                            double *he_uv, sq_relax_report *rep, sq_error *err);

/* sq_zsystem.c: the Newton system of an energy summed over triangles in
 * the unknowns z of basis B (he_uv = c + P z): H_z = sum P^T H_f P and
 * g_z = sum P^T g_f, lower triangle, pattern built once (sq_zsys_init),
 * solved by CHOLMOD (symbolic factorization once, refactored per solve). */
typedef struct sq_zsys {
    const sq_mesh *m;
    const sq_uv_basis *B;
    uint32_t *h_off;     /* nz + 1: CSR rows of the lower triangle           */
    uint32_t *h_col;     /* sorted within a row                              */
    double *h_val;
    uint32_t *h_row;     /* the row of every entry (for the solver)          */
    sq_spd *fac;         /* the analyzed factorization                       */
    size_t *slot_off;    /* nf + 1, or NULL: each face's entries of h_val in */
    uint32_t *slot;      /* the order sq_zsys_add_face adds them (a cache of */
                         /* its searches, kept when under SQ_ZSYS_SLOTS)     */
} sq_zsys;

/* The most cached entry positions (32 MB): faces of maps up to about 200K
 * triangles; larger ones search the pattern at every assembly. */
#define SQ_ZSYS_SLOTS (8u << 20)

sq_status sq_zsys_init(sq_zsys *S, const sq_mesh *m, const sq_uv_basis *B, sq_error *err);
/* The entry (i, j), i >= j, of the pattern. */
double *sq_zsys_entry(sq_zsys *S, uint32_t i, uint32_t j);
/* H_z = 0 and gz (nz) = 0. */
void sq_zsys_zero(sq_zsys *S, double *gz);
/* Adds face f's gradient g and Hessian H (row-major 6x6) in its corner
 * coordinates (corners from f_he[f] on, u v each) to H_z and gz. */
void sq_zsys_add_face(sq_zsys *S, uint32_t f, const double g[6], const double H[36], double *gz);
/* out (ncoord) = P d: the corners' change for a change d of the unknowns. */
void sq_zsys_linear(const sq_uv_basis *B, const double *d, double *out);
/* H_z d = -gz, with the smallest of 1e-10, 1e-8, ... times the mean
 * diagonal added that factors; held (nz or NULL): unknowns whose step is
 * 0. H_z's values are changed where held. */
sq_status sq_zsys_solve(sq_zsys *S, const uint8_t *held, const double *gz, double *d, sq_error *err);
void sq_zsys_free(sq_zsys *S);

#endif
