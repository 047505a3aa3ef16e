/* seamquad: making a seamless map exact by snapping to a dyadic grid.
 *
 * A published map is seamless only up to rounding (about 1e-13 of its
 * size): its seams are rotations by k * 90 degrees plus translations that
 * hold to the last bits. The T-mesh and the quantization decide everything
 * exactly, so they need transitions that hold exactly in doubles. This step
 * moves every UV by at most a few units of a grid h = 2^e (about 2^-40 of
 * the UV diagonal) so that they do:
 *
 *  1. Seam curves: maximal chains of seam edges between nodes (cones,
 *     vertices on one or three or more seam edges; a closed chain without
 *     any gets one of its vertices as a node). One rotation per curve (all
 *     its edges must agree) and one translation t_c, the mean over its
 *     edges, rounded to the grid.
 *  2. Around a node the transitions of the curves it meets compose to
 *     x -> R x + T. If R is not the identity (a cone of valence 1, 2 or 3
 *     mod 4) the node's UV is the fixed point (I - R)^-1 T: exact, on the
 *     grid h/2. If R = I the composition must be the identity: T = 0. The
 *     rounded t_c need not give that, so in each component of the graph of
 *     nodes and curves, a spanning tree rooted at a node with R != I (if
 *     there is one) is walked from the leaves: each node with R = I gets
 *     T = 0 exactly by a change of the translation of the curve to its
 *     parent (that curve enters its closure once, as a rotation: the change
 *     is exact). A root with R = I must close by itself; otherwise the map
 *     is refused.
 *  3. Every vertex: its first corner takes its rounded UV (or the fixed
 *     point), and the other corners follow by the transitions across the
 *     seams around it. Rotations only swap and negate; the sums stay on the
 *     grid and below 2^52 grid units, so every value is exact.
 *
 * The caller then runs sq_map_check (exact). If the rounding flipped a
 * triangle (one of area near h^2), the grid is refined (h / 256, twice)
 * before the map is refused with the triangle named.
 *
 * Cost: O(halfedges) per grid; memory: a copy of the UVs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"

typedef struct xform {
    int r;
    double t[2];
} xform;

typedef struct snap_ctx {
    sq_map *M;
    const uint8_t *seam;
    uint32_t *he_curve;   /* nh: curve of the edge, UINT32_MAX if none          */
    int8_t *he_dir;       /* nh: +1 on the curve's own side, -1 on the other   */
    uint32_t nc;          /* curves                                            */
    uint32_t *c_he;       /* nc: first halfedge on the own side                */
    uint32_t *c_end;      /* 2 nc: the curve's end nodes (vertices)            */
    int *c_rot;           /* nc                                                */
    double *c_t;          /* 2 nc                                              */
    uint8_t *node;        /* nv                                                */
} snap_ctx;

static double snap(double x, double h) { return nearbyint(x / h) * h; }

/* x -> T2(T1(x)) */
static xform compose(const xform *T2, const xform *T1)
{
    xform o;
    double Rt[2];
    o.r = (T1->r + T2->r) & 3;
    sq_map_rotate(T2->r, T1->t, Rt);
    o.t[0] = Rt[0] + T2->t[0];
    o.t[1] = Rt[1] + T2->t[1];
    return o;
}

/* The transition across halfedge e's edge, from e's face to its twin's. */
static xform edge_xform(const snap_ctx *S, uint32_t e)
{
    xform T = {0, {0.0, 0.0}};
    uint32_t c = S->he_curve[e];
    if (c == UINT32_MAX) return T;
    T.r = S->c_rot[c];
    T.t[0] = S->c_t[2 * (size_t)c];
    T.t[1] = S->c_t[2 * (size_t)c + 1];
    if (S->he_dir[e] < 0) {
        int ri;
        double ti[2];
        sq_map_inverse(T.r, T.t, &ri, ti);
        T.r = ri, T.t[0] = ti[0], T.t[1] = ti[1];
    }
    return T;
}

/* Seam degree of every vertex; nodes; curves by walking chains. */
static sq_status find_curves(snap_ctx *S, double tol_abs, sq_error *err)
{
    sq_map *M = S->M;
    const sq_mesh *m = &M->mesh;
    uint32_t *deg = calloc(m->nv, sizeof *deg);
    if (!deg) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam curves)");
    for (uint32_t h = 0; h < m->nh; h++)
        if (S->seam[h]) deg[m->he_vert[h]]++; /* each edge counted once per end */
    for (uint32_t v = 0; v < m->nv; v++)
        S->node[v] = deg[v] > 0 && (deg[v] != 2 || M->valence[v] != 4);
    free(deg);
    /* walk from nodes first, then closed chains */
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t h0 = 0; h0 < m->nh; h0++) {
            if (!S->seam[h0] || S->he_curve[h0] != UINT32_MAX) continue;
            uint32_t a = m->he_vert[h0];
            if (pass == 0 && !S->node[a]) continue;
            if (pass == 1) S->node[a] = 1;
            uint32_t c = S->nc++;
            S->c_he[c] = h0;
            S->c_rot[c] = M->he_rot[h0];
            S->c_end[2 * (size_t)c] = a;
            double sum[2] = {0.0, 0.0};
            uint32_t count = 0, h = h0;
            for (;;) {
                uint32_t g = m->he_twin[h];
                S->he_curve[h] = S->he_curve[g] = c;
                S->he_dir[h] = 1;
                S->he_dir[g] = -1;
                if (M->he_rot[h] != S->c_rot[c])
                    return sq_error_set(err, SQ_ERR_ARGUMENT,
                                        "the seam curve from vertex %u changes its rotation at "
                                        "edge (%u, %u): %d x 90 degrees, then %d x 90 degrees "
                                        "(a seam curve must use one transition)",
                                        a, m->he_vert[h], sq_map_dst(m, h), S->c_rot[c],
                                        M->he_rot[h]);
                sum[0] += M->he_t[2 * (size_t)h];
                sum[1] += M->he_t[2 * (size_t)h + 1];
                count++;
                uint32_t b = sq_map_dst(m, h);
                if (S->node[b]) {
                    S->c_end[2 * (size_t)c + 1] = b;
                    break;
                }
                /* the other seam edge out of b */
                uint32_t n = m->he_next[h], k = n, next = UINT32_MAX;
                do {
                    if (S->seam[k] && k != g) next = k;
                    k = sq_map_rotate_out(m, k);
                } while (k != n);
                if (next == UINT32_MAX || S->he_curve[next] != UINT32_MAX)
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "seam curves: vertex %u has two seam edges but its chain "
                                        "does not continue",
                                        b);
                h = next;
            }
            double t[2] = {sum[0] / count, sum[1] / count};
            S->c_t[2 * (size_t)c] = t[0];
            S->c_t[2 * (size_t)c + 1] = t[1];
            /* one translation along the curve, within the tolerance */
            h = h0;
            for (;;) {
                double d = hypot(M->he_t[2 * (size_t)h] - t[0], M->he_t[2 * (size_t)h + 1] - t[1]);
                if (!(d <= tol_abs))
                    return sq_error_set(err, SQ_ERR_ARGUMENT,
                                        "the seam curve from vertex %u changes its translation at "
                                        "edge (%u, %u) by %.3g (tolerance %.3g): a seam curve "
                                        "must use one transition",
                                        a, m->he_vert[h], sq_map_dst(m, h), d, tol_abs);
                uint32_t b = sq_map_dst(m, h);
                if (b == S->c_end[2 * (size_t)c + 1] && S->node[b]) break;
                uint32_t n = m->he_next[h], k = n, g = m->he_twin[h];
                do {
                    if (S->seam[k] && k != g) break;
                    k = sq_map_rotate_out(m, k);
                } while (k != n);
                h = k;
            }
        }
    }
    return SQ_OK;
}

/* Composition of the transitions around vertex v, starting in the chart of
 * halfedge h0 = v_he[v]. If `curve` is a curve met once there, *D_rot and
 * *D_sign describe d(T)/d(t_curve) = D_sign * R^D_rot. */
static xform around(const snap_ctx *S, uint32_t v, uint32_t curve, int *D_rot, int *D_sign)
{
    const sq_mesh *m = &S->M->mesh;
    xform A = {0, {0.0, 0.0}};
    uint32_t h0 = m->v_he[v], h = h0;
    int rot_at = 0, dir_at = 0, r_curve = 0, found = 0;
    do {
        uint32_t e = sq_map_prev(m, h);
        if (S->he_curve[e] != UINT32_MAX) {
            xform T = edge_xform(S, e);
            A = compose(&T, &A);
            if (S->he_curve[e] == curve && !found) {
                found = 1;
                rot_at = A.r; /* rotations up to and including this step */
                dir_at = S->he_dir[e];
                r_curve = S->c_rot[curve];
            }
        }
        h = sq_map_rotate_out(m, h);
    } while (h != h0);
    if (found && D_rot) {
        /* later steps rotate by A.r - rot_at; t_step = t_c (dir +1) or
         * -R^{-r_c} t_c (dir -1) */
        int after = (A.r - rot_at) & 3;
        if (dir_at > 0)
            *D_rot = after, *D_sign = 1;
        else
            *D_rot = (after - r_curve) & 3, *D_sign = -1;
    }
    return A;
}

/* Step 2: closure at every node with R = I, by the spanning trees. */
static sq_status close_nodes(snap_ctx *S, sq_error *err)
{
    const sq_mesh *m = &S->M->mesh;
    uint32_t nv = m->nv;
    uint32_t *adj_off = calloc((size_t)nv + 1, sizeof *adj_off);
    uint32_t *adj = malloc((2 * (size_t)S->nc + 1) * sizeof *adj);
    uint32_t *order = malloc((nv + 1) * sizeof *order);
    uint32_t *parent = malloc((nv + 1) * sizeof *parent);
    uint8_t *seen = calloc(nv + 1, 1);
    sq_status st = SQ_OK;
    if (!adj_off || !adj || !order || !parent || !seen) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam nodes)");
        goto done;
    }
    for (uint32_t c = 0; c < S->nc; c++) {
        uint32_t a = S->c_end[2 * (size_t)c], b = S->c_end[2 * (size_t)c + 1];
        if (a == b) continue;
        adj_off[a + 1]++, adj_off[b + 1]++;
    }
    for (uint32_t v = 0; v < nv; v++) adj_off[v + 1] += adj_off[v];
    {
        uint32_t *fill = malloc((nv + 1) * sizeof *fill);
        if (!fill) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam nodes)");
            goto done;
        }
        memcpy(fill, adj_off, nv * sizeof *fill);
        for (uint32_t c = 0; c < S->nc; c++) {
            uint32_t a = S->c_end[2 * (size_t)c], b = S->c_end[2 * (size_t)c + 1];
            if (a == b) continue;
            adj[fill[a]++] = c, adj[fill[b]++] = c;
        }
        free(fill);
    }
    /* rotation of each node's closure (depends on rotations only) */
    int *rtot = malloc(nv * sizeof *rtot);
    if (!rtot) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam nodes)");
        goto done;
    }
    for (uint32_t v = 0; v < nv; v++) rtot[v] = S->node[v] ? around(S, v, UINT32_MAX, NULL, NULL).r : 0;
    /* roots: prefer nodes with R != I; BFS */
    uint32_t no = 0;
    for (int pass = 0; pass < 2 && !st; pass++)
        for (uint32_t v0 = 0; v0 < nv; v0++) {
            if (!S->node[v0] || seen[v0]) continue;
            if (pass == 0 && rtot[v0] == 0) continue;
            uint32_t head = no;
            seen[v0] = 1;
            parent[v0] = UINT32_MAX;
            order[no++] = v0;
            while (head < no) {
                uint32_t v = order[head++];
                for (uint32_t k = adj_off[v]; k < adj_off[v + 1]; k++) {
                    uint32_t c = adj[k];
                    uint32_t w = S->c_end[2 * (size_t)c] == v ? S->c_end[2 * (size_t)c + 1]
                                                               : S->c_end[2 * (size_t)c];
                    if (seen[w]) continue;
                    seen[w] = 1;
                    parent[w] = c;
                    order[no++] = w;
                }
            }
        }
    for (uint32_t i = no; i-- > 0 && !st;) {
        uint32_t v = order[i];
        if (rtot[v] != 0) continue;
        int D_rot = 0, D_sign = 0;
        uint32_t c = parent[v];
        xform A = around(S, v, c, &D_rot, &D_sign);
        if (A.t[0] == 0.0 && A.t[1] == 0.0) continue;
        if (c == UINT32_MAX) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "the seams around vertex %u do not close: their transitions "
                              "compose to a translation by (%.3g, %.3g) instead of the identity",
                              v, A.t[0], A.t[1]);
            break;
        }
        /* t_c += delta with D delta = -T: delta = -D_sign R^{-D_rot} T */
        double d[2];
        sq_map_rotate((4 - D_rot) & 3, A.t, d);
        S->c_t[2 * (size_t)c] -= D_sign * d[0];
        S->c_t[2 * (size_t)c + 1] -= D_sign * d[1];
        A = around(S, v, UINT32_MAX, NULL, NULL);
        if (A.t[0] != 0.0 || A.t[1] != 0.0)
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "seam snapping: vertex %u still does not close (%.3g, %.3g)", v,
                              A.t[0], A.t[1]);
    }
    free(rtot);
done:
    free(adj_off);
    free(adj);
    free(order);
    free(parent);
    free(seen);
    return st;
}

/* Step 3: every corner's UV from its vertex's first corner. */
static void assign_uvs(snap_ctx *S, const double *uv0, double h)
{
    sq_map *M = S->M;
    const sq_mesh *m = &M->mesh;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], k = h0;
        double x[2];
        xform A = {0, {0.0, 0.0}};
        if (S->node[v]) A = around(S, v, UINT32_MAX, NULL, NULL);
        if (A.r == 1) {
            x[0] = 0.5 * (A.t[0] - A.t[1]), x[1] = 0.5 * (A.t[0] + A.t[1]);
        } else if (A.r == 2) {
            x[0] = 0.5 * A.t[0], x[1] = 0.5 * A.t[1];
        } else if (A.r == 3) {
            x[0] = 0.5 * (A.t[0] + A.t[1]), x[1] = 0.5 * (A.t[1] - A.t[0]);
        } else {
            x[0] = snap(uv0[2 * (size_t)h0], h), x[1] = snap(uv0[2 * (size_t)h0 + 1], h);
        }
        do {
            M->he_uv[2 * (size_t)k] = x[0];
            M->he_uv[2 * (size_t)k + 1] = x[1];
            uint32_t e = sq_map_prev(m, k);
            if (S->he_curve[e] != UINT32_MAX) {
                xform T = edge_xform(S, e);
                double y[2];
                sq_map_rotate(T.r, x, y);
                x[0] = y[0] + T.t[0], x[1] = y[1] + T.t[1];
            }
            k = sq_map_rotate_out(m, k);
        } while (k != h0);
    }
    for (uint32_t e = 0; e < m->nh; e++) {
        xform T = edge_xform(S, e);
        M->he_rot[e] = (uint8_t)T.r;
        M->he_t[2 * (size_t)e] = T.t[0];
        M->he_t[2 * (size_t)e + 1] = T.t[1];
    }
}

sq_status sq_map_snap(sq_map *M, const uint8_t *seam, double tol_abs, sq_map_report *rep,
                      sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    snap_ctx S;
    memset(&S, 0, sizeof S);
    S.M = M;
    S.seam = seam;
    S.he_curve = malloc(m->nh * sizeof *S.he_curve);
    S.he_dir = calloc(m->nh, 1);
    S.c_he = malloc((m->nh / 2 + 1) * sizeof *S.c_he);
    S.c_end = malloc((m->nh + 2) * sizeof *S.c_end);
    S.c_rot = malloc((m->nh / 2 + 1) * sizeof *S.c_rot);
    S.c_t = malloc((m->nh + 2) * sizeof *S.c_t);
    S.node = calloc(m->nv, 1);
    double *uv0 = malloc(2 * (size_t)m->nh * sizeof *uv0);
    double *t0 = malloc((m->nh + 2) * sizeof *t0);
    sq_status st = SQ_OK;
    if (!S.he_curve || !S.he_dir || !S.c_he || !S.c_end || !S.c_rot || !S.c_t || !S.node || !uv0 ||
        !t0) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (seam snapping)");
        goto done;
    }
    for (uint32_t h = 0; h < m->nh; h++) S.he_curve[h] = UINT32_MAX;
    memcpy(uv0, M->he_uv, 2 * (size_t)m->nh * sizeof *uv0);
    if ((st = find_curves(&S, tol_abs, err))) goto done;
    rep->seam_curves = S.nc;
    memcpy(t0, S.c_t, 2 * (size_t)S.nc * sizeof *t0);
    double big = 0.0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t h = 0; h < 2 * m->nh; h++) big = fmax(big, fabs(uv0[h]));
    for (uint32_t h = 0; h < m->nh; h++)
        for (int i = 0; i < 2; i++)
            lo[i] = fmin(lo[i], uv0[2 * h + i]), hi[i] = fmax(hi[i], uv0[2 * h + i]);
    double diag = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(diag > 0)) {
        st = sq_error_set(err, SQ_ERR_DEGENERATE, "the map's UV points all coincide");
        goto done;
    }
    /* grid: 2^-40 of the diagonal, coarse enough that |uv| stays below
     * 2^50 grid units (room for the sums of step 3) */
    int e = ilogb(diag) - 40, e_min = ilogb(big) - 50;
    if (e < e_min) e = e_min;
    for (int attempt = 0; attempt < 3; attempt++, e -= 8) {
        if (e < e_min) break;
        double h = ldexp(1.0, e);
        memcpy(S.c_t, t0, 2 * (size_t)S.nc * sizeof *t0);
        for (uint32_t c = 0; c < 2 * S.nc; c++) S.c_t[c] = snap(S.c_t[c], h);
        if ((st = close_nodes(&S, err))) goto done;
        assign_uvs(&S, uv0, h);
        sq_error tmp;
        st = sq_map_check(M, 0, &tmp);
        rep->grid = h;
        if (!st) break;
        if (err) *err = tmp;
    }
    if (!st) {
        uint32_t moved = 0;
        for (uint32_t i = 0; i < 2 * m->nh; i++) moved += M->he_uv[i] != uv0[i];
        rep->moved_uv = moved;
    }
done:
    free(S.he_curve);
    free(S.he_dir);
    free(S.c_he);
    free(S.c_end);
    free(S.c_rot);
    free(S.c_t);
    free(S.node);
    free(uv0);
    free(t0);
    return st;
}
