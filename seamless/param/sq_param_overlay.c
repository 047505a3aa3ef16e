/* seamquad: step 7', the interior map by overlay (sq_param_steps.h;
 * sq_overlay.h; seamless-notes 5): the cut surface A and Omega B (every
 * unit square fanned from its centre, its boundary edges split at the
 * surface's boundary vertices) are mapped onto the unit disk by Tutte's
 * theorem with the same boundary points (by Omega's arc length); their
 * common refinement is a triangulation of the surface whose every triangle
 * lies in one triangle of B, whose affine map gives its UVs. Bijective in
 * exact arithmetic for any Omega, convex or not, immersed or not; no
 * chords, no cells. Fills P. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_overlay.h"
#include "sq_param_steps.h"
#include "sq_predicates.h"

/* Step 7', the surface's side: the cut surface A on the unit disk, once
 * per attempt (overlay_with may then try several triangulations of
 * Omega). Ids: [0, nbl) the boundary loop from the copy of Omega's first
 * corner, [nbl, na) the vertices off the cut. */
typedef struct surface_disk {
    uint32_t nbl, na; /* [nbl, ns) S's vertices off the cut, [ns, na) the */
    uint32_t ns, nf;  /* fans' added vertices (sq_param_grade_fans); nf  */
                      /* triangles (S's, the fans' replaced)            */
    uint32_t *fin;    /* nf: the input face of every triangle            */
    double *p3;       /* 3 na: 3D positions                                */
    uint32_t *mseq;   /* nbl: the cut halfedge naming boundary vertex i    */
    uint32_t *a2s;    /* ns: the surface vertex of every id but the fans'  */
    uint32_t *tri;    /* 3 nf: the faces of S in ids                       */
    uint32_t *twin;   /* 3 nf: their twins, SQ_NONE across the cut         */
    uint32_t *wb;     /* O->cut.nv: the id of Omega's boundary vertices    */
    uint32_t *bstart; /* nbnd: the id at the start of Omega's boundary     */
                      /* edge i (its surface points follow it)             */
    double *buv;      /* 2 nbl: the boundary's UVs                         */
    double *xy;       /* 2 na: disk positions                              */
} surface_disk;

static void surface_disk_free(surface_disk *A)
{
    free(A->mseq), free(A->a2s), free(A->tri), free(A->twin), free(A->wb), free(A->bstart);
    free(A->buv), free(A->xy), free(A->fin), free(A->p3);
    memset(A, 0, sizeof *A);
}

static sq_status surface_disk_build(ctx *c, const uint32_t *oseq, surface_disk *A)
{
    sq_tsurf *S = &c->S;
    const sq_metapolygon *W = &c->O->cut;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    uint32_t nb = W->nbnd;
    uint32_t *bidx = malloc((size_t)S->nh * sizeof *bidx), *aid = malloc((size_t)S->nv * sizeof *aid);
    uint32_t *hpos = malloc((size_t)S->nh * sizeof *hpos);
    double *p3 = NULL;
    memset(A, 0, sizeof *A);
    A->mseq = malloc((size_t)S->nh * sizeof *A->mseq);
    A->tri = malloc(3 * (size_t)S->nf * sizeof *A->tri);
    A->twin = malloc(3 * (size_t)S->nf * sizeof *A->twin);
    A->wb = malloc((size_t)W->nv * sizeof *A->wb);
    A->bstart = malloc((size_t)nb * sizeof *A->bstart);
    if (!bidx || !aid || !hpos || !A->mseq || !A->tri || !A->twin || !A->wb || !A->bstart) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* the surface's boundary loop, from the copy of Omega's first corner */
    for (uint32_t h = 0; h < S->nh; h++) bidx[h] = SQ_NONE;
    uint32_t h0 = c->o2m[oseq[0]], h = h0, nbl = 0;
    if (h0 == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: Omega's boundary has no surface copy");
        goto done;
    }
    do {
        bidx[h] = nbl;
        A->mseq[nbl++] = h;
        h = sq_tsurf_next_boundary(S, h);
    } while (h != h0 && nbl < S->nh);
    if (h != h0) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: the surface boundary loop does not close");
        goto done;
    }
    uint32_t na = nbl;
    for (uint32_t v = 0; v < S->nv; v++) aid[v] = S->v_ncut[v] ? SQ_NONE : na++;
    A->nbl = nbl, A->na = na;
    /* Omega's boundary vertices: their surface copies */
    for (uint32_t v = 0; v < W->nv; v++) A->wb[v] = SQ_NONE;
    for (uint32_t i = 0; i < nb; i++) {
        uint32_t f = oseq[i], v = W->he_vert[f], m = c->o2m[f];
        if (m == SQ_NONE || bidx[m] == SQ_NONE || (A->wb[v] != SQ_NONE && A->wb[v] != bidx[m])) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: Omega's boundary vertex %u has no single surface copy", v);
            goto done;
        }
        A->wb[v] = A->bstart[i] = bidx[m];
    }
    A->a2s = malloc((size_t)na * sizeof *A->a2s);
    A->buv = malloc(2 * (size_t)nbl * sizeof *A->buv);
    A->xy = malloc(2 * (size_t)na * sizeof *A->xy);
    p3 = malloc(3 * (size_t)na * sizeof *p3);
    if (!A->a2s || !A->buv || !A->xy || !p3) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t i = 0; i < nbl; i++) {
        A->a2s[i] = S->vert[A->mseq[i]];
        const double *u = c->uv + 2 * (size_t)c->sec_uv[A->mseq[i]];
        A->buv[2 * i] = u[0], A->buv[2 * i + 1] = u[1];
    }
    for (uint32_t v = 0; v < S->nv; v++)
        if (aid[v] != SQ_NONE) A->a2s[aid[v]] = v;
    /* the boundary on the unit circle by Omega's arc length */
    double L = 0, s = 0;
    for (uint32_t i = 0; i < nbl; i++) {
        const double *u = A->buv + 2 * i, *w = A->buv + 2 * ((i + 1) % nbl);
        L += hypot(w[0] - u[0], w[1] - u[1]);
    }
    for (uint32_t i = 0; i < nbl; i++) {
        double t = 6.283185307179586 * s / L;
        A->xy[2 * i] = cos(t), A->xy[2 * i + 1] = sin(t);
        const double *u = A->buv + 2 * i, *w = A->buv + 2 * ((i + 1) % nbl);
        s += hypot(w[0] - u[0], w[1] - u[1]);
    }
    /* A's triangles: the faces of S, a boundary corner named by its sector */
    for (uint32_t f = 0; f < S->nf && st == SQ_OK; f++) {
        uint32_t e = S->f_he[f];
        for (uint32_t i = 0; i < 3; i++, e = S->next[e]) {
            hpos[e] = 3 * f + i;
            uint32_t v = S->vert[e], sec = aid[v] != SQ_NONE ? SQ_NONE : sq_tsurf_sector_of(S, e);
            A->tri[3 * f + i] = aid[v] != SQ_NONE ? aid[v] : sec == SQ_NONE ? SQ_NONE : bidx[sec];
            if (A->tri[3 * f + i] == SQ_NONE)
                st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: a sector of vertex %u is off the boundary loop", v);
        }
    }
    if (st) goto done;
    for (uint32_t f = 0; f < S->nf; f++) {
        uint32_t e = S->f_he[f];
        for (uint32_t i = 0; i < 3; i++, e = S->next[e]) A->twin[3 * f + i] = S->kind[e] ? SQ_NONE : hpos[S->twin[e]];
    }
    for (uint32_t i = 0; i < na; i++) memcpy(p3 + 3 * (size_t)i, S->pos + 3 * (size_t)A->a2s[i], 3 * sizeof *p3);
    A->ns = na, A->nf = S->nf, A->p3 = p3, p3 = NULL;
    A->fin = malloc(((size_t)S->nf + 1) * sizeof *A->fin);
    if (!A->fin) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < S->nf; f++) A->fin[f] = S->forig[f];
    /* the fans along the cut graded (fewer crossings) */
    if (c->opt->fans == SQ_FANS_ON) {
        uint32_t added = 0;
        st = sq_param_grade_fans(nbl, SQ_FAN_MIN_RUN, A->twin, &A->nf, &A->tri, &A->fin, &A->na, &A->p3, &added, err);
        if (st == SQ_OK && added) {
            na = A->na;
            double *xy = realloc(A->xy, 2 * (size_t)na * sizeof *xy);
            uint32_t *tw = realloc(A->twin, 3 * (size_t)A->nf * sizeof *tw);
            if (xy) A->xy = xy;
            if (tw) A->twin = tw;
            int pr = !xy || !tw ? -1 : sq_param_pair_twins(A->nf, A->tri, A->twin);
            if (pr == -1) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            else if (pr) st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: the graded fans are no manifold disk");
        }
        if (st) goto done;
    }
    st = sq_param_disk_tutte(A->nf, A->tri, A->twin, nbl, na - nbl, A->p3, A->xy, err);
done:
    free(bidx), free(aid), free(hpos), free(p3);
    if (st) surface_disk_free(A);
    return st;
}

/* The overlay's crossings as output vertices: each at its parameter along
 * its surface edge (3D) and along its domain edge (UV). */
typedef struct cross_fill {
    const sq_overlay *X;
    const double *ap3, *buv;
    const uint32_t *atri, *btri;
    double *pos, *uv; /* the first crossing's */
} cross_fill;

static void *fill_crossings(void *arg)
{
    const cross_fill *F = arg;
    const sq_overlay *X = F->X;
    for (uint32_t k = 0; k < X->nx; k++) {
        uint32_t h = X->x_ha[k], h1 = sq_param_corner_next(h);
        const double *p0 = F->ap3 + 3 * (size_t)F->atri[h], *p1 = F->ap3 + 3 * (size_t)F->atri[h1];
        double t = X->x_ta[k], *p = F->pos + 3 * (size_t)k;
        for (int d = 0; d < 3; d++) p[d] = (1 - t) * p0[d] + t * p1[d];
    }
    for (uint32_t k = 0; k < X->nx; k++) {
        uint32_t h = X->x_hb[k], h1 = sq_param_corner_next(h);
        const double *u0 = F->buv + 2 * (size_t)F->btri[h], *u1 = F->buv + 2 * (size_t)F->btri[h1];
        double t = X->x_tb[k];
        for (int d = 0; d < 2; d++) F->uv[2 * (size_t)k + d] = (1 - t) * u0[d] + t * u1[d];
    }
    return NULL;
}

/* Step 7', Omega's side: B, Omega triangulated (omega_triangulation),
 * on the unit disk with A's boundary points. Ids: A's na first (B's
 * boundary points are A's), then B's interior vertices up to nv. */
typedef struct omega_disk {
    uint32_t nv;
    double *buv;          /* 2 nv: Omega's UVs (A's interior ones unused) */
    sq_param_tri_list bt; /* B's triangles                               */
    uint32_t *btw;        /* 3 bt.n: their twins                         */
    double *xy;           /* 2 nv: disk positions                        */
} omega_disk;

static void omega_disk_free(omega_disk *B)
{
    free(B->bt.t), free(B->btw), free(B->xy), free(B->buv);
    memset(B, 0, sizeof *B);
}

/* B for Omega triangulated in C's rectangles (NULL: in unit squares):
 * every triangle positively oriented, a manifold disk, its interior on
 * the disk by Tutte's map with weights from Omega's UVs. The caller frees
 * B (omega_disk_free), also after a failure. */
static sq_status omega_disk_build(ctx *c, const surface_disk *A, const uint32_t *oseq, const sq_omega_cells *C,
                                  omega_disk *B)
{
    sq_error *err = c->err;
    uint32_t nbl = A->nbl, na = A->na;
    double *p3 = NULL;
    memset(B, 0, sizeof *B);
    sq_status st = sq_param_omega_triangulation(c->O, C, nbl, na, A->wb, oseq, A->bstart, A->buv, &B->nv, &B->buv,
                                                &B->bt, err);
    if (st) goto done;
    const uint32_t nv = B->nv, *btri = B->bt.t;
    const double *buv = B->buv;
    uint32_t nbt = B->bt.n;
    /* the memory limit, before the disk map's factorization */
    const uint64_t max_memory = sq_param_max_memory(c->opt);
    if ((uint64_t)nbt > max_memory / SQ_BYTES_PER_DISK_TRIANGLE) {
        st = sq_error_set(err, SQ_ERR_SOLVER,
                          "overlay: Omega triangulated has %u triangles; its disk map would need about %llu MB, "
                          "more than the memory limit of %llu MB (--max-memory)",
                          nbt, (unsigned long long)(((uint64_t)nbt * SQ_BYTES_PER_DISK_TRIANGLE) >> 20),
                          (unsigned long long)(max_memory >> 20));
        goto done;
    }
    for (uint32_t g = 0; g < nbt; g++)
        if (sq_orient2d(buv + 2 * (size_t)btri[3 * g], buv + 2 * (size_t)btri[3 * g + 1], buv + 2 * (size_t)btri[3 * g + 2]) <= 0) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: Omega's triangle %u is not positively oriented", g);
            goto done;
        }
    B->xy = malloc(2 * (size_t)nv * sizeof *B->xy);
    p3 = calloc(3 * (size_t)nv, sizeof *p3);
    B->btw = malloc(3 * (size_t)nbt * sizeof *B->btw);
    if (!B->xy || !p3 || !B->btw) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (sq_param_pair_twins(nbt, btri, B->btw)) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: Omega's triangulation is not a manifold disk");
        goto done;
    }
    /* B on the disk: A's positions for the shared boundary, Tutte inside
     * with weights from Omega's geometry (its UVs, flat) */
    memcpy(B->xy, A->xy, 2 * (size_t)na * sizeof *B->xy);
    for (uint32_t i = 0; i < nv; i++)
        if (i < nbl || i >= na) p3[3 * (size_t)i] = buv[2 * i], p3[3 * (size_t)i + 1] = buv[2 * i + 1];
    st = sq_param_disk_tutte(nbt, btri, B->btw, na, nv - na, p3, B->xy, err);
    if (st == SQ_OK) st = stop_if_cancelled(c);
done:
    free(p3);
    return st;
}

/* P from the overlay X of A and B: positions, UVs, triangles, their input
 * faces and cut halfedges, valences (not yet the twins and seams). */
static sq_status overlay_output(ctx *c, const surface_disk *A, const omega_disk *B, const sq_overlay *X,
                                const int32_t *valence, sq_param *P)
{
    sq_tsurf *S = &c->S;
    const uint32_t nbl = A->nbl, na = A->na, nv = B->nv, *btri = B->bt.t;
    const double *buv = B->buv;
    /* the output: S's vertices, then the fans' and B's interior vertices
     * (ids from ns on), then the crossings */
    const uint32_t ns = A->ns;
    uint32_t nout = S->nv + (nv - ns) + X->nx;
    P->nv = nout, P->nf = X->ntri, P->nv_input = S->nv_input, P->nuv = nv + X->nx;
    P->pos = malloc(3 * (size_t)nout * sizeof *P->pos);
    P->uv = malloc(2 * (size_t)P->nuv * sizeof *P->uv);
    P->tri = malloc(3 * (size_t)X->ntri * sizeof *P->tri);
    P->tri_uv = malloc(3 * (size_t)X->ntri * sizeof *P->tri_uv);
    P->he_seam = malloc(3 * (size_t)X->ntri);
    P->he_cut = malloc(3 * (size_t)X->ntri);
    P->tri_in = malloc((size_t)X->ntri * sizeof *P->tri_in);
    P->valence = malloc((size_t)S->nv_input * sizeof *P->valence);
    if (!P->pos || !P->uv || !P->tri || !P->tri_uv || !P->he_seam || !P->he_cut || !P->tri_in || !P->valence)
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    const uint32_t *a2s = A->a2s, *atri = A->tri;
    const double *ap3 = A->p3;
    memcpy(P->pos, S->pos, 3 * (size_t)S->nv * sizeof *P->pos);
    for (uint32_t i = ns; i < na; i++) memcpy(P->pos + 3 * ((size_t)S->nv + i - ns), ap3 + 3 * (size_t)i, 3 * sizeof *P->pos);
    memcpy(P->valence, valence, (size_t)S->nv_input * sizeof *P->valence);
    for (uint32_t i = na; i < nv; i++) {
        const uint32_t *t = atri + 3 * (size_t)X->loc[i];
        const double *l = X->bary + 3 * (size_t)i;
        double *p = P->pos + 3 * ((size_t)S->nv + i - ns);
        for (int d = 0; d < 3; d++)
            p[d] = l[0] * ap3[3 * (size_t)t[0] + d] + l[1] * ap3[3 * (size_t)t[1] + d] + l[2] * ap3[3 * (size_t)t[2] + d];
    }
    /* the crossings' points and UVs beside the triangles below (in a thread
     * of their own where allowed: they write other arrays) */
    cross_fill cf = {X, ap3, buv, atri, btri, P->pos + 3 * ((size_t)S->nv + nv - ns), P->uv + 2 * (size_t)nv};
    pthread_t cf_th;
    int cf_helper = c->opt->threads > 1 && pthread_create(&cf_th, NULL, fill_crossings, &cf) == 0;
    if (!cf_helper) fill_crossings(&cf);
    /* UVs: the boundary's and B's own; A's interior vertices by their B
     * triangle (the crossings': fill_crossings) */
    memcpy(P->uv, buv, 2 * (size_t)nbl * sizeof *P->uv);
    memcpy(P->uv + 2 * (size_t)na, buv + 2 * (size_t)na, 2 * (size_t)(nv - na) * sizeof *P->uv);
    for (uint32_t i = nbl; i < na; i++) {
        const uint32_t *t = btri + 3 * (size_t)X->loc[i];
        const double *l = X->bary + 3 * (size_t)i;
        for (int d = 0; d < 2; d++)
            P->uv[2 * (size_t)i + d] = l[0] * buv[2 * (size_t)t[0] + d] + l[1] * buv[2 * (size_t)t[1] + d] +
                                       l[2] * buv[2 * (size_t)t[2] + d];
    }
    for (uint32_t f = 0; f < X->ntri; f++) P->tri_in[f] = A->fin[X->tri_fa[f]];
    for (uint32_t f = 0; f < X->ntri; f++)
        for (int i = 0; i < 3; i++) {
            uint32_t o = X->tri[3 * (size_t)f + i];
            P->tri_uv[3 * (size_t)f + i] = o;
            P->tri[3 * (size_t)f + i] = o < ns ? a2s[o] : S->nv + (o - ns);
            uint32_t o1 = X->tri[3 * (size_t)f + (i + 1) % 3];
            P->he_cut[3 * (size_t)f + i] = o < nbl && o1 == (o + 1) % nbl ? S->kind[A->mseq[o]] : 0;
        }
    if (cf_helper) pthread_join(cf_th, NULL);
    return SQ_OK;
}

/* P's twins and seams (the refined surface closed), every UV triangle's
 * orientation checked exactly; stats: sizes (and distortion unless
 * distortion_later). */
static sq_status overlay_check(ctx *c, sq_param *P, sq_param_stats *stats)
{
    sq_error *err = c->err;
    /* the seams from the output's twins (corner k's edge against the one
     * across it; every edge with exactly two triangles, opposite: the
     * refined surface is closed; sq_param_verify checks the whole mesh of
     * the final map) */
    P->he_twin = malloc(3 * (size_t)P->nf * sizeof *P->he_twin);
    if (!P->he_twin) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    int pr = sq_param_pair_twins_threads(P->nf, P->tri, P->he_twin, c->opt->threads);
    if (pr == -1) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    uint32_t seams = 0, bad = 0, first = SQ_NONE;
    for (uint32_t k = 0; k < 3 * P->nf && !pr; k++) {
        uint32_t g = P->he_twin[k];
        if (g == SQ_NONE) {
            pr = -3;
            break;
        }
        P->he_seam[k] = P->tri_uv[k] != P->tri_uv[sq_param_corner_next(g)] ||
                        P->tri_uv[sq_param_corner_next(k)] != P->tri_uv[g];
        if (P->he_seam[k] && k < g) seams++;
    }
    if (pr)
        return sq_error_set(err, SQ_ERR_INTERNAL, "overlay: the refined surface is not closed: an edge %s",
                            pr == -3 ? "with one triangle" : "with more than two triangles, or two in one direction");
    for (uint32_t f = 0; f < P->nf; f++)
        if (sq_orient2d(P->uv + 2 * (size_t)P->tri_uv[3 * f], P->uv + 2 * (size_t)P->tri_uv[3 * f + 1],
                        P->uv + 2 * (size_t)P->tri_uv[3 * f + 2]) <= 0) {
            if (first == SQ_NONE) first = f;
            bad++;
        }
    stats->verts_out = P->nv, stats->faces_out = P->nf;
    stats->steiner = P->nv - P->nv_input;
    stats->nuv = P->nuv;
    stats->seam_edges = seams;
    if (!bad && !distortion_later(c)) sq_param_distortion(P, stats);
    if (bad && !c->keep_flips)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "the interior map (overlay) is not injective in floating point: %u of %u UV "
                            "triangles are not positively oriented (first: face %u)",
                            bad, P->nf, first);
    return SQ_OK;
}

/* Step 7' against one triangulation of Omega (omega_triangulation; C:
 * the chords' rectangles, or NULL: the unit squares): Omega on the disk
 * with A's boundary points (omega_disk_build), the overlay, and P from it
 * (overlay_output, overlay_check). */
static sq_status overlay_with(ctx *c, const surface_disk *A, const uint32_t *oseq, const sq_omega_cells *C,
                              const int32_t *valence, sq_param *P, sq_param_stats *stats)
{
    omega_disk B;
    sq_overlay X;
    sq_overlay_init(&X);
    sq_status st = omega_disk_build(c, A, oseq, C, &B);
    if (st) goto done;
    sq_overlay_mesh Am = {A->nf, A->tri, A->twin}, Bm = {B.bt.n, B.bt.t, B.btw};
    progress(c, "overlay", 0.75);
    /* in two threads where the caller allows them (the same result) */
    uint64_t budget = c->opt->max_crossings ? c->opt->max_crossings
                      : c->qtri             ? sq_param_crossing_budget(c->opt, c->m->nv, c->m->nf)
                                            : steiner_budget(c);
    /* the memory limit, checked by the sample before the walk allocates */
    const uint64_t max_memory = sq_param_max_memory(c->opt);
    const uint64_t mem_cap = max_memory / SQ_BYTES_PER_CROSSING;
    const int by_memory = mem_cap < budget;
    if (by_memory) budget = mem_cap;
    /* given up at once where the sample expects a quarter more than the
     * budget (the overlay's rule) or more than the variants' gate; a
     * failure counts as the gate's where the gate is below the former */
    st = sq_overlay_build_threads(A->nbl, A->na, B.nv, B.xy, &Am, &Bm, budget, c->gate ? c->gate : UINT64_MAX,
                                  c->opt->threads ? c->opt->threads : 1, c->cancel, &X, c->err);
    stats->crossings_expected = X.expected;
    stats->gated = st == SQ_ERR_SOLVER && c->gate && c->gate < budget + budget / 4 && X.expected > c->gate;
    if (st == SQ_ERR_SOLVER && by_memory && !stats->gated && !cancelled(c) && c->err) {
        char msg[2 * sizeof c->err->msg];
        snprintf(msg, sizeof msg, "%s (the memory limit: %llu MB allow %llu crossings; --max-memory)", c->err->msg,
                 (unsigned long long)(max_memory >> 20), (unsigned long long)mem_cap);
        sq_error_set(c->err, st, "%s", msg);
    }
    if (cancelled(c)) st = stop_if_cancelled(c);
    if (st) goto done;
    stats->crossings = X.nx;
    stats->fan_vertices = A->na - A->ns;
    st = overlay_output(c, A, &B, &X, valence, P);
    if (st == SQ_OK) st = overlay_check(c, P, stats);
done:
    sq_overlay_free(&X);
    omega_disk_free(&B);
    return st;
}

/* Step 7': the cut surface on the disk once, then Omega triangulated in
 * its unit squares, and where that fails (over the budget, mostly) and
 * `rectangles` is 1, in the rectangles of its chords: fewer edges for the
 * surface to cross where Omega is large against the surface (femur,
 * rocker_arm, elk with guidance), more where it is not (fandisk, eight,
 * cup, helmet), hence second (docs/param.md, step 7'). */
sq_status sq_param_overlay_map(ctx *c, const int32_t *valence, int rectangles, sq_param *P,
                               sq_param_stats *stats)
{
    const sq_metapolygon *W = &c->O->cut;
    if (sq_tsurf_split_blocking(&c->S, 0) < 0 || sec_reserve(c)) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    uint32_t *oseq = malloc(((size_t)W->nbnd + 1) * sizeof *oseq);
    if (!oseq) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    surface_disk A;
    memset(&A, 0, sizeof A);
    sq_omega_cells C;
    sq_omega_cells_init(&C);
    sq_status st = sq_param_omega_boundary(W, oseq) == SQ_NONE
                       ? sq_error_set(c->err, SQ_ERR_INTERNAL, "Omega's boundary loop has not %u edges", W->nbnd)
                       : surface_disk_build(c, oseq, &A);
    if (st == SQ_OK) st = overlay_with(c, &A, oseq, NULL, valence, P, stats);
    if (st == SQ_ERR_SOLVER && rectangles) {
        sq_param_free(P);
        st = sq_omega_cells_build(c->O, 0, NULL, &C, c->err);
        if (st == SQ_OK) st = overlay_with(c, &A, oseq, &C, valence, P, stats);
    }
    sq_omega_cells_free(&C);
    surface_disk_free(&A);
    free(oseq);
    return st;
}

/* SQ_INTERIOR_AUTO: the cells have passed; the overlay (step 7') on the
 * same cut, tree and boundary map (the state saved before the cells)
 * replaces their map when it passes as well: it is far less distorted
 * (docs/param.md, step 7'). Its failure (over the budget, degenerate) is
 * not an error: the cells' map stays. Only running out of memory is. */
sq_status sq_param_overlay_after_cells(ctx *c, const sq_param_before_cells *saved, const int32_t *valence,
                                       sq_param *out, sq_param_stats *stats)
{
    sq_param P;
    sq_param_init(&P);
    sq_param_stats s = *stats;
    sq_error e, *keep = c->err;
    sq_error_clear(&e);
    c->err = &e;
    free(c->h_uv); /* it describes the surface being dropped */
    c->h_uv = NULL;
    progress(c, "overlay (after the cells)", 0.9);
    sq_status st = sq_param_before_cells_restore(c, saved);
    /* the unit squares only: after the cells, the rectangles never made
     * the overlay pass on the shared models and cost up to 1.4 s more */
    if (st == SQ_OK) st = sq_param_overlay_map(c, valence, 0, &P, &s);
    /* the independent check too, before it replaces a map that passed:
     * a failure here falls back to the cells' map instead of ending the
     * run (the overlay is bijective in exact arithmetic; its UVs are not) */
    if (st == SQ_OK) st = sq_param_verify(&P, SQ_PARAM_VERIFY_INTEGER, &e) ? SQ_ERR_SOLVER : SQ_OK;
    c->err = keep;
    if (st == SQ_OK) {
        sq_param_free(out);
        *out = P;
        s.overlay = 1;
        s.chords = s.cells = s.rounds = s.cells_refined = 0;
        *stats = s;
        return SQ_OK;
    }
    sq_param_free(&P);
    if (st == SQ_ERR_NOMEM) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    return SQ_OK;
}
