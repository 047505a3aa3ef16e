/* Tests of sq_tmesh_lengths (integer T-mesh arc lengths by min-cost flow on
 * the double cover): malformed input; tori cut into rectangles; closed quad
 * meshes as T-meshes (the hand-built cube and the shared QuadriFlow
 * meshes), whose face sides turn between faces so that arcs with two ends
 * of one sign occur; random rectangle subdivisions of a torus with
 * T-junctions and randomly turned side labels; a target quad count.
 * Every result is checked independently here: each face's opposite sides
 * sum equally, every arc >= min_length.
 *
 * SQ_LENGTHS_VERBOSE=1 prints the measured costs (against plain rounding
 * and the linear relaxation) and solve times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sq_tmesh_lengths.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

static int verbose(void)
{
    const char *v = getenv("SQ_LENGTHS_VERBOSE");
    return v && *v && *v != '0';
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t rng = 0x2545f4914f6cdd1dull;
static uint32_t rnd(uint32_t n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng % n);
}
static double rnd01(void) { return (double)rnd(1u << 30) / (double)(1u << 30); }

/* ---- a T-mesh owned by the test ---------------------------------------- */

typedef struct tmesh {
    uint32_t n_faces, n_arcs;
    uint32_t *side_off, *side_arc;
    double *target, *weight;
    int64_t *truth;  /* a known exact solution (NULL if none) */
} tmesh;

static void tm_free(tmesh *t)
{
    free(t->side_off);
    free(t->side_arc);
    free(t->target);
    free(t->weight);
    free(t->truth);
    memset(t, 0, sizeof *t);
}

static sq_tmesh_sides sides_of(const tmesh *t, int64_t min_length)
{
    sq_tmesh_sides T = {t->n_faces, t->n_arcs, t->side_off, t->side_arc, t->target, t->weight, min_length, NULL};
    return T;
}

static int64_t side_sum(const tmesh *t, uint32_t f, uint32_t s, const int64_t *L)
{
    int64_t sum = 0;
    for (uint32_t i = t->side_off[4 * f + s]; i < t->side_off[4 * f + s + 1]; i++) sum += L[t->side_arc[i]];
    return sum;
}

/* The independent check: exact constraints and the lower bound. */
static void assert_valid(const tmesh *t, const int64_t *L, int64_t min_length)
{
    for (uint32_t a = 0; a < t->n_arcs; a++) assert_true(L[a] >= min_length);
    for (uint32_t f = 0; f < t->n_faces; f++) {
        assert_int_equal(side_sum(t, f, 0, L), side_sum(t, f, 2, L));
        assert_int_equal(side_sum(t, f, 1, L), side_sum(t, f, 3, L));
    }
}

static int is_valid(const tmesh *t, const int64_t *L, int64_t min_length)
{
    for (uint32_t a = 0; a < t->n_arcs; a++)
        if (L[a] < min_length) return 0;
    for (uint32_t f = 0; f < t->n_faces; f++)
        if (side_sum(t, f, 0, L) != side_sum(t, f, 2, L) || side_sum(t, f, 1, L) != side_sum(t, f, 3, L)) return 0;
    return 1;
}

static double cost_of(const tmesh *t, const int64_t *L)
{
    double c = 0.0;
    for (uint32_t a = 0; a < t->n_arcs; a++) c += (t->weight ? t->weight[a] : 1.0) * fabs((double)L[a] - t->target[a]);
    return c;
}

/* Turns the side labels of every face by a random multiple of 90 degrees
 * (side s becomes side s + r): the constraints stay the same equations,
 * but the bi-directed graph's signs change (arcs with two +1 or two -1
 * ends appear, as across rotational seams). */
static void turn_labels(tmesh *t)
{
    uint32_t *off = malloc((4 * (size_t)t->n_faces + 1) * sizeof *off);
    uint32_t *arc = malloc(2 * (size_t)t->n_arcs * sizeof *arc);
    assert_non_null(off);
    assert_non_null(arc);
    off[0] = 0;
    for (uint32_t f = 0; f < t->n_faces; f++) {
        uint32_t r = rnd(4);
        for (uint32_t s = 0; s < 4; s++) {
            uint32_t old = 4 * f + ((s + 4 - r) & 3);  /* new side s is old side s - r */
            uint32_t n = t->side_off[old + 1] - t->side_off[old];
            memcpy(arc + off[4 * f + s], t->side_arc + t->side_off[old], n * sizeof *arc);
            off[4 * f + s + 1] = off[4 * f + s] + n;
        }
    }
    free(t->side_off);
    free(t->side_arc);
    t->side_off = off;
    t->side_arc = arc;
}

/* ---- closed quad meshes as T-meshes ------------------------------------ */

typedef struct edge_key {
    uint32_t lo, hi, slot;
} edge_key;

static int cmp_edge(const void *a, const void *b)
{
    const edge_key *x = a, *y = b;
    if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
    return x->slot < y->slot ? -1 : x->slot > y->slot;
}

/* Face f's side s is the edge (quad[4f+s], quad[4f+s+1]); arcs are edges.
 * Returns 0 when some edge is not on exactly two faces. */
static int tm_from_quads(tmesh *t, const uint32_t *quad, uint32_t nf)
{
    memset(t, 0, sizeof *t);
    edge_key *k = malloc(4 * (size_t)nf * sizeof *k);
    assert_non_null(k);
    for (uint32_t i = 0; i < 4 * nf; i++) {
        uint32_t a = quad[i], b = quad[(i & ~3u) + ((i + 1) & 3)];
        k[i] = (edge_key){a < b ? a : b, a < b ? b : a, i};
    }
    qsort(k, 4 * (size_t)nf, sizeof *k, cmp_edge);
    t->n_faces = nf;
    t->n_arcs = 2 * nf;
    t->side_off = malloc((4 * (size_t)nf + 1) * sizeof *t->side_off);
    t->side_arc = malloc(4 * (size_t)nf * sizeof *t->side_arc);
    t->target = malloc(2 * (size_t)nf * sizeof *t->target);
    assert_non_null(t->side_off);
    assert_non_null(t->side_arc);
    assert_non_null(t->target);
    int ok = 1;
    for (uint32_t i = 0; i < 4 * nf; i += 2) {
        if (i + 1 >= 4 * nf || k[i].lo != k[i + 1].lo || k[i].hi != k[i + 1].hi ||
            (i + 2 < 4 * nf && k[i + 2].lo == k[i].lo && k[i + 2].hi == k[i].hi)) {
            ok = 0;
            break;
        }
        t->side_arc[k[i].slot] = i / 2;
        t->side_arc[k[i + 1].slot] = i / 2;
    }
    for (uint32_t i = 0; i <= 4 * nf; i++) t->side_off[i] = i;
    for (uint32_t a = 0; a < t->n_arcs; a++) t->target[a] = 1.0;
    free(k);
    return ok;
}

/* The cube: vertex x + 2y + 4z, six quads, valence-3 corners. */
static void tm_cube(tmesh *t)
{
    static const uint32_t quad[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
    assert_true(tm_from_quads(t, quad, 6));
}

/* A closed quad mesh from an OBJ file (v and f lines; f with 4 corners). */
static int tm_from_obj(tmesh *t, const char *path)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return 0;
    size_t cap = 1024, n = 0;
    uint32_t *quad = malloc(cap * sizeof *quad);
    assert_non_null(quad);
    char line[1024];
    int ok = 1;
    while (fgets(line, sizeof line, fp)) {
        if (line[0] != 'f' || line[1] != ' ') continue;
        char *p = line + 2;
        uint32_t c = 0, v[4];
        for (;;) {
            char *end;
            long idx = strtol(p, &end, 10);
            if (end == p) break;
            if (c < 4) v[c] = (uint32_t)(idx - 1);
            c++;
            p = end;
            while (*p && *p != ' ' && *p != '\t' && *p != '\n') p++;
        }
        if (c != 4) {
            ok = 0;
            break;
        }
        if (n + 4 > cap) {
            cap *= 2;
            quad = realloc(quad, cap * sizeof *quad);
            assert_non_null(quad);
        }
        memcpy(quad + n, v, sizeof v);
        n += 4;
    }
    fclose(fp);
    if (ok) ok = tm_from_quads(t, quad, (uint32_t)(n / 4));
    free(quad);
    return ok;
}

/* ---- rectangles on a torus ---------------------------------------------- */

typedef struct rect {
    uint32_t x0, x1, y0, y1;
} rect;

typedef struct point {
    uint32_t line, at;
} point;

static int cmp_point(const void *a, const void *b)
{
    const point *x = a, *y = b;
    if (x->line != y->line) return x->line < y->line ? -1 : 1;
    return x->at < y->at ? -1 : x->at > y->at;
}

typedef struct arc_key {
    uint32_t dir, line, at, slot;
} arc_key;

static int cmp_arc(const void *a, const void *b)
{
    const arc_key *x = a, *y = b;
    if (x->dir != y->dir) return x->dir < y->dir ? -1 : 1;
    if (x->line != y->line) return x->line < y->line ? -1 : 1;
    if (x->at != y->at) return x->at < y->at ? -1 : 1;
    return x->slot < y->slot ? -1 : x->slot > y->slot;
}

/* Breakpoints of line `line` in [from, to] (sorted, `to` may be the period:
 * then it stands for 0 and is appended). */
static uint32_t breaks(const point *pts, uint32_t np, uint32_t line, uint32_t from, uint32_t to, uint32_t period,
                       uint32_t *out)
{
    uint32_t n = 0, lo = 0, hi = np;
    while (lo < hi) {  /* first point at or after (line, from) */
        uint32_t mid = lo + (hi - lo) / 2;
        if (pts[mid].line < line || (pts[mid].line == line && pts[mid].at < from))
            lo = mid + 1;
        else
            hi = mid;
    }
    for (uint32_t i = lo; i < np && pts[i].line == line && pts[i].at <= to; i++) out[n++] = pts[i].at;
    if (to == period) out[n++] = period;
    return n;
}

/* The T-mesh of a tiling of the torus [0,X) x [0,Y) by rectangles. The
 * arcs are the pieces of the rectangles' sides between corners; their true
 * lengths (integers) are an exact solution, kept in t->truth. */
static void tm_from_rects(tmesh *t, const rect *r, uint32_t nr, uint32_t X, uint32_t Y)
{
    memset(t, 0, sizeof *t);
    /* corners on horizontal lines (line y, at x) and vertical lines (line x, at y) */
    point *hp = malloc(4 * (size_t)nr * sizeof *hp), *vp = malloc(4 * (size_t)nr * sizeof *vp);
    assert_non_null(hp);
    assert_non_null(vp);
    for (uint32_t i = 0; i < nr; i++) {
        uint32_t ys[2] = {r[i].y0 % Y, r[i].y1 % Y}, xs[2] = {r[i].x0 % X, r[i].x1 % X};
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                hp[4 * i + 2 * a + b] = (point){ys[a], xs[b]};
                vp[4 * i + 2 * a + b] = (point){xs[b], ys[a]};
            }
    }
    qsort(hp, 4 * (size_t)nr, sizeof *hp, cmp_point);
    qsort(vp, 4 * (size_t)nr, sizeof *vp, cmp_point);
    /* each side's arcs, in counterclockwise order */
    size_t cap = 64 * (size_t)nr, n = 0;
    arc_key *k = malloc(cap * sizeof *k);
    uint32_t *len = malloc(cap * sizeof *len);
    uint32_t *buf = malloc((4 * (size_t)nr + 2) * sizeof *buf);
    t->side_off = malloc((4 * (size_t)nr + 1) * sizeof *t->side_off);
    assert_non_null(k);
    assert_non_null(len);
    assert_non_null(buf);
    assert_non_null(t->side_off);
    t->side_off[0] = 0;
    for (uint32_t i = 0; i < nr; i++) {
        for (uint32_t s = 0; s < 4; s++) {
            int horiz = (s == 0 || s == 2);
            uint32_t line = horiz ? (s == 0 ? r[i].y0 : r[i].y1 % Y) : (s == 1 ? r[i].x1 % X : r[i].x0);
            uint32_t from = horiz ? r[i].x0 : r[i].y0, to = horiz ? r[i].x1 : r[i].y1;
            uint32_t nb = breaks(horiz ? hp : vp, 4 * nr, line, from, to, horiz ? X : Y, buf);
            /* duplicates removed */
            uint32_t m = 0;
            for (uint32_t j = 0; j < nb; j++)
                if (m == 0 || buf[m - 1] != buf[j]) buf[m++] = buf[j];
            assert_true(m >= 2 && buf[0] == from && buf[m - 1] == to);
            int reverse = (s == 2 || s == 3);
            for (uint32_t j = 0; j + 1 < m; j++) {
                uint32_t jj = reverse ? m - 2 - j : j;
                assert_true(n < cap);
                k[n] = (arc_key){horiz ? 0u : 1u, line, buf[jj], (uint32_t)n};
                len[n] = buf[jj + 1] - buf[jj];
                n++;
            }
            t->side_off[4 * i + s + 1] = (uint32_t)n;
        }
    }
    arc_key *sorted = malloc(n * sizeof *sorted);
    assert_non_null(sorted);
    memcpy(sorted, k, n * sizeof *k);
    qsort(sorted, n, sizeof *sorted, cmp_arc);
    assert_true(n % 2 == 0);
    t->n_faces = nr;
    t->n_arcs = (uint32_t)(n / 2);
    t->side_arc = malloc(n * sizeof *t->side_arc);
    t->target = malloc(n / 2 * sizeof *t->target);
    t->truth = malloc(n / 2 * sizeof *t->truth);
    assert_non_null(t->side_arc);
    assert_non_null(t->target);
    assert_non_null(t->truth);
    for (size_t i = 0; i < n; i += 2) {
        /* each piece is seen from both sides of its line */
        assert_true(sorted[i].dir == sorted[i + 1].dir && sorted[i].line == sorted[i + 1].line &&
                    sorted[i].at == sorted[i + 1].at);
        assert_int_equal(len[sorted[i].slot], len[sorted[i + 1].slot]);
        t->side_arc[sorted[i].slot] = (uint32_t)(i / 2);
        t->side_arc[sorted[i + 1].slot] = (uint32_t)(i / 2);
        t->truth[i / 2] = len[sorted[i].slot];
        t->target[i / 2] = len[sorted[i].slot];
    }
    free(sorted);
    free(k);
    free(len);
    free(buf);
    free(hp);
    free(vp);
}

/* An a x b grid of rectangles (column widths w, row heights h) on a torus. */
static void tm_grid(tmesh *t, uint32_t a, uint32_t b, const uint32_t *w, const uint32_t *h)
{
    rect *r = malloc((size_t)a * b * sizeof *r);
    assert_non_null(r);
    uint32_t X = 0, Y = 0;
    for (uint32_t i = 0; i < a; i++) X += w[i];
    for (uint32_t j = 0; j < b; j++) Y += h[j];
    uint32_t y = 0;
    for (uint32_t j = 0; j < b; j++) {
        uint32_t x = 0;
        for (uint32_t i = 0; i < a; i++) {
            r[j * a + i] = (rect){x, x + w[i], y, y + h[j]};
            x += w[i];
        }
        y += h[j];
    }
    tm_from_rects(t, r, a * b, X, Y);
    free(r);
}

/* A random subdivision: an a x b grid of cells of size `cell`, then
 * `splits` random cuts of a random rectangle by a segment from one of its
 * sides to the opposite one (its ends are T-junctions). */
static void tm_random(tmesh *t, uint32_t a, uint32_t b, uint32_t cell, uint32_t splits)
{
    size_t cap = (size_t)a * b + splits;
    rect *r = malloc(cap * sizeof *r);
    assert_non_null(r);
    uint32_t n = 0;
    for (uint32_t j = 0; j < b; j++)
        for (uint32_t i = 0; i < a; i++) r[n++] = (rect){i * cell, (i + 1) * cell, j * cell, (j + 1) * cell};
    for (uint32_t s = 0; s < splits; s++) {
        uint32_t i = rnd(n);
        rect q = r[i];
        if (rnd(2) && q.x1 - q.x0 >= 2) {
            uint32_t x = q.x0 + 1 + rnd(q.x1 - q.x0 - 1);
            r[i].x1 = x;
            r[n++] = (rect){x, q.x1, q.y0, q.y1};
        } else if (q.y1 - q.y0 >= 2) {
            uint32_t y = q.y0 + 1 + rnd(q.y1 - q.y0 - 1);
            r[i].y1 = y;
            r[n++] = (rect){q.x0, q.x1, y, q.y1};
        }
    }
    tm_from_rects(t, r, n, a * cell, b * cell);
    free(r);
}

/* ---- tests --------------------------------------------------------------- */

static void expect_error(const tmesh *t, int64_t m, sq_status code, const char *needle)
{
    sq_tmesh_sides T = sides_of(t, m);
    int64_t *L = malloc((t->n_arcs + 1) * sizeof *L);
    assert_non_null(L);
    sq_error err;
    sq_status s = sq_tmesh_lengths(&T, L, NULL, &err);
    if (s != code || !strstr(err.msg, needle)) fprintf(stderr, "got %d '%s'\n", (int)s, err.msg);
    assert_int_equal(s, code);
    assert_int_equal(err.code, code);
    assert_non_null(strstr(err.msg, needle));
    free(L);
}

static void test_bad_input(void **state)
{
    (void)state;
    tmesh t = {0};
    tm_cube(&t);
    int64_t L[12];
    sq_error err;
    assert_int_equal(sq_tmesh_lengths(NULL, L, NULL, &err), SQ_ERR_ARGUMENT);
    expect_error(&t, 0, SQ_ERR_ARGUMENT, "min_length 0");
    t.target[5] = NAN;
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "arc 5 has target nan");
    t.target[5] = -1.0;
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "arc 5 has target -1");
    t.target[5] = 0.0;
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "arc 5 has target 0");
    t.target[5] = 1e300;
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "arc 5 has target");
    t.target[5] = 1.0;
    t.weight = calloc(12, sizeof *t.weight);
    assert_non_null(t.weight);
    t.weight[7] = -2.0;
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "arc 7 has weight -2");
    free(t.weight);
    t.weight = NULL;
    /* the arc of face 0's right side also on its bottom (three sides) */
    uint32_t keep = t.side_arc[0];
    uint32_t other = t.side_arc[1];
    t.side_arc[0] = other;
    char needle[64];
    snprintf(needle, sizeof needle, "arc %u lies on more than two sides", other);
    expect_error(&t, 1, SQ_ERR_ARGUMENT, needle);
    t.side_arc[0] = keep;
    /* an index out of range names the face and side */
    t.side_arc[9] = 12;
    expect_error(&t, 1, SQ_ERR_INDEX, "side 1 of face 2 names arc 12");
    tm_free(&t);
    tm_cube(&t);
    /* an empty side */
    t.side_off[5] = t.side_off[4];
    expect_error(&t, 1, SQ_ERR_ARGUMENT, "side 0 of face 1 has no arc");
    tm_free(&t);
    /* an arc twice on one side: one face, bottom [0, 0], right [1], top
     * [1], left [2, 2] */
    {
        uint32_t off[5] = {0, 2, 3, 4, 6}, arc[6] = {0, 0, 1, 1, 2, 2};
        double tg[3] = {1, 1, 1};
        sq_tmesh_sides T = {1, 3, off, arc, tg, NULL, 1, NULL};
        int64_t L3[3];
        assert_int_equal(sq_tmesh_lengths(&T, L3, NULL, &err), SQ_ERR_ARGUMENT);
        assert_non_null(strstr(err.msg, "arc 0 lies twice on side 0 of face 0"));
    }
    /* an arc that appears once: 2 n_arcs occurrences fail to add up */
    {
        uint32_t off[5] = {0, 1, 2, 3, 4}, arc[4] = {0, 1, 0, 1};
        double tg[3] = {1, 1, 1};
        sq_tmesh_sides T = {1, 3, off, arc, tg, NULL, 1, NULL};
        int64_t L3[3];
        assert_int_equal(sq_tmesh_lengths(&T, L3, NULL, &err), SQ_ERR_ARGUMENT);
        assert_non_null(strstr(err.msg, "not 2 n_arcs = 6"));
    }
    /* unrealizable: one face, bottom [0, 1], right [2, 1], top [0], left
     * [2]: the constraints say L1 = 0 < 1 */
    {
        uint32_t off[5] = {0, 2, 4, 5, 6}, arc[6] = {0, 1, 2, 1, 0, 2};
        double tg[3] = {1, 1, 1};
        sq_tmesh_sides T = {1, 3, off, arc, tg, NULL, 1, NULL};
        int64_t L3[3];
        assert_int_equal(sq_tmesh_lengths(&T, L3, NULL, &err), SQ_ERR_UNREALIZABLE);
        assert_non_null(strstr(err.msg, "no lengths >= 1"));
    }
    /* for_quads: a bad count */
    tm_cube(&t);
    sq_tmesh_sides T = sides_of(&t, 1);
    assert_int_equal(sq_tmesh_lengths_for_quads(&T, NAN, L, NULL, &err), SQ_ERR_ARGUMENT);
    assert_int_equal(sq_tmesh_lengths_for_quads(&T, 0.5, L, NULL, &err), SQ_ERR_ARGUMENT);
    tm_free(&t);
}

/* The cube: all targets k give all lengths k; min_length above the targets
 * gives min_length; the same with turned labels. */
static void test_cube(void **state)
{
    (void)state;
    for (int turned = 0; turned < 4; turned++) {
        tmesh t = {0};
        tm_cube(&t);
        if (turned) turn_labels(&t);
        int64_t L[12];
        sq_error err;
        for (int k = 1; k <= 5; k++) {
            for (uint32_t a = 0; a < 12; a++) t.target[a] = k;
            sq_tmesh_sides T = sides_of(&t, 1);
            sq_tmesh_lengths_stats st;
            assert_int_equal(sq_tmesh_lengths(&T, L, &st, &err), SQ_OK);
            assert_valid(&t, L, 1);
            for (uint32_t a = 0; a < 12; a++) assert_int_equal(L[a], k);
            assert_true(st.cost == 0.0);
            assert_true(st.quads == 6.0 * k * k);
        }
        /* zero weights: any valid lengths cost 0; still valid ones */
        t.weight = calloc(12, sizeof *t.weight);
        assert_non_null(t.weight);
        for (uint32_t a = 0; a < 12; a++) t.target[a] = 1.0 + 0.37 * a;
        sq_tmesh_sides Tz = sides_of(&t, 2);
        assert_int_equal(sq_tmesh_lengths(&Tz, L, NULL, &err), SQ_OK);
        assert_valid(&t, L, 2);
        free(t.weight);
        t.weight = NULL;
        for (uint32_t a = 0; a < 12; a++) t.target[a] = 1.0;
        sq_tmesh_sides T = sides_of(&t, 3);
        assert_int_equal(sq_tmesh_lengths(&T, L, NULL, &err), SQ_OK);
        for (uint32_t a = 0; a < 12; a++) assert_int_equal(L[a], 3);
        /* the box a x b x c: the cube's edges fall into three parallel
         * classes; targets 2, 3, 5 by class are met exactly */
        tmesh box;
        tm_cube(&box);
        int64_t cls[12];
        /* class of an edge: its direction (x, y or z) from the vertex bits */
        static const uint32_t quad[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
        for (uint32_t i = 0; i < 24; i++) {
            uint32_t u = quad[i], v = quad[(i & ~3u) + ((i + 1) & 3)];
            uint32_t d = u ^ v;
            cls[box.side_arc[i]] = d == 1 ? 2 : d == 2 ? 3 : 5;
        }
        for (uint32_t a = 0; a < 12; a++) t.target[a] = (double)cls[a];
        /* t's arcs are box's arcs (same construction), only labels differ */
        T = sides_of(&t, 1);
        assert_int_equal(sq_tmesh_lengths(&T, L, NULL, &err), SQ_OK);
        for (uint32_t a = 0; a < 12; a++) assert_int_equal(L[a], cls[a]);
        tm_free(&box);
        tm_free(&t);
    }
}

/* Solves, checks, compares with rounding and the lower bound. */
typedef struct outcome {
    double cost, rounding, bound;
    int rounding_feasible;
    uint32_t half_arcs, solves;
    double seconds;
} outcome;

static outcome solve_checked(const tmesh *t, int64_t m)
{
    sq_tmesh_sides T = sides_of(t, m);
    int64_t *L = malloc(t->n_arcs * sizeof *L);
    assert_non_null(L);
    sq_error err;
    sq_tmesh_lengths_stats st;
    double t0 = now();
    sq_status s = sq_tmesh_lengths(&T, L, &st, &err);
    double t1 = now();
    if (s != SQ_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(s, SQ_OK);
    assert_valid(t, L, m);
    outcome o = {cost_of(t, L), st.rounding_cost, st.lower_bound, st.rounding_feasible, st.half_arcs, st.solves,
                 t1 - t0};
    assert_true(fabs(o.cost - st.cost) <= 1e-9 * (1.0 + o.cost));
    /* never worse than plain rounding where that is valid */
    if (o.rounding_feasible) assert_true(o.cost <= o.rounding + 1e-9 * (1.0 + o.cost));
    /* the bound (integer weights resolve 2^-20 of the largest weight) */
    double tol = 1e-5 * (1.0 + o.cost);
    assert_true(o.bound <= o.cost + tol);
    /* an integral relaxation is returned as is: optimal */
    if (o.half_arcs == 0) assert_true(o.cost <= o.bound + tol);
    double q = 0.0;
    for (uint32_t f = 0; f < t->n_faces; f++) q += (double)side_sum(t, f, 0, L) * (double)side_sum(t, f, 1, L);
    assert_true(q == st.quads);
    if (verbose() && t->n_arcs > 5000)
        printf("  %u arcs: %u solves, %u half arcs, %.3f s, cost %.1f bound %.1f\n", t->n_arcs, st.solves,
               st.half_arcs, t1 - t0, o.cost, o.bound);
    free(L);
    return o;
}

/* The best integer cost of one column (or row) of a torus grid: all its
 * arcs have one length x (by enumeration). */
static double best_class(const double *tg, uint32_t n, int64_t m)
{
    double best = INFINITY;
    for (int64_t x = m; x <= 40; x++) {
        double c = 0.0;
        for (uint32_t i = 0; i < n; i++) c += fabs((double)x - tg[i]);
        if (c < best) best = c;
    }
    return best;
}

/* Tori cut into a x b rectangles: integer widths come back exactly; with
 * noisy targets the result is the optimum, found by enumeration (all arcs
 * across a column have one length, and likewise along a row). */
static void test_torus_grid(void **state)
{
    (void)state;
    int optimal = 0;
    for (int trial = 0; trial < 40; trial++) {
        uint32_t a = 1 + rnd(8), b = 1 + rnd(8), w[8], h[8];
        for (uint32_t i = 0; i < 8; i++) {
            w[i] = 1 + rnd(6);
            h[i] = 1 + rnd(6);
        }
        tmesh t = {0};
        tm_grid(&t, a, b, w, h);
        assert_int_equal(t.n_faces, a * b);
        assert_int_equal(t.n_arcs, 2 * a * b);
        /* the arcs' classes, before the labels turn: the bottom arc of face
         * (i, j) = j a + i is in column i, its left arc in row j */
        uint32_t *cls = malloc(t.n_arcs * sizeof *cls);
        assert_non_null(cls);
        for (uint32_t f = 0; f < t.n_faces; f++) {
            cls[t.side_arc[t.side_off[4 * f]]] = f % a;
            cls[t.side_arc[t.side_off[4 * f + 3]]] = a + f / a;
        }
        if (trial & 1) turn_labels(&t);
        outcome o = solve_checked(&t, 1);
        assert_true(o.cost == 0.0);
        for (uint32_t k = 0; k < t.n_arcs; k++) t.target[k] = (double)t.truth[k] * 1.7 + 1.6 * (rnd01() - 0.5);
        int64_t m = 1 + (trial % 3 == 0);
        o = solve_checked(&t, m);
        double best = 0.0, tg[8];
        for (uint32_t c = 0; c < a + b; c++) {
            uint32_t n = 0;
            for (uint32_t k = 0; k < t.n_arcs; k++)
                if (cls[k] == c) tg[n++] = t.target[k];
            assert_int_equal(n, c < a ? b : a);
            best += best_class(tg, n, m);
        }
        assert_true(o.bound <= best + 1e-6);
        assert_true(o.cost >= best - 1e-9);
        optimal += o.cost <= best + 1e-9;
        free(cls);
        tm_free(&t);
    }
    if (verbose()) printf("torus grids: %d of 40 optimal\n", optimal);
    assert_int_equal(optimal, 40);
}

static const char *const quad_models[] = {"3holes", "botijo", "bunny", "elephant", "fertility"};

/* The shared QuadriFlow meshes as T-meshes: all targets k give k, noisy
 * targets give exact lengths no worse than rounding. */
static void test_quad_meshes(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof quad_models / sizeof *quad_models; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/data/quads/%s_quadriflow5k.obj", SQ_SHARED_DIR, quad_models[i]);
        tmesh t = {0};
        assert_true(tm_from_obj(&t, path));
        assert_true(t.n_faces > 4000);
        int64_t *L = malloc(t.n_arcs * sizeof *L);
        assert_non_null(L);
        for (int k = 1; k <= 3; k++) {
            for (uint32_t a = 0; a < t.n_arcs; a++) t.target[a] = k;
            sq_tmesh_sides T = sides_of(&t, 1);
            sq_error err;
            assert_int_equal(sq_tmesh_lengths(&T, L, NULL, &err), SQ_OK);
            for (uint32_t a = 0; a < t.n_arcs; a++) assert_int_equal(L[a], k);
        }
        /* noise that rounds to 1 everywhere: rounding is valid */
        for (uint32_t a = 0; a < t.n_arcs; a++) t.target[a] = 1.0 + 0.9 * (rnd01() - 0.5);
        outcome o1 = solve_checked(&t, 1);
        assert_true(o1.rounding_feasible);
        /* noise around 2.5 with weights: rounding is (almost surely) not valid */
        t.weight = malloc(t.n_arcs * sizeof *t.weight);
        assert_non_null(t.weight);
        for (uint32_t a = 0; a < t.n_arcs; a++) {
            t.target[a] = 2.5 + 2.0 * (rnd01() - 0.5);
            t.weight[a] = 0.5 + rnd01();
        }
        outcome o2 = solve_checked(&t, 1);
        assert_false(o2.rounding_feasible);
        /* measured: at the bound (optimal) on all five */
        assert_true(o2.cost <= o2.bound * 1.01);
        if (verbose())
            printf("%-10s %u faces %u arcs: noise~1 cost %.1f (rounding %.1f, bound %.1f) %.3f s;"
                   " noise~2.5 cost %.1f (rounding %.1f invalid, bound %.1f, %u half arcs) %.3f s\n",
                   quad_models[i], t.n_faces, t.n_arcs, o1.cost, o1.rounding, o1.bound, o1.seconds, o2.cost,
                   o2.rounding, o2.bound, o2.half_arcs, o2.seconds);
        free(L);
        tm_free(&t);
    }
}

/* Random rectangle subdivisions with T-junctions and turned labels. */
static void test_random_tmeshes(void **state)
{
    (void)state;
    double worst = 0.0, gap_sum = 0.0, bound_sum = 0.0;
    int with_halves = 0;
    for (int trial = 0; trial < 60; trial++) {
        tmesh t = {0};
        tm_random(&t, 1 + rnd(5), 1 + rnd(5), 8 + rnd(8), 5 + rnd(60));
        if (trial % 4) turn_labels(&t);
        int64_t m = 1 + (trial % 3 == 2);
        /* the truth (integer) is met exactly where it respects min_length */
        int truth_ok = is_valid(&t, t.truth, m);
        outcome o = solve_checked(&t, m);
        if (truth_ok) assert_true(o.cost == 0.0);
        double scale = 0.3 + 2.0 * rnd01();
        for (uint32_t a = 0; a < t.n_arcs; a++) t.target[a] = fmax(0.05, (double)t.truth[a] * scale + rnd01() - 0.5);
        o = solve_checked(&t, m);
        with_halves += o.half_arcs > 0;
        double excess = (o.cost - o.bound) / (1.0 + o.bound);
        if (excess > worst) worst = excess;
        gap_sum += o.cost - o.bound;
        bound_sum += o.bound;
        assert_true(o.cost <= 1.02 * o.bound + 1.0);
        /* targets unrelated to the tiling fight the constraints: the
         * relaxation is often half-integral, and the rounds decide */
        for (uint32_t a = 0; a < t.n_arcs; a++) t.target[a] = 0.3 + 4.0 * rnd01();
        o = solve_checked(&t, m);
        with_halves += o.half_arcs > 0;
        excess = (o.cost - o.bound) / (1.0 + o.bound);
        if (excess > worst) worst = excess;
        gap_sum += o.cost - o.bound;
        bound_sum += o.bound;
        /* measured: worst 0.4% above the bound over 200 such meshes */
        assert_true(o.cost <= 1.02 * o.bound + 1.0);
        tm_free(&t);
    }
    if (verbose())
        printf("random T-meshes: %d of 120 with a half-integral relaxation; cost above the bound: worst %.4f,"
               " total %.2f of %.1f\n", with_halves, worst, gap_sum, bound_sum);
    assert_true(with_halves >= 10);  /* the rounds were exercised */
}

/* A target quad count on several T-meshes, 1K to 20K quads. */
static void test_for_quads(void **state)
{
    (void)state;
    tmesh ts[3];
    uint32_t w[6] = {3, 1, 4, 1, 5, 9}, h[6] = {2, 6, 5, 3, 5, 8};
    tm_grid(&ts[0], 6, 6, w, h);
    tm_random(&ts[1], 3, 3, 20, 60);
    turn_labels(&ts[1]);
    tm_cube(&ts[2]);
    for (uint32_t a = 0; a < ts[2].n_arcs; a++) ts[2].target[a] = 1.0 + 0.3 * a;
    const double counts[] = {1000, 3000, 8000, 20000};
    for (int i = 0; i < 3; i++) {
        int64_t *L = malloc(ts[i].n_arcs * sizeof *L);
        assert_non_null(L);
        for (int c = 0; c < 4; c++) {
            sq_tmesh_sides T = sides_of(&ts[i], 1);
            sq_tmesh_lengths_stats st;
            sq_error err;
            assert_int_equal(sq_tmesh_lengths_for_quads(&T, counts[c], L, &st, &err), SQ_OK);
            assert_valid(&ts[i], L, 1);
            double q = 0.0;
            for (uint32_t f = 0; f < ts[i].n_faces; f++)
                q += (double)side_sum(&ts[i], f, 0, L) * (double)side_sum(&ts[i], f, 1, L);
            assert_true(q == st.quads);
            assert_true(st.min_quads >= (double)ts[i].n_faces && st.min_quads < counts[0]);
            if (verbose())
                printf("for_quads mesh %d: %.0f asked, %.0f reached (scale %.3g, %u solves, min %.0f)\n", i,
                       counts[c], q, st.target_scale, st.solves, st.min_quads);
            assert_true(fabs(q - counts[c]) <= 0.05 * counts[c]);
        }
        free(L);
    }
    /* below the smallest count: the smallest layout (a quad mesh: all ones) */
    int64_t L[12];
    sq_tmesh_sides T = sides_of(&ts[2], 1);
    sq_tmesh_lengths_stats st;
    sq_error err;
    assert_int_equal(sq_tmesh_lengths_for_quads(&T, 3, L, &st, &err), SQ_OK);
    assert_true(st.min_quads == 6.0 && st.quads == 6.0);
    for (int a = 0; a < 12; a++) assert_int_equal(L[a], 1);
    for (int i = 0; i < 3; i++) tm_free(&ts[i]);
}

/* Over 20K arcs: keeps the test fast (no timing asserted; the times are
 * printed with SQ_LENGTHS_VERBOSE). */
static void test_large(void **state)
{
    (void)state;
    tmesh t = {0};
    tm_random(&t, 70, 70, 12, 4000);
    turn_labels(&t);
    assert_true(t.n_arcs > 20000);
    for (uint32_t a = 0; a < t.n_arcs; a++) t.target[a] = fmax(0.05, (double)t.truth[a] * 0.6 + rnd01() - 0.5);
    outcome o = solve_checked(&t, 1);
    assert_true(o.cost <= o.bound * 1.01);
    if (verbose())
        printf("large: %u faces %u arcs, cost %.1f (rounding %.1f%s, bound %.1f, %u half arcs, %u solves), %.3f s\n",
               t.n_faces, t.n_arcs, o.cost, o.rounding, o.rounding_feasible ? "" : " invalid", o.bound, o.half_arcs,
               o.solves, o.seconds);
    tm_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_torus_grid),
        cmocka_unit_test(test_quad_meshes),
        cmocka_unit_test(test_random_tmeshes),
        cmocka_unit_test(test_for_quads),
        cmocka_unit_test(test_large),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
