/* seamquad: cones for a mesh that has none, from the singularities of a
 * smooth cross field (sq_cross_field.h, docs/cones_from_field.md).
 *
 * 1. field: sq_cross_field (smooth or curvature-aligned);
 * 2. valences: k_v = 4 - index_v (sq_cross_field_indices); Gauss-Bonnet,
 *    sum of (4 - k_v) = 4 chi, holds exactly by construction;
 * 3. cancel nearby +/- pairs (sq_cones_from_field_cancel.c);
 * 4. repair (sq_cones_from_field_repair), which keeps the sum:
 *    a. while some vertex v has k_v <= 1: find the nearest vertex w (fewest
 *       mesh edges; ties: larger valence, then smaller Euclidean distance,
 *       then smaller index) with k_w >= 3, and set k_v += 1, k_w -= 1.
 *       Such a w exists: if every other vertex had k <= 2 (index >= 2),
 *       then sum of indices >= 3 + 2 (V - 1) = 2 V + 1 > 8 >= 4 chi, since
 *       a closed triangle mesh has V >= 4 and chi <= 2. Each step lowers
 *       the total deficit sum of max(0, 2 - k) by one and creates no new
 *       deficit (k_w - 1 >= 2), so it ends after exactly that many steps.
 *    b. genus 1 with exactly one valence-3 and one valence-5 vertex and no
 *       other cone: both become 4 (the pair cancels: +1 - 1 = 0), leaving
 *       the torus without cones, which is realizable;
 * 5. check: sq_cones_check_gauss_bonnet and sq_cones_check_realizable. */
#include "sq_clock.h"
#include "sq_cross_field.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cones.h"

static int64_t defect_sum(uint32_t nv, const int32_t *valence)
{
    int64_t s = 0;
    for (uint32_t v = 0; v < nv; v++) s += 4 - (int64_t)valence[v];
    return s;
}

static double dist2(const sq_mesh *m, uint32_t a, uint32_t b)
{
    const double *p = m->pos + 3 * (size_t)a, *q = m->pos + 3 * (size_t)b;
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
           (p[2] - q[2]) * (p[2] - q[2]);
}

/* Breadth-first search from v for the best receiver (see 3a above).
 * seen[] holds stamps; queue has room for nv entries. */
static uint32_t nearest_receiver(const sq_mesh *m, const int32_t *valence, uint32_t v,
                                 uint32_t *seen, uint32_t stamp, uint32_t *queue)
{
    uint32_t head = 0, tail = 0, layer_end;
    queue[tail++] = v;
    seen[v] = stamp;
    while (head < tail) {
        layer_end = tail;
        uint32_t best = UINT32_MAX;
        for (; head < layer_end; head++) {
            uint32_t a = queue[head];
            if (a != v && valence[a] >= 3) {
                if (best == UINT32_MAX || valence[a] > valence[best] ||
                    (valence[a] == valence[best] &&
                     (dist2(m, v, a) < dist2(m, v, best) ||
                      (dist2(m, v, a) == dist2(m, v, best) && a < best))))
                    best = a;
            }
            uint32_t h0 = m->v_he[a], h = h0;
            do {
                uint32_t b = m->he_vert[m->he_next[h]];
                if (seen[b] != stamp) {
                    seen[b] = stamp;
                    queue[tail++] = b;
                }
                h = m->he_next[m->he_next[h]];
                h = m->he_twin[h];
            } while (h != h0);
        }
        if (best != UINT32_MAX) return best;
    }
    return UINT32_MAX;
}

sq_status sq_cones_from_field_repair(const sq_mesh *m, int32_t *valence, uint32_t *moved,
                                     int *cancelled, sq_error *err)
{
    if (moved) *moved = 0;
    if (cancelled) *cancelled = 0;
    int64_t before = defect_sum(m->nv, valence);
    if (before != 4 * sq_mesh_euler(m))
        return sq_error_set(err, SQ_ERR_GAUSS_BONNET,
                            "cone repair: the valences violate Gauss-Bonnet before repair "
                            "(sum of 4 - k = %lld, 4*chi = %lld)",
                            (long long)before, (long long)(4 * sq_mesh_euler(m)));
    uint32_t *seen = NULL, *queue = NULL, nmoved = 0;
    uint32_t stamp = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        while (valence[v] <= 1) {
            if (!seen) {
                seen = calloc(m->nv, sizeof *seen);
                queue = malloc((size_t)m->nv * sizeof *queue);
                if (!seen || !queue) {
                    free(seen);
                    free(queue);
                    return sq_error_set(err, SQ_ERR_NOMEM, "cone repair: out of memory");
                }
            }
            uint32_t w = nearest_receiver(m, valence, v, seen, ++stamp, queue);
            if (w == UINT32_MAX) { /* impossible by the counting argument */
                free(seen);
                free(queue);
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "cone repair: no vertex of valence >= 3 to take a "
                                    "quarter turn from vertex %u",
                                    v);
            }
            assert(valence[w] >= 3);
            valence[v] += 1;
            valence[w] -= 1;
            nmoved++;
        }
    }
    free(seen);
    free(queue);
    if (sq_mesh_genus(m) == 1) {
        uint32_t n3 = 0, n5 = 0, other = 0, v3 = 0, v5 = 0;
        for (uint32_t v = 0; v < m->nv; v++) {
            if (valence[v] == 3) n3++, v3 = v;
            else if (valence[v] == 5) n5++, v5 = v;
            else if (valence[v] != 4) other++;
        }
        if (n3 == 1 && n5 == 1 && other == 0) {
            valence[v3] = valence[v5] = 4;
            if (cancelled) *cancelled = 1;
        }
    }
    if (moved) *moved = nmoved;
    assert(defect_sum(m->nv, valence) == before);
    return SQ_OK;
}

void sq_cones_from_field_default_options(sq_cones_from_field_options *opt)
{
    memset(opt, 0, sizeof *opt);
    sq_cross_field_default_options(&opt->field);
    opt->field.align = SQ_FIELD_CURVATURE;
    opt->cancel_radius = 3.0;
}

static double mean_edge_length(const sq_mesh *m)
{
    double s = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t t = m->he_twin[h];
        if (t < h) continue;
        s += sqrt(dist2(m, m->he_vert[h], m->he_vert[t]));
    }
    return s / (double)(m->nh / 2);
}

sq_status sq_cones_from_field(const sq_mesh *m, const sq_cones_from_field_options *opt_in,
                              int32_t *valence, sq_cones_from_field_stats *stats,
                              sq_error *err)
{
    sq_cones_from_field_options opt;
    if (opt_in) opt = *opt_in;
    else sq_cones_from_field_default_options(&opt);
    sq_cones_from_field_stats s;
    memset(&s, 0, sizeof s);
    if (!m || !valence) return sq_error_set(err, SQ_ERR_ARGUMENT, "cones from field: NULL argument");
    double t0 = sq_now();
    double *u = malloc(2 * (size_t)m->nf * sizeof *u);
    if (!u) return sq_error_set(err, SQ_ERR_NOMEM, "cones from field: out of memory");
    sq_status st = sq_cross_field(m, &opt.field, u, &s.field, err);
    if (st) goto done;
    double t1 = sq_now();
    s.t_field = t1 - t0;
    st = sq_cross_field_indices(m, u, valence, err);
    if (st) goto done;
    for (uint32_t v = 0; v < m->nv; v++) {
        /* index in quarter turns -> valence */
        valence[v] = 4 - valence[v];
        if (valence[v] != 4) s.raw_singularities++;
        if (valence[v] <= 1) s.low_valence++;
    }
    s.t_indices = sq_now() - t1;
    int64_t chi = sq_mesh_euler(m);
    assert(defect_sum(m->nv, valence) == 4 * chi);
    st = sq_cones_from_field_cancel(m, valence, opt.cancel_radius * mean_edge_length(m),
                                    &s.cancelled, err);
    if (st) goto done;
    assert(defect_sum(m->nv, valence) == 4 * chi);
    st = sq_cones_from_field_repair(m, valence, &s.moved_units, &s.torus_pair_cancelled, err);
    if (st) goto done;
    /* verified, not assumed: the result must pass what `seamquad check` does */
    st = sq_cones_check_gauss_bonnet(m->nv, valence, chi, err);
    if (!st) st = sq_cones_check_realizable(m->nv, valence, sq_mesh_genus(m), err);
    if (st) {
        char msg[SQ_ERROR_MSG_MAX];
        memcpy(msg, err ? err->msg : "", err ? sizeof msg : 1);
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cones from field: result fails its check: %s",
                          msg);
        goto done;
    }
    for (uint32_t v = 0; v < m->nv; v++) s.cones += valence[v] != 4;
    s.t_total = sq_now() - t0;
done:
    free(u);
    if (stats) *stats = s;
    return st;
}
