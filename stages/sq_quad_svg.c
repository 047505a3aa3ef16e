/* seamquad: a picture of a quad mesh (sq_quad_svg.h).
 *
 * An orthographic view from a fixed direction (from the front, above and to
 * the left of the bounding box's centre), every quad facing the viewer drawn
 * as a polygon, far ones first (painter's order by the quad's mean depth),
 * shaded by the angle between its normal and the light (which comes from
 * the viewer's direction); irregular vertices facing the viewer marked: red
 * below valence 4, blue above. Quads seen edge-on or from behind are left
 * out. Painter's order is exact for convex, non-overlapping shapes and close
 * enough for a picture of a closed surface.
 *
 * Cost: O(q log q) for q quads; the file holds about 120 bytes per quad. */
#include "sq_quad_svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sq_io.h"

typedef struct drawn {
    double depth;
    uint32_t q;
    double shade;
} drawn;

static int by_depth(const void *a, const void *b)
{
    double x = ((const drawn *)a)->depth, y = ((const drawn *)b)->depth;
    return (x > y) - (x < y);
}

/* view frame: right r, up u, towards the viewer w (unit, orthonormal) */
static void view_frame(double r[3], double u[3], double w[3])
{
    const double az = 0.6, el = 0.45;
    w[0] = sin(az) * cos(el), w[1] = sin(el), w[2] = cos(az) * cos(el);
    r[0] = cos(az), r[1] = 0, r[2] = -sin(az);
    u[0] = w[1] * r[2] - w[2] * r[1];
    u[1] = w[2] * r[0] - w[0] * r[2];
    u[2] = w[0] * r[1] - w[1] * r[0];
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

sq_status sq_quad_svg_write(const char *path, uint32_t nv, const double *pos, uint32_t nq,
                            const uint32_t *quad, const char *title, sq_error *err)
{
    if (!path || !pos || !quad || !nv || !nq) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_quad_svg_write: empty mesh");
    double r[3], u[3], w[3];
    view_frame(r, u, w);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    double *xy = malloc(2 * (size_t)nv * sizeof *xy);
    drawn *d = malloc((size_t)nq * sizeof *d);
    int32_t *val = calloc(nv, sizeof *val);
    uint8_t *front = calloc(nv, 1);
    if (!xy || !d || !val || !front) {
        free(xy), free(d), free(val), free(front);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (picture of %u quads)", nq);
    }
    for (uint32_t v = 0; v < nv; v++) {
        const double *p = pos + 3 * (size_t)v;
        xy[2 * v] = dot3(p, r), xy[2 * v + 1] = dot3(p, u);
        for (int i = 0; i < 2; i++) lo[i] = fmin(lo[i], xy[2 * v + i]), hi[i] = fmax(hi[i], xy[2 * v + i]);
    }
    uint32_t n = 0;
    for (uint32_t q = 0; q < nq; q++) {
        const uint32_t *c = quad + 4 * (size_t)q;
        const double *p0 = pos + 3 * (size_t)c[0], *p1 = pos + 3 * (size_t)c[1], *p2 = pos + 3 * (size_t)c[2],
                     *p3 = pos + 3 * (size_t)c[3];
        for (int k = 0; k < 4; k++) val[c[k]]++;
        /* the quad's normal: the cross product of its diagonals */
        double a[3], b[3], nrm[3];
        for (int i = 0; i < 3; i++) a[i] = p2[i] - p0[i], b[i] = p3[i] - p1[i];
        nrm[0] = a[1] * b[2] - a[2] * b[1];
        nrm[1] = a[2] * b[0] - a[0] * b[2];
        nrm[2] = a[0] * b[1] - a[1] * b[0];
        double len = sqrt(dot3(nrm, nrm));
        if (!(len > 0)) continue;
        double facing = dot3(nrm, w) / len;
        if (facing <= 0) continue;
        d[n].q = q;
        d[n].shade = facing;
        d[n].depth = (dot3(p0, w) + dot3(p1, w) + dot3(p2, w) + dot3(p3, w)) / 4;
        for (int k = 0; k < 4; k++) front[c[k]] = 1;
        n++;
    }
    qsort(d, n, sizeof *d, by_depth);
    double size = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double S = size > 0 ? 760.0 / size : 1.0, W = (hi[0] - lo[0]) * S + 40, H = (hi[1] - lo[1]) * S + 60;
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (!st) {
        FILE *f = af.fp;
        fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\">\n",
                W, H, W, H);
        fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
        if (title) {
            fprintf(f, "<text x=\"20\" y=\"28\" font-family=\"sans-serif\" font-size=\"16\">");
            for (const char *s = title; *s; s++) {
                if (*s == '<') fputs("&lt;", f);
                else if (*s == '&') fputs("&amp;", f);
                else fputc(*s, f);
            }
            fprintf(f, "</text>\n");
        }
        fprintf(f, "<g stroke=\"#1a1a1a\" stroke-width=\"%.2f\" stroke-linejoin=\"round\">\n",
                fmin(0.6, fmax(0.15, 12.0 / sqrt((double)nq))));
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t *c = quad + 4 * (size_t)d[i].q;
            int g = (int)(90 + 150 * d[i].shade);
            fprintf(f, "<polygon fill=\"rgb(%d,%d,%d)\" points=\"", g, g, (int)fmin(255, g + 12));
            for (int k = 0; k < 4; k++)
                fprintf(f, "%s%.1f,%.1f", k ? " " : "", 20 + (xy[2 * c[k]] - lo[0]) * S,
                        40 + (hi[1] - xy[2 * c[k] + 1]) * S);
            fprintf(f, "\"/>\n");
        }
        fprintf(f, "</g>\n");
        for (uint32_t v = 0; v < nv; v++) {
            if (!front[v] || val[v] == 4 || val[v] == 0) continue;
            fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"%s\"/>\n", 20 + (xy[2 * v] - lo[0]) * S,
                    40 + (hi[1] - xy[2 * v + 1]) * S, val[v] < 4 ? "#d7191c" : "#2c7bb6");
        }
        fprintf(f, "</svg>\n");
        st = sq_atomic_commit(&af, err);
    }
    free(xy), free(d), free(val), free(front);
    return st;
}
