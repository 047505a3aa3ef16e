/* Tests for core/sq_sparse.c: CHOLMOD (SPD) and UMFPACK (LU) solves.
 *
 * Every system has a known solution x*: b = A x* is formed here, the solver
 * must return x* (relative error) and a small residual |A x - b| / |b|. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_sparse.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

/* ---- triplet matrices built in the tests -------------------------------- */

typedef struct triplets {
    uint32_t n;
    size_t count, cap;
    uint32_t *rows, *cols;
    double *vals;
} triplets;

static void trip_init(triplets *t, uint32_t n)
{
    memset(t, 0, sizeof *t);
    t->n = n;
}

static void trip_add(triplets *t, uint32_t i, uint32_t j, double v)
{
    if (t->count == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 64;
        t->rows = realloc(t->rows, t->cap * sizeof *t->rows);
        t->cols = realloc(t->cols, t->cap * sizeof *t->cols);
        t->vals = realloc(t->vals, t->cap * sizeof *t->vals);
        assert_non_null(t->rows);
        assert_non_null(t->cols);
        assert_non_null(t->vals);
    }
    t->rows[t->count] = i;
    t->cols[t->count] = j;
    t->vals[t->count] = v;
    t->count++;
}

/* Symmetric edge term w (x_i - x_j)^2: four triplets, duplicates intended. */
static void trip_add_edge(triplets *t, uint32_t i, uint32_t j, double w)
{
    trip_add(t, i, i, w);
    trip_add(t, j, j, w);
    trip_add(t, i, j, -w);
    trip_add(t, j, i, -w);
}

static void trip_free(triplets *t)
{
    free(t->rows);
    free(t->cols);
    free(t->vals);
    memset(t, 0, sizeof *t);
}

/* y = A x, every triplet counted (duplicates summed). */
static void matvec_general(const triplets *t, const double *x, double *y)
{
    memset(y, 0, t->n * sizeof *y);
    for (size_t k = 0; k < t->count; k++) y[t->rows[k]] += t->vals[k] * x[t->cols[k]];
}

/* y = A x for the symmetric matrix whose lower triangle the triplets give
 * (entries above the diagonal ignored, as sq_spd_factor does). */
static void matvec_lower(const triplets *t, const double *x, double *y)
{
    memset(y, 0, t->n * sizeof *y);
    for (size_t k = 0; k < t->count; k++) {
        const uint32_t i = t->rows[k], j = t->cols[k];
        if (i < j) continue;
        y[i] += t->vals[k] * x[j];
        if (i != j) y[j] += t->vals[k] * x[i];
    }
}

static double norm2(const double *x, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) s += x[i] * x[i];
    return sqrt(s);
}

static double relative_diff(const double *x, const double *y, size_t n)
{
    double d = 0;
    for (size_t i = 0; i < n; i++) d += (x[i] - y[i]) * (x[i] - y[i]);
    return sqrt(d) / norm2(y, n);
}

/* A smooth but non-trivial known solution, one per right-hand side. */
static double known(size_t i, uint32_t column)
{
    return sin(0.013 * (double)i * (column + 1)) + 0.5 * cos(0.0071 * (double)i) + column;
}

/* 2D grid graph Laplacian of side x side vertices plus `shift` times the
 * identity, assembled edge by edge (so diagonals come as duplicates). */
static void grid_laplacian(triplets *t, uint32_t side, double shift)
{
    trip_init(t, side * side);
    for (uint32_t r = 0; r < side; r++)
        for (uint32_t c = 0; c < side; c++) {
            const uint32_t v = r * side + c;
            if (c + 1 < side) trip_add_edge(t, v, v + 1, 1.0);
            if (r + 1 < side) trip_add_edge(t, v, v + side, 1.0);
            trip_add(t, v, v, shift);
        }
}

typedef void (*matvec_fn)(const triplets *, const double *, double *);

/* Solves A X = A X* for nrhs known columns with the given solver and checks
 * relative error and residual of every column. */
static void check_solve(const triplets *t, uint32_t nrhs, int spd, matvec_fn mv, double tol)
{
    const size_t n = t->n;
    double *xs = malloc(n * nrhs * sizeof *xs), *b = malloc(n * nrhs * sizeof *b);
    double *x = malloc(n * nrhs * sizeof *x), *r = malloc(n * sizeof *r);
    assert_true(xs && b && x && r);
    for (uint32_t k = 0; k < nrhs; k++) {
        for (size_t i = 0; i < n; i++) xs[k * n + i] = known(i, k);
        mv(t, xs + k * n, b + k * n);
    }
    sq_error err;
    sq_error_clear(&err);
    if (spd) {
        sq_spd *f = NULL;
        assert_int_equal(sq_spd_factor(t->n, t->count, t->rows, t->cols, t->vals, &f, &err), SQ_OK);
        assert_non_null(f);
        assert_int_equal(sq_spd_solve(f, nrhs, b, x, &err), SQ_OK);
        sq_spd_free(f);
    } else {
        sq_lu *f = NULL;
        assert_int_equal(sq_lu_factor(t->n, t->count, t->rows, t->cols, t->vals, &f, &err), SQ_OK);
        assert_non_null(f);
        assert_int_equal(sq_lu_solve(f, nrhs, b, x, &err), SQ_OK);
        sq_lu_free(f);
    }
    for (uint32_t k = 0; k < nrhs; k++) {
        assert_true(relative_diff(x + k * n, xs + k * n, n) < tol);
        mv(t, x + k * n, r);
        assert_true(relative_diff(r, b + k * n, n) < tol);
    }
    free(xs);
    free(b);
    free(x);
    free(r);
}

/* ---- SPD (CHOLMOD) -------------------------------------------------------- */

/* sq_spd_factor_auto, then sq_spd_refactor with new values on the same
 * pattern: both solve like a fresh factorization; an indefinite refactor
 * fails, and a later good one works again. Sizes on both sides of the
 * simplicial/supernodal switch. */
static void refactor_case(uint32_t side)
{
    triplets a, b;
    grid_laplacian(&a, side, 0.5);
    grid_laplacian(&b, side, 2.0);
    for (size_t k = 0; k < b.count; k++) b.vals[k] *= 1.0 + 0.3 * sin((double)k); /* same pattern */
    for (uint32_t v = 0; v < b.n; v++) trip_add(&b, v, v, 0.0);
    for (uint32_t v = 0; v < a.n; v++) trip_add(&a, v, v, 0.0);
    const size_t n = a.n;
    double *xs = malloc(n * sizeof *xs), *rhs = malloc(n * sizeof *rhs), *x = malloc(n * sizeof *x);
    assert_true(xs && rhs && x);
    for (size_t i = 0; i < n; i++) xs[i] = known(i, 0);
    sq_error err;
    sq_spd *f = NULL;
    assert_int_equal(sq_spd_factor_auto(a.n, a.count, a.rows, a.cols, a.vals, &f, &err), SQ_OK);
    matvec_lower(&a, xs, rhs);
    assert_int_equal(sq_spd_solve(f, 1, rhs, x, &err), SQ_OK);
    assert_true(relative_diff(x, xs, n) < 1e-9);
    /* b may not be SPD after the perturbation: only compare when it is */
    sq_spd *g = NULL;
    if (sq_spd_factor(b.n, b.count, b.rows, b.cols, b.vals, &g, &err) == SQ_OK) {
        assert_int_equal(sq_spd_refactor(f, b.count, b.rows, b.cols, b.vals, &err), SQ_OK);
        matvec_lower(&b, xs, rhs);
        assert_int_equal(sq_spd_solve(f, 1, rhs, x, &err), SQ_OK);
        assert_true(relative_diff(x, xs, n) < 1e-9);
        sq_spd_free(g);
    }
    /* indefinite values on the same pattern: refused */
    double *neg = malloc(a.count * sizeof *neg);
    assert_non_null(neg);
    for (size_t k = 0; k < a.count; k++) neg[k] = -a.vals[k];
    assert_int_equal(sq_spd_refactor(f, a.count, a.rows, a.cols, neg, &err), SQ_ERR_SOLVER);
    assert_non_null(strstr(err.msg, "not positive definite"));
    /* and a good one again */
    assert_int_equal(sq_spd_refactor(f, a.count, a.rows, a.cols, a.vals, &err), SQ_OK);
    matvec_lower(&a, xs, rhs);
    assert_int_equal(sq_spd_solve(f, 1, rhs, x, &err), SQ_OK);
    assert_true(relative_diff(x, xs, n) < 1e-9);
    /* the same matrix with its triplets in reverse order (the refactor's
     * cached slots no longer match and are found again), twice */
    triplets r;
    trip_init(&r, a.n);
    for (size_t k = a.count; k-- > 0;) trip_add(&r, a.rows[k], a.cols[k], a.vals[k]);
    for (int pass = 0; pass < 2; pass++) {
        memset(x, 0, n * sizeof *x);
        assert_int_equal(sq_spd_refactor(f, r.count, r.rows, r.cols, r.vals, &err), SQ_OK);
        assert_int_equal(sq_spd_solve(f, 1, rhs, x, &err), SQ_OK);
        assert_true(relative_diff(x, xs, n) < 1e-9);
    }
    /* a factorization not made for refactoring (sq_spd_factor) refactors too */
    sq_spd *h = NULL;
    assert_int_equal(sq_spd_factor(a.n, a.count, a.rows, a.cols, a.vals, &h, &err), SQ_OK);
    assert_int_equal(sq_spd_refactor(h, r.count, r.rows, r.cols, r.vals, &err), SQ_OK);
    memset(x, 0, n * sizeof *x);
    assert_int_equal(sq_spd_solve(h, 1, rhs, x, &err), SQ_OK);
    assert_true(relative_diff(x, xs, n) < 1e-9);
    sq_spd_free(h);
    trip_free(&r);
    assert_int_equal(sq_spd_refactor(NULL, a.count, a.rows, a.cols, a.vals, &err), SQ_ERR_ARGUMENT);
    sq_spd_free(f);
    free(neg);
    free(xs);
    free(rhs);
    free(x);
    trip_free(&a);
    trip_free(&b);
}

static void test_spd_refactor(void **state)
{
    (void)state;
    refactor_case(20);  /* 400 unknowns: simplicial */
    refactor_case(450); /* 202,500: CHOLMOD chooses (supernodal) */
}


static void test_spd_grid_laplacian(void **state)
{
    (void)state;
    triplets t;
    grid_laplacian(&t, 100, 1.0); /* n = 10^4, both triangles given */
    check_solve(&t, 1, 1, matvec_lower, 1e-10);
    check_solve(&t, 3, 1, matvec_lower, 1e-10); /* several right-hand sides */
    trip_free(&t);
}

/* Upper-triangle entries are ignored: adding garbage there changes nothing. */
static void test_spd_upper_ignored(void **state)
{
    (void)state;
    triplets lower, garbage;
    trip_init(&lower, 2500);
    trip_init(&garbage, 2500);
    triplets full;
    grid_laplacian(&full, 50, 0.5);
    for (size_t k = 0; k < full.count; k++) {
        const uint32_t i = full.rows[k], j = full.cols[k];
        if (i < j) {
            trip_add(&garbage, i, j, 1e30 * (double)(k % 7) - 3.0); /* ignored */
            continue;
        }
        trip_add(&lower, i, j, full.vals[k]);
        trip_add(&garbage, i, j, full.vals[k]);
    }
    check_solve(&lower, 2, 1, matvec_lower, 1e-10);
    check_solve(&garbage, 2, 1, matvec_lower, 1e-10);
    /* Both give the same solution as the full matrix. */
    const size_t n = 2500;
    double *b = malloc(n * sizeof *b), *x1 = malloc(n * sizeof *x1), *x2 = malloc(n * sizeof *x2);
    assert_true(b && x1 && x2);
    for (size_t i = 0; i < n; i++) b[i] = known(i, 0);
    sq_spd *f1 = NULL, *f2 = NULL;
    assert_int_equal(sq_spd_factor(2500, lower.count, lower.rows, lower.cols, lower.vals, &f1, NULL), SQ_OK);
    assert_int_equal(sq_spd_factor(2500, garbage.count, garbage.rows, garbage.cols, garbage.vals, &f2, NULL), SQ_OK);
    assert_int_equal(sq_spd_solve(f1, 1, b, x1, NULL), SQ_OK);
    assert_int_equal(sq_spd_solve(f2, 1, b, x2, NULL), SQ_OK);
    assert_true(relative_diff(x1, x2, n) < 1e-14);
    sq_spd_free(f1);
    sq_spd_free(f2);
    free(b);
    free(x1);
    free(x2);
    trip_free(&lower);
    trip_free(&garbage);
    trip_free(&full);
}

/* A = [[4,1,0],[1,3,1],[0,1,2]] given as pieces that only sum to A. */
static void test_duplicates_summed(void **state)
{
    (void)state;
    static const double a[3][3] = {{4, 1, 0}, {1, 3, 1}, {0, 1, 2}};
    static const double xs[3] = {1, -2, 3};
    triplets t;
    trip_init(&t, 3);
    for (uint32_t i = 0; i < 3; i++)
        for (uint32_t j = 0; j < 3; j++) {
            if (a[i][j] == 0) continue;
            trip_add(&t, i, j, 0.25 * a[i][j]);
            trip_add(&t, i, j, 10.0);
            trip_add(&t, i, j, 0.75 * a[i][j] - 10.0);
        }
    double b[3];
    for (int i = 0; i < 3; i++) b[i] = a[i][0] * xs[0] + a[i][1] * xs[1] + a[i][2] * xs[2];
    double x[3];
    sq_spd *s = NULL;
    assert_int_equal(sq_spd_factor(3, t.count, t.rows, t.cols, t.vals, &s, NULL), SQ_OK);
    assert_int_equal(sq_spd_solve(s, 1, b, x, NULL), SQ_OK);
    for (int i = 0; i < 3; i++) assert_true(fabs(x[i] - xs[i]) < 1e-12);
    sq_spd_free(s);
    sq_lu *l = NULL;
    assert_int_equal(sq_lu_factor(3, t.count, t.rows, t.cols, t.vals, &l, NULL), SQ_OK);
    memcpy(x, b, sizeof x);
    assert_int_equal(sq_lu_solve(l, 1, x, x, NULL), SQ_OK); /* in place */
    for (int i = 0; i < 3; i++) assert_true(fabs(x[i] - xs[i]) < 1e-12);
    sq_lu_free(l);
    trip_free(&t);
}

static void expect_spd_failure(uint32_t n, const triplets *t, sq_status code, const char *words)
{
    sq_error err;
    sq_error_clear(&err);
    sq_spd *f = (sq_spd *)&err; /* must be reset to NULL on failure */
    assert_int_equal(sq_spd_factor(n, t->count, t->rows, t->cols, t->vals, &f, &err), code);
    assert_null(f);
    assert_int_equal(err.code, code);
    assert_non_null(strstr(err.msg, words));
}

static void test_spd_rejects_indefinite(void **state)
{
    (void)state;
    triplets t;
    trip_init(&t, 2); /* [[1, 2], [2, 1]]: eigenvalues 3 and -1 */
    trip_add(&t, 0, 0, 1);
    trip_add(&t, 1, 0, 2);
    trip_add(&t, 1, 1, 1);
    expect_spd_failure(2, &t, SQ_ERR_SOLVER, "not positive definite");
    trip_free(&t);

    trip_init(&t, 1);
    trip_add(&t, 0, 0, -1);
    expect_spd_failure(1, &t, SQ_ERR_SOLVER, "not positive definite");
    trip_free(&t);

    trip_init(&t, 4); /* the zero matrix */
    expect_spd_failure(4, &t, SQ_ERR_SOLVER, "not positive definite");
    trip_free(&t);

    /* Large: grid Laplacian minus 0.5 I is indefinite (its spectrum
     * starts at 0). */
    grid_laplacian(&t, 100, -0.5);
    expect_spd_failure(t.n, &t, SQ_ERR_SOLVER, "not positive definite");
    trip_free(&t);
}

/* Positive semidefinite and singular: the Laplacian of a weighted 3-cycle.
 * With these weights roundoff leaves the last Cholesky pivot positive (about
 * 3e-16 of its diagonal entry), so CHOLMOD alone would factor it. */
static void test_spd_rejects_roundoff_pivot(void **state)
{
    (void)state;
    static const double w[3] = {0x1.2618c6694c318p+0, 0x1.28fef61251fdfp-1,
                                0x1.02eaf97505d5fp+0};
    triplets t;
    trip_init(&t, 3);
    for (uint32_t i = 0; i < 3; i++) trip_add_edge(&t, i, (i + 1) % 3, w[i]);
    expect_spd_failure(3, &t, SQ_ERR_SOLVER, "numerically singular");
    trip_free(&t);

    /* Badly scaled but regular: diag(1, 1e-17) is solved exactly. */
    trip_init(&t, 2);
    trip_add(&t, 0, 0, 1);
    trip_add(&t, 1, 1, 1e-17);
    const double b[2] = {3, 2e-17};
    double x[2];
    sq_spd *s = NULL;
    assert_int_equal(sq_spd_factor(2, t.count, t.rows, t.cols, t.vals, &s, NULL), SQ_OK);
    assert_int_equal(sq_spd_solve(s, 1, b, x, NULL), SQ_OK);
    assert_true(fabs(x[0] - 3) < 1e-15 && fabs(x[1] - 2) < 1e-15);
    sq_spd_free(s);
    sq_lu *l = NULL;
    assert_int_equal(sq_lu_factor(2, t.count, t.rows, t.cols, t.vals, &l, NULL), SQ_OK);
    assert_int_equal(sq_lu_solve(l, 1, b, x, NULL), SQ_OK);
    assert_true(fabs(x[0] - 3) < 1e-15 && fabs(x[1] - 2) < 1e-15);
    sq_lu_free(l);
    trip_free(&t);
}

/* ---- Hermitian positive definite (CHOLMOD, complex) ---------------------- */

/* Magnetic Laplacian of a side x side grid: edge (u, v), u > v, weight w and
 * phase t gives A(u,u) += w, A(v,v) += w, A(u,v) = -w e^{it} (A(v,u) its
 * conjugate), plus shift times the identity: Hermitian, positive definite
 * for shift > 0. Lower triangle only, two doubles per triplet (trip_add
 * stores the real part, im[] the imaginary part). */
typedef struct ctriplets {
    triplets t;
    double *v;    /* 2 per triplet */
    size_t v_cap; /* triplets v has room for */
} ctriplets;

static void ctrip_add(ctriplets *c, uint32_t i, uint32_t j, double re, double im)
{
    trip_add(&c->t, i, j, re);
    if (c->v_cap < c->t.cap) {
        c->v = realloc(c->v, 2 * c->t.cap * sizeof *c->v);
        assert_non_null(c->v);
        c->v_cap = c->t.cap;
    }
    c->v[2 * (c->t.count - 1)] = re, c->v[2 * (c->t.count - 1) + 1] = im;
}

static void magnetic_laplacian(ctriplets *c, uint32_t side, double shift)
{
    trip_init(&c->t, side * side);
    c->v = NULL, c->v_cap = 0;
    for (uint32_t r = 0; r < side; r++)
        for (uint32_t q = 0; q < side; q++) {
            const uint32_t v = r * side + q;
            for (int dir = 0; dir < 2; dir++) {
                if ((dir == 0 && q + 1 == side) || (dir == 1 && r + 1 == side)) continue;
                const uint32_t u = dir ? v + side : v + 1;
                const double w = 1.0 + 0.5 * sin(0.37 * v + dir), t = 0.9 * r - 0.4 * q + dir;
                ctrip_add(c, u, u, w, 0);
                ctrip_add(c, v, v, w, 0);
                ctrip_add(c, u, v, -w * cos(t), -w * sin(t));
            }
            ctrip_add(c, v, v, shift, 0);
        }
}

/* y = A x, x and y complex (interleaved), A Hermitian from its lower triangle */
static void cmatvec(const ctriplets *c, const double *x, double *y)
{
    memset(y, 0, 2 * (size_t)c->t.n * sizeof *y);
    for (size_t k = 0; k < c->t.count; k++) {
        const uint32_t i = c->t.rows[k], j = c->t.cols[k];
        const double ar = c->v[2 * k], ai = c->v[2 * k + 1];
        if (i < j) continue;
        y[2 * i] += ar * x[2 * j] - ai * x[2 * j + 1], y[2 * i + 1] += ar * x[2 * j + 1] + ai * x[2 * j];
        if (i != j) /* conj(a) x_i */
            y[2 * j] += ar * x[2 * i] + ai * x[2 * i + 1], y[2 * j + 1] += ar * x[2 * i + 1] - ai * x[2 * i];
    }
}

/* The complex solve against the known solution, and against the real
 * system of size 2n with the same minimizer ([re -im; im re] blocks). */
static void check_hpd(uint32_t side, uint32_t nrhs)
{
    ctriplets c;
    magnetic_laplacian(&c, side, 0.25);
    const size_t n = c.t.n, m = 2 * n;
    double *xs = calloc(m * nrhs, sizeof *xs), *b = malloc(m * nrhs * sizeof *b);
    double *x = malloc(m * nrhs * sizeof *x), *r = malloc(m * sizeof *r), *xr = malloc(m * sizeof *xr);
    assert_true(xs && b && x && r && xr);
    for (uint32_t k = 0; k < nrhs; k++) {
        for (size_t i = 0; i < m; i++) xs[k * m + i] = known(i, k);
        cmatvec(&c, xs + k * m, b + k * m);
    }
    sq_error err;
    sq_error_clear(&err);
    sq_spd *f = NULL;
    assert_int_equal(sq_hpd_factor(c.t.n, c.t.count, c.t.rows, c.t.cols, c.v, &f, &err), SQ_OK);
    assert_int_equal(sq_spd_solve(f, nrhs, b, x, &err), SQ_OK);
    sq_spd_free(f);
    for (uint32_t k = 0; k < nrhs; k++) {
        assert_true(relative_diff(x + k * m, xs + k * m, m) < 1e-9);
        cmatvec(&c, x + k * m, r);
        assert_true(relative_diff(r, b + k * m, m) < 1e-12);
    }
    /* the realification: unknowns (re z_i, im z_i) at 2i, 2i+1 */
    triplets t;
    trip_init(&t, (uint32_t)m);
    for (size_t k = 0; k < c.t.count; k++) {
        const uint32_t i = c.t.rows[k], j = c.t.cols[k];
        const double ar = c.v[2 * k], ai = c.v[2 * k + 1];
        trip_add(&t, 2 * i, 2 * j, ar);
        trip_add(&t, 2 * i + 1, 2 * j + 1, ar);
        trip_add(&t, 2 * i + 1, 2 * j, ai);
        if (i != j) trip_add(&t, 2 * i, 2 * j + 1, -ai); /* row > col: kept */
    }
    assert_int_equal(sq_spd_factor(t.n, t.count, t.rows, t.cols, t.vals, &f, &err), SQ_OK);
    assert_int_equal(sq_spd_solve(f, 1, b, xr, &err), SQ_OK);
    sq_spd_free(f);
    assert_true(relative_diff(x, xr, m) < 1e-11);
    trip_free(&t);
    free(xs), free(b), free(x), free(r), free(xr);
    trip_free(&c.t);
    free(c.v);
}

static void test_hpd_magnetic_laplacian(void **state)
{
    (void)state;
    check_hpd(40, 1);  /* 1,600 unknowns: the simplicial code */
    check_hpd(40, 2);  /* two right-hand sides */
    check_hpd(180, 1); /* 32,400 (64,800 real): the supernodal code */
}

static void test_hpd_rejects(void **state)
{
    (void)state;
    ctriplets c;
    magnetic_laplacian(&c, 30, -4.0); /* the spectrum starts below 4 */
    sq_error err;
    sq_error_clear(&err);
    sq_spd *f = (sq_spd *)&err;
    assert_int_equal(sq_hpd_factor(c.t.n, c.t.count, c.t.rows, c.t.cols, c.v, &f, &err), SQ_ERR_SOLVER);
    assert_null(f);
    assert_non_null(strstr(err.msg, "not positive definite"));
    c.v[2 * 5 + 1] = NAN; /* an imaginary part */
    f = (sq_spd *)&err;
    assert_int_equal(sq_hpd_factor(c.t.n, c.t.count, c.t.rows, c.t.cols, c.v, &f, &err), SQ_ERR_ARGUMENT);
    assert_null(f);
    assert_non_null(strstr(err.msg, "non-finite"));
    trip_free(&c.t);
    free(c.v);
}

/* ---- LU (UMFPACK) --------------------------------------------------------- */

/* Nonsymmetric: grid Laplacian + I with a convection term. */
static void test_lu_nonsymmetric(void **state)
{
    (void)state;
    triplets t;
    grid_laplacian(&t, 100, 1.0);
    for (uint32_t v = 0; v + 1 < t.n; v++) {
        trip_add(&t, v, v + 1, 0.4);
        trip_add(&t, v + 1, v, -0.4);
    }
    check_solve(&t, 1, 0, matvec_general, 1e-10);
    check_solve(&t, 3, 0, matvec_general, 1e-10);
    trip_free(&t);

    /* A small dense nonsymmetric, non-diagonally-dominant system. */
    trip_init(&t, 3);
    static const double a[3][3] = {{0, 2, 1}, {3, 0, -1}, {1, 5, 0}};
    for (uint32_t i = 0; i < 3; i++)
        for (uint32_t j = 0; j < 3; j++)
            if (a[i][j] != 0) trip_add(&t, i, j, a[i][j]);
    check_solve(&t, 2, 0, matvec_general, 1e-12);
    trip_free(&t);
}

static void expect_lu_failure(uint32_t n, const triplets *t, sq_status code, const char *words)
{
    sq_error err;
    sq_error_clear(&err);
    sq_lu *f = (sq_lu *)&err;
    assert_int_equal(sq_lu_factor(n, t->count, t->rows, t->cols, t->vals, &f, &err), code);
    assert_null(f);
    assert_int_equal(err.code, code);
    assert_non_null(strstr(err.msg, words));
}

static void test_lu_singular(void **state)
{
    (void)state;
    triplets t;
    trip_init(&t, 2); /* [[1, 2], [2, 4]]: rank 1 */
    trip_add(&t, 0, 0, 1);
    trip_add(&t, 0, 1, 2);
    trip_add(&t, 1, 0, 2);
    trip_add(&t, 1, 1, 4);
    expect_lu_failure(2, &t, SQ_ERR_SOLVER, "singular");
    trip_free(&t);

    trip_init(&t, 3); /* column 2 is empty */
    trip_add(&t, 0, 0, 1);
    trip_add(&t, 1, 1, 1);
    trip_add(&t, 2, 0, 1);
    expect_lu_failure(3, &t, SQ_ERR_SOLVER, "singular");
    trip_free(&t);

    /* Roundoff-level pivot: Laplacian of a weighted 4-cycle. */
    static const double w[4] = {0x1.cd4da6cb9a9b5p+0, 0x1.638e15b2c71c3p+0,
                                0x1.a4e5ac1b49cb6p-1, 0x1.07da9e8e0fb54p-1};
    trip_init(&t, 4);
    for (uint32_t i = 0; i < 4; i++) trip_add_edge(&t, i, (i + 1) % 4, w[i]);
    expect_lu_failure(4, &t, SQ_ERR_SOLVER, "singular");
    trip_free(&t);

    trip_init(&t, 3); /* entries that cancel to the zero matrix */
    trip_add(&t, 0, 0, 1);
    trip_add(&t, 0, 0, -1);
    expect_lu_failure(3, &t, SQ_ERR_SOLVER, "singular");
    trip_free(&t);
}

/* ---- arguments ------------------------------------------------------------ */

static void test_bad_arguments(void **state)
{
    (void)state;
    const uint32_t rows[2] = {0, 1}, cols[2] = {0, 1};
    const double vals[2] = {1, 1};
    const uint32_t bad_rows[2] = {0, 2};
    const double nan_vals[2] = {1, NAN};
    sq_error err;
    sq_spd *s = NULL;
    sq_lu *l = NULL;

    assert_int_equal(sq_spd_factor(0, 0, NULL, NULL, NULL, &s, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "size n is 0"));
    assert_int_equal(sq_lu_factor(0, 0, NULL, NULL, NULL, &l, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "size n is 0"));

    assert_int_equal(sq_spd_factor(2, 2, bad_rows, cols, vals, &s, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "triplet 1 has index (2, 1) outside the 2 x 2 matrix"));
    assert_int_equal(sq_lu_factor(2, 2, rows, bad_rows, vals, &l, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "triplet 1 has index (1, 2) outside"));

    assert_int_equal(sq_spd_factor(2, 2, rows, cols, nan_vals, &s, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "non-finite"));
    assert_int_equal(sq_lu_factor(2, 2, rows, cols, nan_vals, &l, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "non-finite"));

    assert_int_equal(sq_spd_factor(2, 2, NULL, cols, vals, &s, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_lu_factor(2, 2, rows, cols, vals, NULL, &err), SQ_ERR_ARGUMENT);
    assert_null(s);
    assert_null(l);

    /* Solves: NULL factorization or arrays; a NULL sq_error is allowed. */
    double b[2] = {1, 2}, x[2];
    assert_int_equal(sq_spd_solve(NULL, 1, b, x, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_lu_solve(NULL, 1, b, x, NULL), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_spd_factor(2, 2, rows, cols, vals, &s, NULL), SQ_OK);
    assert_int_equal(sq_spd_solve(s, 1, NULL, x, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_spd_solve(s, 0, NULL, NULL, &err), SQ_OK); /* nothing to do */
    assert_int_equal(sq_spd_solve(s, 1, b, x, &err), SQ_OK);
    assert_true(x[0] == 1 && x[1] == 2);
    const double inf_b[2] = {INFINITY, 0};
    assert_int_equal(sq_spd_solve(s, 1, inf_b, x, &err), SQ_ERR_SOLVER);
    assert_non_null(strstr(err.msg, "not finite"));
    sq_spd_free(s);
    sq_spd_free(NULL);
    sq_lu_free(NULL);
}

/* ---- a real mesh: uniform graph Laplacian of the bunny ------------------ */

typedef struct mesh {
    uint32_t nv, nf;
    double *xyz;
    uint32_t *tri;
} mesh;

/* Minimal OFF reader for this test (header "OFF", counts, vertices,
 * triangles "3 i j k"); fails the test on anything else. */
static void read_off(const char *path, mesh *m)
{
    FILE *fp = fopen(path, "r");
    if (!fp) fail_msg("cannot open %s", path);
    char magic[8] = {0};
    unsigned nv, nf, ne;
    assert_int_equal(fscanf(fp, "%7s %u %u %u", magic, &nv, &nf, &ne), 4);
    assert_string_equal(magic, "OFF");
    m->nv = nv;
    m->nf = nf;
    m->xyz = malloc(3 * (size_t)nv * sizeof *m->xyz);
    m->tri = malloc(3 * (size_t)nf * sizeof *m->tri);
    assert_true(m->xyz && m->tri);
    for (size_t i = 0; i < 3 * (size_t)nv; i++) assert_int_equal(fscanf(fp, "%lf", &m->xyz[i]), 1);
    for (size_t f = 0; f < nf; f++) {
        unsigned k, a, b, c;
        assert_int_equal(fscanf(fp, "%u %u %u %u", &k, &a, &b, &c), 4);
        assert_int_equal(k, 3);
        assert_true(a < nv && b < nv && c < nv);
        m->tri[3 * f] = a;
        m->tri[3 * f + 1] = b;
        m->tri[3 * f + 2] = c;
    }
    fclose(fp);
}

static int cmp_edge(const void *p, const void *q)
{
    const uint64_t a = *(const uint64_t *)p, b = *(const uint64_t *)q;
    return (a > b) - (a < b);
}

/* Unique undirected edges of the mesh, as (lo << 32 | hi). */
static size_t mesh_edges(const mesh *m, uint64_t **out)
{
    uint64_t *e = malloc(3 * (size_t)m->nf * sizeof *e);
    assert_non_null(e);
    size_t count = 0;
    for (size_t f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            if (a > b) {
                const uint64_t s = a;
                a = b;
                b = s;
            }
            e[count++] = a << 32 | b;
        }
    qsort(e, count, sizeof *e, cmp_edge);
    size_t unique = 0;
    for (size_t k = 0; k < count; k++)
        if (unique == 0 || e[k] != e[unique - 1]) e[unique++] = e[k];
    *out = e;
    return unique;
}

static void test_bunny_pinned_laplacian(void **state)
{
    (void)state;
    mesh m;
    read_off(SQ_SHARED_DIR "/data/libigl/bunny.off", &m);
    assert_int_equal(m.nv, 3485);
    uint64_t *edges = NULL;
    const size_t ne = mesh_edges(&m, &edges);
    assert_int_equal(ne, 3 * (size_t)m.nf / 2); /* closed mesh */

    /* Known solution: a smooth function of the vertex positions. */
    const uint32_t n = m.nv, pin = 0;
    double *xs = malloc(n * sizeof *xs);
    assert_non_null(xs);
    for (uint32_t v = 0; v < n; v++)
        xs[v] = 10 * m.xyz[3 * v + 1] + sin(30 * m.xyz[3 * v]) + 0.1 * v / n;

    /* (1) Full Laplacian with row `pin` replaced by x_pin = xs[pin]: a
     * nonsymmetric matrix, solved by LU. */
    triplets lu;
    trip_init(&lu, n);
    for (size_t k = 0; k < ne; k++) {
        const uint32_t a = (uint32_t)(edges[k] >> 32), b = (uint32_t)edges[k];
        if (a != pin) {
            trip_add(&lu, a, a, 1);
            trip_add(&lu, a, b, -1);
        }
        if (b != pin) {
            trip_add(&lu, b, b, 1);
            trip_add(&lu, b, a, -1);
        }
    }
    trip_add(&lu, pin, pin, 1);
    double *b = malloc(n * sizeof *b), *x = malloc(n * sizeof *x), *r = malloc(n * sizeof *r);
    assert_true(b && x && r);
    matvec_general(&lu, xs, b);
    sq_error err;
    sq_lu *f = NULL;
    assert_int_equal(sq_lu_factor(n, lu.count, lu.rows, lu.cols, lu.vals, &f, &err), SQ_OK);
    assert_int_equal(sq_lu_solve(f, 1, b, x, &err), SQ_OK);
    sq_lu_free(f);
    matvec_general(&lu, x, r);
    assert_true(relative_diff(r, b, n) < 1e-12);
    assert_true(relative_diff(x, xs, n) < 1e-9);
    assert_true(x[pin] == xs[pin]);

    /* (2) The same system with the pinned vertex eliminated symmetrically:
     * the reduced Laplacian is SPD (the mesh is connected), solved by
     * Cholesky. Unknowns are the vertices other than `pin`, index v - 1. */
    assert_int_equal(pin, 0);
    triplets spd;
    trip_init(&spd, n - 1);
    double *rb = malloc((n - 1) * sizeof *rb), *rx = malloc((n - 1) * sizeof *rx);
    assert_true(rb && rx);
    for (uint32_t v = 1; v < n; v++) rb[v - 1] = b[v];
    for (size_t k = 0; k < ne; k++) {
        const uint32_t a = (uint32_t)(edges[k] >> 32), c = (uint32_t)edges[k];
        assert_true(a < c);
        if (a == pin) { /* move the known x_pin to the right-hand side */
            trip_add(&spd, c - 1, c - 1, 1);
            rb[c - 1] += xs[pin];
        } else {
            trip_add_edge(&spd, a - 1, c - 1, 1);
        }
    }
    sq_spd *s = NULL;
    assert_int_equal(sq_spd_factor(n - 1, spd.count, spd.rows, spd.cols, spd.vals, &s, &err), SQ_OK);
    assert_int_equal(sq_spd_solve(s, 1, rb, rx, &err), SQ_OK);
    sq_spd_free(s);
    matvec_lower(&spd, rx, r);
    assert_true(relative_diff(r, rb, n - 1) < 1e-12);
    /* Both solvers agree with each other and with the known solution. */
    assert_true(relative_diff(rx, x + 1, n - 1) < 1e-9);
    assert_true(relative_diff(rx, xs + 1, n - 1) < 1e-9);

    /* Without the pin the Laplacian is singular (constants span its
     * kernel). Roundoff leaves a tiny last pivot rather than an exact zero;
     * both solvers must still refuse it. */
    triplets sing;
    trip_init(&sing, n);
    for (size_t k = 0; k < ne; k++)
        trip_add_edge(&sing, (uint32_t)(edges[k] >> 32), (uint32_t)edges[k], 1);
    sq_lu *g = (sq_lu *)&err;
    assert_int_equal(sq_lu_factor(n, sing.count, sing.rows, sing.cols, sing.vals, &g, &err),
                     SQ_ERR_SOLVER);
    assert_null(g);
    assert_non_null(strstr(err.msg, "singular"));
    sq_spd *h = (sq_spd *)&err;
    assert_int_equal(sq_spd_factor(n, sing.count, sing.rows, sing.cols, sing.vals, &h, &err),
                     SQ_ERR_SOLVER);
    assert_null(h);
    assert_true(strstr(err.msg, "singular") || strstr(err.msg, "not positive definite"));

    trip_free(&sing);
    trip_free(&lu);
    trip_free(&spd);
    free(rb);
    free(rx);
    free(b);
    free(x);
    free(r);
    free(xs);
    free(edges);
    free(m.xyz);
    free(m.tri);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spd_grid_laplacian),
        cmocka_unit_test(test_spd_upper_ignored),
        cmocka_unit_test(test_duplicates_summed),
        cmocka_unit_test(test_spd_rejects_indefinite),
        cmocka_unit_test(test_spd_rejects_roundoff_pivot),
        cmocka_unit_test(test_spd_refactor),
        cmocka_unit_test(test_hpd_magnetic_laplacian),
        cmocka_unit_test(test_hpd_rejects),
        cmocka_unit_test(test_lu_nonsymmetric),
        cmocka_unit_test(test_lu_singular),
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_bunny_pinned_laplacian),
    };
    return cmocka_run_group_tests_name("sparse", tests, NULL, NULL);
}
