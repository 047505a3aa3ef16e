/* seamquad: the genus-1 (torus) domain, seed 6.2 and 6.3 with two pieces.
 *
 * Why two pieces (seamless-notes 2, 7; docs/domain.md, "Genus 1"): one
 * metapolygon of a torus is a meta-4-gon, and the only torus pattern with
 * one branch point, a b a^-1 b^-1, glues by translations only, so padding
 * can never change its closure vector: padding alone equalizes it only when
 * the cones happen to close up. Following seed 6.2 (CSZZ19 uses 2 to 4
 * pieces) the cones are split into two groups of excess +2 and -2, each
 * built into its own metapolygon (seed 5.2): a meta-6-gon H and a
 * meta-2-gon T. The exhaustive enumeration of the 105 pairings of their 8
 * sides (sq_g1_patterns) leaves 6 that close into a torus with two regular
 * branch points (two classes of four right corners): H's opposite sides
 * pair up, and T is inserted into one opposite pair. A 6-gon and a 2-gon
 * have 6 mod 4 != 0 and 2 mod 4 != 0 sides, so neither has a padding
 * invariant, and padding every side of both once adds 2 to every side: the
 * exact solve always has a nonnegative integral solution without
 * refinement (proof in docs/domain.md; the test checks it over thousands
 * of random cone sets and side lengths).
 * Splits of excess +-1 (a meta-5-gon and a meta-3-gon) admit no such
 * pattern at all (0 of 105), which is Jucovic-Trenkler's exception {3, 5}:
 * every other torus cone multiset has a subset of excess -2 ({2}, {3,3} or
 * larger ones), see split_candidates.
 *
 * Steps:
 * 1. candidate splits of the cones (excess -2 for T, +2 for H), each built
 *    into two metapolygons and subdivided (seed 5.1-5.4);
 * 2. for every split and every one of the 6 patterns, the exact padding
 *    solve with two pieces and one equality per pair (seed 6.3,
 *    sq_pad_solve); candidates sorted by quads after padding (seed 9.3);
 * 3. the cheapest candidate: both pieces padded (seed 6.1), then glued
 *    along the pair that joins H to T (seed 6.3: "we only glue a subset so
 *    as to yield a disk topology mesh Q"). Q has 6 sides; the two ends of
 *    the glued pair become straight corners (90 + 90 degrees), one in each
 *    corner class, so each class is two right corners and one straight
 *    one;
 * 4. if the fully glued mesh is not simple (tiny sides of one quad glued
 *    to each other), the next candidate, then one more layer on every side
 *    of both pieces (adds 2 to every side: pairs stay equal).
 * No cones: an m x m grid with a b a^-1 b^-1 (m = 3, the smallest whose
 * glued torus is a simple mesh). */
#include "sq_domain_internal.h"

#include <stdlib.h>
#include <string.h>

#include "sq_domain_genus1.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_padding.h"

#define NPAT_MAX 8u     /* patterns of (6, 2) sides: 6                    */
#define NSPLIT_MAX 40u  /* candidate splits of the cones                 */
#define GRID_TORUS 3u   /* side of the cone-free torus grid               */

/* One metapolygon piece and its subdivision. */
typedef struct piece {
    uint32_t n;          /* cones in the piece        */
    uint32_t *order;     /* admissible valence order  */
    sq_metapolygon meta;
    sq_mp_quads sub;
} piece;

typedef struct split {
    piece p[2]; /* p[0]: the meta-6-gon H (excess +2); p[1]: the meta-2-gon T */
    uint64_t quads0;
} split;

typedef struct candidate {
    uint32_t split, pattern;
    uint64_t added;
    int64_t w[8];
} candidate;

static void piece_free(piece *p)
{
    free(p->order);
    sq_metapolygon_free(&p->meta);
    sq_mp_quads_free(&p->sub);
    memset(p, 0, sizeof *p);
}

/* Seed 5.2, 5.4: the metapolygon of `n` valences, subdivided; it must have
 * `corners` corners. keep: val is the construction order (seed 9.2, must
 * be admissible); build: glue-edge choices (NULL: seed 5.3). */
static sq_status piece_build(piece *p, const uint32_t *val, uint32_t n, uint32_t corners, int keep,
                             const sq_build_options *build, sq_error *err)
{
    memset(p, 0, sizeof *p);
    sq_metapolygon_init(&p->meta);
    p->n = n;
    p->order = malloc(((size_t)n + 1) * sizeof *p->order);
    if (!p->order) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    sq_status st = sq_domain_order(val, n, keep, p->order, err);
    if (st == SQ_OK) st = sq_metapolygon_build(&p->meta, p->order, n, build, NULL, err);
    if (st == SQ_OK) st = sq_metapolygon_subdivide(&p->meta, &p->sub, err);
    if (st == SQ_OK && p->sub.ncorner != corners)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "a piece of excess %d has %u corners, not %u",
                          (int)corners - 4, p->sub.ncorner, corners);
    return st;
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

/* Appends mask cur (n entries at mask + count * n) to the list if its
 * multiset of valences is new; returns the new count. */
static uint32_t add_if_new(const uint32_t *irr, uint32_t n, uint8_t *mask, uint32_t count,
                           uint32_t *key, uint32_t *key2)
{
    const uint8_t *cur = mask + (size_t)count * n;
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++)
        if (cur[i]) key[m++] = irr[i];
    qsort(key, m, sizeof *key, cmp_u32);
    for (uint32_t e = 0; e < count; e++) {
        uint32_t m2 = 0;
        for (uint32_t i = 0; i < n; i++)
            if (mask[(size_t)e * n + i]) key2[m2++] = irr[i];
        if (m2 != m) continue;
        qsort(key2, m2, sizeof *key2, cmp_u32);
        if (!memcmp(key, key2, (size_t)m * sizeof *key)) return count;
    }
    return count + 1;
}

/* A balancing order of the cones: a negative cone while the running excess
 * is above -2 (the one that lands on -2 when possible), else a positive
 * one (the smallest, or with `largest` the largest). prefix[t] is the
 * excess of seq[0..t]. */
static void balancing_order(const uint32_t *irr, uint32_t n, int largest, uint32_t *seq,
                            int64_t *prefix, uint8_t *used)
{
    memset(used, 0, n);
    int64_t sum = 0;
    for (uint32_t t = 0; t < n; t++) {
        uint32_t pick = UINT32_MAX;
        int want_neg = sum > -2;
        for (int pass = 0; pass < 2 && pick == UINT32_MAX; pass++, want_neg = !want_neg) {
            for (uint32_t i = 0; i < n; i++) {
                if (used[i] || (irr[i] < 4) != want_neg) continue;
                if (pick == UINT32_MAX) {
                    pick = i;
                } else if (want_neg) {
                    uint32_t best = sum == -1 ? 3u : 2u; /* 2 from 0, 3 from -1 */
                    if (irr[i] == best && irr[pick] != best) pick = i;
                } else if (largest ? irr[i] > irr[pick] : irr[i] < irr[pick]) {
                    pick = i;
                }
            }
        }
        used[pick] = 1;
        seq[t] = pick;
        sum += (int64_t)irr[pick] - 4;
        prefix[t] = sum;
    }
}

/* Seed 6.2: subsets of the cones of excess -2 (for the meta-2-gon), as
 * masks over irr (cap of them, n entries each). First one valence-2 cone
 * and two valence-3 cones; then the prefixes of excess -2 of two balancing
 * orders, spread evenly over their lengths (how the cones are shared
 * between the pieces changes the padding a lot, so several are tried and
 * the solve picks, seed 9.3). Distinct multisets only. Every torus multiset
 * except {3, 5} yields at least one: it has a valence-2 cone, or two
 * valence-3 cones, or else one valence-3 cone and positive cones adding up
 * to +1, which is {3, 5}. */
static uint32_t split_candidates(const uint32_t *irr, uint32_t n, uint8_t *mask, uint32_t cap)
{
    uint32_t count = 0;
    uint32_t *seq = malloc(((size_t)n + 1) * sizeof *seq);
    uint32_t *ends = malloc(((size_t)n + 1) * sizeof *ends);
    uint8_t *used = malloc((size_t)n + 1);
    uint32_t *key = malloc(((size_t)n + 1) * sizeof *key);
    uint32_t *key2 = malloc(((size_t)n + 1) * sizeof *key2);
    int64_t *prefix = malloc(((size_t)n + 1) * sizeof *prefix);
    if (!seq || !ends || !used || !key || !key2 || !prefix) goto done;

    for (uint32_t c = 0; c < 2 && count < cap; c++) { /* {2} or {3, 3} */
        uint8_t *cur = mask + (size_t)count * n;
        memset(cur, 0, n);
        uint32_t want = c == 0 ? 2 : 3, need = c == 0 ? 1 : 2, got = 0;
        for (uint32_t i = 0; i < n && got < need; i++)
            if (irr[i] == want) cur[i] = 1, got++;
        if (got == need) count = add_if_new(irr, n, mask, count, key, key2);
    }
    for (int largest = 0; largest < 2; largest++) {
        balancing_order(irr, n, largest, seq, prefix, used);
        uint32_t nends = 0;
        for (uint32_t t = 0; t + 1 < n; t++)
            if (prefix[t] == -2) ends[nends++] = t;
        const uint32_t room = (cap - count) / (2 - (uint32_t)largest);
        for (uint32_t e = 0; e < nends && e < room && count < cap; e++) {
            /* evenly spread when there are more ends than room */
            const uint32_t step = room > 1 ? room - 1 : 1;
            uint32_t t = nends <= room ? ends[e] : ends[(uint64_t)e * (nends - 1) / step];
            uint8_t *cur = mask + (size_t)count * n;
            memset(cur, 0, n);
            for (uint32_t j = 0; j <= t; j++) cur[seq[j]] = 1;
            count = add_if_new(irr, n, mask, count, key, key2);
        }
    }
done:
    free(seq), free(ends), free(used), free(key), free(key2), free(prefix);
    return count;
}

/* Seed 6.1: w[s] layers on every side s of a piece, in side order; keeps
 * corner_v (start vertex of each side) and len up to date. Padding side s
 * turns its start corner into a flat vertex of side s-1, w[s] edges before
 * the new corner; side s-1 and side s+1 grow by w[s] (by 2 w[s] when they
 * are the same side, k = 2). */
static sq_status pad_piece(sq_metapolygon *M, uint32_t k, const int64_t *w, uint32_t *corner_v,
                           uint32_t *len, sq_error *err)
{
    for (uint32_t s = 0; s < k; s++) {
        if (w[s] == 0) continue;
        if (w[s] < 0 || w[s] > (int64_t)(UINT32_MAX / 4))
            return sq_error_set(err, SQ_ERR_INTERNAL, "padding %lld out of range",
                                (long long)w[s]);
        const uint32_t ws = (uint32_t)w[s];
        uint32_t old = corner_v[s];
        sq_status st = sq_metapolygon_glue_grid(M, M->v_he[old], ws, len[s], 1, err);
        if (st) return st;
        uint32_t h = M->v_he[old];
        for (uint32_t t = 0; t < ws; t++) h = M->he_next[h];
        corner_v[s] = M->he_vert[h];
        for (uint32_t t = 0; t < len[s]; t++) h = M->he_next[h];
        corner_v[(s + 1) % k] = M->he_vert[h];
        if (M->v_nface[corner_v[s]] != 1 || M->v_nface[corner_v[(s + 1) % k]] != 1)
            return sq_error_set(err, SQ_ERR_INTERNAL, "padding side %u lost its corners", s);
        len[(s + k - 1) % k] += ws;
        len[(s + 1) % k] += ws;
    }
    return SQ_OK;
}

/* Vertices of the side starting at boundary vertex c, len + 1 entries. */
static void side_vertices(const sq_metapolygon *M, uint32_t c, uint32_t len, uint32_t *out)
{
    uint32_t h = M->v_he[c];
    for (uint32_t t = 0; t <= len; t++) {
        out[t] = M->he_vert[h];
        h = M->he_next[h];
    }
}

/* Quad vertex lists of M's faces [f0, f1) appended to quad, through the
 * vertex map. */
static uint32_t emit_quads(const sq_metapolygon *M, uint32_t f0, uint32_t f1, const uint32_t *map,
                           uint32_t *quad, uint32_t nq)
{
    for (uint32_t f = f0; f < f1; f++) {
        uint32_t h = M->f_he[f];
        for (uint32_t c = 0; c < 4; c++, h = M->he_next[h])
            quad[4 * (size_t)nq + c] = map[M->he_vert[h]];
        nq++;
    }
    return nq;
}

/* Step 3: pads both pieces of split S by w (+ extra on every side) and
 * glues them along the pair (glue, partner[glue]) into D->quads; fills
 * pattern, k, corner_vert, side_len and padding (8 entries: the 6 sides of
 * Q, then the glued pair's H side and T side). Replaces what D held. */
static sq_status assemble(const split *S, const uint32_t *partner, uint32_t glue,
                          const int64_t *w0, int64_t extra, sq_domain *D, sq_error *err)
{
    static const uint32_t K[2] = {6, 2};
    sq_metapolygon M[2];
    uint32_t corner[2][6], len[2][6];
    int64_t w[8];
    uint32_t *map = NULL, *quad = NULL, *sa = NULL, *sb = NULL;
    sq_status st = SQ_OK;
    sq_metapolygon_init(&M[0]);
    sq_metapolygon_init(&M[1]);
    for (uint32_t s = 0; s < 8; s++) w[s] = w0[s] + extra;
    for (uint32_t p = 0; p < 2 && st == SQ_OK; p++) {
        const sq_mp_quads *sub = &S->p[p].sub;
        st = sq_metapolygon_copy(&M[p], &sub->mesh, err);
        for (uint32_t j = 0; j < K[p] && st == SQ_OK; j++) {
            corner[p][j] = sub->bnd_vert[sub->corner_pos[j]];
            len[p][j] = sub->side_len[j];
        }
        if (st == SQ_OK) st = pad_piece(&M[p], K[p], w + (p ? 6 : 0), corner[p], len[p], err);
    }
    if (st) goto done;

    /* the glued pair: side g of H (forward) onto side q of T (backward) */
    const uint32_t g = glue, q = partner[glue] - 6;
    const uint32_t L = len[0][g];
    if (len[1][q] != L) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "glued sides have %u and %u edges", L, len[1][q]);
        goto done;
    }
    const uint32_t nv0 = M[0].nv, nv1 = M[1].nv;
    map = malloc(((size_t)nv0 + nv1) * sizeof *map);
    quad = malloc(4 * ((size_t)M[0].nf + M[1].nf) * sizeof *quad);
    sa = malloc(((size_t)L + 1) * sizeof *sa);
    sb = malloc(((size_t)L + 1) * sizeof *sb);
    if (!map || !quad || !sa || !sb) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    side_vertices(&M[0], corner[0][g], L, sa);
    side_vertices(&M[1], corner[1][q], L, sb);
    uint32_t *map1 = map + nv0;
    for (uint32_t v = 0; v < nv0; v++) map[v] = v;
    for (uint32_t v = 0; v < nv1; v++) map1[v] = SQ_NONE;
    for (uint32_t t = 0; t <= L; t++) map1[sb[L - t]] = sa[t];
    uint32_t nv = nv0;
    for (uint32_t v = 0; v < nv1; v++)
        if (map1[v] == SQ_NONE) map1[v] = nv++;

    /* faces: H's subdivision, T's subdivision, H's padding, T's padding */
    const uint32_t f0 = S->p[0].sub.mesh.nf, f1 = S->p[1].sub.mesh.nf;
    uint32_t nq = 0;
    nq = emit_quads(&M[0], 0, f0, map, quad, nq);
    nq = emit_quads(&M[1], 0, f1, map1, quad, nq);
    nq = emit_quads(&M[0], f0, M[0].nf, map, quad, nq);
    nq = emit_quads(&M[1], f1, M[1].nf, map1, quad, nq);

    sq_metapolygon_free(&D->quads);
    sq_metapolygon_init(&D->quads);
    st = sq_g1_quads_to_disk(nv, nq, quad, &D->quads, err);
    if (st) goto done;

    /* Q's sides: H's g+1 .. g+5, then T's q+1; straight corners 0 and 5 */
    D->k = 6;
    if (!D->corner_vert) D->corner_vert = malloc(6 * sizeof *D->corner_vert);
    if (!D->side_len) D->side_len = malloc(6 * sizeof *D->side_len);
    if (!D->padding) D->padding = malloc(8 * sizeof *D->padding);
    if (!D->corner_vert || !D->side_len || !D->padding) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    uint32_t piece_side[6], q_of[8];
    for (uint32_t i = 0; i < 8; i++) q_of[i] = SQ_NONE;
    for (uint32_t i = 0; i < 5; i++) piece_side[i] = (g + 1 + i) % 6;
    piece_side[5] = 6 + (q + 1) % 2;
    for (uint32_t i = 0; i < 6; i++) {
        uint32_t s = piece_side[i], p = s >= 6, j = p ? s - 6 : s;
        q_of[s] = i;
        D->corner_vert[i] = p ? map1[corner[1][j]] : map[corner[0][j]];
        D->side_len[i] = len[p][j];
        D->padding[i] = w[s];
    }
    D->padding[6] = w[g];     /* the glued pair: H's side, then T's side */
    D->padding[7] = w[6 + q];
    st = sq_pattern_alloc(&D->pattern, 6, err);
    if (st) goto done;
    for (uint32_t i = 0; i < 6; i++) {
        uint32_t j = q_of[partner[piece_side[i]]];
        if (j == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "side %u of Q pairs with the glued side", i);
            goto done;
        }
        D->pattern.partner[i] = j;
    }
    D->pattern.straight[0] = D->pattern.straight[5] = 1;
    sq_pattern_info info;
    st = sq_pattern_validate(&D->pattern, &info, err);
    if (st == SQ_OK && info.genus != 1)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "Q's pattern has genus %u", info.genus);
done:
    sq_metapolygon_free(&M[0]);
    sq_metapolygon_free(&M[1]);
    free(map), free(quad), free(sa), free(sb);
    return st;
}

/* No cones: the GRID_TORUS x GRID_TORUS grid with a b a^-1 b^-1 (or the
 * caller's 4-sided genus-1 pattern). */
static sq_status build_flat(const sq_domain_options *opt, sq_domain *D, sq_error *err)
{
    const uint32_t m = GRID_TORUS;
    sq_status st = sq_metapolygon_make_grid(&D->meta, m, m, err);
    if (st) return st;
    if (opt && opt->pattern) {
        sq_pattern_info info;
        st = sq_pattern_validate(opt->pattern, &info, err);
        if (st == SQ_OK && (opt->pattern->k != 4 || info.genus != 1))
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "a torus without cones needs a 4-sided genus-1 pattern");
        for (uint32_t i = 0; st == SQ_OK && i < 4; i++)
            if (opt->pattern->straight && opt->pattern->straight[i])
                st = sq_error_set(err, SQ_ERR_ARGUMENT, "corner %u of the pattern is straight", i);
        if (st == SQ_OK) st = sq_pattern_copy(&D->pattern, opt->pattern, err);
    } else {
        st = sq_pattern_torus(&D->pattern, err);
    }
    if (st == SQ_OK) st = sq_metapolygon_copy(&D->quads, &D->meta, err);
    if (st) return st;
    D->k = 4;
    D->corner_vert = malloc(4 * sizeof *D->corner_vert);
    D->side_len = malloc(4 * sizeof *D->side_len);
    D->padding = calloc(4, sizeof *D->padding);
    D->f_meta_face = malloc((size_t)m * m * sizeof *D->f_meta_face);
    if (!D->corner_vert || !D->side_len || !D->padding || !D->f_meta_face)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    uint32_t vert[4], dist[4];
    if (sq_metapolygon_nonflat(&D->quads, 4, vert, NULL, dist) != 4)
        return sq_error_set(err, SQ_ERR_INTERNAL, "the torus grid is not a meta-4-gon");
    for (uint32_t i = 0; i < 4; i++) D->corner_vert[i] = vert[i], D->side_len[i] = dist[i];
    for (uint32_t f = 0; f < m * m; f++) D->f_meta_face[f] = f;
    D->nf_unpadded = m * m;
    D->quads_unpadded = (uint64_t)m * m;
    D->quads_added = 0;
    D->offset = 0;
    D->offsets_feasible = 1;
    D->refine = 1;
    if (!sq_domain_glued_is_simple(D))
        return sq_error_set(err, SQ_ERR_INTERNAL, "the %ux%u torus grid is not simple", m, m);
    return SQ_OK;
}

static int cmp_cand(const void *x, const void *y, const split *S)
{
    const candidate *a = x, *b = y;
    uint64_t ta = S[a->split].quads0 + a->added, tb = S[b->split].quads0 + b->added;
    if (ta != tb) return ta < tb ? -1 : 1;
    if (a->split != b->split) return a->split < b->split ? -1 : 1;
    return (a->pattern > b->pattern) - (a->pattern < b->pattern);
}

/* insertion sort (few candidates) with the split table as context */
static void sort_cands(candidate *c, uint32_t n, const split *S)
{
    for (uint32_t i = 1; i < n; i++) {
        candidate x = c[i];
        uint32_t j = i;
        while (j > 0 && cmp_cand(&c[j - 1], &x, S) > 0) c[j] = c[j - 1], j--;
        c[j] = x;
    }
}

/* Step 2: the exact two-piece padding solve (seed 6.3) for one split and
 * pattern. Returns 1 with w and added filled if solved without refinement. */
static int solve_candidate(const split *S, const uint32_t *partner, candidate *c)
{
    sq_pad_system sys;
    sq_pad_system_init(&sys);
    int64_t Lh[6], Lt[2];
    for (uint32_t j = 0; j < 6; j++) Lh[j] = S->p[0].sub.side_len[j];
    for (uint32_t j = 0; j < 2; j++) Lt[j] = S->p[1].sub.side_len[j];
    int ok = sq_pad_system_add_piece(&sys, 6, Lh, NULL, NULL) == SQ_OK &&
             sq_pad_system_add_piece(&sys, 2, Lt, NULL, NULL) == SQ_OK;
    for (uint32_t i = 0; i < 8 && ok; i++) {
        if (partner[i] < i) continue;
        uint32_t side[2] = {i, partner[i]};
        int32_t coef[2] = {1, -1};
        ok = sq_pad_system_add_constraint(&sys, 2, side, coef, NULL) == SQ_OK;
    }
    if (ok) {
        sq_pad_result res;
        memset(&res, 0, sizeof res);
        res.w = c->w;
        ok = sq_pad_solve(&sys, NULL, &res, NULL) == SQ_OK && res.outcome == SQ_PAD_SOLVED &&
             res.d == 1;
        c->added = res.added_quads;
    }
    sq_pad_system_free(&sys);
    return ok;
}

/* D, assembled from candidate c (of the ncand, on the splits S), is the
 * domain: its statistics, the meta-6-gon as D->meta (its quads come first
 * in Q) and the cones' order, the meta-6-gon's first. */
static sq_status take_chosen(sq_domain *D, split *S, const candidate *cand, uint32_t ncand, const candidate *c,
                             sq_error *err)
{
    D->offset = c->pattern;
    D->offsets_feasible = 0; /* feasible patterns of the chosen split */
    for (uint32_t e = 0; e < ncand; e++)
        D->offsets_feasible += cand[e].split == c->split;
    D->refine = 1;
    const uint64_t q0 = S[c->split].quads0;
    D->quads_unpadded = q0;
    D->quads_added = D->quads.nf - q0;
    /* the meta-6-gon is D->meta; its quads come first in Q */
    split *sp = &S[c->split];
    sq_metapolygon_free(&D->meta);
    D->meta = sp->p[0].meta;
    sq_metapolygon_init(&sp->p[0].meta);
    D->nf_unpadded = sp->p[0].sub.mesh.nf;
    free(D->f_meta_face);
    D->f_meta_face = malloc(((size_t)D->nf_unpadded + 1) * sizeof *D->f_meta_face);
    if (!D->f_meta_face) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t f = 0; f < D->nf_unpadded; f++)
        D->f_meta_face[f] = D->meta.he_face[sp->p[0].sub.f_origin[f]];
    memcpy(D->order, sp->p[0].order, (size_t)sp->p[0].n * sizeof *D->order);
    memcpy(D->order + sp->p[0].n, sp->p[1].order,
           (size_t)sp->p[1].n * sizeof *D->order);
    return SQ_OK;
}

sq_status sq_domain_build_genus1(const uint32_t *irr, uint32_t n, const sq_domain_options *opt,
                                 sq_domain *D, sq_error *err)
{
    if (n == 0) return build_flat(opt, D, err);
    if (opt && opt->pattern)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "a torus with cones is built from two pieces with their own side "
                            "pattern (seed 6.2, docs/domain.md); a pattern cannot be given");

    /* the 6 two-piece patterns of a meta-6-gon and a meta-2-gon */
    static const uint32_t K[2] = {6, 2};
    uint32_t pat[NPAT_MAX * 8], glue[NPAT_MAX];
    uint32_t npat = sq_g1_patterns(2, K, NPAT_MAX, pat, glue);
    if (npat == 0 || npat > NPAT_MAX)
        return sq_error_set(err, SQ_ERR_INTERNAL, "%u two-piece torus patterns", npat);
    for (uint32_t p = 0; p < npat; p++)
        if (glue[p] == UINT32_MAX)
            return sq_error_set(err, SQ_ERR_INTERNAL, "pattern %u has no pair to glue", p);
    uint32_t only = opt && opt->offset != SQ_NONE ? opt->offset : SQ_NONE;
    if (only != SQ_NONE && only >= npat)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "genus 1: offset %u names no two-piece pattern (0..%u)", only,
                            npat - 1);

    /* step 1: candidate splits */
    uint8_t *mask = malloc((size_t)NSPLIT_MAX * n);
    uint32_t *val = malloc(((size_t)n + 1) * sizeof *val);
    split *S = calloc(NSPLIT_MAX, sizeof *S);
    candidate *cand = calloc((size_t)NSPLIT_MAX * NPAT_MAX, sizeof *cand);
    uint32_t nsplit = 0, ncand = 0;
    sq_status st = SQ_OK;
    if (!mask || !val || !S || !cand) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* seed 9.2 (guided): the caller's split, each piece in its order */
    const int given = opt && opt->keep_order && opt->g1_split > 0;
    if (given && opt->g1_split >= n) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "genus 1: a split of %u of the %u cones into T",
                          opt->g1_split, n);
        goto done;
    }
    uint32_t nmask = 1;
    if (given) {
        int64_t ex = 0;
        for (uint32_t i = n - opt->g1_split; i < n; i++) ex += (int64_t)irr[i] - 4;
        if (ex != -2) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "genus 1: the given meta-2-gon's cones have excess %lld, not -2",
                              (long long)ex);
            goto done;
        }
        memset(mask, 0, n);
        memset(mask + (n - opt->g1_split), 1, opt->g1_split);
    } else {
        nmask = split_candidates(irr, n, mask, NSPLIT_MAX);
    }
    if (nmask == 0) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "genus 1: no subset of the cones has excess -2, so no two-piece "
                          "domain exists (only {3, 5} should get here, Jucovic-Trenkler)");
        goto done;
    }
    for (uint32_t s = 0; s < nmask; s++) {
        const uint8_t *m = mask + (size_t)s * n;
        split *sp = &S[nsplit];
        uint32_t nh = 0, nt = 0;
        for (uint32_t i = 0; i < n; i++)
            if (!m[i]) val[nh++] = irr[i];
        st = piece_build(&sp->p[0], val, nh, 6, given, given ? opt->build : NULL, err);
        for (uint32_t i = 0; i < n; i++)
            if (m[i]) val[nt++] = irr[i];
        if (st == SQ_OK) st = piece_build(&sp->p[1], val, nt, 2, given, NULL, err);
        if (st) {
            piece_free(&sp->p[0]), piece_free(&sp->p[1]);
            goto done;
        }
        sp->quads0 = (uint64_t)sp->p[0].sub.mesh.nf + sp->p[1].sub.mesh.nf;
        nsplit++;
    }

    /* step 2: exact padding solve per split and pattern (seed 6.3, 9.3) */
    for (uint32_t s = 0; s < nsplit; s++) {
        for (uint32_t p = 0; p < npat; p++) {
            if (only != SQ_NONE && p != only) continue;
            candidate *c = &cand[ncand];
            memset(c, 0, sizeof *c);
            c->split = s, c->pattern = p;
            if (solve_candidate(&S[s], pat + 8 * (size_t)p, c)) ncand++;
        }
    }
    D->offsets_feasible = ncand;
    if (ncand == 0) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "genus 1: none of %u splits x %u patterns has an integral padding "
                          "(the exact solve should always succeed: a bug)",
                          nsplit, only != SQ_NONE ? 1u : npat);
        goto done;
    }
    sort_cands(cand, ncand, S);

    /* steps 3-4: assemble the cheapest simple one */
    int found = 0;
    for (uint32_t pass = 0; pass < 3 && !found && st == SQ_OK; pass++) {
        for (uint32_t ci = 0; ci < ncand && !found; ci++) {
            const candidate *c = &cand[ci];
            const uint32_t *partner = pat + 8 * (size_t)c->pattern;
            st = assemble(&S[c->split], partner, glue[c->pattern], c->w, (int64_t)pass, D, err);
            if (st) break;
            const uint64_t q0 = S[c->split].quads0;
            if (pass == 0 && D->quads.nf != q0 + c->added) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "padding added %llu quads, the solver predicted %llu",
                                  (unsigned long long)(D->quads.nf - q0),
                                  (unsigned long long)c->added);
                break;
            }
            for (uint32_t i = 0; i < 6 && st == SQ_OK; i++)
                if (D->side_len[i] != D->side_len[D->pattern.partner[i]])
                    st = sq_error_set(err, SQ_ERR_INTERNAL,
                                      "after padding side %u has %u edges, its partner %u %u", i,
                                      D->side_len[i], D->pattern.partner[i],
                                      D->side_len[D->pattern.partner[i]]);
            if (st) break;
            found = sq_domain_glued_is_simple(D);
            if (found) st = take_chosen(D, S, cand, ncand, c, err);
        }
    }
    if (st == SQ_OK && !found)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "genus 1: none of %u padded candidates (with up to 2 extra layers) "
                          "glues into a simple quad mesh",
                          ncand);
done:
    for (uint32_t s = 0; s < nsplit; s++) piece_free(&S[s].p[0]), piece_free(&S[s].p[1]);
    free(mask), free(val), free(S), free(cand);
    return st;
}
