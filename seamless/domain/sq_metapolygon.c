/* seamquad: metapolygon storage, editing primitives, queries and the
 * structural check (seed 5, Def. 5.1 - 5.3). See sq_metapolygon.h for the
 * halfedge conventions. */
#include "sq_metapolygon.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* ---- storage ------------------------------------------------------------ */

void sq_metapolygon_init(sq_metapolygon *P)
{
    memset(P, 0, sizeof *P);
    P->bnd_he = SQ_NONE;
}

void sq_metapolygon_free(sq_metapolygon *P)
{
    free(P->he_next);
    free(P->he_twin);
    free(P->he_vert);
    free(P->he_face);
    free(P->v_he);
    free(P->v_nface);
    free(P->f_he);
    free(P->f_valence);
    sq_metapolygon_init(P);
}

/* Grows each array of `arrs` to `cap` entries. The arrays stay valid (and
 * the caller's capacity unchanged) if one reallocation fails. */
static int grow_arrays(uint32_t **arrs[], int count, uint32_t cap)
{
    for (int a = 0; a < count; a++) {
        uint32_t *p = realloc(*arrs[a], (size_t)cap * sizeof(uint32_t));
        if (!p) return 0;
        *arrs[a] = p;
    }
    return 1;
}

/* Capacity that holds `need` entries: doubling, at least 16, below
 * SQ_NONE (indices must stay distinct from the SQ_NONE marker). */
static uint32_t grown_capacity(uint32_t cap, uint64_t need)
{
    uint64_t c = cap < 16 ? 16 : cap;
    while (c < need) c *= 2;
    if (c >= SQ_NONE) c = SQ_NONE - 1;
    return (uint32_t)c;
}

sq_status sq_metapolygon_reserve(sq_metapolygon *P, uint64_t more_v, uint64_t more_f,
                                 uint64_t more_h, sq_error *err)
{
    uint64_t need_v = (uint64_t)P->nv + more_v;
    uint64_t need_f = (uint64_t)P->nf + more_f;
    uint64_t need_h = (uint64_t)P->nh + more_h;
    if (more_v >= SQ_NONE || more_f >= SQ_NONE || more_h >= SQ_NONE ||
        need_v >= SQ_NONE || need_f >= SQ_NONE || need_h >= SQ_NONE)
        return sq_error_set(err, SQ_ERR_NOMEM,
                            "metapolygon too large for 32-bit indices: %llu vertices, "
                            "%llu faces, %llu halfedges requested",
                            (unsigned long long)need_v, (unsigned long long)need_f,
                            (unsigned long long)need_h);
    if (need_h > P->cap_h) {
        uint32_t cap = grown_capacity(P->cap_h, need_h);
        uint32_t **arrs[] = {&P->he_next, &P->he_twin, &P->he_vert, &P->he_face};
        if (!grow_arrays(arrs, 4, cap))
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for %u metapolygon halfedges",
                                cap);
        P->cap_h = cap;
    }
    if (need_v > P->cap_v) {
        uint32_t cap = grown_capacity(P->cap_v, need_v);
        uint32_t **arrs[] = {&P->v_he, &P->v_nface};
        if (!grow_arrays(arrs, 2, cap))
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for %u metapolygon vertices",
                                cap);
        P->cap_v = cap;
    }
    if (need_f > P->cap_f) {
        uint32_t cap = grown_capacity(P->cap_f, need_f);
        uint32_t **arrs[] = {&P->f_he, &P->f_valence};
        if (!grow_arrays(arrs, 2, cap))
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for %u metapolygon faces", cap);
        P->cap_f = cap;
    }
    return SQ_OK;
}

sq_status sq_metapolygon_copy(sq_metapolygon *dst, const sq_metapolygon *src, sq_error *err)
{
    if (dst == src) return SQ_OK;
    sq_metapolygon tmp;
    sq_metapolygon_init(&tmp);
    sq_status st = sq_metapolygon_reserve(&tmp, src->nv, src->nf, src->nh, err);
    if (st != SQ_OK) {
        sq_metapolygon_free(&tmp);
        return st;
    }
    size_t hb = (size_t)src->nh * sizeof(uint32_t);
    size_t vb = (size_t)src->nv * sizeof(uint32_t);
    size_t fb = (size_t)src->nf * sizeof(uint32_t);
    if (hb) {
        memcpy(tmp.he_next, src->he_next, hb);
        memcpy(tmp.he_twin, src->he_twin, hb);
        memcpy(tmp.he_vert, src->he_vert, hb);
        memcpy(tmp.he_face, src->he_face, hb);
    }
    if (vb) {
        memcpy(tmp.v_he, src->v_he, vb);
        memcpy(tmp.v_nface, src->v_nface, vb);
    }
    if (fb) {
        memcpy(tmp.f_he, src->f_he, fb);
        memcpy(tmp.f_valence, src->f_valence, fb);
    }
    tmp.nv = src->nv;
    tmp.nf = src->nf;
    tmp.nh = src->nh;
    tmp.bnd_he = src->bnd_he;
    tmp.nbnd = src->nbnd;
    sq_metapolygon_free(dst);
    *dst = tmp;
    return SQ_OK;
}

/* ---- editing primitives ------------------------------------------------- */

/* Seed Def. 5.4 step 1 for an empty P: P' is just the k-gon. */
sq_status sq_metapolygon_add_polygon(sq_metapolygon *P, uint32_t k, uint32_t *face,
                                     sq_error *err)
{
    if (P->nf != 0 || P->nv != 0 || P->nh != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "add_polygon needs an empty metapolygon (this one has %u faces)",
                            P->nf);
    if (k < 2)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "a polygon needs at least 2 edges, got %u", k);
    sq_status st = sq_metapolygon_reserve(P, k, 1, 2ull * k, err);
    if (st != SQ_OK) return st;
    /* interior halfedge 2t runs t -> t+1; its twin 2t+1 runs t+1 -> t. */
    for (uint32_t t = 0; t < k; t++) {
        uint32_t s = 2 * t, b = 2 * t + 1;
        uint32_t t1 = (t + 1) % k;
        P->he_vert[s] = t;
        P->he_vert[b] = t1;
        P->he_twin[s] = b;
        P->he_twin[b] = s;
        P->he_face[s] = 0;
        P->he_face[b] = SQ_NONE;
        P->he_next[s] = 2 * t1;
        P->he_next[b] = 2 * ((t + k - 1) % k) + 1; /* t -> t-1 */
        P->v_nface[t] = 1;
        P->v_he[t] = 2 * ((t + k - 1) % k) + 1;    /* boundary, leaves t */
    }
    P->f_he[0] = 0;
    P->f_valence[0] = k;
    P->nv = k;
    P->nf = 1;
    P->nh = 2 * k;
    P->bnd_he = 1;
    P->nbnd = k;
    if (face) *face = 0;
    return SQ_OK;
}

uint32_t sq_metapolygon_boundary_prev(const sq_metapolygon *P, uint32_t h)
{
    assert(h < P->nh && P->he_face[h] == SQ_NONE);
    uint32_t g = h;
    for (uint32_t guard = 0; guard <= P->nh; guard++) {
        g = P->he_next[P->he_twin[g]];           /* next outgoing halfedge */
        uint32_t in = P->he_twin[g];
        if (P->he_face[in] == SQ_NONE) return in; /* boundary, enters origin */
    }
    assert(!"boundary_prev: no boundary halfedge around the vertex");
    return SQ_NONE;
}

/* Seed Def. 5.4 step 1 (n_glued = 1: an i-gon on one edge) and the cells
 * of the grids of steps 2 and 3 (n_glued = 2 or 3). */
sq_status sq_metapolygon_glue_polygon(sq_metapolygon *P, uint32_t h, uint32_t n_glued,
                                      uint32_t n_new_verts, uint32_t *face,
                                      uint32_t *first_bnd, uint32_t *last_bnd,
                                      sq_error *err)
{
    if (h >= P->nh || P->he_face[h] != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "glue halfedge %u is not a boundary halfedge",
                            h);
    if (n_glued < 1 || n_glued >= P->nbnd)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cannot glue along %u boundary edges of a boundary of %u edges",
                            n_glued, P->nbnd);
    uint32_t j = n_new_verts, n = n_glued;
    sq_status st = sq_metapolygon_reserve(P, j, 1, 2ull * (j + 1ull), err);
    if (st != SQ_OK) return st;

    uint32_t hp = sq_metapolygon_boundary_prev(P, h); /* enters p_0 */
    uint32_t hl = h;                                  /* last of the run */
    for (uint32_t t = 1; t < n; t++) hl = P->he_next[hl];
    uint32_t hn = P->he_next[hl];                     /* leaves p_n */
    uint32_t p0 = P->he_vert[h], pn = P->he_vert[hn];
    uint32_t f = P->nf, q0 = P->nv, e0 = P->nh;

    /* The face runs p_0 -(run)-> p_n -> q_1 -> ... -> q_j -> p_0. New edge t
     * (t = 0..j) has interior halfedge s_t = e0+2t from (t ? q_t : p_n) to
     * (t < j ? q_{t+1} : p_0) and boundary twin b_t = e0+2t+1. The new
     * boundary runs p_0 -> q_j -> ... -> q_1 -> p_n, i.e. b_j, ..., b_0. */
    for (uint32_t t = 0; t <= j; t++) {
        uint32_t s = e0 + 2 * t, b = s + 1;
        uint32_t from = t ? q0 + t - 1 : pn;
        uint32_t to = t < j ? q0 + t : p0;
        P->he_vert[s] = from;
        P->he_vert[b] = to;
        P->he_twin[s] = b;
        P->he_twin[b] = s;
        P->he_face[s] = f;
        P->he_face[b] = SQ_NONE;
        P->he_next[s] = t < j ? s + 2 : h;
        P->he_next[b] = t > 0 ? b - 2 : hn;
    }
    uint32_t bj = e0 + 2 * j + 1, b0 = e0 + 1;
    P->he_next[hl] = e0;
    P->he_next[hp] = bj;

    /* The run's halfedges now belong to f; the run's inner vertices p_1 ..
     * p_{n-1} become interior. */
    uint32_t g = h;
    for (uint32_t t = 0; t < n; t++) {
        P->he_face[g] = f;
        P->v_nface[P->he_vert[g]]++;
        if (t > 0) P->v_he[P->he_vert[g]] = g;
        g = P->he_next[g];
    }
    P->v_nface[pn]++;
    P->v_he[p0] = bj;
    for (uint32_t t = 1; t <= j; t++) {
        P->v_nface[q0 + t - 1] = 1;
        P->v_he[q0 + t - 1] = e0 + 2 * (t - 1) + 1; /* b_{t-1} leaves q_t */
    }
    P->f_he[f] = h;
    P->f_valence[f] = n + j + 1;
    P->nf++;
    P->nv += j;
    P->nh += 2 * (j + 1);
    P->nbnd = P->nbnd - n + j + 1;
    if (P->he_face[P->bnd_he] != SQ_NONE) P->bnd_he = bj;
    if (face) *face = f;
    if (first_bnd) *first_bnd = bj;
    if (last_bnd) *last_bnd = b0;
    return SQ_OK;
}

/* ---- queries ------------------------------------------------------------ */

/* Def. 5.1: corner, flat, concave by the number of incident faces. */
sq_mp_vertex_kind sq_metapolygon_vertex_kind(const sq_metapolygon *P, uint32_t v)
{
    assert(v < P->nv);
    if (P->he_face[P->v_he[v]] != SQ_NONE) return SQ_MP_INTERIOR;
    uint32_t c = P->v_nface[v];
    assert(c >= 1);
    return c >= 4 ? SQ_MP_OVERFULL : (sq_mp_vertex_kind)c;
}

/* Def. 5.2: the k of a meta-k-gon. */
uint32_t sq_metapolygon_count_corners(const sq_metapolygon *P)
{
    if (P->bnd_he == SQ_NONE) return 0;
    uint32_t count = 0, h = P->bnd_he;
    do {
        if (P->v_nface[P->he_vert[h]] == 1) count++;
        h = P->he_next[h];
    } while (h != P->bnd_he);
    return count;
}

/* Seed 5.1: C(P) and d(v, w). */
uint32_t sq_metapolygon_nonflat(const sq_metapolygon *P, uint32_t cap, uint32_t *vert,
                                uint32_t *out_he, uint32_t *dist)
{
    if (P->bnd_he == SQ_NONE) return 0;
    uint32_t start = P->bnd_he;
    while (P->v_nface[P->he_vert[start]] == 2) {
        start = P->he_next[start];
        if (start == P->bnd_he) return 0; /* meta-0-gon */
    }
    uint32_t count = 0, d = 0, h = start;
    do {
        uint32_t v = P->he_vert[h];
        if (P->v_nface[v] != 2) {
            if (count > 0 && count - 1 < cap && dist) dist[count - 1] = d;
            if (count < cap) {
                if (vert) vert[count] = v;
                if (out_he) out_he[count] = h;
            }
            count++;
            d = 0;
        }
        d++;
        h = P->he_next[h];
    } while (h != start);
    if (count - 1 < cap && dist) dist[count - 1] = d;
    return count;
}

/* Seed 5.1: I(P), the valences of the irregular faces. */
uint32_t sq_metapolygon_irregular(const sq_metapolygon *P, uint32_t cap, uint32_t *valence)
{
    uint32_t count = 0;
    for (uint32_t f = 0; f < P->nf; f++) {
        if (P->f_valence[f] == 4) continue;
        if (count < cap && valence) valence[count] = P->f_valence[f];
        count++;
    }
    return count;
}

/* Def. 5.3: e(P) = sum of e(p_i). */
int64_t sq_metapolygon_excess(const sq_metapolygon *P)
{
    int64_t e = 0;
    for (uint32_t f = 0; f < P->nf; f++) e += (int64_t)P->f_valence[f] - 4;
    return e;
}

uint32_t sq_metapolygon_count_quads(const sq_metapolygon *P)
{
    uint32_t q = 0;
    for (uint32_t f = 0; f < P->nf; f++) q += P->f_valence[f] == 4;
    return q;
}

/* ---- structural check --------------------------------------------------- */

#define FAIL(...)                                               \
    do {                                                        \
        st = sq_error_set(err, SQ_ERR_INTERNAL, __VA_ARGS__);   \
        goto done;                                              \
    } while (0)

/* Def. 5.1 (with the flags) on top of the halfedge invariants. */
sq_status sq_metapolygon_validate(const sq_metapolygon *P, unsigned flags, sq_error *err)
{
    if (P->nf == 0) {
        if (P->nv || P->nh || P->nbnd || P->bnd_he != SQ_NONE)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "metapolygon without faces has %u vertices, %u halfedges", P->nv,
                                P->nh);
        return SQ_OK;
    }
    sq_status st = SQ_OK;
    uint32_t nv = P->nv, nh = P->nh, nf = P->nf;
    uint32_t *stamp = calloc(nv, sizeof *stamp);
    uint32_t *nout = calloc(nv, sizeof *nout);     /* outgoing halfedges     */
    uint32_t *nfaces = calloc(nv, sizeof *nfaces); /* outgoing interior ones */
    uint8_t *seen = calloc(nh, 1);
    uint32_t *queue = malloc((size_t)nv * sizeof *queue);
    if (!stamp || !nout || !nfaces || !seen || !queue) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory validating a metapolygon");
        goto done;
    }
    if (nh % 2) FAIL("odd number of halfedges (%u)", nh);
    uint32_t n_interior = 0, n_boundary = 0;
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t t = P->he_twin[h], nx = P->he_next[h], v = P->he_vert[h];
        if (t >= nh || t == h || P->he_twin[t] != h) FAIL("halfedge %u: bad twin %u", h, t);
        if (nx >= nh) FAIL("halfedge %u: next %u out of range", h, nx);
        if (v >= nv) FAIL("halfedge %u: vertex %u out of range", h, v);
        if (P->he_vert[nx] != P->he_vert[t])
            FAIL("halfedge %u: next starts at %u, twin at %u", h, P->he_vert[nx], P->he_vert[t]);
        if (P->he_face[h] == SQ_NONE) {
            if (P->he_face[t] == SQ_NONE) FAIL("edge of halfedge %u has no face", h);
            if (P->he_face[nx] != SQ_NONE) FAIL("boundary halfedge %u: next %u is interior", h, nx);
            n_boundary++;
        } else {
            if (P->he_face[h] >= nf) FAIL("halfedge %u: face %u out of range", h, P->he_face[h]);
            nfaces[v]++;
            n_interior++;
        }
        nout[v]++;
    }
    /* faces: closed cycles of the stated valence, no repeated vertex */
    uint64_t sum_valence = 0;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t h0 = P->f_he[f], h = h0, c = 0;
        if (h0 >= nh) FAIL("face %u: first halfedge %u out of range", f, h0);
        do {
            if (P->he_face[h] != f) FAIL("face %u: halfedge %u belongs to face %u", f, h,
                                         P->he_face[h]);
            if (seen[h]) FAIL("face %u: halfedge %u visited twice", f, h);
            seen[h] = 1;
            uint32_t v = P->he_vert[h];
            if (stamp[v] == f + 1) FAIL("face %u repeats vertex %u", f, v);
            stamp[v] = f + 1;
            c++;
            h = P->he_next[h];
        } while (h != h0 && c <= nh);
        if (c != P->f_valence[f]) FAIL("face %u: %u edges, valence says %u", f, c,
                                       P->f_valence[f]);
        if (c < 2) FAIL("face %u has valence %u < 2", f, c);
        sum_valence += c;
    }
    if (sum_valence != n_interior)
        FAIL("%u interior halfedges, but faces account for %llu", n_interior,
             (unsigned long long)sum_valence);
    /* boundary: one loop through every boundary halfedge, each vertex once */
    if (P->bnd_he >= nh || P->he_face[P->bnd_he] != SQ_NONE)
        FAIL("bnd_he %u is not a boundary halfedge", P->bnd_he);
    memset(stamp, 0, (size_t)nv * sizeof *stamp);
    {
        uint32_t h = P->bnd_he, c = 0;
        do {
            uint32_t v = P->he_vert[h];
            if (stamp[v]) FAIL("boundary loop passes vertex %u twice", v);
            stamp[v] = 1;
            if (P->v_he[v] != h) FAIL("boundary vertex %u: v_he %u, not its boundary halfedge %u",
                                      v, P->v_he[v], h);
            c++;
            h = P->he_next[h];
        } while (h != P->bnd_he && c <= nh);
        if (c != n_boundary || c != P->nbnd)
            FAIL("boundary loop has %u halfedges; %u boundary halfedges exist, nbnd = %u", c,
                 n_boundary, P->nbnd);
    }
    /* vertices: stored data, one fan each (manifold), valences */
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t h0 = P->v_he[v];
        if (h0 >= nh || P->he_vert[h0] != v) FAIL("vertex %u: v_he %u does not leave it", v, h0);
        if (nfaces[v] != P->v_nface[v])
            FAIL("vertex %u: %u incident faces, stored %u", v, nfaces[v], P->v_nface[v]);
        if (nfaces[v] == 0) FAIL("vertex %u has no face", v);
        uint32_t c = 0, g = h0;
        do {
            c++;
            g = P->he_next[P->he_twin[g]];
        } while (g != h0 && c <= nout[v]);
        if (c != nout[v]) FAIL("vertex %u is not manifold: a fan of %u of its %u halfedges", v, c,
                               nout[v]);
        int on_boundary = stamp[v] != 0;
        if (flags & SQ_MP_CHECK_METAPOLYGON) {
            uint32_t k = nfaces[v];
            uint32_t max_bnd = (flags & SQ_MP_CHECK_ALLOW_CONCAVE) ? 3 : 2;
            if (!on_boundary && k != 4)
                FAIL("Def. 5.1: interior vertex %u has valence %u, not 4", v, k);
            if (on_boundary && k > max_bnd)
                FAIL("Def. 5.1: boundary vertex %u has valence %u > %u", v, k, max_bnd);
        }
    }
    /* connected, and a disk: Euler characteristic V - E + F = 1 */
    {
        memset(stamp, 0, (size_t)nv * sizeof *stamp);
        uint32_t head = 0, tail = 0;
        queue[tail++] = 0;
        stamp[0] = 1;
        while (head < tail) {
            uint32_t v = queue[head++], g = P->v_he[v], c = 0;
            do {
                uint32_t w = P->he_vert[P->he_twin[g]];
                if (!stamp[w]) {
                    stamp[w] = 1;
                    queue[tail++] = w;
                }
                g = P->he_next[P->he_twin[g]];
            } while (g != P->v_he[v] && ++c <= nout[v]);
        }
        if (tail != nv) FAIL("not connected: %u of %u vertices reachable", tail, nv);
        int64_t chi = (int64_t)nv - (int64_t)(nh / 2) + (int64_t)nf;
        if (chi != 1) FAIL("Euler characteristic %lld, a disk has 1", (long long)chi);
    }
done:
    free(stamp);
    free(nout);
    free(nfaces);
    free(seen);
    free(queue);
    return st;
}
