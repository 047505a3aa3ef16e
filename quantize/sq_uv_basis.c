/* seamquad: the basis of seamless maps with fixed transitions, and the
 * basis helpers (sq_uv_basis.h).
 *
 * With rotations and translations both fixed, a vertex's corners are tied
 * to each other by the transitions across the seams around it: once one
 * corner (the first, at halfedge v_he[v]) is placed, the others follow.
 * Corner h of v, reached from the first corner by crossing seams with
 * accumulated transition x -> R^r x + t, is R^r z_v + t, where z_v is the
 * vertex's unknown point. Around a vertex that is not a cone the
 * accumulated transition returns to the identity (the map is valid), so the
 * corners agree on every edge for every z. A cone keeps its point: the
 * composition around it is a rotation about that point (valence 1, 2, 3
 * mod 4) or, for a valence that is a multiple of 4 other than 4, a point an
 * integer-grid map needs on the grid; either way it stays put.
 *
 * A map without cones (a flat torus) is only defined up to a global
 * translation: its first vertex is pinned.
 *
 * Cost: O(halfedges) time and memory; one entry per coordinate row. */
#include "sq_uv_basis.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"

void sq_uv_basis_free(sq_uv_basis *B)
{
    if (!B) return;
    free(B->row_off);
    free(B->col);
    free(B->val);
    free(B->c);
    free(B->z0);
    memset(B, 0, sizeof *B);
}

void sq_uv_basis_eval(const sq_uv_basis *B, const double *z, double *he_uv)
{
    for (uint32_t k = 0; k < B->ncoord; k++) {
        double s = B->c[k];
        for (uint32_t j = B->row_off[k]; j < B->row_off[k + 1]; j++) s += B->val[j] * z[B->col[j]];
        he_uv[k] = s;
    }
}

/* Row entries of R^r z for the unknown pair (z[i], z[i+1]): coordinate
 * `axis` of the result is sign * z[i + pick]. */
static void rotated_entry(int r, int axis, uint32_t i, uint32_t *col, double *val)
{
    /* r=0: (x, y); r=1: (-y, x); r=2: (-x, -y); r=3: (y, -x) */
    static const int pick[4][2] = {{0, 1}, {1, 0}, {0, 1}, {1, 0}};
    static const double sign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    *col = i + (uint32_t)pick[r & 3][axis];
    *val = sign[r & 3][axis];
}

sq_status sq_uv_basis_fixed_transitions(const sq_map *M, sq_uv_basis *out, sq_error *err)
{
    if (!M || !out) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_uv_basis_fixed_transitions: NULL argument");
    memset(out, 0, sizeof *out);
    const sq_mesh *m = &M->mesh;
    uint32_t cones = 0;
    for (uint32_t v = 0; v < m->nv; v++) cones += M->valence[v] != 4;
    uint32_t pinned = cones == 0 ? 0 : UINT32_MAX;
    uint32_t nfree = 0;
    for (uint32_t v = 0; v < m->nv; v++) nfree += M->valence[v] == 4 && v != pinned;
    out->nz = 2 * nfree;
    out->ncoord = 2 * m->nh;
    out->row_off = malloc(((size_t)out->ncoord + 1) * sizeof *out->row_off);
    out->col = malloc((size_t)out->ncoord * sizeof *out->col);
    out->val = malloc((size_t)out->ncoord * sizeof *out->val);
    out->c = malloc((size_t)out->ncoord * sizeof *out->c);
    out->z0 = malloc(((size_t)out->nz + 1) * sizeof *out->z0);
    int8_t *rot = malloc(m->nh);
    uint32_t *unk = malloc(m->nh * sizeof *unk);
    if (!out->row_off || !out->col || !out->val || !out->c || !out->z0 || !rot || !unk) {
        free(rot);
        free(unk);
        sq_uv_basis_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (basis of %u halfedges)", m->nh);
    }
    /* every corner: the rotation from its vertex's first corner, and the
     * vertex's unknown pair (UINT32_MAX: fixed) */
    uint32_t next = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], h = h0, u = UINT32_MAX;
        if (M->valence[v] == 4 && v != pinned) {
            u = next;
            next += 2;
            out->z0[u] = M->he_uv[2 * (size_t)h0];
            out->z0[u + 1] = M->he_uv[2 * (size_t)h0 + 1];
        }
        int r = 0;
        do {
            rot[h] = (int8_t)r;
            unk[h] = u;
            r = (r + M->he_rot[sq_map_prev(m, h)]) & 3;
            h = sq_map_rotate_out(m, h);
        } while (h != h0);
        assert(u == UINT32_MAX || r == 0);
    }
    assert(next == out->nz);
    uint32_t e = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t h0 = m->v_he[m->he_vert[h]];
        double Rp[2];
        sq_map_rotate(rot[h], M->he_uv + 2 * (size_t)h0, Rp);
        for (int a = 0; a < 2; a++) {
            size_t k = 2 * (size_t)h + a;
            out->row_off[k] = e;
            if (unk[h] == UINT32_MAX) {
                out->c[k] = M->he_uv[k];
            } else {
                rotated_entry(rot[h], a, unk[h], &out->col[e], &out->val[e]);
                e++;
                out->c[k] = M->he_uv[k] - Rp[a];
            }
        }
    }
    out->row_off[out->ncoord] = e;
    free(rot);
    free(unk);
    return SQ_OK;
}
