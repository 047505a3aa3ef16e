/* seamquad: exact geometric predicates on double inputs.
 *
 * A floating-point filter with a proven error bound answers almost every
 * call; when it cannot decide, the determinant is evaluated exactly with GMP
 * rationals (every finite double is a rational). Results are exact for all
 * finite inputs. */
#ifndef SQ_PREDICATES_H
#define SQ_PREDICATES_H

#ifdef __cplusplus
extern "C" {
#endif

/* Sign of det [b-a, c-a]: +1 if a, b, c turn counter-clockwise, -1 if
 * clockwise, 0 if exactly collinear. */
int sq_orient2d(const double a[2], const double b[2], const double c[2]);

/* Same, always evaluated exactly (reference for tests and benchmarks). */
int sq_orient2d_exact(const double a[2], const double b[2], const double c[2]);

/* 1 if the three 3D points are exactly collinear (or coincide), else 0. */
int sq_collinear3d(const double a[3], const double b[3], const double c[3]);

#ifdef __cplusplus
}
#endif
#endif
