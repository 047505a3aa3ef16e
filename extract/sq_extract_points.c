/* Step 1 of the extraction: the grid points of an integer-grid map.
 *
 * Every integer point of the map is found once, on the element of the mesh
 * whose relative interior holds it:
 *  - a mesh vertex whose UV is integer (the same in every chart: the
 *    transitions are integer);
 *  - an edge, once per undirected edge (in the chart of its halfedge
 *    h < twin(h)): integer points X of the open segment (a, b), that is
 *    orient2d(a, b, X) = 0 and X strictly between a and b along the
 *    segment's major axis;
 *  - a face: integer points X with orient2d > 0 against all three edges.
 * Candidates come from a floating-point scan (one column per integer
 * coordinate, rounded outwards by one); the decision is always the exact
 * predicate, so a candidate missed by rounding is impossible and a wrong
 * one is rejected.
 *
 * Then the outgoing directions of each point (sq_extract_internal.h). At a
 * vertex, the corners are visited counterclockwise and each takes the axis
 * directions of its chart in the half-open angle [edge of h, edge of
 * prev(h)), decided exactly with the neighbour D = v + d (integer). Their
 * number must equal the vertex's valence (its angle sum / (pi/2)). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_extract_internal.h"
#include "sq_predicates.h"

typedef struct point_list {
    uint32_t n, cap;
    uint8_t *kind;
    uint32_t *elem;
    double *uv;
} point_list;

static int push_point(point_list *L, sq_grid_kind kind, uint32_t elem, double u, double v)
{
    if (L->n == L->cap) {
        uint32_t cap = L->cap ? 2 * L->cap : 1024;
        uint8_t *k = realloc(L->kind, cap);
        if (!k) return 0;
        L->kind = k;
        uint32_t *e = realloc(L->elem, (size_t)cap * sizeof *e);
        if (!e) return 0;
        L->elem = e;
        double *w = realloc(L->uv, 2 * (size_t)cap * sizeof *w);
        if (!w) return 0;
        L->uv = w;
        L->cap = cap;
    }
    L->kind[L->n] = (uint8_t)kind;
    L->elem[L->n] = elem;
    L->uv[2 * (size_t)L->n] = u;
    L->uv[2 * (size_t)L->n + 1] = v;
    L->n++;
    return 1;
}

static int is_integer(double x) { return floor(x) == x; }

/* The map's UVs are finite and small enough for exact integer steps, and
 * the grid points (about the UV area plus the edges' lengths) are within
 * SQ_EXTRACT_MAX_POINTS. */
static sq_status check_size(const sq_map *M, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    double est = m->nv;
    for (uint32_t h = 0; h < m->nh; h++) {
        const double *a = M->he_uv + 2 * (size_t)h;
        if (!(fabs(a[0]) < SQ_EXTRACT_MAX_UV && fabs(a[1]) < SQ_EXTRACT_MAX_UV))
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "face %u: UV (%.17g, %.17g) is beyond 2^40 in magnitude: the grid "
                                "would have too many points",
                                m->he_face[h], a[0], a[1]);
        const double *b = M->he_uv + 2 * (size_t)m->he_next[h];
        const double *c = M->he_uv + 2 * (size_t)sq_grid_prev(m, h);
        est += 0.5 * (fabs(b[0] - a[0]) + fabs(b[1] - a[1]));
        if (h == m->f_he[m->he_face[h]])
            est += 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    if (est > SQ_EXTRACT_MAX_POINTS)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "the map's UV area and edge lengths allow about %.3g grid points, more "
                            "than the %u an extraction may have: scale the map down",
                            est, SQ_EXTRACT_MAX_POINTS);
    return SQ_OK;
}

/* Integer points strictly inside the edge of halfedge h, in its chart. */
static int edge_points(const sq_map *M, uint32_t h, point_list *L)
{
    const sq_mesh *m = &M->mesh;
    const double *a = M->he_uv + 2 * (size_t)h, *b = M->he_uv + 2 * (size_t)m->he_next[h];
    int ax = fabs(b[0] - a[0]) >= fabs(b[1] - a[1]) ? 0 : 1, ot = 1 - ax;
    double lo = fmin(a[ax], b[ax]), hi = fmax(a[ax], b[ax]);
    if (!(lo < hi)) return 1; /* a point: no UV triangle has such an edge */
    double slope = (b[ot] - a[ot]) / (b[ax] - a[ax]); /* |slope| <= 1 */
    for (double t = floor(lo) + 1.0; t < hi; t += 1.0) {
        double s = floor(a[ot] + (t - a[ax]) * slope);
        for (double c = s; c <= s + 1.0; c += 1.0) {
            double X[2];
            X[ax] = t;
            X[ot] = c;
            if (sq_orient2d(a, b, X) == 0) {
                if (!push_point(L, SQ_GRID_EDGE, h, X[0], X[1])) return 0;
                break;
            }
        }
    }
    return 1;
}

/* Integer points strictly inside face f, in its chart, by columns of u. */
static int face_points(const sq_map *M, uint32_t f, point_list *L)
{
    const sq_mesh *m = &M->mesh;
    uint32_t h0 = m->f_he[f], h1 = m->he_next[h0], h2 = m->he_next[h1];
    const double *c[3] = {M->he_uv + 2 * (size_t)h0, M->he_uv + 2 * (size_t)h1,
                          M->he_uv + 2 * (size_t)h2};
    double umin = fmin(c[0][0], fmin(c[1][0], c[2][0])), umax = fmax(c[0][0], fmax(c[1][0], c[2][0]));
    double vmin = fmin(c[0][1], fmin(c[1][1], c[2][1])), vmax = fmax(c[0][1], fmax(c[1][1], c[2][1]));
    for (double u = floor(umin) + 1.0; u < umax; u += 1.0) {
        /* the column's span, approximately, from the edges that reach it */
        double lo = vmax, hi = vmin;
        for (int i = 0; i < 3; i++) {
            const double *p = c[i], *q = c[(i + 1) % 3];
            if (p[0] == q[0] || u < fmin(p[0], q[0]) || u > fmax(p[0], q[0])) continue;
            double v = p[1] + (u - p[0]) * (q[1] - p[1]) / (q[0] - p[0]);
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
        double v0 = fmax(floor(lo) - 1.0, floor(vmin) + 1.0), v1 = fmin(ceil(hi) + 1.0, ceil(vmax) - 1.0);
        for (double v = v0; v <= v1; v += 1.0) {
            const double X[2] = {u, v};
            if (sq_orient2d(c[0], c[1], X) > 0 && sq_orient2d(c[1], c[2], X) > 0 &&
                sq_orient2d(c[2], c[0], X) > 0 && !push_point(L, SQ_GRID_FACE, f, u, v))
                return 0;
        }
    }
    return 1;
}

/* 1 if axis direction d leaves vertex corner h (integer UV) in the
 * half-open angle [edge of h, edge of prev(h)). */
static int corner_holds(const sq_map *M, uint32_t h, int d)
{
    const sq_mesh *m = &M->mesh;
    const double *o = M->he_uv + 2 * (size_t)h, *a = M->he_uv + 2 * (size_t)m->he_next[h],
                 *b = M->he_uv + 2 * (size_t)sq_grid_prev(m, h);
    double D[2];
    sq_grid_step(o, d, D);
    int s1 = sq_orient2d(o, a, D);
    if (s1 > 0) return sq_orient2d(o, D, b) > 0;
    if (s1 < 0) return 0;
    /* on the line of h's edge: on it when a lies on D's side of o */
    switch (d) {
    case 0: return a[0] > o[0];
    case 1: return a[1] > o[1];
    case 2: return a[0] < o[0];
    default: return a[1] < o[1];
    }
}

static uint64_t mix(uint64_t x)
{
    x ^= x >> 31;
    x *= 0x7fb5d329728ea185ull;
    x ^= x >> 27;
    x *= 0x81dadef4bc2dd44dull;
    x ^= x >> 33;
    return x;
}

static uint32_t hash_key(sq_grid_kind kind, uint32_t elem, const double uv[2])
{
    uint64_t x = mix(((uint64_t)kind << 32) ^ elem);
    x = mix(x ^ (uint64_t)(int64_t)uv[0]);
    x = mix(x ^ (uint64_t)(int64_t)uv[1]);
    return (uint32_t)x;
}

uint32_t sq_grid_find(const sq_grid *G, sq_grid_kind kind, uint32_t elem, const double uv[2])
{
    if (!G->htab) return SQ_NONE;
    for (uint32_t i = hash_key(kind, elem, uv) & G->hmask;; i = (i + 1) & G->hmask) {
        uint32_t p = G->htab[i];
        if (p == SQ_NONE) return SQ_NONE;
        if (G->kind[p] == kind && G->elem[p] == elem && G->uv[2 * (size_t)p] == uv[0] &&
            G->uv[2 * (size_t)p + 1] == uv[1])
            return p;
    }
}

const char *sq_grid_describe(const sq_grid *G, uint32_t p, char *buf, size_t n)
{
    static const char *what[3] = {"at vertex", "inside the edge of halfedge", "inside face"};
    snprintf(buf, n, "grid point %u (%s %u, UV (%.17g, %.17g))", p, what[G->kind[p] % 3], G->elem[p],
             G->uv[2 * (size_t)p], G->uv[2 * (size_t)p + 1]);
    return buf;
}

void sq_grid_free(sq_grid *G)
{
    free(G->kind);
    free(G->elem);
    free(G->uv);
    free(G->slot_off);
    free(G->slot_point);
    free(G->slot_he);
    free(G->slot_dir);
    free(G->vert_point);
    free(G->htab);
    memset(G, 0, sizeof *G);
}

/* The slots of every point; at vertices, checks their count against the
 * valence. */
static sq_status build_slots(const sq_map *M, sq_grid *G, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint64_t total = 0;
    for (uint32_t p = 0; p < G->n; p++)
        total += G->kind[p] == SQ_GRID_VERTEX ? (uint64_t)(M->valence[G->elem[p]] > 0 ? M->valence[G->elem[p]] : 0) : 4u;
    if (total > 4ull * SQ_EXTRACT_MAX_POINTS)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "too many grid directions (%llu)",
                            (unsigned long long)total);
    G->slot_off = malloc(((size_t)G->n + 1) * sizeof *G->slot_off);
    G->slot_point = malloc((size_t)(total ? total : 1) * sizeof *G->slot_point);
    G->slot_he = malloc((size_t)(total ? total : 1) * sizeof *G->slot_he);
    G->slot_dir = malloc((size_t)(total ? total : 1));
    if (!G->slot_off || !G->slot_point || !G->slot_he || !G->slot_dir)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid directions)");
    uint32_t s = 0;
    for (uint32_t p = 0; p < G->n; p++) {
        G->slot_off[p] = s;
        if (G->kind[p] != SQ_GRID_VERTEX) {
            uint32_t h = G->kind[p] == SQ_GRID_EDGE ? G->elem[p] : m->f_he[G->elem[p]];
            for (int d = 0; d < 4; d++, s++) {
                G->slot_point[s] = p;
                G->slot_he[s] = h;
                G->slot_dir[s] = (uint8_t)d;
            }
            continue;
        }
        uint32_t v = G->elem[p], k = (uint32_t)M->valence[v], found = 0;
        uint32_t h = m->v_he[v];
        uint32_t deg = sq_mesh_vertex_valence(m, v);
        for (uint32_t i = 0; i < deg; i++, h = m->he_twin[sq_grid_prev(m, h)]) {
            int in[4];
            for (int d = 0; d < 4; d++) in[d] = corner_holds(M, h, d);
            int first = -1;
            for (int d = 0; d < 4; d++)
                if (in[d] && !in[(d + 3) % 4]) first = d;
            if (first < 0) {
                if (in[0]) /* all four: a corner of 360 degrees */
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "vertex %u: the corner of face %u holds every direction",
                                        v, m->he_face[h]);
                continue;
            }
            for (int j = 0; j < 4 && in[(first + j) % 4]; j++) {
                if (found == k)
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "vertex %u (valence %u): more than %u grid directions "
                                        "around it",
                                        v, k, k);
                G->slot_point[s] = p;
                G->slot_he[s] = h;
                G->slot_dir[s] = (uint8_t)((first + j) % 4);
                s++, found++;
            }
        }
        if (found != k)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "vertex %u (valence %u): %u grid directions around it", v, k, found);
    }
    G->slot_off[G->n] = s;
    G->nslot = s;
    return SQ_OK;
}

static sq_status build_hash(sq_grid *G, sq_error *err)
{
    uint32_t size = 16;
    while (size < 2 * (G->nedge + G->nface)) size *= 2;
    G->htab = malloc((size_t)size * sizeof *G->htab);
    if (!G->htab) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid point table)");
    memset(G->htab, 0xff, (size_t)size * sizeof *G->htab);
    G->hmask = size - 1;
    for (uint32_t p = G->nvert; p < G->n; p++) {
        const double *uv = G->uv + 2 * (size_t)p;
        uint32_t i = hash_key((sq_grid_kind)G->kind[p], G->elem[p], uv) & G->hmask;
        while (G->htab[i] != SQ_NONE) i = (i + 1) & G->hmask;
        G->htab[i] = p;
    }
    return SQ_OK;
}

sq_status sq_grid_build(const sq_map *M, sq_grid *G, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    memset(G, 0, sizeof *G);
    sq_status st = check_size(M, err);
    if (st) return st;
    point_list L = {0};
    G->vert_point = malloc((size_t)(m->nv ? m->nv : 1) * sizeof *G->vert_point);
    if (!G->vert_point) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid points)");
    for (uint32_t v = 0; v < m->nv; v++) {
        const double *uv = M->he_uv + 2 * (size_t)m->v_he[v];
        G->vert_point[v] = SQ_NONE;
        if (is_integer(uv[0]) && is_integer(uv[1])) {
            G->vert_point[v] = L.n;
            if (!push_point(&L, SQ_GRID_VERTEX, v, uv[0], uv[1])) goto nomem;
        } else if (M->valence[v] != 4) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "vertex %u: a cone of valence %d at UV (%.17g, %.17g), not an "
                              "integer point: the map is not an integer-grid map",
                              v, M->valence[v], uv[0], uv[1]);
            goto fail;
        }
    }
    G->nvert = L.n;
    for (uint32_t h = 0; h < m->nh; h++)
        if (h < m->he_twin[h] && !edge_points(M, h, &L)) goto nomem;
    G->nedge = L.n - G->nvert;
    for (uint32_t f = 0; f < m->nf; f++)
        if (!face_points(M, f, &L)) goto nomem;
    G->nface = L.n - G->nvert - G->nedge;
    G->n = L.n;
    G->kind = L.kind, G->elem = L.elem, G->uv = L.uv;
    L.kind = NULL, L.elem = NULL, L.uv = NULL;
    if (G->n == 0) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT,
                          "the map holds no integer point: its quad mesh would be empty (is it "
                          "scaled to the integer grid?)");
        goto fail;
    }
    if ((st = build_slots(M, G, err)) || (st = build_hash(G, err))) goto fail;
    return SQ_OK;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid points)");
fail:
    free(L.kind), free(L.elem), free(L.uv);
    sq_grid_free(G);
    return st;
}
