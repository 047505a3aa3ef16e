/* seamquad: the pipeline from a closed triangle mesh to a quad mesh
 * (sq_remesh.h; docs/remesh.md).
 *
 * Each stage's result is checked before the next starts: the map on the
 * mesh from the field's rotations and param's map are checked exactly
 * (param's again as an sq_map, stage 3), the optimizer and the
 * quantizer return maps that pass sq_map_check (the integer-grid map with
 * SQ_MAP_REQUIRE_INTEGER), and the extraction builds its mesh only from a
 * valid integer-grid map. Two things no stage before checks: a quad folded
 * in 3D (its corners lie on the surface but the quad turns over it), which
 * the untangling step relaxes, any left failing the run; and quads through
 * each other or through a thin part of the surface, which the verify stage
 * finds with CGAL's exact test and refuses.
 *
 * Cost: where the map on the mesh itself is valid (13 of the 15 mpz
 * models), a few seconds for stages 2 to 4 (sparse Cholesky factorizations
 * of the input's size); otherwise dominated by the optimizer on param's
 * refinement (one sparse Cholesky per iteration on about twice its
 * vertices) and by param on large cone sets; memory by the refinement. */
#include "sq_remesh.h"
#include "sq_remesh_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_cgal_adapter.h"
#include "sq_closest_point.h"
#include "sq_cone_connection.h"
#include "sq_cones.h"

/* The share of the whole run each stage is given in the progress report
 * (rough proportions on the mpz models at 5K quads: the optimizer's rounds
 * dominate). */
#define SHARE_CONES 0.03
#define SHARE_PARAM 0.15
#define SHARE_OPTIMIZE 0.52
#define SHARE_QUANTIZE 0.13
#define SHARE_EXTRACT 0.03
#define SHARE_SMOOTH 0.12

typedef struct progress_ctx {
    const sq_remesh_options *opt;
    const char *stage;
    double base, share;
    double done;        /* the largest fraction reported: never goes back */
    uint32_t iterations;
} progress_ctx;

/* Reports the stage's fraction as a fraction of the whole run; a stage whose
 * own progress goes back (param's, between its attempts and steps) does not
 * move the whole run's back. */
static void report(progress_ctx *pc, double fraction)
{
    double f = pc->base + pc->share * fmin(fmax(fraction, 0.0), 1.0);
    if (f < pc->done) f = pc->done;
    pc->done = f;
    if (pc->opt->progress) pc->opt->progress(pc->opt->user, pc->stage, f);
}

static void param_progress(void *ctx, const char *stage, double fraction)
{
    (void)stage;
    report(ctx, fraction);
}

static void optimize_progress(void *user, uint32_t iteration, double energy, double step)
{
    (void)energy, (void)step;
    progress_ctx *pc = user;
    report(pc, (double)iteration / pc->iterations);
}

static void smooth_progress(void *user, const char *phase, int iteration, double energy,
                            uint32_t folded)
{
    (void)phase, (void)energy, (void)folded;
    progress_ctx *pc = user;
    report(pc, (double)iteration / pc->iterations);
}

static void begin(progress_ctx *pc, sq_remesh_stats *stats, const char *stage, double share)
{
    pc->base += pc->share;
    pc->share = share;
    pc->stage = stage;
    stats->stage = stage;
    report(pc, 0);
}

/* The triangle mesh m's intersecting triangle pairs (CGAL), computed
 * once per layout: kept in stats->input_self_intersections (-1: not yet). */
static sq_status mesh_self_intersections(const sq_mesh *m, sq_remesh_stats *stats, uint64_t *pairs,
                                         sq_error *err)
{
    if (stats->input_self_intersections >= 0) {
        *pairs = (uint64_t)stats->input_self_intersections;
        return SQ_OK;
    }
    uint32_t *tri = sq_mesh_triangles(m);
    if (!tri) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (self-intersection test)");
    sq_status st = sq_cgal_self_intersections(m->nv, m->pos, m->nf, tri, pairs, NULL, 0, err);
    free(tri);
    if (!st) stats->input_self_intersections = (int64_t)*pairs;
    return st;
}

/* Where Q's vertices lie on m (smoothing and repair keep them on it): the
 * closest-point tree, each vertex's nearest face and its barycentric
 * coordinates there, and m's vertex normals, for the turned-over test. */
typedef struct on_surface {
    uint32_t *tri, *face;
    double *bary, *vn;
    sq_cp_tree tree;
} on_surface;

static void on_surface_free(on_surface *o)
{
    sq_cp_tree_free(&o->tree);
    free(o->tri), free(o->face), free(o->bary), free(o->vn);
}

static sq_status on_surface_init(const sq_mesh *m, uint32_t nv, on_surface *o, sq_error *err)
{
    memset(o, 0, sizeof *o);
    o->tri = sq_mesh_triangles(m);
    o->face = malloc(((size_t)nv + 1) * sizeof *o->face);
    o->bary = malloc(3 * ((size_t)nv + 1) * sizeof *o->bary);
    o->vn = sq_mesh_vertex_normals(m);
    if (!o->tri || !o->face || !o->bary || !o->vn) {
        on_surface_free(o);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quads on the surface)");
    }
    sq_status st = sq_cp_tree_build(m->nv, m->pos, m->nf, o->tri, &o->tree, err);
    if (st) on_surface_free(o);
    return st;
}

/* Q's vertices located on m afresh. */
static void on_surface_locate(on_surface *o, const sq_quad_mesh *Q)
{
    for (uint32_t v = 0; v < Q->nv; v++) {
        sq_cp_hit hit;
        sq_cp_tree_query(&o->tree, Q->pos + 3 * (size_t)v, &hit);
        o->face[v] = hit.tri;
        memcpy(o->bary + 3 * (size_t)v, hit.bary, sizeof hit.bary);
    }
}

/* Step 6 of extract on the final quads (sq_quad_mesh_check_shapes), the
 * turned-over test on m included. */
static sq_status check_final_shapes(const sq_mesh *m, const sq_quad_mesh *Q, sq_error *err)
{
    on_surface o;
    sq_status st = on_surface_init(m, Q->nv, &o, err);
    if (st) return st;
    on_surface_locate(&o, Q);
    st = sq_quad_mesh_check_shapes(Q, m, o.face, o.bary, sq_bbox_diagonal(m->nv, m->pos), NULL, err);
    on_surface_free(&o);
    /* the run's own result failed, not its input: a stage failure */
    if (st == SQ_ERR_DEGENERATE) {
        st = SQ_ERR_SOLVER;
        if (err) err->code = st;
    }
    return st;
}

/* mark grown by one ring of edge neighbours (grow: scratch of nv) */
static void grow_ring(const sq_quad_star *S, uint32_t nv, uint8_t *mark, uint8_t *grow)
{
    memcpy(grow, mark, nv);
    for (uint32_t v = 0; v < nv; v++)
        if (mark[v])
            for (uint32_t k = S->off[v]; k < S->off[v + 1]; k++) grow[S->next[k]] = 1;
    memcpy(mark, grow, nv);
}

/* The quads turned over on m (Q located afresh into o), or if none, 1 if
 * some quad is folded: 0 when Q has neither. */
static sq_status count_turned_or_folded(const sq_mesh *m, const sq_quad_mesh *Q, on_surface *o, uint32_t *bad,
                                        sq_error *err)
{
    on_surface_locate(o, Q);
    sq_status st = sq_quad_mesh_count_turned(Q, m, o->vn, o->face, o->bary, bad, NULL, NULL, err);
    for (uint32_t f = 0; !st && f < Q->nq && !*bad; f++) {
        const uint32_t *q = Q->quad + 4 * (size_t)f;
        *bad += sq_quad_fold_margin(Q->pos + 3 * (size_t)q[0], Q->pos + 3 * (size_t)q[1],
                                    Q->pos + 3 * (size_t)q[2], Q->pos + 3 * (size_t)q[3]) < 0.0;
    }
    return st;
}

/* Where smoothing turned quads over: the vertices of those quads, then
 * also 1 to 16 rings around them, back at their unsmoothed places (keep),
 * until no quad is turned or folded. *turned: the turned quads left (0
 * when that worked, else the count with all of them smoothed); *kept: the
 * vertices put back. */
static sq_status revert_turned(const sq_mesh *m, sq_quad_mesh *Q, const double *keep, uint32_t *turned,
                               uint32_t *kept, sq_error *err)
{
    *kept = 0;
    uint8_t *flags = malloc((size_t)Q->nq + 1), *mark = calloc((size_t)Q->nv + 1, 1),
            *grow = malloc((size_t)Q->nv + 1);
    double *smoothed = malloc(3 * ((size_t)Q->nv + 1) * sizeof *smoothed);
    sq_quad_star S = {NULL, NULL, NULL};
    on_surface o;
    memset(&o, 0, sizeof o);
    sq_status st = SQ_OK;
    if (!flags || !mark || !grow || !smoothed) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (smoothing)");
    if (!st) st = on_surface_init(m, Q->nv, &o, err);
    if (!st) {
        on_surface_locate(&o, Q);
        st = sq_quad_mesh_count_turned(Q, m, o.vn, o.face, o.bary, turned, NULL, flags, err);
    }
    if (!st && *turned) st = sq_quad_star_build(Q->nv, Q->nq, Q->quad, &S, err);
    if (!st && *turned) {
        memcpy(smoothed, Q->pos, 3 * (size_t)Q->nv * sizeof *smoothed);
        for (uint32_t f = 0; f < Q->nq; f++)
            if (flags[f])
                for (int k = 0; k < 4; k++) mark[Q->quad[4 * (size_t)f + k]] = 1;
        uint32_t left = *turned;
        for (int ring = 0; ring <= 16 && left && !st; ring++) {
            if (ring) grow_ring(&S, Q->nv, mark, grow);
            *kept = 0;
            for (uint32_t v = 0; v < Q->nv; v++)
                if (mark[v]) memcpy(Q->pos + 3 * (size_t)v, keep + 3 * (size_t)v, 3 * sizeof *keep), ++*kept;
            st = count_turned_or_folded(m, Q, &o, &left, err);
        }
        if (!st && left) memcpy(Q->pos, smoothed, 3 * (size_t)Q->nv * sizeof *smoothed), *kept = 0;
        else if (!st) *turned = 0;
    }
    on_surface_free(&o);
    sq_quad_star_free(&S);
    free(flags), free(mark), free(grow), free(smoothed);
    return st;
}

/* Where the smoothed quads intersect themselves and the unsmoothed ones
 * (keep) do not: the vertices of the quads involved, then also 1 to 16
 * rings around them, back at their unsmoothed places, until no pair is
 * left and no quad is turned or folded. Returns in *left the pairs left
 * (0: done; else Q->pos is as it came); *kept the vertices put back. */
static sq_status revert_intersecting(const sq_mesh *m, sq_quad_mesh *Q, const double *keep, uint64_t *left,
                                     uint32_t *kept, sq_error *err)
{
    enum { LIST = 65536 };
    *kept = 0;
    uint32_t *list = malloc(2 * (size_t)LIST * sizeof *list);
    uint8_t *mark = calloc((size_t)Q->nv + 1, 1), *grow = malloc((size_t)Q->nv + 1);
    double *start = malloc(3 * ((size_t)Q->nv + 1) * sizeof *start);
    sq_quad_star S = {NULL, NULL, NULL};
    on_surface o;
    memset(&o, 0, sizeof o);
    sq_status st = SQ_OK;
    if (!list || !mark || !grow || !start) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (verify)");
    if (!st) st = sq_remesh_quad_intersections(Q, left, list, LIST, err);
    if (!st && *left) st = on_surface_init(m, Q->nv, &o, err);
    if (!st && *left) st = sq_quad_star_build(Q->nv, Q->nq, Q->quad, &S, err);
    if (!st && *left) {
        memcpy(start, Q->pos, 3 * (size_t)Q->nv * sizeof *start);
        uint64_t n = *left < LIST ? *left : LIST;
        for (uint64_t k = 0; k < 2 * n; k++)
            for (int c = 0; c < 4; c++) mark[Q->quad[4 * (size_t)list[k] + c]] = 1;
        for (int ring = 0; ring <= 16 && *left && !st; ring++) {
            if (ring) grow_ring(&S, Q->nv, mark, grow);
            *kept = 0;
            for (uint32_t v = 0; v < Q->nv; v++)
                if (mark[v]) memcpy(Q->pos + 3 * (size_t)v, keep + 3 * (size_t)v, 3 * sizeof *keep), ++*kept;
            if ((st = sq_remesh_quad_intersections(Q, left, NULL, 0, err)) || *left) continue;
            uint32_t bad = 0;
            if ((st = count_turned_or_folded(m, Q, &o, &bad, err))) break;
            if (bad) *left = 1; /* not done: a wider ring */
        }
        if (!st && *left) memcpy(Q->pos, start, 3 * (size_t)Q->nv * sizeof *start), *kept = 0;
    }
    on_surface_free(&o);
    sq_quad_star_free(&S);
    free(list), free(mark), free(grow), free(start);
    return st;
}

/* Before stage 7: where the unsmoothed quads pass through each other and
 * the input does not intersect itself, stage 8's repair on them, kept
 * only if it leaves no pair (stats->repaired_unsmoothed: the pairs it
 * removed). Smoothing then starts from quads that pass verify, which are
 * also what verify falls back to around the smoothed quads' intersections;
 * from quads that do not, the smoother's quick steps tend to fail on the
 * tangled ones and it goes on with its thorough steps (cid/elephant at 5K:
 * 15 pairs in 9 relaxed folds, one round of repair; smoothing 4.5 -> 1.4
 * s, 4.08 -> 4.31 degrees). *before (malloc'ed): the positions before the
 * repair when it moved them, else NULL. */
static sq_status repair_before_smoothing(const sq_mesh *m, sq_quad_mesh *Q, double **before, sq_remesh_stats *stats,
                                         sq_error *err)
{
    *before = NULL;
    uint64_t pairs = 0, in = 0, left = 0;
    uint32_t rounds = 0;
    sq_status st = sq_remesh_quad_intersections(Q, &pairs, NULL, 0, err);
    if (!st && pairs) st = mesh_self_intersections(m, stats, &in, err);
    if (st || !pairs || in) return st;
    double *start = malloc(3 * ((size_t)Q->nv + 1) * sizeof *start);
    if (!start) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (verify)");
    memcpy(start, Q->pos, 3 * (size_t)Q->nv * sizeof *start);
    st = sq_remesh_repair_intersections(m, Q, &left, &rounds, err);
    if (st || left) {
        memcpy(Q->pos, start, 3 * (size_t)Q->nv * sizeof *start);
        free(start);
        return st;
    }
    stats->repaired_unsmoothed = pairs;
    *before = start;
    return SQ_OK;
}

/* Stage 7: Q smoothed on m's surface. Q->pos becomes the smoothed
 * positions, and *raw (malloc'ed) the unsmoothed ones, when smoothing
 * succeeds with no quad folded; otherwise Q is unchanged, *raw NULL and
 * stats->smooth_why says why. Errors other than the smoother's own
 * failure (out of memory) fail the run. */
static sq_status smooth_stage(const sq_mesh *m, sq_quad_mesh *Q, progress_ctx *pc, double **raw,
                              sq_remesh_stats *stats, sq_error *err)
{
    *raw = NULL;
    uint32_t *tri = sq_mesh_triangles(m);
    double *keep = malloc(3 * ((size_t)Q->nv + 1) * sizeof *keep);
    if (!tri || !keep) {
        free(tri), free(keep);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (smoothing)");
    }
    memcpy(keep, Q->pos, 3 * (size_t)Q->nv * sizeof *keep);
    sq_smooth_options so;
    sq_smooth_options_default(&so);
    so.progress = smooth_progress;
    so.progress_user = pc;
    pc->iterations = (uint32_t)so.iterations; /* untangling: none after stage 6, mostly */
    sq_error serr = {0};
    sq_status st = sq_smooth_quads(m->nv, m->pos, m->nf, tri, Q->nv, Q->pos, Q->nq, Q->quad, &so,
                                   &stats->smooth, &serr);
    free(tri);
    if (st == SQ_ERR_NOMEM) {
        free(keep);
        return sq_error_set(err, st, "%s", serr.msg);
    }
    uint32_t turned = 0;
    if (!st && !stats->smooth.after.folded) st = revert_turned(m, Q, keep, &turned, &stats->smooth_kept, &serr);
    if (st == SQ_ERR_NOMEM) {
        free(keep);
        return sq_error_set(err, st, "%s", serr.msg);
    }
    if (st || stats->smooth.after.folded > 0 || turned) {
        snprintf(stats->smooth_why, sizeof stats->smooth_why, "%.150s",
                 st ? serr.msg : turned ? "a quad turned over after smoothing" : "a quad folded after smoothing");
        memcpy(Q->pos, keep, 3 * (size_t)Q->nv * sizeof *keep);
        free(keep);
        stats->smooth_reverted = 1;
        return SQ_OK;
    }
    stats->smoothed = 1;
    *raw = keep;
    return SQ_OK;
}

void sq_remesh_result_free(sq_remesh_result *r)
{
    if (!r) return;
    sq_quad_mesh_free(&r->quads);
    free(r->valence);
    sq_map_free(&r->map);
    sq_map_free(&r->optimized);
    sq_map_free(&r->igm);
    memset(r, 0, sizeof *r);
}

/* Stages 5 to 8 from the optimized map M: the quads of a layout of about
 * `quads` quads (or edges of about `edge_length`) in out->quads and its
 * integer-grid map in igm, verified. On failure stats->stage names the
 * stage; out->quads and igm may hold its partial results (the caller
 * frees them). */
static sq_status quads_from_map(const sq_mesh *m, const sq_map *M, const sq_remesh_options *opt, double quads,
                                double edge_length, int targets, progress_ctx *pc, sq_remesh_result *out, sq_map *igm,
                                sq_remesh_stats *stats, sq_error *err)
{
    double *raw = NULL;
    sq_status st;
    stats->input_self_intersections = -1;
    /* 5. quantize (with its own optimization step) */
    double t1 = sq_now();
    begin(pc, stats, "quantize", SHARE_QUANTIZE);
    sq_quantize_options qo;
    memset(&qo, 0, sizeof qo);
    qo.quads = quads;
    qo.edge_length = edge_length;
    qo.targets = targets;
    qo.optimize = 1;
    qo.optimize_iterations = M->mesh.nf >= SQ_REMESH_STEP5_CAP_FACES ? SQ_REMESH_STEP5_ITERATIONS : 0;
    st = sq_quantize(M, &qo, igm, &stats->quantize, err);
    stats->t_quantize = sq_now() - t1;
    if (st) goto done;

    /* 6. extract, untangle */
    t1 = sq_now();
    begin(pc, stats, "extract", SHARE_EXTRACT);
    st = sq_extract(igm, &out->quads, &stats->extract, err);
    if (!st) st = sq_extract_untangle(igm, &out->quads, &stats->untangle, err);
    stats->t_extract = sq_now() - t1;
    if (st) goto done;

    /* 7. smooth, from quads that do not pass through each other where the
     * repair can separate them; the smoother untangles what is left
     * folded first */
    if (!opt->no_smoothing) {
        double *extracted = NULL; /* the positions before that repair */
        t1 = sq_now();
        if (stats->untangle.folded_after == 0)
            st = repair_before_smoothing(m, &out->quads, &extracted, stats, err);
        stats->t_verify += sq_now() - t1;
        if (st) goto done;
        t1 = sq_now();
        begin(pc, stats, "smooth", SHARE_SMOOTH);
        st = smooth_stage(m, &out->quads, pc, &raw, stats, err);
        if (!st && stats->smooth_reverted && extracted) {
            /* the repair left quads the smoother cannot untangle (nearly
             * folded: vmas/pinion at 1K): smoothing from the quads as
             * extracted, verify's repair after it */
            memcpy(out->quads.pos, extracted, 3 * (size_t)out->quads.nv * sizeof *extracted);
            stats->repaired_unsmoothed = 0;
            stats->smooth_reverted = 0;
            stats->smooth_why[0] = 0;
            st = smooth_stage(m, &out->quads, pc, &raw, stats, err);
        }
        free(extracted);
        stats->t_smooth = sq_now() - t1;
        if (st) goto done;
    }
    /* a quad still folded fails the run */
    if (!stats->smoothed && stats->untangle.folded_after > 0) {
        stats->stage = "extract";
        st = sq_error_set(err, SQ_ERR_SOLVER,
                          "%u of %u quads stay folded over the surface after untangling (the "
                          "integer-grid map is too distorted there); more optimizer "
                          "iterations may help",
                          stats->untangle.folded_after, out->quads.nq);
        goto done;
    }
    /* 8. no quad surface through itself where the input is not */
    t1 = sq_now() - stats->t_verify; /* with the repair before smoothing */
    begin(pc, stats, "verify", 1.0 - pc->base - pc->share);
    st = sq_remesh_quad_intersections(&out->quads, &stats->self_intersections, NULL, 0, err);
    stats->t_verify = sq_now() - t1;
    if (st) goto done;
    if (stats->self_intersections > 0 && raw && stats->untangle.folded_after == 0) {
        /* the unsmoothed quads, if they pass */
        double *smoothed = out->quads.pos;
        uint64_t pairs = 0;
        out->quads.pos = raw;
        st = sq_remesh_quad_intersections(&out->quads, &pairs, NULL, 0, err);
        if (st) {
            out->quads.pos = smoothed;
            goto done;
        }
        out->quads.pos = smoothed;
        if (pairs == 0) {
            /* the smoothed quads repaired if they can be (where the input
             * does not intersect itself), else those involved (and rings
             * around them) put back unsmoothed, else all unsmoothed */
            uint64_t in = 0, left = 1, found = stats->self_intersections;
            uint32_t rounds = 0;
            st = mesh_self_intersections(m, stats, &in, err);
            if (st) goto done;
            if (in == 0) {
                st = sq_remesh_repair_intersections(m, &out->quads, &left, &rounds, err);
                if (st) goto done;
            }
            uint32_t kept = 0;
            if (left != 0) { /* the repair's best, then the quads involved unsmoothed */
                st = revert_intersecting(m, &out->quads, raw, &left, &kept, err);
                if (st) goto done;
            }
            if (left == 0) {
                stats->repaired = kept ? 0 : found;
                stats->repair_rounds = rounds;
                stats->smooth_kept += kept;
                stats->self_intersections = 0;
            } else {
                snprintf(stats->smooth_why, sizeof stats->smooth_why,
                         "%llu pairs of the smoothed quads' triangles intersect, none of the unsmoothed",
                         (unsigned long long)found);
                stats->self_intersections = 0;
                stats->smoothed = 0;
                stats->smooth_reverted = 1;
                out->quads.pos = raw;
                raw = smoothed;
            }
            stats->t_verify = sq_now() - t1;
        }
    }
    if (stats->self_intersections > 0) {
        uint64_t in = 0;
        st = mesh_self_intersections(m, stats, &in, err);
        stats->t_verify = sq_now() - t1;
        if (st) goto done;
        if (in == 0) { /* the quads around the intersections relaxed on the surface */
            uint64_t left = 0;
            st = sq_remesh_repair_intersections(m, &out->quads, &left, &stats->repair_rounds, err);
            stats->t_verify = sq_now() - t1;
            if (st) goto done;
            if (left > 0 && raw && stats->smoothed && stats->untangle.folded_after == 0) {
                /* the smoothed quads (and the unsmoothed ones, which
                 * intersect too) cannot be repaired: the unsmoothed ones
                 * (none folded) repaired instead, if they can be
                 * (vmas/pinion at 1K) */
                double *smoothed = out->quads.pos;
                uint64_t found = 0, left_raw = 0;
                uint32_t rounds = 0;
                out->quads.pos = raw;
                st = sq_remesh_quad_intersections(&out->quads, &found, NULL, 0, err);
                if (!st && found) st = sq_remesh_repair_intersections(m, &out->quads, &left_raw, &rounds, err);
                stats->t_verify = sq_now() - t1;
                if (st) {
                    out->quads.pos = smoothed;
                    goto done;
                }
                if (left_raw == 0) {
                    /* the smoothed quads, with those involved (and rings
                     * around them) put back at the repaired unsmoothed
                     * places, if that leaves no pair */
                    double *repaired_raw = out->quads.pos;
                    uint64_t left_mix = 1;
                    uint32_t kept = 0;
                    out->quads.pos = smoothed;
                    st = revert_intersecting(m, &out->quads, repaired_raw, &left_mix, &kept, err);
                    stats->t_verify = sq_now() - t1;
                    if (st) goto done;
                    if (left_mix == 0) {
                        stats->smooth_kept += kept;
                        stats->repair_rounds = rounds;
                        left = 0;
                    } else {
                        out->quads.pos = repaired_raw;
                    }
                }
                if (left_raw == 0 && left != 0) {
                    snprintf(stats->smooth_why, sizeof stats->smooth_why,
                             "%llu pairs of the smoothed quads' triangles intersect after the repair",
                             (unsigned long long)left);
                    stats->smoothed = 0;
                    stats->smooth_reverted = 1;
                    stats->self_intersections = found;
                    stats->repair_rounds = rounds;
                    left = 0;
                    raw = smoothed; /* freed at the end */
                } else {
                    out->quads.pos = smoothed;
                }
            }
            stats->repaired = stats->self_intersections - left;
            stats->self_intersections = left;
        }
        if (in == 0 && stats->self_intersections > 0) {
            st = sq_error_set(err, SQ_ERR_SOLVER,
                              "%llu pairs of the quads' triangles intersect after %u rounds of "
                              "relaxing them on the surface (the quad surface passes through itself "
                              "where the input does not: quads too skewed for the surface's thin "
                              "parts or near the cones); more optimizer iterations may help",
                              (unsigned long long)stats->self_intersections, stats->repair_rounds);
            goto done;
        }
    }
    /* the smoothed quads' figures are those returned (after the repair and
     * what went back unsmoothed) */
    if (stats->smoothed) sq_quad_quality_compute(out->quads.pos, out->quads.nq, out->quads.quad, &stats->smooth.after);
    /* no quad the referee would reject as degenerate */
    st = check_final_shapes(m, &out->quads, err);
    stats->t_verify = sq_now() - t1;
    if (st) goto done;
done:
    free(raw);
    return st;
}

/* The layouts tried from one map: their size, `quads` (or `edge_length`)
 * around a base size, and the arcs' targets (sq_quantize_options). */
typedef struct layout_size {
    double base_quads, base_edge; /* the size the layouts revolve around */
    double quads, edge_length;    /* the next layout's                   */
    int targets;                  /* the next layout's SQ_TARGETS_*      */
    uint32_t tried;               /* layouts tried at this base, less 1  */
} layout_size;

/* The next layout after one of stats->quantize.quads quads was refused.
 * Where the size asked was below the fewest quads the cones allow (the
 * layout came out larger), a quarter more than that becomes the base: the
 * fewest quads are the most skewed (cheburashka, chair and botijo with
 * their field's cones at 1K: 1,253 to 1,556 quads refused, 1,575 to 1,993
 * valid). Around a base, the arcs' targets alternate between their
 * lengths in the map (the first layout's) and on the surface, every arc
 * rounded anew: where the map is far from isometric, the two differ most
 * (mpz/femur at 5K: 108 pairs of intersecting triangles with the map's,
 * none with the surface's); after both, 3% more quads (within the 5% the
 * size allows). */
static void next_layout(const sq_remesh_stats *stats, layout_size *L)
{
    const double got = stats->quantize.quads, fewest = stats->quantize.min_quads;
    const int min_limited = fewest > 0 && got <= 1.05 * fewest &&
                            (L->base_edge > 0 || got > 1.05 * L->base_quads);
    if (min_limited) {
        L->base_quads = L->quads = 1.25 * got;
        L->base_edge = L->edge_length = 0;
        L->targets = SQ_TARGETS_MAP;
        L->tried = 0;
        return;
    }
    L->tried++;
    L->targets = L->tried % 2 ? SQ_TARGETS_SURFACE : SQ_TARGETS_MAP;
    const double factor = L->tried < 2 ? 1.0 : 1.03;
    if (L->base_edge > 0) L->edge_length = L->base_edge / sqrt(factor);
    else L->quads = factor * L->base_quads;
}

/* Forgets a refused layout's figures (stages 5 to 8) but its stage times,
 * added to t[4] (quantize, extract, smooth, verify). */
static void refused_layout(sq_remesh_stats *stats, double t[4])
{
    t[0] += stats->t_quantize, t[1] += stats->t_extract, t[2] += stats->t_smooth, t[3] += stats->t_verify;
    memset(&stats->quantize, 0, sizeof stats->quantize);
    memset(&stats->extract, 0, sizeof stats->extract);
    memset(&stats->untangle, 0, sizeof stats->untangle);
    memset(&stats->smooth, 0, sizeof stats->smooth);
    stats->smoothed = stats->smooth_reverted = 0;
    stats->smooth_why[0] = 0;
    stats->smooth_kept = 0;
    stats->self_intersections = stats->repaired = stats->repaired_unsmoothed = 0;
    stats->input_self_intersections = -1;
    stats->repair_rounds = 0;
    stats->t_quantize = stats->t_extract = stats->t_smooth = stats->t_verify = 0;
}

/* The magnified layouts (sq_remesh_magnify.c): at most this many points
 * kept from the intersecting quads of the refused layouts, and only after
 * a layout with at most MAGNIFY_MAX_PAIRS pairs per quad (femur's cones at
 * 1K: 0.084; helmet's from param's map: 2.8) */
#define MAGNIFY_POINTS 4096u
#define MAGNIFY_MAX_PAIRS 0.1

/* One run of the pipeline; *cones (if not NULL) gets a copy of the cones
 * once stage 1 has them, whatever happens after. */
static sq_status remesh_once(const sq_mesh *m, const int32_t *valence, const sq_remesh_options *opt,
                             sq_remesh_result *out, sq_remesh_stats *stats, int32_t **cones, sq_error *err)
{
    memset(stats, 0, sizeof *stats);
    sq_map M, igm;
    memset(&M, 0, sizeof M);
    memset(&igm, 0, sizeof igm);
    if (opt && opt->map) { /* taken over whatever happens next */
        M = *opt->map;
        memset(opt->map, 0, sizeof *opt->map);
    }
    if (!m || !opt || !out) {
        sq_map_free(&M);
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_remesh: NULL argument");
    }
    memset(out, 0, sizeof *out);
    if (opt->quads < 0 || opt->edge_length < 0 || (opt->quads > 0 && opt->edge_length > 0)) {
        sq_map_free(&M);
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_remesh: give a quad count or an edge length, not both");
    }
    double t0 = sq_now();
    progress_ctx pc = {opt, "cones", 0, 0, 0, 0};
    sq_param P;
    sq_param_init(&P);
    sq_status st = SQ_OK;

    /* 1. cones */
    begin(&pc, stats, "cones", SHARE_CONES);
    out->valence = malloc(((size_t)m->nv + 1) * sizeof *out->valence);
    if (!out->valence) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (cones)");
        goto fail;
    }
    if (M.mesh.nv) { /* the caller's map: its cones, checked against those given */
        stats->from_map = 1;
        if (M.mesh.nv < m->nv) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "the map has %u vertices, fewer than the mesh's %u",
                              M.mesh.nv, m->nv);
            goto fail;
        }
        memcpy(out->valence, M.valence, (size_t)m->nv * sizeof *out->valence);
        for (uint32_t v = 0; v < M.mesh.nv && !st; v++) {
            /* no cone at an added vertex; at the mesh's, the cones given (if any) */
            int32_t want = v >= m->nv ? 4 : valence ? valence[v] : M.valence[v];
            if (M.valence[v] != want)
                st = sq_error_set(err, SQ_ERR_ARGUMENT,
                                  "the map's angle sum at vertex %u makes a cone of valence %d, the cones "
                                  "given say %d",
                                  v, (int)M.valence[v], (int)want);
        }
    } else if (valence) {
        memcpy(out->valence, valence, (size_t)m->nv * sizeof *valence);
        st = sq_cones_check_gauss_bonnet(m->nv, valence, sq_mesh_euler(m), err);
        if (!st) st = sq_cones_check_realizable(m->nv, valence, sq_mesh_genus(m), err);
    } else {
        sq_cones_from_field_options fo;
        sq_cones_from_field_default_options(&fo);
        stats->cones_from_field = 1;
        st = sq_cones_from_field(m, &fo, out->valence, &stats->field, err);
    }
    if (st) goto fail;
    for (uint32_t v = 0; v < m->nv; v++) stats->cones += out->valence[v] != 4;
    stats->t_cones = sq_now() - t0;
    if (cones && (*cones = malloc(((size_t)m->nv + 1) * sizeof **cones)))
        memcpy(*cones, out->valence, (size_t)m->nv * sizeof **cones);

    /* 2. the map: on the mesh itself from the cross field's rotations
     * (sq_map_from_rotations); where that fails, or when asked, param's
     * (seed 7-9). Not when the caller gave the map. */
    double t1 = sq_now();
    if (!stats->from_map && opt->param != SQ_REMESH_PARAM_ALWAYS) {
        begin(&pc, stats, "map", SHARE_PARAM);
        double *turn = malloc(((size_t)m->nh + 1) * sizeof *turn);
        if (!turn) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (cone connection)");
            goto fail;
        }
        sq_error e2;
        st = sq_cone_connection(m, out->valence, turn, NULL, &e2);
        if (st == SQ_OK) st = sq_map_from_rotations(m, out->valence, turn, NULL, &M, &stats->rotations, err);
        else if (st != SQ_ERR_NOMEM) {
            snprintf(stats->rotations.why, sizeof stats->rotations.why, "cone connection: %.150s", e2.msg);
            st = SQ_OK;
        } else
            sq_error_set(err, st, "%s", e2.msg);
        free(turn);
        stats->map_from_rotations = stats->rotations.valid;
        stats->t_rotations = sq_now() - t1;
        if (st) goto fail;
        if (!stats->map_from_rotations && opt->param == SQ_REMESH_PARAM_NEVER) {
            st = sq_error_set(err, SQ_ERR_SOLVER, "no valid map on the mesh (%s), and param is not to run (--param never)",
                              stats->rotations.why);
            goto fail;
        }
    }
    t1 = sq_now();
    if (!stats->from_map && !stats->map_from_rotations) {
        if (strcmp(pc.stage, "map") == 0) /* param takes over the map's share */
            pc.stage = "param", stats->stage = "param";
        else
            begin(&pc, stats, "param", SHARE_PARAM);
        sq_param_options po;
        sq_param_options_default(&po);
        po.seed = opt->seed ? opt->seed : 1;
        po.attempts = opt->attempts ? opt->attempts : 4;
        po.progress = param_progress;
        po.progress_ctx = &pc;
        st = sq_param_build(m, out->valence, &po, &P, &stats->param, err);
        stats->t_param = sq_now() - t1;
        if (st) goto fail;
    }

    /* 3 and 4. the map, exact, optimized; param's is simplified in rounds
     * (a map on the mesh, the caller's or the field's, is optimized whole:
     * it has no added vertices to remove) */
    t1 = sq_now();
    begin(&pc, stats, "optimize", SHARE_OPTIMIZE);
    if (opt->keep_maps) {
        if (stats->map_from_rotations) st = sq_map_copy(&M, &out->map, err);
        else if (!stats->from_map) st = sq_param_map(&P, m, out->valence, &out->map, err);
        if (st) goto fail;
    }
    sq_optimize_options oo;
    memset(&oo, 0, sizeof oo);
    oo.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
    pc.iterations = opt->optimize_iterations ? opt->optimize_iterations : SQ_REMESH_ITERATIONS;
    oo.progress = optimize_progress;
    oo.user = &pc;
    if (stats->from_map || stats->map_from_rotations) {
        sq_param_optimize_report *rep = &stats->optimize;
        rep->conformal_before = sq_map_conformal_mean(&M);
        rep->faces_before = rep->faces_after = M.mesh.nf;
        oo.max_iterations = pc.iterations;
        sq_optimize_report r;
        st = sq_optimize_map_free_or_fixed(&M, &oo, &r, err);
        rep->iterations = r.iterations;
        rep->fixed_rounds = r.fixed_rounds;
        rep->reference_iterations = r.reference_iterations;
        memcpy(rep->why, r.why, sizeof rep->why);
        rep->conformal_after = sq_map_conformal_mean(&M);
    } else {
        st = sq_param_optimize(m, out->valence, &P, &oo, pc.iterations, &M, &stats->optimize, err);
    }
    sq_param_free(&P);
    stats->t_optimize = sq_now() - t1;
    if (st) goto fail;

    /* 5 to 8, from the optimized map: a layout at the size asked; where
     * its quads are refused (folded, or through each other beyond repair),
     * other sizes (next_layout) */
    progress_ctx pc_layout = pc;
    double refused_t[4] = {0, 0, 0, 0}; /* the refused layouts' stage times */
    layout_size L;
    memset(&L, 0, sizeof L);
    L.base_quads = L.quads = opt->edge_length > 0 ? 0 : opt->quads > 0 ? opt->quads : SQ_REMESH_QUADS;
    L.base_edge = L.edge_length = opt->edge_length;
    L.targets = SQ_TARGETS_MAP;
    double *pts = NULL; /* the intersecting quads of the refused layouts */
    uint32_t npts = 0;
    for (stats->layouts = 1;; stats->layouts++) {
        st = quads_from_map(m, &M, opt, L.quads, L.edge_length, L.targets, &pc, out, &igm, stats, err);
        stats->layout_targets = L.targets;
        if (st != SQ_ERR_SOLVER || stats->layouts == SQ_REMESH_LAYOUTS + SQ_REMESH_MAGNIFIED ||
            !(strcmp(stats->stage, "extract") == 0 || strcmp(stats->stage, "verify") == 0))
            break;
        if (strcmp(stats->stage, "verify") == 0 && stats->self_intersections > 0) {
            sq_error e2;
            if (!pts && !(pts = malloc(3 * (size_t)MAGNIFY_POINTS * sizeof *pts))) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (intersecting quads)");
                break;
            }
            sq_status s2 = sq_remesh_intersecting_points(&out->quads, pts, &npts, MAGNIFY_POINTS, &e2);
            if (s2) {
                st = s2;
                if (err) *err = e2;
                break;
            }
        }
        /* nothing to magnify, or intersections everywhere (a map too
         * distorted as a whole: helmet's from param, thousands of pairs) */
        if (stats->layouts >= SQ_REMESH_LAYOUTS &&
            (npts == 0 || (double)stats->self_intersections > MAGNIFY_MAX_PAIRS * stats->quantize.quads))
            break;
        snprintf(stats->layout_why, sizeof stats->layout_why, "%.0f quads (targets in the %s%s): %s: %.100s",
                 stats->quantize.quads, L.targets == SQ_TARGETS_MAP ? "map" : "surface",
                 stats->magnified ? ", magnified" : "", stats->stage, err ? err->msg : "");
        if (stats->layouts >= SQ_REMESH_LAYOUTS) {
            /* the map magnified around every intersection so far, twice
             * as much each time; the layout at the size asked */
            const double edge = L.base_edge > 0 ? L.base_edge : sqrt(sq_mesh_area(m) / L.base_quads);
            stats->magnified++;
            const double t2 = sq_now();
            sq_error e2;
            sq_optimize_options mo = oo; /* the optimizer's budget, as the first time */
            mo.max_iterations = opt->optimize_iterations ? opt->optimize_iterations : SQ_REMESH_ITERATIONS;
            sq_status s2 = sq_remesh_magnify_map(&M, pts, npts, 2 * edge, (double)(1u << stats->magnified), &mo, &e2);
            stats->t_optimize += sq_now() - t2;
            if (s2) { /* out of memory fails the run; otherwise the layout's refusal stands */
                if (s2 == SQ_ERR_NOMEM) {
                    st = s2;
                    if (err) *err = e2;
                }
                break;
            }
            L.quads = L.base_quads, L.edge_length = L.base_edge, L.targets = SQ_TARGETS_MAP;
        } else
            next_layout(stats, &L);
        refused_layout(stats, refused_t);
        sq_quad_mesh_free(&out->quads);
        sq_map_free(&igm);
        double done = pc.done; /* progress never goes back */
        pc = pc_layout;
        pc.done = done;
    }
    free(pts);
    stats->t_quantize += refused_t[0], stats->t_extract += refused_t[1];
    stats->t_smooth += refused_t[2], stats->t_verify += refused_t[3];
    if (st) goto fail;
    report(&pc, 1);
    if (opt->keep_maps) {
        out->optimized = M;
        out->igm = igm;
        memset(&M, 0, sizeof M);
        memset(&igm, 0, sizeof igm);
    }
    sq_map_free(&M);
    sq_map_free(&igm);
    stats->t_total = sq_now() - t0;
    return SQ_OK;

fail:
    stats->t_total = sq_now() - t0;
    sq_param_free(&P);
    sq_map_free(&M);
    sq_map_free(&igm);
    sq_remesh_result_free(out);
    return st;
}

/* The progress of both runs: a second run (param's map) reports its
 * stages again, never behind the first's last fraction. */
typedef struct monotone {
    void (*progress)(void *user, const char *stage, double fraction);
    void *user;
    double last;
} monotone;

static void monotone_progress(void *user, const char *stage, double fraction)
{
    monotone *mo = user;
    if (fraction > mo->last) mo->last = fraction;
    mo->progress(mo->user, stage, mo->last);
}

sq_status sq_remesh(const sq_mesh *m, const int32_t *valence, const sq_remesh_options *opt,
                    sq_remesh_result *out, sq_remesh_stats *stats, sq_error *err)
{
    sq_remesh_stats local;
    if (!stats) stats = &local;
    if (!opt) return remesh_once(m, valence, opt, out, stats, NULL, err);
    int32_t *cones = NULL;
    monotone mo = {opt->progress, opt->user, 0};
    sq_remesh_options o1 = *opt;
    if (opt->progress) o1.progress = monotone_progress, o1.user = &mo;
    sq_status st = remesh_once(m, valence, &o1, out, stats, &cones, err);
    /* where the quads of the map on the mesh fail a later stage (an arc of
     * the T-mesh far shorter than a quad, as on a cube whose map is exact;
     * quads through each other), param's map gets its turn */
    if (st && stats->map_from_rotations && st != SQ_ERR_NOMEM && cones && opt->param != SQ_REMESH_PARAM_NEVER) {
        sq_rotation_map_report first = stats->rotations;
        const char *stage = stats->stage ? stats->stage : "?";
        snprintf(first.why, sizeof first.why, "its quads failed at %s: %.150s", stage, err ? err->msg : "");
        first.valid = 0;
        double lost = stats->t_total;
        sq_remesh_options o2 = o1;
        o2.param = SQ_REMESH_PARAM_ALWAYS;
        st = remesh_once(m, cones, &o2, out, stats, NULL, err);
        stats->cones_from_field = valence == NULL;
        stats->rotations = first;
        stats->t_rotations = lost;
        stats->t_total += lost;
    }
    free(cones);
    return st;
}
