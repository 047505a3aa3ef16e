/* seamquad: closest point of one triangle to a point.
 *
 * The nearest of four candidates, by their actual distance to p: the
 * closest points of the three sides (segments), and where p projects into
 * the triangle (the sides' orientation tests against the normal, as signs
 * of triple products) the projection, as a barycentric combination.
 * Written for needles (inputs have triangles of area 1e-12 of the squared
 * diagonal): classifying p by differences of dot products (the Voronoi
 * regions of the closed form) loses every digit there (points on a
 * needle's side came back 0.16 of the triangle's size away); the sides'
 * points need no normal, and where a needle's normal, and with it the
 * projection, is off by rounding, p is within the needle's width of a
 * side, whose point then wins. */
#include <math.h>

#include "sq_closest_point.h"

static double dot3(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

static void sub3(const double *u, const double *v, double *w)
{
    w[0] = u[0] - v[0], w[1] = u[1] - v[1], w[2] = u[2] - v[2];
}

static void cross(const double *u, const double *v, double *w)
{
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
}

/* q = the combination of the corners with weights w */
static void combine(const double *a, const double *b, const double *c, const double w[3], double q[3])
{
    for (int k = 0; k < 3; k++) {
        if (w[1] == 0.0 && w[2] == 0.0) q[k] = a[k];
        else if (w[0] == 0.0 && w[2] == 0.0) q[k] = b[k];
        else if (w[0] == 0.0 && w[1] == 0.0) q[k] = c[k];
        else q[k] = w[0] * a[k] + w[1] * b[k] + w[2] * c[k];
    }
}

static double dist2(const double *p, const double *q)
{
    double d[3];
    sub3(p, q, d);
    return dot3(d, d);
}

void sq_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double bary[3], double q[3])
{
    const double *corner[3] = {a, b, c};
    double best = INFINITY;
    /* the sides' closest points: pure corners and side points are exact */
    for (int k = 0; k < 3; k++) {
        const double *x = corner[k], *y = corner[(k + 1) % 3];
        double xy[3], xp[3];
        sub3(y, x, xy);
        sub3(p, x, xp);
        const double l2 = dot3(xy, xy);
        const double t = l2 > 0 ? fmin(fmax(dot3(xp, xy) / l2, 0.0), 1.0) : 0.0;
        double w[3], r[3];
        w[k] = 1.0 - t, w[(k + 1) % 3] = t, w[(k + 2) % 3] = 0.0;
        combine(a, b, c, w, r);
        const double d2 = dist2(p, r);
        if (d2 < best) {
            best = d2;
            for (int i = 0; i < 3; i++) bary[i] = w[i], q[i] = r[i];
        }
    }
    /* the projection onto the plane, where p projects inside */
    double ab[3], ac[3], n[3];
    sub3(b, a, ab);
    sub3(c, a, ac);
    cross(ab, ac, n);
    const double nn = dot3(n, n);
    if (!(nn > 0)) return;
    double w[3];
    for (int k = 0; k < 3; k++) {
        /* the side opposite corner k with p, against n: corner k's weight */
        const double *x = corner[(k + 1) % 3], *y = corner[(k + 2) % 3];
        double xy[3], xp[3], e[3];
        sub3(y, x, xy);
        sub3(p, x, xp);
        cross(xy, xp, e);
        w[k] = dot3(e, n) / nn;
        if (!(w[k] > 0)) return; /* outside, or on a side: a side point is nearest */
    }
    const double s = w[0] + w[1] + w[2];
    for (int k = 0; k < 3; k++) w[k] /= s;
    double r[3];
    combine(a, b, c, w, r);
    const double d2 = dist2(p, r);
    if (d2 < best)
        for (int i = 0; i < 3; i++) bary[i] = w[i], q[i] = r[i];
}
