/* seamquad: a T-mesh face re-embedded onto its integer rectangle
 * (sq_patch_embed.h explains the sweep and the Tutte fallback). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_mean_value.h"
#include "sq_patch_embed.h"
#include "sq_predicates.h"
#include "sq_sparse.h"

/* A piecewise linear map through points (x_i, y_i), x increasing. */
typedef struct plmap {
    uint32_t n;
    double *x, *y;
} plmap;

/* by the new coordinate: the boundary's order, set by quantization */
static int cmp_pair(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return (p[1] > q[1]) - (p[1] < q[1]);
}

static double pl_eval(const plmap *F, double x)
{
    if (x <= F->x[0]) return F->y[0];
    if (x >= F->x[F->n - 1]) return F->y[F->n - 1];
    uint32_t lo = 0, hi = F->n - 1; /* x[lo] <= x < x[hi] */
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (F->x[mid] <= x) lo = mid;
        else hi = mid;
    }
    if (F->x[hi] == F->x[lo]) return F->y[lo];
    double w = (x - F->x[lo]) / (F->x[hi] - F->x[lo]);
    return F->y[lo] + w * (F->y[hi] - F->y[lo]);
}

/* The boundary vertices of one side (bit `side` of fixed): key coordinate
 * k (0: u, 1: v); image coordinate `img` of out_uv. */
static sq_status side_map(const sq_patch *P, const double *out_uv, int k, uint8_t side, int img,
                          plmap *F, sq_error *err)
{
    uint32_t n = 0;
    double *buf = malloc(2 * ((size_t)P->nv + 1) * sizeof *buf);
    if (!buf) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (patch sides)");
    for (uint32_t v = 0; v < P->nv; v++) {
        if (!(P->fixed[v] & side)) continue;
        buf[2 * (size_t)n] = P->uv[2 * (size_t)v + k];
        buf[2 * (size_t)n + 1] = out_uv[2 * (size_t)v + img];
        n++;
    }
    if (n < 2) {
        free(buf);
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "patch: a side has %u boundary vertices (its two corners at least "
                            "are needed)",
                            n);
    }
    qsort(buf, n, 2 * sizeof *buf, cmp_pair);
    F->n = n;
    F->x = malloc(n * sizeof *F->x);
    F->y = malloc(n * sizeof *F->y);
    if (!F->x || !F->y) {
        free(buf);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (patch sides)");
    }
    for (uint32_t i = 0; i < n; i++) {
        F->x[i] = buf[2 * (size_t)i];
        F->y[i] = buf[2 * (size_t)i + 1];
        /* the old coordinates follow the same order up to their rounding
         * (computed crossings): made non-decreasing */
        if (i && F->x[i] < F->x[i - 1]) F->x[i] = F->x[i - 1];
        if (i && !(F->y[i] > F->y[i - 1])) {
            free(buf);
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "patch: two boundary vertices of one side share the place %.17g",
                                F->y[i]);
        }
    }
    free(buf);
    return SQ_OK;
}

static uint32_t count_flips(const sq_patch *P, const double *uv)
{
    uint32_t bad = 0;
    for (uint32_t t = 0; t < P->nt; t++) {
        const uint32_t *c = P->tri + 3 * (size_t)t;
        bad += sq_orient2d(uv + 2 * (size_t)c[0], uv + 2 * (size_t)c[1], uv + 2 * (size_t)c[2]) <= 0;
    }
    return bad;
}

static sq_status sweep(const sq_patch *P, double *out_uv, sq_error *err)
{
    plmap F[4];
    memset(F, 0, sizeof F);
    sq_status st;
    if ((st = side_map(P, out_uv, 0, SQ_PATCH_BOTTOM, 0, &F[0], err)) || /* u -> s */
        (st = side_map(P, out_uv, 0, SQ_PATCH_TOP, 0, &F[1], err)) ||
        (st = side_map(P, out_uv, 1, SQ_PATCH_LEFT, 1, &F[2], err)) ||   /* v -> t */
        (st = side_map(P, out_uv, 1, SQ_PATCH_RIGHT, 1, &F[3], err)))
        goto done;
    double a = (double)P->a;
    for (uint32_t v = 0; v < P->nv; v++) {
        if (P->fixed[v]) continue;
        double u = P->uv[2 * (size_t)v], w = P->uv[2 * (size_t)v + 1];
        double tau = fmin(1.0, fmax(0.0, w / P->H));
        double s = (1.0 - tau) * pl_eval(&F[0], u) + tau * pl_eval(&F[1], u);
        double sig = fmin(1.0, fmax(0.0, s / a));
        double t = (1.0 - sig) * pl_eval(&F[2], w) + sig * pl_eval(&F[3], w);
        out_uv[2 * (size_t)v] = s;
        out_uv[2 * (size_t)v + 1] = t;
    }
done:
    for (int i = 0; i < 4; i++) free(F[i].x), free(F[i].y);
    return st;
}

/* Tutte's map: every free vertex a positive combination of its
 * neighbours, the boundary fixed. Mean-value weights (Floater 2003) from
 * the map's own shape (they reproduce an affine map exactly, so a face
 * whose boundary moves little keeps its shape), where a triangle is too
 * thin for them the uniform weight; any positive weights give a bijection
 * onto a convex boundary. mean_value = 0: uniform weights throughout (a
 * symmetric system: CHOLMOD), else UMFPACK. */
static sq_status tutte_solve(const sq_patch *P, double *out_uv, int mean_value, const double *pos,
                             sq_error *err)
{
    uint32_t *id = malloc(((size_t)P->nv + 1) * sizeof *id), nfree = 0;
    size_t cap = 12 * (size_t)P->nt + 1, nnz = 0;
    uint32_t *ri = malloc(cap * sizeof *ri), *ci = malloc(cap * sizeof *ci);
    double *val = malloc(cap * sizeof *val);
    double *rhs = NULL, *x = NULL;
    sq_spd *f = NULL;
    sq_lu *lu = NULL;
    sq_status st = SQ_OK;
    if (!id || !ri || !ci || !val) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (patch Tutte map)");
        goto done;
    }
    for (uint32_t v = 0; v < P->nv; v++) id[v] = P->fixed[v] ? UINT32_MAX : nfree++;
    if (!nfree) goto done;
    rhs = calloc(2 * (size_t)nfree, sizeof *rhs);
    x = malloc(2 * (size_t)nfree * sizeof *x);
    if (!rhs || !x) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (patch Tutte map)");
        goto done;
    }
    for (uint32_t t = 0; t < P->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t i = P->tri[3 * (size_t)t + k];
            if (id[i] == UINT32_MAX) continue;
            uint32_t nb[2] = {P->tri[3 * (size_t)t + (k + 1) % 3], P->tri[3 * (size_t)t + (k + 2) % 3]};
            double half_tan = 0;
            double pi[3], pa[3], pb[3];
            if (mean_value) {
                for (int c = 0; c < 3; c++) {
                    pi[c] = pos ? pos[3 * (size_t)i + c] : c < 2 ? P->uv[2 * (size_t)i + c] : 0;
                    pa[c] = pos ? pos[3 * (size_t)nb[0] + c] : c < 2 ? P->uv[2 * (size_t)nb[0] + c] : 0;
                    pb[c] = pos ? pos[3 * (size_t)nb[1] + c] : c < 2 ? P->uv[2 * (size_t)nb[1] + c] : 0;
                }
                half_tan = sq_half_tan(pi, pa, pb);
            }
            for (int e = 0; e < 2; e++) {
                uint32_t j = nb[e];
                double w = 1.0;
                if (mean_value) {
                    const double *q = e ? pb : pa;
                    double d = sqrt((q[0] - pi[0]) * (q[0] - pi[0]) + (q[1] - pi[1]) * (q[1] - pi[1]) +
                                    (q[2] - pi[2]) * (q[2] - pi[2]));
                    w = half_tan / d;
                    if (!(w > 0) || !isfinite(w)) w = 1.0;
                }
                ri[nnz] = ci[nnz] = id[i], val[nnz++] = w;
                if (id[j] != UINT32_MAX) {
                    ri[nnz] = id[i], ci[nnz] = id[j], val[nnz++] = -w;
                } else {
                    rhs[id[i]] += w * out_uv[2 * (size_t)j];
                    rhs[nfree + id[i]] += w * out_uv[2 * (size_t)j + 1];
                }
            }
        }
    if (mean_value) {
        if ((st = sq_lu_factor(nfree, nnz, ri, ci, val, &lu, err))) goto done;
        if ((st = sq_lu_solve(lu, 2, rhs, x, err))) goto done;
    } else {
        if ((st = sq_spd_factor(nfree, nnz, ri, ci, val, &f, err))) goto done;
        if ((st = sq_spd_solve(f, 2, rhs, x, err))) goto done;
    }
    for (uint32_t v = 0; v < P->nv; v++)
        if (id[v] != UINT32_MAX) {
            out_uv[2 * (size_t)v] = x[id[v]];
            out_uv[2 * (size_t)v + 1] = x[nfree + id[v]];
        }
done:
    sq_spd_free(f);
    sq_lu_free(lu);
    free(id), free(ri), free(ci), free(val), free(rhs), free(x);
    return st;
}

sq_status sq_patch_embed_tutte(const sq_patch *P, double *out_uv, sq_error *err)
{
    return tutte_solve(P, out_uv, 1, NULL, err);
}

sq_status sq_patch_embed(const sq_patch *P, double *out_uv, int *method, sq_error *err)
{
    if (!P || !out_uv || !P->uv || !P->tri || !P->fixed || !(P->W > 0) || !(P->H > 0) ||
        P->a < 1 || P->b < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_patch_embed: bad patch");
    sq_status st;
    uint32_t bad = 0;
    if (P->pos) { /* the surface's own shape: mean-value weights in 3D */
        st = tutte_solve(P, out_uv, 1, P->pos, err);
        if (st && st != SQ_ERR_SOLVER) return st;
        bad = st ? P->nt : count_flips(P, out_uv);
        if (!bad) {
            if (method) *method = SQ_PATCH_SURFACE;
            return SQ_OK;
        }
    }
    if ((st = sweep(P, out_uv, err))) return st;
    bad = count_flips(P, out_uv);
    if (!bad) {
        if (method) *method = SQ_PATCH_SWEEP;
        return SQ_OK;
    }
    /* a singular mean-value system (weights of very thin triangles) is
     * one more reason for the uniform weights */
    st = tutte_solve(P, out_uv, 1, NULL, err);
    if (st && st != SQ_ERR_SOLVER) return st;
    uint32_t bad2 = st ? P->nt : count_flips(P, out_uv);
    if (bad2) { /* rounding in a badly conditioned mean-value system */
        if ((st = tutte_solve(P, out_uv, 0, NULL, err))) return st;
        bad2 = count_flips(P, out_uv);
    }
    if (bad2)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "patch %lld x %lld: %u of %u triangles flip under the sweep and %u "
                            "under Tutte's map in doubles: not embedded",
                            (long long)P->a, (long long)P->b, bad, P->nt, bad2);
    if (method) *method = SQ_PATCH_TUTTE;
    return SQ_OK;
}
