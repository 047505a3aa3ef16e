/* seamquad: metapolygon extension E(P, i), seed 5.1, Def. 5.4 and
 * Theorem 5.5.
 *
 * Step 1 glues an i-gon to a boundary edge; gluing raises the valence of
 * the edge's two endpoints by one (corner -> flat, flat -> concave) and
 * adds i-2 corners. Steps 2 and 3 then fill the (at most two) concave
 * vertices with regular grids, reading the configuration off C(P'), the
 * cyclic sequence of non-flat boundary vertices, and the distances d(v, w)
 * between them (sq_metapolygon_nonflat). The cases of the seed's Figure 4:
 *   b  corner-corner edge: no concave vertex, nothing to fill;
 *   c  2-gon on a flat-flat edge, d(v0,v1) = d(v2,v3): one step-2 grid;
 *   d  flat-corner edge: one concave vertex, one step-3 grid;
 *   e  2-gon on a flat-flat edge, d(v0,v1) != d(v2,v3): one step-2 grid
 *      leaves one concave vertex, one step-3 grid;
 *   f  i != 2 on a flat-flat edge: two separated concave vertices, two
 *      step-3 grids. */
#include "sq_metapolygon.h"

#include <assert.h>
#include <stdlib.h>

/* C(P') with the kind of every entry (scratch owned by the extension). */
typedef struct nonflat_seq {
    uint32_t n, cap;
    uint32_t *vert, *out_he, *dist;
} nonflat_seq;

static void seq_free(nonflat_seq *s)
{
    free(s->vert);
    free(s->out_he);
    free(s->dist);
}

static sq_status seq_read(const sq_metapolygon *P, nonflat_seq *s, sq_error *err)
{
    uint32_t n = sq_metapolygon_nonflat(P, 0, NULL, NULL, NULL);
    if (n > s->cap) {
        uint32_t cap = n + 8;
        uint32_t *a = realloc(s->vert, (size_t)cap * sizeof *a);
        if (a) s->vert = a;
        uint32_t *b = realloc(s->out_he, (size_t)cap * sizeof *b);
        if (b) s->out_he = b;
        uint32_t *c = realloc(s->dist, (size_t)cap * sizeof *c);
        if (c) s->dist = c;
        if (!a || !b || !c) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for C(P')");
        s->cap = cap;
    }
    s->n = sq_metapolygon_nonflat(P, s->cap, s->vert, s->out_he, s->dist);
    assert(s->n == n);
    return SQ_OK;
}

static uint32_t seq_kind(const sq_metapolygon *P, const nonflat_seq *s, uint32_t j)
{
    return P->v_nface[s->vert[j % s->n]];
}

static void seq_count(const sq_metapolygon *P, const nonflat_seq *s, uint32_t *corners,
                      uint32_t *concave)
{
    *corners = *concave = 0;
    for (uint32_t j = 0; j < s->n; j++) {
        uint32_t k = seq_kind(P, s, j);
        assert(k == SQ_MP_CORNER || k == SQ_MP_CONCAVE); /* Theorem 5.5 proof */
        if (k == SQ_MP_CORNER) (*corners)++;
        if (k == SQ_MP_CONCAVE) (*concave)++;
    }
}

/* Def. 5.4 input: meta-k-gon P (the empty one counts as k = 4), k > 0,
 * i > max(1, 4 - k), i != 4; *k_out: k. */
static sq_status check_input(const sq_metapolygon *P, uint32_t i, uint32_t *k_out, sq_error *err)
{
    const int empty = P->nf == 0;
    const uint32_t k = empty ? 4 : sq_metapolygon_count_corners(P);
    *k_out = k;
    if (i == 4)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "Def. 5.4: cannot extend by a 4-gon (regular faces are fill, not "
                            "cones)");
    if (i < 2)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "Def. 5.4: valence %u is below 2 (i > max(1, 4-k) is required)", i);
    if (!empty) {
        uint32_t h = P->bnd_he;
        do {
            uint32_t v = P->he_vert[h];
            if (P->v_nface[v] > 2)
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "Def. 5.4: input is not a metapolygon: boundary vertex %u "
                                    "has %u faces",
                                    v, P->v_nface[v]);
            h = P->he_next[h];
        } while (h != P->bnd_he);
        if (k == 0)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "Def. 5.4: input is a meta-0-gon; extension needs k > 0 corners");
    }
    if ((int64_t)i <= 4 - (int64_t)k)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "Def. 5.4: a %u-gon cannot extend a meta-%u-gon (needs i > 4 - k = "
                            "%d)",
                            i, k, 4 - (int)k);
    return SQ_OK;
}

sq_status sq_metapolygon_extend(sq_metapolygon *P, uint32_t i, uint32_t glue_he,
                                sq_extend_stats *stats, sq_error *err)
{
    sq_extend_stats local;
    if (!stats) stats = &local;
    stats->face = SQ_NONE;
    stats->glue_he = SQ_NONE;
    stats->concave = stats->grids_step2 = stats->grids_step3 = 0;
    stats->quads_step2 = stats->quads_step3 = 0;

    /* Def. 5.4 input */
    int empty = P->nf == 0;
    uint32_t k;
    sq_status st0 = check_input(P, i, &k, err);
    if (st0) return st0;

    /* Step 1 on the empty metapolygon: P' is just the i-gon, already a
     * meta-i-gon. */
    if (empty) {
        if (glue_he != SQ_NONE)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "glue halfedge %u given, but the metapolygon is empty", glue_he);
        sq_status st = sq_metapolygon_add_polygon(P, i, &stats->face, err);
        assert(st != SQ_OK || sq_metapolygon_count_corners(P) == i);
        return st;
    }
    if (glue_he == SQ_NONE) {
        sq_status st = sq_metapolygon_default_glue_edge(P, i, &glue_he, err);
        if (st != SQ_OK) return st;
    }
    if (glue_he >= P->nh || P->he_face[glue_he] != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "glue halfedge %u is not a boundary halfedge (of %u halfedges)",
                            glue_he, P->nh);
    stats->glue_he = glue_he;

    uint32_t nf0 = P->nf;
    uint32_t k_out = k + i - 4;
    nonflat_seq C = {0};
    uint32_t corners, concave;

    /* Step 1: glue an i-gon along one of its edges to glue_he. */
    sq_status st = sq_metapolygon_glue_polygon(P, glue_he, 1, i - 2, &stats->face, NULL, NULL,
                                               err);
    if (st != SQ_OK) goto done;
    if ((st = seq_read(P, &C, err)) != SQ_OK) goto done;
    seq_count(P, &C, &corners, &concave);
    stats->concave = concave;
    /* Theorem 5.5 proof: m <= 2 concave vertices, |C(P')| = k + i - 4 + 2m */
    assert(concave <= 2);
    assert(corners == k_out + concave);

    /* Step 2: v0 v1 v2 v3 in C(P'), v1 and v2 concave, v0 and v3 corners:
     * glue a d(v1,v2) x min(d(v0,v1), d(v2,v3)) grid with three sides,
     * two of its corners at v1 and v2. */
    if (concave == 2) {
        for (uint32_t j = 0; j < C.n; j++) {
            uint32_t jm = (j + C.n - 1) % C.n, j1 = (j + 1) % C.n, j2 = (j + 2) % C.n;
            if (seq_kind(P, &C, j) != SQ_MP_CONCAVE || seq_kind(P, &C, j1) != SQ_MP_CONCAVE)
                continue;
            if (seq_kind(P, &C, jm) != SQ_MP_CORNER || seq_kind(P, &C, j2) != SQ_MP_CORNER)
                continue;
            assert(jm != j2); /* |C(P')| > 4, Theorem 5.5 proof */
            uint32_t d01 = C.dist[jm], d12 = C.dist[j], d23 = C.dist[j1];
            uint32_t m = d01 < d23 ? d01 : d23;
            uint32_t anchor = sq_metapolygon_boundary_prev(P, C.out_he[j]); /* enters v1 */
            st = sq_metapolygon_glue_grid(P, anchor, m, d12, 3, err);
            if (st != SQ_OK) goto done;
            stats->grids_step2 = 1;
            stats->quads_step2 = (uint64_t)m * d12;
            if ((st = seq_read(P, &C, err)) != SQ_OK) goto done;
            uint32_t c2, m2;
            seq_count(P, &C, &c2, &m2);
            /* one fewer corner and concave vertex, or two when d01 = d23 */
            assert(c2 == corners - (d01 == d23 ? 2 : 1));
            assert(m2 == (d01 == d23 ? 0u : 1u));
            corners = c2;
            concave = m2;
            break;
        }
    }

    /* Step 3: while v0 v1 v2 in C(P') has v1 concave between corners v0
     * and v2: glue a d(v0,v1) x d(v1,v2) grid with two sides, one corner at
     * v1. */
    while (concave > 0) {
        uint32_t j = 0;
        for (; j < C.n; j++) {
            if (seq_kind(P, &C, j) != SQ_MP_CONCAVE) continue;
            uint32_t jm = (j + C.n - 1) % C.n, j1 = (j + 1) % C.n;
            if (seq_kind(P, &C, jm) == SQ_MP_CORNER && seq_kind(P, &C, j1) == SQ_MP_CORNER &&
                jm != j1)
                break;
        }
        if (j == C.n || stats->grids_step3 == 2) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "Theorem 5.5 violated: %u concave vertices left after %u step-3 "
                              "grids (i = %u, k = %u)",
                              concave, stats->grids_step3, i, k);
            goto done;
        }
        uint32_t jm = (j + C.n - 1) % C.n;
        uint32_t d01 = C.dist[jm], d12 = C.dist[j];
        uint32_t anchor = sq_metapolygon_boundary_prev(P, C.out_he[j]); /* enters v1 */
        st = sq_metapolygon_glue_grid(P, anchor, d01, d12, 2, err);
        if (st != SQ_OK) goto done;
        stats->grids_step3++;
        stats->quads_step3 += (uint64_t)d01 * d12;
        if ((st = seq_read(P, &C, err)) != SQ_OK) goto done;
        uint32_t c3, m3;
        seq_count(P, &C, &c3, &m3);
        assert(c3 == corners - 1 && m3 == concave - 1); /* Theorem 5.5 proof */
        corners = c3;
        concave = m3;
    }

    /* Theorem 5.5: a meta-(k+i-4)-gon whose only new irregular face is the
     * i-gon: faces nf0+1 .. are the grids' 4-gons. */
    assert(concave == 0 && corners == k_out);
    assert(P->f_valence[nf0] == i);
    assert(P->nf - nf0 - 1 == stats->quads_step2 + stats->quads_step3);
#ifndef NDEBUG
    for (uint32_t f = nf0 + 1; f < P->nf; f++) assert(P->f_valence[f] == 4);
#endif
    if (corners != k_out || P->f_valence[nf0] != i ||
        P->nf - nf0 - 1 != stats->quads_step2 + stats->quads_step3)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "Theorem 5.5 violated: E(P, %u) of a meta-%u-gon has %u corners", i,
                          k, corners);
done:
    seq_free(&C);
    return st;
}
