/* seamquad: the closest point of one triangle in 3D to a point. */
#ifndef SQ_CLOSEST_POINT_TRIANGLE_H
#define SQ_CLOSEST_POINT_TRIANGLE_H

#ifdef __cplusplus
extern "C" {
#endif

/* Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision
 * Detection, 5.1.5): barycentrics in bary, the point in q. */
void sq_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double bary[3], double q[3]);

#ifdef __cplusplus
}
#endif
#endif
