/* seamquad: steps 1-3 of an attempt (sq_param_steps.h): the cut graph, the
 * domain Q for its side pattern (with guidance, seed 9.2: Algorithm 1's
 * cone order and Q's corners aligned with the surface's), its cone tree
 * and Omega. */
#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_cone_connection.h"
#include "sq_param_steps.h"

/* ---- step 1-3: cut graph, domain, Omega ------------------------------ */

/* Whether the domain is built by Algorithm 1 (seed 9.2) and the cone tree
 * may come from the surface (seed 9.4): genus >= 2 unless guidance is
 * off; genus 1 only with SQ_GUIDE_ON (and cones: see build_domain). */
int sq_param_uses_algorithm1(int guidance, int genus)
{
    return genus >= 2 ? guidance != SQ_GUIDE_OFF : genus == 1 && guidance == SQ_GUIDE_ON;
}

/* Genus 1 (seed 6.2 with seed 9.2): the cones of the meta-2-gon T, which
 * lies on Q's boundary side 5: one valence-2 cone or two valence-3 cones
 * (every admissible torus cone set but {3, 5} has one, docs/domain.md),
 * those nearest the circle and, for two, nearest each other in the disk
 * layout. Sets in_t[i] for the chosen cones (pos: 2 per cone); returns
 * how many (0: none). */
static uint32_t choose_t_cones(uint32_t n, const int32_t *val, const double *pos, uint8_t *in_t)
{
    double best = HUGE_VAL;
    uint32_t bi = SQ_NONE, bj = SQ_NONE;
    for (uint32_t i = 0; i < n; i++) {
        double di = 1.0 - hypot(pos[2 * i], pos[2 * i + 1]);
        if (val[i] == 2 && 2 * di < best) best = 2 * di, bi = i, bj = SQ_NONE;
        if (val[i] != 3) continue;
        for (uint32_t j = i + 1; j < n; j++) {
            if (val[j] != 3) continue;
            double dj = 1.0 - hypot(pos[2 * j], pos[2 * j + 1]);
            double sc = di + dj + hypot(pos[2 * i] - pos[2 * j], pos[2 * i + 1] - pos[2 * j + 1]);
            if (sc < best) best = sc, bi = i, bj = j;
        }
    }
    memset(in_t, 0, n);
    if (bi == SQ_NONE) return 0;
    in_t[bi] = 1;
    if (bj != SQ_NONE) in_t[bj] = 1;
    return bj != SQ_NONE ? 2 : 1;
}

/* sq_guide_cone_order for the torus's two pieces: H's cones first, in
 * radial order among themselves, then T's (choose_t_cones; *nt of them). */
static sq_status order_genus1(uint32_t nc, const int32_t *val, const double *pos, uint32_t *order,
                              uint32_t *nt, sq_error *err)
{
    uint8_t *in_t = malloc((size_t)nc + 1);
    int32_t *hv = malloc(((size_t)nc + 1) * sizeof *hv);
    double *hp = malloc((2 * (size_t)nc + 2) * sizeof *hp);
    uint32_t *hi = malloc(((size_t)nc + 1) * sizeof *hi), *ho = malloc(((size_t)nc + 1) * sizeof *ho);
    sq_status st = SQ_OK;
    uint32_t nh = 0;
    if (!in_t || !hv || !hp || !hi || !ho) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    *nt = choose_t_cones(nc, val, pos, in_t);
    if (*nt == 0) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "genus 1: no cone of valence 2 and no two of valence 3 (the cone set "
                          "admits no two-piece domain)");
        goto done;
    }
    for (uint32_t i = 0; i < nc; i++) {
        if (in_t[i]) continue;
        hi[nh] = i, hv[nh] = val[i];
        hp[2 * nh] = pos[2 * i], hp[2 * nh + 1] = pos[2 * i + 1];
        nh++;
    }
    st = sq_guide_cone_order(nh, hv, hp, ho, err);
    if (st) goto done;
    for (uint32_t i = 0; i < nh; i++) order[i] = hi[ho[i]];
    for (uint32_t i = 0, t = nh; i < nc; i++)
        if (in_t[i]) order[t++] = i;
done:
    free(in_t), free(hv), free(hp), free(hi), free(ho);
    return st;
}

/* Seed 9.2: the cut surface in the unit disk, its cones ordered by
 * distance from the centre (prefix condition kept); val (nc valences of
 * the cones in vertex order) is reordered in place, and the surface vertex
 * and disk position of every construction step recorded. Genus 1: the
 * cones of the meta-2-gon (choose_t_cones) go last, the meta-6-gon's in
 * radial order before them; *nt receives their number (0 for genus >= 2). */
static sq_status guided_order(ctx *c, int32_t *val, uint32_t nc, uint32_t *nt)
{
    const sq_mesh *m = c->m;
    const uint32_t k = c->G.pattern.k;
    double *v_xy = malloc(2 * (size_t)m->nv * sizeof *v_xy), *ang = malloc(((size_t)k + 1) * sizeof *ang);
    double *pos = malloc((2 * (size_t)nc + 2) * sizeof *pos);
    uint32_t *cv = malloc(((size_t)nc + 1) * sizeof *cv), *order = malloc(((size_t)nc + 1) * sizeof *order);
    int32_t *v2 = malloc(((size_t)nc + 1) * sizeof *v2);
    c->step_vertex = malloc(((size_t)nc + 1) * sizeof *c->step_vertex);
    c->glue.chosen = malloc(((size_t)nc + 1) * sizeof *c->glue.chosen);
    c->step_xy = malloc((2 * (size_t)nc + 2) * sizeof *c->step_xy);
    sq_status st = SQ_OK;
    if (!v_xy || !ang || !pos || !cv || !order || !v2 || !c->step_vertex || !c->step_xy || !c->glue.chosen) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* SQ_TREE_QTRI: the layout with little length distortion, so that Q's
     * cones lie about as far apart as the surface's (docs/param.md) */
    st = c->opt->tree == SQ_TREE_QTRI ? sq_guide_surface_arap(m, &c->G, SQ_GUIDE_ARAP_ITERS, v_xy, ang, c->err)
                                      : sq_guide_surface_disk(m, &c->G, v_xy, ang, c->err);
    if (st) goto done;
    c->surf_corner_angle = ang;
    ang = NULL;
    uint32_t n = 0;
    for (uint32_t v = 0; v < m->nv && n < nc; v++)
        if (c->S_valence[v] != 4) {
            cv[n] = v, pos[2 * n] = v_xy[2 * v], pos[2 * n + 1] = v_xy[2 * v + 1];
            if (isnan(pos[2 * n])) {
                st = sq_error_set(c->err, SQ_ERR_INTERNAL, "guidance: cone %u lies on the cut graph", v);
                goto done;
            }
            n++;
        }
    if (n != nc) {
        st = sq_error_set(c->err, SQ_ERR_INTERNAL, "guidance: %u cones, expected %u", n, nc);
        goto done;
    }
    *nt = 0;
    st = sq_mesh_genus(m) == 1 ? order_genus1(nc, val, pos, order, nt, c->err)
                               : sq_guide_cone_order(nc, val, pos, order, c->err);
    if (st) goto done;
    for (uint32_t i = 0; i < nc; i++) {
        v2[i] = val[order[i]];
        c->step_vertex[i] = cv[order[i]];
        c->step_xy[2 * i] = pos[2 * order[i]], c->step_xy[2 * i + 1] = pos[2 * order[i] + 1];
    }
    memcpy(val, v2, (size_t)nc * sizeof *val);
done:
    free(v_xy);
    free(ang);
    free(pos);
    free(cv);
    free(order);
    free(v2);
    return st;
}

/* ---- seed 9.2: Q's cones and corners against the surface's ------------ */

/* Genus >= 2 after Algorithm 1: the vertex of Q at the centre of the j-th
 * irregular metapolygon face, i.e. the cone of construction step j.
 * qv: D->ncones entries. */
sq_status sq_param_step_q_vertices(ctx *c, uint32_t *qv)
{
    const sq_metapolygon *Q = &c->D->quads, *M = &c->D->meta;
    uint32_t *mstep = malloc(((size_t)M->nf + 1) * sizeof *mstep);
    uint8_t *qbnd = calloc((size_t)Q->nv + 1, 1);
    sq_status st = SQ_OK;
    if (!mstep || !qbnd) {
        free(mstep), free(qbnd);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    uint32_t j = 0;
    for (uint32_t f = 0; f < M->nf; f++) mstep[f] = M->f_valence[f] != 4 ? j++ : SQ_NONE;
    const uint32_t nh = j; /* genus 1: steps nh.. are the meta-2-gon's cones */
    for (uint32_t s = 0; s < c->D->ncones; s++) qv[s] = SQ_NONE;
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) qbnd[Q->he_vert[h]] = 1;
    for (uint32_t v = 0; v < Q->nv && st == SQ_OK; v++) {
        if (Q->v_nface[v] == 4 || qbnd[v]) continue;
        uint32_t f = Q->he_face[Q->v_he[v]];
        uint32_t s = f != SQ_NONE && f < c->D->nf_unpadded ? mstep[c->D->f_meta_face[f]] : SQ_NONE;
        if (s == SQ_NONE && f != SQ_NONE && c->D->genus == 1) /* a cone of T: its first free step */
            for (uint32_t t = nh; t < c->D->ncones && s == SQ_NONE; t++)
                if (qv[t] == SQ_NONE && c->D->order[t] == Q->v_nface[v]) s = t;
        if (s == SQ_NONE || s >= c->D->ncones || Q->v_nface[v] != c->D->order[s] || qv[s] != SQ_NONE)
            st = sq_error_set(c->err, SQ_ERR_INTERNAL, "guidance: cone vertex %u of Q has no step", v);
        else
            qv[s] = v;
    }
    for (uint32_t s = 0; st == SQ_OK && s < c->D->ncones; s++)
        if (qv[s] == SQ_NONE) st = sq_error_set(c->err, SQ_ERR_INTERNAL, "guidance: step %u has no cone in Q", s);
    free(mstep);
    free(qbnd);
    return st;
}

static double ang_diff(double a, double b)
{
    double d = fmod(a - b, 2 * SQ_GUIDE_PI);
    if (d > SQ_GUIDE_PI) d -= 2 * SQ_GUIDE_PI;
    if (d < -SQ_GUIDE_PI) d += 2 * SQ_GUIDE_PI;
    return d;
}

/* The domain again with another side correspondence (genus >= 2) or
 * gluing of the two pieces (genus 1), `offset`, its metapolygon from
 * Algorithm 1's recorded glue edges (no layouts; the caller sets
 * c->glue.chosen[0] to SQ_NONE first). *out: NULL when that offset has no
 * padding solution or needs a slide. Reads c only (errors to c->err), so
 * threads with their own err may share it. */
static sq_status rebuild_at(ctx *c, const int32_t *val, uint32_t nc, const sq_domain_options *dopt,
                            uint32_t offset, sq_domain **out)
{
    *out = NULL;
    sq_build_options again;
    memset(&again, 0, sizeof again);
    again.glue_he = c->glue.chosen;
    sq_domain_options o = *dopt;
    o.build = &again, o.offset = offset;
    sq_domain *D = calloc(1, sizeof *D);
    if (!D) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    if (sq_domain_build(c->D->genus, val, nc, &o, D, NULL) == SQ_OK && !D->slid) {
        *out = D;
        return SQ_OK;
    }
    sq_domain_free(D);
    free(D);
    return SQ_OK;
}

void sq_param_domain_replace(ctx *c, sq_domain *D)
{
    sq_domain_free(c->D);
    free(c->D);
    c->D = D;
}

/* Seed 9.2 and seed 4 ("these can be brought into one-to-one
 * correspondence, respecting cyclic order"): of the k cyclic shifts between
 * Q's corners and the surface's, the one whose corners lie at the most
 * similar angles when Q is laid out with its cones pinned to the surface
 * cones' disk positions; Q is rebuilt with it (the shifts that admit no
 * padding are skipped). */
static sq_status align_corners(ctx *c, const int32_t *val, uint32_t nc, const sq_domain_options *dopt)
{
    sq_domain *D = c->D;
    const sq_metapolygon *Q = &D->quads;
    const uint32_t k = D->k;
    if (D->slid) return SQ_OK;
    uint32_t *qv = malloc(((size_t)D->ncones + 1) * sizeof *qv);
    double *xy = malloc((2 * (size_t)Q->nv + 2) * sizeof *xy);
    double *cost = malloc((size_t)k * sizeof *cost), *psi = malloc((size_t)k * sizeof *psi);
    uint32_t *ord = malloc((size_t)k * sizeof *ord);
    sq_status st = SQ_OK;
    if (!qv || !xy || !cost || !psi || !ord) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    st = sq_param_step_q_vertices(c, qv);
    if (st == SQ_OK) st = sq_guide_metapolygon_layout(Q, c->step_xy, D->ncones, qv, xy, c->err);
    if (st) goto done;
    /* psi[j]: angle of the unpadded quad mesh's corner j (Q corner i is its
     * corner (i + offset) % k) */
    for (uint32_t i = 0; i < k; i++) {
        uint32_t v = D->corner_vert[i];
        psi[(i + D->offset) % k] = atan2(xy[2 * v + 1], xy[2 * v]);
    }
    for (uint32_t o = 0; o < k; o++) {
        cost[o] = 0;
        for (uint32_t i = 0; i < k; i++) {
            double d = ang_diff(psi[(i + o) % k], c->surf_corner_angle[surface_corner_of_q(c, i)]);
            cost[o] += d * d;
        }
        uint32_t j = o;
        while (j > 0 && cost[ord[j - 1]] > cost[o]) ord[j] = ord[j - 1], j--;
        ord[j] = o;
    }
    c->glue.chosen[0] = SQ_NONE; /* rebuild_at's glue edges from step 1 on */
    for (uint32_t t = 0; t < k && st == SQ_OK; t++) {
        uint32_t o = ord[t];
        if (o == D->offset) break; /* the current domain is the best */
        sq_domain *D2 = NULL;
        st = rebuild_at(c, val, nc, dopt, o, &D2);
        if (st == SQ_OK && D2) {
            sq_param_domain_replace(c, D2);
            st = sq_cut_graph_domain_offset(&c->G, &c->D->pattern, &c->r, c->err);
            break;
        }
    }
done:
    free(qv);
    free(xy);
    free(cost);
    free(psi);
    free(ord);
    return st;
}

/* How well the domain c->D fits the surface (genus 1, guided): Q laid out
 * with the meta-6-gon's cones pinned to their surface cones' disk
 * positions (the first ncones - nt steps); *swap: whether the two cones of
 * the meta-2-gon (nt = 2) fit better exchanged; *r_out: of the cyclic
 * side correspondences valid for the cut's word, the one whose corners lie
 * at the most similar angles. Returns the squared angle differences plus
 * the squared distances of T's cones from their surface cones (HUGE_VAL
 * on failure, with st set). */
static double genus1_fit(ctx *c, uint32_t nt, uint32_t *r_out, int *swap, sq_status *st)
{
    const sq_domain *D = c->D;
    const sq_metapolygon *Q = &D->quads;
    const uint32_t k = D->k, nh = D->ncones - nt;
    uint32_t *qv = malloc(((size_t)D->ncones + 1) * sizeof *qv);
    double *xy = malloc((2 * (size_t)Q->nv + 2) * sizeof *xy);
    double best = HUGE_VAL;
    *swap = 0;
    *st = qv && xy ? SQ_OK : sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    if (*st == SQ_OK) *st = sq_param_step_q_vertices(c, qv);
    if (*st == SQ_OK) *st = sq_guide_metapolygon_layout(Q, c->step_xy, nh, qv, xy, c->err);
    assert(k == 6); /* a torus domain with cones: H's five sides and T's */
    if (*st == SQ_OK) {
        double dt[2] = {0, 0};
        for (int w = 0; w < 2; w++)
            for (uint32_t t = 0; t < nt; t++) {
                uint32_t q = qv[nh + (nt == 2 && w ? 1 - t : t)];
                dt[w] += pow(xy[2 * q] - c->step_xy[2 * (nh + t)], 2) +
                         pow(xy[2 * q + 1] - c->step_xy[2 * (nh + t) + 1], 2);
            }
        *swap = nt == 2 && dt[1] < dt[0];
        for (uint32_t r = 0; r < k; r++) {
            if (!sq_cut_graph_shift_pairs(&c->pcw, &D->pattern, r)) continue;
            double cost = dt[*swap];
            for (uint32_t i = 0; i < k; i++) {
                uint32_t v = D->corner_vert[i];
                double d = ang_diff(atan2(xy[2 * v + 1], xy[2 * v]), c->surf_corner_angle[surface_corner(k, r, i)]);
                cost += d * d;
            }
            if (cost < best) best = cost, *r_out = r;
        }
    }
    free(qv);
    free(xy);
    return best;
}

/* align_genus1's six gluings, shared by its two threads: offset p rebuilt
 * (the current domain's own offset `skip` as it is) and fitted into D2[p]
 * (NULL for `skip`), fit[p], r[p], swap[p], st[p] (errors in err[p]). */
typedef struct genus1_jobs {
    const ctx *c;
    const int32_t *val;
    uint32_t nc, nt, skip;
    const sq_domain_options *dopt;
    sq_domain *D2[6];
    double fit[6];
    uint32_t r[6];
    int swap[6];
    sq_status st[6];
    sq_error err[6];
    _Atomic uint32_t next;
} genus1_jobs;

static void *genus1_worker(void *arg)
{
    genus1_jobs *J = arg;
    for (uint32_t p; (p = atomic_fetch_add(&J->next, 1)) < 6;) {
        J->fit[p] = HUGE_VAL;
        ctx c2 = *J->c; /* its own error and domain; the rest read only */
        c2.err = &J->err[p];
        if ((J->st[p] = stop_if_cancelled(&c2)) != SQ_OK) continue; /* each layout ~0.4 s on elk */
        if (p != J->skip) {
            J->st[p] = rebuild_at(&c2, J->val, J->nc, J->dopt, p, &J->D2[p]);
            if (J->st[p] || !J->D2[p]) continue;
            c2.D = J->D2[p];
        }
        J->fit[p] = genus1_fit(&c2, J->nt, &J->r[p], &J->swap[p], &J->st[p]);
    }
    return NULL;
}

/* Seed 9.2 and seed 4 for genus 1: of the 6 ways to glue the meta-2-gon T
 * to the meta-6-gon H (the pairings of docs/domain.md, "Genus 1"), H
 * rebuilt from Algorithm 1's recorded glue edges, and of the cyclic side
 * correspondences with the cut surface, the pair that fits the surface
 * best (genus1_fit); T's two cones are matched to theirs by position. */
static sq_status align_genus1(ctx *c, const int32_t *val, uint32_t nc, const sq_domain_options *dopt)
{
    /* the six gluings of the meta-2-gon, two at a time where the caller
     * allows two threads (each a CHOLMOD layout of Q, the five others
     * after a domain build); the same choice as one after another: the
     * current domain first, then the first best in offset order; the
     * first error in that order */
    genus1_jobs *J = calloc(1, sizeof *J);
    if (!J) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    const uint32_t skip = c->D->offset;
    assert(skip < 6); /* the torus domain's six sides */
    J->c = c, J->val = val, J->nc = nc, J->nt = dopt->g1_split, J->skip = skip, J->dopt = dopt;
    atomic_init(&J->next, 0);
    c->glue.chosen[0] = SQ_NONE; /* rebuild_at's glue edges from step 1 on */
    pthread_t th;
    int threaded = c->opt->threads > 1 && pthread_create(&th, NULL, genus1_worker, J) == 0;
    genus1_worker(J);
    if (threaded) pthread_join(th, NULL);
    sq_status st = J->st[skip];
    uint32_t best_r = c->r, pick = SQ_NONE;
    int best_swap = 0;
    double best = J->fit[skip];
    if (st && c->err) *c->err = J->err[skip];
    if (st == SQ_OK && best < HUGE_VAL) best_r = J->r[skip], best_swap = J->swap[skip];
    for (uint32_t p = 0; p < 6 && st == SQ_OK; p++) {
        if (p == skip) continue;
        if (J->st[p]) {
            st = J->st[p];
            if (c->err) *c->err = J->err[p];
        } else if (J->D2[p] && J->fit[p] < best) {
            best = J->fit[p], best_r = J->r[p], best_swap = J->swap[p], pick = p;
        }
    }
    for (uint32_t p = 0; p < 6; p++)
        if (J->D2[p] && (p != pick || st)) {
            sq_domain_free(J->D2[p]);
            free(J->D2[p]);
        }
    if (st == SQ_OK && pick != SQ_NONE) sq_param_domain_replace(c, J->D2[pick]);
    free(J);
    if (st) return st;
    c->r = best_r;
    if (best_swap) {
        const uint32_t a = c->D->ncones - 2, b = a + 1;
        uint32_t tv = c->step_vertex[a];
        c->step_vertex[a] = c->step_vertex[b], c->step_vertex[b] = tv;
        for (int e = 0; e < 2; e++) {
            double tx = c->step_xy[2 * a + e];
            c->step_xy[2 * a + e] = c->step_xy[2 * b + e], c->step_xy[2 * b + e] = tx;
        }
    }
    return SQ_OK;
}

/* The handles' rotations of a smooth cross field with these cones
 * (docs/holonomy.md): c->G moved across cones until every map built on it
 * has them. A graph given on a refined mesh was steered on the unrefined
 * one: measured only. Genus 1: after the domain and its alignment, whose
 * straight corners (Q corner j = G corner (2k - j - r) mod k) decide the
 * rotations; c->r follows the renumbered corners. */
static sq_status steer_cut(ctx *c, const int32_t *valence, sq_param_stats *st_out)
{
    const sq_mesh *m = c->m;
    sq_error *err = c->err;
    double *turn = malloc((size_t)m->nh * sizeof *turn);
    sq_cut_steer_stats ss;
    memset(&ss, 0, sizeof ss);
    sq_status st = turn ? SQ_OK : sq_error_set(err, SQ_ERR_NOMEM, "out of memory (rotations)");
    if (st == SQ_OK) st = sq_cone_connection(m, valence, turn, NULL, err);
    const uint32_t k = c->G.pattern.k;
    if (st == SQ_OK && c->G.genus == 1) {
        if (!c->D || c->D->pattern.k != k) {
            free(turn);
            return sq_error_set(err, SQ_ERR_INTERNAL, "rotations: genus 1 needs the aligned domain");
        }
        for (uint32_t j = 0; j < k; ++j) c->G.pattern.straight[(2 * k - j - c->r) % k] = c->D->pattern.straight[j];
    }
    if (st == SQ_OK && !c->given_G) st = sq_cut_graph_steer(m, valence, turn, &c->G, &ss, err);
    else if (st == SQ_OK) {
        sq_error e2;
        if (sq_cut_graph_rotation_mismatch(m, &c->G, turn, &ss.norm_after, &ss.wrong_loops_after, &e2))
            ss.norm_after = UINT32_MAX; /* unknown; the graph is used as it is */
        ss.norm_before = ss.norm_after;
    }
    free(turn);
    if (st) return st;
    c->r = (c->r + k - ss.corner_shift % k) % k;
    if (st_out) {
        st_out->rot_mismatch_before = ss.norm_before;
        st_out->rot_mismatch_after = ss.norm_after;
        st_out->rot_reroutes = ss.reroutes;
    }
    return SQ_OK;
}

/* ---- steps 1-3 ------------------------------------------------------- */

/* Steps 1-3: the cut graph c->G (c->given_G where set), the domain Q c->D
 * (with Algorithm 1 and its corners aligned where guided), its cone tree
 * (c->T, or Q triangulated with SQ_TREE_QTRI) and Omega c->O. st_out (may
 * be NULL): sizes and the steps' times. */
sq_status sq_param_build_domain(ctx *c, const int32_t *valence, sq_param_stats *st_out)
{
    const sq_mesh *m = c->m;
    sq_error *err = c->err;
    uint32_t genus = (uint32_t)sq_mesh_genus(m);
    uint8_t *cone = calloc(m->nv, 1);
    int32_t *val = malloc((size_t)m->nv * sizeof *val);
    sq_status st = SQ_OK;
    if (!cone || !val) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    uint32_t nc = 0;
    for (uint32_t v = 0; v < m->nv; v++)
        if (valence[v] != 4) cone[v] = 1, val[nc++] = valence[v];
    if (st_out) st_out->genus = genus, st_out->ncones = nc;
    double t0 = sq_now();
    progress(c, "cut graph", 0.0);
    sq_cut_options copt;
    sq_cut_options_default(&copt);
    copt.seed = c->opt->seed;
    sq_cut_stats cst;
    memset(&cst, 0, sizeof cst);
    if (c->given_G) { /* the cut graph of the attempt on the unrefined mesh */
        sq_cut_graph_free(&c->G);
        c->G = *c->given_G;
        sq_cut_graph_init(c->given_G);
        st = sq_cut_boundary_word(m, &c->G, err); /* its sides on m's halfedges */
        if (st == SQ_OK) st = sq_cut_graph_check(m, cone, &c->G, err);
    } else if (genus >= 2)
        st = sq_cut_graph_build(m, cone, &copt, &c->G, &cst, err);
    else
        st = sq_cut_graph_build_low_genus(m, cone, &copt, &c->G, &cst, err);
    /* a loop or chain path the cut graph cannot route (it would need an
     * edge split) depends on the sampling seed, not on the input: a
     * limitation of this cut graph, retried with the next seed */
    if (st == SQ_ERR_ARGUMENT && (cst.failure == SQ_CUT_FAIL_NO_PATH || cst.failure == SQ_CUT_FAIL_NO_LOOP ||
                                  cst.failure == SQ_CUT_FAIL_NEEDS_SPLIT)) {
        st = SQ_ERR_SOLVER;
        if (err) err->code = st;
        if (st_out) st_out->cut_needs_split = 1;
    }
    if (st) goto done;
    if (genus >= 2) st = steer_cut(c, valence, st_out);
    if (st) goto done;
    st = sq_pattern_reversed(&c->G.pattern, &c->pcw, err);
    if (st) goto done;
    double t1 = sq_now();
    progress(c, "domain", 0.1);
    sq_domain_options dopt;
    memset(&dopt, 0, sizeof dopt);
    dopt.offset = SQ_NONE;
    if (genus >= 2) dopt.pattern = &c->pcw;
    sq_build_options bopt;
    memset(&bopt, 0, sizeof bopt);
    const int mode = c->opt->guidance;
    c->guided = mode == SQ_GUIDE_ON || (mode == SQ_GUIDE_AUTO && genus >= 2);
    if (st_out) st_out->guided = c->guided;
    if (sq_param_uses_algorithm1(mode, (int)genus) && (genus >= 2 || nc > 0)) {
        /* seed 9.2: cones in the order of their distance from the centre
         * of the cut surface's disk layout, each glued where the layout of
         * the growing metapolygon is closest to it (Algorithm 1); genus 1:
         * for the meta-6-gon, the meta-2-gon's cones chosen near the
         * circle */
        uint32_t nt = 0;
        st = guided_order(c, val, nc, &nt);
        if (st == SQ_OK && genus >= 2 && c->opt->tree == SQ_TREE_QTRI) st = sq_param_qtri_joinable(c, nc);
        if (st) goto done;
        c->glue.c = c->step_xy;
        c->glue.cancel = c->cancel;
        bopt.chooser = sq_guide_glue_chooser;
        bopt.chooser_user = &c->glue;
        dopt.build = &bopt;
        dopt.keep_order = 1;
        dopt.g1_split = nt;
    }
    st = sq_domain_build(genus, val, nc, &dopt, c->D, err);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st) goto done;
    if (st_out) st_out->quads_unpadded = c->D->quads_unpadded, st_out->quads_added = c->D->quads_added;
    {   /* the memory limit: Omega, the cone tree and the interior map grow
         * with Q (sq_param_options.max_memory) */
        const uint64_t max_memory = sq_param_max_memory(c->opt);
        const uint64_t nq = c->D->quads_unpadded + c->D->quads_added;
        if (nq > max_memory / SQ_BYTES_PER_DOMAIN_QUAD) {
            st = sq_error_set(err, SQ_ERR_SOLVER,
                              "domain: Q has %llu quads (%llu of padding); Omega and the interior map would need "
                              "about %llu MB, more than the memory limit of %llu MB (--max-memory)",
                              (unsigned long long)nq, (unsigned long long)c->D->quads_added,
                              (unsigned long long)((nq * SQ_BYTES_PER_DOMAIN_QUAD) >> 20),
                              (unsigned long long)(max_memory >> 20));
            goto done;
        }
    }
    c->k = c->D->k;
    st = sq_cut_graph_domain_offset(&c->G, &c->D->pattern, &c->r, err);
    if (st == SQ_OK && c->step_vertex && genus == 1) st = align_genus1(c, val, nc, &dopt);
    else if (st == SQ_OK && c->step_vertex) st = align_corners(c, val, nc, &dopt);
    if (st == SQ_OK && genus == 1 && nc > 0) st = steer_cut(c, valence, st_out);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st) goto done;
    double t2 = sq_now();
    progress(c, "omega", 0.2);
    st = SQ_ERR_SOLVER;
    if (c->step_vertex && c->opt->tree == SQ_TREE_QTRI) st = sq_param_qtri_tree(c);
    else if (c->step_vertex) st = sq_param_guided_tree(c);
    if (st_out) st_out->surface_tree = st == SQ_OK;
    /* the surface tree could not be replicated in Q's quads: Q's own
     * tree (tree qtri's attempt fails instead) */
    if (st == SQ_ERR_SOLVER && !(c->step_vertex && c->opt->tree == SQ_TREE_QTRI))
        st = sq_cone_tree_shortest(&c->D->quads, SQ_NONE, c->T, err);
    if (st == SQ_OK && !c->qtri) st = sq_omega_build(c->D, c->T, c->O, err);
    if (st == SQ_OK && c->s_tree_next && !c->qtri) st = sq_param_guided_root(c);
    if (st == SQ_OK) st = stop_if_cancelled(c);
    if (st) goto done;
    double t3 = sq_now();
    if (st_out) {
        st_out->genus = genus;
        st_out->ncones = nc;
        st_out->cut_edges = c->G.ncut_edges;
        st_out->quads_unpadded = c->D->quads_unpadded;
        st_out->quads_added = c->D->quads_added;
        st_out->tree_edges = c->qtri ? c->qt_edges : c->T->nedges;
        st_out->tree_segments = tree_nseg(c);
        st_out->t_cut = t1 - t0;
        st_out->t_domain = t2 - t1;
        st_out->t_omega = t3 - t2;
    }
done:
    free(cone);
    free(val);
    return st;
}
