/* Helpers shared by the reader and writer tests (test_read_*.c,
 * test_write.c). Include after <cmocka.h>. */
#ifndef IO_TEST_UTIL_H
#define IO_TEST_UTIL_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sq_io.h"

#define IO_DATA SQ_SHARED_DIR "/data/"

/* Fails unless st == want and the message contains `sub`. */
#define expect_error(st, e, want, sub) io_expect_error((st), (e), (want), (sub), __FILE__, __LINE__)

static inline void io_expect_error(sq_status st, const sq_error *e, sq_status want,
                                   const char *sub, const char *file, int line)
{
    if (st != want)
        fail_msg("%s:%d: status %s, expected %s (message: %s)", file, line, sq_status_name(st),
                 sq_status_name(want), e->msg);
    if (e->code != want)
        fail_msg("%s:%d: err.code %s, expected %s", file, line, sq_status_name(e->code),
                 sq_status_name(want));
    if (!strstr(e->msg, sub))
        fail_msg("%s:%d: message lacks '%s': %s", file, line, sub, e->msg);
}

/* Parses a NUL-terminated string with one of the parsers. */
typedef sq_status (*io_parser)(const char *, size_t, const char *, sq_soup *, sq_error *);

static inline sq_status io_parse(io_parser parse, const char *text, sq_soup *s, sq_error *e)
{
    return parse(text, strlen(text), "mem", s, e);
}

/* Parses text that must be valid; fails with the message otherwise. */
static inline void io_parse_ok(io_parser parse, const char *text, sq_soup *s)
{
    sq_error e;
    sq_status st = parse(text, strlen(text), "mem", s, &e);
    if (st) fail_msg("parse failed: %s: %s\n--- input:\n%s", sq_status_name(st), e.msg, text);
}

/* Soup invariants every reader guarantees on success. */
static inline void io_check_soup(const sq_soup *s)
{
    assert_true(s->nv > 0 && s->nf > 0);
    assert_non_null(s->pos);
    assert_non_null(s->face_off);
    assert_non_null(s->face_idx);
    assert_int_equal(s->face_off[0], 0);
    for (uint32_t f = 0; f < s->nf; f++) {
        assert_true(s->face_off[f + 1] >= s->face_off[f] + 3);
        for (uint32_t c = s->face_off[f]; c < s->face_off[f + 1]; c++) {
            assert_true(s->face_idx[c] < s->nv);
            if (s->face_uv) assert_true(s->face_uv[c] == SQ_NONE || s->face_uv[c] < s->nuv);
        }
    }
    if (s->vert_line) {
        for (uint32_t v = 0; v < s->nv; v++) assert_true(s->vert_line[v] >= 1);
    }
    if (s->face_line) {
        for (uint32_t f = 0; f < s->nf; f++) assert_true(s->face_line[f] >= 1);
    }
}

/* A fresh directory under $TMPDIR or /tmp; io_rmdir removes it. */
static inline void io_mkdtemp(char *buf, size_t n)
{
    const char *t = getenv("TMPDIR");
    snprintf(buf, n, "%s/sq_io_test.XXXXXX", t && *t ? t : "/tmp");
    if (!mkdtemp(buf)) fail_msg("mkdtemp %s failed", buf);
}

/* Number of entries in a directory other than . and .. (-1 if missing). */
static inline int io_count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *de;
    while ((de = readdir(d)))
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..")) n++;
    closedir(d);
    return n;
}

/* Removes a directory and the plain files and empty directories in it. */
static inline void io_rmdir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *de;
    char p[4096];
    while ((de = readdir(d))) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        if (snprintf(p, sizeof p, "%s/%s", dir, de->d_name) >= (int)sizeof p) continue;
        if (unlink(p) != 0) io_rmdir(p);
    }
    closedir(d);
    rmdir(dir);
}

static inline void io_write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) fail_msg("cannot create %s", path);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* One mesh of ../shared/data/MANIFEST.tsv. */
typedef struct io_manifest_row {
    char file[256];
    long nv, nf;
} io_manifest_row;

/* Reads the `file`, `V` and `F` columns (found by name in the header).
 * Returns the number of rows; *rows is malloc'ed. */
static inline int io_read_manifest(io_manifest_row **rows)
{
    FILE *f = fopen(IO_DATA "MANIFEST.tsv", "r");
    if (!f) fail_msg("cannot open " IO_DATA "MANIFEST.tsv");
    char line[8192];
    int cfile = -1, cv = -1, cf = -1, n = 0;
    *rows = NULL;
    for (int first = 1; fgets(line, sizeof line, f); first = 0) {
        line[strcspn(line, "\r\n")] = '\0';
        char *fld[32];
        int nf = 0;
        for (char *tok = line, *tab; nf < 32; tok = tab + 1) {
            fld[nf++] = tok;
            tab = strchr(tok, '\t');
            if (!tab) break;
            *tab = '\0';
        }
        if (first) {
            for (int k = 0; k < nf; k++) {
                if (!strcmp(fld[k], "file")) cfile = k;
                if (!strcmp(fld[k], "V")) cv = k;
                if (!strcmp(fld[k], "F")) cf = k;
            }
            if (cfile < 0 || cv < 0 || cf < 0) fail_msg("MANIFEST.tsv lacks file/V/F columns");
            continue;
        }
        if (nf <= cfile || nf <= cv || nf <= cf || !fld[cfile][0]) continue;
        *rows = realloc(*rows, (size_t)(n + 1) * sizeof **rows);
        assert_non_null(*rows);
        snprintf((*rows)[n].file, sizeof (*rows)[n].file, "%s", fld[cfile]);
        (*rows)[n].nv = atol(fld[cv]);
        (*rows)[n].nf = atol(fld[cf]);
        n++;
    }
    fclose(f);
    return n;
}

/* 1 when the name ends with ext (e.g. ".obj"). */
static inline int io_has_ext(const char *name, const char *ext)
{
    size_t a = strlen(name), b = strlen(ext);
    return a >= b && !strcmp(name + a - b, ext);
}

/* Reads every MANIFEST mesh with extension ext and checks its counts.
 * Returns how many were read. */
static inline int io_read_manifest_meshes(const char *ext)
{
    io_manifest_row *rows;
    int n = io_read_manifest(&rows), done = 0;
    for (int k = 0; k < n; k++) {
        if (!io_has_ext(rows[k].file, ext)) continue;
        char path[600];
        snprintf(path, sizeof path, IO_DATA "%s", rows[k].file);
        sq_soup s;
        sq_error e;
        sq_status st = sq_read_mesh(path, &s, &e);
        if (st) fail_msg("%s: %s", rows[k].file, e.msg);
        if ((long)s.nv != rows[k].nv || (long)s.nf != rows[k].nf)
            fail_msg("%s: read V=%u F=%u, MANIFEST says V=%ld F=%ld", rows[k].file, s.nv, s.nf,
                     rows[k].nv, rows[k].nf);
        io_check_soup(&s);
        assert_string_equal(s.path, path);
        assert_int_equal(s.line_kind, 0);
        sq_soup_free(&s);
        done++;
    }
    free(rows);
    return done;
}

#endif
