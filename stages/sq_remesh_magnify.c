/* seamquad: the magnified layouts of remesh (stage 8, docs/remesh.md):
 * where the quads of a layout pass through each other beyond repair they
 * are too large for the surface there (a thin part, a valence-22 cone's
 * wedges on a rim, a rough patch between close cones); the map is
 * optimized again drawn larger around them, so that a layout at the same
 * quad count puts smaller quads there and larger ones elsewhere. */
#include <math.h>
#include <stdlib.h>

#include "sq_remesh.h"
#include "sq_remesh_internal.h"

sq_status sq_remesh_intersecting_points(const sq_quad_mesh *Q, double *pts, uint32_t *npts, uint32_t cap,
                                        sq_error *err)
{
    uint32_t room = cap - *npts, want = room / 2 + 1;
    uint32_t *list = malloc(2 * (size_t)want * sizeof *list);
    if (!list) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (intersecting quads)");
    uint64_t pairs = 0;
    sq_status st = sq_remesh_quad_intersections(Q, &pairs, list, want, err);
    for (uint64_t i = 0; !st && i < 2 * (pairs < want ? pairs : want) && *npts < cap; i++) {
        const uint32_t *q = Q->quad + 4 * (size_t)list[i];
        double *p = pts + 3 * (size_t)*npts;
        p[0] = p[1] = p[2] = 0;
        for (int k = 0; k < 4; k++)
            for (int d = 0; d < 3; d++) p[d] += 0.25 * Q->pos[3 * (size_t)q[k] + d];
        ++*npts;
    }
    free(list);
    return st;
}

sq_status sq_remesh_magnify_map(sq_map *M, const double *pts, uint32_t npts, double radius, double factor,
                                const sq_optimize_options *base, sq_error *err)
{
    const sq_mesh *mm = &M->mesh;
    double *scale = malloc(((size_t)mm->nf + 1) * sizeof *scale);
    if (!scale) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (magnified map)");
    for (uint32_t f = 0; f < mm->nf; f++) {
        double c[3] = {0, 0, 0}, best = INFINITY;
        uint32_t h = mm->f_he[f];
        for (int k = 0; k < 3; k++, h = mm->he_next[h])
            for (int d = 0; d < 3; d++) c[d] += mm->pos[3 * (size_t)mm->he_vert[h] + d] / 3;
        for (uint32_t i = 0; i < npts; i++) {
            const double *p = pts + 3 * (size_t)i;
            double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2], d2 = dx * dx + dy * dy + dz * dz;
            if (d2 < best) best = d2;
        }
        scale[f] = 1 + (factor - 1) * exp(-best / (radius * radius));
    }
    sq_optimize_options oo = *base;
    oo.face_scale = scale;
    oo.keep_last = 1;
    oo.progress = NULL;
    sq_optimize_report r;
    sq_status st = sq_optimize_map_free_or_fixed(M, &oo, &r, err);
    free(scale);
    return st;
}
