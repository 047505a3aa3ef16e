/* seamquad: helpers of the genus-1 domain (sq_domain_genus1.h): the
 * exhaustive enumeration of two-piece side pairings (seed 6.2, 6.3) and a
 * quad-list to halfedge-disk constructor (the padded pieces glued along one
 * pair of sides, seed 6.3: "here we only glue a subset so as to yield a
 * disk topology mesh Q"). */
#include "sq_domain_genus1.h"
#include "sq_union_find.h"

#include <stdlib.h>
#include <string.h>

/* ---- pattern enumeration ------------------------------------------------- */

typedef struct enum_ctx {
    uint32_t npieces, n;
    uint32_t piece_of[SQ_G1_MAX_SIDES], next[SQ_G1_MAX_SIDES];
    uint32_t partner[SQ_G1_MAX_SIDES];
    uint32_t cap, count;
    uint32_t *out, *glue;
} enum_ctx;

/* A complete pairing: keep it if every corner class has four corners and
 * the pieces are connected. */
static void consider(enum_ctx *c)
{
    uint32_t parent[SQ_G1_MAX_SIDES], size[SQ_G1_MAX_SIDES] = {0};
    uint32_t pparent[SQ_G1_MAX_SIDES];
    for (uint32_t i = 0; i < c->n; i++) parent[i] = i;
    for (uint32_t p = 0; p < c->npieces; p++) pparent[p] = p;
    for (uint32_t i = 0; i < c->n; i++) {
        uint32_t j = c->partner[i];
        sq_uf_union(parent, i, c->next[j]);
        sq_uf_union(parent, c->next[i], j);
        sq_uf_union(pparent, c->piece_of[i], c->piece_of[j]);
    }
    for (uint32_t i = 0; i < c->n; i++) size[sq_uf_find(parent, i)]++;
    for (uint32_t i = 0; i < c->n; i++)
        if (size[i] != 0 && size[i] != 4) return;
    for (uint32_t p = 0; p < c->npieces; p++)
        if (sq_uf_find(pparent, p) != 0) return;
    if (c->count < c->cap) {
        if (c->out) memcpy(c->out + (size_t)c->count * c->n, c->partner, c->n * sizeof(uint32_t));
        if (c->glue) {
            uint32_t g = UINT32_MAX;
            for (uint32_t i = 0; i < c->n && g == UINT32_MAX; i++) {
                uint32_t j = c->partner[i];
                if (c->piece_of[i] == 0 && c->piece_of[j] == 1 &&
                    sq_uf_find(parent, i) != sq_uf_find(parent, c->next[i]))
                    g = i;
            }
            c->glue[c->count] = g;
        }
    }
    c->count++;
}

static void pair_up(enum_ctx *c)
{
    uint32_t a = 0;
    while (a < c->n && c->partner[a] != UINT32_MAX) a++;
    if (a == c->n) {
        consider(c);
        return;
    }
    for (uint32_t b = a + 1; b < c->n; b++) {
        if (c->partner[b] != UINT32_MAX) continue;
        c->partner[a] = b, c->partner[b] = a;
        pair_up(c);
        c->partner[a] = c->partner[b] = UINT32_MAX;
    }
}

uint32_t sq_g1_patterns(uint32_t npieces, const uint32_t *k, uint32_t cap, uint32_t *out,
                        uint32_t *glue)
{
    enum_ctx c;
    memset(&c, 0, sizeof c);
    uint32_t n = 0;
    for (uint32_t p = 0; p < npieces; p++) {
        if (k[p] == 0 || n + k[p] > SQ_G1_MAX_SIDES) return 0;
        for (uint32_t s = 0; s < k[p]; s++) {
            c.piece_of[n + s] = p;
            c.next[n + s] = n + (s + 1) % k[p];
        }
        n += k[p];
    }
    if (n == 0 || n % 2) return 0;
    c.npieces = npieces, c.n = n, c.cap = cap, c.out = out, c.glue = glue;
    for (uint32_t i = 0; i < n; i++) c.partner[i] = UINT32_MAX;
    pair_up(&c);
    return c.count;
}

/* ---- quads to a halfedge disk -------------------------------------------- */

typedef struct he_rec {
    uint64_t key; /* origin << 32 | target */
    uint32_t h;
} he_rec;

static int cmp_rec(const void *x, const void *y)
{
    const he_rec *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return (a->h > b->h) - (a->h < b->h);
}

/* Position of key in the sorted records, or UINT32_MAX. */
static uint32_t lookup(const he_rec *r, uint32_t n, uint64_t key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (r[mid].key < key) lo = mid + 1;
        else hi = mid;
    }
    return lo < n && r[lo].key == key ? (uint32_t)lo : UINT32_MAX;
}

sq_status sq_g1_quads_to_disk(uint32_t nv, uint32_t nf, const uint32_t *quad, sq_metapolygon *Q,
                              sq_error *err)
{
    if (nf == 0 || nv == 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "empty quad disk");
    if (Q->nf || Q->nv || Q->nh)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "quads_to_disk needs an empty metapolygon");
    if ((uint64_t)nf * 8 >= SQ_NONE)
        return sq_error_set(err, SQ_ERR_NOMEM, "%u quads: too many for 32-bit halfedges", nf);
    const uint32_t ni = 4 * nf;
    he_rec *r = malloc((size_t)ni * sizeof *r);
    uint32_t *out_bnd = malloc((size_t)nv * sizeof *out_bnd);
    sq_status st = SQ_OK;
    if (!r || !out_bnd) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < ni; h++) {
        uint32_t f = h / 4, c = h % 4;
        uint32_t a = quad[4 * (size_t)f + c], b = quad[4 * (size_t)f + (c + 1) % 4];
        if (a >= nv || b >= nv || a == b) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "quad %u: bad vertex %u or %u", f, a, b);
            goto done;
        }
        r[h].key = (uint64_t)a << 32 | b;
        r[h].h = h;
    }
    qsort(r, ni, sizeof *r, cmp_rec);
    for (uint32_t t = 1; t < ni; t++)
        if (r[t].key == r[t - 1].key) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "edge %u -> %u is used twice in the same direction (not a "
                              "manifold, consistently oriented disk)",
                              (uint32_t)(r[t].key >> 32), (uint32_t)r[t].key);
            goto done;
        }
    /* count boundary halfedges: interior halfedges without a reversed twin */
    uint32_t nb = 0;
    for (uint32_t t = 0; t < ni; t++) {
        uint64_t rev = (r[t].key & 0xffffffffu) << 32 | (r[t].key >> 32);
        if (lookup(r, ni, rev) == UINT32_MAX) nb++;
    }
    st = sq_metapolygon_reserve(Q, nv, nf, (uint64_t)ni + nb, err);
    if (st) goto done;
    Q->nv = nv, Q->nf = nf, Q->nh = ni + nb, Q->nbnd = nb;
    Q->bnd_he = SQ_NONE;
    for (uint32_t v = 0; v < nv; v++) Q->v_he[v] = SQ_NONE, Q->v_nface[v] = 0, out_bnd[v] = SQ_NONE;
    for (uint32_t f = 0; f < nf; f++) {
        Q->f_he[f] = 4 * f;
        Q->f_valence[f] = 4;
        for (uint32_t c = 0; c < 4; c++) {
            uint32_t h = 4 * f + c;
            Q->he_vert[h] = quad[4 * (size_t)f + c];
            Q->he_next[h] = 4 * f + (c + 1) % 4;
            Q->he_face[h] = f;
            Q->v_nface[quad[4 * (size_t)f + c]]++;
            if (Q->v_he[Q->he_vert[h]] == SQ_NONE) Q->v_he[Q->he_vert[h]] = h;
        }
    }
    uint32_t b = ni;
    for (uint32_t t = 0; t < ni; t++) {
        const uint32_t h = r[t].h;
        uint64_t rev = (r[t].key & 0xffffffffu) << 32 | (r[t].key >> 32);
        uint32_t u = lookup(r, ni, rev);
        if (u != UINT32_MAX) {
            Q->he_twin[h] = r[u].h;
            continue;
        }
        /* boundary halfedge from the target back to the origin */
        uint32_t from = (uint32_t)r[t].key;
        if (out_bnd[from] != SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "vertex %u has two outgoing boundary edges (not a disk)", from);
            goto done;
        }
        Q->he_twin[h] = b, Q->he_twin[b] = h;
        Q->he_vert[b] = from;
        Q->he_face[b] = SQ_NONE;
        out_bnd[from] = b;
        b++;
    }
    for (uint32_t h = ni; h < ni + nb; h++) {
        uint32_t to = Q->he_vert[Q->he_twin[h]]; /* the twin runs to -> from */
        if (out_bnd[to] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "boundary breaks at vertex %u", to);
            goto done;
        }
        Q->he_next[h] = out_bnd[to];
    }
    for (uint32_t v = 0; v < nv; v++) {
        if (Q->v_he[v] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "vertex %u is in no quad", v);
            goto done;
        }
        if (out_bnd[v] != SQ_NONE) Q->v_he[v] = out_bnd[v];
    }
    if (nb) Q->bnd_he = ni;
    st = sq_metapolygon_validate(Q, 0, err);
done:
    free(r), free(out_bnd);
    return st;
}
