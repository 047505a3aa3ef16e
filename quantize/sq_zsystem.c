/* seamquad: the Newton system of an energy summed over triangles, in the
 * unknowns z of a basis of seamless maps (sq_optimize_internal.h).
 *
 * The corners are he_uv = c + P z (sq_uv_basis.h). A triangle's gradient g
 * and Hessian H in its six corner coordinates pull back to z as P^T g and
 * P^T H P. The pattern of the sum (lower triangle, CSR by row, columns
 * sorted) is built once from the faces' rows of P, with, for each face,
 * the positions of the entries it adds to (when they fit SQ_ZSYS_SLOTS);
 * each assembly adds into it; each solve refactors the same symbolic
 * factorization (CHOLMOD, sq_sparse.h). Used by the optimizer
 * (sq_optimize.c), the field fit (sq_map_from_rotations.c) and the
 * untangler (sq_map_untangle.c).
 *
 * Cost: the pattern about 14 entries per pair of unknowns, the positions
 * about 21 per face; one sparse Cholesky per solve. */
#include <stdlib.h>
#include <string.h>

#include "sq_optimize_internal.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

sq_status sq_zsys_init(sq_zsys *S, const sq_mesh *m, const sq_uv_basis *B, sq_error *err)
{
    memset(S, 0, sizeof *S);
    S->m = m;
    S->B = B;
    uint32_t nz = B->nz;
    uint32_t maxrow = 0;
    for (uint32_t k = 0; k < B->ncoord; k++)
        if (B->row_off[k + 1] - B->row_off[k] > maxrow) maxrow = B->row_off[k + 1] - B->row_off[k];
    size_t *cnt = calloc((size_t)nz + 1, sizeof *cnt);
    uint32_t *cols = malloc((6 * (size_t)maxrow + 1) * sizeof *cols);
    if (!cnt || !cols) {
        free(cnt);
        free(cols);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Hessian pattern)");
    }
    /* pass 0 counts, pass 1 fills (with repeats), then sort and unique */
    uint32_t *fill = NULL, *pos = NULL;
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t f = 0; f < m->nf; f++) {
            uint32_t hc[3];
            sq_face_corners(m, f, hc);
            uint32_t n = 0;
            for (int c = 0; c < 3; c++)
                for (int a = 0; a < 2; a++) {
                    size_t k = 2 * (size_t)hc[c] + a;
                    for (uint32_t j = B->row_off[k]; j < B->row_off[k + 1]; j++) {
                        uint32_t q = B->col[j], i;
                        for (i = 0; i < n && cols[i] != q; i++) {}
                        if (i == n) cols[n++] = q;
                    }
                }
            for (uint32_t i = 0; i < n; i++)
                for (uint32_t j = 0; j < n; j++) {
                    if (cols[j] > cols[i]) continue;
                    if (pass == 0) cnt[cols[i]]++;
                    else fill[pos[cols[i]]++] = cols[j];
                }
        }
        if (pass == 0) {
            pos = malloc(((size_t)nz + 1) * sizeof *pos);
            size_t s = 0;
            for (uint32_t i = 0; i < nz; i++) {
                size_t c = cnt[i];
                cnt[i] = s;
                s += c;
            }
            cnt[nz] = s;
            total = s;
            if (total >= UINT32_MAX) {
                free(cnt);
                free(cols);
                free(pos);
                return sq_error_set(err, SQ_ERR_ARGUMENT, "Hessian pattern too large");
            }
            fill = malloc((total + 1) * sizeof *fill);
            if (!pos || !fill) {
                free(cnt);
                free(cols);
                free(pos);
                free(fill);
                return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Hessian pattern)");
            }
            for (uint32_t i = 0; i < nz; i++) pos[i] = (uint32_t)cnt[i];
        }
    }
    free(pos);
    free(cols);
    /* sort and unique each row in place */
    S->h_off = malloc(((size_t)nz + 1) * sizeof *S->h_off);
    if (!S->h_off) {
        free(cnt);
        free(fill);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Hessian pattern)");
    }
    uint32_t w = 0;
    for (uint32_t i = 0; i < nz; i++) {
        uint32_t *row = fill + cnt[i];
        size_t len = cnt[i + 1] - cnt[i];
        if (len <= 64) { /* most rows: a vertex's few dozen, with repeats */
            for (size_t a = 1; a < len; a++) {
                uint32_t x = row[a];
                size_t b = a;
                for (; b > 0 && row[b - 1] > x; b--) row[b] = row[b - 1];
                row[b] = x;
            }
        } else {
            qsort(row, len, sizeof *row, cmp_u32);
        }
        S->h_off[i] = w;
        for (size_t j = 0; j < len; j++)
            if (j == 0 || row[j] != row[j - 1]) fill[w++] = row[j];
    }
    S->h_off[nz] = w;
    free(cnt);
    /* the unique entries into an array of their size (fill held repeats) */
    S->h_col = malloc(((size_t)w + 1) * sizeof *S->h_col);
    S->h_val = malloc(((size_t)w + 1) * sizeof *S->h_val);
    if (S->h_col) memcpy(S->h_col, fill, (size_t)w * sizeof *fill);
    free(fill);
    if (!S->h_col || !S->h_val) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Hessian pattern)");
    /* each face's entry positions, in sq_zsys_add_face's order */
    size_t nslot = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t f = 0; f < m->nf; f++) {
            uint32_t hc[3];
            sq_face_corners(m, f, hc);
            if (pass == 1) S->slot_off[f] = nslot;
            for (int k1 = 0; k1 < 6; k1++) {
                size_t r1 = 2 * (size_t)hc[k1 / 2] + k1 % 2;
                for (uint32_t j1 = B->row_off[r1]; j1 < B->row_off[r1 + 1]; j1++)
                    for (int k2 = 0; k2 < 6; k2++) {
                        size_t r2 = 2 * (size_t)hc[k2 / 2] + k2 % 2;
                        for (uint32_t j2 = B->row_off[r2]; j2 < B->row_off[r2 + 1]; j2++) {
                            if (B->col[j2] > B->col[j1]) continue;
                            if (pass == 1) S->slot[nslot] = (uint32_t)(sq_zsys_entry(S, B->col[j1], B->col[j2]) - S->h_val);
                            nslot++;
                        }
                    }
            }
        }
        if (pass == 0) {
            if (nslot > SQ_ZSYS_SLOTS) return SQ_OK; /* searched instead */
            S->slot_off = malloc(((size_t)m->nf + 1) * sizeof *S->slot_off);
            S->slot = malloc((nslot + 1) * sizeof *S->slot);
            if (!S->slot_off || !S->slot) {
                free(S->slot_off), free(S->slot);
                S->slot_off = NULL, S->slot = NULL;
                return SQ_OK; /* searched instead */
            }
            nslot = 0;
        }
    }
    S->slot_off[m->nf] = nslot;
    return SQ_OK;
}

double *sq_zsys_entry(sq_zsys *S, uint32_t i, uint32_t j)
{
    /* i >= j; binary search in row i */
    uint32_t lo = S->h_off[i], hi = S->h_off[i + 1];
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (S->h_col[mid] < j) lo = mid + 1;
        else hi = mid;
    }
    return &S->h_val[lo];
}

void sq_zsys_zero(sq_zsys *S, double *gz)
{
    memset(gz, 0, S->B->nz * sizeof *gz);
    memset(S->h_val, 0, S->h_off[S->B->nz] * sizeof *S->h_val);
}

void sq_zsys_add_face(sq_zsys *S, uint32_t f, const double g[6], const double H[36], double *gz)
{
    const sq_uv_basis *B = S->B;
    uint32_t hc[3];
    sq_face_corners(S->m, f, hc);
    /* the entry positions cached at setup, else searched */
    const uint32_t *sl = S->slot ? S->slot + S->slot_off[f] : NULL;
    for (int k1 = 0; k1 < 6; k1++) {
        size_t r1 = 2 * (size_t)hc[k1 / 2] + k1 % 2;
        for (uint32_t j1 = B->row_off[r1]; j1 < B->row_off[r1 + 1]; j1++) {
            uint32_t c1 = B->col[j1];
            double v1 = B->val[j1];
            gz[c1] += v1 * g[k1];
            for (int k2 = 0; k2 < 6; k2++) {
                size_t r2 = 2 * (size_t)hc[k2 / 2] + k2 % 2;
                for (uint32_t j2 = B->row_off[r2]; j2 < B->row_off[r2 + 1]; j2++) {
                    uint32_t c2 = B->col[j2];
                    if (c2 > c1) continue;
                    double *e = sl ? S->h_val + *sl++ : sq_zsys_entry(S, c1, c2);
                    *e += v1 * H[k1 * 6 + k2] * B->val[j2];
                }
            }
        }
    }
}

void sq_zsys_linear(const sq_uv_basis *B, const double *d, double *out)
{
    for (uint32_t k = 0; k < B->ncoord; k++) {
        double s = 0;
        for (uint32_t j = B->row_off[k]; j < B->row_off[k + 1]; j++) s += B->val[j] * d[B->col[j]];
        out[k] = s;
    }
}

sq_status sq_zsys_solve(sq_zsys *S, const uint8_t *held, const double *gz, double *d, sq_error *err)
{
    uint32_t nz = S->B->nz, nnz = S->h_off[nz];
    if (!S->h_row) {
        S->h_row = malloc(((size_t)nnz + 1) * sizeof *S->h_row);
        if (!S->h_row) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Newton system)");
        for (uint32_t i = 0; i < nz; i++)
            for (uint32_t j = S->h_off[i]; j < S->h_off[i + 1]; j++) S->h_row[j] = i;
    }
    double *rhs = malloc(((size_t)nz + 1) * sizeof *rhs);
    if (!rhs) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Newton system)");
    double diag = 0;
    for (uint32_t i = 0; i < nz; i++) diag += *sq_zsys_entry(S, i, i);
    diag = nz ? diag / nz : 1.0;
    if (!(diag > 0)) diag = 1.0;
    for (uint32_t i = 0; i < nz; i++) rhs[i] = -gz[i];
    if (held) {
        /* a held unknown: its row and column become the identity's, its
         * right-hand side 0, so its step is 0 */
        for (uint32_t i = 0; i < nz; i++)
            for (uint32_t j = S->h_off[i]; j < S->h_off[i + 1]; j++)
                if (held[i] || held[S->h_col[j]]) S->h_val[j] = S->h_col[j] == i ? diag : 0.0;
        for (uint32_t i = 0; i < nz; i++)
            if (held[i]) rhs[i] = 0;
    }
    sq_status st = SQ_ERR_SOLVER;
    for (double mu = 1e-10; mu < 1e2 && st; mu *= 100) {
        for (uint32_t i = 0; i < nz; i++) *sq_zsys_entry(S, i, i) += mu * diag;
        if (S->fac) st = sq_spd_refactor(S->fac, nnz, S->h_row, S->h_col, S->h_val, err);
        else st = sq_spd_factor_auto(nz, nnz, S->h_row, S->h_col, S->h_val, &S->fac, err);
        if (!st) st = sq_spd_solve(S->fac, 1, rhs, d, err);
        for (uint32_t i = 0; i < nz; i++) *sq_zsys_entry(S, i, i) -= mu * diag;
    }
    free(rhs);
    return st;
}

void sq_zsys_free(sq_zsys *S)
{
    free(S->h_off);
    free(S->h_col);
    free(S->h_val);
    free(S->h_row);
    free(S->slot_off);
    free(S->slot);
    sq_spd_free(S->fac);
    memset(S, 0, sizeof *S);
}
