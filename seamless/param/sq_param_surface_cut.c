/* seamquad: step 4 of an attempt (sq_param_steps.h): the cut graph and the
 * cone tree on the surface, labelled as Omega's boundary (seed 7, 9.4):
 * the cut graph's sides, the tree's segments routed from Q's tree (or,
 * with SQ_TREE_QTRI, the surface tree itself), each cone of Q matched to
 * the surface cone it stands for (seed 9.2). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_steps.h"

/* ---- step 4: the cut graph and the cone tree on the surface ----------- */

/* Halfedges of a polyline run from start halfedge h to vertex end_v along
 * the boundary (after splits). */
sq_status sq_param_walk_run(ctx *c, uint32_t h, uint32_t end_v, uint32_t **out, uint32_t *n)
{
    uint32_t cap = 16, cnt = 0;
    uint32_t *a = malloc(cap * sizeof *a);
    if (!a) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    for (;;) {
        if (cnt == cap) {
            cap *= 2;
            uint32_t *p = realloc(a, cap * sizeof *p);
            if (!p) return free(a), sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
            a = p;
        }
        a[cnt++] = h;
        if (sq_ts_head(&c->S, h) == end_v) break;
        if (cnt > c->S.nh) return free(a), sq_error_set(c->err, SQ_ERR_INTERNAL, "run walk does not end");
        h = sq_tsurf_next_boundary(&c->S, h);
    }
    *out = a;
    *n = cnt;
    return SQ_OK;
}

/* Labels the surface cut graph's sides with Omega's labels (Q side i of the
 * clockwise reading; the root splits side root_side) and returns the root. */
sq_status sq_param_cut_surface(ctx *c, const uint32_t *hmap, uint32_t *root_he)
{
    sq_tsurf *S = &c->S;
    const sq_omega *O = c->O;
    sq_cut_graph *G = &c->G;
    uint32_t k = c->k;
    for (uint32_t s = 0; s < k; s++) {
        uint32_t i = q_side_of_surface(c, s); /* clockwise side k-1-s = Q side i + r */
        for (uint32_t e = G->side_off[s]; e < G->side_off[s + 1]; e++) {
            uint32_t h = hmap[G->side_he[e]];
            if (!S->kind[h]) sq_tsurf_cut_edge(S, h, SQ_TS_SEAM, i, O->label_partner[i]);
            else if (S->label[h] != i)
                return sq_error_set(c->err, SQ_ERR_INTERNAL, "surface side %u: label %u, expected %u", s,
                                    S->label[h], i);
        }
    }
    /* consistency of the walk with the cut graph's word */
    for (uint32_t e = 0; e + 1 < G->side_off[k]; e++)
        if (sq_tsurf_next_boundary(S, hmap[G->side_he[e]]) != hmap[G->side_he[e + 1]])
            return sq_error_set(c->err, SQ_ERR_INTERNAL, "cut graph walk disagrees at side edge %u", e);
    /* the root: a vertex inside surface side s_r (Q side root_side) */
    uint32_t qs = O->root_side;
    uint32_t s_r = surface_side_of_q(c, qs);
    uint32_t a = G->side_off[s_r], n = G->side_off[s_r + 1] - a;
    if (O->root_pos == 0) {
        /* the root is Q's corner qs = the start of counterclockwise side
         * (k - (qs + r)) mod k; no side is split (the genus-0 slit) */
        uint32_t sc = surface_corner_of_q(c, qs);
        if (O->nlabels != k + 2 * tree_nseg(c))
            return sq_error_set(c->err, SQ_ERR_INTERNAL, "Omega splits a side at a corner root");
        *root_he = hmap[G->side_he[G->side_off[sc]]];
        return SQ_OK;
    }
    if (n == 1) { /* split the side's only edge */
        if (sq_tsurf_split_edge(S, hmap[G->side_he[a]], 0.5) == SQ_NONE)
            return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    /* walk the side again (splits change it) */
    uint32_t *side = NULL, ns = 0;
    sq_status st = sq_param_walk_run(c, hmap[G->side_he[a]], G->corner_vertex[(s_r + 1) % k], &side, &ns);
    if (st) return st;
    /* clockwise fraction root_pos / side_len from Q corner qs = counter-
     * clockwise fraction 1 - that from the side's start */
    double frac = 1.0 - (double)O->root_pos / (double)c->D->side_len[qs];
    uint32_t ir = (uint32_t)lround(frac * ns);
    if (ir < 1) ir = 1;
    if (ir > ns - 1) ir = ns - 1;
    uint32_t at = SQ_NONE;
    for (uint32_t e = 1; c->root_surface != SQ_NONE && e < ns; e++)
        if (S->vert[side[e]] == c->root_surface) at = e;
    if (at != SQ_NONE) {
        ir = at; /* the surface tree's root path ends here */
    } else if (c->root_step != SQ_NONE) {
        /* seed 9.4 guided tree: any place on the side splits it validly;
         * the one nearest the cone Q's root path leaves from */
        double best = INFINITY;
        for (uint32_t e = 1; e < ns; e++) {
            double d = sq_ts_dist(S, S->vert[side[e]], c->step_vertex[c->root_step]);
            if (d < best) best = d, ir = e;
        }
    }
    uint32_t lr = k + 2 * tree_nseg(c);
    if (O->nlabels != lr + 2 || O->label_partner[lr] != lr + 1) {
        free(side);
        return sq_error_set(c->err, SQ_ERR_INTERNAL, "Omega has no root-split labels");
    }
    for (uint32_t e = 0; e < ir; e++) S->label[side[e]] = lr, S->label[S->twin[side[e]]] = lr + 1;
    *root_he = side[ir];
    free(side);
    return SQ_OK;
}

/* ---- seed 9.2: the surface cone each cone of Q stands for ------------- */

/* Genus 0 (and a torus without cones) with SQ_GUIDE_ON: the cut surface
 * and Q are laid out in the unit disk with corresponding corners at the
 * same angles and Q's cones matched to the surface's by position (sq_guide.h); Q corner i is
 * the start of counterclockwise surface side (k - (i + r) % k) % k, as in
 * sq_param_cut_surface. Where the cones do not pair up (some on the cut or on Q's
 * boundary), c->q_target is dropped and the tree is unguided. */
static sq_status targets_by_matching(ctx *c)
{
    const sq_mesh *m = c->m;
    const sq_metapolygon *Q = &c->D->quads;
    const uint32_t k = c->k;
    sq_status st = SQ_OK;
    double *v_xy = malloc(2 * (size_t)m->nv * sizeof *v_xy);
    double *q_xy = malloc(2 * (size_t)Q->nv * sizeof *q_xy);
    double *sang = malloc((size_t)k * sizeof *sang), *qang = malloc((size_t)k * sizeof *qang);
    uint32_t nq = 0, ns = 0;
    uint32_t *qv = malloc(((size_t)Q->nv + 1) * sizeof *qv), *sv = malloc(((size_t)m->nv + 1) * sizeof *sv);
    double *a = NULL, *b = NULL;
    int32_t *av = NULL, *bv = NULL;
    uint32_t *match = NULL;
    uint8_t *qbnd = calloc((size_t)Q->nv + 1, 1);
    if (!v_xy || !q_xy || !sang || !qang || !qv || !sv || !qbnd) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    st = sq_guide_surface_disk(m, &c->G, v_xy, sang, c->err);
    if (st) goto done;
    for (uint32_t i = 0; i < k; i++) qang[i] = sang[surface_corner_of_q(c, i)];
    st = sq_guide_domain_disk(c->D, qang, q_xy, c->err);
    if (st) goto done;
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) qbnd[Q->he_vert[h]] = 1;
    for (uint32_t v = 0; v < Q->nv; v++)
        if (!qbnd[v] && Q->v_nface[v] != 4) qv[nq++] = v;
    for (uint32_t v = 0; v < m->nv; v++)
        if (c->S.valence[v] != 4 && !isnan(v_xy[2 * v])) sv[ns++] = v;
    if (nq != ns) goto unguided;
    a = malloc((2 * (size_t)nq + 2) * sizeof *a), b = malloc((2 * (size_t)nq + 2) * sizeof *b);
    av = malloc(((size_t)nq + 1) * sizeof *av), bv = malloc(((size_t)nq + 1) * sizeof *bv);
    match = malloc(((size_t)nq + 1) * sizeof *match);
    if (!a || !b || !av || !bv || !match) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t i = 0; i < nq; i++) {
        a[2 * i] = q_xy[2 * qv[i]], a[2 * i + 1] = q_xy[2 * qv[i] + 1], av[i] = (int32_t)Q->v_nface[qv[i]];
        b[2 * i] = v_xy[2 * sv[i]], b[2 * i + 1] = v_xy[2 * sv[i] + 1], bv[i] = c->S.valence[sv[i]];
    }
    if (sq_guide_match(nq, a, av, b, bv, match, NULL) != SQ_OK) goto unguided;
    for (uint32_t i = 0; i < nq; i++) c->q_target[qv[i]] = sv[match[i]];
    goto done;
unguided:
    free(c->q_target);
    c->q_target = NULL;
done:
    free(v_xy);
    free(q_xy);
    free(sang);
    free(qang);
    free(qv);
    free(sv);
    free(qbnd);
    free(a);
    free(b);
    free(av);
    free(bv);
    free(match);
    return st;
}

/* c->q_target (Q->nv): the surface cone each cone of Q stands for. After
 * Algorithm 1 (genus >= 1) that is the cone of the step that made it;
 * otherwise the nearest one in the disk layouts (targets_by_matching). */
sq_status sq_param_guide_targets(ctx *c)
{
    const sq_metapolygon *Q = &c->D->quads;
    c->q_target = malloc(((size_t)Q->nv + 1) * sizeof *c->q_target);
    if (!c->q_target) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t v = 0; v < Q->nv; v++) c->q_target[v] = SQ_NONE;
    if (!c->step_vertex) return targets_by_matching(c);
    uint32_t *qv = malloc(((size_t)c->D->ncones + 1) * sizeof *qv);
    if (!qv) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    sq_status st = sq_param_step_q_vertices(c, qv);
    for (uint32_t j = 0; st == SQ_OK && j < c->D->ncones; j++) c->q_target[qv[j]] = c->step_vertex[j];
    free(qv);
    return st;
}

typedef struct node_item {
    uint32_t ti;     /* tree vertex index */
    uint32_t sector; /* M sector for the next child */
    uint32_t pos;    /* next position in the rotation list */
} node_item;

/* Seed 9.4: the surface tree's path from the origin of `sector` to
 * `target` (both on the tree chosen by sq_guide_surface_tree), taken as
 * the route when it still exists unchanged: every edge uncut and not
 * split, every inner vertex off the cut and regular, the target off the
 * cut, and its first edge inside `sector`. Returns 1 (path set), 0 (not
 * usable), -1 (out of memory). */
static int given_path(ctx *c, uint32_t sector, uint32_t target, uint32_t **path, uint32_t *npath)
{
    sq_tsurf *S = &c->S;
    const uint32_t *nx = c->s_tree_next;
    uint32_t a = S->vert[sector], first = c->step_vertex[0], nv = c->m->nv;
    if (a >= nv || target >= nv || S->v_ncut[target]) return 0;
    if (nx[a] == SQ_NONE && a != first) return 0; /* not on the surface tree */
    if (nx[target] == SQ_NONE && target != first) return 0;
    /* a's ancestors, then target's up to the first common one */
    uint32_t na = 0, nb = 0, lca = SQ_NONE;
    for (uint32_t x = a; x != SQ_NONE && na <= nv; x = nx[x]) na++;
    uint32_t *up = malloc(((size_t)na + 1) * sizeof *up);
    if (!up) return -1;
    na = 0;
    for (uint32_t x = a; x != SQ_NONE && na <= nv; x = nx[x]) up[na++] = x;
    uint32_t *dn = NULL;
    for (uint32_t x = target; x != SQ_NONE && nb <= nv; x = nx[x], nb++) {
        for (uint32_t i = 0; i < na; i++)
            if (up[i] == x) {
                lca = i;
                break;
            }
        if (lca != SQ_NONE) break;
    }
    int r = 0;
    if (lca == SQ_NONE) goto out;
    /* vertices: up[0 .. lca], then target's chain below the lca reversed */
    uint32_t nd = nb; /* target's chain: nb vertices before the lca */
    dn = malloc(((size_t)nd + 1) * sizeof *dn);
    if (!dn) {
        r = -1;
        goto out;
    }
    {
        uint32_t i = 0;
        for (uint32_t x = target; i < nd; x = nx[x]) dn[i++] = x;
    }
    uint32_t len = lca + nd; /* edges */
    if (len == 0) goto out;
    uint32_t *p = realloc(*path, ((size_t)len + 1) * sizeof *p);
    if (!p) {
        r = -1;
        goto out;
    }
    *path = p;
    for (uint32_t e = 0; e < len; e++) {
        uint32_t x = e < lca ? up[e] : e == lca ? up[lca] : dn[nd - (e - lca)];
        uint32_t y = e + 1 <= lca ? up[e + 1] : dn[nd - 1 - (e - lca)];
        if (e > 0 && (S->v_ncut[x] || S->valence[x] != 4)) goto out;
        uint32_t h0 = S->v_he[x], h = h0, found = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == y) found = h;
            h = sq_ts_ccw(S, h);
        } while (h != h0 && found == SQ_NONE);
        if (found == SQ_NONE || S->kind[found]) goto out;
        p[e] = found;
    }
    if (sq_tsurf_sector_of(S, p[0]) != sector) goto out;
    *npath = len;
    r = 1;
out:
    free(up);
    free(dn);
    return r;
}

/* Seed 9.4: Q's cone tree c->T replicated on the surface from root_he,
 * segment by segment, depth first: each segment a path along edges (the
 * surface tree's own where guided and still usable, else routed) or,
 * where cones or cuts block that, through faces with Steiner vertices, to
 * its cone (the matched one, c->q_target, where guided) or a free vertex;
 * cut and labelled k + 2s, k + 2s + 1. */
sq_status sq_param_replicate_tree(ctx *c, uint32_t root_he)
{
    sq_tsurf *S = &c->S;
    const sq_cone_tree *T = c->T;
    const sq_metapolygon *Q = &c->D->quads;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    uint32_t *ti_of = malloc((size_t)Q->nv * sizeof *ti_of);
    uint32_t *seg_of = malloc((size_t)Q->nh * sizeof *seg_of);
    uint8_t *free_cone = malloc(S->nv_input); /* cones are input vertices */
    uint8_t *only = calloc(S->nv_input, 1);    /* the guided target alone   */
    node_item *stack = malloc(((size_t)T->nverts + 1) * sizeof *stack);
    uint32_t *path = NULL, npath = 0;
    if (!ti_of || !seg_of || !free_cone || !only || !stack) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < Q->nv; v++) ti_of[v] = SQ_NONE;
    for (uint32_t i = 0; i < T->nverts; i++) ti_of[T->vert[i]] = i;
    for (uint32_t h = 0; h < Q->nh; h++) seg_of[h] = SQ_NONE;
    for (uint32_t s = 0; s < T->nseg; s++) seg_of[T->seg_he[T->seg_off[s]]] = s;
    for (uint32_t v = 0; v < S->nv_input; v++) free_cone[v] = S->valence[v] != 4;
    /* length scale: surface length per quad edge */
    double area = 0;
    for (uint32_t f = 0; f < S->nf; f++) {
        uint32_t h = S->f_he[f];
        const double *p = S->pos + 3 * S->vert[h], *q = S->pos + 3 * S->vert[S->next[h]],
                     *r = S->pos + 3 * S->vert[S->next[S->next[h]]];
        double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
        area += 0.5 * sqrt(x * x + y * y + z * z);
    }
    double scale = sqrt(area / (double)Q->nf);
    uint32_t nst = 0, done_seg = 0;
    stack[nst++] = (node_item){0, root_he, 0};
    while (nst) {
        node_item *it = &stack[nst - 1];
        uint32_t ti = it->ti;
        uint32_t r0 = T->rot_off[ti], r1 = T->rot_off[ti + 1];
        uint32_t p = it->pos + r0;
        if (ti != 0 && p == r0) p++; /* skip the parent edge */
        if (p >= r1) {
            nst--;
            continue;
        }
        it->pos = p + 1 - r0;
        uint32_t qh = T->rot_he[p];
        uint32_t s = seg_of[qh];
        if (s == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tree halfedge %u starts no segment", qh);
            goto done;
        }
        uint32_t last = T->seg_he[T->seg_off[s + 1] - 1];
        uint32_t qend = Q->he_vert[Q->he_next[last]];
        uint32_t te = ti_of[qend];
        /* first a path along existing edges through vertices off the cut;
         * where cones or cuts block it, a path through faces with Steiner
         * vertices on the crossed edges (seed 9.4, [SAPH04]) */
        int is_cone_node = (T->node[te] & SQ_TREE_CONE) != 0;
        double tlen = scale * (double)(T->seg_off[s + 1] - T->seg_off[s]);
        npath = 0;
        /* guided: only the matched cone is a target (seed 9.2) */
        uint32_t tgt = is_cone_node && c->q_target ? c->q_target[qend] : SQ_NONE;
        if (tgt != SQ_NONE && !free_cone[tgt]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cone at vertex %u is matched twice", tgt);
            goto done;
        }
        /* seed 9.4 guided tree: a regular branch vertex goes where the
         * surface tree branched, while that vertex is still free */
        uint32_t btgt = !is_cone_node && c->q_branch ? c->q_branch[qend] : SQ_NONE;
        if (btgt != SQ_NONE && S->v_ncut[btgt]) btgt = SQ_NONE;
        /* the surface tree's own path, where it leaves in this sector */
        uint32_t want = tgt != SQ_NONE ? tgt : btgt;
        if (want != SQ_NONE && c->s_tree_next) {
            int r = given_path(c, it->sector, want, &path, &npath);
            if (r < 0) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                goto done;
            }
        }
        const uint8_t *mask = free_cone;
        if (tgt != SQ_NONE) only[tgt] = 1, mask = only;
        if (npath == 0 && sq_tsurf_open_sector(S, it->sector) < 0) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
        if (npath == 0 && btgt != SQ_NONE) {
            if (sq_tsurf_open_vertex(S, btgt) < 0) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                goto done;
            }
            /* a regular input vertex as the route's one target */
            only[btgt] = 1;
            st = sq_tsurf_route(S, it->sector, SQ_ROUTE_CONE, 4, only, tlen, SQ_NONE, &path, &npath, err);
            only[btgt] = 0;
            if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            if (st == SQ_ERR_INTERNAL) st = SQ_OK, npath = 0; /* unreachable: a free branch vertex */
            if (st) goto done;
        }
        if (npath == 0 && is_cone_node)
            for (uint32_t v = 0; v < S->nv_input; v++)
                if (mask[v] && S->valence[v] == (int32_t)Q->v_nface[qend] && sq_tsurf_open_vertex(S, v) < 0) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    goto done;
                }
        if (npath == 0)
            st = sq_tsurf_route(S, it->sector, is_cone_node ? SQ_ROUTE_CONE : SQ_ROUTE_FREE,
                                is_cone_node ? (int32_t)Q->v_nface[qend] : 4, mask, tlen, SQ_NONE,
                                &path, &npath, err);
        if (st == SQ_ERR_INTERNAL) {
            npath = 0;
            st = sq_tsurf_route_faces(S, it->sector, is_cone_node ? SQ_ROUTE_CONE : SQ_ROUTE_FREE,
                                      is_cone_node ? (int32_t)Q->v_nface[qend] : 4, mask, tlen,
                                      SQ_NONE, &path, &npath, err);
        }
        if (tgt != SQ_NONE) only[tgt] = 0;
        if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        if (st) goto done;
        if (over_budget(c)) {
            st = budget_error(c, "cone tree");
            goto done;
        }
        uint32_t lab = c->k + 2 * s;
        for (uint32_t e = 0; e < npath; e++) sq_tsurf_cut_edge(S, path[e], SQ_TS_SEAM, lab, lab + 1);
        uint32_t vend = sq_ts_head(S, path[npath - 1]);
        if (vend < S->nv_input) free_cone[vend] = 0;
        it->sector = path[0];
        done_seg++;
        stack[nst++] = (node_item){te, S->twin[path[npath - 1]], 0};
        progress(c, "cone tree", 0.3 + 0.1 * done_seg / (double)T->nseg);
    }
    if (done_seg != T->nseg) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "replicated %u of %u tree segments", done_seg, T->nseg);
        goto done;
    }
    for (uint32_t v = 0; v < S->nv_input; v++)
        if (free_cone[v]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cone at vertex %u was not reached by the tree", v);
            goto done;
        }
done:
    free(ti_of);
    free(seg_of);
    free(free_cone);
    free(only);
    free(stack);
    free(path);
    return st;
}

/* SQ_TREE_QTRI: the surface tree itself is the cut, no routing: each
 * segment of Omega's tree is the surface tree's path between the two
 * surface nodes it joins (the same plane tree), labelled as Omega labels
 * it: k + 2s on the halfedges walked away from the root, k + 2s + 1 on
 * their twins. */
sq_status sq_param_qtri_surface_tree(ctx *c)
{
    sq_tsurf *S = &c->S;
    const sq_mesh *m = c->m;
    const uint32_t *nx = c->s_tree_next, nv = m->nv;
    uint32_t *par = malloc((size_t)nv * sizeof *par), *queue = malloc((size_t)nv * sizeof *queue);
    uint32_t *list = malloc(((size_t)nv + 1) * sizeof *list);
    sq_status st = SQ_OK;
    if (!par || !queue || !list || c->root_surface == SQ_NONE) {
        st = par && queue && list ? sq_error_set(c->err, SQ_ERR_INTERNAL, "tree qtri: no surface root")
                                  : sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < nv; v++) par[v] = SQ_NONE;
    uint32_t nq = 0;
    par[c->root_surface] = c->root_surface, queue[nq++] = c->root_surface;
    for (uint32_t i = 0; i < nq; i++) {
        uint32_t x = queue[i], h0 = m->v_he[x], h = h0;
        do {
            uint32_t w = m->he_vert[m->he_next[h]];
            if ((nx[x] == w || nx[w] == x) && par[w] == SQ_NONE) par[w] = x, queue[nq++] = w;
            h = m->he_twin[m->he_next[m->he_next[h]]];
        } while (h != h0);
    }
    for (uint32_t s = 0; s < c->qt_nseg && st == SQ_OK; s++) {
        uint32_t a = c->qt_from[s], cnt = 0;
        for (uint32_t y = c->qt_to[s]; y != a; y = par[y]) {
            if (y == SQ_NONE || par[y] == y || cnt >= nv) {
                st = sq_error_set(c->err, SQ_ERR_INTERNAL, "tree qtri: surface segment %u does not reach its start", s);
                break;
            }
            list[cnt++] = y;
        }
        if (st) break;
        list[cnt++] = a;
        for (uint32_t i = cnt - 1; i > 0 && st == SQ_OK; i--) {
            uint32_t x = list[i], y = list[i - 1], found = sq_ts_find(S, x, y);
            if (found == SQ_NONE || S->kind[found]) {
                st = sq_error_set(c->err, SQ_ERR_INTERNAL, "tree qtri: surface edge %u-%u of segment %u is %s", x,
                                  y, s, found == SQ_NONE ? "missing" : "cut already");
                break;
            }
            sq_tsurf_cut_edge(S, found, SQ_TS_SEAM, c->k + 2 * s, c->k + 2 * s + 1);
        }
    }
    if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
done:
    free(par), free(queue), free(list);
    return st;
}
