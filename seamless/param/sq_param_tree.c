/* seamquad: the cone tree in Q (seed 9.4; sq_param_steps.h): with guidance,
 * the surface's tree chosen first and Q's following it (guided_tree), or
 * the surface tree copied into Q triangulated (qtri_tree, SQ_TREE_QTRI). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_steps.h"
#include "sq_qtri.h"

/* Q's root cost for the surface root path `root`: on the side of Q standing
 * for root's side, the distance from the same fraction of it; `other`
 * elsewhere. */
static void fill_root_cost(const ctx *c, const sq_guide_root *root, double *cost, double other)
{
    const sq_metapolygon *Q = &c->D->quads;
    for (uint32_t v = 0; v < Q->nv; v++) cost[v] = other;
    if (root->side == SQ_NONE) return;
    uint32_t qs_side = q_side_of_surface(c, root->side);
    uint32_t ns = c->G.side_off[root->side + 1] - c->G.side_off[root->side];
    double t_want = (1.0 - (double)root->index / (double)ns) * (double)c->D->side_len[qs_side];
    uint32_t h = Q->v_he[c->D->corner_vert[qs_side]];
    for (uint32_t t = 0; t < c->D->side_len[qs_side]; t++, h = Q->he_next[h])
        if (t > 0) cost[Q->he_vert[h]] = fabs((double)t - t_want);
}

/* seed 9.4: the root path leaves from the cone nearest the circle */
static uint32_t root_step(const ctx *c)
{
    uint32_t rs = 0;
    double best = -1;
    for (uint32_t j = 0; j < c->D->ncones; j++) {
        double r = hypot(c->step_xy[2 * j], c->step_xy[2 * j + 1]);
        if (r > best) best = r, rs = j;
    }
    return rs;
}

/* Seed 9.4 (guided, genus >= 1): the cone tree chosen on the surface in
 * radial order (the steps' order) and replicated in Q. SQ_ERR_SOLVER when
 * either side is blocked: the caller then takes Q's own shortest tree. */
sq_status sq_param_guided_tree(ctx *c)
{
    const sq_metapolygon *Q = &c->D->quads;
    uint32_t n = c->D->ncones;
    size_t n1 = (size_t)n + 1;
    uint32_t *qv = malloc(n1 * sizeof *qv), *att = malloc(n1 * sizeof *att);
    uint32_t *sv = malloc(n1 * sizeof *sv), *qa = malloc(n1 * sizeof *qa), *qs = malloc(n1 * sizeof *qs);
    double *qf = malloc(n1 * sizeof *qf), *rcost = NULL;
    double *frac = malloc(n1 * sizeof *frac);
    uint8_t *side = malloc(n1);
    c->q_branch = malloc(((size_t)Q->nv + 1) * sizeof *c->q_branch);
    c->s_tree_next = malloc(((size_t)c->m->nv + 1) * sizeof *c->s_tree_next);
    sq_status st = SQ_OK;
    if (!qv || !att || !sv || !qa || !qs || !qf || !frac || !side || !c->q_branch || !c->s_tree_next)
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    if (st == SQ_OK) st = sq_param_step_q_vertices(c, qv);
    uint32_t rs = root_step(c);
    for (uint32_t j = 0; qs && qf && j < n1; j++) qs[j] = SQ_NONE, qf[j] = 0;
    /* the surface tree first, Q's following it near the same places */
    if (st == SQ_OK)
        st = sq_guide_surface_tree(c->m, &c->G, n, c->step_vertex, att, frac, side, sv, c->s_tree_next, c->err);
    /* the surface root path as the seed draws it (to the nearest side),
     * not attached: it tells Q where its root should be */
    sq_guide_root root = {rs, SQ_NONE, SQ_NONE, SQ_NONE};
    if (st == SQ_OK)
        st = sq_guide_surface_root(c->m, &c->G, n, c->step_vertex, c->s_tree_next, NULL, &root, c->err);
    if (st == SQ_OK && root.side != SQ_NONE) {
        rcost = malloc(((size_t)Q->nv + 1) * sizeof *rcost);
        if (!rcost) st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        else fill_root_cost(c, &root, rcost, 1e6);
    }
    if (st == SQ_OK)
        st = sq_cone_tree_guided(Q, n, qv, att, frac, side, rs, rcost, qa, qs, qf, c->T, c->err);
    if (st == SQ_OK) c->root_step = rs;
    if (st == SQ_OK) {
        /* a regular branch vertex of Q's tree stands for the surface
         * vertex where the same path joined the surface tree, or, where
         * that is a cone, for the vertex at the same fraction of the
         * surface path that Q's branch vertex lies on */
        for (uint32_t v = 0; v < Q->nv; v++) c->q_branch[v] = SQ_NONE;
        for (uint32_t j = 1; j < n; j++) {
            if (qa[j] == SQ_NONE || Q->v_nface[qa[j]] != 4) continue;
            if (sv[j] != SQ_NONE && c->S_valence[sv[j]] == 4) {
                c->q_branch[qa[j]] = sv[j];
                continue;
            }
            uint32_t p = qs[j];
            if (p == SQ_NONE || p >= n) continue;
            /* surface path p: from its cone along the tree to sv[p] */
            uint32_t len = 0;
            for (uint32_t x = c->step_vertex[p]; x != SQ_NONE && x != sv[p] && len <= c->m->nv; x = c->s_tree_next[x]) len++;
            uint32_t want = (uint32_t)lround(qf[j] * (double)len);
            if (want < 1 || want >= len) continue;
            uint32_t x = c->step_vertex[p];
            for (uint32_t i = 0; i < want; i++) x = c->s_tree_next[x];
            if (c->S_valence[x] == 4) c->q_branch[qa[j]] = x;
        }
    } else {
        free(c->q_branch);
        c->q_branch = NULL;
        free(c->s_tree_next);
        c->s_tree_next = NULL;
    }
    free(qv);
    free(att);
    free(sv);
    free(qa);
    free(qs);
    free(qf);
    free(rcost);
    free(frac);
    free(side);
    return st;
}

/* After Omega (guided tree): the surface tree's root path to the surface
 * side standing for the side of Q that Q's root lies on, attached to the
 * surface tree; sq_param_cut_surface puts the surface root where it ends. */
sq_status sq_param_guided_root(ctx *c)
{
    const sq_omega *O = c->O;
    if (O->root_pos == 0 || O->root_side >= c->k) return SQ_OK; /* a corner root: the genus-0 slit */
    sq_guide_root root = {c->root_step, surface_side_of_q(c, O->root_side), SQ_NONE, SQ_NONE};
    sq_status st = sq_guide_surface_root(c->m, &c->G, c->D->ncones, c->step_vertex, c->s_tree_next,
                                         c->s_tree_next, &root, c->err);
    if (st == SQ_OK && root.vertex != SQ_NONE) c->root_surface = root.vertex;
    return st;
}

/* Tree qtri: SQ_ERR_SOLVER naming the first cone the surface tree could
 * not join (att from sq_guide_surface_tree), SQ_OK if it joined them all */
static sq_status qtri_all_joined(ctx *c, const uint32_t *att, uint32_t n)
{
    for (uint32_t j = 1; j < n; j++)
        if (att[j] == SQ_NONE)
            return c->walled = 1, sq_error_set(c->err, SQ_ERR_SOLVER,
                                "tree qtri: the surface tree cannot join the cone at vertex %u (walled in by the cut)",
                                c->step_vertex[j]);
    return SQ_OK;
}

/* SQ_TREE_QTRI (seed 9.4 as the seed does it): the surface tree and its
 * root path, copied into Q triangulated with room made by edge splits
 * along the paths (sq_qtri_replicate: the same plane tree, always), and
 * Omega laid out from that (sq_qtri_omega). The attempt fails
 * (SQ_ERR_SOLVER) where the surface tree leaves a cone unjoined. */
sq_status sq_param_qtri_tree(ctx *c)
{
    const sq_metapolygon *Q = &c->D->quads;
    const uint32_t n = c->D->ncones;
    const size_t n1 = (size_t)n + 1;
    uint32_t *qv = malloc(n1 * sizeof *qv), *att = malloc(n1 * sizeof *att), *sv = malloc(n1 * sizeof *sv);
    double *frac = malloc(n1 * sizeof *frac), *xy = malloc((2 * (size_t)Q->nv + 2) * sizeof *xy);
    uint8_t *side = malloc(n1);
    uint32_t *qfrom = NULL, *qto = NULL, *node = NULL;
    sq_qtri T;
    sq_qtri_init(&T);
    c->qtri = 1;
    c->s_tree_next = malloc(((size_t)c->m->nv + 1) * sizeof *c->s_tree_next);
    sq_status st = SQ_OK;
    if (!qv || !att || !sv || !frac || !xy || !side || !c->s_tree_next)
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    if (st == SQ_OK) st = sq_param_step_q_vertices(c, qv);
    if (st == SQ_OK)
        st = sq_guide_surface_tree(c->m, &c->G, n, c->step_vertex, att, frac, side, sv, c->s_tree_next, c->err);
    if (st == SQ_OK) st = qtri_all_joined(c, att, n);
    const uint32_t rs = root_step(c);
    sq_guide_root root = {rs, SQ_NONE, SQ_NONE, SQ_NONE};
    if (st == SQ_OK)
        st = sq_guide_surface_root(c->m, &c->G, n, c->step_vertex, c->s_tree_next, c->s_tree_next, &root, c->err);
    if (st == SQ_OK && root.vertex == SQ_NONE)
        st = sq_error_set(c->err, SQ_ERR_SOLVER, "tree qtri: no root path from the cone at vertex %u",
                          c->step_vertex[rs]);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st == SQ_OK) st = sq_guide_metapolygon_layout(Q, c->step_xy, n, qv, xy, c->err);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st == SQ_OK) st = sq_qtri_build(c->D, xy, &T, c->err);
    /* the memory limit: Omega, its coarsening and the overlay's domain
     * mesh grow with Q triangulated (sq_param_options.max_memory) */
    T.max_faces = sq_param_max_memory(c->opt) / SQ_BYTES_PER_QTRI_FACE;
    if (st == SQ_OK)
        st = sq_qtri_replicate(&T, c->D, c->m, &c->G, n, c->step_vertex, qv, c->s_tree_next, sv, &root,
                               q_side_of_surface(c, root.side), c->err);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st == SQ_OK) st = sq_qtri_omega(&T, c->D, c->O, &c->qt_nseg, &qfrom, &qto, c->err);
    /* a coarse triangulation of Omega serves the overlay as well (seed 10)
     * with fewer crossings */
    uint32_t removed = 0;
    if (st == SQ_OK) st = sq_omega_coarsen(c->O, &removed, c->err);
    /* the segments' ends as surface vertices */
    if (st == SQ_OK) {
        node = malloc((size_t)T.S.nv * sizeof *node);
        c->qt_from = malloc(((size_t)c->qt_nseg + 1) * sizeof *c->qt_from);
        c->qt_to = malloc(((size_t)c->qt_nseg + 1) * sizeof *c->qt_to);
        if (!node || !c->qt_from || !c->qt_to) st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    if (st == SQ_OK) {
        for (uint32_t v = 0; v < T.S.nv; v++) node[v] = SQ_NONE;
        for (uint32_t j = 0; j < n; j++) {
            node[T.cone[j]] = c->step_vertex[j];
            if (j && T.att[j] != SQ_NONE) node[T.att[j]] = sv[j];
        }
        node[T.root] = root.vertex;
        for (uint32_t s = 0; s < c->qt_nseg && st == SQ_OK; s++) {
            c->qt_from[s] = node[qfrom[s]], c->qt_to[s] = node[qto[s]];
            if (c->qt_from[s] == SQ_NONE || c->qt_to[s] == SQ_NONE)
                st = sq_error_set(c->err, SQ_ERR_INTERNAL, "tree qtri: segment %u ends at no surface node", s);
        }
    }
    if (st == SQ_OK) c->root_surface = root.vertex, c->root_step = rs;
    c->qt_verts = T.S.nv, c->qt_steiner = (uint32_t)T.splits, c->qt_edges = 0;
    for (uint32_t h = 0; h < T.S.nh; h++) c->qt_edges += T.S.kind[h] && T.S.label[h] == SQ_NONE && h < T.S.twin[h];
    sq_qtri_free(&T);
    free(qv), free(att), free(sv), free(frac), free(xy), free(side), free(qfrom), free(qto), free(node);
    return st;
}

/* Tree qtri, genus >= 2 (whose cone order the domain keeps): whether the
 * surface tree joins every cone in the guided order, decided before the
 * domain is built (about 0.45 s on femur, whose every cut-graph seed walls
 * a cone in; sq_param_qtri_tree would find it only after). SQ_ERR_SOLVER if not. */
sq_status sq_param_qtri_joinable(ctx *c, uint32_t n)
{
    uint32_t *att = malloc(((size_t)n + 1) * sizeof *att);
    double *frac = malloc(((size_t)n + 1) * sizeof *frac);
    uint8_t *side = malloc((size_t)n + 1);
    sq_status st = !att || !frac || !side ? sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory")
                   : sq_guide_surface_tree(c->m, &c->G, n, c->step_vertex, att, frac, side, NULL, NULL, c->err);
    if (st == SQ_OK) st = qtri_all_joined(c, att, n);
    free(att), free(frac), free(side);
    return st;
}
