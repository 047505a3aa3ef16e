/* seamquad: the genus-0 domain (seed 6.5), with padding instead of the
 * seed's n x n refinement.
 *
 * Seed 6.5: on the sphere the cone valences have total excess -8, so no
 * single metapolygon exists (Prop. 5.1 needs > -4). Split the cones into
 * four groups of excess -2, build a meta-2-gon for each, glue them in two
 * pairs into two meta-0-gons (every boundary vertex flat), glue those along
 * their boundary circles into a closed quad mesh S of the sphere, and cut S
 * along one edge: a disk with two concave boundary points (seed Fig. 2 c).
 *
 * Where the seed subdivides the pieces (m x m and n x n grids) to make the
 * glued sides match, we pad (seed 6.1), which adds far fewer quads:
 *
 * - A subdivided meta-2-gon has two corners and two sides, A and B, of even
 *   lengths a, b (seed 5.4: a metapolygon side of l edges becomes 2l quad
 *   edges). Both neighbours of side B are side A, so x layers on B give
 *   a' = a + 2x, b' = b; y layers on A give b' = b + 2y. Both paddings cost
 *   x b + y a + 2 x y quads (in either order).
 * - Pair (P, Q): glue side A of P forward onto side A of Q backward. The
 *   lengths are even, so their difference is even: x = |a_P - a_Q| / 2
 *   layers on the B side of the shorter one equalize them; no refinement.
 *   The four corners become two flat points (90 + 90 degrees); the result
 *   is a meta-0-gon whose boundary circle is B_P followed by B_Q.
 * - The two perimeters b_P + b_Q and b_R + b_S are even; y = half their
 *   difference layers on the A side of one piece of the shorter pair make
 *   them equal. Each layer there costs the pair's common A length.
 * - The circles are glued reversed with a rotation offset r: every boundary
 *   vertex is flat, so every glued point gets 2 + 2 quads (360 degrees)
 *   whatever r is; r is chosen to keep S simple (below).
 * The pairing of the four pieces (3 ways) and which side of each piece is A
 * (2 ways each) are enumerated, 48 layouts, and the one with the fewest
 * quads wins (seed 9.3). With every x, y at its minimum the count is exact:
 * any further layer only adds quads.
 *
 * Simplicity: tiny pieces (a 2-gon is two quads) can glue into two edges
 * between one pair of vertices, which no mesh tool accepts. Layouts are
 * tried in order of cost and, for each, rotation offsets, until S is simple
 * and has an edge between two vertices of valence 4 (the cut edge must not
 * touch a cone: seed 6.5 keeps the cones interior). If none is, every piece
 * gets one more layer on B (keeps each pair's A sides equal) and the first
 * piece of each pair one more on A (keeps the perimeters equal), and the
 * search repeats (at most MAX_EXTRA times).
 *
 * What D holds (docs/domain.md, "Genus 0"): quads = S cut along the edge
 * (u, v), a disk whose boundary loop has two halfedges; k = 2, partner =
 * {1, 0}, corners u, v, sides of length 1: gluing side 0 onto side 1 closes
 * the cut and gives back S. meta = the first group's metapolygon; faces
 * 0 .. nf_unpadded-1 of quads subdivide it (f_meta_face), then come the
 * other groups' subdivision quads, then every padding quad. quads_unpadded
 * counts the subdivision quads of all four groups. padding has k + 8
 * entries: padding[0] = padding[1] = 0 (the two sides of D get none), then
 * for group g = 0..3 padding[2 + 2g] = layers on its B side and
 * padding[3 + 2g] = layers on its A side. order = the four groups' admissible
 * orders, group 0 first. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "sq_domain_internal.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_valence_order.h"
#include "sq_union_find.h"

/* Extra padding rounds tried when no layout glues into a simple mesh. */
#define MAX_EXTRA 4u

/* Rotation offsets tried per layout (spread over the perimeter). */
#define MAX_ROTATIONS 64u

#define NLAYOUTS 48u

/* One group of cones and its meta-2-gon (seed 6.5). */
typedef struct g0_piece {
    uint32_t ncones;
    uint32_t *order;      /* ncones: admissible order (seed 5.2)           */
    sq_metapolygon meta;  /* the meta-2-gon                                */
    sq_mp_quads sub;      /* its subdivision (seed 5.4)                    */
    uint32_t corner[2];   /* vertices of sub.mesh; side j: corner j -> j+1 */
    uint32_t len[2];      /* side lengths in quad edges (even)             */
} g0_piece;

/* Four pieces from one grouping. */
typedef struct g0_pieces {
    g0_piece p[4];
    uint64_t quads; /* subdivision quads of all four */
} g0_pieces;

/* Pairing, sides and padding (seed 6.1, 6.5): pieces pc[0], pc[1] form the
 * first meta-0-gon, pc[2], pc[3] the second. Slot j's side a[j] is its A
 * side; x[j] layers go on its B side, y[j] on its A side. */
typedef struct g0_layout {
    uint32_t id;
    uint8_t pc[4], a[4];
    uint64_t x[4], y[4];
    uint64_t added;
} g0_layout;

static void piece_free(g0_piece *p)
{
    free(p->order);
    sq_metapolygon_free(&p->meta);
    sq_mp_quads_free(&p->sub);
    memset(p, 0, sizeof *p);
}

static void pieces_free(g0_pieces *P)
{
    for (int g = 0; g < 4; g++) piece_free(&P->p[g]);
    P->quads = 0;
}

/* ---- step 1: grouping ---------------------------------------------------- */

/* Seed 6.5: four groups of total excess -2 each. The grouping is an explicit
 * choice (geometric grouping, seed 9, is later work): groups 0, 1, 2 each
 * take one valence-2 cone (the first `twos` of them) or two valence-3 cones;
 * group 3 takes every other cone.
 *
 * Why this always works: excess e(l) = l - 4 is -2 for l = 2, -1 for l = 3
 * and >= 0 for every other allowed valence (l >= 2, l != 4). With t cones of
 * valence 2, s of valence 3 and total positive excess E+ >= 0, the sum is
 * -2t - s + E+ = -8, so 2t + s = 8 + E+ >= 8. Then t + floor(s/2) >= 3:
 * t >= 3 is immediate; t = 2 gives s >= 4; t = 1 gives s >= 6; t = 0 gives
 * s >= 8. So three groups of excess -2 exist for every `twos` in
 * [max(0, 3 - floor(s/2)), min(3, t)], and group 3 has excess
 * -8 - 3 (-2) = -2 > -4: an admissible order of it exists (Prop. 5.1), and
 * it is not empty (an empty group has excess 0). group_of gets 0..3 per
 * cone. Returns 0 if `twos` is out of that range. */
static int genus0_grouping(const uint32_t *irr, uint32_t n, uint32_t twos, uint32_t *group_of)
{
    uint32_t t = 0, s = 0;
    for (uint32_t i = 0; i < n; i++) t += irr[i] == 2, s += irr[i] == 3;
    if (twos > 3 || twos > t || 3 - twos > s / 2) return 0;
    uint32_t g2 = 0, n3 = 0; /* groups given a 2; 3s handed out */
    for (uint32_t i = 0; i < n; i++) {
        group_of[i] = 3;
        if (irr[i] == 2 && g2 < twos) group_of[i] = g2++;
        else if (irr[i] == 3 && n3 < 2 * (3 - twos)) group_of[i] = twos + n3++ / 2;
    }
    assert(g2 == twos && n3 == 2 * (3 - twos));
    return 1;
}

/* ---- step 2: the meta-2-gons ---------------------------------------------- */

static sq_status build_piece(g0_piece *p, const uint32_t *vals, uint32_t nv,
                             const sq_build_options *bopt, uint32_t group, sq_error *err)
{
    p->order = malloc(((size_t)nv + 1) * sizeof *p->order);
    if (!p->order) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    p->ncones = nv;
    sq_metapolygon_init(&p->meta);
    int64_t e = sq_valence_excess(vals, nv);
    if (e != -2)
        return sq_error_set(err, SQ_ERR_INTERNAL, "genus 0: cone group %u has excess %lld, not -2",
                            group, (long long)e);
    /* seed 5.2: positive excess first */
    sq_status st = sq_valence_order_admissible(vals, nv, p->order, err);
    if (st == SQ_OK) st = sq_metapolygon_build(&p->meta, p->order, nv, bopt, NULL, err);
    if (st == SQ_OK) st = sq_metapolygon_subdivide(&p->meta, &p->sub, err);
    if (st) return st;
    if (p->sub.ncorner != 2)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "genus 0: cone group %u gives a meta-%u-gon, expected a meta-2-gon",
                            group, p->sub.ncorner);
    for (int j = 0; j < 2; j++) {
        p->corner[j] = p->sub.bnd_vert[p->sub.corner_pos[j]];
        p->len[j] = p->sub.side_len[j];
        if (p->len[j] == 0 || p->len[j] % 2)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "genus 0: side %d of group %u has odd length %u", j, group,
                                p->len[j]);
    }
    return SQ_OK;
}

static uint64_t best_total(const g0_pieces *P);

/* Orders tried for the last group, whose metapolygon size depends strongly
 * on the order of its valences (seed 5.3; e.g. mpz/homer's group: 886 to
 * 1086 quads over a few orders): the input order, valences descending, and
 * deterministic shuffles; fewer for large groups. */
static uint32_t orders_to_try(uint32_t m)
{
    return m <= 256 ? 8 : m <= 2048 ? 4 : 1;
}

static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static int cmp_desc(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a < b) - (a > b);
}

/* Groups 0-2 (one 2 or two 3s: a single order each) and, for group 3, the
 * order among orders_to_try that gives the fewest quads after minimal
 * padding (sq_valence_order_admissible keeps the input order within the
 * positive and the negative valences, so permuting its input picks among
 * admissible orders). */
static sq_status build_pieces(const uint32_t *irr, uint32_t n, const uint32_t *group_of,
                              const sq_build_options *bopt, g0_pieces *P, sq_error *err)
{
    memset(P, 0, sizeof *P);
    uint32_t *vals = malloc(((size_t)n + 1) * sizeof *vals);
    if (!vals) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    sq_status st = SQ_OK;
    uint32_t m = 0;
    for (uint32_t g = 0; g < 4 && st == SQ_OK; g++) {
        m = 0;
        for (uint32_t i = 0; i < n; i++)
            if (group_of[i] == g) vals[m++] = irr[i];
        st = build_piece(&P->p[g], vals, m, bopt, g, err);
        if (st == SQ_OK) P->quads += P->p[g].sub.mesh.nf;
    }
    uint64_t best = st == SQ_OK ? best_total(P) : 0, rs = 0x5eedull ^ n;
    const uint32_t tries = orders_to_try(m);
    for (uint32_t t = 1; t < tries && st == SQ_OK; t++) {
        if (t == 1) {
            qsort(vals, m, sizeof *vals, cmp_desc);
        } else {
            for (uint32_t i = m; i > 1; i--) {
                uint32_t j = (uint32_t)(splitmix64(&rs) % i), x = vals[i - 1];
                vals[i - 1] = vals[j], vals[j] = x;
            }
        }
        g0_piece keep = P->p[3];
        memset(&P->p[3], 0, sizeof P->p[3]);
        st = build_piece(&P->p[3], vals, m, bopt, 3, err);
        if (st) {
            piece_free(&keep);
            break;
        }
        const uint64_t q_old = P->quads;
        P->quads = q_old - keep.sub.mesh.nf + P->p[3].sub.mesh.nf;
        uint64_t total = best_total(P);
        if (total < best) {
            best = total;
            piece_free(&keep);
        } else {
            piece_free(&P->p[3]);
            P->p[3] = keep;
            P->quads = q_old;
        }
    }
    free(vals);
    return st;
}

/* ---- step 3: padding choice ------------------------------------------------ */

static const uint8_t pairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};

/* Layout `id` (pairing id / 16, A sides from the bits of id % 16) with the
 * minimal padding plus `extra` layers (see the header comment). */
static void make_layout(const g0_pieces *P, uint32_t id, uint64_t extra, g0_layout *L)
{
    memset(L, 0, sizeof *L);
    L->id = id;
    uint64_t A[4], B[4];
    for (int j = 0; j < 4; j++) {
        L->pc[j] = pairings[id / 16][j];
        L->a[j] = (uint8_t)((id >> j) & 1u);
        const g0_piece *p = &P->p[L->pc[j]];
        A[j] = p->len[L->a[j]];
        B[j] = p->len[1 - L->a[j]];
    }
    uint64_t per[2];
    for (int q = 0; q < 2; q++) {
        int j0 = 2 * q, j1 = 2 * q + 1;
        uint64_t la = A[j0] > A[j1] ? A[j0] : A[j1];
        L->x[j0] = (la - A[j0]) / 2 + extra;
        L->x[j1] = (la - A[j1]) / 2 + extra;
        L->y[j0] = extra;
        per[q] = B[j0] + B[j1];
    }
    if (per[0] < per[1]) L->y[0] += (per[1] - per[0]) / 2;
    else L->y[2] += (per[0] - per[1]) / 2;
    for (int j = 0; j < 4; j++)
        L->added += L->x[j] * B[j] + L->y[j] * A[j] + 2 * L->x[j] * L->y[j];
}

static int cmp_layout(const void *x, const void *y)
{
    const g0_layout *a = x, *b = y;
    if (a->added != b->added) return a->added < b->added ? -1 : 1;
    return (a->id > b->id) - (a->id < b->id);
}

/* ---- padding and gluing ---------------------------------------------------- */

/* The boundary vertex `steps` edges after boundary vertex v. */
static uint32_t walk(const sq_metapolygon *Q, uint32_t v, uint64_t steps)
{
    uint32_t h = Q->v_he[v];
    assert(Q->he_face[h] == SQ_NONE);
    for (uint64_t t = 0; t < steps; t++) h = Q->he_next[h];
    return Q->he_vert[h];
}

/* Seed 6.1 on a meta-2-gon: w layers on side s (corner[s] -> corner[1-s]);
 * the other side grows by 2w and the corners move to the strip's ends. */
static sq_status pad_side(sq_metapolygon *Q, uint32_t corner[2], uint32_t len[2], int s,
                          uint64_t w, sq_error *err)
{
    if (w == 0) return SQ_OK;
    const int o = 1 - s;
    if (w > UINT32_MAX / 4 || (uint64_t)len[o] + 2 * w > UINT32_MAX / 4)
        return sq_error_set(err, SQ_ERR_NOMEM, "genus 0: padding of %llu layers is too large",
                            (unsigned long long)w);
    sq_status st = sq_metapolygon_glue_grid(Q, Q->v_he[corner[s]], (uint32_t)w, len[s], 1, err);
    if (st) return st;
    /* corner[o] is untouched: side o, then w edges up the strip */
    corner[s] = walk(Q, corner[o], (uint64_t)len[o] + w);
    corner[o] = walk(Q, corner[s], len[s]);
    len[o] += 2 * (uint32_t)w;
    assert(Q->v_nface[corner[0]] == 1 && Q->v_nface[corner[1]] == 1);
    return SQ_OK;
}

/* The padded pieces of one layout, ready for gluing. */
typedef struct g0_padded {
    sq_metapolygon W[4];  /* slot j: piece pc[j], padded          */
    uint32_t corner[4][2], len[4][2];
    uint32_t base[4];     /* first global vertex of slot j        */
    uint32_t nv, nf;      /* totals                               */
    uint32_t per;         /* common perimeter of the two circles  */
    uint32_t *circle[2];  /* per global vertices each, in order   */
    uint32_t *parent, *cls, *fv, *key_he;
    uint64_t *key;
    uint32_t ncls;
} g0_padded;

static void padded_free(g0_padded *G)
{
    for (int j = 0; j < 4; j++) sq_metapolygon_free(&G->W[j]);
    free(G->circle[0]), free(G->circle[1]);
    free(G->parent), free(G->cls), free(G->fv), free(G->key), free(G->key_he);
    memset(G, 0, sizeof *G);
}

/* Pads the four pieces as L says and prepares the gluing data. */
static sq_status pad_layout(const g0_pieces *P, const g0_layout *L, g0_padded *G, sq_error *err)
{
    memset(G, 0, sizeof *G);
    sq_status st = SQ_OK;
    uint64_t nv = 0, nf = 0;
    for (int j = 0; j < 4 && st == SQ_OK; j++) {
        const g0_piece *p = &P->p[L->pc[j]];
        sq_metapolygon_init(&G->W[j]);
        st = sq_metapolygon_copy(&G->W[j], &p->sub.mesh, err);
        G->corner[j][0] = p->corner[0], G->corner[j][1] = p->corner[1];
        G->len[j][0] = p->len[0], G->len[j][1] = p->len[1];
        const int a = L->a[j];
        if (st == SQ_OK) st = pad_side(&G->W[j], G->corner[j], G->len[j], 1 - a, L->x[j], err);
        if (st == SQ_OK) st = pad_side(&G->W[j], G->corner[j], G->len[j], a, L->y[j], err);
        G->base[j] = (uint32_t)nv;
        nv += G->W[j].nv;
        nf += G->W[j].nf;
        if (nf > UINT32_MAX / 8 || nv > UINT32_MAX / 8)
            st = sq_error_set(err, SQ_ERR_NOMEM, "genus 0: domain too large for 32-bit indices");
    }
    if (st) return st;
    G->nv = (uint32_t)nv, G->nf = (uint32_t)nf;
    /* the invariants the padding promised */
    for (int q = 0; q < 2; q++) {
        int j0 = 2 * q, j1 = 2 * q + 1;
        if (G->len[j0][L->a[j0]] != G->len[j1][L->a[j1]])
            return sq_error_set(err, SQ_ERR_INTERNAL, "genus 0: A sides of pair %d differ", q);
    }
    uint64_t per0 = (uint64_t)G->len[0][1 - L->a[0]] + G->len[1][1 - L->a[1]];
    uint64_t per1 = (uint64_t)G->len[2][1 - L->a[2]] + G->len[3][1 - L->a[3]];
    uint64_t unpadded = 0;
    for (int j = 0; j < 4; j++) unpadded += P->p[L->pc[j]].sub.mesh.nf;
    if (per0 != per1 || nf - unpadded != L->added)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "genus 0: perimeters %llu, %llu; padding added %llu quads, predicted "
                            "%llu",
                            (unsigned long long)per0, (unsigned long long)per1,
                            (unsigned long long)(nf - unpadded), (unsigned long long)L->added);
    G->per = (uint32_t)per0;
    G->circle[0] = malloc((size_t)G->per * sizeof(uint32_t));
    G->circle[1] = malloc((size_t)G->per * sizeof(uint32_t));
    G->parent = malloc((size_t)G->nv * sizeof(uint32_t));
    G->cls = malloc((size_t)G->nv * sizeof(uint32_t));
    G->fv = malloc(4 * (size_t)G->nf * sizeof(uint32_t));
    G->key = malloc(4 * (size_t)G->nf * sizeof(uint64_t));
    G->key_he = malloc(4 * (size_t)G->nf * sizeof(uint32_t));
    if (!G->circle[0] || !G->circle[1] || !G->parent || !G->cls || !G->fv || !G->key ||
        !G->key_he)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    /* circle q: side B of slot 2q, then side B of slot 2q+1 (after the A
     * sides are glued, corner B-start of one is the A-end of the other) */
    for (int q = 0; q < 2; q++) {
        uint32_t c = 0;
        for (int j = 2 * q; j < 2 * q + 2; j++) {
            const sq_metapolygon *W = &G->W[j];
            const int b = 1 - L->a[j];
            uint32_t h = W->v_he[G->corner[j][b]];
            for (uint32_t t = 0; t < G->len[j][b]; t++) {
                G->circle[q][c++] = G->base[j] + W->he_vert[h];
                h = W->he_next[h];
            }
        }
        assert(c == G->per);
    }
    return SQ_OK;
}

/* Glues the padded pieces with rotation offset r into the sphere S: vertex
 * classes in G->cls (0 .. G->ncls-1), faces in G->fv (4 per quad, slot
 * order, each slot's faces in index order). */
static void glue_sphere(const g0_layout *L, g0_padded *G, uint32_t r)
{
    for (uint32_t v = 0; v < G->nv; v++) G->parent[v] = v;
    /* pairs: side A of slot 2q forward onto side A of slot 2q+1 backward */
    for (int q = 0; q < 2; q++) {
        const int j0 = 2 * q, j1 = 2 * q + 1;
        const uint32_t len = G->len[j0][L->a[j0]];
        uint32_t h0 = G->W[j0].v_he[G->corner[j0][L->a[j0]]];
        uint32_t v1 = G->corner[j1][L->a[j1]];
        /* the vertices of A1 backward: walk A1 forward into a scratch run
         * (G->cls is free until the classes are numbered) */
        uint32_t h1 = G->W[j1].v_he[v1];
        for (uint32_t t = 0; t <= len; t++) {
            G->cls[t] = G->base[j1] + G->W[j1].he_vert[h1];
            h1 = G->W[j1].he_next[h1];
        }
        for (uint32_t t = 0; t <= len; t++) {
            sq_uf_union(G->parent, G->base[j0] + G->W[j0].he_vert[h0], G->cls[len - t]);
            h0 = G->W[j0].he_next[h0];
        }
    }
    /* the circles, reversed, rotated by r */
    for (uint32_t t = 0; t < G->per; t++)
        sq_uf_union(G->parent, G->circle[0][t], G->circle[1][(r + G->per - t) % G->per]);
    uint32_t nc = 0;
    for (uint32_t v = 0; v < G->nv; v++) G->cls[v] = SQ_NONE;
    for (uint32_t v = 0; v < G->nv; v++) {
        uint32_t root = sq_uf_find(G->parent, v);
        if (G->cls[root] == SQ_NONE) G->cls[root] = nc++;
        G->cls[v] = G->cls[root];
    }
    G->ncls = nc;
    uint32_t c = 0;
    for (int j = 0; j < 4; j++) {
        const sq_metapolygon *W = &G->W[j];
        for (uint32_t f = 0; f < W->nf; f++) {
            uint32_t h = W->f_he[f];
            for (int i = 0; i < 4; i++) {
                G->fv[c++] = G->cls[G->base[j] + W->he_vert[h]];
                h = W->he_next[h];
            }
        }
    }
    assert(c == 4 * G->nf);
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Looks up directed edge (u, v) among the sorted keys; SQ_NONE if absent. */
static uint32_t find_key(const uint64_t *key, uint32_t n, uint64_t want)
{
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (key[mid] < want) lo = mid + 1;
        else hi = mid;
    }
    return lo < n && key[lo] == want ? lo : SQ_NONE;
}

/* 1 if the sphere in G->fv is a simple closed quad mesh (no quad repeats a
 * vertex; every directed edge once, with its reverse; V - E + F = 2), and
 * then *cut gets a halfedge (index into fv) between two vertices of valence
 * 4, or SQ_NONE if there is none. Leaves G->key sorted (key << 32 | he). */
static int sphere_is_simple(g0_padded *G, uint32_t *val, uint32_t *cut)
{
    const uint32_t nh = 4 * G->nf;
    *cut = SQ_NONE;
    memset(val, 0, (size_t)G->ncls * sizeof *val);
    for (uint32_t f = 0; f < G->nf; f++) {
        const uint32_t *q = G->fv + 4 * (size_t)f;
        for (int i = 0; i < 4; i++) {
            val[q[i]]++;
            for (int k = i + 1; k < 4; k++)
                if (q[i] == q[k]) return 0;
        }
    }
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t f = h / 4, i = h % 4;
        uint64_t u = G->fv[h], v = G->fv[4 * f + (i + 1) % 4];
        G->key[h] = u << 32 | v;
    }
    qsort(G->key, nh, sizeof *G->key, cmp_u64);
    for (uint32_t h = 1; h < nh; h++)
        if (G->key[h] == G->key[h - 1]) return 0;
    for (uint32_t h = 0; h < nh; h++) {
        uint64_t k = G->key[h], rev = (k & 0xffffffffu) << 32 | k >> 32;
        if (find_key(G->key, nh, rev) == SQ_NONE) return 0;
    }
    if ((int64_t)G->ncls - (int64_t)nh / 2 + (int64_t)G->nf != 2) return 0;
    for (uint32_t h = 0; h < nh && *cut == SQ_NONE; h++) {
        uint32_t f = h / 4, i = h % 4;
        if (val[G->fv[h]] == 4 && val[G->fv[4 * f + (i + 1) % 4]] == 4) *cut = h;
    }
    return 1;
}

/* ---- step 4: the disk D = S cut along one edge ----------------------------- */

/* The quad disk of S (faces fv, 4 each, nc vertices, simple and closed, keys
 * sorted by sphere_is_simple) cut along the edge of face halfedge `cut`:
 * an sq_metapolygon whose boundary loop is the two sides of that edge.
 * Faces keep the order of fv; face halfedges are 4f .. 4f+3. */
static sq_status quads_from_sphere(g0_padded *G, const uint32_t *val, uint32_t cut,
                                   sq_metapolygon *Q, sq_error *err)
{
    const uint32_t nf = G->nf, nc = G->ncls, nh = 4 * nf + 2;
    sq_metapolygon_init(Q);
    Q->he_next = malloc((size_t)nh * sizeof(uint32_t));
    Q->he_twin = malloc((size_t)nh * sizeof(uint32_t));
    Q->he_vert = malloc((size_t)nh * sizeof(uint32_t));
    Q->he_face = malloc((size_t)nh * sizeof(uint32_t));
    Q->v_he = malloc((size_t)nc * sizeof(uint32_t));
    Q->v_nface = malloc((size_t)nc * sizeof(uint32_t));
    Q->f_he = malloc((size_t)nf * sizeof(uint32_t));
    Q->f_valence = malloc((size_t)nf * sizeof(uint32_t));
    if (!Q->he_next || !Q->he_twin || !Q->he_vert || !Q->he_face || !Q->v_he || !Q->v_nface ||
        !Q->f_he || !Q->f_valence) {
        sq_metapolygon_free(Q);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    Q->nv = Q->cap_v = nc;
    Q->nf = Q->cap_f = nf;
    Q->nh = Q->cap_h = nh;
    memcpy(Q->v_nface, val, (size_t)nc * sizeof *val);
    for (uint32_t f = 0; f < nf; f++) {
        Q->f_he[f] = 4 * f;
        Q->f_valence[f] = 4;
        for (uint32_t i = 0; i < 4; i++) {
            uint32_t h = 4 * f + i;
            Q->he_vert[h] = G->fv[h];
            Q->he_next[h] = 4 * f + (i + 1) % 4;
            Q->he_face[h] = f;
            Q->v_he[G->fv[h]] = h;
        }
    }
    /* twins: the halfedge of the reversed key. The sorted keys lost their
     * halfedge indices, so index them again: key_he[k] = halfedge of key k */
    for (uint32_t h = 0; h < 4 * nf; h++) {
        uint32_t f = h / 4, i = h % 4;
        uint64_t k = (uint64_t)G->fv[h] << 32 | G->fv[4 * f + (i + 1) % 4];
        G->key_he[find_key(G->key, 4 * nf, k)] = h;
    }
    for (uint32_t h = 0; h < 4 * nf; h++) {
        uint32_t f = h / 4, i = h % 4;
        uint64_t rev = (uint64_t)G->fv[4 * f + (i + 1) % 4] << 32 | G->fv[h];
        Q->he_twin[h] = G->key_he[find_key(G->key, 4 * nf, rev)];
    }
    /* the cut: h1 = u -> v and h2 = v -> u get boundary twins b1 (v -> u)
     * and b2 (u -> v), which form the boundary loop b1, b2 */
    const uint32_t h1 = cut, h2 = Q->he_twin[cut], b1 = 4 * nf, b2 = 4 * nf + 1;
    const uint32_t u = Q->he_vert[h1], v = Q->he_vert[h2];
    Q->he_twin[h1] = b1, Q->he_twin[b1] = h1;
    Q->he_twin[h2] = b2, Q->he_twin[b2] = h2;
    Q->he_vert[b1] = v, Q->he_vert[b2] = u;
    Q->he_face[b1] = Q->he_face[b2] = SQ_NONE;
    Q->he_next[b1] = b2, Q->he_next[b2] = b1;
    Q->v_he[u] = b2, Q->v_he[v] = b1;
    Q->bnd_he = b2;
    Q->nbnd = 2;
    return sq_metapolygon_validate(Q, 0, err);
}

/* ---- the builder --------------------------------------------------------- */

/* Cheapest total over the 48 layouts of P (minimal padding). */
static uint64_t best_total(const g0_pieces *P)
{
    uint64_t best = UINT64_MAX;
    for (uint32_t id = 0; id < NLAYOUTS; id++) {
        g0_layout L;
        make_layout(P, id, 0, &L);
        if (L.added < best) best = L.added;
    }
    return best + P->quads;
}

/* Step 4: D from the pieces (best), the layout chosen, the glued sphere G
 * (val: its scratch; cut: the regular edge to cut it along). Faces:
 * group 0's subdivision quads first (they index D->meta), then the other
 * groups', then the padding quads. */
static sq_status assemble_domain(sq_domain *D, const g0_pieces *best, const g0_layout *chosen, g0_padded *G,
                                 uint32_t *val, uint32_t cut, uint32_t n, sq_error *err)
{
    sq_status st = SQ_OK;
    uint32_t *perm = malloc(((size_t)G->nf + 1) * sizeof *perm);
    uint32_t *fv2 = malloc(4 * ((size_t)G->nf + 1) * sizeof *fv2);
    uint32_t *origin = malloc(((size_t)G->nf + 1) * sizeof *origin);
    if (!perm || !fv2 || !origin) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    uint32_t first[4], c = 0, slot0 = 0;
    if (st == SQ_OK) {
        for (int j = 0; j < 4; j++) {
            first[j] = j ? first[j - 1] + G->W[j - 1].nf : 0;
            if (chosen->pc[j] == 0) slot0 = (uint32_t)j;
        }
        /* subdivision quads of slot0, then of the others, then padding */
        for (uint32_t pass = 0; pass < 3; pass++) {
            for (uint32_t j = 0; j < 4; j++) {
                uint32_t nsub = best->p[chosen->pc[j]].sub.mesh.nf;
                uint32_t lo = pass == 2 ? nsub : 0, hi = pass == 2 ? G->W[j].nf : nsub;
                if ((pass == 0) != (j == slot0) && pass != 2) continue;
                for (uint32_t f = lo; f < hi; f++) {
                    origin[c] = f;
                    perm[c++] = first[j] + f;
                }
            }
        }
        assert(c == G->nf);
        uint32_t cut_new = SQ_NONE;
        for (uint32_t f = 0; f < G->nf; f++) {
            memcpy(fv2 + 4 * (size_t)f, G->fv + 4 * (size_t)perm[f], 4 * sizeof *fv2);
            if (perm[f] == cut / 4) cut_new = 4 * f + cut % 4;
        }
        memcpy(G->fv, fv2, 4 * (size_t)G->nf * sizeof *fv2);
        /* re-sort the keys for the new face order (same edges) */
        for (uint32_t h = 0; h < 4 * G->nf; h++) {
            uint32_t f = h / 4, i = h % 4;
            G->key[h] = (uint64_t)G->fv[h] << 32 | G->fv[4 * f + (i + 1) % 4];
        }
        qsort(G->key, 4 * (size_t)G->nf, sizeof *G->key, cmp_u64);
        st = quads_from_sphere(G, val, cut_new, &D->quads, err);
    }
    const g0_piece *p0 = &best->p[0];
    uint32_t nf0 = p0->sub.mesh.nf;
    if (st == SQ_OK) {
        D->k = 2;
        D->offset = 0;
        D->refine = 1;
        D->offsets_feasible = 1;
        D->quads_unpadded = best->quads;
        D->quads_added = chosen->added;
        D->nf_unpadded = nf0;
        D->f_meta_face = malloc(((size_t)nf0 + 1) * sizeof *D->f_meta_face);
        D->corner_vert = malloc(2 * sizeof *D->corner_vert);
        D->side_len = malloc(2 * sizeof *D->side_len);
        D->padding = calloc(2 + 8, sizeof *D->padding);
        if (!D->f_meta_face || !D->corner_vert || !D->side_len || !D->padding)
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    if (st == SQ_OK) st = sq_metapolygon_copy(&D->meta, &p0->meta, err);
    if (st == SQ_OK) st = sq_pattern_alloc(&D->pattern, 2, err);
    if (st == SQ_OK) {
        for (uint32_t f = 0; f < nf0; f++)
            D->f_meta_face[f] = D->meta.he_face[p0->sub.f_origin[origin[f]]];
        D->pattern.partner[0] = 1, D->pattern.partner[1] = 0;
        D->corner_vert[0] = D->quads.he_vert[D->quads.bnd_he];
        D->corner_vert[1] = D->quads.he_vert[D->quads.he_next[D->quads.bnd_he]];
        D->side_len[0] = D->side_len[1] = 1;
        for (int j = 0; j < 4; j++) {
            D->padding[2 + 2 * chosen->pc[j]] = (int64_t)chosen->x[j];
            D->padding[3 + 2 * chosen->pc[j]] = (int64_t)chosen->y[j];
        }
        /* construction order: group 0 first */
        uint32_t m = 0;
        for (int g = 0; g < 4; g++) {
            memcpy(D->order + m, best->p[g].order, best->p[g].ncones * sizeof *D->order);
            m += best->p[g].ncones;
        }
        assert(m == n);
        D->ncones = n;
    }
    free(perm), free(fv2), free(origin);
    return st;
}

sq_status sq_domain_build_genus0(const uint32_t *irr, uint32_t n, const sq_domain_options *opt,
                                 sq_domain *D, sq_error *err)
{
    if (opt && opt->pattern)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "genus 0: a side-pairing pattern does not apply (the sphere's domain "
                            "is cut along one edge, seed 6.5)");
    if (opt && opt->offset != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "genus 0: a side correspondence offset does not apply (seed 6.5)");
    if (opt && opt->build && opt->build->glue_he)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "genus 0: per-step glue edges do not apply to the four pieces; give a "
                            "chooser instead");
    const sq_build_options *bopt = opt ? opt->build : NULL;
    int64_t excess = sq_valence_excess(irr, n);
    for (uint32_t i = 0; i < n; i++)
        if (irr[i] < 2 || irr[i] == 4)
            return sq_error_set(err, SQ_ERR_ARGUMENT, "genus 0: valence %u of cone %u", irr[i], i);
    if (excess != -8)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "genus 0: the valences have total excess %lld, the sphere needs -8",
                            (long long)excess);

    uint32_t *group_of = malloc(((size_t)n + 1) * sizeof *group_of);
    if (!group_of) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    sq_status st = SQ_OK;

    /* steps 1-2: every admissible number of valence-2 groups; the grouping
     * with the fewest quads after minimal padding wins */
    g0_pieces best, cand;
    memset(&best, 0, sizeof best);
    uint64_t best_quads = UINT64_MAX;
    for (uint32_t twos = 0; twos <= 3 && st == SQ_OK; twos++) {
        if (!genus0_grouping(irr, n, twos, group_of)) continue;
        st = build_pieces(irr, n, group_of, bopt, &cand, err);
        if (st) {
            pieces_free(&cand);
            break;
        }
        uint64_t total = best_total(&cand);
        if (total < best_quads) {
            pieces_free(&best);
            best = cand;
            best_quads = total;
        } else {
            pieces_free(&cand);
        }
    }
    free(group_of);
    if (st == SQ_OK && best_quads == UINT64_MAX)
        st = sq_error_set(err, SQ_ERR_INTERNAL, "genus 0: no grouping of the cones (a bug)");
    if (st) {
        pieces_free(&best);
        return st;
    }

    /* step 3: layouts by cost; the first that glues simple wins */
    g0_layout lay[NLAYOUTS], chosen;
    memset(&chosen, 0, sizeof chosen);
    g0_padded G;
    memset(&G, 0, sizeof G);
    uint32_t *val = NULL, cut = SQ_NONE;
    int found = 0;
    for (uint32_t extra = 0; extra <= MAX_EXTRA && !found && st == SQ_OK; extra++) {
        for (uint32_t id = 0; id < NLAYOUTS; id++) make_layout(&best, id, extra, &lay[id]);
        qsort(lay, NLAYOUTS, sizeof lay[0], cmp_layout);
        for (uint32_t c = 0; c < NLAYOUTS && !found && st == SQ_OK; c++) {
            padded_free(&G);
            st = pad_layout(&best, &lay[c], &G, err);
            if (st) break;
            free(val);
            val = malloc(((size_t)G.nv + 1) * sizeof *val);
            if (!val) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                break;
            }
            const uint32_t nrot = G.per < MAX_ROTATIONS ? G.per : MAX_ROTATIONS;
            for (uint32_t t = 0; t < nrot && !found; t++) {
                uint32_t r = (uint32_t)((uint64_t)t * G.per / nrot);
                glue_sphere(&lay[c], &G, r);
                if (sphere_is_simple(&G, val, &cut) && cut != SQ_NONE) {
                    found = 1;
                    chosen = lay[c];
                }
            }
        }
    }
    if (st == SQ_OK && !found)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "genus 0: no layout of the four pieces glues into a simple quad mesh "
                          "with a regular edge, even with %u extra layers",
                          MAX_EXTRA);

    /* step 4: D */
    if (st == SQ_OK) st = assemble_domain(D, &best, &chosen, &G, val, cut, n, err);
    padded_free(&G);
    free(val);
    pieces_free(&best);
    if (st == SQ_OK && !sq_domain_glued_is_simple(D))
        st = sq_error_set(err, SQ_ERR_INTERNAL, "genus 0: the glued domain is not simple (a bug)");
    return st;
}
