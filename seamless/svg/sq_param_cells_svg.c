/* seamquad: the picture of the cells of Omega holding bad triangles
 * (sq_param_write_cells_svg; the diagnosis: param/sq_param_cells.c), each
 * on the surface (projected on its best-fitting plane) and in UV. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_seamless_svg.h"

static const double *uv_of(const sq_param *P, uint32_t corner) { return P->uv + 2 * (size_t)P->tri_uv[corner]; }

#define CELL_PX 420.0

/* writes one panel: the faces of the cell holding face f0, drawn with
 * coordinates xy (2 per corner), scaled into a box at (x0, y0) */
static void panel(FILE *fp, const sq_param *P, const uint32_t *cell, uint32_t id, const double *xy, double x0,
                  double y0)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t f = 0; f < P->nf; f++)
        if (cell[f] == id)
            for (uint32_t k = 0; k < 3; k++)
                for (int d = 0; d < 2; d++) lo[d] = fmin(lo[d], xy[6 * (size_t)f + 2 * k + d]), hi[d] = fmax(hi[d], xy[6 * (size_t)f + 2 * k + d]);
    double big = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double s = big > 0 ? CELL_PX / big : 1;
#define PX(f, k) (x0 + (xy[6 * (size_t)(f) + 2 * (k)] - lo[0]) * s)
#define PY(f, k) (y0 + (hi[1] - xy[6 * (size_t)(f) + 2 * (k) + 1]) * s)
    for (uint32_t f = 0; f < P->nf; f++) {
        if (cell[f] != id) continue;
        fprintf(fp, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\" stroke=\"#999\" stroke-width=\"0.3\"/>\n",
                PX(f, 0), PY(f, 0), PX(f, 1), PY(f, 1), PX(f, 2), PY(f, 2), sq_param_face_bad(P, f) ? "#f77" : "#eee");
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        if (cell[f] != id) continue;
        for (uint32_t k = 0; k < 3; k++) {
            uint8_t kind = P->he_cut[3 * f + k];
            if (!kind) continue;
            fprintf(fp, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"1.6\"/>\n",
                    PX(f, k), PY(f, k), PX(f, (k + 1) % 3), PY(f, (k + 1) % 3), kind == 1 ? "black" : "#2255dd");
        }
    }
#undef PX
#undef PY
}

sq_status sq_param_write_cells_svg(const char *path, const sq_param *P, const sq_param_cell *cells,
                                   uint32_t ncells, sq_error *err)
{
    if (!path || !P || !P->he_cut) return sq_error_set(err, SQ_ERR_ARGUMENT, "cells SVG: no path or no cut kinds");
    sq_mesh m;
    sq_status st = sq_param_mesh(P, path, &m, err);
    if (st) return st;
    uint32_t *cell = malloc(((size_t)P->nf + 1) * sizeof *cell);
    double *xy3 = malloc(6 * (size_t)P->nf * sizeof *xy3), *xyu = malloc(6 * (size_t)P->nf * sizeof *xyu);
    if (!cell || !xy3 || !xyu || sq_param_label_cells(P, &m, cell) == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t c = 0; c < 3 * P->nf; c++) xyu[2 * c] = uv_of(P, c)[0], xyu[2 * c + 1] = uv_of(P, c)[1];
    sq_atomic_file af;
    st = sq_atomic_open(&af, path, err);
    if (st) goto done;
    FILE *fp = af.fp;
    double W = 2 * CELL_PX + 60, H = ncells * (CELL_PX + 70) + 40;
    fprintf(fp, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\">\n", W, H);
    fprintf(fp, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    fprintf(fp, "<text x=\"20\" y=\"22\" font-size=\"13\">cells with bad UV triangles (red): on the surface (left, "
                "projected on the cell's plane) and in UV (right); black: cut, blue: chords</text>\n");
    for (uint32_t i = 0; i < ncells; i++) {
        const sq_param_cell *C = &cells[i];
        if (C->first_bad >= P->nf) continue;
        uint32_t id = cell[C->first_bad];
        /* the cell's plane: centroid and two axes from the normal */
        double cx[3] = {0, 0, 0}, nrm[3] = {0, 0, 0};
        uint32_t cnt = 0;
        for (uint32_t f = 0; f < P->nf; f++) {
            if (cell[f] != id) continue;
            const double *a = P->pos + 3 * (size_t)P->tri[3 * f], *b = P->pos + 3 * (size_t)P->tri[3 * f + 1],
                         *c = P->pos + 3 * (size_t)P->tri[3 * f + 2];
            double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            nrm[0] += u[1] * w[2] - u[2] * w[1], nrm[1] += u[2] * w[0] - u[0] * w[2], nrm[2] += u[0] * w[1] - u[1] * w[0];
            for (int d = 0; d < 3; d++) cx[d] += a[d];
            cnt++;
        }
        double ln = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (cnt) cx[0] /= cnt, cx[1] /= cnt, cx[2] /= cnt;
        if (ln > 0) nrm[0] /= ln, nrm[1] /= ln, nrm[2] /= ln;
        else nrm[2] = 1;
        double e1[3] = {1, 0, 0};
        if (fabs(nrm[0]) > 0.9) e1[0] = 0, e1[1] = 1;
        double dt = e1[0] * nrm[0] + e1[1] * nrm[1] + e1[2] * nrm[2];
        for (int d = 0; d < 3; d++) e1[d] -= dt * nrm[d];
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        for (int d = 0; d < 3; d++) e1[d] /= l1;
        double e2[3] = {nrm[1] * e1[2] - nrm[2] * e1[1], nrm[2] * e1[0] - nrm[0] * e1[2], nrm[0] * e1[1] - nrm[1] * e1[0]};
        for (uint32_t c = 0; c < 3 * P->nf; c++) {
            if (cell[c / 3] != id) continue;
            const double *p = P->pos + 3 * (size_t)P->tri[c];
            double q[3] = {p[0] - cx[0], p[1] - cx[1], p[2] - cx[2]};
            xy3[2 * c] = q[0] * e1[0] + q[1] * e1[1] + q[2] * e1[2];
            xy3[2 * c + 1] = q[0] * e2[0] + q[1] * e2[1] + q[2] * e2[2];
        }
        double y = 40 + i * (CELL_PX + 70);
        fprintf(fp, "<text x=\"20\" y=\"%.0f\" font-size=\"12\">cell %" PRIu32 ": %" PRIu32 " of %" PRIu32
                    " triangles bad; rectangle %.6g x %.6g at (%.6g, %.6g); surface length of its sides "
                    "u=min %.3g, v=min %.3g, u=max %.3g, v=max %.3g; %" PRIu32 " runs</text>\n",
                y + 14, i, C->bad, C->faces, C->umax - C->umin, C->vmax - C->vmin, C->umin, C->vmin, C->side_len[0],
                C->side_len[1], C->side_len[2], C->side_len[3], C->runs);
        panel(fp, P, cell, id, xy3, 20, y + 30);
        panel(fp, P, cell, id, xyu, CELL_PX + 40, y + 30);
    }
    fprintf(fp, "</svg>\n");
    if (ferror(fp)) {
        sq_atomic_abort(&af);
        st = sq_error_set(err, SQ_ERR_IO, "%s: write failed", path);
        goto done;
    }
    st = sq_atomic_commit(&af, err);
done:
    sq_mesh_free(&m);
    free(cell);
    free(xy3);
    free(xyu);
    return st;
}
