/* seamquad: edge splits between blocked vertices: room for the surface
 * cone tree where the cut walls a cone in (tree qtri, seed 9.4;
 * sq_param.c), and room for the cut graph's loops and paths between
 * adjacent cones (seed 9.1; sq_param_attempts.c). See sq_param_internal.h. */
#include <stdlib.h>
#include <string.h>

#include "sq_param_internal.h"
#include "sq_soup.h"

/* The m2 halfedge from u to v (both vertices of m2), or SQ_NONE. */
static uint32_t find_he(const sq_mesh *m2, uint32_t u, uint32_t v)
{
    uint32_t h0 = m2->v_he[u], h = h0;
    do {
        if (m2->he_vert[m2->he_next[h]] == v) return h;
        h = m2->he_next[m2->he_twin[h]];
    } while (h != h0);
    return SQ_NONE;
}

sq_status sq_param_split_walls(const sq_mesh *m, const int32_t *valence, const uint8_t *he_cut, sq_mesh *m2,
                               int32_t **val2, uint32_t **fparent, uint8_t **cut2, uint32_t *nsplit,
                               sq_error *err)
{
    memset(m2, 0, sizeof *m2);
    *val2 = NULL, *fparent = NULL, *nsplit = 0;
    if (cut2) *cut2 = NULL;
    sq_status st = SQ_OK;
    uint8_t *blocked = calloc(m->nv, 1);
    uint32_t *mid = malloc((size_t)m->nh * sizeof *mid);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    if (!blocked || !mid) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    /* the vertices the surface tree may not pass: cones and the cut's */
    for (uint32_t v = 0; v < m->nv; v++) blocked[v] = valence[v] != 4;
    for (uint32_t h = 0; he_cut && h < m->nh; h++)
        if (he_cut[h]) blocked[m->he_vert[h]] = 1;
    /* a midpoint on every other edge between two of them */
    uint32_t n = 0;
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t t = m->he_twin[h], a = m->he_vert[h], b = m->he_vert[t];
        if (h < t) mid[h] = mid[t] = !(he_cut && he_cut[h]) && blocked[a] && blocked[b] ? m->nv + n++ : SQ_NONE;
    }
    *nsplit = n;
    if (!n) goto done;
    soup.nv = m->nv + n;
    soup.pos = malloc(3 * (size_t)soup.nv * sizeof *soup.pos);
    soup.face_off = malloc((4 * (size_t)m->nf + 1) * sizeof *soup.face_off);
    soup.face_idx = malloc(12 * (size_t)m->nf * sizeof *soup.face_idx);
    *fparent = malloc(4 * (size_t)m->nf * sizeof **fparent);
    if (!soup.pos || !soup.face_off || !soup.face_idx || !*fparent) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    memcpy(soup.pos, m->pos, 3 * (size_t)m->nv * sizeof *soup.pos);
    for (uint32_t h = 0; h < m->nh; h++)
        if (mid[h] != SQ_NONE && h < m->he_twin[h]) {
            const double *p = m->pos + 3 * (size_t)m->he_vert[h], *q = m->pos + 3 * (size_t)m->he_vert[m->he_twin[h]];
            for (int d = 0; d < 3; d++) soup.pos[3 * (size_t)mid[h] + d] = 0.5 * (p[d] + q[d]);
        }
    /* each face: its corners and the midpoints of its split edges */
    uint32_t nf = 0, *idx = soup.face_idx;
    soup.face_off[0] = 0;
#define TRI(x, y, z) (idx[3 * nf] = (x), idx[3 * nf + 1] = (y), idx[3 * nf + 2] = (z), (*fparent)[nf] = f, \
                      nf++, soup.face_off[nf] = 3 * nf)
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h[3] = {m->f_he[f], 0, 0};
        h[1] = m->he_next[h[0]], h[2] = m->he_next[h[1]];
        /* rotated so that the edges split come first: edge i runs from
         * corner i to i + 1 */
        uint32_t k = 0, r = 0;
        for (uint32_t i = 0; i < 3; i++) k += mid[h[i]] != SQ_NONE;
        if (k == 1)
            while (mid[h[r]] == SQ_NONE) r++;
        if (k == 2)
            while (mid[h[(r + 2) % 3]] != SQ_NONE) r++; /* the unsplit edge last */
        uint32_t a = m->he_vert[h[r]], b = m->he_vert[h[(r + 1) % 3]], c = m->he_vert[h[(r + 2) % 3]];
        uint32_t mab = mid[h[r]], mbc = mid[h[(r + 1) % 3]], mca = mid[h[(r + 2) % 3]];
        if (k == 0) {
            TRI(a, b, c);
        } else if (k == 1) {
            TRI(a, mab, c);
            TRI(mab, b, c);
        } else if (k == 2) {
            TRI(mab, b, mbc);
            TRI(a, mab, mbc);
            TRI(a, mbc, c);
        } else {
            TRI(a, mab, mca);
            TRI(mab, b, mbc);
            TRI(mca, mbc, c);
            TRI(mab, mbc, mca);
        }
    }
#undef TRI
    soup.nf = nf;
    st = sq_mesh_from_soup(&soup, 0, m2, err);
    if (st) goto done;
    *val2 = malloc((size_t)m2->nv * sizeof **val2);
    if (cut2) *cut2 = calloc(m2->nh, 1);
    if (!*val2 || (cut2 && !*cut2)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    memcpy(*val2, valence, (size_t)m->nv * sizeof **val2);
    for (uint32_t v = m->nv; v < m2->nv; v++) (*val2)[v] = 4;
    /* the cut: the same edges (none was split) */
    for (uint32_t h = 0; he_cut && cut2 && h < m->nh && st == SQ_OK; h++) {
        if (!he_cut[h]) continue;
        uint32_t g = find_he(m2, m->he_vert[h], m->he_vert[m->he_twin[h]]);
        if (g == SQ_NONE) st = sq_error_set(err, SQ_ERR_INTERNAL, "split walls: cut edge %u lost", h);
        else (*cut2)[g] = 1;
    }
done:
    free(blocked), free(mid);
    sq_soup_free(&soup);
    if (st) {
        sq_mesh_free(m2);
        free(*val2), free(*fparent);
        *val2 = NULL, *fparent = NULL;
        if (cut2) free(*cut2), *cut2 = NULL;
    }
    return st;
}
