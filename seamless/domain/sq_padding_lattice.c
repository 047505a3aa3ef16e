/* seamquad: integral solutions of the padding system (seed 6.3 asks for
 * w in Z^|w|). Column Hermite normal form by extended-Euclid column
 * operations: M U = H with U unimodular and H lower echelon. Writing
 * w = U y, the pivot entries of y are forced (H y = r) and the others are
 * free, so an integral solution exists iff the forced entries are
 * integers, the columns of U beyond the rank are a basis of the integral
 * null space, and the least common denominator of the forced entries is
 * the smallest refinement d for which d * r has an integral solution. */
#include "sq_padding_internal.h"

#include <assert.h>
#include <stdlib.h>

static void col_swap(mpz_t *A, uint32_t rows, uint32_t n, uint32_t r0, uint32_t a, uint32_t b)
{
    for (uint32_t i = r0; i < rows; ++i)
        mpz_swap(A[(size_t)i * n + a], A[(size_t)i * n + b]);
}

/* column b -= q * column a, rows r0..rows-1 */
static void col_submul(mpz_t *A, uint32_t rows, uint32_t n, uint32_t r0, uint32_t b, uint32_t a,
                       const mpz_t q)
{
    for (uint32_t i = r0; i < rows; ++i)
        if (mpz_sgn(A[(size_t)i * n + a]) != 0)
            mpz_submul(A[(size_t)i * n + b], q, A[(size_t)i * n + a]);
}

sq_status sq_padding_lattice(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                             mpz_t den, mpz_t *w0, uint32_t *rank, mpz_t *lattice,
                             sq_error *err)
{
    mpz_t *H = malloc(((size_t)m * n + 1) * sizeof *H);
    mpz_t *U = malloc(((size_t)n * n + 1) * sizeof *U);
    uint32_t *prow = malloc(((size_t)n + 1) * sizeof *prow);
    mpq_t *y = malloc(((size_t)n + 1) * sizeof *y);
    if (!H || !U || !prow || !y) {
        free(H);
        free(U);
        free(prow);
        free(y);
        return sq_error_set(err, SQ_ERR_NOMEM, "padding: out of memory (lattice %u x %u)", m,
                            n);
    }
    for (size_t i = 0; i < (size_t)m * n; ++i)
        mpz_init_set(H[i], M[i]);
    for (size_t i = 0; i < (size_t)n * n; ++i)
        mpz_init(U[i]);
    for (uint32_t i = 0; i < n; ++i)
        mpz_set_ui(U[(size_t)i * n + i], 1);
    mpz_t q;
    mpz_init(q);
    uint32_t p = 0;
    for (uint32_t i = 0; i < m && p < n; ++i) {
        for (;;) {
            /* smallest nonzero |H[i][j]|, j >= p */
            uint32_t best = n;
            for (uint32_t j = p; j < n; ++j) {
                const mpz_t *h = &H[(size_t)i * n + j];
                if (mpz_sgn(*h) == 0)
                    continue;
                if (best == n || mpz_cmpabs(*h, H[(size_t)i * n + best]) < 0)
                    best = j;
            }
            if (best == n)
                break; /* row i depends on earlier rows */
            if (best != p) {
                col_swap(H, m, n, i, best, p);
                col_swap(U, n, n, 0, best, p);
            }
            int done = 1;
            for (uint32_t j = p + 1; j < n; ++j) {
                if (mpz_sgn(H[(size_t)i * n + j]) == 0)
                    continue;
                mpz_tdiv_q(q, H[(size_t)i * n + j], H[(size_t)i * n + p]);
                col_submul(H, m, n, i, j, p, q);
                col_submul(U, n, n, 0, j, p, q);
                if (mpz_sgn(H[(size_t)i * n + j]) != 0)
                    done = 0;
            }
            if (done)
                break;
        }
        if (mpz_sgn(H[(size_t)i * n + p]) == 0)
            continue;
        if (mpz_sgn(H[(size_t)i * n + p]) < 0) {
            for (uint32_t t = i; t < m; ++t)
                mpz_neg(H[(size_t)t * n + p], H[(size_t)t * n + p]);
            for (uint32_t t = 0; t < n; ++t)
                mpz_neg(U[(size_t)t * n + p], U[(size_t)t * n + p]);
        }
        prow[p++] = i;
    }
    *rank = p;
    /* forced entries of y: forward substitution in the echelon form */
    for (uint32_t c = 0; c < n; ++c)
        mpq_init(y[c]);
    mpq_t t, s;
    mpq_init(t);
    mpq_init(s);
    mpz_set_ui(den, 1);
    for (uint32_t c = 0; c < p; ++c) {
        const uint32_t i = prow[c];
        mpq_set_z(s, r[i]);
        for (uint32_t c2 = 0; c2 < c; ++c2) {
            if (mpz_sgn(H[(size_t)i * n + c2]) == 0)
                continue;
            mpq_set_z(t, H[(size_t)i * n + c2]);
            mpq_mul(t, t, y[c2]);
            mpq_sub(s, s, t);
        }
        mpq_set_z(t, H[(size_t)i * n + c]);
        mpq_div(y[c], s, t);
        mpz_lcm(den, den, mpq_denref(y[c]));
    }
    /* w0 = U (den * y) */
    mpz_t yz;
    mpz_init(yz);
    for (uint32_t j = 0; j < n; ++j)
        mpz_set_ui(w0[j], 0);
    for (uint32_t c = 0; c < p; ++c) {
        mpz_divexact(yz, den, mpq_denref(y[c]));
        mpz_mul(yz, yz, mpq_numref(y[c]));
        if (mpz_sgn(yz) == 0)
            continue;
        for (uint32_t j = 0; j < n; ++j)
            mpz_addmul(w0[j], U[(size_t)j * n + c], yz);
    }
    for (uint32_t c = p; c < n; ++c)
        for (uint32_t j = 0; j < n; ++j)
            mpz_set(lattice[(size_t)(c - p) * n + j], U[(size_t)j * n + c]);
    mpz_clear(yz);
    mpq_clear(t);
    mpq_clear(s);
    mpz_clear(q);
    for (uint32_t c = 0; c < n; ++c)
        mpq_clear(y[c]);
    for (size_t i = 0; i < (size_t)m * n; ++i)
        mpz_clear(H[i]);
    for (size_t i = 0; i < (size_t)n * n; ++i)
        mpz_clear(U[i]);
    free(H);
    free(U);
    free(prow);
    free(y);
    return SQ_OK;
}
