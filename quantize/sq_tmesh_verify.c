/* seamquad: independent check of a T-mesh against its map (sq_tmesh.h).
 *
 * Decided from the public arrays only (nodes, arcs with their slots, the
 * faces' sides), not from the construction's state:
 *  - every cone of the map is a node; a cone of valence k ends exactly k
 *    arcs, one per ray; every other node ends at least 3, one per slot;
 *  - every arc lies on exactly two sides, once in each direction;
 *  - each face's sides, concatenated, form a closed walk: each arc leaves
 *    the node where the previous one arrives, turning by one quarter (a
 *    convex corner) between sides and by two (straight on) inside a side,
 *    with no arc leaving the node in between: the walk is the boundary of
 *    one region, on its left, a rectangle with 4 corners and T-junctions on
 *    its sides;
 *  - Euler: nodes - arcs + faces = the mesh's Euler characteristic; with
 *    every boundary walk counted as a face this holds iff every face is a
 *    disk;
 *  - opposite sides have equal parametric length (1e-9 relative to the UV
 *    bounding box) and the faces' areas sum to the UV area (1e-9
 *    relative);
 *  - consecutive pieces of an arc meet at one mesh element, and every node
 *    is exact. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_tmesh_internal.h"

#define REL_TOL 1e-9

static int same_point(const sq_map *M, const sq_tmesh_piece *a, const sq_tmesh_piece *b)
{
    const sq_tmesh_end *x = &a->to, *y = &b->from;
    if (x->kind != y->kind) return 0;
    if (x->kind == SQ_TMESH_AT_VERTEX) return x->id == y->id;
    if (x->kind == SQ_TMESH_ON_EDGE)
        return x->id == y->id || M->mesh.he_twin[x->id] == y->id;
    return x->id == y->id;
}

sq_status sq_tmesh_verify(const sq_map *M, const sq_tmesh *T, sq_tmesh_stats *stats, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    sq_status st = SQ_OK;
    uint32_t *deg = NULL, *slot_off = NULL, *slot_arc = NULL, *seen = NULL;
    if (stats) memset(stats, 0, sizeof *stats);

    /* UV area and size */
    double area = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        const double *a = tm_uv(M, h), *b = tm_uv(M, tm_next(M, h)), *c = tm_uv(M, tm_prev(M, h));
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        for (int i = 0; i < 2; i++) {
            lo[i] = fmin(lo[i], fmin(a[i], fmin(b[i], c[i])));
            hi[i] = fmax(hi[i], fmax(a[i], fmax(b[i], c[i])));
        }
    }
    double diag = hypot(hi[0] - lo[0], hi[1] - lo[1]), ltol = REL_TOL * fmax(1.0, diag);

    /* nodes and slots */
    slot_off = calloc((size_t)T->n_nodes + 1, sizeof *slot_off);
    deg = calloc((size_t)T->n_nodes + 1, sizeof *deg);
    seen = calloc((size_t)T->n_arcs + 1, sizeof *seen);
    if (!slot_off || !deg || !seen) goto nomem;
    for (uint32_t n = 0; n < T->n_nodes; n++) {
        const sq_tmesh_node *N = &T->nodes[n];
        if (N->valence < 1 || N->valence > TM_MAX_RAYS || (N->kind != SQ_TMESH_AT_VERTEX && N->valence != 4) ||
            (N->kind == SQ_TMESH_AT_VERTEX && (N->id >= m->nv || N->valence != M->valence[N->id]))) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: node %u has a wrong valence %d", n, N->valence);
            goto done;
        }
        if (!N->exact) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: node %u (kind %d, element %u) is not exact", n, N->kind,
                              N->id);
            goto done;
        }
        slot_off[n + 1] = slot_off[n] + (uint32_t)N->valence;
    }
    slot_arc = malloc(((size_t)slot_off[T->n_nodes] + 1) * sizeof *slot_arc);
    if (!slot_arc) goto nomem;
    memset(slot_arc, 0xff, ((size_t)slot_off[T->n_nodes] + 1) * sizeof *slot_arc);
    for (uint32_t a = 0; a < T->n_arcs; a++) {
        const sq_tmesh_arc *A = &T->arcs[a];
        if (A->piece_count == 0 || A->piece_off + A->piece_count > T->n_pieces || !(A->length > 0)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: arc %u is empty (length %g)", a, A->length);
            goto done;
        }
        for (uint32_t i = 1; i < A->piece_count; i++)
            if (!same_point(M, &T->pieces[A->piece_off + i - 1], &T->pieces[A->piece_off + i])) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: arc %u breaks between its pieces %u and %u", a, i - 1,
                                  i);
                goto done;
            }
        for (int e = 0; e < 2; e++) {
            uint32_t n = A->node[e];
            if (n >= T->n_nodes || A->slot[e] >= (uint32_t)T->nodes[n].valence ||
                slot_arc[slot_off[n] + A->slot[e]] != TM_NONE) {
                st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: arc %u ends at node %u by a slot %u taken or invalid",
                                  a, n, A->slot[e]);
                goto done;
            }
            slot_arc[slot_off[n] + A->slot[e]] = 2 * a + (uint32_t)e;
            deg[n]++;
        }
    }
    uint32_t cone_nodes = 0;
    for (uint32_t n = 0; n < T->n_nodes; n++) {
        const sq_tmesh_node *N = &T->nodes[n];
        int cone = N->kind == SQ_TMESH_AT_VERTEX && N->valence != 4;
        cone_nodes += (uint32_t)cone;
        if (deg[n] != N->degree || (cone && deg[n] != (uint32_t)N->valence) || (!cone && deg[n] < 3)) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "tmesh: node %u (%s %u, valence %d) ends %u arcs (recorded %u)", n,
                              N->kind == SQ_TMESH_AT_VERTEX ? "vertex" : N->kind == SQ_TMESH_ON_EDGE ? "on edge" : "in face",
                              N->id, N->valence, deg[n], N->degree);
            goto done;
        }
    }
    uint32_t cones = 0;
    for (uint32_t v = 0; v < m->nv; v++) cones += M->valence[v] != 4;
    if (cones != cone_nodes) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: %u cones but %u cone nodes", cones, cone_nodes);
        goto done;
    }

    /* faces */
    double sum = 0, mism = 0;
    if (T->side_off[0] != 0) goto badsides;
    for (uint32_t f = 0; f < T->n_faces; f++) {
        uint32_t b = T->side_off[4 * f], e = T->side_off[4 * f + 4];
        if (e <= b || e > 2 * T->n_arcs) goto badsides;
        double len[4];
        for (uint32_t s = 0; s < 4; s++) {
            uint32_t s0 = T->side_off[4 * f + s], s1 = T->side_off[4 * f + s + 1];
            if (s1 <= s0) goto badsides;
            len[s] = 0;
            for (uint32_t i = s0; i < s1; i++) {
                uint32_t a = T->side_arc[i], j = i + 1 < e ? i + 1 : b;
                if (a >= T->n_arcs || (seen[a] & (1u << T->side_rev[i]))) goto badsides;
                seen[a] |= 1u << T->side_rev[i];
                len[s] += T->arcs[a].length;
                /* the turn from this arc to the next one */
                const sq_tmesh_arc *A = &T->arcs[a], *Bn = &T->arcs[T->side_arc[j]];
                uint32_t n = A->node[T->side_rev[i] ? 0 : 1], s_in = A->slot[T->side_rev[i] ? 0 : 1];
                uint32_t n2 = Bn->node[T->side_rev[j] ? 1 : 0], s_out = Bn->slot[T->side_rev[j] ? 1 : 0];
                uint32_t k = (uint32_t)T->nodes[n].valence;
                uint32_t turn = (s_in + k - s_out) % k;
                if (turn == 0) turn = k; /* back along the same arc: a cone of valence 1 or 2 */
                uint32_t want = i + 1 == s1 ? 1 : 2;
                if (n != n2 || turn != want || (want == 2 && slot_arc[slot_off[n] + (s_out + 1) % k] != TM_NONE)) {
                    st = sq_error_set(err, SQ_ERR_INTERNAL,
                                      "tmesh: face %u side %u: arcs %u and %u do not turn by %u quarter(s) at node %u",
                                      f, s, a, T->side_arc[j], want, n);
                    goto done;
                }
            }
        }
        double d02 = fabs(len[0] - len[2]), d13 = fabs(len[1] - len[3]);
        mism = fmax(mism, fmax(d02, d13));
        if (d02 > ltol || d13 > ltol) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "tmesh: face %u is no rectangle: sides of lengths %.17g, %.17g, %.17g, %.17g", f,
                              len[0], len[1], len[2], len[3]);
            goto done;
        }
        if (fabs(T->width[f] - len[0]) > ltol || fabs(T->height[f] - len[1]) > ltol) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: face %u: width or height differs from its sides", f);
            goto done;
        }
        sum += T->width[f] * T->height[f];
    }
    for (uint32_t a = 0; a < T->n_arcs; a++)
        if (seen[a] != 3) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: arc %u is not on two face sides (one each way)", a);
            goto done;
        }
    int64_t chi = (int64_t)m->nv - (int64_t)m->nh / 2 + (int64_t)m->nf;
    int64_t tchi = (int64_t)T->n_nodes - (int64_t)T->n_arcs + (int64_t)T->n_faces;
    if (tchi != chi) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "tmesh: nodes - arcs + faces = %lld, not the surface's Euler characteristic %lld: a face "
                          "is no disk",
                          (long long)tchi, (long long)chi);
        goto done;
    }
    double aerr = fabs(sum - area) / area;
    if (stats) stats->max_side_mismatch = mism, stats->area_error = aerr;
    if (!(aerr <= REL_TOL) || fabs(T->uv_area - area) > REL_TOL * area) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: the faces' areas sum to %.17g, the map's UV area is %.17g",
                          sum, area);
        goto done;
    }
    goto done;
badsides:
    st = sq_error_set(err, SQ_ERR_INTERNAL, "tmesh: the face sides are malformed (empty side, arc out of range or "
                      "an arc twice in one direction)");
    goto done;
nomem:
    st = sq_error_set(err, SQ_ERR_NOMEM, "tmesh: out of memory");
done:
    free(deg), free(slot_off), free(slot_arc), free(seen);
    return st;
}
