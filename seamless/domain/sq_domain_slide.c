/* seamquad: one slide for patterns that fail the rank test (seed 6.4, 9.3;
 * seamless-notes 3, 7). See sq_domain_slide.h and docs/domain.md,
 * "Sliding".
 *
 * Boundary positions: the boundary vertices of the unpadded subdivided
 * metapolygon Q0 are numbered 0..nbnd-1 in boundary (clockwise) order from
 * metapolygon corner 0, so metapolygon side j covers positions cpos[j] ..
 * cpos[j+1]. A straight sequence from position ps to position pe (ps < pe)
 * splits Q0 into piece A (boundary arc ps..pe, then the sequence back) and
 * piece B (arc pe..ps+nbnd, then the sequence back). A piece's sides are
 * the arc cut at the original corners, then its split side last; side 0 of
 * A starts at ps, side 0 of B at pe. */
#include "sq_domain_slide.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "sq_domain_genus1.h" /* sq_g1_quads_to_disk */
#include "sq_domain_internal.h"
#include "sq_padding.h"

#define SPLIT UINT32_MAX

/* Most side correspondences tried per sequence (as sq_domain.c). */
#define MAX_OFFSETS 40u
/* Candidates improved by the solver's descent (seed 9.3) after phase 1. */
#define DESCENT_CANDIDATES 8u
/* Candidates built per pass before giving up on a simple glued mesh. */
#define MAX_BUILDS 24u

typedef struct slide_seq {
    uint32_t ps, pe;   /* boundary positions of the ends, ps < pe          */
    uint32_t first_he; /* halfedge leaving the vertex at ps along the line  */
    uint32_t len;      /* edges                                             */
    uint32_t c1;       /* corners of piece A (c2 = k + 4 - c1)              */
} slide_seq;

typedef struct piece_side {
    uint32_t orig; /* metapolygon side it is part of, SPLIT for the split */
    uint32_t p0;   /* boundary position of its first vertex (mod nbnd)   */
    uint32_t len;  /* quad edges before padding                          */
} piece_side;

typedef struct candidate {
    uint32_t seq, offset;
    uint64_t added;
    int64_t *w; /* system sides: piece A's, then piece B's */
} candidate;

typedef struct slide_ctx {
    const sq_metapolygon *Q0; /* unpadded subdivided metapolygon        */
    uint32_t k, nbnd;
    uint32_t *bnd;       /* nbnd: boundary vertex at each position            */
    uint32_t *corner_at; /* nbnd: metapolygon corner at the position, or SPLIT */
    uint32_t *side_at;   /* nbnd: metapolygon side holding the position        */
    uint32_t *cpos;      /* k + 1: position of corner j, cpos[k] = nbnd        */
} slide_ctx;

static uint32_t walk(const sq_metapolygon *P, uint32_t h, uint64_t steps)
{
    for (uint64_t t = 0; t < steps; t++) h = P->he_next[h];
    return h;
}

static int is_boundary(const sq_metapolygon *P, uint32_t v)
{
    return P->he_face[P->v_he[v]] == SQ_NONE;
}

/* Seed 6.4, 9.3: the straight sequence from the flat boundary vertex v:
 * its interior edge, then through every interior vertex along the opposite
 * edge (valence 4) until the boundary. Returns the number of edges (>= 1)
 * and its last vertex, or 0 when it meets a cone or itself. mark (nv
 * entries, zero) is left zero. he_out (nv entries, optional) receives the
 * halfedges in order. */
static uint32_t trace(const sq_metapolygon *P, uint32_t v, uint8_t *mark, uint32_t *he_out,
                      uint32_t *end, uint32_t *first)
{
    uint32_t hb = P->v_he[v];
    assert(P->he_face[hb] == SQ_NONE && P->v_nface[v] == 2);
    uint32_t g = P->he_next[P->he_twin[hb]]; /* the interior edge at v */
    assert(P->he_vert[g] == v);
    *first = g;
    uint32_t n = 0, ok = 1;
    for (;;) {
        if (he_out) he_out[n] = g;
        n++;
        uint32_t x = P->he_vert[P->he_next[g]];
        if (is_boundary(P, x)) {
            *end = x;
            break;
        }
        if (P->v_nface[x] != 4 || mark[x] || n >= P->nv) { /* a cone, or a crossing */
            ok = 0;
            break;
        }
        mark[x] = 1;
        g = P->he_next[P->he_twin[P->he_next[g]]]; /* the opposite edge at x */
    }
    /* unmark */
    uint32_t h = *first;
    for (uint32_t t = 0; t + 1 < n; t++) {
        mark[P->he_vert[P->he_next[h]]] = 0;
        h = P->he_next[P->he_twin[P->he_next[h]]];
    }
    return ok ? n : 0;
}

/* The sides of a piece: the boundary arc from..to (to <= from + nbnd) cut
 * at the metapolygon corners inside it, then the split side. */
static uint32_t arc_sides(const slide_ctx *c, uint32_t from, uint32_t to, uint32_t split_len,
                          piece_side *out)
{
    uint32_t n = 0, start = from;
    for (uint32_t q = from + 1; q < to; q++) {
        if (c->corner_at[q % c->nbnd] == SPLIT) continue;
        out[n++] = (piece_side){c->side_at[start % c->nbnd], start % c->nbnd, q - start};
        start = q;
    }
    out[n++] = (piece_side){c->side_at[start % c->nbnd], start % c->nbnd, to - start};
    out[n++] = (piece_side){SPLIT, to % c->nbnd, split_len};
    return n;
}

/* Seed 6.3 with a split (seamless-notes 3): two pieces, zero padding on the
 * split sides, every pair of the pattern equal as sums of sub-sides, and
 * both split sides equally long. */
static sq_status make_system(const slide_ctx *c, const piece_side *sd, uint32_t nA, uint32_t nB,
                             const sq_pattern *pat, uint32_t off, sq_pad_system *S, sq_error *err)
{
    int64_t L[2 * 64 + 8];
    uint8_t fl[2 * 64 + 8];
    int64_t *Lh = NULL;
    uint8_t *fh = NULL;
    int64_t *Lp = L;
    uint8_t *fp = fl;
    const uint32_t ns = nA + nB;
    if (ns > sizeof L / sizeof L[0]) {
        Lh = malloc((size_t)ns * sizeof *Lh);
        fh = malloc((size_t)ns);
        if (!Lh || !fh) {
            free(Lh), free(fh);
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        }
        Lp = Lh, fp = fh;
    }
    for (uint32_t s = 0; s < ns; s++) {
        Lp[s] = sd[s].len;
        fp[s] = sd[s].orig == SPLIT ? SQ_PAD_ZERO : 0;
    }
    sq_status st = sq_pad_system_add_piece(S, nA, Lp, fp, err);
    if (!st) st = sq_pad_system_add_piece(S, nB, Lp + nA, fp + nA, err);
    free(Lh), free(fh);
    uint32_t side[8];
    int32_t coef[8];
    for (uint32_t i = 0; i < c->k && !st; i++) {
        const uint32_t p = pat->partner[i];
        if (p < i) continue;
        const uint32_t m = (i + off) % c->k, mp = (p + off) % c->k;
        uint32_t n = 0;
        for (uint32_t s = 0; s < ns && n < 8; s++) {
            if (sd[s].orig == m) side[n] = s, coef[n++] = 1;
            else if (sd[s].orig == mp) side[n] = s, coef[n++] = -1;
        }
        st = sq_pad_system_add_constraint(S, n, side, coef, err);
    }
    if (!st) {
        side[0] = nA - 1, coef[0] = 1;
        side[1] = ns - 1, coef[1] = -1;
        st = sq_pad_system_add_constraint(S, 2, side, coef, err);
    }
    return st;
}

/* Seed 6.1 on one piece with n >= 2 sides: w[s] layers on side s, keeping
 * the corners cv (side s runs from cv[s] to cv[s+1]) and lengths. */
static sq_status pad_piece(sq_metapolygon *P, uint32_t n, uint32_t *cv, uint32_t *len,
                           const int64_t *w, sq_error *err)
{
    for (uint32_t s = 0; s < n; s++) {
        if (w[s] == 0) continue;
        if (w[s] < 0 || w[s] > UINT32_MAX / 4)
            return sq_error_set(err, SQ_ERR_INTERNAL, "slide padding %lld out of range",
                                (long long)w[s]);
        const uint32_t prev = (s + n - 1) % n, next = (s + 1) % n;
        const uint32_t h = P->v_he[cv[s]];
        assert(P->he_face[h] == SQ_NONE);
        const uint32_t hin = sq_metapolygon_boundary_prev(P, h); /* stays on the boundary */
        sq_status st = sq_metapolygon_glue_grid(P, h, (uint32_t)w[s], len[s], 1, err);
        if (st) return st;
        /* the boundary now climbs the grid's first column from cv[s] */
        uint32_t g = walk(P, P->he_next[hin], (uint64_t)w[s]);
        cv[s] = P->he_vert[g];
        cv[next] = P->he_vert[walk(P, g, len[s])];
        len[prev] += (uint32_t)w[s];
        len[next] += (uint32_t)w[s];
    }
    return SQ_OK;
}

/* One piece of Q0 (the faces with face_piece == p) as its own disk; lv
 * (Q0->nv entries) receives local vertex ids, forig the Q0 face of each
 * local face. */
static sq_status piece_disk(const sq_metapolygon *Q0, const uint8_t *face_piece, uint8_t p,
                            uint32_t *lv, uint32_t *forig, uint32_t *nf_out, sq_metapolygon *P,
                            sq_error *err)
{
    uint32_t nf = 0, nv = 0;
    for (uint32_t f = 0; f < Q0->nf; f++) nf += face_piece[f] == p;
    uint32_t *quad = malloc(4 * ((size_t)nf + 1) * sizeof *quad);
    if (!quad) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t v = 0; v < Q0->nv; v++) lv[v] = SQ_NONE;
    uint32_t t = 0;
    for (uint32_t f = 0; f < Q0->nf; f++) {
        if (face_piece[f] != p) continue;
        uint32_t h = Q0->f_he[f];
        for (uint32_t i = 0; i < 4; i++, h = Q0->he_next[h]) {
            uint32_t v = Q0->he_vert[h];
            if (lv[v] == SQ_NONE) lv[v] = nv++;
            quad[4 * (size_t)t + i] = lv[v];
        }
        forig[t++] = f;
    }
    *nf_out = nf;
    sq_status st = sq_g1_quads_to_disk(nv, nf, quad, P, err);
    free(quad);
    return st;
}

/* Faces of piece A (face_piece 0, the rest 1): reachable from the face at
 * boundary position s->ps without crossing the sequence s (blocked: its
 * halfedges, set here). queue: scratch. */
static sq_status mark_piece_a(const sq_metapolygon *Q0, const slide_ctx *c, const slide_seq *s, uint8_t *blocked,
                              uint8_t *face_piece, uint32_t *queue, sq_error *err)
{
    for (uint32_t t = 0, g = s->first_he; t < s->len; t++) {
        blocked[g] = blocked[Q0->he_twin[g]] = 1;
        g = Q0->he_next[Q0->he_twin[Q0->he_next[g]]];
    }
    memset(face_piece, 1, Q0->nf);
    const uint32_t f0 = Q0->he_face[Q0->he_twin[Q0->v_he[c->bnd[s->ps]]]];
    uint32_t head = 0, tail = 0;
    face_piece[f0] = 0;
    queue[tail++] = f0;
    while (head < tail) {
        const uint32_t f = queue[head++];
        uint32_t h = Q0->f_he[f];
        for (uint32_t i = 0; i < Q0->f_valence[f]; i++, h = Q0->he_next[h]) {
            if (blocked[h]) continue;
            const uint32_t g = Q0->he_face[Q0->he_twin[h]];
            if (g == SQ_NONE || face_piece[g] == 0) continue;
            face_piece[g] = 0;
            queue[tail++] = g;
        }
    }
    if (tail == Q0->nf) return sq_error_set(err, SQ_ERR_INTERNAL, "the straight sequence does not split Q");
    return SQ_OK;
}

/* The slide's description (sq_slide_info) for sequence s, pieces of nA and
 * nB sides padded by w, the seam from seam0 to seam1. */
static void fill_info(sq_slide_info *info, const slide_ctx *c, const slide_seq *s, uint32_t nA, uint32_t nB,
                      const int64_t *w, uint32_t seam0, uint32_t seam1)
{
    info->start_vertex = c->bnd[s->ps];
    info->end_vertex = c->bnd[s->pe];
    info->start_side = c->side_at[s->ps];
    info->start_pos = s->ps - c->cpos[info->start_side];
    info->end_side = c->side_at[s->pe];
    info->end_pos = s->pe - c->cpos[info->end_side];
    info->length = s->len;
    info->corners[0] = nA;
    info->corners[1] = nB;
    info->shift = w[0] - w[nA + nB - 2];
    info->seam_start = seam0;
    info->seam_end = seam1;
}

/* Seed 6.4: split Q0 along sequence s, pad both pieces by w, glue them
 * back along the split sides (the slide) and install the result in D. */
static sq_status build_candidate(sq_domain *D, const slide_ctx *c, const uint32_t *fmf0,
                                 const slide_seq *s, const piece_side *sd, uint32_t nA,
                                 uint32_t nB, uint32_t off, const int64_t *w,
                                 sq_slide_info *info, sq_error *err)
{
    const sq_metapolygon *Q0 = c->Q0;
    const uint32_t k = c->k, ns = nA + nB;
    sq_status st = SQ_OK;
    sq_metapolygon P[2], M;
    sq_metapolygon_init(&P[0]), sq_metapolygon_init(&P[1]), sq_metapolygon_init(&M);
    uint8_t *face_piece = malloc((size_t)Q0->nf + 1);
    uint8_t *blocked = calloc((size_t)Q0->nh + 1, 1);
    uint32_t *queue = malloc(((size_t)Q0->nf + 1) * sizeof *queue);
    uint32_t *lv[2] = {malloc(((size_t)Q0->nv + 1) * sizeof(uint32_t)),
                       malloc(((size_t)Q0->nv + 1) * sizeof(uint32_t))};
    uint32_t *forig[2] = {malloc(((size_t)Q0->nf + 1) * sizeof(uint32_t)),
                          malloc(((size_t)Q0->nf + 1) * sizeof(uint32_t))};
    uint32_t *cv = malloc(((size_t)ns + 1) * sizeof *cv);
    uint32_t *ln = malloc(((size_t)ns + 1) * sizeof *ln);
    uint32_t *mB = NULL, *quad = NULL, *fmf = NULL, *corner = NULL, *slen = NULL;
    int64_t *pad = NULL;
    uint32_t nf0[2] = {0, 0};
    if (!face_piece || !blocked || !queue || !lv[0] || !lv[1] || !forig[0] || !forig[1] || !cv ||
        !ln) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    st = mark_piece_a(Q0, c, s, blocked, face_piece, queue, err);
    if (st) goto done;
    /* both pieces as disks, their corners and sides */
    for (uint8_t p = 0; p < 2 && !st; p++)
        st = piece_disk(Q0, face_piece, p, lv[p], forig[p], &nf0[p], &P[p], err);
    if (st) goto done;
    for (uint32_t t = 0; t < ns; t++) {
        const uint32_t p = t >= nA, first = p ? nA : 0, n = p ? nB : nA;
        cv[t] = lv[p][c->bnd[sd[t].p0]];
        ln[t] = sd[t].len;
        const uint32_t nxt = first + (t - first + 1) % n;
        if (cv[t] == SQ_NONE || P[p].v_nface[cv[t]] != 1 ||
            P[p].he_vert[walk(&P[p], P[p].v_he[cv[t]], ln[t])] != lv[p][c->bnd[sd[nxt].p0]]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "piece %u side %u is not a side of its disk",
                              p, t - first);
            goto done;
        }
    }
    /* seed 6.1: pad each piece (zero on the split sides) */
    st = pad_piece(&P[0], nA, cv, ln, w, err);
    if (!st) st = pad_piece(&P[1], nB, cv + nA, ln + nA, w + nA, err);
    if (st) goto done;
    if (ln[nA - 1] != ln[ns - 1]) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "split sides have %u and %u edges after padding",
                          ln[nA - 1], ln[ns - 1]);
        goto done;
    }
    /* seed 6.4: glue B's split side backward onto A's (the slide) */
    const uint32_t L = ln[nA - 1];
    mB = malloc(((size_t)P[1].nv + 1) * sizeof *mB);
    const uint32_t nf = P[0].nf + P[1].nf;
    quad = malloc(4 * ((size_t)nf + 1) * sizeof *quad);
    fmf = malloc(((size_t)nf0[0] + nf0[1] + 1) * sizeof *fmf);
    corner = malloc((size_t)k * sizeof *corner);
    slen = malloc((size_t)k * sizeof *slen);
    pad = malloc(((size_t)k + 2) * sizeof *pad);
    if (!mB || !quad || !fmf || !corner || !slen || !pad) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < P[1].nv; v++) mB[v] = SQ_NONE;
    {
        uint32_t ha = P[0].v_he[cv[nA - 1]], hb = P[1].v_he[cv[ns - 1]];
        uint32_t *sb = malloc(((size_t)L + 1) * sizeof *sb);
        if (!sb) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
        for (uint32_t t = 0; t <= L; t++, hb = P[1].he_next[hb]) sb[t] = P[1].he_vert[hb];
        for (uint32_t t = 0; t <= L; t++, ha = P[0].he_next[ha]) mB[sb[L - t]] = P[0].he_vert[ha];
        free(sb);
    }
    uint32_t nv = P[0].nv;
    for (uint32_t v = 0; v < P[1].nv; v++)
        if (mB[v] == SQ_NONE) mB[v] = nv++;
    /* faces: both pieces' subdivision quads first (f_meta_face), then the
     * padding quads */
    {
        uint32_t t = 0;
        for (uint32_t pass = 0; pass < 2; pass++)
            for (uint32_t p = 0; p < 2; p++) {
                const uint32_t lo = pass ? nf0[p] : 0, hi = pass ? P[p].nf : nf0[p];
                for (uint32_t f = lo; f < hi; f++, t++) {
                    if (!pass) fmf[t] = fmf0[forig[p][f]];
                    uint32_t h = P[p].f_he[f];
                    for (uint32_t i = 0; i < 4; i++, h = P[p].he_next[h]) {
                        const uint32_t v = P[p].he_vert[h];
                        quad[4 * (size_t)t + i] = p ? mB[v] : v;
                    }
                }
            }
    }
    st = sq_g1_quads_to_disk(nv, nf, quad, &M, err);
    if (st) goto done;
    /* Q's corners and sides (metapolygon numbering m; pattern side i is
     * m = i + off) */
    for (uint32_t m = 0; m < k; m++) corner[m] = SQ_NONE, slen[m] = 0;
    for (uint32_t t = 0; t < ns; t++) {
        if (sd[t].orig == SPLIT) continue;
        const uint32_t m = sd[t].orig, v = t < nA ? cv[t] : mB[cv[t]];
        slen[m] += ln[t];
        if (sd[t].p0 == c->cpos[m]) {
            corner[m] = v;
            pad[(m + k - off) % k] = w[t];
        }
    }
    pad[k] = w[0];
    pad[k + 1] = w[nA];
    for (uint32_t m = 0; m < k; m++)
        if (corner[m] == SQ_NONE || M.v_nface[corner[m]] != 1) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "corner %u is lost by the slide", m);
            goto done;
        }
    const uint32_t seam0 = cv[0], seam1 = cv[nA - 1];
    if (M.v_nface[seam0] != 2 || M.v_nface[seam1] != 2) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "a seam end is not flat after the slide");
        goto done;
    }
    /* install */
    sq_metapolygon_free(&D->quads);
    D->quads = M;
    sq_metapolygon_init(&M);
    free(D->f_meta_face), free(D->padding);
    D->f_meta_face = fmf, fmf = NULL;
    D->padding = pad, pad = NULL;
    for (uint32_t i = 0; i < k; i++) {
        D->corner_vert[i] = corner[(i + off) % k];
        D->side_len[i] = slen[(i + off) % k];
    }
    D->offset = off;
    D->refine = 1;
    D->quads_added = D->quads.nf - D->quads_unpadded;
    if (info) fill_info(info, c, s, nA, nB, w, seam0, seam1);
done:
    sq_metapolygon_free(&P[0]), sq_metapolygon_free(&P[1]), sq_metapolygon_free(&M);
    free(face_piece), free(blocked), free(queue), free(lv[0]), free(lv[1]);
    free(forig[0]), free(forig[1]), free(cv), free(ln), free(mB), free(quad), free(fmf);
    free(corner), free(slen), free(pad);
    return st;
}

static int cmp_cand(const void *x, const void *y)
{
    const candidate *a = x, *b = y;
    if (a->added != b->added) return a->added < b->added ? -1 : 1;
    if (a->seq != b->seq) return a->seq < b->seq ? -1 : 1;
    return (a->offset > b->offset) - (a->offset < b->offset);
}

/* state shared by the steps of sq_domain_slide_build */
typedef struct slide_run {
    sq_domain *D;
    slide_ctx *c;
    const sq_metapolygon *Q0;
    const uint32_t *corner_v, *len;
    sq_slide_info *info;
    uint32_t *fmf0, *pos, *offs;
    uint8_t *mark;
    slide_seq *seqs;
    candidate *cand;
    piece_side *sd;
    uint32_t nseq, ncand, noffs;
    uint32_t noff_ok; /* offsets with a feasible point */
    sq_pad_system *S;
} slide_run;

/* boundary positions from corner 0; the corners' positions and sides */
static sq_status slide_positions(slide_run *sr, sq_error *err)
{
    const sq_metapolygon *Q0 = sr->Q0;
    slide_ctx *c = sr->c;
    const uint32_t k = c->k, *corner_v = sr->corner_v, *len = sr->len;
    uint32_t *pos = sr->pos;
    for (uint32_t v = 0; v < Q0->nv; v++) pos[v] = SQ_NONE;
    {
        uint32_t h = Q0->v_he[corner_v[0]];
        for (uint32_t p = 0; p < c->nbnd; p++, h = Q0->he_next[h]) {
            c->bnd[p] = Q0->he_vert[h];
            pos[c->bnd[p]] = p;
            c->corner_at[p] = SPLIT;
        }
    }
    for (uint32_t j = 0, p = 0; j < k; j++) {
        if (pos[corner_v[j]] != p || Q0->v_nface[corner_v[j]] != 1)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "slide: corner %u is not %u edges along the boundary", j, p);
        c->cpos[j] = p;
        c->corner_at[p] = j;
        for (uint32_t q = p; q < p + len[j] && q < c->nbnd; q++) c->side_at[q] = j;
        p += len[j];
        if (j == k - 1 && p != c->nbnd)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "slide: sides cover %u of %u boundary edges", p, c->nbnd);
    }
    c->cpos[k] = c->nbnd;
    return SQ_OK;
}

/* seed 9.3: every straight sequence, found from its earlier end; keep
 * those with c1 mod 4 != 0 (seed 6.4) */
static void slide_sequences(slide_run *sr)
{
    const sq_metapolygon *Q0 = sr->Q0;
    const slide_ctx *c = sr->c;
    const uint32_t k = c->k, *pos = sr->pos;
    sq_slide_info *info = sr->info;
    uint32_t nseq = 0;
    for (uint32_t p = 0; p < c->nbnd; p++) {
        if (c->corner_at[p] != SPLIT || Q0->v_nface[c->bnd[p]] != 2) continue;
        uint32_t end, first, n = trace(Q0, c->bnd[p], sr->mark, NULL, &end, &first);
        if (n == 0 || pos[end] == SQ_NONE || pos[end] <= p) continue;
        info->sequences++;
        uint32_t c1 = 2;
        for (uint32_t j = 0; j < k; j++) c1 += c->cpos[j] > p && c->cpos[j] < pos[end];
        if (c1 % 4 == 0) continue;
        sr->seqs[nseq++] = (slide_seq){p, pos[end], first, n, c1};
    }
    info->valid = nseq;
    sr->nseq = nseq;
}

/* phase 1: the first feasible point of every (sequence, offset) */
static sq_status slide_phase1(slide_run *sr, sq_error *err)
{
    sq_domain *D = sr->D;
    const slide_ctx *c = sr->c;
    const uint32_t k = c->k, noffs = sr->noffs, *offs = sr->offs;
    sq_slide_info *info = sr->info;
    piece_side *sd = sr->sd;
    sq_pad_system *S = sr->S;
    sq_status st = SQ_OK;
    size_t cap = 16;
    candidate *cand = sr->cand = malloc(cap * sizeof *cand);
    uint8_t *off_ok = calloc((size_t)k + 1, 1);
    if (!cand || !off_ok) {
        free(off_ok);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t q = 0; q < sr->nseq && !st; q++) {
        const slide_seq *s = &sr->seqs[q];
        uint32_t nA = arc_sides(c, s->ps, s->pe, s->len, sd);
        uint32_t nB = arc_sides(c, s->pe, s->ps + c->nbnd, s->len, sd + nA);
        assert(nA == s->c1 && nA + nB == k + 4);
        for (uint32_t oi = 0; oi < noffs && !st; oi++) {
            sq_pad_system_free(S);
            sq_pad_system_init(S);
            st = make_system(c, sd, nA, nB, &D->pattern, offs[oi], S, err);
            if (st) break;
            int64_t *w = malloc(((size_t)nA + nB) * sizeof *w);
            if (!w) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                break;
            }
            sq_pad_result res;
            memset(&res, 0, sizeof res);
            res.w = w;
            sq_pad_options popt = {SQ_PAD_OPT_NO_DESCENT, 0};
            if (sq_pad_solve(S, &popt, &res, NULL) != SQ_OK || res.outcome != SQ_PAD_SOLVED ||
                res.d != 1) {
                free(w);
                continue;
            }
            if (sr->ncand == cap) {
                candidate *nc = realloc(cand, 2 * cap * sizeof *cand);
                if (!nc) {
                    free(w);
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
                sr->cand = cand = nc, cap *= 2;
            }
            cand[sr->ncand++] = (candidate){q, offs[oi], res.added_quads, w};
            off_ok[offs[oi]] = 1;
        }
    }
    uint32_t noff_ok = 0;
    for (uint32_t o = 0; o < k; o++) noff_ok += off_ok[o];
    free(off_ok);
    sr->noff_ok = noff_ok;
    if (st) return st;
    info->feasible = sr->ncand;
    if (sr->ncand == 0) {
        const uint32_t rank = sq_pattern_rank(&D->pattern);
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "no slide equalizes the pattern (rank %u%s): %u straight sequences, "
                            "%u of them with corner counts not divisible by 4, none has a "
                            "nonnegative integral padding for any of %u side correspondences "
                            "(seed 6.4)",
                            rank,
                            rank == 0 ? ": every pair glues by a translation, and one slide "
                                        "adds only one direction (seamless-notes 7)"
                                      : "",
                            info->sequences, info->valid, noffs);
    }
    return SQ_OK;
}

/* phase 2 (seed 9.3): descent on the most promising, then sort again */
static sq_status slide_phase2(slide_run *sr, sq_error *err)
{
    const slide_ctx *c = sr->c;
    candidate *cand = sr->cand;
    const uint32_t ncand = sr->ncand;
    piece_side *sd = sr->sd;
    sq_pad_system *S = sr->S;
    sq_status st = SQ_OK;
    qsort(cand, ncand, sizeof *cand, cmp_cand);
    const uint32_t top = ncand < DESCENT_CANDIDATES ? ncand : DESCENT_CANDIDATES;
    for (uint32_t t = 0; t < top && !st; t++) {
        const slide_seq *s = &sr->seqs[cand[t].seq];
        uint32_t nA = arc_sides(c, s->ps, s->pe, s->len, sd);
        uint32_t nB = arc_sides(c, s->pe, s->ps + c->nbnd, s->len, sd + nA);
        sq_pad_system_free(S);
        sq_pad_system_init(S);
        st = make_system(c, sd, nA, nB, &sr->D->pattern, cand[t].offset, S, err);
        if (st) break;
        int64_t *w = malloc(((size_t)nA + nB) * sizeof *w);
        if (!w) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        sq_pad_result res;
        memset(&res, 0, sizeof res);
        res.w = w;
        if (sq_pad_solve(S, NULL, &res, NULL) == SQ_OK && res.outcome == SQ_PAD_SOLVED &&
            res.d == 1 && res.added_quads < cand[t].added) {
            free(cand[t].w);
            cand[t].w = w;
            cand[t].added = res.added_quads;
        } else {
            free(w);
        }
    }
    if (st) return st;
    qsort(cand, top, sizeof *cand, cmp_cand);
    return SQ_OK;
}

/* build the cheapest whose glued mesh is simple; pass 1 adds one layer
 * on every non-split side, which keeps every equality (each sub-side
 * and each split side grows by 2 per pair of neighbours, docs) */
static sq_status slide_build_cheapest(slide_run *sr, sq_error *err)
{
    sq_domain *D = sr->D;
    const slide_ctx *c = sr->c;
    const uint32_t k = c->k, ncand = sr->ncand;
    candidate *cand = sr->cand;
    piece_side *sd = sr->sd;
    sq_status st = SQ_OK;
    int found = 0;
    for (uint32_t pass = 0; pass < 2 && !found && !st; pass++) {
        for (uint32_t t = 0; t < ncand && t < MAX_BUILDS && !found; t++) {
            const slide_seq *s = &sr->seqs[cand[t].seq];
            uint32_t nA = arc_sides(c, s->ps, s->pe, s->len, sd);
            uint32_t nB = arc_sides(c, s->pe, s->ps + c->nbnd, s->len, sd + nA);
            if (pass == 1)
                for (uint32_t u = 0; u < nA + nB; u++) cand[t].w[u] += sd[u].orig != SPLIT;
            st = build_candidate(D, c, sr->fmf0, s, sd, nA, nB, cand[t].offset, cand[t].w,
                                 sr->info, err);
            if (st) break;
            if (pass == 0 && D->quads_added != cand[t].added) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "slide padding added %llu quads, the solver predicted %llu",
                                  (unsigned long long)D->quads_added,
                                  (unsigned long long)cand[t].added);
                break;
            }
            for (uint32_t i = 0; i < k && !st; i++)
                if (D->side_len[i] != D->side_len[D->pattern.partner[i]])
                    st = sq_error_set(err, SQ_ERR_INTERNAL,
                                      "after the slide side %u has %u edges, its partner %u "
                                      "has %u",
                                      i, D->side_len[i], D->pattern.partner[i],
                                      D->side_len[D->pattern.partner[i]]);
            if (st) break;
            found = sq_domain_glued_is_simple(D);
        }
    }
    if (!st && !found)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "none of the %u feasible slides glues into a simple quad mesh",
                          ncand);
    if (!st) D->offsets_feasible = sr->noff_ok;
    return st;
}

sq_status sq_domain_slide_build(sq_domain *D, const uint32_t *corner_v, const uint32_t *len,
                                uint32_t fixed_offset, sq_slide_info *info, sq_error *err)
{
    const uint32_t k = D->k;
    const sq_metapolygon *Q = &D->quads;
    if (D->genus < 2 || k != 8 * D->genus - 4 || D->pattern.k != k || !Q->nf ||
        Q->nf != D->nf_unpadded || !D->f_meta_face || !D->corner_vert || !D->side_len)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "slide: D must hold the unpadded subdivided metapolygon of genus "
                            ">= 2 with its pattern");
    if (fixed_offset != SQ_NONE && fixed_offset >= k)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "offset %u out of range (k = %u)",
                            fixed_offset, k);
    sq_slide_info local;
    if (!info) info = &local;
    memset(info, 0, sizeof *info);

    sq_status st = SQ_OK;
    sq_metapolygon Q0;
    sq_metapolygon_init(&Q0);
    slide_ctx c = {&Q0, k, Q->nbnd, NULL, NULL, NULL, NULL};
    sq_pad_system S;
    sq_pad_system_init(&S);
    slide_run sr = {.D = D, .c = &c, .Q0 = &Q0, .corner_v = corner_v, .len = len,
                    .info = info, .S = &S};

    st = sq_metapolygon_copy(&Q0, Q, err);
    if (st) goto done;
    sr.fmf0 = malloc(((size_t)Q0.nf + 1) * sizeof *sr.fmf0);
    c.bnd = malloc(((size_t)c.nbnd + 1) * sizeof *c.bnd);
    c.corner_at = malloc(((size_t)c.nbnd + 1) * sizeof *c.corner_at);
    c.side_at = malloc(((size_t)c.nbnd + 1) * sizeof *c.side_at);
    c.cpos = malloc(((size_t)k + 1) * sizeof *c.cpos);
    sr.pos = malloc(((size_t)Q0.nv + 1) * sizeof *sr.pos);
    sr.mark = calloc((size_t)Q0.nv + 1, 1);
    sr.seqs = malloc(((size_t)c.nbnd + 1) * sizeof *sr.seqs);
    sr.offs = malloc(((size_t)k + 1) * sizeof *sr.offs);
    sr.sd = malloc(((size_t)k + 4) * sizeof *sr.sd);
    if (!sr.fmf0 || !c.bnd || !c.corner_at || !c.side_at || !c.cpos || !sr.pos || !sr.mark ||
        !sr.seqs || !sr.offs || !sr.sd) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    memcpy(sr.fmf0, D->f_meta_face, (size_t)Q0.nf * sizeof *sr.fmf0);
    if ((st = slide_positions(&sr, err))) goto done;
    slide_sequences(&sr);

    /* side correspondences, as sq_domain.c */
    if (fixed_offset != SQ_NONE) sr.offs[sr.noffs++] = fixed_offset;
    else {
        const uint32_t stride = k <= MAX_OFFSETS ? 1 : (k + MAX_OFFSETS - 1) / MAX_OFFSETS;
        for (uint32_t o = 0; o < k; o += stride) sr.offs[sr.noffs++] = o;
    }

    (void)((st = slide_phase1(&sr, err)) || (st = slide_phase2(&sr, err)) ||
           (st = slide_build_cheapest(&sr, err)));
done:
    for (uint32_t t = 0; t < sr.ncand; t++) free(sr.cand[t].w);
    free(sr.cand);
    sq_pad_system_free(&S);
    sq_metapolygon_free(&Q0);
    free(sr.fmf0), free(c.bnd), free(c.corner_at), free(c.side_at), free(c.cpos), free(sr.pos);
    free(sr.mark), free(sr.seqs), free(sr.offs), free(sr.sd);
    return st;
}
