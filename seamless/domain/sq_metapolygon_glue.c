/* seamquad: choice of the glue edge for metapolygon extension, seed 5.3
 * ("Number of 4-gons").
 *
 * With no geometric guidance (seed 9.2 supplies one), we choose the edge
 * that adds the fewest 4-gons now. Seed 5.3 gives the count for every edge
 * of a side of l edges: l - 1 for i > 4 wherever on the side, and for
 * i = 3 and i = 2 a function of x, the number of edges between the glue
 * edge and the nearest corner (and, for i = 2, of l', the other side at
 * that corner). A greedy minimum is a deliberate, cheap choice: it keeps
 * each step small and never looks ahead; the tests compare it with random
 * choices. */
#include "sq_metapolygon.h"

#include <assert.h>
#include <stdlib.h>

/* Sides of a metapolygon: C(P) with all entries corners. */
typedef struct sides {
    uint32_t k;
    uint32_t *out_he, *len;
} sides;

static sq_status sides_read(const sq_metapolygon *P, sides *s, sq_error *err)
{
    s->out_he = s->len = NULL;
    s->k = sq_metapolygon_nonflat(P, 0, NULL, NULL, NULL);
    if (s->k == 0) return SQ_OK;
    s->out_he = malloc((size_t)s->k * sizeof *s->out_he);
    s->len = malloc((size_t)s->k * sizeof *s->len);
    if (!s->out_he || !s->len) {
        free(s->out_he);
        free(s->len);
        s->out_he = s->len = NULL;
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for metapolygon sides");
    }
    sq_metapolygon_nonflat(P, s->k, NULL, s->out_he, s->len);
    return SQ_OK;
}

static void sides_free(sides *s)
{
    free(s->out_he);
    free(s->len);
}

/* Seed 5.3 count for the edge at position p (0-based from the starting
 * corner) of side s. */
static uint64_t quads_for(const sides *S, uint32_t i, uint32_t s, uint32_t p)
{
    uint64_t l = S->len[s];
    assert(p < l);
    if (i > 4) return S->k == 1 ? l : l - 1; /* see sq_metapolygon.h on k = 1 */
    uint64_t from_start = p, from_end = l - 1 - p;
    uint64_t x = from_start <= from_end ? from_start : from_end;
    if (i == 3) return x + (x + 1) * (l - x - 1);
    assert(i == 2 && S->k >= 3);
    /* l' is the other side at the nearest corner */
    uint64_t lp = from_start <= from_end ? S->len[(s + S->k - 1) % S->k] : S->len[(s + 1) % S->k];
    return x + (l - 2 * x - 1) * (lp + 1);
}

/* Def. 5.4 input conditions for a non-empty P with side list S. */
static int preconditions_hold(const sq_metapolygon *P, const sides *S, uint32_t i)
{
    if (i < 2 || i == 4 || S->k == 0) return 0;
    if ((int64_t)i <= 4 - (int64_t)S->k) return 0;
    for (uint32_t s = 0; s < S->k; s++)
        if (P->v_nface[P->he_vert[S->out_he[s]]] != 1) return 0; /* concave */
    return 1;
}

uint64_t sq_metapolygon_predict_quads(const sq_metapolygon *P, uint32_t i, uint32_t glue_he)
{
    if (i < 2 || i == 4) return UINT64_MAX;
    if (P->nf == 0) return glue_he == SQ_NONE ? 0 : UINT64_MAX;
    if (glue_he >= P->nh || P->he_face[glue_he] != SQ_NONE) return UINT64_MAX;
    sides S;
    if (sides_read(P, &S, NULL) != SQ_OK) return UINT64_MAX;
    uint64_t result = UINT64_MAX;
    if (preconditions_hold(P, &S, i)) {
        for (uint32_t s = 0; s < S.k && result == UINT64_MAX; s++) {
            uint32_t h = S.out_he[s];
            for (uint32_t p = 0; p < S.len[s]; p++, h = P->he_next[h]) {
                if (h == glue_he) {
                    result = quads_for(&S, i, s, p);
                    break;
                }
            }
        }
    }
    sides_free(&S);
    return result;
}

/* Seed 5.3: the cheapest edge; within a side, the position the seed names
 * (corner edge for i = 3, any edge - we take the first - for i > 4, centred
 * edge for i = 2). */
sq_status sq_metapolygon_default_glue_edge(const sq_metapolygon *P, uint32_t i,
                                           uint32_t *glue_he, sq_error *err)
{
    *glue_he = SQ_NONE;
    if (P->nf == 0) return SQ_OK;
    sides S;
    sq_status st = sides_read(P, &S, err);
    if (st != SQ_OK) return st;
    if (!preconditions_hold(P, &S, i)) {
        sides_free(&S);
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "Def. 5.4: no glue edge for a %u-gon on a meta-%u-gon (needs i > "
                            "max(1, 4-k), i != 4, no concave vertex)",
                            i, S.k);
    }
    uint64_t best = UINT64_MAX;
    uint32_t best_s = 0, best_p = 0;
    for (uint32_t s = 0; s < S.k; s++) {
        uint32_t l = S.len[s];
        uint32_t p = 0;
        if (i == 2) {
            /* centred: l odd, (l-1)/2; l even, l/2 - 1 (nearest corner the
             * start) or l/2 (the end), whichever has the shorter l' */
            p = (l - 1) / 2;
            if (l % 2 == 0 && quads_for(&S, i, s, l / 2) < quads_for(&S, i, s, p)) p = l / 2;
        }
        uint64_t q = quads_for(&S, i, s, p);
        if (q < best) {
            best = q;
            best_s = s;
            best_p = p;
        }
    }
    uint32_t h = S.out_he[best_s];
    for (uint32_t p = 0; p < best_p; p++) h = P->he_next[h];
    *glue_he = h;
    sides_free(&S);
    return SQ_OK;
}
