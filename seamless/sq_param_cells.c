/* seamquad: diagnosis of a parametrization that failed its orientation
 * check (sq_param.h: sq_param_bad_cells, sq_param_write_cells_svg).
 *
 * The interior map (seed 8) maps every surface cell onto a rectangle of
 * Omega by Tutte's method; it can only fail in doubles, where a cell's
 * shape on the surface differs so much from its rectangle that Tutte
 * squeezes part of it below the rounding step. Showing those cells (their
 * rectangle, the surface length of each side, the picture on the surface
 * and in UV) is how such failures are understood (docs/param.md,
 * "Pictures and diagnosis").
 * The cells are recovered from the output alone: faces joined across edges
 * that are neither cut nor chord (P->he_cut), on the halfedge mesh of the
 * output's triangles (sq_param_mesh: halfedge c = corner c). */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_param.h"
#include "sq_param_internal.h"
#include "sq_predicates.h"

static const double *uv_of(const sq_param *P, uint32_t corner) { return P->uv + 2 * (size_t)P->tri_uv[corner]; }

static int face_bad(const sq_param *P, uint32_t f)
{
    return sq_orient2d(uv_of(P, 3 * f), uv_of(P, 3 * f + 1), uv_of(P, 3 * f + 2)) <= 0;
}

static int by_bad(const void *a, const void *b)
{
    const sq_param_cell *x = a, *y = b;
    return x->bad != y->bad ? (x->bad < y->bad ? 1 : -1) : (x->first_bad > y->first_bad) - (x->first_bad < y->first_bad);
}

/* which side of the cell's rectangle the UV segment p-q lies on: 0 u=umin,
 * 1 v=vmin, 2 u=umax, 3 v=vmax, 4 none */
static int side_of_segment(const sq_param_cell *C, const double *p, const double *q)
{
    if (p[0] == C->umin && q[0] == C->umin) return 0;
    if (p[1] == C->vmin && q[1] == C->vmin) return 1;
    if (p[0] == C->umax && q[0] == C->umax) return 2;
    if (p[1] == C->vmax && q[1] == C->vmax) return 3;
    return 4;
}

/* labels every face with its cell (faces joined across uncut edges);
 * returns the number of cells, or SQ_NONE when out of memory */
static uint32_t label_cells(const sq_param *P, const sq_mesh *m, uint32_t *cell)
{
    uint32_t *stack = malloc(((size_t)P->nf + 1) * sizeof *stack);
    if (!stack) return SQ_NONE;
    for (uint32_t f = 0; f < P->nf; f++) cell[f] = SQ_NONE;
    uint32_t nc = 0;
    for (uint32_t f0 = 0; f0 < P->nf; f0++) {
        if (cell[f0] != SQ_NONE) continue;
        uint32_t sp = 0;
        stack[sp++] = f0;
        cell[f0] = nc;
        while (sp) {
            uint32_t f = stack[--sp];
            for (uint32_t i = 0; i < 3; i++) {
                uint32_t c = 3 * f + i, d = m->he_twin[c];
                if (P->he_cut[c] || cell[d / 3] != SQ_NONE) continue;
                cell[d / 3] = nc;
                stack[sp++] = d / 3;
            }
        }
        nc++;
    }
    free(stack);
    return nc;
}

sq_status sq_param_bad_cells(const sq_param *P, sq_param_cell *cells, uint32_t max, uint32_t *n,
                             sq_error *err)
{
    *n = 0;
    if (!P || !P->he_cut || !P->tri || !P->tri_uv || !P->uv || !P->pos)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "bad cells: the parametrization has no cut kinds");
    sq_mesh m;
    sq_status st = sq_param_mesh(P, "bad cells", &m, err);
    if (st) return st;
    uint32_t *cell = malloc(((size_t)P->nf + 1) * sizeof *cell);
    sq_param_cell *all = NULL;
    uint32_t nc = cell ? label_cells(P, &m, cell) : SQ_NONE;
    if (nc != SQ_NONE) all = calloc((size_t)nc + 1, sizeof *all);
    if (nc == SQ_NONE || !all) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t i = 0; i < nc; i++) {
        all[i].umin = all[i].vmin = INFINITY, all[i].umax = all[i].vmax = -INFINITY;
        all[i].first_bad = SQ_NONE;
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        sq_param_cell *C = &all[cell[f]];
        C->faces++;
        if (face_bad(P, f)) {
            if (!C->bad) C->first_bad = f;
            C->bad++;
        }
        /* the rectangle from the cell's boundary only: inner vertices of
         * a failed map may lie outside it */
        for (uint32_t i = 0; i < 3; i++) {
            if (!P->he_cut[3 * f + i]) continue;
            const double *p = uv_of(P, 3 * f + i), *q = uv_of(P, 3 * f + (i + 1) % 3);
            C->umin = fmin(C->umin, fmin(p[0], q[0])), C->umax = fmax(C->umax, fmax(p[0], q[0]));
            C->vmin = fmin(C->vmin, fmin(p[1], q[1])), C->vmax = fmax(C->vmax, fmax(p[1], q[1]));
        }
    }
    /* boundary lengths per side, and the runs of one side in boundary
     * order (walk each cell's boundary: from a boundary corner, the next
     * boundary edge turns around the head vertex inside the cell) */
    for (uint32_t f = 0; f < P->nf; f++)
        for (uint32_t i = 0; i < 3; i++) {
            uint32_t c = 3 * f + i;
            if (!P->he_cut[c]) continue;
            sq_param_cell *C = &all[cell[f]];
            uint32_t cn = m.he_next[c];
            const double *a = P->pos + 3 * (size_t)P->tri[c], *b = P->pos + 3 * (size_t)P->tri[cn];
            double len = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            int sd = side_of_segment(C, uv_of(P, c), uv_of(P, cn));
            if (sd < 4) C->side_len[sd] += len;
            else C->other_len += len;
            /* the next boundary edge of the cell: around the head, inside
             * the cell, counterclockwise from the edge's end */
            uint32_t g = cn, guard = 0;
            int sd2 = 4;
            while (guard++ < 1000) {
                if (P->he_cut[g]) {
                    sd2 = side_of_segment(C, uv_of(P, g), uv_of(P, m.he_next[g]));
                    break;
                }
                g = m.he_next[m.he_twin[g]]; /* the next edge out of the head, one face on */
            }
            if (sd2 != sd) C->runs++;
        }
    uint32_t nbad = 0;
    for (uint32_t i = 0; i < nc; i++)
        if (all[i].bad) all[nbad++] = all[i];
    qsort(all, nbad, sizeof *all, by_bad);
    for (uint32_t i = 0; i < nbad && i < max; i++) cells[i] = all[i];
    *n = nbad;
done:
    sq_mesh_free(&m);
    free(cell);
    free(all);
    return st;
}

/* ---- picture ------------------------------------------------------------ */

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
                PX(f, 0), PY(f, 0), PX(f, 1), PY(f, 1), PX(f, 2), PY(f, 2), face_bad(P, f) ? "#f77" : "#eee");
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
    if (!cell || !xy3 || !xyu || label_cells(P, &m, cell) == SQ_NONE) {
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
