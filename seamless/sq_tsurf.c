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
    free(S->face);
    free(S->v_he);
    free(S->kind);
    free(S->label);
    free(S->v_ncut);
    free(S->valence);
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
        S->cap_h = c;
    }
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
    S->v_he[m] = y0;
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

/* 1 if v has a neighbour on the cut */
static int near_cut(const sq_tsurf *S, uint32_t v)
{
    uint32_t h0 = S->v_he[v], h = h0;
    do {
        if (S->v_ncut[sq_ts_head(S, h)]) return 1;
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    return 0;
}

static double edge_len(const sq_tsurf *S, uint32_t a, uint32_t b)
{
    double x = S->pos[3 * a] - S->pos[3 * b], y = S->pos[3 * a + 1] - S->pos[3 * b + 1],
           z = S->pos[3 * a + 2] - S->pos[3 * b + 2];
    return sqrt(x * x + y * y + z * z);
}

sq_status sq_tsurf_route(const sq_tsurf *S, uint32_t start, sq_route_target kind,
                         int32_t target_valence, const uint8_t *cone_free, double target_length,
                         uint32_t target_sector, uint32_t **path, uint32_t *npath, sq_error *err)
{
    assert(S->kind[start]);
    uint32_t nv = S->nv;
    double *dist = malloc((size_t)nv * sizeof *dist);
    uint32_t *pred = malloc((size_t)nv * sizeof *pred); /* halfedge arriving */
    uint32_t *fin = calloc(nv, sizeof *fin);             /* target: final halfedge + 1 */
    heap H = {0};
    sq_status st = SQ_OK;
    if (!dist || !pred || !fin) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    for (uint32_t v = 0; v < nv; v++) dist[v] = INFINITY, pred[v] = SQ_NONE;
    uint32_t src = S->vert[start];
    /* sector target: vertices from which an edge strictly inside the sector
     * leads into its origin */
    if (kind == SQ_ROUTE_SECTOR) {
        for (uint32_t g = sq_ts_ccw(S, target_sector); !S->kind[g]; g = sq_ts_ccw(S, g))
            fin[sq_ts_head(S, g)] = S->twin[g] + 1;
    }
    uint32_t end = SQ_NONE, end_he = SQ_NONE;
    double best_far = -1;
    uint32_t far = SQ_NONE;
    /* first steps: edges strictly inside sector(start) */
    for (uint32_t g = sq_ts_ccw(S, start); !S->kind[g]; g = sq_ts_ccw(S, g)) {
        uint32_t w = sq_ts_head(S, g);
        double d = edge_len(S, src, w);
        if (kind == SQ_ROUTE_CONE && !S->v_ncut[w] && S->valence[w] == target_valence &&
            cone_free[w]) {
            if (end == SQ_NONE || d < dist[end]) {
                if (end != SQ_NONE) dist[end] = INFINITY;
                end = w, end_he = g, dist[w] = d;
            }
            continue;
        }
        if (S->v_ncut[w] || is_cone(S, w)) continue;
        if (d < dist[w]) {
            dist[w] = d, pred[w] = g;
            if (heap_push(&H, w, d)) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
                goto done;
            }
        }
    }
    double end_d = end != SQ_NONE ? dist[end] : INFINITY;
    while (H.n) {
        uint32_t v;
        double d;
        heap_pop(&H, &v, &d);
        if (d > dist[v]) continue;
        if (d >= end_d) break;
        if (kind == SQ_ROUTE_FREE) {
            if (d > best_far) best_far = d, far = v;
            if (d >= target_length) {
                end = v, end_he = SQ_NONE;
                break;
            }
        }
        if (kind == SQ_ROUTE_SECTOR && fin[v]) {
            /* the path ends here: v -> origin of the sector */
            end = S->vert[target_sector], end_he = fin[v] - 1;
            break;
        }
        uint32_t h0 = S->v_he[v], h = h0;
        do {
            uint32_t w = sq_ts_head(S, h);
            double e = d + edge_len(S, v, w);
            if (kind == SQ_ROUTE_CONE && !S->v_ncut[w] && S->valence[w] == target_valence &&
                cone_free[w]) {
                if (e < end_d) end = w, end_he = h, end_d = e;
            } else if (!S->v_ncut[w] && !is_cone(S, w) && (e += (near_cut(S, w) ? e - d : 0), e < dist[w])) {
                dist[w] = e, pred[w] = h;
                if (heap_push(&H, w, e)) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
                    goto done;
                }
            }
            h = sq_ts_ccw(S, h);
        } while (h != h0);
    }
    if (kind == SQ_ROUTE_FREE && end == SQ_NONE && far != SQ_NONE) end = far, end_he = SQ_NONE;
    if (end == SQ_NONE) {
        uint32_t nstart = 0, nfin = 0;
        for (uint32_t g = sq_ts_ccw(S, start); !S->kind[g]; g = sq_ts_ccw(S, g)) {
            uint32_t w = sq_ts_head(S, g);
            if (!S->v_ncut[w] && !is_cone(S, w)) nstart++;
        }
        if (kind == SQ_ROUTE_SECTOR)
            for (uint32_t g = sq_ts_ccw(S, target_sector); !S->kind[g]; g = sq_ts_ccw(S, g)) {
                uint32_t w = sq_ts_head(S, g);
                if (!S->v_ncut[w] && !is_cone(S, w)) nfin++;
            }
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "no path from vertex %u inside its sector to the %s target (%u free first "
                          "steps, %u free last steps)",
                          src, kind == SQ_ROUTE_CONE ? "cone" : kind == SQ_ROUTE_FREE ? "free" : "sector",
                          nstart, nfin);
        goto done;
    }
    /* collect backwards */
    uint32_t cnt = 0;
    uint32_t v = end_he != SQ_NONE ? S->vert[end_he] : end;
    if (end_he != SQ_NONE) cnt++;
    for (uint32_t u = v; u != src; u = S->vert[pred[u]]) cnt++;
    uint32_t *p = realloc(*path, ((size_t)*npath + cnt) * sizeof *p);
    if (!p) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    *path = p;
    uint32_t i = *npath + cnt;
    if (end_he != SQ_NONE) p[--i] = end_he;
    for (uint32_t u = v; u != src; u = S->vert[pred[u]]) p[--i] = pred[u];
    assert(i == *npath);
    *npath += cnt;
done:
    free(dist);
    free(pred);
    free(fin);
    free(H.v);
    free(H.d);
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

static double cdist(const double a[3], const double b[3])
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
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
    /* goals: faces whose vertex opposite the entry edge is the target */
    if (kind == SQ_ROUTE_SECTOR) {
        uint32_t g = target_sector;
        do {
            goal[S->face[g]] = 1;
            g = sq_ts_ccw(S, g);
        } while (!S->kind[g] && g != target_sector);
    } else if (kind == SQ_ROUTE_CONE) {
        for (uint32_t h = 0; h < S->nh; h++) {
            uint32_t v = S->vert[h];
            if (!S->v_ncut[v] && S->valence[v] == target_valence && cone_free[v]) goal[S->face[h]] = 1;
        }
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
    uint32_t endf = SQ_NONE;
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
            if (kind == SQ_ROUTE_CONE && !S->v_ncut[opp] && S->valence[opp] == target_valence &&
                cone_free[opp])
                hit = 1;
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
    /* split the crossed edges in order; the edge from the previous path
     * vertex to each new one exists after the split */
    uint32_t prev = src;
    uint32_t cnt = 0;
    uint32_t *p = realloc(*path, ((size_t)*npath + n + 1) * sizeof *p);
    if (!p) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
        goto done;
    }
    *path = p;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t m = sq_tsurf_split_edge(S, cross[i], 0.5);
        if (m == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (route)");
            goto done;
        }
        /* find the halfedge prev -> m */
        uint32_t h0 = S->v_he[m], h = h0, found = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == prev) found = S->twin[h];
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        if (found == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "face route: no edge to Steiner vertex %u", m);
            goto done;
        }
        p[*npath + cnt++] = found;
        prev = m;
    }
    if (kind != SQ_ROUTE_FREE || n == 0) {
        uint32_t h0 = S->v_he[prev], h = h0, found = SQ_NONE;
        do {
            if (sq_ts_head(S, h) == target) found = h;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        if (found == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "face route: no edge to the target %u", target);
            goto done;
        }
        p[*npath + cnt++] = found;
    }
    *npath += cnt;
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

static int blocked(const sq_tsurf *S, uint32_t w) { return S->v_ncut[w] || is_cone(S, w); }

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
