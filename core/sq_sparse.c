/* seamquad: sparse direct solves (see docs/solvers.md).
 *
 * Symmetric positive definite systems go to CHOLMOD, general square systems
 * to UMFPACK, both from SuiteSparse, through their plain-C `int` interfaces
 * (our sizes are uint32 and a mesh never needs 2^31 nonzeros; larger input
 * is refused with SQ_ERR_ARGUMENT). Every factorization owns its solver
 * state (a cholmod_common, or an UMFPACK Control array), so different
 * factorizations may be used from different threads; one factorization must
 * not be used by two threads at once (CHOLMOD keeps workspace in its common).
 *
 * Licences (Debian's SuiteSparse 5.12 build): UMFPACK is GPL. CHOLMOD's Core
 * and Cholesky modules are LGPL, its Supernodal module is GPL; it is part of
 * the same libcholmod.so, and we leave CHOLMOD's automatic choice between
 * simplicial and supernodal factorization on (CHOLMOD_AUTO: supernodal when
 * flops / nnz(L) >= 40, which holds for mesh Laplacians of a few thousand
 * vertices and more) for systems of 60,000 unknowns and more (200,000 for
 * the optimizer's, SPD_AUTO_SIMPLICIAL_BELOW), and take the simplicial
 * code below that (SPD_SIMPLICIAL_BELOW). So in practice we use
 * the supernodal (GPL) code for large meshes and the simplicial (LGPL) code
 * for small ones.
 *
 * Singular matrices are reported, not solved. Besides the exact failures the
 * libraries report (a pivot that is not positive for Cholesky, a zero pivot
 * for LU), a pivot at roundoff level is rejected too, because a singular
 * matrix such as a graph Laplacian without a pinned vertex usually leaves
 * such a pivot instead of an exact zero, and the "solution" is then noise:
 *  - Cholesky: the computed pivot d_k = a_kk - sum_j l_kj^2 d_j is the exact
 *    pivot of a matrix whose diagonal entry a_kk moved by at most about
 *    (n+1) u a_kk (the terms of the sum are non-negative and add up to at
 *    most a_kk; u = 2^-53). A pivot d_k <= (n+1) eps a_kk (eps = 2u) is
 *    therefore indistinguishable from zero: "numerically singular".
 *  - LU: UMFPACK scales rows to unit 1-norm and reports
 *    rcond = min |u_kk| / max |u_kk|. Below n eps we call the matrix
 *    numerically singular (a heuristic: LU has no bound as clean as
 *    Cholesky's). Badly scaled but regular rows are not affected, because
 *    the ratio is taken after row scaling. */
#include "sq_sparse.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <umfpack.h>

struct sq_spd {
    cholmod_common common; /* owned: CHOLMOD's options, workspace, status */
    cholmod_factor *factor;
    uint32_t n;
    int xtype; /* CHOLMOD_REAL, or CHOLMOD_COMPLEX (sq_hpd_factor) */
    /* For sq_spd_refactor: the lower triangle A was factored from (its
     * pattern fixed, its values overwritten), and where each triplet of the
     * last refactorization landed in it (SLOT_UPPER: above the diagonal,
     * ignored), so that a refactorization fills A in place instead of
     * sorting the triplets again (fertility_tri's integer-grid map, 42,712
     * unknowns: 55 ms -> 3 ms per Newton step). */
    cholmod_sparse *lower;
    size_t *slot;
    size_t nslot;
};

#define SLOT_UPPER SIZE_MAX

struct sq_lu {
    int n;
    int *col_start;  /* compressed-column form of A, kept for refinement */
    int *row_index;
    double *value;
    void *numeric;   /* UMFPACK numeric factorization */
    double *scratch; /* one solution column, so that x may equal b */
    double control[UMFPACK_CONTROL];
};

/* ---- argument checks shared by both factorizations ---------------------- */

/* vals: stride doubles per triplet (1 real; 2 complex: both checked) */
static sq_status check_triplets(const char *who, uint32_t n, size_t nnz, const uint32_t *rows,
                                const uint32_t *cols, const double *vals, size_t stride, void *out,
                                sq_error *err)
{
    if (!out) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: output pointer is NULL", who);
    if (n == 0) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: matrix size n is 0", who);
    if (n > (uint32_t)INT_MAX - 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: matrix size %u exceeds the solver's int range", who, n);
    if (nnz > (size_t)INT_MAX)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "%s: %zu nonzeros exceed the solver's int range", who, nnz);
    if (nnz > 0 && (!rows || !cols || !vals))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL triplet array with %zu nonzeros",
                            who, nnz);
    for (size_t k = 0; k < nnz; k++) {
        if (rows[k] >= n || cols[k] >= n)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: triplet %zu has index (%u, %u) outside the %u x %u matrix",
                                who, k, rows[k], cols[k], n, n);
        if (!isfinite(vals[stride * k]) || !isfinite(vals[stride * k + stride - 1]))
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: triplet %zu at (%u, %u) has a non-finite value", who, k,
                                rows[k], cols[k]);
    }
    return SQ_OK;
}


static sq_status check_solve(const char *who, const void *f, uint32_t nrhs, const double *b,
                             const double *x, sq_error *err)
{
    if (!f) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: factorization is NULL", who);
    if (nrhs > 0 && (!b || !x))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL right-hand side or solution", who);
    return SQ_OK;
}

static sq_status check_solution(const char *who, const double *x, size_t count, sq_error *err)
{
    for (size_t i = 0; i < count; i++)
        if (!isfinite(x[i]))
            return sq_error_set(err, SQ_ERR_SOLVER,
                                "%s: solution entry %zu is not finite (matrix numerically "
                                "singular, or right-hand side not finite)",
                                who, i);
    return SQ_OK;
}

/* ---- CHOLMOD ------------------------------------------------------------- */

static const char *cholmod_status_text(int status)
{
    switch (status) {
    case CHOLMOD_OK: return "ok";
    case CHOLMOD_NOT_INSTALLED: return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
    case CHOLMOD_TOO_LARGE: return "problem too large";
    case CHOLMOD_INVALID: return "invalid input";
    case CHOLMOD_GPU_PROBLEM: return "GPU problem";
    case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
    case CHOLMOD_DSMALL: return "diagonal entry of the factor too small";
    default: return "unknown status";
    }
}

/* Turns a CHOLMOD failure (a NULL/FALSE result or a non-OK status) into our
 * error. Returns SQ_OK if the call succeeded. */
static sq_status cholmod_check(const char *who, const char *step, int ok,
                               const cholmod_common *c, sq_error *err)
{
    if (ok && c->status == CHOLMOD_OK) return SQ_OK;
    const sq_status code = c->status == CHOLMOD_OUT_OF_MEMORY ? SQ_ERR_NOMEM : SQ_ERR_SOLVER;
    return sq_error_set(err, code, "%s: CHOLMOD %s failed: %s (status %d)", who, step,
                        cholmod_status_text(c->status), c->status);
}

/* Systems of fewer unknowns are factored by the simplicial code whatever
 * CHOLMOD_AUTO would choose: the supernodal code enters OpenMP for every
 * factorization, which for the guidance's ~70 layouts of growing
 * metapolygons (seed 9.2, up to 40,000 unknowns) cost more than it saved
 * (cid/elephant's domain step 2.65-3.1 s -> 2.3 s, mpz/elk's 3.0 -> 2.55 s;
 * with every system simplicial, elk's 94,000-unknown layouts lost it
 * again: 2.98 s). */
#define SPD_SIMPLICIAL_BELOW 60000u

/* The optimizer's Newton systems (sq_spd_factor_auto), refactored every
 * iteration, take the simplicial code below this many unknowns: Debian's
 * supernodal code opens OpenMP regions with a compiled-in thread count (4,
 * whatever OMP_NUM_THREADS says), and on a 2-core host 30-45% of the
 * optimizer's samples were then in the kernel (futex, page faults) and
 * libgomp. Same iterates either way; wall time, best of 3: bunny's param
 * map (80K unknowns, 20 iterations) 10.2 -> 6.9 s, mpz/elk's published
 * map 1.01 -> 0.66 s, fertility_tri's integer-grid map at 1K quads (42K
 * unknowns) 4.12 -> 4.32 s. */
#define SPD_AUTO_SIMPLICIAL_BELOW 200000u

/* The optimizer's systems of this many unknowns and more are ordered by
 * CHOLMOD's nested dissection (METIS on the graph, then constrained
 * minimum degree) instead of AMD alone: the ordering costs more (0.04 ->
 * 0.2 s at 42,712 unknowns), once per factorization, and every
 * refactorization less. fertility_tri's integer-grid map at 5K quads
 * (42,712 unknowns, 7 Newton steps): 308 instead of 489 Mflop per
 * factorization, the optimization 1.75 -> 1.45 s; rocker_arm's published
 * map (~20,000 unknowns, 10 steps) 1.30 -> 1.10 s; mpz/elk's (~10,000) no
 * better, hence the bound. CHOLMOD's own choice (nmethods = 0) tries
 * METIS only when flops per factor entry exceed 500, which these 2x2-block
 * systems (about 200) never reach. */
#define SPD_AUTO_NESDIS_FROM 16000u

static void set_cholmod_options(cholmod_common *c)
{
    c->print = 0;                          /* the library never prints */
    c->try_catch = 0;
    c->error_handler = NULL;
    c->supernodal = CHOLMOD_AUTO;          /* see the licence note at the top */
    c->supernodal_switch = 40;
    /* LL', not LDL': a simplicial LDL' factorization happily factors an
     * indefinite matrix (negative D), while LL' stops at the first pivot
     * that is not positive. The supernodal factorization is always LL'. */
    c->final_ll = 1;
    c->final_asis = 1;                     /* keep the factor as computed */
    c->nmethods = 0;                       /* AMD, then METIS if AMD's fill is poor */
    c->postorder = 1;
    c->quick_return_if_not_posdef = 1;
    c->dbound = 0;                         /* no pivot modification, ever */
    c->itype = CHOLMOD_INT;
    c->dtype = CHOLMOD_DOUBLE;
}

/* Checks every Cholesky pivot d_k = L_kk^2 against the diagonal entry of A it
 * came from (see the note on singular matrices at the top). `diag` holds the
 * diagonal of A in the original order. */
static sq_status check_pivots(const char *who, const cholmod_factor *l, const double *diag,
                              sq_error *err)
{
    assert(l->is_ll && (l->xtype == CHOLMOD_REAL || l->xtype == CHOLMOD_COMPLEX));
    const size_t n = l->n, sx = l->xtype == CHOLMOD_COMPLEX ? 2 : 1; /* L's diagonal is real */
    const int *perm = l->Perm;
    const double *lx = l->x;
    const double tolerance = (double)(n + 1) * DBL_EPSILON;
    size_t worst = 0;
    double worst_ratio = INFINITY;
    if (l->is_super) {
        /* Supernode s holds columns super[s] .. super[s+1]-1 as a dense
         * column-major block of pi[s+1]-pi[s] rows starting at lx[px[s]]. */
        const int *super = l->super, *pi = l->pi, *px = l->px;
        for (size_t s = 0; s < l->nsuper; s++) {
            const size_t rows = (size_t)(pi[s + 1] - pi[s]);
            for (int k = super[s]; k < super[s + 1]; k++) {
                const size_t j = (size_t)(k - super[s]);
                const double lkk = lx[sx * ((size_t)px[s] + j * rows + j)];
                const double a = diag[perm ? perm[k] : k];
                const double ratio = lkk * lkk / a;
                if (!(ratio >= worst_ratio)) { /* NaN counts as worst */
                    worst_ratio = ratio;
                    worst = (size_t)k;
                }
            }
        }
    } else {
        /* Simplicial: the diagonal is the first entry of each column. */
        const int *p = l->p;
        for (size_t k = 0; k < n; k++) {
            const double lkk = lx[sx * (size_t)p[k]];
            const double a = diag[perm ? perm[k] : (int)k];
            const double ratio = lkk * lkk / a;
            if (!(ratio >= worst_ratio)) {
                worst_ratio = ratio;
                worst = k;
            }
        }
    }
    if (!(worst_ratio > tolerance)) {
        const long row = perm ? (long)perm[worst] : (long)worst;
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "%s: matrix is numerically singular (Cholesky pivot %zu of %zu, "
                            "at row/column %ld, is %.3g times its diagonal entry: below the "
                            "roundoff level %.3g)",
                            who, worst + 1, n, row, worst_ratio, tolerance);
    }
    return SQ_OK;
}

/* The lower triangle of the triplets as a CHOLMOD matrix (duplicates
 * summed; CHOLMOD would otherwise transpose the upper entries and add them
 * in), and the diagonal of A (caller-allocated, n). */
static sq_status lower_matrix(const char *who, sq_spd *f, size_t nnz, const uint32_t *rows,
                              const uint32_t *cols, const double *vals, double *diag,
                              cholmod_sparse **out, sq_error *err)
{
    const size_t sx = f->xtype == CHOLMOD_COMPLEX ? 2 : 1;
    cholmod_common *c = &f->common;
    size_t lower = 0;
    for (size_t k = 0; k < nnz; k++) lower += rows[k] >= cols[k];
    memset(diag, 0, f->n * sizeof *diag);
    *out = NULL;
    cholmod_triplet *t = cholmod_allocate_triplet(f->n, f->n, lower, -1, f->xtype, c);
    sq_status st = cholmod_check(who, "allocate_triplet", t != NULL, c, err);
    if (st == SQ_OK) {
        int *ti = t->i, *tj = t->j;
        double *tx = t->x;
        size_t m = 0;
        for (size_t k = 0; k < nnz; k++) {
            if (rows[k] < cols[k]) continue;
            ti[m] = (int)rows[k];
            tj[m] = (int)cols[k];
            for (size_t q = 0; q < sx; q++) tx[sx * m + q] = vals[sx * k + q];
            m++;
            if (rows[k] == cols[k]) diag[rows[k]] += vals[sx * k]; /* real on a Hermitian diagonal */
        }
        assert(m == lower);
        t->nnz = m;
        *out = cholmod_triplet_to_sparse(t, m, c); /* sums duplicates */
        st = cholmod_check(who, "triplet_to_sparse", *out != NULL, c, err);
    }
    cholmod_free_triplet(&t, c);
    return st;
}

/* The numeric factorization of a into f->factor (analyzed), and the
 * pivot check. */
static sq_status numeric(const char *who, sq_spd *f, cholmod_sparse *a, const double *diag,
                         sq_error *err)
{
    cholmod_common *c = &f->common;
    sq_status st;
    const int ok = cholmod_factorize(a, f->factor, c);
    if (ok && c->status == CHOLMOD_NOT_POSDEF) {
        /* minor is the failing column in the permuted order. */
        const cholmod_factor *l = f->factor;
        const size_t minor = l->minor;
        const int *perm = l->Perm;
        const long row = (perm && minor < f->n) ? (long)perm[minor] : (long)minor;
        st = sq_error_set(err, SQ_ERR_SOLVER,
                          "%s: matrix is not positive definite (Cholesky pivot %zu of "
                          "%u is not positive, at row/column %ld)",
                          who, minor + 1, f->n, row);
    } else {
        st = cholmod_check(who, "factorize", ok, c, err);
    }
    if (st == SQ_OK) st = check_pivots(who, f->factor, diag, err);
    return st;
}

/* sq_spd_factor (xtype CHOLMOD_REAL: one value per triplet) and
 * sq_hpd_factor (CHOLMOD_COMPLEX: two, real and imaginary part). */
static sq_status factor_x(const char *who, uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                          const double *vals, int xtype, int auto_super, sq_spd **out, sq_error *err)
{
    const size_t sx = xtype == CHOLMOD_COMPLEX ? 2 : 1;
    if (out) *out = NULL;
    sq_status st = check_triplets(who, n, nnz, rows, cols, vals, sx, out, err);
    if (st != SQ_OK) return st;

    sq_spd *f = calloc(1, sizeof *f);
    if (!f) return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    f->n = n, f->xtype = xtype;
    if (!cholmod_start(&f->common)) {
        free(f);
        return sq_error_set(err, SQ_ERR_SOLVER, "%s: cholmod_start failed", who);
    }
    set_cholmod_options(&f->common);
    cholmod_common *c = &f->common;
    if (sx * n < (auto_super ? SPD_AUTO_SIMPLICIAL_BELOW : SPD_SIMPLICIAL_BELOW)) c->supernodal = CHOLMOD_SIMPLICIAL;
    if (auto_super && sx * n >= SPD_AUTO_NESDIS_FROM) {
        c->nmethods = 1;
        c->method[0].ordering = CHOLMOD_NESDIS;
    }

    cholmod_sparse *a = NULL;
    double *diag = calloc(n, sizeof *diag);
    st = diag ? lower_matrix(who, f, nnz, rows, cols, vals, diag, &a, err)
              : sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    if (st == SQ_OK) {
        f->factor = cholmod_analyze(a, c);
        st = cholmod_check(who, "analyze", f->factor != NULL, c, err);
    }
    if (st == SQ_OK) st = numeric(who, f, a, diag, err);
    if (auto_super) f->lower = a; /* refactored many times: kept, freed with f */
    else cholmod_free_sparse(&a, c);
    free(diag);

    if (st != SQ_OK) {
        sq_spd_free(f);
        return st;
    }
    *out = f;
    return SQ_OK;
}

/* Where triplet (r, c), r >= c, lies in the sorted column c of the lower
 * matrix a, or SLOT_UPPER if the pattern has no such entry. */
static size_t find_slot(const cholmod_sparse *a, uint32_t r, uint32_t c)
{
    const int *ap = a->p, *ai = a->i;
    size_t lo = (size_t)ap[c], hi = (size_t)ap[c + 1];
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (ai[mid] < (int)r) lo = mid + 1;
        else hi = mid;
    }
    return lo < (size_t)ap[c + 1] && ai[lo] == (int)r ? lo : SLOT_UPPER;
}

/* f->slot for these triplets. Returns 0 if a lower triplet is not in the
 * pattern of f->lower (the caller then rebuilds the matrix). */
static int build_slots(sq_spd *f, size_t nnz, const uint32_t *rows, const uint32_t *cols)
{
    if (f->nslot != nnz) {
        free(f->slot);
        f->nslot = 0;
        if (!(f->slot = malloc((nnz ? nnz : 1) * sizeof *f->slot))) return 0;
        f->nslot = nnz;
    }
    for (size_t k = 0; k < nnz; k++) {
        f->slot[k] = SLOT_UPPER;
        if (rows[k] < cols[k]) continue;
        if ((f->slot[k] = find_slot(f->lower, rows[k], cols[k])) == SLOT_UPPER) return 0;
    }
    return 1;
}

/* Fills f->lower's values and diag from the triplets through f->slot.
 * Returns 0 if a triplet does not land on its own entry (another pattern
 * than the slots were built for). */
static int fill_slots(sq_spd *f, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                      const double *vals, double *diag)
{
    const size_t sx = f->xtype == CHOLMOD_COMPLEX ? 2 : 1;
    cholmod_sparse *a = f->lower;
    const int *ap = a->p, *ai = a->i;
    double *ax = a->x;
    if (f->nslot != nnz) return 0;
    memset(ax, 0, sx * (size_t)ap[f->n] * sizeof *ax);
    memset(diag, 0, f->n * sizeof *diag);
    for (size_t k = 0; k < nnz; k++) {
        const size_t s = f->slot[k];
        if (rows[k] < cols[k]) {
            if (s != SLOT_UPPER) return 0;
            continue;
        }
        if (s == SLOT_UPPER || ai[s] != (int)rows[k] || s < (size_t)ap[cols[k]] ||
            s >= (size_t)ap[cols[k] + 1])
            return 0;
        for (size_t q = 0; q < sx; q++) ax[sx * s + q] += vals[sx * k + q];
        if (rows[k] == cols[k]) diag[rows[k]] += vals[sx * k];
    }
    return 1;
}

sq_status sq_spd_refactor(sq_spd *f, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                          const double *vals, sq_error *err)
{
    static const char who[] = "sq_spd_refactor";
    if (!f || !f->factor) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: no factorization", who);
    sq_spd *dummy = f;
    sq_status st = check_triplets(who, f->n, nnz, rows, cols, vals, f->xtype == CHOLMOD_COMPLEX ? 2 : 1,
                                  &dummy, err);
    if (st != SQ_OK) return st;
    double *diag = calloc(f->n, sizeof *diag);
    if (!diag) return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    /* the kept matrix, filled in place; the triplets' slots are found
     * again when they do not match (first call, another triplet order) */
    int filled = f->lower && fill_slots(f, nnz, rows, cols, vals, diag);
    if (!filled && f->lower && build_slots(f, nnz, rows, cols))
        filled = fill_slots(f, nnz, rows, cols, vals, diag);
    if (!filled) {
        /* another pattern than the one analyzed (outside the contract, but
         * the symbolic factorization still decides what is stored): a new
         * lower matrix */
        cholmod_free_sparse(&f->lower, &f->common);
        free(f->slot);
        f->slot = NULL, f->nslot = 0;
        st = lower_matrix(who, f, nnz, rows, cols, vals, diag, &f->lower, err);
    }
    if (st == SQ_OK) st = numeric(who, f, f->lower, diag, err);
    free(diag);
    return st;
}

sq_status sq_spd_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                        const double *vals, sq_spd **out, sq_error *err)
{
    return factor_x("sq_spd_factor", n, nnz, rows, cols, vals, CHOLMOD_REAL, 0, out, err);
}

sq_status sq_hpd_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                        const double *vals, sq_spd **out, sq_error *err)
{
    return factor_x("sq_hpd_factor", n, nnz, rows, cols, vals, CHOLMOD_COMPLEX, 0, out, err);
}

sq_status sq_spd_factor_auto(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                             const double *vals, sq_spd **out, sq_error *err)
{
    return factor_x("sq_spd_factor_auto", n, nnz, rows, cols, vals, CHOLMOD_REAL, 1, out, err);
}

sq_status sq_spd_solve(sq_spd *f, uint32_t nrhs, const double *b, double *x, sq_error *err)
{
    static const char who[] = "sq_spd_solve";
    sq_status st = check_solve(who, f, nrhs, b, x, err);
    if (st != SQ_OK || nrhs == 0) return st;
    cholmod_common *c = &f->common;
    const size_t count = (size_t)f->n * nrhs * (f->xtype == CHOLMOD_COMPLEX ? 2 : 1);

    cholmod_dense *bd = cholmod_allocate_dense(f->n, nrhs, f->n, f->xtype, c);
    st = cholmod_check(who, "allocate_dense", bd != NULL, c, err);
    if (st != SQ_OK) return st;
    memcpy(bd->x, b, count * sizeof *b);

    cholmod_dense *xd = cholmod_solve(CHOLMOD_A, f->factor, bd, c);
    st = cholmod_check(who, "solve", xd != NULL, c, err);
    if (st == SQ_OK) {
        assert(xd->nrow == f->n && xd->ncol == nrhs && xd->d == f->n);
        memcpy(x, xd->x, count * sizeof *x);
        st = check_solution(who, x, count, err);
    }
    cholmod_free_dense(&xd, c);
    cholmod_free_dense(&bd, c);
    return st;
}

void sq_spd_free(sq_spd *f)
{
    if (!f) return;
    cholmod_free_factor(&f->factor, &f->common);
    cholmod_free_sparse(&f->lower, &f->common);
    free(f->slot);
    cholmod_finish(&f->common);
    free(f);
}

/* ---- UMFPACK ------------------------------------------------------------- */

static const char *umfpack_status_text(int status)
{
    switch (status) {
    case UMFPACK_OK: return "ok";
    case UMFPACK_WARNING_singular_matrix: return "matrix is singular";
    case UMFPACK_ERROR_out_of_memory: return "out of memory";
    case UMFPACK_ERROR_invalid_Numeric_object: return "invalid numeric object";
    case UMFPACK_ERROR_invalid_Symbolic_object: return "invalid symbolic object";
    case UMFPACK_ERROR_argument_missing: return "argument missing";
    case UMFPACK_ERROR_n_nonpositive: return "n is not positive";
    case UMFPACK_ERROR_invalid_matrix: return "invalid matrix";
    case UMFPACK_ERROR_invalid_system: return "invalid system";
    case UMFPACK_ERROR_ordering_failed: return "ordering failed";
    case UMFPACK_ERROR_internal_error: return "internal error";
    default: return "unknown status";
    }
}

static sq_status umfpack_check(const char *who, const char *step, int status, sq_error *err)
{
    if (status == UMFPACK_OK) return SQ_OK;
    const sq_status code = status == UMFPACK_ERROR_out_of_memory ? SQ_ERR_NOMEM : SQ_ERR_SOLVER;
    return sq_error_set(err, code, "%s: UMFPACK %s failed: %s (status %d)", who, step,
                        umfpack_status_text(status), status);
}

sq_status sq_lu_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                       const double *vals, sq_lu **out, sq_error *err)
{
    static const char who[] = "sq_lu_factor";
    sq_status st = check_triplets(who, n, nnz, rows, cols, vals, 1, out, err);
    if (st != SQ_OK) return st;
    *out = NULL;

    sq_lu *f = calloc(1, sizeof *f);
    if (!f) return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    f->n = (int)n;
    umfpack_di_defaults(f->control);
    f->control[UMFPACK_PRL] = 0;                        /* never print */
    f->control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_AUTO;
    f->control[UMFPACK_IRSTEP] = 2;                     /* iterative refinement steps */
    f->control[UMFPACK_SCALE] = UMFPACK_SCALE_SUM;      /* rows to unit 1-norm */

    const size_t cap = nnz > 0 ? nnz : 1;
    int *ti = malloc(cap * sizeof *ti);
    int *tj = malloc(cap * sizeof *tj);
    f->col_start = malloc(((size_t)n + 1) * sizeof *f->col_start);
    f->row_index = malloc(cap * sizeof *f->row_index);
    f->value = malloc(cap * sizeof *f->value);
    f->scratch = malloc((size_t)n * sizeof *f->scratch);
    if (!ti || !tj || !f->col_start || !f->row_index || !f->value || !f->scratch) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", who);
    } else {
        for (size_t k = 0; k < nnz; k++) {
            ti[k] = (int)rows[k];
            tj[k] = (int)cols[k];
        }
        /* Compressed columns, duplicates summed (Map = NULL). */
        st = umfpack_check(who, "triplet_to_col",
                           umfpack_di_triplet_to_col(f->n, f->n, (int)nnz, ti, tj, vals,
                                                     f->col_start, f->row_index, f->value,
                                                     NULL),
                           err);
    }
    free(ti);
    free(tj);

    void *symbolic = NULL;
    double info[UMFPACK_INFO];
    if (st == SQ_OK) {
        const int status = umfpack_di_symbolic(f->n, f->n, f->col_start, f->row_index,
                                               f->value, &symbolic, f->control, info);
        st = umfpack_check(who, "symbolic analysis", status, err);
    }
    if (st == SQ_OK) {
        const int status = umfpack_di_numeric(f->col_start, f->row_index, f->value, symbolic,
                                              &f->numeric, f->control, info);
        if (status == UMFPACK_WARNING_singular_matrix)
            st = sq_error_set(err, SQ_ERR_SOLVER,
                              "%s: matrix is singular (LU factorization of the %u x %u "
                              "matrix found a zero pivot)",
                              who, n, n);
        else
            st = umfpack_check(who, "numeric factorization", status, err);
    }
    if (st == SQ_OK) {
        const double rcond = info[UMFPACK_RCOND];
        const double tolerance = (double)n * DBL_EPSILON;
        if (!(rcond >= tolerance))
            st = sq_error_set(err, SQ_ERR_SOLVER,
                              "%s: matrix is numerically singular (LU pivot ratio "
                              "min|u_kk|/max|u_kk| = %.3g after row scaling, below the "
                              "roundoff level %.3g)",
                              who, rcond, tolerance);
    }
    umfpack_di_free_symbolic(&symbolic);

    if (st != SQ_OK) {
        sq_lu_free(f);
        return st;
    }
    *out = f;
    return SQ_OK;
}

sq_status sq_lu_solve(sq_lu *f, uint32_t nrhs, const double *b, double *x, sq_error *err)
{
    static const char who[] = "sq_lu_solve";
    sq_status st = check_solve(who, f, nrhs, b, x, err);
    if (st != SQ_OK) return st;
    const size_t n = (size_t)f->n;
    double info[UMFPACK_INFO];
    for (uint32_t k = 0; k < nrhs; k++) {
        /* Solve into scratch, then copy: x may be the same array as b. */
        const int status = umfpack_di_solve(UMFPACK_A, f->col_start, f->row_index, f->value,
                                            f->scratch, b + k * n, f->numeric, f->control, info);
        st = umfpack_check(who, "solve", status, err);
        if (st != SQ_OK) return st;
        memcpy(x + k * n, f->scratch, n * sizeof *x);
    }
    return check_solution(who, x, n * nrhs, err);
}

void sq_lu_free(sq_lu *f)
{
    if (!f) return;
    umfpack_di_free_numeric(&f->numeric);
    free(f->col_start);
    free(f->row_index);
    free(f->value);
    free(f->scratch);
    free(f);
}
