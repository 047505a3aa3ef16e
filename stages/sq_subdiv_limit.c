/* seamquad: the Catmull-Clark limit surface sampled as a watertight quad
 * mesh, positions and normals evaluated on the limit surface (OpenSubdiv
 * patches), and its OBJ writer. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_subdiv.h"

void sq_limit_mesh_free(sq_limit_mesh *lm)
{
    if (!lm) return;
    free(lm->pos);
    free(lm->nrm);
    free(lm->quads);
    memset(lm, 0, sizeof *lm);
}

/* (u, v) of the point at parameter t along side k (corner k to k+1). */
static void side_param(uint32_t k, double t, double *u, double *v)
{
    switch (k) {
    case 0: *u = t; *v = 0.0; break;
    case 1: *u = 1.0; *v = t; break;
    case 2: *u = 1.0 - t; *v = 1.0; break;
    default: *u = 0.0; *v = 1.0 - t; break;
    }
}

sq_status sq_subdiv_limit_mesh(const sq_subdiv *s, const sq_mesh *m, int level,
                               sq_limit_mesh *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (level < 0 || level > 8)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "limit mesh level %d outside 0..8", level);
    if (m->nf != s->nf) return sq_error_set(err, SQ_ERR_ARGUMENT, "mesh and surface differ");
    const uint32_t n = 1u << level; /* segments per base edge */
    const uint64_t ne = m->nh / 2;
    const uint64_t nv = (uint64_t)m->nv + ne * (n - 1) + (uint64_t)m->nf * (n - 1) * (n - 1);
    const uint64_t nq = (uint64_t)m->nf * n * n;
    if (nv > UINT32_MAX || 4 * nq > UINT32_MAX)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "limit mesh level %d too fine: %llu quads",
                            level, (unsigned long long)nq);
    /* Edge numbering: the halfedge h < twin(h) owns the edge. */
    uint32_t *edge_of = malloc((size_t)m->nh * sizeof *edge_of);
    uint32_t *grid = malloc((size_t)(n + 1) * (n + 1) * sizeof *grid);
    out->pos = malloc(3 * nv * sizeof *out->pos);
    out->nrm = malloc(3 * nv * sizeof *out->nrm);
    out->quads = malloc(4 * nq * sizeof *out->quads);
    if (!edge_of || !grid || !out->pos || !out->nrm || !out->quads) {
        free(edge_of);
        free(grid);
        sq_limit_mesh_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for a %llu-quad limit mesh",
                            (unsigned long long)nq);
    }
    out->nv = (uint32_t)nv;
    out->nq = (uint32_t)nq;
    uint32_t ecount = 0;
    for (uint32_t h = 0; h < m->nh; h++)
        if (h < m->he_twin[h]) edge_of[h] = edge_of[m->he_twin[h]] = ecount++;
    const uint32_t ebase = m->nv, fbase = m->nv + ecount * (n - 1);
    /* Base vertices: evaluated from the face of their outgoing halfedge. */
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h = m->v_he[v], f = m->he_face[h], k = h - 4 * f;
        double u, w;
        side_param(k, 0.0, &u, &w);
        sq_subdiv_eval(s, f, u, w, out->pos + 3 * (size_t)v, out->nrm + 3 * (size_t)v);
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        /* grid[i + (n+1)*j]: vertex at (u, v) = (i/n, j/n) */
        for (uint32_t k = 0; k < 4; k++) {
            uint32_t h = 4 * f + k, e = edge_of[h], owner = h < m->he_twin[h];
            for (uint32_t a = 0; a <= n; a++) {
                uint32_t i, j;
                switch (k) {
                case 0: i = a; j = 0; break;
                case 1: i = n; j = a; break;
                case 2: i = n - a; j = n; break;
                default: i = 0; j = n - a; break;
                }
                uint32_t id;
                if (a == 0) id = m->he_vert[h];
                else if (a == n) id = m->he_vert[m->he_next[h]];
                else id = ebase + e * (n - 1) + (owner ? a : n - a) - 1;
                grid[i + (n + 1) * j] = id;
                if (owner && a > 0 && a < n) {
                    double u, w;
                    side_param(k, (double)a / n, &u, &w);
                    sq_subdiv_eval(s, f, u, w, out->pos + 3 * (size_t)id, out->nrm + 3 * (size_t)id);
                }
            }
        }
        for (uint32_t j = 1; j < n; j++)
            for (uint32_t i = 1; i < n; i++) {
                uint32_t id = fbase + f * (n - 1) * (n - 1) + (j - 1) * (n - 1) + (i - 1);
                grid[i + (n + 1) * j] = id;
                sq_subdiv_eval(s, f, (double)i / n, (double)j / n, out->pos + 3 * (size_t)id,
                               out->nrm + 3 * (size_t)id);
            }
        for (uint32_t j = 0; j < n; j++)
            for (uint32_t i = 0; i < n; i++) {
                uint32_t *q = out->quads + 4 * ((size_t)f * n * n + (size_t)j * n + i);
                q[0] = grid[i + (n + 1) * j];
                q[1] = grid[i + 1 + (n + 1) * j];
                q[2] = grid[i + 1 + (n + 1) * (j + 1)];
                q[3] = grid[i + (n + 1) * (j + 1)];
            }
    }
    free(edge_of);
    free(grid);
    return SQ_OK;
}

sq_status sq_limit_mesh_write_obj(const char *path, const sq_limit_mesh *lm, sq_error *err)
{
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *fp = af.fp;
    fprintf(fp, "# seamquad: Catmull-Clark limit surface, %u vertices, %u quads\n", lm->nv, lm->nq);
    for (uint32_t v = 0; v < lm->nv; v++) {
        const double *p = lm->pos + 3 * (size_t)v;
        fprintf(fp, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    for (uint32_t v = 0; v < lm->nv; v++) {
        const double *p = lm->nrm + 3 * (size_t)v;
        fprintf(fp, "vn %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    for (uint32_t q = 0; q < lm->nq; q++) {
        const uint32_t *c = lm->quads + 4 * (size_t)q;
        fprintf(fp, "f %u//%u %u//%u %u//%u %u//%u\n", c[0] + 1, c[0] + 1, c[1] + 1, c[1] + 1,
                c[2] + 1, c[2] + 1, c[3] + 1, c[3] + 1);
    }
    if (ferror(fp)) {
        sq_atomic_abort(&af);
        return sq_error_set(err, SQ_ERR_IO, "%s: write failed", path);
    }
    return sq_atomic_commit(&af, err);
}
