/* seamquad: common refinement of two triangulations of one polygon
 * (sq_overlay.h). */
#include "sq_overlay.h"

#include <assert.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "sq_mesh.h"
#include "sq_predicates.h"

void sq_overlay_init(sq_overlay *X) { memset(X, 0, sizeof *X); }

void sq_overlay_free(sq_overlay *X)
{
    free(X->x_ha);
    free(X->x_hb);
    free(X->x_ta);
    free(X->x_tb);
    free(X->loc);
    free(X->bary);
    free(X->tri);
    free(X->tri_fa);
    free(X->tri_fb);
    sq_overlay_init(X);
}

/* The overlay of one range of B's faces (sq_overlay_build: two ranges,
 * each with its own ov, in two threads or one after the other) */
typedef struct ov {
    uint32_t nbnd, na, nv;
    const double *xy;
    const sq_overlay_mesh *A, *B;
    sq_overlay *X;   /* this range's crossings (ids nv + k) and triangles */
    uint32_t *loc;   /* nv: as sq_overlay.loc, for what this range found  */
    double *bary;    /* 3 nv                                              */
    int keep_g;      /* record x_g (range 1: the merge's budget needs it)  */
    uint32_t *x_g;   /* nx: the B face whose walk made crossing k          */
    uint32_t cap_x;
    uint64_t *hkey; /* crossing table: key (A edge << 32 | B edge) + 1, 0 empty */
    uint32_t *hval;
    uint32_t hcap;
    uint64_t rng;
    int degenerate; /* set by the predicates below */
    uint32_t g0, g1; /* the range [g0, g1) of B's faces                   */
    uint32_t stride; /* every stride-th face of it (the sample: 16, else 1) */
    uint32_t *work;  /* the sample: triangles made per face walked, or NULL */
    uint32_t g;      /* the face being walked                             */
    uint64_t max_crossings;
    sq_status st;    /* the range's result, err its message               */
    sq_error err;
    uint32_t stop_g; /* over the budget after face stop_g (else SQ_NONE)  */
    const _Atomic int *cancel; /* set: stop (NULL: never)                 */
    uint32_t *sa_stamp; /* na: B face + 1 whose edges sa_side holds for  */
    int8_t *sa_side;    /* 3 na: A vertex against them (side_code). An A */
                        /* vertex lies in about six of the A faces a B   */
                        /* face meets.                                   */
} ov;

static inline uint32_t nxt(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }

static int orient(ov *c, uint32_t p, uint32_t q, uint32_t r)
{
    return sq_orient2d(c->xy + 2 * (size_t)p, c->xy + 2 * (size_t)q, c->xy + 2 * (size_t)r);
}

/* The sign of r against the line p -> q; 0 when r is p or q (the input's
 * sharing), and SIDE_ON when it is exactly on the line otherwise. */
#define SIDE_ON 2
static int side_code(ov *c, uint32_t p, uint32_t q, uint32_t r)
{
    if (r == p || r == q) return 0;
    int s = orient(c, p, q, r);
    return s ? s : SIDE_ON;
}

/* The same, SIDE_ON as a 0 that flags the degeneracy */
static int side_of(ov *c, int code)
{
    if (code != SIDE_ON) return code;
    c->degenerate = 1;
    return 0;
}

static int side(ov *c, uint32_t p, uint32_t q, uint32_t r) { return side_of(c, side_code(c, p, q, r)); }

/* Direction p -> x strictly before p -> y counterclockwise (both inside
 * one fan of angle below pi at the boundary vertex p). */
static int before(ov *c, uint32_t p, uint32_t x, uint32_t y)
{
    if (x == y) return 0;
    int s = orient(c, p, x, y);
    if (!s) c->degenerate = 1;
    return s > 0;
}

/* Room for cap crossings in X (and in *x_g, when x_g is not NULL); -1: out
 * of memory */
static int reserve_crossings(sq_overlay *X, uint32_t **x_g, uint32_t cap)
{
    uint32_t *a = realloc(X->x_ha, cap * sizeof *a);
    if (a) X->x_ha = a;
    uint32_t *b = realloc(X->x_hb, cap * sizeof *b);
    if (b) X->x_hb = b;
    double *ta = realloc(X->x_ta, cap * sizeof *ta);
    if (ta) X->x_ta = ta;
    double *tb = realloc(X->x_tb, cap * sizeof *tb);
    if (tb) X->x_tb = tb;
    uint32_t *g = x_g ? realloc(*x_g, cap * sizeof *g) : NULL;
    if (g) *x_g = g;
    return a && b && ta && tb && (!x_g || g) ? 0 : -1;
}

/* Room for cap triangles in X; -1: out of memory */
static int reserve_triangles(sq_overlay *X, uint32_t cap)
{
    uint32_t *t = realloc(X->tri, 3 * (size_t)cap * sizeof *t);
    if (t) X->tri = t;
    uint32_t *ta = realloc(X->tri_fa, cap * sizeof *ta);
    if (ta) X->tri_fa = ta;
    uint32_t *tb = realloc(X->tri_fb, cap * sizeof *tb);
    if (tb) X->tri_fb = tb;
    if (!t || !ta || !tb) return -1;
    X->cap_tri = cap;
    return 0;
}

/* The crossing table's key of A halfedge ha and B halfedge hb (0: empty) */
static uint64_t crossing_key(uint32_t ha, uint32_t hb) { return ((uint64_t)ha << 32 | hb) + 1; }

/* The crossing table's slot of key: the one holding it, or the empty one
 * where it would go (linear probing) */
static uint32_t table_slot(const ov *c, uint64_t key)
{
    uint32_t s = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 32) & (c->hcap - 1);
    while (c->hkey[s] && c->hkey[s] != key) s = (s + 1) & (c->hcap - 1);
    return s;
}

static int crossing_id(ov *c, uint32_t ha, uint32_t hb, uint32_t *id)
{
    const sq_overlay_mesh *A = c->A, *B = c->B;
    if (A->twin[ha] != SQ_NONE && A->twin[ha] < ha) ha = A->twin[ha];
    if (B->twin[hb] != SQ_NONE && B->twin[hb] < hb) hb = B->twin[hb];
    uint64_t key = crossing_key(ha, hb);
    if (2 * (size_t)(c->X->nx + 1) > c->hcap) {
        uint32_t cap = c->hcap ? 2 * c->hcap : 1024;
        uint64_t *k2 = calloc(cap, sizeof *k2);
        uint32_t *v2 = malloc((size_t)cap * sizeof *v2);
        if (!k2 || !v2) {
            free(k2), free(v2);
            return -1;
        }
        for (uint32_t i = 0; i < c->hcap; i++) {
            if (!c->hkey[i]) continue;
            uint32_t s = (uint32_t)((c->hkey[i] * 0x9E3779B97F4A7C15ull) >> 32) & (cap - 1);
            while (k2[s]) s = (s + 1) & (cap - 1);
            k2[s] = c->hkey[i], v2[s] = c->hval[i];
        }
        free(c->hkey), free(c->hval);
        c->hkey = k2, c->hval = v2, c->hcap = cap;
    }
    uint32_t s = table_slot(c, key);
    if (c->hkey[s]) {
        *id = c->hval[s];
        return 0;
    }
    sq_overlay *X = c->X;
    if (X->nx == c->cap_x) {
        uint32_t cap = c->cap_x ? 2 * c->cap_x : 1024;
        if (reserve_crossings(X, c->keep_g ? &c->x_g : NULL, cap)) return -1;
        c->cap_x = cap;
    }
    /* parameters from the (rounded) determinants; the order of events was
     * decided exactly, these only place the point */
    const double *p0 = c->xy + 2 * (size_t)A->tri[ha], *p1 = c->xy + 2 * (size_t)A->tri[nxt(ha)];
    const double *q0 = c->xy + 2 * (size_t)B->tri[hb], *q1 = c->xy + 2 * (size_t)B->tri[nxt(hb)];
    double d0 = (q1[0] - q0[0]) * (p0[1] - q0[1]) - (q1[1] - q0[1]) * (p0[0] - q0[0]);
    double d1 = (q1[0] - q0[0]) * (p1[1] - q0[1]) - (q1[1] - q0[1]) * (p1[0] - q0[0]);
    double e0 = (p1[0] - p0[0]) * (q0[1] - p0[1]) - (p1[1] - p0[1]) * (q0[0] - p0[0]);
    double e1 = (p1[0] - p0[0]) * (q1[1] - p0[1]) - (p1[1] - p0[1]) * (q1[0] - p0[0]);
    double ta = d0 / (d0 - d1), tb = e0 / (e0 - e1);
    if (!(ta >= 0 && ta <= 1)) ta = ta > 1 ? 1 : ta < 0 ? 0 : 0.5; /* NaN: 0.5 */
    if (!(tb >= 0 && tb <= 1)) tb = tb > 1 ? 1 : tb < 0 ? 0 : 0.5;
    uint32_t k = X->nx++;
    X->x_ha[k] = ha, X->x_hb[k] = hb, X->x_ta[k] = ta, X->x_tb[k] = tb;
    if (c->keep_g) c->x_g[k] = c->g;
    c->hkey[s] = key, c->hval[s] = c->nv + k;
    *id = c->nv + k;
    return 0;
}

static void barycentric(const double *p, const double *a, const double *b, const double *d, double *l)
{
    double det = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
    double l1 = ((p[0] - a[0]) * (d[1] - a[1]) - (p[1] - a[1]) * (d[0] - a[0])) / det;
    double l2 = ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / det;
    l[0] = 1 - l1 - l2, l[1] = l1, l[2] = l2;
}

/* The intersection of A's face fa and B's face fb: its vertices in
 * counterclockwise order (ids; crossings created on demand) into poly.
 * Returns their count (0: no common area), -1 on a degenerate or
 * inconsistent configuration, -2 out of memory. */
static int pair_polygon(ov *c, uint32_t fa, uint32_t fb, uint32_t poly[15])
{
    const uint32_t *a = c->A->tri + 3 * (size_t)fa, *b = c->B->tri + 3 * (size_t)fb;
    int sA[3][3], sB[3][3]; /* sA[i][j]: A vertex i against B edge j */
    c->degenerate = 0;
    for (int i = 0; i < 3; i++) {
        uint32_t v = a[i];
        int8_t *sv = c->sa_side + 3 * (size_t)v;
        if (c->sa_stamp[v] != fb + 1) {
            for (int j = 0; j < 3; j++) sv[j] = (int8_t)side_code(c, b[j], b[(j + 1) % 3], v);
            c->sa_stamp[v] = fb + 1;
        }
        for (int j = 0; j < 3; j++) {
            sA[i][j] = side_of(c, sv[j]);
            sB[j][i] = side(c, a[i], a[(i + 1) % 3], b[j]);
        }
    }
    if (c->degenerate) return -1;
    /* local points: A vertex i -> i, B vertex j -> 3 + j (or the A vertex
     * it is), crossing of A edge i and B edge j -> 6 + 3 i + j */
    int mem[15] = {0}, alias[3] = {-1, -1, -1};
    for (int i = 0; i < 3; i++) {
        int j = 0;
        while (j < 3 && a[i] != b[j]) j++;
        if (j < 3) {
            uint32_t p = a[i];
            mem[i] = before(c, p, b[(j + 1) % 3], a[(i + 2) % 3]) && before(c, p, a[(i + 1) % 3], b[(j + 2) % 3]);
            alias[j] = i;
        } else {
            mem[i] = sA[i][0] > 0 && sA[i][1] > 0 && sA[i][2] > 0;
        }
    }
    for (int j = 0; j < 3; j++)
        if (alias[j] < 0) mem[3 + j] = sB[j][0] > 0 && sB[j][1] > 0 && sB[j][2] > 0;
    if (c->degenerate) return -1;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            mem[6 + 3 * i + j] = sA[i][j] * sA[(i + 1) % 3][j] < 0 && sB[j][i] * sB[(j + 1) % 3][i] < 0;
    int nx_[15];
    for (int k = 0; k < 15; k++) nx_[k] = -1;
    /* the supporting edges: each holds 0, 1 or 2 polygon vertices, in
     * order along it: its start, the entry crossing, the exit, its end */
    for (int e = 0; e < 6; e++) {
        int isA = e < 3, i = e % 3;
        if (!isA) { /* skip a B edge that is an A edge (the shared boundary) */
            int same = 0;
            for (int q = 0; q < 3; q++)
                if (a[q] == b[i] && a[(q + 1) % 3] == b[(i + 1) % 3]) same = 1;
            if (same) continue;
        }
        int list[4], n = 0;
        int s0 = isA ? i : (alias[i] >= 0 ? alias[i] : 3 + i);
        int i1 = (i + 1) % 3;
        int s1 = isA ? i1 : (alias[i1] >= 0 ? alias[i1] : 3 + i1);
        if (mem[s0]) list[n++] = s0;
        int entry = -1, exit_ = -1;
        for (int o = 0; o < 3; o++) {
            int x = isA ? 6 + 3 * i + o : 6 + 3 * o + i;
            if (!mem[x]) continue;
            int s = isA ? sA[i][o] : sB[i][o]; /* the start's side of the other edge */
            if (s < 0) {
                if (entry >= 0) return -1;
                entry = x;
            } else {
                if (exit_ >= 0) return -1;
                exit_ = x;
            }
        }
        if (entry >= 0) list[n++] = entry;
        if (exit_ >= 0) {
            if (n == 2) return -1;
            list[n++] = exit_;
        }
        if (mem[s1]) {
            if (n == 2) return -1;
            list[n++] = s1;
        }
        if (n == 2) {
            if (nx_[list[0]] >= 0) return -1;
            nx_[list[0]] = list[1];
        }
    }
    int m = 0, start = -1;
    for (int k = 0; k < 15; k++)
        if (mem[k] && !(k >= 3 && k < 6 && alias[k - 3] >= 0)) {
            m++;
            if (nx_[k] >= 0 && start < 0) start = k;
        }
    if (start < 0) return m <= 2 ? 0 : -1;
    int n = 0, k = start;
    do {
        if (n == 15 || !mem[k]) return -1;
        poly[n++] = (uint32_t)k;
        k = nx_[k];
    } while (k >= 0 && k != start);
    if (k != start || n != m) return -1;
    if (n < 3) return 0;
    /* local points -> ids */
    for (int q = 0; q < n; q++) {
        uint32_t l = poly[q];
        if (l < 3) {
            poly[q] = a[l];
            uint32_t v = a[l];
            if (v >= c->nbnd && c->loc[v] == SQ_NONE) {
                c->loc[v] = fb;
                barycentric(c->xy + 2 * (size_t)v, c->xy + 2 * (size_t)b[0], c->xy + 2 * (size_t)b[1],
                            c->xy + 2 * (size_t)b[2], c->bary + 3 * (size_t)v);
            }
        } else if (l < 6) {
            uint32_t v = b[l - 3];
            poly[q] = v;
            if (v >= c->na && c->loc[v] == SQ_NONE) {
                c->loc[v] = fa;
                barycentric(c->xy + 2 * (size_t)v, c->xy + 2 * (size_t)a[0], c->xy + 2 * (size_t)a[1],
                            c->xy + 2 * (size_t)a[2], c->bary + 3 * (size_t)v);
            }
        } else {
            uint32_t i = (l - 6) / 3, j = (l - 6) % 3;
            if (crossing_id(c, 3 * fa + i, 3 * fb + j, &poly[q])) return -2;
        }
    }
    return n;
}

static int emit(ov *c, const uint32_t *poly, int n, uint32_t fa, uint32_t fb)
{
    sq_overlay *X = c->X;
    for (int k = 1; k + 1 < n; k++) {
        if (X->ntri == X->cap_tri && reserve_triangles(X, X->cap_tri ? 2 * X->cap_tri : 4096)) return -1;
        uint32_t *t = X->tri + 3 * (size_t)X->ntri;
        t[0] = poly[0], t[1] = poly[k], t[2] = poly[k + 1];
        X->tri_fa[X->ntri] = fa, X->tri_fb[X->ntri] = fb;
        X->ntri++;
    }
    return 0;
}

static uint32_t rnd(ov *c)
{
    c->rng ^= c->rng << 13;
    c->rng ^= c->rng >> 7;
    c->rng ^= c->rng << 17;
    return (uint32_t)(c->rng >> 11);
}

/* The face of A holding point p strictly inside, by a randomized walk from
 * face f (terminates with probability 1 on any triangulation). SQ_NONE:
 * outside, degenerate (p on an edge of A) or too many steps. */
static uint32_t locate(ov *c, uint32_t f, uint32_t p)
{
    const sq_overlay_mesh *A = c->A;
    for (uint64_t steps = 0; steps < 8 * (uint64_t)A->nf + 64; steps++) {
        uint32_t r = rnd(c) % 3, moved = 0;
        for (uint32_t k = 0; k < 3 && !moved; k++) {
            uint32_t e = (r + k) % 3, h = 3 * f + e;
            int s = orient(c, A->tri[h], A->tri[nxt(h)], p);
            if (s > 0) continue;
            if (s == 0) {
                c->degenerate = 1;
                return SQ_NONE;
            }
            if (A->twin[h] == SQ_NONE) return SQ_NONE;
            f = A->twin[h] / 3;
            moved = 1;
        }
        if (!moved) return f;
    }
    return SQ_NONE;
}

static uint32_t bad_faces(const double *xy, const sq_overlay_mesh *M)
{
    uint32_t bad = 0;
    for (uint32_t f = 0; f < M->nf; f++) {
        const uint32_t *t = M->tri + 3 * (size_t)f;
        if (sq_orient2d(xy + 2 * (size_t)t[0], xy + 2 * (size_t)t[1], xy + 2 * (size_t)t[2]) <= 0) bad++;
    }
    return bad;
}

#define SPLIT_STRIDE 16u /* the sample: every 16th of B's faces (balanced_split) */

/* The sample's expectation against the budget (more than a quarter above
 * it fails) where max_expected is not 0, and against max_expected itself
 * (UINT64_MAX: the budget alone). */
static sq_status check_expected(uint64_t expected, uint32_t sample_nx, uint64_t max_crossings,
                                uint64_t max_expected, sq_error *err)
{
    const uint64_t b = max_expected ? max_crossings : 0;
    if (b && expected > b + b / 4)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "overlay: more than %llu crossings of surface and domain edges (about %llu expected: "
                            "%u in a sample of every %u-th domain triangle): the two disk maps differ too much",
                            (unsigned long long)b, (unsigned long long)expected, sample_nx, SPLIT_STRIDE);
    if (max_expected && expected > max_expected)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "overlay: about %llu crossings of surface and domain edges expected (%u in a "
                            "sample of every %u-th domain triangle), more than %llu",
                            (unsigned long long)expected, sample_nx, SPLIT_STRIDE,
                            (unsigned long long)max_expected);
    return SQ_OK;
}

/* Walks B's faces [c->g0, c->g1) in order: each from a face of A holding
 * its interior vertex, over the faces of A it meets. c->st, c->err: the
 * first failure; c->stop_g: the face after which this range alone had
 * more than max_crossings crossings. */
static void walk_range(ov *c)
{
    const sq_overlay_mesh *A = c->A, *B = c->B;
    sq_error *err = &c->err;
    sq_overlay *out = c->X;
    sq_status st = SQ_OK;
    uint32_t *mark = malloc((size_t)A->nf * sizeof *mark);
    uint32_t *queue = malloc((size_t)A->nf * sizeof *queue);
    c->sa_stamp = calloc((size_t)c->na + 1, sizeof *c->sa_stamp);
    c->sa_side = malloc(3 * ((size_t)c->na + 1));
    if (!mark || !queue || !c->sa_stamp || !c->sa_side) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < A->nf; f++) mark[f] = SQ_NONE;
    uint32_t hint = 0;
    for (uint32_t g = c->g0; g < c->g1; g += c->stride) {
        c->g = g;
        const uint32_t ntri0 = out->ntri;
        if (c->cancel && g % 64 == 0 && atomic_load(c->cancel)) {
            st = sq_error_set(err, SQ_ERR_SOLVER, "overlay: cancelled");
            goto done;
        }
        const uint32_t *t = B->tri + 3 * (size_t)g;
        uint32_t b = SQ_NONE;
        for (int k = 0; k < 3 && b == SQ_NONE; k++)
            if (t[k] >= c->na) b = t[k];
        if (b == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: domain triangle %u has no interior vertex", g);
            goto done;
        }
        /* the face of A holding b (the same whichever range found it) */
        uint32_t seed = c->loc[b];
        if (seed == SQ_NONE) {
            c->degenerate = 0;
            seed = locate(c, hint, b);
            if (seed == SQ_NONE) {
                st = sq_error_set(err, c->degenerate ? SQ_ERR_SOLVER : SQ_ERR_INTERNAL,
                                  "overlay: domain vertex %u %s", b,
                                  c->degenerate ? "lies on a surface edge (degenerate)"
                                                : "is not inside the surface's disk");
                goto done;
            }
        }
        hint = seed;
        uint32_t qh = 0, qt = 0, npieces = 0;
        queue[qt++] = seed;
        mark[seed] = g;
        while (qh < qt) {
            uint32_t fa = queue[qh++];
            uint32_t poly[15];
            int n = pair_polygon(c, fa, g, poly);
            if (n == -2 || (n > 0 && emit(c, poly, n, fa, g))) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                goto done;
            }
            if (n < 0) {
                st = sq_error_set(err, SQ_ERR_SOLVER,
                                  "overlay: degenerate or inconsistent intersection of surface "
                                  "triangle %u and domain triangle %u",
                                  fa, g);
                goto done;
            }
            if (n == 0) continue;
            npieces++;
            if (c->max_crossings && out->nx > c->max_crossings) break; /* reported below */
            for (uint32_t i = 0; i < 3; i++) {
                uint32_t tw = A->twin[3 * fa + i];
                if (tw == SQ_NONE || mark[tw / 3] == g) continue;
                mark[tw / 3] = g;
                queue[qt++] = tw / 3;
            }
        }
        if (c->max_crossings && out->nx > c->max_crossings) {
            c->stop_g = g;
            break;
        }
        if (!npieces) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: domain triangle %u meets no surface triangle", g);
            goto done;
        }
        if (c->work) c->work[(g - c->g0) / c->stride] = out->ntri - ntri0;
    }
done:
    free(mark);
    free(queue);
    free(c->sa_stamp), free(c->sa_side);
    c->sa_stamp = NULL, c->sa_side = NULL;
    c->st = st;
}

static void *walk_range_thread(void *arg)
{
    walk_range(arg);
    return NULL;
}

/* The id in range 0 of crossing (ha, hb) (canonical halfedges), or
 * SQ_NONE */
static uint32_t find_crossing(const ov *c, uint32_t ha, uint32_t hb)
{
    if (!c->hcap) return SQ_NONE;
    uint32_t s = table_slot(c, crossing_key(ha, hb));
    return c->hkey[s] ? c->hval[s] : SQ_NONE;
}

sq_status sq_overlay_build(uint32_t nbnd, uint32_t na, uint32_t nv, const double *xy,
                           const sq_overlay_mesh *A, const sq_overlay_mesh *B, uint64_t max_crossings,
                           sq_overlay *out, sq_error *err)
{
    return sq_overlay_build_threads(nbnd, na, nv, xy, A, B, max_crossings, 0, 1, NULL, out, err);
}

/* Where to split B's faces between the two ranges so that both walks take
 * about as long: every SPLIT_STRIDE-th face walked on its own first (a
 * sample, about 1/16 of the work; its tables thrown away), the split where
 * the sample's triangles reach half. Any split gives the same overlay (see
 * below); the faces' halves by count left one range with twice the other's
 * work on cid/elephant (1.44 s against 0.87 s). proto: a range as set up,
 * nothing walked or allocated yet. Falls back to the middle. *sample_nx:
 * the sample's crossings (0 if it failed). cap (0: none): the sample stops
 * once it has more crossings (*over = 1), so that its memory is bounded by
 * the caller's budget: the whole walk makes every crossing the sample
 * makes, so it would exceed the same budget. */
static uint32_t balanced_split(const ov *proto, uint64_t cap, uint32_t *sample_nx, int *over)
{
    const uint32_t nf = proto->B->nf, ns = (nf + SPLIT_STRIDE - 1) / SPLIT_STRIDE;
    assert(!proto->X && !proto->hkey && !proto->loc);
    sq_overlay T;
    sq_overlay_init(&T);
    ov d = *proto;
    d.X = &T, d.g0 = 0, d.g1 = nf, d.stride = SPLIT_STRIDE, d.max_crossings = cap;
    d.loc = malloc((size_t)d.nv * sizeof *d.loc);
    d.bary = malloc(3 * (size_t)d.nv * sizeof *d.bary);
    d.work = calloc((size_t)ns + 1, sizeof *d.work);
    uint32_t split = 0;
    if (d.loc && d.bary && d.work) {
        for (uint32_t v = 0; v < d.nv; v++) d.loc[v] = SQ_NONE;
        walk_range(&d);
        uint64_t total = 0, run = 0;
        for (uint32_t k = 0; k < ns; k++) total += d.work[k];
        while (d.st == SQ_OK && split < ns && 2 * (run + d.work[split]) <= total) run += d.work[split++];
        split *= SPLIT_STRIDE;
    }
    *over = d.st == SQ_OK && d.stop_g != SQ_NONE;
    *sample_nx = d.st == SQ_OK ? T.nx : 0;
    free(d.loc), free(d.bary), free(d.work), free(d.hkey), free(d.hval);
    sq_overlay_free(&T);
    return split > 0 && split < nf ? split : nf / 2;
}

/* Range 1's triangles after range 0's in out, with the merged crossing
 * ids (map: X1's crossing k is overlay vertex map[k]), and the locations
 * of the vertices only range 1 located. */
static sq_status append_range1(sq_overlay *out, const sq_overlay *X1, const uint32_t *map, uint32_t nv, sq_error *err)
{
    if (X1->ntri) {
        uint32_t nt = out->ntri + X1->ntri;
        if (nt < out->ntri) return sq_error_set(err, SQ_ERR_NOMEM, "overlay: more than 2^32 triangles");
        if (reserve_triangles(out, nt)) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        for (size_t i = 0; i < 3 * (size_t)X1->ntri; i++) {
            uint32_t v = X1->tri[i];
            out->tri[3 * (size_t)out->ntri + i] = v < nv ? v : map[v - nv];
        }
        memcpy(out->tri_fa + out->ntri, X1->tri_fa, (size_t)X1->ntri * sizeof *X1->tri_fa);
        memcpy(out->tri_fb + out->ntri, X1->tri_fb, (size_t)X1->ntri * sizeof *X1->tri_fb);
        out->ntri = nt;
    }
    for (uint32_t v = 0; v < nv; v++)
        if (out->loc[v] == SQ_NONE && X1->loc[v] != SQ_NONE) {
            out->loc[v] = X1->loc[v];
            memcpy(out->bary + 3 * (size_t)v, X1->bary + 3 * (size_t)v, 3 * sizeof *out->bary);
        }
    return SQ_OK;
}

/* The sample's cap (balanced_split; 0: none): the budget as it stands, and
 * where the expectation is checked against it (check_expected), the
 * sample's count beyond which the check refuses anyway. Not max_expected
 * itself: callers rank the expectations above it (the domain variants). */
static uint64_t sample_cap(uint64_t max_crossings, uint64_t max_expected)
{
    uint64_t cap = max_crossings;
    const uint64_t b = max_expected ? cap : 0;
    const uint64_t e = b ? (b + b / 4) / (SPLIT_STRIDE / 2) + 1 : 0;
    if (e && (!cap || e < cap)) cap = e;
    return cap;
}

/* Two ranges of B's faces, [0, s) and [s, nf) (s from balanced_split,
 * whatever the threads), each walked with its own crossing table,
 * then range 1's crossings merged into range 0's: a crossing of an edge
 * of B between the ranges is made by both, and keeps
 * range 0's id; range 1's others get the next ids in the order range 1
 * made them. That is the numbering of one walk over all faces in order
 * (the face holding a domain vertex and the walks from it do not depend
 * on which range located it first), so the result is that walk's, bit
 * for bit, with one thread or two. The crossing budget: each range stops
 * once it alone has more than max_crossings (range 1 counts the shared
 * crossings too), and the merged count must not exceed it either. */
sq_status sq_overlay_build_threads(uint32_t nbnd, uint32_t na, uint32_t nv, const double *xy,
                                   const sq_overlay_mesh *A, const sq_overlay_mesh *B, uint64_t max_crossings,
                                   uint64_t max_expected, uint32_t threads, const _Atomic int *cancel,
                                   sq_overlay *out, sq_error *err)
{
    sq_overlay_init(out);
    if (!xy || !A || !B || nbnd < 3 || na < nbnd || nv < na || !A->nf || !B->nf)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "overlay: bad arguments");
    uint32_t ba = bad_faces(xy, A), bb = bad_faces(xy, B);
    if (ba || bb)
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "overlay: the disk maps are not embeddings in floating point (%u of %u "
                            "surface triangles, %u of %u domain triangles not positively oriented)",
                            ba, A->nf, bb, B->nf);
    sq_overlay X1;
    sq_overlay_init(&X1);
    ov c[2];
    memset(c, 0, sizeof c);
    for (int r = 0; r < 2; r++) {
        c[r].nbnd = nbnd, c[r].na = na, c[r].nv = nv, c[r].xy = xy, c[r].A = A, c[r].B = B;
        c[r].rng = 0x2545F4914F6CDD1Dull;
        c[r].max_crossings = max_crossings;
        c[r].stop_g = SQ_NONE;
        c[r].cancel = cancel;
        c[r].stride = 1;
    }
    /* the sample (with one thread too: the same result, the same
     * expectation) */
    uint32_t sample_nx = 0;
    int over = 0;
    c[0].g0 = 0,
    c[0].g1 = c[1].g0 = B->nf >= 2 * SPLIT_STRIDE ? balanced_split(&c[0], sample_cap(max_crossings, max_expected),
                                                                    &sample_nx, &over)
                                                   : B->nf / 2;
    c[1].g1 = B->nf;
    const uint64_t expected = (uint64_t)sample_nx * (SPLIT_STRIDE / 2);
    out->expected = expected;
    if (over) /* the sample stopped at its cap: expected is a lower bound */
        return sq_error_set(err, SQ_ERR_SOLVER,
                            "overlay: more than %llu crossings of surface and domain edges expected (at least "
                            "%llu: a sample of every %u-th domain triangle alone made %u before it stopped): the "
                            "two disk maps differ too much",
                            (unsigned long long)max_crossings, (unsigned long long)expected,
                            SPLIT_STRIDE, sample_nx);
    sq_status st = check_expected(expected, sample_nx, max_crossings, max_expected, err);
    if (st) return st;
    c[0].X = out, c[1].X = &X1;
    uint32_t *map = NULL;
    out->loc = malloc((size_t)nv * sizeof *out->loc);
    out->bary = calloc(3 * (size_t)nv, sizeof *out->bary);
    X1.loc = malloc((size_t)nv * sizeof *X1.loc);
    X1.bary = calloc(3 * (size_t)nv, sizeof *X1.bary);
    c[1].keep_g = 1;
    if (!out->loc || !out->bary || !X1.loc || !X1.bary) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < nv; v++) out->loc[v] = X1.loc[v] = SQ_NONE;
    c[0].loc = out->loc, c[0].bary = out->bary, c[1].loc = X1.loc, c[1].bary = X1.bary;
    pthread_t th;
    int helper = threads > 1 && c[1].g0 < c[1].g1 && pthread_create(&th, NULL, walk_range_thread, &c[1]) == 0;
    walk_range(&c[0]);
    if (helper) pthread_join(th, NULL);
    else if (c[0].st == SQ_OK && c[0].stop_g == SQ_NONE) walk_range(&c[1]);
    /* the first failure in face order, as one walk would report it */
    for (int r = 0; r < 2; r++) {
        if (c[r].st) {
            st = c[r].st;
            if (err) *err = c[r].err;
            goto done;
        }
        if (c[r].stop_g != SQ_NONE) break;
    }
    /* range 1's crossings: range 0's id, or the next */
    uint32_t n0 = out->nx, stop_g = c[0].stop_g;
    if (stop_g == SQ_NONE && max_crossings && n0 > max_crossings) stop_g = c[0].g1 - 1;
    map = malloc(((size_t)X1.nx + 1) * sizeof *map);
    if (!map) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (stop_g == SQ_NONE) {
        uint32_t added = 0;
        for (uint32_t k = 0; k < X1.nx; k++) {
            uint32_t id = find_crossing(&c[0], X1.x_ha[k], X1.x_hb[k]);
            if (id == SQ_NONE) {
                if (max_crossings && (uint64_t)n0 + added + 1 > max_crossings) {
                    stop_g = c[1].x_g[k];
                    break;
                }
                id = nv + n0 + added++;
            }
            map[k] = id;
        }
        if (stop_g == SQ_NONE) stop_g = c[1].stop_g;
        if (stop_g == SQ_NONE && added) {
            uint32_t nx = n0 + added;
            if (reserve_crossings(out, NULL, nx)) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                goto done;
            }
            for (uint32_t k = 0; k < X1.nx; k++) {
                uint32_t j = map[k] - nv;
                if (j < n0) continue;
                out->x_ha[j] = X1.x_ha[k], out->x_hb[j] = X1.x_hb[k];
                out->x_ta[j] = X1.x_ta[k], out->x_tb[j] = X1.x_tb[k];
            }
            out->nx = nx;
        }
    }
    if (stop_g != SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_SOLVER,
                          "overlay: more than %llu crossings of surface and domain edges (after %u of "
                          "%u domain triangles): the two disk maps differ too much",
                          (unsigned long long)max_crossings, stop_g + 1, B->nf);
        goto done;
    }
    st = append_range1(out, &X1, map, nv, err);
    if (st) goto done;
    /* every interior vertex of either mesh must have been placed */
    for (uint32_t v = nbnd; v < nv; v++)
        if (out->loc[v] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: vertex %u lies in no triangle of the other mesh", v);
            goto done;
        }
done:
    for (int r = 0; r < 2; r++) free(c[r].hkey), free(c[r].hval);
    free(c[1].x_g);
    free(map);
    sq_overlay_free(&X1);
    if (st) sq_overlay_free(out);
    out->expected = expected; /* also on failure (sq_overlay_free cleared it) */
    return st;
}
