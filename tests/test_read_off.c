/* OFF reader: accepted syntax, every error with its status and message
 * (including the line), truncation of a real file, and every OFF mesh of
 * ../shared/data against MANIFEST.tsv. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "io_test_util.h"

static void test_basic(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_off,
                "OFF\n"
                "4 4 6\n"
                "0 0 0\n"
                "1 0 0\n"
                "0 1 0\n"
                "0 0 1.5e0\n"
                "3 0 2 1\n"
                "3 0 1 3\n"
                "3 1 2 3\n"
                "3 2 0 3\n",
                &s);
    io_check_soup(&s);
    assert_int_equal(s.nv, 4);
    assert_int_equal(s.nf, 4);
    assert_true(s.pos[3] == 1.0 && s.pos[11] == 1.5);
    const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    assert_memory_equal(s.face_idx, idx, sizeof idx);
    for (uint32_t v = 0; v < 4; v++) assert_int_equal(s.vert_line[v], v + 3);
    for (uint32_t f = 0; f < 4; f++) assert_int_equal(s.face_line[f], f + 7);
    assert_null(s.face_uv);
    assert_int_equal(s.nuv, 0);
    assert_string_equal(s.path, "mem");
    sq_soup_free(&s);
}

/* Counts on the header line, comments anywhere, blank lines, CRLF, tabs,
 * polygons, face colours, no edge count, no final newline. */
static void test_layout(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_off,
                "# leading comment\r\n"
                "OFF 5 2\r\n"
                "\r\n"
                "0 0 0   # vertex 0\r\n"
                "# a comment between vertices\r\n"
                "1\t0\t0\r\n"
                "  1 1 0\r\n"
                "0 1 0\r\n"
                "2 0 0\r\n"
                "4 0 1 2 3 255 0 0\r\n"       /* RGB colour: ignored */
                "5 1 4 2 3 0 0.5 0.5 0.5 1",  /* RGBA, no final newline */
                &s);
    io_check_soup(&s);
    const uint32_t off[] = {0, 4, 9};
    assert_memory_equal(s.face_off, off, sizeof off);
    assert_int_equal(s.vert_line[0], 4);
    assert_int_equal(s.vert_line[1], 6);
    assert_int_equal(s.face_line[1], 11);
    sq_soup_free(&s);

    /* one colour-map index after the corners */
    io_parse_ok(sq_parse_off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n", &s);
    sq_soup_free(&s);
}

/* COFF, NOFF, CNOFF and STOFF: the extra per-vertex values are checked and
 * ignored; positions are the first three values. */
static void test_variants(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    io_parse_ok(sq_parse_off,
                "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0\n0 1 0 0 0 1 0.5\n3 0 1 2\n", &s);
    assert_true(s.pos[3] == 1.0 && s.pos[7] == 1.0);
    sq_soup_free(&s);
    io_parse_ok(sq_parse_off, "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
                &s);
    sq_soup_free(&s);
    io_parse_ok(sq_parse_off,
                "CNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1\n1 0 0 0 0 1 1 1 1 1\n0 1 0 0 0 1 1 1 1\n3 0 1 2\n",
                &s);
    sq_soup_free(&s);
    io_parse_ok(sq_parse_off, "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n", &s);
    sq_soup_free(&s);
    expect_error(io_parse(sq_parse_off, "COFF\n3 1 0\n0 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:3: vertex 0 has 3 values, expected 6 or 7 (header COFF)");
    expect_error(io_parse(sq_parse_off, "NOFF\n3 1 0\n0 0 0 1 1 1 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", &s, &e), &e,
                 SQ_ERR_PARSE, "mem:3: vertex 0 has 7 values, expected 6 (header NOFF)");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 0\n0 0 0\n1 0 0 1 1 1\n0 1 0\n3 0 1 2\n", &s, &e), &e,
                 SQ_ERR_PARSE, "mem:4: vertex 1 has 6 values, expected 3 (header OFF)");
    expect_error(io_parse(sq_parse_off, "OFF BINARY\n3 1 0\n", &s, &e), &e, SQ_ERR_FORMAT,
                 "mem:1: binary OFF is not supported");
    expect_error(io_parse(sq_parse_off, "4OFF\n3 1 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: expected the header 'OFF'");
}

static void test_header_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    expect_error(io_parse(sq_parse_off, "", &s, &e), &e, SQ_ERR_EMPTY, "mem: empty file");
    expect_error(io_parse(sq_parse_off, "# nothing\n\n", &s, &e), &e, SQ_ERR_EMPTY,
                 "mem: empty file");
    expect_error(io_parse(sq_parse_off, "\nOF\n3 1 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: expected the header 'OFF' (or COFF, NOFF, CNOFF, STOFF), found 'OF'");
    expect_error(io_parse(sq_parse_off, "3 1 0\n0 0 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "found '3'");
    expect_error(io_parse(sq_parse_off, "ply\nformat ascii 1.0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "found 'ply'");
    const char bin[] = "\x7f" "ELF\x02\x01\x01";
    expect_error(sq_parse_off(bin, sizeof bin - 1, "x.off", &s, &e), &e, SQ_ERR_PARSE,
                 "x.off:1: binary data where the OFF header belongs");
    expect_error(io_parse(sq_parse_off, "OFF\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:1: file ends after the header");
    expect_error(io_parse(sq_parse_off, "OFF\n3\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: expected the counts 'vertices faces [edges]', found 1 values");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 0 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "found more than 3 values");
    expect_error(io_parse(sq_parse_off, "OFF\n-3 1 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: negative vertex count -3");
    expect_error(io_parse(sq_parse_off, "OFF\n3 -1 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: negative face count -1");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 -6\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: negative edge count -6");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1.5 0\n", &s, &e), &e, SQ_ERR_PARSE,
                 "mem:2: bad face count '1.5'");
    expect_error(io_parse(sq_parse_off, "OFF\n0 0 0\n", &s, &e), &e, SQ_ERR_EMPTY,
                 "mem:2: header declares 0 vertices and 0 faces: empty mesh");
    expect_error(io_parse(sq_parse_off, "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", &s, &e), &e,
                 SQ_ERR_EMPTY, "header declares 3 vertices and 0 faces");
}

/* Counts the file cannot hold are rejected before any allocation: these
 * would otherwise ask for tens of gigabytes. */
static void test_absurd_counts(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    expect_error(io_parse(sq_parse_off, "OFF\n2000000000 4000000000 0\n0 0 0\n", &s, &e), &e,
                 SQ_ERR_PARSE,
                 "mem:2: header declares 2000000000 vertices and 4000000000 faces, but only 6 "
                 "bytes follow");
    expect_error(io_parse(sq_parse_off, "OFF 99999999999999999999 1 0\n", &s, &e), &e,
                 SQ_ERR_PARSE, "exceed the limit of 4294967294");
    expect_error(io_parse(sq_parse_off, "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", &s, &e), &e,
                 SQ_ERR_PARSE, "mem:2: header declares 4 vertices and 1 faces, but only 18 bytes "
                               "follow (at least 32 needed)");
    assert_null(s.pos);
}

static void test_truncated(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    /* long lines, so the size check passes and the parse finds the end */
    const char *verts = "OFF\n4 4 0\n0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n"
                        "0.000000 1.000000 0.000000\n0.000000 0.000000 1.000000\n";
    char buf[512];
    snprintf(buf, sizeof buf, "%s3 0 2 1\n3 0 1 3\n", verts);
    expect_error(io_parse(sq_parse_off, buf, &s, &e), &e, SQ_ERR_PARSE,
                 "mem:8: expected 4 faces, file ends after 2");
    expect_error(io_parse(sq_parse_off,
                          "OFF\n3 1 0\n0.000000000 0.0000000000 0.0000000000\n"
                          "1.000000000000 0.000000000000 0.000000000000\n",
                          &s, &e),
                 &e, SQ_ERR_PARSE, "mem:4: expected 3 vertices, file ends after 2");

    /* a real file cut inside its faces: 3holes has 3596 vertices and 7200
     * faces on lines 3 .. 3598 and 3599 .. 10798 */
    char *data;
    size_t size;
    assert_int_equal(sq_read_file(IO_DATA "libigl/3holes.off", &data, &size, &e), SQ_OK);
    size_t cut = 0;
    int lines = 0;
    while (lines < 3598 + 5123) /* keep 5123 complete face lines */
        if (data[cut++] == '\n') lines++;
    expect_error(sq_parse_off(data, cut, "3holes.off", &s, &e), &e, SQ_ERR_PARSE,
                 "3holes.off:8721: expected 7200 faces, file ends after 5123");
    /* cut in the middle of a face line ("3 3015 3 0" cut to "3 30"): that line is
     * reported */
    expect_error(sq_parse_off(data, cut + 4, "3holes.off", &s, &e), &e, SQ_ERR_PARSE,
                 "3holes.off:8722: face 5123 declares 3 corners but the line has only 1 indices");
    /* cut in the vertices */
    cut = 0;
    lines = 0;
    while (lines < 1002) if (data[cut++] == '\n') lines++;
    expect_error(sq_parse_off(data, cut, "3holes.off", &s, &e), &e, SQ_ERR_PARSE,
                 "header declares 3596 vertices and 7200 faces, but only");
    free(data);
}

static void test_element_errors(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    const char *head = "OFF\n3 1 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n";
    char buf[512];
#define WITH(face) (snprintf(buf, sizeof buf, "%s%s", head, face), buf)
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", &s, &e), &e,
                 SQ_ERR_PARSE, "mem:4: bad number 'x' (value 2 of vertex 1)");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0 junk\n3 0 1 2\n", &s, &e),
                 &e, SQ_ERR_PARSE, "mem:5: bad number 'junk' (value 4 of vertex 2)");
    expect_error(io_parse(sq_parse_off, "OFF\n3 1 0\n0 0 0\n1.00000 0\n0 1 0\n3 0 1 2\n", &s, &e), &e,
                 SQ_ERR_PARSE, "mem:4: vertex 1 has 2 values, expected 3");
    expect_error(io_parse(sq_parse_off, WITH("2 0 1\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0 has 2 corners; a face needs at least 3");
    expect_error(io_parse(sq_parse_off, WITH("-3 0 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0 has -3 corners");
    expect_error(io_parse(sq_parse_off, WITH("3.0 0 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0: bad corner count '3.0'");
    expect_error(io_parse(sq_parse_off, WITH("4 0 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0 declares 4 corners but the line has only 3 indices");
    expect_error(io_parse(sq_parse_off, WITH("1000000000 0 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0 declares 1000000000 corners, more than the line holds");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 3\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "mem:6: face 0 corner 3: vertex index 3 out of range (the file has 3 vertices, "
                 "numbered from 0)");
    expect_error(io_parse(sq_parse_off, WITH("3 0 -1 2\n"), &s, &e), &e, SQ_ERR_INDEX,
                 "mem:6: face 0 corner 2: vertex index -1 out of range");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 99999999999999999999\n"), &s, &e), &e,
                 SQ_ERR_INDEX, "vertex index 99999999999999999999 out of range");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 2x\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0: bad vertex index '2x' in corner 3");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 2 1 1 1 1 1\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0 has more than 4 values after its 3 corner indices");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 2 red\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:6: face 0: bad colour value 'red'");
    expect_error(io_parse(sq_parse_off, WITH("3 0 1 2\n3 0 1 2\n"), &s, &e), &e, SQ_ERR_PARSE,
                 "mem:7: unexpected content after the last of the 1 faces declared at line 2");
    /* trailing comments and blank lines are fine */
    io_parse_ok(sq_parse_off, WITH("3 0 1 2\n\n# end\n   \n"), &s);
    sq_soup_free(&s);
#undef WITH
}

static void test_nan_parses(void **state)
{
    (void)state;
    sq_soup s;
    io_parse_ok(sq_parse_off, "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", &s);
    assert_true(s.pos[0] != s.pos[0]);
    assert_int_equal(s.vert_line[0], 3);
    sq_soup_free(&s);
}

static void test_shared_off_files(void **state)
{
    (void)state;
    int n = io_read_manifest_meshes(".off");
    assert_true(n >= 10); /* MANIFEST lists 13 OFF files today */
}

/* Kitten.off has trailing blanks on its lines; rolling_stage is the largest. */
static void test_shared_off_content(void **state)
{
    (void)state;
    sq_soup s;
    sq_error e;
    if (sq_read_mesh(IO_DATA "avaxman/Kitten.off", &s, &e)) fail_msg("%s", e.msg);
    assert_true(s.pos[0] == -23.2043 && s.pos[1] == 28.656 && s.pos[2] == -9.2334);
    assert_int_equal(s.vert_line[0], 3);
    assert_int_equal(s.face_line[0], 3 + 1850);
    sq_soup_free(&s);
    if (sq_read_mesh(IO_DATA "cggs/rolling_stage.off", &s, &e)) fail_msg("%s", e.msg);
    assert_int_equal(s.face_off[s.nf], 300000);
    assert_true(s.pos[0] == 0.054699);
    sq_soup_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_basic),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_variants),
        cmocka_unit_test(test_header_errors),
        cmocka_unit_test(test_absurd_counts),
        cmocka_unit_test(test_truncated),
        cmocka_unit_test(test_element_errors),
        cmocka_unit_test(test_nan_parses),
        cmocka_unit_test(test_shared_off_files),
        cmocka_unit_test(test_shared_off_content),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
