/* seamquad: Omega from Q triangulated (sq_qtri.h, sq_qtri_omega; seed 7,
 * "Compatible Cutting": "the cut quad mesh Q can be laid out isometrically
 * in the plane, yielding the seamless parameter domain Omega").
 *
 * The cut disk: every vertex of S off the cut is one vertex of Omega_c,
 * every vertex on the cut one per sector (a sector is named by the cut
 * halfedge on its clockwise side, sq_tsurf.h). Face halfedges keep S's
 * indices; the boundary halfedge b(h) twin of the cut face halfedge h
 * follows them. Omega_c's boundary runs clockwise (disk on the right):
 * after b(h) comes b(twin g), g the first cut halfedge counterclockwise
 * from h around h's origin. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_edge_hash.h"
#include "sq_predicates.h"
#include "sq_qtri.h"

/* the first cut halfedge counterclockwise from the cut halfedge h around
 * its origin (h itself when it is the only one) */
static uint32_t ccw_cut(const sq_tsurf *S, uint32_t h)
{
    uint32_t g = sq_ts_ccw(S, h);
    while (!S->kind[g]) g = sq_ts_ccw(S, g);
    return g;
}

static int is_tree(const sq_tsurf *S, uint32_t h) { return S->kind[h] && S->label[h] == SQ_NONE; }

/* state shared by the steps of sq_qtri_omega */
typedef struct qomega_ctx {
    const sq_qtri *T;
    const sq_domain *D;
    sq_omega *O;
    const sq_tsurf *S;
    sq_metapolygon *W;
    uint32_t k, nh;
    uint32_t *bidx;   /* cut face halfedge -> b(h) - nh */
    uint32_t *wv;     /* corner -> vertex of Omega_c   */
    uint32_t *vid;    /* uncut vertex -> its vertex    */
    double *cxy;
    uint32_t *par, *queue;
    uint32_t *seg_he; /* tree halfedge away from the root -> segment */
    uint32_t *from, *to, nseg;
    uint32_t nb, nw;  /* boundary halfedges and vertices of Omega_c */
    uint8_t *lab_seen;
} qomega_ctx;

/* vertices: one per uncut vertex and one per sector at the cut */
static void qo_vertices(qomega_ctx *x)
{
    const sq_tsurf *S = x->S;
    const uint32_t nh = x->nh;
    uint32_t *bidx = x->bidx, *wv = x->wv, *vid = x->vid;
    uint32_t nb = 0, nw = 0;
    for (uint32_t h = 0; h < nh; h++) bidx[h] = S->kind[h] ? nb++ : SQ_NONE;
    for (uint32_t v = 0; v < S->nv; v++) vid[v] = S->v_ncut[v] ? SQ_NONE : nw++;
    for (uint32_t h = 0; h < nh; h++)
        if (S->kind[h]) wv[h] = nw++; /* the sector named by h */
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t v = S->vert[h];
        if (!S->kind[h]) wv[h] = vid[v] != SQ_NONE ? vid[v] : SQ_NONE;
    }
    for (uint32_t h = 0; h < nh; h++)
        if (wv[h] == SQ_NONE) wv[h] = wv[sq_tsurf_sector_of(S, h)];
    x->nb = nb, x->nw = nw;
}

/* the cut disk */
static sq_status qo_cut_disk(qomega_ctx *x, sq_error *err)
{
    const sq_tsurf *S = x->S;
    const uint32_t nh = x->nh, nb = x->nb, nw = x->nw;
    const uint32_t *bidx = x->bidx, *wv = x->wv;
    sq_metapolygon *W = x->W = &x->O->cut;
    sq_metapolygon_init(W);
    sq_status st = sq_metapolygon_reserve(W, nw, S->nf, (uint64_t)nh + nb, err);
    if (st) return st;
    W->nv = nw, W->nf = S->nf, W->nh = nh + nb, W->nbnd = nb;
    for (uint32_t v = 0; v < nw; v++) W->v_nface[v] = 0, W->v_he[v] = SQ_NONE;
    for (uint32_t f = 0; f < S->nf; f++) W->f_he[f] = S->f_he[f], W->f_valence[f] = 3;
    for (uint32_t h = 0; h < nh; h++) {
        W->he_vert[h] = wv[h], W->he_next[h] = S->next[h], W->he_face[h] = S->face[h];
        W->v_nface[wv[h]]++;
        if (W->v_he[wv[h]] == SQ_NONE) W->v_he[wv[h]] = h;
        if (!S->kind[h]) {
            W->he_twin[h] = S->twin[h];
            continue;
        }
        uint32_t b = nh + bidx[h];
        W->he_twin[h] = b, W->he_twin[b] = h, W->he_face[b] = SQ_NONE;
        W->he_vert[b] = wv[S->next[h]];
        W->he_next[b] = nh + bidx[S->twin[ccw_cut(S, h)]];
    }
    /* a boundary vertex's v_he: its outgoing boundary halfedge */
    for (uint32_t h = 0; h < nh; h++)
        if (S->kind[h]) W->v_he[wv[h]] = nh + bidx[S->twin[ccw_cut(S, h)]];
    W->bnd_he = nh + bidx[x->T->root_he];
    return sq_metapolygon_validate(W, 0, err);
}

/* tree segments, walked away from the root */
static sq_status qo_segments(qomega_ctx *c, sq_error *err)
{
    const sq_tsurf *S = c->S;
    const sq_qtri *T = c->T;
    const uint32_t nh = c->nh;
    uint32_t *par = c->par, *queue = c->queue, *seg_he = c->seg_he;
    for (uint32_t v = 0; v < S->nv; v++) par[v] = SQ_NONE;
    for (uint32_t h = 0; h < nh; h++) seg_he[h] = SQ_NONE;
    uint32_t nq = 0, nseg = 0;
    queue[nq++] = T->root, par[T->root] = T->root;
    uint32_t *from = c->from = malloc(((size_t)S->nv + 1) * sizeof *from), *to = c->to = malloc(((size_t)S->nv + 1) * sizeof *to);
    if (!from || !to)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Omega)");
    for (uint32_t i = 0; i < nq; i++) {
        uint32_t x = queue[i], h0 = S->v_he[x], h = h0, deg = 0;
        do {
            if (is_tree(S, h)) deg++;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        const int node = x == T->root || deg != 2 || S->valence[x] != 4;
        do {
            if (is_tree(S, h)) {
                uint32_t y = sq_ts_head(S, h);
                if (par[y] == SQ_NONE) {
                    par[y] = x, queue[nq++] = y;
                    /* a new segment at a node, else the parent's */
                    uint32_t s;
                    if (node) {
                        s = nseg++;
                        from[s] = x;
                    } else {
                        uint32_t p = par[x], hp = h0;
                        do {
                            if (sq_ts_head(S, hp) == p) break;
                            hp = sq_ts_ccw(S, hp);
                        } while (hp != h0);
                        s = seg_he[S->twin[hp]];
                    }
                    seg_he[h] = s, to[s] = y;
                } else if (par[x] != y) {
                    return sq_error_set(err, SQ_ERR_INTERNAL, "Omega: the tree has a cycle at vertex %u", x);
                }
            }
            h = sq_ts_ccw(S, h);
        } while (h != h0);
    }
    c->nseg = nseg;
    return SQ_OK;
}

/* labels: Omega's arrays, the labels' sides and partners, every boundary
 * halfedge's label (a side's, or a tree segment's left or right copy) */
static sq_status qo_labels(qomega_ctx *x, sq_error *err)
{
    const sq_tsurf *S = x->S;
    const sq_domain *D = x->D;
    sq_omega *O = x->O;
    const sq_metapolygon *W = x->W;
    const uint32_t k = x->k, nh = x->nh, nw = x->nw, *bidx = x->bidx, *seg_he = x->seg_he;
    const uint32_t lr = k + 2 * x->nseg, nl = lr + 2;
    O->k = k, O->nlabels = nl;
    O->he_label = malloc((size_t)W->nh * sizeof *O->he_label);
    O->he_partner = malloc((size_t)W->nh * sizeof *O->he_partner);
    O->label_side = malloc((size_t)nl * sizeof *O->label_side);
    O->label_partner = malloc((size_t)nl * sizeof *O->label_partner);
    O->label_rot = malloc((size_t)nl);
    O->label_t = malloc(2 * (size_t)nl * sizeof *O->label_t);
    O->xy = malloc(2 * (size_t)nw * sizeof *O->xy);
    O->v_qvert = malloc((size_t)nw * sizeof *O->v_qvert);
    O->he_qhe = malloc((size_t)W->nh * sizeof *O->he_qhe);
    x->lab_seen = calloc(nl, 1);
    if (!O->he_label || !O->he_partner || !O->label_side || !O->label_partner || !O->label_rot || !O->label_t || !O->xy ||
        !O->v_qvert || !O->he_qhe || !x->lab_seen)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Omega)");
    for (uint32_t l = 0; l < nl; l++) {
        O->label_side[l] = l < k ? l : SQ_NONE;
        O->label_partner[l] = l < k ? D->pattern.partner[l] : l ^ 1u;
    }
    if (D->k & 1) /* k is even for every pattern (8g - 4, 6, 2) */
        return sq_error_set(err, SQ_ERR_INTERNAL, "Omega: odd number of sides");
    for (uint32_t h = 0; h < W->nh; h++) O->he_label[h] = O->he_partner[h] = SQ_NONE;
    for (uint32_t h = 0; h < nh; h++) {
        O->he_qhe[h] = h;
        if (!S->kind[h]) continue;
        uint32_t b = nh + bidx[h], l;
        O->he_qhe[b] = S->twin[h];
        O->he_partner[b] = nh + bidx[S->twin[h]];
        if (S->label[h] != SQ_NONE) l = S->label[h];
        else if (seg_he[h] != SQ_NONE) l = k + 2 * seg_he[h];
        else if (seg_he[S->twin[h]] != SQ_NONE) l = k + 2 * seg_he[S->twin[h]] + 1;
        else
            return sq_error_set(err, SQ_ERR_INTERNAL, "Omega: tree edge %u-%u in no segment", S->vert[h],
                                sq_ts_head(S, h));
        O->he_label[b] = l;
    }
    return SQ_OK;
}

/* the root splits its side: the part after it (clockwise, along the
 * boundary loop, which leaves the root along the side's edge whose face
 * halfedge h1 runs into the root) and the partner's part glued to it */
static sq_status qo_root_split(qomega_ctx *c, sq_error *err)
{
    const sq_tsurf *S = c->S;
    const sq_qtri *T = c->T;
    sq_omega *O = c->O;
    const uint32_t nh = c->nh, nb = c->nb, *bidx = c->bidx, lr = c->k + 2 * c->nseg;
    uint32_t h1 = SQ_NONE, x0 = S->v_he[T->root], x = x0;
    do {
        uint32_t in = S->twin[x];
        /* the side's other edge at the root, its face halfedge running
         * into the root (not root_he's edge) */
        if (S->kind[in] && S->label[in] == T->root_side && S->twin[in] != T->root_he) h1 = in;
        x = sq_ts_ccw(S, x);
    } while (x != x0);
    if (h1 == SQ_NONE || O->he_label[nh + bidx[T->root_he]] != T->root_side)
        return sq_error_set(err, SQ_ERR_INTERNAL, "Omega: the root has no edges on its side");
    uint32_t n = 0;
    for (uint32_t b = nh + bidx[h1]; O->he_label[b] == T->root_side && n <= nb; b = c->W->he_next[b], n++) {
        O->he_label[b] = lr;
        O->he_label[O->he_partner[b]] = lr + 1;
    }
    return SQ_OK;
}

/* Omega's integer positions: the common power-of-two scale of the layout,
 * each vertex's position and Q vertex, the bounding box */
static sq_status qo_positions(qomega_ctx *c, sq_error *err)
{
    const sq_tsurf *S = c->S;
    sq_omega *O = c->O;
    const uint32_t nh = c->nh, nw = c->nw, *wv = c->wv;
    const double *cxy = c->cxy;
    int shift = 0;
    for (uint32_t h = 0; h < nh; h++)
        for (int q = 0; q < 2; q++) {
            double x = cxy[2 * h + (uint32_t)q];
            int s = 0;
            while (s <= 40 && ldexp(x, s) != nearbyint(ldexp(x, s))) s++;
            if (s > 40)
                return sq_error_set(err, SQ_ERR_INTERNAL, "Omega: a position is finer than 2^-40");
            shift = s > shift ? s : shift;
        }
    O->xy_shift = shift;
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t v = wv[h];
        int64_t x = (int64_t)ldexp(cxy[2 * h], shift), y = (int64_t)ldexp(cxy[2 * h + 1], shift);
        O->xy[2 * v] = x, O->xy[2 * v + 1] = y;
        O->v_qvert[v] = S->vert[h];
    }
    O->xmin = O->ymin = INT64_MAX, O->xmax = O->ymax = INT64_MIN;
    for (uint32_t v = 0; v < nw; v++) {
        int64_t x = O->xy[2 * v], y = O->xy[2 * v + 1];
        O->xmin = x < O->xmin ? x : O->xmin, O->xmax = x > O->xmax ? x : O->xmax;
        O->ymin = y < O->ymin ? y : O->ymin, O->ymax = y > O->ymax ? y : O->ymax;
    }
    return SQ_OK;
}

/* transitions: one per label, the same on every edge of it */
static sq_status qo_transitions(qomega_ctx *c, sq_error *err)
{
    const sq_tsurf *S = c->S;
    sq_omega *O = c->O;
    const uint32_t nh = c->nh, nl = O->nlabels, *bidx = c->bidx;
    const int shift = O->xy_shift;
    uint8_t *lab_seen = c->lab_seen;
    sq_status st = SQ_OK;
    for (uint32_t h = 0; h < nh && st == SQ_OK; h++) {
        if (!S->kind[h]) continue;
        uint32_t l = O->he_label[nh + bidx[h]];
        uint8_t rot;
        double t[2];
        if (!sq_qtri_transition(c->T, c->cxy, h, &rot, t) || t[0] != nearbyint(t[0]) || t[1] != nearbyint(t[1])) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega: edge %u-%u has no integer transition", S->vert[h],
                              sq_ts_head(S, h));
            break;
        }
        int64_t tx = (int64_t)ldexp(t[0], shift), ty = (int64_t)ldexp(t[1], shift);
        if (!lab_seen[l]) {
            lab_seen[l] = 1, O->label_rot[l] = rot, O->label_t[2 * l] = tx, O->label_t[2 * l + 1] = ty;
        } else if (O->label_rot[l] != rot || O->label_t[2 * l] != tx || O->label_t[2 * l + 1] != ty) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega: label %u has two transitions (edge %u-%u)", l,
                              S->vert[h], sq_ts_head(S, h));
        }
    }
    for (uint32_t l = 0; l < nl && st == SQ_OK; l++)
        if (!lab_seen[l]) st = sq_error_set(err, SQ_ERR_INTERNAL, "Omega: label %u has no edge", l);
    return st;
}

sq_status sq_qtri_omega(const sq_qtri *T, const sq_domain *D, sq_omega *O, uint32_t *nseg_out, uint32_t **seg_from,
                        uint32_t **seg_to, sq_error *err)
{
    const sq_tsurf *S = &T->S;
    const uint32_t k = D->k, nh = S->nh;
    sq_omega_free(O);
    *nseg_out = 0, *seg_from = *seg_to = NULL;
    qomega_ctx x = {.T = T, .D = D, .O = O, .S = S, .k = k, .nh = nh};
    x.bidx = malloc((size_t)nh * sizeof *x.bidx);
    x.wv = malloc((size_t)nh * sizeof *x.wv);
    x.vid = malloc((size_t)S->nv * sizeof *x.vid);
    x.cxy = malloc(2 * (size_t)nh * sizeof *x.cxy);
    x.par = malloc((size_t)S->nv * sizeof *x.par), x.queue = malloc((size_t)S->nv * sizeof *x.queue);
    x.seg_he = malloc((size_t)nh * sizeof *x.seg_he);
    sq_status st = SQ_OK;
    if (!x.bidx || !x.wv || !x.vid || !x.cxy || !x.par || !x.queue || !x.seg_he) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (Omega)");
        goto done;
    }
    st = sq_qtri_layout(T, x.cxy, err);
    if (st) goto done;
    qo_vertices(&x);
    if ((st = qo_cut_disk(&x, err)) || (st = qo_segments(&x, err)) || (st = qo_labels(&x, err)) ||
        (st = qo_root_split(&x, err)) || (st = qo_positions(&x, err)) || (st = qo_transitions(&x, err)))
        goto done;
    O->root_side = T->root_side, O->root_pos = T->root_pos;
    *nseg_out = x.nseg, *seg_from = x.from, *seg_to = x.to;
    x.from = x.to = NULL;
done:
    free(x.lab_seen);
    free(x.bidx), free(x.wv), free(x.vid), free(x.cxy), free(x.par), free(x.queue), free(x.seg_he);
    free(x.from), free(x.to);
    if (st) sq_omega_free(O);
    return st;
}

/* ---- a coarser triangulation of Omega ---------------------------------- */

typedef struct vlist {
    uint32_t n, cap;
    uint32_t *f;
} vlist;

static int vlist_add(vlist *L, uint32_t f)
{
    if (L->n == L->cap) {
        uint32_t c = L->cap ? 2 * L->cap : 8;
        uint32_t *p = realloc(L->f, (size_t)c * sizeof *p);
        if (!p) return -1;
        L->f = p, L->cap = c;
    }
    L->f[L->n++] = f;
    return 0;
}

static int tri_has(const uint32_t *t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

/* 4 sqrt(3) area / (sum of the squared edge lengths): 1 for an
 * equilateral triangle, 0.87 for Q's right halves, 0 for a degenerate one */
static double tri_quality(const double q[3][2])
{
    double a2 = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]);
    double s = 0;
    for (int k = 0; k < 3; k++) {
        double dx = q[(k + 1) % 3][0] - q[k][0], dy = q[(k + 1) % 3][1] - q[k][1];
        s += dx * dx + dy * dy;
    }
    return s > 0 ? 2 * 1.7320508075688772 * a2 / s : 0;
}

/* whether collapsing inner vertex v into its neighbour w keeps a valid
 * triangulation: the link condition (v and w share exactly the two
 * vertices opposite their edge) and every triangle of v that stays turns
 * positively with w in v's place; and no worse shapes: the worst of those
 * triangles with w (tri_quality) at least as good as the worst of them
 * with v (the two triangles on the edge v-w, which go, left out). Without
 * that last rule the collapses leave slivers along Omega's boundary,
 * which the overlay's disk map lays along the circle, across every
 * surface edge there (docs/param.md, "Where the crossings are":
 * cid/elephant 14.95 million faces built against 9.03 million with it) */
static int collapse_ok(const uint32_t *tri, const uint8_t *alive, const vlist *vf, const double *p, uint32_t v,
                       uint32_t w)
{
    uint32_t shared_faces = 0;
    double qnew = 1, qold = 1;
    for (uint32_t i = 0; i < vf[v].n; i++) {
        uint32_t f = vf[v].f[i];
        if (!alive[f]) continue;
        const uint32_t *t = tri + 3 * f;
        if (tri_has(t, w)) {
            shared_faces++;
            continue;
        }
        double q[3][2], o[3][2];
        for (int k = 0; k < 3; k++) {
            uint32_t x = t[k] == v ? w : t[k];
            q[k][0] = p[2 * x], q[k][1] = p[2 * x + 1];
            o[k][0] = p[2 * t[k]], o[k][1] = p[2 * t[k] + 1];
        }
        if (sq_orient2d(q[0], q[1], q[2]) <= 0) return 0;
        double qn = tri_quality(q), qo = tri_quality(o);
        if (qn < qnew) qnew = qn;
        if (qo < qold) qold = qo;
    }
    if (shared_faces != 2) return 0;
    if (qnew < qold) return 0;
    /* common neighbours: only the two opposite vertices */
    uint32_t common = 0;
    for (uint32_t i = 0; i < vf[v].n; i++) {
        uint32_t f = vf[v].f[i];
        if (!alive[f]) continue;
        for (int k = 0; k < 3; k++) {
            uint32_t x = tri[3 * f + (uint32_t)k];
            if (x == v || x == w) continue;
            /* x a neighbour of w too? (each counted once per face of v
             * holding it: twice for a vertex on two of v's faces) */
            for (uint32_t j = 0; j < vf[w].n; j++) {
                uint32_t g = vf[w].f[j];
                if (alive[g] && tri_has(tri + 3 * g, x)) {
                    common++;
                    break;
                }
            }
        }
    }
    /* each opposite vertex lies on two faces of v: counted twice each */
    return common == 4;
}

/* Greedy passes (up to 4): each inner vertex of the triangles tri (alive,
 * faces per vertex vf, positions p) collapsed into its nearest neighbour
 * that keeps the triangulation valid (collapse_ok); gone marks the
 * vertices removed, *removed counts them. */
static sq_status collapse_passes(uint32_t nv, uint32_t *tri, uint8_t *alive, vlist *vf, const double *p,
                                 const uint8_t *bnd, uint8_t *gone, uint32_t *removed, sq_error *err)
{
    for (int pass = 0; pass < 4; pass++) {
        uint32_t done_pass = 0;
        for (uint32_t v = 0; v < nv; v++) {
            if (bnd[v] || gone[v]) continue;
            uint32_t cand[64], nc = 0;
            for (uint32_t i = 0; i < vf[v].n && nc < 60; i++) {
                uint32_t f = vf[v].f[i];
                if (!alive[f]) continue;
                for (int k = 0; k < 3; k++) {
                    uint32_t x = tri[3 * f + (uint32_t)k], dup = 0;
                    for (uint32_t q = 0; q < nc; q++) dup |= cand[q] == x;
                    if (x != v && !dup) cand[nc++] = x;
                }
            }
            /* nearest first */
            for (uint32_t a = 1; a < nc; a++)
                for (uint32_t b = a; b > 0; b--) {
                    double da = hypot(p[2 * cand[b]] - p[2 * v], p[2 * cand[b] + 1] - p[2 * v + 1]);
                    double db = hypot(p[2 * cand[b - 1]] - p[2 * v], p[2 * cand[b - 1] + 1] - p[2 * v + 1]);
                    if (da >= db) break;
                    uint32_t t = cand[b];
                    cand[b] = cand[b - 1], cand[b - 1] = t;
                }
            for (uint32_t q = 0; q < nc; q++) {
                uint32_t w = cand[q];
                if (!collapse_ok(tri, alive, vf, p, v, w)) continue;
                for (uint32_t i = 0; i < vf[v].n; i++) {
                    uint32_t f = vf[v].f[i];
                    if (!alive[f]) continue;
                    uint32_t *t = tri + 3 * f;
                    if (tri_has(t, w)) {
                        alive[f] = 0;
                        continue;
                    }
                    for (int k = 0; k < 3; k++)
                        if (t[k] == v) t[k] = w;
                    if (vlist_add(&vf[w], f)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
                }
                gone[v] = 1, done_pass++;
                break;
            }
        }
        *removed += done_pass;
        if (!done_pass) break;
    }
    return SQ_OK;
}

/* N: W's triangles that are alive, their vertices renumbered by vnew
 * (SQ_NONE: gone), W's boundary kept in order after the faces' halfedges;
 * hmap (W->nh): W's boundary halfedges in N (SQ_NONE elsewhere). */
static sq_status rebuild_cut(const sq_metapolygon *W, const uint32_t *tri, const uint8_t *alive, const uint8_t *gone,
                             uint32_t *vnew, uint32_t *hmap, sq_metapolygon *N, sq_error *err)
{
    const uint32_t nf = W->nf, nv = W->nv, nh = W->nh;
    sq_status st;
    uint32_t mv = 0, mf = 0;
    for (uint32_t v = 0; v < nv; v++) vnew[v] = gone[v] ? SQ_NONE : mv++;
    for (uint32_t f = 0; f < nf; f++) mf += alive[f];
    const uint32_t nbh = W->nbnd, mh = 3 * mf + nbh;
    st = sq_metapolygon_reserve(N, mv, mf, mh, err);
    if (st) return st;
    N->nv = mv, N->nf = mf, N->nh = mh, N->nbnd = nbh;
    /* face halfedges 3f' + k; twins by a hash of (tail, head) */
    sq_edge_hash E = {0, NULL, NULL};
    if (sq_edge_hash_init(&E, mh)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
    for (uint32_t v = 0; v < mv; v++) N->v_nface[v] = 0, N->v_he[v] = SQ_NONE;
    uint32_t ff = 0;
    for (uint32_t f = 0; f < nf; f++) {
        if (!alive[f]) continue;
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t h = 3 * ff + k, a = vnew[tri[3 * f + k]], b = vnew[tri[3 * f + (k + 1) % 3]];
            N->he_vert[h] = a, N->he_next[h] = 3 * ff + (k + 1) % 3, N->he_face[h] = ff, N->he_twin[h] = SQ_NONE;
            N->v_nface[a]++;
            if (N->v_he[a] == SQ_NONE) N->v_he[a] = h;
            E.val[sq_edge_hash_slot(&E, a, b)] = h;
        }
        N->f_he[ff] = 3 * ff, N->f_valence[ff] = 3;
        ff++;
    }
    /* boundary halfedges in W's order after the faces */
    uint32_t bi = 0;
    for (uint32_t h = 0; h < nh; h++) {
        hmap[h] = SQ_NONE;
        if (W->he_face[h] == SQ_NONE) hmap[h] = 3 * mf + bi++;
    }
    for (uint32_t h = 0; h < nh && st == SQ_OK; h++) {
        if (hmap[h] == SQ_NONE) continue;
        uint32_t b = hmap[h], a0 = vnew[W->he_vert[h]], a1 = vnew[W->he_vert[W->he_next[h]]];
        N->he_vert[b] = a0, N->he_next[b] = hmap[W->he_next[h]], N->he_face[b] = SQ_NONE;
        uint32_t f = E.val[sq_edge_hash_slot(&E, a1, a0)];
        if (f == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "coarsen: boundary edge %u-%u lost its face", a0, a1);
            break;
        }
        N->he_twin[b] = f, N->he_twin[f] = b;
        N->v_he[a0] = b;
    }
    for (uint32_t h = 0; h < 3 * mf && st == SQ_OK; h++) {
        if (N->he_twin[h] != SQ_NONE) continue;
        uint32_t a = N->he_vert[h], b = N->he_vert[N->he_next[h]];
        uint32_t t = E.val[sq_edge_hash_slot(&E, b, a)];
        if (t == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "coarsen: edge %u-%u has no twin", a, b);
            break;
        }
        N->he_twin[h] = t;
    }
    sq_edge_hash_free(&E);
    if (st) return st;
    N->bnd_he = hmap[W->bnd_he];
    return sq_metapolygon_validate(N, 0, err);
}

/* The rest of O (labels, partners, Q's halfedges and vertices, layout)
 * renumbered to N (vnew, hmap as rebuild_cut made them); N replaces O's
 * cut. */
static sq_status renumber_omega(sq_omega *O, sq_metapolygon *N, const uint32_t *vnew, const uint32_t *hmap,
                                sq_error *err)
{
    sq_metapolygon *W = &O->cut;
    const uint32_t nv = W->nv, nh = W->nh, mv = N->nv, mh = N->nh;
    uint32_t *lab = malloc((size_t)mh * sizeof *lab), *par = malloc((size_t)mh * sizeof *par);
    uint32_t *qhe = malloc((size_t)mh * sizeof *qhe), *qv = malloc(((size_t)mv + 1) * sizeof *qv);
    int64_t *xy = malloc(2 * ((size_t)mv + 1) * sizeof *xy);
    if (!lab || !par || !qhe || !qv || !xy) {
        free(lab), free(par), free(qhe), free(qv), free(xy);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
    }
    for (uint32_t h = 0; h < mh; h++) lab[h] = par[h] = qhe[h] = SQ_NONE;
    for (uint32_t h = 0; h < nh; h++) {
        if (hmap[h] == SQ_NONE) continue;
        lab[hmap[h]] = O->he_label[h];
        par[hmap[h]] = O->he_partner[h] == SQ_NONE ? SQ_NONE : hmap[O->he_partner[h]];
        qhe[hmap[h]] = O->he_qhe[h];
    }
    for (uint32_t v = 0; v < nv; v++)
        if (vnew[v] != SQ_NONE)
            qv[vnew[v]] = O->v_qvert[v], xy[2 * vnew[v]] = O->xy[2 * v], xy[2 * vnew[v] + 1] = O->xy[2 * v + 1];
    free(O->he_label), free(O->he_partner), free(O->he_qhe), free(O->v_qvert), free(O->xy);
    O->he_label = lab, O->he_partner = par, O->he_qhe = qhe, O->v_qvert = qv, O->xy = xy;
    sq_metapolygon_free(W);
    *W = *N;
    sq_metapolygon_init(N);
    return SQ_OK;
}

sq_status sq_omega_coarsen(sq_omega *O, uint32_t *removed, sq_error *err)
{
    sq_metapolygon *W = &O->cut;
    const uint32_t nf = W->nf, nv = W->nv, nh = W->nh;
    *removed = 0;
    for (uint32_t f = 0; f < nf; f++)
        if (W->f_valence[f] != 3) return sq_error_set(err, SQ_ERR_ARGUMENT, "coarsen: face %u is no triangle", f);
    uint32_t *tri = malloc(3 * (size_t)nf * sizeof *tri);
    uint8_t *alive = malloc((size_t)nf + 1), *bnd = calloc((size_t)nv + 1, 1), *gone = calloc((size_t)nv + 1, 1);
    vlist *vf = calloc((size_t)nv + 1, sizeof *vf);
    double *p = malloc(2 * (size_t)nv * sizeof *p);
    uint32_t *vnew = malloc(((size_t)nv + 1) * sizeof *vnew), *hmap = NULL;
    sq_metapolygon N;
    sq_metapolygon_init(&N);
    sq_status st = SQ_OK;
    if (!tri || !alive || !bnd || !gone || !vf || !p || !vnew) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
        goto done;
    }
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t h = W->f_he[f];
        for (int k = 0; k < 3; k++, h = W->he_next[h]) tri[3 * f + (uint32_t)k] = W->he_vert[h];
        alive[f] = 1;
        for (int k = 0; k < 3; k++)
            if (vlist_add(&vf[tri[3 * f + (uint32_t)k]], f)) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
                goto done;
            }
    }
    for (uint32_t h = 0; h < nh; h++)
        if (W->he_face[h] == SQ_NONE) bnd[W->he_vert[h]] = 1;
    for (uint32_t v = 0; v < nv; v++) p[2 * v] = (double)O->xy[2 * v], p[2 * v + 1] = (double)O->xy[2 * v + 1];
    st = collapse_passes(nv, tri, alive, vf, p, bnd, gone, removed, err);
    hmap = st == SQ_OK ? malloc((size_t)nh * sizeof *hmap) : NULL;
    if (st == SQ_OK && !hmap) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (coarsen)");
    if (st == SQ_OK) st = rebuild_cut(W, tri, alive, gone, vnew, hmap, &N, err);
    if (st == SQ_OK) st = renumber_omega(O, &N, vnew, hmap, err);
done:
    sq_metapolygon_free(&N);
    if (vf)
        for (uint32_t v = 0; v < nv; v++) free(vf[v].f);
    free(tri), free(alive), free(bnd), free(gone), free(vf), free(p), free(vnew), free(hmap);
    return st;
}
