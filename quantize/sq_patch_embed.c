/* seamquad: a T-mesh face re-embedded onto its integer rectangle
 * (sq_patch_embed.h explains the sweep and the Tutte fallback). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_patch_embed.h"
#include "sq_predicates.h"
#include "sq_sparse.h"

/* A piecewise linear map through points (x_i, y_i), x increasing. */
typedef struct plmap {
    uint32_t n;
    double *x, *y;
} plmap;

static int cmp_pair(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return (p[0] > q[0]) - (p[0] < q[0]);
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
    double w = (x - F->x[lo]) / (F->x[hi] - F->x[lo]);
    return F->y[lo] + w * (F->y[hi] - F->y[lo]);
}

/* The boundary vertices of one side: key coordinate k (0: u, 1: v) where
 * the other coordinate equals `at`; image coordinate `img` of out_uv. */
static sq_status side_map(const sq_patch *P, const double *out_uv, int k, double at, int img,
                          plmap *F, sq_error *err)
{
    uint32_t n = 0;
    double *buf = malloc(2 * ((size_t)P->nv + 1) * sizeof *buf);
    if (!buf) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (patch sides)");
    for (uint32_t v = 0; v < P->nv; v++) {
        if (!P->fixed[v] || P->uv[2 * (size_t)v + (1 - k)] != at) continue;
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
        if (i && !(F->x[i] > F->x[i - 1] && F->y[i] > F->y[i - 1])) {
            free(buf);
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "patch: boundary vertices at %.17g and %.17g of one side are not "
                                "in increasing order in both maps (%.17g, %.17g)",
                                F->x[i - 1], F->x[i], F->y[i - 1], F->y[i]);
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
    if ((st = side_map(P, out_uv, 0, 0.0, 0, &F[0], err)) ||  /* bottom: u -> s */
        (st = side_map(P, out_uv, 0, P->H, 0, &F[1], err)) || /* top                  */
        (st = side_map(P, out_uv, 1, 0.0, 1, &F[2], err)) ||  /* left: v -> t         */
        (st = side_map(P, out_uv, 1, P->W, 1, &F[3], err)))   /* right                */
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

/* Tutte's map: every free vertex the mean of its neighbours (an edge in two
 * triangles weighs 2, a boundary edge 1: positive and symmetric). */
sq_status sq_patch_embed_tutte(const sq_patch *P, double *out_uv, sq_error *err)
{
    uint32_t *id = malloc(((size_t)P->nv + 1) * sizeof *id), nfree = 0;
    size_t cap = 12 * (size_t)P->nt + 1, nnz = 0;
    uint32_t *ri = malloc(cap * sizeof *ri), *ci = malloc(cap * sizeof *ci);
    double *val = malloc(cap * sizeof *val);
    double *rhs = NULL, *x = NULL;
    sq_spd *f = NULL;
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
            uint32_t i = P->tri[3 * (size_t)t + k], j = P->tri[3 * (size_t)t + (k + 1) % 3];
            for (int side = 0; side < 2; side++) {
                uint32_t p = side ? j : i, q = side ? i : j;
                if (id[p] == UINT32_MAX) continue;
                ri[nnz] = ci[nnz] = id[p], val[nnz++] = 1.0;
                if (id[q] != UINT32_MAX) {
                    ri[nnz] = id[p], ci[nnz] = id[q], val[nnz++] = -1.0;
                } else {
                    rhs[id[p]] += out_uv[2 * (size_t)q];
                    rhs[nfree + id[p]] += out_uv[2 * (size_t)q + 1];
                }
            }
        }
    if ((st = sq_spd_factor(nfree, nnz, ri, ci, val, &f, err))) goto done;
    if ((st = sq_spd_solve(f, 2, rhs, x, err))) goto done;
    for (uint32_t v = 0; v < P->nv; v++)
        if (id[v] != UINT32_MAX) {
            out_uv[2 * (size_t)v] = x[id[v]];
            out_uv[2 * (size_t)v + 1] = x[nfree + id[v]];
        }
done:
    sq_spd_free(f);
    free(id), free(ri), free(ci), free(val), free(rhs), free(x);
    return st;
}

sq_status sq_patch_embed(const sq_patch *P, double *out_uv, int *method, sq_error *err)
{
    if (!P || !out_uv || !P->uv || !P->tri || !P->fixed || !(P->W > 0) || !(P->H > 0) ||
        P->a < 1 || P->b < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_patch_embed: bad patch");
    sq_status st = sweep(P, out_uv, err);
    if (st) return st;
    uint32_t bad = count_flips(P, out_uv);
    if (!bad) {
        if (method) *method = SQ_PATCH_SWEEP;
        return SQ_OK;
    }
    if ((st = sq_patch_embed_tutte(P, out_uv, err))) return st;
    uint32_t bad2 = count_flips(P, out_uv);
    if (bad2)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "patch %lld x %lld: %u of %u triangles flip under the sweep and %u "
                            "under Tutte's map in doubles: not embedded",
                            (long long)P->a, (long long)P->b, bad, P->nt, bad2);
    if (method) *method = SQ_PATCH_TUTTE;
    return SQ_OK;
}
