/* seamquad: globally optimal smooth cross fields on faces (Knoppel, Crane,
 * Pinkall, Schroeder 2013, "Globally optimal direction fields"), see
 * sq_cross_field.h and docs/cones_from_field.md.
 *
 * Unknowns: u_f in C per face, stored as reals x = (Re u_0, Im u_0, Re u_1,
 * ...). Energy E(u) = sum over edges e = (f, g) of w_e |u_g - rho_e u_f|^2,
 * rho_e = exp(i rot[h]) the 4-symmetric connection of the edge (sq_cross_
 * field_frames.h). E(u) = u^H A u with A Hermitian positive semidefinite;
 * its real form [[Re A, -Im A], [Im A, Re A]] (interleaved per face) is
 * real symmetric and goes to CHOLMOD. M = diag(face area / total area). */
#include "sq_clock.h"
#include "sq_cross_field.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cross_field_frames.h"
#include "sq_sparse.h"

/* Largest edge weight: the weight |e|^2 / (A_f + A_g) grows without bound
 * on a pair of slivers; past this the faces are glued anyway, and a bound
 * keeps the matrix well conditioned (an equilateral pair has 2/sqrt 3). */
#define SQ_CF_MAX_WEIGHT 1e6
/* Relative diagonal shift that keeps A + shift M definite when A is
 * (nearly) singular, e.g. a flat torus; far below any eigenvalue gap that
 * matters for the field. */
#define SQ_CF_REL_SHIFT 1e-9

void sq_cross_field_default_options(sq_cross_field_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->align = SQ_FIELD_SMOOTH;
    opt->max_iterations = 40;
    opt->alignment = 0.0;
}

/* The connection Laplacian as lower-triangle triplets (rows >= cols),
 * without the mass term; the diagonal goes to diag[2 nf] separately so that
 * a shift can be added before factoring. */
typedef struct cf_system {
    uint32_t n;          /* 2 nf */
    size_t nnz;          /* off-diagonal triplets */
    uint32_t *rows, *cols;
    double *vals;
    double *diag;        /* n */
} cf_system;

static void system_free(cf_system *s)
{
    free(s->rows);
    free(s->cols);
    free(s->vals);
    free(s->diag);
    memset(s, 0, sizeof *s);
}

static void push(cf_system *s, uint32_t r, uint32_t c, double v)
{
    assert(r > c);
    s->rows[s->nnz] = r;
    s->cols[s->nnz] = c;
    s->vals[s->nnz] = v;
    s->nnz++;
}

static sq_status assemble(const sq_mesh *m, const sq_cross_field_frames *fr, cf_system *s,
                          sq_error *err)
{
    memset(s, 0, sizeof *s);
    s->n = 2 * m->nf;
    size_t ne = m->nh / 2;
    s->rows = malloc(4 * ne * sizeof *s->rows);
    s->cols = malloc(4 * ne * sizeof *s->cols);
    s->vals = malloc(4 * ne * sizeof *s->vals);
    s->diag = calloc(s->n, sizeof *s->diag);
    if (!s->rows || !s->cols || !s->vals || !s->diag) {
        system_free(s);
        return sq_error_set(err, SQ_ERR_NOMEM, "cross field: out of memory (%u faces)", m->nf);
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t t = m->he_twin[h];
        if (t < h) continue;
        uint32_t f = m->he_face[h], g = m->he_face[t];
        assert(f != g); /* a face never borders itself in a valid mesh */
        const double *a = m->pos + 3 * (size_t)m->he_vert[h];
        const double *b = m->pos + 3 * (size_t)m->he_vert[t];
        double l2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                    (a[2] - b[2]) * (a[2] - b[2]);
        double w = l2 / ((fr->area[f] + fr->area[g]) * fr->total_area);
        if (!(w <= SQ_CF_MAX_WEIGHT)) w = SQ_CF_MAX_WEIGHT;
        double c = w * cos(fr->rot[h]), sn = w * sin(fr->rot[h]);
        s->diag[2 * f] += w;
        s->diag[2 * f + 1] += w;
        s->diag[2 * g] += w;
        s->diag[2 * g + 1] += w;
        /* block (g, f) of the Hermitian matrix is -w rho; block (f, g) is
         * its conjugate transpose. Emit whichever lies below the diagonal. */
        if (g > f) {
            push(s, 2 * g, 2 * f, -c);
            push(s, 2 * g, 2 * f + 1, sn);
            push(s, 2 * g + 1, 2 * f, -sn);
            push(s, 2 * g + 1, 2 * f + 1, -c);
        } else {
            push(s, 2 * f, 2 * g, -c);
            push(s, 2 * f, 2 * g + 1, -sn);
            push(s, 2 * f + 1, 2 * g, sn);
            push(s, 2 * f + 1, 2 * g + 1, -c);
        }
    }
    return SQ_OK;
}

/* Factors A + shift M. */
static sq_status factor(const cf_system *s, const sq_cross_field_frames *fr, double shift,
                        sq_spd **out, sq_error *err)
{
    size_t nnz = s->nnz + s->n;
    uint32_t *rows = malloc(nnz * sizeof *rows), *cols = malloc(nnz * sizeof *cols);
    double *vals = malloc(nnz * sizeof *vals);
    sq_status st;
    if (!rows || !cols || !vals) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cross field: out of memory (matrix of %zu entries)",
                          nnz);
        goto done;
    }
    memcpy(rows, s->rows, s->nnz * sizeof *rows);
    memcpy(cols, s->cols, s->nnz * sizeof *cols);
    memcpy(vals, s->vals, s->nnz * sizeof *vals);
    for (uint32_t i = 0; i < s->n; i++) {
        rows[s->nnz + i] = cols[s->nnz + i] = i;
        vals[s->nnz + i] = s->diag[i] + shift * fr->area[i / 2];
    }
    st = sq_spd_factor(s->n, nnz, rows, cols, vals, out, err);
done:
    free(rows);
    free(cols);
    free(vals);
    return st;
}

/* y = A x (A without the shift; lower triplets stand for both triangles). */
static void apply(const cf_system *s, const double *x, double *y)
{
    for (uint32_t i = 0; i < s->n; i++) y[i] = s->diag[i] * x[i];
    for (size_t k = 0; k < s->nnz; k++) {
        y[s->rows[k]] += s->vals[k] * x[s->cols[k]];
        y[s->cols[k]] += s->vals[k] * x[s->rows[k]];
    }
}

static double mass_dot(const sq_cross_field_frames *fr, uint32_t n, const double *x,
                       const double *y)
{
    double d = 0;
    for (uint32_t i = 0; i < n; i++) d += fr->area[i / 2] * x[i] * y[i];
    return d;
}

static double rayleigh(const cf_system *s, const sq_cross_field_frames *fr, const double *x,
                       double *tmp)
{
    apply(s, x, tmp);
    double num = 0;
    for (uint32_t i = 0; i < s->n; i++) num += x[i] * tmp[i];
    double den = mass_dot(fr, s->n, x, x);
    return den > 0 ? num / den : 0;
}

/* Deterministic start vector for the inverse iteration (splitmix64). */
static double start_value(uint64_t i)
{
    uint64_t z = (i + 1) * 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53 - 0.5;
}

sq_status sq_cross_field(const sq_mesh *m, const sq_cross_field_options *opt_in, double *u,
                         sq_cross_field_info *info, sq_error *err)
{
    sq_cross_field_options opt;
    if (opt_in) opt = *opt_in;
    else sq_cross_field_default_options(&opt);
    if (!u) return sq_error_set(err, SQ_ERR_ARGUMENT, "cross field: output array is NULL");
    if (opt.align != SQ_FIELD_SMOOTH && opt.align != SQ_FIELD_CURVATURE)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cross field: unknown alignment mode %d",
                            (int)opt.align);
    if (!(opt.alignment >= 0) || !isfinite(opt.alignment))
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cross field: alignment shift must be finite and >= 0 (got %g)",
                            opt.alignment);
    if (opt.max_iterations == 0) opt.max_iterations = 40;

    sq_cross_field_info inf;
    memset(&inf, 0, sizeof inf);
    sq_cross_field_frames fr;
    cf_system sys;
    memset(&sys, 0, sizeof sys);
    sq_spd *fac = NULL;
    double *b = NULL, *tmp = NULL;
    double t0 = sq_now();
    sq_status st = sq_cross_field_frames_build(m, &fr, err);
    if (st) return st;
    st = assemble(m, &fr, &sys, err);
    if (st) goto done;
    uint32_t n = sys.n;
    b = malloc((size_t)n * sizeof *b);
    tmp = malloc((size_t)n * sizeof *tmp);
    if (!b || !tmp) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cross field: out of memory (%u faces)", m->nf);
        goto done;
    }
    double trace = 0;
    for (uint32_t i = 0; i < n; i++) trace += sys.diag[i];
    double shift = SQ_CF_REL_SHIFT * trace; /* the mass matrix has trace 2 */
    if (opt.align == SQ_FIELD_CURVATURE) shift += opt.alignment;
    double t1 = sq_now();
    inf.t_assemble = t1 - t0;
    st = factor(&sys, &fr, shift, &fac, err);
    if (st) goto done;
    double t2 = sq_now();
    inf.t_factor = t2 - t1;

    if (opt.align == SQ_FIELD_CURVATURE) {
        /* (A + s M) u = M q (Knoppel et al. 2013, section 6 "alignment") */
        st = sq_cross_field_curvature(m, tmp, err);
        if (st) goto done;
        double qq = 0;
        for (uint32_t i = 0; i < n; i++) {
            b[i] = fr.area[i / 2] * tmp[i];
            qq += tmp[i] * tmp[i];
        }
        if (qq > 0) {
            st = sq_spd_solve(fac, 1, b, u, err);
            if (st) goto done;
        } else {
            /* no anisotropy anywhere (a round sphere): the smoothest field */
            opt.align = SQ_FIELD_SMOOTH;
        }
    }
    if (opt.align == SQ_FIELD_SMOOTH) {
        /* inverse power iteration: u <- (A + shift M)^-1 M u, M-normalized */
        for (uint32_t i = 0; i < n; i++) u[i] = start_value(i);
        double lambda = HUGE_VAL;
        for (uint32_t it = 0; it < opt.max_iterations; it++) {
            for (uint32_t i = 0; i < n; i++) b[i] = fr.area[i / 2] * u[i];
            st = sq_spd_solve(fac, 1, b, u, err);
            if (st) goto done;
            double norm = sqrt(mass_dot(&fr, n, u, u));
            if (!(norm > 0) || !isfinite(norm)) {
                st = sq_error_set(err, SQ_ERR_SOLVER,
                                  "cross field: inverse iteration %u produced a %s vector", it,
                                  norm > 0 ? "non-finite" : "zero");
                goto done;
            }
            for (uint32_t i = 0; i < n; i++) u[i] /= norm;
            inf.iterations = it + 1;
            double l = rayleigh(&sys, &fr, u, tmp);
            int settled = fabs(l - lambda) <= 1e-9 * fabs(l);
            lambda = l;
            if (it >= 2 && settled) break;
        }
    }
    inf.energy = rayleigh(&sys, &fr, u, tmp);
    inf.t_solve = sq_now() - t2;

    /* unit modulus: only the direction matters downstream */
    double maxmod = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        double r = hypot(u[2 * f], u[2 * f + 1]);
        if (r > maxmod) maxmod = r;
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        double r = hypot(u[2 * f], u[2 * f + 1]);
        if (!(r > 1e-300 && r > 1e-15 * maxmod) || !isfinite(r)) {
            u[2 * f] = 1;
            u[2 * f + 1] = 0;
        } else {
            u[2 * f] /= r;
            u[2 * f + 1] /= r;
        }
    }
done:
    if (info) *info = inf;
    sq_spd_free(fac);
    free(b);
    free(tmp);
    system_free(&sys);
    sq_cross_field_frames_free(&fr);
    return st;
}
