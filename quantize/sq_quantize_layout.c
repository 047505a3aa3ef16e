/* seamquad: the T-mesh of a split map read off its chords
 * (sq_quantize_internal.h).
 *
 *  1. Patches: the split triangles joined across edges off the chords
 *     (union-find). Each patch is unfolded from a seed triangle across its
 *     edges: a triangle's chart map composes the transitions of the mesh
 *     edges crossed (exact: rotations and grid translations); a triangle
 *     reached twice must get the same map, since the patch is a flat disk.
 *  2. Boundary: the chord halfedges of a patch form one loop (counter-
 *     clockwise, the patch on the left); every boundary edge runs along
 *     +u, +v, -u or -v of the patch's chart, and the loop must turn left
 *     exactly four times and never right: a rectangle. Its lower-left
 *     corner starts the bottom (+u); the local frame puts it at (0, 0).
 *  3. Nodes: cones, vertices on three or more chord edges, corners. Arcs:
 *     chains of chord edges between nodes.
 *  4. Sides: each patch's four runs as arc lists, in the layout of
 *     sq_tmesh_lengths.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"
#include "sq_quantize_internal.h"
#include "sq_union_find.h"

typedef struct xf {
    int r;
    double t[2];
} xf;

/* x -> B(A(x)) */
static xf xf_then(xf A, xf B)
{
    xf o;
    double Rt[2];
    o.r = (A.r + B.r) & 3;
    sq_map_rotate(B.r, A.t, Rt);
    o.t[0] = Rt[0] + B.t[0], o.t[1] = Rt[1] + B.t[1];
    return o;
}

static void xf_apply(xf A, const double *p, double *out)
{
    double q[2];
    sq_map_rotate(A.r, p, q);
    out[0] = q[0] + A.t[0], out[1] = q[1] + A.t[1];
}

void sq_qlayout_free(sq_qlayout *L)
{
    if (!L) return;
    free(L->tri_patch), free(L->tri_rot), free(L->tri_shift), free(L->W), free(L->H);
    free(L->corner_he), free(L->v_node), free(L->he_arc), free(L->he_fwd), free(L->he_pos);
    free(L->arc_nv), free(L->arc_end), free(L->arc_len), free(L->arc_len3d), free(L->arc_dist), free(L->arc_off);
    free(L->side_off), free(L->side_arc), free(L->side_rev);
    memset(L, 0, sizeof *L);
}

/* The mesh halfedge of face f whose twin lies in face g (the edge a split
 * edge between the two faces lies on; two triangles of a closed manifold
 * mesh share at most one edge unless they are a degenerate pair). */
static uint32_t mesh_edge(const sq_mesh *m, uint32_t f, uint32_t g)
{
    uint32_t h = m->f_he[f];
    for (int k = 0; k < 3; k++, h = m->he_next[h])
        if (m->he_face[m->he_twin[h]] == g) return h;
    return UINT32_MAX;
}

uint32_t sq_qlayout_next_boundary(const sq_split *S, uint32_t h)
{
    const sq_mesh *m = &S->mesh;
    uint32_t g = m->he_next[h];
    uint32_t guard = 0;
    while (!S->on_chord[g] && guard++ < m->nh) g = m->he_next[m->he_twin[g]];
    return g;
}

/* Step 1: patches and their unfolding. */
static sq_status unfold(const sq_map *M, const sq_split *S, sq_qlayout *L, xf *X, sq_error *err)
{
    const sq_mesh *m = &S->mesh;
    uint32_t nt = S->nt, *par = malloc(nt * sizeof *par), *queue = malloc(nt * sizeof *queue);
    uint8_t *seen = calloc(nt, 1);
    sq_status st = SQ_OK;
    if (!par || !queue || !seen) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization patches)");
        goto done;
    }
    for (uint32_t t = 0; t < nt; t++) par[t] = t;
    for (uint32_t h = 0; h < m->nh; h++)
        if (!S->on_chord[h]) sq_uf_union(par, h / 3, m->he_twin[h] / 3);
    L->np = 0;
    for (uint32_t t = 0; t < nt; t++) queue[t] = UINT32_MAX; /* patch of each root */
    for (uint32_t t = 0; t < nt; t++) {
        uint32_t r = sq_uf_find(par, t);
        if (queue[r] == UINT32_MAX) queue[r] = L->np++;
        L->tri_patch[t] = queue[r];
    }
    /* unfold each patch by BFS from its first triangle */
    for (uint32_t t0 = 0; t0 < nt && !st; t0++) {
        if (seen[t0]) continue;
        uint32_t head = 0, tail = 0;
        queue[tail++] = t0;
        seen[t0] = 1;
        X[t0] = (xf){0, {0.0, 0.0}};
        while (head < tail && !st) {
            uint32_t t = queue[head++];
            for (int i = 0; i < 3; i++) {
                uint32_t h = 3 * t + i;
                if (S->on_chord[h]) continue;
                uint32_t g = m->he_twin[h], u = g / 3;
                xf Y = X[t];
                uint32_t ft = S->tri_face[t], fu = S->tri_face[u];
                if (ft != fu) {
                    uint32_t e = mesh_edge(&M->mesh, fu, ft);
                    if (e == UINT32_MAX) {
                        st = sq_error_set(err, SQ_ERR_INTERNAL,
                                          "quantization: split triangles %u and %u meet across "
                                          "mesh faces %u and %u that share no edge",
                                          t, u, ft, fu);
                        break;
                    }
                    /* u's chart -> t's chart is the transition of e (fu -> ft) */
                    xf T = {M->he_rot[e], {M->he_t[2 * (size_t)e], M->he_t[2 * (size_t)e + 1]}};
                    Y = xf_then(T, X[t]);
                }
                if (seen[u]) {
                    if (Y.r != X[u].r || Y.t[0] != X[u].t[0] || Y.t[1] != X[u].t[1])
                        st = sq_error_set(err, SQ_ERR_INTERNAL,
                                          "quantization: patch %u does not unfold consistently "
                                          "(split triangle %u)",
                                          L->tri_patch[t], u);
                    continue;
                }
                seen[u] = 1;
                X[u] = Y;
                queue[tail++] = u;
            }
        }
    }
done:
    free(par), free(queue), free(seen);
    return st;
}

/* Corner UV of split halfedge h (its origin) in its patch's chart X. */
static void patch_uv(const sq_split *S, const xf *X, uint32_t h, double out[2])
{
    xf_apply(X[h / 3], S->uv + 2 * (size_t)h, out);
}

/* The line a boundary halfedge lies on, in its patch's chart: axis 0
 * (u = c) or 1 (v = c), from the coordinates its two ends hold exactly (a
 * chart rotation by an odd multiple of 90 degrees swaps them). */
static int boundary_line(const sq_split *S, const xf *X, uint32_t h, double *c)
{
    uint32_t t = h / 3, i = h % 3, j = (i + 1) % 3;
    double p[2], q[2];
    patch_uv(S, X, h, p);
    patch_uv(S, X, 3 * t + j, q);
    uint8_t ep = S->uv_exact[3 * t + i], eq = S->uv_exact[3 * t + j];
    if (X[t].r & 1) {
        ep = (uint8_t)(((ep & 1) << 1) | ((ep & 2) >> 1));
        eq = (uint8_t)(((eq & 1) << 1) | ((eq & 2) >> 1));
    }
    int vert = (ep & SQ_SPLIT_U_EXACT) && (eq & SQ_SPLIT_U_EXACT) && p[0] == q[0];
    int horiz = (ep & SQ_SPLIT_V_EXACT) && (eq & SQ_SPLIT_V_EXACT) && p[1] == q[1];
    if (vert == horiz) return -1;
    *c = vert ? p[0] : p[1];
    return vert ? 0 : 1;
}

/* Step 2: boundary loops, their four runs, local frames. */
static sq_status frames(const sq_split *S, sq_qlayout *L, xf *X, sq_error *err)
{
    const sq_mesh *m = &S->mesh;
    uint32_t *first = malloc(L->np * sizeof *first);
    uint32_t *loops = calloc(L->np, sizeof *loops);
    uint8_t *visited = calloc(m->nh, 1);
    uint32_t cap = 256, *loop = malloc(cap * sizeof *loop);
    sq_status st = SQ_OK;
    if (!first || !loops || !visited || !loop) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization patches)");
        goto done;
    }
    for (uint32_t p = 0; p < L->np; p++) first[p] = UINT32_MAX;
    for (uint32_t h = 0; h < m->nh; h++) {
        if (!S->on_chord[h] || visited[h]) continue;
        uint32_t p = L->tri_patch[h / 3];
        loops[p]++;
        uint32_t g = h;
        do {
            visited[g] = 1;
            g = sq_qlayout_next_boundary(S, g);
        } while (g != h && !visited[g]);
        if (g != h) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "quantization: patch %u's boundary does not close", p);
            goto done;
        }
        if (first[p] == UINT32_MAX) first[p] = h;
    }
    for (uint32_t p = 0; p < L->np && !st; p++) {
        if (loops[p] != 1) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "quantization: T-mesh face %u has %u boundary loops (a disk has 1): "
                              "the traces do not cut the surface into rectangles",
                              p, loops[p]);
            break;
        }
        /* the loop and each halfedge's line */
        uint32_t n = 0, h = first[p];
        do {
            if (n == cap) {
                uint32_t *g = realloc(loop, 2 * cap * sizeof *loop);
                if (!g) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization patches)");
                    goto done;
                }
                loop = g, cap *= 2;
            }
            loop[n++] = h;
            h = sq_qlayout_next_boundary(S, h);
        } while (h != first[p]);
        int axis_prev = -1;
        double c_prev = 0;
        uint32_t runs = 0, start[5] = {0, 0, 0, 0, 0};
        {
            double c;
            int ax = boundary_line(S, X, loop[n - 1], &c);
            axis_prev = ax, c_prev = c;
        }
        for (uint32_t k = 0; k < n && !st; k++) {
            double c;
            int ax = boundary_line(S, X, loop[k], &c);
            if (ax < 0) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "quantization: T-mesh face %u: a boundary edge at vertex %u lies "
                                  "on no iso-line",
                                  p, m->he_vert[loop[k]]);
                break;
            }
            if (ax != axis_prev || c != c_prev) {
                if (runs < 4) start[runs] = k;
                runs++;
            }
            axis_prev = ax, c_prev = c;
        }
        if (st) break;
        if (runs != 4) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "quantization: T-mesh face %u is not a rectangle: its boundary "
                              "runs along %u iso-lines",
                              p, runs);
            break;
        }
        start[4] = start[0] + n;
        /* each run's direction (0 +u, 1 +v, 2 -u, 3 -v) from its ends */
        int dir[4], bottom = -1;
        for (int r = 0; r < 4; r++) {
            uint32_t a = loop[start[r] % n], b = loop[(start[r + 1] - 1) % n];
            double pa[2], pb[2];
            patch_uv(S, X, a, pa);
            patch_uv(S, X, 3 * (b / 3) + (b % 3 + 1) % 3, pb);
            double c;
            int ax = boundary_line(S, X, a, &c);
            double d = ax == 0 ? pb[1] - pa[1] : pb[0] - pa[0];
            dir[r] = ax == 0 ? (d > 0 ? 1 : 3) : (d > 0 ? 0 : 2);
            if (dir[r] == 0) bottom = r;
        }
        int ok = bottom >= 0;
        for (int r = 0; r < 4 && ok; r++) ok = dir[(bottom + r) % 4] == r;
        if (!ok) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "quantization: T-mesh face %u is not a rectangle: its sides turn "
                              "%d, %d, %d, %d",
                              p, dir[0], dir[1], dir[2], dir[3]);
            break;
        }
        for (int r = 0; r < 4; r++) {
            uint32_t hc = loop[start[(bottom + r) % 4] % n];
            L->corner_he[4 * (size_t)p + r] = hc;
            L->v_node[m->he_vert[hc]] = 1;
        }
        double o[2], r1[2], r2[2];
        patch_uv(S, X, L->corner_he[4 * (size_t)p + 0], o);
        patch_uv(S, X, L->corner_he[4 * (size_t)p + 1], r1);
        patch_uv(S, X, L->corner_he[4 * (size_t)p + 2], r2);
        L->W[p] = r1[0] - o[0];
        L->H[p] = r2[1] - r1[1];
        if (!(L->W[p] > 0) || !(L->H[p] > 0)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "quantization: T-mesh face %u has no area", p);
            break;
        }
    }
done:
    free(first), free(loops), free(visited), free(loop);
    return st;
}

sq_status sq_qlayout_build(const sq_map *M, const sq_split *S, sq_qlayout *L, sq_error *err)
{
    memset(L, 0, sizeof *L);
    const sq_mesh *m = &S->mesh;
    sq_status st = SQ_OK;
    xf *X = malloc(((size_t)S->nt + 1) * sizeof *X);
    L->tri_patch = malloc(((size_t)S->nt + 1) * sizeof *L->tri_patch);
    L->tri_rot = malloc((size_t)S->nt + 1);
    L->tri_shift = malloc(2 * ((size_t)S->nt + 1) * sizeof *L->tri_shift);
    L->v_node = calloc(S->nv, 1);
    L->he_arc = malloc(m->nh * sizeof *L->he_arc);
    L->he_fwd = calloc(m->nh, 1);
    L->he_pos = malloc(m->nh * sizeof *L->he_pos);
    if (!X || !L->tri_patch || !L->tri_rot || !L->tri_shift || !L->v_node || !L->he_arc ||
        !L->he_fwd || !L->he_pos) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
        goto done;
    }
    if ((st = unfold(M, S, L, X, err))) goto done;
    L->W = malloc(L->np * sizeof *L->W);
    L->H = malloc(L->np * sizeof *L->H);
    L->corner_he = malloc(4 * (size_t)L->np * sizeof *L->corner_he);
    if (!L->W || !L->H || !L->corner_he) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
        goto done;
    }
    if ((st = frames(S, L, X, err))) goto done;
    /* local frames: X_t followed by the shift of the patch's corner */
    for (uint32_t t = 0; t < S->nt; t++) {
        uint32_t p = L->tri_patch[t];
        double o[2];
        patch_uv(S, X, L->corner_he[4 * (size_t)p], o);
        L->tri_rot[t] = (uint8_t)X[t].r;
        L->tri_shift[2 * (size_t)t] = X[t].t[0] - o[0];
        L->tri_shift[2 * (size_t)t + 1] = X[t].t[1] - o[1];
    }
    /* Step 3: nodes and arcs */
    {
        uint32_t *deg = calloc(S->nv, sizeof *deg);
        if (!deg) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
            goto done;
        }
        for (uint32_t h = 0; h < m->nh; h++) deg[m->he_vert[h]] += S->on_chord[h];
        for (uint32_t v = 0; v < S->nv; v++)
            if ((deg[v] && deg[v] != 2) || (v < M->mesh.nv && M->valence[v] != 4 && deg[v])) L->v_node[v] = 1;
        free(deg);
    }
    for (uint32_t h = 0; h < m->nh; h++) L->he_arc[h] = UINT32_MAX;
    uint32_t cap = 64, dist_cap = 256, dist_n = 0;
    L->arc_nv = malloc(cap * sizeof *L->arc_nv);
    L->arc_end = malloc(2 * cap * sizeof *L->arc_end);
    L->arc_len = malloc(cap * sizeof *L->arc_len);
    L->arc_len3d = malloc(cap * sizeof *L->arc_len3d);
    L->arc_off = malloc((cap + 1) * sizeof *L->arc_off);
    L->arc_dist = malloc(dist_cap * sizeof *L->arc_dist);
    if (!L->arc_nv || !L->arc_end || !L->arc_len || !L->arc_len3d || !L->arc_off || !L->arc_dist) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
        goto done;
    }
    for (int pass = 0; pass < 2 && !st; pass++)
        for (uint32_t h0 = 0; h0 < m->nh && !st; h0++) {
            if (!S->on_chord[h0] || L->he_arc[h0] != UINT32_MAX) continue;
            if (pass == 0 && !L->v_node[m->he_vert[h0]]) continue;
            if (pass == 1) L->v_node[m->he_vert[h0]] = 1; /* a closed chain */
            if (L->na + 1 >= cap) {
                cap *= 2;
                void *a = realloc(L->arc_nv, cap * sizeof *L->arc_nv), *b = NULL, *c = NULL, *d = NULL;
                void *e = realloc(L->arc_end, 2 * cap * sizeof *L->arc_end);
                if (e) L->arc_end = e;
                if (a && e) L->arc_nv = a, b = realloc(L->arc_len, cap * sizeof *L->arc_len);
                if (b) L->arc_len = b, c = realloc(L->arc_len3d, cap * sizeof *L->arc_len3d);
                if (c) L->arc_len3d = c, d = realloc(L->arc_off, (cap + 1) * sizeof *L->arc_off);
                if (!d) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
                    break;
                }
                L->arc_off = d;
            }
            uint32_t a = L->na++, h = h0, pos = 0;
            L->arc_end[2 * (size_t)a] = m->he_vert[h0];
            double len = 0, len3 = 0;
            L->arc_off[a] = dist_n;
            for (;;) {
                if (dist_n + 2 >= dist_cap) {
                    dist_cap *= 2;
                    double *d = realloc(L->arc_dist, dist_cap * sizeof *d);
                    if (!d) {
                        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
                        break;
                    }
                    L->arc_dist = d;
                }
                uint32_t g = m->he_twin[h];
                L->he_arc[h] = L->he_arc[g] = a;
                L->he_fwd[h] = 1, L->he_fwd[g] = 0;
                L->he_pos[h] = pos;
                L->arc_dist[dist_n++] = len;
                const double *p = S->uv + 2 * (size_t)h, *q = S->uv + 2 * (size_t)(3 * (h / 3) + (h % 3 + 1) % 3);
                len += hypot(q[0] - p[0], q[1] - p[1]);
                const double *P = S->pos + 3 * (size_t)m->he_vert[h], *Q = S->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
                len3 += sqrt((Q[0] - P[0]) * (Q[0] - P[0]) + (Q[1] - P[1]) * (Q[1] - P[1]) + (Q[2] - P[2]) * (Q[2] - P[2]));
                pos++;
                uint32_t v = m->he_vert[m->he_next[h]];
                if (L->v_node[v]) break;
                /* the other chord edge out of v */
                uint32_t k = m->he_next[h], next = UINT32_MAX, guard = 0;
                do {
                    if (S->on_chord[k] && k != g) next = k;
                    k = m->he_twin[m->he_next[m->he_next[k]]];
                } while (k != m->he_next[h] && guard++ < m->nh);
                if (next == UINT32_MAX || L->he_arc[next] != UINT32_MAX) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL,
                                      "quantization: the chord through vertex %u does not continue", v);
                    break;
                }
                h = next;
            }
            if (st) break;
            L->arc_dist[dist_n++] = len; /* the last node */
            L->arc_end[2 * (size_t)a + 1] = m->he_vert[m->he_next[h]];
            L->arc_nv[a] = pos + 1;
            L->arc_len[a] = len;
            L->arc_len3d[a] = len3;
        }
    if (st) goto done;
    L->arc_off[L->na] = dist_n;
    /* the twins' positions: the origin of the twin of a forward halfedge at
     * position i is the vertex at position i + 1 */
    for (uint32_t h = 0; h < m->nh; h++)
        if (S->on_chord[h] && L->he_fwd[h]) L->he_pos[m->he_twin[h]] = L->he_pos[h] + 1;
    /* Step 4: sides */
    L->side_off = malloc((4 * (size_t)L->np + 1) * sizeof *L->side_off);
    L->side_arc = malloc((2 * (size_t)L->na + 4 * (size_t)L->np + 1) * sizeof *L->side_arc);
    L->side_rev = malloc(2 * (size_t)L->na + 4 * (size_t)L->np + 1);
    if (!L->side_off || !L->side_arc || !L->side_rev) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization layout)");
        goto done;
    }
    uint32_t n = 0;
    for (uint32_t p = 0; p < L->np && !st; p++)
        for (int s = 0; s < 4; s++) {
            L->side_off[4 * (size_t)p + s] = n;
            uint32_t h = L->corner_he[4 * (size_t)p + s], end = L->corner_he[4 * (size_t)p + (s + 1) % 4];
            uint32_t last = UINT32_MAX;
            do {
                uint32_t a = L->he_arc[h];
                if (a != last || L->v_node[m->he_vert[h]]) {
                    if (n >= 2 * L->na + 4 * L->np) {
                        st = sq_error_set(err, SQ_ERR_INTERNAL, "quantization: too many side arcs");
                        break;
                    }
                    L->side_arc[n] = a;
                    L->side_rev[n] = !L->he_fwd[h];
                    n++;
                    last = a;
                }
                h = sq_qlayout_next_boundary(S, h);
            } while (h != end);
        }
    L->side_off[4 * (size_t)L->np] = n;
done:
    free(X);
    if (st) sq_qlayout_free(L);
    return st;
}

void sq_qlayout_patch_triangles(const sq_split *S, const sq_qlayout *L, uint32_t *off, uint32_t *list)
{
    memset(off, 0, ((size_t)L->np + 1) * sizeof *off);
    for (uint32_t t = 0; t < S->nt; t++) off[L->tri_patch[t] + 1]++;
    for (uint32_t p = 0; p < L->np; p++) off[p + 1] += off[p];
    for (uint32_t t = 0; t < S->nt; t++) list[off[L->tri_patch[t]]++] = t; /* off[p] now at p's end */
    for (uint32_t p = L->np; p > 0; p--) off[p] = off[p - 1];
    off[0] = 0;
}
