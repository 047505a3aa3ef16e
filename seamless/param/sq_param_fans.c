/* seamquad: graded fans along the cut of the overlay's surface disk
 * (step 7', sq_param_overlay.c; sq_param_internal.h).
 *
 * The cut surface's boundary carries a vertex at every boundary vertex of
 * Omega (so that both disks share their boundary points), which splits an
 * input edge on the cut into up to hundreds of pieces, each joined to the
 * face's opposite vertex: a fan of thin triangles reaching from the cut
 * deep into the surface. In the disk, every one of those long edges
 * crosses every row of Omega's triangles between the circle and the fan's
 * apex: on mpz/elk the fans of 16 or more triangles (3% of the surface's
 * triangles) made half of the overlay's 8.2 million faces. Graded, elk's
 * crossings drop from 4.09 to 2.26 million, elephant's from 4.44 to 3.09
 * million (docs/param.md, "Graded fans along the cut").
 *
 * This pass replaces every such fan by a graded triangulation of the same
 * polygon (apex c, base p_0 .. p_k on one straight input edge, in one
 * input face): a binary tree of added vertices whose depth above the base
 * halves with the width of the base they stand on, so that the long edges
 * are few and the many short ones stay near the cut. The polygon's
 * outline (its base and the two edges c-p_0, c-p_k) is kept, so the rest
 * of the triangulation is unchanged; every added vertex lies strictly
 * inside the polygon, in the input face's plane, and every new triangle
 * is positively oriented there (see grade). The map stays bijective: the
 * overlay needs only a triangulated disk, which this still is.
 *
 * The library never prints or exits. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_internal.h"

/* The height of a fan's top added vertex above the base, in units of the
 * base's width (below it every vertex stands at half its parent's height
 * over half its base): low vertices keep the many short edges close to the
 * cut, where Omega's layers are thin too. Crossings of the overlay against
 * this value, fans of 12 or more triangles (mpz/elk, cid/elephant; 4.09M,
 * 4.44M without the fans): 1/2: 3.02M, 4.16M; 1/8: 2.72M, 3.83M; 1/32:
 * 2.46M, 3.53M; with fans of 3 or more (SQ_FAN_MIN_RUN): 1/32: 2.41M,
 * 3.29M; 1/128: 2.26M, 3.09M; 1/256: 2.22M, 3.03M. 1/128 keeps the
 * smallest heights in the disk maps far above the solver's rounding. */
#define FAN_HEIGHT (1.0 / 128)

/* a growing face list (tri, fin) and vertex list (p3) */
typedef struct fan_out {
    uint32_t nf, capf, nv, capv;
    uint32_t *tri, *fin;
    double *p3;
} fan_out;

static int add_face(fan_out *o, uint32_t a, uint32_t b, uint32_t c, uint32_t fin)
{
    if (o->nf == o->capf) {
        uint32_t cap = o->capf * 2 + 64;
        uint32_t *t = realloc(o->tri, 3 * (size_t)cap * sizeof *t);
        if (!t) return -1;
        o->tri = t;
        uint32_t *g = realloc(o->fin, (size_t)cap * sizeof *g);
        if (!g) return -1;
        o->fin = g, o->capf = cap;
    }
    uint32_t *t = o->tri + 3 * (size_t)o->nf;
    t[0] = a, t[1] = b, t[2] = c;
    o->fin[o->nf++] = fin;
    return 0;
}

static uint32_t add_vertex(fan_out *o, const double *p)
{
    if (o->nv == o->capv) {
        uint32_t cap = o->capv * 2 + 64;
        double *q = realloc(o->p3, 3 * (size_t)cap * sizeof *q);
        if (!q) return SQ_NONE;
        o->p3 = q, o->capv = cap;
    }
    memcpy(o->p3 + 3 * (size_t)o->nv, p, 3 * sizeof *p);
    return o->nv++;
}

static const double *vpos(const fan_out *o, uint32_t v) { return o->p3 + 3 * (size_t)v; }

static double dist3(const double *a, const double *b)
{
    return sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
}

/* distance of x from the line through a and b (a != b) */
static double line_dist(const double *a, const double *b, const double *x)
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    double cx = d[1] * e[2] - d[2] * e[1], cy = d[2] * e[0] - d[0] * e[2], cz = d[0] * e[1] - d[1] * e[0];
    return sqrt(cx * cx + cy * cy + cz * cz) / dist3(a, b);
}

/* The polygon (x; p[i] .. p[j]) (base p[i..j] on one line, x off it, faces
 * (p_t, p_t+1, x) counterclockwise) triangulated: j - i <= 2 as a fan
 * from x; else a vertex q on the segment from the base's middle point p_m
 * towards x, at FAN_HEIGHT times the base's width above it (at most half
 * as high as x: below the top vertex, half its parent's height), the
 * triangles (p_i, q, x), (q, p_j, x), and the two halves as polygons
 * (q; p_i .. p_m), (q; p_m .. p_j). q lies strictly inside the triangle
 * (p_i, p_j, x) (p_m strictly between p_i and p_j, 0 < tau <= 1/2), hence
 * every triangle made is positively oriented in the face's plane. */
static int grade(fan_out *o, const uint32_t *p, uint32_t i, uint32_t j, uint32_t x, uint32_t fin, int depth)
{
    if (j - i <= 2 || depth > 40) {
        for (uint32_t t = i; t < j; t++)
            if (add_face(o, p[t], p[t + 1], x, fin)) return -1;
        return 0;
    }
    uint32_t m = i + (j - i) / 2;
    const double *pi = vpos(o, p[i]), *pj = vpos(o, p[j]), *pm = vpos(o, p[m]), *px = vpos(o, x);
    double w = dist3(pi, pj), h = line_dist(pi, pj, px), tau = h > 0 ? FAN_HEIGHT * w / h : 0.5;
    if (!(tau < 0.5)) tau = 0.5;
    double q[3];
    for (int d = 0; d < 3; d++) q[d] = pm[d] + tau * (px[d] - pm[d]);
    uint32_t qv = add_vertex(o, q);
    if (qv == SQ_NONE) return -1;
    if (add_face(o, p[i], qv, x, fin) || add_face(o, qv, p[j], x, fin)) return -1;
    if (grade(o, p, i, m, qv, fin, depth + 1)) return -1;
    return grade(o, p, m, j, qv, fin, depth + 1);
}

/* g continues f's fan: a fan face (bcorner: the corner of its base) with
 * f's apex and f's input face */
static int same_fan(const uint32_t *tri, const uint32_t *fin, const uint32_t *bcorner, uint32_t f, uint32_t g)
{
    return g != SQ_NONE && bcorner[g] != SQ_NONE && fin[g] == fin[f] &&
           tri[3 * g + (bcorner[g] + 2) % 3] == tri[3 * f + (bcorner[f] + 2) % 3];
}

sq_status sq_param_grade_fans(uint32_t nbl, uint32_t min_run, const uint32_t *twin, uint32_t *nf_io,
                              uint32_t **tri_io, uint32_t **fin_io, uint32_t *nv_io, double **p3_io,
                              uint32_t *added, sq_error *err)
{
    const uint32_t nf = *nf_io, nv = *nv_io;
    const uint32_t *tri = *tri_io, *fin = *fin_io;
    *added = 0;
    uint32_t *bstart = malloc(((size_t)nbl + 1) * sizeof *bstart); /* boundary id -> fan face whose base */
    uint32_t *bend = malloc(((size_t)nbl + 1) * sizeof *bend);     /* starts / ends there               */
    uint32_t *bcorner = malloc(((size_t)nf + 1) * sizeof *bcorner);  /* face -> corner of its base, or NONE */
    uint8_t *dead = calloc((size_t)nf + 1, 1);
    uint32_t *run = NULL, *pid = NULL;
    fan_out o = {0};
    sq_status st = SQ_OK;
    if (!bstart || !bend || !bcorner || !dead) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (fans)");
        goto done;
    }
    /* the fan faces: a base on the boundary (no twin), the apex inside */
    for (uint32_t v = 0; v < nbl; v++) bstart[v] = bend[v] = SQ_NONE;
    for (uint32_t f = 0; f < nf; f++) {
        bcorner[f] = SQ_NONE;
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t a = tri[3 * f + k], b = tri[3 * f + (k + 1) % 3], c = tri[3 * f + (k + 2) % 3];
            if (twin[3 * f + k] == SQ_NONE && a < nbl && b < nbl && c >= nbl) {
                bcorner[f] = k;
                bstart[a] = f, bend[b] = f;
            }
        }
    }
    o.nv = o.capv = nv;
    o.p3 = malloc(3 * ((size_t)nv + 1) * sizeof *o.p3);
    run = malloc(((size_t)nbl + 2) * sizeof *run);
    pid = malloc(((size_t)nbl + 2) * sizeof *pid);
    if (!o.p3 || !run || !pid) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (fans)");
        goto done;
    }
    memcpy(o.p3, *p3_io, 3 * (size_t)nv * sizeof *o.p3);
    /* the runs: consecutive fan faces with one apex, one input face and a
     * straight base, from a face whose predecessor is none of them */
    for (uint32_t f = 0; f < nf && st == SQ_OK; f++) {
        if (bcorner[f] == SQ_NONE || dead[f]) continue;
        uint32_t c = tri[3 * f + (bcorner[f] + 2) % 3], g = bend[tri[3 * f + bcorner[f]]];
        if (g != f && same_fan(tri, fin, bcorner, f, g)) continue;
        /* one run after the other along the fan, a new one where the base bends */
        for (uint32_t h = f; h != SQ_NONE && st == SQ_OK;) {
            uint32_t n = 0, start = h, bent = SQ_NONE;
            pid[0] = tri[3 * h + bcorner[h]];
            while (h != SQ_NONE && n < nbl) {
                uint32_t b = tri[3 * h + (bcorner[h] + 1) % 3];
                if (!same_fan(tri, fin, bcorner, f, h) || dead[h]) break;
                if (n >= 1) { /* straight: b on the line of the run's first piece */
                    const double *p0 = vpos(&o, pid[0]), *p1 = vpos(&o, pid[1]), *pb = vpos(&o, b);
                    if (!(line_dist(p0, p1, pb) <= 1e-9 * dist3(p0, pb))) {
                        bent = h;
                        break;
                    }
                }
                run[n++] = h;
                pid[n] = b;
                h = bstart[b];
                if (h == start) break;
            }
            if (n >= min_run) {
                for (uint32_t t = 0; t < n; t++) dead[run[t]] = 1;
                uint32_t before = o.nv;
                if (grade(&o, pid, 0, n, c, fin[f], 0)) st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (fans)");
                *added += o.nv - before;
            }
            h = bent;
        }
    }
    if (st || !*added) goto done;
    /* the faces kept, in their order, then the new ones */
    uint32_t nkeep = 0;
    for (uint32_t f = 0; f < nf; f++) nkeep += !dead[f];
    uint32_t nout = nkeep + o.nf;
    uint32_t *t2 = malloc(3 * (size_t)nout * sizeof *t2), *f2 = malloc((size_t)nout * sizeof *f2);
    if (!t2 || !f2) {
        free(t2), free(f2);
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (fans)");
        goto done;
    }
    uint32_t w = 0;
    for (uint32_t f = 0; f < nf; f++)
        if (!dead[f]) {
            memcpy(t2 + 3 * (size_t)w, tri + 3 * (size_t)f, 3 * sizeof *t2);
            f2[w++] = fin[f];
        }
    memcpy(t2 + 3 * (size_t)w, o.tri, 3 * (size_t)o.nf * sizeof *t2);
    memcpy(f2 + w, o.fin, (size_t)o.nf * sizeof *f2);
    free(*tri_io), free(*fin_io), free(*p3_io);
    *tri_io = t2, *fin_io = f2, *p3_io = o.p3, o.p3 = NULL;
    *nf_io = nout, *nv_io = o.nv;
done:
    free(bstart), free(bend), free(bcorner), free(dead), free(run), free(pid);
    free(o.tri), free(o.fin), free(o.p3);
    return st;
}
