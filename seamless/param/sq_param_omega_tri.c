/* seamquad: Omega triangulated for the overlay (step 7'; sq_param_overlay.c):
 * each unit square (or each chords' rectangle) fanned from its centre, its
 * boundary edges split at the surface's boundary vertices, graded layers
 * where a side carries many of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"
#include "sq_omega_cells.h"
#include "sq_param_internal.h"

static int tri_add(sq_param_tri_list *L, uint32_t a, uint32_t b, uint32_t c)
{
    if (L->n == L->cap) {
        uint32_t cap = L->cap ? 2 * L->cap : 4096;
        uint32_t *p = realloc(L->t, 3 * (size_t)cap * sizeof *p);
        if (!p) return -1;
        L->t = p, L->cap = cap;
    }
    L->t[3 * L->n] = a, L->t[3 * L->n + 1] = b, L->t[3 * L->n + 2] = c;
    L->n++;
    return 0;
}

/* Triangles (c, p0, x1), (c, x1, x2), ..., (c, xn, p1). */
static int tri_fan(sq_param_tri_list *L, uint32_t c, uint32_t p0, uint32_t n, const uint32_t *x, uint32_t p1)
{
    uint32_t prev = p0;
    for (uint32_t k = 0; k < n; prev = x[k++])
        if (tri_add(L, c, prev, x[k])) return -1;
    return tri_add(L, c, prev, p1);
}

/* The sizes of the layers above n points: each keeps every other point of
 * the one below, its first and its last, until two are left. Returns the
 * number of layers L (sizes[1..L]). */
static uint32_t layer_sizes(uint32_t n, uint32_t sizes[41])
{
    uint32_t L = 0;
    while (n > 2 && L < 40) {
        n = (n - 1) / 2 + 1 + (n - 1) % 2;
        sizes[++L] = n;
    }
    return L;
}

/* Triangles between the n points x (on the segment p0-p1, parameters t
 * filled here) and the apex c: layers of points moving towards c, each
 * keeping every other point of the one below (its first and last too),
 * until two are left, then a fan from c; the layers' points get new ids
 * from *next with their uv. x and t need room for 2 n + 32 entries. */
static int boundary_layers(sq_param_tri_list *L, uint32_t n, uint32_t *x, double *t, uint32_t c, uint32_t p0,
                           uint32_t p1, double *uv, uint32_t *next)
{
    const double *P0 = uv + 2 * (size_t)p0, *P1 = uv + 2 * (size_t)p1, *C = uv + 2 * (size_t)c;
    double d[2] = {P1[0] - P0[0], P1[1] - P0[1]};
    double dd = d[0] * d[0] + d[1] * d[1];
    double ct = ((C[0] - P0[0]) * d[0] + (C[1] - P0[1]) * d[1]) / dd;
    for (uint32_t k = 0; k < n; k++) {
        const double *u = uv + 2 * (size_t)x[k];
        t[k] = ((u[0] - P0[0]) * d[0] + (u[1] - P0[1]) * d[1]) / dd;
    }
    uint32_t sizes[41], nl = layer_sizes(n, sizes);
    uint32_t *lo = x, *up = x + n + 32;
    double *tlo = t, *tup = t + n + 32, slo = 0;
    for (uint32_t l = 1; l <= nl; l++) {
        double sl = 0.9 * ldexp(1.0, (int)l - (int)nl);
        uint32_t m = 0;
        for (uint32_t k = 0; k < n; k++) {
            if (k % 2 && k != n - 1) continue;
            uint32_t id = (*next)++;
            for (int q = 0; q < 2; q++) uv[2 * (size_t)id + q] = (1 - sl) * (P0[q] + tlo[k] * d[q]) + sl * C[q];
            up[m] = id, tup[m] = tlo[k], m++;
        }
        if (tri_add(L, p0, lo[0], up[0])) return -1;
        uint32_t i = 0, j = 0;
        while (i + 1 < n || j + 1 < m) {
            double xl = i + 1 < n ? (1 - slo) * tlo[i + 1] + slo * ct : 2;
            double xu = j + 1 < m ? (1 - sl) * tup[j + 1] + sl * ct : 2;
            if (xl < xu) {
                if (tri_add(L, lo[i], lo[i + 1], up[j])) return -1;
                i++;
            } else {
                if (tri_add(L, lo[i], up[j + 1], up[j])) return -1;
                j++;
            }
        }
        if (tri_add(L, lo[n - 1], p1, up[m - 1])) return -1;
        uint32_t *ti = lo;
        lo = up, up = ti;
        double *td = tlo;
        tlo = tup, tup = td;
        n = m, slo = sl;
    }
    return tri_fan(L, c, p0, n, lo, p1);
}

static int cell_side(const sq_metapolygon *W, const uint8_t *he_chord, uint32_t h)
{
    return W->he_face[W->he_twin[h]] == SQ_NONE || !he_chord || he_chord[h];
}

/* The UVs of B's first vertices (nv of them, the layers' filled later):
 * A's boundary points (buv0), Omega's vertices (wid) and the midpoints
 * (mid) from Omega's layout in units of gs. NULL: out of memory. */
static double *first_uvs(const sq_omega *O, uint32_t nv, uint32_t nbl, uint32_t na, const double *buv0,
                         const uint32_t *wid, const uint32_t *mid, double gs)
{
    const sq_metapolygon *W = &O->cut;
    double *uv = malloc(2 * (size_t)nv * sizeof *uv);
    if (!uv) return NULL;
    memcpy(uv, buv0, 2 * (size_t)nbl * sizeof *uv);
    for (uint32_t v = 0; v < W->nv; v++)
        if (wid[v] != SQ_NONE && wid[v] >= na)
            uv[2 * (size_t)wid[v]] = (double)O->xy[2 * v] * gs, uv[2 * (size_t)wid[v] + 1] = (double)O->xy[2 * v + 1] * gs;
    for (uint32_t h = 0; h < W->nh; h++)
        if (mid[h] != SQ_NONE && h < W->he_twin[h]) {
            uint32_t a = W->he_vert[h], b = W->he_vert[W->he_twin[h]];
            uv[2 * (size_t)mid[h]] = 0.5 * (double)(O->xy[2 * a] + O->xy[2 * b]) * gs;
            uv[2 * (size_t)mid[h] + 1] = 0.5 * (double)(O->xy[2 * a + 1] + O->xy[2 * b + 1]) * gs;
        }
    return uv;
}

sq_status sq_param_omega_triangulation(const sq_omega *O, const sq_omega_cells *C, uint32_t nbl, uint32_t na,
                                       const uint32_t *wb, const uint32_t *oseq, const uint32_t *bstart,
                                       const double *buv0, uint32_t *nv_out, double **uv_out,
                                       sq_param_tri_list *bt, sq_error *err)
{
    const sq_metapolygon *W = &O->cut;
    const uint8_t *chord = C ? C->he_chord : NULL;
    const double gs = ldexp(1.0, -O->xy_shift); /* xy in units of 2^-xy_shift */
    uint32_t ncells = C ? C->ncells : W->nf, nb = W->nbnd;
    uint32_t *wid = malloc((size_t)W->nv * sizeof *wid), *opos = malloc((size_t)W->nh * sizeof *opos);
    uint32_t *mid = malloc((size_t)W->nh * sizeof *mid), *cstart = malloc((size_t)ncells * sizeof *cstart);
    uint32_t *cid_of = malloc(((size_t)ncells + 1) * sizeof *cid_of);
    uint32_t *ring = malloc(((size_t)W->nh + 1) * sizeof *ring);
    uint32_t *pts = malloc(2 * ((size_t)nbl + W->nh + 64) * sizeof *pts);
    double *pt = malloc(2 * ((size_t)nbl + W->nh + 64) * sizeof *pt), *uv = NULL;
    sq_status st = SQ_OK;
    uint32_t nv = na;
    if (!wid || !opos || !mid || !cstart || !cid_of || !ring || !pts || !pt) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < W->nh; h++) opos[h] = mid[h] = SQ_NONE;
    for (uint32_t i = 0; i < nb; i++) opos[oseq[i]] = i;
    for (uint32_t k = 0; k < ncells; k++) cstart[k] = SQ_NONE;
    for (uint32_t h = 0; h < W->nh; h++) {
        uint32_t f = W->he_face[h];
        if (f == SQ_NONE || !cell_side(W, chord, h)) continue;
        uint32_t k = C ? C->f_cell[f] : f;
        if (cstart[k] == SQ_NONE) cstart[k] = h;
    }
    memcpy(wid, wb, (size_t)W->nv * sizeof *wid);
    for (uint32_t h = 0; h < W->nh; h++)
        if (W->he_face[h] != SQ_NONE && cell_side(W, chord, h) && wid[W->he_vert[h]] == SQ_NONE)
            wid[W->he_vert[h]] = nv++;
    /* interior edges joining two boundary vertices get a midpoint (no
     * dividing edge); numbered after the centres */
    const uint32_t WANTED = SQ_NONE - 1;
    for (uint32_t h = 0; h < W->nh; h++) {
        uint32_t t = W->he_twin[h];
        if (W->he_face[h] == SQ_NONE || W->he_face[t] == SQ_NONE || t < h || !cell_side(W, chord, h)) continue;
        if (wid[W->he_vert[h]] < nbl && wid[W->he_vert[t]] < nbl) mid[h] = mid[t] = WANTED;
    }
    /* a centre per cell, but not for a triangle of Omega (from Q
     * triangulated) whose sides carry no surface point and need no
     * midpoint: that triangle is one of B's as it is */
    for (uint32_t k = 0; k < ncells; k++) {
        cid_of[k] = SQ_NONE;
        uint32_t h = cstart[k];
        int tri = !C && h != SQ_NONE && W->f_valence[W->he_face[h]] == 3, need = !tri;
        for (int e = 0; tri && e < 3; e++, h = W->he_next[h])
            if (mid[h] != SQ_NONE || (opos[h] != SQ_NONE && (bstart[opos[h]] + 1) % nbl != bstart[(opos[h] + 1) % nb]))
                need = 1;
        if (need) cid_of[k] = nv++;
    }
    for (uint32_t h = 0; h < W->nh; h++)
        if (mid[h] == WANTED && h < W->he_twin[h]) mid[h] = mid[W->he_twin[h]] = nv++;
    uint32_t layer0 = nv, next = 0;
    for (int pass = 0; pass < 2 && st == SQ_OK; pass++) {
        if (pass == 1) {
            uv = first_uvs(O, nv, nbl, na, buv0, wid, mid, gs);
            if (!uv) {
                st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                break;
            }
            next = layer0;
        }
        for (uint32_t k = 0; k < ncells && st == SQ_OK; k++) {
            uint32_t nr = 0, h = cstart[k];
            if (h == SQ_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: cell %u has no side", k);
                break;
            }
            do {
                ring[nr++] = h;
                uint32_t g = W->he_next[h];
                while (!cell_side(W, chord, g)) g = W->he_next[W->he_twin[g]];
                h = g;
            } while (h != cstart[k] && nr <= W->nh);
#define DIR(e, q) (O->xy[2 * W->he_vert[W->he_next[e]] + (q)] - O->xy[2 * W->he_vert[e] + (q)])
            uint32_t r0 = 0;
            while (r0 < nr && DIR(ring[r0], 0) == DIR(ring[(r0 + nr - 1) % nr], 0) &&
                   DIR(ring[r0], 1) == DIR(ring[(r0 + nr - 1) % nr], 1))
                r0++;
            if (h != cstart[k] || r0 == nr) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "overlay: cell %u is not a rectangle", k);
                break;
            }
            int64_t bx0 = INT64_MAX, by0 = INT64_MAX, bx1 = INT64_MIN, by1 = INT64_MIN;
            for (uint32_t q = 0; q < nr; q++) {
                int64_t x = O->xy[2 * W->he_vert[ring[q]]], y = O->xy[2 * W->he_vert[ring[q]] + 1];
                bx0 = x < bx0 ? x : bx0, bx1 = x > bx1 ? x : bx1, by0 = y < by0 ? y : by0, by1 = y > by1 ? y : by1;
            }
            uint32_t cid = cid_of[k];
            if (cid == SQ_NONE) { /* a triangle of Omega as it is */
                if (pass == 1 && tri_add(bt, wid[W->he_vert[ring[0]]], wid[W->he_vert[ring[1]]], wid[W->he_vert[ring[2]]]))
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                continue;
            }
            if (pass == 1 && nr == 3 && !C) {
                /* a triangle (Omega from Q triangulated): its incentre,
                 * which projects inside every side (the layers above a
                 * side need that; the centroid of an obtuse triangle
                 * does not) */
                double sx = 0, sy = 0, sw = 0;
                for (uint32_t q = 0; q < 3; q++) {
                    uint32_t a = W->he_vert[ring[(q + 1) % 3]], b = W->he_vert[ring[(q + 2) % 3]];
                    double w = hypot((double)(O->xy[2 * a] - O->xy[2 * b]), (double)(O->xy[2 * a + 1] - O->xy[2 * b + 1]));
                    sx += w * (double)O->xy[2 * W->he_vert[ring[q]]], sy += w * (double)O->xy[2 * W->he_vert[ring[q]] + 1];
                    sw += w;
                }
                uv[2 * (size_t)cid] = sx / sw * gs, uv[2 * (size_t)cid + 1] = sy / sw * gs;
            } else if (pass == 1) {
                uv[2 * (size_t)cid] = 0.5 * (double)(bx0 + bx1) * gs, uv[2 * (size_t)cid + 1] = 0.5 * (double)(by0 + by1) * gs;
            }
            for (uint32_t q = 0; q < nr && st == SQ_OK;) {
                uint32_t e0 = ring[(r0 + q) % nr], np = 0, e = e0, q1 = q;
                for (;;) {
                    if (e != e0) pts[np++] = wid[W->he_vert[e]];
                    if (opos[e] != SQ_NONE) {
                        uint32_t i = opos[e], m1 = bstart[(i + 1) % nb];
                        for (uint32_t p = (bstart[i] + 1) % nbl; p != m1; p = (p + 1) % nbl) pts[np++] = p;
                    } else if (mid[e] != SQ_NONE) {
                        pts[np++] = mid[e];
                    }
                    q1++;
                    if (q1 == nr) break;
                    uint32_t en = ring[(r0 + q1) % nr];
                    if (DIR(en, 0) != DIR(e, 0) || DIR(en, 1) != DIR(e, 1)) break;
                    e = en;
                }
                uint32_t p0 = wid[W->he_vert[e0]], p1 = wid[W->he_vert[W->he_next[e]]];
                if (pass == 0) {
                    uint32_t sizes[41], L = np >= 3 ? layer_sizes(np, sizes) : 0;
                    for (uint32_t l = 1; l <= L; l++) nv += sizes[l];
                } else if (np >= 3 ? boundary_layers(bt, np, pts, pt, cid, p0, p1, uv, &next)
                                   : tri_fan(bt, cid, p0, np, pts, p1)) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                }
                q = q1;
            }
#undef DIR
        }
    }
done:
    free(wid), free(opos), free(mid), free(cstart), free(cid_of), free(ring), free(pts), free(pt);
    if (st) free(uv), uv = NULL;
    *nv_out = nv, *uv_out = uv;
    return st;
}
