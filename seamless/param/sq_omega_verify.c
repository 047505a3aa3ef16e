/* seamquad: independent check of the flat domain Omega (seed 3, conditions
 * (1) and (3); seed 7; seed 8 "Boundary Map"). Recomputes from D and T what
 * sq_omega_cut and sq_omega_layout derived, in exact integers; see
 * sq_omega.h for the list of checks. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"
#include "sq_omega_grid.h"


#define FAIL(...)                                                                                  \
    do {                                                                                           \
        st = sq_error_set(err, SQ_ERR_INTERNAL, __VA_ARGS__);                                      \
        goto done;                                                                                 \
    } while (0)

/* a failed check inside a step of sq_omega_verify */
#define REJECT(...) return sq_error_set(err, SQ_ERR_INTERNAL, __VA_ARGS__)

/* state shared by the steps of sq_omega_verify */
typedef struct {
    const sq_domain *D;
    const sq_cone_tree *T;
    const sq_omega *O;
    const sq_metapolygon *Q, *C;
    uint32_t k;
    uint32_t *angle, *pangle, *copies, *asum;
    uint32_t *bcopy; /* Q he -> cut bnd he */
    uint32_t *glued; /* Q bnd he -> partner */
    uint32_t *lab;   /* expected label */
    uint32_t *tdeg;
    uint8_t *on_bnd, *cbnd;
    uint32_t *side_a, *side_b;
} verify_ctx;

/* the copy maps agree with Q face by face */
static sq_status check_face_copies(const verify_ctx *vc, sq_error *err)
{
    const sq_metapolygon *Q = vc->Q, *C = vc->C;
    const sq_omega *O = vc->O;
    for (uint32_t f = 0; f < C->nf; f++) {
        if (C->f_valence[f] != 4 || Q->f_valence[f] != 4) REJECT("omega: face %u is not a quad", f);
        uint32_t h = C->f_he[f], q = O->he_qhe[h];
        if (q != Q->f_he[f]) REJECT("omega: face %u starts at another corner than in Q", f);
        for (uint32_t i = 0; i < 4; i++, h = C->he_next[h], q = Q->he_next[q]) {
            if (O->he_qhe[h] != q || O->v_qvert[C->he_vert[h]] != Q->he_vert[q])
                REJECT("omega: face %u corner %u does not copy Q", f, i);
        }
    }
    return SQ_OK;
}

/* tree and boundary marks of Q; the sides' labels and glued partners */
static sq_status mark_tree_and_sides(verify_ctx *vc, sq_error *err)
{
    const sq_domain *D = vc->D;
    const sq_cone_tree *T = vc->T;
    const sq_metapolygon *Q = vc->Q;
    const uint32_t k = vc->k;
    uint32_t *bcopy = vc->bcopy, *glued = vc->glued, *lab = vc->lab, *tdeg = vc->tdeg;
    for (uint32_t h = 0; h < Q->nh; h++) {
        bcopy[h] = glued[h] = lab[h] = SQ_NONE;
        if (Q->he_face[h] == SQ_NONE) vc->on_bnd[Q->he_vert[h]] = 1;
    }
    for (uint32_t s = 0; s < T->nseg; s++)
        for (uint32_t r = T->seg_off[s]; r < T->seg_off[s + 1]; r++) {
            uint32_t h = T->seg_he[r];
            lab[Q->he_twin[h]] = k + 2 * s;     /* the boundary copy left of h */
            lab[h] = k + 2 * s + 1;             /* copies twin(h): right side  */
            tdeg[Q->he_vert[h]]++;
            tdeg[Q->he_vert[Q->he_twin[h]]]++;
        }
    /* sides: label and glued partner of every boundary halfedge of Q */
    uint32_t maxlen = 0;
    for (uint32_t i = 0; i < k; i++)
        if (D->side_len[i] > maxlen) maxlen = D->side_len[i];
    uint32_t *side_a = vc->side_a = malloc(((size_t)maxlen + 1) * sizeof *side_a);
    uint32_t *side_b = vc->side_b = malloc(((size_t)maxlen + 1) * sizeof *side_b);
    if (!side_a || !side_b)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t i = 0; i < k; i++) {
        uint32_t j = D->pattern.partner[i], L = D->side_len[i];
        if (D->side_len[j] != L) REJECT("omega: sides %u and %u differ in length", i, j);
        uint32_t h = Q->v_he[D->corner_vert[i]];
        for (uint32_t t = 0; t < L; t++, h = Q->he_next[h]) side_a[t] = h, lab[h] = i;
        h = Q->v_he[D->corner_vert[j]];
        for (uint32_t t = 0; t < L; t++, h = Q->he_next[h]) side_b[t] = h;
        for (uint32_t t = 0; t < L; t++) glued[side_a[t]] = side_b[L - 1 - t];
    }
    return SQ_OK;
}

/* the root's split of its side, the label count and the labels' sides */
static sq_status check_root_labels(verify_ctx *vc, sq_error *err)
{
    const sq_domain *D = vc->D;
    const sq_cone_tree *T = vc->T;
    const sq_omega *O = vc->O;
    const sq_metapolygon *Q = vc->Q;
    const uint32_t k = vc->k;
    uint32_t *lab = vc->lab;
    /* the root inside side r splits r after the root, and the part of its
     * partner glued to that, off as labels k + 2 nseg and k + 2 nseg + 1 */
    uint32_t split = 0;
    {
        uint32_t r = SQ_NONE, m = 0;
        for (uint32_t i = 0; i < k && r == SQ_NONE; i++) {
            uint32_t h = Q->v_he[D->corner_vert[i]];
            for (uint32_t t = 0; t < D->side_len[i]; t++, h = Q->he_next[h])
                if (Q->he_vert[h] == T->root) r = i, m = t;
        }
        if (r == SQ_NONE) REJECT("omega: the tree's root %u is not on a side of Q", T->root);
        if (O->root_side != r || O->root_pos != m)
            REJECT("omega: root recorded at side %u position %u, is at side %u position %u",
                   O->root_side, O->root_pos, r, m);
        split = m > 0;
        uint32_t j = D->pattern.partner[r], L = D->side_len[r];
        uint32_t h = Q->v_he[D->corner_vert[r]];
        for (uint32_t t = 0; t < L; t++, h = Q->he_next[h])
            if (split && t >= m) lab[h] = k + 2 * T->nseg;
        h = Q->v_he[D->corner_vert[j]];
        for (uint32_t t = 0; t < L; t++, h = Q->he_next[h])
            if (split && t < L - m) lab[h] = k + 2 * T->nseg + 1;
    }
    if (O->k != k || O->nlabels != k + 2 * T->nseg + 2 * split) REJECT("omega: wrong label count");
    for (uint32_t l = 0; l < O->nlabels; l++) {
        uint32_t want = l < k                    ? l
                        : l < k + 2 * T->nseg    ? SQ_NONE
                        : l == k + 2 * T->nseg   ? O->root_side
                                                 : D->pattern.partner[O->root_side];
        if (O->label_side[l] != want) REJECT("omega: label %u lies on side %u, expected %u", l,
                                             O->label_side[l], want);
    }
    return SQ_OK;
}

/* boundary halfedges of the cut: what they copy, labels, partners */
static sq_status check_boundary_copies(verify_ctx *vc, sq_error *err)
{
    const sq_omega *O = vc->O;
    const sq_metapolygon *Q = vc->Q, *C = vc->C;
    const uint32_t *lab = vc->lab;
    uint32_t *bcopy = vc->bcopy;
    for (uint32_t b = 0; b < C->nh; b++) {
        uint32_t c = C->he_twin[b];
        if (C->he_face[b] != SQ_NONE) {
            if (C->he_face[c] == SQ_NONE) continue;
            /* an uncut edge: an interior edge of Q off the tree */
            if (O->he_qhe[c] != Q->he_twin[O->he_qhe[b]] || lab[O->he_qhe[b]] != SQ_NONE ||
                Q->he_face[Q->he_twin[O->he_qhe[b]]] == SQ_NONE)
                REJECT("omega: inner halfedge %u does not copy an uncut edge of Q", b);
            continue;
        }
        uint32_t q = O->he_qhe[b];
        if (q >= Q->nh || O->he_qhe[c] != Q->he_twin[q]) REJECT("omega: boundary halfedge %u: "
                                                               "bad copy", b);
        if (bcopy[q] != SQ_NONE) REJECT("omega: halfedge %u of Q copied twice", q);
        bcopy[q] = b;
        if (lab[q] == SQ_NONE || O->he_label[b] != lab[q])
            REJECT("omega: boundary halfedge %u has label %u, expected %u", b, O->he_label[b],
                   lab[q]);
        vc->cbnd[C->he_vert[b]] = 1;
    }
    for (uint32_t b = 0; b < C->nh; b++) {
        if (C->he_face[b] != SQ_NONE) continue;
        uint32_t q = O->he_qhe[b];
        /* its other copy: the glued side's edge, or the tree edge's other side */
        uint32_t oq = Q->he_face[q] == SQ_NONE ? vc->glued[q] : Q->he_twin[q];
        uint32_t p = oq == SQ_NONE ? SQ_NONE : bcopy[oq];
        if (p == SQ_NONE || O->he_partner[b] != p || O->he_partner[p] != b)
            REJECT("omega: boundary halfedge %u has the wrong partner", b);
        uint32_t l = O->he_label[b], pl = O->he_label[p];
        if (O->label_partner[l] != pl || O->label_partner[pl] != l)
            REJECT("omega: labels %u and %u are not partners", l, pl);
    }
    return SQ_OK;
}

/* layout: unit squares, regular interior vertices, the boundary's turning */
static sq_status check_layout(const verify_ctx *vc, sq_error *err)
{
    const sq_omega *O = vc->O;
    const sq_metapolygon *Q = vc->Q, *C = vc->C;
    /* layout: counterclockwise axis-aligned unit squares */
    for (uint32_t f = 0; f < C->nf; f++) {
        uint32_t h = C->f_he[f], d0 = 4;
        for (uint32_t i = 0; i < 4; i++, h = C->he_next[h]) {
            uint32_t a = C->he_vert[h], z = C->he_vert[C->he_next[h]];
            uint32_t d = dir_of(O->xy[2 * z] - O->xy[2 * a], O->xy[2 * z + 1] - O->xy[2 * a + 1]);
            if (d > 3) REJECT("omega: face %u edge %u is not a unit axis edge", f, i);
            if (i == 0) {
                d0 = d;
                if (d != O->f_dir[f]) REJECT("omega: face %u: stored direction is wrong", f);
            } else if (d != ((d0 + i) & 3u)) {
                REJECT("omega: face %u is not a counterclockwise unit square", f);
            }
        }
    }
    /* interior vertices: four quads, a regular vertex of Q off the tree */
    for (uint32_t w = 0; w < C->nv; w++) {
        uint32_t v = O->v_qvert[w];
        if (vc->cbnd[w]) continue;
        if (C->v_nface[w] != 4 || vc->on_bnd[v] || Q->v_nface[v] != 4 || vc->tdeg[v])
            REJECT("omega: interior vertex %u (vertex %u of Q) is not a regular point", w, v);
    }
    /* boundary: turn at each vertex vs its quad corners; total turning */
    int64_t turning = 0;
    for (uint32_t b = 0; b < C->nh; b++) {
        if (C->he_face[b] != SQ_NONE) continue;
        uint32_t n = C->he_next[b], a = C->he_vert[b], w = C->he_vert[n];
        uint32_t z = C->he_vert[C->he_next[n]];
        uint32_t din = dir_of(O->xy[2 * w] - O->xy[2 * a], O->xy[2 * w + 1] - O->xy[2 * a + 1]);
        uint32_t dout = dir_of(O->xy[2 * z] - O->xy[2 * w], O->xy[2 * z + 1] - O->xy[2 * w + 1]);
        if (din > 3 || dout > 3) REJECT("omega: boundary edge %u is not a unit axis edge", b);
        /* the disk lies to the right: n corners turn by n - 2 quarter turns */
        int64_t nc = C->v_nface[w];
        if (((int64_t)dout - (int64_t)din - (nc - 2)) % 4 != 0)
            REJECT("omega: boundary vertex %u (vertex %u of Q): %lld quad corners but the "
                   "boundary turns from direction %u to %u",
                   w, O->v_qvert[w], (long long)nc, din, dout);
        turning += 2 - nc;
    }
    if (C->nbnd && turning != 4)
        REJECT("omega: the boundary turns by %lld quarter turns, not 4", (long long)turning);
    return SQ_OK;
}

/* transitions on every boundary edge, faces on opposite sides, and
 * partner transitions inverse */
static sq_status check_transitions(const verify_ctx *vc, sq_error *err)
{
    const sq_omega *O = vc->O;
    const sq_metapolygon *C = vc->C;
    const uint32_t k = vc->k;
    for (uint32_t b = 0; b < C->nh; b++) {
        if (C->he_face[b] != SQ_NONE) continue;
        uint32_t p = O->he_partner[b], l = O->he_label[b], r = O->label_rot[l];
        int64_t tx = O->label_t[2 * l], ty = O->label_t[2 * l + 1];
        uint32_t ends[2][2] = {{C->he_vert[b], C->he_vert[C->he_next[p]]},
                               {C->he_vert[C->he_next[b]], C->he_vert[p]}};
        for (int e = 0; e < 2; e++) {
            int64_t x, y;
            rot(r, O->xy[2 * ends[e][0]], O->xy[2 * ends[e][0] + 1], &x, &y);
            if (x + tx != O->xy[2 * ends[e][1]] || y + ty != O->xy[2 * ends[e][1] + 1])
                REJECT("omega: label %u (%s %u): vertex %u (vertex %u of Q) is not mapped onto "
                       "its copy %u",
                       l, O->label_side[l] != SQ_NONE ? "side" : "tree segment",
                       O->label_side[l] != SQ_NONE ? O->label_side[l] : (l - k) / 2, ends[e][0],
                       O->v_qvert[ends[e][0]], ends[e][1]);
            if (O->v_qvert[ends[e][0]] != O->v_qvert[ends[e][1]] &&
                O->label_side[l] == SQ_NONE)
                REJECT("omega: tree copies %u, %u of different vertices", ends[e][0], ends[e][1]);
        }
        /* inward normals: into the face, across the edge */
        uint32_t c = C->he_twin[b], cp = C->he_twin[p];
        uint32_t c1 = C->he_vert[C->he_next[c]], c2 = C->he_vert[C->he_next[C->he_next[c]]];
        uint32_t p1 = C->he_vert[C->he_next[cp]], p2 = C->he_vert[C->he_next[C->he_next[cp]]];
        int64_t nx, ny;
        rot(r, O->xy[2 * c2] - O->xy[2 * c1], O->xy[2 * c2 + 1] - O->xy[2 * c1 + 1], &nx, &ny);
        if (nx != -(O->xy[2 * p2] - O->xy[2 * p1]) ||
            ny != -(O->xy[2 * p2 + 1] - O->xy[2 * p1 + 1]))
            REJECT("omega: label %u: the faces on the two copies of boundary edge %u overlap", l,
                   b);
    }
    for (uint32_t l = 0; l < O->nlabels; l++) {
        uint32_t m = O->label_partner[l];
        if (m >= O->nlabels || O->label_partner[m] != l || m == l)
            REJECT("omega: label %u has a bad partner", l);
        int64_t x, y;
        rot(O->label_rot[m], O->label_t[2 * l], O->label_t[2 * l + 1], &x, &y);
        if (((O->label_rot[l] + O->label_rot[m]) & 3u) || x + O->label_t[2 * m] ||
            y + O->label_t[2 * m + 1])
            REJECT("omega: transitions of labels %u and %u are not inverse", l, m);
    }
    return SQ_OK;
}

/* angles: per copy, per vertex of Q, per glued point (seed 3 (1), 8) */
static sq_status check_angles(verify_ctx *vc, sq_error *err)
{
    const sq_omega *O = vc->O;
    const sq_metapolygon *Q = vc->Q, *C = vc->C;
    const uint8_t *on_bnd = vc->on_bnd;
    uint32_t *angle = vc->angle, *pangle = vc->pangle, *copies = vc->copies, *asum = vc->asum;
    sq_status st = sq_omega_angles(vc->D, O, angle, pangle, err);
    if (st) return st;
    for (uint32_t w = 0; w < C->nv; w++) {
        copies[O->v_qvert[w]]++;
        asum[O->v_qvert[w]] += angle[w];
    }
    for (uint32_t v = 0; v < Q->nv; v++) {
        if (asum[v] != Q->v_nface[v])
            REJECT("omega: vertex %u of Q: its copies have %u quad corners, Q has %u", v, asum[v],
                   Q->v_nface[v]);
        int cone = !on_bnd[v] && Q->v_nface[v] != 4;
        if (cone) {
            uint32_t want = vc->tdeg[v];
            if (copies[v] != want)
                REJECT("omega: cone %u (valence %u) has %u copies, tree degree %u", v,
                       Q->v_nface[v], copies[v], want);
            if (pangle[v] != Q->v_nface[v])
                REJECT("omega: cone %u: angle %u x 90 deg, valence %u", v, pangle[v],
                       Q->v_nface[v]);
        } else if (pangle[v] != 4) {
            REJECT("omega: vertex %u of Q (%s) has angle %u x 90 deg, not 360", v,
                   on_bnd[v] ? "on a side or a corner class" : "interior", pangle[v]);
        }
    }
    for (uint32_t w = 0; w < C->nv; w++) {
        uint32_t v = O->v_qvert[w];
        if (!on_bnd[v] && Q->v_nface[v] != 4 && !vc->cbnd[w])
            REJECT("omega: cone %u has a copy %u inside Omega", v, w);
    }
    return SQ_OK;
}

sq_status sq_omega_verify(const sq_domain *D, const sq_cone_tree *T, const sq_omega *O,
                          sq_error *err)
{
    const sq_metapolygon *Q = &D->quads, *C = &O->cut;
    sq_status st = sq_metapolygon_validate(C, 0, err);
    if (st) return st;
    const uint32_t k = D->k;
    verify_ctx vc = {.D = D, .T = T, .O = O, .Q = Q, .C = C, .k = k};
    vc.angle = malloc((C->nv ? C->nv : 1) * sizeof *vc.angle);
    vc.pangle = malloc((Q->nv ? Q->nv : 1) * sizeof *vc.pangle);
    vc.copies = calloc(Q->nv ? Q->nv : 1, sizeof *vc.copies);
    vc.asum = calloc(Q->nv ? Q->nv : 1, sizeof *vc.asum);
    vc.bcopy = malloc((Q->nh ? Q->nh : 1) * sizeof *vc.bcopy);
    vc.glued = malloc((Q->nh ? Q->nh : 1) * sizeof *vc.glued);
    vc.lab = malloc((Q->nh ? Q->nh : 1) * sizeof *vc.lab);
    vc.tdeg = calloc(Q->nv ? Q->nv : 1, sizeof *vc.tdeg);
    vc.on_bnd = calloc(Q->nv ? Q->nv : 1, 1);
    vc.cbnd = calloc(C->nv ? C->nv : 1, 1);
    if (!vc.angle || !vc.pangle || !vc.copies || !vc.asum || !vc.bcopy || !vc.glued || !vc.lab ||
        !vc.tdeg || !vc.on_bnd || !vc.cbnd) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }

    /* counts: faces kept, one new vertex and two boundary edges per tree
     * edge (Euler characteristic 1 is checked by validate) */
    if (C->nf != Q->nf) FAIL("omega: %u faces, Q has %u", C->nf, Q->nf);
    if (C->nv != Q->nv + T->nedges)
        FAIL("omega: %u vertices, expected %u + %u tree edges", C->nv, Q->nv, T->nedges);
    if (C->nbnd != Q->nbnd + 2 * T->nedges)
        FAIL("omega: %u boundary edges, expected %u + 2 x %u", C->nbnd, Q->nbnd, T->nedges);

    (void)((st = check_face_copies(&vc, err)) || (st = mark_tree_and_sides(&vc, err)) ||
           (st = check_root_labels(&vc, err)) || (st = check_boundary_copies(&vc, err)) ||
           (st = check_layout(&vc, err)) || (st = check_transitions(&vc, err)) ||
           (st = check_angles(&vc, err)));
done:
    free(vc.angle);
    free(vc.pangle);
    free(vc.copies);
    free(vc.asum);
    free(vc.bcopy);
    free(vc.glued);
    free(vc.lab);
    free(vc.tdeg);
    free(vc.on_bnd);
    free(vc.cbnd);
    free(vc.side_a);
    free(vc.side_b);
    return st;
}
