/* PLY reader: the same content in ascii, binary_little_endian and
 * binary_big_endian (built byte by byte here), all 16 type names, skipped
 * elements and properties (scalars and lists), provenance, and every error
 * with its status and message. Round trips through sq_write_ply are in
 * test_write.c. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "io_test_util.h"

enum { ASCII, LE, BE };
static const char *const fmt_name[] = {"ascii", "binary_little_endian", "binary_big_endian"};

/* A PLY file under construction. */
typedef struct pb {
    unsigned char d[16384];
    size_t n;
    int fmt;
} pb;

static void pb_bytes(pb *b, const void *p, size_t n)
{
    assert_true(b->n + n <= sizeof b->d);
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void pb_text(pb *b, const char *s)
{
    pb_bytes(b, s, strlen(s));
}

static int type_is_float(const char *t)
{
    return !strcmp(t, "float") || !strcmp(t, "double") || !strcmp(t, "float32") ||
           !strcmp(t, "float64");
}

static size_t type_size(const char *t)
{
    static const struct { const char *n; size_t s; } tab[] = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},  {"short", 2},   {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},   {"uint", 4},   {"int32", 4},   {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (size_t k = 0; k < sizeof tab / sizeof tab[0]; k++)
        if (!strcmp(tab[k].n, t)) return tab[k].s;
    fail_msg("bad type %s", t);
    return 0;
}

/* One value of the given type in the file's encoding. */
static void pb_val(pb *b, const char *type, double v)
{
    if (b->fmt == ASCII) {
        char s[64];
        if (type_is_float(type))
            snprintf(s, sizeof s, "%.17g ", v);
        else
            snprintf(s, sizeof s, "%lld ", (long long)v);
        pb_text(b, s);
        return;
    }
    size_t n = type_size(type);
    uint64_t u;
    if (n == 8 && type_is_float(type)) {
        memcpy(&u, &v, 8);
    } else if (type_is_float(type)) {
        float f = (float)v;
        uint32_t w;
        memcpy(&w, &f, 4);
        u = w;
    } else {
        u = (uint64_t)(int64_t)v; /* two's complement, truncated below */
    }
    unsigned char o[8];
    for (size_t k = 0; k < n; k++) {
        unsigned char byte = (unsigned char)(u >> (8 * k));
        o[b->fmt == LE ? k : n - 1 - k] = byte;
    }
    pb_bytes(b, o, n);
}

/* End of a record: ascii records are lines. */
static void pb_eol(pb *b)
{
    if (b->fmt != ASCII) return;
    if (b->n && b->d[b->n - 1] == ' ') b->n--;
    pb_text(b, "\n");
}

static void pb_header(pb *b, int fmt, const char *body)
{
    b->n = 0;
    b->fmt = fmt;
    pb_text(b, "ply\nformat ");
    pb_text(b, fmt_name[fmt]);
    pb_text(b, " 1.0\n");
    pb_text(b, body);
}

static const double tet_pos[] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, -2.25, 0.5, 1};
static const uint32_t tet_idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};

/* A tetrahedron with extra elements and properties around the ones we
 * keep, using all 16 type names. */
static void build_rich(pb *b, int fmt)
{
    pb_header(b, fmt,
              "comment made by test_read_ply\n"
              "obj_info any text\n"
              "element misc 2\n"
              "property char a\nproperty int8 b\nproperty short c\nproperty ushort d\n"
              "property uint16 e\nproperty uint32 f\nproperty float g\nproperty double h\n"
              "property int i\n"
              "element vertex 4\n"
              "property float32 x\nproperty uchar red\nproperty double y\n"
              "property list uchar int extra_list\nproperty int16 z\n"
              "property float64 confidence\n"
              "element edge 2\n"
              "property int vertex1\nproperty list ushort float weights\nproperty uint vertex2\n"
              "element face 4\n"
              "property uint8 flags\nproperty list uint8 uint32 vertex_indices\n"
              "property list int32 short other\n"
              "end_header\n");
    for (int r = 0; r < 2; r++) {
        pb_val(b, "char", -5 - r);
        pb_val(b, "int8", -128);
        pb_val(b, "short", -32768);
        pb_val(b, "ushort", 65535);
        pb_val(b, "uint16", 1);
        pb_val(b, "uint32", 4294967295.0);
        pb_val(b, "float", 0.25);
        pb_val(b, "double", -1e300);
        pb_val(b, "int", -2147483648.0);
        pb_eol(b);
    }
    for (int v = 0; v < 4; v++) {
        pb_val(b, "float32", tet_pos[3 * v]);
        pb_val(b, "uchar", 200 + v);
        pb_val(b, "double", tet_pos[3 * v + 1]);
        pb_val(b, "uchar", v); /* extra_list: v items */
        for (int k = 0; k < v; k++) pb_val(b, "int", -k);
        pb_val(b, "int16", tet_pos[3 * v + 2]);
        pb_val(b, "float64", 0.125 * v);
        pb_eol(b);
    }
    for (int r = 0; r < 2; r++) {
        pb_val(b, "int", r);
        pb_val(b, "ushort", 3);
        for (int k = 0; k < 3; k++) pb_val(b, "float", k * 0.5);
        pb_val(b, "uint", r + 1);
        pb_eol(b);
    }
    for (int f = 0; f < 4; f++) {
        pb_val(b, "uint8", 7);
        pb_val(b, "uint8", 3);
        for (int k = 0; k < 3; k++) pb_val(b, "uint32", tet_idx[3 * f + k]);
        pb_val(b, "int32", f % 2 ? 0 : 2);
        for (int k = 0; k < (f % 2 ? 0 : 2); k++) pb_val(b, "short", -1);
        pb_eol(b);
    }
}

static sq_status pb_parse(const pb *b, sq_soup *s, sq_error *e)
{
    return sq_parse_ply((const char *)b->d, b->n, "t.ply", s, e);
}

static void test_three_encodings(void **state)
{
    (void)state;
    for (int fmt = ASCII; fmt <= BE; fmt++) {
        pb b;
        sq_soup s;
        sq_error e;
        build_rich(&b, fmt);
        if (pb_parse(&b, &s, &e)) fail_msg("%s: %s", fmt_name[fmt], e.msg);
        io_check_soup(&s);
        assert_int_equal(s.nv, 4);
        assert_int_equal(s.nf, 4);
        assert_memory_equal(s.pos, tet_pos, sizeof tet_pos);
        assert_memory_equal(s.face_idx, tet_idx, sizeof tet_idx);
        assert_null(s.face_uv);
        assert_string_equal(s.path, "t.ply");
        char where[64];
        if (fmt == ASCII) {
            /* header: 30 lines; misc records on 31-32, vertices 33-36,
             * edges 37-38, faces 39-42 */
            assert_int_equal(s.line_kind, 0);
            assert_int_equal(s.vert_line[0], 33);
            assert_int_equal(s.face_line[3], 42);
            assert_string_equal(sq_soup_where_face(&s, 3, where, sizeof where), "t.ply:42");
        } else {
            assert_int_equal(s.line_kind, 1);
            for (uint32_t v = 0; v < 4; v++) assert_int_equal(s.vert_line[v], v + 1);
            for (uint32_t f = 0; f < 4; f++) assert_int_equal(s.face_line[f], f + 1);
            assert_string_equal(sq_soup_where_face(&s, 3, where, sizeof where),
                                "t.ply record 4");
        }
        sq_soup_free(&s);
    }
}

/* x of every type name reads back as the same double. */
static void test_all_coordinate_types(void **state)
{
    (void)state;
    static const char *const types[] = {"char",  "uchar", "short",  "ushort", "int",   "uint",
                                        "float", "double", "int8",  "uint8",  "int16", "uint16",
                                        "int32", "uint32", "float32", "float64"};
    for (int fmt = ASCII; fmt <= BE; fmt++) {
        for (size_t t = 0; t < sizeof types / sizeof types[0]; t++) {
            char head[256];
            snprintf(head, sizeof head,
                     "element vertex 3\nproperty %s x\nproperty %s y\nproperty %s z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n",
                     types[t], types[t], types[t]);
            pb b;
            pb_header(&b, fmt, head);
            int is_signed = types[t][0] != 'u';
            double v0 = is_signed ? -7 : 7, v1 = 100, v2 = 0;
            for (int r = 0; r < 3; r++) {
                pb_val(&b, types[t], v0 + r);
                pb_val(&b, types[t], v1);
                pb_val(&b, types[t], v2);
                pb_eol(&b);
            }
            pb_val(&b, "uchar", 3);
            for (int k = 0; k < 3; k++) pb_val(&b, "int", k);
            pb_eol(&b);
            sq_soup s;
            sq_error e;
            if (pb_parse(&b, &s, &e)) fail_msg("%s %s: %s", fmt_name[fmt], types[t], e.msg);
            for (int r = 0; r < 3; r++) {
                assert_true(s.pos[3 * r] == v0 + r);
                assert_true(s.pos[3 * r + 1] == v1 && s.pos[3 * r + 2] == v2);
            }
            sq_soup_free(&s);
        }
    }
}

/* Exact bytes of a small big-endian file, written out by hand. */
static void test_big_endian_bytes(void **state)
{
    (void)state;
    static const char head[] = "ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
                               "property float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar ushort vertex_index\n"
                               "end_header\n";
    static const unsigned char body[] = {
        0x3f, 0x80, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xc0, 0x40, 0x00, 0x00, /* 1 2 -3 */
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, /* 0 0 0  */
        0x3e, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, /* .25 0 0 */
        0x03, 0x00, 0x02, 0x00, 0x01, 0x00, 0x00,                               /* 3: 2 1 0 */
    };
    pb b;
    b.n = 0;
    pb_bytes(&b, head, sizeof head - 1);
    pb_bytes(&b, body, sizeof body);
    sq_soup s;
    sq_error e;
    if (pb_parse(&b, &s, &e)) fail_msg("%s", e.msg);
    const double pos[] = {1, 2, -3, 0, 0, 0, 0.25, 0, 0};
    const uint32_t idx[] = {2, 1, 0};
    assert_memory_equal(s.pos, pos, sizeof pos);
    assert_memory_equal(s.face_idx, idx, sizeof idx);
    sq_soup_free(&s);
    /* the same body read as little-endian: index 0x0200 is out of range */
    pb_header(&b, LE, "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar ushort vertex_index\nend_header\n");
    pb_bytes(&b, body, sizeof body);
    expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_INDEX,
                 "t.ply: face record 1: corner 1: vertex index 512 out of range (the file has 3 "
                 "vertices, numbered from 0)");
}

/* Ascii layout: CRLF, blank lines, extra blanks, comments in the header. */
static void test_ascii_layout(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_ply,
                "ply\r\nformat ascii 1.0\r\ncomment hello\r\n\r\nelement vertex 3\r\n"
                "property double x\r\nproperty double y\r\nproperty double z\r\n"
                "element face 2\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                "0 0 0\r\n\r\n  1\t0  0  \r\n0 1 0\r\n3 0 1 2\r\n4 0 1 2 0",
                &s);
    assert_int_equal(s.vert_line[0], 12);
    assert_int_equal(s.vert_line[1], 14);
    assert_int_equal(s.face_line[1], 17);
    const uint32_t off[] = {0, 3, 7};
    assert_memory_equal(s.face_off, off, sizeof off);
    sq_soup_free(&s);
    /* an element without properties takes no bytes, whatever its count */
    io_parse_ok(sq_parse_ply,
                "ply\nformat ascii 1.0\nelement nothing 4611686018427387904\n"
                "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                &s);
    sq_soup_free(&s);
}

/* Header text with x y z and a triangle list, for the error tests. */
#define HEAD_ASCII "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n" \
                   "property float y\nproperty float z\nelement face 1\n"
#define TRI_LIST "property list uchar int vertex_indices\nend_header\n"
#define VERTS "0 0 0\n1 0 0\n0 1 0\n"

static void test_header_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    static const struct { const char *text; sq_status st; const char *msg; } cases[] = {
        {"", SQ_ERR_EMPTY, "mem: empty file"},
        {"PLY\n", SQ_ERR_PARSE, "mem:1: not a PLY file: the first line must be 'ply'"},
        {"OFF\n3 1 0\n", SQ_ERR_PARSE, "not a PLY file"},
        {"ply\nelement vertex 3\nend_header\n", SQ_ERR_PARSE, "mem: the header has no 'format' line"},
        {"ply\nformat binary_middle_endian 1.0\n", SQ_ERR_PARSE,
         "mem:2: unknown encoding (expected ascii, binary_little_endian or binary_big_endian) "
         "'binary_middle_endian'"},
        {"ply\nformat ascii 2.0\n", SQ_ERR_PARSE, "mem:2: unsupported PLY version '2.0'"},
        {"ply\nformat ascii\n", SQ_ERR_PARSE, "mem:2: expected 'format ENCODING 1.0'"},
        {"ply\nformat ascii 1.0\nformat ascii 1.0\n", SQ_ERR_PARSE, "mem:3: second 'format' line"},
        {"ply\nformat ascii 1.0\nelemnt vertex 3\n", SQ_ERR_PARSE,
         "mem:3: unknown header statement 'elemnt'"},
        {"ply\nformat ascii 1.0\nproperty float x\n", SQ_ERR_PARSE,
         "mem:3: 'property' before any 'element'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n", SQ_ERR_PARSE,
         "mem:3: the header ends without 'end_header'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nend_header junk\n", SQ_ERR_PARSE,
         "mem:4: text after 'end_header'"},
        {"ply\nformat ascii 1.0\nelement vertex\n", SQ_ERR_PARSE,
         "mem:3: expected 'element NAME COUNT'"},
        {"ply\nformat ascii 1.0\nelement vertex 3x\n", SQ_ERR_PARSE, "mem:3: bad element count '3x'"},
        {"ply\nformat ascii 1.0\nelement vertex -3\n", SQ_ERR_PARSE,
         "mem:3: negative element count '-3'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty flaot x\n", SQ_ERR_PARSE,
         "mem:4: bad property type 'flaot'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float\n", SQ_ERR_PARSE,
         "mem:4: expected 'property TYPE NAME'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar int\n", SQ_ERR_PARSE,
         "mem:4: expected 'property list COUNT_TYPE ITEM_TYPE NAME'"},
        {"ply\nformat ascii 1.0\nelement f 3\nproperty list float int a\n", SQ_ERR_PARSE,
         "mem:4: list count type must be an integer type, not 'float'"},
        {"ply\nformat ascii 1.0\nelement f 3\nproperty list uchar in a\n", SQ_ERR_PARSE,
         "mem:4: bad list item type 'in'"},
        {"ply\nformat ascii 1.0\nelement f 3\nproperty list uint32_t int a\n", SQ_ERR_PARSE,
         "mem:4: bad list count type 'uint32_t'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty double x\n",
         SQ_ERR_PARSE, "mem:5: duplicate property 'x'"},
        {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", SQ_ERR_PARSE,
         "mem: the header declares no 'vertex' element"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n0 0 0\n", SQ_ERR_EMPTY,
         "mem: the header declares no 'face' element (a point cloud has no surface)"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement vertex 1\n"
         "element face 0\nend_header\n", SQ_ERR_PARSE, "mem:5: second 'vertex' element"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "element face 1\n" TRI_LIST, SQ_ERR_PARSE, "mem:3: the vertex element lacks property z"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar float x\n"
         "property float y\nproperty float z\nelement face 1\n" TRI_LIST, SQ_ERR_PARSE,
         "mem:3: vertex property 'x' is a list; coordinates must be scalars"},
        {HEAD_ASCII "property list uchar int indices\nend_header\n", SQ_ERR_PARSE,
         "mem:7: the face element has no vertex_indices (or vertex_index) list"},
        {HEAD_ASCII "property int vertex_indices\nend_header\n", SQ_ERR_PARSE,
         "mem:7: face property 'vertex_indices' must be a list"},
        {HEAD_ASCII "property list uchar float vertex_indices\nend_header\n", SQ_ERR_PARSE,
         "mem:7: face vertex indices have type float; an integer type is required"},
        {HEAD_ASCII "property list uchar int vertex_index\nproperty list uchar int "
                    "vertex_indices\nend_header\n", SQ_ERR_PARSE,
         "mem:7: the face element has both vertex_indices and vertex_index"},
        {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
         "property float z\nelement face 0\n" TRI_LIST, SQ_ERR_EMPTY,
         "mem: the header declares 0 vertices and 0 faces: empty mesh"},
        {"ply\nformat ascii 1.0\nelement vertex 4294967295\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\n" TRI_LIST, SQ_ERR_PARSE,
         "mem: 4294967295 vertices and 1 faces exceed the limit of 4294967294"},
        {"ply\nformat ascii 1.0\n\x01\x02\x03\n", SQ_ERR_PARSE,
         "mem:3: binary data inside the header"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        sq_status st = io_parse(sq_parse_ply, cases[k].text, &s, &e);
        if (st != cases[k].st || !strstr(e.msg, cases[k].msg))
            fail_msg("case %zu: got %s '%s', expected %s '%s'", k, sq_status_name(st), e.msg,
                     sq_status_name(cases[k].st), cases[k].msg);
        assert_null(s.pos);
    }
}

static void test_ascii_record_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    static const struct { const char *text; sq_status st; const char *msg; } cases[] = {
        {HEAD_ASCII TRI_LIST "0 0 0\n1 0 0 5\n0 1 0\n3 0 1 2\n", SQ_ERR_PARSE,
         "mem:11: vertex record 2: the line has more values than the element's properties"},
        {HEAD_ASCII TRI_LIST "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", SQ_ERR_PARSE,
         "mem:11: vertex record 2: the line ends before property 'z'"},
        {HEAD_ASCII TRI_LIST "0 0 0\n1 0 abc\n0 1 0\n3 0 1 2\n", SQ_ERR_PARSE,
         "mem:11: vertex record 2: property 'z': bad number 'abc'"},
        {HEAD_ASCII TRI_LIST VERTS "3 0 1 1.5\n", SQ_ERR_PARSE,
         "mem:13: face record 1: property 'vertex_indices': '1.5' is not an integer (type int)"},
        {HEAD_ASCII TRI_LIST VERTS "256 0 1 2\n", SQ_ERR_PARSE,
         "mem:13: face record 1: property 'vertex_indices': 256 is out of range for type uchar"},
        {HEAD_ASCII TRI_LIST VERTS "3 0 1 3\n", SQ_ERR_INDEX,
         "mem:13: face record 1: corner 3: vertex index 3 out of range (the file has 3 vertices"},
        {HEAD_ASCII TRI_LIST VERTS "3 0 -1 2\n", SQ_ERR_INDEX,
         "mem:13: face record 1: corner 2: vertex index -1 out of range"},
        {HEAD_ASCII TRI_LIST VERTS "2 0 1\n", SQ_ERR_PARSE,
         "mem:13: face record 1: face has 2 corners; a face needs at least 3"},
        {HEAD_ASCII TRI_LIST VERTS "0\n", SQ_ERR_PARSE, "face has 0 corners"},
        {HEAD_ASCII TRI_LIST VERTS "9 0 1 2\n", SQ_ERR_PARSE,
         "mem:13: face record 1: list 'vertex_indices' has 9 items, more than the line holds"},
        {HEAD_ASCII TRI_LIST VERTS "4 0 1 2\n", SQ_ERR_PARSE,
         "mem:13: face record 1: the line ends before property 'vertex_indices'"},
        {HEAD_ASCII TRI_LIST VERTS "3 0 1\n", SQ_ERR_PARSE,
         "mem:13: face record 1: the line ends before property 'vertex_indices'"},
        {HEAD_ASCII "property list int int vertex_indices\nend_header\n" VERTS "-3 0 1 2\n",
         SQ_ERR_PARSE, "mem:13: face record 1: list 'vertex_indices' has negative count -3"},
        {HEAD_ASCII TRI_LIST VERTS "3 0 1 2\n3 0 1 2\n", SQ_ERR_PARSE,
         "mem:14: unexpected content after the last element"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 3\n" TRI_LIST VERTS "3 0 1 2\n3 0 1 2\n",
         SQ_ERR_PARSE, "mem:14: expected 3 'face' records, file ends after 2"},
        {"ply\nformat ascii 1.0\nelement vertex 30\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\n" TRI_LIST VERTS "3 0 1 2\n",
         SQ_ERR_PARSE,
         "mem:3: element 'vertex' declares 30 records of at least 6 bytes each, but only 26 "
         "bytes of data are left"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        sq_status st = io_parse(sq_parse_ply, cases[k].text, &s, &e);
        if (st != cases[k].st || !strstr(e.msg, cases[k].msg))
            fail_msg("case %zu: got %s '%s', expected %s '%s'", k, sq_status_name(st), e.msg,
                     sq_status_name(cases[k].st), cases[k].msg);
    }
}

/* A binary file with 3 float vertices and one face of list type `lt`. */
static void build_tri(pb *b, int fmt, const char *list_head, const char *ct, double count,
                      const char *it, const double *items, int nitems)
{
    char head[512];
    snprintf(head, sizeof head,
             "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\n%s\nend_header\n", list_head);
    pb_header(b, fmt, head);
    for (int v = 0; v < 9; v++) pb_val(b, "float", v == 3 || v == 7 ? 1 : 0);
    pb_val(b, ct, count);
    for (int k = 0; k < nitems; k++) pb_val(b, it, items[k]);
}

static void test_binary_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    pb b;
    const double tri[] = {0, 1, 2};
    for (int fmt = LE; fmt <= BE; fmt++) {
        build_tri(&b, fmt, "property list uchar int vertex_indices", "uchar", 3, "int", tri, 3);
        assert_int_equal(pb_parse(&b, &s, &e), SQ_OK);
        sq_soup_free(&s);
        /* truncated: the last index loses two bytes */
        b.n -= 2;
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply: face record 1: list 'vertex_indices' has 3 items, more than the "
                     "rest of the file holds (truncated file or wrong count)");
        /* truncated inside a scalar */
        build_tri(&b, fmt, "property list uchar int vertex_indices\nproperty int flags", "uchar",
                  3, "int", tri, 3);
        pb_val(&b, "int", 1);
        b.n -= 2;
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply: face record 1: the file ends inside property 'flags' (truncated "
                     "file)");
        /* trailing bytes */
        build_tri(&b, fmt, "property list uchar int vertex_indices", "uchar", 3, "int", tri, 3);
        pb_text(&b, "xyz");
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply: 3 bytes of unexpected data after the last element");
        /* negative list count (signed count type) */
        build_tri(&b, fmt, "property list char int vertex_indices", "char", -1, "int", tri, 3);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply: face record 1: list 'vertex_indices' has negative count -1");
        /* a count far beyond the data: no allocation, a clear message */
        build_tri(&b, fmt, "property list int int vertex_indices", "int", 2000000000, "int", tri,
                  3);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply: face record 1: list 'vertex_indices' has 2000000000 items, more than "
                     "the rest of the file holds");
        /* the same for a list that is skipped */
        build_tri(&b, fmt, "property list ushort double weights\n"
                  "property list uchar int vertex_indices", "ushort", 60000, "double", tri, 3);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "list 'weights' has 60000 items, more than the rest of the file holds");
        /* unsigned 32-bit index beyond nv; signed negative index */
        const double big[] = {0, 1, 4294967295.0};
        build_tri(&b, fmt, "property list uchar uint vertex_indices", "uchar", 3, "uint", big, 3);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_INDEX,
                     "t.ply: face record 1: corner 3: vertex index 4294967295 out of range");
        const double neg[] = {0, -2, 1};
        build_tri(&b, fmt, "property list uchar short vertex_indices", "uchar", 3, "short", neg,
                  3);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_INDEX,
                     "t.ply: face record 1: corner 2: vertex index -2 out of range");
        /* element counts beyond the data */
        pb_header(&b, fmt, "element vertex 1000\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n");
        for (int v = 0; v < 9; v++) pb_val(&b, "float", 0);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply:3: element 'vertex' declares 1000 records of at least 12 bytes each, "
                     "but only 36 bytes of data are left");
        /* a huge skipped element */
        pb_header(&b, fmt, "element junk 99999999999\nproperty double a\n"
                           "element vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n");
        for (int v = 0; v < 9; v++) pb_val(&b, "float", 0);
        pb_val(&b, "uchar", 3);
        for (int k = 0; k < 3; k++) pb_val(&b, "int", k);
        expect_error(pb_parse(&b, &s, &e), &e, SQ_ERR_PARSE,
                     "t.ply:3: element 'junk' declares 99999999999 records of at least 8 bytes");
    }
}

static void test_no_nul_terminator(void **state)
{
    (void)state;
    /* every prefix of a valid file fails cleanly (ASan checks the reads) */
    for (int fmt = ASCII; fmt <= BE; fmt++) {
        pb b;
        build_rich(&b, fmt);
        for (size_t n = 0; n < b.n; n++) {
            unsigned char *copy = malloc(n ? n : 1);
            memcpy(copy, b.d, n);
            sq_soup s;
            sq_error e;
            sq_status st = sq_parse_ply((const char *)copy, n, "p.ply", &s, &e);
            /* the last byte of an ascii file is its final newline */
            if (!(fmt == ASCII && n == b.n - 1)) {
                if (st == SQ_OK) fail_msg("%s prefix %zu of %zu parsed", fmt_name[fmt], n, b.n);
                assert_non_null(strstr(e.msg, "p.ply"));
            } else {
                assert_int_equal(st, SQ_OK);
                sq_soup_free(&s);
            }
            free(copy);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_encodings),
        cmocka_unit_test(test_all_coordinate_types),
        cmocka_unit_test(test_big_endian_bytes),
        cmocka_unit_test(test_ascii_layout),
        cmocka_unit_test(test_header_errors),
        cmocka_unit_test(test_ascii_record_errors),
        cmocka_unit_test(test_binary_errors),
        cmocka_unit_test(test_no_nul_terminator),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
