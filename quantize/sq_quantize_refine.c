/* seamquad: refinement chords for the T-mesh faces the embedding could not
 * place (sq_quantize_internal.h).
 *
 * Why: the sweep (sq_patch_embed.h) is piecewise linear along each side,
 * with a kink where an arc ends on it, so it is smooth only between the
 * lines through those nodes; a long thin triangle across such a line can
 * flip at any size, and inside a cell the sweep bends straight lines
 * (bilinear), which flips a triangle thinner than the bend over its
 * length. Cutting the patch's triangles along the kink lines removes the
 * first; cutting along a grid of grid x grid cells shortens every piece,
 * which removes the second once the cells are small enough. The cuts are
 * chords of sq_map_split with an empty extent: they refine the mesh (every
 * new vertex on an input triangle, so on the surface) and add no arc, so
 * the T-mesh and its integer lengths stay the same.
 *
 * Cost: O(triangles of the failed patches x their lines), then a sort of
 * all chords. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_quantize_internal.h"

typedef struct cand {
    uint32_t face;
    uint8_t axis, fresh; /* fresh: proposed now, else a chord already given */
    double c, tol;
} cand;

static int cmp_cand(const void *a, const void *b)
{
    const cand *p = a, *q = b;
    if (p->face != q->face) return (p->face > q->face) - (p->face < q->face);
    if (p->axis != q->axis) return (p->axis > q->axis) - (p->axis < q->axis);
    if (p->c != q->c) return (p->c > q->c) - (p->c < q->c);
    return (p->fresh > q->fresh) - (p->fresh < q->fresh); /* a given chord first */
}

/* corner i of split triangle t in its patch's frame */
static void local_corner(const sq_split *S, const sq_qlayout *L, uint32_t t, int i, double q[2])
{
    sq_map_rotate(L->tri_rot[t], S->uv + 6 * (size_t)t + 2 * i, q);
    q[0] += L->tri_shift[2 * (size_t)t];
    q[1] += L->tri_shift[2 * (size_t)t + 1];
}

static sq_status push(cand **v, size_t *n, size_t *cap, cand c)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 256;
        cand *g = realloc(*v, nc * sizeof *g);
        if (!g) return SQ_ERR_NOMEM;
        *v = g, *cap = nc;
    }
    (*v)[(*n)++] = c;
    return SQ_OK;
}

/* one more (axis, c) line of a patch */
static sq_status push_line(double **line, size_t *n, size_t *cap, int axis, double c)
{
    if (*n == *cap) {
        double *g = realloc(*line, 4 * *cap * sizeof *g);
        if (!g) return SQ_ERR_NOMEM;
        *line = g, *cap *= 2;
    }
    (*line)[2 * *n] = axis, (*line)[2 * *n + 1] = c, ++*n;
    return SQ_OK;
}

sq_status sq_qlayout_refine_chords(const sq_split *S, const sq_qlayout *L, const uint8_t *failed,
                                   uint32_t grid, sq_chord **chords, uint32_t *n, uint32_t *cap,
                                   sq_error *err)
{
    const sq_mesh *m = &S->mesh;
    sq_status st = SQ_OK;
    uint32_t *tri_off = malloc(((size_t)L->np + 1) * sizeof *tri_off);
    uint32_t *tri_list = malloc(((size_t)S->nt + 1) * sizeof *tri_list);
    size_t nline_cap = 64, ncand = 0, cand_cap = 0;
    double *line = malloc(2 * nline_cap * sizeof *line); /* (axis, c) of one patch */
    cand *C = NULL;
    if (!tri_off || !tri_list || !line) {
        st = SQ_ERR_NOMEM;
        goto done;
    }
    sq_qlayout_patch_triangles(S, L, tri_off, tri_list);
    for (uint32_t k = 0; k < *n && !st; k++)
        st = push(&C, &ncand, &cand_cap, (cand){(*chords)[k].face, (*chords)[k].axis, 0, (*chords)[k].c, 0});
    for (uint32_t p = 0; p < L->np && !st; p++) {
        if (!failed[p]) continue;
        double W = L->W[p], H = L->H[p], tol = 1e-9 * fmax(W, H);
        size_t nl = 0;
        /* the kink lines: the nodes strictly inside each side */
        for (int s = 0; s < 4 && !st; s++) {
            uint32_t h = L->corner_he[4 * (size_t)p + s], end = L->corner_he[4 * (size_t)p + (s + 1) % 4];
            for (h = sq_qlayout_next_boundary(S, h); h != end; h = sq_qlayout_next_boundary(S, h)) {
                if (!L->v_node[m->he_vert[h]]) continue;
                double q[2];
                local_corner(S, L, h / 3, (int)(h % 3), q);
                int axis = s == 0 || s == 2 ? 0 : 1;
                if ((st = push_line(&line, &nl, &nline_cap, axis, q[axis]))) break;
            }
        }
        for (uint32_t i = 1; i < grid && !st; i++)
            for (int axis = 0; axis < 2 && !st; axis++)
                st = push_line(&line, &nl, &nline_cap, axis, (axis ? H : W) * i / grid);
        /* each line in the chart of every mesh face it crosses inside p */
        for (uint32_t k = tri_off[p]; k < tri_off[p + 1] && !st; k++) {
            uint32_t t = tri_list[k];
            double q[3][2];
            for (int i = 0; i < 3; i++) local_corner(S, L, t, i, q[i]);
            int r = L->tri_rot[t];
            for (size_t j = 0; j < nl && !st; j++) {
                int a = (int)line[2 * j];
                double c = line[2 * j + 1];
                double lo = fmin(q[0][a], fmin(q[1][a], q[2][a])), hi = fmax(q[0][a], fmax(q[1][a], q[2][a]));
                if (!(c > lo && c < hi)) continue;
                /* local_a = sgn p_ax + shift_a with ax the chart axis that
                 * the rotation takes to local axis a */
                int ax = a ^ (r & 1);
                double e[2] = {ax == 0, ax == 1}, d[2];
                sq_map_rotate(r, e, d);
                double sgn = d[a] > 0 ? 1.0 : -1.0;
                double cc = sgn * (c - L->tri_shift[2 * (size_t)t + a]);
                st = push(&C, &ncand, &cand_cap, (cand){S->tri_face[t], (uint8_t)ax, 1, cc, tol});
            }
        }
    }
    if (st) goto done;
    qsort(C, ncand, sizeof *C, cmp_cand);
    /* keep a fresh line unless a kept one of its face and axis is within
     * its tolerance: looking back at the last kept, ahead at the next
     * given chord */
    {
        size_t g0 = 0;
        while (g0 < ncand && !st) {
            size_t g1 = g0;
            while (g1 < ncand && C[g1].face == C[g0].face && C[g1].axis == C[g0].axis) g1++;
            double last = -INFINITY, next = INFINITY;
            for (size_t i = g0; i < g1 && !st; i++) {
                if (!C[i].fresh) {
                    last = C[i].c;
                    continue;
                }
                next = INFINITY;
                for (size_t j = i + 1; j < g1; j++)
                    if (!C[j].fresh) {
                        next = C[j].c;
                        break;
                    }
                if (C[i].c - last <= C[i].tol || next - C[i].c <= C[i].tol) continue;
                last = C[i].c;
                if (*n == *cap) {
                    uint32_t nc = *cap ? 2 * *cap : 256;
                    sq_chord *g = realloc(*chords, (size_t)nc * sizeof *g);
                    if (!g) {
                        st = SQ_ERR_NOMEM;
                        break;
                    }
                    *chords = g, *cap = nc;
                }
                (*chords)[(*n)++] = (sq_chord){C[i].face, C[i].axis, C[i].c, INFINITY, -INFINITY};
            }
            g0 = g1;
        }
    }
done:
    free(tri_off), free(tri_list), free(line), free(C);
    if (st == SQ_ERR_NOMEM) return sq_error_set(err, st, "out of memory (quantization refinement)");
    return st;
}
