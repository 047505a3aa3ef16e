/* seamquad: the isometric layout of Omega_c and its seamless transitions
 * (seed 7: "Using the unit square metric, the cut quad mesh Q can be laid
 * out isometrically in the plane, yielding the seamless parameter domain
 * Omega"; seed 3, 8; seamless-notes 5).
 *
 * Every quad is a unit square with integer corners; a face is placed from a
 * neighbour across an uncut edge: the shared edge is reversed, and going
 * counterclockwise round a face each edge direction turns by +90 degrees.
 * Breadth-first over faces, every vertex keeps the first position it gets
 * and every later face must agree (the closing condition: it holds because
 * Omega_c is a disk whose interior vertices all have four quads). All
 * arithmetic is in int64; directions are 0..3 (+x, +y, -x, -y).
 *
 * Transitions: for each boundary label l (a side of Q, or one side of a
 * tree segment), the first edge with that label fixes the rotation r and
 * the translation t that carry it onto its other copy (reversed); every
 * other edge with label l must then agree exactly. */
#include <stdlib.h>
#include <string.h>

#include "sq_omega.h"
#include "sq_omega_grid.h"


sq_status sq_omega_layout(const sq_domain *D, sq_omega *O, sq_error *err)
{
    (void)D;
    const sq_metapolygon *C = &O->cut;
    sq_status st = SQ_OK;
    free(O->xy), free(O->f_dir), free(O->label_rot), free(O->label_t);
    O->xy = malloc(2 * (size_t)(C->nv ? C->nv : 1) * sizeof *O->xy);
    O->f_dir = malloc((C->nf ? C->nf : 1) * sizeof *O->f_dir);
    O->label_rot = malloc((O->nlabels ? O->nlabels : 1) * sizeof *O->label_rot);
    O->label_t = malloc(2 * (size_t)(O->nlabels ? O->nlabels : 1) * sizeof *O->label_t);
    uint8_t *vset = calloc(C->nv ? C->nv : 1, 1);
    uint8_t *lset = calloc(O->nlabels ? O->nlabels : 1, 1);
    uint32_t *queue = malloc((C->nf ? C->nf : 1) * sizeof *queue);
    int64_t *forg = malloc(2 * (size_t)(C->nf ? C->nf : 1) * sizeof *forg);
    if (!O->xy || !O->f_dir || !O->label_rot || !O->label_t || !vset || !lset || !queue ||
        !forg) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t f = 0; f < C->nf; f++) {
        if (C->f_valence[f] != 4) {
            st = sq_error_set(err, SQ_ERR_ARGUMENT, "omega: face %u has %u sides, not a quad", f,
                              C->f_valence[f]);
            goto done;
        }
        O->f_dir[f] = 0xff;
    }
    if (C->nf == 0) goto done;

    /* breadth-first placement; face 0's first corner at the origin, its
     * first edge along +x; forg: position of each face's first corner */
    uint32_t nq = 0;
    queue[nq++] = 0;
    O->f_dir[0] = 0;
    forg[0] = forg[1] = 0;
    for (uint32_t qi = 0; qi < nq; qi++) {
        uint32_t f = queue[qi], h = C->f_he[f], d = O->f_dir[f];
        int64_t x = forg[2 * f], y = forg[2 * f + 1];
        for (uint32_t i = 0; i < 4; i++, h = C->he_next[h], d = (d + 1) & 3u) {
            uint32_t v = C->he_vert[h];
            if (!vset[v]) {
                vset[v] = 1;
                O->xy[2 * v] = x;
                O->xy[2 * v + 1] = y;
            } else if (O->xy[2 * v] != x || O->xy[2 * v + 1] != y) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "omega: layout does not close: vertex %u (copy of vertex %u of "
                                  "Q) at (%lld, %lld) from face %u but (%lld, %lld) before",
                                  v, O->v_qvert[v], (long long)x, (long long)y, f,
                                  (long long)O->xy[2 * v], (long long)O->xy[2 * v + 1]);
                goto done;
            }
            int64_t hx = x + DX[d], hy = y + DY[d]; /* head of h */
            /* the neighbour across an uncut edge: t = twin(h) starts at
             * h's head and runs the opposite way (direction d + 2) */
            uint32_t t = C->he_twin[h], g = C->he_face[t];
            if (g != SQ_NONE && O->f_dir[g] == 0xff) {
                uint32_t gd = (d + 2) & 3u;
                int64_t gx = hx, gy = hy;
                for (uint32_t e = t; e != C->f_he[g]; e = C->he_next[e]) {
                    gx += DX[gd], gy += DY[gd];
                    gd = (gd + 1) & 3u;
                }
                O->f_dir[g] = (uint8_t)gd;
                forg[2 * g] = gx;
                forg[2 * g + 1] = gy;
                queue[nq++] = g;
            }
            x = hx;
            y = hy;
        }
    }
    if (nq != C->nf) {
        st = sq_error_set(err, SQ_ERR_INTERNAL, "omega: layout reached %u of %u faces", nq,
                          C->nf);
        goto done;
    }
    O->xmin = O->xmax = O->xy[0];
    O->ymin = O->ymax = O->xy[1];
    for (uint32_t v = 0; v < C->nv; v++) {
        if (!vset[v]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "omega: vertex %u was not placed", v);
            goto done;
        }
        int64_t x = O->xy[2 * v], y = O->xy[2 * v + 1];
        if (x < O->xmin) O->xmin = x;
        if (x > O->xmax) O->xmax = x;
        if (y < O->ymin) O->ymin = y;
        if (y > O->ymax) O->ymax = y;
    }

    /* transitions, seed 3 and 8: y = R^r x + t on every edge of a label */
    for (uint32_t b = 0; b < C->nh; b++) {
        if (C->he_face[b] != SQ_NONE) continue;
        uint32_t l = O->he_label[b], p = O->he_partner[b];
        if (l >= O->nlabels || p == SQ_NONE || O->he_label[p] != O->label_partner[l]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "omega: boundary halfedge %u has a bad label or partner", b);
            goto done;
        }
        /* b: a -> z; its partner runs z' -> a' */
        uint32_t a = C->he_vert[b], z = C->he_vert[C->he_next[b]];
        uint32_t a2 = C->he_vert[C->he_next[p]], z2 = C->he_vert[p];
        int64_t ax = O->xy[2 * a], ay = O->xy[2 * a + 1], zx = O->xy[2 * z], zy = O->xy[2 * z + 1];
        int64_t a2x = O->xy[2 * a2], a2y = O->xy[2 * a2 + 1];
        int64_t z2x = O->xy[2 * z2], z2y = O->xy[2 * z2 + 1];
        if (!lset[l]) {
            uint32_t d1 = dir_of(zx - ax, zy - ay), d2 = dir_of(z2x - a2x, z2y - a2y);
            if (d1 > 3 || d2 > 3) {
                st = sq_error_set(err, SQ_ERR_INTERNAL,
                                  "omega: boundary edge %u is not a unit axis edge", b);
                goto done;
            }
            uint32_t r = (d2 + 4 - d1) & 3u;
            int64_t rx, ry;
            rot(r, ax, ay, &rx, &ry);
            lset[l] = 1;
            O->label_rot[l] = (uint8_t)r;
            O->label_t[2 * l] = a2x - rx;
            O->label_t[2 * l + 1] = a2y - ry;
        }
        uint32_t r = O->label_rot[l];
        int64_t tx = O->label_t[2 * l], ty = O->label_t[2 * l + 1], rx, ry, sx, sy;
        rot(r, ax, ay, &rx, &ry);
        rot(r, zx, zy, &sx, &sy);
        if (rx + tx != a2x || ry + ty != a2y || sx + tx != z2x || sy + ty != z2y) {
            const char *what = O->label_side[l] != SQ_NONE ? "side" : "tree segment";
            uint32_t idx = O->label_side[l] != SQ_NONE ? O->label_side[l] : (l - O->k) / 2;
            st = sq_error_set(err, SQ_ERR_INTERNAL,
                              "omega: %s %u is not seamless: boundary edge %u (copy of vertex %u "
                              "of Q) is not mapped onto its other copy by rotation %u x 90 deg "
                              "+ (%lld, %lld)",
                              what, idx, b, O->v_qvert[a], r, (long long)tx, (long long)ty);
            goto done;
        }
    }
    for (uint32_t l = 0; l < O->nlabels; l++)
        if (!lset[l]) {
            st = sq_error_set(err, SQ_ERR_INTERNAL, "omega: label %u has no boundary edge", l);
            goto done;
        }
done:
    free(vset);
    free(lset);
    free(queue);
    free(forg);
    return st;
}
