/* seamquad: metapolygon to quad mesh, seed 5.4 ("subdividing each k-gon of
 * a metapolygon into k 4-gons yields a quad mesh").
 *
 * Layout. With ne edges, the quad mesh has the metapolygon's nv vertices,
 * then one midpoint per edge (nv + edge id), then one centre per face
 * (nv + ne + f). Every interior halfedge h of P (from v, in face f, after
 * hp in f) owns quad q(h) = (v, mid(h), centre(f), mid(hp)), interior
 * halfedges 4q .. 4q+3 in that order. Every boundary halfedge b (u -> w) of
 * P becomes two boundary halfedges u -> mid(b) and mid(b) -> w. */
#include "sq_metapolygon_subdivide.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

void sq_mp_quads_free(sq_mp_quads *Q)
{
    sq_metapolygon_free(&Q->mesh);
    free(Q->v_origin_kind);
    free(Q->v_origin);
    free(Q->f_origin);
    free(Q->v_corner);
    free(Q->bnd_vert);
    free(Q->bnd_he);
    free(Q->corner_pos);
    free(Q->side_len);
    memset(Q, 0, sizeof *Q);
    sq_metapolygon_init(&Q->mesh);
}

/* Seed 5.4 needs a metapolygon: no boundary vertex on more than two
 * faces. */
static sq_status check_boundary(const sq_metapolygon *P, sq_error *err)
{
    uint32_t h = P->bnd_he;
    do {
        if (P->v_nface[P->he_vert[h]] > 2)
            return sq_error_set(err, SQ_ERR_ARGUMENT, "seed 5.4 needs a metapolygon: boundary vertex %u has %u faces",
                                P->he_vert[h], P->v_nface[P->he_vert[h]]);
        h = P->he_next[h];
    } while (h != P->bnd_he);
    return SQ_OK;
}

/* out's boundary order (bnd_vert, bnd_he, from its mesh's bnd_he), its
 * corners (the vertices v_corner marks) and the sides between them. */
static sq_status boundary_sides(sq_mp_quads *out, sq_error *err)
{
    const sq_metapolygon *M = &out->mesh;
    out->nbnd = M->nbnd;
    uint32_t ncorner = 0;
    {
        uint32_t h = M->bnd_he, j = 0;
        do {
            out->bnd_vert[j] = M->he_vert[h];
            out->bnd_he[j] = h;
            ncorner += out->v_corner[M->he_vert[h]];
            j++;
            h = M->he_next[h];
        } while (h != M->bnd_he);
        assert(j == out->nbnd);
    }
    out->ncorner = ncorner;
    out->corner_pos = malloc((size_t)(ncorner ? ncorner : 1) * sizeof(uint32_t));
    out->side_len = malloc((size_t)(ncorner ? ncorner : 1) * sizeof(uint32_t));
    if (!out->corner_pos || !out->side_len)
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory subdividing a metapolygon");
    {
        uint32_t c = 0;
        for (uint32_t j = 0; j < out->nbnd; j++)
            if (out->v_corner[out->bnd_vert[j]]) out->corner_pos[c++] = j;
        for (uint32_t s = 0; s < ncorner; s++) {
            uint32_t next = s + 1 < ncorner ? out->corner_pos[s + 1]
                                            : out->corner_pos[0] + out->nbnd;
            out->side_len[s] = next - out->corner_pos[s];
            assert(out->side_len[s] >= 2 && out->side_len[s] % 2 == 0);
        }
        assert(ncorner == 0 || out->corner_pos[0] == 0);
    }
    /* corners of the quad mesh are exactly the valence-1 boundary vertices */
    assert(sq_metapolygon_count_corners(M) == ncorner);
    return SQ_OK;
}

sq_status sq_metapolygon_subdivide(const sq_metapolygon *P, sq_mp_quads *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    sq_metapolygon_init(&out->mesh);
    if (P->nf == 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cannot subdivide an empty metapolygon");
    sq_status st = check_boundary(P, err);
    if (st) return st;
    const uint32_t nv = P->nv, nf = P->nf, nh = P->nh, nb = P->nbnd;
    uint32_t *e_id = malloc((size_t)nh * sizeof *e_id);
    uint32_t *q_id = malloc((size_t)nh * sizeof *q_id);
    uint32_t *fprev = malloc((size_t)nh * sizeof *fprev);
    uint32_t *b_id = malloc((size_t)nh * sizeof *b_id);
    sq_metapolygon *M = &out->mesh;
    if (!e_id || !q_id || !fprev || !b_id) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory subdividing a metapolygon");
        goto done;
    }
    uint32_t ne = 0, nq = 0;
    for (uint32_t h = 0; h < nh; h++)
        if (h < P->he_twin[h]) e_id[h] = e_id[P->he_twin[h]] = ne++;
    for (uint32_t h = 0; h < nh; h++) q_id[h] = b_id[h] = SQ_NONE;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t h0 = P->f_he[f], h = h0, prev = SQ_NONE;
        do {
            q_id[h] = nq++;
            if (prev != SQ_NONE) fprev[h] = prev;
            prev = h;
            h = P->he_next[h];
        } while (h != h0);
        fprev[h0] = prev;
    }
    /* boundary start: leaving a corner when there is one */
    uint32_t bstart = P->bnd_he;
    {
        uint32_t nonflat_he;
        if (sq_metapolygon_nonflat(P, 1, NULL, &nonflat_he, NULL) > 0) bstart = nonflat_he;
        uint32_t h = bstart, t = 0;
        do {
            b_id[h] = t++;
            h = P->he_next[h];
        } while (h != bstart);
        assert(t == nb);
    }
    uint64_t nvq = (uint64_t)nv + ne + nf, nhq = 4ull * nq + 2ull * nb;
    st = sq_metapolygon_reserve(M, nvq, nq, nhq, err);
    if (st != SQ_OK) goto done;
    out->v_origin_kind = malloc((size_t)nvq);
    out->v_origin = malloc((size_t)nvq * sizeof(uint32_t));
    out->v_corner = calloc((size_t)nvq, 1);
    out->f_origin = malloc((size_t)nq * sizeof(uint32_t));
    out->bnd_vert = malloc(2ull * nb * sizeof(uint32_t));
    out->bnd_he = malloc(2ull * nb * sizeof(uint32_t));
    if (!out->v_origin_kind || !out->v_origin || !out->v_corner || !out->f_origin ||
        !out->bnd_vert || !out->bnd_he) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory subdividing a metapolygon");
        goto done;
    }
#define MID(h) (nv + e_id[h])
#define CENTRE(f) (nv + ne + (f))
#define B0(b) (4 * nq + 2 * b_id[b])
#define B1(b) (4 * nq + 2 * b_id[b] + 1)
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t f = P->he_face[h];
        if (f == SQ_NONE) {
            /* b = h: u -> mid -> w; t its interior twin (w -> u) */
            uint32_t t = P->he_twin[h];
            uint32_t b0 = B0(h), b1 = B1(h);
            M->he_vert[b0] = P->he_vert[h];
            M->he_vert[b1] = MID(h);
            M->he_face[b0] = M->he_face[b1] = SQ_NONE;
            M->he_next[b0] = b1;
            M->he_next[b1] = B0(P->he_next[h]);
            M->he_twin[b0] = 4 * q_id[P->he_next[t]] + 3;
            M->he_twin[b1] = 4 * q_id[t] + 0;
            continue;
        }
        uint32_t q = q_id[h], hp = fprev[h];
        uint32_t t = P->he_twin[h], tp = P->he_twin[hp];
        M->he_vert[4 * q + 0] = P->he_vert[h];
        M->he_vert[4 * q + 1] = MID(h);
        M->he_vert[4 * q + 2] = CENTRE(f);
        M->he_vert[4 * q + 3] = MID(hp);
        for (uint32_t c = 0; c < 4; c++) {
            M->he_next[4 * q + c] = 4 * q + (c + 1) % 4;
            M->he_face[4 * q + c] = q;
        }
        M->he_twin[4 * q + 0] = P->he_face[t] == SQ_NONE ? B1(t) : 4 * q_id[P->he_next[t]] + 3;
        M->he_twin[4 * q + 1] = 4 * q_id[P->he_next[h]] + 2;
        M->he_twin[4 * q + 2] = 4 * q_id[hp] + 1;
        M->he_twin[4 * q + 3] = P->he_face[tp] == SQ_NONE ? B0(tp) : 4 * q_id[tp] + 0;
        M->f_he[q] = 4 * q;
        M->f_valence[q] = 4;
        out->f_origin[q] = h;
    }
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t h = P->v_he[v];
        int boundary = P->he_face[h] == SQ_NONE;
        M->v_nface[v] = P->v_nface[v];
        M->v_he[v] = boundary ? B0(h) : 4 * q_id[h] + 0;
        out->v_origin_kind[v] = SQ_MP_ORIGIN_VERTEX;
        out->v_origin[v] = v;
        out->v_corner[v] = boundary && P->v_nface[v] == 1;
    }
    for (uint32_t h = 0; h < nh; h++) {
        uint32_t t = P->he_twin[h];
        if (h > t) continue;
        uint32_t m = MID(h);
        if (P->he_face[h] == SQ_NONE || P->he_face[t] == SQ_NONE) {
            uint32_t b = P->he_face[h] == SQ_NONE ? h : t;
            M->v_nface[m] = 2;
            M->v_he[m] = B1(b);
        } else {
            M->v_nface[m] = 4;
            M->v_he[m] = 4 * q_id[h] + 1;
        }
        out->v_origin_kind[m] = SQ_MP_ORIGIN_EDGE;
        out->v_origin[m] = h;
    }
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t c = CENTRE(f);
        M->v_nface[c] = P->f_valence[f];
        M->v_he[c] = 4 * q_id[P->f_he[f]] + 2;
        out->v_origin_kind[c] = SQ_MP_ORIGIN_FACE;
        out->v_origin[c] = f;
    }
    M->nv = (uint32_t)nvq;
    M->nf = nq;
    M->nh = (uint32_t)nhq;
    M->bnd_he = B0(bstart);
    M->nbnd = 2 * nb;
#undef MID
#undef CENTRE
#undef B0
#undef B1

    st = boundary_sides(out, err);
done:
    free(e_id);
    free(q_id);
    free(fprev);
    free(b_id);
    if (st != SQ_OK) sq_mp_quads_free(out);
    return st;
}
