/* seamquad: cutting Q along the cone tree into the disk Omega_c (seed 7:
 * "Cutting both, Q and M^c, along the respective spanning trees, yields
 * disk topology surfaces with all extraordinary vertices or singularities
 * lying on the boundary"; seed Fig. 2 c -> d).
 *
 * An edge of Q is cut if it is on Q's boundary or on the tree. A vertex of
 * Omega_c is a sector: a maximal run of face corners around one vertex of Q
 * in which consecutive corners share an uncut edge (union-find over the
 * corners). An interior vertex of Q off the tree is one sector; a tree
 * vertex of degree d inside Q gives d sectors; a boundary vertex of Q with
 * d tree edges gives d + 1. Every cut edge side becomes a boundary halfedge
 * of Omega_c, and the boundary loop is stitched by turning
 * counterclockwise through each sector. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"

static uint32_t uf_find(uint32_t *p, uint32_t x)
{
    while (p[x] != x) {
        p[x] = p[p[x]];
        x = p[x];
    }
    return x;
}

static void uf_union(uint32_t *p, uint32_t a, uint32_t b)
{
    a = uf_find(p, a);
    b = uf_find(p, b);
    if (a != b) p[a < b ? b : a] = a < b ? a : b;
}

/* state shared by the steps of sq_omega_cut */
typedef struct {
    const sq_domain *D;
    const sq_cone_tree *T;
    const sq_metapolygon *Q;
    sq_omega *O;
    sq_metapolygon *C;
    uint32_t k, nh;
    uint64_t nfh, nb, nv64;
    uint32_t *c_of, *c_prev, *uf, *vid, *side_of, *side_pos, *seg_lab;
    uint8_t *cutq;
    uint32_t **side_he;
    uint32_t nv;                       /* sectors found */
    uint32_t split, xa, xb, rs, rp;    /* the root's split of its side */
} cut_ctx;

/* face halfedges of Q -> cut indices, face by face from f_he */
static sq_status cut_faces(cut_ctx *x, sq_error *err)
{
    const sq_metapolygon *Q = x->Q;
    sq_omega *O = x->O;
    sq_metapolygon *C = x->C;
    uint32_t *c_of = x->c_of, *c_prev = x->c_prev;
    for (uint32_t h = 0; h < Q->nh; h++) c_of[h] = SQ_NONE;
    uint32_t c = 0;
    for (uint32_t f = 0; f < Q->nf; f++) {
        uint32_t h = Q->f_he[f], val = Q->f_valence[f], c0 = c;
        for (uint32_t i = 0; i < val; i++, c++, h = Q->he_next[h]) {
            if (Q->he_face[h] != f)
                return sq_error_set(err, SQ_ERR_INTERNAL, "omega: face %u of Q is broken", f);
            c_of[h] = c;
            O->he_qhe[c] = h;
            C->he_face[c] = f;
            C->he_next[c] = c0 + (i + 1) % val;
            c_prev[c] = c0 + (i + val - 1) % val;
        }
        if (h != Q->f_he[f])
            return sq_error_set(err, SQ_ERR_INTERNAL, "omega: face %u of Q has a wrong valence", f);
        C->f_he[f] = c0;
        C->f_valence[f] = val;
    }
    return SQ_OK;
}

/* cut edges (Q's boundary and the tree) and the tree segments' labels */
static sq_status cut_mark_edges(cut_ctx *x, sq_error *err)
{
    const sq_metapolygon *Q = x->Q;
    const sq_cone_tree *T = x->T;
    const uint32_t k = x->k;
    uint8_t *cutq = x->cutq;
    uint32_t *seg_lab = x->seg_lab;
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) cutq[h] = cutq[Q->he_twin[h]] = 1;
    for (uint32_t h = 0; h < Q->nh; h++) seg_lab[h] = SQ_NONE;
    for (uint32_t s = 0; s < T->nseg; s++)
        for (uint32_t r = T->seg_off[s]; r < T->seg_off[s + 1]; r++) {
            uint32_t h = T->seg_he[r];
            if (cutq[h])
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "omega: tree edge (halfedge %u) is on Q's boundary or repeated",
                                    h);
            cutq[h] = cutq[Q->he_twin[h]] = 1;
            /* the face left of the segment's halfedge is on its left side */
            seg_lab[h] = k + 2 * s;
            seg_lab[Q->he_twin[h]] = k + 2 * s + 1;
        }
    return SQ_OK;
}

/* sectors: corner c at v joins the corner across the edge of prev(c);
 * numbers the sectors as the cut's vertices (x->nv of them) */
static sq_status cut_sectors(cut_ctx *x, sq_error *err)
{
    const sq_metapolygon *Q = x->Q;
    sq_omega *O = x->O;
    sq_metapolygon *C = x->C;
    const uint64_t nfh = x->nfh, nv64 = x->nv64;
    uint32_t *uf = x->uf, *vid = x->vid;
    for (uint32_t i = 0; i < nfh; i++) uf[i] = i;
    for (uint32_t i = 0; i < nfh; i++) {
        uint32_t p = O->he_qhe[x->c_prev[i]];
        if (!x->cutq[p]) uf_union(uf, i, x->c_of[Q->he_twin[p]]);
    }
    for (uint32_t i = 0; i < nfh; i++) vid[i] = SQ_NONE;
    uint32_t nv = 0;
    for (uint32_t i = 0; i < nfh; i++) {
        uint32_t r = uf_find(uf, i);
        if (vid[r] == SQ_NONE) {
            if (nv >= nv64)
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "omega: more than Q.nv + tree edges = %llu sectors",
                                    (unsigned long long)nv64);
            vid[r] = nv;
            O->v_qvert[nv] = Q->he_vert[O->he_qhe[i]];
            C->v_he[nv] = i;
            C->v_nface[nv] = 0;
            nv++;
        }
        C->he_vert[i] = vid[r];
        C->v_nface[vid[r]]++;
    }
    x->nv = nv;
    return SQ_OK;
}

/* Q's sides: side and position of every boundary halfedge */
static sq_status cut_sides(cut_ctx *x, sq_error *err)
{
    const sq_domain *D = x->D;
    const sq_metapolygon *Q = x->Q;
    const uint32_t k = x->k;
    uint32_t *side_of = x->side_of;
    for (uint32_t h = 0; h < Q->nh; h++) side_of[h] = SQ_NONE;
    uint64_t covered = 0;
    for (uint32_t i = 0; i < k; i++) {
        uint32_t h = Q->v_he[D->corner_vert[i]];
        for (uint32_t t = 0; t < D->side_len[i]; t++, h = Q->he_next[h]) {
            if (Q->he_face[h] != SQ_NONE || side_of[h] != SQ_NONE)
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "omega: side %u of Q is not a run of boundary edges", i);
            side_of[h] = i;
            x->side_pos[h] = t;
            x->side_he[i][t] = h;
            covered++;
        }
        if (h != Q->v_he[D->corner_vert[(i + 1) % k]])
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "omega: side %u of Q does not end at corner %u", i, (i + 1) % k);
    }
    if (covered != Q->nbnd)
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "omega: Q's sides cover %llu of %u boundary edges",
                            (unsigned long long)covered, Q->nbnd);
    return SQ_OK;
}

/* the root's place on Q's boundary; inside a side it splits that side
 * and the part of its partner glued to it into two labels each */
static sq_status cut_root(cut_ctx *x, sq_error *err)
{
    const sq_domain *D = x->D;
    const sq_cone_tree *T = x->T;
    const sq_metapolygon *Q = x->Q;
    sq_omega *O = x->O;
    uint32_t *side_of = x->side_of, *side_pos = x->side_pos;
    O->root_side = O->root_pos = SQ_NONE;
    {
        uint32_t h = Q->v_he[T->root];
        if (T->root >= Q->nv || Q->he_face[h] != SQ_NONE || side_of[h] == SQ_NONE)
            return sq_error_set(err, SQ_ERR_ARGUMENT, "omega: the tree's root %u is not on Q's "
                                                      "boundary", T->root);
        O->root_side = side_of[h];
        O->root_pos = side_pos[h];
    }
    const uint32_t split = O->root_pos > 0, xa = x->k + 2 * T->nseg, xb = xa + 1;
    const uint32_t rs = O->root_side, rp = D->pattern.partner[rs];
    const uint32_t rl = D->side_len[rs], rm = O->root_pos;
    if (!split) O->nlabels -= 2;
    for (uint32_t h = 0; h < Q->nh; h++) {
        if (!split || side_of[h] == SQ_NONE) continue;
        /* side rs position t glues to side rp position L-1-t */
        if (side_of[h] == rs && side_pos[h] >= rm) side_of[h] = xa;
        else if (side_of[h] == rp && side_pos[h] < rl - rm) side_of[h] = xb;
    }
    x->split = split;
    x->xa = xa;
    x->xb = xb;
    x->rs = rs;
    x->rp = rp;
    return SQ_OK;
}

/* boundary halfedges of the cut: one per side of a cut edge */
static sq_status cut_boundary(cut_ctx *x, sq_error *err)
{
    const sq_metapolygon *Q = x->Q;
    sq_omega *O = x->O;
    sq_metapolygon *C = x->C;
    const uint64_t nfh = x->nfh;
    const uint32_t nh = x->nh;
    uint32_t b = (uint32_t)nfh;
    for (uint32_t i = 0; i < nfh; i++) {
        uint32_t h = O->he_qhe[i], t = Q->he_twin[h];
        if (!x->cutq[h]) {
            C->he_twin[i] = x->c_of[t];
            O->he_label[i] = SQ_NONE;
            continue;
        }
        if (b >= nh)
            return sq_error_set(err, SQ_ERR_INTERNAL, "omega: more boundary edges than expected");
        C->he_twin[i] = b;
        C->he_twin[b] = i;
        C->he_vert[b] = C->he_vert[C->he_next[i]];
        C->he_face[b] = SQ_NONE;
        O->he_qhe[b] = t;
        O->he_label[i] = SQ_NONE;
        O->he_label[b] = Q->he_face[t] == SQ_NONE ? x->side_of[t] : x->seg_lab[h];
        if (O->he_label[b] == SQ_NONE)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "omega: cut edge (halfedge %u) has no label", h);
        b++;
    }
    if (b != nh)
        return sq_error_set(err, SQ_ERR_INTERNAL, "omega: %u boundary edges, expected %llu",
                            b - (uint32_t)nfh, (unsigned long long)x->nb);
    return SQ_OK;
}

/* boundary loop: from the tail corner of b's interior twin, turn
 * counterclockwise through the sector to its last corner x; the next
 * boundary halfedge is the twin of prev(x) */
static sq_status cut_boundary_loop(cut_ctx *cx, sq_error *err)
{
    const sq_metapolygon *Q = cx->Q;
    const sq_omega *O = cx->O;
    sq_metapolygon *C = cx->C;
    const uint32_t *c_prev = cx->c_prev;
    for (uint32_t b = (uint32_t)cx->nfh; b < cx->nh; b++) {
        uint32_t x = C->he_twin[b], v = Q->he_vert[O->he_qhe[x]];
        for (uint32_t steps = 0;; steps++) {
            uint32_t p = O->he_qhe[c_prev[x]];
            if (cx->cutq[p]) break;
            x = cx->c_of[Q->he_twin[p]];
            if (steps > Q->v_nface[v])
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "omega: sector without end at vertex %u of Q", v);
        }
        C->he_next[b] = C->he_twin[c_prev[x]];
        C->v_he[C->he_vert[b]] = b;
    }
    return SQ_OK;
}

/* the other copy of every boundary edge, and the labels' partners and sides */
static sq_status cut_partners(cut_ctx *x, sq_error *err)
{
    const sq_domain *D = x->D;
    const sq_metapolygon *Q = x->Q;
    sq_omega *O = x->O;
    const sq_metapolygon *C = x->C;
    const uint64_t nfh = x->nfh;
    const uint32_t nh = x->nh, k = x->k, split = x->split;
    const uint32_t xa = x->xa, xb = x->xb, rs = x->rs, rp = x->rp;
    for (uint32_t i = 0; i < nh; i++) O->he_partner[i] = SQ_NONE;
    for (uint32_t b = (uint32_t)nfh; b < nh; b++) {
        uint32_t q = O->he_qhe[b], other;
        if (Q->he_face[q] == SQ_NONE) {
            uint32_t l = x->side_of[q];
            uint32_t i = l == xa && split ? rs : l == xb && split ? rp : l;
            uint32_t j = D->pattern.partner[i], L = D->side_len[i];
            if (D->side_len[j] != L)
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "omega: sides %u and %u glue but have lengths %u and %u", i,
                                    j, L, D->side_len[j]);
            /* side i forward glues to side j backward */
            other = x->side_he[j][L - 1 - x->side_pos[q]];
        } else {
            other = Q->he_twin[q]; /* the copy whose face is on q's side */
        }
        uint32_t ob = C->he_twin[x->c_of[Q->he_twin[other]]];
        if (ob < nfh)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "omega: partner of boundary edge %u is inside", b);
        O->he_partner[b] = ob;
    }
    for (uint32_t l = 0; l < O->nlabels; l++) {
        O->label_partner[l] = l < k ? D->pattern.partner[l] : k + ((l - k) ^ 1u);
        O->label_side[l] = l < k ? l : l == xa ? rs : l == xb ? rp : SQ_NONE;
    }
    return SQ_OK;
}

sq_status sq_omega_cut(const sq_domain *D, const sq_cone_tree *T, sq_omega *O, sq_error *err)
{
    const sq_metapolygon *Q = &D->quads;
    sq_omega_free(O);
    const uint32_t k = D->k;
    uint64_t nfh = 0;
    for (uint32_t f = 0; f < Q->nf; f++) nfh += Q->f_valence[f];
    const uint64_t nb = (uint64_t)Q->nbnd + 2 * (uint64_t)T->nedges;
    const uint64_t nh64 = nfh + nb, nv64 = (uint64_t)Q->nv + T->nedges;
    if (nh64 >= UINT32_MAX || nv64 >= UINT32_MAX)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "omega: Q too large (%llu halfedges)",
                            (unsigned long long)nh64);
    const uint32_t nh = (uint32_t)nh64;
    sq_status st = SQ_OK;
    uint32_t *c_of = malloc((Q->nh ? Q->nh : 1) * sizeof *c_of);
    uint32_t *c_prev = malloc((nfh ? nfh : 1) * sizeof *c_prev);
    uint32_t *uf = malloc((nfh ? nfh : 1) * sizeof *uf);
    uint32_t *vid = malloc((nfh ? nfh : 1) * sizeof *vid);
    uint8_t *cutq = calloc(Q->nh ? Q->nh : 1, 1);
    uint32_t *side_of = malloc((Q->nh ? Q->nh : 1) * sizeof *side_of);
    uint32_t *side_pos = malloc((Q->nh ? Q->nh : 1) * sizeof *side_pos);
    uint32_t *seg_lab = malloc((Q->nh ? Q->nh : 1) * sizeof *seg_lab);
    uint32_t **side_he = calloc(k ? k : 1, sizeof *side_he);
    O->v_qvert = malloc(nv64 * sizeof *O->v_qvert);
    O->he_qhe = malloc(nh * sizeof *O->he_qhe);
    O->he_label = malloc(nh * sizeof *O->he_label);
    O->he_partner = malloc(nh * sizeof *O->he_partner);
    O->nlabels = k + 2 * T->nseg + 2; /* trimmed below if the root is a corner */
    O->label_partner = malloc(O->nlabels * sizeof *O->label_partner);
    O->label_side = malloc(O->nlabels * sizeof *O->label_side);
    if (!c_of || !c_prev || !uf || !vid || !cutq || !side_of || !side_pos || !seg_lab ||
        !side_he || !O->v_qvert || !O->he_qhe || !O->he_label || !O->he_partner ||
        !O->label_partner || !O->label_side) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t i = 0; i < k; i++)
        if (!(side_he[i] = malloc(((size_t)D->side_len[i] + 1) * sizeof **side_he))) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
    st = sq_metapolygon_reserve(&O->cut, nv64, Q->nf, nh, err);
    if (st) goto done;
    sq_metapolygon *C = &O->cut;
    O->k = k;

    cut_ctx x = {.D = D, .T = T, .Q = Q, .O = O, .C = C, .k = k, .nh = nh, .nfh = nfh,
                 .nb = nb, .nv64 = nv64, .c_of = c_of, .c_prev = c_prev, .uf = uf,
                 .vid = vid, .side_of = side_of, .side_pos = side_pos, .seg_lab = seg_lab,
                 .cutq = cutq, .side_he = side_he};
    if ((st = cut_faces(&x, err)) || (st = cut_mark_edges(&x, err)) ||
        (st = cut_sectors(&x, err)) || (st = cut_sides(&x, err)) || (st = cut_root(&x, err)) ||
        (st = cut_boundary(&x, err)) || (st = cut_boundary_loop(&x, err)) ||
        (st = cut_partners(&x, err)))
        goto done;
    const uint32_t nv = x.nv;

    C->nv = nv;
    C->nf = Q->nf;
    C->nh = nh;
    C->nbnd = (uint32_t)nb;
    C->bnd_he = SQ_NONE;
    if (k && Q->nbnd) {
        uint32_t q = Q->v_he[D->corner_vert[0]];
        C->bnd_he = C->he_twin[c_of[Q->he_twin[q]]];
    } else if (nb) {
        C->bnd_he = (uint32_t)nfh;
    }
    if (nv != nv64) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "omega: %u vertices after cutting, expected Q's %u + %u tree edges", nv,
                          Q->nv, T->nedges);
        goto done;
    }
    st = sq_metapolygon_validate(C, 0, err);
done:
    free(c_of);
    free(c_prev);
    free(uf);
    free(vid);
    free(cutq);
    free(side_of);
    free(side_pos);
    free(seg_lab);
    if (side_he)
        for (uint32_t i = 0; i < k; i++) free(side_he[i]);
    free(side_he);
    if (st) sq_omega_free(O);
    return st;
}
