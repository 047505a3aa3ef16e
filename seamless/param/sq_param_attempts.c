/* seamquad: the attempts of sq_param_build, one after another or several
 * at once.
 *
 * Attempt a uses the cut-graph seed seed + a (or seed + a / 2, alternating
 * the cone trees); only SQ_ERR_SOLVER (a map that fails its exact checks,
 * the Steiner budget) is retried. The result is the lowest attempt that
 * passes, or that fails otherwise; with every attempt failing, the last.
 * The attempts are taken in order by sq_param_options.threads threads
 * (the caller's among them; with 1, one after another in the caller's),
 * each building its own map (the library has no global
 * state; the sparse solvers keep theirs per call); once attempt a ends
 * without SQ_ERR_SOLVER, the attempts after it are cancelled and the ones
 * before it are awaited, so the result is the same as one after another,
 * only sooner. Progress is reported for the lowest attempt still running.
 * With the fallback, its first attempt sits in the same list after the
 * default choices' first, its others after their second (sq_param_build),
 * so with two threads its first one runs from the start; they are heavy:
 * nothing starts beside one (it holds up to a gigabyte and runs its
 * overlay and simplification in two threads), but it may start beside a
 * default attempt already running. One exception to "the lowest that
 * passes": where the first attempt passes with the cells' map, the
 * fallback's first goes on (or starts) with a budget of
 * SQ_REPLACE_PER_FACE crossings per input face, and its map replaces the
 * cells' where it passes (replaces_cells); that too does not depend on
 * the threads. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_cones.h"
#include "sq_param.h"
#include "sq_param_internal.h"

/* The options of attempt a. */
static sq_param_options attempt_options(const sq_param_options *o, uint32_t a, int alternate)
{
    sq_param_options x = *o;
    x.seed = o->seed + (alternate ? a / 2 : a);
    if (alternate) x.tree = a % 2 ? SQ_TREE_DOMAIN : SQ_TREE_SURFACE;
    return x;
}

static const char *retry_message(int alternate, uint32_t a)
{
    return alternate && a % 2 ? "retry with the domain's cone tree" : "retry with another cut graph";
}

typedef struct job {
    sq_param_options o;
    const char *msg; /* progress line once it is the lowest still running */
    int heavy;       /* the fallback's: nothing starts beside it          */
    sq_param out;
    sq_param_stats stats;
    sq_error err;
    sq_status st;
    _Atomic int cancel;
    _Atomic uint64_t limit; /* the overlay's crossings allowed (0: its own) */
    int done;
    struct pool *pool;
} job;

typedef struct pool {
    const sq_mesh *m;
    const int32_t *valence;
    const sq_param_options *o; /* the caller's: progress goes there */
    uint32_t n;
    job *jobs;
    pthread_mutex_t mu;
    pthread_cond_t cv; /* a job ended: a heavy one may have ended */
    int heavy_running;
    uint32_t next;   /* the next attempt to start                         */
    uint32_t ended;  /* the lowest attempt that ended without SQ_ERR_SOLVER */
    uint32_t lowest; /* the lowest attempt not done: it reports progress  */
    uint64_t replace_limit; /* crossings for replacing a cells map (0: no) */
} pool;

static void job_progress(void *ctx, const char *stage, double f)
{
    job *J = ctx;
    pool *P = J->pool;
    pthread_mutex_lock(&P->mu);
    if ((uint32_t)(J - P->jobs) == P->lowest && P->o->progress) P->o->progress(P->o->progress_ctx, stage, f);
    pthread_mutex_unlock(&P->mu);
}

/* Whether the fallback's first attempt (list position 1) replaces the
 * first's: that passed with the cells' map (no overlay), and the
 * fallback's passes, if it has ended, within replace_limit crossings,
 * with its first domain (its variants stop once the limit is set) and an
 * expectation at most a quarter above the limit (as the overlay requires
 * once the limit is set: the same whenever it was set). Before it ends:
 * whether it may still. */
static int replaces_cells(const pool *P)
{
    const job *A = &P->jobs[0], *B = &P->jobs[1];
    const uint64_t L = P->replace_limit;
    if (!L || P->n < 2 || !B->heavy) return 0;
    if (!A->done || A->st != SQ_OK || A->stats.overlay) return 0;
    return !B->done || (B->st == SQ_OK && B->stats.crossings <= L && B->stats.domain_variant == 0 &&
                        B->stats.crossings_expected <= L + L / 4);
}

static void *worker(void *arg)
{
    pool *P = arg;
    pthread_mutex_lock(&P->mu);
    for (;;) {
        uint32_t a = P->next;
        if (a >= P->n || a > P->ended) break;
        job *J = &P->jobs[a];
        if (P->heavy_running) { /* nothing starts beside a heavy one: it may use both threads */
            pthread_cond_wait(&P->cv, &P->mu);
            continue;
        }
        P->next++;
        if (J->heavy) P->heavy_running = 1;
        pthread_mutex_unlock(&P->mu);
        J->st = sq_param_build_once(P->m, P->valence, &J->o, &J->cancel, &J->limit, &J->out, &J->stats, &J->err);
        pthread_mutex_lock(&P->mu);
        J->done = 1;
        if (J->heavy) P->heavy_running = 0;
        if (J->st != SQ_ERR_SOLVER && a < P->ended) {
            /* a cells map of the first attempt may yield to the fallback's
             * first (replaces_cells): that one goes on (or starts), with
             * the budget of such a replacement */
            const int provisional = replaces_cells(P);
            P->ended = provisional ? 1 : a;
            if (provisional) atomic_store(&P->jobs[1].limit, P->replace_limit);
            for (uint32_t b = P->ended + 1; b < P->n; b++) atomic_store(&P->jobs[b].cancel, 1);
        }
        if (a == P->lowest) {
            /* as one after another: the line of every attempt after the
             * lowest done, up to the one that ended the run */
            uint32_t from = P->lowest + 1;
            while (P->lowest < P->n && P->jobs[P->lowest].done) P->lowest++;
            for (uint32_t k = from; k <= P->lowest && k < P->n && k <= P->ended && P->o->progress; k++)
                if (P->jobs[k].msg) P->o->progress(P->o->progress_ctx, P->jobs[k].msg, 0.0);
        }
        pthread_cond_broadcast(&P->cv);
    }
    pthread_mutex_unlock(&P->mu);
    return NULL;
}

/* Runs the attempts jobs[0, n) (their options, messages and heaviness
 * set) on `threads` threads in order, as described at the top; *pick: the
 * result, the lowest that ended without SQ_ERR_SOLVER (else the last),
 * or the fallback's first where it replaces the first's cells map
 * (replace_limit crossings; 0: never). */
static sq_status run_jobs(const sq_mesh *m, const int32_t *valence, const sq_param_options *o, job *jobs,
                          uint32_t n, uint32_t threads, uint64_t replace_limit, uint32_t *pick, sq_error *err)
{
    pool P;
    memset(&P, 0, sizeof P);
    P.m = m, P.valence = valence, P.o = o, P.n = n, P.jobs = jobs, P.replace_limit = replace_limit;
    P.ended = n, P.lowest = 0;
    pthread_t *th = calloc(threads, sizeof *th);
    if (!th || pthread_mutex_init(&P.mu, NULL) != 0) {
        free(th);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (attempt threads)");
    }
    if (pthread_cond_init(&P.cv, NULL) != 0) {
        pthread_mutex_destroy(&P.mu);
        free(th);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (attempt threads)");
    }
    for (uint32_t a = 0; a < n; a++) {
        job *J = &jobs[a];
        J->o.progress = job_progress, J->o.progress_ctx = J;
        J->pool = &P, J->st = SQ_ERR_SOLVER;
        atomic_init(&J->cancel, 0);
        atomic_init(&J->limit, 0);
        sq_param_init(&J->out);
    }
    /* threads - 1 helpers; this thread works too */
    uint32_t started = 0;
    for (uint32_t t = 1; t < threads; t++)
        if (pthread_create(&th[started], NULL, worker, &P) == 0) started++;
    worker(&P);
    for (uint32_t t = 0; t < started; t++) pthread_join(th[t], NULL);
    pthread_cond_destroy(&P.cv);
    pthread_mutex_destroy(&P.mu);
    free(th);
    /* the lowest that passed (else the last), or the replacement of its
     * cells map */
    uint32_t lo = n ? n - 1 : 0;
    for (uint32_t a = 0; a < n; a++)
        if (jobs[a].done && jobs[a].st != SQ_ERR_SOLVER) {
            lo = a;
            break;
        }
    if (lo == 0 && replaces_cells(&P) && jobs[1].done) lo = 1;
    *pick = lo;
    return SQ_OK;
}

uint64_t sq_param_crossing_budget(const sq_param_options *o, uint32_t nv, uint32_t nf)
{
    uint64_t base = sq_param_steiner_budget(o, nv);
    uint64_t per = SQ_FALLBACK_PER_FACE * (uint64_t)nf;
    if (per > SQ_QTRI_MAX_CROSSINGS) per = SQ_QTRI_MAX_CROSSINGS;
    return per > base ? per : base;
}

/* The fallbacks (SQ_FALLBACK_AUTO): only where the caller left the
 * choices they override at their defaults. */
static int uses_fallback(const sq_param_options *o, int64_t genus)
{
    return genus >= 1 && o->fallback == SQ_FALLBACK_AUTO && o->guidance == SQ_GUIDE_AUTO &&
           o->tree == SQ_TREE_SURFACE && o->interior == SQ_INTERIOR_AUTO && !o->allow_flips;
}

/* The options of the fallback (SQ_FALLBACK_AUTO): the surface tree copied
 * into Q triangulated and the overlay (SQ_TREE_QTRI; for genus 1 with the
 * guided domain, seed 9.2 per piece), whose map the cells could not give:
 * cid/elephant and mpz/elk, whose surface trees Q's quad grid cannot
 * follow (docs/param.md). The Steiner budget of the cuts stays (an
 * attempt whose tree winds fails there, early); the overlay may cross
 * more: tree qtri's own budget (sq_param_crossing_budget) where
 * max_crossings is 0. */
static sq_param_options fallback_options(const sq_mesh *m, const sq_param_options *o)
{
    sq_param_options f = *o;
    f.tree = SQ_TREE_QTRI;
    if (sq_mesh_genus(m) == 1) f.guidance = SQ_GUIDE_ON;
    return f;
}

/* The fallback's attempt at list position a (sq_param_build's order:
 * position 1, then first + 1 .. first + nfb - 1), or SQ_NONE: one of the
 * default choices'. */
static uint32_t fallback_index(uint32_t a, uint32_t first, uint32_t nfb)
{
    if (!nfb) return SQ_NONE;
    if (a == 1) return 0;
    return a > first && a < first + nfb ? a - first : SQ_NONE;
}

/* The attempts of sq_param_build on m (the input, or the input with
 * edges between cones split), with their fallback, in the order below;
 * stats->cut_needs_split is set where any attempt's cut graph failed for
 * want of an edge split. */
static sq_status build_attempts(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                                sq_param *out, sq_param_stats *stats, sq_error *err)
{
    const sq_param_options o = *opt;
    const uint32_t n = o.attempts ? o.attempts : 1;
    sq_status st;
    /* SQ_TREE_ALTERNATE with guidance (genus >= 2, or genus 1 with
     * SQ_GUIDE_ON): each seed twice, the surface tree, then Q's tree */
    const int alternate = sq_param_uses_algorithm1(o.guidance, sq_mesh_genus(m)) && o.tree == SQ_TREE_ALTERNATE;
    /* with the fallback, in this order: the default choices' first
     * attempt, the fallback's first, the default choices' others up to
     * SQ_FALLBACK_AFTER, the fallback's others (at most
     * SQ_FALLBACK_ATTEMPTS in all, from the same seed), then the default
     * choices' other attempts. Why: where the first two default attempts
     * fail, the later ones rarely pass (with the fallback off: block at
     * the 15th, fertility_tri at the 7th, femur at the 3rd; elephant at
     * none of 16, 36 to 54 s spent), and the fallback's maps are far less
     * distorted (mean conformal ratio 129 against 3.7e8 on block;
     * docs/param.md). One ordered list on the threads: with two, the
     * fallback's first attempt runs beside the default choices' first
     * from the start, and the result is still the lowest that passes.
     * The fallback's attempts are heavy (each may hold a gigabyte and use
     * both threads): nothing starts beside one, so on elephant the
     * default attempts 2 and 3 do not compete with the fallback's first,
     * which passes. */
    const int fb = uses_fallback(&o, sq_mesh_genus(m));
    const uint32_t first = fb && n > SQ_FALLBACK_AFTER ? SQ_FALLBACK_AFTER : n;
    const uint32_t nfb = fb ? (n < SQ_FALLBACK_ATTEMPTS ? n : SQ_FALLBACK_ATTEMPTS) : 0;
    const uint32_t total = n + nfb;
    job *jobs = calloc(total, sizeof *jobs);
    if (!jobs) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (attempts)");
    const sq_param_options f = fallback_options(m, &o);
    /* list position a: the default choices' attempt d or the fallback's
     * attempt k (fallback_index) */
    for (uint32_t a = 0, d = 0; a < total; a++) {
        job *J = &jobs[a];
        const uint32_t k = fallback_index(a, first, nfb);
        if (k == SQ_NONE) {
            J->o = attempt_options(&o, d, alternate);
            J->msg = d ? retry_message(alternate, d) : NULL;
            d++;
        } else {
            J->o = attempt_options(&f, k, 0);
            J->heavy = 1;
            J->msg = k == 0 ? "fallback: the surface tree copied into Q triangulated, overlay"
                            : retry_message(0, k);
        }
    }
    uint32_t threads = o.threads ? o.threads : 1, pick = 0;
    if (threads > total) threads = total;
    /* a cells map of the default choices' first attempt (10^8 to 10^10
     * mean conformal ratio on rocker_arm, sculpt, trim-star) yields to the
     * fallback's first attempt where that passes within
     * SQ_REPLACE_PER_FACE crossings per input face (rocker_arm 77, sculpt
     * 32; trim-star's needs 264 per face and about 9 s: kept) */
    const uint64_t replace_limit = nfb ? SQ_REPLACE_PER_FACE * (uint64_t)m->nf : 0;
    st = run_jobs(m, valence, &o, jobs, total, threads, replace_limit, &pick, err);
    if (st == SQ_OK) {
        job *J = &jobs[pick];
        *out = J->out;
        memset(&J->out, 0, sizeof J->out);
        *stats = J->stats;
        stats->attempts = pick + 1;
        stats->seed_used = J->o.seed;
        stats->fallback = J->heavy;
        stats->replaced_cells = pick == 1 && jobs[0].st == SQ_OK;
        *err = J->err;
        st = J->st;
        if (st == SQ_ERR_SOLVER && nfb) {
            /* every attempt failed: why the last of each group did (the
             * default choices' attempt first - 1 sits at position first) */
            const int g1 = sq_mesh_genus(m) == 1;
            char msg[3 * sizeof err->msg];
            int len = snprintf(msg, sizeof msg,
                               "%s; the fallback (%sthe surface tree copied into Q triangulated, overlay; %u "
                               "attempts) failed too: %s",
                               jobs[first > 1 ? first : 0].err.msg, g1 ? "guided domain, " : "", nfb,
                               jobs[first + nfb - 1].err.msg);
            if (total > first + nfb && len > 0 && (size_t)len < sizeof msg)
                snprintf(msg + len, sizeof msg - (size_t)len, "; then attempts %u to %u with the default choices: %s",
                         first + nfb + 1, total, jobs[total - 1].err.msg);
            sq_error_set(err, SQ_ERR_SOLVER, "%s", msg);
        }
    }
    if (st == SQ_ERR_SOLVER)
        for (uint32_t a = 0; a < total; a++) stats->cut_needs_split |= jobs[a].stats.cut_needs_split;
    for (uint32_t a = 0; a < total; a++) sq_param_free(&jobs[a].out);
    free(jobs);
    return st;
}

/* Seed 9.1: "edges between two singular vertices are split to enable
 * loops passing between them". Only where the attempts on the input
 * failed for want of it (a ring of adjacent cones around a handle, a
 * non-cone vertex walled in by cones): every edge between two cones gets
 * its midpoint (sq_param_split_walls, no cut), the attempts run again on
 * that mesh, and the map is expressed on the input (its vertices first,
 * the midpoints among the Steiner vertices, each face naming its input
 * face). Elsewhere the maps stay as they were. */
static sq_status build_split_cones(const sq_mesh *m, const int32_t *valence, const sq_param_options *o,
                                   sq_param *out, sq_param_stats *stats, sq_error *err)
{
    sq_mesh m2;
    int32_t *val2 = NULL;
    uint32_t *fparent = NULL, nsplit = 0;
    sq_error e2;
    sq_error_clear(&e2);
    sq_status s2 = sq_param_split_walls(m, valence, NULL, &m2, &val2, &fparent, NULL, &nsplit, &e2);
    if (s2 == SQ_ERR_NOMEM) {
        *err = e2;
        return s2;
    }
    if (s2 || !nsplit) return SQ_ERR_SOLVER; /* nothing to split: the first failure stands */
    char first[sizeof err->msg];
    snprintf(first, sizeof first, "%s", err->msg);
    sq_status st = build_attempts(&m2, val2, o, out, stats, err);
    stats->verts_in = m->nv, stats->faces_in = m->nf, stats->cone_splits = nsplit, stats->cut_needs_split = 1;
    if (st == SQ_OK) {
        out->nv_input = m->nv;
        for (uint32_t f = 0; f < out->nf; f++) out->tri_in[f] = fparent[out->tri_in[f]];
    } else if (st == SQ_ERR_SOLVER) {
        char msg[3 * sizeof err->msg];
        snprintf(msg, sizeof msg, "%s; with the %u edges between two cones split (seed 9.1): %s", first, nsplit,
                 err->msg);
        sq_error_set(err, st, "%s", msg);
    }
    sq_mesh_free(&m2);
    free(val2), free(fparent);
    return st;
}

sq_status sq_param_build(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                         sq_param *out, sq_param_stats *stats, sq_error *err)
{
    double t_start = sq_now();
    sq_error local_err;
    if (!err) err = &local_err;
    sq_param_options o;
    if (opt) o = *opt;
    else sq_param_options_default(&o);
    sq_param_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    stats->verts_in = m->nv, stats->faces_in = m->nf;
    /* the input's cone set, once for every attempt */
    sq_status st = sq_cones_check_gauss_bonnet(m->nv, valence, sq_mesh_euler(m), err);
    if (st == SQ_OK) st = sq_cones_check_realizable(m->nv, valence, sq_mesh_genus(m), err);
    if (st) return st;
    st = build_attempts(m, valence, &o, out, stats, err);
    if (st == SQ_ERR_SOLVER && stats->cut_needs_split) st = build_split_cones(m, valence, &o, out, stats, err);
    if (st == SQ_OK && o.simplify != SQ_SIMPLIFY_OFF && !o.allow_flips) {
        double t = sq_now();
        if (o.progress) o.progress(o.progress_ctx, "simplify", 0.95);
        stats->faces_unsimplified = out->nf;
        st = sq_param_simplify_threads(m, out, o.threads ? o.threads : 1, &stats->simplified, err);
        if (st) sq_param_free(out);
        else {
            stats->verts_out = out->nv, stats->faces_out = out->nf;
            stats->steiner = out->nv - out->nv_input, stats->nuv = out->nuv;
            sq_param_distortion(out, stats);
        }
        stats->t_simplify = sq_now() - t;
    }
    /* the 3D side: a refinement of m, whatever the attempt and the
     * simplification did */
    if (st == SQ_OK && (st = sq_param_verify_refinement(out, m, &stats->refinement_max_dist, err)))
        sq_param_free(out);
    stats->t_total = sq_now() - t_start;
    return st;
}
