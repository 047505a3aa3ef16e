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

sq_status sq_cone_connection(const sq_mesh *m, const int32_t *valence, double *turn,
                             sq_cone_connection_stats *stats, sq_error *err)
{
    const uint32_t nv = m->nv, nf = m->nf, nh = m->nh, ne = nh / 2;
    const int64_t chi = sq_mesh_euler(m);
    if (chi > 2 || (chi & 1))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cone connection: Euler characteristic %lld",
                            (long long)chi);
    const uint32_t genus = (uint32_t)((2 - chi) / 2), ng = 2 * genus;
    int64_t idx = 0;
    for (uint32_t v = 0; v < nv; ++v) idx += 4 - valence[v];
    if (idx != 4 * chi)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "cone connection: the cones' indices add up to %lld quarter turns, "
                            "Gauss-Bonnet needs %lld",
                            (long long)idx, (long long)(4 * chi));
    sq_status st = SQ_OK;
    uint32_t *eid = malloc((size_t)nh * sizeof *eid), *ehe = malloc((size_t)ne * sizeof *ehe);
    double *fx = malloc((size_t)nf * 6 * sizeof *fx), *farea = malloc((size_t)nf * sizeof *farea);
    double *rho = malloc((size_t)ne * sizeof *rho), *w = malloc((size_t)ne * sizeof *w);
    double *a = calloc(ne, sizeof *a), *angsum = calloc(nv, sizeof *angsum);
    double *bv = calloc(nv, sizeof *bv), *lam = calloc(nv, sizeof *lam);
    uint32_t *ti = malloc(((size_t)3 * ne + nf + nv) * sizeof *ti);
    uint32_t *tj = malloc(((size_t)3 * ne + nf + nv) * sizeof *tj);
    double *tv = malloc(((size_t)3 * ne + nf + nv) * sizeof *tv);
    uint32_t *vpar = malloc((size_t)nv * sizeof *vpar), *fpar = malloc((size_t)nf * sizeof *fpar);
    uint32_t *queue = malloc(((size_t)nv + nf) * sizeof *queue);
    uint8_t *intree = calloc(ne, 1);
    uint32_t *depthv = malloc((size_t)nv * sizeof *depthv), *depthf = malloc((size_t)nf * sizeof *depthf);
    uint32_t *gen = malloc((ng + 1) * sizeof *gen);
    double *z = calloc((size_t)ne * (ng + 1), sizeof *z);
    double *rhs = calloc((size_t)nf * (ng + 1), sizeof *rhs), *psi = calloc((size_t)nf * (ng + 1), sizeof *psi);
    double *G = calloc((size_t)(ng + 1) * (ng + 1), sizeof *G), *nstar = calloc(ng + 1, sizeof *nstar);
    double *nint = calloc(ng + 1, sizeof *nint), *c = calloc(ng + 1, sizeof *c);
    uint32_t *cyc = malloc(((size_t)nf + nv + 2) * sizeof *cyc);
    sq_spd *F = NULL;
    if (!eid || !ehe || !fx || !farea || !rho || !w || !a || !angsum || !bv || !lam || !ti || !tj ||
        !tv || !vpar || !fpar || !queue || !intree || !depthv || !depthf || !gen || !z || !rhs ||
        !psi || !G || !nstar || !nint || !c || !cyc) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cone connection: out of memory");
        goto done;
    }
    {
        uint32_t e = 0;
        for (uint32_t h = 0; h < nh; ++h)
            if (h < m->he_twin[h]) eid[h] = eid[m->he_twin[h]] = e, ehe[e++] = h;
        assert(e == ne);
    }
    for (uint32_t f = 0; f < nf; ++f) face_frame(m, f, fx + 6 * (size_t)f, fx + 6 * (size_t)f + 3, farea + f);
    /* rho: Levi-Civita transport (unfolding) from face(h) to face(twin h);
     * w: |e|^2 / (area f + area g); angle sums at the vertices */
    double wsum = 0.0;
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t h = ehe[e], t = m->he_twin[h], f = m->he_face[h], g = m->he_face[t];
        double d[3];
        edge_vec(m, h, d);
        const double *xf = fx + 6 * (size_t)f, *xg = fx + 6 * (size_t)g;
        const double thf = atan2(dot3(d, xf + 3), dot3(d, xf));
        const double thg = atan2(dot3(d, xg + 3), dot3(d, xg)); /* the same vector in g's frame */
        rho[e] = wrap_pi(thg - thf);
        const double A = farea[f] + farea[g];
        w[e] = A > 0.0 ? dot3(d, d) / A : 1.0;
        wsum += w[e];
    }
    for (uint32_t e = 0; e < ne; ++e) { /* keep the system well scaled */
        const double lo = 1e-6 * wsum / ne, hi = 1e6 * wsum / ne;
        if (!(w[e] >= lo)) w[e] = lo;
        if (w[e] > hi) w[e] = hi;
    }
    for (uint32_t h = 0; h < nh; ++h) {
        double u[3], v2[3];
        edge_vec(m, h, u);
        edge_vec(m, prev_he(m, h), v2);
        for (int k = 0; k < 3; ++k) v2[k] = -v2[k];
        double cr[3];
        cross3(u, v2, cr);
        angsum[m->he_vert[h]] += atan2(sqrt(dot3(cr, cr)), dot3(u, v2));
    }
    /* vertex constraints: sum over the loop around v of a = defect_v - K_v;
     * the loop crosses he_prev(o): C[v][e] = +1 if the canonical halfedge
     * ends at v, -1 if it starts there. Min-norm a = W^-1 C^T lambda with
     * (C W^-1 C^T) lambda = b, a vertex Laplacian; vertex 0 pinned. */
    for (uint32_t v = 0; v < nv; ++v) {
        const double K = 2.0 * PI - angsum[v];
        bv[v] = (4 - valence[v]) * QUARTER - K;
    }
    if (nv > 1) {
        size_t nz = 0;
        for (uint32_t e = 0; e < ne; ++e) {
            const uint32_t h = ehe[e], x = m->he_vert[h], y = dest(m, h);
            const double iw = 1.0 / w[e];
            if (x) ti[nz] = x - 1, tj[nz] = x - 1, tv[nz++] = iw;
            if (y) ti[nz] = y - 1, tj[nz] = y - 1, tv[nz++] = iw;
            if (x && y) ti[nz] = (x > y ? x : y) - 1, tj[nz] = (x > y ? y : x) - 1, tv[nz++] = -iw;
        }
        st = sq_spd_factor(nv - 1, nz, ti, tj, tv, &F, err);
        if (st == SQ_OK) st = sq_spd_solve(F, 1, bv + 1, lam + 1, err);
        sq_spd_free(F);
        F = NULL;
        if (st) goto done;
    }
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t h = ehe[e];
        a[e] = (lam[dest(m, h)] - lam[m->he_vert[h]]) / w[e];
    }
    /* tree-cotree: BFS vertex tree (vpar: halfedge from the parent), BFS
     * face tree over the other edges (fpar: halfedge crossed from the
     * parent face), 2g leftover edges */
    for (uint32_t v = 0; v < nv; ++v) vpar[v] = SQ_NONE;
    for (uint32_t f = 0; f < nf; ++f) fpar[f] = SQ_NONE;
    {
        uint32_t qh = 0, qt = 0;
        queue[qt++] = 0;
        vpar[0] = SQ_NONE - 1, depthv[0] = 0;
        while (qh < qt) {
            const uint32_t x = queue[qh++], h0 = m->v_he[x];
            uint32_t h = h0;
            do {
                const uint32_t y = dest(m, h);
                if (vpar[y] == SQ_NONE) vpar[y] = h, depthv[y] = depthv[x] + 1, intree[eid[h]] = 1, queue[qt++] = y;
                h = m->he_next[m->he_twin[h]];
            } while (h != h0);
        }
        qh = qt = 0;
        queue[qt++] = 0;
        fpar[0] = SQ_NONE - 1, depthf[0] = 0;
        while (qh < qt) {
            const uint32_t f = queue[qh++], h0 = m->f_he[f];
            uint32_t h = h0;
            do {
                const uint32_t g = m->he_face[m->he_twin[h]];
                if (!intree[eid[h]] && fpar[g] == SQ_NONE)
                    fpar[g] = h, depthf[g] = depthf[f] + 1, intree[eid[h]] = 2, queue[qt++] = g;
                h = m->he_next[h];
            } while (h != h0);
        }
        uint32_t k = 0;
        for (uint32_t e = 0; e < ne; ++e)
            if (!intree[e]) {
                if (k == ng) {
                    k = ng + 1;
                    break;
                }
                gen[k++] = ehe[e];
            }
        if (k != ng) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cone connection: %u generators for genus %u", k,
                              genus);
            goto done;
        }
    }
    vpar[0] = SQ_NONE, fpar[0] = SQ_NONE;
    /* z_k: +1 on the primal loop of generator k (its edge, then the tree
     * path back), a closed form whose period on dual generator j is
     * delta_jk; harmonic part by the face Laplacian (face 0 pinned) */
    for (uint32_t k = 0; k < ng; ++k) {
        double *zk = z + (size_t)k * ne;
        const uint32_t h = gen[k];
        zk[eid[h]] += h == ehe[eid[h]] ? 1.0 : -1.0;
        uint32_t x = dest(m, h), y = m->he_vert[h]; /* path x -> y in the tree */
        while (x != y) {
            if (depthv[x] >= depthv[y]) { /* x up: cross from x to its parent */
                const uint32_t p = m->he_twin[vpar[x]];
                zk[eid[p]] += p == ehe[eid[p]] ? 1.0 : -1.0;
                x = m->he_vert[p] == x ? dest(m, p) : m->he_vert[p];
            } else { /* y up: the path enters y from its parent */
                const uint32_t p = vpar[y];
                zk[eid[p]] += p == ehe[eid[p]] ? 1.0 : -1.0;
                y = m->he_vert[p];
            }
        }
        for (uint32_t e = 0; e < ne; ++e) {
            if (zk[e] == 0.0) continue;
            const uint32_t he = ehe[e], f = m->he_face[he], g = m->he_face[m->he_twin[he]];
            rhs[(size_t)k * nf + g] += w[e] * zk[e];
            rhs[(size_t)k * nf + f] -= w[e] * zk[e];
        }
    }
    if (ng) {
        size_t nz = 0;
        for (uint32_t e = 0; e < ne; ++e) {
            const uint32_t h = ehe[e], f = m->he_face[h], g = m->he_face[m->he_twin[h]];
            if (f) ti[nz] = f - 1, tj[nz] = f - 1, tv[nz++] = w[e];
            if (g) ti[nz] = g - 1, tj[nz] = g - 1, tv[nz++] = w[e];
            if (f && g) ti[nz] = (f > g ? f : g) - 1, tj[nz] = (f > g ? g : f) - 1, tv[nz++] = -w[e];
        }
        /* the solver wants the pinned face's row gone: shift the blocks */
        for (uint32_t k = 0; k < ng; ++k) memmove(rhs + (size_t)k * (nf - 1), rhs + (size_t)k * nf + 1, (nf - 1) * sizeof *rhs);
        st = sq_spd_factor(nf - 1, nz, ti, tj, tv, &F, err);
        if (st == SQ_OK) st = sq_spd_solve(F, ng, rhs, psi, err);
        sq_spd_free(F);
        F = NULL;
        if (st) goto done;
        for (uint32_t k = 0; k < ng; ++k) {
            const double *pk = psi + (size_t)k * (nf - 1);
            double *zk = z + (size_t)k * ne;
            for (uint32_t e = 0; e < ne; ++e) {
                const uint32_t h = ehe[e], f = m->he_face[h], g = m->he_face[m->he_twin[h]];
                zk[e] -= (g ? pk[g - 1] : 0.0) - (f ? pk[f - 1] : 0.0);
            }
        }
        for (uint32_t i = 0; i < ng; ++i)
            for (uint32_t j = 0; j < ng; ++j) {
                double s = 0.0;
                for (uint32_t e = 0; e < ne; ++e) s += w[e] * z[(size_t)i * ne + e] * z[(size_t)j * ne + e];
                G[(size_t)i * ng + j] = s;
            }
    }
    /* periods of rho + a on the dual generators: the generator's edge, then
     * the face-tree path back */
    for (uint32_t j = 0; j < ng; ++j) {
        const uint32_t h = gen[j];
        double t = 0.0;
#define CROSS(hh) do { const uint32_t q_ = (hh); const double s_ = q_ == ehe[eid[q_]] ? 1.0 : -1.0; \
                       t += s_ * (rho[eid[q_]] + a[eid[q_]]); } while (0)
        CROSS(h);
        uint32_t x = m->he_face[m->he_twin[h]], y = m->he_face[h]; /* x -> y */
        while (x != y) {
            if (depthf[x] >= depthf[y]) {
                CROSS(m->he_twin[fpar[x]]);
                x = m->he_face[fpar[x]];
            } else {
                CROSS(fpar[y]);
                y = m->he_face[m->he_twin[fpar[y]]] == y ? m->he_face[fpar[y]] : y;
            }
        }
#undef CROSS
        nstar[j] = t / QUARTER;
    }
    int exact = 1;
    if (ng) {
        /* the period of h_k on dual generator j is delta_jk (sign +1: the
         * generator's edge is crossed along its primal loop), so
         * c = (pi/2) n - t, minimizing c^T G c */
        exact = closest_lattice(ng, G, nstar, nint);
        if (exact < 0) {
            st = sq_error_set(err, SQ_ERR_NOMEM, "cone connection: out of memory");
            goto done;
        }
        for (uint32_t k = 0; k < ng; ++k) c[k] = QUARTER * (nint[k] - nstar[k]);
    }
    double energy = 0.0;
    for (uint32_t e = 0; e < ne; ++e) {
        double x = a[e];
        for (uint32_t k = 0; k < ng; ++k) x += c[k] * z[(size_t)k * ne + e];
        energy += w[e] * x * x;
        const double q = (rho[e] + x) / QUARTER;
        turn[ehe[e]] = q;
        turn[m->he_twin[ehe[e]]] = -q;
    }
    /* residuals: every vertex loop must come out at its cone's index */
    double maxres = 0.0;
    for (uint32_t v = 0; v < nv; ++v) {
        const uint32_t h0 = m->v_he[v];
        uint32_t h = h0, n = 0;
        do {
            cyc[n++] = prev_he(m, h);
            h = m->he_next[m->he_twin[h]];
        } while (h != h0);
        double s = 0.0;
        for (uint32_t i = 0; i < n; ++i) s += turn[cyc[i]];
        const double r = fabs(s - nearbyint(s));
        if (r > maxres) maxres = r;
        const long want = ((long)(4 - valence[v]) % 4 + 4) % 4, got = ((long)nearbyint(s) % 4 + 4) % 4;
        if (want != got && r < 0.25) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cone connection: vertex %u turns %ld quarter turns, its cone %ld", v,
                              got, want);
            goto done;
        }
    }
    if (maxres > 1e-6) {
        st = sq_error_set(err, SQ_ERR_SOLVER,
                          "cone connection: a vertex loop is %.3g quarter turns from an integer", maxres);
        goto done;
    }
    if (stats) {
        stats->genus = genus;
        stats->energy = energy;
        stats->max_residual = maxres;
        stats->exact_lattice = exact;
    }
done:
    sq_spd_free(F);
    free(eid), free(ehe), free(fx), free(farea), free(rho), free(w), free(a), free(angsum);
    free(bv), free(lam), free(ti), free(tj), free(tv), free(vpar), free(fpar), free(queue);
    free(intree), free(depthv), free(depthf), free(gen), free(z), free(rhs), free(psi), free(G);
    free(nstar), free(nint), free(c), free(cyc);
    return st;
}

uint32_t sq_cone_connection_rotation(const double *turn, const uint32_t *crossed, uint32_t n)
{
    double s = 0.0;
    for (uint32_t i = 0; i < n; ++i) s += turn[crossed[i]];
    const long r = (long)nearbyint(s);
    return (uint32_t)(((r % 4) + 4) % 4);
}
