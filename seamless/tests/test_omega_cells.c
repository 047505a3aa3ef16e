/* Tests of the rectangle cells of Omega (sq_omega_cells.h; docs/omega.md
 * section 6): on the cone sets of the shared models (the Th_hat files of
 * ../shared/data/mpz and cid/elephant, except twirl, whose valence-1 cone the
 * seed excludes) and on random admissible cone multisets of genus 0..6,
 * build Q, the shortest cone tree, Omega, then the chords and cells, and
 * check beyond the built-in verifier: the cell areas add up to the number of
 * quads, every quad lies inside its cell's box and no two quads of a cell
 * share a unit square, cells = chords + 1 (every chord cuts one disk in
 * two), every chord's start_sector / end_sector is a face halfedge leaving
 * the chord's start / end vertex. The verifier must reject a missing
 * chord, a bent chord, a wrong sector name, a wrong box and a wrong cell.
 * SQ_LONG_TESTS=1 runs 10x more random cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_test_random.h"

#include "sq_cones.h"
#include "sq_domain.h"
#include "sq_omega.h"
#include "sq_omega_cells.h"
#include "sq_omega_cells_internal.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

typedef struct cells_stats {
    uint64_t cases, quads, chords, cells, chord_len, reflex, turns;
} cells_stats;

static uint32_t head(const sq_metapolygon *P, uint32_t h) { return P->he_vert[P->he_next[h]]; }

static int cmp_pair(const void *a, const void *b)
{
    const int64_t *p = a, *q = b;
    if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
    if (p[1] != q[1]) return p[1] < q[1] ? -1 : 1;
    return 0;
}

/* Checks of the brief, written independently of the library's verifier. */
static void check_cells(const sq_omega *O, const sq_omega_cells *C, const char *name)
{
    const sq_metapolygon *P = &O->cut;
    /* cells = chords + 1 */
    if (C->ncells != C->nchords + 1)
        fail_msg("%s: %u cells for %u chords", name, C->ncells, C->nchords);
    /* the areas of the boxes add up to the number of quads */
    uint64_t area = 0;
    for (uint32_t c = 0; c < C->ncells; c++) {
        const int64_t *b = C->cell_box + 4 * (size_t)c;
        assert_true(b[2] > b[0] && b[3] > b[1]);
        area += (uint64_t)(b[2] - b[0]) * (uint64_t)(b[3] - b[1]);
    }
    if (area != P->nf) fail_msg("%s: cell areas %llu, quads %u", name, (unsigned long long)area,
                                P->nf);
    /* every quad inside its box; distinct unit squares per cell */
    int64_t *sq = malloc(3 * (size_t)P->nf * sizeof *sq);
    uint32_t *order = malloc(((size_t)C->ncells + 1) * sizeof *order);
    assert_non_null(sq), assert_non_null(order);
    memset(order, 0, ((size_t)C->ncells + 1) * sizeof *order);
    for (uint32_t f = 0; f < P->nf; f++) order[C->f_cell[f] + 1]++;
    for (uint32_t c = 0; c < C->ncells; c++) order[c + 1] += order[c];
    for (uint32_t f = 0; f < P->nf; f++) {
        uint32_t c = C->f_cell[f], h = P->f_he[f];
        const int64_t *b = C->cell_box + 4 * (size_t)c;
        int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
        for (int e = 0; e < 4; e++, h = P->he_next[h]) {
            int64_t x = O->xy[2 * (size_t)P->he_vert[h]], y = O->xy[2 * (size_t)P->he_vert[h] + 1];
            x0 = x < x0 ? x : x0, y0 = y < y0 ? y : y0;
            x1 = x > x1 ? x : x1, y1 = y > y1 ? y : y1;
        }
        assert_true(x1 - x0 == 1 && y1 - y0 == 1);
        if (x0 < b[0] || y0 < b[1] || x1 > b[2] || y1 > b[3])
            fail_msg("%s: face %u outside the box of its cell %u", name, f, c);
        uint32_t i = order[c]++;
        sq[2 * i] = x0, sq[2 * i + 1] = y0;
    }
    /* order[c] now ends cell c; sort each cell's squares, no repeats */
    for (uint32_t c = 0, begin = 0; c < C->ncells; begin = order[c], c++) {
        uint32_t n = order[c] - begin;
        qsort(sq + 2 * (size_t)begin, n, 2 * sizeof *sq, cmp_pair);
        for (uint32_t i = 1; i < n; i++)
            if (!cmp_pair(sq + 2 * (size_t)(begin + i - 1), sq + 2 * (size_t)(begin + i)))
                fail_msg("%s: two quads of cell %u on one unit square", name, c);
    }
    /* chord ends: sector names are face halfedges leaving the right vertex */
    for (uint32_t i = 0; i < C->nchords; i++) {
        const sq_omega_chord *c = &C->chord[i];
        uint32_t first = C->chord_he[c->he_off], last = C->chord_he[c->he_off + c->len - 1];
        assert_true(c->start_sector < P->nh && c->end_sector < P->nh);
        assert_int_equal(P->he_vert[c->start_sector], P->he_vert[first]);
        assert_int_equal(P->he_vert[c->end_sector], head(P, last));
        assert_true(P->he_face[c->start_sector] != SQ_NONE);
        assert_true(P->he_face[c->end_sector] != SQ_NONE);
        assert_true(c->start_sector != first);
        assert_true(c->end_sector != P->he_twin[last]);
    }
    free(sq), free(order);
}

/* Long cells halved (sq_omega_cells_build's max_side and face_limit): the
 * reflex chords come first, unchanged; every cell fits its limit; the
 * brief still holds (the builder's own verifier ran too). base: the
 * build without limits. */
static void check_split(const sq_omega *O, const sq_omega_cells *base, const char *name)
{
    const sq_metapolygon *P = &O->cut;
    uint32_t *limit = malloc((P->nf ? P->nf : 1) * sizeof *limit);
    assert_non_null(limit);
    for (uint32_t round = 0; round < 4; round++) {
        uint32_t max_side = round < 3 ? round + 1 : 0;
        /* round 3: a limit per quad, 1 to 4 by a hash of the quad, or of
         * its base cell (then equal in the whole cell); the test's random
         * stream is left alone */
        for (uint32_t f = 0; f < P->nf; f++) {
            uint32_t hf = f * 2654435761u, hc = base->f_cell[f] * 2246822519u;
            limit[f] = 1 + ((hf >> 13) % 2 ? (hc >> 11) % 4 : (hf >> 17) % 4);
        }
        sq_omega_cells C;
        sq_error err;
        sq_omega_cells_init(&C);
        if (sq_omega_cells_build(O, max_side, round == 3 ? limit : NULL, &C, &err))
            fail_msg("%s: cells (max_side %u): %s", name, max_side, err.msg);
        check_cells(O, &C, name);
        assert_true(C.nchords >= base->nchords);
        for (uint32_t i = 0; i < base->nchords; i++) {
            assert_int_equal(C.chord[i].len, base->chord[i].len);
            assert_memory_equal(C.chord_he + C.chord[i].he_off, base->chord_he + base->chord[i].he_off,
                                base->chord[i].len * sizeof *C.chord_he);
        }
        uint32_t *lim = malloc(C.ncells * sizeof *lim);
        assert_non_null(lim);
        for (uint32_t c = 0; c < C.ncells; c++) lim[c] = max_side ? max_side : UINT32_MAX;
        if (round == 3)
            for (uint32_t f = 0; f < P->nf; f++)
                if (limit[f] < lim[C.f_cell[f]]) lim[C.f_cell[f]] = limit[f];
        for (uint32_t c = 0; c < C.ncells; c++) {
            const int64_t *b = C.cell_box + 4 * (size_t)c;
            if (b[2] - b[0] > (int64_t)lim[c] || b[3] - b[1] > (int64_t)lim[c])
                fail_msg("%s: cell %u is %lld x %lld, limit %u", name, c, (long long)(b[2] - b[0]),
                         (long long)(b[3] - b[1]), lim[c]);
        }
        if (max_side == 1) assert_int_equal(C.ncells, P->nf); /* unit squares */
        free(lim);
        sq_omega_cells_free(&C);
    }
    free(limit);
}

/* Omega of one cone multiset, or 0 if the domain builder declines (genus 0
 * and 1 builders do not cover every multiset). */
static int build_omega(uint32_t genus, const int32_t *val, uint32_t n, sq_domain *D,
                       sq_cone_tree *T, sq_omega *O, const char *name)
{
    sq_error err;
    if (sq_domain_build(genus, val, n, NULL, D, &err)) {
        if (genus >= 2) fail_msg("%s: domain: %s", name, err.msg);
        print_message("%s: domain not built (%s), skipped\n", name, err.msg);
        return 0;
    }
    if (sq_cone_tree_shortest(&D->quads, SQ_NONE, T, &err)) fail_msg("%s: tree: %s", name, err.msg);
    if (sq_omega_build(D, T, O, &err)) fail_msg("%s: omega: %s", name, err.msg);
    return 1;
}

static void run_case(uint32_t genus, const int32_t *val, uint32_t n, cells_stats *cs,
                     const char *name)
{
    sq_domain D;
    sq_cone_tree T;
    sq_omega O;
    sq_omega_cells C;
    sq_error err;
    sq_cone_tree_init(&T);
    sq_omega_init(&O);
    sq_omega_cells_init(&C);
    if (!build_omega(genus, val, n, &D, &T, &O, name)) return;
    if (sq_omega_cells_build(&O, 0, NULL, &C, &err)) fail_msg("%s: cells: %s", name, err.msg);
    if (sq_omega_cells_verify(&O, &C, &err)) fail_msg("%s: verify: %s", name, err.msg);
    check_cells(&O, &C, name);
    check_split(&O, &C, name);
    if (cs) {
        cs->cases++;
        cs->quads += O.cut.nf;
        cs->chords += C.nchords;
        cs->cells += C.ncells;
        for (uint32_t i = 0; i < C.nchords; i++) cs->chord_len += C.chord[i].len;
        for (uint32_t v = 0; v < O.cut.nv; v++)
            if (O.cut.he_face[O.cut.v_he[v]] == SQ_NONE && O.cut.v_nface[v] >= 3) cs->reflex++;
        /* turns of the tree: regular vertices of tree degree 2 whose two
         * tree edges are not opposite */
        const sq_metapolygon *Q = &D.quads;
        for (uint32_t i = 1; i < T.nverts; i++) {
            if (T.node[i] || T.rot_off[i + 1] - T.rot_off[i] != 2) continue;
            uint32_t a = T.rot_he[T.rot_off[i]], b = T.rot_he[T.rot_off[i] + 1];
            if (Q->he_next[Q->he_twin[Q->he_next[Q->he_twin[a]]]] != b) cs->turns++;
        }
    }
    sq_omega_cells_free(&C);
    sq_omega_free(&O);
    sq_cone_tree_free(&T);
    sq_domain_free(&D);
}

/* The valence multiset of a Th_hat file and the genus from Gauss-Bonnet. */
static uint32_t read_cones(const char *rel, int32_t *out, uint32_t cap, uint32_t *genus)
{
    char path[512];
    snprintf(path, sizeof path, "%s/data/%s", SQ_SHARED_DIR, rel);
    FILE *f = fopen(path, "r");
    if (!f) fail_msg("cannot open %s", path);
    uint32_t nv = 0;
    int ch, prev = '\n';
    while ((ch = fgetc(f)) != EOF) {
        if (ch == '\n' && prev != '\n') nv++;
        prev = ch;
    }
    if (prev != '\n') nv++;
    fclose(f);
    int32_t *val = malloc(nv * sizeof *val);
    sq_error err;
    assert_non_null(val);
    if (sq_cones_read(path, nv, val, NULL, &err)) fail_msg("%s: %s", path, err.msg);
    int64_t curv = 0;
    uint32_t n = 0;
    for (uint32_t v = 0; v < nv; v++) {
        curv += 4 - val[v];
        if (val[v] != 4) {
            assert_true(n < cap);
            out[n++] = val[v];
        }
    }
    free(val);
    /* sum (4 - k) = 4 chi = 8 - 8 g */
    assert_int_equal((8 - curv) % 8, 0);
    *genus = (uint32_t)((8 - curv) / 8);
    return n;
}

static void test_shared_models(void **state)
{
    (void)state;
    static const char *models[] = {
        "cid/elephant_Th_hat", "mpz/helmet_Th_hat",  "mpz/genus3_Th_hat",
        "mpz/fertility_tri_Th_hat", "mpz/block_Th_hat", "mpz/cup_Th_hat",
        "mpz/eight_Th_hat",    "mpz/elk_Th_hat",     "mpz/fandisk_Th_hat",
        "mpz/femur_Th_hat",    "mpz/holes3_Th_hat",  "mpz/homer_Th_hat",
        "mpz/knot1_Th_hat",    "mpz/rocker_arm_Th_hat", "mpz/sculpt_Th_hat",
        "mpz/trim-star_Th_hat",
    };
    for (size_t m = 0; m < sizeof models / sizeof models[0]; m++) {
        int32_t v[1024];
        uint32_t genus, n = read_cones(models[m], v, 1024, &genus);
        cells_stats cs = {0};
        run_case(genus, v, n, &cs, models[m]);
        if (cs.cases)
            print_message("%-24s genus %u: %6llu quads, %3llu tree turns, %4llu reflex corners, "
                          "%4llu chords (total length %6llu), %4llu cells\n",
                          models[m], genus, (unsigned long long)cs.quads,
                          (unsigned long long)cs.turns,
                          (unsigned long long)cs.reflex, (unsigned long long)cs.chords,
                          (unsigned long long)cs.chord_len, (unsigned long long)cs.cells);
    }
}

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static void test_random(void **state)
{
    (void)state;
    rng_state = 20260715;
    uint32_t per = long_mode() ? 100 : SANITIZED ? 3 : 10;
    for (uint32_t g = 2; g <= 6; g++) {
        cells_stats cs = {0};
        for (uint32_t c = 0; c < per; c++) {
            int32_t v[1024];
            uint32_t n = random_cones(g, v, 1024);
            char name[64];
            snprintf(name, sizeof name, "genus %u case %u", g, c);
            run_case(g, v, n, &cs, name);
        }
        print_message("genus %u: %llu cases, mean %llu quads, %llu tree turns, %llu chords, "
                      "%llu cells\n",
                      g, (unsigned long long)cs.cases, (unsigned long long)(cs.quads / cs.cases),
                      (unsigned long long)(cs.turns / cs.cases),
                      (unsigned long long)(cs.chords / cs.cases),
                      (unsigned long long)(cs.cells / cs.cases));
    }
}

static void test_low_genus(void **state)
{
    (void)state;
    static const int32_t cube[] = {3, 3, 3, 3, 3, 3, 3, 3};
    static const int32_t g0b[] = {2, 2, 3, 3, 3, 5, 3, 3};
    static const int32_t torus[] = {3, 3, 5, 5};
    static const int32_t torus2[] = {2, 6, 3, 5, 3, 5};
    struct {
        uint32_t genus;
        const int32_t *v;
        uint32_t n;
    } cases[] = {{0, cube, 8}, {0, g0b, 8}, {1, torus, 4}, {1, torus2, 6}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char name[32];
        snprintf(name, sizeof name, "low genus case %zu", c);
        run_case(cases[c].genus, cases[c].v, cases[c].n, NULL, name);
    }
}

/* f_cell and cell_box recomputed for C's current chords (for the missing
 * chord test: the cells are then consistent with the chords, and only the
 * geometry can tell that a chord is missing). */
static void relabel(const sq_omega *O, sq_omega_cells *C)
{
    const sq_metapolygon *P = &O->cut;
    uint32_t *stack = malloc(P->nf * sizeof *stack);
    assert_non_null(stack);
    for (uint32_t f = 0; f < P->nf; f++) C->f_cell[f] = SQ_NONE;
    uint32_t nc = 0;
    for (uint32_t f0 = 0; f0 < P->nf; f0++) {
        if (C->f_cell[f0] != SQ_NONE) continue;
        uint32_t sp = 0;
        C->f_cell[f0] = nc;
        stack[sp++] = f0;
        while (sp) {
            uint32_t f = stack[--sp], h = P->f_he[f];
            for (int e = 0; e < 4; e++, h = P->he_next[h]) {
                uint32_t g = P->he_face[P->he_twin[h]];
                if (g != SQ_NONE && !C->he_chord[h] && C->f_cell[g] == SQ_NONE)
                    C->f_cell[g] = nc, stack[sp++] = g;
            }
        }
        nc++;
    }
    C->ncells = nc;
    for (uint32_t c = 0; c < nc; c++) {
        C->cell_box[4 * c] = C->cell_box[4 * c + 1] = INT64_MAX;
        C->cell_box[4 * c + 2] = C->cell_box[4 * c + 3] = INT64_MIN;
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        int64_t *b = C->cell_box + 4 * (size_t)C->f_cell[f];
        uint32_t h = P->f_he[f];
        for (int e = 0; e < 4; e++, h = P->he_next[h]) {
            int64_t x = O->xy[2 * (size_t)P->he_vert[h]], y = O->xy[2 * (size_t)P->he_vert[h] + 1];
            b[0] = x < b[0] ? x : b[0], b[1] = y < b[1] ? y : b[1];
            b[2] = x > b[2] ? x : b[2], b[3] = y > b[3] ? y : b[3];
        }
    }
    free(stack);
}

/* The verifier is not vacuous: break one thing at a time. */
static void test_verify_catches(void **state)
{
    (void)state;
    static const int32_t helmet[] = {3, 3, 3, 3, 3, 3, 5, 7, 22};
    sq_domain D;
    sq_cone_tree T;
    sq_omega O;
    sq_omega_cells C;
    sq_error err;
    sq_cone_tree_init(&T);
    sq_omega_init(&O);
    sq_omega_cells_init(&C);
    assert_true(build_omega(3, helmet, 9, &D, &T, &O, "helmet"));
    const sq_metapolygon *P = &O.cut;
    assert_int_equal(sq_omega_cells_build(&O, 0, NULL, &C, &err), SQ_OK);
    assert_true(C.nchords >= 3);
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_OK);

    /* each chord in turn: the last ones dropped, cells relabelled to match */
    for (uint32_t keep = C.nchords; keep-- > 0;) {
        sq_omega_cells M;
        sq_omega_cells_init(&M);
        M.nchords = keep;
        M.chord = C.chord;
        M.chord_he = C.chord_he;
        M.he_chord = calloc(P->nh, 1);
        M.f_cell = malloc(P->nf * sizeof *M.f_cell);
        M.cell_box = malloc(4 * (size_t)P->nf * sizeof *M.cell_box);
        assert_non_null(M.he_chord), assert_non_null(M.f_cell), assert_non_null(M.cell_box);
        for (uint32_t i = 0; i < keep; i++)
            for (uint32_t k = 0; k < C.chord[i].len; k++) {
                uint32_t h = C.chord_he[C.chord[i].he_off + k];
                M.he_chord[h] = M.he_chord[P->he_twin[h]] = 1;
            }
        relabel(&O, &M);
        assert_int_equal(M.ncells, keep + 1);
        assert_int_equal(sq_omega_cells_verify(&O, &M, &err), SQ_ERR_INTERNAL);
        if (keep == C.nchords - 1) print_message("missing chord: %s\n", err.msg);
        free(M.he_chord), free(M.f_cell), free(M.cell_box);
    }
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_OK);

    /* a bent chord: its first edge replaced by the next edge clockwise */
    {
        uint32_t i = 0, *h0 = &C.chord_he[C.chord[i].he_off], old = *h0;
        *h0 = P->he_next[P->he_twin[old]];
        assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
        *h0 = old;
    }
    /* a wrong sector name: the other halfedge of the same edge, then a
     * halfedge leaving another vertex */
    {
        sq_omega_chord *c = &C.chord[C.nchords - 1];
        uint32_t s = c->start_sector, e = c->end_sector;
        c->start_sector = P->he_twin[s];
        assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
        c->start_sector = s;
        c->end_sector = C.chord_he[c->he_off];
        assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
        c->end_sector = e;
    }
    /* a sector bounded by the chord's own edge: name the sector on the
     * other side (the clockwise bound of the part counterclockwise of it) */
    {
        sq_omega_chord *c = &C.chord[0];
        uint32_t s = c->start_sector;
        c->start_sector = C.chord_he[c->he_off];
        assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
        c->start_sector = s;
    }
    /* a box one unit too wide, then too narrow */
    C.cell_box[2] += 1;
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
    C.cell_box[2] -= 2;
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
    C.cell_box[2] += 1;
    /* a face in the wrong cell */
    {
        uint32_t f = C.chord_he[0] < P->nh ? P->he_face[C.chord_he[0]] : 0, old = C.f_cell[f];
        C.f_cell[f] = C.f_cell[P->he_face[P->he_twin[C.chord_he[0]]]];
        assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
        C.f_cell[f] = old;
    }
    /* a chord flag lost */
    C.he_chord[C.chord_he[0]] = 0;
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_ERR_INTERNAL);
    C.he_chord[C.chord_he[0]] = 1;
    assert_int_equal(sq_omega_cells_verify(&O, &C, &err), SQ_OK);

    sq_omega_cells_free(&C);
    sq_omega_free(&O);
    sq_cone_tree_free(&T);
    sq_domain_free(&D);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_verify_catches),
        cmocka_unit_test(test_shared_models),
        cmocka_unit_test(test_random),
        cmocka_unit_test(test_low_genus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
