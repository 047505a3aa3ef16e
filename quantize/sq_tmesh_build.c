/* seamquad: assembling the T-mesh from the traces (docs/tmesh.md).
 *
 * The traces (sq_tmesh_trace.c) are split at their nodes into arcs: at the
 * cone they start from, at the vertices that are nodes, at the marks that
 * T-junctions and stops left on them, and at their end. Where two traces met
 * head-on, the meeting point joins exactly two arcs along one line: it is no
 * node, and the two arcs become one. Each arc end gets its slot: the ray of
 * the vertex it leaves by (counted around the vertex across seams) or its
 * direction in the node's chart. The faces are then the orbits of the darts
 * (arcs with a direction) under "arrive at a node, leave by the next arc
 * clockwise": the face lies on the left. The turn at a node counts the
 * quarter turns between the two slots: 1 at a corner, 2 along a side. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_tmesh_internal.h"

/* a node position on a trace: the start of piece 0 (kind 0), inside piece k
 * at s (kind 1), or the end of piece k (kind 2) */
typedef struct tpos {
    uint32_t k;
    uint8_t kind;
    double s;
    uint32_t node;
} tpos;

typedef struct rarc {
    uint32_t trace;
    tpos a, b;
    uint32_t node[2], slot[2];
    uint32_t piece_off, piece_count;
    double length, length3d;
    double tau_a;              /* tau at a */
    double end_ss, end_b;      /* tau at b = end_ss + end_b: sigma s (the  */
                               /* end's coordinate along the line, signed) */
                               /* and the piece's offset, kept apart       */
} rarc;

typedef struct builder {
    const sq_map *M;
    tm_traces *T;
    uint32_t *tp_off, *tp;     /* pieces of each trace, in order */
    sq_error *err;
} builder;

static int tpos_cmp(const tpos *x, const tpos *y, int sigma)
{
    if (x->k != y->k) return x->k < y->k ? -1 : 1;
    if (x->kind != y->kind) return x->kind < y->kind ? -1 : 1;
    if (x->kind == 1 && x->s != y->s) return sigma * (x->s < y->s ? -1 : 1);
    return 0;
}

static const tm_piece *piece_of(const builder *B, uint32_t t, uint32_t k)
{
    return &B->T->pieces[B->tp[B->tp_off[t] + k]];
}

/* The coordinate along the line of piece P of node n's point. */
static double node_s(const builder *B, uint32_t n, const tm_piece *P, int *exact)
{
    const sq_map *M = B->M;
    const tm_node *N = &B->T->nodes[n];
    int r = tm_rc(P->dir);
    *exact = N->exact;
    if (N->kind == SQ_TMESH_AT_VERTEX) {
        uint32_t h = sq_tmesh_corner(M, P->face, N->id);
        return h == TM_NONE ? NAN : tm_uv(M, h)[r];
    }
    if (N->kind == SQ_TMESH_IN_FACE || M->mesh.he_face[N->id] == P->face) return N->uv[r];
    double q[2];
    if (!sq_tmesh_transform(M, N->id, N->uv, q)) {
        *exact = 0;
        sq_map_rotate(M->he_rot[N->id], N->uv, q);
        q[0] += M->he_t[2 * (size_t)N->id], q[1] += M->he_t[2 * (size_t)N->id + 1];
    }
    return q[r];
}

/* tau (parametric distance from the trace's cone) at a position, as
 * sigma s (*ss) plus the piece's offset (*b) */
static void tau_parts(const builder *B, uint32_t t, const tpos *p, double *ss, double *b)
{
    *ss = 0, *b = 0;
    if (p->kind == 0) return;
    const tm_piece *P = piece_of(B, t, p->k);
    *b = P->b;
    if (p->kind == 1) {
        *ss = tm_sigma(P->dir) * p->s;
        return;
    }
    int ex;
    double s = node_s(B, p->node, P, &ex);
    if (!ex && P->s1_exact) s = P->s1;
    *ss = tm_sigma(P->dir) * s;
}

static double tau_at(const builder *B, uint32_t t, const tpos *p)
{
    double ss, b;
    tau_parts(B, t, p, &ss, &b);
    return ss + b;
}

static void piece_point(const sq_map *M, const sq_tmesh_piece *P, const sq_tmesh_end *e, double out[3])
{
    const sq_mesh *m = &M->mesh;
    if (e->kind == SQ_TMESH_AT_VERTEX) {
        memcpy(out, m->pos + 3 * (size_t)e->id, 3 * sizeof *out);
        return;
    }
    double X[2];
    X[tm_rc(P->dir)] = e->s, X[tm_cc(P->dir)] = P->c;
    uint32_t h = m->f_he[P->face], hs[3] = {h, tm_next(M, h), tm_prev(M, h)};
    const double *a = tm_uv(M, hs[0]), *b = tm_uv(M, hs[1]), *c = tm_uv(M, hs[2]);
    double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    double l1 = ((X[0] - a[0]) * (c[1] - a[1]) - (X[1] - a[1]) * (c[0] - a[0])) / det;
    double l2 = ((b[0] - a[0]) * (X[1] - a[1]) - (b[1] - a[1]) * (X[0] - a[0])) / det;
    double l0 = 1 - l1 - l2;
    for (int i = 0; i < 3; i++)
        out[i] = l0 * m->pos[3 * (size_t)m->he_vert[hs[0]] + i] + l1 * m->pos[3 * (size_t)m->he_vert[hs[1]] + i] +
                 l2 * m->pos[3 * (size_t)m->he_vert[hs[2]] + i];
}

/* The public end of piece P at its start (end = 0) or end (end = 1), cut at
 * position p when p lies inside it or is a node at its end. */
static sq_tmesh_end piece_end(const builder *B, const tm_piece *P, int end, const tpos *p)
{
    sq_tmesh_end e;
    memset(&e, 0, sizeof e);
    if (p && p->kind == 1) {
        e.kind = P->he != TM_NONE ? SQ_TMESH_ON_EDGE : SQ_TMESH_IN_FACE;
        e.id = P->he != TM_NONE ? P->he : P->face;
        e.exact = 1, e.s = p->s;
        return e;
    }
    int kind = end ? P->end_kind : P->start_kind;
    uint32_t id = end ? P->end_id : P->start_id;
    e.s = end ? P->s1 : P->s0;
    e.exact = end ? P->s1_exact : kind == TM_END_VERTEX;
    if (kind == TM_END_VERTEX) {
        e.kind = SQ_TMESH_AT_VERTEX, e.id = id, e.exact = 1;
    } else if (kind == TM_END_EDGE) {
        e.kind = SQ_TMESH_ON_EDGE, e.id = id;
    } else {
        e.kind = P->he != TM_NONE ? SQ_TMESH_ON_EDGE : SQ_TMESH_IN_FACE;
        e.id = P->he != TM_NONE ? P->he : P->face;
    }
    if (p && p->node != TM_NONE && e.kind != SQ_TMESH_AT_VERTEX && !e.exact) {
        int ex;
        double s = node_s(B, p->node, P, &ex);
        if (ex) e.s = s, e.exact = 1;
    }
    return e;
}

/* The slot by which a piece (face f, moving in direction d) leaves node n. */
static int slot_of(const sq_map *M, const tm_node *N, uint32_t f, int d, uint32_t *slot)
{
    if (N->kind == SQ_TMESH_AT_VERTEX) {
        uint32_t h = sq_tmesh_corner(M, f, N->id);
        int r = h == TM_NONE ? -1 : sq_tmesh_find_ray(M, h, d);
        if (r < 0) return 0;
        *slot = (uint32_t)r;
        return 1;
    }
    if (N->kind == SQ_TMESH_IN_FACE) {
        if (f != N->id) return 0;
        *slot = (uint32_t)d;
        return 1;
    }
    uint32_t h = N->id, th = M->mesh.he_twin[h];
    if (M->mesh.he_face[h] == f) *slot = (uint32_t)d;
    else if (M->mesh.he_face[th] == f) *slot = (uint32_t)((d + M->he_rot[th]) & 3);
    else return 0;
    return 1;
}

static int node_valence(const sq_map *M, const tm_node *N)
{
    return N->kind == SQ_TMESH_AT_VERTEX ? M->valence[N->id] : 4;
}

/* The left-hand mesh face and direction of the first piece of a dart. */
static void dart_chart(const sq_map *M, const sq_tmesh *T, uint32_t dart, uint32_t *face, int *dir)
{
    const sq_tmesh_arc *a = &T->arcs[dart >> 1];
    const sq_tmesh_piece *P = &T->pieces[(dart & 1) ? a->piece_off + a->piece_count - 1 : a->piece_off];
    int d = (dart & 1) ? (P->dir + 2) & 3 : P->dir;
    *face = P->face, *dir = d;
    if (P->he == TM_NONE) return;
    /* along an edge: the face on the left of the motion */
    const double *p = tm_uv(M, P->he), *q = tm_uv(M, tm_next(M, P->he));
    int r = tm_rc(d);
    int along = (q[r] - p[r]) * tm_sigma(d) > 0;
    if (!along) {
        *face = M->mesh.he_face[M->mesh.he_twin[P->he]];
        *dir = (d + M->he_rot[P->he]) & 3;
    }
}

sq_status sq_tmesh_build(const sq_map *M, sq_tmesh *out, sq_tmesh_stats *stats, sq_error *err)
{
    double t0 = sq_now();
    const sq_mesh *m = &M->mesh;
    memset(out, 0, sizeof *out);
    if (stats) memset(stats, 0, sizeof *stats);
    tm_traces T;
    sq_status st = sq_tmesh_trace(M, &T, err);
    if (st != SQ_OK) return st;

    builder B = {M, &T, NULL, NULL, err};
    tpos *pos = NULL;
    rarc *ra = NULL;
    sq_tmesh_piece *rp = NULL;
    uint32_t n_ra = 0, cap_ra = 0, n_rp = 0, cap_rp = 0, n_pos = 0, cap_pos = 0;
    uint32_t *inc_off = NULL, *inc = NULL, *keep = NULL, *newid = NULL, *slot_off = NULL, *slot_dart = NULL;
    uint32_t *dnext = NULL, *dturn = NULL, *orbit = NULL;
    uint8_t *used = NULL;
    sq_tmesh *R = out;
    uint32_t cap_pieces = 0;

    /* pieces of each trace in order (appended in order of k per trace) */
    B.tp_off = calloc((size_t)T.n_traces + 1, sizeof *B.tp_off);
    B.tp = malloc(((size_t)T.n_pieces + 1) * sizeof *B.tp);
    if (!B.tp_off || !B.tp) goto nomem;
    for (uint32_t i = 0; i < T.n_pieces; i++) B.tp_off[T.pieces[i].trace + 1]++;
    for (uint32_t t = 0; t < T.n_traces; t++) B.tp_off[t + 1] += B.tp_off[t];
    for (uint32_t i = 0; i < T.n_pieces; i++) {
        const tm_piece *P = &T.pieces[i];
        B.tp[B.tp_off[P->trace] + P->k] = i;
    }

    /* split every trace at its nodes into raw arcs */
    for (uint32_t t = 0; t < T.n_traces; t++) {
        const tm_trace *tt = &T.traces[t];
        if (tt->n == 0) continue;
        n_pos = 0;
        if (!grow((void **)&pos, &cap_pos, tt->n + 2, sizeof *pos)) goto nomem;
        pos[n_pos++] = (tpos){0, 0, 0, T.vnode[tt->cone]};
        for (uint32_t k = 0; k < tt->n; k++) {
            const tm_piece *P = piece_of(&B, t, k);
            if (P->end_kind == TM_END_VERTEX && T.vnode[P->end_id] != TM_NONE) {
                if (!grow((void **)&pos, &cap_pos, n_pos + 1, sizeof *pos)) goto nomem;
                pos[n_pos++] = (tpos){k, 2, 0, T.vnode[P->end_id]};
            }
        }
        for (uint32_t i = 0; i < T.n_marks; i++) {
            const tm_mark *mk = &T.marks[i];
            if (mk->trace != t) continue;
            if (!grow((void **)&pos, &cap_pos, n_pos + 1, sizeof *pos)) goto nomem;
            pos[n_pos++] = (tpos){mk->k, mk->at_end ? 2 : 1, mk->s, mk->node};
        }
        if (!grow((void **)&pos, &cap_pos, n_pos + 1, sizeof *pos)) goto nomem;
        pos[n_pos++] = (tpos){tt->n - 1, 2, 0, tt->end_node};
        /* sort (insertion: few per trace), one node per position */
        for (uint32_t i = 1; i < n_pos; i++) {
            tpos x = pos[i];
            int sg = tm_sigma(piece_of(&B, t, x.k)->dir);
            uint32_t j = i;
            while (j > 0 && tpos_cmp(&pos[j - 1], &x, sg) > 0) pos[j] = pos[j - 1], j--;
            pos[j] = x;
        }
        uint32_t w = 0;
        for (uint32_t i = 0; i < n_pos; i++) {
            if (w > 0 && tpos_cmp(&pos[w - 1], &pos[i], tm_sigma(piece_of(&B, t, pos[i].k)->dir)) == 0) {
                if (pos[w - 1].node != pos[i].node) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: two nodes (%u, %u) at one point of trace %u",
                                      pos[w - 1].node, pos[i].node, t);
                    goto fail;
                }
                continue;
            }
            pos[w++] = pos[i];
        }
        n_pos = w;
        for (uint32_t i = 0; i + 1 < n_pos; i++) {
            if (!grow((void **)&ra, &cap_ra, n_ra + 1, sizeof *ra)) goto nomem;
            rarc *A = &ra[n_ra++];
            memset(A, 0, sizeof *A);
            A->trace = t, A->a = pos[i], A->b = pos[i + 1];
            A->node[0] = pos[i].node, A->node[1] = pos[i + 1].node;
            A->piece_off = n_rp;
            uint32_t k0 = pos[i].kind == 2 ? pos[i].k + 1 : pos[i].k, k1 = pos[i + 1].k;
            for (uint32_t k = k0; k <= k1; k++) {
                const tm_piece *P = piece_of(&B, t, k);
                if (!grow((void **)&rp, &cap_rp, n_rp + 1, sizeof *rp)) goto nomem;
                sq_tmesh_piece *o = &rp[n_rp++];
                o->face = P->face, o->he = P->he, o->dir = P->dir, o->c = P->c;
                const tpos *pa = k == k0 && pos[i].kind != 0 ? &pos[i] : NULL;
                const tpos *pb = k == k1 ? &pos[i + 1] : NULL;
                o->from = piece_end(&B, P, 0, pa);
                o->to = piece_end(&B, P, 1, pb);
                double x0[3], x1[3];
                piece_point(M, o, &o->from, x0);
                piece_point(M, o, &o->to, x1);
                A->length3d += sqrt((x1[0] - x0[0]) * (x1[0] - x0[0]) + (x1[1] - x0[1]) * (x1[1] - x0[1]) +
                                    (x1[2] - x0[2]) * (x1[2] - x0[2]));
            }
            A->piece_count = n_rp - A->piece_off;
            A->tau_a = tau_at(&B, t, &pos[i]);
            tau_parts(&B, t, &pos[i + 1], &A->end_ss, &A->end_b);
            A->length = (A->end_ss + A->end_b) - A->tau_a;
            const tm_node *N0 = &T.nodes[A->node[0]], *N1 = &T.nodes[A->node[1]];
            const sq_tmesh_piece *f0 = &rp[A->piece_off], *f1 = &rp[n_rp - 1];
            if (A->piece_count == 0 || !slot_of(M, N0, f0->face, f0->dir, &A->slot[0]) ||
                !slot_of(M, N1, f1->face, (f1->dir + 2) & 3, &A->slot[1])) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: an arc of trace %u (from cone %u) leaves node %u or "
                                  "%u by no axis direction", t, tt->cone, A->node[0], A->node[1]);
                goto fail;
            }
        }
    }

    /* arcs at each node; a node joining two arcs along one line (a head-on
     * meeting) is no node */
    inc_off = calloc((size_t)T.n_nodes + 1, sizeof *inc_off);
    inc = malloc(((size_t)2 * n_ra + 1) * sizeof *inc);
    keep = malloc(((size_t)T.n_nodes + 1) * sizeof *keep);
    newid = malloc(((size_t)T.n_nodes + 1) * sizeof *newid);
    used = calloc((size_t)n_ra + 1, 1);
    if (!inc_off || !inc || !keep || !newid || !used) goto nomem;
    for (uint32_t i = 0; i < n_ra; i++) inc_off[ra[i].node[0] + 1]++, inc_off[ra[i].node[1] + 1]++;
    for (uint32_t n = 0; n < T.n_nodes; n++) inc_off[n + 1] += inc_off[n];
    {
        uint32_t *fill = calloc((size_t)T.n_nodes + 1, sizeof *fill);
        if (!fill) goto nomem;
        for (uint32_t i = 0; i < n_ra; i++)
            for (int e = 0; e < 2; e++) {
                uint32_t n = ra[i].node[e];
                inc[inc_off[n] + fill[n]++] = 2 * i + (uint32_t)e;
            }
        free(fill);
    }
    uint32_t n_nodes = 0;
    for (uint32_t n = 0; n < T.n_nodes; n++) {
        uint32_t deg = inc_off[n + 1] - inc_off[n];
        keep[n] = 1;
        if (deg == 2 && node_valence(M, &T.nodes[n]) == 4) {
            uint32_t e0 = inc[inc_off[n]], e1 = inc[inc_off[n] + 1];
            uint32_t s0 = ra[e0 >> 1].slot[e0 & 1], s1 = ra[e1 >> 1].slot[e1 & 1];
            if (((s0 - s1) & 3) == 2) keep[n] = 0;
        }
        if (deg == 0) keep[n] = 0;
        newid[n] = keep[n] ? n_nodes++ : TM_NONE;
    }
    R->nodes = calloc((size_t)n_nodes + 1, sizeof *R->nodes);
    if (!R->nodes) goto nomem;
    R->n_nodes = n_nodes;
    for (uint32_t n = 0; n < T.n_nodes; n++) {
        if (!keep[n]) continue;
        sq_tmesh_node *o = &R->nodes[newid[n]];
        const tm_node *N = &T.nodes[n];
        o->kind = N->kind, o->exact = N->exact, o->id = N->id, o->uv[0] = N->uv[0], o->uv[1] = N->uv[1];
        o->valence = node_valence(M, N);
        o->degree = inc_off[n + 1] - inc_off[n];
    }

    /* arcs: chains of raw arcs through the dropped nodes */
    uint32_t cap_arcs = 0;
    for (uint32_t i = 0; i < n_ra; i++)
        for (int e = 0; e < 2; e++) {
            if (used[i] || !keep[ra[i].node[e]]) continue;
            if (!grow((void **)&R->arcs, &cap_arcs, R->n_arcs + 1, sizeof *R->arcs)) goto nomem;
            sq_tmesh_arc *A = &R->arcs[R->n_arcs++];
            memset(A, 0, sizeof *A);
            A->node[0] = newid[ra[i].node[e]], A->slot[0] = ra[i].slot[e];
            A->piece_off = R->n_pieces;
            uint32_t r = i;
            int from = e;
            for (;;) {
                used[r] = 1;
                const rarc *X = &ra[r];
                if (!grow((void **)&R->pieces, &cap_pieces, R->n_pieces + X->piece_count, sizeof *R->pieces))
                    goto nomem;
                for (uint32_t j = 0; j < X->piece_count; j++) {
                    sq_tmesh_piece p = rp[X->piece_off + (from ? X->piece_count - 1 - j : j)];
                    if (from) {
                        sq_tmesh_end x = p.from;
                        p.from = p.to, p.to = x, p.dir = (uint8_t)((p.dir + 2) & 3);
                    }
                    R->pieces[R->n_pieces++] = p;
                }
                A->length += X->length, A->length3d += X->length3d;
                uint32_t far = X->node[1 - from];
                if (keep[far]) {
                    A->node[1] = newid[far], A->slot[1] = X->slot[1 - from];
                    break;
                }
                uint32_t me = 2 * r + (uint32_t)(1 - from), e0 = inc[inc_off[far]], e1 = inc[inc_off[far] + 1];
                uint32_t other = e0 == me ? e1 : e0;
                if (from == 0 && (other & 1) == 1) {
                    /* a head-on meeting: the two traces' tau there sum to
                     * an exact value (the node's, where its point is
                     * rounded; else sigma s + sigma' s' of one point in two
                     * charts, exact where the charts agree exactly, plus
                     * the offsets), where adding the two lengths rounds */
                    const rarc *Y = &ra[other >> 1];
                    const double sum = T.nodes[far].has_sum ? T.nodes[far].sum
                                                            : (X->end_ss + Y->end_ss) + (X->end_b + Y->end_b);
                    A->length += (sum - X->tau_a - Y->tau_a) - X->length - Y->length;
                }
                r = other >> 1, from = (int)(other & 1);
                if (used[r]) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: a trace closes on itself without a node");
                    goto fail;
                }
            }
            A->piece_count = R->n_pieces - A->piece_off;
        }
    for (uint32_t i = 0; i < n_ra; i++)
        if (!used[i]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "tmesh: the trace from cone %u closes into a loop through no node (its meetings are all "
                              "head-on)",
                              T.traces[ra[i].trace].cone);
            goto fail;
        }

    /* faces: orbits of the darts, turning clockwise at each node */
    slot_off = calloc((size_t)R->n_nodes + 1, sizeof *slot_off);
    if (!slot_off) goto nomem;
    for (uint32_t n = 0; n < R->n_nodes; n++) slot_off[n + 1] = slot_off[n] + (uint32_t)R->nodes[n].valence;
    slot_dart = malloc(((size_t)slot_off[R->n_nodes] + 1) * sizeof *slot_dart);
    dnext = malloc(((size_t)2 * R->n_arcs + 1) * sizeof *dnext);
    dturn = malloc(((size_t)2 * R->n_arcs + 1) * sizeof *dturn);
    orbit = malloc(((size_t)2 * R->n_arcs + 1) * sizeof *orbit);
    if (!slot_dart || !dnext || !dturn || !orbit) goto nomem;
    memset(slot_dart, 0xff, ((size_t)slot_off[R->n_nodes] + 1) * sizeof *slot_dart);
    for (uint32_t a = 0; a < R->n_arcs; a++)
        for (int e = 0; e < 2; e++) {
            const sq_tmesh_arc *A = &R->arcs[a];
            uint32_t n = A->node[e];
            if (A->slot[e] >= (uint32_t)R->nodes[n].valence || slot_dart[slot_off[n] + A->slot[e]] != TM_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: two arcs leave node %u (%s %u) by slot %u", n,
                                  R->nodes[n].kind == SQ_TMESH_AT_VERTEX ? "vertex" : "at mesh element",
                                  R->nodes[n].id, A->slot[e]);
                goto fail;
            }
            slot_dart[slot_off[n] + A->slot[e]] = 2 * a + (uint32_t)e;
        }
    for (uint32_t d = 0; d < 2 * R->n_arcs; d++) {
        const sq_tmesh_arc *A = &R->arcs[d >> 1];
        uint32_t n = A->node[(d & 1) ^ 1], s_in = A->slot[(d & 1) ^ 1], k = (uint32_t)R->nodes[n].valence;
        for (uint32_t i = 1; i <= k; i++) {
            uint32_t x = slot_dart[slot_off[n] + (s_in + k - i) % k];
            if (x != TM_NONE) {
                dnext[d] = x, dturn[d] = i;
                break;
            }
        }
    }
    free(used);
    used = calloc((size_t)2 * R->n_arcs + 1, 1);
    /* every dart lies on one side of one face: at most 2 n_arcs of each */
    size_t nd = (size_t)2 * R->n_arcs + 1;
    R->side_arc = malloc(nd * sizeof *R->side_arc);
    R->side_rev = malloc(nd);
    R->side_off = malloc((4 * nd + 1) * sizeof *R->side_off);
    R->width = malloc(nd * sizeof *R->width);
    R->height = malloc(nd * sizeof *R->height);
    if (!used || !R->side_arc || !R->side_rev || !R->side_off || !R->width || !R->height) goto nomem;
    R->side_off[0] = 0;
    for (uint32_t d0 = 0; d0 < 2 * R->n_arcs; d0++) {
        if (used[d0]) continue;
        uint32_t len = 0, corners = 0, bad = TM_NONE;
        for (uint32_t d = d0; !used[d]; d = dnext[d]) {
            used[d] = 1, orbit[len++] = d;
            if (dturn[d] == 1) corners++;
            else if (dturn[d] != 2) bad = d;
        }
        uint32_t f = R->n_faces;
        if (bad != TM_NONE || corners != 4) {
            const sq_tmesh_arc *A = &R->arcs[orbit[0] >> 1];
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "tmesh: face %u (through node %u) is no rectangle: %u convex corners%s (turn of %u "
                              "quarters)",
                              f, A->node[0], corners, bad != TM_NONE ? " and a reflex or cusp corner" : "",
                              bad != TM_NONE ? dturn[bad] : 0);
            goto fail;
        }
        /* dart i starts a side iff the previous dart ends at a corner */
        uint32_t start[4], ns = 0;
        for (uint32_t i = 0; i < len; i++)
            if (dturn[orbit[(i + len - 1) % len]] == 1) start[ns++] = i;
        int bottom = 0;
        for (int s = 0; s < 4; s++) {
            uint32_t fc;
            int dir;
            dart_chart(M, R, orbit[start[s]], &fc, &dir);
            if (dir == 0) {
                bottom = s;
                break;
            }
        }
        uint32_t w = R->side_off[4 * f];
        double side_len[4];
        for (int s = 0; s < 4; s++) {
            int ss = (bottom + s) % 4;
            uint32_t i0 = start[ss], i1 = start[(ss + 1) % 4];
            side_len[s] = 0;
            for (uint32_t i = i0; i != i1; i = (i + 1) % len) {
                R->side_arc[w] = orbit[i] >> 1, R->side_rev[w] = (uint8_t)(orbit[i] & 1), w++;
                side_len[s] += R->arcs[orbit[i] >> 1].length;
            }
            R->side_off[4 * f + (uint32_t)s + 1] = w;
        }
        R->width[f] = 0.5 * (side_len[0] + side_len[2]);
        R->height[f] = 0.5 * (side_len[1] + side_len[3]);
        R->n_faces++;
    }

    /* UV area */
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        const double *a = tm_uv(M, h), *b = tm_uv(M, tm_next(M, h)), *c = tm_uv(M, tm_prev(M, h));
        R->uv_area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }

    sq_tmesh_stats vs;
    st = sq_tmesh_verify(M, R, &vs, err);
    if (st != SQ_OK) goto fail;
    if (stats) {
        *stats = vs;
        stats->cones = T.cones, stats->traces = T.n_traces, stats->empty_traces = T.empty_traces;
        stats->steps = T.n_pieces, stats->vertex_passes = T.vertex_passes, stats->edge_pieces = T.edge_pieces;
        stats->t_junctions = T.t_junctions, stats->meets = T.meets, stats->overtaken = T.overtaken;
        stats->nodes = R->n_nodes, stats->arcs = R->n_arcs, stats->faces = R->n_faces;
        stats->seconds = sq_now() - t0;
    }
    goto done;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "tmesh: out of memory");
fail:
    sq_tmesh_free(R);
done:
    free(B.tp_off), free(B.tp), free(pos), free(ra), free(rp), free(inc_off), free(inc), free(keep), free(newid);
    free(slot_off), free(slot_dart), free(dnext), free(dturn), free(orbit), free(used);
    sq_tmesh_traces_free(&T);
    return st;
}

void sq_tmesh_free(sq_tmesh *T)
{
    if (!T) return;
    free(T->nodes), free(T->arcs), free(T->pieces), free(T->side_off), free(T->side_arc), free(T->side_rev);
    free(T->width), free(T->height);
    memset(T, 0, sizeof *T);
}
