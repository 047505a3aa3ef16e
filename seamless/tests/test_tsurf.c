/* Property tests of the editable triangle surface (sq_tsurf.h) on real
 * meshes of ../shared/data: random edge splits, cuts, region boundaries,
 * sectors, routes (with Steiner vertices through walls of blocked
 * vertices), opening of sectors and vertices, and blocking-edge splits.
 * Every operation is followed by an independent check of the whole
 * structure (check_tsurf). Seeded; SQ_LONG_TESTS=1 runs many more rounds. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_test_mesh.h"
#include "sq_test_random.h"
#include "sq_tsurf.h"

static double urand(void) { return (double)(rng() >> 11) * (1.0 / 9007199254740992.0); }

/* ---- independent structure check ---------------------------------------- */

static double face_area(const sq_tsurf *S, uint32_t f)
{
    uint32_t h = S->f_he[f];
    const double *a = S->pos + 3 * S->vert[h], *b = S->pos + 3 * S->vert[S->next[h]],
                 *c = S->pos + 3 * S->vert[S->next[S->next[h]]];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static double total_area(const sq_tsurf *S)
{
    double A = 0;
    for (uint32_t f = 0; f < S->nf; f++) A += face_area(S, f);
    return A;
}

static int blocked_v(const sq_tsurf *S, uint32_t v) { return S->v_ncut[v] || S->valence[v] != 4; }

#define CHECK(c, ...)                                                                   \
    do {                                                                                \
        if (!(c)) fail_msg("check_tsurf: " __VA_ARGS__);                                 \
    } while (0)

/* Validates every invariant of the surface; euler and area0 are the values
 * of the input mesh (splits keep both). */
static void check_tsurf(const sq_tsurf *S, int64_t euler, double area0)
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

static void snap_take(snap *s, const sq_tsurf *S)
{
    s->nv = S->nv, s->nh = S->nh;
    s->vert = malloc(S->nh * sizeof *s->vert);
    s->head = malloc(S->nh * sizeof *s->head);
    s->pos = malloc(3 * (size_t)S->nv * sizeof *s->pos);
    assert_true(s->vert && s->head && s->pos);
    for (uint32_t h = 0; h < S->nh; h++) s->vert[h] = S->vert[h], s->head[h] = sq_ts_head(S, h);
    memcpy(s->pos, S->pos, 3 * (size_t)S->nv * sizeof *s->pos);
}

static void snap_free(snap *s)
{
    free(s->vert), free(s->head), free(s->pos);
    memset(s, 0, sizeof *s);
}

/* s: parameter of point p on segment a->b; *off: distance from the line */
static double seg_param(const double *a, const double *b, const double *p, double *off)
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
static void check_since(const sq_tsurf *S, const snap *s, int mid)
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
static uint32_t regions(const sq_tsurf *S, uint32_t *reg)
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
static uint32_t my_path(const sq_tsurf *S, uint32_t a, uint32_t b, const uint8_t *ok, uint32_t *out)
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

static void cut_vertex_path(sq_tsurf *S, const uint32_t *p, uint32_t n, uint8_t kind)
{
    for (uint32_t i = 0; i + 1 < n; i++) {
        uint32_t h = sq_ts_find(S, p[i], p[i + 1]);
        assert_int_not_equal(h, SQ_NONE);
        sq_tsurf_cut_edge(S, h, kind, 7, 8);
    }
}

/* h strictly inside the sector named by the cut halfedge s */
static int strictly_inside(const sq_tsurf *S, uint32_t s, uint32_t h)
{
    uint32_t g = sq_ts_ccw(S, s);
    while (!S->kind[g]) {
        if (g == h) return 1;
        g = sq_ts_ccw(S, g);
    }
    return 0;
}

/* ---- 1. random splits ----------------------------------------------------- */

static void split_run(const char *rel, uint32_t nsplit)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    sq_tsurf_init(&S);
    uint32_t *he_map = malloc(m.nh * sizeof *he_map);
    assert_non_null(he_map);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, he_map, &err), SQ_OK);
    int64_t euler = sq_mesh_euler(&m);
    double area0 = total_area(&S);
    assert_true(area0 > 0);
    check_tsurf(&S, euler, area0);
    /* he_map and face order */
    for (uint32_t h = 0; h < m.nh; h++) {
        uint32_t g = he_map[h];
        assert_true(g < S.nh);
        assert_int_equal(S.vert[g], m.he_vert[h]);
        assert_int_equal(sq_ts_head(&S, g), m.he_vert[m.he_next[h]]);
        assert_int_equal(S.face[g], m.he_face[h]);
        assert_int_equal(S.twin[g], he_map[m.he_twin[h]]);
    }
    for (uint32_t f = 0; f < m.nf; f++) assert_int_equal(he_map[m.f_he[f]], 3 * f);
    for (uint32_t v = 0; v < S.nv; v++) assert_int_equal(S.valence[v], 4);

    /* cut ~6% of the edges, labelled by their original halfedges */
    uint32_t nh0 = S.nh;
    uint8_t *okind = calloc(nh0, 1);
    double *olen = malloc(nh0 * sizeof *olen), *clen = calloc(nh0, sizeof *clen);
    assert_true(okind && olen && clen);
    for (uint32_t h = 0; h < nh0; h++) {
        if (rnd(33) || S.kind[h]) continue;
        uint8_t k = rnd(2) ? SQ_TS_SEAM : SQ_TS_CHORD;
        sq_tsurf_cut_edge(&S, h, k, h, S.twin[h]);
        okind[h] = okind[S.twin[h]] = k;
    }
    /* re-cutting keeps v_ncut (cut_edge on a cut edge only relabels) */
    for (uint32_t h = 0; h < nh0; h++)
        if (okind[h] && rnd(10) == 0) sq_tsurf_cut_edge(&S, h, okind[h], h, S.twin[h]);
    check_tsurf(&S, euler, area0);
    snap s0;
    snap_take(&s0, &S);
    for (uint32_t h = 0; h < nh0; h++) {
        double off;
        (void)off;
        const double *a = S.pos + 3 * s0.vert[h], *b = S.pos + 3 * s0.head[h];
        olen[h] = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }

    for (uint32_t it = 0; it < nsplit; it++) {
        /* bias towards cut edges, so that cut state is split often */
        uint32_t h = rnd(S.nh);
        if (rnd(3) == 0)
            for (uint32_t k = 0; k < 20 && !S.kind[h]; k++) h = rnd(S.nh);
        double t = 0.05 + 0.9 * urand();
        uint32_t g = S.twin[h], a = S.vert[h], b = sq_ts_head(&S, h), c = S.vert[sq_ts_prev(&S, h)],
                 d = S.vert[sq_ts_prev(&S, g)];
        uint8_t kh = S.kind[h];
        uint32_t lh = S.label[h], lg = S.label[g], nv = S.nv, ncut_a = S.v_ncut[a], ncut_b = S.v_ncut[b];
        double pa[3], pb[3];
        memcpy(pa, S.pos + 3 * a, sizeof pa);
        memcpy(pb, S.pos + 3 * b, sizeof pb);
        uint32_t mv = sq_tsurf_split_edge(&S, h, t);
        assert_int_equal(mv, nv);
        assert_int_equal(S.nv, nv + 1);
        for (int i = 0; i < 3; i++) assert_true(fabs(S.pos[3 * mv + i] - ((1 - t) * pa[i] + t * pb[i])) <= 1e-12 * (1 + fabs(pa[i]) + fabs(pb[i])));
        /* h keeps its origin and direction; the two halves and their state */
        assert_int_equal(S.vert[h], a);
        assert_int_equal(sq_ts_head(&S, h), mv);
        assert_int_equal(S.vert[g], b);
        assert_int_equal(sq_ts_head(&S, g), mv);
        uint32_t h2 = sq_ts_find(&S, mv, b), g2 = S.twin[h];
        assert_int_equal(S.twin[h2], g);
        assert_int_equal(sq_ts_head(&S, g2), a);
        assert_int_equal(S.kind[h2], kh);
        assert_int_equal(S.kind[g2], kh);
        assert_int_equal(S.label[h2], lh);
        assert_int_equal(S.label[g2], lg);
        assert_int_equal(S.v_ncut[mv], kh ? 2u : 0u);
        assert_int_equal(S.v_ncut[a], ncut_a);
        assert_int_equal(S.v_ncut[b], ncut_b);
        assert_int_equal(S.valence[mv], 4);
        /* the new vertex sees a, b, c, d and nothing else */
        assert_int_not_equal(sq_ts_find(&S, mv, c), SQ_NONE);
        assert_int_not_equal(sq_ts_find(&S, mv, d), SQ_NONE);
        assert_int_equal(sq_ts_find(&S, a, b), SQ_NONE);
        uint32_t deg = 0, x = S.v_he[mv];
        do deg++, x = sq_ts_ccw(&S, x);
        while (x != S.v_he[mv]);
        assert_int_equal(deg, 4);
        if (it % 97 == 0) check_tsurf(&S, euler, area0);
    }
    check_tsurf(&S, euler, area0);
    check_since(&S, &s0, 0);
    /* cut pieces: on the segment of their label, same direction, same kind,
     * and together exactly the original edge */
    for (uint32_t x = 0; x < S.nh; x++) {
        if (!S.kind[x]) continue;
        uint32_t L = S.label[x];
        assert_true(L < nh0);
        assert_int_equal(okind[L], S.kind[x]);
        const double *a = s0.pos + 3 * s0.vert[L], *b = s0.pos + 3 * s0.head[L];
        double o1, o2, s1 = seg_param(a, b, S.pos + 3 * S.vert[x], &o1),
                       s2 = seg_param(a, b, S.pos + 3 * sq_ts_head(&S, x), &o2);
        assert_true(o1 < 1e-9 && o2 < 1e-9);
        assert_true(s1 > -1e-12 && s2 < 1 + 1e-12 && s2 > s1);
        clen[L] += (s2 - s1) * olen[L];
    }
    for (uint32_t h = 0; h < nh0; h++) {
        if (okind[h]) assert_true(fabs(clen[h] - olen[h]) <= 1e-9 * olen[h]);
        else assert_true(clen[h] == 0);
    }
    /* twin labels: a cut piece labelled L has a twin labelled twin0(L) */
    for (uint32_t x = 0; x < S.nh; x++) {
        if (!S.kind[x]) continue;
        uint32_t L = S.label[x], Lt = S.label[S.twin[x]];
        assert_true(Lt < nh0);
        assert_int_equal(s0.vert[Lt], s0.head[L]);
        assert_int_equal(s0.head[Lt], s0.vert[L]);
    }
    /* forig: every face lies in the input face it names, oriented like it,
     * and the faces of each input face add up to its area */
    double *farea = calloc(m.nf, sizeof *farea);
    assert_non_null(farea);
    for (uint32_t f = 0; f < S.nf; f++) {
        uint32_t F = S.forig[f], e = m.f_he[F];
        assert_true(F < m.nf);
        const double *q[3];
        for (int i = 0; i < 3; i++, e = m.he_next[e]) q[i] = m.pos + 3 * (size_t)m.he_vert[e];
        double n[3], u[3] = {q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]},
                     w[3] = {q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2]};
        n[0] = u[1] * w[2] - u[2] * w[1], n[1] = u[2] * w[0] - u[0] * w[2], n[2] = u[0] * w[1] - u[1] * w[0];
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        uint32_t h = S.f_he[f];
        const double *p[3];
        for (int i = 0; i < 3; i++, h = S.next[h]) p[i] = S.pos + 3 * (size_t)S.vert[h];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                /* on the inner side of input edge k (relative to its area) */
                const double *a = q[k], *b = q[(k + 1) % 3];
                double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap[3] = {p[i][0] - a[0], p[i][1] - a[1], p[i][2] - a[2]};
                double cx = ab[1] * ap[2] - ab[2] * ap[1], cy = ab[2] * ap[0] - ab[0] * ap[2], cz = ab[0] * ap[1] - ab[1] * ap[0];
                assert_true((cx * n[0] + cy * n[1] + cz * n[2]) / nn >= -1e-9 * nn);
            }
        double g1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]},
               g2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double t[3] = {g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]};
        assert_true(t[0] * n[0] + t[1] * n[1] + t[2] * n[2] > 0);
        farea[F] += 0.5 * sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    }
    for (uint32_t F = 0; F < m.nf; F++) {
        uint32_t e = m.f_he[F];
        const double *q0 = m.pos + 3 * (size_t)m.he_vert[e], *q1 = m.pos + 3 * (size_t)m.he_vert[m.he_next[e]],
                     *q2 = m.pos + 3 * (size_t)m.he_vert[m.he_next[m.he_next[e]]];
        double u[3] = {q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]}, w[3] = {q2[0] - q0[0], q2[1] - q0[1], q2[2] - q0[2]};
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
        double a = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
        assert_true(fabs(farea[F] - a) <= 1e-9 * a);
    }
    free(farea);
    snap_free(&s0);
    free(okind), free(olen), free(clen), free(he_map);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_split_random(void **state)
{
    (void)state;
    rng_state = 0x75A1;
    int L = long_mode();
    split_run("mpz/knot1.obj", L ? 20000 : 1500);
    split_run("mpz/eight.obj", L ? 30000 : 2500);
    if (L) split_run("libigl/bunny.off", 30000);
}

/* sq_tsurf_copy: a deep copy, equal array by array (forig too), that then changes
 * independently of its source (the refinement rounds of sq_param restore
 * the surface from one). */
static void assert_tsurf_equal(const sq_tsurf *a, const sq_tsurf *b)
{
    assert_true(a->nv == b->nv && a->nf == b->nf && a->nh == b->nh && a->nv_input == b->nv_input);
    assert_memory_equal(a->pos, b->pos, 3 * (size_t)a->nv * sizeof *a->pos);
    assert_memory_equal(a->v_he, b->v_he, a->nv * sizeof *a->v_he);
    assert_memory_equal(a->v_ncut, b->v_ncut, a->nv * sizeof *a->v_ncut);
    assert_memory_equal(a->valence, b->valence, a->nv * sizeof *a->valence);
    assert_memory_equal(a->f_he, b->f_he, a->nf * sizeof *a->f_he);
    assert_memory_equal(a->forig, b->forig, a->nf * sizeof *a->forig);
    assert_memory_equal(a->vert, b->vert, a->nh * sizeof *a->vert);
    assert_memory_equal(a->next, b->next, a->nh * sizeof *a->next);
    assert_memory_equal(a->face, b->face, a->nh * sizeof *a->face);
    assert_memory_equal(a->twin, b->twin, a->nh * sizeof *a->twin);
    assert_memory_equal(a->kind, b->kind, a->nh * sizeof *a->kind);
    assert_memory_equal(a->label, b->label, a->nh * sizeof *a->label);
}

static void test_copy(void **state)
{
    (void)state;
    rng_state = 0xC0B1;
    sq_mesh m;
    sq_tsurf S, A, B;
    sq_error err;
    sq_test_load_mesh(&m, "mpz/knot1.obj");
    sq_tsurf_init(&S), sq_tsurf_init(&A), sq_tsurf_init(&B);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
    for (uint32_t i = 0; i < 300; i++) {
        uint32_t h = rnd(S.nh);
        if (rnd(2)) sq_tsurf_cut_edge(&S, h, SQ_TS_SEAM, h, S.twin[h]);
        else assert_int_not_equal(sq_tsurf_split_edge(&S, h, 0.5), SQ_NONE);
    }
    double area = total_area(&S);
    assert_int_equal(sq_tsurf_copy(&A, &S), 0);
    assert_tsurf_equal(&A, &S);
    assert_int_equal(sq_tsurf_copy(&B, &S), 0);
    /* the copy grows and cuts on its own; the source stays as it was */
    for (uint32_t i = 0; i < 300; i++) {
        uint32_t h = rnd(A.nh);
        if (rnd(2)) sq_tsurf_cut_edge(&A, h, SQ_TS_CHORD, h, A.twin[h]);
        else assert_int_not_equal(sq_tsurf_split_edge(&A, h, 0.25), SQ_NONE);
    }
    assert_true(A.nv > S.nv);
    check_tsurf(&A, sq_mesh_euler(&m), area);
    assert_tsurf_equal(&B, &S);
    /* copying over a used surface replaces it */
    assert_int_equal(sq_tsurf_copy(&A, &S), 0);
    assert_tsurf_equal(&A, &S);
    sq_tsurf_free(&S), sq_tsurf_free(&A), sq_tsurf_free(&B);
    sq_mesh_free(&m);
}

static void test_from_mesh_rejects_polygons(void **state)
{
    (void)state;
    /* a closed quad mesh (cube) must be refused, not copied */
    static const char cube[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    sq_soup soup;
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    memset(&soup, 0, sizeof soup);
    assert_int_equal(sq_parse_obj(cube, sizeof cube - 1, "cube.obj", &soup, &err), SQ_OK);
    assert_int_equal(sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &m, &err), SQ_OK);
    sq_tsurf_init(&S);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_ERR_ARGUMENT);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
    sq_soup_free(&soup);
}

/* ---- 2. region boundaries and sectors ------------------------------------ */

static void check_boundary(const sq_tsurf *S, const uint32_t *reg)
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

static void boundary_run(const char *rel, uint32_t trials)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    sq_tsurf_init(&S);
    int64_t euler = sq_mesh_euler(&m);
    for (uint32_t tr = 0; tr < trials; tr++) {
        assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
        double area0 = total_area(&S);
        /* a face-connected patch grown from a random face */
        uint32_t want = 3 + rnd(120);
        uint8_t *in = calloc(S.nf, 1);
        uint32_t *q = malloc(S.nf * sizeof *q), nq = 0;
        assert_true(in && q);
        q[nq++] = rnd(S.nf), in[q[0]] = 1;
        for (uint32_t i = 0; i < nq && nq < want; i++) {
            uint32_t h = S.f_he[q[i]];
            for (int k = 0; k < 3 && nq < want; k++, h = S.next[h]) {
                uint32_t f = S.face[S.twin[h]];
                if (!in[f] && rnd(4)) in[f] = 1, q[nq++] = f;
            }
        }
        uint32_t nbd = 0;
        for (uint32_t h = 0; h < S.nh; h++)
            if (in[S.face[h]] && !in[S.face[S.twin[h]]]) {
                sq_tsurf_cut_edge(&S, h, SQ_TS_SEAM, 1, 2);
                nbd++;
            }
        check_tsurf(&S, euler, area0);
        uint32_t *reg = malloc(S.cap_f * sizeof *reg);
        assert_non_null(reg);
        /* the patch is one region; its complement may fall into several */
        uint32_t nr = regions(&S, reg);
        assert_true(nr >= 2);
        uint32_t rin = reg[q[0]];
        for (uint32_t f = 0; f < S.nf; f++) assert_int_equal(reg[f] == rin, in[f]);
        check_boundary(&S, reg);
        /* the loops around the patch hold exactly its boundary edges */
        uint32_t around = 0;
        for (uint32_t h = 0; h < S.nh; h++) around += S.kind[h] && reg[S.face[h]] == rin;
        assert_int_equal(around, nbd);
        /* splits (of cut edges, too) keep all of it; the loops grow */
        uint32_t nsp = 20 + rnd(60), cut_splits = 0;
        for (uint32_t i = 0; i < nsp; i++) {
            uint32_t h = rnd(S.nh);
            if (rnd(2))
                for (uint32_t k = 0; k < 40 && !S.kind[h]; k++) h = rnd(S.nh);
            cut_splits += S.kind[h] != 0;
            assert_int_not_equal(sq_tsurf_split_edge(&S, h, 0.05 + 0.9 * urand()), SQ_NONE);
        }
        check_tsurf(&S, euler, area0);
        reg = realloc(reg, S.nf * sizeof *reg);
        assert_int_equal(regions(&S, reg), nr);
        check_boundary(&S, reg);
        around = 0;
        for (uint32_t h = 0; h < S.nh; h++) around += S.kind[h] && reg[S.face[h]] == reg[q[0]];
        assert_int_equal(around, nbd + cut_splits);
        free(reg), free(in), free(q);
    }
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_boundary_loops(void **state)
{
    (void)state;
    rng_state = 0xB0B;
    int L = long_mode();
    boundary_run("mpz/knot1.obj", L ? 300 : 20);
    boundary_run("mpz/eight.obj", L ? 300 : 15);
}

/* ---- 3. routes ------------------------------------------------------------- */

/* Routes from start and checks the returned path; returns SQ_OK or the
 * route's status (the path is then not checked). */
static sq_status route_checked(sq_tsurf *S, uint32_t start, sq_route_target kind, int32_t tval,
                               const uint8_t *cone_free, double tlen, uint32_t tsec, uint32_t **path,
                               uint32_t *npath, sq_error *err)
{
    snap s;
    snap_take(&s, S);
    uint8_t *blk = malloc(S->nv);
    assert_non_null(blk);
    for (uint32_t v = 0; v < S->nv; v++) blk[v] = (uint8_t)blocked_v(S, v);
    uint32_t src = S->vert[start], tgt = kind == SQ_ROUTE_SECTOR ? S->vert[tsec] : SQ_NONE;
    *npath = 0;
    sq_status st = sq_tsurf_route(S, start, kind, tval, cone_free, tlen, tsec, path, npath, err);
    if (st != SQ_OK) {
        if (getenv("TSURF_DEBUG") && tgt != SQ_NONE) {
            uint32_t e = sq_ts_find(S, src, tgt);
            fprintf(stderr, "src %u tgt %u adjacent %d cut %d; nv %u (was %u)\n", src, tgt, e != SQ_NONE, e != SQ_NONE && S->kind[e], S->nv, s.nv);
            for (uint32_t v = s.nv; v < S->nv; v++) {
                uint32_t g0 = S->v_he[v], g = g0;
                fprintf(stderr, "  new %u:", v);
                do fprintf(stderr, " %u%s", sq_ts_head(S, g), blocked_v(S, sq_ts_head(S, g)) ? "*" : ""), g = sq_ts_ccw(S, g);
                while (g != g0);
                fprintf(stderr, "\n");
            }
        }
        snap_free(&s);
        free(blk);
        return st;
    }
    uint32_t n = *npath;
    const uint32_t *p = *path;
    assert_true(n >= 1);
    check_since(S, &s, 1);
    assert_int_equal(S->vert[p[0]], src);
    assert_true(strictly_inside(S, start, p[0]));
    uint8_t *on = calloc(S->nv, 1);
    assert_non_null(on);
    on[src] = 1;
    for (uint32_t i = 0; i < n; i++) {
        assert_true(p[i] < S->nh);
        assert_int_equal(S->kind[p[i]], SQ_TS_UNCUT);
        if (i) assert_int_equal(S->vert[p[i]], sq_ts_head(S, p[i - 1]));
        uint32_t w = sq_ts_head(S, p[i]);
        if (on[w]) fail_msg("route repeats vertex %u", w);
        on[w] = 1;
        int last = i + 1 == n;
        if (!last || kind == SQ_ROUTE_FREE) {
            /* inner vertices (and a free end): off the cut, no cone, and
             * either new (Steiner) or unblocked before the route */
            assert_int_equal(S->v_ncut[w], 0);
            assert_int_equal(S->valence[w], 4);
            if (w < s.nv && blk[w]) fail_msg("route passes through vertex %u, blocked before", w);
        }
    }
    uint32_t end = sq_ts_head(S, p[n - 1]);
    if (kind == SQ_ROUTE_SECTOR) {
        assert_int_equal(end, tgt);
        assert_true(strictly_inside(S, tsec, S->twin[p[n - 1]]));
    } else if (kind == SQ_ROUTE_CONE) {
        assert_int_equal(S->v_ncut[end], 0);
        assert_int_equal(S->valence[end], tval);
        assert_true(cone_free[end]);
    }
    free(on);
    free(blk);
    snap_free(&s);
    return SQ_OK;
}

/* a random sector of region r whose origin differs from `not` */
static uint32_t random_sector(const sq_tsurf *S, const uint32_t *reg, uint32_t r, uint32_t not)
{
    uint32_t n = 0, pick = SQ_NONE;
    for (uint32_t h = 0; h < S->nh; h++)
        if (S->kind[h] && reg[S->face[h]] == r && S->vert[h] != not && rnd(++n) == 0) pick = h;
    return pick;
}

/* genus 0: a random cut path, then chords by SECTOR routes, each splitting
 * its region in two */
static void route_sector_run(const char *rel, uint32_t rounds)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    assert_int_equal(sq_mesh_euler(&m), 2);
    sq_tsurf_init(&S);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
    int64_t euler = 2;
    double area0 = total_area(&S);
    uint32_t *vp = malloc(S.nv * sizeof *vp);
    assert_non_null(vp);
    uint32_t a = rnd(S.nv), b;
    do b = rnd(S.nv);
    while (b == a);
    uint32_t n = my_path(&S, a, b, NULL, vp);
    assert_true(n >= 2);
    cut_vertex_path(&S, vp, n, SQ_TS_SEAM);
    free(vp);
    check_tsurf(&S, euler, area0);
    uint32_t *reg = NULL, *path = NULL, npath = 0, want = 1, failed = 0, gap = 0;
    char first[1400] = "";
    for (uint32_t r = 0; r < rounds; r++) {
        reg = realloc(reg, S.nf * sizeof *reg);
        assert_non_null(reg);
        uint32_t nr = regions(&S, reg);
        assert_int_equal(nr, want);
        /* a region with two distinct boundary vertices, at random */
        uint32_t s1 = SQ_NONE, s2 = SQ_NONE;
        for (int tries = 0; tries < 50 && s2 == SQ_NONE; tries++) {
            s1 = random_sector(&S, reg, reg[rnd(S.nf)], SQ_NONE);
            if (s1 != SQ_NONE) s2 = random_sector(&S, reg, reg[S.face[s1]], S.vert[s1]);
        }
        assert_int_not_equal(s2, SQ_NONE);
        uint32_t v1 = S.vert[s1], v2 = S.vert[s2];
        sq_status st = route_checked(&S, s1, SQ_ROUTE_SECTOR, 0, NULL, 0, s2, &path, &npath, &err);
        /* a failed route must leave a valid surface behind */
        check_tsurf(&S, euler, area0);
        if (st != SQ_OK) {
            /* known gap (docs/param.md): two ends joined by a cut edge,
             * whose only route would run through the face on that edge */
            uint32_t e = sq_ts_find(&S, v1, v2);
            if (e != SQ_NONE && S.kind[e]) {
                gap++;
                continue;
            }
            if (!failed++) snprintf(first, sizeof first, "round %u: %u -> %u: %s", r, v1, v2, err.msg);
            continue;
        }
        for (uint32_t i = 0; i < npath; i++) sq_tsurf_cut_edge(&S, path[i], SQ_TS_SEAM, 100 + r, 200 + r);
        check_tsurf(&S, euler, area0);
        want++; /* a chord of a disk splits it */
    }
    reg = realloc(reg, S.nf * sizeof *reg);
    assert_int_equal(regions(&S, reg), want);
    check_boundary(&S, reg);
    if (failed) fail_msg("%s: %u of %u SECTOR routes failed; first: %s", rel, failed, rounds, first);
    assert_true(gap <= rounds / 10);
    free(reg), free(path);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_route_sector(void **state)
{
    (void)state;
    rng_state = 0x5EC7;
    int L = long_mode();
    route_sector_run("libigl/decimated-knight.off", L ? 150 : 40);
    for (int i = 0; i < (L ? 20 : 4); i++) route_sector_run("libigl/decimated-knight.off", L ? 60 : 15);
    route_sector_run("libigl/bumpy.off", L ? 300 : 30);
}

/* cones of a Th_hat file: a cut path, then CONE and FREE routes */
static void route_cone_run(const char *rel, const char *cones, uint32_t rounds)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    int32_t *val = sq_test_load_valence(cones, m.nv);
    sq_tsurf_init(&S);
    assert_int_equal(sq_tsurf_from_mesh(&m, val, &S, NULL, &err), SQ_OK);
    for (uint32_t v = 0; v < m.nv; v++) assert_int_equal(S.valence[v], val[v]);
    int64_t euler = sq_mesh_euler(&m);
    double area0 = total_area(&S);
    uint8_t *ok = malloc(S.nv), *cone_free = NULL;
    uint32_t *vp = malloc(S.nv * sizeof *vp);
    assert_true(ok && vp);
    for (uint32_t v = 0; v < S.nv; v++) ok[v] = val[v] == 4;
    uint32_t a, b, n;
    do {
        a = rnd(S.nv), b = rnd(S.nv);
        n = (a != b && ok[a] && ok[b]) ? my_path(&S, a, b, ok, vp) : 0;
    } while (n < 2);
    cut_vertex_path(&S, vp, n, SQ_TS_SEAM);
    check_tsurf(&S, euler, area0);
    double diag = 0;
    for (int k = 0; k < 3; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (uint32_t v = 0; v < S.nv; v++) lo = fmin(lo, S.pos[3 * v + k]), hi = fmax(hi, S.pos[3 * v + k]);
        diag += (hi - lo) * (hi - lo);
    }
    diag = sqrt(diag);
    uint32_t *path = NULL, npath = 0;
    for (uint32_t r = 0; r < rounds; r++) {
        /* the start: a random sector of the cut */
        uint32_t s1;
        do s1 = rnd(S.nh);
        while (!S.kind[s1]);
        if (r % 2 == 0) {
            /* the valence of a random cone still off the cut */
            cone_free = realloc(cone_free, S.nv);
            assert_non_null(cone_free);
            uint32_t c = SQ_NONE, k = 0;
            for (uint32_t v = 0; v < S.nv; v++) {
                cone_free[v] = (uint8_t)(rnd(4) != 0);
                if (S.valence[v] != 4 && !S.v_ncut[v] && cone_free[v] && rnd(++k) == 0) c = v;
            }
            if (c == SQ_NONE) continue;
            sq_status st = route_checked(&S, s1, SQ_ROUTE_CONE, S.valence[c], cone_free, 0, 0, &path, &npath, &err);
            if (st != SQ_OK) fail_msg("%s: round %u: CONE route from %u failed: %s", rel, r, S.vert[s1], err.msg);
        } else {
            double len = urand() * 0.3 * diag;
            sq_status st = route_checked(&S, s1, SQ_ROUTE_FREE, 0, NULL, len, 0, &path, &npath, &err);
            if (st != SQ_OK) fail_msg("%s: round %u: FREE route from %u failed: %s", rel, r, S.vert[s1], err.msg);
        }
        check_tsurf(&S, euler, area0);
        for (uint32_t i = 0; i < npath; i++) sq_tsurf_cut_edge(&S, path[i], SQ_TS_SEAM, r, r);
        check_tsurf(&S, euler, area0);
    }
    free(path), free(cone_free), free(ok), free(vp), free(val);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_route_cone_free(void **state)
{
    (void)state;
    rng_state = 0xC0DE;
    int L = long_mode();
    route_cone_run("mpz/eight.obj", "mpz/eight_Th_hat", L ? 60 : 12);
    route_cone_run("mpz/knot1.obj", "mpz/knot1_Th_hat", L ? 60 : 12);
    if (L)
        for (int i = 0; i < 10; i++) route_cone_run("mpz/helmet.obj", "mpz/helmet_Th_hat", 40);
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

static void walled_make(walled *W, const char *rel)
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

static void walled_free(walled *W)
{
    sq_tsurf_free(&W->S);
    sq_mesh_free(&W->m);
}

static void test_route_walls(void **state)
{
    (void)state;
    rng_state = 0x3A11;
    int trials = long_mode() ? 200 : 12;
    const char *meshes[] = {"libigl/decimated-knight.off", "libigl/bumpy.off"};
    uint32_t *path = NULL, npath = 0, *reg = NULL;
    sq_error err;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, meshes[tr % 2 ? 1 : 0]);
        sq_tsurf *S = &W.S;
        reg = realloc(reg, S->cap_f * sizeof *reg);
        assert_int_equal(regions(S, reg), 1);
        /* out of a one-face sector of c to the far end of the path */
        uint32_t s1 = S->v_he[W.c];
        for (uint32_t k = rnd(8); k; k--) s1 = sq_ts_ccw(S, s1);
        uint32_t s2 = S->v_he[W.far];
        while (!S->kind[s2]) s2 = sq_ts_ccw(S, s2);
        uint32_t nv0 = S->nv;
        int out = tr % 2 == 0;
        sq_status st = out ? route_checked(S, s1, SQ_ROUTE_SECTOR, 0, NULL, 0, s2, &path, &npath, &err)
                           : route_checked(S, s2, SQ_ROUTE_SECTOR, 0, NULL, 0, s1, &path, &npath, &err);
        if (st != SQ_OK) fail_msg("walled trial %d (%s): route failed: %s", tr, out ? "out of the star" : "into the star", err.msg);
        /* the link edge and the cone wall need Steiner vertices */
        assert_true(S->nv >= nv0 + 1 + (W.nring2 ? 1u : 0u));
        check_tsurf(S, W.euler, W.area0);
        for (uint32_t i = 0; i < npath; i++) sq_tsurf_cut_edge(S, path[i], SQ_TS_SEAM, 9, 9);
        check_tsurf(S, W.euler, W.area0);
        reg = realloc(reg, S->nf * sizeof *reg);
        assert_int_equal(regions(S, reg), 2);
        check_boundary(S, reg);
        walled_free(&W);
    }
    free(path), free(reg);
}

/* A CONE route through a wall: the target cone's whole ring is blocked (on
 * the cut or cones of another valence), so the route must end by a Steiner
 * vertex on the edge opposite the cone. */
static void test_route_cone_walled(void **state)
{
    (void)state;
    rng_state = 0xFACE;
    int trials = long_mode() ? 200 : 12;
    uint32_t *path = NULL, npath = 0;
    sq_error err;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, tr % 2 ? "libigl/bumpy.off" : "libigl/decimated-knight.off");
        sq_tsurf *S = &W.S;
        /* the target: a random vertex far from c, with its ring blocked */
        uint32_t c2;
        for (uint32_t tries = 0;; tries++) {
            assert_true(tries < 100000);
            c2 = rnd(S->nv);
            if (S->v_ncut[c2] || S->valence[c2] != 4) continue;
            int bad = 0;
            uint32_t h0 = S->v_he[c2], h = h0;
            do {
                uint32_t w = sq_ts_head(S, h);
                bad |= S->valence[w] != 4 || w == W.c;
                h = sq_ts_ccw(S, h);
            } while (h != h0);
            if (!bad) break;
        }
        S->valence[c2] = 3;
        uint32_t h0 = S->v_he[c2], h = h0;
        do {
            uint32_t w = sq_ts_head(S, h);
            if (!S->v_ncut[w]) S->valence[w] = 6;
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        uint8_t *cone_free = malloc(S->nv);
        assert_non_null(cone_free);
        memset(cone_free, 1, S->nv);
        uint32_t s1 = S->v_he[W.far];
        while (!S->kind[s1]) s1 = sq_ts_ccw(S, s1);
        uint32_t nv0 = S->nv;
        sq_status st = route_checked(S, s1, SQ_ROUTE_CONE, 3, cone_free, 0, 0, &path, &npath, &err);
        if (st != SQ_OK) fail_msg("walled cone trial %d: route failed: %s", tr, err.msg);
        assert_int_equal(sq_ts_head(S, path[npath - 1]), c2);
        assert_true(S->nv > nv0);
        check_tsurf(S, W.euler, W.area0);
        free(cone_free);
        walled_free(&W);
    }
    free(path);
}

/* ---- 4. opening sectors and vertices --------------------------------------- */

static void test_open(void **state)
{
    (void)state;
    rng_state = 0x0BE7;
    int trials = long_mode() ? 200 : 10;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, tr % 2 ? "libigl/bumpy.off" : "libigl/decimated-knight.off");
        sq_tsurf *S = &W.S;
        /* sectors of random cut vertices (every face at c is one) */
        for (int k = 0; k < 30; k++) {
            uint32_t s;
            if (k < 4) {
                s = S->v_he[W.c];
                for (uint32_t j = rnd(8); j; j--) s = sq_ts_ccw(S, s);
            } else {
                do s = rnd(S->nh);
                while (!S->kind[s]);
            }
            /* a one-face sector whose opposite edge is cut cannot open */
            if (S->kind[sq_ts_ccw(S, s)] && S->kind[S->next[s]]) continue;
            snap sn;
            snap_take(&sn, S);
            uint32_t nv0 = S->nv;
            int64_t n = sq_tsurf_open_sector(S, s);
            assert_true(n >= 0);
            assert_int_equal((int64_t)(S->nv - nv0), n);
            check_since(S, &sn, 1);
            snap_free(&sn);
            check_tsurf(S, W.euler, W.area0);
            /* every edge strictly inside the sector now leads off the cut
             * and to no cone, and there is one */
            uint32_t g = sq_ts_ccw(S, s), inner = 0;
            while (!S->kind[g]) {
                uint32_t w = sq_ts_head(S, g);
                if (blocked_v(S, w)) fail_msg("open_sector(%u): inner neighbour %u still blocked", s, w);
                inner++;
                g = sq_ts_ccw(S, g);
            }
            assert_true(inner >= 1);
            assert_int_equal(sq_tsurf_open_sector(S, s), 0);
        }
        /* vertices off the cut next to the wall */
        for (int k = 0; k < 20; k++) {
            uint32_t v;
            do v = rnd(S->nv);
            while (blocked_v(S, v));
            snap sn;
            snap_take(&sn, S);
            uint32_t nv0 = S->nv;
            int64_t n = sq_tsurf_open_vertex(S, v);
            assert_true(n >= 0);
            assert_int_equal((int64_t)(S->nv - nv0), n);
            check_since(S, &sn, 1);
            snap_free(&sn);
            check_tsurf(S, W.euler, W.area0);
            uint32_t h0 = S->v_he[v], h = h0;
            do {
                if (blocked_v(S, sq_ts_head(S, h)))
                    fail_msg("open_vertex(%u): neighbour %u still blocked", v, sq_ts_head(S, h));
                h = sq_ts_ccw(S, h);
            } while (h != h0);
        }
        walled_free(&W);
    }
}

/* ---- 5. blocking edges ------------------------------------------------------ */

static uint32_t count_blocking(const sq_tsurf *S, int cones)
{
    uint32_t n = 0;
    for (uint32_t h = 0; h < S->nh; h++) {
        if (S->kind[h] || S->vert[h] > sq_ts_head(S, h)) continue;
        uint32_t a = S->vert[h], b = sq_ts_head(S, h);
        int ca = S->v_ncut[a] > 0, cb = S->v_ncut[b] > 0;
        int ka = !ca && S->valence[a] != 4, kb = !cb && S->valence[b] != 4;
        if ((ca && cb) || (cones && ((ka && (kb || cb)) || (kb && ca)))) n++;
    }
    return n;
}

static void test_split_blocking(void **state)
{
    (void)state;
    rng_state = 0xB10C;
    int trials = long_mode() ? 200 : 12;
    uint32_t *reg = NULL;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, tr % 2 ? "mpz/eight.obj" : "libigl/decimated-knight.off");
        sq_tsurf *S = &W.S;
        /* more cut edges and cones at random */
        for (uint32_t k = 0; k < S->nh / 40; k++) {
            uint32_t h = rnd(S->nh);
            if (!S->kind[h]) sq_tsurf_cut_edge(S, h, rnd(2) ? SQ_TS_SEAM : SQ_TS_CHORD, 5, 6);
        }
        for (uint32_t k = 0; k < S->nv / 30; k++) S->valence[rnd(S->nv)] = 3 + (int32_t)rnd(2) * 2;
        check_tsurf(S, W.euler, W.area0);
        int cones = tr % 3 != 0;
        reg = realloc(reg, S->nf * sizeof *reg);
        uint32_t nr = regions(S, reg);
        uint32_t before = count_blocking(S, cones);
        assert_true(before > 0);
        snap sn;
        snap_take(&sn, S);
        uint32_t nv0 = S->nv;
        int64_t n = sq_tsurf_split_blocking(S, cones);
        assert_int_equal((int64_t)before, n);
        assert_int_equal((int64_t)(S->nv - nv0), n);
        check_since(S, &sn, 1);
        snap_free(&sn);
        check_tsurf(S, W.euler, W.area0);
        assert_int_equal(count_blocking(S, cones), 0);
        assert_int_equal(count_blocking(S, 0), 0);
        reg = realloc(reg, S->nf * sizeof *reg);
        assert_int_equal(regions(S, reg), nr);
        assert_int_equal(sq_tsurf_split_blocking(S, cones), 0);
        walled_free(&W);
    }
    free(reg);
}

/* ---- known reproductions ---------------------------------------------------- */

/* A CONE route from a cut vertex a whose sector holds the target cone c as a
 * neighbour, every other neighbour of c blocked: the route may reach the
 * midpoint of an edge of c's ring that ends at c (not opposite it) and
 * continue to the edge opposite c in the same face. */
static void test_route_cone_next_to_start(void **state)
{
    (void)state;
    rng_state = 0xAD1;
    int trials = long_mode() ? 200 : 20, failed = 0;
    uint32_t *path = NULL, npath = 0;
    char first[1400] = "";
    sq_error err;
    for (int tr = 0; tr < trials; tr++) {
        sq_mesh m;
        sq_tsurf S;
        sq_test_load_mesh(&m, "libigl/decimated-knight.off");
        sq_tsurf_init(&S);
        assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
        int64_t euler = sq_mesh_euler(&m);
        double area0 = total_area(&S);
        uint32_t *vp = malloc(S.nv * sizeof *vp), n = 0;
        assert_non_null(vp);
        while (n < 3) {
            uint32_t a = rnd(S.nv), b = rnd(S.nv);
            n = a == b ? 0 : my_path(&S, a, b, NULL, vp);
        }
        cut_vertex_path(&S, vp, n, SQ_TS_SEAM);
        /* a: inner vertex of the path; c: a neighbour of a off the cut */
        uint32_t a = vp[1 + rnd(n - 2)], ac = S.v_he[a];
        for (uint32_t k = rnd(12); k || S.v_ncut[sq_ts_head(&S, ac)]; k ? k-- : 0) ac = sq_ts_ccw(&S, ac);
        uint32_t c = sq_ts_head(&S, ac);
        S.valence[c] = 3;
        uint32_t h0 = S.v_he[c], h = h0;
        do {
            uint32_t w = sq_ts_head(&S, h);
            if (!S.v_ncut[w]) S.valence[w] = 6;
            h = sq_ts_ccw(&S, h);
        } while (h != h0);
        uint8_t *cone_free = malloc(S.nv);
        assert_non_null(cone_free);
        memset(cone_free, 1, S.nv);
        uint32_t s1 = sq_tsurf_sector_of(&S, ac);
        sq_status st = route_checked(&S, s1, SQ_ROUTE_CONE, 3, cone_free, 0, 0, &path, &npath, &err);
        if (st != SQ_OK) {
            if (!failed++)
                snprintf(first, sizeof first, "trial %d: start vertex %u, cone %u (adjacent): %s", tr, a, c, err.msg);
        } else {
            assert_int_equal(sq_ts_head(&S, path[npath - 1]), c);
            check_tsurf(&S, euler, area0);
        }
        free(cone_free), free(vp);
        sq_tsurf_free(&S);
        sq_mesh_free(&m);
    }
    free(path);
    if (failed) fail_msg("%d of %d CONE routes to a cone next to the start failed; first: %s", failed, trials, first);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_from_mesh_rejects_polygons),
        cmocka_unit_test(test_split_random),
        cmocka_unit_test(test_copy),
        cmocka_unit_test(test_boundary_loops),
        cmocka_unit_test(test_route_sector),
        cmocka_unit_test(test_route_cone_free),
        cmocka_unit_test(test_route_walls),
        cmocka_unit_test(test_route_cone_walled),
        cmocka_unit_test(test_open),
        cmocka_unit_test(test_split_blocking),
        cmocka_unit_test(test_route_cone_next_to_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
