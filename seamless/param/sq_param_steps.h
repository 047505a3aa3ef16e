/* seamquad: the working state of one attempt of sq_param_build (the ctx
 * below) and the steps that share it, one file per step (not a public
 * API; sq_param_internal.h holds what the output's checks and pictures
 * share):
 *   sq_param_domain.c      steps 1-3: cut graph, domain Q (seed 9.2's
 *                          Algorithm 1 and corner alignment), Omega
 *   sq_param_tree.c        the cone tree in Q (seed 9.4, guided or qtri)
 *   sq_param_surface_cut.c step 4: the cut graph and the cone tree on the
 *                          surface
 *   sq_param_boundary.c    step 5: the boundary map
 *   sq_param_interior.c    steps 6-7c: chords, Tutte's map of the cells,
 *                          flips repaired, cells halved
 *   sq_param_overlay.c     step 7': the interior map by overlay
 *   sq_param_assemble.c    the output P from the surface and its UVs
 *   sq_param.c             one attempt: the steps in order (build_once)
 * (seed 7 "Compatible Cutting", seed 8 "Bijective Parametrization",
 * seamless-notes 5; docs/param.md). */
#ifndef SQ_PARAM_STEPS_H
#define SQ_PARAM_STEPS_H

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_guide.h"
#include "sq_omega.h"
#include "sq_omega_cells.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_tsurf.h"

/* ---- working state ---------------------------------------------------- */

/* One attempt's state: built by build_once (sq_param.c), filled by the
 * steps in order, freed at the attempt's end (the domain, Omega and tree
 * handed over to the output). */
typedef struct ctx {
    const sq_mesh *m;         /* the mesh parametrized: the input, or the     */
                              /* input with wall splits (build_walled)       */
    sq_cut_graph *given_G;    /* the cut graph to use (its he_cut on m, m     */
                              /* refined where it walled a cone in; taken    */
                              /* over), or NULL                              */
    int walled;               /* tree qtri: the surface tree left a cone out */
    const sq_param_options *opt; /* never NULL (sq_param_build fills defaults) */
    sq_error *err;            /* where the steps report                      */
    sq_tsurf S;          /* the editable surface: m, cut and refined       */
    sq_cut_graph G;      /* the cut graph on m (seed 7, 9.1)               */
    sq_pattern pcw;      /* the cut disk's word read clockwise            */
    uint32_t k, r;       /* sides; Q side i = clockwise side (i + r) % k   */
    sq_domain *D;        /* the domain Q                                   */
    sq_cone_tree *T;     /* Q's cone tree (unused with qtri)               */
    sq_omega *O;         /* the flat domain Omega                          */
    sq_omega_cells C;    /* Omega's cells, the chords' rectangles (6-7c)   */
    uint32_t *o2m;       /* O->cut.nh: M halfedge naming the same sector   */
    uint32_t *sec_uv;    /* 3 S.cap_f: UV index of the sector named by h   */
    uint32_t cap_sec;    /* sec_uv's room (sec_reserve)                    */
    double *uv;          /* 2 cap_uv: the UV points, nuv of them used      */
    uint32_t nuv, cap_uv;
    int dyadic;          /* seam UVs are multiples of 2^-dyadic             */
    int keep_flips;      /* debugging: return a map with flips (tests)     */
    int guided;          /* seed 9.2 guidance (sq_param_options.guidance)  */
    const int32_t *S_valence; /* the input's valences (m->nv)              */
    double *step_xy;       /* disk positions of the steps' cones          */
    double *surf_corner_angle; /* k: the cut graph's corners on the circle */
    sq_guide_glue glue;    /* Algorithm 1's chooser: c = step_xy, chosen */
                           /* = its glue edge per step (for rebuilds)     */
    uint32_t *step_vertex; /* genus >= 1, guided: the surface cone of each */
                           /* metapolygon step (seed 9.2, Algorithm 1)     */
    uint32_t *s_tree_next; /* m->nv: the surface tree (sq_guide_surface_tree) */
    uint32_t root_surface; /* the surface tree's root vertex on the cut    */
    uint32_t root_step;    /* the step whose cone (nearest the circle) Q's */
                           /* root path starts from (SQ_NONE: not guided)  */
    uint32_t *q_branch;  /* Q->nv: seed 9.4 guided tree: the surface vertex */
                         /* where the surface tree branched for a regular  */
                         /* branch vertex of Q's tree; SQ_NONE elsewhere,  */
                         /* NULL when the tree is not guided               */
    uint32_t *q_target;  /* Q->nv: the surface cone matched to a cone of Q */
                         /* (seed 9.2 guidance), SQ_NONE elsewhere; NULL   */
                         /* when unguided                                  */
    const _Atomic int *cancel;  /* another attempt passed: stop (may be NULL)  */
    uint64_t gate;              /* domain variants: the overlay's expected    */
                                /* crossings above which this domain is given */
                                /* up for the next variant (0: none)          */
    uint32_t *h_uv;             /* S.nh: corner_uv of every halfedge once the */
                                /* interior map of a round is done; else NULL */
    uint32_t *face_limit;       /* O->cut.nf or NULL: cell size limits per quad */
                                /* of Omega (step 7c, refinement rounds)       */
    int qtri;                   /* SQ_TREE_QTRI: Omega from Q triangulated     */
    uint32_t qt_nseg;           /* its tree segments (O's labels k + 2s, +1)   */
    uint32_t *qt_from, *qt_to;  /* qt_nseg: the surface nodes each joins, the  */
                                /* one nearer the root first                   */
    uint32_t qt_verts, qt_steiner; /* Q triangulated: vertices, Steiner ones   */
    uint32_t qt_edges;          /* its tree's edges                            */
} ctx;

/* Reports a stage to the caller's progress callback, if any. */
static inline void progress(ctx *c, const char *stage, double f)
{
    if (c->opt && c->opt->progress) c->opt->progress(c->opt->progress_ctx, stage, f);
}

/* sec_uv grown to S.cap_h entries (the new ones SQ_NONE): after every step
 * that may add halfedges. 0; -1: out of memory. */
static inline int sec_reserve(ctx *c)
{
    uint32_t need = c->S.cap_h;
    if (need <= c->cap_sec) return 0;
    uint32_t *p = realloc(c->sec_uv, (size_t)need * sizeof *p);
    if (!p) return -1;
    for (uint32_t i = c->cap_sec; i < need; i++) p[i] = SQ_NONE;
    c->sec_uv = p;
    c->cap_sec = need;
    return 0;
}

/* A new UV point (u, v); its index, SQ_NONE when out of memory. */
static inline uint32_t uv_add(ctx *c, double u, double v)
{
    if (c->nuv == c->cap_uv) {
        uint32_t cap = c->cap_uv ? 2 * c->cap_uv : 1024;
        double *p = realloc(c->uv, 2 * (size_t)cap * sizeof *p);
        if (!p) return SQ_NONE;
        c->uv = p;
        c->cap_uv = cap;
    }
    c->uv[2 * c->nuv] = u;
    c->uv[2 * c->nuv + 1] = v;
    return c->nuv++;
}

/* The UV index of the corner of face(h) at its origin: the vertex's own
 * (v_uv, once the interior map has run; may be NULL before) off the cut,
 * its sector's on the cut; SQ_NONE where there is none yet. */
static inline uint32_t corner_uv(const ctx *c, const uint32_t *v_uv, uint32_t h)
{
    if (c->h_uv) return c->h_uv[h];
    const sq_tsurf *S = &c->S;
    uint32_t v = S->vert[h];
    if (!S->v_ncut[v]) return v_uv ? v_uv[v] : SQ_NONE;
    uint32_t sec = sq_tsurf_sector_of(S, h);
    return sec == SQ_NONE ? SQ_NONE : c->sec_uv[sec];
}

/* Q's sides and corners against the cut graph's (sq_cut_graph_domain_offset:
 * Q is read clockwise, the cut graph counterclockwise, shifted by r): the
 * surface side standing for Q side qs, its inverse, and the surface corner
 * standing for Q corner i. */
static inline uint32_t surface_side_of_q(const ctx *c, uint32_t qs) { return c->k - 1 - (qs + c->r) % c->k; }
static inline uint32_t q_side_of_surface(const ctx *c, uint32_t s) { return (2 * c->k - 1 - s - c->r % c->k) % c->k; }
static inline uint32_t surface_corner(uint32_t k, uint32_t r, uint32_t i) { return (k - (i + r) % k) % k; }
static inline uint32_t surface_corner_of_q(const ctx *c, uint32_t i) { return surface_corner(c->k, c->r, i); }

/* Steiner vertex budget: beyond it the cut paths are refining the surface
 * without end (regions too narrow for the domain's combinatorics) */
static inline uint64_t steiner_budget(const ctx *c) { return sq_param_steiner_budget(c->opt, c->S.nv_input); }

/* the distortion statistics are left to sq_param_build, which measures
 * them after the simplification (of a map 2 to 13 times smaller) */
static inline int distortion_later(const ctx *c) { return c->opt->simplify != SQ_SIMPLIFY_OFF && !c->opt->allow_flips; }

/* Whether another attempt has passed and this one should stop. */
static inline int cancelled(const ctx *c) { return c->cancel && atomic_load(c->cancel); }

/* Between the long steps: SQ_ERR_SOLVER once the attempt is cancelled. */
static inline sq_status stop_if_cancelled(const ctx *c)
{
    return cancelled(c) ? sq_error_set(c->err, SQ_ERR_SOLVER, "cancelled: an earlier attempt passed") : SQ_OK;
}

/* Also true once the attempt is cancelled: every long loop checks it. */
static inline int over_budget(const ctx *c)
{
    return (uint64_t)(c->S.nv - c->S.nv_input) > steiner_budget(c) || cancelled(c);
}

/* SQ_ERR_SOLVER: the Steiner budget exceeded at `stage`. */
static inline sq_status budget_error(ctx *c, const char *stage)
{
    return sq_error_set(c->err, SQ_ERR_SOLVER,
                        "%s: more than %llu Steiner vertices were needed (input %u vertices); the "
                        "surface cut is too far from the domain's shape (try other --seed values, "
                        "or a larger --max-steiner)",
                        stage, (unsigned long long)steiner_budget(c), c->S.nv_input);
}

/* x rounded to the seams' dyadic grid (multiples of 2^-dyadic). */
static inline double snap(const ctx *c, double x) { return ldexp(nearbyint(ldexp(x, c->dyadic)), -c->dyadic); }

/* y = R^rot x + t (R: +90 degrees), exact for dyadic x */
static inline void transition(const sq_omega *O, uint32_t l, const double x[2], double y[2])
{
    double a = x[0], b = x[1];
    for (uint32_t i = 0; i < O->label_rot[l]; i++) {
        double t = a;
        a = -b, b = t;
    }
    y[0] = a + ldexp((double)O->label_t[2 * l], -O->xy_shift);
    y[1] = b + ldexp((double)O->label_t[2 * l + 1], -O->xy_shift);
}

/* segments of the cone tree (Q's, or the triangulated Q's) */
static inline uint32_t tree_nseg(const ctx *c) { return c->qtri ? c->qt_nseg : c->T->nseg; }

/* ---- steps 1-3: the domain Q and Omega (sq_param_domain.c) ------------- */

/* Steps 1-3: the cut graph c->G, the domain Q c->D (guided: Algorithm 1,
 * corners aligned), its cone tree and Omega c->O; st_out (may be NULL):
 * sizes and times. */
sq_status sq_param_build_domain(ctx *c, const int32_t *valence, sq_param_stats *st_out);

/* After Algorithm 1: qv[j] (D->ncones) the vertex of Q at the centre of
 * the j-th irregular metapolygon face, the cone of step j. */
sq_status sq_param_step_q_vertices(ctx *c, uint32_t *qv);
/* c->D freed and replaced by D. */
void sq_param_domain_replace(ctx *c, sq_domain *D);

/* ---- the cone tree in Q (sq_param_tree.c) ------------------------------- */

/* Seed 9.4, guided: the surface tree first, Q's tree c->T following it;
 * c->q_branch, c->s_tree_next.
 * SQ_ERR_SOLVER where either side is blocked. */
sq_status sq_param_guided_tree(ctx *c);
/* After Omega (guided tree): the surface tree's root path to the side
 * standing for Q's root side; c->root_surface where it ends. */
sq_status sq_param_guided_root(ctx *c);
/* SQ_TREE_QTRI: the surface tree and its root path copied into Q
 * triangulated, Omega laid out from that (c->O, c->qt_*). SQ_ERR_SOLVER
 * where the surface tree leaves a cone unjoined (c->walled). */
sq_status sq_param_qtri_tree(ctx *c);
/* SQ_TREE_QTRI, genus >= 2: SQ_ERR_SOLVER unless the surface tree joins
 * all n cones in the guided order (decided before the domain is built). */
sq_status sq_param_qtri_joinable(ctx *c, uint32_t n);

/* ---- step 4: the cut on the surface (sq_param_surface_cut.c) ---------- */

/* The cut graph's sides on the surface c->S labelled with Omega's labels
 * (hmap: m's halfedges in S); *root_he: where the cone tree starts. */
sq_status sq_param_cut_surface(ctx *c, const uint32_t *hmap, uint32_t *root_he);
/* Seed 9.2: c->q_target, the surface cone each cone of Q stands for (the
 * steps' cones after Algorithm 1, else matched in the disk layouts). */
sq_status sq_param_guide_targets(ctx *c);
/* Seed 9.4: Q's cone tree replicated on the surface from root_he, cut and
 * labelled as Omega's tree segments. */
sq_status sq_param_replicate_tree(ctx *c, uint32_t root_he);
/* SQ_TREE_QTRI: the surface tree's paths themselves cut and labelled as
 * Omega's tree segments (no routing). */
sq_status sq_param_qtri_surface_tree(ctx *c);

/* The halfedges of the boundary run from halfedge h to vertex end_v
 * (after splits) into *out (the caller frees it), *n of them. */
sq_status sq_param_walk_run(ctx *c, uint32_t h, uint32_t end_v, uint32_t **out, uint32_t *n);

/* ---- step 5: boundary map (sq_param_boundary.c) ----------------------- */

/* Step 5: the surface's cut boundary split at Omega's boundary grid points
 * and given UVs (c->sec_uv, c->uv; the seams' UVs exact transitions of
 * each other, on the dyadic grid c->dyadic); c->o2m for Omega's boundary
 * halfedges. */
sq_status sq_param_boundary_map(ctx *c);

/* Omega's boundary as face halfedges counterclockwise into oseq (room for
 * W->nbnd): their count, SQ_NONE when the loop does not close. */
uint32_t sq_param_omega_boundary(const sq_metapolygon *W, uint32_t *oseq);
/* The polyline he[0..n) split at the arc-length fractions j / N (frac[j]
 * where frac is not NULL), existing vertices taken where close; matched
 * (N + 1): the vertex of every fraction. */
sq_status sq_param_split_polyline(ctx *c, const uint32_t *he, uint32_t n, uint32_t N, const double *frac,
                                  uint32_t *matched);
/* UVs of the polyline he[0..n) whose vertices matched[0..N] sit at the
 * grid points g (times gs), the others between by arc length, snapped;
 * uvv (n + 1): the UV index of every polyline vertex. */
sq_status sq_param_polyline_uv(ctx *c, const uint32_t *he, uint32_t n, const uint32_t *matched,
                               const int64_t *g, double gs, uint32_t N, uint32_t *uvv);

/* ---- steps 6-7c: the interior map by cells (sq_param_interior.c) ------- */

/* The state of an attempt before its cells (step 6): every refinement
 * round starts again from it, so the cut graph, domain, tree and boundary
 * map are built once per attempt. */
typedef struct sq_param_before_cells {
    sq_tsurf S;
    uint32_t *sec_uv, cap_sec;
    double *uv;
    uint32_t nuv;
    uint32_t *o2m;
} sq_param_before_cells;

/* The state saved (sq_param_before_cells_save), freed, and restored into
 * c (sec_uv and uv only grow, so they have room). */
sq_status sq_param_before_cells_save(const ctx *c, sq_param_before_cells *b);
void sq_param_before_cells_free(sq_param_before_cells *b);
sq_status sq_param_before_cells_restore(ctx *c, const sq_param_before_cells *b);
/* Steps 6-7c with up to opt->refine rounds, each from `saved`: cells,
 * chords, Tutte, flips repaired, bad cells halved. *v_uv: the UV index of
 * every surface vertex (the caller frees it); *t_round, *t3: when the last
 * round and its Tutte map began. */
sq_status sq_param_cells_map(ctx *c, const sq_param_before_cells *saved, uint32_t **v_uv, sq_param_stats *stats,
                             double *t_round, double *t3);

/* ---- step 7': the interior map by overlay (sq_param_overlay.c) ---------- */

/* Step 7': the cut surface on the disk once, then Omega triangulated in
 * its unit squares, and where that fails (over the budget, mostly) and
 * `rectangles` is 1, in the rectangles of its chords. Fills P and stats;
 * every triangle checked. */
sq_status sq_param_overlay_map(ctx *c, const int32_t *valence, int rectangles, sq_param *P,
                               sq_param_stats *stats);
/* SQ_INTERIOR_AUTO after the cells passed: the overlay on the same cut,
 * tree and boundary map (saved) replaces *out where it passes too; its
 * failure keeps the cells' map (only out of memory is an error). */
sq_status sq_param_overlay_after_cells(ctx *c, const sq_param_before_cells *saved, const int32_t *valence,
                                       sq_param *out, sq_param_stats *stats);

/* ---- output (sq_param_assemble.c) ------------------------------------- */

/* P from the surface c->S and its UVs (corner_uv with v_uv): positions,
 * triangles, UVs compacted to the used ones, seams, cut halfedges, input
 * faces and valences; stats' sizes (and distortion unless
 * distortion_later). SQ_ERR_SOLVER where a UV triangle is not positively
 * oriented (exact predicate), unless c->keep_flips. */
sq_status sq_param_assemble(ctx *c, const uint32_t *v_uv, const int32_t *valence, sq_param *P,
                            sq_param_stats *stats);

#endif /* SQ_PARAM_STEPS_H */
