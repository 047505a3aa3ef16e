/* seamquad: seamless parametrization of a closed surface (sq_param.h;
 * seed 7 "Compatible Cutting", seed 8 "Bijective Parametrization",
 * seamless-notes 5; docs/param.md): one attempt, its steps in order
 * (build_once; the steps in the files sq_param_steps.h lists), with the
 * walled cones' edge splits (build_walled) and the domain variants
 * (sq_param_build_once). */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_param_steps.h"

void sq_param_options_default(sq_param_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->seed = 1;
    opt->refine = SQ_PARAM_REFINE;
}

void sq_param_init(sq_param *P) { memset(P, 0, sizeof *P); }

void sq_param_free(sq_param *P)
{
    free(P->pos);
    free(P->tri);
    free(P->tri_uv);
    free(P->tri_in);
    free(P->uv);
    free(P->he_seam);
    free(P->he_cut);
    free(P->valence);
    free(P->he_twin);
    if (P->domain) sq_domain_free(P->domain);
    if (P->tree) sq_cone_tree_free(P->tree);
    if (P->omega) sq_omega_free(P->omega);
    free(P->domain);
    free(P->tree);
    free(P->omega);
    sq_param_init(P);
}

/* Steiner vertices allowed (sq_param_options.max_steiner) */
uint64_t sq_param_steiner_budget(const sq_param_options *opt, uint32_t nv_input)
{
    return opt->max_steiner ? opt->max_steiner : 9u * (uint64_t)nv_input + 100000u;
}


/* The inputs of one build (build_once, build_walled). */
typedef struct build_in {
    const sq_mesh *m;
    const int32_t *valence;        /* m->nv: a cone's valence, 4 elsewhere  */
    const sq_param_options *opt;   /* never NULL; stats are never NULL here */
    const _Atomic int *cancel;     /* may be NULL (sq_param_build_once)     */
    uint32_t variant;              /* Algorithm 1's tie order (sq_guide_glue) */
    uint64_t gate;                 /* the overlay's expected crossings above */
                                   /* which the domain is given up (0: none) */
} build_in;

/* The attempt's state for `in` (given_G: as ctx.given_G). ctx_free frees
 * it, also after a failure here. */
static sq_status ctx_init(ctx *c, const build_in *in, sq_cut_graph *given_G, sq_error *err)
{
    memset(c, 0, sizeof *c);
    c->m = in->m, c->opt = in->opt, c->err = err, c->cancel = in->cancel, c->given_G = given_G;
    c->glue.variant = in->variant, c->gate = in->gate;
    c->keep_flips = in->opt->allow_flips;
    c->root_step = c->root_surface = SQ_NONE;
    c->S_valence = in->valence;
    sq_tsurf_init(&c->S);
    sq_cut_graph_init(&c->G);
    sq_pattern_init(&c->pcw);
    sq_omega_cells_init(&c->C);
    c->D = calloc(1, sizeof *c->D);
    c->T = calloc(1, sizeof *c->T);
    c->O = calloc(1, sizeof *c->O);
    if (!c->D || !c->T || !c->O) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    sq_domain_init(c->D);
    sq_cone_tree_init(c->T);
    sq_omega_init(c->O);
    return SQ_OK;
}

static void ctx_free(ctx *c)
{
    sq_tsurf_free(&c->S);
    sq_cut_graph_free(&c->G);
    sq_pattern_free(&c->pcw);
    sq_omega_cells_free(&c->C);
    if (c->D) sq_domain_free(c->D);
    if (c->T) sq_cone_tree_free(c->T);
    if (c->O) sq_omega_free(c->O);
    free(c->D);
    free(c->T);
    free(c->O);
    free(c->o2m);
    free(c->q_target);
    free(c->q_branch);
    free(c->s_tree_next);
    free(c->step_vertex);
    free(c->glue.chosen);
    sq_guide_glue_free(&c->glue);
    free(c->step_xy);
    free(c->surf_corner_angle);
    free(c->sec_uv);
    free(c->h_uv);
    free(c->uv);
    free(c->face_limit);
    free(c->qt_from);
    free(c->qt_to);
}

/* Step 4: the surface c->S made from m (hmap: m->nh, m's halfedges in S),
 * its cut graph labelled as Omega's boundary, and the cone tree on it. */
static sq_status surface_step(ctx *c, const build_in *in, uint32_t *hmap)
{
    sq_error *err = c->err;
    sq_status st = sq_tsurf_from_mesh(in->m, in->valence, &c->S, hmap, err);
    if (st) return st;
    if (sec_reserve(c)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    uint32_t root_he = SQ_NONE;
    st = sq_param_cut_surface(c, hmap, &root_he);
    if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    if (st == SQ_OK && c->qtri) {
        st = sq_param_qtri_surface_tree(c);
    } else {
        if (st == SQ_OK && c->guided) st = sq_param_guide_targets(c);
        if (st == SQ_OK) st = sq_param_replicate_tree(c, root_he);
    }
    return st;
}

/* Step 5: c->o2m, then the boundary map. */
static sq_status boundary_step(ctx *c)
{
    c->o2m = malloc((size_t)c->O->cut.nh * sizeof *c->o2m);
    if (!c->o2m || sec_reserve(c)) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t h = 0; h < c->O->cut.nh; h++) c->o2m[h] = SQ_NONE;
    sq_status st = sq_param_boundary_map(c);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    return st;
}

/* When the parts of the interior map began (sq_now), for stats' times. */
typedef struct interior_times {
    double round;   /* the last round of the cells (step 6)           */
    double tutte;   /* its Tutte map (step 7; step 7' alone: the overlay) */
    double check;   /* the check and assembly                          */
    double overlay; /* how long the overlay after the cells took (0: none) */
} interior_times;

/* Steps 6-8: the interior map into out. Step 7' alone (every triangle
 * checked) with SQ_INTERIOR_OVERLAY(_CHORDS) or Omega of triangles
 * (qtri: its faces alone); else the cells with up to opt->refine rounds
 * of step 7c, checked and assembled, then with SQ_INTERIOR_AUTO the
 * overlay on the same cuts, whose map replaces theirs where it passes. */
static sq_status interior_step(ctx *c, const int32_t *valence, sq_param *out, sq_param_stats *stats,
                               interior_times *t)
{
    const sq_param_options *opt = c->opt;
    sq_status st = SQ_OK;
    if (opt->interior == SQ_INTERIOR_OVERLAY || c->qtri) {
        /* step 7' instead of 6-7c (Omega of triangles: its faces alone) */
        progress(c, "disk maps", 0.55);
        stats->overlay = 1;
        /* checks every triangle too */
        st = sq_param_overlay_map(c, valence, !c->qtri, out, stats);
        if (st == SQ_OK) t->check = sq_now();
        return st;
    }
    sq_param_before_cells saved;
    memset(&saved, 0, sizeof saved);
    uint32_t *v_uv = NULL;
    int then_overlay = opt->interior == SQ_INTERIOR_AUTO && !c->keep_flips;
    if (opt->refine || then_overlay) st = sq_param_before_cells_save(c, &saved);
    if (st == SQ_OK) st = sq_param_cells_map(c, &saved, &v_uv, stats, &t->round, &t->tutte);
    if (st == SQ_OK) {
        t->check = sq_now();
        progress(c, "check", 0.9);
        st = sq_param_assemble(c, v_uv, valence, out, stats);
    }
    if (st == SQ_OK && then_overlay) {
        double t_ov = sq_now();
        st = sq_param_overlay_after_cells(c, &saved, valence, out, stats);
        if (st == SQ_OK) t->overlay = sq_now() - t_ov;
    }
    sq_param_before_cells_free(&saved);
    free(v_uv);
    return st;
}

/* One attempt with the options as given (opt and stats are never NULL here;
 * the cone set has passed its checks), with up to opt->refine rounds of
 * step 7c: steps 1-3 (sq_param_build_domain), 4, 5 and the interior map.
 * given_G: the cut graph to use (taken over), or NULL; walled_G (may be
 * NULL): receives the cut graph where the qtri tree was walled in. */
static sq_status build_once(const build_in *in, sq_cut_graph *given_G, sq_cut_graph *walled_G, sq_param *out,
                            sq_param_stats *stats, sq_error *err)
{
    double t_start = sq_now();
    memset(stats, 0, sizeof *stats);
    stats->verts_in = in->m->nv, stats->faces_in = in->m->nf;
    ctx c;
    sq_status st = ctx_init(&c, in, given_G, err);
    uint32_t *hmap = malloc((size_t)in->m->nh * sizeof *hmap);
    if (st == SQ_OK && !hmap) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    if (st == SQ_OK) st = sq_param_build_domain(&c, in->valence, stats);
    if (st) goto done;
    double t0 = sq_now();
    progress(&c, "cone tree", 0.3);
    st = surface_step(&c, in, hmap);
    if (st) goto done;
    stats->tree_qtri = c.qtri, stats->qtri_verts = c.qt_verts, stats->qtri_steiner = c.qt_steiner;
    double t1 = sq_now();
    progress(&c, "boundary map", 0.45);
    st = boundary_step(&c);
    if (st) goto done;
    double t2 = sq_now();
    interior_times t = {t2, t2, t2, 0};
    st = interior_step(&c, in->valence, out, stats, &t);
    if (st) goto done;
    out->domain = c.D, out->omega = c.O;
    c.D = NULL, c.O = NULL;
    if (!c.qtri) out->tree = c.T, c.T = NULL; /* (no quad tree: Omega of triangles) */
    double t5 = sq_now();
    stats->t_tree = t1 - t0;
    stats->t_boundary = t2 - t1;
    stats->t_cells = t.tutte - t.round;
    stats->t_tutte = t.check - t.tutte;
    stats->t_check = t5 - t.check - t.overlay;
    stats->t_overlay = t.overlay;
    if (stats->overlay && (in->opt->interior != SQ_INTERIOR_AUTO || c.qtri)) /* step 7' alone: no Tutte of cells */
        stats->t_overlay = stats->t_tutte, stats->t_tutte = 0;
    stats->t_total = t5 - t_start;
    progress(&c, "map built", 0.9);
done:
    if (st) sq_param_free(out);
    if (st == SQ_ERR_SOLVER && c.walled && walled_G) { /* the caller refines around it */
        *walled_G = c.G;
        sq_cut_graph_init(&c.G);
    }
    ctx_free(&c);
    free(hmap);
    return st;
}

/* Tree qtri, genus >= 2: where the surface tree cannot join a cone walled
 * in by the cut graph (its vertices and the cones block the tree's
 * paths), the same cut graph on the mesh with a midpoint on every other
 * edge between two blocked vertices (sq_param_split_walls): the midpoints
 * are free, so the tree passes between them. The map of that mesh is
 * one of the input's: the midpoints lie on its edges and count as
 * Steiner vertices, its faces name their input faces. */
static sq_status build_walled(const build_in *in, sq_param *out, sq_param_stats *stats, sq_error *err)
{
    const sq_mesh *m = in->m;
    const int32_t *valence = in->valence;
    const sq_param_options *opt = in->opt;
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    const int refine = opt->tree == SQ_TREE_QTRI && sq_mesh_genus(m) >= 2;
    sq_status st = build_once(in, NULL, refine ? &G : NULL, out, stats, err);
    if (st != SQ_ERR_SOLVER || !G.he_cut) {
        sq_cut_graph_free(&G);
        return st;
    }
    sq_mesh m2;
    int32_t *val2 = NULL;
    uint32_t *fparent = NULL, nsplit = 0;
    uint8_t *cut2 = NULL;
    sq_error e2;
    sq_error_clear(&e2);
    sq_status s2 = sq_param_split_walls(m, valence, G.he_cut, &m2, &val2, &fparent, &cut2, &nsplit, &e2);
    if (s2 == SQ_ERR_NOMEM) st = s2, *err = e2;
    if (s2 || !nsplit) { /* nothing to split, or the split mesh is invalid: the first failure */
        sq_cut_graph_free(&G);
        return st;
    }
    /* the same cut (its edges were not split; length, genus and choices
     * kept), on m2's halfedges */
    free(G.he_cut);
    G.he_cut = cut2;
    build_in in2 = *in;
    in2.m = &m2, in2.valence = val2;
    st = build_once(&in2, &G, NULL, out, stats, err);
    sq_cut_graph_free(&G);
    stats->verts_in = m->nv, stats->faces_in = m->nf, stats->wall_splits = nsplit;
    if (st == SQ_OK) {
        /* back to the input: its vertices first, the midpoints added */
        out->nv_input = m->nv;
        for (uint32_t f = 0; f < out->nf; f++) out->tri_in[f] = fparent[out->tri_in[f]];
    } else if (err && !(in->cancel && atomic_load(in->cancel))) {
        char msg[2 * sizeof err->msg];
        snprintf(msg, sizeof msg, "with %u edges split around cones walled in by the cut: %s", nsplit, err->msg);
        sq_error_set(err, st, "%s", msg);
    }
    sq_mesh_free(&m2);
    free(val2), free(fparent);
    return st;
}

/* Domain variants (tree qtri, genus >= 1): Algorithm 1's glue choices
 * meet exact ties (a cone beyond a convex vertex of the growing
 * metapolygon is as near to both its edges), and which edge takes the
 * cone changes the whole domain after it: the overlay's crossings on
 * mpz/elk went from 0.66 to 3.1 million over 10 ways of breaking the ties
 * (docs/param.md). So where the overlay's sample expects more
 * than SQ_VARIANT_PER_FACE crossings per input face, the attempt gives
 * that domain up (about 1/16 of the walk's time) and builds the next
 * variant (sq_guide_glue.variant: another tie order), up to
 * SQ_VARIANTS; if none is under it, the one expecting the fewest is built
 * again without the gate. The same cut graph every time: this is one
 * attempt of sq_param_build. */
sq_status sq_param_build_once(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                              const _Atomic int *cancel, sq_param *out, sq_param_stats *stats, sq_error *err)
{
    const uint32_t nvar = opt->variants ? opt->variants : SQ_VARIANTS;
    build_in in = {m, valence, opt, cancel, 0, 0};
    if (opt->tree != SQ_TREE_QTRI || sq_mesh_genus(m) < 1 || opt->max_crossings || nvar < 2)
        return build_walled(&in, out, stats, err);
    const uint64_t gate = (opt->variant_gate ? opt->variant_gate : SQ_VARIANT_PER_FACE) * (uint64_t)m->nf;
    uint64_t best = UINT64_MAX;
    uint32_t best_v = 0, v = 0;
    sq_status st = SQ_OK;
    for (; v < nvar; v++) {
        if (v && opt->progress) {
            char msg[160];
            snprintf(msg, sizeof msg, "domain variant %u (the overlay expected %llu crossings)", v + 1,
                     (unsigned long long)stats->crossings_expected);
            opt->progress(opt->progress_ctx, msg, 0.1);
        }
        in.variant = v, in.gate = gate;
        st = build_walled(&in, out, stats, err);
        if (st != SQ_ERR_SOLVER || !stats->gated || (cancel && atomic_load(cancel))) break;
        if (stats->crossings_expected < best) best = stats->crossings_expected, best_v = v;
    }
    if (v == nvar) { /* none under the gate */
        if (opt->progress) opt->progress(opt->progress_ctx, "domain variant with the fewest crossings expected", 0.1);
        in.variant = best_v, in.gate = 0;
        st = build_walled(&in, out, stats, err);
        v = best_v;
    }
    stats->domain_variant = v;
    return st;
}
