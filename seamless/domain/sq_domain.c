/* seamquad: the combinatorial seamless domain (see sq_domain.h). */
#include "sq_clock.h"
#include "sq_domain.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cones.h"
#include "sq_domain_internal.h"
#include "sq_domain_slide.h"
#include "sq_mesh.h"
#include "sq_metapolygon_subdivide.h"
#include "sq_padding.h"
#include "sq_valence_order.h"
#include "sq_union_find.h"

void sq_domain_init(sq_domain *D)
{
    memset(D, 0, sizeof *D);
    sq_metapolygon_init(&D->meta);
    sq_metapolygon_init(&D->quads);
    sq_pattern_init(&D->pattern);
    D->refine = 1;
}

void sq_domain_free(sq_domain *D)
{
    if (!D) return;
    free(D->order);
    sq_metapolygon_free(&D->meta);
    sq_metapolygon_free(&D->quads);
    free(D->f_meta_face);
    sq_pattern_free(&D->pattern);
    free(D->corner_vert);
    free(D->side_len);
    free(D->padding);
    sq_domain_init(D);
}

/* The boundary vertex `steps` edges after boundary vertex v, following the
 * boundary loop (clockwise, sq_metapolygon convention). */
static uint32_t walk_boundary(const sq_metapolygon *Q, uint32_t v, uint64_t steps)
{
    uint32_t h = Q->v_he[v];
    assert(Q->he_face[h] == SQ_NONE);
    for (uint64_t t = 0; t < steps; t++) h = Q->he_next[h];
    return Q->he_vert[h];
}

void sq_domain_side_vertices(const sq_domain *D, uint32_t side, uint32_t *verts)
{
    const sq_metapolygon *Q = &D->quads;
    uint32_t h = Q->v_he[D->corner_vert[side]];
    for (uint32_t t = 0; t <= D->side_len[side]; t++) {
        verts[t] = Q->he_vert[h];
        h = Q->he_next[h];
    }
}

/* Most side correspondences tried (seed 9.3 search). */
#define MAX_OFFSETS 40u

/* Offsets whose padding is improved by the solver's descent (phase 2)
 * when there are more than 36 sides (genus > 5); below, all of them. */
#define DESCENT_CANDIDATES 6u

/* One feasible side correspondence (seed 6.3): offset, padding, cost. */
typedef struct offset_choice {
    uint32_t offset;
    uint64_t d, added;
    long double total; /* quads after refinement and padding */
    int64_t *w;        /* k */
} offset_choice;

static int cmp_choice(const void *x, const void *y)
{
    const offset_choice *a = x, *b = y;
    if (a->total != b->total) return a->total < b->total ? -1 : 1;
    return (a->offset > b->offset) - (a->offset < b->offset);
}

/* Seed 6.3 / 9.3: every cyclic offset between the pattern's sides and the
 * metapolygon's (or only `fixed`) with a padding solution, sorted by the
 * number of quads after padding. Returns the count (0: none feasible; err
 * then holds the last solver message); *out is malloc'ed, free each w. */
static uint32_t feasible_offsets(const sq_pattern *pat, const uint32_t *meta_len, uint32_t fixed,
                                 uint64_t quads0, offset_choice **out, sq_error *err)
{
    const uint32_t k = pat->k;
    offset_choice *c = calloc(k, sizeof *c);
    int64_t *L = malloc((size_t)k * sizeof *L);
    uint32_t n = 0;
    if (!c || !L) {
        free(c), free(L);
        sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        *out = NULL;
        return 0;
    }
    /* every offset while k is small; beyond, an evenly spread sample (each
     * solve is an exact elimination of size k: k solves would cost k^4) */
    const uint32_t stride = k <= MAX_OFFSETS ? 1 : (k + MAX_OFFSETS - 1) / MAX_OFFSETS;
    for (uint32_t o = 0; o < k; o++) {
        if (fixed != SQ_NONE ? o != fixed : o % stride != 0) continue;
        for (uint32_t i = 0; i < k; i++) L[i] = meta_len[(i + o) % k];
        int64_t *w = malloc((size_t)k * sizeof *w);
        if (!w) {
            for (uint32_t t = 0; t < n; t++) free(c[t].w);
            free(c), free(L);
            sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            *out = NULL;
            return 0;
        }
        sq_pad_result res;
        memset(&res, 0, sizeof res);
        res.w = w;
        sq_error e2;
        /* phase 1: the first feasible point of every offset (cheap) */
        sq_pad_options popt = {SQ_PAD_OPT_NO_DESCENT, 0};
        if (sq_pad_solve_pattern(pat, L, &popt, &res, &e2) != SQ_OK) {
            if (err) *err = e2;
            free(w);
            continue;
        }
        c[n].offset = o;
        c[n].d = res.d;
        c[n].added = res.added_quads;
        c[n].total = (long double)res.d * (long double)res.d * (long double)quads0 +
                     (long double)res.added_quads;
        c[n].w = w;
        n++;
    }
    qsort(c, n, sizeof *c, cmp_choice);
    /* phase 2: improve the most promising offsets by the solver's descent
     * (seed 9.3: fewest quads), then sort again */
    const uint32_t refine_top = k <= 36 || n < DESCENT_CANDIDATES ? n : DESCENT_CANDIDATES;
    for (uint32_t t = 0; t < refine_top; t++) {
        for (uint32_t i = 0; i < k; i++) L[i] = meta_len[(i + c[t].offset) % k];
        sq_pad_result res;
        memset(&res, 0, sizeof res);
        res.w = c[t].w;
        if (sq_pad_solve_pattern(pat, L, NULL, &res, NULL) != SQ_OK) continue;
        c[t].d = res.d;
        c[t].added = res.added_quads;
        c[t].total = (long double)res.d * (long double)res.d * (long double)quads0 +
                     (long double)res.added_quads;
    }
    qsort(c, n, sizeof *c, cmp_choice);
    free(L);
    *out = c;
    return n;
}

/* Seed 6.1: glue w[s] layers of quads on every side; keeps corner_v and len
 * (metapolygon numbering) up to date. */
static sq_status apply_padding(sq_metapolygon *Q, uint32_t k, uint32_t offset, const int64_t *w,
                               uint32_t *corner_v, uint32_t *len, sq_error *err)
{
    for (uint32_t s = 0; s < k; s++) {
        if (w[s] == 0) continue;
        const uint32_t m = (s + offset) % k, prev = (m + k - 1) % k, next = (m + 1) % k;
        if (w[s] < 0 || w[s] > UINT32_MAX / 2)
            return sq_error_set(err, SQ_ERR_INTERNAL, "padding %lld out of range",
                                (long long)w[s]);
        uint32_t h = Q->v_he[corner_v[m]];
        assert(Q->he_face[h] == SQ_NONE);
        sq_status st = sq_metapolygon_glue_grid(Q, h, (uint32_t)w[s], len[m], 1, err);
        if (st) return st;
        /* corner prev is untouched (k >= 3): the new corners of side m lie
         * len[prev] + w and len[prev] + w + len[m] edges after it */
        assert(k >= 3);
        corner_v[m] = walk_boundary(Q, corner_v[prev], (uint64_t)len[prev] + (uint64_t)w[s]);
        corner_v[next] = walk_boundary(Q, corner_v[m], len[m]);
        assert(Q->v_nface[corner_v[m]] == 1 && Q->v_nface[corner_v[next]] == 1);
        len[prev] += (uint32_t)w[s];
        len[next] += (uint32_t)w[s];
    }
    return SQ_OK;
}

/* 1 if gluing all identified sides gives a simple closed quad mesh (every
 * edge determined by its two vertices, no quad with a repeated vertex). */
int sq_domain_glued_is_simple(const sq_domain *D)
{
    sq_soup soup;
    if (sq_domain_glue(D, NULL, &soup, NULL, NULL)) return 0;
    sq_mesh m;
    sq_status st = sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS | SQ_MESH_SKIP_DEGENERATE, &m,
                                     NULL);
    sq_soup_free(&soup);
    if (st == SQ_OK) sq_mesh_free(&m);
    return st == SQ_OK;
}

sq_status sq_domain_order(const uint32_t *val, uint32_t n, int keep, uint32_t *out, sq_error *err)
{
    if (!keep) return sq_valence_order_admissible(val, n, out, err);
    memmove(out, val, (size_t)n * sizeof *val);
    return sq_valence_check_sequence(out, n, NULL, err);
}

/* D takes the subdivided metapolygon sub (freed here) as its quads, with
 * the faces' metapolygon faces and arrays for its D->k corners and sides;
 * *corner_v, *len (D->k, the caller frees them): sub's corners and side
 * lengths, before padding. */
static sq_status take_subdivision(sq_domain *D, sq_mp_quads *sub, uint32_t **corner_v, uint32_t **len, sq_error *err)
{
    const uint32_t k = D->k;
    D->quads_unpadded = sub->mesh.nf;
    D->nf_unpadded = sub->mesh.nf;
    D->f_meta_face = malloc((size_t)sub->mesh.nf * sizeof *D->f_meta_face);
    *corner_v = malloc((size_t)k * sizeof **corner_v);
    *len = malloc((size_t)k * sizeof **len);
    D->corner_vert = malloc((size_t)k * sizeof *D->corner_vert);
    D->side_len = malloc((size_t)k * sizeof *D->side_len);
    D->padding = malloc((size_t)k * sizeof *D->padding);
    if (!D->f_meta_face || !*corner_v || !*len || !D->corner_vert || !D->side_len || !D->padding) {
        sq_mp_quads_free(sub);
        free(*corner_v), free(*len);
        *corner_v = *len = NULL;
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t f = 0; f < sub->mesh.nf; f++) D->f_meta_face[f] = D->meta.he_face[sub->f_origin[f]];
    for (uint32_t j = 0; j < k; j++) {
        (*corner_v)[j] = sub->bnd_vert[sub->corner_pos[j]];
        (*len)[j] = sub->side_len[j];
    }
    D->quads = sub->mesh;
    sq_metapolygon_init(&sub->mesh);
    sq_mp_quads_free(sub);
    return SQ_OK;
}

/* Seed 6.4: D by one slide (sq_domain_slide_build), recorded in D. */
static sq_status build_slid(sq_domain *D, uint32_t *corner_v, uint32_t *len, uint32_t offset, sq_error *err)
{
    sq_slide_info info;
    memset(&info, 0, sizeof info);
    sq_status st = sq_domain_slide_build(D, corner_v, len, offset, &info, err);
    if (st) return st;
    D->slid = 1;
    D->slide_length = info.length;
    D->slide_shift = info.shift;
    D->slide_start = info.seam_start;
    D->slide_end = info.seam_end;
    return SQ_OK;
}

/* D's side pattern: opt's, or the canonical one of the genus; k sides,
 * that genus. */
static sq_status set_pattern(sq_domain *D, uint32_t genus, uint32_t k, const sq_domain_options *opt, sq_error *err)
{
    sq_status st;
    if (opt && opt->pattern) st = sq_pattern_copy(&D->pattern, opt->pattern, err);
    else st = sq_pattern_canonical(genus, &D->pattern, err);
    if (st == SQ_OK && D->pattern.k != k)
        st = sq_error_set(err, SQ_ERR_ARGUMENT, "the pattern has %u sides, genus %u needs %u", D->pattern.k, genus, k);
    if (st == SQ_OK) {
        sq_pattern_info info;
        st = sq_pattern_validate(&D->pattern, &info, err);
        if (st == SQ_OK && info.genus != genus)
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "the pattern has genus %u, not %u", info.genus, genus);
    }
    return st;
}

/* After seed 6.1's padding: the quads added as the solver predicted
 * (expect_added; UINT64_MAX: no prediction) and every side as long as its
 * partner. */
static sq_status check_padded(const sq_domain *D, uint64_t expect_added, sq_error *err)
{
    if (expect_added != UINT64_MAX && D->quads_added != expect_added)
        return sq_error_set(err, SQ_ERR_INTERNAL, "padding added %llu quads, the solver predicted %llu",
                            (unsigned long long)D->quads_added, (unsigned long long)expect_added);
    for (uint32_t i = 0; i < D->k; i++)
        if (D->side_len[i] != D->side_len[D->pattern.partner[i]])
            return sq_error_set(err, SQ_ERR_INTERNAL, "after padding side %u has %u edges, its partner %u has %u", i,
                                D->side_len[i], D->pattern.partner[i], D->side_len[D->pattern.partner[i]]);
    return SQ_OK;
}

sq_status sq_domain_build(uint32_t genus, const int32_t *valences, uint32_t ncones,
                          const sq_domain_options *opt, sq_domain *D, sq_error *err)
{
    double t0 = sq_now();
    sq_domain_init(D);
    D->genus = genus;
    sq_status st = sq_valences_check_realizable(ncones, valences, genus, err);
    if (st) return st;

    /* cones of valence 4 are regular points: not part of the construction */
    uint32_t *irr = malloc(((size_t)ncones + 1) * sizeof *irr);
    D->order = malloc(((size_t)ncones + 1) * sizeof *D->order);
    if (!irr || !D->order) {
        free(irr);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < ncones; i++)
        if (valences[i] != 4) irr[n++] = (uint32_t)valences[i];
    D->ncones = n;
    if (genus < 2) {
        memcpy(D->order, irr, (size_t)n * sizeof *irr);
        st = genus == 0 ? sq_domain_build_genus0(irr, n, opt, D, err)
                        : sq_domain_build_genus1(irr, n, opt, D, err);
        free(irr);
        if (st) goto fail;
        D->seconds = sq_now() - t0;
        return SQ_OK;
    }
    /* seed 5.2: positive excess first */
    st = sq_domain_order(irr, n, opt && opt->keep_order, D->order, err);
    free(irr);
    if (st) goto fail;

    /* seed 5.1-5.2: the metapolygon */
    st = sq_metapolygon_build(&D->meta, D->order, n, opt ? opt->build : NULL, NULL, err);
    if (st) goto fail;

    /* seed 5.4: subdivide */
    sq_mp_quads sub;
    st = sq_metapolygon_subdivide(&D->meta, &sub, err);
    if (st) goto fail;
    const uint32_t k = sub.ncorner;
    if (k != 8 * genus - 4) {
        sq_mp_quads_free(&sub);
        st = sq_error_set(err, SQ_ERR_INTERNAL, "metapolygon has %u corners, expected 8g-4 = %u",
                          k, 8 * genus - 4);
        goto fail;
    }
    D->k = k;
    uint32_t *corner_v = NULL, *len = NULL;
    st = take_subdivision(D, &sub, &corner_v, &len, err);
    if (st) goto fail;

    st = set_pattern(D, genus, k, opt, err);
    if (st) {
        free(corner_v), free(len);
        goto fail;
    }

    /* seed 6.3, 9.3: padding numbers for every side correspondence; the
     * cheapest whose glued mesh is simple (no two quads sharing two edges,
     * no quad touching itself: tiny sides of one face can glue that way)
     * wins */
    offset_choice *choice = NULL;
    uint32_t nchoice = feasible_offsets(&D->pattern, len, opt ? opt->offset : SQ_NONE,
                                        D->quads_unpadded, &choice, err);
    D->offsets_feasible = nchoice;
    if (nchoice == 0) { /* seed 6.4: the pattern fails the rank test: one slide */
        free(choice);
        st = build_slid(D, corner_v, len, opt ? opt->offset : SQ_NONE, err);
        free(corner_v), free(len);
        if (st) goto fail;
        D->seconds = sq_now() - t0;
        return SQ_OK;
    }
    sq_metapolygon unpadded;
    sq_metapolygon_init(&unpadded);
    uint32_t *corner0 = malloc((size_t)k * sizeof *corner0), *len0 = malloc((size_t)k * sizeof *len0);
    if (!corner0 || !len0) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    if (st == SQ_OK) {
        memcpy(corner0, corner_v, (size_t)k * sizeof *corner0);
        memcpy(len0, len, (size_t)k * sizeof *len0);
        st = sq_metapolygon_copy(&unpadded, &D->quads, err);
    }
    uint32_t simple_found = 0, tried = 0;
    /* pass 0: the solver's padding; pass 1: one more layer on every side
     * (the all-ones shift keeps every pair equal, seamless-notes 3), which
     * moves the glued sides apart when short sides of one face would glue
     * into a double edge */
    for (uint32_t c = 0; c < 2 * nchoice && st == SQ_OK && !simple_found; c++) {
        const uint32_t pass = c / nchoice, ci = c % nchoice;
        if (choice[ci].d != 1) continue; /* refinement: not built yet, see below */
        if (pass == 1 && tried >= nchoice + 3) break;
        tried++;
        if (tried > 1) { /* undo the previous attempt */
            st = sq_metapolygon_copy(&D->quads, &unpadded, err);
            memcpy(corner_v, corner0, (size_t)k * sizeof *corner_v);
            memcpy(len, len0, (size_t)k * sizeof *len);
            if (st) break;
        }
        D->offset = choice[ci].offset;
        D->refine = choice[ci].d;
        memcpy(D->padding, choice[ci].w, (size_t)k * sizeof *D->padding);
        uint64_t expect_added = choice[ci].added;
        if (pass == 1) {
            /* the solver did not count these quads: no prediction */
            for (uint32_t i = 0; i < k; i++) D->padding[i] += 1;
            expect_added = UINT64_MAX;
        }
        /* seed 6.1: glue the padding strips */
        st = apply_padding(&D->quads, k, D->offset, D->padding, corner_v, len, err);
        if (st) break;
        for (uint32_t i = 0; i < k; i++) {
            D->corner_vert[i] = corner_v[(i + D->offset) % k];
            D->side_len[i] = len[(i + D->offset) % k];
        }
        D->quads_added = D->quads.nf - D->quads_unpadded;
        st = check_padded(D, expect_added, err);
        if (st == SQ_OK) simple_found = sq_domain_glued_is_simple(D);
    }
    for (uint32_t c = 0; c < nchoice; c++) free(choice[c].w);
    free(choice), free(corner0), free(len0);
    sq_metapolygon_free(&unpadded);
    if (st == SQ_OK && !simple_found)
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "none of the %u feasible side correspondences (%u without "
                          "refinement) glues into a simple quad mesh; refinement is not built "
                          "yet",
                          nchoice, tried);
    free(corner_v), free(len);
    if (st) goto fail;
    D->seconds = sq_now() - t0;
    return SQ_OK;
fail:
    sq_domain_free(D);
    return st;
}

/* ---- gluing ------------------------------------------------------------- */

sq_status sq_domain_glue(const sq_domain *D, const double *xy, sq_soup *out,
                         uint32_t *closed_of, sq_error *err)
{
    const sq_metapolygon *Q = &D->quads;
    memset(out, 0, sizeof *out);
    uint32_t maxlen = 0;
    for (uint32_t i = 0; i < D->k; i++)
        if (D->side_len[i] > maxlen) maxlen = D->side_len[i];
    uint32_t *parent = malloc((size_t)Q->nv * sizeof *parent);
    uint32_t *id = malloc((size_t)Q->nv * sizeof *id);
    uint32_t *a = malloc(((size_t)maxlen + 1) * sizeof *a);
    uint32_t *b = malloc(((size_t)maxlen + 1) * sizeof *b);
    sq_status st = SQ_OK;
    if (!parent || !id || !a || !b) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < Q->nv; v++) parent[v] = v;
    for (uint32_t i = 0; i < D->k; i++) {
        uint32_t j = D->pattern.partner[i];
        if (j < i) continue;
        uint32_t L = D->side_len[i];
        if (D->side_len[j] != L) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "sides %u and %u differ in length", i, j);
            goto done;
        }
        sq_domain_side_vertices(D, i, a);
        sq_domain_side_vertices(D, j, b);
        /* side i forward glues to side j backward */
        for (uint32_t t = 0; t <= L; t++) {
            uint32_t ra = sq_uf_find(parent, a[t]), rb = sq_uf_find(parent, b[L - t]);
            if (ra != rb) parent[ra < rb ? rb : ra] = ra < rb ? ra : rb;
        }
    }
    uint32_t nc = 0;
    for (uint32_t v = 0; v < Q->nv; v++) id[v] = SQ_NONE;
    for (uint32_t v = 0; v < Q->nv; v++) {
        uint32_t r = sq_uf_find(parent, v);
        if (id[r] == SQ_NONE) id[r] = nc++;
        id[v] = id[r];
    }
    out->nv = nc;
    out->nf = Q->nf;
    out->pos = calloc(3 * (size_t)nc, sizeof *out->pos);
    out->face_off = malloc(((size_t)Q->nf + 1) * sizeof *out->face_off);
    out->face_idx = malloc(4 * (size_t)Q->nf * sizeof *out->face_idx);
    if (!out->pos || !out->face_off || !out->face_idx) {
        sq_soup_free(out);
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (xy) {
        for (uint32_t v = Q->nv; v-- > 0;) { /* lowest index wins */
            out->pos[3 * (size_t)id[v]] = xy[2 * (size_t)v];
            out->pos[3 * (size_t)id[v] + 1] = xy[2 * (size_t)v + 1];
        }
    }
    uint32_t c = 0;
    for (uint32_t f = 0; f < Q->nf; f++) {
        out->face_off[f] = c;
        uint32_t h0 = Q->f_he[f], h = h0;
        do {
            if (c >= 4 * (size_t)Q->nf) {
                sq_soup_free(out);
                st = sq_error_set(err, SQ_ERR_INTERNAL, "face %u of Q is not a quad", f);
                goto done;
            }
            out->face_idx[c++] = id[Q->he_vert[h]];
            h = Q->he_next[h];
        } while (h != h0);
    }
    out->face_off[Q->nf] = c;
    if (closed_of) memcpy(closed_of, id, (size_t)Q->nv * sizeof *id);
done:
    free(parent), free(id), free(a), free(b);
    return st;
}

/* ---- verification -------------------------------------------------------- */

static int cmp_i32(const void *x, const void *y)
{
    int32_t a = *(const int32_t *)x, b = *(const int32_t *)y;
    return (a > b) - (a < b);
}

sq_status sq_domain_verify(const sq_domain *D, const int32_t *valences, uint32_t ncones,
                           sq_error *err)
{
    const sq_metapolygon *Q = &D->quads;
    sq_status st = sq_metapolygon_validate(Q, 0, err);
    if (st) return st;
    for (uint32_t f = 0; f < Q->nf; f++)
        if (Q->f_valence[f] != 4)
            return sq_error_set(err, SQ_ERR_INTERNAL, "face %u of Q has %u sides", f,
                                Q->f_valence[f]);
    /* corners: the right-angle corners of the pattern are exactly the
     * boundary vertices with one quad; straight corners have two. Genus 0
     * (seed 6.5) is the sphere cut along one edge: its two "corners" are
     * the edge's ends, with their full set of quads. */
    uint32_t ncorner = 0, nright = 0;
    for (uint32_t v = 0; v < Q->nv; v++) ncorner += Q->v_nface[v] == 1;
    for (uint32_t i = 0; i < D->k; i++) nright += !D->pattern.straight[i];
    if (D->genus > 0 && ncorner != nright)
        return sq_error_set(err, SQ_ERR_INTERNAL, "Q has %u corners, expected %u", ncorner,
                            nright);
    uint64_t perimeter = 0;
    for (uint32_t i = 0; i < D->k; i++) {
        uint32_t want = D->pattern.straight[i] ? 2 : 1;
        if (D->genus > 0 && Q->v_nface[D->corner_vert[i]] != want)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "corner %u (vertex %u) has %u quads, expected %u", i,
                                D->corner_vert[i], Q->v_nface[D->corner_vert[i]], want);
        if (walk_boundary(Q, D->corner_vert[i], D->side_len[i]) != D->corner_vert[(i + 1) % D->k])
            return sq_error_set(err, SQ_ERR_INTERNAL, "side %u does not end at corner %u", i,
                                (i + 1) % D->k);
        if (D->side_len[i] != D->side_len[D->pattern.partner[i]])
            return sq_error_set(err, SQ_ERR_INTERNAL, "sides %u and %u differ in length", i,
                                D->pattern.partner[i]);
        perimeter += D->side_len[i];
    }
    if (perimeter != Q->nbnd)
        return sq_error_set(err, SQ_ERR_INTERNAL, "sides cover %llu of %u boundary edges",
                            (unsigned long long)perimeter, Q->nbnd);

    /* glue and check the closed mesh with the input validator */
    sq_soup soup;
    st = sq_domain_glue(D, NULL, &soup, NULL, err);
    if (st) return st;
    sq_mesh m;
    st = sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS | SQ_MESH_SKIP_DEGENERATE, &m, err);
    sq_soup_free(&soup);
    if (st) {
        char msg[SQ_ERROR_MSG_MAX];
        snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
        return sq_error_set(err, SQ_ERR_INTERNAL, "the glued domain is not a valid closed mesh: %s",
                            msg);
    }
    if (sq_mesh_genus(&m) != (int64_t)D->genus) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "the glued domain has genus %lld, expected %u",
                          (long long)sq_mesh_genus(&m), D->genus);
        sq_mesh_free(&m);
        return st;
    }
    int32_t *got = malloc(((size_t)m.nv + 1) * sizeof *got);
    int32_t *want = malloc(((size_t)ncones + 1) * sizeof *want);
    uint32_t ng = 0, nw = 0;
    if (!got || !want) {
        free(got), free(want);
        sq_mesh_free(&m);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t v = 0; v < m.nv; v++) {
        uint32_t val = sq_mesh_vertex_valence(&m, v);
        if (val != 4) got[ng++] = (int32_t)val;
    }
    for (uint32_t i = 0; i < ncones; i++)
        if (valences[i] != 4) want[nw++] = valences[i];
    qsort(got, ng, sizeof *got, cmp_i32);
    qsort(want, nw, sizeof *want, cmp_i32);
    if (ng != nw || memcmp(got, want, (size_t)ng * sizeof *got))
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "the glued domain has %u irregular vertices, expected %u cones "
                          "(multisets differ)",
                          ng, nw);
    free(got), free(want);
    sq_mesh_free(&m);
    return st;
}
