/* Unit tests of cone files and cone admissibility (core/sq_cones.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_cones.h"

#define PI 3.14159265358979323846

static sq_status parse(const char *text, uint32_t nv, int32_t *val, sq_cone_format *fmt,
                       sq_error *err)
{
    sq_error_clear(err);
    return sq_cones_parse(text, strlen(text), "c.txt", nv, val, fmt, err);
}

static void expect(const char *text, uint32_t nv, sq_status code, const char *sub)
{
    int32_t val[16];
    sq_cone_format fmt;
    sq_error err;
    sq_status st = parse(text, nv, val, &fmt, &err);
    if (st != code || !strstr(err.msg, sub))
        fail_msg("'%s': expected %s with '%s', got %s: %s", text, sq_status_name(code), sub,
                 sq_status_name(st), err.msg);
}

static void test_th_hat(void **state)
{
    (void)state;
    char text[512];
    snprintf(text, sizeof text, "%.17g\n%.17g\r\n%.17g\n\n%.17g\n%.17g", 2 * PI, 1.5 * PI,
             2.5 * PI + 4e-7, 11 * PI, PI);
    int32_t val[5];
    sq_cone_format fmt = 0;
    sq_error err;
    assert_int_equal(parse(text, 5, val, &fmt, &err), SQ_OK);
    assert_int_equal(fmt, SQ_CONES_TH_HAT);
    assert_int_equal(val[0], 4);
    assert_int_equal(val[1], 3);
    assert_int_equal(val[2], 5);
    assert_int_equal(val[3], 22);
    assert_int_equal(val[4], 2);
    /* 6 significant digits as some tools print */
    assert_int_equal(parse("6.28319\n4.71239\n", 2, val, &fmt, &err), SQ_ERR_CONE_VALUE);
    assert_int_equal(parse("6.2831853\n4.712389\n", 2, val, &fmt, &err), SQ_OK);
}

static void test_th_hat_errors(void **state)
{
    (void)state;
    expect("6.283185307179586\n6.283185307179586\n", 3, SQ_ERR_CONE_COUNT,
           "2 angles for a mesh with 3 vertices");
    expect("6.283185307179586\n6.3\n", 2, SQ_ERR_CONE_VALUE,
           "c.txt:2: angle 6.2999999999999998 of vertex 1 is not a multiple of pi/2");
    expect("6.283185307179586\n0\n", 2, SQ_ERR_CONE_VALUE, "not positive");
    expect("6.283185307179586\n-1.5707963267948966\n", 2, SQ_ERR_CONE_VALUE, "not positive");
    expect("6.283185307179586\nabc\n", 2, SQ_ERR_PARSE, "c.txt:2: 'abc' is not a finite number");
    expect("6.283185307179586\nnan\n", 2, SQ_ERR_PARSE, "not a finite number");
    expect("6.28 1 2\n", 1, SQ_ERR_PARSE, "c.txt:1: 3 fields");
    expect("6.283185307179586\n1 3\n", 2, SQ_ERR_PARSE, "c.txt:2: 2 field(s), but line 1 made this a Th_hat");
}

static void test_list(void **state)
{
    (void)state;
    int32_t val[10];
    sq_cone_format fmt = 0;
    sq_error err;
    assert_int_equal(parse("# cones\n0 3\n  9 5 # comment\n\n4 4\n", 10, val, &fmt, &err), SQ_OK);
    assert_int_equal(fmt, SQ_CONES_LIST);
    assert_int_equal(val[0], 3);
    assert_int_equal(val[9], 5);
    assert_int_equal(val[4], 4);
    assert_int_equal(val[1], 4);
    uint32_t hist[8];
    assert_int_equal(sq_cones_histogram(10, val, hist, 8), 2);
    assert_int_equal(hist[3], 1);
    assert_int_equal(hist[5], 1);
    assert_int_equal(hist[4], 8);
    /* empty file / comments only: a list with no cones */
    assert_int_equal(parse("# nothing\n", 10, val, &fmt, &err), SQ_OK);
    assert_int_equal(fmt, SQ_CONES_LIST);
    assert_int_equal(sq_cones_histogram(10, val, NULL, 0), 0);
    assert_int_equal(parse("", 10, val, &fmt, &err), SQ_OK);
}

static void test_list_errors(void **state)
{
    (void)state;
    expect("0 3\n10 5\n", 10, SQ_ERR_INDEX, "c.txt:2: vertex 10 is out of range");
    expect("0 3\n-1 5\n", 10, SQ_ERR_INDEX, "vertex -1 is out of range");
    expect("0 3\n2 0\n", 10, SQ_ERR_CONE_VALUE, "c.txt:2: valence 0 of vertex 2");
    expect("0 3\n0 5\n", 10, SQ_ERR_CONE_VALUE, "c.txt:2: vertex 0 is listed twice");
    expect("0 3.5\n", 10, SQ_ERR_PARSE, "c.txt:1: expected two integers");
    expect("0 3\n5\n", 10, SQ_ERR_PARSE, "c.txt:2: 1 field(s), but line 1 made this a cone list");
    int32_t val[4];
    sq_error err;
    assert_int_equal(sq_cones_parse("0 3\0 1 2", 8, "c.txt", 4, val, NULL, &err), SQ_ERR_PARSE);
    assert_non_null(strstr(err.msg, "NUL"));
}

static void test_gauss_bonnet(void **state)
{
    (void)state;
    sq_error err;
    int32_t cube[8] = {3, 3, 3, 3, 3, 3, 3, 3};
    assert_int_equal(sq_cones_check_gauss_bonnet(8, cube, 2, &err), SQ_OK);
    cube[0] = 4;
    assert_int_equal(sq_cones_check_gauss_bonnet(8, cube, 2, &err), SQ_ERR_GAUSS_BONNET);
    assert_non_null(strstr(err.msg, "is 7, but a closed surface of genus 0"));
    int32_t torus[3] = {4, 4, 4};
    assert_int_equal(sq_cones_check_gauss_bonnet(3, torus, 0, &err), SQ_OK);
    int32_t g3[4] = {12, 4, 5, 7}; /* excess 8+1+3 = 12 != 16 */
    assert_int_equal(sq_cones_check_gauss_bonnet(4, g3, -4, &err), SQ_ERR_GAUSS_BONNET);
    g3[3] = 11;
    assert_int_equal(sq_cones_check_gauss_bonnet(4, g3, -4, &err), SQ_OK);
}

static void test_realizable(void **state)
{
    (void)state;
    sq_error err;
    int32_t t35[5] = {4, 3, 4, 5, 4};
    assert_int_equal(sq_cones_check_realizable(5, t35, 1, &err), SQ_ERR_UNREALIZABLE);
    assert_non_null(strstr(err.msg, "Jucovic"));
    int32_t t3355[4] = {3, 3, 5, 5};
    assert_int_equal(sq_cones_check_realizable(4, t3355, 1, &err), SQ_OK);
    int32_t t26[2] = {2, 6};
    assert_int_equal(sq_valences_check_realizable(2, t26, 1, &err), SQ_OK);
    int32_t v1[6] = {1, 3, 3, 3, 3, 3};
    assert_int_equal(sq_cones_check_realizable(6, v1, 0, &err), SQ_ERR_UNREALIZABLE);
    assert_non_null(strstr(err.msg, "vertex 0 has a cone of valence 1"));
    assert_int_equal(sq_valences_check_realizable(6, v1, 0, &err), SQ_ERR_UNREALIZABLE);
    assert_non_null(strstr(err.msg, "valence 1"));
    int32_t gb[2] = {3, 5};
    assert_int_equal(sq_valences_check_realizable(2, gb, 2, &err), SQ_ERR_GAUSS_BONNET);
    int32_t none[1] = {4};
    assert_int_equal(sq_valences_check_realizable(0, none, 1, &err), SQ_OK);
    assert_int_equal(sq_valences_check_realizable(0, none, 0, &err), SQ_ERR_GAUSS_BONNET);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_th_hat),      cmocka_unit_test(test_th_hat_errors),
        cmocka_unit_test(test_list),        cmocka_unit_test(test_list_errors),
        cmocka_unit_test(test_gauss_bonnet), cmocka_unit_test(test_realizable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
