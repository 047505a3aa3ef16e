/* seamquad: editable triangle surface with cut edges (sq_tsurf.h). */
#include "sq_tsurf.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void sq_tsurf_init(sq_tsurf *S) { memset(S, 0, sizeof *S); }

void sq_tsurf_free(sq_tsurf *S)
{
    free(S->pos);
    free(S->vert);
    free(S->next);
    free(S->twin);
    free(S->f_he);
    free(S->forig);
    free(S->face);
    free(S->v_he);
    free(S->kind);
    free(S->label);
    free(S->v_ncut);
    free(S->valence);
    free(S->hvec);
    sq_tsurf_init(S);
}

static int grow(sq_tsurf *S, uint32_t need_v, uint32_t need_f, uint32_t need_h)
{
    if (need_v > S->cap_v) {
        uint32_t c = S->cap_v ? S->cap_v : 64;
        while (c < need_v) c = c + c / 2 + 16;
        double *p = realloc(S->pos, 3 * (size_t)c * sizeof *p);
        if (!p) return -1;
        S->pos = p;
        uint32_t *vh = realloc(S->v_he, (size_t)c * sizeof *vh);
        if (!vh) return -1;
        S->v_he = vh;
        uint32_t *nc = realloc(S->v_ncut, (size_t)c * sizeof *nc);
        if (!nc) return -1;
        S->v_ncut = nc;
        int32_t *va = realloc(S->valence, (size_t)c * sizeof *va);
        if (!va) return -1;
        S->valence = va;
        S->cap_v = c;
    }
    if (need_f > S->cap_f) {
        uint32_t c = S->cap_f ? S->cap_f : 64;
        while (c < need_f) c = c + c / 2 + 16;
        uint32_t *t = realloc(S->f_he, (size_t)c * sizeof *t);
        if (!t) return -1;
        S->f_he = t;
        t = realloc(S->forig, (size_t)c * sizeof *t);
        if (!t) return -1;
        S->forig = t;
        S->cap_f = c;
    }
    if (need_h > S->cap_h) {
        uint32_t c = S->cap_h ? S->cap_h : 192;
        while (c < need_h) c = c + c / 2 + 48;
        uint32_t *t = realloc(S->vert, (size_t)c * sizeof *t);
        if (!t) return -1;
        S->vert = t;
        t = realloc(S->next, (size_t)c * sizeof *t);
        if (!t) return -1;
        S->next = t;
        t = realloc(S->face, (size_t)c * sizeof *t);
        if (!t) return -1;
        S->face = t;
        uint32_t *tw = realloc(S->twin, (size_t)c * sizeof *tw);
        if (!tw) return -1;
        S->twin = tw;
        uint8_t *k = realloc(S->kind, (size_t)c * sizeof *k);
        if (!k) return -1;
        S->kind = k;
        uint32_t *l = realloc(S->label, (size_t)c * sizeof *l);
        if (!l) return -1;
        S->label = l;
        if (S->hvec) {
            double *hv = realloc(S->hvec, 2 * (size_t)c * sizeof *hv);
            if (!hv) return -1;
            S->hvec = hv;
        }
        S->cap_h = c;
    }
    return 0;
}

int sq_tsurf_copy(sq_tsurf *dst, const sq_tsurf *src)
{
    sq_tsurf_free(dst);
    if (src->hvec && !(dst->hvec = malloc(2 * sizeof *dst->hvec))) return -1;
    /* at least one of each, so that no array stays NULL */
    if (grow(dst, src->nv ? src->nv : 1, src->nf ? src->nf : 1, src->nh ? src->nh : 1)) {
        sq_tsurf_free(dst);
        return -1;
    }
    size_t nv = src->nv, nf = src->nf, nh = src->nh;
    memcpy(dst->pos, src->pos, 3 * nv * sizeof *dst->pos);
    memcpy(dst->v_he, src->v_he, nv * sizeof *dst->v_he);
    memcpy(dst->v_ncut, src->v_ncut, nv * sizeof *dst->v_ncut);
    memcpy(dst->valence, src->valence, nv * sizeof *dst->valence);
    memcpy(dst->f_he, src->f_he, nf * sizeof *dst->f_he);
    memcpy(dst->forig, src->forig, nf * sizeof *dst->forig);
    memcpy(dst->vert, src->vert, nh * sizeof *dst->vert);
    memcpy(dst->next, src->next, nh * sizeof *dst->next);
    memcpy(dst->face, src->face, nh * sizeof *dst->face);
    memcpy(dst->twin, src->twin, nh * sizeof *dst->twin);
    memcpy(dst->kind, src->kind, nh * sizeof *dst->kind);
    memcpy(dst->label, src->label, nh * sizeof *dst->label);
    if (src->hvec) memcpy(dst->hvec, src->hvec, 2 * nh * sizeof *dst->hvec);
    dst->nv = src->nv, dst->nf = src->nf, dst->nh = src->nh, dst->nv_input = src->nv_input;
    return 0;
}

sq_status sq_tsurf_from_mesh(const sq_mesh *m, const int32_t *valence, sq_tsurf *S,
                             uint32_t *he_map, sq_error *err)
{
    sq_tsurf_free(S);
    if (grow(S, m->nv + m->nv / 4 + 64, m->nf + m->nf / 2 + 64, 3 * (m->nf + m->nf / 2 + 64)))
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (surface copy)");
    S->nv = S->nv_input = m->nv;
    S->nf = m->nf;
    S->nh = 3 * m->nf;
    memcpy(S->pos, m->pos, 3 * (size_t)m->nv * sizeof *S->pos);
    /* map mesh halfedges to corner halfedges */
    uint32_t *of = malloc((size_t)m->nh * sizeof *of);
    if (!of) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (surface copy)");
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        for (uint32_t i = 0; i < 3; i++) {
            if (i && h == m->f_he[f])
                return free(of), sq_error_set(err, SQ_ERR_ARGUMENT, "face %u is not a triangle", f);
            of[h] = 3 * f + i;
            S->vert[3 * f + i] = m->he_vert[h];
            S->next[3 * f + i] = 3 * f + (i + 1) % 3;
            S->face[3 * f + i] = f;
            h = m->he_next[h];
        }
        S->f_he[f] = 3 * f;
        S->forig[f] = f;
        if (h != m->f_he[f]) {
            free(of);
            return sq_error_set(err, SQ_ERR_ARGUMENT, "face %u is not a triangle", f);
        }
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        if (m->he_face[h] == SQ_NONE || m->he_twin[h] == SQ_NONE) {
            free(of);
            return sq_error_set(err, SQ_ERR_ARGUMENT, "the mesh is not closed (edge %u-%u)",
                                m->he_vert[h], m->he_vert[m->he_next[h]]);
        }
        S->twin[of[h]] = of[m->he_twin[h]];
    }
    for (uint32_t h = 0; h < S->nh; h++) {
        S->v_he[S->vert[h]] = h;
        S->kind[h] = SQ_TS_UNCUT;
        S->label[h] = SQ_NONE;
    }
    if (he_map) memcpy(he_map, of, (size_t)m->nh * sizeof *of);
    for (uint32_t v = 0; v < S->nv; v++) {
        S->v_ncut[v] = 0;
        S->valence[v] = valence ? valence[v] : 4;
    }
    free(of);
    return SQ_OK;
}

uint32_t sq_tsurf_split_edge(sq_tsurf *S, uint32_t h, double t)
{
    assert(t > 0 && t < 1);
    if (grow(S, S->nv + 1, S->nf + 2, S->nh + 6)) return SQ_NONE;
    uint32_t g = S->twin[h];
    uint32_t hn = S->next[h], hp = S->next[hn];
    uint32_t gn = S->next[g], gp = S->next[gn];
    uint32_t a = S->vert[h], b = S->vert[hn], c = S->vert[hp], d = S->vert[gp];
    uint32_t m = S->nv++;
    for (int i = 0; i < 3; i++) S->pos[3 * m + i] = (1 - t) * S->pos[3 * a + i] + t * S->pos[3 * b + i];
    S->valence[m] = 4;
    S->v_ncut[m] = S->kind[h] ? 2 : 0;
    uint32_t x1 = S->nh, y0 = x1 + 1, y2 = x1 + 2, x2 = x1 + 3, z0 = x1 + 4, z2 = x1 + 5;
    S->nh += 6;
    uint32_t f = S->face[h], f2 = S->face[g], F1 = S->nf++, F2 = S->nf++;
    S->face[x1] = f, S->face[y0] = S->face[hn] = S->face[y2] = F1;
    S->face[x2] = f2, S->face[z0] = S->face[gn] = S->face[z2] = F2;
    S->f_he[f] = h, S->f_he[f2] = g;
    /* face of h: (a m c) = h x1 hp; new face (m b c) = y0 hn y2 */
    S->vert[x1] = m, S->vert[y0] = m, S->vert[y2] = c;
    S->next[h] = x1, S->next[x1] = hp, S->next[hp] = h;
    S->next[y0] = hn, S->next[hn] = y2, S->next[y2] = y0;
    /* face of g: (b m d) = g x2 gp; new face (m a d) = z0 gn z2 */
    S->vert[x2] = m, S->vert[z0] = m, S->vert[z2] = d;
    S->next[g] = x2, S->next[x2] = gp, S->next[gp] = g;
    S->next[z0] = gn, S->next[gn] = z2, S->next[z2] = z0;
    /* twins */
    S->twin[x1] = y2, S->twin[y2] = x1;
    S->twin[x2] = z2, S->twin[z2] = x2;
    S->twin[h] = z0, S->twin[z0] = h;
    S->twin[y0] = g, S->twin[g] = y0;
    S->kind[x1] = S->kind[y2] = S->kind[x2] = S->kind[z2] = SQ_TS_UNCUT;
    S->label[x1] = S->label[y2] = S->label[x2] = S->label[z2] = SQ_NONE;
    S->kind[y0] = S->kind[h], S->label[y0] = S->label[h];
    S->kind[z0] = S->kind[g], S->label[z0] = S->label[g];
    S->f_he[F1] = y0;
    S->f_he[F2] = z0;
    S->forig[F1] = S->forig[f], S->forig[F2] = S->forig[f2];
    S->v_he[m] = y0;
    if (S->hvec) {
        /* halves of h and g in their faces' frames; the new edges m-c and
         * m-d: c - m = (c - a) - (b - a) / 2, the same on g's side */
        double *V = S->hvec;
        for (int q = 0; q < 2; q++) {
            V[2 * h + q] *= 0.5, V[2 * y0 + q] = V[2 * h + q];
            V[2 * g + q] *= 0.5, V[2 * z0 + q] = V[2 * g + q];
            V[2 * x1 + q] = -V[2 * hp + q] - V[2 * h + q], V[2 * y2 + q] = -V[2 * x1 + q];
            V[2 * x2 + q] = -V[2 * gp + q] - V[2 * g + q], V[2 * z2 + q] = -V[2 * x2 + q];
        }
    }
    return m;
}

void sq_tsurf_cut_edge(sq_tsurf *S, uint32_t h, uint8_t kind, uint32_t label_h,
                       uint32_t label_twin)
{
    uint32_t g = S->twin[h];
    if (!S->kind[h]) {
        S->v_ncut[S->vert[h]]++;
        S->v_ncut[S->vert[g]]++;
    }
    S->kind[h] = S->kind[g] = kind;
    S->label[h] = label_h;
    S->label[g] = label_twin;
}

uint32_t sq_tsurf_sector_of(const sq_tsurf *S, uint32_t h)
{
    if (!S->v_ncut[S->vert[h]]) return SQ_NONE;
    uint32_t g = h;
    while (!S->kind[g]) g = sq_ts_cw(S, g);
    return g;
}

uint32_t sq_tsurf_next_boundary(const sq_tsurf *S, uint32_t h)
{
    uint32_t g = S->next[h];
    while (!S->kind[g]) g = S->next[S->twin[g]];
    return g;
}

static int is_cone(const sq_tsurf *S, uint32_t v) { return S->valence[v] != 4; }

int64_t sq_tsurf_split_blocking(sq_tsurf *S, int cones)
{
    int64_t n = 0;
    /* edges moved by a split get higher indices and are visited later;
     * edges created by a split join the new vertex (off the cut, regular)
     * to others and never need a split */
    for (uint32_t h = 0; h < S->nh; h++) {
        if (S->kind[h]) continue;
        uint32_t a = S->vert[h], b = sq_ts_head(S, h);
        if (a > b) continue; /* each edge once */
        int ca = S->v_ncut[a] > 0, cb = S->v_ncut[b] > 0;
        int bad = ca && cb;
        if (!bad && cones) {
            int ka = !ca && is_cone(S, a), kb = !cb && is_cone(S, b);
            bad = (ka && (kb || cb)) || (kb && ca);
        }
        if (!bad) continue;
        if (sq_tsurf_split_edge(S, h, 0.5) == SQ_NONE) return -1;
        n++;
    }
    return n;
}

/* ---- Dijkstra --------------------------------------------------------- */

typedef struct heap {
    uint32_t n, cap;
    uint32_t *v;
    double *d;
} heap;

static int heap_push(heap *H, uint32_t v, double d)
{
    if (H->n == H->cap) {
        uint32_t c = H->cap ? 2 * H->cap : 256;
        uint32_t *vv = realloc(H->v, (size_t)c * sizeof *vv);
        if (!vv) return -1;
        H->v = vv;
        double *dd = realloc(H->d, (size_t)c * sizeof *dd);
        if (!dd) return -1;
        H->d = dd;
        H->cap = c;
    }
    uint32_t i = H->n++;
    while (i && H->d[(i - 1) / 2] > d) {
        H->v[i] = H->v[(i - 1) / 2], H->d[i] = H->d[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    H->v[i] = v, H->d[i] = d;
    return 0;
}

static void heap_pop(heap *H, uint32_t *v, double *d)
{
    *v = H->v[0], *d = H->d[0];
    uint32_t lv = H->v[--H->n];
    double ld = H->d[H->n];
    uint32_t i = 0;
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= H->n) break;
        if (c + 1 < H->n && H->d[c + 1] < H->d[c]) c++;
        if (H->d[c] >= ld) break;
        H->v[i] = H->v[c], H->d[i] = H->d[c];
        i = c;
    }
    H->v[i] = lv, H->d[i] = ld;
}

static double cdist(const double a[3], const double b[3])
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

static int blocked(const sq_tsurf *S, uint32_t w) { return S->v_ncut[w] || is_cone(S, w); }

/* Route graph: nodes 0 .. nv-1 are vertices off the cut that are not
 * cones; node nv + h (h a halfedge of an uncut edge whose two ends are
 * blocked) is that edge's midpoint, a Steiner vertex made only if the route
 * uses it, reached from face(twin h) and continuing into face(h). Every
 * step stays in one face: a vertex and the edge opposite it, or two edges
 * of a face whose third vertex is blocked. Edges with an end at the start
 * are never crossed, and an edge with an end at the target ends the route:
 * splitting such an edge would cut a face that a later step relies on. */
static uint32_t edge_node(const sq_tsurf *S, uint32_t h) { return S->nv + h; }

static int crossable(const sq_tsurf *S, uint32_t h)
{
    return !S->kind[h] && blocked(S, S->vert[h]) && blocked(S, sq_ts_head(S, h));
}

static void node_pos(const sq_tsurf *S, uint32_t n, double p[3])
{
    if (n < S->nv) {
        for (int k = 0; k < 3; k++) p[k] = S->pos[3 * n + k];
        return;
    }
    uint32_t h = n - S->nv, a = S->vert[h], b = sq_ts_head(S, h);
    for (int k = 0; k < 3; k++) p[k] = 0.5 * (S->pos[3 * a + k] + S->pos[3 * b + k]);
}

typedef struct route_ctx {
    sq_tsurf *S;
    double *dist;
    uint32_t *pred;
    heap H;
    uint8_t *ring; /* hops to the cut, capped (NULL: none) */
} route_ctx;

/* cost factor of entering a vertex k rings away from the cut: paths keep
 * their distance from earlier cuts, so that no region becomes a thin strip
 * or a bay that the interior map would have to squeeze */
static double ring_factor(uint8_t k)
{
    static const double f[] = {2, 2, 1, 1, 1, 1};
    return k < 6 ? f[k] : 1;
}

#define RING_CAP 6
static uint8_t *rings(const sq_tsurf *S)
{
    uint8_t *r = malloc(S->nv);
    uint32_t *q = malloc((size_t)S->nv * sizeof *q);
    if (!r || !q) {
        free(r), free(q);
        return NULL;
    }
    uint32_t nq = 0;
    for (uint32_t v = 0; v < S->nv; v++) {
        r[v] = RING_CAP;
        if (S->v_ncut[v]) r[v] = 0, q[nq++] = v;
    }
    for (uint32_t i = 0; i < nq; i++) {
        uint32_t v = q[i];
        if (r[v] + 1 >= RING_CAP) continue;
        uint32_t h0 = S->v_he[v], h = h0;
        do {
            uint32_t w = sq_ts_head(S, h);
            if (r[w] > r[v] + 1) r[w] = (uint8_t)(r[v] + 1), q[nq++] = w;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
    }
    free(q);
    return r;
}

static int relax(route_ctx *R, uint32_t from, uint32_t to, double d_from)
{
    double a[3], b[3];
    node_pos(R->S, from, a);
    node_pos(R->S, to, b);
    double e = cdist(a, b);
    if (to >= R->S->nv) e *= ring_factor(1);
    else if (R->ring) e *= ring_factor(R->ring[to]);
    e += d_from;
    if (e < R->dist[to]) {
        R->dist[to] = e;
        R->pred[to] = from;
        return heap_push(&R->H, to, e);
    }
    return 0;
}

static int is_target_cone(const sq_tsurf *S, uint32_t v, int32_t valence, const uint8_t *cone_free)
{
    return v < S->nv_input && !S->v_ncut[v] && S->valence[v] == valence && cone_free && cone_free[v];
}

/* An edge a route may cross in its middle: uncut, both ends blocked, no end
 * at the start; an end at the sector target only through the terminal
 * nodes (fin), never on the way */
static int may_cross(const sq_tsurf *S, uint32_t h, uint32_t src, uint32_t tgt, sq_route_target kind,
                     const uint8_t *fin)
{
    if (!crossable(S, h)) return 0;
    uint32_t a = S->vert[h], b = sq_ts_head(S, h);
    /* spokes inside the start sector: the first step's face must survive */
    if ((a == src || b == src) && fin[S->nv + h] == 2) return 0;
    /* a spoke of the sector target only as the last step */
    if (kind == SQ_ROUTE_SECTOR && (a == tgt || b == tgt)) return fin[S->nv + S->twin[h]] == 1;
    return 1;
}

/* Sector routes: the nodes from which the target sector (target_sector,
 * at its origin) can be entered get fin = 1: the edge opposite the origin
 * in each of its faces, entered from the other side; its free vertices;
 * its spokes, from either side. */
static void mark_sector_ends(const sq_tsurf *S, uint32_t target_sector, uint8_t *fin)
{
    uint32_t g = target_sector;
    do {
        uint32_t o = S->next[g];
        if (crossable(S, o)) fin[edge_node(S, o)] = 1;
        g = sq_ts_ccw(S, g);
        if (S->kind[g]) break;
        uint32_t w = sq_ts_head(S, g);
        if (!blocked(S, w)) fin[w] = 1;
        if (crossable(S, g)) fin[edge_node(S, g)] = fin[edge_node(S, S->twin[g])] = 1;
    } while (1);
}

/* The route found (endn back to src through R's predecessors, the node
 * SRC standing for src) made of S's halfedges: edge nodes split at their
 * midpoints, the target vertex tgt last (not for a free route), appended
 * to *path (*npath). */
static sq_status emit_route(sq_tsurf *S, const route_ctx *R, uint32_t endn, uint32_t SRC, uint32_t src, uint32_t tgt,
                            sq_route_target kind, uint32_t **path, uint32_t *npath, sq_error *err)
{
    uint32_t cnt = 0;
    for (uint32_t n = endn; n != SRC; n = R->pred[n]) cnt++;
    uint32_t *seq = malloc(((size_t)cnt + 2) * sizeof *seq);
    if (!seq) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
    {
        uint32_t i = cnt;
        for (uint32_t n = endn; n != SRC; n = R->pred[n]) seq[--i] = n;
    }
    uint32_t nv0 = S->nv; /* node ids refer to this numbering */
    uint32_t *p = realloc(*path, ((size_t)*npath + cnt + 1) * sizeof *p);
    if (!p) {
        free(seq);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
    }
    *path = p;
    uint32_t prev = src, k = 0;
    for (uint32_t i = 0; i <= cnt; i++) {
        uint32_t v;
        if (i == cnt) {
            if (kind == SQ_ROUTE_FREE) break;
            v = tgt;
        } else if (seq[i] < nv0) {
            v = seq[i];
        } else {
            v = sq_tsurf_split_edge(S, seq[i] - nv0, 0.5);
            if (v == SQ_NONE) {
                free(seq);
                return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
            }
        }
        uint32_t h0 = S->v_he[prev], h = h0, f = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == v) f = h;
            h = sq_ts_ccw(S, h);
        } while (h != h0 && f == SQ_NONE);
        if (f == SQ_NONE) {
            free(seq);
            return sq_error_set(err, SQ_ERR_INTERNAL, "route: vertices %u and %u are not adjacent", prev, v);
        }
        p[*npath + k++] = f;
        prev = v;
    }
    *npath += k;
    free(seq);
    return SQ_OK;
}

sq_status sq_tsurf_route(sq_tsurf *S, uint32_t start, sq_route_target kind, int32_t target_valence,
                         const uint8_t *cone_free, double target_length, uint32_t target_sector,
                         uint32_t **path, uint32_t *npath, sq_error *err)
{
    assert(S->kind[start]);
    uint32_t nn = S->nv + S->nh;
    route_ctx R = {S, malloc((size_t)nn * sizeof(double)), malloc((size_t)nn * sizeof(uint32_t)), {0}, rings(S)};
    uint8_t *fin = calloc(nn, 1);
    sq_status st = SQ_OK;
    if (!R.dist || !R.pred || !fin) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    for (uint32_t i = 0; i < nn; i++) R.dist[i] = INFINITY, R.pred[i] = SQ_NONE;
    uint32_t src = S->vert[start];
    const uint32_t SRC = UINT32_MAX - 1;
    uint32_t tgt = SQ_NONE; /* target vertex (cone or sector origin) */
#define PUSH_FAIL                                                                   \
    do {                                                                            \
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");             \
        goto done;                                                                  \
    } while (0)
    if (kind == SQ_ROUTE_SECTOR) tgt = S->vert[target_sector], mark_sector_ends(S, target_sector, fin);
    /* spokes strictly inside sector(start): never crossed (fin = 2) */
    for (uint32_t g = sq_ts_ccw(S, start); !S->kind[g] && g != start; g = sq_ts_ccw(S, g))
        if (!fin[S->nv + g]) fin[S->nv + g] = fin[S->nv + S->twin[g]] = 2;
    /* first steps inside sector(start) */
    {
        uint32_t g = start;
        for (;;) {
            uint32_t o = S->next[g];
            if (may_cross(S, o, src, tgt, kind, fin)) {
                uint32_t n = edge_node(S, S->twin[o]);
                double a[3], b[3];
                node_pos(S, n, a);
                node_pos(S, src, b);
                double e = 2 * cdist(a, b);
                if (e < R.dist[n]) {
                    R.dist[n] = e, R.pred[n] = SRC;
                    if (heap_push(&R.H, n, e)) PUSH_FAIL;
                }
            }
            g = sq_ts_ccw(S, g);
            if (S->kind[g]) break;
            uint32_t w = sq_ts_head(S, g);
            if (crossable(S, g)) {
                /* the first step may split a spoke of the start: its
                 * midpoint continues into either face of the spoke */
                double a[3], b[3];
                node_pos(S, edge_node(S, g), a);
                node_pos(S, src, b);
                double e = 2 * cdist(a, b);
                uint32_t ns[2] = {edge_node(S, g), edge_node(S, S->twin[g])};
                for (int i = 0; i < 2; i++)
                    if (e < R.dist[ns[i]]) {
                        R.dist[ns[i]] = e, R.pred[ns[i]] = SRC;
                        if (heap_push(&R.H, ns[i], e)) PUSH_FAIL;
                    }
            }
            if (kind == SQ_ROUTE_SECTOR && w == tgt) continue;
            if (!blocked(S, w)) {
                double e = sq_ts_dist(S, src, w) * (R.ring ? ring_factor(R.ring[w]) : 1);
                if (e < R.dist[w]) {
                    R.dist[w] = e, R.pred[w] = SRC;
                    if (heap_push(&R.H, w, e)) PUSH_FAIL;
                }
            }
        }
    }
    uint32_t endn = SQ_NONE;
    double best_far = -1;
    uint32_t far = SQ_NONE;
    while (R.H.n) {
        uint32_t n;
        double d;
        heap_pop(&R.H, &n, &d);
        if (d > R.dist[n]) continue;
        if (kind == SQ_ROUTE_SECTOR && fin[n] == 1) {
            endn = n;
            break;
        }
        if (kind == SQ_ROUTE_FREE && n < S->nv) {
            if (d > best_far) best_far = d, far = n;
            if (d >= target_length) {
                endn = n;
                break;
            }
        }
        if (n < S->nv) {
            uint32_t h0 = S->v_he[n], h = h0;
            do {
                uint32_t w = sq_ts_head(S, h);
                if (kind == SQ_ROUTE_CONE && is_target_cone(S, w, target_valence, cone_free)) {
                    endn = n, tgt = w;
                    goto found;
                }
                if (!blocked(S, w) && relax(&R, n, w, d)) PUSH_FAIL;
                uint32_t o = S->next[h]; /* opposite n in face(h) */
                if (may_cross(S, o, src, tgt, kind, fin) && relax(&R, n, edge_node(S, S->twin[o]), d)) PUSH_FAIL;
                h = sq_ts_ccw(S, h);
            } while (h != h0);
        } else {
            uint32_t h = n - S->nv; /* continue into face(h) */
            if (kind == SQ_ROUTE_CONE) {
                uint32_t ends[3] = {S->vert[h], sq_ts_head(S, h), S->vert[sq_ts_prev(S, h)]};
                for (int i = 0; i < 3; i++)
                    if (is_target_cone(S, ends[i], target_valence, cone_free)) {
                        endn = n, tgt = ends[i];
                        goto found;
                    }
            }
            uint32_t c = S->vert[sq_ts_prev(S, h)];
            if (!blocked(S, c)) {
                if (relax(&R, n, c, d)) PUSH_FAIL;
            } else {
                uint32_t o1 = S->next[h], o2 = sq_ts_prev(S, h);
                if (may_cross(S, o1, src, tgt, kind, fin) && relax(&R, n, edge_node(S, S->twin[o1]), d)) PUSH_FAIL;
                if (may_cross(S, o2, src, tgt, kind, fin) && relax(&R, n, edge_node(S, S->twin[o2]), d)) PUSH_FAIL;
            }
        }
    }
    if (kind == SQ_ROUTE_FREE && endn == SQ_NONE && far != SQ_NONE) endn = far;
found:
    if (endn == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "no path from vertex %u inside its sector to the %s target",
                          src, kind == SQ_ROUTE_CONE ? "cone" : kind == SQ_ROUTE_FREE ? "free" : "sector");
        goto done;
    }
    st = emit_route(S, &R, endn, SRC, src, tgt, kind, path, npath, err);
#undef PUSH_FAIL
done:
    free(R.dist);
    free(R.pred);
    free(R.H.v);
    free(R.H.d);
    free(R.ring);
    free(fin);
    return st;
}

/* ---- routes through faces (Steiner vertices on crossed edges) ---------- */

static void centroid(const sq_tsurf *S, uint32_t f, double c[3])
{
    uint32_t h = S->f_he[f];
    c[0] = c[1] = c[2] = 0;
    for (int i = 0; i < 3; i++, h = S->next[h])
        for (int k = 0; k < 3; k++) c[k] += S->pos[3 * S->vert[h] + k] / 3;
}


/* Face routes: the goal faces, those whose vertex opposite the entry edge
 * may be the target (the target sector's fan; every face at a target
 * cone). */
static void mark_goals(const sq_tsurf *S, sq_route_target kind, int32_t target_valence, const uint8_t *cone_free,
                       uint32_t target_sector, uint8_t *goal)
{
    if (kind == SQ_ROUTE_SECTOR) {
        uint32_t g = target_sector;
        do {
            goal[S->face[g]] = 1;
            g = sq_ts_ccw(S, g);
        } while (!S->kind[g] && g != target_sector);
    } else if (kind == SQ_ROUTE_CONE) {
        for (uint32_t h = 0; h < S->nh; h++) {
            uint32_t v = S->vert[h];
            if (is_target_cone(S, v, target_valence, cone_free)) goal[S->face[h]] = 1;
        }
    }
}

/* The face route's crossed halfedges (cross, n of them) split in order at
 * their midpoints; the edge from the previous path vertex to each new one
 * exists after the split; then the edge to target (for a free route only
 * where nothing was crossed). The path's halfedges appended to *path
 * (*npath). */
static sq_status emit_face_route(sq_tsurf *S, const uint32_t *cross, uint32_t n, uint32_t src, uint32_t target,
                                 sq_route_target kind, uint32_t **path, uint32_t *npath, sq_error *err)
{
    uint32_t prev = src;
    uint32_t cnt = 0;
    uint32_t *p = realloc(*path, ((size_t)*npath + n + 1) * sizeof *p);
    if (!p) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
    *path = p;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t m = sq_tsurf_split_edge(S, cross[i], 0.5);
        if (m == SQ_NONE) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        /* find the halfedge prev -> m */
        uint32_t h0 = S->v_he[m], h = h0, found = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == prev) found = S->twin[h];
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        if (found == SQ_NONE) return sq_error_set(err, SQ_ERR_INTERNAL, "face route: no edge to Steiner vertex %u", m);
        p[*npath + cnt++] = found;
        prev = m;
    }
    if (kind != SQ_ROUTE_FREE || n == 0) {
        uint32_t h0 = S->v_he[prev], h = h0, found = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == target) found = h;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        if (found == SQ_NONE) return sq_error_set(err, SQ_ERR_INTERNAL, "face route: no edge to the target %u", target);
        p[*npath + cnt++] = found;
    }
    *npath += cnt;
    return SQ_OK;
}

sq_status sq_tsurf_route_faces(sq_tsurf *S, uint32_t start, sq_route_target kind,
                               int32_t target_valence, const uint8_t *cone_free,
                               double target_length, uint32_t target_sector, uint32_t **path,
                               uint32_t *npath, sq_error *err)
{
    assert(S->kind[start]);
    uint32_t nf = S->nf;
    double *dist = malloc((size_t)nf * sizeof *dist);
    uint32_t *pred = malloc((size_t)nf * sizeof *pred); /* halfedge crossed into f (in f) */
    uint8_t *goal = calloc(nf, 1);
    double *cen = malloc(3 * (size_t)nf * sizeof *cen);
    uint32_t *cross = NULL;
    heap H = {0};
    sq_status st = SQ_OK;
    if (!dist || !pred || !goal || !cen) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    for (uint32_t f = 0; f < nf; f++) dist[f] = INFINITY, pred[f] = SQ_NONE, centroid(S, f, cen + 3 * f);
    uint32_t src = S->vert[start];
    mark_goals(S, kind, target_valence, cone_free, target_sector, goal);
    /* Two passes. The search is over faces, so a face holding the target
     * that is first reached across an edge at the target is never entered
     * again across the edge opposite it, which the route must: where the
     * first pass finds nothing for that reason, the second enters such
     * faces only across that edge. */
    uint32_t endf = SQ_NONE;
    for (int strict = 0; strict < 2 && endf == SQ_NONE; strict++) {
    if (strict) {
        if (kind == SQ_ROUTE_FREE) break;
        for (uint32_t f = 0; f < nf; f++) dist[f] = INFINITY, pred[f] = SQ_NONE;
        H.n = 0;
    }
    /* start faces: the sector's fan; the first crossing is the edge
     * opposite src */
    {
        uint32_t g = start;
        do {
            uint32_t f = S->face[g];
            dist[f] = 0;
            pred[f] = SQ_NONE;
            if (heap_push(&H, f, 0)) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
                goto done;
            }
            g = sq_ts_ccw(S, g);
        } while (!S->kind[g] && g != start);
    }
    while (H.n) {
        uint32_t f;
        double d;
        heap_pop(&H, &f, &d);
        if (d > dist[f]) continue;
        if (pred[f] != SQ_NONE) {
            /* the target must be the vertex of f opposite the entry edge */
            uint32_t opp = S->vert[sq_ts_prev(S, pred[f])];
            int hit = 0;
            if (kind == SQ_ROUTE_SECTOR && goal[f] && opp == S->vert[target_sector]) hit = 1;
            if (kind == SQ_ROUTE_CONE && is_target_cone(S, opp, target_valence, cone_free)) hit = 1;
            if (kind == SQ_ROUTE_FREE && d >= target_length) hit = 1;
            if (hit) {
                endf = f;
                break;
            }
        }
        /* cross an uncut edge of f; from a start face only the edge
         * opposite src */
        uint32_t h = S->f_he[f];
        for (int i = 0; i < 3; i++, h = S->next[h]) {
            if (S->kind[h]) continue;
            if (pred[f] == SQ_NONE && (S->vert[h] == src || sq_ts_head(S, h) == src)) continue;
            if (pred[f] != SQ_NONE && h == pred[f]) continue;
            uint32_t t = S->twin[h], g = S->face[t];
            if (strict && goal[g]) {
                uint32_t opp = S->vert[sq_ts_prev(S, t)];
                if (kind == SQ_ROUTE_SECTOR ? opp != S->vert[target_sector]
                                            : !is_target_cone(S, opp, target_valence, cone_free))
                    continue;
            }
            double e = d + cdist(cen + 3 * f, cen + 3 * g);
            if (e < dist[g]) {
                dist[g] = e, pred[g] = t;
                if (heap_push(&H, g, e)) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
                    goto done;
                }
            }
        }
    }
    }
    if (endf == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "no route through faces from vertex %u", src);
        goto done;
    }
    /* the crossed halfedges, from the start */
    uint32_t n = 0;
    for (uint32_t f = endf; pred[f] != SQ_NONE; f = S->face[S->twin[pred[f]]]) n++;
    cross = malloc(((size_t)n + 1) * sizeof *cross);
    if (!cross) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    {
        uint32_t i = n;
        for (uint32_t f = endf; pred[f] != SQ_NONE; f = S->face[S->twin[pred[f]]]) cross[--i] = S->twin[pred[f]];
    }
    uint32_t target = S->vert[sq_ts_prev(S, pred[endf])];
    st = emit_face_route(S, cross, n, src, target, kind, path, npath, err);
done:
    free(dist);
    free(pred);
    free(goal);
    free(cen);
    free(cross);
    free(H.v);
    free(H.d);
    return st;
}


int64_t sq_tsurf_open_sector(sq_tsurf *S, uint32_t h)
{
    int64_t n = 0;
    uint32_t v = S->vert[h];
    if (!S->v_ncut[v]) return 0;
    /* edges strictly inside the sector leading to blocked vertices */
    uint32_t g = sq_ts_ccw(S, h);
    int inner = 0;
    while (!S->kind[g]) {
        inner = 1;
        uint32_t nx = sq_ts_ccw(S, g); /* computed before a split changes the fan */
        if (blocked(S, sq_ts_head(S, g))) {
            if (sq_tsurf_split_edge(S, g, 0.5) == SQ_NONE) return -1;
            n++;
            /* g now ends at the new vertex; the fan gained one edge after g */
        }
        g = nx;
    }
    if (!inner) { /* one face: open its opposite edge */
        uint32_t o = S->next[h];
        if (!S->kind[o]) {
            if (sq_tsurf_split_edge(S, o, 0.5) == SQ_NONE) return -1;
            n++;
        }
    }
    return n;
}

int64_t sq_tsurf_open_vertex(sq_tsurf *S, uint32_t v)
{
    int64_t n = 0;
    uint32_t h0 = S->v_he[v], h = h0;
    /* collect first: splits change the fan */
    uint32_t buf[64], k = 0;
    do {
        if (!S->kind[h] && blocked(S, sq_ts_head(S, h)) && k < 64) buf[k++] = h;
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    for (uint32_t i = 0; i < k; i++) {
        if (sq_tsurf_split_edge(S, buf[i], 0.5) == SQ_NONE) return -1;
        n++;
    }
    return n;
}
