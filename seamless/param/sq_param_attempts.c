/* seamquad: the attempts of sq_param_build, one after another or several
 * at once.
 *
 * Attempt a of each kind uses the cut-graph seed seed + a; only SQ_ERR_SOLVER (a map that fails its exact checks,
 * the Steiner budget) is retried. The result is the lowest attempt that
 * passes, or that fails otherwise; with every attempt failing, the last.
 * The attempts are taken in order by sq_param_options.threads threads
 * (the caller's among them; with 1, one after another in the caller's),
 * each building its own map (the library has no global
 * state; the sparse solvers keep theirs per call); once attempt a ends
 * without SQ_ERR_SOLVER, the attempts after it are cancelled and the ones
 * before it are awaited, so the result is the same as one after another,
 * only sooner. Progress is reported for the lowest attempt still running.
 * With SQ_TREE_AUTO (genus >= 1, the other choices at their defaults),
 * tree qtri's first attempt comes first and the surface tree's are its
 * fallback (sq_param_build's order, build_attempts). Tree qtri's attempts
 * are heavy: nothing starts beside one (it holds up to a gigabyte and
 * runs its overlay and simplification in two threads), but one may start
 * beside a surface tree's attempt already running. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_cones.h"
#include "sq_param.h"
#include "sq_param_internal.h"

/* The options of attempt a of one kind: the cut-graph seed seed + a. */
static sq_param_options attempt_options(const sq_param_options *o, uint32_t a)
{
    sq_param_options x = *o;
    x.seed = o->seed + a;
    return x;
}

typedef struct job {
    sq_param_options o;
    const char *msg; /* progress line once it is the lowest still running */
    int heavy;       /* tree qtri's: nothing starts beside it             */
    sq_param out;
    sq_param_stats stats;
    sq_error err;
    sq_status st;
    _Atomic int cancel;
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
} pool;

static void job_progress(void *ctx, const char *stage, double f)
{
    job *J = ctx;
    pool *P = J->pool;
    pthread_mutex_lock(&P->mu);
    if ((uint32_t)(J - P->jobs) == P->lowest && P->o->progress) P->o->progress(P->o->progress_ctx, stage, f);
    pthread_mutex_unlock(&P->mu);
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
        J->st = sq_param_build_once(P->m, P->valence, &J->o, &J->cancel, &J->out, &J->stats, &J->err);
        pthread_mutex_lock(&P->mu);
        J->done = 1;
        if (J->heavy) P->heavy_running = 0;
        if (J->st != SQ_ERR_SOLVER && a < P->ended) {
            P->ended = a;
            for (uint32_t b = a + 1; b < P->n; b++) atomic_store(&P->jobs[b].cancel, 1);
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
 * result, the lowest that ended without SQ_ERR_SOLVER (else the last). */
static sq_status run_jobs(const sq_mesh *m, const int32_t *valence, const sq_param_options *o, job *jobs,
                          uint32_t n, uint32_t threads, uint32_t *pick, sq_error *err)
{
    pool P;
    memset(&P, 0, sizeof P);
    P.m = m, P.valence = valence, P.o = o, P.n = n, P.jobs = jobs;
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
    /* the lowest that passed (else the last) */
    uint32_t lo = n ? n - 1 : 0;
    for (uint32_t a = 0; a < n; a++)
        if (jobs[a].done && jobs[a].st != SQ_ERR_SOLVER) {
            lo = a;
            break;
        }
    *pick = lo;
    return SQ_OK;
}

uint64_t sq_param_crossing_budget(const sq_param_options *o, uint32_t nv, uint32_t nf)
{
    uint64_t base = sq_param_steiner_budget(o, nv);
    uint64_t per = SQ_QTRI_PER_FACE * (uint64_t)nf;
    if (per > SQ_QTRI_MAX_CROSSINGS) per = SQ_QTRI_MAX_CROSSINGS;
    return per > base ? per : base;
}

/* SQ_TREE_AUTO's two kinds of attempts: only where the caller left the
 * other choices at their defaults, and for genus >= 1 (tree qtri needs a
 * cone tree with a root path to the cut). */
static int uses_both_trees(const sq_param_options *o, int64_t genus)
{
    return genus >= 1 && o->tree == SQ_TREE_AUTO && o->guidance == SQ_GUIDE_AUTO && o->interior == SQ_INTERIOR_AUTO &&
           !o->allow_flips;
}

/* The options of one kind of attempt: tree qtri (genus 1 with the guided
 * domain, seed 9.2 per piece, where guidance is auto), or the surface
 * tree. The Steiner budget of the cuts stays (an attempt whose tree winds
 * fails there, early); tree qtri's overlay may cross more: its own budget
 * (sq_param_crossing_budget) where max_crossings is 0. */
static sq_param_options tree_options(const sq_mesh *m, const sq_param_options *o, int tree)
{
    sq_param_options f = *o;
    f.tree = tree;
    if (tree == SQ_TREE_QTRI && sq_mesh_genus(m) == 1 && f.guidance == SQ_GUIDE_AUTO) f.guidance = SQ_GUIDE_ON;
    return f;
}

/* The attempts of sq_param_build on m (the input, or the input with
 * edges between cones split), of one kind or both, in the order below;
 * stats->cut_needs_split is set where any attempt's cut graph failed for
 * want of an edge split. */
static sq_status build_attempts(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                                sq_param *out, sq_param_stats *stats, sq_error *err)
{
    const sq_param_options o = *opt;
    const uint32_t n = o.attempts ? o.attempts : 1;
    sq_status st;
    /* SQ_TREE_AUTO with both trees, in this order: tree qtri's attempts
     * (at most SQ_QTRI_ATTEMPTS), then the surface tree's. Why: tree
     * qtri's maps are as little distorted as the surface tree's or far
     * less (helmet 29.5 against 419, sculpt 92 against 367, rocker_arm 735
     * against 2e8), and on the shared models it passes within its first 3
     * attempts on every one of genus >= 1 (the first for genus >= 2;
     * bench/bench_param_modes.sh, bench_param.sh). One ordered list on
     * the threads: the result is the lowest that passes, whatever the
     * threads. */
    const int both = uses_both_trees(&o, sq_mesh_genus(m));
    const uint32_t nq = both ? (n < SQ_QTRI_ATTEMPTS ? n : SQ_QTRI_ATTEMPTS) : 0;
    const uint32_t total = n + nq;
    job *jobs = calloc(total, sizeof *jobs);
    if (!jobs) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (attempts)");
    const int one = o.tree == SQ_TREE_QTRI ? SQ_TREE_QTRI : SQ_TREE_SURFACE; /* the one kind without both */
    const sq_param_options fq = tree_options(m, &o, SQ_TREE_QTRI), fs = tree_options(m, &o, both ? SQ_TREE_SURFACE : one);
    uint32_t last_q = 0, last_s = 0;
    for (uint32_t a = 0; a < total; a++) {
        job *J = &jobs[a];
        if (a >= nq) {
            const uint32_t d = a - nq;
            J->o = attempt_options(&fs, d);
            J->heavy = fs.tree == SQ_TREE_QTRI;
            J->msg = !d ? (nq ? "fallback: the surface tree replicated in Q's quads" : NULL)
                        : "retry with another cut graph";
            last_s = a;
        } else {
            J->o = attempt_options(&fq, a);
            J->heavy = 1;
            J->msg = a ? "retry tree qtri with another cut graph" : NULL;
            last_q = a;
        }
    }
    uint32_t threads = o.threads ? o.threads : 1, pick = 0;
    if (threads > total) threads = total;
    st = run_jobs(m, valence, &o, jobs, total, threads, &pick, err);
    if (st == SQ_OK) {
        job *J = &jobs[pick];
        *out = J->out;
        memset(&J->out, 0, sizeof J->out);
        *stats = J->stats;
        stats->attempts = pick + 1;
        stats->seed_used = J->o.seed;
        stats->fallback = nq && !J->heavy;
        *err = J->err;
        st = J->st;
        if (st == SQ_ERR_SOLVER && nq) {
            /* every attempt failed: why the last of each kind did */
            char msg[3 * sizeof err->msg];
            snprintf(msg, sizeof msg,
                     "%s (tree qtri, %u attempts); the fallback (the surface tree replicated in Q's quads, %u "
                     "attempts) failed too: %s",
                     jobs[last_q].err.msg, nq, n, jobs[last_s].err.msg);
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
