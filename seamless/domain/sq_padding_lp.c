/* seamquad: a tiny exact linear program for the padding system when the
 * shift argument of seamless-notes 3 does not apply (forced zero padding
 * on split sides, seed 6.4; several pieces, seed 6.2). Dense two-phase
 * simplex over Q (GMP mpq) with Bland's rule, so it terminates and its
 * answer (infeasible, or an optimal vertex) is exact. Systems have at most
 * a few hundred unknowns. */
#include "sq_padding_internal.h"

#include <assert.h>
#include <stdlib.h>

typedef struct tableau {
    uint32_t m, n, w; /* rows, structural columns, row width (n + m + 1) */
    mpq_t *T;         /* (m + 1) x w; row m is the reduced-cost row      */
    uint32_t *basis;  /* m                                               */
    mpq_t f, g;
} tableau;

#define AT(tb, i, j) ((tb)->T[(size_t)(i) * (tb)->w + (j)])

static void pivot(tableau *tb, uint32_t pr, uint32_t pc)
{
    mpq_inv(tb->f, AT(tb, pr, pc));
    for (uint32_t j = 0; j < tb->w; ++j)
        if (mpq_sgn(AT(tb, pr, j)) != 0)
            mpq_mul(AT(tb, pr, j), AT(tb, pr, j), tb->f);
    for (uint32_t i = 0; i <= tb->m; ++i) {
        if (i == pr || mpq_sgn(AT(tb, i, pc)) == 0)
            continue;
        mpq_set(tb->f, AT(tb, i, pc));
        for (uint32_t j = 0; j < tb->w; ++j) {
            if (mpq_sgn(AT(tb, pr, j)) == 0)
                continue;
            mpq_mul(tb->g, tb->f, AT(tb, pr, j));
            mpq_sub(AT(tb, i, j), AT(tb, i, j), tb->g);
        }
    }
    tb->basis[pr] = pc;
}

/* Minimizes over the columns < allowed; returns 0 at optimum, 1 if
 * unbounded. */
static int simplex(tableau *tb, uint32_t allowed)
{
    const uint32_t rhs = tb->w - 1;
    for (;;) {
        uint32_t enter = allowed;
        for (uint32_t j = 0; j < allowed; ++j)
            if (mpq_sgn(AT(tb, tb->m, j)) < 0) {
                enter = j;
                break;
            }
        if (enter == allowed)
            return 0;
        uint32_t leave = tb->m;
        for (uint32_t i = 0; i < tb->m; ++i) {
            if (mpq_sgn(AT(tb, i, enter)) <= 0)
                continue;
            mpq_div(tb->g, AT(tb, i, rhs), AT(tb, i, enter));
            if (leave == tb->m) {
                mpq_set(tb->f, tb->g);
                leave = i;
                continue;
            }
            const int c = mpq_cmp(tb->g, tb->f);
            if (c < 0 || (c == 0 && tb->basis[i] < tb->basis[leave])) {
                mpq_set(tb->f, tb->g);
                leave = i;
            }
        }
        if (leave == tb->m)
            return 1;
        pivot(tb, leave, enter);
    }
}

sq_status sq_padding_lp(uint32_t m, uint32_t n, const mpz_t *M, const mpz_t *r,
                        const mpz_t *cost, int *feasible, mpq_t *vertex, sq_error *err)
{
    tableau tb;
    tb.m = m;
    tb.n = n;
    tb.w = n + m + 1;
    const uint32_t rhs = tb.w - 1;
    tb.T = malloc(((size_t)(m + 1) * tb.w) * sizeof *tb.T);
    tb.basis = malloc(((size_t)m + 1) * sizeof *tb.basis);
    if (!tb.T || !tb.basis) {
        free(tb.T);
        free(tb.basis);
        return sq_error_set(err, SQ_ERR_NOMEM, "padding LP: out of memory (%u x %u)", m, n);
    }
    for (size_t i = 0; i < (size_t)(m + 1) * tb.w; ++i)
        mpq_init(tb.T[i]);
    mpq_init(tb.f);
    mpq_init(tb.g);
    for (uint32_t i = 0; i < m; ++i) {
        const int neg = mpz_sgn(r[i]) < 0;
        for (uint32_t j = 0; j < n; ++j) {
            mpq_set_z(AT(&tb, i, j), M[(size_t)i * n + j]);
            if (neg)
                mpq_neg(AT(&tb, i, j), AT(&tb, i, j));
        }
        mpq_set_z(AT(&tb, i, rhs), r[i]);
        if (neg)
            mpq_neg(AT(&tb, i, rhs), AT(&tb, i, rhs));
        mpq_set_ui(AT(&tb, i, n + i), 1, 1);
        tb.basis[i] = n + i;
    }
    /* phase 1: minimize the sum of the artificials */
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < m; ++i)
            mpq_sub(AT(&tb, m, j), AT(&tb, m, j), AT(&tb, i, j));
    for (uint32_t i = 0; i < m; ++i)
        mpq_sub(AT(&tb, m, rhs), AT(&tb, m, rhs), AT(&tb, i, rhs));
    int unb = simplex(&tb, n + m);
    assert(!unb); /* bounded below by 0 */
    (void)unb;
    *feasible = mpq_sgn(AT(&tb, m, rhs)) == 0;
    sq_status st = SQ_OK;
    if (*feasible) {
        /* drive the artificials out of the basis; rows where that is
         * impossible are redundant and stay inert */
        for (uint32_t i = 0; i < m; ++i) {
            if (tb.basis[i] < n)
                continue;
            for (uint32_t j = 0; j < n; ++j)
                if (mpq_sgn(AT(&tb, i, j)) != 0) {
                    pivot(&tb, i, j);
                    break;
                }
        }
        /* phase 2: reduced costs of the real objective */
        for (uint32_t j = 0; j < tb.w; ++j)
            mpq_set_ui(AT(&tb, m, j), 0, 1);
        for (uint32_t j = 0; j < n; ++j)
            mpq_set_z(AT(&tb, m, j), cost[j]);
        for (uint32_t i = 0; i < m; ++i) {
            const uint32_t b = tb.basis[i];
            if (b >= n || mpz_sgn(cost[b]) == 0)
                continue;
            mpq_set_z(tb.f, cost[b]);
            for (uint32_t j = 0; j < tb.w; ++j) {
                if (mpq_sgn(AT(&tb, i, j)) == 0)
                    continue;
                mpq_mul(tb.g, tb.f, AT(&tb, i, j));
                mpq_sub(AT(&tb, m, j), AT(&tb, m, j), tb.g);
            }
        }
        if (simplex(&tb, n))
            st = sq_error_set(err, SQ_ERR_INTERNAL, "padding LP: unbounded (negative cost?)");
        for (uint32_t j = 0; j < n; ++j)
            mpq_set_ui(vertex[j], 0, 1);
        for (uint32_t i = 0; i < m; ++i)
            if (tb.basis[i] < n)
                mpq_set(vertex[tb.basis[i]], AT(&tb, i, rhs));
    }
    for (size_t i = 0; i < (size_t)(m + 1) * tb.w; ++i)
        mpq_clear(tb.T[i]);
    mpq_clear(tb.f);
    mpq_clear(tb.g);
    free(tb.T);
    free(tb.basis);
    return st;
}
