/* seamquad: the helpers of the sq_tsurf tests (test_tsurf.c,
 * test_tsurf_route.c): an independent check of the whole structure
 * (check_tsurf), snapshots to check what an operation changed, regions
 * and vertex paths for cuts. Test code only. */
#ifndef SQ_TEST_TSURF_H
#define SQ_TEST_TSURF_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sq_mesh.h"
#include "sq_test_mesh.h"
#include "sq_test_random.h"
#include "sq_tsurf.h"

static inline double urand(void) { return (double)(rng() >> 11) * (1.0 / 9007199254740992.0); }

/* ---- independent structure check ---------------------------------------- */

static inline double face_area(const sq_tsurf *S, uint32_t f)
{
    uint32_t h = S->f_he[f];
    const double *a = S->pos + 3 * S->vert[h], *b = S->pos + 3 * S->vert[S->next[h]],
                 *c = S->pos + 3 * S->vert[S->next[S->next[h]]];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static inline double total_area(const sq_tsurf *S)
{
    double A = 0;
    for (uint32_t f = 0; f < S->nf; f++) A += face_area(S, f);
    return A;
}

static inline int blocked_v(const sq_tsurf *S, uint32_t v) { return S->v_ncut[v] || S->valence[v] != 4; }

#define CHECK(c, ...)                                                                   \
    do {                                                                                \
        if (!(c)) fail_msg("check_tsurf: " __VA_ARGS__);                                 \
    } while (0)

/* Validates every invariant of the surface; euler and area0 are the values
 * of the input mesh (splits keep both). */
static inline void check_tsurf(const sq_tsurf *S, int64_t euler, double area0)
{
    CHECK(S->nh == 3 * S->nf, "nh %u != 3 nf %u", S->nh, S->nf);
    CHECK(S->nv <= S->cap_v && S->nf <= S->cap_f && S->nh <= S->cap_h, "count above capacity");
    CHECK((int64_t)S->nv - (int64_t)(S->nh / 2) + (int64_t)S->nf == euler, "Euler characteristic changed: %lld != %lld",
          (long long)((int64_t)S->nv - (int64_t)(S->nh / 2) + (int64_t)S->nf), (long long)euler);
    uint32_t *cnt = calloc(S->nf > S->nv ? S->nf : S->nv, sizeof *cnt);
    uint32_t *ncut = calloc(S->nv, sizeof *ncut);
    assert_non_null(cnt);
    assert_non_null(ncut);
    for (uint32_t h = 0; h < S->nh; h++) {
        uint32_t n = S->next[h], t = S->twin[h];
        CHECK(n < S->nh && t < S->nh && S->vert[h] < S->nv && S->face[h] < S->nf, "halfedge %u out of range", h);
        CHECK(n != h && S->next[S->next[n]] == h, "halfedge %u: next^3 != id", h);
        CHECK(S->face[n] == S->face[h], "halfedge %u: face differs along next", h);
        CHECK(t != h && S->twin[t] == h, "halfedge %u: twin(twin) != h", h);
        CHECK(S->vert[t] == S->vert[n] && S->vert[S->next[t]] == S->vert[h], "halfedge %u: twin endpoints not swapped", h);
        CHECK(S->vert[h] != S->vert[n], "halfedge %u is a loop", h);
        CHECK(S->face[t] != S->face[h], "halfedge %u and its twin in one face", h);
        CHECK(S->kind[h] <= SQ_TS_CHORD, "halfedge %u: kind %u", h, S->kind[h]);
        CHECK(S->kind[h] == S->kind[t], "halfedge %u: kind %u, twin %u", h, S->kind[h], S->kind[t]);
        if (!S->kind[h]) CHECK(S->label[h] == SQ_NONE, "uncut halfedge %u has label %u", h, S->label[h]);
        else ncut[S->vert[h]]++;
        cnt[S->face[h]]++;
    }
    for (uint32_t f = 0; f < S->nf; f++) {
        CHECK(cnt[f] == 3, "face %u has %u halfedges", f, cnt[f]);
        CHECK(S->f_he[f] < S->nh && S->face[S->f_he[f]] == f, "f_he[%u] invalid", f);
        CHECK(face_area(S, f) > 0, "face %u has zero area", f);
    }
    memset(cnt, 0, S->nv * sizeof *cnt);
    for (uint32_t h = 0; h < S->nh; h++) cnt[S->vert[h]]++;
    for (uint32_t v = 0; v < S->nv; v++) {
        CHECK(S->v_he[v] < S->nh && S->vert[S->v_he[v]] == v, "v_he[%u] does not leave it", v);
        CHECK(S->v_ncut[v] == ncut[v], "v_ncut[%u] = %u, counted %u", v, S->v_ncut[v], ncut[v]);
        uint32_t h0 = S->v_he[v], h = h0, k = 0;
        do {
            CHECK(S->vert[h] == v, "fan of %u leaves it", v);
            h = sq_ts_ccw(S, h);
            k++;
        } while (h != h0 && k <= cnt[v]);
        /* one closed fan holding every outgoing halfedge: manifold */
        CHECK(h == h0 && k == cnt[v] && k >= 3, "fan of vertex %u: %u of %u halfedges", v, k, cnt[v]);
        for (int i = 0; i < 3; i++) CHECK(isfinite(S->pos[3 * v + i]), "vertex %u not finite", v);
    }
    double A = total_area(S);
    CHECK(fabs(A - area0) <= 1e-12 * area0, "area %.17g != %.17g", A, area0);
    free(cnt);
    free(ncut);
}

/* ---- helpers -------------------------------------------------------------- */

typedef struct snap {
    uint32_t nv, nh;
    uint32_t *vert, *head;
    double *pos;
} snap;

static inline void snap_take(snap *s, const sq_tsurf *S)
{
    s->nv = S->nv, s->nh = S->nh;
    s->vert = malloc(S->nh * sizeof *s->vert);
    s->head = malloc(S->nh * sizeof *s->head);
    s->pos = malloc(3 * (size_t)S->nv * sizeof *s->pos);
    assert_true(s->vert && s->head && s->pos);
    for (uint32_t h = 0; h < S->nh; h++) s->vert[h] = S->vert[h], s->head[h] = sq_ts_head(S, h);
    memcpy(s->pos, S->pos, 3 * (size_t)S->nv * sizeof *s->pos);
}

static inline void snap_free(snap *s)
{
    free(s->vert), free(s->head), free(s->pos);
    memset(s, 0, sizeof *s);
}

/* s: parameter of point p on segment a->b; *off: distance from the line */
static inline double seg_param(const double *a, const double *b, const double *p, double *off)
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, q[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double s = (q[0] * d[0] + q[1] * d[1] + q[2] * d[2]) / dd;
    double r2 = 0;
    for (int i = 0; i < 3; i++) r2 += (q[i] - s * d[i]) * (q[i] - s * d[i]);
    *off = sqrt(r2 / dd);
    return s;
}

/* After any number of splits since the snapshot: every old halfedge keeps
 * its origin and its direction (its head on the old segment), and every
 * new vertex lies on the old segment of an old halfedge whose head it now
 * is. If mid, new vertices were made by midpoint splits of distinct old
 * edges: each new vertex is the head of exactly two old halfedges, twins
 * before, at the midpoint. */
static inline void check_since(const sq_tsurf *S, const snap *s, int mid)
{
    uint32_t *seen = calloc(S->nv, sizeof *seen);
    assert_non_null(seen);
    for (uint32_t h = 0; h < s->nh; h++) {
        CHECK(S->vert[h] == s->vert[h], "old halfedge %u changed origin %u -> %u", h, s->vert[h], S->vert[h]);
        uint32_t b = sq_ts_head(S, h);
        if (b == s->head[h]) continue;
        CHECK(b >= s->nv, "old halfedge %u now ends at old vertex %u (was %u)", h, b, s->head[h]);
        double off, t = seg_param(s->pos + 3 * s->vert[h], s->pos + 3 * s->head[h], S->pos + 3 * b, &off);
        CHECK(t > 0 && t < 1 && off < 1e-9, "old halfedge %u: head %u off its segment (t %g, off %g)", h, b, t, off);
        if (mid) CHECK(fabs(t - 0.5) < 1e-9, "Steiner vertex %u not a midpoint (t %g)", b, t);
        seen[b]++;
    }
    for (uint32_t v = s->nv; v < S->nv; v++) {
        if (mid) CHECK(seen[v] == 2, "new vertex %u is the head of %u old halfedges", v, seen[v]);
        else CHECK(seen[v] <= 2, "new vertex %u is the head of %u old halfedges", v, seen[v]);
    }
    free(seen);
}

/* Regions: faces connected across uncut edges. Returns their number. */
static inline uint32_t regions(const sq_tsurf *S, uint32_t *reg)
{
    uint32_t *q = malloc(S->nf * sizeof *q), n = 0;
    assert_non_null(q);
    for (uint32_t f = 0; f < S->nf; f++) reg[f] = SQ_NONE;
    for (uint32_t f0 = 0; f0 < S->nf; f0++) {
        if (reg[f0] != SQ_NONE) continue;
        uint32_t nq = 0;
        reg[f0] = n, q[nq++] = f0;
        for (uint32_t i = 0; i < nq; i++) {
            uint32_t h = S->f_he[q[i]];
            for (int k = 0; k < 3; k++, h = S->next[h]) {
                if (S->kind[h]) continue;
                uint32_t g = S->face[S->twin[h]];
                if (reg[g] == SQ_NONE) reg[g] = n, q[nq++] = g;
            }
        }
        n++;
    }
    free(q);
    return n;
}

/* Shortest path (edge lengths) from a to b over vertices for which ok[]
 * (a and b always allowed); returns the number of vertices, 0 if none. */
static inline uint32_t my_path(const sq_tsurf *S, uint32_t a, uint32_t b, const uint8_t *ok, uint32_t *out)
{
    uint32_t nv = S->nv;
    double *d = malloc(nv * sizeof *d);
    uint32_t *pr = malloc(nv * sizeof *pr);
    uint8_t *done = calloc(nv, 1);
    assert_true(d && pr && done);
    for (uint32_t v = 0; v < nv; v++) d[v] = INFINITY, pr[v] = SQ_NONE;
    d[a] = 0;
    for (;;) {
        uint32_t u = SQ_NONE;
        for (uint32_t v = 0; v < nv; v++)
            if (!done[v] && d[v] < INFINITY && (u == SQ_NONE || d[v] < d[u])) u = v;
        if (u == SQ_NONE || u == b) break;
        done[u] = 1;
        if (u != a && ok && !ok[u]) continue;
        uint32_t h0 = S->v_he[u], h = h0;
        do {
            uint32_t w = sq_ts_head(S, h);
            const double *p = S->pos + 3 * u, *q = S->pos + 3 * w;
            double l = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
            if (!S->kind[h] && (w == b || !ok || ok[w]) && d[u] + l < d[w]) d[w] = d[u] + l, pr[w] = u;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
    }
    uint32_t n = 0;
    if (d[b] < INFINITY) {
        for (uint32_t v = b; v != SQ_NONE; v = pr[v]) n++;
        uint32_t i = n;
        for (uint32_t v = b; v != SQ_NONE; v = pr[v]) out[--i] = v;
    }
    free(d), free(pr), free(done);
    return n;
}

static inline void cut_vertex_path(sq_tsurf *S, const uint32_t *p, uint32_t n, uint8_t kind)
{
    for (uint32_t i = 0; i + 1 < n; i++) {
        uint32_t h = sq_ts_find(S, p[i], p[i + 1]);
        assert_int_not_equal(h, SQ_NONE);
        sq_tsurf_cut_edge(S, h, kind, 7, 8);
    }
}

/* h strictly inside the sector named by the cut halfedge s */
static inline int strictly_inside(const sq_tsurf *S, uint32_t s, uint32_t h)
{
    uint32_t g = sq_ts_ccw(S, s);
    while (!S->kind[g]) {
        if (g == h) return 1;
        g = sq_ts_ccw(S, g);
    }
    return 0;
}

/* Walls: the star of vertex c is cut (every face at c is its own sector,
 * closed off by its link edge between two cut vertices), a path leads from
 * c away, and the second ring of c is made of blocking cones. A route out of
 * (or into) a sector of c must cross the link edge and then the wall of
 * cones by Steiner vertices. */
typedef struct walled {
    sq_mesh m;
    sq_tsurf S;
    int64_t euler;
    double area0;
    uint32_t c, far;  /* the star centre and the far end of its path */
    uint32_t nring2;
} walled;

static inline void walled_make(walled *W, const char *rel)
{
    sq_error err;
    sq_test_load_mesh(&W->m, rel);
    sq_tsurf_init(&W->S);
    assert_int_equal(sq_tsurf_from_mesh(&W->m, NULL, &W->S, NULL, &err), SQ_OK);
    sq_tsurf *S = &W->S;
    W->euler = sq_mesh_euler(&W->m);
    W->area0 = total_area(S);
    uint32_t c = W->c = rnd(S->nv);
    uint8_t *near = calloc(S->nv, 1), *ok = malloc(S->nv);
    uint32_t *vp = malloc(S->nv * sizeof *vp);
    assert_true(near && ok && vp);
    near[c] = 1;
    uint32_t h0 = S->v_he[c], h = h0;
    do {
        near[sq_ts_head(S, h)] = 1;
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    for (uint32_t v = 0; v < S->nv; v++) {
        if (!near[v] || v == c) continue;
        uint32_t g0 = S->v_he[v], g = g0;
        do {
            uint32_t w = sq_ts_head(S, g);
            if (!near[w]) near[w] = 2;
            g = sq_ts_ccw(S, g);
        } while (g != g0);
    }
    /* path from a ring-1 vertex to a vertex far away, avoiding rings 0-1 */
    for (uint32_t v = 0; v < S->nv; v++) ok[v] = near[v] != 1 && v != c;
    uint32_t n = 0, ha = h0;
    for (uint32_t tries = 0; n < 4; tries++) {
        if (tries % 8 == 7) ha = sq_ts_ccw(S, ha); /* another first vertex */
        assert_true(tries < 1000);
        W->far = rnd(S->nv);
        n = near[W->far] ? 0 : my_path(S, sq_ts_head(S, ha), W->far, ok, vp);
    }
    /* star of c */
    do {
        sq_tsurf_cut_edge(S, h, SQ_TS_SEAM, 3, 4);
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    cut_vertex_path(S, vp, n, SQ_TS_SEAM);
    /* ring 2 off the cut: blocking cones of valence 5 */
    W->nring2 = 0;
    for (uint32_t v = 0; v < S->nv; v++)
        if (near[v] == 2 && !S->v_ncut[v]) S->valence[v] = 5, W->nring2++;
    free(near), free(ok), free(vp);
    check_tsurf(S, W->euler, W->area0);
}

static inline void walled_free(walled *W)
{
    sq_tsurf_free(&W->S);
    sq_mesh_free(&W->m);
}

static inline void check_boundary(const sq_tsurf *S, const uint32_t *reg)
{
    uint32_t ncut = 0;
    uint32_t *pre = calloc(S->nh, sizeof *pre);
    uint8_t *vis = calloc(S->nh, 1);
    assert_true(pre && vis);
    for (uint32_t h = 0; h < S->nh; h++) {
        if (!S->kind[h]) continue;
        ncut++;
        uint32_t nb = sq_tsurf_next_boundary(S, h);
        assert_true(nb < S->nh && S->kind[nb]);
        assert_int_equal(S->vert[nb], sq_ts_head(S, h));
        assert_int_equal(reg[S->face[nb]], reg[S->face[h]]);
        assert_int_equal(nb, sq_tsurf_sector_of(S, S->next[h]));
        /* no cut edge strictly between twin(h) and nb, clockwise around the
         * head: nb is the first cut halfedge clockwise from next(h) */
        assert_true(nb == S->next[h] || strictly_inside(S, nb, S->next[h]));
        pre[nb]++;
    }
    /* a permutation of the cut halfedges whose orbits are closed loops */
    uint32_t total = 0;
    for (uint32_t h = 0; h < S->nh; h++) {
        if (!S->kind[h]) continue;
        assert_int_equal(pre[h], 1);
        if (vis[h]) continue;
        uint32_t g = h, len = 0;
        do {
            assert_false(vis[g]);
            vis[g] = 1;
            len++;
            g = sq_tsurf_next_boundary(S, g);
        } while (g != h && len <= ncut);
        assert_int_equal(g, h);
        total += len;
    }
    assert_int_equal(total, ncut);
    /* sectors */
    for (uint32_t h = 0; h < S->nh; h++) {
        uint32_t s = sq_tsurf_sector_of(S, h);
        if (!S->v_ncut[S->vert[h]]) {
            assert_int_equal(s, SQ_NONE);
            continue;
        }
        assert_true(s < S->nh && S->kind[s]);
        assert_int_equal(S->vert[s], S->vert[h]);
        assert_true(s == h || strictly_inside(S, s, h));
        assert_int_equal(reg[S->face[s]], reg[S->face[h]]);
        if (S->kind[h]) assert_int_equal(s, h);
    }
    free(pre), free(vis);
}

#endif
