/* Step 2 of the extraction: tracing one grid edge.
 *
 * A slot of grid point P is the unit segment from P to Q = P + d, d an axis
 * direction of some face's chart. The segment is followed on the surface
 * through a sequence of simplices, always in the chart of one current face
 * where P and Q have exact integer coordinates (transitions are rotations
 * by multiples of 90 degrees plus integer translations, so P and Q stay
 * exact in every chart, and d stays an axis direction). Three states:
 *
 *  - FACE f: the open segment runs through the interior of f. With the
 *    signs s_i = orient2d(P, Q, c_i) of f's corners, the segment leaves f
 *    through the edge (c_i, c_i+1) with s_i < 0 < s_i+1, or through a
 *    corner with s = 0 whose opposite edge is where it came in (s_j > 0 >
 *    s_k). Then orient2d of the exit edge and Q (or, for a corner, the
 *    coordinate along d, which is exact) tells whether Q comes first: Q
 *    inside f, on the exit edge, at the corner, or beyond, where the
 *    segment crosses into the twin's face (P and Q mapped by the edge's
 *    transition) or passes through the corner's vertex.
 *  - VERTEX at corner h (in h's face): the segment passes through a mesh
 *    vertex. Its corners are visited counterclockwise, mapping P and Q
 *    across each edge, until one holds the ray towards Q strictly inside
 *    (FACE) or along its first edge (EDGE). A vertex passed mid-segment is
 *    regular (a cone is an integer point, and the open unit segment holds
 *    none), so one turn of the corners finds the ray: the charts of a
 *    regular vertex unfold into one plane.
 *  - EDGE e (in e's face): the segment runs along e towards its head; Q is
 *    inside e, at the head, or beyond it (VERTEX at the head).
 *
 * The start is the slot's own state: a vertex point starts in VERTEX at the
 * slot's corner (which holds d in its half-open angle), an edge point in
 * FACE on the side Q lies on (or EDGE along it), a face point in FACE.
 *
 * At the end, the arrival slot is the direction of P - Q at the grid point
 * found at Q: in the chart of its face, its edge's halfedge, or, at a
 * vertex, the corner that holds the ray Q -> P in its half-open angle (the
 * corner of the last face, or the next one counterclockwise when the ray
 * lies along that corner's closing edge). */
#include <math.h>
#include <stdio.h>

#include "sq_extract_internal.h"
#include "sq_predicates.h"

typedef struct walk {
    const sq_map *M;
    const sq_mesh *m;
    uint32_t face;   /* the current chart */
    double P[2], Q[2];
    int axis;        /* the coordinate that changes along the segment */
    double sgn;      /* its sign from P to Q */
} walk;

static void set_axis(walk *w)
{
    w->axis = w->Q[0] != w->P[0] ? 0 : 1;
    w->sgn = w->Q[w->axis] > w->P[w->axis] ? 1.0 : -1.0;
}

/* Position of X along the segment's direction (exact: a sign flip). */
static double along(const walk *w, const double *X) { return w->sgn * X[w->axis]; }

static const double *corner(const walk *w, uint32_t h) { return w->M->he_uv + 2 * (size_t)h; }

/* Moves the chart across halfedge h of the current face. */
static void cross(walk *w, uint32_t h)
{
    int r = w->M->he_rot[h];
    const double *t = w->M->he_t + 2 * (size_t)h;
    double p[2], q[2];
    sq_map_rotate(r, w->P, p);
    sq_map_rotate(r, w->Q, q);
    w->P[0] = p[0] + t[0], w->P[1] = p[1] + t[1];
    w->Q[0] = q[0] + t[0], w->Q[1] = q[1] + t[1];
    w->face = w->m->he_face[w->m->he_twin[h]];
    set_axis(w);
}

enum { ST_FACE, ST_VERTEX, ST_EDGE, END_FACE, END_EDGE, END_VERTEX };

static sq_status fail(const sq_grid *G, uint32_t s, const walk *w, sq_error *err, const char *what)
{
    char buf[160];
    return sq_error_set(err, SQ_ERR_INTERNAL,
                        "tracing the grid edge from %s in direction %u of its chart: %s (face %u, "
                        "segment (%.17g, %.17g) -> (%.17g, %.17g) in its chart)",
                        sq_grid_describe(G, G->slot_point[s], buf, sizeof buf),
                        (unsigned)G->slot_dir[s], what, w->face, w->P[0], w->P[1], w->Q[0], w->Q[1]);
}

/* FACE: the next state, with *h the exit edge or corner. */
static int face_step(walk *w, uint32_t *h)
{
    const sq_mesh *m = w->m;
    uint32_t he[3];
    he[0] = m->f_he[w->face], he[1] = m->he_next[he[0]], he[2] = m->he_next[he[1]];
    int s[3], zeros = 0, z = -1;
    for (int i = 0; i < 3; i++) {
        s[i] = sq_orient2d(w->P, w->Q, corner(w, he[i]));
        if (!s[i]) zeros++, z = i;
    }
    int exit_edge = -1;
    if (zeros == 0) {
        for (int i = 0; i < 3; i++)
            if (s[i] < 0 && s[(i + 1) % 3] > 0) exit_edge = i;
    } else if (zeros == 1) {
        int j = (z + 1) % 3, k = (z + 2) % 3;
        if (s[j] < 0 && s[k] > 0) exit_edge = j;
        else if (s[j] > 0 && s[k] < 0) {
            const double *c = corner(w, he[z]);
            double a = along(w, w->Q), b = along(w, c);
            *h = he[z];
            return a < b ? END_FACE : a == b ? END_VERTEX : ST_VERTEX;
        }
    }
    if (exit_edge < 0) return -1;
    *h = he[exit_edge];
    int o = sq_orient2d(corner(w, he[exit_edge]), corner(w, he[(exit_edge + 1) % 3]), w->Q);
    if (o > 0) return END_FACE;
    if (o == 0) return END_EDGE;
    cross(w, he[exit_edge]);
    return ST_FACE;
}

/* VERTEX: from corner *h, counterclockwise to the corner holding the ray
 * towards Q; returns ST_FACE (then *h is that corner) or ST_EDGE (*h is the
 * edge's halfedge), -1 if a whole turn finds none. */
static int vertex_step(walk *w, uint32_t *h)
{
    const sq_mesh *m = w->m;
    uint32_t h0 = *h, hv = h0;
    do {
        const double *o = corner(w, hv), *a = corner(w, m->he_next[hv]),
                     *b = corner(w, sq_grid_prev(m, hv));
        int s1 = sq_orient2d(o, a, w->Q);
        if (s1 > 0 && sq_orient2d(o, w->Q, b) > 0) {
            *h = hv;
            return ST_FACE;
        }
        if (s1 == 0 && along(w, a) > along(w, o)) {
            *h = hv;
            return ST_EDGE;
        }
        uint32_t hp = sq_grid_prev(m, hv);
        cross(w, hp);
        hv = m->he_twin[hp];
    } while (hv != h0);
    return -1;
}

/* The arrival slot at vertex corner hw (Q = hw's UV): the corner holding
 * the ray Q -> P, this one or the next counterclockwise. */
static uint32_t arrival_at_vertex(walk *w, const sq_grid *G, uint32_t hw)
{
    const sq_mesh *m = w->m;
    uint32_t p = G->vert_point[m->he_vert[hw]];
    if (p == SQ_NONE) return SQ_NONE;
    for (int tries = 0; tries < 2; tries++) {
        int d = sq_grid_dir_of(w->P[0] - w->Q[0], w->P[1] - w->Q[1]);
        for (uint32_t s = G->slot_off[p]; s < G->slot_off[p + 1]; s++)
            if (G->slot_he[s] == hw && G->slot_dir[s] == d) return s;
        uint32_t hp = sq_grid_prev(m, hw);
        cross(w, hp);
        hw = m->he_twin[hp];
    }
    return SQ_NONE;
}

sq_status sq_grid_trace(const sq_map *M, const sq_grid *G, uint32_t s, uint32_t *to,
                        uint32_t *steps, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint32_t p = G->slot_point[s], h = G->slot_he[s];
    walk w = {M, m, m->he_face[h], {0, 0}, {0, 0}, 0, 1.0};
    const double *P = G->kind[p] == SQ_GRID_VERTEX ? M->he_uv + 2 * (size_t)h : G->uv + 2 * (size_t)p;
    w.P[0] = P[0], w.P[1] = P[1];
    sq_grid_step(w.P, G->slot_dir[s], w.Q);
    set_axis(&w);

    int state;
    if (G->kind[p] == SQ_GRID_VERTEX) {
        state = ST_VERTEX;
    } else if (G->kind[p] == SQ_GRID_FACE) {
        state = ST_FACE;
    } else {
        const double *a = corner(&w, h), *b = corner(&w, m->he_next[h]);
        int o = sq_orient2d(a, b, w.Q);
        if (o > 0) {
            state = ST_FACE;
        } else if (o < 0) {
            cross(&w, h);
            state = ST_FACE;
        } else if (along(&w, b) > along(&w, w.P)) {
            state = ST_EDGE;
        } else {
            cross(&w, h);
            h = m->he_twin[h];
            state = ST_EDGE;
        }
    }

    uint32_t n = 0, limit = 3 * m->nh + 64;
    for (;;) {
        if (++n > limit) return fail(G, s, &w, err, "no end after crossing every face three times");
        if (state == ST_FACE) {
            state = face_step(&w, &h);
            if (state < 0) return fail(G, s, &w, err, "the segment does not cross the face");
        } else if (state == ST_VERTEX) {
            uint32_t v = m->he_vert[h];
            if (n > 1 && M->valence[v] != 4) {
                char msg[96];
                snprintf(msg, sizeof msg, "passes through the cone at vertex %u", v);
                return fail(G, s, &w, err, msg);
            }
            state = vertex_step(&w, &h);
            if (state < 0) {
                char msg[96];
                snprintf(msg, sizeof msg, "no corner at vertex %u holds the segment", v);
                return fail(G, s, &w, err, msg);
            }
        } else if (state == ST_EDGE) {
            uint32_t hn = m->he_next[h];
            double a = along(&w, w.Q), b = along(&w, corner(&w, hn));
            if (a < b) {
                state = END_EDGE;
            } else {
                h = hn;
                state = a == b ? END_VERTEX : ST_VERTEX;
            }
        } else {
            break;
        }
    }
    *steps = n;

    uint32_t q = SQ_NONE, t = SQ_NONE;
    if (state == END_VERTEX) {
        t = arrival_at_vertex(&w, G, h);
        if (t == SQ_NONE)
            return fail(G, s, &w, err, "ends at a mesh vertex that is not a grid point or has no "
                                       "direction back");
    } else {
        if (state == END_FACE) {
            q = sq_grid_find(G, SQ_GRID_FACE, w.face, w.Q);
        } else {
            uint32_t hc = h < m->he_twin[h] ? h : m->he_twin[h];
            if (hc != h) cross(&w, h);
            q = sq_grid_find(G, SQ_GRID_EDGE, hc, w.Q);
        }
        int d = sq_grid_dir_of(w.P[0] - w.Q[0], w.P[1] - w.Q[1]);
        if (q == SQ_NONE || d < 0)
            return fail(G, s, &w, err, state == END_FACE ? "its end inside the face is not a grid point"
                                                         : "its end inside an edge is not a grid point");
        t = G->slot_off[q] + (uint32_t)d;
    }
    *to = t;
    return SQ_OK;
}
