/* seamquad: OBJ output of a map (sq_map_write_obj): v lines in the mesh's
 * vertex order, one vt per distinct UV point of a vertex (its wedges), f
 * v/vt lines in the mesh's face order. */
#include <stdlib.h>

#include "sq_io.h"
#include "sq_map_internal.h"

sq_status sq_map_write_obj(const char *path, const sq_map *M, sq_error *err)
{
    const sq_mesh *m = &M->mesh;
    uint32_t *he_idx = malloc(m->nh * sizeof *he_idx);
    double *uv = malloc(2 * (size_t)m->nh * sizeof *uv);
    uint32_t *face_off = malloc(((size_t)m->nf + 1) * sizeof *face_off);
    uint32_t *face_idx = malloc(m->nh * sizeof *face_idx);
    uint32_t *face_uv = malloc(m->nh * sizeof *face_uv);
    sq_status st = SQ_OK;
    if (!he_idx || !uv || !face_off || !face_idx || !face_uv) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (map output)");
        goto done;
    }
    uint32_t nuv = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], k = h0, first = nuv;
        do {
            const double *p = M->he_uv + 2 * (size_t)k;
            uint32_t i = first;
            while (i < nuv && (uv[2 * (size_t)i] != p[0] || uv[2 * (size_t)i + 1] != p[1])) i++;
            if (i == nuv) {
                uv[2 * (size_t)nuv] = p[0];
                uv[2 * (size_t)nuv + 1] = p[1];
                nuv++;
            }
            he_idx[k] = i;
            k = sq_map_rotate_out(m, k);
        } while (k != h0);
    }
    for (uint32_t f = 0; f < m->nf; f++) {
        face_off[f] = 3 * f;
        uint32_t h = m->f_he[f];
        for (int i = 0; i < 3; i++, h = m->he_next[h]) {
            face_idx[3 * (size_t)f + i] = m->he_vert[h];
            face_uv[3 * (size_t)f + i] = he_idx[h];
        }
    }
    face_off[m->nf] = 3 * m->nf;
    st = sq_write_obj(path, m->nv, m->pos, m->nf, face_off, face_idx, nuv, uv, face_uv, err);
done:
    free(he_idx);
    free(uv);
    free(face_off);
    free(face_idx);
    free(face_uv);
    return st;
}
