/* seamquad: steps 6-7c, the interior map by cells (sq_param_steps.h):
 * Omega's chords replayed on the surface, Tutte's map of every cell onto
 * its rectangle, flipped triangles repaired, and the cells that failed
 * halved for the next round. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_mean_value.h"
#include "sq_param_steps.h"
#include "sq_predicates.h"
#include "sq_sparse.h"

/* corner_uv of every halfedge at once (c->h_uv), for the checks after the
 * interior map: each sector is walked once, counterclockwise from the cut
 * halfedge that bounds it, instead of once per corner. 0: no memory. */
static int corner_table(ctx *c, const uint32_t *v_uv)
{
    const sq_tsurf *S = &c->S;
    uint32_t *t = malloc(((size_t)S->nh + 1) * sizeof *t);
    if (!t) return 0;
    for (uint32_t h = 0; h < S->nh; h++) {
        if (!S->v_ncut[S->vert[h]]) t[h] = v_uv[S->vert[h]];
        if (!S->kind[h] || !S->v_ncut[S->vert[h]]) continue;
        uint32_t u = c->sec_uv[h];
        t[h] = u;
        for (uint32_t g = sq_ts_ccw(S, h); !S->kind[g]; g = sq_ts_ccw(S, g)) t[g] = u;
    }
    free(c->h_uv);
    c->h_uv = t;
    return 1;
}

/* ---- step 6: chords of Omega replayed on the surface ------------------ */

static sq_status replay_chords(ctx *c)
{
    sq_tsurf *S = &c->S;
    const sq_omega *O = c->O;
    const sq_metapolygon *W = &O->cut;
    const sq_omega_cells *C = &c->C;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    uint32_t *path = NULL, npath = 0, *pl = NULL, npl = 0, *matched = NULL, *uvv = NULL;
    int64_t *g = NULL;
    for (uint32_t ci = 0; ci < C->nchords && st == SQ_OK; ci++) {
        const sq_omega_chord *ch = &C->chord[ci];
        if (over_budget(c)) {
            st = budget_error(c, "cells");
            break;
        }
        uint32_t ms = c->o2m[ch->start_sector], me = c->o2m[ch->end_sector];
        if (ms == SQ_NONE || me == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "chord %u: its %s sector has no surface copy", ci,
                              ms == SQ_NONE ? "start" : "end");
            break;
        }
        npath = 0;
        if (sq_tsurf_open_sector(S, ms) < 0 || sq_tsurf_open_sector(S, me) < 0 || sec_reserve(c)) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        st = sq_tsurf_route(S, ms, SQ_ROUTE_SECTOR, 0, NULL, 0, me, &path, &npath, err);
        if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        if (st == SQ_ERR_INTERNAL) {
            npath = 0;
            st = sq_tsurf_route_faces(S, ms, SQ_ROUTE_SECTOR, 0, NULL, 0, me, &path, &npath, err);
            if (st == SQ_OK && sec_reserve(c)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        }
        if (st) break;
        for (uint32_t e = 0; e < npath; e++) sq_tsurf_cut_edge(S, path[e], SQ_TS_CHORD, SQ_NONE, SQ_NONE);
        /* the new sub-sectors at both ends keep their vertex's UV */
        c->sec_uv[path[0]] = c->sec_uv[ms];
        c->sec_uv[S->twin[path[npath - 1]]] = c->sec_uv[me];
        uint32_t N = ch->len;
        uint32_t end_v = sq_ts_head(S, path[npath - 1]);
        matched = realloc(matched, ((size_t)N + 1) * sizeof *matched);
        g = realloc(g, 2 * ((size_t)N + 1) * sizeof *g);
        if (!matched || !g) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        for (uint32_t j = 0; j <= N; j++) {
            uint32_t f = C->chord_he[ch->he_off + (j < N ? j : N - 1)];
            uint32_t ov = j < N ? W->he_vert[f] : W->he_vert[W->he_next[f]];
            g[2 * j] = O->xy[2 * ov], g[2 * j + 1] = O->xy[2 * ov + 1];
        }
        st = sq_param_split_polyline(c, path, npath, N, NULL, matched);
        if (st) break;
        if (sec_reserve(c)) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        /* walk the (split) path: follow the chord through its vertices */
        free(pl);
        pl = malloc(((size_t)npath + N + 1) * sizeof *pl);
        if (!pl) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        npl = 0;
        {
            uint32_t h = path[0];
            for (;;) {
                pl[npl++] = h;
                uint32_t v = sq_ts_head(S, h);
                if (v == end_v) break;
                /* the chord continues from v: the other chord edge at v */
                uint32_t t = S->twin[h], q = sq_ts_ccw(S, t);
                while (S->kind[q] != SQ_TS_CHORD || q == t) q = sq_ts_ccw(S, q);
                h = q;
            }
        }
        uvv = realloc(uvv, ((size_t)npl + 1) * sizeof *uvv);
        if (!uvv) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        /* the path's end points keep their UVs: only its inside is new */
        st = sq_param_polyline_uv(c, pl, npl, matched, g, 1.0, N, uvv);
        if (st) break;
        for (uint32_t q = 1; q < npl; q++) {
            c->sec_uv[pl[q]] = uvv[q];                  /* left side  */
            c->sec_uv[S->twin[pl[q - 1]]] = uvv[q];     /* right side */
        }
        /* Omega chord halfedges -> surface halfedges */
        uint32_t j = 0;
        for (uint32_t q = 0; q <= npl && j <= N; q++) {
            uint32_t v = q < npl ? S->vert[pl[q]] : end_v;
            if (v != matched[j]) continue;
            if (j < N) c->o2m[C->chord_he[ch->he_off + j]] = pl[q];
            if (j > 0) c->o2m[W->he_twin[C->chord_he[ch->he_off + j - 1]]] = S->twin[pl[q - 1]];
            j++;
        }
        if (j != N + 1) st = sq_error_set(err, SQ_ERR_INTERNAL, "chord %u: %u of %u grid points", ci, j, N + 1);
        progress(c, "cells", 0.55 + 0.15 * (ci + 1) / (double)C->nchords);
    }
    free(path);
    free(pl);
    free(matched);
    free(uvv);
    free(g);
    return st;
}

/* ---- step 7: Tutte map of every cell onto its rectangle --------------- */

static sq_status tutte(ctx *c, uint32_t *v_uv)
{
    sq_tsurf *S = &c->S;
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    uint32_t nv = S->nv;
    uint32_t *idx = malloc((size_t)nv * sizeof *idx);
    if (!idx) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    uint32_t n = 0;
    for (uint32_t v = 0; v < nv; v++) idx[v] = S->v_ncut[v] ? SQ_NONE : n++;
    size_t cap = 8 * (size_t)n + 16, nnz = 0;
    uint32_t *ri = malloc(cap * sizeof *ri), *cj = malloc(cap * sizeof *cj);
    double *val = malloc(cap * sizeof *val), *rhs = calloc(2 * (size_t)n + 2, sizeof *rhs),
           *x = malloc((2 * (size_t)n + 2) * sizeof *x);
    sq_lu *lu = NULL;
    if (!ri || !cj || !val || !rhs || !x) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < nv && st == SQ_OK; v++) {
        if (idx[v] == SQ_NONE) continue;
        uint32_t h0 = S->v_he[v], h = h0;
        double diag = 0;
        do {
            uint32_t w = sq_ts_head(S, h);
            /* faces on both sides of edge v-w: face(h) has third vertex
             * tri[prev(h)]; the twin's face has tri[prev(twin h)] */
            uint32_t a = S->vert[sq_ts_prev(S, h)], b = S->vert[sq_ts_prev(S, S->twin[h])];
            double wt = sq_mean_value_weight(S->pos + 3 * v, S->pos + 3 * w, S->pos + 3 * a, S->pos + 3 * b);
            diag += wt;
            if (nnz + 2 > cap) {
                cap *= 2;
                uint32_t *r2 = realloc(ri, cap * sizeof *ri), *c2 = realloc(cj, cap * sizeof *cj);
                double *v2 = realloc(val, cap * sizeof *val);
                if (r2) ri = r2;
                if (c2) cj = c2;
                if (v2) val = v2;
                if (!r2 || !c2 || !v2) {
                    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
                    break;
                }
            }
            if (idx[w] != SQ_NONE) {
                ri[nnz] = idx[v], cj[nnz] = idx[w], val[nnz] = -wt, nnz++;
            } else {
                uint32_t u = corner_uv(c, NULL, S->twin[h]);
                if (u == SQ_NONE) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL, "vertex %u on the cut has no UV in its sector", w);
                    break;
                }
                rhs[idx[v]] += wt * c->uv[2 * u];
                rhs[n + idx[v]] += wt * c->uv[2 * u + 1];
            }
            h = sq_ts_ccw(S, h);
        } while (h != h0);
        ri[nnz] = idx[v], cj[nnz] = idx[v], val[nnz] = diag, nnz++;
    }
    if (st) goto done;
    if (n > 0) {
        st = sq_lu_factor(n, nnz, ri, cj, val, &lu, err);
        if (st == SQ_OK) st = sq_lu_solve(lu, 2, rhs, x, err);
        if (st) goto done;
    }
    for (uint32_t v = 0; v < nv; v++) {
        if (idx[v] == SQ_NONE) {
            v_uv[v] = SQ_NONE;
            continue;
        }
        v_uv[v] = uv_add(c, x[idx[v]], x[n + idx[v]]);
        if (v_uv[v] == SQ_NONE) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
    }
done:
    if (lu) sq_lu_free(lu);
    free(idx);
    free(ri);
    free(cj);
    free(val);
    free(rhs);
    free(x);
    return st;
}

/* ---- step 7b: vertices moved into the kernels of their stars ---------- */

/* The UV of the corner of face(h) at its origin (every corner has one
 * once the interior map has run). */
static const double *corner_xy(const ctx *c, const uint32_t *v_uv, uint32_t h)
{
    return c->uv + 2 * (size_t)corner_uv(c, v_uv, h);
}

static int face_ok(const ctx *c, const uint32_t *v_uv, uint32_t f)
{
    uint32_t h = c->S.f_he[f];
    return sq_orient2d(corner_xy(c, v_uv, h), corner_xy(c, v_uv, c->S.next[h]),
                       corner_xy(c, v_uv, c->S.next[c->S.next[h]])) > 0;
}

/* Clips the convex polygon p (n points, counterclockwise) by the half-plane
 * left of a->b; returns the new count (q: room for n + 1 points). */
static uint32_t clip_left(const double *p, uint32_t n, const double a[2], const double b[2], double *q)
{
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++) {
        const double *x = p + 2 * i, *y = p + 2 * ((i + 1) % n);
        double sx = (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]);
        double sy = (b[0] - a[0]) * (y[1] - a[1]) - (b[1] - a[1]) * (y[0] - a[0]);
        if (sx > 0) q[2 * m] = x[0], q[2 * m + 1] = x[1], m++;
        if ((sx > 0) != (sy > 0) && sx != sy) {
            double t = sx / (sx - sy);
            q[2 * m] = x[0] + t * (y[0] - x[0]), q[2 * m + 1] = x[1] + t * (y[1] - x[1]), m++;
        }
    }
    return m;
}

/* Tutte's map is bijective in exact arithmetic, but where a cell is
 * squeezed its vertices can land within a rounding step of a line and
 * their triangles flip in doubles. Each vertex off the cut on such a
 * triangle is moved to the centroid of the kernel of its star (the points
 * that see every edge of its link on the left), kept only if its star then
 * has fewer bad triangles (exact predicate); a few sweeps, the neighbours
 * of moved vertices included. This is the vertex step of progressive
 * embedding [SJZP19] without its collapses: it never makes a triangle bad,
 * and every triangle is checked exactly afterwards anyway. Returns the
 * number of bad triangles left. */
static uint32_t repair_flips(ctx *c, uint32_t *v_uv, uint32_t sweeps)
{
    sq_tsurf *S = &c->S;
    uint32_t nv = S->nv, nbad = 0;
    uint8_t *mark = calloc(nv, 1);
    uint32_t *list = malloc((size_t)nv * sizeof *list);
    uint32_t cap = 64;
    double *poly = malloc(2 * (size_t)cap * sizeof *poly), *tmp = malloc(2 * (size_t)cap * sizeof *tmp);
    uint32_t *badf = NULL, nbf = 0;
    if (!mark || !list || !poly || !tmp) goto out;
    for (uint32_t f = 0; f < S->nf; f++) nbad += !face_ok(c, v_uv, f);
    /* thousands of bad triangles are a squeezed map, not rounding: the
     * vertex moves cannot help there, and cost time */
    if (nbad == 0 || nbad > 1000) goto out;
    badf = malloc((size_t)nbad * sizeof *badf);
    if (!badf) goto out;
    for (uint32_t f = 0; f < S->nf; f++)
        if (!face_ok(c, v_uv, f)) badf[nbf++] = f;
    for (uint32_t it = 0; it < sweeps && nbad; it++) {
        uint32_t nl = 0, keep = 0;
        for (uint32_t i = 0; i < nbf; i++) {
            uint32_t f = badf[i];
            if (face_ok(c, v_uv, f)) continue;
            badf[keep++] = f; /* bad faces only get fewer */
            uint32_t h = S->f_he[f];
            for (int k = 0; k < 3; k++, h = S->next[h]) {
                uint32_t v = S->vert[h];
                if (!S->v_ncut[v] && !mark[v]) mark[v] = 1, list[nl++] = v;
                /* and the free neighbours, which may have to make room */
                uint32_t g0 = S->v_he[v], g = g0;
                do {
                    uint32_t w = sq_ts_head(S, g);
                    if (!S->v_ncut[w] && !mark[w]) mark[w] = 1, list[nl++] = w;
                    g = sq_ts_ccw(S, g);
                } while (g != g0);
            }
        }
        nbf = keep;
        uint32_t moved = 0;
        for (uint32_t i = 0; i < nl; i++) {
            uint32_t v = list[i];
            mark[v] = 0;
            /* the link counterclockwise: heads of the outgoing halfedges */
            uint32_t deg = 0, g0 = S->v_he[v], g = g0;
            do {
                deg++;
                g = sq_ts_ccw(S, g);
            } while (g != g0);
            if (deg + 8 > cap) {
                cap = 2 * (deg + 8);
                double *p2 = realloc(poly, 2 * (size_t)cap * sizeof *poly), *t2 = realloc(tmp, 2 * (size_t)cap * sizeof *tmp);
                if (p2) poly = p2;
                if (t2) tmp = t2;
                if (!p2 || !t2) goto out;
            }
            /* start from the link's bounding box, clip by every link edge */
            double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            uint32_t bad_before = 0, was_bad = 0; /* was_bad: bit i for the i-th face (i < 32) */
            g = g0;
            for (uint32_t i = 0; i < deg; i++, g = sq_ts_ccw(S, g)) {
                const double *w = corner_xy(c, v_uv, S->twin[g]);
                for (int k = 0; k < 2; k++) lo[k] = fmin(lo[k], w[k]), hi[k] = fmax(hi[k], w[k]);
                int b = !face_ok(c, v_uv, S->face[g]);
                bad_before += b;
                if (b && i < 32) was_bad |= 1u << i;
            }
            if (deg > 32) continue; /* (never on a triangle mesh of sane valence) */
            if (!bad_before && it > 0) continue;
            uint32_t n = 4;
            poly[0] = lo[0], poly[1] = lo[1], poly[2] = hi[0], poly[3] = lo[1];
            poly[4] = hi[0], poly[5] = hi[1], poly[6] = lo[0], poly[7] = hi[1];
            g = g0;
            do {
                /* face(g) = (v, head(g), head(ccw g)): v must lie left of
                 * head(g) -> head(ccw g) */
                const double *a = corner_xy(c, v_uv, S->next[g]), *b = corner_xy(c, v_uv, sq_ts_prev(S, g));
                n = clip_left(poly, n, a, b, tmp);
                double *sw = poly;
                poly = tmp, tmp = sw;
                g = sq_ts_ccw(S, g);
            } while (g != g0 && n >= 3);
            if (n < 3) continue;
            double cx = 0, cy = 0;
            for (uint32_t k = 0; k < n; k++) cx += poly[2 * k], cy += poly[2 * k + 1];
            cx /= n, cy /= n;
            double *p = c->uv + 2 * v_uv[v], old[2] = {p[0], p[1]};
            p[0] = cx, p[1] = cy;
            uint32_t bad_after = 0, worse = 0;
            g = g0;
            for (uint32_t i = 0; i < deg; i++, g = sq_ts_ccw(S, g)) {
                int b = !face_ok(c, v_uv, S->face[g]);
                bad_after += b;
                if (b && !(was_bad >> i & 1u)) worse = 1; /* a good triangle would turn bad */
            }
            if (!worse && (bad_after < bad_before || bad_before == 0)) {
                nbad -= bad_before - bad_after;
                moved++;
            } else {
                p[0] = old[0], p[1] = old[1];
            }
        }
        if (!moved) break;
    }
out:
    free(badf);
    free(mark);
    free(list);
    free(poly);
    free(tmp);
    return nbad;
}

/* ---- step 7c: the cells that failed, halved for the next round -------- */

/* Tutte's map of a cell is bijective in exact arithmetic (convex target,
 * no edge between two vertices of the cut: sq_tsurf_split_blocking), but
 * where the surface cell's shape differs from its rectangle it squeezes
 * parts of the cell exponentially, below double precision. A smaller
 * rectangle covers a shorter stretch of the surface, whose shape differs
 * less: every cell of Omega that holds a bad triangle is limited to
 * ceil(s / 2) x ceil(s / 2) quads, s its longer side, for the next round
 * (sq_omega_cells_build halves it by chords until it fits); the other
 * cells keep their limits. Surface faces are assigned to Omega's cells by
 * flooding from the surface copies (o2m) of the cells' boundary halfedges
 * across uncut edges. *halved receives the number of cells given a new
 * limit; when it is not 0, c->face_limit holds the next round's limits. */
static sq_status refine_bad_cells(ctx *c, const uint32_t *v_uv, uint32_t *halved)
{
    const sq_tsurf *S = &c->S;
    const sq_metapolygon *P = &c->O->cut;
    const sq_omega_cells *C = &c->C;
    *halved = 0;
    uint32_t *fc = malloc((size_t)S->nf * sizeof *fc), *stack = malloc((size_t)S->nf * sizeof *stack);
    uint32_t *lim = malloc((size_t)(C->ncells ? C->ncells : 1) * sizeof *lim); /* per cell */
    sq_status st = SQ_OK;
    if (!fc || !stack || !lim) {
        st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    uint32_t sp = 0;
    for (uint32_t f = 0; f < S->nf; f++) fc[f] = SQ_NONE;
    for (uint32_t h = 0; h < P->nh; h++) {
        uint32_t of = P->he_face[h];
        if (of == SQ_NONE || (!C->he_chord[h] && P->he_face[P->he_twin[h]] != SQ_NONE)) continue;
        uint32_t sh = c->o2m[h];
        if (sh == SQ_NONE) continue;
        uint32_t f = S->face[sh];
        if (fc[f] == SQ_NONE) fc[f] = C->f_cell[of], stack[sp++] = f;
    }
    while (sp) {
        uint32_t f = stack[--sp], g = S->f_he[f];
        for (uint32_t e = 0; e < 3; e++, g = S->next[g]) {
            if (S->kind[g]) continue;
            uint32_t n = S->face[S->twin[g]];
            if (fc[n] == SQ_NONE) fc[n] = fc[f], stack[sp++] = n;
        }
    }
    /* the new limit of each bad cell that can still be halved */
    for (uint32_t k = 0; k < C->ncells; k++) lim[k] = UINT32_MAX;
    for (uint32_t f = 0; f < S->nf; f++) {
        uint32_t k = fc[f];
        if (k == SQ_NONE || lim[k] != UINT32_MAX || face_ok(c, v_uv, f)) continue;
        const int64_t *b = C->cell_box + 4 * (size_t)k;
        int64_t side = b[2] - b[0] > b[3] - b[1] ? b[2] - b[0] : b[3] - b[1];
        if (side > 1) lim[k] = (uint32_t)((side + 1) / 2), ++*halved; /* a unit square stays */
    }
    if (*halved == 0) goto done;
    if (!c->face_limit) {
        c->face_limit = malloc((size_t)(P->nf ? P->nf : 1) * sizeof *c->face_limit);
        if (!c->face_limit) {
            st = sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
            goto done;
        }
        for (uint32_t f = 0; f < P->nf; f++) c->face_limit[f] = UINT32_MAX;
    }
    for (uint32_t f = 0; f < P->nf; f++) {
        uint32_t l = lim[C->f_cell[f]];
        if (l < c->face_limit[f]) c->face_limit[f] = l;
    }
done:
    free(fc);
    free(stack);
    free(lim);
    return st;
}

void sq_param_before_cells_free(sq_param_before_cells *b)
{
    sq_tsurf_free(&b->S);
    free(b->sec_uv);
    free(b->uv);
    free(b->o2m);
    memset(b, 0, sizeof *b);
}

sq_status sq_param_before_cells_save(const ctx *c, sq_param_before_cells *b)
{
    size_t nh = c->O->cut.nh;
    memset(b, 0, sizeof *b);
    b->sec_uv = malloc((size_t)(c->cap_sec ? c->cap_sec : 1) * sizeof *b->sec_uv);
    b->uv = malloc(2 * (size_t)(c->nuv ? c->nuv : 1) * sizeof *b->uv);
    b->o2m = malloc((nh ? nh : 1) * sizeof *b->o2m);
    if (!b->sec_uv || !b->uv || !b->o2m || sq_tsurf_copy(&b->S, &c->S)) {
        sq_param_before_cells_free(b);
        return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    }
    memcpy(b->sec_uv, c->sec_uv, (size_t)c->cap_sec * sizeof *b->sec_uv);
    memcpy(b->uv, c->uv, 2 * (size_t)c->nuv * sizeof *b->uv);
    memcpy(b->o2m, c->o2m, nh * sizeof *b->o2m);
    b->cap_sec = c->cap_sec, b->nuv = c->nuv;
    return SQ_OK;
}

/* Back to the saved state (sec_uv and uv only grow, so they have room). */
sq_status sq_param_before_cells_restore(ctx *c, const sq_param_before_cells *b)
{
    if (sq_tsurf_copy(&c->S, &b->S)) return sq_error_set(c->err, SQ_ERR_NOMEM, "out of memory");
    memcpy(c->sec_uv, b->sec_uv, (size_t)b->cap_sec * sizeof *c->sec_uv);
    for (uint32_t i = b->cap_sec; i < c->cap_sec; i++) c->sec_uv[i] = SQ_NONE;
    memcpy(c->uv, b->uv, 2 * (size_t)b->nuv * sizeof *c->uv);
    c->nuv = b->nuv;
    memcpy(c->o2m, b->o2m, (size_t)c->O->cut.nh * sizeof *c->o2m);
    return SQ_OK;
}

/* Steps 6-7c with up to c->opt->refine rounds: Omega's cells (the chords
 * replayed on the surface), Tutte's map of every cell, flips repaired
 * (7b), and where triangles stay bad the cells holding them halved for the
 * next round (7c), which starts again from `saved` (filled when
 * opt->refine is not 0). *v_uv: the last round's UV index per surface
 * vertex (the caller frees it); *t_round, *t3: when the last round and
 * its Tutte map began. stats: chords, cells, rounds, cells_refined. */
sq_status sq_param_cells_map(ctx *c, const sq_param_before_cells *saved, uint32_t **v_uv, sq_param_stats *stats,
                             double *t_round, double *t3)
{
    sq_error *err = c->err;
    sq_status st = SQ_OK;
    for (uint32_t round = 0; st == SQ_OK; round++) {
        st = stop_if_cancelled(c);
        if (st) break;
        if (round) {
            progress(c, "halving the cells with bad triangles", 0.55);
            free(c->h_uv); /* it describes the surface being dropped */
            c->h_uv = NULL;
            st = sq_param_before_cells_restore(c, saved);
            if (st) break;
            *t_round = sq_now();
        }
        progress(c, "cells", 0.55);
        st = sq_omega_cells_build(c->O, 0, c->face_limit, &c->C, err);
        if (st == SQ_OK) st = replay_chords(c);
        if (st) break;
        stats->chords = c->C.nchords, stats->cells = c->C.ncells;
        if (sq_tsurf_split_blocking(&c->S, 0) < 0 || sec_reserve(c)) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        *t3 = sq_now();
        progress(c, "tutte", 0.7);
        free(*v_uv);
        *v_uv = malloc((size_t)c->S.nv * sizeof **v_uv);
        if (!*v_uv) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
            break;
        }
        st = tutte(c, *v_uv);
        if (st == SQ_OK && !corner_table(c, *v_uv)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        if (st) break;
        /* step 7b; step 8 checks every triangle */
        if (repair_flips(c, *v_uv, 50) == 0 || round >= c->opt->refine) break;
        uint32_t halved = 0;
        st = refine_bad_cells(c, *v_uv, &halved); /* step 7c */
        if (st || halved == 0) break;
        stats->rounds = round + 1;
        stats->cells_refined += halved;
    }
    return st;
}
