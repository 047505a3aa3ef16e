/* seamquad: closest point of one triangle to a point (Ericson, "Real-Time
 * Collision Detection", 5.1.5: Voronoi regions of vertices, edges, face). */
#include "sq_closest_point.h"

static double dot3(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

void sq_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double bary[3], double q[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
        bp[k] = p[k] - b[k];
        cp[k] = p[k] - c[k];
    }
    double u = 1.0, v = 0.0, w = 0.0; /* weights of a, b, c */
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d1 <= 0.0 && d2 <= 0.0) {
        u = 1.0, v = 0.0, w = 0.0;                        /* vertex a */
    } else if (d3 >= 0.0 && d4 <= d3) {
        u = 0.0, v = 1.0, w = 0.0;                        /* vertex b */
    } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        double t = d1 / (d1 - d3);                        /* edge ab */
        u = 1.0 - t, v = t, w = 0.0;
    } else if (d6 >= 0.0 && d5 <= d6) {
        u = 0.0, v = 0.0, w = 1.0;                        /* vertex c */
    } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        double t = d2 / (d2 - d6);                        /* edge ac */
        u = 1.0 - t, v = 0.0, w = t;
    } else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));   /* edge bc */
        u = 0.0, v = 1.0 - t, w = t;
    } else {
        double den = va + vb + vc;                        /* face */
        if (den > 0.0) {
            v = vb / den, w = vc / den, u = 1.0 - v - w;
        } else { /* degenerate triangle: fall back to the nearest corner */
            double da = dot3(ap, ap), db = dot3(bp, bp), dc = dot3(cp, cp);
            u = da <= db && da <= dc, v = !u && db <= dc, w = !u && !v;
        }
    }
    bary[0] = u, bary[1] = v, bary[2] = w;
    /* pure corners and edge points are reproduced exactly */
    for (int k = 0; k < 3; k++) {
        if (v == 0.0 && w == 0.0) q[k] = a[k];
        else if (u == 0.0 && w == 0.0) q[k] = b[k];
        else if (u == 0.0 && v == 0.0) q[k] = c[k];
        else q[k] = u * a[k] + v * b[k] + w * c[k];
    }
}
