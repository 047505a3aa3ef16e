/* seamquad: quantization driver (sq_quantize.h): T-mesh, split, layout,
 * integer lengths, embedding. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_quantize.h"
#include "sq_quantize_internal.h"
#include "sq_tmesh.h"
#include "sq_tmesh_lengths.h"

static sq_status check_options(const sq_quantize_options *opt, sq_error *err)
{
    if (!opt) return sq_error_set(err, SQ_ERR_ARGUMENT, "quantize: no options");
    if (opt->quads != 0 && !(opt->quads >= 1 && opt->quads <= 1e8))
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "quantize: the quad count must be between 1 and 1e8 (got %g)", opt->quads);
    if (opt->quads == 0 && !(opt->edge_length > 0 && isfinite(opt->edge_length)))
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "quantize: give a quad count or a positive edge length (got %g)",
                            opt->edge_length);
    if (opt->targets != SQ_TARGETS_SURFACE && opt->targets != SQ_TARGETS_MAP)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "quantize: unknown target kind %d", opt->targets);
    return SQ_OK;
}

/* Per-arc minimum lengths (see the caller). Arcs are sorted by their end
 * pair to find parallel ones. */
static int cmp_pair64(const void *a, const void *b)
{
    const uint64_t *p = a, *q = b;
    return (p[0] > q[0]) - (p[0] < q[0]);
}

static void arcs_minimum(const sq_qlayout *L, int64_t *min_arc)
{
    uint64_t *key = malloc(((size_t)L->na + 1) * 2 * sizeof *key);
    for (uint32_t a = 0; a < L->na; a++) {
        uint32_t u = L->arc_end[2 * (size_t)a], v = L->arc_end[2 * (size_t)a + 1];
        min_arc[a] = u == v ? 3 : 1;
        if (key) key[2 * (size_t)a] = u < v ? ((uint64_t)u << 32 | v) : ((uint64_t)v << 32 | u), key[2 * (size_t)a + 1] = a;
    }
    if (!key) return; /* without the table: no extra minimum (a double edge is then refused later) */
    qsort(key, L->na, 2 * sizeof *key, cmp_pair64);
    for (uint32_t i = 0; i + 1 < L->na; i++)
        if (key[2 * (size_t)i] == key[2 * (size_t)i + 2]) {
            uint32_t a = (uint32_t)key[2 * (size_t)i + 1], b = (uint32_t)key[2 * (size_t)i + 3];
            if (min_arc[a] < 2) min_arc[a] = 2;
            if (min_arc[b] < 2) min_arc[b] = 2;
        }
    free(key);
}

/* Steps 2-4 once. Where the embedding cannot place a patch, *failed
 * (allocated here, np) marks it and S and L are kept for the refinement;
 * else they are freed. */
static sq_status quantize_round(const sq_map *M, const sq_chord *chords, uint32_t n_chords,
                                const sq_quantize_options *opt, sq_map *igm, sq_quantize_stats *stats,
                                sq_split *keep_S, sq_qlayout *keep_L, uint8_t **failed, sq_error *err)
{
    double t0 = sq_now();
    sq_status st = SQ_OK;
    memset(igm, 0, sizeof *igm);
    sq_split S;
    sq_qlayout L;
    memset(&L, 0, sizeof L);
    *failed = NULL;
    int64_t *length = NULL, *min_arc = NULL;
    double *target = NULL;
    if ((st = sq_map_split(M, chords, n_chords, &S, err))) return st;
    double t1 = sq_now();
    stats->seconds_split = t1 - t0;
    stats->split_vertices = S.nv;
    stats->split_triangles = S.nt;
    if ((st = sq_qlayout_build(M, &S, &L, err))) goto done;
    double t2 = sq_now();
    stats->seconds_layout = t2 - t1;
    stats->faces = L.np;
    stats->arcs = L.na;
    stats->nodes = 0;
    for (uint32_t v = 0; v < S.nv; v++) stats->nodes += L.v_node[v];
    length = malloc(((size_t)L.na + 1) * sizeof *length);
    target = malloc(((size_t)L.na + 1) * sizeof *target);
    if (!length || !target) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization)");
        goto done;
    }
    const double *len = opt->targets == SQ_TARGETS_MAP ? L.arc_len : L.arc_len3d;
    double scale = opt->quads > 0 ? 1.0 : 1.0 / opt->edge_length;
    if (opt->quads > 0) {
        /* targets normalized so that the map's faces hold about quads quads:
         * the solver rescales them to the count */
        double area = 0;
        for (uint32_t p = 0; p < L.np; p++) {
            /* each face's area in target units: the product of its bottom's
             * and its right side's target lengths */
            double w = 0, h = 0;
            for (uint32_t k = L.side_off[4 * (size_t)p]; k < L.side_off[4 * (size_t)p + 1]; k++) w += len[L.side_arc[k]];
            for (uint32_t k = L.side_off[4 * (size_t)p + 1]; k < L.side_off[4 * (size_t)p + 2]; k++) h += len[L.side_arc[k]];
            area += w * h;
        }
        scale = area > 0 ? sqrt(opt->quads / area) : 1.0;
    }
    for (uint32_t a = 0; a < L.na; a++) target[a] = fmax(len[a] * scale, 1e-6);
    /* a simple quad mesh: an arc that closes on its node needs 3 (1 would
     * join a vertex to itself, 2 give two edges between two vertices), two
     * arcs between the same two nodes need 2 each (two length-1 arcs would
     * be one edge twice) */
    min_arc = malloc(((size_t)L.na + 1) * sizeof *min_arc);
    if (!min_arc) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization)");
        goto done;
    }
    arcs_minimum(&L, min_arc);
    sq_tmesh_sides T = {L.np, L.na, L.side_off, L.side_arc, target, NULL, 1, min_arc};
    sq_tmesh_lengths_stats ls;
    memset(&ls, 0, sizeof ls);
    if (opt->quads > 0)
        st = sq_tmesh_lengths_for_quads(&T, opt->quads, length, &ls, err);
    else
        st = sq_tmesh_lengths(&T, length, &ls, err);
    if (st) goto done;
    double t3 = sq_now();
    stats->seconds_lengths = t3 - t2;
    stats->min_quads = ls.min_quads;
    *failed = calloc((size_t)L.np + 1, 1);
    if (!*failed) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization)");
        goto done;
    }
    if ((st = sq_qlayout_embed(M, &S, &L, length, igm, &stats->fallback_faces, *failed, err))) {
        if (st == SQ_ERR_SOLVER) {
            *keep_S = S, *keep_L = L;
            free(length), free(target), free(min_arc);
            return st;
        }
        goto done;
    }
    free(*failed), *failed = NULL;
    stats->seconds_embed = sq_now() - t3;
    stats->quads = 0;
    for (uint32_t p = 0; p < L.np; p++) {
        int64_t a = 0, b = 0;
        for (uint32_t k = L.side_off[4 * (size_t)p]; k < L.side_off[4 * (size_t)p + 1]; k++) a += length[L.side_arc[k]];
        for (uint32_t k = L.side_off[4 * (size_t)p + 1]; k < L.side_off[4 * (size_t)p + 2]; k++) b += length[L.side_arc[k]];
        stats->quads += (double)a * (double)b;
    }
    stats->cones = 0;
    for (uint32_t v = 0; v < M->mesh.nv; v++) stats->cones += M->valence[v] != 4;
done:
    free(length), free(target), free(min_arc);
    sq_qlayout_free(&L);
    sq_split_free(&S);
    if (st) free(*failed), *failed = NULL;
    stats->seconds = sq_now() - t0;
    return st;
}

/* Refinement rounds: the kink lines, then grids of 4 x 4 and 16 x 16. */
static const uint32_t refine_grid[] = {1, 4, 16};

sq_status sq_quantize_chords(const sq_map *M, const sq_chord *chords, uint32_t n_chords,
                             const sq_quantize_options *opt, sq_map *igm, sq_quantize_stats *stats,
                             sq_error *err)
{
    sq_quantize_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    double t0 = sq_now();
    sq_status st = check_options(opt, err);
    if (st) return st;
    sq_chord *all = NULL;
    uint32_t n_all = 0, cap_all = 0;
    for (uint32_t round = 0;; round++) {
        sq_split S;
        sq_qlayout L;
        uint8_t *failed = NULL;
        st = quantize_round(M, all ? all : chords, all ? n_all : n_chords, opt, igm, stats, &S, &L, &failed, err);
        if (!failed) break;
        /* st == SQ_ERR_SOLVER: some patches not embedded */
        if (round < sizeof refine_grid / sizeof *refine_grid) {
            for (uint32_t p = 0; p < L.np; p++) stats->refined_faces += failed[p];
            sq_error e2;
            sq_status s2 = SQ_OK;
            if (!all) {
                all = malloc(((size_t)n_chords + 1) * sizeof *all);
                if (!all) s2 = sq_error_set(&e2, SQ_ERR_NOMEM, "out of memory (quantization refinement)");
                else memcpy(all, chords, (size_t)n_chords * sizeof *all), n_all = cap_all = n_chords;
            }
            if (!s2) s2 = sq_qlayout_refine_chords(&S, &L, failed, refine_grid[round], &all, &n_all, &cap_all, &e2);
            if (s2 && err) *err = e2;
            if (s2) st = s2;
            stats->refine_rounds = round + 1;
        }
        free(failed);
        sq_qlayout_free(&L);
        sq_split_free(&S);
        if (st != SQ_ERR_SOLVER || round >= sizeof refine_grid / sizeof *refine_grid) break;
    }
    free(all);
    stats->seconds = sq_now() - t0;
    return st;
}

/* The T-mesh's pieces as chords: a piece on the line v = c (running along
 * u) or u = c, bounded by its ends. */
static sq_chord *pieces_to_chords(const sq_tmesh *T, uint32_t *n)
{
    sq_chord *ch = malloc(((size_t)T->n_pieces + 1) * sizeof *ch);
    if (!ch) return NULL;
    uint32_t k = 0;
    for (uint32_t i = 0; i < T->n_pieces; i++) {
        const sq_tmesh_piece *P = T->pieces + i;
        int plus = P->dir == 0 || P->dir == 1;
        /* an end crossing a mesh edge (rounded position) extends the chord
         * to the face's boundary; an exact end (a vertex, a node, also a
         * node inside an edge the piece runs along) bounds it */
        int open_from = P->from.kind == SQ_TMESH_ON_EDGE && !P->from.exact;
        int open_to = P->to.kind == SQ_TMESH_ON_EDGE && !P->to.exact;
        double a = open_from ? (plus ? -INFINITY : INFINITY) : P->from.s;
        double b = open_to ? (plus ? INFINITY : -INFINITY) : P->to.s;
        if (a == b) continue;
        ch[k].face = P->face;
        ch[k].axis = (P->dir & 1) ? 0 : 1;
        ch[k].c = P->c;
        ch[k].lo = fmin(a, b);
        ch[k].hi = fmax(a, b);
        k++;
    }
    *n = k;
    return ch;
}

sq_status sq_quantize(const sq_map *M, const sq_quantize_options *opt, sq_map *igm,
                      sq_quantize_stats *stats, sq_error *err)
{
    sq_quantize_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    sq_status st = check_options(opt, err);
    if (st) return st;
    double t0 = sq_now();
    sq_tmesh T;
    if ((st = sq_tmesh_build(M, &T, NULL, err))) return st;
    stats->seconds_tmesh = sq_now() - t0;
    uint32_t n = 0;
    sq_chord *ch = pieces_to_chords(&T, &n);
    if (!ch) {
        sq_tmesh_free(&T);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization chords)");
    }
    double tt = stats->seconds_tmesh;
    st = sq_quantize_chords(M, ch, n, opt, igm, stats, err);
    stats->seconds_tmesh = tt;
    stats->seconds += tt;
    free(ch);
    sq_tmesh_free(&T);
    if (!st && opt->optimize) {
        /* step 5: transitions and cones fixed, so still an integer-grid map
         * with the same quads; most of the gain comes in the first steps.
         * Triangles far from their surface shape are held, not given
         * progressive references: the quads' figures of bench/README.md
         * are measured so. */
        sq_optimize_options oo;
        memset(&oo, 0, sizeof oo);
        oo.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
        oo.max_iterations = opt->optimize_iterations ? opt->optimize_iterations : 20;
        oo.tolerance = 1e-3;
        oo.reference_bound = INFINITY;
        st = sq_optimize_map(igm, &oo, &stats->optimize, err);
        stats->seconds += stats->optimize.seconds;
        if (st) sq_map_free(igm);
    }
    return st;
}
