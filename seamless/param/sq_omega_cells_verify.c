/* seamquad: independent check of the rectangle cells of Omega (see
 * sq_omega_cells_internal.h for the list). Uses only O (cut, xy) and the
 * output C: chords are re-walked in the layout, sectors and cells
 * recomputed, every cell's tiling of its box checked square by square. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega_cells_internal.h"
#include "sq_omega_grid.h"

#define FAIL(...)                                                                                  \
    do {                                                                                           \
        st = sq_error_set(err, SQ_ERR_INTERNAL, __VA_ARGS__);                                      \
        goto done;                                                                                 \
    } while (0)

static uint32_t head(const sq_metapolygon *P, uint32_t h) { return P->he_vert[P->he_next[h]]; }

static uint32_t ccw(const sq_metapolygon *P, uint32_t h)
{
    uint32_t g = h;
    while (P->he_next[g] != h) g = P->he_next[g];
    return P->he_twin[g];
}

/* the unit direction 0..3 of halfedge h in the layout, 4 if not a unit step */
static uint32_t he_dir(const sq_omega *O, uint32_t h)
{
    const sq_metapolygon *P = &O->cut;
    uint32_t a = P->he_vert[h], b = head(P, h);
    return dir_of(O->xy[2 * (size_t)b] - O->xy[2 * (size_t)a],
                  O->xy[2 * (size_t)b + 1] - O->xy[2 * (size_t)a + 1]);
}

/* Edge of h is a boundary edge or lies on a chord with index < limit. */
static int bounds(const sq_metapolygon *P, const uint32_t *chord_of, uint32_t h, uint32_t limit)
{
    return P->he_face[h] == SQ_NONE || P->he_face[P->he_twin[h]] == SQ_NONE ||
           (chord_of[h] != SQ_NONE && chord_of[h] < limit);
}

/* s names the sector of vertex v (at the time chord `limit` is added) that
 * the chord's halfedge `own` (leaving v) lies in. Returns a message or
 * NULL. */
static const char *check_sector(const sq_metapolygon *P, const uint32_t *chord_of, uint32_t v,
                                uint32_t s, uint32_t own, uint32_t limit)
{
    if (s >= P->nh) return "is not a halfedge";
    if (P->he_vert[s] != v) return "does not leave the chord's vertex";
    if (P->he_face[s] == SQ_NONE) return "is a boundary halfedge, not a face halfedge";
    if (!bounds(P, chord_of, s, limit)) return "is neither a boundary edge nor an earlier chord";
    uint32_t g = s;
    for (uint32_t n = 0; n <= P->v_nface[v]; n++) {
        g = ccw(P, g);
        if (g == own) return NULL;
        if (bounds(P, chord_of, g, limit)) return "bounds another sector than the chord's";
    }
    return "does not reach the chord";
}

/* The chords (chord_of, vfirst: nh and nv entries, set here; on_bnd
 * given): contiguous, interior, straight, stopping at the first vertex on
 * the boundary or an earlier chord; he_chord agrees. */
static sq_status verify_chords(const sq_omega *O, const sq_omega_cells *C, const uint8_t *on_bnd, uint32_t *chord_of,
                               uint32_t *vfirst, sq_error *err)
{
    const sq_metapolygon *P = &O->cut;
    sq_status st = SQ_OK;
    for (uint32_t h = 0; h < P->nh; h++) chord_of[h] = SQ_NONE;
    for (uint32_t v = 0; v < P->nv; v++) vfirst[v] = SQ_NONE;
    uint64_t total = 0;
    for (uint32_t i = 0; i < C->nchords; i++) {
        const sq_omega_chord *c = &C->chord[i];
        if (c->len == 0) FAIL("omega cells: chord %u is empty", i);
        if (c->he_off != total) FAIL("omega cells: chord %u does not follow chord %u", i, i - 1);
        total += c->len;
        if (total > P->nh) FAIL("omega cells: chords hold more halfedges than Omega_c");
        const uint32_t *he = C->chord_he + c->he_off;
        uint32_t d = SQ_NONE;
        for (uint32_t k = 0; k < c->len; k++) {
            uint32_t h = he[k];
            if (h >= P->nh) FAIL("omega cells: chord %u, edge %u: not a halfedge", i, k);
            if (P->he_face[h] == SQ_NONE || P->he_face[P->he_twin[h]] == SQ_NONE)
                FAIL("omega cells: chord %u, edge %u (halfedge %u) is not an interior edge", i,
                     k, h);
            if (chord_of[h] != SQ_NONE)
                FAIL("omega cells: halfedge %u lies on chords %u and %u", h, chord_of[h], i);
            uint32_t dk = he_dir(O, h);
            if (dk == 4) FAIL("omega cells: chord %u, edge %u is not a unit step", i, k);
            if (k == 0) d = dk;
            else if (dk != d) FAIL("omega cells: chord %u turns at its edge %u", i, k);
            if (k > 0 && P->he_vert[h] != head(P, he[k - 1]))
                FAIL("omega cells: chord %u is broken before its edge %u", i, k);
            uint32_t x = head(P, h);
            if (k + 1 < c->len) {
                if (on_bnd[x] || P->v_nface[x] != 4)
                    FAIL("omega cells: chord %u passes through boundary vertex %u", i, x);
                if (vfirst[x] != SQ_NONE)
                    FAIL("omega cells: chord %u crosses chord %u at vertex %u without stopping",
                         i, vfirst[x], x);
            } else if (!on_bnd[x] && vfirst[x] == SQ_NONE) {
                FAIL("omega cells: chord %u ends at vertex %u, inside Omega_c and on no "
                     "earlier chord",
                     i, x);
            }
        }
        uint32_t v0 = P->he_vert[he[0]], x = head(P, he[c->len - 1]);
        if (!on_bnd[v0] && vfirst[v0] == SQ_NONE)
            FAIL("omega cells: chord %u starts at vertex %u inside Omega_c and on no earlier chord",
                 i, v0);
        /* sectors named at the moment the chord is added */
        const char *why = check_sector(P, chord_of, v0, c->start_sector, he[0], i);
        if (why) FAIL("omega cells: chord %u: start_sector %u %s", i, c->start_sector, why);
        why = check_sector(P, chord_of, x, c->end_sector, P->he_twin[he[c->len - 1]], i);
        if (why) FAIL("omega cells: chord %u: end_sector %u %s", i, c->end_sector, why);
        for (uint32_t k = 0; k < c->len; k++) chord_of[he[k]] = chord_of[P->he_twin[he[k]]] = i;
        if (vfirst[v0] == SQ_NONE) vfirst[v0] = i;
        for (uint32_t k = 0; k < c->len; k++)
            if (vfirst[head(P, he[k])] == SQ_NONE) vfirst[head(P, he[k])] = i;
    }
    for (uint32_t h = 0; h < P->nh; h++)
        if ((C->he_chord[h] != 0) != (chord_of[h] != SQ_NONE))
            FAIL("omega cells: he_chord[%u] = %u disagrees with the chord list", h,
                 C->he_chord[h]);
done:
    return st;
}

/* Sectors: at most two quads between consecutive boundary or chord edges,
 * at every vertex (each sector is named by its clockwise face halfedge, so
 * every cut face halfedge starts one). */
static sq_status verify_sectors(const sq_metapolygon *P, const uint32_t *chord_of, sq_error *err)
{
    sq_status st = SQ_OK;
    for (uint32_t s = 0; s < P->nh; s++) {
        if (P->he_face[s] == SQ_NONE || !bounds(P, chord_of, s, SQ_NONE)) continue;
        uint32_t v = P->he_vert[s], q = 1, g = ccw(P, s);
        while (!bounds(P, chord_of, g, SQ_NONE) && q <= P->v_nface[v]) g = ccw(P, g), q++;
        if (q > 2)
            FAIL("omega cells: vertex %u has a sector of %u quads (from halfedge %u) between "
                 "boundary and chord edges",
                 v, q, s);
    }
done:
    return st;
}

/* Cells: constant across non-chord edges, different across chords, each
 * connected (comp, stack: nf entries of scratch). */
static sq_status verify_cells(const sq_metapolygon *P, const sq_omega_cells *C, const uint32_t *chord_of,
                              uint32_t *comp, uint32_t *stack, sq_error *err)
{
    sq_status st = SQ_OK;
    if (C->ncells == 0 && P->nf) FAIL("omega cells: no cells");
    for (uint32_t f = 0; f < P->nf; f++) {
        if (C->f_cell[f] >= C->ncells)
            FAIL("omega cells: face %u has cell %u of %u", f, C->f_cell[f], C->ncells);
        comp[f] = SQ_NONE;
    }
    for (uint32_t h = 0; h < P->nh; h++) {
        uint32_t f = P->he_face[h], g = P->he_face[P->he_twin[h]];
        if (f == SQ_NONE || g == SQ_NONE) continue;
        if ((C->f_cell[f] == C->f_cell[g]) != (chord_of[h] == SQ_NONE))
            FAIL("omega cells: faces %u and %u (cells %u, %u) %s a chord", f, g, C->f_cell[f],
                 C->f_cell[g], chord_of[h] == SQ_NONE ? "are not separated by" : "are across");
    }
    uint32_t ncomp = 0;
    for (uint32_t f0 = 0; f0 < P->nf; f0++) {
        if (comp[f0] != SQ_NONE) continue;
        uint32_t sp = 0;
        comp[f0] = ncomp;
        stack[sp++] = f0;
        while (sp) {
            uint32_t f = stack[--sp], h = P->f_he[f];
            for (uint32_t e = 0; e < 4; e++, h = P->he_next[h]) {
                uint32_t g = P->he_face[P->he_twin[h]];
                if (g != SQ_NONE && chord_of[h] == SQ_NONE && comp[g] == SQ_NONE)
                    comp[g] = ncomp, stack[sp++] = g;
            }
        }
        ncomp++;
    }
    if (ncomp != C->ncells)
        FAIL("omega cells: %u connected pieces between chords, but %u cells", ncomp, C->ncells);
done:
    return st;
}

/* Every cell tiles its box exactly: count = area, each unit square of the
 * box covered once (so none outside), its cut edges on the box's
 * boundary. */
static sq_status verify_tiling(const sq_omega *O, const sq_omega_cells *C, const uint32_t *chord_of, sq_error *err)
{
    const sq_metapolygon *P = &O->cut;
    sq_status st = SQ_OK;
    uint64_t *count = NULL, *off = NULL;
    uint8_t *cover = NULL;
    const size_t nf1 = P->nf ? P->nf : 1;
    count = calloc(C->ncells ? C->ncells : 1, sizeof *count);
    off = malloc(((size_t)C->ncells + 1) * sizeof *off);
    if (!count || !off) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < P->nf; f++) count[C->f_cell[f]]++;
    off[0] = 0;
    for (uint32_t c = 0; c < C->ncells; c++) {
        const int64_t *b = C->cell_box + 4 * (size_t)c;
        if (b[2] <= b[0] || b[3] <= b[1] || b[2] - b[0] > (int64_t)P->nf ||
            b[3] - b[1] > (int64_t)P->nf)
            FAIL("omega cells: cell %u has an empty or oversized box", c);
        uint64_t area = (uint64_t)(b[2] - b[0]) * (uint64_t)(b[3] - b[1]);
        if (area != count[c])
            FAIL("omega cells: cell %u has %llu quads but its box %lld x %lld", c,
                 (unsigned long long)count[c], (long long)(b[2] - b[0]), (long long)(b[3] - b[1]));
        off[c + 1] = off[c] + area;
    }
    cover = calloc(nf1, 1);
    if (!cover) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        uint32_t c = C->f_cell[f], h = P->f_he[f];
        const int64_t *b = C->cell_box + 4 * (size_t)c;
        int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
        for (uint32_t e = 0; e < 4; e++, h = P->he_next[h]) {
            uint32_t v = P->he_vert[h];
            int64_t x = O->xy[2 * (size_t)v], y = O->xy[2 * (size_t)v + 1];
            if (x < x0) x0 = x;
            if (y < y0) y0 = y;
            if (x > x1) x1 = x;
            if (y > y1) y1 = y;
            if (x < b[0] || x > b[2] || y < b[1] || y > b[3])
                FAIL("omega cells: face %u of cell %u leaves the cell's box at vertex %u", f, c,
                     v);
            if (P->he_face[P->he_twin[h]] != SQ_NONE && chord_of[h] == SQ_NONE) continue;
            /* a boundary or chord edge: on a side of the box */
            uint32_t w = head(P, h);
            int64_t x2 = O->xy[2 * (size_t)w], y2 = O->xy[2 * (size_t)w + 1];
            int on_side = (x == x2 && (x == b[0] || x == b[2])) ||
                          (y == y2 && (y == b[1] || y == b[3]));
            if (!on_side)
                FAIL("omega cells: edge %u-%u of cell %u is a boundary or chord edge inside "
                     "the cell's box",
                     v, w, c);
        }
        if (x1 - x0 != 1 || y1 - y0 != 1)
            FAIL("omega cells: face %u is not a unit square in the layout", f);
        uint64_t i = off[c] + (uint64_t)(x0 - b[0]) * (uint64_t)(b[3] - b[1]) +
                     (uint64_t)(y0 - b[1]);
        if (cover[i])
            FAIL("omega cells: face %u covers a unit square of cell %u twice", f, c);
        cover[i] = 1;
    }
done:
    free(count);
    free(off);
    free(cover);
    return st;
}

sq_status sq_omega_cells_verify(const sq_omega *O, const sq_omega_cells *C, sq_error *err)
{
    const sq_metapolygon *P = &O->cut;
    sq_status st = SQ_OK;
    size_t nv1 = P->nv ? P->nv : 1, nh1 = P->nh ? P->nh : 1, nf1 = P->nf ? P->nf : 1;
    uint8_t *on_bnd = calloc(nv1, 1);
    uint32_t *chord_of = malloc(nh1 * sizeof *chord_of);
    uint32_t *vfirst = malloc(nv1 * sizeof *vfirst); /* first chord through a vertex */
    uint32_t *comp = malloc(nf1 * sizeof *comp);
    uint32_t *stack = malloc(nf1 * sizeof *stack);
    if (!on_bnd || !chord_of || !vfirst || !comp || !stack) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < P->nf; f++)
        if (P->f_valence[f] != 4) FAIL("omega cells: face %u is not a quad", f);
    for (uint32_t h = 0; h < P->nh; h++)
        if (P->he_face[h] == SQ_NONE) on_bnd[P->he_vert[h]] = 1;
    st = verify_chords(O, C, on_bnd, chord_of, vfirst, err);
    if (st == SQ_OK) st = verify_sectors(P, chord_of, err);
    if (st == SQ_OK) st = verify_cells(P, C, chord_of, comp, stack, err);
    if (st == SQ_OK) st = verify_tiling(O, C, chord_of, err);
done:
    free(on_bnd);
    free(chord_of);
    free(vfirst);
    free(comp);
    free(stack);
    return st;
}
