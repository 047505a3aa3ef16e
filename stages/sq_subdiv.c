/* seamquad: Catmull-Clark surface of a closed quad mesh (OpenSubdiv patches
 * with B-spline end caps) and uniform refinement. See docs/subdiv.md. */
#include "sq_subdiv.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_osd_adapter.h"

void sq_subdiv_free(sq_subdiv *s)
{
    if (!s) return;
    sq_osd_free(s->osd);
    free(s->cv);
    free(s->patch_face);
    free(s->patch_dom);
    free(s->face_first);
    free(s->face_patch);
    memset(s, 0, sizeof *s);
}

static double bbox_diagonal(uint32_t nv, const double *pos)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (uint32_t v = 0; v < nv; v++)
        for (int c = 0; c < 3; c++) {
            double x = pos[3 * (size_t)v + c];
            if (x < lo[c]) lo[c] = x;
            if (x > hi[c]) hi[c] = x;
        }
    double d = 0.0;
    for (int c = 0; c < 3; c++) d += (hi[c] - lo[c]) * (hi[c] - lo[c]);
    return sqrt(d);
}

sq_status sq_subdiv_build(const sq_mesh *mesh, int isolation, sq_subdiv *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (!mesh || mesh->nf == 0)
        return sq_error_set(err, SQ_ERR_EMPTY, "subdivision of an empty mesh");
    if (mesh->nh != 4 * (uint64_t)mesh->nf)
        return sq_error_set(err, SQ_ERR_POLYGON,
                            "Catmull-Clark export needs a pure-quad mesh (%u faces, %u corners)",
                            mesh->nf, mesh->nh);
    /* Face corners in halfedge order: halfedge 4f+k starts at corner k. */
    uint32_t *fo = malloc(((size_t)mesh->nf + 1) * sizeof *fo);
    uint32_t *fi = malloc((size_t)mesh->nh * sizeof *fi);
    if (!fo || !fi) {
        free(fo);
        free(fi);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t f = 0; f <= mesh->nf; f++) fo[f] = 4 * f;
    for (uint32_t f = 0; f < mesh->nf; f++) {
        uint32_t h = mesh->f_he[f];
        for (uint32_t k = 0; k < 4; k++, h = mesh->he_next[h]) {
            if (h != 4 * f + k || mesh->he_face[h] != f) {
                free(fo);
                free(fi);
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "mesh halfedges are not in soup corner order (face %u)", f);
            }
            fi[4 * f + k] = mesh->he_vert[h];
        }
    }
    sq_status st = sq_osd_create(mesh->nv, mesh->pos, mesh->nf, fo, fi, isolation, &out->osd, err);
    free(fo);
    free(fi);
    if (st) return st;
    out->nf = mesh->nf;
    out->isolation = isolation;
    out->np = sq_osd_patch_count(out->osd);
    out->bbox_diag = bbox_diagonal(mesh->nv, mesh->pos);
    size_t np = out->np;
    out->cv = malloc(48 * np * sizeof *out->cv);
    out->patch_face = malloc(np * sizeof *out->patch_face);
    out->patch_dom = malloc(4 * np * sizeof *out->patch_dom);
    out->face_first = calloc((size_t)mesh->nf + 1, sizeof *out->face_first);
    out->face_patch = malloc(np * sizeof *out->face_patch);
    if (!out->cv || !out->patch_face || !out->patch_dom || !out->face_first || !out->face_patch) {
        sq_subdiv_free(out);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for %zu patches", np);
    }
    for (uint32_t p = 0; p < out->np; p++) {
        sq_osd_patch(out->osd, p, out->cv + 48 * (size_t)p, &out->patch_face[p],
                     out->patch_dom + 4 * (size_t)p);
        if (out->patch_face[p] >= mesh->nf) {
            sq_status e = sq_error_set(err, SQ_ERR_INTERNAL, "patch %u on face %u of %u", p,
                                       out->patch_face[p], mesh->nf);
            sq_subdiv_free(out);
            return e;
        }
        out->face_first[out->patch_face[p] + 1]++;
    }
    for (uint32_t f = 0; f < mesh->nf; f++) out->face_first[f + 1] += out->face_first[f];
    for (uint32_t p = 0; p < out->np; p++) {
        /* fill in order, using face_first[f] as a cursor, restored below */
        out->face_patch[out->face_first[out->patch_face[p]]++] = p;
    }
    for (uint32_t f = mesh->nf; f > 0; f--) out->face_first[f] = out->face_first[f - 1];
    out->face_first[0] = 0;
    return SQ_OK;
}

void sq_subdiv_eval(const sq_subdiv *s, uint32_t f, double u, double v, double P[3], double N[3])
{
    double du[3], dv[3];
    sq_osd_eval(s->osd, f, UINT32_MAX, u, v, P, du, dv);
    if (!N) return;
    N[0] = du[1] * dv[2] - du[2] * dv[1];
    N[1] = du[2] * dv[0] - du[0] * dv[2];
    N[2] = du[0] * dv[1] - du[1] * dv[0];
    double l = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (l > 0) {
        N[0] /= l;
        N[1] /= l;
        N[2] /= l;
    }
}

sq_status sq_subdiv_refine(const sq_soup *in, int levels, sq_soup *out, sq_error *err)
{
    memset(out, 0, sizeof *out);
    return sq_osd_refine_uniform(in->nv, in->pos, in->nf, in->face_off, in->face_idx, levels,
                                 &out->nv, &out->pos, &out->nf, &out->face_off, &out->face_idx,
                                 err);
}
