/* seamquad: sparse linear solves (CHOLMOD for symmetric positive definite,
 * UMFPACK for general square systems). Matrices come in as triplets
 * (row, col, value) with duplicates summed, 0-based. No global state: every
 * factorization owns its solver context. */
#ifndef SQ_SPARSE_H
#define SQ_SPARSE_H

#include <stddef.h>
#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_spd sq_spd;   /* Cholesky factorization (CHOLMOD)   */
typedef struct sq_lu sq_lu;     /* LU factorization (UMFPACK)         */

/* Symmetric positive definite matrix of size n. Give either triangle or
 * both: entries with row < col are ignored (the lower triangle is used). */
sq_status sq_spd_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                        const double *vals, sq_spd **out, sq_error *err);
/* The same for a matrix refactored many times (sq_spd_refactor) with more
 * fill than a Laplacian's: the optimizer's Newton systems (2x2 blocks per
 * vertex). The simplicial code below 200,000 unknowns (sq_spd_factor:
 * 60,000), CHOLMOD's choice between simplicial and supernodal (flops per
 * entry of the factor) above; sq_sparse.c gives the measurements. */
sq_status sq_spd_factor_auto(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                             const double *vals, sq_spd **out, sq_error *err);
/* Hermitian positive definite complex matrix of size n: vals holds two
 * doubles per triplet (real, imaginary part); the lower triangle is used
 * (entries with row < col are ignored), the upper is its conjugate. The
 * diagonal's imaginary parts must be 0. Half the unknowns and about half
 * the work of the real system of size 2n that a complex-linear least
 * squares problem would otherwise give (docs/solvers.md). */
sq_status sq_hpd_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                        const double *vals, sq_spd **out, sq_error *err);
/* A new matrix with the same nonzero pattern as the one f was made from
 * (the same triplet positions; values may differ, also to zero): its
 * numeric factorization, reusing f's ordering and symbolic analysis (on
 * failure f must not be used for solves until a refactorization
 * succeeds). */
sq_status sq_spd_refactor(sq_spd *f, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                          const double *vals, sq_error *err);
/* Solves A X = B for nrhs columns stored one after another (n each; with
 * sq_hpd_factor, n complex numbers each, interleaved real and imaginary
 * part). */
sq_status sq_spd_solve(sq_spd *f, uint32_t nrhs, const double *b, double *x, sq_error *err);
void sq_spd_free(sq_spd *f);

/* General square matrix of size n. */
sq_status sq_lu_factor(uint32_t n, size_t nnz, const uint32_t *rows, const uint32_t *cols,
                       const double *vals, sq_lu **out, sq_error *err);
sq_status sq_lu_solve(sq_lu *f, uint32_t nrhs, const double *b, double *x, sq_error *err);
void sq_lu_free(sq_lu *f);

#ifdef __cplusplus
}
#endif
#endif
