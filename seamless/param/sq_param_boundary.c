/* seamquad: step 5, the boundary map (sq_param_steps.h): the surface's cut
 * boundary matched run by run to Omega's boundary, split at Omega's grid
 * points by arc length, its UVs on a dyadic grid, and each partner run's
 * UVs the exact transition of its primary's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_steps.h"

/* ---- step 5: boundary map ---------------------------------------------- */

typedef struct run {
    uint32_t label;
    uint32_t m0, mn;   /* M run: first halfedge index in mseq, count */
    uint32_t o0, on;   /* Omega run: first index in oseq, count      */
} run;

/* Splits the polyline of halfedges he[0..n) at the arc-length fractions
 * j / N (j = 1 .. N-1; frac[j] instead when frac is not NULL), snapping to
 * existing vertices that are close. matched (N + 1 entries) receives the
 * vertex for every j. */
sq_status sq_param_split_polyline(ctx *c, const uint32_t *he, uint32_t n, uint32_t N, const double *frac,
                                  uint32_t *matched)
{
    sq_tsurf *S = &c->S;
    double *cum = malloc(((size_t)n + 1) * sizeof *cum);
    uint8_t *used = calloc((size_t)n + 1, 1);
    if (!cum || !used) {
        free(cum), free(used);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    cum[0] = 0;
    for (uint32_t i = 0; i < n; i++) cum[i + 1] = cum[i] + sq_ts_dist(S, S->vert[he[i]], sq_ts_head(S, he[i]));
    double L = cum[n], unit = L / N;
    matched[0] = S->vert[he[0]];
    matched[N] = sq_ts_head(S, he[n - 1]);
    used[0] = used[n] = 1;
    /* decide per target: an existing vertex or a split point */
    uint32_t *tgt_edge = malloc((size_t)N * sizeof *tgt_edge);
    double *tgt_s = malloc((size_t)N * sizeof *tgt_s);
    if (!tgt_edge || !tgt_s) {
        free(cum), free(used), free(tgt_edge), free(tgt_s);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    uint32_t i = 0;
    for (uint32_t j = 1; j < N; j++) {
        double s = frac ? L * frac[j] : unit * j;
        while (i + 1 < n && cum[i + 1] <= s) i++;
        tgt_edge[j] = i, tgt_s[j] = s;
        double tol = frac ? 0.15 * L * fmin(frac[j] - frac[j - 1], frac[j + 1] - frac[j]) : 0.15 * unit;
        double d0 = s - cum[i], d1 = cum[i + 1] - s, li = cum[i + 1] - cum[i];
        if (d0 < tol && d0 < 0.3 * li && !used[i]) {
            used[i] = 1, matched[j] = S->vert[he[i]], tgt_edge[j] = SQ_NONE;
        } else if (d1 < tol && d1 < 0.3 * li && i + 1 < n && !used[i + 1]) {
            used[i + 1] = 1, matched[j] = S->vert[he[i + 1]], tgt_edge[j] = SQ_NONE;
        }
    }
    sq_status st = SQ_OK;
    /* splits, last target first, so that each edge's first half keeps its
     * index and covers [cum[i], current end) */
    double *end_s = malloc((size_t)n * sizeof *end_s);
    if (!end_s) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto out;
    }
    for (uint32_t e = 0; e < n; e++) end_s[e] = cum[e + 1];
    for (uint32_t j = N; j-- > 1;) {
        if (tgt_edge[j] == SQ_NONE) continue;
        uint32_t e = tgt_edge[j];
        double t = (tgt_s[j] - cum[e]) / (end_s[e] - cum[e]);
        if (!(t > 1e-12 && t < 1 - 1e-12)) t = 0.5;
        uint32_t v = sq_tsurf_split_edge(S, he[e], t);
        if (v == SQ_NONE) {
            st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
            goto out;
        }
        end_s[e] = tgt_s[j];
        matched[j] = v;
    }
out:
    free(end_s);
    free(cum);
    free(used);
    free(tgt_edge);
    free(tgt_s);
    return st;
}

/* UVs of the polyline he[0..n) whose vertices matched[0..N] sit at the
 * grid points g[0..N] (integer); intermediate vertices by arc length,
 * snapped. uvv receives the UV index per polyline vertex (n + 1). */
sq_status sq_param_polyline_uv(ctx *c, const uint32_t *he, uint32_t n, const uint32_t *matched,
                               const int64_t *g, double gs, uint32_t N, uint32_t *uvv)
{
    sq_tsurf *S = &c->S;
    uint32_t j = 0, i0 = 0;
    for (uint32_t i = 0; i <= n; i++) {
        uint32_t v = i < n ? S->vert[he[i]] : sq_ts_head(S, he[n - 1]);
        if (j <= N && v == matched[j]) {
            uvv[i] = uv_add(c, (double)g[2 * j] * gs, (double)g[2 * j + 1] * gs);
            if (uvv[i] == SQ_NONE) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
            if (j > 0 && i > i0 + 1) { /* fill i0+1 .. i-1 */
                double tot = 0;
                for (uint32_t q = i0; q < i; q++) tot += sq_ts_dist(S, S->vert[he[q]], sq_ts_head(S, he[q]));
                double acc = 0;
                for (uint32_t q = i0 + 1; q < i; q++) {
                    acc += sq_ts_dist(S, S->vert[he[q - 1]], sq_ts_head(S, he[q - 1]));
                    double lam = acc / tot;
                    double x = ((double)g[2 * (j - 1)] + lam * (double)(g[2 * j] - g[2 * (j - 1)])) * gs;
                    double y = ((double)g[2 * (j - 1) + 1] + lam * (double)(g[2 * j + 1] - g[2 * (j - 1) + 1])) * gs;
                    uvv[q] = uv_add(c, snap(c, x), snap(c, y));
                    if (uvv[q] == SQ_NONE) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
                }
            }
            i0 = i;
            j++;
        }
    }
    if (j != N + 1)
        return sq_error_set(c->err, SQ_ERR_INTERNAL, "polyline: %u of %u grid points matched", j, N + 1);
    return SQ_OK;
}

/* Omega's boundary as face halfedges, counterclockwise from the twin of
 * its boundary halfedge bnd_he (Omega_c's boundary halfedges run
 * clockwise). Returns the count, or SQ_NONE when the loop does not close
 * after nbnd edges. oseq: room for W->nbnd. */
uint32_t sq_param_omega_boundary(const sq_metapolygon *W, uint32_t *oseq)
{
    uint32_t b = W->bnd_he, nb = W->nbnd;
    for (uint32_t i = 0; i < nb; i++) {
        oseq[nb - 1 - i] = W->he_twin[b];
        b = W->he_next[b];
    }
    return b == W->bnd_he ? nb : SQ_NONE;
}

/* The surface's boundary loop: *mseq (the caller frees it), its *nm cut
 * halfedges in order from the first one. */
static sq_status surface_boundary(ctx *c, uint32_t **mseq_out, uint32_t *nm_out)
{
    sq_tsurf *S = &c->S;
    sq_error *err = c->err;
    uint32_t *mseq = NULL, nm = 0, capm = 0;
    /* M: boundary loop from the first cut graph halfedge */
    uint32_t h0 = SQ_NONE;
    for (uint32_t h = 0; h < S->nh && h0 == SQ_NONE; h++)
        if (S->kind[h]) h0 = h;
    {
        uint32_t h = h0;
        do {
            if (nm == capm) {
                capm = capm ? 2 * capm : 1024;
                uint32_t *p = realloc(mseq, capm * sizeof *p);
                if (!p) {
                    free(mseq);
                    return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                }
                mseq = p;
            }
            mseq[nm++] = h;
            h = sq_tsurf_next_boundary(S, h);
        } while (h != h0 && nm <= S->nh);
        if (h != h0) {
            free(mseq);
            return sq_error_set(err, SQ_ERR_INTERNAL, "the surface boundary loop does not close");
        }
    }
    *mseq_out = mseq, *nm_out = nm;
    return SQ_OK;
}

/* Both boundary loops, Omega's (oseq, nb) and the surface's (mseq, nm), in
 * runs of equal labels, matched label by label: *mrun (the caller frees
 * it), *nmr of them, each with its Omega run (o0, on). */
static sq_status match_runs(ctx *c, const uint32_t *oseq, uint32_t nb, const uint32_t *mseq, uint32_t nm,
                            run **mrun_out, uint32_t *nmr_out)
{
    sq_tsurf *S = &c->S;
    const sq_omega *O = c->O;
    const sq_metapolygon *W = &O->cut;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    run *orun = NULL, *mrun = NULL;
    uint32_t nmr = 0;
    /* runs of equal labels; rotate both so that a run starts at index 0 */
#define OLABEL(f) (O->he_label[W->he_twin[f]])
    uint32_t so = 0, sm = 0;
    while (so < nb && OLABEL(oseq[so]) == OLABEL(oseq[(so + nb - 1) % nb])) so++;
    while (sm < nm && S->label[mseq[sm]] == S->label[mseq[(sm + nm - 1) % nm]]) sm++;
    if (so == nb || sm == nm) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "a boundary has one label only");
        goto done;
    }
    orun = malloc((size_t)nb * sizeof *orun);
    mrun = malloc((size_t)nm * sizeof *mrun);
    if (!orun || !mrun) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    uint32_t nor = 0;
    for (uint32_t i = 0; i < nb; i++) {
        uint32_t f = oseq[(so + i) % nb];
        if (i == 0 || OLABEL(f) != orun[nor - 1].label) orun[nor++] = (run){OLABEL(f), 0, 0, (so + i) % nb, 0};
        orun[nor - 1].on++;
    }
    for (uint32_t i = 0; i < nm; i++) {
        uint32_t h = mseq[(sm + i) % nm];
        if (i == 0 || S->label[h] != mrun[nmr - 1].label) mrun[nmr++] = (run){S->label[h], (sm + i) % nm, 0, 0, 0};
        mrun[nmr - 1].mn++;
    }
    if (nor != nmr) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "surface and domain boundaries have %u and %u labelled pieces", nmr, nor);
        goto done;
    }
    uint32_t shift = 0;
    while (shift < nor && orun[shift].label != mrun[0].label) shift++;
    for (uint32_t i = 0; i < nor; i++)
        if (shift == nor || orun[(i + shift) % nor].label != mrun[i].label) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "the surface cut is not compatible with Omega's (piece %u: label %u)", i,
                              mrun[i].label);
            goto done;
        }
    /* per M run: its Omega run */
    for (uint32_t i = 0; i < nmr; i++) {
        mrun[i].o0 = orun[(i + shift) % nor].o0;
        mrun[i].on = orun[(i + shift) % nor].on;
    }
#undef OLABEL
done:
    free(orun);
    if (st) free(mrun), mrun = NULL, nmr = 0;
    *mrun_out = mrun, *nmr_out = nmr;
    return st;
}

/* The dyadic grid of the seams' UVs: c->dyadic such that Omega's
 * coordinates and translations (in units of 2^-xy_shift) times 2^dyadic
 * stay below 2^50; at most 40; SQ_ERR_INTERNAL below 8 or xy_shift. */
static sq_status choose_dyadic(ctx *c)
{
    const sq_omega *O = c->O;
    const sq_metapolygon *W = &O->cut;
    int64_t mx = 1;
    for (uint32_t v = 0; v < W->nv; v++) {
        int64_t a = llabs(O->xy[2 * v]), b = llabs(O->xy[2 * v + 1]);
        if (a > mx) mx = a;
        if (b > mx) mx = b;
    }
    for (uint32_t l = 0; l < O->nlabels; l++) {
        int64_t a = llabs(O->label_t[2 * l]) + llabs(O->label_t[2 * l + 1]);
        if (a > mx) mx = a;
    }
    int e = 0;
    frexp((double)(2 * mx + 2), &e);
    c->dyadic = 50 - e + O->xy_shift; /* xy in units of 2^-xy_shift */
    if (c->dyadic > 40) c->dyadic = 40;
    if (c->dyadic < 8 || c->dyadic < O->xy_shift)
        return sq_error_set(c->err, SQ_ERR_INTERNAL, "domain too large for exact seams");
    return SQ_OK;
}

/* The runs' UVs: every primary run (label below its partner's) split at
 * its Omega run's grid points and given UVs, then every partner run the
 * exact transition of its primary's; c->o2m for Omega's boundary
 * halfedges. */
static sq_status map_runs(ctx *c, const uint32_t *oseq, uint32_t nb, const uint32_t *mseq, uint32_t nm,
                          const run *mrun, uint32_t nmr)
{
    sq_tsurf *S = &c->S;
    const sq_omega *O = c->O;
    const sq_metapolygon *W = &O->cut;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    uint32_t *pl = NULL, npl = 0, *matched = NULL, *uvv = NULL;
    int64_t *g = NULL;
    double *gfrac = NULL;
    const double gs = ldexp(1.0, -O->xy_shift);
    /* run ends, before any split changes the halfedges' heads */
    uint32_t *run_end = malloc((size_t)nmr * sizeof *run_end);
    if (!run_end) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t i = 0; i < nmr; i++) run_end[i] = sq_ts_head(S, mseq[(mrun[i].m0 + mrun[i].mn - 1) % nm]);
    /* primary runs: split, UV; partner runs: exact transition */
    uint32_t *prim_of = malloc((size_t)O->nlabels * sizeof *prim_of);
    uint32_t **mlist = calloc(nmr, sizeof *mlist);
    uint32_t *mlen = calloc(nmr, sizeof *mlen);
    uint32_t **mmatch = calloc(nmr, sizeof *mmatch);
    if (!prim_of || !mlist || !mlen || !mmatch) {
        free(prim_of), free(mlist), free(mlen), free(mmatch), free(run_end);
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t l = 0; l < O->nlabels; l++) prim_of[l] = SQ_NONE;
    for (uint32_t i = 0; i < nmr; i++) prim_of[mrun[i].label] = i;
    for (uint32_t pass = 0; pass < 2 && st == SQ_OK; pass++) {
        for (uint32_t i = 0; i < nmr && st == SQ_OK; i++) {
            uint32_t l = mrun[i].label, lp = O->label_partner[l];
            int primary = l < lp;
            if ((pass == 0) != primary) continue;
            uint32_t N = mrun[i].on;
            uint32_t hs = mseq[mrun[i].m0];
            uint32_t end_v = run_end[i];
            free(pl);
            pl = malloc((size_t)mrun[i].mn * sizeof *pl);
            matched = realloc(matched, ((size_t)N + 1) * sizeof *matched);
            g = realloc(g, 2 * ((size_t)N + 1) * sizeof *g);
            gfrac = realloc(gfrac, ((size_t)N + 1) * sizeof *gfrac);
            if (!pl || !matched || !g || !gfrac) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                break;
            }
            for (uint32_t j = 0; j <= N; j++) {
                uint32_t f = oseq[(mrun[i].o0 + (j < N ? j : N - 1)) % nb];
                uint32_t ov = j < N ? W->he_vert[f] : W->he_vert[W->he_next[f]];
                g[2 * j] = O->xy[2 * ov], g[2 * j + 1] = O->xy[2 * ov + 1];
            }
            /* Omega's run by arc length where its edges are not all unit
             * ones (Q triangulated; on Q's grid the fractions are j / N) */
            if (O->xy_shift) {
                gfrac[0] = 0;
                for (uint32_t j = 1; j <= N; j++)
                    gfrac[j] = gfrac[j - 1] + hypot((double)(g[2 * j] - g[2 * j - 2]), (double)(g[2 * j + 1] - g[2 * j - 1]));
                for (uint32_t j = 1; j <= N; j++) gfrac[j] /= gfrac[N];
            }
            if (primary) {
                for (uint32_t e = 0; e < mrun[i].mn; e++) pl[e] = mseq[(mrun[i].m0 + e) % nm];
                st = sq_param_split_polyline(c, pl, mrun[i].mn, N, O->xy_shift ? gfrac : NULL, matched);
                if (st) break;
                if (sec_reserve(c)) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
                free(pl);
                pl = NULL;
                st = sq_param_walk_run(c, hs, end_v, &pl, &npl);
                if (st) break;
                uvv = realloc(uvv, ((size_t)npl + 1) * sizeof *uvv);
                if (!uvv) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
                st = sq_param_polyline_uv(c, pl, npl, matched, g, gs, N, uvv);
                if (st) break;
                for (uint32_t q = 0; q < npl; q++) c->sec_uv[pl[q]] = uvv[q];
                mlist[i] = pl, mlen[i] = npl, pl = NULL;
                mmatch[i] = malloc(((size_t)N + 1) * sizeof **mmatch);
                if (!mmatch[i]) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
                memcpy(mmatch[i], matched, ((size_t)N + 1) * sizeof *matched);
            } else {
                uint32_t ip = prim_of[lp];
                if (ip == SQ_NONE || !mlist[ip]) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "label %u has no primary run", l);
                    break;
                }
                free(pl);
                pl = NULL;
                st = sq_param_walk_run(c, hs, end_v, &pl, &npl);
                if (st) break;
                if (npl != mlen[ip]) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "run %u: %u edges, partner %u", l, npl, mlen[ip]);
                    break;
                }
                /* vertex q of this run is vertex npl - q of the partner */
                for (uint32_t q = 0; q < npl; q++) {
                    if (q == 0) {
                        c->sec_uv[pl[0]] = uv_add(c, (double)g[0] * gs, (double)g[1] * gs);
                        continue;
                    }
                    uint32_t hq = mlist[ip][npl - q];
                    double x[2] = {c->uv[2 * c->sec_uv[hq]], c->uv[2 * c->sec_uv[hq] + 1]}, y[2];
                    transition(O, lp, x, y);
                    c->sec_uv[pl[q]] = uv_add(c, y[0], y[1]);
                }
                mlist[i] = pl, mlen[i] = npl, pl = NULL;
                mmatch[i] = malloc(((size_t)N + 1) * sizeof **mmatch);
                if (!mmatch[i]) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
                for (uint32_t j = 0; j <= N; j++) mmatch[i][j] = mmatch[ip][N - j];
            }
            /* Omega face halfedges -> M halfedges at the matched vertices */
            uint32_t j = 0;
            for (uint32_t q = 0; q < mlen[i] && j < N; q++)
                if (S->vert[mlist[i][q]] == mmatch[i][j]) {
                    c->o2m[oseq[(mrun[i].o0 + j) % nb]] = mlist[i][q];
                    j++;
                }
            if (j != N) st = sq_error_set(err, SQ_ERR_INTERNAL, "run %u: %u of %u grid points found", l, j, N);
        }
    }
    for (uint32_t i = 0; i < nmr; i++) free(mlist[i]), free(mmatch[i]);
    free(mlist), free(mlen), free(mmatch), free(prim_of), free(run_end);
done:
    free(pl);
    free(matched);
    free(uvv);
    free(g);
    free(gfrac);
    return st;
}

/* Step 5: Omega's and the surface's boundaries matched run by run
 * (match_runs), the seams' dyadic grid chosen, the runs mapped (map_runs). */
sq_status sq_param_boundary_map(ctx *c)
{
    const sq_metapolygon *W = &c->O->cut;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    /* Omega: boundary face halfedges counterclockwise */
    uint32_t nb = W->nbnd;
    uint32_t *oseq = malloc((size_t)nb * sizeof *oseq);
    uint32_t *mseq = NULL, nm = 0, nmr = 0;
    run *mrun = NULL;
    if (!oseq) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    if (sq_param_omega_boundary(W, oseq) == SQ_NONE)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega's boundary loop has not %u edges", nb);
    if (st == SQ_OK) st = surface_boundary(c, &mseq, &nm);
    if (st == SQ_OK) st = match_runs(c, oseq, nb, mseq, nm, &mrun, &nmr);
    if (st == SQ_OK) st = choose_dyadic(c);
    if (st == SQ_OK) st = map_runs(c, oseq, nb, mseq, nm, mrun, nmr);
    free(oseq);
    free(mseq);
    free(mrun);
    return st;
}
