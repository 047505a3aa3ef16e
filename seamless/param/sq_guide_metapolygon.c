/* seamquad: seed 9.2, Algorithm 1 (guided metapolygon construction): after
 * each extension the metapolygon is laid out in the plane with the
 * barycentres of its irregular faces pinned to the positions of their
 * singularities in the unit-disk layout of the cut surface, and the next
 * irregular face is glued to the boundary edge closest to the next
 * singularity. The layout is a least-squares conformal one in the sense of
 * [LPRM02] for polygons: every face as close as possible to a similar copy
 * of the regular polygon with its number of sides (one similarity per
 * face, shared edges couple them). It only guides a choice, so it needs no
 * strict property (seed 9.2). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_guide.h"
#include "sq_sparse.h"
#include "sq_valence_order.h"

/* Complex triplets of the Hermitian normal equations: v holds (re, im). */
typedef struct trip {
    uint32_t *r, *c;
    double *v;
    size_t n, cap;
} trip;

static int trip_add(trip *T, uint32_t r, uint32_t c, double re, double im)
{
    if (r < c) return 0; /* lower triangle only (sq_hpd_factor) */
    if (T->n == T->cap) {
        size_t cap = T->cap ? 2 * T->cap : 1024;
        uint32_t *r2 = realloc(T->r, cap * sizeof *r2);
        if (r2) T->r = r2;
        uint32_t *c2 = realloc(T->c, cap * sizeof *c2);
        if (c2) T->c = c2;
        double *v2 = realloc(T->v, 2 * cap * sizeof *v2);
        if (v2) T->v = v2;
        if (!r2 || !c2 || !v2) return -1;
        T->cap = cap;
    }
    T->r[T->n] = r, T->c[T->n] = c, T->v[2 * T->n] = re, T->v[2 * T->n + 1] = im, T->n++;
    return 0;
}

/* adds w |row . z - rhs|^2 (complex coefficients cf[2i], cf[2i+1]) to the
 * normal equations: A(i, j) += w conj(cf_i) cf_j, b(i) += w conj(cf_i) rhs */
static int add_row(trip *T, double *b, const uint32_t *idx, const double *cf, int k, double rr, double ri,
                   double w)
{
    for (int i = 0; i < k; i++) {
        const double ar = cf[2 * i], ai = -cf[2 * i + 1]; /* conj(cf_i) */
        b[2 * idx[i]] += w * (ar * rr - ai * ri), b[2 * idx[i] + 1] += w * (ar * ri + ai * rr);
        for (int j = 0; j < k; j++) {
            const double br = cf[2 * j], bi = cf[2 * j + 1];
            if (trip_add(T, idx[i], idx[j], w * (ar * br - ai * bi), w * (ar * bi + ai * br))) return -1;
        }
    }
    return 0;
}

/* The energy is complex-linear in the vertex positions z = x + iy and the
 * faces' similarities a (every residual below is a complex-linear form), so
 * its normal equations are one Hermitian system of nv + nf complex
 * unknowns: the same minimizer as the real system of 2 nv + 2 nf, in about
 * half the time (sq_hpd_factor). */
sq_status sq_guide_metapolygon_layout(const sq_metapolygon *P, const double *c, uint32_t npinned,
                                      const uint32_t *pin_vert, double *xy, sq_error *err)
{
    const uint32_t nv = P->nv, nf = P->nf, n = nv + nf;
    trip T = {0};
    double *b = calloc(2 * (size_t)n + 2, sizeof *b), *x = malloc((2 * (size_t)n + 2) * sizeof *x);
    uint32_t *fv = NULL, *ix = NULL;
    double *cf = NULL;
    sq_spd *F = NULL;
    sq_status st = SQ_OK;
    uint32_t maxval = 0;
    for (uint32_t f = 0; f < nf; f++)
        if (P->f_valence[f] > maxval) maxval = P->f_valence[f];
    fv = malloc(((size_t)maxval + 1) * sizeof *fv);
    ix = malloc(((size_t)maxval + 1) * sizeof *ix);
    cf = malloc((2 * (size_t)maxval + 2) * sizeof *cf);
    if (!b || !x || !fv || !ix || !cf) goto nomem;
    uint32_t irr = 0;
    for (uint32_t f = 0; f < nf; f++) {
        const uint32_t k = P->f_valence[f];
        uint32_t h = P->f_he[f];
        for (uint32_t j = 0; j < k; j++, h = P->he_next[h]) fv[j] = P->he_vert[h];
        const uint32_t a = nv + f;
        for (uint32_t j = 0; j < k; j++) {
            uint32_t p = fv[j], q = fv[(j + 1) % k];
            double t0 = 2 * SQ_GUIDE_PI * j / k, t1 = 2 * SQ_GUIDE_PI * (j + 1) / k;
            double dx = cos(t1) - cos(t0), dy = sin(t1) - sin(t0);
            /* (z_q - z_p) - a d = 0, d = dx + i dy */
            uint32_t i1[3] = {q, p, a};
            double c1[6] = {1, 0, -1, 0, -dx, -dy};
            if (add_row(&T, b, i1, c1, 3, 0, 0, 1)) goto nomem;
        }
        /* a small pull towards one common similarity keeps the system
         * definite before two faces are pinned */
        if (trip_add(&T, a, a, 1e-3, 0)) goto nomem;
        b[2 * a] += 1e-3 * 0.1;
        if (!pin_vert && k != 4 && irr < npinned) { /* the barycentre at c[irr] */
            for (uint32_t j = 0; j < k; j++) ix[j] = fv[j], cf[2 * j] = 1.0 / k, cf[2 * j + 1] = 0;
            if (add_row(&T, b, ix, cf, (int)k, c[2 * irr], c[2 * irr + 1], 10)) goto nomem;
        }
        if (k != 4) irr++;
    }
    for (uint32_t j = 0; pin_vert && j < npinned; j++) {
        uint32_t i = pin_vert[j];
        double one[2] = {1, 0};
        if (add_row(&T, b, &i, one, 1, c[2 * j], c[2 * j + 1], 10)) goto nomem;
    }
    if (!pin_vert && irr < npinned) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "guidance: %u irregular faces, expected %u", irr, npinned);
        goto done;
    }
    st = sq_hpd_factor(n, T.n, T.r, T.c, T.v, &F, err);
    if (st == SQ_OK) st = sq_spd_solve(F, 1, b, x, err);
    if (st) goto done;
    memcpy(xy, x, 2 * (size_t)nv * sizeof *xy);
    goto done;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
done:
    if (F) sq_spd_free(F);
    free(T.r);
    free(T.c);
    free(T.v);
    free(b);
    free(x);
    free(fv);
    free(ix);
    free(cf);
    return st;
}

static double seg_dist2(const double *p, const double *a, const double *b)
{
    double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double dx = a[0] + t * ex - p[0], dy = a[1] + t * ey - p[1];
    return dx * dx + dy * dy;
}

/* New vertices (index >= G->nv_laid) placed at the average of their placed
 * neighbours, a few sweeps; old vertices keep their layout. */
static void extend_layout(const sq_metapolygon *P, sq_guide_glue *G)
{
    const uint32_t nv0 = G->nv_laid;
    uint8_t *placed = calloc(P->nv + 1, 1);
    double *sum = malloc((3 * (size_t)P->nv + 3) * sizeof *sum);
    if (!placed || !sum) {
        free(placed), free(sum);
        G->nv_laid = 0; /* forces a full layout next time */
        return;
    }
    memset(placed, 1, nv0);
    for (int sweep = 0; sweep < 40; sweep++) {
        memset(sum + 3 * (size_t)nv0, 0, 3 * (size_t)(P->nv - nv0) * sizeof *sum);
        for (uint32_t h = 0; h < P->nh; h++) {
            uint32_t v = P->he_vert[h], w = P->he_vert[P->he_twin[h]];
            if (v < nv0 || !placed[w]) continue;
            sum[3 * v] += G->xy[2 * w], sum[3 * v + 1] += G->xy[2 * w + 1], sum[3 * v + 2] += 1;
        }
        for (uint32_t v = nv0; v < P->nv; v++)
            if (sum[3 * v + 2] > 0) {
                G->xy[2 * v] = sum[3 * v] / sum[3 * v + 2], G->xy[2 * v + 1] = sum[3 * v + 1] / sum[3 * v + 2];
                placed[v] = 1;
            }
    }
    free(placed);
    free(sum);
}

#define GLUE_TIE 1e-9

/* a hash of (h, v) (splitmix64's finalizer) */
static uint64_t tie_key(uint32_t h, uint32_t v)
{
    uint64_t z = ((uint64_t)v << 32 | h) + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

sq_status sq_guide_glue_chooser(void *user, const sq_metapolygon *P, uint32_t step, uint32_t valence,
                                uint32_t *glue_he, sq_error *err)
{
    sq_guide_glue *G = user;
    const double *c = G->c;
    *glue_he = SQ_NONE;
    if (G->cancel && atomic_load(G->cancel)) return sq_error_set(err, SQ_ERR_SOLVER, "cancelled: an earlier attempt passed");
    if (G->cap < P->nv) {
        double *xy = realloc(G->xy, (2 * (size_t)P->nv + 2) * sizeof *xy);
        if (!xy) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        G->xy = xy, G->cap = P->nv;
    }
    /* a full layout while the metapolygon is small or has grown by a
     * quarter since the last one; otherwise the last layout, extended */
    if (P->nf <= 5000 || G->nv_laid == 0 || P->nf > G->nf_laid + G->nf_laid / 4) {
        sq_status st = sq_guide_metapolygon_layout(P, c, step, NULL, G->xy, err);
        if (st) return st;
        G->nv_laid = P->nv, G->nf_laid = P->nf;
    } else {
        extend_layout(P, G);
    }
    const double *xy = G->xy;
    /* the nearest boundary edge; of edges whose distances agree to a
     * relative 1e-9 the first in index order (variant 0) or the least
     * tie_key (G->variant): exact ties are common (a cone beyond a convex
     * vertex is equally near both its edges) and must not be decided by
     * the layout's last bits, which another solver or BLAS changes
     * (mpz/elk's step 6 did) */
    double best = INFINITY;
    uint64_t best_key = 0;
    for (uint32_t h = 0; h < P->nh; h++) {
        if (P->he_face[h] != SQ_NONE) continue;
        double d = seg_dist2(c + 2 * step, xy + 2 * P->he_vert[h], xy + 2 * P->he_vert[P->he_next[h]]);
        if (d > best * (1 + GLUE_TIE)) continue;
        const int tie = d >= best * (1 - GLUE_TIE);
        if (tie && !G->variant) continue;
        const uint64_t key = G->variant ? tie_key(h, G->variant) : 0;
        if (tie && key >= best_key) continue;
        if (sq_metapolygon_predict_quads(P, valence, h) == UINT64_MAX) continue;
        if (d < best) best = d;
        best_key = key, *glue_he = h;
    }
    if (G->chosen) G->chosen[step] = *glue_he;
    return SQ_OK;
}

void sq_guide_glue_free(sq_guide_glue *G)
{
    free(G->xy);
    G->xy = NULL;
    G->cap = G->nv_laid = G->nf_laid = 0;
}

sq_status sq_guide_cone_order(uint32_t n, const int32_t *valence, const double *xy, uint32_t *order,
                              sq_error *err)
{
    uint32_t *byd = malloc(((size_t)n + 1) * sizeof *byd), *pref = calloc((size_t)n + 1, sizeof *pref);
    uint32_t *index = malloc(((size_t)n + 1) * sizeof *index);
    double *r = malloc(((size_t)n + 1) * sizeof *r);
    sq_status st = SQ_OK;
    if (!byd || !pref || !index || !r) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* preferred: by distance from the disk centre (insertion sort: n is the
     * number of cones) */
    for (uint32_t i = 0; i < n; i++) {
        r[i] = xy[2 * i] * xy[2 * i] + xy[2 * i + 1] * xy[2 * i + 1];
        uint32_t j = i;
        while (j > 0 && r[byd[j - 1]] > r[i]) byd[j] = byd[j - 1], j--;
        byd[j] = i;
    }
    /* seed 9.2: valences > 4 moved forward where the prefix condition
     * needs them (sq_valence_order_greedy) */
    for (uint32_t i = 0; i < n; i++) pref[i] = (uint32_t)valence[byd[i]];
    st = sq_valence_order_greedy_index(pref, n, index, err);
    for (uint32_t i = 0; st == SQ_OK && i < n; i++) order[i] = byd[index[i]];
done:
    free(byd);
    free(pref);
    free(index);
    free(r);
    return st;
}
