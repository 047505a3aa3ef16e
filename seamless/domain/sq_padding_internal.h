/* seamquad: exact linear algebra behind sq_padding.c (not public API).
 * Matrices are dense, row-major, of GMP numbers; m rows, n columns. */
#ifndef SQ_PADDING_INTERNAL_H
#define SQ_PADDING_INTERNAL_H

#include <stdint.h>

#include <gmp.h>

#include "sq_error.h"

/* sq_padding_rational.c: Gaussian elimination over Q of M w = r.
 * Outputs: *rank; *consistent; if inconsistent, cert (m entries, set) with
 * cert^T M = 0 and cert^T r != 0, scaled to integers; if consistent,
 * basic (n entries) the solution with every free unknown 0, and kernel
 * (n * n entries, first n - rank columns used, column j at kernel[j*n ..])
 * the standard null-space basis (one vector per free unknown) scaled to
 * primitive integer vectors. Every output array must be mpz/mpq-initialized
 * by the caller. */
sq_status sq_padding_rational(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                              uint32_t *rank, int *consistent, mpz_t *cert, mpq_t *basic,
                              mpz_t *kernel, sq_error *err);

/* sq_padding_lattice.c: integral solutions of M w = r via a column Hermite
 * normal form M U = H (U unimodular). Requires a consistent system.
 * Outputs: den, the least positive integer with M w = den * r solvable in
 * integers; w0 (n) such an integral solution; *rank; lattice (n * n,
 * first n - rank columns used, column j at lattice[j*n ..]) a basis of the
 * integral null space ker M cap Z^n. */
sq_status sq_padding_lattice(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                             mpz_t den, mpz_t *w0, uint32_t *rank, mpz_t *lattice,
                             sq_error *err);

/* sq_padding_lp.c: exact simplex (Bland's rule) for
 *   minimize cost . w  subject to  M w = r, w >= 0.
 * *feasible is 0 if no such w exists; else vertex (n) is an optimal vertex
 * (cost >= 0 is required, so the problem is bounded). */
sq_status sq_padding_lp(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                        const mpz_t *cost, int *feasible, mpq_t *vertex, sq_error *err);

#endif
