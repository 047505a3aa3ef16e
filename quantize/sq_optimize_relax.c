/* seamquad: local relaxation of a map's extreme triangles, step 0 of
 * sq_optimize_map (sq_optimize_internal.h, docs/optimize.md).
 *
 * Why: param's maps hold slivers far below the scale of their neighbours
 * (fandisk: 94 triangles of UV area 1e-97 to 1e-20 against a mean of 1e-2,
 * corners 1e-93 off a straight side). Newton widens such a triangle by a
 * bounded factor per step, and a moved seam vertex is rounded to a grid of
 * about 1e-14 of the map's extent (sq_optimize.c, eval_fixed_exact), so the
 * slivers never move, and their barriers (symmetric Dirichlet energy
 * 1e186) keep the map's mean distortion where it was through any number of
 * iterations.
 *
 * What: a vertex that is not a cone, beside a triangle stretched by more
 * than the bound, is moved to whichever of a few candidates lowers the
 * worst stretch of its triangles: the mean of its neighbours and the mean
 * of the apexes that would make each of its triangles similar to its
 * triangle on the surface, each at 8^-j of the way (j = 0..RELAX_STEPS).
 * The stretch of a triangle is max(s1, 1/s2) (s1 >= s2 the singular values
 * of the Jacobian from the surface, as the optimizer scales it;
 * sq_sd_log_stretch). A move is a jump, not a small step: a sliver corner
 * goes straight to the scale of its neighbours, and a stack of slivers
 * opens from the outside in. A vertex on a seam moves its first corner
 * rounded to the grid and the others by the transitions, every sum exact
 * (no seam vertex moves if grid is 0). A move is kept only if every
 * triangle of the vertex is positive by the exact predicate (sq_orient2d)
 * and the worst stretch among them fell by RELAX_GAIN, so the map stays
 * exact and valid and no triangle ends worse than the worst it started
 * beside.
 *
 * Order: a FIFO of the vertices beside a triangle above the bound, then of
 * every vertex whose ring a move changed; at most RELAX_TRIES tries per
 * vertex first queued. Cost per try: the candidates (a few, the search
 * along a target stops once the ring gets worse) times the valence. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_map_internal.h"
#include "sq_optimize_internal.h"
#include "sq_predicates.h"

/* at most this many tries per vertex first queued, on average */
#define RELAX_TRIES 100
/* the candidates along each target: 8^-j of the way, j = 0..RELAX_STEPS
 * (down to 1e-36: a stack of slivers spans tens of orders of magnitude) */
#define RELAX_STEPS 40
/* a move must lower the worst log stretch of the ring by this (1%) */
#define RELAX_GAIN 0.01

/* A vertex's corners around it: he[k] its k-th outgoing halfedge
 * (counterclockwise from v_he), rot[k] the rotation from the chart of
 * he[0] to that of he[k], uv[2k..] the corner (scratch). */
typedef struct ring {
    uint32_t n, cap;
    uint32_t *he;
    uint8_t *rot;
    double *uv;
    int seam; /* some transition around v is not the identity */
} ring;

static int ring_load(const sq_map *M, uint32_t v, ring *R)
{
    const sq_mesh *m = &M->mesh;
    uint32_t h0 = m->v_he[v], h = h0, n = 0;
    uint8_t r = 0;
    R->seam = 0;
    do {
        if (n == R->cap) {
            uint32_t cap = R->cap ? 2 * R->cap : 16;
            uint32_t *he = realloc(R->he, cap * sizeof *he);
            if (he) R->he = he;
            uint8_t *rot = realloc(R->rot, cap);
            if (rot) R->rot = rot;
            double *uv = realloc(R->uv, 2 * (size_t)cap * sizeof *uv);
            if (uv) R->uv = uv;
            if (!he || !rot || !uv) return 0;
            R->cap = cap;
        }
        R->he[n] = h, R->rot[n] = r, n++;
        uint32_t e = sq_map_prev(m, h);
        if (M->he_rot[e] != 0 || M->he_t[2 * (size_t)e] != 0 || M->he_t[2 * (size_t)e + 1] != 0) R->seam = 1;
        r = (uint8_t)((r + M->he_rot[e]) & 3);
        h = sq_map_rotate_out(m, h);
    } while (h != h0);
    R->n = n;
    return 1;
}

/* v's corners with its first at p (rounded to the grid g on a seam), the
 * others by the transitions around it, into R->uv; 0 if a sum is not
 * exact or the walk does not close. */
static int ring_place(const sq_map *M, ring *R, const double p[2], double g)
{
    const sq_mesh *m = &M->mesh;
    double q[2] = {p[0], p[1]};
    if (R->seam) q[0] = nearbyint(q[0] / g) * g, q[1] = nearbyint(q[1] / g) * g;
    for (uint32_t k = 0; k < R->n; k++) {
        R->uv[2 * k] = q[0], R->uv[2 * k + 1] = q[1];
        uint32_t e = sq_map_prev(m, R->he[k]);
        double nq[2];
        if (!sq_map_apply(M->he_rot[e], M->he_t + 2 * (size_t)e, q, nq)) return 0;
        q[0] = nq[0], q[1] = nq[1];
    }
    return q[0] == R->uv[0] && q[1] == R->uv[1];
}

/* the corners of h's face starting at h's origin */
static void corners_from(const sq_mesh *m, const double *he_uv, uint32_t h, double uv[6])
{
    uint32_t a = m->he_next[h], b = m->he_next[a];
    uv[0] = he_uv[2 * (size_t)h], uv[1] = he_uv[2 * (size_t)h + 1];
    uv[2] = he_uv[2 * (size_t)a], uv[3] = he_uv[2 * (size_t)a + 1];
    uv[4] = he_uv[2 * (size_t)b], uv[5] = he_uv[2 * (size_t)b + 1];
}

/* the face's corners in the order of F (its first halfedge first) */
static void face_uv(const sq_mesh *m, const double *he_uv, uint32_t f, double uv[6])
{
    corners_from(m, he_uv, m->f_he[f], uv);
}

/* The worst log stretch of v's triangles with its corners at R->uv; -1 if
 * one of them would not be positive (exact), or if the angles at v would
 * not sum to 2 pi: a jump (unlike a continuous step) can land where a
 * self-overlapping ring of neighbours winds twice, every triangle positive
 * around a new cone. */
static double ring_worst(const sq_mesh *m, const sq_sd_face *F, const double *he_uv, const ring *R)
{
    double worst = 0, angles = 0;
    for (uint32_t k = 0; k < R->n; k++) {
        uint32_t h = R->he[k], f = m->he_face[h];
        double uv[6];
        face_uv(m, he_uv, f, uv);
        uint32_t c = m->f_he[f] == h ? 0 : m->he_next[m->f_he[f]] == h ? 1 : 2;
        uv[2 * c] = R->uv[2 * k], uv[2 * c + 1] = R->uv[2 * k + 1];
        if (sq_orient2d(uv, uv + 2, uv + 4) <= 0) return -1;
        angles += sq_map_corner_angle(uv + 2 * ((c + 2) % 3), uv + 2 * c, uv + 2 * ((c + 1) % 3));
        if (F[f].area > 0) worst = fmax(worst, sq_sd_log_stretch(&F[f], uv));
    }
    return fabs(angles - 4 * SQ_MAP_HALF_PI) < 1.0 ? worst : -1;
}

/* The two targets of v in the chart of its first corner: the mean of its
 * neighbours, and the mean of the apexes that make each triangle (v, a, b)
 * similar to its surface triangle on its UV edge a b. Each is a mean of
 * displacements from v's corner, rotated back into the first chart. */
static void targets(const sq_mesh *m, const double *he_uv, uint32_t v, const ring *R, double t[4])
{
    double sum[2] = {0, 0}, apex[2] = {0, 0};
    const double *P = m->pos + 3 * (size_t)v;
    for (uint32_t k = 0; k < R->n; k++) {
        uint32_t h = R->he[k], a = m->he_next[h], b = m->he_next[a];
        const double *uh = he_uv + 2 * (size_t)h;
        const double *ua = he_uv + 2 * (size_t)a, *ub = he_uv + 2 * (size_t)b;
        const double *Pa = m->pos + 3 * (size_t)m->he_vert[a], *Pb = m->pos + 3 * (size_t)m->he_vert[b];
        double e[3], w[3], c[3];
        for (int i = 0; i < 3; i++) e[i] = Pb[i] - Pa[i], w[i] = P[i] - Pa[i];
        c[0] = e[1] * w[2] - e[2] * w[1], c[1] = e[2] * w[0] - e[0] * w[2], c[2] = e[0] * w[1] - e[1] * w[0];
        double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        double zr = ee > 0 ? (e[0] * w[0] + e[1] * w[1] + e[2] * w[2]) / ee : 0.5;
        double zi = ee > 0 ? sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / ee : 0.5;
        /* ua + z (ub - ua), complex, as a displacement from uh */
        double dx = ub[0] - ua[0], dy = ub[1] - ua[1];
        double d1[2] = {ua[0] - uh[0], ua[1] - uh[1]};
        double d2[2] = {ua[0] - uh[0] + zr * dx - zi * dy, ua[1] - uh[1] + zr * dy + zi * dx};
        double r1[2], r2[2];
        sq_map_rotate((4 - R->rot[k]) & 3, d1, r1);
        sq_map_rotate((4 - R->rot[k]) & 3, d2, r2);
        sum[0] += r1[0], sum[1] += r1[1], apex[0] += r2[0], apex[1] += r2[1];
    }
    const double *p = he_uv + 2 * (size_t)R->he[0];
    t[0] = p[0] + sum[0] / R->n, t[1] = p[1] + sum[1] / R->n;
    t[2] = p[0] + apex[0] / R->n, t[3] = p[1] + apex[1] / R->n;
}

sq_status sq_optimize_relax(const sq_map *M, const sq_sd_face *F, double bound, double grid,
                            double *he_uv, sq_relax_report *rep, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    memset(rep, 0, sizeof *rep);
    double lb = log(bound);
    double *ls = malloc((size_t)m->nf * sizeof *ls);
    uint8_t *seen = calloc(m->nv, 1);
    uint32_t *list = malloc((size_t)m->nv * sizeof *list);
    ring R = {0};
    sq_status st = SQ_OK;
    if (!ls || !seen || !list) goto nomem;
    double worst = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        double uv[6];
        face_uv(m, he_uv, f, uv);
        ls[f] = F[f].area > 0 ? sq_sd_log_stretch(&F[f], uv) : 0;
        worst = fmax(worst, ls[f]);
    }
    rep->worst_before = rep->worst_after = exp(fmin(worst, 700));
    /* a FIFO of vertices to try: first those beside a triangle above the
     * bound, then again every vertex of a ring that changed */
    uint32_t head = 0, tail = 0, queued = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        if (!(ls[f] > lb)) continue;
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) {
            uint32_t v = m->he_vert[h];
            if (M->valence[v] == 4 && !seen[v]) seen[v] = 1, list[tail++] = v, queued++;
        }
    }
    tail %= m->nv;
    uint64_t budget = (uint64_t)RELAX_TRIES * queued;
    while (queued > 0 && rep->tries < budget) {
        uint32_t v = list[head];
        head = (head + 1) % m->nv;
        queued--;
        seen[v] = 0;
        rep->tries++;
        if (!ring_load(M, v, &R)) goto nomem;
        if (R.seam && !(grid > 0)) continue;
        for (uint32_t k = 0; k < R.n; k++)
            R.uv[2 * k] = he_uv[2 * (size_t)R.he[k]], R.uv[2 * k + 1] = he_uv[2 * (size_t)R.he[k] + 1];
        double cur = ring_worst(m, F, he_uv, &R);
        if (!(cur > lb)) continue;
        double t[4], best = cur - RELAX_GAIN, bp[2];
        const double *p = he_uv + 2 * (size_t)R.he[0];
        int found = 0;
        targets(m, he_uv, v, &R, t);
        for (int k = 0; k < 2; k++) {
            /* from the whole way down; past the first valid point, the
             * ring only gets closer to where it is: stop once it worsens */
            double s = 1, last = INFINITY;
            for (int j = 0; j <= RELAX_STEPS; j++, s *= 0.125) {
                double q[2] = {p[0] + s * (t[2 * k] - p[0]), p[1] + s * (t[2 * k + 1] - p[1])};
                if (!isfinite(q[0]) || !isfinite(q[1]) || !ring_place(M, &R, q, grid)) continue;
                double w = ring_worst(m, F, he_uv, &R);
                if (w < 0) continue;
                if (w < best) best = w, bp[0] = q[0], bp[1] = q[1], found = 1;
                if (w > last) break;
                last = w;
            }
        }
        if (!found || !ring_place(M, &R, bp, grid)) continue;
        for (uint32_t k = 0; k < R.n; k++) {
            he_uv[2 * (size_t)R.he[k]] = R.uv[2 * k];
            he_uv[2 * (size_t)R.he[k] + 1] = R.uv[2 * k + 1];
            uint32_t f = m->he_face[R.he[k]];
            double uv[6];
            face_uv(m, he_uv, f, uv);
            ls[f] = F[f].area > 0 ? sq_sd_log_stretch(&F[f], uv) : 0;
        }
        rep->moves++;
        /* v again, and its neighbours: their rings changed */
        for (uint32_t k = 0; k <= R.n; k++) {
            uint32_t w = k < R.n ? m->he_vert[m->he_next[R.he[k]]] : v;
            if (M->valence[w] != 4 || seen[w]) continue;
            seen[w] = 1, list[tail] = w, tail = (tail + 1) % m->nv, queued++;
        }
    }
    worst = 0;
    for (uint32_t f = 0; f < m->nf; f++) worst = fmax(worst, ls[f]);
    rep->worst_after = exp(fmin(worst, 700));
    goto out;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (relaxation, %u faces)", m->nf);
out:
    free(ls), free(seen), free(list), free(R.he), free(R.rot), free(R.uv);
    return st;
}
