/* seamquad: tracing the cone separatrices of an exact seamless map, all
 * together in order of parametric distance (the motorcycle graph of
 * Quantized Global Parametrization; docs/tmesh.md).
 *
 * A trace is always in one of two states:
 *  - at a vertex, about to leave it along one of its axis rays (the rays
 *    are the axis directions of the corners' charts, counted around the
 *    vertex across seams: valence[v] of them);
 *  - on the inside of an edge, about to enter a face with the line
 *    u = c or v = c (exact c) of that face's chart.
 * One step adds one piece: the chord of the line through the face (from an
 * edge or from a vertex to an edge or to the opposite vertex) or a whole
 * mesh edge when the ray runs along it. Which edge or vertex the chord
 * leaves by is decided by comparing the corners' coordinates with c; at a
 * regular vertex the trace continues along the opposite ray (two quarter
 * turns further around), at a cone it stops.
 *
 * Before a piece is added it is tested against the pieces already in its
 * face (a piece along an edge: in both faces): perpendicular pieces meet at
 * the exact point (c1, c2), located in the triangle by sq_orient2d; pieces
 * on the same line in opposite directions meet head-on. The trace stops at
 * the first meeting along the piece; a head-on meeting with the front of a
 * moving trace stops both (one arc). Meetings at mesh vertices are decided
 * by the vertex's ray occupancy instead: a trace that arrives at a vertex
 * some trace already passed or reached stops there. A meeting is ignored
 * where the other piece ends at the point and its trace stopped there on a
 * cone or a trace (that trace, met at the same point, decides), or is still
 * moving and reached the point no earlier (it will stop on this one when
 * it moves on).
 *
 * The traces move in order of their parametric distance (tau), one piece at
 * a time. Where the new piece crosses, inside a face, the last piece of a
 * moving trace that reached the crossing later than the new piece's trace
 * does (larger tau there), and nothing has been attached to that piece yet,
 * the other trace is cut back to the crossing and stops on the new piece:
 * the trace that arrived first survives; at a moving trace's front the
 * smaller tau wins too (above). Elsewhere (crossings at vertices, pieces
 * that carry nodes) the trace that drew its piece first survives, which
 * differs from the first arrival by less than one piece.
 * A map without cones (a flat torus) gets the four rays of vertex 0. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_predicates.h"
#include "sq_tmesh_internal.h"

static int cmpd(double a, double b) { return (a > b) - (a < b); }

/* sign of cross(a - p, w_d), w_d the unit vector of direction d, from exact
 * comparisons only */
static int cross_aw(const double *p, const double *a, int d)
{
    switch (d & 3) {
    case 0: return cmpd(p[1], a[1]);
    case 1: return cmpd(a[0], p[0]);
    case 2: return cmpd(a[1], p[1]);
    default: return cmpd(p[0], a[0]);
    }
}

int sq_tmesh_vertex_rays(const sq_map *M, uint32_t v, tm_ray *rays, int max)
{
    const sq_mesh *m = &M->mesh;
    uint32_t h0 = m->v_he[v], h = h0, guard = 0;
    int n = 0;
    do {
        const double *p = tm_uv(M, h), *a = tm_uv(M, tm_next(M, h)), *b = tm_uv(M, tm_prev(M, h));
        int in[4];
        /* half-open corner [a, b): d is counted in the corner whose first
         * edge it runs along */
        for (int d = 0; d < 4; d++) in[d] = cross_aw(p, a, d) >= 0 && cross_aw(p, b, d) < 0;
        for (int d = 0; d < 4; d++) {
            if (!in[d] || in[(d + 3) & 3]) continue;
            for (int e = d; e < d + 4 && in[e & 3]; e++) {
                if (n >= max) return -1;
                rays[n].h = h, rays[n].dir = (uint8_t)(e & 3);
                rays[n].on_edge = cross_aw(p, a, e & 3) == 0;
                n++;
            }
            break;
        }
        h = m->he_twin[tm_prev(M, h)];
        if (++guard > m->nh) return -1;
    } while (h != h0);
    return n;
}

int sq_tmesh_find_ray(const sq_map *M, uint32_t h, int d)
{
    const sq_mesh *m = &M->mesh;
    const double *p = tm_uv(M, h), *a = tm_uv(M, tm_next(M, h)), *b = tm_uv(M, tm_prev(M, h));
    uint32_t th;
    int td;
    if (cross_aw(p, a, d) >= 0 && cross_aw(p, b, d) < 0) {
        th = h, td = d & 3;
    } else if (cross_aw(p, b, d) == 0 && cross_aw(p, a, d) > 0) {
        /* along the corner's second edge: the ray of the next corner */
        uint32_t pv = tm_prev(M, h);
        th = m->he_twin[pv], td = (d + M->he_rot[pv]) & 3;
    } else {
        return -1;
    }
    tm_ray rays[TM_MAX_RAYS];
    int n = sq_tmesh_vertex_rays(M, m->he_vert[h], rays, TM_MAX_RAYS);
    for (int i = 0; i < n; i++)
        if (rays[i].h == th && rays[i].dir == td) return i;
    return -1;
}

uint32_t sq_tmesh_corner(const sq_map *M, uint32_t f, uint32_t v)
{
    uint32_t h = M->mesh.f_he[f];
    for (int i = 0; i < 3; i++, h = tm_next(M, h))
        if (M->mesh.he_vert[h] == v) return h;
    return TM_NONE;
}

static void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

int sq_tmesh_transform(const sq_map *M, uint32_t h, const double p[2], double out[2])
{
    double q[2], s, e;
    sq_map_rotate(M->he_rot[h], p, q);
    const double *t = M->he_t + 2 * (size_t)h;
    for (int i = 0; i < 2; i++) {
        two_sum(q[i], t[i], &s, &e);
        if (e != 0) return 0;
        out[i] = s;
    }
    return 1;
}

/* ---- the tracer ----------------------------------------------------------- */

typedef struct tr_front {
    uint32_t v, ray;   /* at a vertex: leave along ray `ray` of v          */
    uint32_t e;        /* at an edge: enter he_face[e] through e ...       */
    uint8_t d;         /* ... in direction d on the line c of its chart    */
    double c, b;       /* b: tau = sigma s + b in that chart               */
    double vb, vs;     /* at a vertex: b and sigma s of the arrival piece   */
} tr_front;

typedef struct tr_occ {
    uint32_t next, trace, ray;
    uint8_t arrive;
} tr_occ;

typedef struct tr_rec {
    uint32_t piece, next;
} tr_rec;

typedef struct tracer {
    const sq_map *M;
    tm_traces *T;
    tr_front *front;
    uint32_t *face_head, n_rec, cap_rec;
    tr_rec *rec;
    uint32_t *vocc_head, n_occ, cap_occ;
    tr_occ *occ;
    uint32_t *heap, n_heap;
    struct win *wins;       /* crossings the new piece wins (see step) */
    uint32_t n_wins, cap_wins;
    sq_error *err;
    sq_status st;
} tracer;

static sq_status fail(tracer *tr, sq_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static sq_status fail(tracer *tr, sq_status code, const char *fmt, ...)
{
    if (tr->st != SQ_OK) return tr->st;
    char buf[SQ_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    tr->st = code;
    return sq_error_set(tr->err, code, "tmesh: %s", buf);
}

static sq_status nomem(tracer *tr) { return fail(tr, SQ_ERR_NOMEM, "out of memory while tracing"); }

/* heap of active traces by tau (ties: trace index) */
static int heap_less(const tracer *tr, uint32_t a, uint32_t b)
{
    double ta = tr->T->traces[a].tau, tb = tr->T->traces[b].tau;
    return ta < tb || (ta == tb && a < b);
}

static void heap_push(tracer *tr, uint32_t t)
{
    uint32_t i = tr->n_heap++;
    tr->heap[i] = t;
    while (i > 0) {
        uint32_t p = (i - 1) / 2;
        if (!heap_less(tr, tr->heap[i], tr->heap[p])) break;
        uint32_t x = tr->heap[i];
        tr->heap[i] = tr->heap[p], tr->heap[p] = x, i = p;
    }
}

static uint32_t heap_pop(tracer *tr)
{
    uint32_t top = tr->heap[0], i = 0;
    tr->heap[0] = tr->heap[--tr->n_heap];
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, s = i;
        if (l < tr->n_heap && heap_less(tr, tr->heap[l], tr->heap[s])) s = l;
        if (r < tr->n_heap && heap_less(tr, tr->heap[r], tr->heap[s])) s = r;
        if (s == i) break;
        uint32_t x = tr->heap[i];
        tr->heap[i] = tr->heap[s], tr->heap[s] = x, i = s;
    }
    return top;
}

static uint32_t new_node(tracer *tr, uint8_t kind, uint32_t id, const double uv[2], uint8_t exact)
{
    tm_traces *T = tr->T;
    if (!grow((void **)&T->nodes, &T->cap_nodes, T->n_nodes + 1, sizeof *T->nodes)) {
        nomem(tr);
        return TM_NONE;
    }
    tm_node *n = &T->nodes[T->n_nodes];
    n->kind = kind, n->id = id, n->uv[0] = uv[0], n->uv[1] = uv[1], n->exact = exact;
    n->has_sum = 0, n->sum = 0;
    return T->n_nodes++;
}

static uint32_t vertex_node(tracer *tr, uint32_t v)
{
    if (tr->T->vnode[v] == TM_NONE)
        tr->T->vnode[v] = new_node(tr, SQ_TMESH_AT_VERTEX, v, tm_uv(tr->M, tr->M->mesh.v_he[v]), 1);
    return tr->T->vnode[v];
}

static uint32_t find_mark(const tm_traces *T, uint32_t t, uint32_t k, int at_end, double s)
{
    for (uint32_t i = 0; i < T->n_marks; i++) {
        const tm_mark *m = &T->marks[i];
        if (m->trace == t && m->k == k && m->at_end == at_end && (at_end || m->s == s)) return m->node;
    }
    return TM_NONE;
}

static int add_mark(tracer *tr, uint32_t t, uint32_t k, int at_end, double s, uint32_t node)
{
    tm_traces *T = tr->T;
    if (find_mark(T, t, k, at_end, s) != TM_NONE) return 1;
    if (!grow((void **)&T->marks, &T->cap_marks, T->n_marks + 1, sizeof *T->marks)) {
        nomem(tr);
        return 0;
    }
    tm_mark *m = &T->marks[T->n_marks++];
    m->trace = t, m->k = k, m->at_end = (uint8_t)at_end, m->s = at_end ? 0 : s, m->node = node;
    return 1;
}

static int add_occ(tracer *tr, uint32_t v, uint32_t ray, uint32_t t, int arrive)
{
    if (!grow((void **)&tr->occ, &tr->cap_occ, tr->n_occ + 1, sizeof *tr->occ)) {
        nomem(tr);
        return 0;
    }
    tr_occ *o = &tr->occ[tr->n_occ];
    o->trace = t, o->ray = ray, o->arrive = (uint8_t)arrive, o->next = tr->vocc_head[v];
    tr->vocc_head[v] = tr->n_occ++;
    return 1;
}

static int add_record(tracer *tr, uint32_t f, uint32_t piece)
{
    if (!grow((void **)&tr->rec, &tr->cap_rec, tr->n_rec + 1, sizeof *tr->rec)) return 0;
    tr->rec[tr->n_rec].piece = piece;
    tr->rec[tr->n_rec].next = tr->face_head[f];
    tr->face_head[f] = tr->n_rec++;
    return 1;
}

/* The line (d, c) of he_face[h]'s chart in the chart across h. */
static int line_across(const sq_map *M, uint32_t h, int d, double c, int *d2, double *c2)
{
    double p[2], q[2];
    p[tm_cc(d)] = c, p[tm_rc(d)] = 0;
    if (!sq_tmesh_transform(M, h, p, q)) return 0;
    *d2 = (d + M->he_rot[h]) & 3;
    *c2 = q[tm_cc(*d2)];
    return 1;
}

/* Coordinate along the line (d, c) where it crosses edge x (rounded). */
static double edge_cross_s(const sq_map *M, uint32_t x, int d, double c)
{
    const double *p = tm_uv(M, x), *q = tm_uv(M, tm_next(M, x));
    int r = tm_rc(d), k = tm_cc(d);
    double s = p[r] + (c - p[k]) * (q[r] - p[r]) / (q[k] - p[k]);
    double lo = p[r] < q[r] ? p[r] : q[r], hi = p[r] < q[r] ? q[r] : p[r];
    return s < lo ? lo : s > hi ? hi : s;
}

enum { LOC_OUT, LOC_IN, LOC_EDGE, LOC_VERTEX };

static int locate(const sq_map *M, uint32_t f, const double X[2], uint32_t *edge)
{
    uint32_t h = M->mesh.f_he[f];
    int zeros = 0;
    for (int i = 0; i < 3; i++, h = tm_next(M, h)) {
        int o = sq_orient2d(tm_uv(M, h), tm_uv(M, tm_next(M, h)), X);
        if (o < 0) return LOC_OUT;
        if (o == 0) zeros++, *edge = h;
    }
    return zeros == 0 ? LOC_IN : zeros == 1 ? LOC_EDGE : LOC_VERTEX;
}

/* the view of piece Q in face F (F is Q's face or, along an edge, its twin's) */
static void view(const sq_map *M, const tm_piece *Q, uint32_t F, int *d, double *c)
{
    if (Q->face == F) {
        *d = Q->dir, *c = Q->c;
    } else {
        *d = (Q->dir + M->he_rot[Q->he]) & 3, *c = Q->c2;
    }
}

/* X (in F's chart) in the chart of piece Q's own face */
static int to_piece_chart(const sq_map *M, const tm_piece *Q, uint32_t F, const double X[2], double out[2])
{
    if (Q->face == F) {
        out[0] = X[0], out[1] = X[1];
        return 1;
    }
    return sq_tmesh_transform(M, M->mesh.he_twin[Q->he], X, out);
}

/* Where X (on Q's line, in the closed triangle F, not at a vertex) lies on
 * the stored piece Q: -1 beyond its end, 0 its start, 1 inside (*qs), 2 its
 * end. */
static int pos_on_piece(const tm_piece *Q, const double Xq[2], int loc, uint32_t x, double *qs)
{
    double xs = Xq[tm_rc(Q->dir)];
    int sg = tm_sigma(Q->dir);
    if (Q->end_kind == TM_END_POINT) {
        int c = sg * cmpd(xs, Q->s1);
        if (c > 0) return -1;
        if (c == 0) return 2;
    } else if (Q->he == TM_NONE && loc == LOC_EDGE && Q->end_kind == TM_END_EDGE && x == Q->end_id) {
        return 2;
    }
    if (Q->he == TM_NONE && loc == LOC_EDGE && Q->start_kind == TM_END_EDGE && x == Q->start_id) return 0;
    *qs = xs;
    return 1;
}

/* Where X (on the new piece P's line, in F, not at a vertex) lies on P:
 * 0 start, 1 inside (*s, in P's chart), 2 end; -2 inconsistent. */
static int pos_on_new(const tm_piece *P, const double Xp[2], int loc, uint32_t x, double *s)
{
    if (P->he != TM_NONE || loc == LOC_IN) {
        *s = Xp[tm_rc(P->dir)];
        return 1;
    }
    if (P->start_kind == TM_END_EDGE && x == P->start_id) return 0;
    if (P->end_kind == TM_END_EDGE && x == P->end_id) return 2;
    return -2;
}

typedef struct contact {
    int where;          /* 0 start, 1 inside, 2 end of the new piece      */
    double s;           /* inside or end: coordinate along the new piece  */
    uint32_t q;         /* the piece met                                  */
    int headon, meet;
    uint32_t qk;        /* the position on q's trace: (qk, end) or ...    */
    uint8_t q_at_end;
    double qs;          /* ... (qk, qs)                                   */
    uint32_t F;         /* the face where the meeting was found           */
    double X[2];        /* the point in F's chart                         */
    uint8_t exact, loc;
    uint32_t x;         /* loc == LOC_EDGE: the edge of F                 */
} contact;

/* A crossing inside a face where the new piece's trace reaches the point
 * before the trace whose last piece already runs through it (in parametric
 * distance): that trace is cut back to the point. */
typedef struct win {
    uint32_t q, F;
    double X[2], s, qs;
} win;

static int contact_before(const contact *a, const contact *b, int sigma)
{
    if (a->where != b->where) return a->where < b->where;
    if (a->where == 1) return sigma * cmpd(a->s, b->s) < 0;
    return 0;
}

static int has_mark_on(const tm_traces *T, uint32_t t, uint32_t k)
{
    for (uint32_t i = 0; i < T->n_marks; i++)
        if (T->marks[i].trace == t && T->marks[i].k == k) return 1;
    return 0;
}

/* Tests the new piece P (trace t) against the pieces in face F; keeps the
 * first meeting along P in *best, and lists the crossings P wins. */
static int check_face(tracer *tr, uint32_t t, const tm_piece *P, uint32_t F, contact *best, int *found)
{
    const sq_map *M = tr->M;
    const tm_traces *T = tr->T;
    int dp;
    double cp;
    view(M, P, F, &dp, &cp);
    for (uint32_t r = tr->face_head[F]; r != TM_NONE; r = tr->rec[r].next) {
        const tm_piece *Q = &T->pieces[tr->rec[r].piece];
        const tm_trace *QT = &T->traces[Q->trace];
        int is_last = QT->last == (uint32_t)(Q - T->pieces);
        int dq;
        double cq;
        view(M, Q, F, &dq, &cq);
        contact ct;
        memset(&ct, 0, sizeof ct);
        ct.q = (uint32_t)(Q - T->pieces), ct.F = F;
        if ((dq ^ dp) & 1) {
            double X[2], Xq[2], Xp[2];
            X[tm_cc(dp)] = cp, X[tm_cc(dq)] = cq;
            uint32_t x = TM_NONE;
            int loc = locate(M, F, X, &x);
            if (loc == LOC_OUT || loc == LOC_VERTEX) continue;
            if (!to_piece_chart(M, Q, F, X, Xq) || !to_piece_chart(M, P, F, X, Xp)) {
                fail(tr, SQ_ERR_INTERNAL, "the meeting point of traces %u and %u in face %u is not exact across edge %u",
                     t, Q->trace, F, Q->face == F ? P->he : Q->he);
                return 0;
            }
            double qs = 0;
            int wq = pos_on_piece(Q, Xq, loc, x, &qs);
            if (wq < 0) continue;
            int wp = pos_on_new(P, Xp, loc, x, &ct.s);
            if (wq == 2 && is_last && QT->state != TM_STOPPED) {
                /* the front of a moving trace: the first to arrive there
                 * survives; on a tie the other stops when it moves on */
                double tq = tm_sigma(Q->dir) * Xq[tm_rc(Q->dir)] + Q->b;
                double ta = tm_sigma(P->dir) * Xp[tm_rc(P->dir)] + P->b;
                if (!(tq < ta)) continue;
            } else if (wq == 2 && is_last && QT->reason != TM_STOP_MEET) {
                continue;
            }
            if (wp == -2) {
                fail(tr, SQ_ERR_INTERNAL, "trace %u meets trace %u on edge %u of face %u off its chord", t, Q->trace,
                     x, F);
                return 0;
            }
            if (wp == 2) ct.s = Xp[tm_rc(P->dir)];
            ct.where = wp;
            if (wq == 2) ct.qk = Q->k, ct.q_at_end = 1;
            else if (wq == 0) ct.qk = Q->k - 1, ct.q_at_end = 1;
            else ct.qk = Q->k, ct.qs = qs;
            ct.X[0] = X[0], ct.X[1] = X[1], ct.exact = 1, ct.loc = (uint8_t)loc, ct.x = x;
            if (loc == LOC_IN && wp == 1 && wq == 1 && Q->trace != t && is_last && QT->state == TM_AT_EDGE &&
                Q->end_kind == TM_END_EDGE && !has_mark_on(T, Q->trace, Q->k) &&
                tm_sigma(Q->dir) * qs + Q->b > tm_sigma(P->dir) * ct.s + P->b) {
                if (!grow((void **)&tr->wins, &tr->cap_wins, tr->n_wins + 1, sizeof *tr->wins)) {
                    nomem(tr);
                    return 0;
                }
                win *w = &tr->wins[tr->n_wins++];
                w->q = ct.q, w->F = F, w->X[0] = X[0], w->X[1] = X[1], w->s = ct.s, w->qs = qs;
                continue;
            }
        } else if (cq == cp) {
            if (dq == dp) {
                fail(tr, SQ_ERR_INTERNAL, "trace %u runs along trace %u in the same direction in face %u", t, Q->trace,
                     F);
                return 0;
            }
            ct.headon = 1;
            ct.meet = is_last && QT->state != TM_STOPPED && Q->trace != t;
            ct.qk = Q->k, ct.q_at_end = 1;
            if (Q->end_kind == TM_END_POINT) {
                double Xq[2], X[2], Xp[2];
                Xq[tm_rc(Q->dir)] = Q->s1, Xq[tm_cc(Q->dir)] = Q->c;
                if (Q->face == F) {
                    X[0] = Xq[0], X[1] = Xq[1];
                } else if (!sq_tmesh_transform(M, Q->he, Xq, X)) {
                    fail(tr, SQ_ERR_INTERNAL, "the end of trace %u is not exact across edge %u", Q->trace, Q->he);
                    return 0;
                }
                uint32_t x = TM_NONE;
                int loc = locate(M, F, X, &x);
                if (loc == LOC_OUT || loc == LOC_VERTEX || !to_piece_chart(M, P, F, X, Xp)) {
                    fail(tr, SQ_ERR_INTERNAL, "trace %u meets the end of trace %u head-on off face %u", t, Q->trace, F);
                    return 0;
                }
                int wp = pos_on_new(P, Xp, loc, x, &ct.s);
                if (wp == -2) {
                    fail(tr, SQ_ERR_INTERNAL, "trace %u meets trace %u head-on off its chord in face %u", t, Q->trace,
                         F);
                    return 0;
                }
                if (wp == 2) ct.s = Xp[tm_rc(P->dir)];
                ct.where = wp;
                ct.X[0] = X[0], ct.X[1] = X[1], ct.exact = 1, ct.loc = (uint8_t)loc, ct.x = x;
            } else if (P->start_kind == Q->end_kind && P->start_id == Q->end_id) {
                ct.where = 0; /* at P's start: an edge point or a vertex */
                ct.loc = Q->end_kind == TM_END_EDGE ? LOC_EDGE : LOC_VERTEX;
                ct.x = Q->end_id;
            } else {
                fail(tr, SQ_ERR_INTERNAL, "trace %u meets trace %u head-on in face %u away from its start", t,
                     Q->trace, F);
                return 0;
            }
        } else {
            continue;
        }
        if (!*found || contact_before(&ct, best, tm_sigma(P->dir)) ||
            (ct.where == best->where && ct.meet && !best->meet && (ct.where != 1 || ct.s == best->s))) {
            *best = ct;
            *found = 1;
        }
    }
    return 1;
}

/* The node at the contact (created on first use) */
static uint32_t contact_node(tracer *tr, const tm_piece *P, const contact *ct)
{
    const sq_map *M = tr->M;
    tm_traces *T = tr->T;
    uint32_t qt = T->pieces[ct->q].trace;
    if (ct->loc == LOC_VERTEX) return vertex_node(tr, P->start_kind == TM_END_VERTEX ? P->start_id : ct->x);
    uint32_t node = find_mark(T, qt, ct->qk, ct->q_at_end, ct->qs);
    double X[2] = {ct->X[0], ct->X[1]};
    uint8_t kind = SQ_TMESH_IN_FACE;
    uint32_t id = ct->F;
    if (ct->loc == LOC_EDGE) {
        uint32_t x = ct->x, tx = M->mesh.he_twin[x];
        if (!ct->exact) { /* head-on at the entry point: the line on the edge */
            int d;
            double c;
            view(M, P, ct->F, &d, &c);
            X[tm_cc(d)] = c, X[tm_rc(d)] = edge_cross_s(M, x, d, c);
        }
        kind = SQ_TMESH_ON_EDGE, id = x;
        if (tx < x) {
            double Y[2];
            if (!sq_tmesh_transform(M, x, X, Y) && ct->exact) {
                fail(tr, SQ_ERR_INTERNAL, "a T-junction on edge %u is not exact across it", x);
                return TM_NONE;
            }
            if (!ct->exact) sq_map_rotate(M->he_rot[x], X, Y), Y[0] += M->he_t[2 * x], Y[1] += M->he_t[2 * x + 1];
            X[0] = Y[0], X[1] = Y[1], id = tx;
        }
    }
    if (node == TM_NONE) {
        node = new_node(tr, kind, id, X, ct->exact);
        if (node == TM_NONE || !add_mark(tr, qt, ct->qk, ct->q_at_end, ct->qs, node)) return TM_NONE;
    } else if (ct->exact && !T->nodes[node].exact) {
        T->nodes[node].uv[0] = X[0], T->nodes[node].uv[1] = X[1], T->nodes[node].exact = 1;
    }
    return node;
}

static int append_piece(tracer *tr, uint32_t t, const tm_piece *P)
{
    tm_traces *T = tr->T;
    if (!grow((void **)&T->pieces, &T->cap_pieces, T->n_pieces + 1, sizeof *T->pieces)) {
        nomem(tr);
        return 0;
    }
    uint32_t id = T->n_pieces++;
    T->pieces[id] = *P;
    T->pieces[id].trace = t, T->pieces[id].k = T->traces[t].n++;
    T->traces[t].last = id;
    if (P->he != TM_NONE) T->edge_pieces++;
    if (!add_record(tr, P->face, id) ||
        (P->he != TM_NONE && !add_record(tr, tr->M->mesh.he_face[tr->M->mesh.he_twin[P->he]], id))) {
        nomem(tr);
        return 0;
    }
    return 1;
}

static void stop(tracer *tr, uint32_t t, int reason, uint32_t node)
{
    tm_trace *tt = &tr->T->traces[t];
    tt->state = TM_STOPPED, tt->reason = (uint8_t)reason, tt->end_node = node;
}

/* Trace t arrives at vertex w by ray j (its last piece ends there). */
static int arrive(tracer *tr, uint32_t t, uint32_t w, int j)
{
    const sq_map *M = tr->M;
    if (j < 0) {
        fail(tr, SQ_ERR_INTERNAL, "trace %u arrives at vertex %u by no axis ray", t, w);
        return 0;
    }
    int taken = tr->vocc_head[w] != TM_NONE;
    if (!add_occ(tr, w, (uint32_t)j, t, 1)) return 0;
    if (taken || M->valence[w] != 4) {
        uint32_t node = vertex_node(tr, w);
        if (node == TM_NONE) return 0;
        if (M->valence[w] == 4) tr->T->t_junctions++;
        stop(tr, t, M->valence[w] != 4 ? TM_STOP_CONE : TM_STOP_ON_TRACE, node);
        return 1;
    }
    tm_ray rays[TM_MAX_RAYS];
    int n = sq_tmesh_vertex_rays(M, w, rays, TM_MAX_RAYS);
    if (n != 4) {
        fail(tr, SQ_ERR_INTERNAL, "regular vertex %u has %d axis rays in the map's charts (angle sum not 2 pi)", w, n);
        return 0;
    }
    uint32_t out = (uint32_t)(j + 2) % 4;
    if (!add_occ(tr, w, out, t, 0)) return 0;
    tr->front[t].v = w, tr->front[t].ray = out;
    tr->T->traces[t].state = TM_AT_VERTEX;
    tr->T->vertex_passes++;
    return 1;
}

/* The crossings won by trace t's new piece (its last), before its stop
 * `best` (NULL: none): each losing trace is cut back to the crossing and
 * stops there, a T-junction on t. Only a loser whose last piece holds the
 * crossing, ends on an edge, carries no node and is still moving is cut
 * (nothing depends on the part removed). */
static int cut_back(tracer *tr, uint32_t t, const contact *best)
{
    tm_traces *T = tr->T;
    const tm_piece *P = &T->pieces[T->traces[t].last];
    int sg = tm_sigma(P->dir);
    for (uint32_t i = 0; i < tr->n_wins; i++) {
        const win *w = &tr->wins[i];
        if (best && !(best->where == 2 || sg * w->s < sg * best->s)) continue;
        tm_piece *Q = &T->pieces[w->q];
        if (T->traces[Q->trace].state != TM_AT_EDGE) continue; /* already cut */
        uint32_t node = new_node(tr, SQ_TMESH_IN_FACE, w->F, w->X, 1);
        if (node == TM_NONE || !add_mark(tr, t, P->k, 0, w->s, node) || !add_mark(tr, Q->trace, Q->k, 1, 0, node))
            return 0;
        Q->end_kind = TM_END_POINT, Q->end_id = TM_NONE, Q->s1 = w->qs, Q->s1_exact = 1;
        stop(tr, Q->trace, TM_STOP_ON_TRACE, node);
        T->t_junctions++, T->overtaken++;
    }
    return 1;
}

/* One step of trace t: builds its next piece, tests it, adds it. */
static int step(tracer *tr, uint32_t t)
{
    const sq_map *M = tr->M;
    const sq_mesh *m = &M->mesh;
    tm_traces *T = tr->T;
    tm_trace *tt = &T->traces[t];
    tr_front *fr = &tr->front[t];
    tm_piece P;
    memset(&P, 0, sizeof P);
    P.he = TM_NONE;
    if (tt->state == TM_AT_VERTEX) {
        /* a trace arrived along this ray: it is this trace's path already */
        for (uint32_t o = tr->vocc_head[fr->v]; o != TM_NONE; o = tr->occ[o].next)
            if (tr->occ[o].arrive && tr->occ[o].ray == fr->ray && tr->occ[o].trace != t) {
                uint32_t node = vertex_node(tr, fr->v);
                if (node == TM_NONE) return 0;
                if (tt->n == 0) T->empty_traces++;
                else T->meets++;
                stop(tr, t, TM_STOP_MEET, node);
                return 1;
            }
        tm_ray rays[TM_MAX_RAYS];
        int n = sq_tmesh_vertex_rays(M, fr->v, rays, TM_MAX_RAYS);
        if (n <= (int)fr->ray) {
            fail(tr, SQ_ERR_INTERNAL, "vertex %u has no ray %u", fr->v, fr->ray);
            return 0;
        }
        tm_ray ry = rays[fr->ray];
        uint32_t h = ry.h;
        int d = ry.dir;
        const double *p = tm_uv(M, h);
        P.face = m->he_face[h], P.dir = (uint8_t)d, P.c = p[tm_cc(d)];
        P.start_kind = TM_END_VERTEX, P.start_id = fr->v;
        P.s0 = p[tm_rc(d)];
        /* tau at v is sigma s + b in both charts: the difference of the
         * two sigma s is exact wherever the charts differ by an exact
         * translation, so b stays exact on exact maps */
        P.b = fr->vb + (fr->vs - tm_sigma(d) * P.s0);
        if (ry.on_edge) {
            int d2;
            P.he = h;
            if (!line_across(M, h, d, P.c, &d2, &P.c2)) {
                fail(tr, SQ_ERR_INTERNAL, "the trace along edge %u is not exact across it", h);
                return 0;
            }
            P.end_kind = TM_END_VERTEX, P.end_id = m->he_vert[tm_next(M, h)];
            P.s1 = tm_uv(M, tm_next(M, h))[tm_rc(d)], P.s1_exact = 1;
        } else {
            P.end_kind = TM_END_EDGE, P.end_id = tm_next(M, h);
            P.s1 = edge_cross_s(M, P.end_id, d, P.c);
        }
    } else {
        uint32_t e = fr->e;
        int d = fr->d, k = tm_cc(d);
        double c = fr->c;
        const double *p0 = tm_uv(M, e), *p1 = tm_uv(M, tm_next(M, e)), *p2 = tm_uv(M, tm_prev(M, e));
        int s0 = cmpd(p0[k], c), s1 = cmpd(p1[k], c), s2 = cmpd(p2[k], c);
        if (s0 == 0 || s0 != -s1 || cross_aw(p0, p1, d) <= 0) {
            fail(tr, SQ_ERR_INTERNAL, "trace %u does not enter face %u through edge %u (inexact transition?)", t,
                 m->he_face[e], e);
            return 0;
        }
        P.face = m->he_face[e], P.dir = (uint8_t)d, P.c = c;
        P.start_kind = TM_END_EDGE, P.start_id = e;
        P.s0 = edge_cross_s(M, e, d, c);
        P.b = fr->b;
        if (s2 == 0) {
            P.end_kind = TM_END_VERTEX, P.end_id = m->he_vert[tm_prev(M, e)];
            P.s1 = p2[tm_rc(d)], P.s1_exact = 1;
        } else {
            P.end_kind = TM_END_EDGE, P.end_id = s2 == s1 ? tm_prev(M, e) : tm_next(M, e);
            P.s1 = edge_cross_s(M, P.end_id, d, c);
        }
    }

    /* meetings with the pieces already drawn */
    contact best;
    int found = 0;
    memset(&best, 0, sizeof best);
    tr->n_wins = 0;
    if (!check_face(tr, t, &P, P.face, &best, &found)) return 0;
    if (P.he != TM_NONE && !check_face(tr, t, &P, m->he_face[m->he_twin[P.he]], &best, &found)) return 0;

    if (found) {
        uint32_t node;
        if (best.where == 0) {
            node = contact_node(tr, &P, &best);
            if (node == TM_NONE) return 0;
            if (tt->state == TM_AT_EDGE && !add_mark(tr, t, T->pieces[tt->last].k, 1, 0, node)) return 0;
        } else {
            if (best.where == 1) {
                P.end_kind = TM_END_POINT, P.end_id = TM_NONE;
            }
            P.s1 = best.s, P.s1_exact = 1;
            if (!append_piece(tr, t, &P) || !cut_back(tr, t, &best)) return 0;
            node = contact_node(tr, &P, &best);
            if (node == TM_NONE || !add_mark(tr, t, T->pieces[tt->last].k, 1, 0, node)) return 0;
            tt->tau = tm_sigma(P.dir) * P.s1 + P.b;
        }
        if (best.meet || best.headon) {
            /* two traces head-on on one line: tau_A + tau_B is constant
             * along it; taken at the line's point of coordinate 0 in the
             * face's chart, it is exact where the meeting point is not (or
             * is exact but off the integer grid, where adding the two
             * traces' lengths would round) */
            const tm_piece *Q = &T->pieces[best.q];
            double Y[2], Yq[2];
            Y[tm_rc(P.dir)] = 0, Y[tm_cc(P.dir)] = P.c;
            if (to_piece_chart(M, Q, best.F, Y, Yq)) {
                T->nodes[node].has_sum = 1;
                T->nodes[node].sum = P.b + tm_sigma(Q->dir) * Yq[tm_rc(Q->dir)] + Q->b;
            }
        }
        if (best.meet) {
            stop(tr, T->pieces[best.q].trace, TM_STOP_MEET, node);
            T->meets++;
        } else {
            T->t_junctions++;
        }
        stop(tr, t, best.headon ? TM_STOP_MEET : TM_STOP_ON_TRACE, node);
        return 1;
    }

    if (!append_piece(tr, t, &P) || !cut_back(tr, t, NULL)) return 0;
    tt->tau = tm_sigma(P.dir) * P.s1 + P.b;
    if (P.end_kind == TM_END_EDGE) {
        uint32_t x = P.end_id;
        int d2;
        double c2;
        if (!line_across(M, x, P.dir, P.c, &d2, &c2)) {
            fail(tr, SQ_ERR_INTERNAL, "trace %u: the line %s = %.17g of face %u is not exact across edge %u", t,
                 P.dir & 1 ? "u" : "v", P.c, P.face, x);
            return 0;
        }
        fr->e = m->he_twin[x], fr->d = (uint8_t)d2, fr->c = c2;
        fr->b = P.b - tm_sigma(d2) * M->he_t[2 * (size_t)x + tm_rc(d2)];
        tt->state = TM_AT_EDGE;
        return 1;
    }
    /* arrives at a vertex: find its ray there (the corner of the piece's
     * face at the vertex, direction back along the piece) */
    uint32_t w = P.end_id, corner = sq_tmesh_corner(M, P.face, w);
    fr->vb = P.b, fr->vs = tm_sigma(P.dir) * P.s1;
    return arrive(tr, t, w, sq_tmesh_find_ray(M, corner, (P.dir + 2) & 3));
}

sq_status sq_tmesh_trace(const sq_map *M, tm_traces *T, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    memset(T, 0, sizeof *T);
    tracer tr;
    memset(&tr, 0, sizeof tr);
    tr.M = M, tr.T = T, tr.err = err;
    uint32_t n_traces = 0, cones = 0;
    for (uint32_t v = 0; v < m->nv; v++)
        if (M->valence[v] != 4) {
            if (M->valence[v] < 1 || M->valence[v] > TM_MAX_RAYS)
                return sq_error_set(err, SQ_ERR_ARGUMENT, "tmesh: vertex %u has valence %d", v, M->valence[v]);
            n_traces += (uint32_t)M->valence[v], cones++;
        }
    /* a map without cones (a flat torus): the four rays of vertex 0 are
     * traced as if it were a cone; it ends 4 arcs, a node like any other */
    uint32_t seed = TM_NONE;
    if (cones == 0) seed = 0, n_traces = 4;
    T->cones = cones;
    T->vnode = malloc((size_t)m->nv * sizeof *T->vnode);
    T->traces = calloc(n_traces, sizeof *T->traces);
    tr.front = calloc(n_traces, sizeof *tr.front);
    tr.face_head = malloc((size_t)m->nf * sizeof *tr.face_head);
    tr.vocc_head = malloc((size_t)m->nv * sizeof *tr.vocc_head);
    tr.heap = malloc((size_t)n_traces * sizeof *tr.heap);
    if (!T->vnode || !T->traces || !tr.front || !tr.face_head || !tr.vocc_head || !tr.heap) {
        nomem(&tr);
        goto done;
    }
    T->n_traces = n_traces;
    memset(T->vnode, 0xff, (size_t)m->nv * sizeof *T->vnode);
    memset(tr.face_head, 0xff, (size_t)m->nf * sizeof *tr.face_head);
    memset(tr.vocc_head, 0xff, (size_t)m->nv * sizeof *tr.vocc_head);

    /* every cone: its rays, counterclockwise, one trace each */
    uint32_t t = 0;
    for (uint32_t v = 0; v < m->nv && tr.st == SQ_OK; v++) {
        if (M->valence[v] == 4 && v != seed) continue;
        tm_ray rays[TM_MAX_RAYS];
        int n = sq_tmesh_vertex_rays(M, v, rays, TM_MAX_RAYS);
        if (n != M->valence[v]) {
            fail(&tr, SQ_ERR_INTERNAL, "cone %u of valence %d has %d axis rays in the map's charts", v, M->valence[v],
                 n);
            break;
        }
        if (vertex_node(&tr, v) == TM_NONE) break;
        for (int i = 0; i < n; i++, t++) {
            tm_trace *tt = &T->traces[t];
            tt->cone = v, tt->ray = (uint32_t)i, tt->state = TM_AT_VERTEX, tt->last = TM_NONE;
            tt->end_node = TM_NONE;
            tr.front[t].v = v, tr.front[t].ray = (uint32_t)i, tr.front[t].vb = 0, tr.front[t].vs = 0;
            if (!add_occ(&tr, v, (uint32_t)i, t, 0)) break;
            heap_push(&tr, t);
        }
    }

    /* the budget: far more pieces than any map whose traces close */
    uint64_t budget = 400ull * m->nf + 1000ull * n_traces + 100000ull;
    while (tr.st == SQ_OK && tr.n_heap > 0) {
        uint32_t u = heap_pop(&tr);
        if (T->traces[u].state == TM_STOPPED) continue;
        if (!step(&tr, u)) break;
        if (T->traces[u].state != TM_STOPPED) heap_push(&tr, u);
        if (T->n_pieces > budget) {
            fail(&tr, SQ_ERR_INTERNAL,
                 "traces do not end: %u pieces after %u cones' separatrices (trace %u from cone %u still running; a "
                 "trace winding around a flat region without meeting another?)",
                 T->n_pieces, n_traces, u, T->traces[u].cone);
            break;
        }
    }
done:
    free(tr.front), free(tr.face_head), free(tr.rec);
    free(tr.vocc_head), free(tr.occ), free(tr.heap), free(tr.wins);
    if (tr.st != SQ_OK) {
        sq_tmesh_traces_free(T);
        return tr.st;
    }
    return SQ_OK;
}

void sq_tmesh_traces_free(tm_traces *T)
{
    free(T->traces), free(T->pieces), free(T->marks), free(T->nodes), free(T->vnode);
    memset(T, 0, sizeof *T);
}
