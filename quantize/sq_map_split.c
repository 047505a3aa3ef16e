/* seamquad: a map's triangles split along iso-line chords (sq_map_split.h
 * explains what and why). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"
#include "sq_map_split.h"
#include "sq_predicates.h"

typedef struct line {
    uint8_t axis;
    double c;
} line;

/* A vertex of a cell polygon, in the chart of the face being cut. */
typedef struct pvert {
    uint32_t id;      /* output vertex                                          */
    uint8_t kind;     /* 0 face corner, 1 edge crossing, 2 line crossing, 3 centre */
    uint8_t edge;     /* kind 1: the face's edge (corner edge -> edge + 1)      */
    line on;          /* kind 1: the line whose crossing it is                  */
    uint8_t both;     /* kind 1: two lines cross exactly there: uv is exact     */
    double uv[2];     /* exact where kind 0 and 2; kind 1: on.axis exact        */
    uint32_t support; /* the polygon edge from here to the next: 0..2 the     */
                      /* face's edges, 3 + i its line i                        */
} pvert;

typedef struct growbuf {
    void *p;
    size_t n, cap, size;
} growbuf;

static void *gb_push(growbuf *g)
{
    if (g->n == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 64;
        void *p = realloc(g->p, cap * g->size);
        if (!p) return NULL;
        g->p = p, g->cap = cap;
    }
    return (char *)g->p + g->size * g->n++;
}

typedef struct ctx {
    const sq_map *M;
    const sq_mesh *m;
    /* chords grouped by face */
    uint32_t *chord_off, *chord_idx;
    const sq_chord *chords;
    /* edge crossings: for the smaller halfedge of each pair, its points in
     * order from its origin, as lines of its face's chart */
    uint32_t *ep_off;   /* nh + 1 (only smaller halfedges have entries) */
    line *ep_line;
    uint32_t *ep_id;
    line *ep_other;     /* a second line through the point (axis 2: none):   */
                        /* two lines cross exactly on the edge              */
    growbuf pos;        /* double[3] */
    growbuf tri;        /* uint32_t[3] */
    growbuf tface;      /* uint32_t */
    growbuf tuv;        /* double[6] */
    growbuf tex;        /* uint8_t[3] */
    growbuf tarc;       /* uint8_t[3] */
    uint32_t nv;
} ctx;

/* sgn * p[ax] of R^k p, for the component `axis`. */
static void rot_component(int k, int axis, int *sgn, int *ax)
{
    static const int S[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    static const int A[4][2] = {{0, 1}, {1, 0}, {0, 1}, {1, 0}};
    *sgn = S[k & 3][axis];
    *ax = A[k & 3][axis];
}

/* The line p_A[axis] = c seen in chart B, where p_B = R^r p_A + t. */
static line line_to(line L, int r, const double *t)
{
    int sgn, ax;
    rot_component((4 - r) & 3, L.axis, &sgn, &ax); /* p_A[axis] = sgn (p_B - t)[ax] */
    line o;
    o.axis = (uint8_t)ax;
    o.c = sgn * L.c + t[ax];
    return o;
}

static int sign_d(double x) { return (x > 0) - (x < 0); }

/* sign(p[L.axis] - L.c) for a point on segment a -> b on line `on` (not
 * parallel to L): exact, by orient2d against the crossing of the lines. */
static int side_edge_point(const double *a, const double *b, line on, line L)
{
    if (on.axis == L.axis) return sign_d(on.c - L.c);
    double X[2];
    X[L.axis] = L.c;
    X[on.axis] = on.c;
    int o = sq_orient2d(a, b, X) * sign_d(b[on.axis] - a[on.axis]);
    return L.axis == 0 ? o : -o;
}

static const double *corner_uv(const ctx *C, uint32_t f, int k)
{
    uint32_t h = C->m->f_he[f];
    while (k--) h = C->m->he_next[h];
    return C->M->he_uv + 2 * (size_t)h;
}

static int side_of(const ctx *C, uint32_t f, const pvert *p, line L)
{
    if (p->kind == 1)
        return side_edge_point(corner_uv(C, f, p->edge), corner_uv(C, f, (p->edge + 1) % 3), p->on, L);
    return sign_d(p->uv[L.axis] - L.c);
}

static int strictly_cuts(const double *uv0, const double *uv1, const double *uv2, line L)
{
    int s0 = sign_d(uv0[L.axis] - L.c), s1 = sign_d(uv1[L.axis] - L.c), s2 = sign_d(uv2[L.axis] - L.c);
    return (s0 < 0 || s1 < 0 || s2 < 0) && (s0 > 0 || s1 > 0 || s2 > 0);
}

static uint32_t new_vertex(ctx *C, const double *p3)
{
    double *q = gb_push(&C->pos);
    if (!q) return UINT32_MAX;
    q[0] = p3[0], q[1] = p3[1], q[2] = p3[2];
    return C->nv++;
}

/* Orders crossings along edge a -> b (exact). */
typedef struct ecross {
    line L;
    const double *a, *b;
} ecross;

static int cmp_cross(const void *x, const void *y)
{
    const ecross *P = x, *Q = y;
    /* position of P relative to Q's line: P before Q iff P lies on a's side
     * of Q's line */
    int sa = sign_d(P->a[Q->L.axis] - Q->L.c);
    int sp = side_edge_point(P->a, P->b, P->L, Q->L);
    if (sp == 0) return 0;
    return sp == sa ? -1 : 1;
}

/* The lines of face f that cut it, deduplicated (into *out). */
static sq_status face_lines(const ctx *C, uint32_t f, growbuf *out)
{
    out->n = 0;
    const double *u0 = corner_uv(C, f, 0), *u1 = corner_uv(C, f, 1), *u2 = corner_uv(C, f, 2);
    for (uint32_t k = C->chord_off[f]; k < C->chord_off[f + 1]; k++) {
        const sq_chord *ch = C->chords + C->chord_idx[k];
        line L = {ch->axis, ch->c};
        if (!strictly_cuts(u0, u1, u2, L)) continue;
        int dup = 0;
        for (size_t i = 0; i < out->n && !dup; i++) {
            const line *o = (const line *)out->p + i;
            dup = o->axis == L.axis && o->c == L.c;
        }
        if (dup) continue;
        line *dst = gb_push(out);
        if (!dst) return SQ_ERR_NOMEM;
        *dst = L;
    }
    return SQ_OK;
}

/* Step 1: every mesh edge split where a line of either face crosses it. */
static sq_status edge_crossings(ctx *C, sq_error *err)
{
    const sq_mesh *m = C->m;
    growbuf lines = {0, 0, 0, sizeof(line)}, cross = {0, 0, 0, sizeof(ecross)};
    growbuf eline = {0, 0, 0, sizeof(line)}, eid = {0, 0, 0, sizeof(uint32_t)};
    growbuf eother = {0, 0, 0, sizeof(line)};
    sq_status st = SQ_OK;
    C->ep_off = calloc((size_t)m->nh + 1, sizeof *C->ep_off);
    if (!C->ep_off) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (edge crossings)");
    for (uint32_t h = 0; h < m->nh && !st; h++) {
        C->ep_off[h] = (uint32_t)eline.n;
        uint32_t g = m->he_twin[h];
        if (g < h) continue;
        const double *a = C->M->he_uv + 2 * (size_t)h, *b = C->M->he_uv + 2 * (size_t)m->he_next[h];
        cross.n = 0;
        for (int side = 0; side < 2 && !st; side++) {
            uint32_t e = side ? g : h, f = m->he_face[e];
            if ((st = face_lines(C, f, &lines))) break;
            const double *ea = C->M->he_uv + 2 * (size_t)e, *eb = C->M->he_uv + 2 * (size_t)m->he_next[e];
            for (size_t i = 0; i < lines.n; i++) {
                line L = ((line *)lines.p)[i];
                if (sign_d(ea[L.axis] - L.c) * sign_d(eb[L.axis] - L.c) >= 0) continue;
                if (side) L = line_to(L, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
                ecross *x = gb_push(&cross);
                if (!x) {
                    st = SQ_ERR_NOMEM;
                    break;
                }
                x->L = L, x->a = a, x->b = b;
            }
        }
        if (st) break;
        if (cross.n > 1) qsort(cross.p, cross.n, sizeof(ecross), cmp_cross);
        for (size_t i = 0; i < cross.n; i++) {
            ecross *x = (ecross *)cross.p + i;
            if (i && cmp_cross(x - 1, x) == 0) { /* the same point */
                if (x[-1].L.axis != x->L.axis) ((line *)eother.p)[eother.n - 1] = x->L;
                continue;
            }
            double s = (x->L.c - a[x->L.axis]) / (b[x->L.axis] - a[x->L.axis]);
            const double *pa = m->pos + 3 * (size_t)m->he_vert[h], *pb = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
            double p3[3] = {pa[0] + s * (pb[0] - pa[0]), pa[1] + s * (pb[1] - pa[1]), pa[2] + s * (pb[2] - pa[2])};
            line *dl = gb_push(&eline);
            uint32_t *di = gb_push(&eid);
            line *db = gb_push(&eother);
            if (!dl || !di || !db || (*di = new_vertex(C, p3)) == UINT32_MAX) {
                st = SQ_ERR_NOMEM;
                break;
            }
            db->axis = 2, db->c = 0.0;
            *dl = x->L;
        }
    }
    C->ep_off[m->nh] = (uint32_t)eline.n;
    C->ep_line = eline.p;
    C->ep_id = eid.p;
    C->ep_other = eother.p;
    free(lines.p);
    free(cross.p);
    if (st) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (edge crossings)");
    return SQ_OK;
}

/* The face's boundary polygon: corners and edge crossings in order. */
static sq_status boundary_polygon(const ctx *C, uint32_t f, growbuf *poly)
{
    const sq_mesh *m = C->m;
    poly->n = 0;
    uint32_t h = m->f_he[f];
    for (int k = 0; k < 3; k++, h = m->he_next[h]) {
        pvert *p = gb_push(poly);
        if (!p) return SQ_ERR_NOMEM;
        memset(p, 0, sizeof *p);
        p->id = m->he_vert[h];
        p->kind = 0;
        p->uv[0] = C->M->he_uv[2 * (size_t)h], p->uv[1] = C->M->he_uv[2 * (size_t)h + 1];
        p->support = (uint32_t)k;
        uint32_t g = m->he_twin[h], own = h < g ? h : g;
        uint32_t n = C->ep_off[own + 1] - C->ep_off[own];
        const double *a = C->M->he_uv + 2 * (size_t)h, *b = C->M->he_uv + 2 * (size_t)m->he_next[h];
        for (uint32_t i = 0; i < n; i++) {
            uint32_t j = own == h ? C->ep_off[own] + i : C->ep_off[own] + (n - 1 - i);
            line L = C->ep_line[j];
            if (own != h) L = line_to(L, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
            pvert *q = gb_push(poly);
            if (!q) return SQ_ERR_NOMEM;
            memset(q, 0, sizeof *q);
            q->id = C->ep_id[j];
            q->kind = 1;
            q->edge = (uint8_t)k;
            q->on = L;
            double s = (L.c - a[L.axis]) / (b[L.axis] - a[L.axis]);
            q->uv[L.axis] = L.c;
            q->uv[1 - L.axis] = a[1 - L.axis] + s * (b[1 - L.axis] - a[1 - L.axis]);
            q->support = (uint32_t)k;
            q->both = a[1 - L.axis] == b[1 - L.axis]; /* an edge along a line: exact */
            line O = C->ep_other[j];
            if (O.axis != 2) { /* two lines cross exactly here: exact */
                if (own != h) O = line_to(O, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
                q->uv[O.axis] = O.c;
                q->both = 1;
            }
        }
    }
    return SQ_OK;
}

typedef struct xpoint {
    uint32_t i, j, id;
} xpoint;

/* Splits the convex polygon `in` by line li of face f into out[0] (side
 * -1) and out[1] (side +1); returns 0 if the line does not cut it. */
static int split_polygon(ctx *C, uint32_t f, const line *lines, uint32_t li, const growbuf *in,
                         growbuf out[2], growbuf *xs, sq_status *st)
{
    line L = lines[li];
    size_t n = in->n;
    const pvert *P = in->p;
    int8_t sg[512];
    int8_t *s = n <= sizeof sg ? sg : malloc(n);
    if (!s) return *st = SQ_ERR_NOMEM, 0;
    int neg = 0, pos = 0;
    for (size_t i = 0; i < n; i++) {
        s[i] = (int8_t)side_of(C, f, &P[i], L);
        neg |= s[i] < 0, pos |= s[i] > 0;
    }
    if (!neg || !pos) {
        if (s != sg) free(s);
        return 0;
    }
    for (int k = 0; k < 2; k++) {
        int S = k ? 1 : -1;
        out[k].n = 0;
        for (size_t i = 0; i < n && !*st; i++) {
            size_t j = (i + 1) % n;
            if (s[i] * S >= 0) {
                pvert *q = gb_push(&out[k]);
                if (!q) {
                    *st = SQ_ERR_NOMEM;
                    break;
                }
                *q = P[i];
                q->support = (s[i] == 0 && s[j] * S < 0) ? 3 + li : P[i].support;
            }
            if (s[i] * s[j] < 0) {
                pvert X;
                memset(&X, 0, sizeof X);
                uint32_t sup = P[i].support;
                if (sup < 3) { /* on the face's edge: an existing crossing */
                    const sq_mesh *m = C->m;
                    uint32_t h = m->f_he[f];
                    for (uint32_t e = 0; e < sup; e++) h = m->he_next[h];
                    uint32_t g = m->he_twin[h], own = h < g ? h : g, found = UINT32_MAX;
                    for (uint32_t q = C->ep_off[own]; q < C->ep_off[own + 1]; q++) {
                        line E = C->ep_line[q], O = C->ep_other[q];
                        if (own != h) E = line_to(E, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
                        if (own != h && O.axis != 2) O = line_to(O, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
                        if ((E.axis == L.axis && E.c == L.c) || (O.axis == L.axis && O.c == L.c)) found = q;
                    }
                    if (found == UINT32_MAX) {
                        *st = SQ_ERR_INTERNAL;
                        break;
                    }
                    const double *a = corner_uv(C, f, (int)sup), *b = corner_uv(C, f, (int)(sup + 1) % 3);
                    double t = (L.c - a[L.axis]) / (b[L.axis] - a[L.axis]);
                    X.id = C->ep_id[found];
                    X.kind = 1;
                    X.edge = (uint8_t)sup;
                    X.on = L;
                    X.uv[L.axis] = L.c;
                    X.uv[1 - L.axis] = a[1 - L.axis] + t * (b[1 - L.axis] - a[1 - L.axis]);
                    X.both = a[1 - L.axis] == b[1 - L.axis];
                    line O = C->ep_other[found];
                    if (O.axis != 2) {
                        if (own != h) O = line_to(O, C->M->he_rot[g], C->M->he_t + 2 * (size_t)g);
                        X.uv[O.axis] = O.c;
                        X.both = 1;
                    }
                } else { /* the crossing of two lines: exact, one per pair */
                    uint32_t mi = sup - 3, a = mi < li ? mi : li, b = mi < li ? li : mi;
                    line Mline = lines[mi];
                    X.kind = 2;
                    X.uv[L.axis] = L.c;
                    X.uv[Mline.axis] = Mline.c;
                    X.id = UINT32_MAX;
                    for (size_t q = 0; q < xs->n; q++) {
                        const xpoint *x = (const xpoint *)xs->p + q;
                        if (x->i == a && x->j == b) X.id = x->id;
                    }
                    if (X.id == UINT32_MAX) {
                        /* position: barycentric in the face's UV triangle */
                        const double *p0 = corner_uv(C, f, 0), *p1 = corner_uv(C, f, 1), *p2 = corner_uv(C, f, 2);
                        double d = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
                        double l1 = ((X.uv[0] - p0[0]) * (p2[1] - p0[1]) - (X.uv[1] - p0[1]) * (p2[0] - p0[0])) / d;
                        double l2 = ((p1[0] - p0[0]) * (X.uv[1] - p0[1]) - (p1[1] - p0[1]) * (X.uv[0] - p0[0])) / d;
                        const sq_mesh *m = C->m;
                        uint32_t h = m->f_he[f];
                        const double *q0 = m->pos + 3 * (size_t)m->he_vert[h];
                        const double *q1 = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
                        const double *q2 = m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]];
                        double p3[3];
                        for (int c = 0; c < 3; c++) p3[c] = q0[c] + l1 * (q1[c] - q0[c]) + l2 * (q2[c] - q0[c]);
                        X.id = new_vertex(C, p3);
                        xpoint *x = gb_push(xs);
                        if (X.id == UINT32_MAX || !x) {
                            *st = SQ_ERR_NOMEM;
                            break;
                        }
                        x->i = a, x->j = b, x->id = X.id;
                    }
                }
                X.support = s[j] * S > 0 ? sup : 3 + li;
                pvert *q = gb_push(&out[k]);
                if (!q) {
                    *st = SQ_ERR_NOMEM;
                    break;
                }
                *q = X;
            }
        }
    }
    if (s != sg) free(s);
    return 1;
}

/* sign(coordinate of p along line L - x), exactly: p lies on L; its
 * coordinate along L is exact unless p is the crossing of L itself with a
 * mesh edge, where orient2d against the crossing of L and the line
 * through x decides. x = +-INFINITY: the sign of -x. */
static int along_sign(const ctx *C, uint32_t f, const pvert *p, line L, double x)
{
    if (isinf(x)) return x > 0 ? -1 : 1;
    line M = {(uint8_t)(1 - L.axis), x};
    if (p->kind == 1 && !p->both && p->on.axis == L.axis)
        return side_edge_point(corner_uv(C, f, p->edge), corner_uv(C, f, (p->edge + 1) % 3), p->on, M);
    return sign_d(p->uv[M.axis] - x);
}

/* Chord test: does the cell edge p -> q (support line li, or the face's
 * edge) lie on a chord of face f? */
static int on_chord(const ctx *C, uint32_t f, const line *lines, uint32_t support, const pvert *p,
                    const pvert *q)
{
    line L;
    if (support >= 3) {
        L = lines[support - 3];
    } else {
        /* a chord along the face's edge: a line through both its ends */
        const double *a = corner_uv(C, f, (int)support), *b = corner_uv(C, f, (int)(support + 1) % 3);
        if (a[0] == b[0]) L.axis = 0, L.c = a[0];
        else if (a[1] == b[1]) L.axis = 1, L.c = a[1];
        else return 0;
    }
    for (uint32_t k = C->chord_off[f]; k < C->chord_off[f + 1]; k++) {
        const sq_chord *ch = C->chords + C->chord_idx[k];
        if (ch->axis != L.axis || ch->c != L.c) continue;
        /* both ends within the chord's extent, decided exactly (an edge a
         * rounding error long beyond a chord's end is not on it) */
        if (along_sign(C, f, p, L, ch->lo) >= 0 && along_sign(C, f, q, L, ch->lo) >= 0 &&
            along_sign(C, f, p, L, ch->hi) <= 0 && along_sign(C, f, q, L, ch->hi) <= 0)
            return 1;
    }
    return 0;
}

/* Triangles of one convex cell: a fan from the first corner where every
 * vertex is a corner, else from a centre vertex. */
static sq_status emit_cell(ctx *C, uint32_t f, const line *lines, const growbuf *cell)
{
    const pvert *P = cell->p;
    size_t n = cell->n;
    int corners = 1;
    for (size_t i = 0; i < n; i++)
        if (P[(i + n - 1) % n].support == P[i].support) corners = 0;
    pvert centre;
    memset(&centre, 0, sizeof centre);
    size_t first = 0, count = n - 2;
    if (!corners || n > 3) {
        if (!corners) {
            double p3[3] = {0, 0, 0};
            for (size_t i = 0; i < n; i++) {
                const double *q = (const double *)C->pos.p + 3 * (size_t)P[i].id;
                for (int c = 0; c < 3; c++) p3[c] += q[c] / (double)n;
                centre.uv[0] += P[i].uv[0] / (double)n, centre.uv[1] += P[i].uv[1] / (double)n;
            }
            centre.kind = 3;
            centre.support = UINT32_MAX;
            if ((centre.id = new_vertex(C, p3)) == UINT32_MAX) return SQ_ERR_NOMEM;
            count = n;
        }
    }
    for (size_t k = 0; k < count; k++) {
        const pvert *v[3];
        uint8_t arc[3];
        if (corners) {
            v[0] = &P[first], v[1] = &P[first + k + 1], v[2] = &P[first + k + 2];
            arc[0] = k == 0 ? on_chord(C, f, lines, v[0]->support, v[0], v[1]) : 0;
            arc[1] = on_chord(C, f, lines, v[1]->support, v[1], v[2]);
            arc[2] = k == count - 1 ? on_chord(C, f, lines, v[2]->support, v[2], v[0]) : 0;
        } else {
            v[0] = &centre, v[1] = &P[k], v[2] = &P[(k + 1) % n];
            arc[0] = 0;
            arc[1] = on_chord(C, f, lines, v[1]->support, v[1], v[2]);
            arc[2] = 0;
        }
        uint32_t *t = gb_push(&C->tri);
        uint32_t *tf = gb_push(&C->tface);
        double *uv = gb_push(&C->tuv);
        uint8_t *ex = gb_push(&C->tex), *ta = gb_push(&C->tarc);
        if (!t || !tf || !uv || !ex || !ta) return SQ_ERR_NOMEM;
        *tf = f;
        for (int c = 0; c < 3; c++) {
            t[c] = v[c]->id;
            uv[2 * c] = v[c]->uv[0], uv[2 * c + 1] = v[c]->uv[1];
            uint8_t e = 0;
            if (v[c]->kind == 0 || v[c]->kind == 2) e = SQ_SPLIT_U_EXACT | SQ_SPLIT_V_EXACT;
            else if (v[c]->kind == 1)
                e = v[c]->both ? SQ_SPLIT_U_EXACT | SQ_SPLIT_V_EXACT
                               : v[c]->on.axis == 0 ? SQ_SPLIT_U_EXACT : SQ_SPLIT_V_EXACT;
            ex[c] = e;
            ta[c] = arc[c];
        }
    }
    return SQ_OK;
}

/* A new empty cell (a growbuf of pvert) at the end of cells. */
static growbuf *new_cell(growbuf *cells)
{
    growbuf *g = gb_push(cells);
    if (!g) return NULL;
    memset(g, 0, sizeof *g);
    g->size = sizeof(pvert);
    return g;
}

/* Step 2: every face cut by its lines, the cells triangulated. */
static sq_status cut_faces(ctx *C, sq_error *err)
{
    const sq_mesh *m = C->m;
    growbuf lines = {0, 0, 0, sizeof(line)}, xs = {0, 0, 0, sizeof(xpoint)};
    growbuf cells = {0, 0, 0, sizeof(growbuf)};
    growbuf out[2] = {{0, 0, 0, sizeof(pvert)}, {0, 0, 0, sizeof(pvert)}};
    sq_status st = SQ_OK;
    for (uint32_t f = 0; f < m->nf && !st; f++) {
        if ((st = face_lines(C, f, &lines))) break;
        xs.n = 0;
        /* the cells, each a growbuf of pvert */
        for (size_t i = 0; i < cells.n; i++) ((growbuf *)cells.p)[i].n = 0;
        size_t ncell = 1;
        if (!cells.n && !new_cell(&cells)) {
            st = SQ_ERR_NOMEM;
            break;
        }
        if ((st = boundary_polygon(C, f, (growbuf *)cells.p))) break;
        for (uint32_t li = 0; li < lines.n && !st; li++) {
            size_t nc = ncell;
            for (size_t ci = 0; ci < nc && !st; ci++) {
                growbuf *cell = (growbuf *)cells.p + ci;
                if (!split_polygon(C, f, lines.p, li, cell, out, &xs, &st) || st) continue;
                /* cell <- out[0]; a new cell <- out[1] */
                growbuf tmp = *cell;
                *cell = out[0];
                out[0] = tmp;
                if (ncell == cells.n && !new_cell(&cells)) {
                    st = SQ_ERR_NOMEM;
                    break;
                }
                growbuf *dst = (growbuf *)cells.p + ncell++;
                tmp = *dst;
                *dst = out[1];
                out[1] = tmp;
                out[1].n = 0;
            }
        }
        for (size_t ci = 0; ci < ncell && !st; ci++) st = emit_cell(C, f, lines.p, (growbuf *)cells.p + ci);
    }
    for (size_t i = 0; i < cells.n; i++) free(((growbuf *)cells.p)[i].p);
    free(cells.p), free(lines.p), free(xs.p), free(out[0].p), free(out[1].p);
    if (st == SQ_ERR_INTERNAL)
        return sq_error_set(err, st, "map split: a line crosses a face's edge where no crossing was made");
    if (st) return sq_error_set(err, st, "out of memory (map split)");
    return SQ_OK;
}

void sq_split_free(sq_split *S)
{
    if (!S) return;
    sq_mesh_free(&S->mesh);
    free(S->pos), free(S->tri), free(S->tri_face), free(S->uv), free(S->uv_exact), free(S->on_chord);
    memset(S, 0, sizeof *S);
}

sq_status sq_map_split(const sq_map *M, const sq_chord *chords, uint32_t n_chords, sq_split *out,
                       sq_error *err)
{
    memset(out, 0, sizeof *out);
    ctx C;
    memset(&C, 0, sizeof C);
    C.M = M, C.m = &M->mesh, C.chords = chords;
    C.pos.size = 3 * sizeof(double);
    C.tri.size = 3 * sizeof(uint32_t);
    C.tface.size = sizeof(uint32_t);
    C.tuv.size = 6 * sizeof(double);
    C.tex.size = 3;
    C.tarc.size = 3;
    const sq_mesh *m = C.m;
    sq_status st = SQ_OK;
    C.chord_off = calloc((size_t)m->nf + 1, sizeof *C.chord_off);
    C.chord_idx = malloc(((size_t)n_chords + 1) * sizeof *C.chord_idx);
    if (!C.chord_off || !C.chord_idx) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map split)");
        goto done;
    }
    for (uint32_t k = 0; k < n_chords; k++) {
        if (chords[k].face >= m->nf || chords[k].axis > 1 || !isfinite(chords[k].c)) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "map split: chord %u is bad", k);
            goto done;
        }
        C.chord_off[chords[k].face + 1]++;
    }
    for (uint32_t f = 0; f < m->nf; f++) C.chord_off[f + 1] += C.chord_off[f];
    {
        uint32_t *fill = malloc(((size_t)m->nf + 1) * sizeof *fill);
        if (!fill) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map split)");
            goto done;
        }
        memcpy(fill, C.chord_off, (size_t)m->nf * sizeof *fill);
        for (uint32_t k = 0; k < n_chords; k++) C.chord_idx[fill[chords[k].face]++] = k;
        free(fill);
    }
    for (uint32_t v = 0; v < m->nv; v++)
        if (new_vertex(&C, m->pos + 3 * (size_t)v) == UINT32_MAX) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map split)");
            goto done;
        }
    if ((st = edge_crossings(&C, err))) goto done;
    if ((st = cut_faces(&C, err))) goto done;
    out->nv = C.nv;
    out->nv_input = m->nv;
    out->nt = (uint32_t)C.tri.n;
    out->pos = C.pos.p, C.pos.p = NULL;
    out->tri = C.tri.p, C.tri.p = NULL;
    out->tri_face = C.tface.p, C.tface.p = NULL;
    out->uv = C.tuv.p, C.tuv.p = NULL;
    out->uv_exact = C.tex.p, C.tex.p = NULL;
    out->on_chord = C.tarc.p, C.tarc.p = NULL;
    /* the halfedge mesh (validates: closed, manifold, oriented) */
    {
        sq_soup soup;
        memset(&soup, 0, sizeof soup);
        soup.nv = out->nv, soup.pos = out->pos, soup.nf = out->nt, soup.face_idx = out->tri;
        soup.face_off = malloc(((size_t)out->nt + 1) * sizeof *soup.face_off);
        if (!soup.face_off) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map split)");
            goto done;
        }
        for (uint32_t t = 0; t <= out->nt; t++) soup.face_off[t] = 3 * t;
        sq_error e2;
        st = sq_mesh_from_soup(&soup, SQ_MESH_SKIP_DEGENERATE, &out->mesh, &e2);
        free(soup.face_off);
        if (st) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "map split: the split mesh is broken: %s", e2.msg);
            goto done;
        }
        for (uint32_t h = 0; h < out->mesh.nh; h++)
            if (out->on_chord[h]) out->on_chord[out->mesh.he_twin[h]] = 1;
    }
done:
    if (st) sq_split_free(out);
    free(C.chord_off), free(C.chord_idx), free(C.ep_off), free(C.ep_line), free(C.ep_id), free(C.ep_other);
    free(C.pos.p), free(C.tri.p), free(C.tface.p), free(C.tuv.p), free(C.tex.p), free(C.tarc.p);
    return st;
}
