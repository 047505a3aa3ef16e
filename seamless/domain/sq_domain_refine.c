/* seamquad: the domain at twice the resolution.
 *
 * Every quad of Q is split into 2 x 2 quads (seed 5.4's subdivision applied
 * to a quad mesh), so every length doubles: sides, padding, the slide. The
 * metapolygon, the cones and the side pattern are unchanged; Q's vertices
 * keep their indices (new ones come after them), and the quads of old quad
 * f are 4f .. 4f+3. Used where a path of the cone tree needs room between
 * two others that Q's grid does not have (sq_param_tree.c, guided tree). */
#include <stdlib.h>
#include <string.h>

#include "sq_domain.h"
#include "sq_metapolygon_subdivide.h"

sq_status sq_domain_refine2(const sq_domain *D, sq_domain *out, sq_error *err)
{
    sq_domain_free(out);
    const sq_metapolygon *Q = &D->quads;
    for (uint32_t f = 0; f < Q->nf; f++)
        if (Q->f_valence[f] != 4) return sq_error_set(err, SQ_ERR_ARGUMENT, "domain refine: face %u of Q is no quad", f);
    sq_mp_quads sub;
    sq_status st = sq_metapolygon_subdivide(Q, &sub, err);
    if (st) return st;
    out->quads = sub.mesh;
    memset(&sub.mesh, 0, sizeof sub.mesh);
    sq_mp_quads_free(&sub);
    out->genus = D->genus, out->ncones = D->ncones, out->k = D->k, out->offset = D->offset;
    out->nf_unpadded = 4 * D->nf_unpadded;
    out->refine = 2 * D->refine;
    out->quads_unpadded = 4 * D->quads_unpadded, out->quads_added = 4 * D->quads_added;
    out->offsets_feasible = D->offsets_feasible, out->slid = D->slid;
    out->slide_length = 2 * D->slide_length, out->slide_shift = 2 * D->slide_shift;
    out->slide_start = D->slide_start, out->slide_end = D->slide_end;
    out->seconds = D->seconds;
    out->order = malloc(((size_t)D->ncones + 1) * sizeof *out->order);
    out->f_meta_face = malloc(((size_t)out->nf_unpadded + 1) * sizeof *out->f_meta_face);
    out->corner_vert = malloc(((size_t)D->k + 1) * sizeof *out->corner_vert);
    out->side_len = malloc(((size_t)D->k + 1) * sizeof *out->side_len);
    out->padding = malloc(((size_t)D->k + 1) * sizeof *out->padding);
    if (!out->order || !out->f_meta_face || !out->corner_vert || !out->side_len || !out->padding) {
        sq_domain_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    memcpy(out->order, D->order, (size_t)D->ncones * sizeof *out->order);
    for (uint32_t f = 0; f < out->nf_unpadded; f++) out->f_meta_face[f] = D->f_meta_face[f / 4];
    for (uint32_t i = 0; i < D->k; i++) {
        out->corner_vert[i] = D->corner_vert[i];
        out->side_len[i] = 2 * D->side_len[i];
        out->padding[i] = D->padding ? 2 * D->padding[i] : 0;
    }
    st = sq_metapolygon_copy(&out->meta, &D->meta, err);
    if (st == SQ_OK) st = sq_pattern_copy(&out->pattern, &D->pattern, err);
    if (st) sq_domain_free(out);
    return st;
}
