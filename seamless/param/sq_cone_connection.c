/* seamquad: the smooth cross field's rotations for given cones, as a
 * trivial connection (sq_cone_connection.h; docs/holonomy.md).
 *
 * Quantities live on halfedges and are antisymmetric (x[twin h] = -x[h]);
 * each edge is stored once, on its canonical halfedge h < twin(h), as
 * index e = position among canonical halfedges. A "loop around v" crosses
 * he_prev(o) for every outgoing halfedge o of v: counterclockwise. */
#include "sq_cone_connection.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_sparse.h"

#define PI 3.14159265358979323846
#define QUARTER (PI / 2.0)

static uint32_t prev_he(const sq_mesh *m, uint32_t h)
{
    uint32_t p = h;
    while (m->he_next[p] != h) p = m->he_next[p];
    return p;
}

static uint32_t dest(const sq_mesh *m, uint32_t h) { return m->he_vert[m->he_next[h]]; }

static void edge_vec(const sq_mesh *m, uint32_t h, double d[3])
{
    const double *a = m->pos + 3 * (size_t)m->he_vert[h], *b = m->pos + 3 * (size_t)dest(m, h);
    for (int k = 0; k < 3; ++k) d[k] = b[k] - a[k];
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Face frames: x along the face's first halfedge, y = n x x. */
static void face_frame(const sq_mesh *m, uint32_t f, double x[3], double y[3], double *area)
{
    const uint32_t h = m->f_he[f];
    double e0[3], e1[3], n[3];
    edge_vec(m, h, e0);
    edge_vec(m, m->he_next[h], e1);
    cross3(e0, e1, n);
    const double nn = sqrt(dot3(n, n)), l0 = sqrt(dot3(e0, e0));
    *area = 0.5 * nn;
    for (int k = 0; k < 3; ++k) x[k] = e0[k] / l0, n[k] /= nn;
    cross3(n, x, y);
}

static double wrap_pi(double a)
{
    while (a > PI) a -= 2.0 * PI;
    while (a <= -PI) a += 2.0 * PI;
    return a;
}

/* Quadratic form (n - n*)^T G (n - n*) */
static double qform(uint32_t k, const double *G, const double *d)
{
    double s = 0.0;
    for (uint32_t i = 0; i < k; ++i)
        for (uint32_t j = 0; j < k; ++j) s += d[i] * G[(size_t)i * k + j] * d[j];
    return s;
}

/* The integers n closest to nstar in the metric G: exhaustive over
 * round(nstar) + {-1, 0, 1}^k for k <= 10, else coordinate descent from
 * the rounding. */
static int closest_lattice(uint32_t k, const double *G, const double *nstar, double *n)
{
    double *d = malloc((k + 1) * sizeof *d), *best = malloc((k + 1) * sizeof *best);
    int *off = calloc(k + 1, sizeof *off);
    if (!d || !best || !off) {
        free(d), free(best), free(off);
        return -1;
    }
    for (uint32_t i = 0; i < k; ++i) n[i] = nearbyint(nstar[i]);
    int exact = k <= 10;
    if (exact) {
        double bestv = INFINITY;
        for (uint32_t i = 0; i < k; ++i) off[i] = -1;
        for (;;) {
            for (uint32_t i = 0; i < k; ++i) d[i] = n[i] + off[i] - nstar[i];
            const double v = qform(k, G, d);
            if (v < bestv) {
                bestv = v;
                for (uint32_t i = 0; i < k; ++i) best[i] = n[i] + off[i];
            }
            uint32_t i = 0;
            while (i < k && off[i] == 1) off[i++] = -1;
            if (i == k) break;
            off[i]++;
        }
        memcpy(n, best, k * sizeof *n);
    } else {
        for (uint32_t i = 0; i < k; ++i) d[i] = n[i] - nstar[i];
        double cur = qform(k, G, d);
        for (int improved = 1; improved;) {
            improved = 0;
            for (uint32_t i = 0; i < k; ++i)
                for (int s = -1; s <= 1; s += 2) {
                    d[i] += s;
                    const double v = qform(k, G, d);
                    if (v < cur - 1e-12) cur = v, n[i] += s, improved = 1;
                    else d[i] -= s;
                }
        }
    }
    free(d), free(best), free(off);
    return exact;
}

/* The arrays the steps share. Edges are the canonical halfedges h <
 * twin(h), numbered e = eid[h] (= eid[twin h]); ehe[e] is that halfedge.
 * Per-edge quantities are measured crossing ehe[e] from its face to its
 * twin's. */
typedef struct conn {
    const sq_mesh *m;
    uint32_t ne, ng;          /* edges; generators (2 genus)                */
    uint32_t *eid, *ehe;
    double *rho, *w, *a;      /* transport, weight, correction (per edge)   */
    uint32_t *vpar, *fpar;    /* vertex tree: halfedge from the parent;     */
                              /* face tree: halfedge crossed from the parent */
    uint32_t *depthv, *depthf;
    uint32_t *gen;            /* ng: the leftover edges' halfedges           */
    double *z;                /* ng x ne: harmonic forms, period delta_jk    */
    double *G;                /* ng x ng: their Gram matrix                  */
    double *nstar;            /* ng: generator totals of rho + a / quarter   */
    sq_error *err;
} conn;

static double sign_of(const conn *C, uint32_t h) { return h == C->ehe[C->eid[h]] ? 1.0 : -1.0; }

/* rho: Levi-Civita transport (unfolding) from face(h) to face(twin h);
 * w: |e|^2 / (area f + area g), clamped to 1e-6 .. 1e6 of the mean so
 * that the systems stay well scaled. */
static sq_status edge_geometry(conn *C)
{
    const sq_mesh *m = C->m;
    double *fx = malloc((size_t)m->nf * 6 * sizeof *fx), *farea = malloc((size_t)m->nf * sizeof *farea);
    if (!fx || !farea) {
        free(fx), free(farea);
        return sq_error_set(C->err, SQ_ERR_NOMEM, "cone connection: out of memory");
    }
    for (uint32_t f = 0; f < m->nf; ++f) face_frame(m, f, fx + 6 * (size_t)f, fx + 6 * (size_t)f + 3, farea + f);
    double wsum = 0.0;
    for (uint32_t e = 0; e < C->ne; ++e) {
        const uint32_t h = C->ehe[e], f = m->he_face[h], g = m->he_face[m->he_twin[h]];
        double d[3];
        edge_vec(m, h, d);
        const double *xf = fx + 6 * (size_t)f, *xg = fx + 6 * (size_t)g;
        const double thf = atan2(dot3(d, xf + 3), dot3(d, xf));
        const double thg = atan2(dot3(d, xg + 3), dot3(d, xg)); /* the same vector in g's frame */
        C->rho[e] = wrap_pi(thg - thf);
        const double A = farea[f] + farea[g];
        C->w[e] = A > 0.0 ? dot3(d, d) / A : 1.0;
        wsum += C->w[e];
    }
    const double lo = 1e-6 * wsum / C->ne, hi = 1e6 * wsum / C->ne;
    for (uint32_t e = 0; e < C->ne; ++e) {
        if (!(C->w[e] >= lo)) C->w[e] = lo;
        if (C->w[e] > hi) C->w[e] = hi;
    }
    free(fx), free(farea);
    return SQ_OK;
}

/* The correction a with the smallest norm giving every vertex loop its
 * cone's defect: sum over the loop around v of a = defect_v - K_v. The
 * loop crosses he_prev(o): the edge's sign there is +1 if its canonical
 * halfedge ends at v, -1 if it starts there. a = W^-1 C^T lambda with
 * (C W^-1 C^T) lambda = b, a vertex Laplacian; vertex 0 pinned (b sums to
 * 0 by Gauss-Bonnet). */
static sq_status vertex_correction(conn *C, const int32_t *valence)
{
    const sq_mesh *m = C->m;
    const uint32_t nv = m->nv, ne = C->ne;
    double *angsum = calloc(nv, sizeof *angsum), *bv = calloc(nv, sizeof *bv), *lam = calloc(nv, sizeof *lam);
    uint32_t *ti = malloc((3 * (size_t)ne + 1) * sizeof *ti), *tj = malloc((3 * (size_t)ne + 1) * sizeof *tj);
    double *tv = malloc((3 * (size_t)ne + 1) * sizeof *tv);
    sq_status st = SQ_OK;
    if (!angsum || !bv || !lam || !ti || !tj || !tv) {
        st = sq_error_set(C->err, SQ_ERR_NOMEM, "cone connection: out of memory");
        goto done;
    }
    for (uint32_t h = 0; h < m->nh; ++h) { /* corner angles */
        double u[3], v2[3], cr[3];
        edge_vec(m, h, u);
        edge_vec(m, prev_he(m, h), v2);
        for (int k = 0; k < 3; ++k) v2[k] = -v2[k];
        cross3(u, v2, cr);
        angsum[m->he_vert[h]] += atan2(sqrt(dot3(cr, cr)), dot3(u, v2));
    }
    for (uint32_t v = 0; v < nv; ++v) bv[v] = (4 - valence[v]) * QUARTER - (2.0 * PI - angsum[v]);
    if (nv > 1) {
        size_t nz = 0;
        for (uint32_t e = 0; e < ne; ++e) {
            const uint32_t h = C->ehe[e], x = m->he_vert[h], y = dest(m, h);
            const double iw = 1.0 / C->w[e];
            if (x) ti[nz] = x - 1, tj[nz] = x - 1, tv[nz++] = iw;
            if (y) ti[nz] = y - 1, tj[nz] = y - 1, tv[nz++] = iw;
            if (x && y) ti[nz] = (x > y ? x : y) - 1, tj[nz] = (x > y ? y : x) - 1, tv[nz++] = -iw;
        }
        sq_spd *F = NULL;
        st = sq_spd_factor(nv - 1, nz, ti, tj, tv, &F, C->err);
        if (st == SQ_OK) st = sq_spd_solve(F, 1, bv + 1, lam + 1, C->err);
        sq_spd_free(F);
        if (st) goto done;
    }
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t h = C->ehe[e];
        C->a[e] = (lam[dest(m, h)] - lam[m->he_vert[h]]) / C->w[e];
    }
done:
    free(angsum), free(bv), free(lam), free(ti), free(tj), free(tv);
    return st;
}

/* Tree-cotree: a BFS vertex tree, a BFS face tree over the other edges,
 * and the 2g edges left over (C->gen). */
static sq_status tree_cotree(conn *C)
{
    const sq_mesh *m = C->m;
    uint32_t *queue = malloc(((size_t)m->nv + m->nf) * sizeof *queue);
    uint8_t *intree = calloc(C->ne, 1);
    if (!queue || !intree) {
        free(queue), free(intree);
        return sq_error_set(C->err, SQ_ERR_NOMEM, "cone connection: out of memory");
    }
    for (uint32_t v = 0; v < m->nv; ++v) C->vpar[v] = SQ_NONE;
    for (uint32_t f = 0; f < m->nf; ++f) C->fpar[f] = SQ_NONE;
    uint32_t qh = 0, qt = 0;
    queue[qt++] = 0, C->depthv[0] = 0;
    C->vpar[0] = SQ_NONE - 1; /* the root: reached, no parent */
    while (qh < qt) {
        const uint32_t x = queue[qh++], h0 = m->v_he[x];
        uint32_t h = h0;
        do {
            const uint32_t y = dest(m, h);
            if (C->vpar[y] == SQ_NONE)
                C->vpar[y] = h, C->depthv[y] = C->depthv[x] + 1, intree[C->eid[h]] = 1, queue[qt++] = y;
            h = m->he_next[m->he_twin[h]];
        } while (h != h0);
    }
    qh = qt = 0;
    queue[qt++] = 0, C->depthf[0] = 0;
    C->fpar[0] = SQ_NONE - 1;
    while (qh < qt) {
        const uint32_t f = queue[qh++], h0 = m->f_he[f];
        uint32_t h = h0;
        do {
            const uint32_t g = m->he_face[m->he_twin[h]];
            if (!intree[C->eid[h]] && C->fpar[g] == SQ_NONE)
                C->fpar[g] = h, C->depthf[g] = C->depthf[f] + 1, intree[C->eid[h]] = 2, queue[qt++] = g;
            h = m->he_next[h];
        } while (h != h0);
    }
    C->vpar[0] = SQ_NONE, C->fpar[0] = SQ_NONE;
    uint32_t k = 0;
    for (uint32_t e = 0; e < C->ne && k <= C->ng; ++e)
        if (!intree[e]) {
            if (k < C->ng) C->gen[k] = C->ehe[e];
            ++k;
        }
    free(queue), free(intree);
    if (k != C->ng)
        return sq_error_set(C->err, SQ_ERR_INTERNAL, "cone connection: %u generators for genus %u", k, C->ng / 2);
    return SQ_OK;
}

/* Harmonic forms: z_k = +1 along the primal loop of generator k (its edge,
 * then the vertex tree back), a closed form whose period on dual generator
 * j is delta_jk; its exact part removed by the face Laplacian (face 0
 * pinned); then their Gram matrix. */
static sq_status harmonic_basis(conn *C)
{
    const sq_mesh *m = C->m;
    const uint32_t ne = C->ne, ng = C->ng, nf = m->nf;
    if (!ng) return SQ_OK;
    double *rhs = calloc((size_t)nf * ng, sizeof *rhs), *psi = calloc((size_t)nf * ng, sizeof *psi);
    uint32_t *ti = malloc((3 * (size_t)ne + 1) * sizeof *ti), *tj = malloc((3 * (size_t)ne + 1) * sizeof *tj);
    double *tv = malloc((3 * (size_t)ne + 1) * sizeof *tv);
    sq_status st = SQ_OK;
    if (!rhs || !psi || !ti || !tj || !tv) {
        st = sq_error_set(C->err, SQ_ERR_NOMEM, "cone connection: out of memory");
        goto done;
    }
    for (uint32_t k = 0; k < ng; ++k) {
        double *zk = C->z + (size_t)k * ne;
        const uint32_t h = C->gen[k];
        zk[C->eid[h]] += sign_of(C, h);
        uint32_t x = dest(m, h), y = m->he_vert[h]; /* the tree path x -> y */
        while (x != y) {
            if (C->depthv[x] >= C->depthv[y]) { /* x up: cross from x to its parent */
                const uint32_t p = m->he_twin[C->vpar[x]];
                zk[C->eid[p]] += sign_of(C, p);
                x = dest(m, p);
            } else { /* y up: the path enters y from its parent */
                const uint32_t p = C->vpar[y];
                zk[C->eid[p]] += sign_of(C, p);
                y = m->he_vert[p];
            }
        }
        for (uint32_t e = 0; e < ne; ++e) {
            if (zk[e] == 0.0) continue;
            const uint32_t he = C->ehe[e], f = m->he_face[he], g = m->he_face[m->he_twin[he]];
            /* rows of the pinned face dropped: face f is row f - 1 */
            if (g) rhs[(size_t)k * (nf - 1) + g - 1] += C->w[e] * zk[e];
            if (f) rhs[(size_t)k * (nf - 1) + f - 1] -= C->w[e] * zk[e];
        }
    }
    size_t nz = 0;
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t h = C->ehe[e], f = m->he_face[h], g = m->he_face[m->he_twin[h]];
        if (f) ti[nz] = f - 1, tj[nz] = f - 1, tv[nz++] = C->w[e];
        if (g) ti[nz] = g - 1, tj[nz] = g - 1, tv[nz++] = C->w[e];
        if (f && g) ti[nz] = (f > g ? f : g) - 1, tj[nz] = (f > g ? g : f) - 1, tv[nz++] = -C->w[e];
    }
    sq_spd *F = NULL;
    st = sq_spd_factor(nf - 1, nz, ti, tj, tv, &F, C->err);
    if (st == SQ_OK) st = sq_spd_solve(F, ng, rhs, psi, C->err);
    sq_spd_free(F);
    if (st) goto done;
    for (uint32_t k = 0; k < ng; ++k) {
        const double *pk = psi + (size_t)k * (nf - 1);
        double *zk = C->z + (size_t)k * ne;
        for (uint32_t e = 0; e < ne; ++e) {
            const uint32_t h = C->ehe[e], f = m->he_face[h], g = m->he_face[m->he_twin[h]];
            zk[e] -= (g ? pk[g - 1] : 0.0) - (f ? pk[f - 1] : 0.0);
        }
    }
    for (uint32_t i = 0; i < ng; ++i)
        for (uint32_t j = 0; j < ng; ++j) {
            double sum = 0.0;
            for (uint32_t e = 0; e < ne; ++e) sum += C->w[e] * C->z[(size_t)i * ne + e] * C->z[(size_t)j * ne + e];
            C->G[(size_t)i * ng + j] = sum;
        }
done:
    free(rhs), free(psi), free(ti), free(tj), free(tv);
    return st;
}

/* Totals of rho + a on the dual generators (the generator's edge, then
 * the face tree back), in quarter turns. */
static void generator_periods(conn *C)
{
    const sq_mesh *m = C->m;
    for (uint32_t j = 0; j < C->ng; ++j) {
        const uint32_t h = C->gen[j];
        double t = 0.0;
#define CROSS(hh) do { const uint32_t q_ = (hh); t += sign_of(C, q_) * (C->rho[C->eid[q_]] + C->a[C->eid[q_]]); } while (0)
        CROSS(h);
        uint32_t x = m->he_face[m->he_twin[h]], y = m->he_face[h]; /* the face path x -> y */
        while (x != y) {
            if (C->depthf[x] >= C->depthf[y]) {
                CROSS(m->he_twin[C->fpar[x]]);
                x = m->he_face[C->fpar[x]];
            } else {
                CROSS(C->fpar[y]);
                y = m->he_face[C->fpar[y]];
            }
        }
#undef CROSS
        C->nstar[j] = t / QUARTER;
    }
}

/* Every vertex loop must come out at its cone's index (an error names the
 * first that does not); returns the largest distance from an integer. */
static sq_status check_vertex_loops(const sq_mesh *m, const int32_t *valence, const double *turn,
                                    double *maxres, sq_error *err)
{
    *maxres = 0.0;
    for (uint32_t v = 0; v < m->nv; ++v) {
        const uint32_t h0 = m->v_he[v];
        uint32_t h = h0;
        double s = 0.0;
        do {
            s += turn[prev_he(m, h)];
            h = m->he_next[m->he_twin[h]];
        } while (h != h0);
        const double r = fabs(s - nearbyint(s));
        if (r > *maxres) *maxres = r;
        const long want = ((long)(4 - valence[v]) % 4 + 4) % 4, got = ((long)nearbyint(s) % 4 + 4) % 4;
        if (want != got && r < 0.25)
            return sq_error_set(err, SQ_ERR_INTERNAL,
                                "cone connection: vertex %u turns %ld quarter turns, its cone %ld", v, got, want);
    }
    if (*maxres > 1e-6)
        return sq_error_set(err, SQ_ERR_SOLVER, "cone connection: a vertex loop is %.3g quarter turns from an integer",
                            *maxres);
    return SQ_OK;
}

sq_status sq_cone_connection(const sq_mesh *m, const int32_t *valence, double *turn,
                             sq_cone_connection_stats *stats, sq_error *err)
{
    const uint32_t nv = m->nv, nf = m->nf, nh = m->nh, ne = nh / 2;
    const int64_t chi = sq_mesh_euler(m);
    if (chi > 2 || (chi & 1))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cone connection: Euler characteristic %lld", (long long)chi);
    const uint32_t genus = (uint32_t)((2 - chi) / 2), ng = 2 * genus;
    int64_t idx = 0;
    for (uint32_t v = 0; v < nv; ++v) idx += 4 - valence[v];
    if (idx != 4 * chi)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cone connection: the cones' indices add up to %lld quarter turns, "
                            "Gauss-Bonnet needs %lld",
                            (long long)idx, (long long)(4 * chi));
    conn C;
    memset(&C, 0, sizeof C);
    C.m = m, C.ne = ne, C.ng = ng, C.err = err;
    C.eid = malloc((size_t)nh * sizeof *C.eid), C.ehe = malloc((size_t)ne * sizeof *C.ehe);
    C.rho = malloc((size_t)ne * sizeof *C.rho), C.w = malloc((size_t)ne * sizeof *C.w);
    C.a = calloc(ne, sizeof *C.a);
    C.vpar = malloc((size_t)nv * sizeof *C.vpar), C.fpar = malloc((size_t)nf * sizeof *C.fpar);
    C.depthv = malloc((size_t)nv * sizeof *C.depthv), C.depthf = malloc((size_t)nf * sizeof *C.depthf);
    C.gen = malloc((ng + 1) * sizeof *C.gen);
    C.z = calloc((size_t)ne * (ng + 1), sizeof *C.z);
    C.G = calloc((size_t)(ng + 1) * (ng + 1), sizeof *C.G);
    C.nstar = calloc(ng + 1, sizeof *C.nstar);
    double *nint = calloc(ng + 1, sizeof *nint), *c = calloc(ng + 1, sizeof *c);
    sq_status st = SQ_OK;
    if (!C.eid || !C.ehe || !C.rho || !C.w || !C.a || !C.vpar || !C.fpar || !C.depthv || !C.depthf || !C.gen ||
        !C.z || !C.G || !C.nstar || !nint || !c) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cone connection: out of memory");
        goto done;
    }
    uint32_t e = 0;
    for (uint32_t h = 0; h < nh; ++h)
        if (h < m->he_twin[h]) C.eid[h] = C.eid[m->he_twin[h]] = e, C.ehe[e++] = h;
    assert(e == ne);
    st = edge_geometry(&C);
    if (st == SQ_OK) st = vertex_correction(&C, valence);
    if (st == SQ_OK) st = tree_cotree(&C);
    if (st == SQ_OK) st = harmonic_basis(&C);
    if (st) goto done;
    generator_periods(&C);
    /* the harmonic h_k has period delta_jk on dual generator j, so the
     * generators' totals become integers n with c = (pi/2) n - t; n the
     * closest lattice point in the correction's norm c^T G c */
    int exact = 1;
    if (ng) {
        exact = closest_lattice(ng, C.G, C.nstar, nint);
        if (exact < 0) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "cone connection: out of memory");
            goto done;
        }
        for (uint32_t k = 0; k < ng; ++k) c[k] = QUARTER * (nint[k] - C.nstar[k]);
    }
    double energy = 0.0;
    for (e = 0; e < ne; ++e) {
        double x = C.a[e];
        for (uint32_t k = 0; k < ng; ++k) x += c[k] * C.z[(size_t)k * ne + e];
        energy += C.w[e] * x * x;
        const double q = (C.rho[e] + x) / QUARTER;
        turn[C.ehe[e]] = q;
        turn[m->he_twin[C.ehe[e]]] = -q;
    }
    double maxres = 0.0;
    st = check_vertex_loops(m, valence, turn, &maxres, err);
    if (st) goto done;
    if (stats) {
        stats->genus = genus;
        stats->energy = energy;
        stats->max_residual = maxres;
        stats->exact_lattice = exact;
    }
done:
    free(C.eid), free(C.ehe), free(C.rho), free(C.w), free(C.a), free(C.vpar), free(C.fpar);
    free(C.depthv), free(C.depthf), free(C.gen), free(C.z), free(C.G), free(C.nstar), free(nint), free(c);
    return st;
}

uint32_t sq_cone_connection_rotation(const double *turn, const uint32_t *crossed, uint32_t n)
{
    double s = 0.0;
    for (uint32_t i = 0; i < n; ++i) s += turn[crossed[i]];
    const long r = (long)nearbyint(s);
    return (uint32_t)(((r % 4) + 4) % 4);
}
