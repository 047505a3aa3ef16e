/* seamquad: quad mesh smoothing on a triangle surface (docs/smooth.md).
 *
 * Each outer iteration: every vertex gets a tangent frame at its current
 * position on the surface (the normal of the surface triangle it lies on)
 * and two unknowns, its offset in that plane in units of its mean incident
 * edge length; Ceres (sq_ceres_adapter.h) minimizes the objective of
 * sq_smooth_energy.c under the no-fold constraint; the result is projected
 * back onto the surface (closest point, sq_closest_point.h) and accepted
 * only if no quad folds there and (smoothing) no referee measure gets
 * worse (quality_not_worse, after revert_worsened); otherwise the step is
 * halved, up to MAX_BACKTRACK times, then retried with damping, then
 * rejected. A quick step that fails or stalls early makes every later
 * solve start from a small trust region (docs/smooth.md, "Trust
 * region"). From the second half of the iterations on, quad vertices are
 * first pinned on the surface's sharp points where the quads would cut
 * them off (pin_far_surface_vertices, sq_smooth_pin.c) and held there. */
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_ceres_adapter.h"
#include "sq_closest_point.h"
#include "sq_mesh.h"
#include "sq_smooth_internal.h"

#define MAX_BACKTRACK 8
#define MAX_RETRY 2         /* damped retries of a rejected outer step        */
#define DAMPING_START 0.25  /* damping weight of the first retry             */
#define PIN_SJAC_FLOOR 0.2  /* a pin may not take a quad's scaled Jacobian below */

void sq_smooth_options_default(sq_smooth_options *o)
{
    memset(o, 0, sizeof *o);
    o->iterations = 10;
    o->solver_iterations = 5;
    o->linear_iterations = 10;
    o->untangle_solver_iterations = 20;
    o->untangle_linear_iterations = 500;
    o->untangle_iterations = 30;
    o->angle_weight = 1.0;
    o->length_weight = 1.0;
    o->untangle_weight = 4.0;
    o->barrier_weight = 0.1;
    o->fold_margin = 0.01;
    o->untangle_target = 1e-3;
    o->pin_threshold = 0.3;
    o->function_tolerance = 1e-6;
    o->stop_tolerance = 1e-4;
    o->thorough_stop_tolerance = 1e-3;
    o->gradient_tolerance = 1e-10;
    o->parameter_tolerance = 1e-8;
    o->trust_region_radius = 1e4;
    o->cautious_trust_region_radius = 1.0;
    o->num_threads = 1;
}

typedef struct smoother {
    const sq_smooth_options *opt;
    sq_smooth_stats *stats;
    sq_cp_tree tree;
    const double *tri_normal;   /* 3*snt unit normals                       */
    const double *vnormal;      /* 3*snv area-weighted vertex normals        */
    const uint32_t *stri;       /* 3*snt surface triangles                   */
    double *vbary, *cand_bary;  /* 3*nv barycentrics of each vertex in vtri  */
    uint32_t nv, nq;
    const uint32_t *quads;
    double *pos;                /* 3*nv, caller's array: the accepted state  */
    uint32_t *vtri;             /* nv: surface triangle of each vertex       */
    double *frame, *h, *ref_normal, *threshold, *x, *cand, *margin, *target, *ideal_log;
    uint32_t *cand_tri, *con_quad, *res_off, *res_param, *res_dim;
    uint32_t *pin_v, *pin_s;    /* snv each: candidate pins (sq_smooth_pin.c)  */
    unsigned char *pinned;      /* nv: 1 = held on a surface vertex (Fidelity) */
    uint32_t *vq_off, *vq;      /* quads around each vertex (CSR: nv+1, 4*nq)  */
    uint32_t snv;
    const double *spos;
    unsigned char *untangle;
    double *base_angle;         /* 4*nq: corner angles at the solve's start    */
    double *old_sjac, *old_ratio; /* nq: each quad's scaled Jacobian and edge  */
                                /* ratio in the accepted state (revert_pass)   */
    unsigned char *old_turned;  /* nq: turned over there (quad_turned)         */
    unsigned char *thin;        /* snt: too thin for its own normal            */
    double *unit_vnormal;       /* 3*snv: vnormal normalized (quad_turned)     */
    unsigned char *dirty;       /* nq: to be judged again (revert_pass)        */
    sq_smooth_ctx ctx;
    double radius;              /* Levenberg-Marquardt's first trust region  */
} smoother;

static void set_frames(smoother *s)
{
    for (uint32_t v = 0; v < s->nv; v++) {
        double *f = s->frame + 9 * (size_t)v;
        /* the surface's smooth normal at the vertex: area-weighted vertex
         * normals interpolated with its barycentric coordinates (a sliver
         * triangle's own normal is noise; see docs/smooth.md) */
        const double *bc = s->vbary + 3 * (size_t)v;
        const uint32_t *tv = s->stri + 3 * (size_t)s->vtri[v];
        double n[3];
        for (int k = 0; k < 3; k++)
            n[k] = bc[0] * s->vnormal[3 * (size_t)tv[0] + k] + bc[1] * s->vnormal[3 * (size_t)tv[1] + k] +
                   bc[2] * s->vnormal[3 * (size_t)tv[2] + k];
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(nl > 0.0)) memcpy(n, s->tri_normal + 3 * (size_t)s->vtri[v], sizeof n), nl = 1.0;
        for (int k = 0; k < 3; k++) n[k] /= nl;
        /* t1: n x (the axis least aligned with n), t2 = n x t1 */
        int ax = fabs(n[0]) <= fabs(n[1]) ? (fabs(n[0]) <= fabs(n[2]) ? 0 : 2) : (fabs(n[1]) <= fabs(n[2]) ? 1 : 2);
        double a[3] = {0, 0, 0};
        a[ax] = 1.0;
        double t1[3] = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]};
        double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
        for (int k = 0; k < 3; k++) t1[k] /= l;
        double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
        memcpy(f, t1, sizeof t1);
        memcpy(f + 3, t2, sizeof t2);
        memcpy(f + 6, n, 3 * sizeof(double));
    }
    /* h: mean length of the incident edges (every edge is seen from both quads) */
    memset(s->h, 0, s->nv * sizeof(double));
    uint32_t *cnt = s->cand_tri; /* scratch */
    memset(cnt, 0, s->nv * sizeof(uint32_t));
    double total = 0.0;
    for (uint32_t q = 0; q < s->nq; q++)
        for (int k = 0; k < 4; k++) {
            uint32_t a = s->quads[4 * (size_t)q + k], b = s->quads[4 * (size_t)q + (k + 1) % 4];
            const double *pa = s->pos + 3 * (size_t)a, *pb = s->pos + 3 * (size_t)b;
            double d = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                            (pa[2] - pb[2]) * (pa[2] - pb[2]));
            s->h[a] += d, s->h[b] += d;
            cnt[a]++, cnt[b]++;
            total += d;
        }
    double mean = total / (4.0 * s->nq);
    /* per-quad reference normal: the mean of its corners' surface normals */
    for (uint32_t q = 0; q < s->nq; q++) {
        double *n = s->ref_normal + 3 * (size_t)q;
        n[0] = n[1] = n[2] = 0.0;
        for (int k = 0; k < 4; k++)
            for (int j = 0; j < 3; j++) n[j] += s->frame[9 * (size_t)s->quads[4 * (size_t)q + k] + 6 + j];
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int j = 0; j < 3; j++) n[j] = l > 0.0 ? n[j] / l : (j == 2);
    }
    for (uint32_t v = 0; v < s->nv; v++) {
        s->h[v] = cnt[v] ? s->h[v] / cnt[v] : mean;
        if (!(s->h[v] > 0.0)) s->h[v] = mean > 0.0 ? mean : 1.0;
    }
    /* each corner's angle now, around the new reference normals: during the
     * solve a corner's angle is taken on the branch within pi of it, so a
     * corner near 0 or 360 degrees does not jump by 360 when a trial step
     * crosses (measured: femur's quads from quantize, with corners of 2 to
     * 7 degrees on bent quads, stalled at 10.0 degrees with Ceres rejecting
     * 41 of 56 steps; 6.4 degrees with the branch kept) */
    for (uint32_t q = 0; q < s->nq; q++) {
        const double *x[4];
        for (int k = 0; k < 4; k++) x[k] = s->pos + 3 * (size_t)s->quads[4 * (size_t)q + k];
        sq_smooth_corner_angles(x, s->ref_normal + 3 * (size_t)q, s->base_angle + 4 * (size_t)q);
    }
    s->ctx.base_angle = s->base_angle;
}

static void compute_margins(smoother *s, const double *pos)
{
    for (uint32_t q = 0; q < s->nq; q++) {
        const uint32_t *f = s->quads + 4 * (size_t)q;
        s->margin[q] = sq_quad_fold_margin(pos + 3 * (size_t)f[0], pos + 3 * (size_t)f[1],
                                           pos + 3 * (size_t)f[2], pos + 3 * (size_t)f[3]);
    }
}

/* Quad f (its corners in pos, each in surface triangle tri[v] at
 * barycentrics bary[3v..]) turned over on the surface: every corner facing
 * away from both the interpolated unit vertex normals there and the
 * triangle's own normal (the latter skipped on a triangle too thin to have
 * one), as sq_quad_mesh_count_turned (extract/sq_extract.h) judges the
 * result. */
static int quad_turned(const smoother *s, const double *pos, const uint32_t *tri, const double *bary,
                       const uint32_t *f)
{
    const double *p[4], *ns[4], *nf[4];
    double sm[4][3];
    for (int k = 0; k < 4; k++) {
        uint32_t v = f[k], t = tri[v];
        const double *bc = bary + 3 * (size_t)v;
        const uint32_t *tv = s->stri + 3 * (size_t)t;
        for (int i = 0; i < 3; i++)
            sm[k][i] = bc[0] * s->unit_vnormal[3 * (size_t)tv[0] + i] +
                       bc[1] * s->unit_vnormal[3 * (size_t)tv[1] + i] + bc[2] * s->unit_vnormal[3 * (size_t)tv[2] + i];
        double l = sqrt(sm[k][0] * sm[k][0] + sm[k][1] * sm[k][1] + sm[k][2] * sm[k][2]);
        if (l > 0.0) sm[k][0] /= l, sm[k][1] /= l, sm[k][2] /= l;
        p[k] = pos + 3 * (size_t)v, ns[k] = sm[k];
        nf[k] = s->thin[t] ? sm[k] : s->tri_normal + 3 * (size_t)t;
    }
    return sq_quad_turn_margin_either(p, ns, nf) < 0.0;
}

/* The acceptance test of a smoothing step (docs/smooth.md, "Acceptance"):
 * none of the referee's measures gets worse, and the primary one improves. */
static int quality_not_worse(const sq_quad_quality *n, const sq_quad_quality *o)
{
    return n->angle_mean_dev_deg < o->angle_mean_dev_deg && n->sjac_min >= o->sjac_min &&
           n->edge_ratio_mean <= o->edge_ratio_mean && n->folded == 0;
}

/* Local acceptance (docs/smooth.md, "Acceptance"): a quad that the candidate
 * would fold or turn over on the surface (quad_turned; one already turned
 * may stay so), push below min(its own, the current minimum) scaled
 * Jacobian or give an edge ratio above its own + tau gets its four vertices reverted
 * to the accepted state; repeated until no quad is reverted (a revert
 * changes the neighbours' quads). revert_worsened: tau = infinity, then
 * 1, 1/2, ... (then 0) while the mean edge ratio is above the current one.
 * The first round judges every quad with a moved corner, the later ones
 * only the quads of a vertex reverted since (the others are as they were
 * when accepted): the same reverts as judging all of them every round.
 * The accepted state's figures are s->old_sjac and s->old_ratio
 * (set_old_shapes). */
static void set_old_shapes(smoother *s)
{
    for (uint32_t q = 0; q < s->nq; q++) {
        sq_quad_quality qo;
        sq_quad_quality_compute_shapes(s->pos, 1, s->quads + 4 * (size_t)q, &qo);
        s->old_sjac[q] = qo.sjac_min, s->old_ratio[q] = qo.edge_ratio_mean;
        s->old_turned[q] = (unsigned char)quad_turned(s, s->pos, s->vtri, s->vbary, s->quads + 4 * (size_t)q);
    }
}

static void revert_pass(smoother *s, const sq_quad_quality *g, double tau)
{
    memset(s->dirty, 1, s->nq);
    for (int round = 0; round < 64; round++) {
        uint32_t reverted = 0;
        for (uint32_t q = 0; q < s->nq; q++) {
            if (!s->dirty[q]) continue;
            s->dirty[q] = 0;
            const uint32_t *f = s->quads + 4 * (size_t)q;
            int moved = 0;
            for (int k = 0; k < 4; k++)
                moved |= memcmp(s->cand + 3 * (size_t)f[k], s->pos + 3 * (size_t)f[k], 3 * sizeof(double)) != 0;
            if (!moved) continue;
            sq_quad_quality qn;
            sq_quad_quality_compute_shapes(s->cand, 1, f, &qn);
            int bad = qn.folded || !(qn.fold_margin_min >= s->threshold[q]) ||
                      !(qn.sjac_min >= fmin(s->old_sjac[q], g->sjac_min)) ||
                      !(qn.edge_ratio_mean <= s->old_ratio[q] + tau) ||
                      (!s->old_turned[q] && quad_turned(s, s->cand, s->cand_tri, s->cand_bary, f));
            if (!bad) continue;
            for (int k = 0; k < 4; k++) {
                uint32_t v = f[k];
                memcpy(s->cand + 3 * (size_t)v, s->pos + 3 * (size_t)v, 3 * sizeof(double));
                memcpy(s->cand_bary + 3 * (size_t)v, s->vbary + 3 * (size_t)v, 3 * sizeof(double));
                s->cand_tri[v] = s->vtri[v];
                for (uint32_t j = s->vq_off[v]; j < s->vq_off[v + 1]; j++) s->dirty[s->vq[j]] = 1;
            }
            reverted++;
        }
        if (!reverted) return;
    }
}

static void revert_worsened(smoother *s, const sq_quad_quality *g)
{
    revert_pass(s, g, INFINITY);
    for (double tau = 1.0;; tau *= 0.5) {
        sq_quad_quality qn;
        sq_quad_quality_compute_shapes(s->cand, s->nq, s->quads, &qn);
        if (qn.edge_ratio_mean <= g->edge_ratio_mean) return;
        if (tau < 1e-4) tau = 0.0;
        revert_pass(s, g, tau);
        if (tau == 0.0) return;
    }
}

/* Fidelity pins (docs/smooth.md, "Fidelity"): each surface vertex that
 * the quads miss by a wide gap (sq_smooth_find_pins) gets its quad vertex
 * moved onto it and held there, unless that would take one of the vertex's
 * quads below its fold threshold, or its scaled Jacobian below both its own
 * and the larger of PIN_SJAC_FLOOR and the untangled mesh's minimum, or the
 * mesh's mean |angle - 90| or mean edge ratio above the untangled mesh's:
 * the smoother's promise (docs/smooth.md, "Acceptance") holds with pins.
 * A vertex of more than 16 quads is not pinned (the check's fixed arrays).
 * Returns the number of vertices pinned now, or -1 with err set. */
static int pin_far_surface_vertices(smoother *s, sq_error *err)
{
    uint32_t n;
    if (sq_smooth_find_pins(s->snv, s->spos, s->nv, s->pos, s->nq, s->quads, s->h, s->opt->pin_threshold,
                            s->pin_v, s->pin_s, &n, err) != SQ_OK)
        return -1;
    const sq_quad_quality *in = &s->stats->untangled; /* the promise is kept from here */
    double floor = fmax(PIN_SJAC_FLOOR, in->sjac_min);
    sq_quad_quality g;
    sq_quad_quality_compute(s->pos, s->nq, s->quads, &g);
    double ang_sum = g.angle_mean_dev_deg * s->nq, ratio_sum = g.edge_ratio_mean * s->nq;
    int pinned = 0;
    for (uint32_t a = 0; a < n; a++) {
        uint32_t v = s->pin_v[a];
        uint32_t deg = s->vq_off[v + 1] - s->vq_off[v];
        if (s->pinned[v] || deg > 16) continue;
        sq_quad_quality qo[16], qn;
        int turned[16];
        for (uint32_t j = 0; j < deg; j++) {
            const uint32_t *f = s->quads + 4 * (size_t)s->vq[s->vq_off[v] + j];
            sq_quad_quality_compute(s->pos, 1, f, &qo[j]);
            turned[j] = quad_turned(s, s->pos, s->vtri, s->vbary, f);
        }
        double *x = s->pos + 3 * (size_t)v, old[3], old_bary[3];
        uint32_t old_tri = s->vtri[v];
        memcpy(old, x, sizeof old);
        memcpy(old_bary, s->vbary + 3 * (size_t)v, sizeof old_bary);
        sq_cp_hit hit; /* the surface vertex as a point of one of its triangles */
        sq_cp_tree_query(&s->tree, s->spos + 3 * (size_t)s->pin_s[a], &hit);
        memcpy(x, hit.point, sizeof hit.point);
        s->vtri[v] = hit.tri;
        memcpy(s->vbary + 3 * (size_t)v, hit.bary, sizeof hit.bary);
        int ok = 1;
        double dang = 0.0, dratio = 0.0;
        for (uint32_t j = 0; j < deg && ok; j++) {
            uint32_t q = s->vq[s->vq_off[v] + j];
            const uint32_t *f = s->quads + 4 * (size_t)q;
            sq_quad_quality_compute(s->pos, 1, f, &qn);
            double m = sq_quad_fold_margin(s->pos + 3 * (size_t)f[0], s->pos + 3 * (size_t)f[1],
                                           s->pos + 3 * (size_t)f[2], s->pos + 3 * (size_t)f[3]);
            ok = !qn.folded && m >= s->threshold[q] && qn.sjac_min >= fmin(qo[j].sjac_min, floor) &&
                 (turned[j] || !quad_turned(s, s->pos, s->vtri, s->vbary, f));
            dang += qn.angle_mean_dev_deg - qo[j].angle_mean_dev_deg;
            dratio += qn.edge_ratio_mean - qo[j].edge_ratio_mean;
        }
        ok = ok && (ang_sum + dang) / s->nq < in->angle_mean_dev_deg &&
             (ratio_sum + dratio) / s->nq <= in->edge_ratio_mean;
        if (!ok) {
            memcpy(x, old, sizeof old);
            s->vtri[v] = old_tri;
            memcpy(s->vbary + 3 * (size_t)v, old_bary, sizeof old_bary);
            continue;
        }
        ang_sum += dang, ratio_sum += dratio;
        s->pinned[v] = 1;
        pinned++;
    }
    return pinned;
}

/* One outer step. Returns 1 accepted, 0 rejected (would fold or not
 * decrease), 2 no progress (Ceres took no step), or -1 with err set. */
static int outer_step(smoother *s, int smoothing, sq_error *err)
{
    const sq_smooth_options *o = s->opt;
    uint32_t nres = s->nq, ncon = 0;
    s->res_off[0] = 0;
    for (uint32_t q = 0; q < s->nq; q++) {
        for (int k = 0; k < 4; k++) s->res_param[4 * (size_t)q + k] = s->quads[4 * (size_t)q + k];
        s->res_off[q + 1] = 4 * (q + 1);
        s->res_dim[q] = sq_smooth_residual_count(&s->ctx, q);
        if (s->threshold[q] > -INFINITY) s->con_quad[ncon++] = q;
    }
    if (smoothing && s->ctx.damping > 0.0) /* retry: a damped, shorter step */
        for (uint32_t v = 0; v < s->nv; v++, nres++) {
            s->res_off[nres + 1] = s->res_off[nres] + 1;
            s->res_param[s->res_off[nres]] = v;
            s->res_dim[nres] = 2;
        }
    /* constraint blocks reuse res_param (same four vertices as the quad) */
    uint32_t *con_off = malloc((ncon + 1) * sizeof(uint32_t));
    uint32_t *con_param = malloc(4 * (size_t)(ncon ? ncon : 1) * sizeof(uint32_t));
    if (!con_off || !con_param) {
        free(con_off), free(con_param);
        sq_error_set(err, SQ_ERR_NOMEM, "smooth: out of memory");
        return -1;
    }
    con_off[0] = 0;
    for (uint32_t c = 0; c < ncon; c++) {
        memcpy(con_param + 4 * (size_t)c, s->quads + 4 * (size_t)s->con_quad[c], 4 * sizeof(uint32_t));
        con_off[c + 1] = 4 * (c + 1);
    }
    memset(s->x, 0, 2 * (size_t)s->nv * sizeof(double));
    sq_nlls_problem p = {s->nv, 2, s->x, nres, s->res_off, s->res_param, s->res_dim,
                         sq_smooth_residual_cb, ncon, con_off, con_param,
                         sq_smooth_feasible_cb, &s->ctx, smoothing ? s->pinned : NULL};
    sq_nlls_options no;
    sq_nlls_options_default(&no);
    int quick = smoothing && !s->stats->thorough;
    no.max_iterations = quick ? o->solver_iterations : o->untangle_solver_iterations;
    no.max_linear_iterations = quick ? o->linear_iterations : o->untangle_linear_iterations;
    no.function_tolerance = o->function_tolerance;
    no.gradient_tolerance = o->gradient_tolerance;
    no.parameter_tolerance = o->parameter_tolerance;
    no.num_threads = o->num_threads;
    no.initial_trust_region_radius = s->radius;
    sq_nlls_summary sum;
    sq_status st = sq_nlls_solve(&p, &no, &sum, err);
    free(con_off), free(con_param);
    if (st != SQ_OK) return -1;
    s->stats->solver_iterations += sum.iterations;
    s->stats->solver_rejected += sum.unsuccessful_steps;
    memcpy(s->stats->linear_solver, sum.linear_solver, sizeof sum.linear_solver);
    if (sum.successful_steps == 0) return 2;

    sq_quad_quality q_old;
    if (smoothing) sq_quad_quality_compute(s->pos, s->nq, s->quads, &q_old), set_old_shapes(s);
    double lambda = 1.0;
    for (int bt = 0; bt <= MAX_BACKTRACK; bt++, lambda *= 0.5) {
        for (uint32_t v = 0; v < s->nv; v++) {
            if (smoothing && s->pinned[v]) { /* held exactly where it is */
                memcpy(s->cand + 3 * (size_t)v, s->pos + 3 * (size_t)v, 3 * sizeof(double));
                memcpy(s->cand_bary + 3 * (size_t)v, s->vbary + 3 * (size_t)v, 3 * sizeof(double));
                s->cand_tri[v] = s->vtri[v];
                continue;
            }
            const double *b = s->ctx.base + 3 * (size_t)v, *f = s->frame + 9 * (size_t)v;
            double y[3];
            for (int k = 0; k < 3; k++)
                y[k] = b[k] + lambda * s->h[v] * (s->x[2 * v] * f[k] + s->x[2 * v + 1] * f[3 + k]);
            sq_cp_hit hit;
            sq_cp_tree_query(&s->tree, y, &hit);
            memcpy(s->cand + 3 * (size_t)v, hit.point, sizeof hit.point);
            s->cand_tri[v] = hit.tri;
            memcpy(s->cand_bary + 3 * (size_t)v, hit.bary, sizeof hit.bary);
        }
        if (smoothing) revert_worsened(s, &q_old);
        int ok = 1;
        for (uint32_t q = 0; q < s->nq && ok; q++) {
            if (s->threshold[q] == -INFINITY) continue;
            const uint32_t *f = s->quads + 4 * (size_t)q;
            double m = sq_quad_fold_margin(s->cand + 3 * (size_t)f[0], s->cand + 3 * (size_t)f[1],
                                           s->cand + 3 * (size_t)f[2], s->cand + 3 * (size_t)f[3]);
            if (!(m >= s->threshold[q])) ok = 0;
        }
        if (ok && smoothing) {
            sq_quad_quality q_new;
            sq_quad_quality_compute(s->cand, s->nq, s->quads, &q_new);
            ok = quality_not_worse(&q_new, &q_old);
        }
        if (ok) {
            memcpy(s->pos, s->cand, 3 * (size_t)s->nv * sizeof(double));
            memcpy(s->vtri, s->cand_tri, s->nv * sizeof(uint32_t));
            memcpy(s->vbary, s->cand_bary, 3 * (size_t)s->nv * sizeof(double));
            return 1;
        }
        s->stats->backtracks++;
    }
    s->stats->steps_rejected++;
    return 0;
}

/* Quick solves from the cautious trust region from here on; 0 where they
 * already are, or the solves are thorough. */
static int go_cautious(smoother *s)
{
    if (s->stats->thorough || s->radius <= s->opt->cautious_trust_region_radius) return 0;
    s->radius = s->opt->cautious_trust_region_radius;
    s->stats->cautious = 1;
    return 1;
}

static double max_dist_rel(const sq_cp_tree *t, uint32_t nv, const double *pos, double diag)
{
    double worst = 0.0;
    for (uint32_t v = 0; v < nv; v++) {
        sq_cp_hit hit;
        sq_cp_tree_query(t, pos + 3 * (size_t)v, &hit);
        if (hit.dist2 > worst) worst = hit.dist2;
    }
    return sqrt(worst) / diag;
}

sq_status sq_smooth_quads(uint32_t snv, const double *spos, uint32_t snt, const uint32_t *stri,
                          uint32_t nv, double *pos, uint32_t nq, const uint32_t *quads,
                          const sq_smooth_options *opt, sq_smooth_stats *stats, sq_error *err)
{
    sq_smooth_options defaults;
    if (!opt) sq_smooth_options_default(&defaults), opt = &defaults;
    memset(stats, 0, sizeof *stats);
    double t0 = sq_now();
    if (nq == 0 || nv == 0) return sq_error_set(err, SQ_ERR_EMPTY, "smooth: the quad mesh is empty");
    for (size_t i = 0; i < 4 * (size_t)nq; i++)
        if (quads[i] >= nv)
            return sq_error_set(err, SQ_ERR_INDEX, "smooth: quad %zu uses vertex %u of %u", i / 4, quads[i], nv);
    if (opt->iterations < 0 || opt->untangle_iterations < 0 || opt->solver_iterations < 1 ||
        opt->untangle_solver_iterations < 1 || opt->linear_iterations < 1 || opt->untangle_linear_iterations < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "smooth: iteration counts must be >= 0 (solver and linear >= 1)");

    smoother s;
    memset(&s, 0, sizeof s);
    double diag = 0.0;
    s.opt = opt, s.stats = stats, s.nv = nv, s.nq = nq, s.quads = quads, s.pos = pos;
    s.radius = opt->trust_region_radius;
    sq_status st = sq_cp_tree_build(snv, spos, snt, stri, &s.tree, err);
    if (st != SQ_OK) return st;
    double *tri_normal = malloc(3 * (size_t)snt * sizeof(double));
    double *base = malloc(3 * (size_t)nv * sizeof(double));
    s.vtri = malloc(nv * sizeof(uint32_t));
    s.frame = malloc(9 * (size_t)nv * sizeof(double));
    s.h = malloc(nv * sizeof(double));
    s.ref_normal = malloc(3 * (size_t)nq * sizeof(double));
    s.threshold = malloc(nq * sizeof(double));
    s.margin = malloc(nq * sizeof(double));
    s.x = malloc(2 * (size_t)nv * sizeof(double));
    s.cand = malloc(3 * (size_t)nv * sizeof(double));
    s.cand_tri = malloc(nv * sizeof(uint32_t));
    s.con_quad = malloc(nq * sizeof(uint32_t));
    s.res_off = malloc(((size_t)nq + nv + 1) * sizeof(uint32_t));
    s.res_param = malloc((4 * (size_t)nq + nv) * sizeof(uint32_t));
    s.res_dim = malloc(((size_t)nq + nv) * sizeof(uint32_t));
    s.pin_v = malloc(((size_t)snv + 1) * sizeof(uint32_t));
    s.pin_s = malloc(((size_t)snv + 1) * sizeof(uint32_t));
    s.pinned = calloc(nv, 1);
    s.vq_off = calloc((size_t)nv + 1, sizeof(uint32_t));
    s.vq = malloc(4 * (size_t)nq * sizeof(uint32_t));
    s.snv = snv, s.spos = spos;
    s.untangle = calloc(nq, 1);
    s.base_angle = malloc(4 * (size_t)nq * sizeof(double));
    s.old_sjac = malloc((size_t)nq * sizeof(double));
    s.old_ratio = malloc((size_t)nq * sizeof(double));
    s.dirty = malloc(nq);
    s.old_turned = malloc(nq);
    s.thin = malloc((size_t)snt + 1);
    s.unit_vnormal = malloc(3 * ((size_t)snv + 1) * sizeof(double));
    s.target = malloc(4 * (size_t)nq * sizeof(double));
    s.ideal_log = malloc(4 * (size_t)nq * sizeof(double));
    double *vnormal = calloc(3 * (size_t)snv, sizeof(double));
    s.vbary = malloc(3 * (size_t)nv * sizeof(double));
    s.cand_bary = malloc(3 * (size_t)nv * sizeof(double));
    if (!tri_normal || !base || !s.vtri || !s.frame || !s.h || !s.ref_normal || !s.threshold || !s.margin ||
        !s.x || !s.cand || !s.cand_tri || !s.con_quad || !s.res_off || !s.res_param || !s.res_dim ||
        !s.untangle || !s.base_angle || !s.pin_v || !s.pin_s || !s.pinned || !s.vq_off || !s.vq || !s.target || !s.ideal_log ||
        !vnormal || !s.vbary || !s.cand_bary || !s.old_sjac || !s.old_ratio || !s.dirty || !s.old_turned || !s.thin || !s.unit_vnormal) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "smooth: out of memory for %u vertices", nv);
        goto done;
    }
    s.tri_normal = tri_normal, s.vnormal = vnormal, s.stri = stri;
    for (size_t i = 0; i < 4 * (size_t)nq; i++) s.vq_off[quads[i] + 1]++;
    for (uint32_t v = 0; v < nv; v++) s.vq_off[v + 1] += s.vq_off[v];
    for (uint32_t q = 0; q < nq; q++) /* fill, then shift back */
        for (int k = 0; k < 4; k++) s.vq[s.vq_off[quads[4 * (size_t)q + k]]++] = q;
    for (uint32_t v = nv; v > 0; v--) s.vq_off[v] = s.vq_off[v - 1];
    s.vq_off[0] = 0;
    diag = sq_bbox_diagonal(snv, spos);
    for (uint32_t t = 0; t < snt; t++) {
        const double *a = spos + 3 * (size_t)stri[3 * (size_t)t], *b = spos + 3 * (size_t)stri[3 * (size_t)t + 1],
                     *c = spos + 3 * (size_t)stri[3 * (size_t)t + 2];
        double *n = tri_normal + 3 * (size_t)t;
        n[0] = 0, n[1] = 0, n[2] = 1; /* kept only without area: not in a validated surface */
        s.thin[t] = !sq_triangle_unit_normal(a, b, c, n);
    }
    sq_area_weighted_normals(snv, spos, snt, stri, vnormal);
    for (uint32_t v = 0; v < snv; v++) {
        const double *n = vnormal + 3 * (size_t)v;
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) s.unit_vnormal[3 * (size_t)v + k] = l > 0.0 ? n[k] / l : 0.0;
    }
    sq_smooth_targets(nv, nq, quads, s.target, s.ideal_log);
    s.ctx = (sq_smooth_ctx){nv, nq, quads, base, s.frame, s.h, s.ref_normal, s.untangle, s.threshold,
                            NULL, NULL, s.con_quad, opt->angle_weight, opt->length_weight,
                            opt->untangle_weight, opt->barrier_weight, 0.0, 0, NULL};

    sq_quad_quality_compute(pos, nq, quads, &stats->before);
    stats->dist_before_rel = max_dist_rel(&s.tree, nv, pos, diag);
    /* 1. project every vertex onto the surface */
    for (uint32_t v = 0; v < nv; v++) {
        sq_cp_hit hit;
        sq_cp_tree_query(&s.tree, pos + 3 * (size_t)v, &hit);
        memcpy(pos + 3 * (size_t)v, hit.point, sizeof hit.point);
        s.vtri[v] = hit.tri;
        memcpy(s.vbary + 3 * (size_t)v, hit.bary, sizeof hit.bary);
    }
    sq_quad_quality_compute(pos, nq, quads, &stats->projected);

    /* 2. untangle: quads with fold margin < target get the untangling terms and
     * no constraint; every other quad must keep its margin >= min(fold_margin, margin) */
    for (;;) {
        compute_margins(&s, pos);
        uint32_t ntarget = 0;
        for (uint32_t q = 0; q < nq; q++) {
            int target = !(s.margin[q] >= opt->untangle_target);
            s.untangle[q] = (unsigned char)target;
            ntarget += (uint32_t)target;
            s.threshold[q] = target ? -INFINITY : fmin(opt->fold_margin, 0.5 * s.margin[q]);
        }
        if (opt->progress) opt->progress(opt->progress_user, "untangle", stats->untangle_iterations, 0.0, ntarget);
        if (ntarget == 0) break;
        if (stats->untangle_iterations >= opt->untangle_iterations) {
            uint32_t first = 0;
            while (first < nq && !s.untangle[first]) first++;
            st = sq_error_set(err, SQ_ERR_SOLVER,
                              "smooth: untangling left %u quads folded or nearly folded (fold margin < %g) "
                              "after %d iterations; first: quad %u (0-based)",
                              ntarget, opt->untangle_target, stats->untangle_iterations, first);
            goto done;
        }
        memcpy(base, pos, 3 * (size_t)nv * sizeof(double));
        set_frames(&s);
        int r = outer_step(&s, 0, err);
        stats->untangle_iterations++;
        if (r < 0) {
            st = err ? err->code : SQ_ERR_SOLVER;
            goto done;
        }
    }
    sq_quad_quality_compute(pos, nq, quads, &stats->untangled);

    /* 3. smooth: the fold thresholds are fixed from here on; the angle and
     * length targets of docs/smooth.md "Targets" (untangling aims at 90
     * degrees and equal edges: measured faster on the elephant) */
    s.ctx.target = s.target, s.ctx.ideal_log = s.ideal_log;
    memset(s.untangle, 0, nq);
    compute_margins(&s, pos);
    for (uint32_t q = 0; q < nq; q++) s.threshold[q] = fmin(opt->fold_margin, 0.5 * s.margin[q]);
    memcpy(base, pos, 3 * (size_t)nv * sizeof(double));
    set_frames(&s); /* reference normals of the energy */
    stats->energy_before = sq_smooth_energy(&s.ctx, pos);
    double energy = stats->energy_before;
    snprintf(stats->stop_reason, sizeof stats->stop_reason, "iteration limit (%d)", opt->iterations);
    int retries = 0;
    for (int it = 0; it < opt->iterations; it++) {
        memcpy(base, pos, 3 * (size_t)nv * sizeof(double));
        set_frames(&s);
        /* fidelity pins from the second half of the iterations on (measured:
         * pinning from the start stalls the smoothing of crease-rich
         * models sooner; docs/smooth.md, "Fidelity"); a retry keeps the pins */
        if (opt->pin_threshold > 0.0 && stats->iterations >= opt->iterations / 2 && !retries) {
            int np = pin_far_surface_vertices(&s, err);
            if (np < 0) {
                st = err ? err->code : SQ_ERR_NOMEM;
                goto done;
            }
            stats->pinned += (uint32_t)np;
            if (np) energy = sq_smooth_energy(&s.ctx, pos);
        }
        int r = outer_step(&s, 1, err);
        if (r < 0) {
            st = err ? err->code : SQ_ERR_SOLVER;
            goto done;
        }
        if (r != 1 && go_cautious(&s)) {
            /* Levenberg-Marquardt's first steps overshot (its trust region
             * shrank through rejected steps until the solve ended): the
             * same step again, and every later one, from a small region */
            it--;
            continue;
        }
        if (r != 1 && !stats->thorough && stats->iterations == 0) {
            /* the short, inexact solves found no acceptable first step
             * (slivers: ill-conditioned normal equations): solve as
             * thoroughly as untangling does from here on */
            stats->thorough = 1;
            it--;
            continue;
        }
        if (r == 2) {
            snprintf(stats->stop_reason, sizeof stats->stop_reason, "converged: the solver found no better step");
            break;
        }
        if (r == 0) {
            /* retry from the same state with a damped step: each vertex's
             * offset gets a residual damping * (a, b), damping x4 per retry */
            if (retries == MAX_RETRY && !stats->thorough) {
                /* the quick, inexact solves lead nowhere from here (homer's
                 * quads from its cones at 5K after one iteration): go on
                 * with thorough solves from the same state */
                stats->thorough = 1;
                retries = 0;
                s.ctx.damping = 0.0;
                it--;
                continue;
            }
            if (retries == MAX_RETRY) {
                snprintf(stats->stop_reason, sizeof stats->stop_reason,
                         "step rejected: after re-projection it would fold a quad or worsen a quality measure, "
                         "even halved %d times and damped %d times", MAX_BACKTRACK, MAX_RETRY);
                break;
            }
            retries++, stats->retries++;
            s.ctx.damping = s.ctx.damping > 0.0 ? 4.0 * s.ctx.damping : DAMPING_START;
            it--; /* a retry does not count as an iteration */
            continue;
        }
        retries = 0;
        s.ctx.damping = s.ctx.damping > DAMPING_START ? 0.25 * s.ctx.damping : 0.0;
        stats->iterations++;
        double e = sq_smooth_energy(&s.ctx, pos);
        if (opt->progress) opt->progress(opt->progress_user, "smooth", stats->iterations, e, 0);
        const double tol = stats->thorough ? opt->thorough_stop_tolerance : opt->stop_tolerance;
        int small = energy - e <= tol * energy;
        energy = e;
        if (small && e > 0.5 * stats->energy_before && go_cautious(&s))
            continue; /* the quick steps stalled early: first from a small region */
        if (small && !stats->thorough && e > 0.5 * stats->energy_before) {
            /* the quick steps stalled before removing half the energy
             * (block's skewed quads): go on with thorough solves */
            stats->thorough = 1;
            continue;
        }
        if (small) {
            snprintf(stats->stop_reason, sizeof stats->stop_reason,
                     "converged: relative energy decrease below %g", tol);
            break;
        }
    }
    stats->energy_after = energy;
    st = SQ_OK;
done:
    sq_quad_quality_compute(pos, nq, quads, &stats->after);
    stats->dist_after_rel = diag > 0.0 ? max_dist_rel(&s.tree, nv, pos, diag) : 0.0;
    stats->fold_rejections = s.ctx.fold_rejections;
    stats->seconds = sq_now() - t0;
    sq_cp_tree_free(&s.tree);
    free(tri_normal), free(base), free(s.vtri), free(s.frame), free(s.h), free(s.ref_normal);
    free(s.threshold), free(s.margin), free(s.x), free(s.cand), free(s.cand_tri), free(s.con_quad);
    free(s.res_off), free(s.res_param), free(s.res_dim), free(s.untangle), free(s.pin_v), free(s.pin_s);
    free(s.pinned), free(s.vq_off), free(s.vq), free(s.base_angle), free(s.old_sjac), free(s.old_ratio), free(s.dirty);
    free(s.old_turned), free(s.thin), free(s.unit_vnormal);
    free(vnormal), free(s.vbary), free(s.cand_bary), free(s.target), free(s.ideal_log);
    return st;
}
