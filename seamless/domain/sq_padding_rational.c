/* seamquad: exact rational Gaussian elimination for the padding system
 * (seed 6.3: "As A and b are rational (in fact integer), the result w is
 * rational"). Reduced row echelon form of [M | r | I] over Q with GMP mpq;
 * the identity block records the row operations, so an inconsistent row
 * yields its certificate (the violated invariant). */
#include "sq_padding_internal.h"

#include <assert.h>
#include <stdlib.h>

/* Multiplies the vector v (len entries, mpq) by the lcm of its
 * denominators and divides by the gcd of the numerators: a primitive
 * integer vector, written to out. */
static void primitive(uint32_t len, mpq_t *v, mpz_t *out)
{
    mpz_t l, g;
    mpz_init_set_ui(l, 1);
    mpz_init_set_ui(g, 0);
    for (uint32_t i = 0; i < len; ++i)
        mpz_lcm(l, l, mpq_denref(v[i]));
    for (uint32_t i = 0; i < len; ++i) {
        mpz_divexact(out[i], l, mpq_denref(v[i]));
        mpz_mul(out[i], out[i], mpq_numref(v[i]));
        mpz_gcd(g, g, out[i]);
    }
    if (mpz_sgn(g) != 0)
        for (uint32_t i = 0; i < len; ++i)
            mpz_divexact(out[i], out[i], g);
    mpz_clear(l);
    mpz_clear(g);
}

sq_status sq_padding_rational(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                              uint32_t *rank, int *consistent, mpz_t *cert, mpq_t *basic,
                              mpz_t *kernel, sq_error *err)
{
    const size_t w = (size_t)n + 1 + m; /* columns: M, r, transform */
    mpq_t *A = malloc(((size_t)m * w + 1) * sizeof *A);
    uint32_t *pivot_col = malloc(((size_t)m + 1) * sizeof *pivot_col);
    uint8_t *is_pivot = calloc((size_t)n + 1, 1);
    mpq_t *tmpv = malloc(((size_t)n + m + 1) * sizeof *tmpv);
    if (!A || !pivot_col || !is_pivot || !tmpv) {
        free(A);
        free(pivot_col);
        free(is_pivot);
        free(tmpv);
        return sq_error_set(err, SQ_ERR_NOMEM, "padding: out of memory (%u x %u system)", m,
                            n);
    }
    for (size_t i = 0; i < (size_t)m * w; ++i)
        mpq_init(A[i]);
    for (size_t i = 0; i < (size_t)n + m + 1; ++i)
        mpq_init(tmpv[i]);
    for (uint32_t i = 0; i < m; ++i) {
        for (uint32_t j = 0; j < n; ++j)
            mpq_set_z(A[i * w + j], M[(size_t)i * n + j]);
        mpq_set_z(A[i * w + n], r[i]);
        mpq_set_ui(A[i * w + n + 1 + i], 1, 1);
    }
    mpq_t f;
    mpq_init(f);
    uint32_t rk = 0;
    for (uint32_t c = 0; c < n && rk < m; ++c) {
        uint32_t p = m;
        for (uint32_t i = rk; i < m; ++i)
            if (mpq_sgn(A[i * w + c]) != 0) {
                p = i;
                break;
            }
        if (p == m)
            continue;
        if (p != rk)
            for (size_t j = 0; j < w; ++j)
                mpq_swap(A[(size_t)p * w + j], A[(size_t)rk * w + j]);
        /* normalize the pivot row */
        mpq_inv(f, A[rk * w + c]);
        for (size_t j = c; j < w; ++j)
            if (mpq_sgn(A[rk * w + j]) != 0)
                mpq_mul(A[rk * w + j], A[rk * w + j], f);
        for (uint32_t i = 0; i < m; ++i) {
            if (i == rk || mpq_sgn(A[i * w + c]) == 0)
                continue;
            mpq_set(f, A[i * w + c]);
            for (size_t j = c; j < w; ++j) {
                if (mpq_sgn(A[rk * w + j]) == 0)
                    continue;
                mpq_mul(tmpv[0], f, A[rk * w + j]);
                mpq_sub(A[i * w + j], A[i * w + j], tmpv[0]);
            }
        }
        pivot_col[rk++] = c;
        is_pivot[c] = 1;
    }
    *rank = rk;
    *consistent = 1;
    for (uint32_t i = rk; i < m; ++i) {
        if (mpq_sgn(A[i * w + n]) != 0) {
            *consistent = 0;
            for (uint32_t j = 0; j < m; ++j)
                mpq_set(tmpv[j], A[i * w + n + 1 + j]);
            primitive(m, tmpv, cert);
            break;
        }
    }
    if (*consistent) {
        for (uint32_t j = 0; j < n; ++j)
            mpq_set_ui(basic[j], 0, 1);
        for (uint32_t i = 0; i < rk; ++i)
            mpq_set(basic[pivot_col[i]], A[i * w + n]);
        uint32_t col = 0;
        for (uint32_t fcol = 0; fcol < n; ++fcol) {
            if (is_pivot[fcol])
                continue;
            for (uint32_t j = 0; j < n; ++j)
                mpq_set_ui(tmpv[j], 0, 1);
            mpq_set_ui(tmpv[fcol], 1, 1);
            for (uint32_t i = 0; i < rk; ++i)
                mpq_neg(tmpv[pivot_col[i]], A[i * w + fcol]);
            primitive(n, tmpv, kernel + (size_t)col * n);
            ++col;
        }
        assert(col == n - rk);
    }
    mpq_clear(f);
    for (size_t i = 0; i < (size_t)m * w; ++i)
        mpq_clear(A[i]);
    for (size_t i = 0; i < (size_t)n + m + 1; ++i)
        mpq_clear(tmpv[i]);
    free(A);
    free(pivot_col);
    free(is_pivot);
    free(tmpv);
    return SQ_OK;
}
