/* seamquad: exact orientation predicates (see docs/predicates.md).
 *
 * sq_orient2d first evaluates the determinant in double precision and
 * accepts its sign when a proven error bound says the sign cannot be wrong
 * (a semi-static filter: the bound scales with the magnitude of the two
 * products). Otherwise it evaluates the determinant exactly with GMP
 * integers. The result is exact for every finite input, over the whole
 * double range (subnormals, products that underflow or overflow, and
 * differences that overflow included).
 *
 * Non-finite input (NaN or infinity) is a caller bug: callers validate
 * coordinates when they read them. Debug builds assert; release builds
 * return 0 ("degenerate") from sq_orient2d and sq_orient2d_exact, and so 1
 * ("collinear") from sq_collinear3d, so that such a point is never taken for
 * a valid one. The fast path does not pay for this check: a non-finite input
 * always makes the filter's magnitude non-finite, which sends it to the exact
 * path, where the check lives.
 *
 * ---------------------------------------------------------------------------
 * Error bound of the filter.
 *
 * Assumptions: IEEE 754 binary64 arithmetic, round to nearest, no extended
 * intermediate precision (FLT_EVAL_METHOD == 0, checked below). Let
 * u = 2^-53 (unit roundoff) and m = 2^-1075 (half the smallest subnormal).
 * For doubles x, y:
 *   fl(x - y) = (x - y)(1 + d)          |d| <= u  (exact model, also for
 *                                                  subnormal results)
 *   fl(x * y) = x y (1 + d) + e         |d| <= u, |e| <= m (e only on underflow)
 * as long as nothing overflows. Overflow is excluded by the test
 * S <= DBL_MAX below: any infinity or NaN in the inputs, the differences or
 * the products makes S infinite or NaN.
 *
 * With l = (bx-ax)(cy-ay) and r = (by-ay)(cx-ax) exact, the exact
 * determinant is det = l - r. The filter computes four rounded differences,
 * L = fl(t1 t2), R = fl(t3 t4), D = fl(L - R) and S = fl(|L| + |R|).
 * Each product carries three rounding factors (two differences and the
 * product itself), so with g = 3u / (1 - 3u) (the usual bound on a product of
 * three factors (1 + d_i)):
 *   |L - l| <= g |l| + m,   hence   |l| <= (|L| + m) / (1 - g),
 * and the same for R. Then
 *   |D - det| <= u |L - R| + |L - l| + |R - r|
 *             <= (u + g/(1-g)) (|L| + |R|) + 2m (1 + g/(1-g)).
 * g/(1-g) = 3u/(1-6u), and |L| + |R| <= S/(1-u). Requiring S >= 2^-960
 * turns the absolute term into a relative one: 2m(1 + g/(1-g)) < 3m
 * <= 3 * 2^-115 S, far below u^2 S. The bound is finally itself computed in
 * floating point, E = fl(C S), which is at least C S (1 - u) because C S is
 * a normal number (S >= 2^-960 keeps it above 2^-1022). Collecting terms,
 * |D - det| <= E holds whenever
 *   C (1 - u) >= [ (u + 3u/(1-6u)) / (1-u) + 3 * 2^-115 ] ,
 * whose right side is 4u + 26.004.. u^2 + O(u^3). We take
 *   C = 4u + 32u^2 = 2^-51 + 2^-101     (exactly representable),
 * checked with exact rationals. If |D| > E then D and det have the same sign.
 * (The same constant also covers a compiler that fuses the final subtraction
 * into an FMA, D = fl(t1 t2 - R): the coefficient of |L| then drops to about
 * 3u and that of |R| is unchanged. C11 permits contraction only inside one
 * expression; every operation below is its own statement.)
 *
 * When S < 2^-960 (tiny coordinates, including all-zero products) or S is
 * not finite (overflow), or |D| <= E, the exact path decides.
 * ---------------------------------------------------------------------------
 * Exact path.
 *
 * Every finite nonzero double is M 2^k with M an integer, |M| < 2^53 and
 * k >= -1126. Scaling all six coordinates by 2^-kmin (kmin the smallest such
 * exponent among them) makes them integers without changing the sign of the
 * determinant (it is multiplied by 2^(-2 kmin) > 0), so the determinant is
 * evaluated in GMP integers (mpz). The integers have at most about 2150
 * bits and the products 4300; the four temporaries are allocated once, at
 * their final size, per call. */
#include "sq_predicates.h"

#include <assert.h>
#include <float.h>
#include <math.h>

#include <gmp.h>

#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "sq_predicates.c: the filter's error bound needs FLT_EVAL_METHOD == 0 (SSE2, no x87)"
#endif

/* C = 4u + 32u^2 with u = 2^-53 (see the derivation above). */
static const double filter_factor = 0x1p-51 + 0x1p-101;
/* Below this magnitude the products may have lost digits to underflow. */
static const double filter_min_magnitude = 0x1p-960;

static int sign_of_int(int x) { return (x > 0) - (x < 0); }
static int sign_of_double(double x) { return (x > 0) - (x < 0); }

static int all_finite(const double a[2], const double b[2], const double c[2])
{
    return isfinite(a[0]) && isfinite(a[1]) && isfinite(b[0]) && isfinite(b[1]) &&
           isfinite(c[0]) && isfinite(c[1]);
}

/* Exponent k of the last mantissa bit: x = M 2^k with M an integer, |M| < 2^53.
 * x must be finite and nonzero. */
static int ulp_exponent(double x)
{
    int e;
    (void)frexp(x, &e); /* x = f 2^e, 0.5 <= |f| < 1 */
    return e - 53;
}

/* z = x 2^-base, an integer because base <= ulp_exponent(x). */
static void set_scaled(mpz_t z, double x, int base)
{
    if (x == 0) {
        mpz_set_ui(z, 0);
        return;
    }
    int e;
    const double f = frexp(x, &e);
    /* ldexp(f, 53) is an integer of at most 53 bits: mpz_set_d is exact. */
    mpz_set_d(z, ldexp(f, 53));
    assert(e - 53 >= base);
    mpz_mul_2exp(z, z, (mp_bitcnt_t)(e - 53 - base));
}

/* Exact sign of det [b-a, c-a] with GMP integers. Inputs must be finite. */
static int orient2d_gmp(const double a[2], const double b[2], const double c[2])
{
    const double *coords[6] = {&a[0], &a[1], &b[0], &b[1], &c[0], &c[1]};
    int base = 0, top = 0, any_nonzero = 0;
    for (int i = 0; i < 6; i++) {
        const double x = *coords[i];
        if (x == 0) continue;
        int e;
        (void)frexp(x, &e); /* |x| < 2^e */
        const int k = ulp_exponent(x);
        if (!any_nonzero || k < base) base = k;
        if (!any_nonzero || e > top) top = e;
        any_nonzero = 1;
    }
    if (!any_nonzero) return 0; /* all six coordinates are zero */

    /* Scaled coordinates are below 2^span, differences below 2^(span+1),
     * products below 2^(2 span + 2). One spare bit each for the sign. */
    const mp_bitcnt_t span = (mp_bitcnt_t)(top - base);
    mpz_t left, right, diff, other;
    mpz_init2(left, 2 * span + 4);
    mpz_init2(right, 2 * span + 4);
    mpz_init2(diff, span + 2);
    mpz_init2(other, span + 2);

    /* left = (bx - ax)(cy - ay) */
    set_scaled(left, b[0], base);
    set_scaled(other, a[0], base);
    mpz_sub(left, left, other);
    set_scaled(diff, c[1], base);
    set_scaled(other, a[1], base);
    mpz_sub(diff, diff, other);
    mpz_mul(left, left, diff);

    /* right = (by - ay)(cx - ax) */
    set_scaled(right, b[1], base);
    set_scaled(other, a[1], base);
    mpz_sub(right, right, other);
    set_scaled(diff, c[0], base);
    set_scaled(other, a[0], base);
    mpz_sub(diff, diff, other);
    mpz_mul(right, right, diff);

    const int sign = sign_of_int(mpz_cmp(left, right));
    mpz_clears(left, right, diff, other, (mpz_ptr)0);
    return sign;
}

/* Slow path of sq_orient2d: the filter could not decide. */
static int orient2d_slow(const double a[2], const double b[2], const double c[2])
{
    if (!all_finite(a, b, c)) {
        assert(!"sq_orient2d: non-finite coordinate (callers must validate input)");
        return 0;
    }
    /* A rounded difference is zero exactly when the exact one is, and has
     * the same sign. So if one product has a zero factor, the sign of the
     * other product decides without arithmetic. This settles coincident
     * points and projections onto a coordinate plane (flat meshes). */
    const int sbax = sign_of_double(b[0] - a[0]), scay = sign_of_double(c[1] - a[1]);
    const int sbay = sign_of_double(b[1] - a[1]), scax = sign_of_double(c[0] - a[0]);
    if (sbax == 0 || scay == 0) return -(sbay * scax);
    if (sbay == 0 || scax == 0) return sbax * scay;
    return orient2d_gmp(a, b, c);
}

int sq_orient2d(const double a[2], const double b[2], const double c[2])
{
    /* One operation per statement: see the remark on contraction above. */
    const double bax = b[0] - a[0];
    const double cay = c[1] - a[1];
    const double bay = b[1] - a[1];
    const double cax = c[0] - a[0];
    const double left = bax * cay;
    const double right = bay * cax;
    const double det = left - right;
    const double magnitude = fabs(left) + fabs(right);
    /* NaN fails both comparisons and goes to the slow path too. */
    if (magnitude >= filter_min_magnitude && magnitude <= DBL_MAX) {
        const double bound = filter_factor * magnitude;
        if (det > bound) return 1;
        if (det < -bound) return -1;
    }
    return orient2d_slow(a, b, c);
}

int sq_orient2d_exact(const double a[2], const double b[2], const double c[2])
{
    if (!all_finite(a, b, c)) {
        assert(!"sq_orient2d_exact: non-finite coordinate (callers must validate input)");
        return 0;
    }
    return orient2d_gmp(a, b, c);
}

/* The cross product (b-a) x (c-a) has as components the orientation
 * determinants of the projections onto the three coordinate planes, each
 * evaluated exactly from the original coordinates (never from rounded
 * differences). The points are collinear iff all three vanish. */
int sq_collinear3d(const double a[3], const double b[3], const double c[3])
{
    /* xy, yz and zx projections; the common non-degenerate case exits after
     * the first filtered test. */
    static const int axes[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    for (int k = 0; k < 3; k++) {
        /* A non-finite coordinate spoils only the projections that use its
         * axis, so check here rather than rely on sq_orient2d. */
        if (!isfinite(a[k]) || !isfinite(b[k]) || !isfinite(c[k])) {
            assert(!"sq_collinear3d: non-finite coordinate (callers must validate input)");
            return 1;
        }
    }
    for (int p = 0; p < 3; p++) {
        const int i = axes[p][0], j = axes[p][1];
        const double pa[2] = {a[i], a[j]};
        const double pb[2] = {b[i], b[j]};
        const double pc[2] = {c[i], c[j]};
        if (sq_orient2d(pa, pb, pc) != 0) return 0;
    }
    return 1;
}
