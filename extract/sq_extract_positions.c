/* Step 4 of the extraction: where each grid point lies in 3D.
 *
 * A point at a mesh vertex takes the vertex's position. A point inside an
 * edge (a, b) of its chart takes the affine combination with the parameter
 * t = (X - a).(b - a) / |b - a|^2 (the point is exactly on the segment, so
 * this is its exact ratio up to rounding), clamped to [0, 1]. A point inside
 * a face takes the barycentric coordinates of its UV in the face's UV
 * triangle (ratios of signed areas, normalized to sum 1, each clamped to be
 * non-negative). Every position is thus a convex combination of the corners
 * of one triangle: on the input surface. The location (face and
 * barycentrics) is kept for later stages. */
#include <stdlib.h>

#include "sq_extract_internal.h"

static double cross2(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Index 0..2 of halfedge h in its face (from f_he[f]). */
static int corner_index(const sq_mesh *m, uint32_t h)
{
    uint32_t g = m->f_he[m->he_face[h]];
    return g == h ? 0 : m->he_next[g] == h ? 1 : 2;
}

sq_status sq_grid_positions(const sq_map *M, const sq_grid *G, sq_quad_mesh *out, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    size_t n = G->n;
    out->pos = malloc(3 * n * sizeof *out->pos);
    out->kind = malloc(n);
    out->elem = malloc(n * sizeof *out->elem);
    out->uv = malloc(2 * n * sizeof *out->uv);
    out->loc_face = malloc(n * sizeof *out->loc_face);
    out->loc_bary = malloc(3 * n * sizeof *out->loc_bary);
    if (!out->pos || !out->kind || !out->elem || !out->uv || !out->loc_face || !out->loc_bary)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quad mesh vertices)");
    for (size_t p = 0; p < n; p++) {
        const double *X = G->uv + 2 * p;
        double *bary = out->loc_bary + 3 * p;
        bary[0] = bary[1] = bary[2] = 0.0;
        out->kind[p] = G->kind[p];
        out->elem[p] = G->elem[p];
        out->uv[2 * p] = X[0];
        out->uv[2 * p + 1] = X[1];
        uint32_t f;
        if (G->kind[p] == SQ_GRID_VERTEX) {
            uint32_t h = m->v_he[G->elem[p]];
            f = m->he_face[h];
            bary[corner_index(m, h)] = 1.0;
        } else if (G->kind[p] == SQ_GRID_EDGE) {
            uint32_t h = G->elem[p];
            f = m->he_face[h];
            const double *a = M->he_uv + 2 * (size_t)h, *b = M->he_uv + 2 * (size_t)m->he_next[h];
            double ex = b[0] - a[0], ey = b[1] - a[1];
            double t = ((X[0] - a[0]) * ex + (X[1] - a[1]) * ey) / (ex * ex + ey * ey);
            t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
            bary[corner_index(m, h)] = 1.0 - t;
            bary[corner_index(m, m->he_next[h])] = t;
        } else {
            f = G->elem[p];
            uint32_t h0 = m->f_he[f], h1 = m->he_next[h0], h2 = m->he_next[h1];
            const double *a = M->he_uv + 2 * (size_t)h0, *b = M->he_uv + 2 * (size_t)h1,
                         *c = M->he_uv + 2 * (size_t)h2;
            double w[3] = {cross2(X, b, c), cross2(X, c, a), cross2(X, a, b)}, sum = 0.0;
            for (int i = 0; i < 3; i++) {
                if (!(w[i] > 0.0)) w[i] = 0.0;
                sum += w[i];
            }
            if (!(sum > 0.0))
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "grid point %zu inside face %u: no barycentric coordinates", p, f);
            for (int i = 0; i < 3; i++) bary[i] = w[i] / sum;
        }
        out->loc_face[p] = f;
        uint32_t g = m->f_he[f];
        double *x = out->pos + 3 * p;
        x[0] = x[1] = x[2] = 0.0;
        for (int i = 0; i < 3; i++, g = m->he_next[g]) {
            const double *y = m->pos + 3 * (size_t)m->he_vert[g];
            for (int k = 0; k < 3; k++) x[k] += bary[i] * y[k];
        }
        if (G->kind[p] == SQ_GRID_VERTEX) { /* exactly the vertex */
            const double *y = m->pos + 3 * (size_t)G->elem[p];
            x[0] = y[0], x[1] = y[1], x[2] = y[2];
        }
    }
    out->nv = G->n;
    return SQ_OK;
}
