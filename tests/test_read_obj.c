/* OBJ reader: every accepted syntax, every error with its status and
 * message (including the line), provenance, and every OBJ mesh of
 * ../shared/data against MANIFEST.tsv. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "io_test_util.h"
#include "sq_text.h"

static const char *tetra =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "v 0 0 1\n"
    "f 1 3 2\n"
    "f 1 2 4\n"
    "f 2 3 4\n"
    "f 3 1 4\n";

static void test_basic(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj, tetra, &s);
    io_check_soup(&s);
    assert_int_equal(s.nv, 4);
    assert_int_equal(s.nf, 4);
    assert_true(s.pos[3] == 1.0 && s.pos[4] == 0.0 && s.pos[11] == 1.0);
    const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    assert_memory_equal(s.face_idx, idx, sizeof idx);
    const uint32_t off[] = {0, 3, 6, 9, 12};
    assert_memory_equal(s.face_off, off, sizeof off);
    for (uint32_t v = 0; v < 4; v++) assert_int_equal(s.vert_line[v], v + 1);
    for (uint32_t f = 0; f < 4; f++) assert_int_equal(s.face_line[f], f + 5);
    assert_null(s.face_uv);
    assert_int_equal(s.nuv, 0);
    assert_string_equal(s.path, "mem");
    assert_int_equal(s.line_kind, 0);
    char where[64];
    assert_string_equal(sq_soup_where_face(&s, 2, where, sizeof where), "mem:7");
    sq_soup_free(&s);
}

static void test_numbers(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj,
                "v -1.5e-3 +2 .25\n"
                "v 0x1p-2 1E2 -0\n"
                "v 0.30007200000000002 -5.5732229999999996 1e-310\n"
                "f 1 2 3\n",
                &s);
    assert_true(s.pos[0] == -1.5e-3 && s.pos[1] == 2.0 && s.pos[2] == 0.25);
    assert_true(s.pos[3] == 0.25 && s.pos[4] == 100.0 && s.pos[5] == 0.0 && signbit(s.pos[5]));
    assert_true(s.pos[6] == 0.30007200000000002 && s.pos[7] == -5.5732229999999996);
    assert_true(s.pos[8] == 1e-310);
    sq_soup_free(&s);

    /* nan and inf parse (the mesh builder rejects them with the line) */
    io_parse_ok(sq_parse_obj, "v nan 0 0\nv 1 inf 0\nv 0 1 -1e999\nf 1 2 3\n", &s);
    assert_true(isnan(s.pos[0]) && isinf(s.pos[4]) && isinf(s.pos[8]) && s.pos[8] < 0);
    sq_soup_free(&s);
}

/* Corner forms a, a/b, a/b/c, a//c; vt with 1..3 values; vn. */
static void test_corner_forms(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj,
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                "vt 0.5 0.25\nvt 0.125\nvt 1 2 3\n"
                "vn 0 0 1\nvn 1 0 0\n"
                "f 1/1 2/2 3/3\n"      /* line 10 */
                "f 1/1/1 2/2/2 4/3/1\n"
                "f 2//1 3//2 4//2\n"
                "f 3/2 1 4//1\n",      /* mixed: uv only at corner 1 */
                &s);
    io_check_soup(&s);
    assert_int_equal(s.nuv, 3);
    assert_true(s.uv[0] == 0.5 && s.uv[1] == 0.25);
    assert_true(s.uv[2] == 0.125 && s.uv[3] == 0.0); /* v defaults to 0 */
    assert_true(s.uv[4] == 1.0 && s.uv[5] == 2.0);   /* w is not stored */
    assert_non_null(s.face_uv);
    const uint32_t idx[] = {0, 1, 2, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    const uint32_t uv[] = {0, 1, 2, 0, 1, 2, SQ_NONE, SQ_NONE, SQ_NONE, 1, SQ_NONE, SQ_NONE};
    assert_memory_equal(s.face_idx, idx, sizeof idx);
    assert_memory_equal(s.face_uv, uv, sizeof uv);
    assert_int_equal(s.face_line[0], 10);
    assert_int_equal(s.face_line[3], 13);
    sq_soup_free(&s);

    /* vt lines but no face uses them: face_uv stays NULL, uv is kept */
    io_parse_ok(sq_parse_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 1 1\nf 1//1 2 3\nvn 0 0 1\n", &s);
    assert_null(s.face_uv);
    assert_int_equal(s.nuv, 1);
    sq_soup_free(&s);
}

static void test_relative_and_forward(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj,
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                "f -3/-3 -2/-2 -1/-1\n"
                "v 0 0 1\n"
                "f -4 -3 -1\n"
                "f 1 2 5\n" /* forward reference: vertex 5 defined below */
                "v 2 2 2\n",
                &s);
    io_check_soup(&s);
    const uint32_t idx[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
    assert_memory_equal(s.face_idx, idx, sizeof idx);
    assert_int_equal(s.face_uv[0], 0);
    assert_int_equal(s.face_uv[2], 2);
    assert_int_equal(s.face_uv[3], SQ_NONE);
    assert_int_equal(s.vert_line[4], 11);
    sq_soup_free(&s);
}

/* Comments, blanks, ignored statements, CRLF, tabs, BOM, no final newline. */
static void test_ignored_and_layout(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj,
                "\xEF\xBB\xBF# comment line\r\n"
                "mtllib a.mtl\r\n"
                "o Object name with spaces\r\n"
                "\r\n"
                "   \t\r\n"
                "g grp\r\n"
                "v 0 0 0 # trailing comment\r\n"
                "\tv\t1  0\t0 \r\n"
                "v 0 1 0\r\n"
                "s off\r\n"
                "usemtl mat#1\r\n"
                "#v 9 9 9\r\n"
                "f 1 2 3",
                &s);
    io_check_soup(&s);
    assert_int_equal(s.nv, 3);
    assert_int_equal(s.nf, 1);
    assert_true(s.pos[3] == 1.0);
    assert_int_equal(s.vert_line[0], 7);
    assert_int_equal(s.vert_line[1], 8);
    assert_int_equal(s.face_line[0], 13);
    sq_soup_free(&s);

    /* CR-LF and LF give the same soup */
    sq_soup a, b;
    io_parse_ok(sq_parse_obj, "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", &a);
    io_parse_ok(sq_parse_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &b);
    assert_memory_equal(a.pos, b.pos, 9 * sizeof(double));
    assert_memory_equal(a.face_idx, b.face_idx, 3 * sizeof(uint32_t));
    sq_soup_free(&a);
    sq_soup_free(&b);
}

/* Optional 4th value w (must be 1) and trailing colour (ignored). */
static void test_vertex_variants(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    io_parse_ok(sq_parse_obj, "v 1 2 3 1.0\nv 4 5 6 0.5 0.5 0.5\nv 7 8 9\nf 1 2 3\n", &s);
    const double want[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    assert_memory_equal(s.pos, want, sizeof want);
    sq_soup_free(&s);

    expect_error(io_parse(sq_parse_obj, "v 0 0 0\nv 1 2 3 0.5\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: vertex has homogeneous weight w = 0.5");
    expect_error(io_parse(sq_parse_obj, "v 1 2\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: vertex has 2 values");
    expect_error(io_parse(sq_parse_obj, "v 1 2 3 4 5\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: vertex has 5 values");
    expect_error(io_parse(sq_parse_obj, "v 1 2 3 4 5 6 7 8\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: vertex has more than 7 values");
    expect_error(io_parse(sq_parse_obj, "\nv\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: vertex has 0 values");
    expect_error(io_parse(sq_parse_obj, "vt\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: texture coordinate has 0 values");
    expect_error(io_parse(sq_parse_obj, "vt 1 2 3 4\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: texture coordinate has more than 3 values");
    expect_error(io_parse(sq_parse_obj, "vn 1 2\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: normal has 2 values");
    /* on failure the soup is zeroed */
    assert_null(s.pos);
    assert_int_equal(s.nv, 0);
}

static void test_polygons_kept(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_obj,
                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                "f 1 2 3 4\nf 2 5 3 4 1\nf 1 2 3\n",
                &s);
    const uint32_t off[] = {0, 4, 9, 12};
    assert_memory_equal(s.face_off, off, sizeof off);
    sq_soup_free(&s);
}

static void test_bad_numbers(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\nv 1 2 x\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: bad number 'x' (value 3 of the vertex)");
    expect_error(io_parse(sq_parse_obj, "v 1 2 3abc\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: bad number '3abc'");
    expect_error(io_parse(sq_parse_obj, "v 1 2.0.0 3\n", &s, &e), &e, SQ_ERR_PARSE,
                 "bad number '2.0.0'");
    expect_error(io_parse(sq_parse_obj, "v 1,5 2 3\n", &s, &e), &e, SQ_ERR_PARSE,
                 "bad number '1,5'");
    expect_error(io_parse(sq_parse_obj, "v 1 2 3\nvt 0.5 y\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: bad number 'y' (value 2 of the texture coordinate)");
    expect_error(io_parse(sq_parse_obj, "vn 0 0 -\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: bad number '-'");
    /* longer than any sensible number: rejected, and quoted with an ellipsis */
    char buf[400] = "v 1 2 ";
    memset(buf + 6, '1', 300);
    buf[306] = '\0';
    expect_error(io_parse(sq_parse_obj, buf, &s, &e), &e, SQ_ERR_PARSE, "mem:1: bad number '111");
    assert_non_null(strstr(e.msg, "...'"));
}

static void test_face_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    const char *v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    char buf[512];
#define WITH(face) (snprintf(buf, sizeof buf, "%s%s", v3, face), buf)
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:4: face has 2 corners; a face needs at least 3");
    expect_error(io_parse(sq_parse_obj, WITH("f\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:4: face has 0 corners");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 0\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "mem:4: vertex index 0 in face corner 3 (OBJ indices start at 1)");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 3\nf 1 2 9\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "mem:5: face corner 3 refers to vertex 9, but the file has only 3 vertices");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 -2 -4\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "mem:4: relative vertex index -4 in face corner 3 reaches before the first "
                 "vertex (3 defined before this line)");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 99999999999999999999999\n"), &s, &e), &e,
                 SQ_ERR_INDEX, "mem:4: vertex index 99999999999999999999999 in face corner 3");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 -99999999999999999999999\n"), &s, &e), &e,
                 SQ_ERR_INDEX, "relative vertex index -99999999999999999999999");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 4294967296\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "vertex index 4294967296 in face corner 3 is out of range");
    expect_error(io_parse(sq_parse_obj, WITH("vt 0 0\nf 1/1 2/2 3/2\n"), &s, &e), &e,
                 SQ_ERR_INDEX,
                 "mem:5: face corner 2 refers to texture coordinate 2, but the file has only 1");
    expect_error(io_parse(sq_parse_obj, WITH("vt 0 0\nf 1/1 2/-2 3/1\n"), &s, &e), &e,
                 SQ_ERR_INDEX, "relative texture coordinate index -2 in face corner 2");
    expect_error(io_parse(sq_parse_obj, WITH("vn 0 0 1\nf 1//1 2//1 3//2\n"), &s, &e), &e,
                 SQ_ERR_INDEX, "mem:5: a face corner refers to normal 2, but the file has only 1");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 3/0\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "texture coordinate index 0 in face corner 3");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 a\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:4: bad vertex index 'a' in face corner 3");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2 3.0\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "bad vertex index '3.0'");
    expect_error(io_parse(sq_parse_obj, WITH("f 1 2/x 3\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "bad texture coordinate index 'x' in face corner 2");
    static const char *const bad_corners[] = {"1/", "1//", "/1", "1/1/", "1/1/1/1", "//1", "/"};
    for (size_t k = 0; k < sizeof bad_corners / sizeof bad_corners[0]; k++) {
        char face[64], sub[80];
        snprintf(face, sizeof face, "f 1 2 %s\n", bad_corners[k]);
        snprintf(sub, sizeof sub, "mem:4: bad face corner '%s' (corner 3)", bad_corners[k]);
        expect_error(io_parse(sq_parse_obj, WITH(face), &s, &e), &e, SQ_ERR_PARSE, sub);
    }
#undef WITH
}

static void test_unsupported_statements(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\nv 1 0 0\nl 1 2\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:3: 'l' (line element) is not supported");
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\np 1\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: 'p' (point element) is not supported");
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\nvp 0.5\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: unknown or unsupported OBJ statement 'vp'");
    expect_error(io_parse(sq_parse_obj, "V 0 0 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: unknown or unsupported OBJ statement 'V'");
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\ncurv 0 1 1 2\n", &s, &e), &e, SQ_ERR_PARSE,
                 "statement 'curv'");
    /* a binary file: named as such, bytes quoted safely */
    const char bin[] = "v 0 0 0\n\x01\x02\x7f\xff\x00zz\n";
    expect_error(sq_parse_obj(bin, sizeof bin - 1, "b.obj", &s, &e), &e, SQ_ERR_PARSE,
                 "b.obj:2: line holds binary data");
    const char hi[] = "\xc3\xa9t\xc3\xa9 1 2\n";
    expect_error(sq_parse_obj(hi, sizeof hi - 1, "u.obj", &s, &e), &e, SQ_ERR_PARSE,
                 "statement '\\xc3\\xa9t\\xc3\\xa9'");
}

static void test_empty(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    expect_error(sq_parse_obj("", 0, "e.obj", &s, &e), &e, SQ_ERR_EMPTY,
                 "e.obj: no vertices and no faces");
    expect_error(sq_parse_obj(NULL, 0, "e.obj", &s, &e), &e, SQ_ERR_EMPTY, "e.obj: no vertices");
    expect_error(io_parse(sq_parse_obj, "# only a comment\n\n", &s, &e), &e, SQ_ERR_EMPTY,
                 "mem: no vertices and no faces");
    expect_error(io_parse(sq_parse_obj, "v 0 0 0\nv 1 1 1\n", &s, &e), &e, SQ_ERR_EMPTY,
                 "mem: no faces ('f' lines); 2 vertices");
    expect_error(io_parse(sq_parse_obj, "f 1 2 3\n", &s, &e), &e, SQ_ERR_INDEX,
                 "mem:1: face corner 1 refers to vertex 1, but the file has only 0 vertices");
    expect_error(sq_parse_obj("x", 1, "n", NULL, &e), &e, SQ_ERR_ARGUMENT, "NULL");
}

/* The buffer need not be NUL-terminated: a parse of a prefix sees only it. */
static void test_no_nul_terminator(void **state)
{
    (void)state;
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 5 5 5";
    sq_soup s;
    sq_error e;
    /* cut inside the last number: "v 5 5 5" -> "v 5 5" */
    assert_int_equal(sq_parse_obj(text, strlen(text) - 2, "m", &s, &e), SQ_ERR_PARSE);
    assert_non_null(strstr(e.msg, "m:5: vertex has 2 values"));
    /* cut after "f 1 2 3": valid */
    assert_int_equal(sq_parse_obj(text, 32, "m", &s, &e), SQ_OK);
    assert_int_equal(s.nv, 3);
    sq_soup_free(&s);
    /* a number touching the end of the buffer */
    char exact[] = {'v', ' ', '1', ' ', '2', ' ', '3'};
    assert_int_equal(sq_parse_obj(exact, sizeof exact, "m", &s, &e), SQ_ERR_EMPTY);
}

static void test_null_name(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    assert_int_equal(sq_parse_obj(tetra, strlen(tetra), NULL, &s, &e), SQ_OK);
    assert_null(s.path);
    char where[32];
    assert_string_equal(sq_soup_where_vertex(&s, 0, where, sizeof where), "");
    sq_soup_free(&s);
    assert_int_equal(sq_parse_obj("f 1 2 3\n", 8, NULL, &s, &e), SQ_ERR_INDEX);
    assert_non_null(strstr(e.msg, "(buffer):1:"));
}

/* The fast decimal path gives exactly strtod's bits, and accepts exactly
 * the tokens strtod reads completely. */
static void test_number_fast_path(void **state)
{
    (void)state;
    static const char *const fixed[] = {
        "0", "-0", "+0", "0.", ".0", "1.", ".5", "-.5e-3", "9007199254740992",
        "9007199254740993", "-9007199254740993", "9007199254740992e22", "1e22", "1e23",
        "1e-22", "1e-23", "123456789012345678e-22", "0.30007200000000002", "4.9e-324",
        "1.7976931348623157e308", "1e309", "0.000000000000000000000000000001", "1e", "1e+",
        "e5", ".", "+", "-", "1.2.3", "1e5.0", "00001.5000", "0x10", "nan", "-inf", "1e0001",
        "1e99999", "12345678901234567890", "1234567890123456789", "0.1234567890123456789"};
    unsigned seed = 12345;
    for (int k = 0; k < 400000; k++) {
        char buf[96];
        if (k < (int)(sizeof fixed / sizeof fixed[0])) {
            snprintf(buf, sizeof buf, "%s", fixed[k]);
        } else {
            /* random decimal: sign, 0-20 integer digits, optional fraction
             * of 0-20 digits, optional exponent of 1-4 digits */
            size_t n = 0;
#define RND() (seed = seed * 1103515245u + 12345u, (seed >> 16) & 0x7fff)
            if (RND() % 3 == 0) buf[n++] = RND() % 2 ? '-' : '+';
            int id = (int)(RND() % 21), fd = (int)(RND() % 21);
            for (int i = 0; i < id; i++) buf[n++] = (char)('0' + (RND() % 4 ? RND() % 10 : 0));
            if (RND() % 4) {
                buf[n++] = '.';
                for (int i = 0; i < fd; i++) buf[n++] = (char)('0' + RND() % 10);
            }
            if (RND() % 3 == 0) {
                buf[n++] = RND() % 2 ? 'e' : 'E';
                if (RND() % 2) buf[n++] = RND() % 2 ? '-' : '+';
                int ed = 1 + (int)(RND() % 3);
                for (int i = 0; i < ed; i++) buf[n++] = (char)('0' + RND() % 10);
            }
#undef RND
            buf[n] = '\0';
        }
        sq_span tok = {buf, buf + strlen(buf)};
        double got = 0, want;
        int ok = sq_span_to_double(tok, &got) == 0;
        char *end;
        want = strtod(buf, &end);
        int want_ok = buf[0] != '\0' && *end == '\0';
        if (ok != want_ok) fail_msg("'%s': accepted %d, strtod %d", buf, ok, want_ok);
        if (ok && memcmp(&got, &want, sizeof got) != 0 && !(isnan(got) && isnan(want)))
            fail_msg("'%s': %.17g, strtod %.17g", buf, got, want);
    }
}

static void test_shared_obj_files(void **state)
{
    (void)state;
    int n = io_read_manifest_meshes(".obj");
    assert_true(n >= 25); /* MANIFEST lists 31 OBJ files today */
}

/* The mpz files carry a seamless UV: every corner has one. */
static void test_shared_obj_uv(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    if (sq_read_mesh(IO_DATA "mpz/knot1.obj", &s, &e)) fail_msg("%s", e.msg);
    assert_int_equal(s.nuv, 312);
    assert_non_null(s.face_uv);
    for (uint32_t c = 0; c < s.face_off[s.nf]; c++) assert_true(s.face_uv[c] < s.nuv);
    /* first face line of the file is "f 8/8 1/1 7/7" */
    assert_int_equal(s.face_idx[0], 7);
    assert_int_equal(s.face_uv[1], 0);
    assert_int_equal(s.face_line[0], s.nv + s.nuv + 2); /* a blank line between */
    sq_soup_free(&s);

    /* bob has v/vt/vn corners, o, mtllib, usemtl and a comment */
    if (sq_read_mesh(IO_DATA "nvdiffrec/bob_tri.obj", &s, &e)) fail_msg("%s", e.msg);
    assert_non_null(s.face_uv);
    assert_int_equal(s.face_idx[0], 1340);
    assert_int_equal(s.face_uv[0], 0);
    sq_soup_free(&s);
}

static void test_read_mesh_dispatch(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    assert_int_equal(sq_format_from_path("a/b.OBJ"), SQ_FORMAT_OBJ);
    assert_int_equal(sq_format_from_path("x.Off"), SQ_FORMAT_OFF);
    assert_int_equal(sq_format_from_path("dir.ply/x.ply"), SQ_FORMAT_PLY);
    assert_int_equal(sq_format_from_path("dir.obj/x"), SQ_FORMAT_UNKNOWN);
    assert_int_equal(sq_format_from_path(".obj"), SQ_FORMAT_UNKNOWN);
    assert_int_equal(sq_format_from_path("x.objx"), SQ_FORMAT_UNKNOWN);
    assert_int_equal(sq_format_from_path(NULL), SQ_FORMAT_UNKNOWN);
    expect_error(sq_read_mesh("mesh.stl", &s, &e), &e, SQ_ERR_FORMAT,
                 "mesh.stl: unknown mesh file extension '.stl' (supported: .obj, .off, .ply)");
    expect_error(sq_read_mesh("dir.obj/mesh", &s, &e), &e, SQ_ERR_FORMAT,
                 "dir.obj/mesh: no file extension");
    expect_error(sq_read_mesh("/nonexistent/dir/m.obj", &s, &e), &e, SQ_ERR_IO,
                 "/nonexistent/dir/m.obj: cannot open: No such file or directory");

    char dir[256], path[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/d.obj", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    expect_error(sq_read_mesh(path, &s, &e), &e, SQ_ERR_IO, "d.obj: cannot read: Is a directory");
    snprintf(path, sizeof path, "%s/bad.obj", dir);
    io_write_file(path, "v 0 0 0\nv 1 0 0\nf 1 2\n", 22);
    /* parse errors from a file start with its path */
    char sub[600];
    snprintf(sub, sizeof sub, "%s:3: face has 2 corners", path);
    expect_error(sq_read_mesh(path, &s, &e), &e, SQ_ERR_PARSE, sub);
    io_rmdir(dir);
}

static void test_read_file(void **state)
{
    (void)state;
    char *data;
    size_t size;
    sq_error e;
    assert_int_equal(sq_read_file(IO_DATA "mpz/knot1.obj", &data, &size, &e), SQ_OK);
    assert_int_equal(size, 37961); /* MANIFEST: the file as fetched */
    assert_int_equal(data[size], '\0');
    assert_int_equal(strncmp(data, "v 0.44243900000000003", 21), 0);
    free(data);
    /* a device that is not a regular file: read to its end */
    assert_int_equal(sq_read_file("/dev/null", &data, &size, &e), SQ_OK);
    assert_int_equal(size, 0);
    assert_int_equal(data[0], '\0');
    free(data);
    expect_error(sq_read_file("/no/such/file", &data, &size, &e), &e, SQ_ERR_IO,
                 "/no/such/file: cannot open: No such file or directory");
    assert_null(data);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_basic),
        cmocka_unit_test(test_numbers),
        cmocka_unit_test(test_corner_forms),
        cmocka_unit_test(test_relative_and_forward),
        cmocka_unit_test(test_ignored_and_layout),
        cmocka_unit_test(test_vertex_variants),
        cmocka_unit_test(test_polygons_kept),
        cmocka_unit_test(test_bad_numbers),
        cmocka_unit_test(test_face_errors),
        cmocka_unit_test(test_unsupported_statements),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_no_nul_terminator),
        cmocka_unit_test(test_null_name),
        cmocka_unit_test(test_number_fast_path),
        cmocka_unit_test(test_shared_obj_files),
        cmocka_unit_test(test_shared_obj_uv),
        cmocka_unit_test(test_read_mesh_dispatch),
        cmocka_unit_test(test_read_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
