/* seamquad: diagnosis of a parametrization that failed its orientation
 * check (sq_param.h: sq_param_bad_cells; its picture: svg/sq_param_cells_svg.c).
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

int sq_param_face_bad(const sq_param *P, uint32_t f)
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

uint32_t sq_param_label_cells(const sq_param *P, const sq_mesh *m, uint32_t *cell)
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
    uint32_t nc = cell ? sq_param_label_cells(P, &m, cell) : SQ_NONE;
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
        if (sq_param_face_bad(P, f)) {
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
