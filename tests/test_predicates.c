/* Tests for core/sq_predicates.c: exact orient2d and 3D collinearity.
 *
 * Every expected sign is either derived by hand in a comment or computed by
 * an independent reference written here with GMP rationals (mpq), which
 * shares no code with the library's integer-scaling evaluation. Cases are
 * near-degenerate on purpose, and several tests also count how often naive
 * double evaluation is wrong, to prove that they exercise hard inputs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>

#include <gmp.h>

#include "sq_predicates.h"

/* ---- helpers -------------------------------------------------------------- */

/* Deterministic 64-bit generator (splitmix64 recurrence); fixed seeds. */
typedef struct rng {
    uint64_t state;
} rng;

static uint64_t rng_next(rng *r)
{
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1) with 53 random bits. */
static double rng_unit(rng *r) { return (double)(rng_next(r) >> 11) * 0x1p-53; }

/* Uniform in [-1, 1). */
static double rng_signed(rng *r) { return 2.0 * rng_unit(r) - 1.0; }

/* Uniform integer in [lo, hi]. */
static int rng_int(rng *r, int lo, int hi)
{
    return lo + (int)(rng_next(r) % (uint64_t)(hi - lo + 1));
}

/* Moves x by k ulps (k may be negative). */
static double step_ulps(double x, int k)
{
    for (; k > 0; k--) x = nextafter(x, INFINITY);
    for (; k < 0; k++) x = nextafter(x, -INFINITY);
    return x;
}

/* Independent exact reference: sign of (bx-ax)(cy-ay) - (by-ay)(cx-ax) in
 * rationals. mpq_set_d is exact for finite doubles. */
static int reference_orient2d(const double a[2], const double b[2], const double c[2])
{
    mpq_t ax, ay, bx, by, cx, cy, left, right;
    mpq_inits(ax, ay, bx, by, cx, cy, left, right, (mpq_ptr)0);
    mpq_set_d(ax, a[0]);
    mpq_set_d(ay, a[1]);
    mpq_set_d(bx, b[0]);
    mpq_set_d(by, b[1]);
    mpq_set_d(cx, c[0]);
    mpq_set_d(cy, c[1]);
    mpq_sub(bx, bx, ax); /* bx - ax */
    mpq_sub(cy, cy, ay); /* cy - ay */
    mpq_sub(by, by, ay); /* by - ay */
    mpq_sub(cx, cx, ax); /* cx - ax */
    mpq_mul(left, bx, cy);
    mpq_mul(right, by, cx);
    const int s = mpq_cmp(left, right);
    mpq_clears(ax, ay, bx, by, cx, cy, left, right, (mpq_ptr)0);
    return (s > 0) - (s < 0);
}

/* Independent exact reference: 1 iff (b-a) x (c-a) == 0 in rationals. */
static int reference_collinear3d(const double a[3], const double b[3], const double c[3])
{
    mpq_t u[3], v[3], t, s;
    mpq_inits(t, s, (mpq_ptr)0);
    for (int i = 0; i < 3; i++) {
        mpq_inits(u[i], v[i], (mpq_ptr)0);
        mpq_set_d(t, a[i]);
        mpq_set_d(u[i], b[i]);
        mpq_sub(u[i], u[i], t);
        mpq_set_d(v[i], c[i]);
        mpq_sub(v[i], v[i], t);
    }
    int collinear = 1;
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        mpq_mul(t, u[j], v[k]);
        mpq_mul(s, u[k], v[j]);
        if (!mpq_equal(t, s)) collinear = 0;
    }
    for (int i = 0; i < 3; i++) mpq_clears(u[i], v[i], (mpq_ptr)0);
    mpq_clears(t, s, (mpq_ptr)0);
    return collinear;
}

/* What a naive implementation computes. The products go through volatile
 * variables so that no compiler fuses them into an FMA (which would make the
 * naive version more accurate than the one we mean to compare against). */
static double rounded_cross(double a, double b, double c, double d)
{
    volatile double left = a * b;
    volatile double right = c * d;
    return left - right;
}

static int naive_orient2d(const double a[2], const double b[2], const double c[2])
{
    const double det = rounded_cross(b[0] - a[0], c[1] - a[1], b[1] - a[1], c[0] - a[0]);
    return (det > 0) - (det < 0);
}

static int naive_collinear3d(const double a[3], const double b[3], const double c[3])
{
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return rounded_cross(u[1], v[2], u[2], v[1]) == 0 &&
           rounded_cross(u[2], v[0], u[0], v[2]) == 0 &&
           rounded_cross(u[0], v[1], u[1], v[0]) == 0;
}

/* Checks sq_orient2d, sq_orient2d_exact and the symmetries of the
 * determinant (cyclic shift keeps the sign, a swap flips it) against an
 * expected sign. */
static void check_orient(const double a[2], const double b[2], const double c[2], int expected)
{
    assert_int_equal(sq_orient2d(a, b, c), expected);
    assert_int_equal(sq_orient2d_exact(a, b, c), expected);
    assert_int_equal(sq_orient2d(b, c, a), expected);
    assert_int_equal(sq_orient2d(c, a, b), expected);
    assert_int_equal(sq_orient2d(b, a, c), -expected);
    assert_int_equal(sq_orient2d(a, c, b), -expected);
}

/* ---- orient2d: simple and hand-derived cases ---------------------------- */

static void test_orient2d_basic(void **state)
{
    (void)state;
    const double o[2] = {0, 0}, x[2] = {1, 0}, y[2] = {0, 1}, xy[2] = {2, 2}, h[2] = {1, 1};
    check_orient(o, x, y, 1);
    check_orient(o, y, x, -1);
    check_orient(o, h, xy, 0);
    check_orient(o, o, x, 0);  /* two coincident points */
    check_orient(h, h, h, 0);  /* three coincident points */
    check_orient(o, o, o, 0);  /* all zero */
    const double neg[2] = {-3, -3};
    check_orient(neg, o, h, 0);
}

/* The classic grid: p = (0.5 + i u, 0.5 + j u) with u = 2^-53 the spacing of
 * doubles in [0.5, 1), against b = (12, 12), c = (24, 24). Expanding,
 * orient(p, b, c) = 12 (py - px), so the exact sign is sign(j - i). */
static void test_orient2d_ulp_grid(void **state)
{
    (void)state;
    const double b[2] = {12, 12}, c[2] = {24, 24};
    const int size = 256;
    int naive_wrong = 0;
    double px = 0.5;
    for (int i = 0; i < size; i++, px = nextafter(px, 1.0)) {
        double py = 0.5;
        for (int j = 0; j < size; j++, py = nextafter(py, 1.0)) {
            const double p[2] = {px, py};
            const int expected = (j > i) - (j < i);
            assert_int_equal(sq_orient2d(p, b, c), expected);
            assert_int_equal(sq_orient2d(b, c, p), expected);
            assert_int_equal(sq_orient2d(c, b, p), -expected);
            naive_wrong += naive_orient2d(p, b, c) != expected;
        }
    }
    assert_int_equal(reference_orient2d((double[2]){0.5, nextafter(0.5, 1)}, b, c), 1);
    /* The grid is hard: naive evaluation gets many of these signs wrong. */
    assert_true(naive_wrong > size * size / 10);
}

/* a = (x, x) and b = (y, y) on the line y = x; then
 * orient(a, b, c) = (y - x)(cy - cx). Move c off the line by one ulp. */
static void test_orient2d_one_ulp_off_diagonal(void **state)
{
    (void)state;
    rng r = {0x5eed0001};
    int naive_wrong = 0;
    for (int n = 0; n < 20000; n++) {
        const int scale = rng_int(&r, -60, 60);
        const double x = ldexp(rng_signed(&r), scale);
        const double y = ldexp(rng_signed(&r), scale + rng_int(&r, -3, 3));
        const double z = ldexp(rng_signed(&r), scale + rng_int(&r, -3, 3));
        const int up = rng_int(&r, 0, 1);
        const double a[2] = {x, x}, b[2] = {y, y};
        const double c[2] = {z, up ? nextafter(z, INFINITY) : nextafter(z, -INFINITY)};
        const int expected = ((y > x) - (y < x)) * (up ? 1 : -1);
        check_orient(a, b, c, expected);
        const double on[2] = {z, z};
        check_orient(a, b, on, 0);
        naive_wrong += naive_orient2d(a, b, c) != expected;
    }
    assert_true(naive_wrong > 0);
}

/* ---- orient2d: the ends of the double range ----------------------------- */

static void test_orient2d_huge(void **state)
{
    (void)state;
    const double big = DBL_MAX, tiny = 0x1p-1074;
    /* Differences overflow to infinity; the line y = x through the origin. */
    const double lo[2] = {-big, -big}, hi[2] = {big, big}, o[2] = {0, 0};
    check_orient(lo, hi, o, 0);
    check_orient(lo, hi, (double[2]){0, tiny}, 1);
    check_orient(lo, hi, (double[2]){tiny, 0}, -1);
    check_orient(lo, hi, (double[2]){big, nextafter(big, 0)}, -1);
    check_orient(lo, hi, (double[2]){-big, nextafter(-big, 0)}, 1);
    /* Products overflow: points t (1, 2), 2t (1, 2), 4t (1, 2) with t = 1e300. */
    const double t = 1e300;
    const double p[2] = {t, 2 * t}, q[2] = {2 * t, 4 * t}, s[2] = {4 * t, 8 * t};
    check_orient(p, q, s, 0); /* all on y = 2x exactly */
    check_orient(p, q, (double[2]){s[0], nextafter(s[1], INFINITY)}, 1);
    check_orient(p, q, (double[2]){s[0], nextafter(s[1], 0)}, -1);
    check_orient((double[2]){-t, -2 * t}, q, s, 0);
    /* Naive evaluation overflows to inf - inf = NaN here. */
    assert_int_equal(naive_orient2d(p, q, (double[2]){s[0], nextafter(s[1], INFINITY)}), 0);
    assert_int_equal(reference_orient2d(p, q, (double[2]){s[0], nextafter(s[1], INFINITY)}), 1);
}

static void test_orient2d_tiny(void **state)
{
    (void)state;
    /* Products of 1e-300 underflow to zero: naive says collinear. */
    const double t = 1e-300;
    const double o[2] = {0, 0}, b[2] = {t, 2 * t}, c[2] = {2 * t, 4 * t};
    check_orient(o, b, c, 0);
    const double up[2] = {2 * t, nextafter(4 * t, 1)};
    check_orient(o, b, up, 1);
    check_orient(o, b, (double[2]){2 * t, nextafter(4 * t, 0)}, -1);
    assert_int_equal(naive_orient2d(o, b, up), 0);
    /* Subnormals: the smallest steps there are. */
    const double d = 0x1p-1074;
    check_orient(o, (double[2]){d, d}, (double[2]){2 * d, 2 * d}, 0);
    check_orient(o, (double[2]){d, d}, (double[2]){2 * d, 3 * d}, 1);
    check_orient((double[2]){d, 0}, (double[2]){0, d}, (double[2]){-d, 2 * d}, 0);
    check_orient((double[2]){d, 0}, (double[2]){0, d}, (double[2]){-d, 3 * d}, -1);
    /* Mixed magnitudes: a tiny point against a huge segment. The line
     * through (-1e300, -1e300) and (1e300, 1e300) is y = x. */
    const double big = 1e300;
    check_orient((double[2]){-big, -big}, (double[2]){big, big}, (double[2]){d, 0}, -1);
    check_orient((double[2]){-big, -big}, (double[2]){big, big}, (double[2]){d, d}, 0);
    /* Near the filter's threshold: coordinates about 2^-480 and 2^-481. */
    const double e = 0x1.8p-480;
    check_orient(o, (double[2]){e, e}, (double[2]){2 * e, nextafter(2 * e, 1)}, 1);
    check_orient(o, (double[2]){e, e}, (double[2]){2 * e, 2 * e}, 0);
}

/* ---- orient2d: exactly collinear points far from the origin ------------- */

/* Dyadic number with `bits` random significant bits and its top bit at 2^top. */
static double random_dyadic(rng *r, int bits, int top)
{
    const uint64_t m = (rng_next(r) >> (64 - bits)) | (1ull << (bits - 1));
    const double x = ldexp((double)m, top - bits + 1);
    return rng_int(r, 0, 1) ? x : -x;
}

static void test_orient2d_collinear_far(void **state)
{
    (void)state;
    rng r = {0x5eed0002};
    /* Points O + k d on a fixed-point grid far from the origin: all
     * coordinates exact, the line does not pass through the origin. */
    for (int n = 0; n < 20000; n++) {
        const double ox = ldexp((double)rng_int(&r, 1, 1 << 20), 24);
        const double oy = -ldexp((double)rng_int(&r, 1, 1 << 20), 25);
        const double dx = ldexp((double)rng_int(&r, -1000, 1000), -7);
        const double dy = ldexp((double)rng_int(&r, -1000, 1000), -7);
        const int k[3] = {rng_int(&r, -(1 << 20), 1 << 20), rng_int(&r, -(1 << 20), 1 << 20),
                          rng_int(&r, -(1 << 20), 1 << 20)};
        double p[3][2];
        for (int i = 0; i < 3; i++) {
            p[i][0] = ox + k[i] * dx;
            p[i][1] = oy + k[i] * dy;
            /* the construction is exact */
            assert_true(p[i][0] - ox == k[i] * dx && p[i][1] - oy == k[i] * dy);
        }
        check_orient(p[0], p[1], p[2], 0);
        /* One ulp off the line: the reference decides. */
        const double q[2] = {p[2][0], nextafter(p[2][1], INFINITY)};
        check_orient(p[0], p[1], q, reference_orient2d(p[0], p[1], q));
    }
    /* Lines through the origin with direction (dx, dy) small odd integers and
     * parameters of wildly different magnitudes: coordinates exact, but the
     * differences round. Naive evaluation then often misses zero. */
    int naive_wrong = 0;
    for (int n = 0; n < 20000; n++) {
        const double dx = 2 * rng_int(&r, -20, 20) + 1, dy = 2 * rng_int(&r, -20, 20) + 1;
        double p[3][2];
        for (int i = 0; i < 3; i++) {
            const double s = random_dyadic(&r, 45, rng_int(&r, -40, 60));
            p[i][0] = s * dx;
            p[i][1] = s * dy;
        }
        assert_int_equal(reference_orient2d(p[0], p[1], p[2]), 0);
        check_orient(p[0], p[1], p[2], 0);
        naive_wrong += naive_orient2d(p[0], p[1], p[2]) != 0;
    }
    assert_true(naive_wrong > 1000);
}

/* ---- orient2d: randomized comparison with the rational reference -------- */

/* Near-degenerate triple at a random scale; kinds:
 * 0: c near segment ab, then moved a few ulps;
 * 1: like 0 with a, b at different scales;
 * 2: like 0 translated far away (translation rounds, so c leaves the line);
 * 3: exactly collinear through the origin (exact multiples);
 * 4: anywhere in the double range, including overflowing differences;
 * 5: coordinates near 2^-530, whose products underflow into subnormals. */
static int random_near_degenerate(rng *r, double a[2], double b[2], double c[2])
{
    const int kind = rng_int(r, 0, 5);
    const int scale = kind == 4   ? rng_int(r, -1070, 1020)
                      : kind == 5 ? rng_int(r, -560, -480)
                                  : rng_int(r, -200, 200);
    const int scale_b = kind == 1 ? scale + rng_int(r, -40, 40) : scale;
    for (int i = 0; i < 2; i++) {
        a[i] = ldexp(rng_signed(r), scale);
        b[i] = ldexp(rng_signed(r), scale_b);
    }
    if (kind == 3) {
        const double s = random_dyadic(r, 40, rng_int(r, -30, 30));
        const double t = random_dyadic(r, 40, rng_int(r, -30, 30));
        const double w = random_dyadic(r, 40, rng_int(r, -30, 30));
        const double dx = 2 * rng_int(r, -8, 8) + 1, dy = 2 * rng_int(r, -8, 8) + 1;
        const double unit = ldexp(1.0, scale);
        a[0] = s * dx * unit;
        a[1] = s * dy * unit;
        b[0] = t * dx * unit;
        b[1] = t * dy * unit;
        c[0] = w * dx * unit;
        c[1] = w * dy * unit;
        return kind;
    }
    const double t = rng_signed(r) * 2;
    for (int i = 0; i < 2; i++) {
        c[i] = a[i] * (1 - t) + b[i] * t;
        c[i] = step_ulps(c[i], rng_int(r, -2, 2));
    }
    if (kind == 2) {
        const double shift[2] = {ldexp(rng_signed(r), scale + 20), ldexp(rng_signed(r), scale + 20)};
        for (int i = 0; i < 2; i++) {
            a[i] += shift[i];
            b[i] += shift[i];
            c[i] += shift[i];
        }
    }
    return kind;
}

static void test_orient2d_random_vs_reference(void **state)
{
    (void)state;
    rng r = {0x5eed0003};
    const int cases = 120000;
    int by_sign[3] = {0, 0, 0}, naive_wrong = 0, done = 0;
    while (done < cases) {
        double a[2], b[2], c[2];
        random_near_degenerate(&r, a, b, c);
        if (!(isfinite(a[0]) && isfinite(a[1]) && isfinite(b[0]) && isfinite(b[1]) &&
              isfinite(c[0]) && isfinite(c[1])))
            continue;
        const int expected = reference_orient2d(a, b, c);
        assert_int_equal(sq_orient2d(a, b, c), expected);
        assert_int_equal(sq_orient2d_exact(a, b, c), expected);
        assert_int_equal(sq_orient2d(c, b, a), -expected);
        by_sign[expected + 1]++;
        naive_wrong += naive_orient2d(a, b, c) != expected;
        done++;
    }
    /* The sample is genuinely near-degenerate and covers all three answers. */
    assert_true(by_sign[0] > cases / 20 && by_sign[1] > cases / 20 && by_sign[2] > cases / 20);
    assert_true(naive_wrong > cases / 50);
}

/* ---- collinear3d ---------------------------------------------------------- */

static void test_collinear3d_exact_with_rounding_differences(void **state)
{
    (void)state;
    rng r = {0x5eed0004};
    int naive_wrong = 0;
    for (int n = 0; n < 20000; n++) {
        /* s (dx, dy, dz), small odd integer direction, 45-bit parameters
         * over a wide range of magnitudes: exact points, rounded differences. */
        const double d[3] = {2 * rng_int(&r, -20, 20) + 1, 2 * rng_int(&r, -20, 20) + 1,
                             2 * rng_int(&r, -20, 20) + 1};
        double p[3][3];
        for (int i = 0; i < 3; i++) {
            const double s = random_dyadic(&r, 45, rng_int(&r, -50, 50));
            for (int k = 0; k < 3; k++) p[i][k] = s * d[k];
        }
        assert_int_equal(reference_collinear3d(p[0], p[1], p[2]), 1);
        assert_int_equal(sq_collinear3d(p[0], p[1], p[2]), 1);
        assert_int_equal(sq_collinear3d(p[2], p[0], p[1]), 1);
        naive_wrong += !naive_collinear3d(p[0], p[1], p[2]);
    }
    assert_true(naive_wrong > 1000);

    /* Far from the origin, on a fixed-point grid: O + k d. */
    for (int n = 0; n < 5000; n++) {
        double o[3], d[3], p[3][3];
        for (int k = 0; k < 3; k++) {
            o[k] = ldexp((double)rng_int(&r, -(1 << 20), 1 << 20), 26);
            d[k] = ldexp((double)rng_int(&r, -1000, 1000), -6);
        }
        for (int i = 0; i < 3; i++) {
            const int t = rng_int(&r, -(1 << 20), 1 << 20);
            for (int k = 0; k < 3; k++) {
                p[i][k] = o[k] + t * d[k];
                assert_true(p[i][k] - o[k] == t * d[k]); /* exact construction */
            }
        }
        assert_int_equal(sq_collinear3d(p[0], p[1], p[2]), 1);
        /* One ulp off in one coordinate: collinear only if the reference
         * says so (e.g. when d = 0). */
        p[2][n % 3] = nextafter(p[2][n % 3], INFINITY);
        assert_int_equal(sq_collinear3d(p[0], p[1], p[2]),
                         reference_collinear3d(p[0], p[1], p[2]));
    }
    /* Coincident points are collinear. */
    const double a[3] = {1e10, -3, 0.25}, b[3] = {1e-10, 7, 1};
    assert_int_equal(sq_collinear3d(a, a, b), 1);
    assert_int_equal(sq_collinear3d(a, b, a), 1);
    assert_int_equal(sq_collinear3d(b, b, b), 1);
}

/* Thin faces, area about 1e-16 of the bounding box: not collinear. */
static void test_collinear3d_thin_faces(void **state)
{
    (void)state;
    const double a[3] = {0, 0, 0}, b[3] = {1, 1, 1};
    const double c[3] = {0.5, 0.5, nextafter(0.5, 1)};
    assert_int_equal(sq_collinear3d(a, b, c), 0);
    assert_int_equal(sq_collinear3d(a, b, (double[3]){0.5, 0.5, 0.5}), 1);
    /* Collinear in the xy and zx projections? no: only xy is degenerate. */
    assert_int_equal(sq_collinear3d(a, (double[3]){1, 1, 0}, (double[3]){2, 2, 0x1p-1074}), 0);
    assert_int_equal(sq_collinear3d(a, (double[3]){1, 1, 0}, (double[3]){2, 2, 0}), 1);

    rng r = {0x5eed0005};
    int not_collinear = 0;
    for (int n = 0; n < 20000; n++) {
        /* Unit box, optionally translated (translation rounds). */
        const double shift = (n % 2) ? ldexp(1.0, rng_int(&r, 1, 30)) : 0;
        double p[3], q[3], m[3];
        for (int k = 0; k < 3; k++) {
            p[k] = rng_unit(&r) + shift;
            q[k] = rng_unit(&r) + shift;
            m[k] = 0.5 * p[k] + 0.5 * q[k];
        }
        m[n % 3] = step_ulps(m[n % 3], (n / 3) % 2 ? 1 : -1);
        const int expected = reference_collinear3d(p, q, m);
        assert_int_equal(sq_collinear3d(p, q, m), expected);
        assert_int_equal(sq_collinear3d(m, q, p), expected);
        not_collinear += !expected;
    }
    assert_true(not_collinear > 19000);
}

/* Non-finite input is documented as a caller bug: asserts in debug builds,
 * "degenerate" in release builds. Only the release behaviour is testable. */
static void test_non_finite_release(void **state)
{
    (void)state;
#ifdef NDEBUG
    const double o[2] = {0, 0}, x[2] = {1, 0}, nan2[2] = {NAN, 0}, inf2[2] = {0, INFINITY};
    assert_int_equal(sq_orient2d(o, x, nan2), 0);
    assert_int_equal(sq_orient2d(inf2, o, x), 0);
    assert_int_equal(sq_orient2d_exact(o, inf2, x), 0);
    const double p[3] = {0, 0, 0}, q[3] = {1, 2, 3}, bad[3] = {0, NAN, 1};
    assert_int_equal(sq_collinear3d(p, q, bad), 1);
#else
    skip();
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_orient2d_basic),
        cmocka_unit_test(test_orient2d_ulp_grid),
        cmocka_unit_test(test_orient2d_one_ulp_off_diagonal),
        cmocka_unit_test(test_orient2d_huge),
        cmocka_unit_test(test_orient2d_tiny),
        cmocka_unit_test(test_orient2d_collinear_far),
        cmocka_unit_test(test_orient2d_random_vs_reference),
        cmocka_unit_test(test_collinear3d_exact_with_rounding_differences),
        cmocka_unit_test(test_collinear3d_thin_faces),
        cmocka_unit_test(test_non_finite_release),
    };
    return cmocka_run_group_tests_name("predicates", tests, NULL, NULL);
}
