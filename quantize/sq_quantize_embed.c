/* seamquad: the integer-grid map from the T-mesh layout and integer arc
 * lengths (sq_quantize_internal.h).
 *
 *  1. Along each arc of integer length n and real length l, the vertex at
 *     real distance d from its first node goes to n d / l, rounded to the
 *     dyadic grid 2^-24 (the next grid point where two vertices would
 *     share one): the same value for both patches of the arc, and every
 *     sum below exact.
 *  2. Each patch becomes [0, a] x [0, b] (a = its bottom's and top's
 *     length, b = its sides'); its boundary vertices go to their arc
 *     positions along the four sides, and sq_patch_embed places the rest
 *     (the sweep, or Tutte's map where the sweep flips a triangle).
 *  3. The split mesh with these UVs is read as a map and must pass every
 *     exact check of an integer-grid map (sq_map_from_soup with
 *     SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER): positive triangles,
 *     transitions that are rotations plus integer translations, cones on
 *     integer points with their angles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"
#include "sq_patch_embed.h"
#include "sq_quantize_internal.h"
#include "sq_union_find.h"

/* The grid of arc positions: 2^-24, so that side offsets up to 2^28 plus a
 * position stay exact in doubles. */
#define ALPHA_GRID 16777216.0

sq_status sq_qlayout_embed(const sq_map *M, const sq_split *S, const sq_qlayout *L,
                           const int64_t *length, sq_map *igm, uint32_t *fallback, uint8_t *failed,
                           sq_error *err)
{
    const sq_mesh *m = &S->mesh;
    sq_status st = SQ_OK;
    uint32_t ndist = L->arc_off[L->na];
    double *alpha = malloc(((size_t)ndist + 1) * sizeof *alpha);
    uint32_t *tri_off = calloc((size_t)L->np + 1, sizeof *tri_off);
    uint32_t *tri_list = malloc(((size_t)S->nt + 1) * sizeof *tri_list);
    /* a patch's vertices are its wedges: the corners around a vertex joined
     * across edges off the chords (a face may touch itself at a vertex) */
    uint32_t *wedge = malloc(((size_t)m->nh + 1) * sizeof *wedge);
    uint32_t *loc = malloc(((size_t)m->nh + 1) * sizeof *loc), *stamp = malloc(((size_t)m->nh + 1) * sizeof *stamp);
    /* a patch's local vertices: at most one per corner (a patch that
     * touches itself has more of them than the mesh has vertices) */
    size_t nloc = (size_t)m->nh + 1;
    uint32_t *lv = malloc(nloc * sizeof *lv); /* local -> vertex */
    double *old_uv = malloc(2 * nloc * sizeof *old_uv);
    double *lpos = malloc(3 * nloc * sizeof *lpos);
    double *new_uv = malloc(2 * nloc * sizeof *new_uv);
    uint8_t *fixed = malloc(nloc);
    uint32_t *ltri = malloc(3 * ((size_t)S->nt + 1) * sizeof *ltri);
    /* the output's vt: one per (patch, vertex) */
    uint32_t *face_uv = malloc(3 * ((size_t)S->nt + 1) * sizeof *face_uv);
    size_t vt_cap = (size_t)S->nv + 16, nvt = 0;
    double *vt = malloc(2 * vt_cap * sizeof *vt);
    if (!alpha || !lpos || !wedge || !tri_off || !tri_list || !loc || !stamp || !lv || !old_uv || !new_uv || !fixed ||
        !ltri || !face_uv || !vt) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization embedding)");
        goto done;
    }
    if (fallback) *fallback = 0;
    uint32_t nfailed = 0;
    sq_error e_patch;
    if (failed) memset(failed, 0, L->np);
    /* 1. arc positions */
    for (uint32_t a = 0; a < L->na && !st; a++) {
        uint32_t o = L->arc_off[a], n = L->arc_nv[a];
        double len = L->arc_len[a], N = (double)length[a];
        if (length[a] < 1) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "quantization: arc %u has length %lld", a, (long long)length[a]);
            break;
        }
        double g = 1.0 / ALPHA_GRID, *x = alpha + o;
        for (uint32_t i = 0; i < n; i++)
            x[i] = i == 0 ? 0.0 : i == n - 1 ? N : nearbyint(N * L->arc_dist[o + i] / len * ALPHA_GRID) / ALPHA_GRID;
        for (uint32_t i = 1; i + 1 < n; i++) x[i] = fmax(x[i], x[i - 1] + g);
        for (uint32_t i = n - 1; i-- > 1;) x[i] = fmin(x[i], x[i + 1] - g);
        for (uint32_t i = 1; i < n; i++)
            if (!(x[i] > x[i - 1])) {
                st = sq_error_set(err, SQ_ERR_SOLVER,
                                  "quantization: arc %u (integer length %lld) has %u vertices: "
                                  "more than its length holds at a spacing of 2^-24",
                                  a, (long long)length[a], n);
                break;
            }
    }
    if (st) goto done;
    sq_qlayout_patch_triangles(S, L, tri_off, tri_list);
    for (uint32_t h = 0; h < m->nh; h++) wedge[h] = h, stamp[h] = UINT32_MAX;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t e = m->he_next[m->he_next[h]]; /* the edge into h's origin */
        if (!S->on_chord[e]) sq_uf_union(wedge, h, m->he_twin[e]);
    }
    for (uint32_t p = 0; p < L->np && !st; p++) {
        /* 2. integer size */
        int64_t side[4] = {0, 0, 0, 0};
        for (int s = 0; s < 4; s++)
            for (uint32_t k = L->side_off[4 * (size_t)p + s]; k < L->side_off[4 * (size_t)p + s + 1]; k++)
                side[s] += length[L->side_arc[k]];
        if (side[0] != side[2] || side[1] != side[3]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "quantization: T-mesh face %u has integer sides %lld, %lld, %lld, %lld "
                              "(opposite sides must be equal)",
                              p, (long long)side[0], (long long)side[1], (long long)side[2], (long long)side[3]);
            break;
        }
        int64_t A = side[0], B = side[1];
        /* local vertices and their old coordinates */
        uint32_t nl = 0;
        for (uint32_t k = tri_off[p]; k < tri_off[p + 1]; k++) {
            uint32_t t = tri_list[k];
            for (int i = 0; i < 3; i++) {
                uint32_t v = S->tri[3 * (size_t)t + i], w = sq_uf_find(wedge, 3 * t + (uint32_t)i);
                if (stamp[w] != p) {
                    stamp[w] = p;
                    loc[w] = nl;
                    lv[nl] = v;
                    double q[2];
                    sq_map_rotate(L->tri_rot[t], S->uv + 6 * (size_t)t + 2 * i, q);
                    old_uv[2 * (size_t)nl] = q[0] + L->tri_shift[2 * (size_t)t];
                    old_uv[2 * (size_t)nl + 1] = q[1] + L->tri_shift[2 * (size_t)t + 1];
                    fixed[nl] = 0;
                    nl++;
                }
                ltri[3 * (size_t)(k - tri_off[p]) + i] = loc[w];
            }
        }
        /* boundary: arc positions along the four sides */
        double W = L->W[p], H = L->H[p];
        for (int s = 0; s < 4 && !st; s++) {
            uint32_t h = L->corner_he[4 * (size_t)p + s], end = L->corner_he[4 * (size_t)p + (s + 1) % 4];
            uint32_t cur = UINT32_MAX;
            double offset = 0.0;
            do {
                uint32_t v = m->he_vert[h], a = L->he_arc[h], l = loc[sq_uf_find(wedge, h)];
                if (cur == UINT32_MAX) cur = a;
                else if (L->v_node[v]) offset += (double)length[cur], cur = a;
                double x = alpha[L->arc_off[a] + L->he_pos[h]];
                double along = offset + (L->he_fwd[h] ? x : (double)length[a] - x);
                double nu, nv_;
                switch (s) {
                case 0: nu = along, nv_ = 0.0, old_uv[2 * (size_t)l + 1] = 0.0; break;
                case 1: nu = (double)A, nv_ = along, old_uv[2 * (size_t)l] = W; break;
                case 2: nu = (double)A - along, nv_ = (double)B, old_uv[2 * (size_t)l + 1] = H; break;
                default: nu = 0.0, nv_ = (double)B - along, old_uv[2 * (size_t)l] = 0.0; break;
                }
                if (h == L->corner_he[4 * (size_t)p + s]) { /* a corner: exact in both */
                    static const int cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
                    old_uv[2 * (size_t)l] = cu[s] ? W : 0.0;
                    old_uv[2 * (size_t)l + 1] = cv[s] ? H : 0.0;
                }
                if (fixed[l] && (new_uv[2 * (size_t)l] != nu || new_uv[2 * (size_t)l + 1] != nv_)) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL,
                                      "quantization: T-mesh face %u: vertex %u gets two places on "
                                      "its boundary",
                                      p, v);
                    break;
                }
                fixed[l] |= (uint8_t)(1u << s);
                if (h == L->corner_he[4 * (size_t)p + s]) fixed[l] |= (uint8_t)(1u << ((s + 3) % 4));
                new_uv[2 * (size_t)l] = nu;
                new_uv[2 * (size_t)l + 1] = nv_;
                h = sq_qlayout_next_boundary(S, h);
            } while (h != end);
        }
        if (st) break;
        for (uint32_t l = 0; l < nl; l++) memcpy(lpos + 3 * (size_t)l, S->pos + 3 * (size_t)lv[l], 3 * sizeof *lpos);
        sq_patch P = {nl, tri_off[p + 1] - tri_off[p], old_uv, ltri, W, H, A, B, fixed, lpos};
        int method = 0;
        sq_error *pe = failed && nfailed ? &e_patch : err; /* the first failure's message kept */
        if ((st = sq_patch_embed(&P, new_uv, &method, pe))) {
            if (st != SQ_ERR_SOLVER || !failed) {
                if (pe != err && err) *err = e_patch;
                break;
            }
            failed[p] = 1, nfailed++, st = SQ_OK; /* the next patch; the caller refines this one */
            continue;
        }
        if (method != SQ_PATCH_SURFACE && fallback) (*fallback)++;
        /* vt of this patch */
        if (nvt + nl > vt_cap) {
            vt_cap = 2 * (nvt + nl);
            double *g = realloc(vt, 2 * vt_cap * sizeof *vt);
            if (!g) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization embedding)");
                break;
            }
            vt = g;
        }
        memcpy(vt + 2 * nvt, new_uv, 2 * (size_t)nl * sizeof *vt);
        for (uint32_t k = tri_off[p]; k < tri_off[p + 1]; k++)
            for (int i = 0; i < 3; i++)
                face_uv[3 * (size_t)tri_list[k] + i] = (uint32_t)nvt + ltri[3 * (size_t)(k - tri_off[p]) + i];
        nvt += nl;
    }
    if (st) goto done;
    if (nfailed) {
        st = SQ_ERR_SOLVER;
        if (nfailed > 1 && err) {
            char first[sizeof err->msg];
            memcpy(first, err->msg, sizeof first);
            sq_error_set(err, st, "%u T-mesh faces not embedded, the first: %s", nfailed, first);
        }
        goto done;
    }
    /* 3. the map, checked exactly */
    {
        sq_soup soup;
        memset(&soup, 0, sizeof soup);
        soup.nv = S->nv, soup.pos = S->pos, soup.nf = S->nt, soup.face_idx = S->tri;
        soup.nuv = (uint32_t)nvt, soup.uv = vt, soup.face_uv = face_uv;
        soup.face_off = malloc(((size_t)S->nt + 1) * sizeof *soup.face_off);
        if (!soup.face_off) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (quantization embedding)");
            goto done;
        }
        for (uint32_t t = 0; t <= S->nt; t++) soup.face_off[t] = 3 * t;
        sq_error e2;
        st = sq_map_from_soup(&soup, &M->mesh, M->valence, 1e-9,
                              SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER | SQ_MAP_ALLOW_FLAT_3D, igm,
                              NULL, &e2);
        free(soup.face_off);
        if (st) st = sq_error_set(err, SQ_ERR_INTERNAL, "quantization: the integer-grid map fails its check: %s", e2.msg);
    }
done:
    free(alpha), free(wedge), free(tri_off), free(tri_list), free(loc), free(stamp), free(lv), free(old_uv), free(lpos);
    free(new_uv), free(fixed), free(ltri), free(face_uv), free(vt);
    return st;
}
