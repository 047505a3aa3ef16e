/* seamquad: the boundary word of the cut disk (seed 6, seed 7: the 8g-4
 * sides of M^c and their identification).
 *
 * Walk the boundary of the mesh cut along he_cut with the disk on the
 * left (sq_cut_boundary_next), starting at a branch corner; cut it into
 * sides at every corner whose vertex is a branch point (cut degree != 2).
 * Side i runs from corner i to corner i+1; its partner is the side made of
 * the twins of its halfedges in reverse order (the other side of the same
 * branch), which is the gluing convention of sq_pattern.h. Branch points
 * may have degree 1 (genus 0: one path), 3 (genus 1: theta graph; one
 * corner per class is then marked straight) or 4 (genus >= 1 hole chain).
 * The word is counterclockwise; the domain Q's is clockwise
 * (sq_pattern_reversed, sq_cut_graph_domain_offset). */
#include "sq_cut_graph.h"
#include "sq_cut_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

sq_status sq_cut_boundary_word(const sq_mesh *m, sq_cut_graph *G, sq_error *err)
{
    const uint8_t *cut = G->he_cut;
    sq_status st = SQ_OK;
    free(G->point_vertex);
    free(G->side_off);
    free(G->side_he);
    free(G->corner_vertex);
    G->point_vertex = G->side_off = G->side_he = G->corner_vertex = NULL;
    sq_pattern_free(&G->pattern);
    uint32_t *deg = calloc(m->nv, sizeof *deg);
    uint32_t *side_of = malloc((size_t)m->nh * sizeof *side_of);
    if (!deg || !side_of) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (boundary)");
        goto done;
    }
    uint32_t ncuthe = 0, h0 = SQ_NONE;
    for (uint32_t h = 0; h < m->nh; ++h)
        if (cut[h]) {
            assert(cut[m->he_twin[h]]);
            deg[m->he_vert[h]]++;
            ++ncuthe;
        }
    G->ncut_edges = ncuthe / 2;
    uint32_t np = 0, degsum = 0;
    for (uint32_t v = 0; v < m->nv; ++v)
        if (deg[v] && deg[v] != 2) {
            ++np;
            degsum += deg[v];
        }
    G->npoints = np;
    G->nbranches = degsum / 2;
    G->point_vertex = malloc(((size_t)np + 1) * sizeof *G->point_vertex);
    G->side_he = malloc(((size_t)ncuthe + 1) * sizeof *G->side_he);
    G->side_off = malloc(((size_t)ncuthe + 2) * sizeof *G->side_off);
    G->corner_vertex = malloc(((size_t)ncuthe + 1) * sizeof *G->corner_vertex);
    if (!G->point_vertex || !G->side_he || !G->side_off || !G->corner_vertex) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (boundary)");
        goto done;
    }
    np = 0;
    for (uint32_t v = 0; v < m->nv; ++v)
        if (deg[v] && deg[v] != 2)
            G->point_vertex[np++] = v;
    for (uint32_t h = 0; h < m->nh && h0 == SQ_NONE; ++h)
        if (cut[h] && deg[m->he_vert[h]] != 2)
            h0 = h;
    if (h0 == SQ_NONE) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: the cut has no branch point");
        goto done;
    }
    /* The walk must visit every cut halfedge once: one boundary loop. */
    uint32_t n = 0, k = 0, h = h0;
    do {
        if (n == ncuthe) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "cut graph: boundary walk does not close");
            goto done;
        }
        if (deg[m->he_vert[h]] != 2) {
            G->side_off[k] = n;
            G->corner_vertex[k] = m->he_vert[h];
            ++k;
        }
        side_of[h] = k - 1;
        G->side_he[n++] = h;
        h = sq_cut_boundary_next(m, cut, h);
    } while (h != h0);
    G->side_off[k] = n;
    if (n != ncuthe) {
        st = sq_error_set(err, SQ_ERR_INTERNAL,
                          "cut graph: the cut surface has more than one boundary loop (the "
                          "loop through a branch corner has %u of %u boundary edges)",
                          n, ncuthe);
        goto done;
    }
    st = sq_pattern_alloc(&G->pattern, k, err);
    if (st != SQ_OK)
        goto done;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t a = G->side_off[i], b = G->side_off[i + 1];
        const uint32_t j = side_of[m->he_twin[G->side_he[a]]];
        const uint32_t c = G->side_off[j], d = G->side_off[j + 1];
        if (d - c != b - a || j == i) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "cut graph: side %u (%u edges) and its partner %u (%u edges) "
                              "do not pair up", i, b - a, j, d - c);
            goto done;
        }
        for (uint32_t t = 0; t < b - a; ++t)
            if (G->side_he[c + t] != m->he_twin[G->side_he[b - 1 - t]]) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "cut graph: side %u is not the reverse of side %u", j, i);
                goto done;
            }
        G->pattern.partner[i] = j;
    }
    /* Degree-3 branch points (the genus-1 theta graph, sq_cut_low_genus.c)
     * have three corners; the domain Q gives each such class two right
     * corners and one straight one (docs/domain.md, "Genus 1"). On the
     * surface any corner can take the straight angle: mark the first corner
     * of each class. Degree-1 (genus 0) and degree-4 points keep right
     * corners only. */
    if (k > 0) {
        uint32_t *cls = malloc((size_t)k * sizeof *cls);
        uint8_t *done_cls = calloc(k, 1);
        if (!cls || !done_cls) {
            free(cls);
            free(done_cls);
            st = sq_error_set(err, SQ_ERR_NOMEM, "cut graph: out of memory (boundary)");
            goto done;
        }
        sq_pattern_corner_classes(&G->pattern, cls);
        for (uint32_t i = 0; i < k; ++i)
            if (deg[G->corner_vertex[i]] == 3 && !done_cls[cls[i]]) {
                done_cls[cls[i]] = 1;
                G->pattern.straight[i] = 1;
            }
        free(cls);
        free(done_cls);
    }
    G->rank = sq_pattern_rank(&G->pattern);
done:
    free(deg);
    free(side_of);
    return st;
}
