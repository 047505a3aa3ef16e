/* The broken inputs of tests/data/broken/EXPECTED_io.tsv: each file fails
 * with the listed status and a message containing the listed text. Files
 * the readers accept (nan.obj) must then be rejected by the mesh builder.
 * (`seamquad check` runs the same table end to end: tests/cli_check.sh.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "io_test_util.h"
#include "sq_mesh.h"

#define BROKEN SQ_TEST_DATA_DIR "/broken/"

static void test_expected_io(void **state)
{
    (void)state;
    FILE *f = fopen(BROKEN "EXPECTED_io.tsv", "r");
    if (!f) fail_msg("cannot open " BROKEN "EXPECTED_io.tsv");
    char line[2048];
    int rows = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0') continue;
        char *file = line, *status = strchr(file, '\t');
        if (!status) fail_msg("bad row: %s", line);
        *status++ = '\0';
        char *sub = strchr(status, '\t');
        if (!sub) fail_msg("bad row for %s", file);
        *sub++ = '\0';

        char path[4096];
        snprintf(path, sizeof path, BROKEN "%s", file);
        sq_soup s;
        sq_error e;
        sq_status st = sq_read_mesh(path, &s, &e);
        if (st == SQ_OK) {
            sq_mesh m;
            st = sq_mesh_from_soup(&s, 0, &m, &e);
            if (st == SQ_OK) sq_mesh_free(&m);
            sq_soup_free(&s);
        } else {
            /* every read error starts with the path */
            if (strncmp(e.msg, path, strlen(path)) != 0)
                fail_msg("%s: message does not start with the path: %s", file, e.msg);
        }
        if (strcmp(sq_status_name(st), status) != 0)
            fail_msg("%s: status %s, expected %s (%s)", file, sq_status_name(st), status, e.msg);
        if (!strstr(e.msg, sub)) fail_msg("%s: message lacks '%s': %s", file, sub, e.msg);
        rows++;
    }
    fclose(f);
    assert_true(rows >= 7);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_expected_io),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
