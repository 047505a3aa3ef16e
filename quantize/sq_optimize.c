/* seamquad: projected Newton on the symmetric Dirichlet energy of a
 * seamless map, in a basis that keeps it seamless (sq_optimize.h).
 *
 * Step 0: the extreme triangles relaxed by single-vertex jumps
 * (sq_optimize_relax.c). Then one iteration:
 *  1. the map's corners from the unknowns (he_uv = c + P z; with fixed
 *     transitions exactly seamless, eval_fixed_exact);
 *  2. every triangle's gradient and positive semidefinite Hessian
 *     (sq_optimize_energy.c), pulled back to z: g_z = P^T g, H_z = P^T H P,
 *     accumulated into a pattern built once;
 *  3. H_z d = -g_z by Cholesky (CHOLMOD: analyzed once, refactored per
 *     step), with a small multiple of the mean diagonal added so the
 *     system stays definite; held unknowns get d = 0;
 *  4. the step: at most 0.8 of the largest one that keeps every triangle
 *     positive, halved until the energy falls by the Armijo fraction
 *     1e-4 * alpha * g.d, and then accepted only if sq_orient2d (exact)
 *     finds every triangle positive.
 * The energy is a mean over the surface area (slivers floored,
 * WEIGHT_FLOOR; triangles not positive in doubles at the start held and
 * left out, and without progressive references those above PSI_HOLD too;
 * while a triangle is far from its shape on the surface, each is measured
 * against a progressive reference instead, PROG_PATIENCE),
 * so its scale does not depend on the mesh. It stops after max_iterations,
 * when a full step gains less than tolerance (relative), when three cut
 * steps in a row do (stalled), or when no step passes.
 *
 * Afterwards, with fixed transitions on a grid, the last iterate is the
 * map (it is exactly seamless already); otherwise the translations are
 * re-estimated from the corners (rotations as before) and the map is
 * snapped by the code that reads maps (sq_map_snap). Either way
 * sq_map_check decides; if it fails, or the energy did not fall, the
 * original map is restored.
 *
 * Cost per iteration: one sparse Cholesky of the size of the unknowns
 * (about the vertex count times two) plus O(faces) work for each energy
 * evaluation of the line search. Memory: the Hessian pattern (about 14
 * entries per unknown pair), the factor, and three copies of the corners. */
#include "sq_optimize.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_map_internal.h"
#include "sq_optimize_internal.h"
#include "sq_predicates.h"
#include "sq_sparse.h"
#include "sq_uv_basis.h"

typedef struct opt_ctx {
    const sq_mesh *m;
    const sq_uv_basis *B;
    sq_sd_face *F;       /* nf: the surface's triangles                       */
    sq_sd_face *R;       /* nf or NULL: progressive references (reference_update) */
    const sq_sd_face *E; /* the triangles the energy is measured against: F or R */
    double floor_r;      /* the references' weight floor (an area)            */
    double weight_f, weight_r; /* 1 / total area of F and of R                */
    double weight;       /* 1 / total surface area                            */
    sq_zsys sys;         /* the Newton system (sq_zsystem.c)                  */
    uint8_t *held;       /* nz or NULL: unknowns kept at their value           */
} opt_ctx;

/* Triangles far smaller than the mean (a refinement's slivers: 1e-19 of it
 * occur) are weighed as if WEIGHT_FLOOR times the mean: with their true
 * area their barrier falls below the rounding of the Newton system, the
 * step ignores them and the line search then cuts every step to the
 * fraction that keeps them positive. A larger floor lets the slivers'
 * shapes dominate the energy instead. Measured on homer's integer-grid
 * maps, 20 iterations: at 5K quads the energy ends at 10.0 with no floor,
 * 4.49 with 1e-12, 4.89 with 1e-9, 5.57 with 1e-6 (mean |angle - 90| of
 * the quads 9.06, 8.94, 8.92, 11.66); at 20K 5.61, 4.20, 4.25, 4.24. */
#define WEIGHT_FLOOR 1e-12

/* See eval_fixed_exact: sides shorter than this many grid steps are held. */
#define TINY_SIDE 1048576.0

/* Without progressive references (PROG_PATIENCE), triangles whose energy is
 * above this at the start (singular values 1e6 apart) are held, as are,
 * with or without them, triangles not positive in doubles (see
 * sq_optimize_map): Newton
 * raises such a triangle's determinant by a bounded factor per step, and
 * until then its barrier swamps every other triangle's progress in the sum
 * (param's integer-grid maps start at mean energies of 1e25 to 1e94;
 * published maps' integer-grid maps are unchanged by the hold at 1e12:
 * helmet, homer, fertility_tri bit for bit in quality, femur within 0.2
 * degrees; 1e8 cost helmet 1.7 degrees at 1K quads). */
#define PSI_HOLD 1e12

/* Progressive references (Liu et al. 2018): while some triangle's energy is
 * above the bound K, every iteration measures each triangle against a
 * reference between its current shape and its shape on the surface
 * (sq_sd_reference), the nearest to the surface's whose energy is at most
 * K, so no triangle's barrier dominates the Newton system and steps are not
 * cut to nothing by the worst one. The references are weighed by at least
 * the mean area (not WEIGHT_FLOOR): a sliver's barrier then holds it in the
 * Newton step instead of cutting the step. The phase ends when every
 * triangle is within K of its surface shape, or when the energy against
 * the surface has not fallen by the tolerance in PROG_PATIENCE iterations
 * (a few triangles that cannot reach the bound would otherwise weigh on the
 * rest for good); then the iterations go on against the surface. Measured
 * from param's maps (200 iterations, mean conformal ratio by
 * check_param.py): helmet 419 -> 9.8 (without: 256 after 100), knot1
 * 2196 -> 4.7 (374); published maps unchanged within 1% (helmet 1.571 ->
 * 1.583, femur, homer, elk, eight the same). */
#define PROG_PATIENCE 10

/* Step 0 (sq_optimize_relax.c) moves the vertices (not cones) beside
 * triangles stretched by more than this (max(s1, 1/s2)): what the
 * iterations cannot fix, or only slowly. Without progressive references
 * (quantize's step 5), 100; measured on the published maps' integer-grid
 * maps at 5K quads, mean |angle - 90| of the quads: helmet 21.25 (at 1e4)
 * -> 16.77, femur 14.01 -> 11.91, the other 13 models within 0.1 degrees
 * (bench/bench_quantize.sh). With references, which handle stretches up
 * to about sqrt(K) themselves, 1e4: at 100, step 0 moved 54 times more
 * vertices of trim-star's map of param (214,156 moves, 15.7 s per call,
 * and remesh calls it every round) for the same worst stretch. */
#define RELAX_BOUND 100.0
#define RELAX_BOUND_REFERENCES 1e4

/* Holds every unknown corner h depends on (hold_face: of all three). */
static void hold_corner(opt_ctx *X, uint32_t h)
{
    for (size_t r = 2 * (size_t)h; r < 2 * (size_t)h + 2; r++)
        for (uint32_t j = X->B->row_off[r]; j < X->B->row_off[r + 1]; j++) X->held[X->B->col[j]] = 1;
}

static void hold_face(opt_ctx *X, uint32_t f)
{
    uint32_t hc[3];
    sq_face_corners(X->m, f, hc);
    for (int c = 0; c < 3; c++) hold_corner(X, hc[c]);
}

/* Mean energy of the corners he_uv (INFINITY if a triangle is not positive
 * in doubles); *max gets the worst triangle's. */
static double energy(const opt_ctx *X, const double *he_uv, double *max)
{
    double sum = 0, worst = 0;
    for (uint32_t f = 0; f < X->m->nf; f++) {
        double uv[6];
        sq_face_uv(X->m, he_uv, f, uv);
        if (X->E[f].area == 0) {
            /* left out of the energy, but it must stay positive */
            if (!(sq_orient2d(uv, uv + 2, uv + 4) > 0)) return INFINITY;
            continue;
        }
        double p = sq_sd_psi(&X->E[f], uv);
        if (!isfinite(p)) return INFINITY;
        sum += X->E[f].area * p;
        if (p > worst) worst = p;
    }
    if (max) *max = worst;
    return sum * X->weight;
}

static int all_positive(const sq_mesh *m, const double *he_uv)
{
    for (uint32_t f = 0; f < m->nf; f++) {
        double uv[6];
        sq_face_uv(m, he_uv, f, uv);
        if (sq_orient2d(uv, uv + 2, uv + 4) <= 0) return 0;
    }
    return 1;
}

/* g_z and H_z at the corners he_uv. */
static void assemble(opt_ctx *X, const double *he_uv, double *gz)
{
    sq_zsys_zero(&X->sys, gz);
    for (uint32_t f = 0; f < X->m->nf; f++) {
        if (X->E[f].area == 0) continue;
        double uv[6], g[6], H[36];
        sq_face_uv(X->m, he_uv, f, uv);
        sq_sd_grad_hess(&X->E[f], uv, X->weight, g, H);
        sq_zsys_add_face(&X->sys, f, g, H, gz);
    }
}

void sq_optimize_energy(const sq_map *M, double *mean, double *max)
{
    const sq_mesh *m = &M->mesh;
    double a3 = sq_sd_surface_area(m), auv = 0, sum = 0, worst = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        double uv[6];
        sq_face_uv(m, M->he_uv, f, uv);
        auv += 0.5 * ((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[3] - uv[1]) * (uv[4] - uv[0]));
    }
    double scale = a3 > 0 && auv > 0 ? sqrt(auv / a3) : 1.0;
    a3 = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t hc[3];
        sq_face_corners(m, f, hc);
        double uv[6];
        sq_face_uv(m, M->he_uv, f, uv);
        sq_sd_face F;
        if (!sq_sd_prepare(m->pos + 3 * (size_t)m->he_vert[hc[0]], m->pos + 3 * (size_t)m->he_vert[hc[1]],
                           m->pos + 3 * (size_t)m->he_vert[hc[2]], scale, &F))
            continue;
        double p = sq_sd_psi(&F, uv);
        sum += F.area * p;
        a3 += F.area;
        if (p > worst) worst = p;
    }
    if (mean) *mean = a3 > 0 ? sum / a3 : INFINITY;
    if (max) *max = worst;
}

/* Writes the corners into M, re-derives the translations (fixed: kept) and
 * makes the map exact. */
static sq_status install(sq_map *M, const double *he_uv, int fixed, unsigned check_flags,
                         sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint8_t *seam = malloc(m->nh);
    if (!seam) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seams)");
    for (uint32_t h = 0; h < m->nh; h++)
        seam[h] = M->he_rot[h] != 0 || M->he_t[2 * (size_t)h] != 0 || M->he_t[2 * (size_t)h + 1] != 0;
    memcpy(M->he_uv, he_uv, 2 * (size_t)m->nh * sizeof *he_uv);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t h = 0; h < m->nh; h++)
        for (int i = 0; i < 2; i++)
            lo[i] = fmin(lo[i], he_uv[2 * h + i]), hi[i] = fmax(hi[i], he_uv[2 * h + i]);
    double diag = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if (!fixed) {
        for (uint32_t h = 0; h < m->nh; h++) {
            if (!seam[h]) continue;
            double Rp[2];
            sq_map_rotate(M->he_rot[h], M->he_uv + 2 * (size_t)h, Rp);
            const double *q = M->he_uv + 2 * (size_t)m->he_next[m->he_twin[h]];
            M->he_t[2 * (size_t)h] = q[0] - Rp[0];
            M->he_t[2 * (size_t)h + 1] = q[1] - Rp[1];
        }
    }
    sq_map_report rep;
    memset(&rep, 0, sizeof rep);
    sq_status st = sq_map_snap(M, seam, 1e-9 * diag, &rep, err);
    free(seam);
    if (!st) st = sq_map_check(M, check_flags, err);
    return st;
}

/* Fixed transitions, exactly. The grid h: 2^-50 of the largest coordinate
 * or translation (with a factor 4 of room for the optimization to grow
 * the map), so every sum of two values on it is exact; 0 if a translation
 * is not on it (the caller then snaps the map instead). */
static double fixed_grid(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    double big = 0;
    for (size_t k = 0; k < 2 * (size_t)m->nh; k++)
        big = fmax(big, fmax(fabs(M->he_uv[k]), fabs(M->he_t[k])));
    if (!(big > 0) || !isfinite(big)) return 0;
    double h = ldexp(1.0, ilogb(2 * big) + 1 - 53);
    for (size_t k = 0; k < 2 * (size_t)m->nh; k++)
        if (nearbyint(M->he_t[k] / h) * h != M->he_t[k]) return 0;
    return h;
}

/* 1 for the vertices that move with rounding: not cones (which never
 * move), with a seam edge (a transition that is not the identity) at them */
static uint8_t *seam_vertices(const sq_map *M)
{
    const sq_mesh *m = &M->mesh;
    uint8_t *s = calloc(m->nv ? m->nv : 1, 1);
    if (!s) return NULL;
    for (uint32_t h = 0; h < m->nh; h++)
        if (M->he_rot[h] != 0 || M->he_t[2 * (size_t)h] != 0 || M->he_t[2 * (size_t)h + 1] != 0)
            s[m->he_vert[h]] = s[m->he_vert[m->he_next[h]]] = 1;
    for (uint32_t v = 0; v < m->nv; v++)
        if (M->valence[v] != 4) s[v] = 0;
    return s;
}

/* The corners for the unknowns z, exactly seamless: a vertex whose
 * unknowns equal the input's keeps its corners bit for bit; a moved
 * vertex on a seam takes its first corner's point rounded to the grid h,
 * and its other corners follow around it by the transitions
 * (sq_map_apply, exact on the grid); a moved vertex without a seam takes
 * its point as it is (all its corners are one, nothing to add), so the
 * slivers of a refinement far below any global grid (param's maps) can
 * move at their own scale. No snapping of the whole map.
 * Returns 0 if a sum was not exact (a point outside the grid's range). */
static int eval_fixed_exact(const sq_map *M, const sq_uv_basis *B, const double *z, double h,
                            const uint8_t *vseam, double *out)
{
    const sq_mesh *m = &M->mesh;
    memcpy(out, M->he_uv, 2 * (size_t)m->nh * sizeof *out);
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v];
        size_t r = 2 * (size_t)h0;
        if (B->row_off[r + 1] == B->row_off[r]) continue; /* a cone: fixed */
        uint32_t u = B->col[B->row_off[r]];
        assert(B->val[B->row_off[r]] == 1.0 && B->col[B->row_off[r + 1]] == u + 1);
        if (z[u] == B->z0[u] && z[u + 1] == B->z0[u + 1]) continue;
        double p[2] = {z[u], z[u + 1]};
        if (vseam[v]) p[0] = nearbyint(p[0] / h) * h, p[1] = nearbyint(p[1] / h) * h;
        uint32_t k = h0;
        do {
            out[2 * (size_t)k] = p[0];
            out[2 * (size_t)k + 1] = p[1];
            uint32_t e = sq_map_prev(m, k);
            double q[2];
            if (!sq_map_apply(M->he_rot[e], M->he_t + 2 * (size_t)e, p, q)) return 0;
            p[0] = q[0], p[1] = q[1];
            k = sq_map_rotate_out(m, k);
        } while (k != h0);
        if (p[0] != out[2 * (size_t)h0] || p[1] != out[2 * (size_t)h0 + 1]) return 0;
    }
    return 1;
}

/* Progressive references at the corners he_uv (sq_sd_reference): every
 * triangle's energy over its reference at most K. Returns the number of
 * triangles whose reference is not the surface's own. */
static uint32_t reference_update(opt_ctx *X, const double *he_uv, double K)
{
    uint32_t n = 0;
    double total = 0;
    for (uint32_t f = 0; f < X->m->nf; f++) {
        double uv[6];
        sq_face_uv(X->m, he_uv, f, uv);
        if (sq_sd_reference(&X->F[f], uv, K, &X->R[f]) < 1.0) n++;
        if (X->R[f].area > 0 && X->R[f].area < X->floor_r) X->R[f].area = X->floor_r;
        total += X->R[f].area;
    }
    X->weight_r = total > 0 ? 1.0 / total : 1.0;
    return n;
}

/* The energy is measured against the surface's triangles (F) or the
 * progressive references (R). */
static void use_faces(opt_ctx *X, int refs)
{
    X->E = refs ? X->R : X->F;
    X->weight = refs ? X->weight_r : X->weight_f;
}

sq_status sq_optimize_map(sq_map *M, const sq_optimize_options *opt, sq_optimize_report *rep,
                          sq_error *err)
{
    sq_optimize_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!M || !opt) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_optimize_map: NULL argument");
    double t0 = sq_now();
    sq_status st = sq_map_check(M, 0, err);
    if (st) return st;
    sq_error tmp;
    int fixed = opt->basis == SQ_OPTIMIZE_FIXED_TRANSITIONS;
    /* with fixed transitions an integer-grid map stays one (and must) */
    unsigned check_flags =
        fixed && !sq_map_check(M, SQ_MAP_REQUIRE_INTEGER, &tmp) ? SQ_MAP_REQUIRE_INTEGER : 0;
    uint32_t max_it = opt->max_iterations ? opt->max_iterations : 100;
    double tol = opt->tolerance > 0 ? opt->tolerance : 1e-4;

    const sq_mesh *m = &M->mesh;
    opt_ctx X;
    memset(&X, 0, sizeof X);
    X.m = m;
    sq_uv_basis B;
    memset(&B, 0, sizeof B);
    size_t nc = 2 * (size_t)m->nh;
    double *orig = malloc(nc * sizeof *orig), *orig_t = malloc(nc * sizeof *orig_t);
    double *uv = malloc(nc * sizeof *uv), *trial = malloc(nc * sizeof *trial);
    double *duv = malloc(nc * sizeof *duv);
    double *z = NULL, *zt = NULL, *gz = NULL, *d = NULL;
    uint8_t *vseam = NULL;
    uint8_t *orig_rot = malloc(m->nh);
    X.F = calloc(m->nf, sizeof *X.F);
    X.E = X.F;
    double K = opt->reference_bound == 0 ? SQ_OPTIMIZE_REFERENCE_BOUND : opt->reference_bound;
    if (K > 4 && isfinite(K) && !(X.R = calloc(m->nf, sizeof *X.R))) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (optimizer references)");
        goto done;
    }
    if (!orig || !orig_t || !uv || !trial || !duv || !orig_rot || !X.F) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (optimizer, %u faces)", m->nf);
        goto done;
    }
    memcpy(orig, M->he_uv, nc * sizeof *orig);
    memcpy(orig_t, M->he_t, nc * sizeof *orig_t);
    memcpy(orig_rot, M->he_rot, m->nh);

    /* the surface scaled to the map's area */
    double auv = 0, total = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        double c6[6];
        sq_face_uv(m, M->he_uv, f, c6);
        auv += 0.5 * ((c6[2] - c6[0]) * (c6[5] - c6[1]) - (c6[3] - c6[1]) * (c6[4] - c6[0]));
    }
    /* the surface's area as magnified by face_scale (if given) */
    sq_sd_surface_scaled(m, 1.0, opt->face_scale, X.F);
    double a3 = 0;
    for (uint32_t f = 0; f < m->nf; f++) a3 += X.F[f].area;
    sq_sd_surface_scaled(m, a3 > 0 && auv > 0 ? sqrt(auv / a3) : 1.0, opt->face_scale, X.F);
    for (uint32_t f = 0; f < m->nf; f++) total += X.F[f].area;
    /* step 0: the extreme triangles relaxed by local moves that Newton's
     * rounded steps cannot make (sq_optimize_relax.c; RELAX_BOUND). The
     * relaxed map is exact and valid: it is the start, and what comes back
     * if the iterations fail. */
    sq_relax_report rr;
    double rb = opt->relax_bound > 0 ? opt->relax_bound : X.R ? RELAX_BOUND_REFERENCES : RELAX_BOUND;
    memset(&rr, 0, sizeof rr);
    if (isfinite(rb) && (st = sq_optimize_relax(M, X.F, rb, fixed_grid(M), M->he_uv, &rr, err))) goto done;
    rep->relax_moves = (uint32_t)(rr.moves > UINT32_MAX ? UINT32_MAX : rr.moves);
    rep->relax_stretch_before = rr.worst_before;
    rep->relax_stretch_after = rr.worst_after;
    if (rr.moves > 0) {
        /* every move kept the transitions, the cones and v's angle sum;
         * checked all the same, the input back if it fails */
        if (sq_map_check(M, check_flags, &tmp)) {
            memcpy(M->he_uv, orig, nc * sizeof *orig);
            rep->relax_moves = 0;
            rep->relax_stretch_after = rep->relax_stretch_before;
        } else {
            rep->changed = 1;
            memcpy(orig, M->he_uv, nc * sizeof *orig);
        }
    }
    st = fixed ? sq_uv_basis_fixed_transitions(M, &B, err) : sq_uv_basis_free_translations(M, &B, err);
    if (st) goto done;
    X.B = &B;
    rep->unknowns = B.nz;
    rep->seconds_basis = sq_now() - t0;
    z = malloc(((size_t)B.nz + 1) * sizeof *z), zt = malloc(((size_t)B.nz + 1) * sizeof *zt);
    gz = malloc(((size_t)B.nz + 1) * sizeof *gz), d = malloc(((size_t)B.nz + 1) * sizeof *d);
    if (!z || !zt || !gz || !d) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (optimizer, %u unknowns)", B.nz);
        goto done;
    }
    memcpy(z, B.z0, B.nz * sizeof *z);

    /* weight floor (see WEIGHT_FLOOR) */
    double floor_w = WEIGHT_FLOOR * total / m->nf;
    X.floor_r = total / m->nf; /* see PROG_PATIENCE */
    total = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        if (X.F[f].area > 0 && X.F[f].area < floor_w) X.F[f].area = floor_w;
        total += X.F[f].area;
    }
    X.weight = X.weight_f = total > 0 ? 1.0 / total : 1.0;

    /* with fixed transitions on a grid, every iterate is evaluated exactly
     * (eval_fixed_exact): what the line search's exact test accepts is
     * what is returned */
    double hgrid = fixed ? fixed_grid(M) : 0;
    sq_uv_basis_eval(&B, z, uv);
    if (hgrid > 0) memcpy(uv, M->he_uv, nc * sizeof *uv);
    X.held = calloc((size_t)B.nz + 1, 1);
    if (!X.held) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (optimizer)");
        goto done;
    }
    if (hgrid > 0) {
        /* a triangle with a corner on a seam and a side or a height below
         * TINY_SIDE grid steps would change shape, or flip, when that
         * corner rounds to the grid: its seam corners are held (its other
         * corners move unrounded, checked exactly like every triangle) */
        if (!(vseam = seam_vertices(M))) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (optimizer)");
            goto done;
        }
        for (uint32_t f = 0; f < m->nf; f++) {
            uint32_t hc[3];
            sq_face_corners(m, f, hc);
            if (!vseam[m->he_vert[hc[0]]] && !vseam[m->he_vert[hc[1]]] && !vseam[m->he_vert[hc[2]]]) continue;
            double a6[6];
            sq_face_uv(m, uv, f, a6);
            double l0 = hypot(a6[2] - a6[0], a6[3] - a6[1]), l1 = hypot(a6[4] - a6[2], a6[5] - a6[3]);
            double l2 = hypot(a6[0] - a6[4], a6[1] - a6[5]);
            double cross = (a6[2] - a6[0]) * (a6[5] - a6[1]) - (a6[3] - a6[1]) * (a6[4] - a6[0]);
            double l = fmin(fmin(l0, l1), fmin(l2, fabs(cross) / fmax(l0, fmax(l1, l2))));
            if (l >= TINY_SIDE * hgrid) continue;
            rep->held_triangles++;
            int frozen = 0;
            for (int c = 0; c < 3; c++) {
                uint32_t v = m->he_vert[hc[c]];
                if (vseam[v]) hold_corner(&X, hc[c]);
                if (vseam[v] || M->valence[v] != 4) frozen++;
            }
            /* all its corners frozen: its energy is constant, left out */
            if (frozen == 3) X.F[f].area = 0;
        }
    }
    double e = energy(&X, uv, &rep->max_energy_before);
    rep->energy_before = rep->energy_after = e;
    rep->max_energy_after = rep->max_energy_before;
    double hold_above = X.R ? INFINITY : PSI_HOLD;
    if (!isfinite(e) || !(rep->max_energy_before <= hold_above)) {
        /* Triangles above PSI_HOLD, or not positive in doubles (exactly
         * positive, but thinner than rounding: param's maps have them), are
         * held where they are: every unknown their corners depend on is
         * frozen, so their corners keep their bits and they stay positive;
         * they leave the energy, the rest moves. */
        for (uint32_t f = 0; f < m->nf; f++) {
            double a6[6];
            sq_face_uv(m, uv, f, a6);
            const double psi = sq_sd_psi(&X.F[f], a6);
            /* an infinite energy (a triangle flat in 3D or in doubles) is
             * held even where nothing finite is (hold_above infinite) */
            if (X.F[f].area == 0 || (isfinite(psi) && psi <= hold_above)) continue;
            X.F[f].area = 0;
            rep->held_triangles++;
            hold_face(&X, f);
        }
        e = energy(&X, uv, &rep->max_energy_before);
        rep->energy_before = rep->energy_after = e;
        rep->max_energy_after = rep->max_energy_before;
        if (!isfinite(e)) {
            snprintf(rep->why, sizeof rep->why, "the energy is not finite at the start");
            goto done;
        }
    }
    if (B.nz == 0) {
        snprintf(rep->why, sizeof rep->why, "no free unknowns");
        goto done;
    }
    if ((st = sq_zsys_init(&X.sys, &M->mesh, &B, err))) goto done;
    snprintf(rep->why, sizeof rep->why, "reached %u iterations", max_it);
    int stalls = 0, prog = X.R != NULL, prog_stalls = 0;
    double best_true = e;
    double e_true = e;
    for (uint32_t it = 0; it < max_it; it++) {
        double ts = sq_now();
        uint32_t nref = 0;
        if (X.R && prog) {
            nref = reference_update(&X, uv, K);
            use_faces(&X, nref > 0);
            e = energy(&X, uv, NULL);
        }
        assemble(&X, uv, gz);
        st = sq_zsys_solve(&X.sys, X.held, gz, d, err);
        rep->seconds_solve += sq_now() - ts;
        if (st) goto done;
        double slope = 0;
        for (uint32_t i = 0; i < B.nz; i++) slope += gz[i] * d[i];
        if (!(slope < 0)) {
            snprintf(rep->why, sizeof rep->why, "converged (no descent direction)");
            break;
        }
        sq_zsys_linear(&B, d, duv);
        double amax = INFINITY;
        for (uint32_t f = 0; f < m->nf; f++) {
            double a6[6], b6[6];
            sq_face_uv(m, uv, f, a6);
            sq_face_uv(m, duv, f, b6);
            amax = fmin(amax, sq_sd_max_step(a6, b6));
        }
        double alpha = fmin(1.0, 0.8 * amax), e_new = INFINITY;
        int ok = 0;
        for (int ls = 0; ls < 60 && alpha > 0; ls++, alpha *= 0.5) {
            for (uint32_t i = 0; i < B.nz; i++) zt[i] = z[i] + alpha * d[i];
            if (hgrid > 0) {
                if (!eval_fixed_exact(M, &B, zt, hgrid, vseam, trial)) continue;
            } else {
                sq_uv_basis_eval(&B, zt, trial);
            }
            e_new = energy(&X, trial, NULL);
            if (e_new <= e + 1e-4 * alpha * slope && all_positive(m, trial)) {
                ok = 1;
                break;
            }
        }
        if (!ok) {
            snprintf(rep->why, sizeof rep->why, "no step lowers the energy (iteration %u)", it + 1);
            break;
        }
        double drop = (e - e_new) / e;
        memcpy(z, zt, B.nz * sizeof *z);
        memcpy(uv, trial, nc * sizeof *uv);
        e = e_new;
        rep->iterations = it + 1;
        if (prog) {
            use_faces(&X, 0);
            double et = energy(&X, uv, NULL);
            drop = (e_true - et) / e_true;
            e_true = et;
            if (et < best_true * (1 - tol)) best_true = et, prog_stalls = 0;
            else if (++prog_stalls == PROG_PATIENCE) prog = 0;
            if (nref) {
                rep->reference_iterations++;
                if (opt->progress) opt->progress(opt->user, opt->progress_base + it + 1, e_true, alpha);
                e = e_true;
                continue;
            }
            prog = 0;
        }
        if (opt->progress) opt->progress(opt->user, opt->progress_base + it + 1, e, alpha);
        /* small progress with a full step: converged; with steps cut short
         * by the orientation guard three times in a row: stalled */
        if (drop >= tol) {
            stalls = 0;
        } else if (alpha == 1.0) {
            snprintf(rep->why, sizeof rep->why, "converged (energy fell by %.2g < %.2g)", drop, tol);
            break;
        } else if (++stalls == 3) {
            snprintf(rep->why, sizeof rep->why,
                     "stalled (steps cut to %.2g of Newton's to keep triangles positive)", alpha);
            break;
        }
    }
    if (rep->iterations == 0) {
        snprintf(rep->why, sizeof rep->why, "the energy did not decrease");
        goto done;
    }
    if (hgrid > 0) {
        memcpy(M->he_uv, uv, nc * sizeof *uv);
        st = sq_map_check(M, check_flags, &tmp);
    } else {
        st = install(M, uv, fixed, check_flags, &tmp);
    }
    if (st) {
        memcpy(M->he_uv, orig, nc * sizeof *orig);
        memcpy(M->he_t, orig_t, nc * sizeof *orig_t);
        memcpy(M->he_rot, orig_rot, m->nh);
        snprintf(rep->why, sizeof rep->why, "the optimized map failed the exact check: %.100s", tmp.msg);
        st = SQ_OK;
        goto done;
    }
    use_faces(&X, 0);
    double after_max = 0, after = energy(&X, M->he_uv, &after_max);
    if (!(after < rep->energy_before) && !(opt->keep_last && isfinite(after))) {
        /* the snapped map (free translations) is not the iterate: never
         * return a map that is worse by the energy the report states */
        memcpy(M->he_uv, orig, nc * sizeof *orig);
        memcpy(M->he_t, orig_t, nc * sizeof *orig_t);
        memcpy(M->he_rot, orig_rot, m->nh);
        snprintf(rep->why, sizeof rep->why, "the energy did not decrease");
        goto done;
    }
    rep->changed = 1;
    rep->iterate_kept = 1;
    rep->energy_after = after;
    rep->max_energy_after = after_max;
done:
    free(orig);
    free(orig_t);
    free(orig_rot);
    free(uv);
    free(trial);
    free(duv);
    free(z);
    free(zt);
    free(gz);
    free(d);
    free(X.F);
    free(X.R);
    sq_zsys_free(&X.sys);
    free(X.held);
    free(vseam);
    sq_uv_basis_free(&B);
    rep->seconds = sq_now() - t0;
    return st;
}
