/* seamquad: the padding equation system of seed 6.3 (see sq_padding.h and
 * docs/padding.md). This file builds the system, drives the exact solve
 * (sq_padding_rational.c, sq_padding_lattice.c, sq_padding_lp.c) and
 * runs the integral descent on the number of added quads (seed 9.3). */
#include "sq_padding.h"

#include <assert.h>
#include <gmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_padding_internal.h"

/* ---- the system container ---------------------------------------------- */

void sq_pad_system_init(sq_pad_system *S) { memset(S, 0, sizeof *S); }

void sq_pad_system_free(sq_pad_system *S)
{
    if (!S)
        return;
    free(S->piece_first);
    free(S->length);
    free(S->flags);
    free(S->con_first);
    free(S->term_side);
    free(S->term_coef);
    memset(S, 0, sizeof *S);
}

static int grow(void **p, uint32_t *cap, uint64_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    uint64_t c = *cap ? *cap : 8;
    while (c < need)
        c *= 2;
    if (c > UINT32_MAX)
        return 0;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = (uint32_t)c;
    return 1;
}

static sq_status ensure_heads(sq_pad_system *S, sq_error *err)
{
    if (!S->piece_first) {
        S->piece_first = calloc(1, sizeof *S->piece_first);
        if (!S->piece_first)
            return sq_error_set(err, SQ_ERR_NOMEM, "padding system: out of memory");
        S->cap_pieces = 0;
    }
    if (!S->con_first) {
        S->con_first = calloc(1, sizeof *S->con_first);
        if (!S->con_first)
            return sq_error_set(err, SQ_ERR_NOMEM, "padding system: out of memory");
        S->cap_con = 0;
    }
    return SQ_OK;
}

sq_status sq_pad_system_add_piece(sq_pad_system *S, uint32_t n, const int64_t *length,
                                  const uint8_t *flags, sq_error *err)
{
    if (n < 2)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "padding system: piece %u has %u sides; need >= 2", S->npieces, n);
    for (uint32_t i = 0; i < n; ++i)
        if (length[i] < 0)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "padding system: piece %u side %u has negative length %lld",
                                S->npieces, i, (long long)length[i]);
    sq_status st = ensure_heads(S, err);
    if (st != SQ_OK)
        return st;
    const uint64_t ns = (uint64_t)S->nsides + n;
    uint32_t cap_l = S->cap_sides, cap_f = S->cap_sides;
    uint32_t cap_p = S->cap_pieces;
    void *pf = S->piece_first;
    if (!grow((void **)&S->length, &cap_l, ns, sizeof *S->length) ||
        !grow((void **)&S->flags, &cap_f, ns, sizeof *S->flags) ||
        !grow(&pf, &cap_p, (uint64_t)S->npieces + 2, sizeof *S->piece_first))
        return sq_error_set(err, SQ_ERR_NOMEM, "padding system: out of memory");
    S->piece_first = pf;
    S->cap_pieces = cap_p;
    S->cap_sides = cap_l < cap_f ? cap_l : cap_f;
    for (uint32_t i = 0; i < n; ++i) {
        S->length[S->nsides + i] = length[i];
        S->flags[S->nsides + i] = flags ? flags[i] : 0;
    }
    S->nsides = (uint32_t)ns;
    S->piece_first[++S->npieces] = S->nsides;
    return SQ_OK;
}

sq_status sq_pad_system_add_constraint(sq_pad_system *S, uint32_t n, const uint32_t *side,
                                       const int32_t *coef, sq_error *err)
{
    if (n < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "padding system: empty constraint");
    for (uint32_t t = 0; t < n; ++t) {
        if (coef[t] == 0 || coef[t] == INT32_MIN)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "padding system: constraint %u term %u has coefficient %d",
                                S->ncon, t, coef[t]);
    }
    sq_status st = ensure_heads(S, err);
    if (st != SQ_OK)
        return st;
    const uint64_t nt = (uint64_t)S->nterms + n;
    uint32_t cap_s = S->cap_terms, cap_c = S->cap_terms, cap_q = S->cap_con;
    void *cf = S->con_first;
    if (!grow((void **)&S->term_side, &cap_s, nt, sizeof *S->term_side) ||
        !grow((void **)&S->term_coef, &cap_c, nt, sizeof *S->term_coef) ||
        !grow(&cf, &cap_q, (uint64_t)S->ncon + 2, sizeof *S->con_first))
        return sq_error_set(err, SQ_ERR_NOMEM, "padding system: out of memory");
    S->con_first = cf;
    S->cap_con = cap_q;
    S->cap_terms = cap_s < cap_c ? cap_s : cap_c;
    for (uint32_t t = 0; t < n; ++t) {
        S->term_side[S->nterms + t] = side[t];
        S->term_coef[S->nterms + t] = coef[t];
    }
    S->nterms = (uint32_t)nt;
    S->con_first[++S->ncon] = S->nterms;
    return SQ_OK;
}

sq_status sq_pad_system_from_pattern(sq_pad_system *S, const sq_pattern *pat,
                                     const int64_t *length, sq_error *err)
{
    if (S->nsides != 0 || S->ncon != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "padding system: not empty");
    sq_status st = sq_pattern_validate(pat, NULL, err);
    if (st != SQ_OK)
        return st;
    uint8_t *flags = calloc(pat->k, 1);
    if (!flags)
        return sq_error_set(err, SQ_ERR_NOMEM, "padding system: out of memory");
    for (uint32_t i = 0; i < pat->k; ++i)
        if (pat->straight && pat->straight[i])
            flags[i] = SQ_PAD_STRAIGHT_START;
    st = sq_pad_system_add_piece(S, pat->k, length, flags, err);
    free(flags);
    for (uint32_t i = 0; i < pat->k && st == SQ_OK; ++i) {
        const uint32_t j = pat->partner[i];
        if (j < i)
            continue;
        const uint32_t sides[2] = {i, j};
        const int32_t coef[2] = {1, -1};
        st = sq_pad_system_add_constraint(S, 2, sides, coef, err);
    }
    return st;
}

/* ---- helpers over the system ------------------------------------------- */

typedef struct pad_ctx {
    const sq_pad_system *S;
    uint32_t n;
    uint32_t *piece_of; /* nsides */
    uint32_t *prev, *next;
    uint32_t ncorner;   /* right-angle corners (prev(s), s) */
    uint32_t *corner_a, *corner_b;
} pad_ctx;

static int straight_start(const sq_pad_system *S, uint32_t s)
{
    return (S->flags[s] & SQ_PAD_STRAIGHT_START) != 0;
}

static sq_status ctx_init(pad_ctx *c, const sq_pad_system *S, sq_error *err)
{
    memset(c, 0, sizeof *c);
    c->S = S;
    c->n = S->nsides;
    const size_t n = S->nsides ? S->nsides : 1;
    c->piece_of = malloc(n * sizeof(uint32_t));
    c->prev = malloc(n * sizeof(uint32_t));
    c->next = malloc(n * sizeof(uint32_t));
    c->corner_a = malloc(n * sizeof(uint32_t));
    c->corner_b = malloc(n * sizeof(uint32_t));
    if (!c->piece_of || !c->prev || !c->next || !c->corner_a || !c->corner_b)
        return sq_error_set(err, SQ_ERR_NOMEM, "padding: out of memory");
    for (uint32_t p = 0; p < S->npieces; ++p) {
        const uint32_t a = S->piece_first[p], b = S->piece_first[p + 1];
        for (uint32_t s = a; s < b; ++s) {
            c->piece_of[s] = p;
            c->prev[s] = s == a ? b - 1 : s - 1;
            c->next[s] = s + 1 == b ? a : s + 1;
        }
    }
    for (uint32_t s = 0; s < S->nsides; ++s)
        if (!straight_start(S, s)) {
            c->corner_a[c->ncorner] = c->prev[s];
            c->corner_b[c->ncorner++] = s;
        }
    return SQ_OK;
}

static void ctx_free(pad_ctx *c)
{
    free(c->piece_of);
    free(c->prev);
    free(c->next);
    free(c->corner_a);
    free(c->corner_b);
}

static sq_status check_system(const sq_pad_system *S, sq_error *err)
{
    if (S->nsides == 0 || S->npieces == 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "padding system: no sides");
    for (uint32_t t = 0; t < S->nterms; ++t)
        if (S->term_side[t] >= S->nsides)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "padding system: a constraint names side %u of %u",
                                S->term_side[t], S->nsides);
    for (uint32_t p = 0; p < S->npieces; ++p) {
        const uint32_t a = S->piece_first[p], b = S->piece_first[p + 1];
        uint32_t right = 0;
        for (uint32_t s = a; s < b; ++s)
            right += !straight_start(S, s);
        if (right == 0)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "padding system: piece %u has no right-angle corner", p);
    }
    return SQ_OK;
}

/* ---- final lengths and the objective ----------------------------------- */

sq_status sq_pad_final_lengths(const sq_pad_system *S, uint64_t d, const int64_t *w,
                               int64_t *final_length, sq_error *err)
{
    if (d > INT64_MAX)
        return sq_error_set(err, SQ_ERR_INTERNAL, "padding: refinement %llu too large",
                            (unsigned long long)d);
    for (uint32_t p = 0; p < S->npieces; ++p) {
        const uint32_t a = S->piece_first[p], b = S->piece_first[p + 1];
        for (uint32_t s = a; s < b; ++s) {
            const uint32_t pv = s == a ? b - 1 : s - 1, nx = s + 1 == b ? a : s + 1;
            int64_t v;
            int ovf = __builtin_mul_overflow(S->length[s], (int64_t)d, &v);
            if (!straight_start(S, s))
                ovf |= __builtin_add_overflow(v, w[pv], &v);
            if (!straight_start(S, nx))
                ovf |= __builtin_add_overflow(v, w[nx], &v);
            if (ovf)
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "padding: final length of side %u overflows 64 bits", s);
            final_length[s] = v;
        }
    }
    return SQ_OK;
}

sq_status sq_pad_added_quads(const sq_pad_system *S, uint64_t d, const int64_t *w,
                             uint64_t *quads, sq_error *err)
{
    mpz_t acc, t, u;
    mpz_init(acc);
    mpz_init(t);
    mpz_init(u);
    for (uint32_t p = 0; p < S->npieces; ++p) {
        const uint32_t a = S->piece_first[p], b = S->piece_first[p + 1];
        for (uint32_t s = a; s < b; ++s) {
            const uint32_t pv = s == a ? b - 1 : s - 1;
            /* strip: w_s x (d L_s) */
            mpz_set_si(t, (long)w[s]);
            mpz_set_si(u, (long)S->length[s]);
            mpz_mul_ui(u, u, (unsigned long)d);
            mpz_addmul(acc, t, u);
            /* corner square at a right-angle corner */
            if (!straight_start(S, s)) {
                mpz_set_si(u, (long)w[pv]);
                mpz_addmul(acc, t, u);
            }
        }
    }
    sq_status st = SQ_OK;
    if (mpz_sgn(acc) < 0 || mpz_sizeinbase(acc, 2) > 64)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "padding: added quad count %s",
                          mpz_sgn(acc) < 0 ? "negative (w < 0)" : "exceeds 64 bits");
    else
        *quads = (uint64_t)mpz_get_ui(acc);
    mpz_clear(acc);
    mpz_clear(t);
    mpz_clear(u);
    return st;
}

/* ---- integral descent on the added-quad count (seed 9.3) ---------------- */

/* Change of the objective for w -> w + t v: t a + t^2 b. Returns 0 on
 * overflow. */
static int move_coeffs(const pad_ctx *c, const int64_t *dL, const int64_t *w, const int64_t *v,
                       int64_t *a, int64_t *b)
{
    int64_t A = 0, B = 0, x;
    int ovf = 0;
    for (uint32_t s = 0; s < c->n; ++s) {
        if (v[s] == 0)
            continue;
        ovf |= __builtin_mul_overflow(v[s], dL[s], &x);
        ovf |= __builtin_add_overflow(A, x, &A);
    }
    for (uint32_t k = 0; k < c->ncorner; ++k) {
        const uint32_t p = c->corner_a[k], s = c->corner_b[k];
        if (v[p] == 0 && v[s] == 0)
            continue;
        ovf |= __builtin_mul_overflow(w[p], v[s], &x);
        ovf |= __builtin_add_overflow(A, x, &A);
        ovf |= __builtin_mul_overflow(v[p], w[s], &x);
        ovf |= __builtin_add_overflow(A, x, &A);
        ovf |= __builtin_mul_overflow(v[p], v[s], &x);
        ovf |= __builtin_add_overflow(B, x, &B);
    }
    *a = A;
    *b = B;
    return !ovf;
}

static int delta_at(int64_t t, int64_t a, int64_t b, int64_t *delta)
{
    int64_t x, y;
    if (__builtin_mul_overflow(t, a, &x) || __builtin_mul_overflow(t, t, &y) ||
        __builtin_mul_overflow(y, b, &y) || __builtin_add_overflow(x, y, &x))
        return 0;
    *delta = x;
    return 1;
}

/* Steepest descent: repeatedly applies the move +-v (v among the nmove
 * null-space vectors, t >= 1 integral, w + t v >= 0) that lowers the
 * objective most. Every move keeps A w = b and integrality. */
static uint32_t descend(const pad_ctx *c, const int64_t *dL, int64_t *w, const int64_t *moves,
                        uint32_t nmove, uint32_t max_steps)
{
    const uint32_t n = c->n;
    uint32_t steps = 0;
    while (steps < max_steps) {
        int64_t best = 0, best_t = 0;
        uint32_t best_m = 0;
        int best_sign = 0;
        for (uint32_t mv = 0; mv < nmove; ++mv) {
            const int64_t *v = moves + (size_t)mv * n;
            for (int sign = -1; sign <= 1; sign += 2) {
                /* largest step keeping w >= 0 */
                int64_t tmax = INT64_MAX;
                for (uint32_t s = 0; s < n; ++s) {
                    const int64_t vs = sign * v[s];
                    if (vs < 0) {
                        const int64_t lim = w[s] / -vs;
                        if (lim < tmax)
                            tmax = lim;
                    }
                }
                if (tmax == INT64_MAX || tmax == 0)
                    continue; /* v >= 0 never lowers the count; or blocked */
                int64_t a, b;
                if (!move_coeffs(c, dL, w, v, &a, &b))
                    continue;
                if (sign < 0)
                    a = -a; /* (-v): a -> -a, b unchanged */
                int64_t cand[4] = {1, tmax, 1, 1};
                uint32_t nc = 2;
                if (b > 0) {
                    const int64_t t0 = -a / (2 * b);
                    cand[nc++] = t0 < 1 ? 1 : (t0 > tmax ? tmax : t0);
                    cand[nc++] = t0 + 1 < 1 ? 1 : (t0 + 1 > tmax ? tmax : t0 + 1);
                }
                for (uint32_t q = 0; q < nc; ++q) {
                    int64_t dlt;
                    if (delta_at(cand[q], a, b, &dlt) && dlt < best) {
                        best = dlt;
                        best_t = cand[q];
                        best_m = mv;
                        best_sign = sign;
                    }
                }
            }
        }
        if (best >= 0)
            break;
        const int64_t *v = moves + (size_t)best_m * n;
        for (uint32_t s = 0; s < n; ++s)
            w[s] += best_sign * best_t * v[s];
        ++steps;
    }
    return steps;
}

/* Integral repair for the LP path (forced zeros, several pieces): moves the
 * integral solution w along integral null-space vectors to lower its total
 * negativity sum_s max(0, -w_s), trying for each move the step sizes that
 * make one negative entry zero. Returns 1 if it reaches w >= 0. A
 * heuristic: on failure the caller refines instead (exact, but maybe a
 * larger d than necessary). */
static int64_t negativity(const int64_t *w, uint32_t n)
{
    int64_t g = 0;
    for (uint32_t s = 0; s < n; ++s)
        if (w[s] < 0)
            g -= w[s];
    return g;
}

static int repair(uint32_t n, int64_t *w, const int64_t *moves, uint32_t nmove, int64_t *scratch,
                  uint32_t max_steps)
{
    int64_t g = negativity(w, n);
    for (uint32_t step = 0; g > 0 && step < max_steps; ++step) {
        int64_t best = g, best_t = 0;
        uint32_t best_m = 0;
        for (uint32_t mv = 0; mv < nmove; ++mv) {
            const int64_t *v = moves + (size_t)mv * n;
            for (int sign = -1; sign <= 1; sign += 2)
                for (uint32_t s0 = 0; s0 <= n; ++s0) {
                    int64_t t = 1;
                    if (s0 < n) {
                        const int64_t vs = sign * v[s0];
                        if (w[s0] >= 0 || vs <= 0)
                            continue;
                        t = (-w[s0] + vs - 1) / vs;
                    }
                    int ok = 1;
                    for (uint32_t s = 0; s < n && ok; ++s) {
                        int64_t x;
                        ok = !__builtin_mul_overflow(sign * t, v[s], &x) &&
                             !__builtin_add_overflow(w[s], x, &scratch[s]);
                    }
                    if (!ok)
                        continue;
                    const int64_t gn = negativity(scratch, n);
                    if (gn < best) {
                        best = gn;
                        best_t = sign * t;
                        best_m = mv;
                    }
                }
        }
        if (best >= g)
            return 0;
        const int64_t *v = moves + (size_t)best_m * n;
        for (uint32_t s = 0; s < n; ++s)
            w[s] += best_t * v[s];
        g = best;
    }
    return g == 0;
}

/* ---- the solve ---------------------------------------------------------- */

typedef struct gmp_arrays {
    uint32_t m, n;
    mpz_t *M, *r, *rd, *cert, *kernel, *lattice, *w0, *ones, *cost;
    mpq_t *basic, *vertex;
    mpz_t den, tmp;
} gmp_arrays;

static mpz_t *zalloc(size_t k)
{
    mpz_t *a = malloc((k ? k : 1) * sizeof *a);
    if (a)
        for (size_t i = 0; i < k; ++i)
            mpz_init(a[i]);
    return a;
}

static mpq_t *qalloc(size_t k)
{
    mpq_t *a = malloc((k ? k : 1) * sizeof *a);
    if (a)
        for (size_t i = 0; i < k; ++i)
            mpq_init(a[i]);
    return a;
}

static void zfree(mpz_t *a, size_t k)
{
    if (!a)
        return;
    for (size_t i = 0; i < k; ++i)
        mpz_clear(a[i]);
    free(a);
}

static void qfree(mpq_t *a, size_t k)
{
    if (!a)
        return;
    for (size_t i = 0; i < k; ++i)
        mpq_clear(a[i]);
    free(a);
}

static void gmp_free(gmp_arrays *g)
{
    const size_t m = g->m, n = g->n;
    zfree(g->M, m * n);
    zfree(g->r, m);
    zfree(g->rd, m);
    zfree(g->cert, m);
    zfree(g->kernel, n * n);
    zfree(g->lattice, n * n);
    zfree(g->w0, n);
    zfree(g->ones, n);
    zfree(g->cost, n);
    qfree(g->basic, n);
    qfree(g->vertex, n);
    mpz_clear(g->den);
    mpz_clear(g->tmp);
}

/* Rows: one per constraint, one per forced zero, one per straight tie. */
static void build_rows(const pad_ctx *c, gmp_arrays *g)
{
    const sq_pad_system *S = c->S;
    const uint32_t n = c->n;
    uint32_t row = 0;
    for (uint32_t k = 0; k < S->ncon; ++k, ++row) {
        for (uint32_t t = S->con_first[k]; t < S->con_first[k + 1]; ++t) {
            const uint32_t s = S->term_side[t];
            const long a = S->term_coef[t];
            /* L'_s = L_s + w_prev [right corner] + w_next [right corner] */
            if (!straight_start(S, s)) {
                mpz_set_si(g->tmp, a);
                mpz_add(g->M[(size_t)row * n + c->prev[s]], g->M[(size_t)row * n + c->prev[s]],
                        g->tmp);
            }
            if (!straight_start(S, c->next[s])) {
                mpz_set_si(g->tmp, a);
                mpz_add(g->M[(size_t)row * n + c->next[s]], g->M[(size_t)row * n + c->next[s]],
                        g->tmp);
            }
            mpz_set_si(g->tmp, (long)S->length[s]);
            mpz_mul_si(g->tmp, g->tmp, a);
            mpz_sub(g->r[row], g->r[row], g->tmp);
        }
    }
    for (uint32_t s = 0; s < n; ++s)
        if (S->flags[s] & SQ_PAD_ZERO)
            mpz_set_ui(g->M[(size_t)row++ * n + s], 1);
    for (uint32_t s = 0; s < n; ++s)
        if (straight_start(S, s)) {
            mpz_set_si(g->M[(size_t)row * n + c->prev[s]], 1);
            mpz_sub_ui(g->M[(size_t)row * n + s], g->M[(size_t)row * n + s], 1);
            ++row;
        }
    assert(row == g->m);
}

/* Message for an inconsistent system: the invariant sum_s c_s L_s that the
 * lengths violate (c from the certificate over the constraint rows). */
static sq_status invariant_message(const pad_ctx *c, gmp_arrays *g, uint32_t rank,
                                   sq_error *err)
{
    const sq_pad_system *S = c->S;
    mpz_t *coef = zalloc(c->n);
    if (!coef)
        return sq_error_set(err, SQ_ERR_NOMEM, "padding: out of memory");
    mpz_t val;
    mpz_init(val);
    for (uint32_t k = 0; k < S->ncon; ++k)
        for (uint32_t t = S->con_first[k]; t < S->con_first[k + 1]; ++t) {
            mpz_set_si(g->tmp, S->term_coef[t]);
            mpz_addmul(coef[S->term_side[t]], g->cert[k], g->tmp);
        }
    for (uint32_t s = 0; s < c->n; ++s) {
        mpz_set_si(g->tmp, (long)S->length[s]);
        mpz_addmul(val, coef[s], g->tmp);
    }
    char buf[600];
    size_t len = 0;
    buf[0] = 0;
    uint32_t shown = 0;
    for (uint32_t s = 0; s < c->n && len + 40 < sizeof buf; ++s) {
        if (mpz_sgn(coef[s]) == 0)
            continue;
        if (!mpz_fits_slong_p(coef[s]))
            continue;
        int w = snprintf(buf + len, sizeof buf - len, "%s%+ld*L%u", shown ? " " : "",
                         mpz_get_si(coef[s]), s);
        if (w < 0)
            break;
        len += (size_t)w;
        ++shown;
    }
    char *vs = mpz_get_str(NULL, 10, val);
    sq_status st = sq_error_set(
        err, SQ_ERR_ARGUMENT,
        "padding cannot equalize the sides: the lengths violate an invariant of padding, "
        "%s = %s instead of 0 (rank %u of %u equations)",
        buf, vs ? vs : "?", rank, g->m);
    free(vs);
    mpz_clear(val);
    zfree(coef, c->n);
    return st;
}

static int z_to_i64(const mpz_t z, int64_t *out)
{
    if (!mpz_fits_slong_p(z) || sizeof(long) < 8)
        return 0;
    *out = (int64_t)mpz_get_si(z);
    return 1;
}

/* state shared by the steps of sq_pad_solve */
typedef struct pad_solve {
    const sq_pad_system *S;
    sq_pad_result *res;
    pad_ctx *c;
    gmp_arrays *g;
    unsigned flags;
    uint32_t n, rank, max_steps;
    uint32_t nmove;                    /* integral null-space moves in moves */
    int64_t *w, *best, *moves, *dL;
    int lp_integral;                   /* the LP vertex is a second start */
} pad_solve;

/* 1. over Q: rank, feasibility, the basic solution (seed 6.3's w) */
static sq_status solve_rational(pad_solve *p, sq_error *err)
{
    gmp_arrays *g = p->g;
    sq_pad_result *res = p->res;
    const uint32_t n = p->n;
    int consistent = 0;
    uint32_t rank = 0;
    sq_status st = sq_padding_rational(g->m, n, g->M, g->r, &rank, &consistent, g->cert,
                                       g->basic, g->kernel, err);
    if (st != SQ_OK)
        return st;
    res->rank = rank;
    p->rank = rank;
    if (!consistent) {
        res->outcome = SQ_PAD_INFEASIBLE_INVARIANT;
        return invariant_message(p->c, g, rank, err);
    }
    mpz_set_ui(g->den, 1);
    for (uint32_t s = 0; s < n; ++s)
        mpz_lcm(g->den, g->den, mpq_denref(g->basic[s]));
    if (!mpz_fits_ulong_p(g->den))
        return sq_error_set(err, SQ_ERR_INTERNAL, "padding: denominator exceeds 64 bits");
    res->rational_den = mpz_get_ui(g->den);
    return SQ_OK;
}

/* 2. over Z: an integral solution, or the least refinement d */
static sq_status solve_integral(pad_solve *p, sq_error *err)
{
    gmp_arrays *g = p->g;
    const uint32_t n = p->n;
    sq_status st;
    uint32_t rank2 = 0;
    if (p->flags & SQ_PAD_OPT_NO_INTEGRAL_SEARCH) {
        /* the seed's rule: d = lcm of the basic solution's denominators */
        for (uint32_t s = 0; s < n; ++s) {
            mpz_divexact(g->tmp, g->den, mpq_denref(g->basic[s]));
            mpz_mul(g->w0[s], g->tmp, mpq_numref(g->basic[s]));
        }
        st = sq_padding_lattice(g->m, n, g->M, g->r, g->tmp, g->ones, &rank2, g->lattice, err);
        /* (g.tmp, g.ones reused as scratch; only the lattice is kept) */
    } else {
        st = sq_padding_lattice(g->m, n, g->M, g->r, g->den, g->w0, &rank2, g->lattice, err);
    }
    if (st != SQ_OK)
        return st;
    assert(rank2 == p->rank);
    if (!mpz_fits_ulong_p(g->den))
        return sq_error_set(err, SQ_ERR_INTERNAL, "padding: refinement exceeds 64 bits");
    p->res->d = mpz_get_ui(g->den);
    for (uint32_t i = 0; i < g->m; ++i)
        mpz_mul(g->rd[i], g->r[i], g->den);
    return SQ_OK;
}

/* integral null-space moves (independent of d): the rows of the rational
 * kernel and of the lattice that fit in 32 bits */
static void null_space_moves(pad_solve *p)
{
    const gmp_arrays *g = p->g;
    const uint32_t n = p->n;
    int64_t *moves = p->moves;
    uint32_t nmove = 0;
    const uint32_t kdim = n - p->rank;
    for (uint32_t src = 0; src < 2; ++src) {
        const mpz_t *K = src == 0 ? (const mpz_t *)g->kernel : (const mpz_t *)g->lattice;
        for (uint32_t j = 0; j < kdim; ++j) {
            int64_t *v = moves + (size_t)nmove * n;
            int ok = 1;
            for (uint32_t s = 0; s < n && ok; ++s)
                ok = z_to_i64(K[(size_t)j * n + s], &v[s]) && v[s] < ((int64_t)1 << 31) &&
                     v[s] > -((int64_t)1 << 31);
            if (ok)
                ++nmove;
        }
    }
    p->nmove = nmove;
}

/* 3. nonnegativity, first part: whether the all-ones vector (over the sides
 * not forced to zero) is in the kernel; if so, shifts w0 to w0 >= 0 and adds
 * the ones as a move. Returns whether it is. */
static int shift_start(pad_solve *p)
{
    const sq_pad_system *S = p->S;
    gmp_arrays *g = p->g;
    const uint32_t n = p->n;
    int ones_in_kernel = 1;
    for (uint32_t s = 0; s < n; ++s)
        mpz_set_ui(g->ones[s], (S->flags[s] & SQ_PAD_ZERO) ? 0 : 1);
    for (uint32_t i = 0; i < g->m && ones_in_kernel; ++i) {
        mpz_set_ui(g->tmp, 0);
        for (uint32_t s = 0; s < n; ++s)
            if (mpz_sgn(g->ones[s]))
                mpz_add(g->tmp, g->tmp, g->M[(size_t)i * n + s]);
        ones_in_kernel = mpz_sgn(g->tmp) == 0;
    }
    if (ones_in_kernel) {
        /* seamless-notes 3: w + c 1 solves the system for every c */
        mpz_set_ui(g->tmp, 0);
        for (uint32_t s = 0; s < n; ++s)
            if (mpz_sgn(g->ones[s]) && mpz_cmp(g->w0[s], g->tmp) < 0)
                mpz_set(g->tmp, g->w0[s]);
        for (uint32_t s = 0; s < n; ++s)
            if (mpz_sgn(g->ones[s]))
                mpz_sub(g->w0[s], g->w0[s], g->tmp);
        p->res->used_shift = 1;
        int64_t *v = p->moves + (size_t)p->nmove * n;
        for (uint32_t s = 0; s < n; ++s)
            v[s] = mpz_get_si(g->ones[s]);
        ++p->nmove;
    }
    return ones_in_kernel;
}

/* 3. nonnegativity, second part: the exact LP's vertex; a start from it
 * (repairing the lattice solution or refining d) unless one exists, and
 * p->lp_integral if the vertex remains a second start */
static sq_status lp_start(pad_solve *p, int ones_in_kernel, int *have_start, sq_error *err)
{
    const sq_pad_system *S = p->S;
    gmp_arrays *g = p->g;
    sq_pad_result *res = p->res;
    const uint32_t n = p->n;
    int64_t *w = p->w;
    for (uint32_t s = 0; s < n; ++s) {
        mpz_set_si(g->cost[s], (long)S->length[s]);
        mpz_mul(g->cost[s], g->cost[s], g->den);
        mpz_add_ui(g->cost[s], g->cost[s], 1);
    }
    int feasible = 0;
    sq_status st = sq_padding_lp(g->m, n, g->M, g->rd, g->cost, &feasible, g->vertex, err);
    if (st != SQ_OK)
        return st;
    (void)ones_in_kernel; /* only in the assertion below */
    if (!feasible) {
        assert(!ones_in_kernel);
        res->outcome = SQ_PAD_INFEASIBLE_NONNEGATIVE;
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "padding cannot equalize the sides: the equations have rational "
                            "solutions (rank %u of %u) but none with every padding w >= 0 "
                            "(exact LP; forced-zero or split sides bind)",
                            p->rank, g->m);
    }
    mpz_set_ui(g->tmp, 1);
    for (uint32_t s = 0; s < n; ++s)
        mpz_lcm(g->tmp, g->tmp, mpq_denref(g->vertex[s]));
    int lp_integral = mpz_cmp_ui(g->tmp, 1) == 0;
    if (!*have_start && !lp_integral) {
        /* an integral point may exist although the vertex is
         * fractional: try to repair the lattice solution first */
        int fits = 1;
        for (uint32_t s = 0; s < n && fits; ++s)
            fits = z_to_i64(g->w0[s], &w[s]);
        if (fits && n <= 128 && repair(n, w, p->moves, p->nmove, p->best, 1000)) {
            for (uint32_t s = 0; s < n; ++s)
                mpz_set_si(g->w0[s], (long)w[s]);
            *have_start = 1;
        }
    }
    if (!*have_start) {
        if (!lp_integral) {
            /* refine further: D v is integral and solves the system
             * for lengths scaled by d D (seed 6.3's argument) */
            mpz_mul(g->den, g->den, g->tmp);
            if (!mpz_fits_ulong_p(g->den))
                return sq_error_set(err, SQ_ERR_INTERNAL, "padding: refinement overflow");
            res->d = mpz_get_ui(g->den);
        }
        for (uint32_t s = 0; s < n; ++s) {
            mpz_divexact(g->w0[s], g->tmp, mpq_denref(g->vertex[s]));
            mpz_mul(g->w0[s], g->w0[s], mpq_numref(g->vertex[s]));
        }
        res->used_lp = 1;
        *have_start = 1;
        lp_integral = 0; /* already used as the start */
    }
    p->lp_integral = lp_integral;
    return SQ_OK;
}

/* the start w0 as 64-bit w, and the refined lengths d L */
static sq_status start_to_int64(pad_solve *p, sq_error *err)
{
    const sq_pad_system *S = p->S;
    for (uint32_t s = 0; s < p->n; ++s) {
        if (!z_to_i64(p->g->w0[s], &p->w[s]))
            return sq_error_set(err, SQ_ERR_INTERNAL, "padding: w_%u exceeds 64 bits", s);
        assert(p->w[s] >= 0);
        if (__builtin_mul_overflow(S->length[s], (int64_t)p->res->d, &p->dL[s]))
            return sq_error_set(err, SQ_ERR_INTERNAL, "padding: refined length overflows");
    }
    return SQ_OK;
}

/* 4. descent over integral null-space moves, from w and (if it is a second
 * start) from the LP vertex; w becomes the better */
static sq_status descend_starts(pad_solve *p, sq_error *err)
{
    const sq_pad_system *S = p->S;
    const gmp_arrays *g = p->g;
    sq_pad_result *res = p->res;
    const uint32_t n = p->n;
    int64_t *w = p->w, *best = p->best;
    if (!(p->flags & SQ_PAD_OPT_NO_DESCENT))
        res->descent_steps = descend(p->c, p->dL, w, p->moves, p->nmove, p->max_steps);
    sq_status st = sq_pad_added_quads(S, res->d, w, &res->added_quads, err);
    if (st != SQ_OK)
        return st;
    if (p->lp_integral) {
        /* second start: the LP vertex (same d), descended; keep the better */
        for (uint32_t s = 0; s < n; ++s) {
            if (!z_to_i64(mpq_numref(g->vertex[s]), &best[s]))
                return sq_error_set(err, SQ_ERR_INTERNAL, "padding: LP vertex exceeds 64 bits");
        }
        uint32_t steps = 0;
        if (!(p->flags & SQ_PAD_OPT_NO_DESCENT))
            steps = descend(p->c, p->dL, best, p->moves, p->nmove, p->max_steps);
        uint64_t q2 = 0;
        st = sq_pad_added_quads(S, res->d, best, &q2, err);
        if (st != SQ_OK)
            return st;
        if (q2 < res->added_quads) {
            memcpy(w, best, (size_t)n * sizeof *w);
            res->added_quads = q2;
            res->descent_steps = steps;
            res->used_lp = 1;
        }
    }
    return SQ_OK;
}

sq_status sq_pad_solve(const sq_pad_system *S, const sq_pad_options *opt, sq_pad_result *res,
                       sq_error *err)
{
    int64_t *user_w = res->w, *user_len = res->final_length;
    memset(res, 0, sizeof *res);
    res->w = user_w;
    res->final_length = user_len;
    res->d = 1;
    res->rational_den = 1;
    sq_status st = check_system(S, err);
    if (st != SQ_OK)
        return st;
    const unsigned flags = opt ? opt->flags : 0;
    const uint32_t max_steps = opt && opt->max_descent_steps ? opt->max_descent_steps : 100000;
    pad_ctx c;
    st = ctx_init(&c, S, err);
    const uint32_t n = S->nsides;
    uint32_t nzero = 0, nstraight = 0;
    for (uint32_t s = 0; s < n; ++s) {
        nzero += (S->flags[s] & SQ_PAD_ZERO) != 0;
        nstraight += straight_start(S, s);
    }
    gmp_arrays g;
    memset(&g, 0, sizeof g);
    mpz_init(g.den);
    mpz_init(g.tmp);
    g.m = S->ncon + nzero + nstraight;
    g.n = n;
    int64_t *w = NULL, *best = NULL, *moves = NULL, *dL = NULL;
    if (st != SQ_OK)
        goto done;
    const size_t m = g.m;
    g.M = zalloc(m * n);
    g.r = zalloc(m);
    g.rd = zalloc(m);
    g.cert = zalloc(m);
    g.kernel = zalloc((size_t)n * n);
    g.lattice = zalloc((size_t)n * n);
    g.w0 = zalloc(n);
    g.ones = zalloc(n);
    g.cost = zalloc(n);
    g.basic = qalloc(n);
    g.vertex = qalloc(n);
    w = malloc((size_t)n * sizeof *w);
    best = malloc((size_t)n * sizeof *best);
    dL = malloc((size_t)n * sizeof *dL);
    moves = malloc(((size_t)2 * n + 1) * n * sizeof *moves);
    if (!g.M || !g.r || !g.rd || !g.cert || !g.kernel || !g.lattice || !g.w0 || !g.ones ||
        !g.cost || !g.basic || !g.vertex || !w || !best || !dL || !moves) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "padding: out of memory (%u sides)", n);
        goto done;
    }
    build_rows(&c, &g);
    res->equations = g.m;

    pad_solve p = {.S = S, .res = res, .c = &c, .g = &g, .flags = flags, .n = n,
                   .max_steps = max_steps, .w = w, .best = best, .moves = moves, .dL = dL};
    if ((st = solve_rational(&p, err)) != SQ_OK || (st = solve_integral(&p, err)) != SQ_OK)
        goto done;
    null_space_moves(&p);

    /* 3. nonnegativity */
    const int ones_in_kernel = shift_start(&p);
    int have_start = ones_in_kernel;
    if (!ones_in_kernel || !(flags & SQ_PAD_OPT_NO_LP_START)) {
        st = lp_start(&p, ones_in_kernel, &have_start, err);
        if (st != SQ_OK)
            goto done;
    }
    assert(have_start);
    if ((st = start_to_int64(&p, err)) != SQ_OK)
        goto done;
    st = sq_pad_added_quads(S, res->d, w, &res->start_quads, err);
    if (st != SQ_OK)
        goto done;

    /* 4. descent over integral null-space moves */
    if ((st = descend_starts(&p, err)) != SQ_OK)
        goto done;
    for (uint32_t s = 0; s < n; ++s)
        assert(w[s] >= 0 && (!(S->flags[s] & SQ_PAD_ZERO) || w[s] == 0));
    if (res->w)
        memcpy(res->w, w, (size_t)n * sizeof *w);
    if (res->final_length) {
        st = sq_pad_final_lengths(S, res->d, w, res->final_length, err);
        if (st != SQ_OK)
            goto done;
#ifndef NDEBUG
        for (uint32_t k = 0; k < S->ncon; ++k) {
            int64_t sum = 0;
            for (uint32_t t = S->con_first[k]; t < S->con_first[k + 1]; ++t)
                sum += S->term_coef[t] * res->final_length[S->term_side[t]];
            assert(sum == 0);
        }
#endif
    }
    res->outcome = SQ_PAD_SOLVED;
    st = SQ_OK;
done:
    free(w);
    free(best);
    free(dL);
    free(moves);
    gmp_free(&g);
    ctx_free(&c);
    return st;
}

sq_status sq_pad_solve_pattern(const sq_pattern *pat, const int64_t *length,
                               const sq_pad_options *opt, sq_pad_result *res, sq_error *err)
{
    sq_pad_system S;
    sq_pad_system_init(&S);
    sq_status st = sq_pad_system_from_pattern(&S, pat, length, err);
    if (st == SQ_OK) {
        st = sq_pad_solve(&S, opt, res, err);
        if (st == SQ_ERR_ARGUMENT && res->outcome == SQ_PAD_INFEASIBLE_INVARIANT) {
            int64_t vx, vy;
            sq_pattern_closure(pat, length, &vx, &vy);
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "padding cannot equalize this pattern: the closure vector "
                              "V = sum_i L_i w^i = (%lld, %lld) is a padding invariant, and the "
                              "pairs' directions u_p span rank %u < 2, so V must lie on their "
                              "line (seamless-notes 7); use a slide or more pieces",
                              (long long)vx, (long long)vy, sq_pattern_rank(pat));
        }
    }
    sq_pad_system_free(&S);
    return st;
}
