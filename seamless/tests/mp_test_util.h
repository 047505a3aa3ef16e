/* Helpers shared by the metapolygon tests: a seeded PRNG, random admissible
 * valence multisets, and a quad-mesh checker that reads only the quads'
 * vertex lists (independent of the halfedge structure under test). */
#ifndef MP_TEST_UTIL_H
#define MP_TEST_UTIL_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_metapolygon.h"
#include "sq_metapolygon_subdivide.h"

/* ---- splitmix64 --------------------------------------------------------- */

typedef struct rng {
    uint64_t s;
} rng;

static inline uint64_t rng_next(rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* uniform in [0, n) (n > 0; the modulo bias is irrelevant here) */
static inline uint32_t rng_below(rng *r, uint32_t n)
{
    return (uint32_t)(rng_next(r) % n);
}

static inline int long_tests(void)
{
    const char *s = getenv("SQ_LONG_TESTS");
    return s && s[0] == '1';
}

/* ---- random valence multisets ------------------------------------------- */

/* Fills v (capacity cap) with a random multiset of valences 2..8 (and,
 * rarely, a large one such as 22) whose total excess is exactly `target`
 * (> -4). Returns the count, or 0 if cap is too small. */
static inline uint32_t random_valences(rng *r, int64_t target, uint32_t max_neg, uint32_t *v,
                                       uint32_t cap)
{
    uint32_t n = 0;
    int64_t cur = 0;
    uint32_t nneg = max_neg ? rng_below(r, max_neg + 1) : 0;
    for (uint32_t j = 0; j < nneg; j++) {
        if (n == cap) return 0;
        v[n] = 2 + rng_below(r, 2);
        cur += (int64_t)v[n++] - 4;
    }
    while (cur > target) {
        if (n == cap) return 0;
        v[n] = cur - target >= 2 && rng_below(r, 2) ? 2 : 3;
        cur += (int64_t)v[n++] - 4;
    }
    while (cur < target) {
        if (n == cap) return 0;
        uint32_t val = rng_below(r, 40) == 0 ? 22 : 5 + rng_below(r, 4);
        if ((int64_t)val - 4 > target - cur) val = (uint32_t)(4 + (target - cur));
        v[n++] = val;
        cur += (int64_t)val - 4;
    }
    /* shuffle: the caller orders */
    for (uint32_t j = n; j > 1; j--) {
        uint32_t k = rng_below(r, j);
        uint32_t t = v[j - 1];
        v[j - 1] = v[k];
        v[k] = t;
    }
    return n;
}

/* ---- independent quad-mesh checker --------------------------------------- */

typedef struct quad_report {
    int ok;
    char why[256];
    int64_t euler;
    uint32_t n_boundary_loops;
    uint32_t n_boundary_verts;
    uint32_t *valence; /* nv: incident quads, caller frees */
    uint8_t *on_boundary; /* nv, caller frees */
} quad_report;

typedef struct dedge {
    uint64_t key; /* (from << 32) | to */
    uint32_t quad, corner;
} dedge;

static int dedge_cmp(const void *a, const void *b)
{
    uint64_t x = ((const dedge *)a)->key, y = ((const dedge *)b)->key;
    return x < y ? -1 : x > y;
}

static inline const dedge *dedge_find(const dedge *d, uint32_t n, uint32_t from, uint32_t to)
{
    uint64_t key = ((uint64_t)from << 32) | to;
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (d[mid].key < key) lo = mid + 1;
        else hi = mid;
    }
    return lo < n && d[lo].key == key ? &d[lo] : NULL;
}

static inline uint32_t uf_find(uint32_t *p, uint32_t x)
{
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
}

/* Checks that quads (4*nq vertex indices < nv, counterclockwise) form an
 * oriented manifold disk: every vertex used, no repeated vertex in a quad,
 * each directed edge once, every vertex one fan, connected, one boundary
 * loop, V - E + F = 1. */
static inline quad_report check_quad_disk(uint32_t nv, uint32_t nq, const uint32_t *quads)
{
    quad_report R;
    memset(&R, 0, sizeof R);
    R.valence = calloc(nv ? nv : 1, sizeof *R.valence);
    R.on_boundary = calloc(nv ? nv : 1, 1);
    dedge *d = malloc((size_t)(4ull * nq + 1) * sizeof *d);
    uint32_t *bnext = malloc((size_t)(nv ? nv : 1) * sizeof *bnext);
    uint32_t *parent = malloc((size_t)(nv ? nv : 1) * sizeof *parent);
    uint32_t nd = 4 * nq;
#define BAD(...)                                             \
    do {                                                     \
        snprintf(R.why, sizeof R.why, __VA_ARGS__);          \
        goto out;                                            \
    } while (0)
    for (uint32_t v = 0; v < nv; v++) {
        bnext[v] = UINT32_MAX;
        parent[v] = v;
    }
    for (uint32_t q = 0; q < nq; q++) {
        for (uint32_t c = 0; c < 4; c++) {
            uint32_t a = quads[4 * q + c], b = quads[4 * q + (c + 1) % 4];
            if (a >= nv) BAD("quad %u: vertex %u out of range", q, a);
            for (uint32_t c2 = c + 1; c2 < 4; c2++)
                if (quads[4 * q + c2] == a) BAD("quad %u repeats vertex %u", q, a);
            d[4 * q + c].key = ((uint64_t)a << 32) | b;
            d[4 * q + c].quad = q;
            d[4 * q + c].corner = c;
            R.valence[a]++;
            uint32_t ra = uf_find(parent, a), rb = uf_find(parent, b);
            if (ra != rb) parent[ra] = rb;
        }
    }
    qsort(d, nd, sizeof *d, dedge_cmp);
    for (uint32_t j = 1; j < nd; j++)
        if (d[j].key == d[j - 1].key)
            BAD("directed edge %u->%u used twice (non-manifold or flipped)",
                (uint32_t)(d[j].key >> 32), (uint32_t)d[j].key);
    uint32_t n_bnd_edges = 0;
    for (uint32_t j = 0; j < nd; j++) {
        uint32_t a = (uint32_t)(d[j].key >> 32), b = (uint32_t)d[j].key;
        if (dedge_find(d, nd, b, a)) continue;
        /* boundary edge a->b; the boundary loop runs b -> a */
        if (bnext[b] != UINT32_MAX) BAD("vertex %u has two outgoing boundary edges", b);
        bnext[b] = a;
        R.on_boundary[a] = R.on_boundary[b] = 1;
        n_bnd_edges++;
    }
    uint32_t ne = (nd + n_bnd_edges) / 2;
    for (uint32_t v = 0; v < nv; v++) {
        if (R.valence[v] == 0) BAD("vertex %u is in no quad", v);
        if (uf_find(parent, v) != uf_find(parent, 0)) BAD("not connected (vertex %u)", v);
        if (R.on_boundary[v]) R.n_boundary_verts++;
    }
    /* one fan per vertex: rotate from a start edge */
    for (uint32_t q = 0; q < nq; q++) {
        for (uint32_t c = 0; c < 4; c++) {
            uint32_t v = quads[4 * q + c];
            if (R.valence[v] & 0x80000000u) continue; /* done */
            /* the rotation below crosses each quad's edge into v; a
             * boundary vertex's fan starts at the quad whose edge out of v
             * is on the boundary */
            if (R.on_boundary[v]) {
                uint32_t nxt = quads[4 * q + (c + 1) % 4];
                if (dedge_find(d, nd, nxt, v)) continue; /* not the start */
            }
            uint32_t count = 0, qq = q, cc = c;
            for (;;) {
                count++;
                uint32_t prev = quads[4 * qq + (cc + 3) % 4];
                const dedge *o = dedge_find(d, nd, v, prev);
                if (!o) break;
                qq = o->quad;
                cc = o->corner;
                if (qq == q) break;
                if (count > R.valence[v]) break;
            }
            if (count != R.valence[v])
                BAD("vertex %u: fan of %u quads, %u incident (non-manifold)", v, count,
                    R.valence[v]);
            R.valence[v] |= 0x80000000u;
        }
    }
    for (uint32_t v = 0; v < nv; v++) R.valence[v] &= 0x7fffffffu;
    /* boundary loops */
    {
        uint8_t *seen = calloc(nv ? nv : 1, 1);
        for (uint32_t v = 0; v < nv; v++) {
            if (!R.on_boundary[v] || seen[v]) continue;
            R.n_boundary_loops++;
            uint32_t w = v;
            while (!seen[w]) {
                seen[w] = 1;
                w = bnext[w];
            }
        }
        free(seen);
    }
    R.euler = (int64_t)nv - ne + nq;
    if (R.n_boundary_loops != 1) BAD("%u boundary loops", R.n_boundary_loops);
    if (R.euler != 1) BAD("Euler characteristic %lld", (long long)R.euler);
    R.ok = 1;
#undef BAD
out:
    free(d);
    free(bnext);
    free(parent);
    return R;
}

static inline void quad_report_free(quad_report *R)
{
    free(R->valence);
    free(R->on_boundary);
}

/* The vertex lists of the subdivided mesh, read through the documented
 * layout (quad q: he_vert[4q .. 4q+3]). Caller frees. */
static inline uint32_t *quads_of(const sq_mp_quads *Q)
{
    uint32_t *quads = malloc((size_t)(4ull * Q->mesh.nf + 1) * sizeof *quads);
    for (uint32_t j = 0; j < 4 * Q->mesh.nf; j++) quads[j] = Q->mesh.he_vert[j];
    return quads;
}

static inline int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

#endif
