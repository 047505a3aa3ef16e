/* seamquad: Omega cut into rectangles by straight chords, the coarse
 * tessellation for the interior map (seed 8; seed 10: "any coarse
 * tessellation (e.g., using one large rectangular face instead of a grid
 * of many quads ...) is sufficient"; seamless-notes 5, compatible
 * triangulation with rectangles for triangles). See sq_omega_cells.h and
 * docs/omega.md section 6.
 *
 * Why the result is a set of rectangles. Omega_c is a disk of unit squares
 * immersed in the plane; a chord is a simple path (its layout is strictly
 * monotone along one axis) from a boundary vertex to the boundary or an
 * earlier chord, so every chord splits one region (a disk) into two disks:
 * cells = chords + 1. A region's corners are the sectors of its boundary
 * vertices. Once no sector spans more than two quads (180 degrees), a
 * region's boundary only turns left, by 90 degrees at a one-quad sector;
 * its total turning is 360 degrees, so it has exactly four corners: an
 * axis-parallel rectangle boundary, and an immersed disk bounded by an
 * embedded curve is embedded (it covers the inside once).
 *
 * How many chords. A sector of q >= 3 quads needs at least
 * need(q) = floor((q - 1) / 2) chords leaving it; a chord along the j-th
 * interior edge (counted counterclockwise) leaves sub-sectors j and q - j
 * and pays off at the start iff need(q) = 1 + need(j) + need(q - j). Where
 * it ends, it splits the sector it arrives in, which may lower that
 * sector's need too (two reflex corners facing each other along a grid
 * line need one chord, not two). Phase 1 adds only chords that pay off at
 * both ends, phase 2 the rest; sectors are always recomputed from the
 * current chord set.
 *
 * Phase 3 (on request: max_side, face_limit) halves long cells: a chord
 * along the grid line nearest the middle of a cell's longer side, from
 * one side to the opposite (a T-junction at both ends, possibly on earlier
 * chords), again until every cell fits its limit. Such a chord splits a
 * rectangle into two rectangles, so the argument above still holds. The
 * surface stage asks for it where Tutte's map of a cell failed
 * (sq_param_interior.c, step 7c).
 *
 * Rotation around a vertex v (faces counterclockwise, sq_metapolygon.h):
 * for a face halfedge h leaving v, twin(prev(h)) is the next outgoing
 * halfedge counterclockwise (across face(h)), next(twin(h)) the next one
 * clockwise. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega_cells.h"
#include "sq_omega_cells_internal.h"

void sq_omega_cells_init(sq_omega_cells *C) { memset(C, 0, sizeof *C); }

void sq_omega_cells_free(sq_omega_cells *C)
{
    free(C->chord);
    free(C->chord_he);
    free(C->he_chord);
    free(C->f_cell);
    free(C->cell_box);
    sq_omega_cells_init(C);
}

typedef struct builder {
    const sq_metapolygon *P;
    uint8_t *on_bnd;   /* nv: vertex on Omega_c's boundary                  */
    uint8_t *on_chord; /* nv: vertex on some chord                          */
    uint8_t *cut;      /* nh: the edge is a boundary or chord edge          */
    sq_omega_cells *C;
    uint32_t cap_chord, nchord_he;
} builder;

static uint32_t head(const sq_metapolygon *P, uint32_t h) { return P->he_vert[P->he_next[h]]; }

static uint32_t prev_in_face(const sq_metapolygon *P, uint32_t h)
{
    uint32_t g = h;
    while (P->he_next[g] != h) g = P->he_next[g];
    return g;
}

/* next outgoing halfedge counterclockwise (h a face halfedge leaving v) */
static uint32_t ccw(const sq_metapolygon *P, uint32_t h)
{
    return P->he_twin[prev_in_face(P, h)];
}

/* the straight continuation of halfedge a across its head, a regular
 * interior vertex: the edge opposite a among the four */
static uint32_t straight(const sq_metapolygon *P, uint32_t a)
{
    return P->he_next[P->he_twin[P->he_next[a]]];
}

static uint32_t need(uint32_t q) { return q >= 3 ? (q - 1) / 2 : 0; }

/* The face halfedge bounding, on its clockwise side, the sector that
 * contains the (uncut) outgoing face halfedge h: the first cut halfedge
 * clockwise from h. SQ_NONE if there is none within the valence. */
static uint32_t sector_bound(const builder *B, uint32_t h)
{
    const sq_metapolygon *P = B->P;
    uint32_t g = h;
    for (uint32_t steps = 0; steps <= P->nh; steps++) {
        g = P->he_next[P->he_twin[g]];
        if (g == h) return SQ_NONE;
        if (B->cut[g]) return P->he_face[g] == SQ_NONE ? SQ_NONE : g;
    }
    return SQ_NONE;
}

/* Walks counterclockwise from the sector bound s: *a = faces from s up to
 * the outgoing halfedge h (SQ_NONE: any), *q = faces of the whole sector. */
static void sector_split(const builder *B, uint32_t s, uint32_t h, uint32_t *a, uint32_t *q)
{
    const sq_metapolygon *P = B->P;
    uint32_t g = s, n = 0;
    *a = 0;
    do {
        g = ccw(P, g);
        n++;
        if (g == h) *a = n;
    } while (!B->cut[g] && n <= P->nh);
    *q = n;
}

/* Sectors of boundary vertex v in counterclockwise order, from the face
 * halfedge along the incoming boundary edge to the outgoing one: bound[i]
 * (the sector's clockwise face halfedge) and size[i] (quads). Returns the
 * count, at most cap. */
static uint32_t sectors(const builder *B, uint32_t v, uint32_t *bound, uint32_t *size,
                        uint32_t cap)
{
    const sq_metapolygon *P = B->P;
    uint32_t bout = P->v_he[v];
    while (P->he_face[bout] != SQ_NONE) bout = P->he_next[P->he_twin[bout]];
    /* clockwise from bout to the last outgoing halfedge before it: the
     * face halfedge along the incoming boundary edge */
    uint32_t s = P->he_next[P->he_twin[bout]];
    while (P->he_next[P->he_twin[s]] != bout) s = P->he_next[P->he_twin[s]];
    uint32_t n = 0, g = s, q = 0;
    for (;;) {
        g = ccw(P, g);
        q++;
        if (!B->cut[g]) continue;
        if (n < cap) bound[n] = s, size[n] = q;
        n++;
        if (P->he_face[g] == SQ_NONE) break;
        s = g, q = 0;
    }
    return n;
}

/* Traces the chord leaving along h; returns its last halfedge, *len.
 * SQ_NONE if it runs longer than Omega_c has edges (impossible when every
 * interior vertex is regular: the layout is monotone along the chord). */
static uint32_t trace(const builder *B, uint32_t h, uint32_t *len)
{
    const sq_metapolygon *P = B->P;
    uint32_t n = 1;
    for (;;) {
        uint32_t x = head(P, h);
        if (B->on_bnd[x] || B->on_chord[x]) break;
        if (n > P->nh / 2) return SQ_NONE;
        h = straight(P, h);
        n++;
    }
    *len = n;
    return h;
}

/* What a chord with last halfedge `last` saves at its end: the need of
 * the sector it arrives in minus the needs of the two parts; *end_bound
 * names that sector. */
static uint32_t end_gain(const builder *B, uint32_t last, uint32_t *end_bound)
{
    const sq_metapolygon *P = B->P;
    uint32_t t = P->he_twin[last];
    uint32_t s = sector_bound(B, t);
    *end_bound = s;
    if (s == SQ_NONE) return 0;
    uint32_t a, q;
    sector_split(B, s, t, &a, &q);
    return need(q) - need(a) - need(q - a);
}

static sq_status add_chord(builder *B, uint32_t h1, sq_error *err)
{
    const sq_metapolygon *P = B->P;
    sq_omega_cells *C = B->C;
    uint32_t len = 0, last = trace(B, h1, &len), eb = SQ_NONE;
    if (last != SQ_NONE) (void)end_gain(B, last, &eb);
    uint32_t sb = sector_bound(B, h1);
    if (sb == SQ_NONE || eb == SQ_NONE)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "omega cells: chord from vertex %u (halfedge %u) has no sector",
                            P->he_vert[h1], h1);
    if (C->nchords == B->cap_chord) {
        uint32_t cap = B->cap_chord ? 2 * B->cap_chord : 64;
        sq_omega_chord *c = realloc(C->chord, cap * sizeof *c);
        if (!c) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        C->chord = c;
        B->cap_chord = cap;
    }
    sq_omega_chord *c = &C->chord[C->nchords++];
    c->len = len;
    c->he_off = B->nchord_he;
    c->start_sector = sb;
    c->end_sector = eb;
    uint32_t h = h1;
    B->on_chord[P->he_vert[h1]] = 1;
    for (uint32_t i = 0; i < len; i++) {
        /* chord_he has room for every interior edge; a chord never reuses
         * one (it stops at the first vertex on a chord) */
        if (B->cut[h])
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "omega cells: chord %u runs along a cut edge (halfedge %u)",
                                C->nchords - 1, h);
        C->chord_he[B->nchord_he++] = h;
        B->cut[h] = B->cut[P->he_twin[h]] = 1;
        C->he_chord[h] = C->he_chord[P->he_twin[h]] = 1;
        B->on_chord[head(P, h)] = 1;
        if (i + 1 < len) h = straight(P, h);
    }
    return SQ_OK;
}

/* The best chord out of the reflex sectors of v, or SQ_NONE: among chords
 * that pay off at the start, the largest end gain (at least min_gain),
 * then the shortest; phase 2 (first_only) considers only v's first reflex
 * sector counterclockwise. */
static uint32_t best_chord(const builder *B, uint32_t v, uint32_t *bound, uint32_t *size,
                           uint32_t cap, uint32_t min_gain, int first_only)
{
    const sq_metapolygon *P = B->P;
    uint32_t ns = sectors(B, v, bound, size, cap);
    if (ns > cap) ns = cap;
    uint32_t best = SQ_NONE, best_gain = 0, best_len = 0;
    for (uint32_t i = 0; i < ns; i++) {
        uint32_t q = size[i];
        if (q < 3) continue;
        uint32_t h = bound[i];
        for (uint32_t j = 1; j < q; j++) {
            h = ccw(P, h);
            if (need(q) != 1 + need(j) + need(q - j)) continue;
            uint32_t len, eb, last = trace(B, h, &len);
            if (last == SQ_NONE) continue;
            uint32_t g = end_gain(B, last, &eb);
            if (g < min_gain) continue;
            if (best == SQ_NONE || g > best_gain || (g == best_gain && len < best_len))
                best = h, best_gain = g, best_len = len;
        }
        if (first_only) break;
    }
    return best;
}

/* Cells: faces joined across edges that are neither boundary nor chord;
 * their boxes in the layout. */
static sq_status label_cells(const sq_omega *O, const builder *B, sq_omega_cells *C,
                             uint32_t *stack, sq_error *err)
{
    const sq_metapolygon *P = &O->cut;
    for (uint32_t f = 0; f < P->nf; f++) C->f_cell[f] = SQ_NONE;
    uint32_t nc = 0;
    for (uint32_t f0 = 0; f0 < P->nf; f0++) {
        if (C->f_cell[f0] != SQ_NONE) continue;
        uint32_t sp = 0;
        C->f_cell[f0] = nc;
        stack[sp++] = f0;
        while (sp) {
            uint32_t f = stack[--sp], g = P->f_he[f];
            for (uint32_t e = 0; e < 4; e++, g = P->he_next[g]) {
                if (B->cut[g]) continue;
                uint32_t n = P->he_face[P->he_twin[g]];
                if (C->f_cell[n] == SQ_NONE) C->f_cell[n] = nc, stack[sp++] = n;
            }
        }
        nc++;
    }
    C->ncells = nc;
    free(C->cell_box);
    C->cell_box = malloc(4 * (size_t)(nc ? nc : 1) * sizeof *C->cell_box);
    if (!C->cell_box) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t c = 0; c < nc; c++) {
        C->cell_box[4 * c] = C->cell_box[4 * c + 1] = INT64_MAX;
        C->cell_box[4 * c + 2] = C->cell_box[4 * c + 3] = INT64_MIN;
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        int64_t *b = C->cell_box + 4 * (size_t)C->f_cell[f];
        uint32_t g = P->f_he[f];
        for (uint32_t e = 0; e < 4; e++, g = P->he_next[g]) {
            int64_t x = O->xy[2 * (size_t)P->he_vert[g]], y = O->xy[2 * (size_t)P->he_vert[g] + 1];
            if (x < b[0]) b[0] = x;
            if (y < b[1]) b[1] = y;
            if (x > b[2]) b[2] = x;
            if (y > b[3]) b[3] = y;
        }
    }
    return SQ_OK;
}

/* Phase 3: every cell wider or taller than its limit (max_side if not 0,
 * and face_limit of each of its quads if given) is halved by a chord
 * across its longer dimension (the grid line nearest its middle), until
 * none is. The chord leaves the cell's side at a straight (two-quad)
 * sector and runs to the opposite side: a cell is a rectangle, so the
 * grid line through its inside meets no other cut first. */
static sq_status split_cells(const sq_omega *O, builder *B, sq_omega_cells *C, uint32_t max_side,
                             const uint32_t *face_limit, uint32_t *stack, uint32_t *pick,
                             uint32_t *lim, sq_error *err)
{
    const sq_metapolygon *P = &O->cut;
    for (;;) {
        sq_status st = label_cells(O, B, C, stack, err);
        if (st) return st;
        uint32_t nc = C->ncells, nsplit = 0;
        for (uint32_t c = 0; c < nc; c++) pick[c] = SQ_NONE, lim[c] = max_side ? max_side : UINT32_MAX;
        if (face_limit)
            for (uint32_t f = 0; f < P->nf; f++)
                if (face_limit[f] < lim[C->f_cell[f]]) lim[C->f_cell[f]] = face_limit[f] ? face_limit[f] : 1;
        /* the halfedge leaving the middle of the bottom (or left) side of
         * the cell, perpendicular to it, inside the cell */
        for (uint32_t f = 0; f < P->nf; f++) {
            uint32_t c = C->f_cell[f];
            const int64_t *b = C->cell_box + 4 * (size_t)c;
            int64_t w = b[2] - b[0], hgt = b[3] - b[1];
            if (pick[c] != SQ_NONE || (w <= (int64_t)lim[c] && hgt <= (int64_t)lim[c])) continue;
            int vertical = w >= hgt; /* split across x: a vertical chord */
            int64_t xm = b[0] + w / 2, ym = b[1] + hgt / 2;
            uint32_t g = P->f_he[f];
            for (uint32_t e = 0; e < 4; e++, g = P->he_next[g]) {
                uint32_t a = P->he_vert[g], d = head(P, g);
                const int64_t *pa = O->xy + 2 * (size_t)a, *pd = O->xy + 2 * (size_t)d;
                int ok = vertical ? (pa[0] == xm && pd[0] == xm && pa[1] == b[1] && pd[1] == b[1] + 1)
                                  : (pa[1] == ym && pd[1] == ym && pa[0] == b[0] && pd[0] == b[0] + 1);
                if (ok && !B->cut[g]) {
                    pick[c] = g;
                    nsplit++;
                    break;
                }
            }
        }
        if (nsplit == 0) return SQ_OK;
        for (uint32_t c = 0; c < nc; c++)
            if (pick[c] != SQ_NONE && (st = add_chord(B, pick[c], err))) return st;
    }
}

sq_status sq_omega_cells_build(const sq_omega *O, uint32_t max_side, const uint32_t *face_limit,
                               sq_omega_cells *C, sq_error *err)
{
    sq_omega_cells_free(C);
    const sq_metapolygon *P = &O->cut;
    size_t nv1 = P->nv ? P->nv : 1, nh1 = P->nh ? P->nh : 1, nf1 = P->nf ? P->nf : 1;
    builder B = {P, malloc(nv1), calloc(nv1, 1), calloc(nh1, 1), C, 0, 0};
    uint32_t *bverts = malloc(nv1 * sizeof *bverts);
    uint32_t *bound = NULL, *size = NULL, *stack = malloc(nf1 * sizeof *stack);
    uint32_t *pick = malloc(nf1 * sizeof *pick), *lim = malloc(nf1 * sizeof *lim);
    C->chord_he = malloc(nh1 * sizeof *C->chord_he);
    C->he_chord = calloc(nh1, 1);
    C->f_cell = malloc(nf1 * sizeof *C->f_cell);
    sq_status st = SQ_OK;
    if (!B.on_bnd || !B.on_chord || !B.cut || !bverts || !stack || !pick || !lim || !C->chord_he ||
        !C->he_chord || !C->f_cell) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < P->nf; f++)
        if (P->f_valence[f] != 4) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "omega cells: face %u is not a quad", f);
            goto done;
        }
    if (P->bnd_he == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "omega cells: Omega_c has no boundary");
        goto done;
    }
    /* boundary vertices in boundary order; the widest fan sizes the
     * sector arrays */
    memset(B.on_bnd, 0, nv1);
    uint32_t nb = 0, maxfan = 1, h = P->bnd_he;
    do {
        uint32_t v = P->he_vert[h];
        if (B.on_bnd[v] || nb >= P->nv) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "omega cells: boundary loop of Omega_c visits vertex %u twice", v);
            goto done;
        }
        B.on_bnd[v] = 1;
        bverts[nb++] = v;
        B.cut[h] = B.cut[P->he_twin[h]] = 1;
        if (P->v_nface[v] > maxfan) maxfan = P->v_nface[v];
        h = P->he_next[h];
    } while (h != P->bnd_he);
    bound = malloc((size_t)(maxfan + 1) * sizeof *bound);
    size = malloc((size_t)(maxfan + 1) * sizeof *size);
    if (!bound || !size) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }

    /* phase 1: chords that pay off at both ends; phase 2: the rest, per
     * vertex counterclockwise */
    for (int again = 1; again;) {
        again = 0;
        for (uint32_t i = 0; i < nb; i++) {
            uint32_t c;
            while ((c = best_chord(&B, bverts[i], bound, size, maxfan + 1, 1, 0)) != SQ_NONE) {
                if ((st = add_chord(&B, c, err))) goto done;
                again = 1;
            }
        }
    }
    for (uint32_t i = 0; i < nb; i++) {
        uint32_t c;
        while ((c = best_chord(&B, bverts[i], bound, size, maxfan + 1, 0, 1)) != SQ_NONE)
            if ((st = add_chord(&B, c, err))) goto done;
    }

    st = max_side || face_limit ? split_cells(O, &B, C, max_side, face_limit, stack, pick, lim, err)
                                : label_cells(O, &B, C, stack, err);
    if (st) goto done;
    st = sq_omega_cells_verify(O, C, err);
done:
    free(B.on_bnd);
    free(B.on_chord);
    free(B.cut);
    free(bverts);
    free(bound);
    free(size);
    free(stack);
    free(pick);
    free(lim);
    if (st) sq_omega_cells_free(C);
    return st;
}
