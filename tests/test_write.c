/* Writers and atomic output: OBJ and PLY round trips on real meshes are
 * bit-exact; a failure (missing directory, failed rename, a write that runs
 * out of space halfway) leaves the target untouched and no temporary file;
 * bad arguments create no file at all. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cmocka.h>
#include <sys/stat.h>

#include "io_test_util.h"
#include "sq_format_double.h"

static void read_or_fail(const char *path, sq_soup *s)
{
    sq_error e;
    if (sq_read_mesh(path, s, &e)) fail_msg("%s", e.msg);
}

/* Same vertices (bit for bit) and faces. */
static void assert_same_mesh(const sq_soup *a, const sq_soup *b)
{
    assert_int_equal(a->nv, b->nv);
    assert_int_equal(a->nf, b->nf);
    assert_memory_equal(a->pos, b->pos, 3 * (size_t)a->nv * sizeof(double));
    assert_memory_equal(a->face_off, b->face_off, ((size_t)a->nf + 1) * sizeof(uint32_t));
    assert_memory_equal(a->face_idx, b->face_idx, (size_t)a->face_off[a->nf] * sizeof(uint32_t));
}

static sq_status write_obj(const char *path, const sq_soup *s, int with_uv, sq_error *e)
{
    return sq_write_obj(path, s->nv, s->pos, s->nf, s->face_off, s->face_idx,
                        with_uv ? s->nuv : 0, with_uv ? s->uv : NULL,
                        with_uv ? s->face_uv : NULL, e);
}

static sq_status write_ply(const char *path, const sq_soup *s, sq_error *e)
{
    return sq_write_ply(path, s->nv, s->pos, s->nf, s->face_off, s->face_idx, e);
}

static void round_trip(const char *mesh, int fmt_ply)
{
    char dir[256], out[512], src[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(src, sizeof src, IO_DATA "%s", mesh);
    snprintf(out, sizeof out, "%s/out.%s", dir, fmt_ply ? "ply" : "obj");
    sq_soup a, b;
    sq_error e;
    read_or_fail(src, &a);
    sq_status st = fmt_ply ? write_ply(out, &a, &e) : write_obj(out, &a, 0, &e);
    if (st) fail_msg("%s", e.msg);
    read_or_fail(out, &b);
    assert_same_mesh(&a, &b);
    assert_int_equal(b.line_kind, fmt_ply ? 1 : 0);
    assert_null(b.face_uv);
    assert_int_equal(io_count_entries(dir), 1); /* no temporary file left */
    sq_soup_free(&a);
    sq_soup_free(&b);
    io_rmdir(dir);
}

static void test_obj_round_trip(void **state)
{
    (void)state;
    round_trip("cid/elephant.obj", 0);
    round_trip("cggs/rolling_stage.off", 0);
    round_trip("quads/bunny_quadriflow5k.obj", 0); /* quads */
}

static void test_ply_round_trip(void **state)
{
    (void)state;
    round_trip("cid/elephant.obj", 1);
    round_trip("mpz/block.obj", 1); /* 17-digit coordinates */
    round_trip("quads/botijo_quadriflow5k.obj", 1);
}

/* The seamless UV of an mpz mesh survives a round trip exactly. */
static void test_obj_uv_round_trip(void **state)
{
    (void)state;
    char dir[256], out[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/uv.obj", dir);
    sq_soup a, b;
    sq_error e;
    read_or_fail(IO_DATA "mpz/fandisk.obj", &a);
    assert_non_null(a.face_uv);
    if (write_obj(out, &a, 1, &e)) fail_msg("%s", e.msg);
    read_or_fail(out, &b);
    assert_same_mesh(&a, &b);
    assert_int_equal(a.nuv, b.nuv);
    assert_memory_equal(a.uv, b.uv, 2 * (size_t)a.nuv * sizeof(double));
    assert_memory_equal(a.face_uv, b.face_uv, (size_t)a.face_off[a.nf] * sizeof(uint32_t));
    sq_soup_free(&a);
    sq_soup_free(&b);
    io_rmdir(dir);
}

/* Doubles that a careless %g or float conversion would change, a corner
 * without uv, a face too large for a uchar count. */
static void test_exact_values(void **state)
{
    (void)state;
    enum { N = 300 };
    static double pos[3 * N];
    const double special[] = {0.1,     1.0 / 3.0, -0.0,     DBL_MIN,  5e-324,
                              DBL_MAX, -1e-300,   3.141592653589793,     123456789.123456789,
                              -2.5e17, 1e22,      0.30007200000000002};
    for (int k = 0; k < 3 * N; k++)
        pos[k] = k < (int)(sizeof special / sizeof special[0]) ? special[k] : sin(k) * exp(k % 50);
    static uint32_t face_off[N + 1], face_idx[3 * N + N], face_uv[3 * N + N];
    uint32_t nf = 0, nc = 0;
    face_off[0] = 0;
    for (uint32_t f = 0; f + 2 < N; f += 3) { /* triangles 0 1 2, 3 4 5, ... */
        for (uint32_t k = 0; k < 3; k++) {
            face_uv[nc] = (f + k) % 5 == 0 ? SQ_NONE : (f + k) % 7;
            face_idx[nc++] = f + k;
        }
        face_off[++nf] = nc;
    }
    for (uint32_t v = 0; v < N; v++) { /* one face with N corners */
        face_uv[nc] = SQ_NONE;
        face_idx[nc++] = v;
    }
    face_off[++nf] = nc;
    const double uv[14] = {0.1, 0.2, 1.0 / 3.0, -0.0, 5e-324, 1, 2, 3, 4, 5, 6, 7, 8, 2.718281828459045};

    char dir[256], obj[512], ply[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(obj, sizeof obj, "%s/x.obj", dir);
    snprintf(ply, sizeof ply, "%s/x.ply", dir);
    sq_error e;
    sq_soup s;
    if (sq_write_obj(obj, N, pos, nf, face_off, face_idx, 7, uv, face_uv, &e)) fail_msg("%s", e.msg);
    read_or_fail(obj, &s);
    assert_int_equal(s.nv, N);
    assert_int_equal(s.nf, nf);
    assert_memory_equal(s.pos, pos, sizeof pos);
    assert_memory_equal(s.face_off, face_off, (nf + 1) * sizeof(uint32_t));
    assert_memory_equal(s.face_idx, face_idx, nc * sizeof(uint32_t));
    assert_memory_equal(s.uv, uv, sizeof uv);
    assert_memory_equal(s.face_uv, face_uv, nc * sizeof(uint32_t));
    sq_soup_free(&s);

    if (sq_write_ply(ply, N, pos, nf, face_off, face_idx, &e)) fail_msg("%s", e.msg);
    read_or_fail(ply, &s);
    assert_memory_equal(s.pos, pos, sizeof pos);
    assert_memory_equal(s.face_off, face_off, (nf + 1) * sizeof(uint32_t));
    assert_memory_equal(s.face_idx, face_idx, nc * sizeof(uint32_t));
    sq_soup_free(&s);
    /* the valence-300 face needs a wider count type than uchar */
    char *text;
    size_t size;
    assert_int_equal(sq_read_file(ply, &text, &size, &e), SQ_OK);
    assert_non_null(strstr(text, "property list uint int vertex_indices\n"));
    assert_int_equal(strncmp(text, "ply\nformat binary_little_endian 1.0\n", 36), 0);
    free(text);
    io_rmdir(dir);
}

/* sq_format_double: every double (random bit patterns, NaN aside) reads
 * back with the same bits, in no more characters than %.17g uses */
static void test_format_double(void **state)
{
    (void)state;
    uint64_t x = 0x9e3779b97f4a7c15u;
    char buf[SQ_FORMAT_DOUBLE_CAP], ref[64];
    for (int k = 0; k < 200000; k++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        double d;
        uint64_t bits = k % 4 == 0 ? x : (x & 0x800fffffffffffffu) | (uint64_t)(1023 + (int)(x % 64) - 32) << 52;
        memcpy(&d, &bits, sizeof d);
        if (isnan(d)) continue;
        int n = sq_format_double(d, buf);
        assert_int_equal(n, (int)strlen(buf));
        double back = strtod(buf, NULL);
        if (memcmp(&back, &d, sizeof d)) fail_msg("%.17g written as %s reads back as %.17g", d, buf, back);
        int m = snprintf(ref, sizeof ref, "%.17g", d);
        assert_true(n <= m);
    }
    assert_int_equal(sq_format_double(-0.0, buf), 2);
    assert_string_equal(buf, "-0");
    sq_format_double(0.1, buf);
    assert_string_equal(buf, "0.1");
}

static void test_ply_header(void **state)
{
    (void)state;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t off[] = {0, 3}, idx[] = {0, 1, 2};
    char dir[256], ply[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(ply, sizeof ply, "%s/t.ply", dir);
    sq_error e;
    assert_int_equal(sq_write_ply(ply, 3, pos, 1, off, idx, &e), SQ_OK);
    char *text;
    size_t size;
    assert_int_equal(sq_read_file(ply, &text, &size, &e), SQ_OK);
    const char *head = "ply\nformat binary_little_endian 1.0\ncomment written by seamquad\n"
                       "element vertex 3\nproperty double x\nproperty double y\n"
                       "property double z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
    size_t h = strlen(head);
    assert_int_equal(size, h + 9 * 8 + 1 + 3 * 4);
    assert_memory_equal(text, head, h);
    const unsigned char face[] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
    assert_memory_equal(text + h + 72, face, sizeof face);
    const unsigned char one[] = {0, 0, 0, 0, 0, 0, 0xf0, 0x3f}; /* 1.0, little-endian */
    assert_memory_equal(text + h + 24, one, 8);
    free(text);
    io_rmdir(dir);
}

static void test_obj_text(void **state)
{
    (void)state;
    const double pos[] = {0.5, 0, -1, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    const uint32_t off[] = {0, 3, 7}, idx[] = {0, 1, 2, 1, 3, 2, 0};
    const uint32_t fuv[] = {0, 1, SQ_NONE, 1, 1, 0, 0};
    const double uv[] = {0.25, 0.75, 1, 0};
    char dir[256], obj[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    sq_error e;
    assert_int_equal(sq_write_obj(obj, 4, pos, 2, off, idx, 2, uv, fuv, &e), SQ_OK);
    char *text;
    size_t size;
    assert_int_equal(sq_read_file(obj, &text, &size, &e), SQ_OK);
    assert_string_equal(text, "# written by seamquad: 4 vertices, 2 faces\n"
                              "v 0.5 0 -1\nv 1 0 0\nv 0 1 0\nv 1 1 1\n"
                              "vt 0.25 0.75\nvt 1 0\n"
                              "f 1/1 2/2 3\nf 2/2 4/2 3/1 1/1\n");
    free(text);
    io_rmdir(dir);
}

/* Face lines are written a few at a time through one buffer, flushed
 * between tokens when full: the same text as formatting each line on its
 * own (checked against snprintf here), for many faces and for a 1000-gon
 * longer than the buffer. */
static void test_obj_face_buffer(void **state)
{
    (void)state;
    enum { NV = 1000, NTRI = 3000 };
    static double pos[3 * NV];
    static uint32_t off[NTRI + 2], idx[3 * NTRI + NV], fuv[3 * NTRI + NV];
    static double uv[2] = {0.5, 0.25};
    for (uint32_t v = 0; v < NV; v++) pos[3 * v] = v, pos[3 * v + 1] = 0.5 * v, pos[3 * v + 2] = 1;
    uint32_t c = 0;
    for (uint32_t f = 0; f < NTRI; f++) {
        off[f] = c;
        for (uint32_t k = 0; k < 3; k++) {
            idx[c] = (7 * f + 331 * k) % NV;
            fuv[c++] = (f + k) % 3 == 0 ? SQ_NONE : 0;
        }
    }
    off[NTRI] = c; /* the 1000-gon */
    for (uint32_t k = 0; k < NV; k++) idx[c] = k, fuv[c++] = k % 2 ? 0 : SQ_NONE;
    off[NTRI + 1] = c;
    char dir[256], obj[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(obj, sizeof obj, "%s/faces.obj", dir);
    sq_error e;
    assert_int_equal(sq_write_obj(obj, NV, pos, NTRI + 1, off, idx, 1, uv, fuv, &e), SQ_OK);
    char *text;
    size_t size;
    assert_int_equal(sq_read_file(obj, &text, &size, &e), SQ_OK);
    const char *p = strstr(text, "\nf ");
    assert_non_null(p);
    p++;
    char want[16384];
    for (uint32_t f = 0; f <= NTRI; f++) {
        int n = snprintf(want, sizeof want, "f");
        for (uint32_t k = off[f]; k < off[f + 1]; k++)
            n += fuv[k] == SQ_NONE ? snprintf(want + n, sizeof want - (size_t)n, " %u", idx[k] + 1)
                                   : snprintf(want + n, sizeof want - (size_t)n, " %u/%u", idx[k] + 1, fuv[k] + 1);
        n += snprintf(want + n, sizeof want - (size_t)n, "\n");
        assert_true(strncmp(p, want, (size_t)n) == 0);
        p += n;
    }
    assert_int_equal(*p, '\0');
    free(text);
    io_rmdir(dir);
}

static void test_missing_directory(void **state)
{
    (void)state;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t off[] = {0, 3}, idx[] = {0, 1, 2};
    char dir[256], out[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/no/such/dir/m.obj", dir);
    sq_error e;
    expect_error(sq_write_obj(out, 3, pos, 1, off, idx, 0, NULL, NULL, &e), &e, SQ_ERR_IO,
                 "m.obj: cannot create a temporary file next to it: No such file or directory");
    assert_non_null(strstr(e.msg, out));
    snprintf(out, sizeof out, "%s/no/m.ply", dir);
    expect_error(sq_write_ply(out, 3, pos, 1, off, idx, &e), &e, SQ_ERR_IO,
                 "No such file or directory");
    assert_int_equal(io_count_entries(dir), 0);
    expect_error(sq_write_ply("", 3, pos, 1, off, idx, &e), &e, SQ_ERR_ARGUMENT, "missing path");
    snprintf(out, sizeof out, "%s/", dir);
    expect_error(sq_write_ply(out, 3, pos, 1, off, idx, &e), &e, SQ_ERR_IO,
                 "the path names a directory");
    assert_int_equal(io_count_entries(dir), 0);
    io_rmdir(dir);
}

static void test_bad_arguments(void **state)
{
    (void)state;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t off[] = {0, 3}, idx[] = {0, 1, 3}, off2[] = {0, 2}, off3[] = {1, 3};
    const uint32_t good[] = {0, 1, 2}, fuv[] = {0, 5, SQ_NONE};
    const double uv[] = {0, 0};
    char dir[256], out[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/m.obj", dir);
    sq_error e;
    expect_error(sq_write_obj(out, 3, pos, 1, off, idx, 0, NULL, NULL, &e), &e, SQ_ERR_ARGUMENT,
                 "face 0 uses vertex 3, but there are 3 vertices");
    expect_error(sq_write_ply(out, 3, pos, 1, off2, good, &e), &e, SQ_ERR_ARGUMENT,
                 "face 0 has fewer than 3 corners");
    expect_error(sq_write_ply(out, 3, pos, 1, off3, good, &e), &e, SQ_ERR_ARGUMENT,
                 "face_off[0] is 1, not 0");
    expect_error(sq_write_obj(out, 3, pos, 1, off, good, 1, uv, fuv, &e), &e, SQ_ERR_ARGUMENT,
                 "corner 1 uses uv 5, but there are 1");
    expect_error(sq_write_obj(out, 3, pos, 1, off, good, 1, uv, NULL, &e), &e, SQ_ERR_ARGUMENT,
                 "uv given without face_uv");
    expect_error(sq_write_obj(out, 3, NULL, 1, off, good, 0, NULL, NULL, &e), &e,
                 SQ_ERR_ARGUMENT, "NULL mesh array");
    expect_error(sq_write_obj(NULL, 3, pos, 1, off, good, 0, NULL, NULL, &e), &e,
                 SQ_ERR_ARGUMENT, "NULL path");
    assert_int_equal(io_count_entries(dir), 0); /* nothing was created */
    io_rmdir(dir);
}

/* a device is written directly, never replaced by a regular file
 * (`seamquad param ... -o /dev/null` once turned /dev/null into one) */
static void test_atomic_device(void **state)
{
    (void)state;
    struct stat sb;
    if (stat("/dev/null", &sb) != 0 || !S_ISCHR(sb.st_mode)) skip();
    sq_atomic_file af;
    sq_error e;
    assert_int_equal(sq_atomic_open(&af, "/dev/null", &e), SQ_OK);
    assert_null(af.tmp_path);
    fputs("v 0 0 0\n", (FILE *)af.fp);
    assert_int_equal(sq_atomic_commit(&af, &e), SQ_OK);
    assert_int_equal(stat("/dev/null", &sb), 0);
    assert_true(S_ISCHR(sb.st_mode));
    assert_int_equal(sq_atomic_open(&af, "/dev/null", &e), SQ_OK);
    sq_atomic_abort(&af);
    assert_int_equal(stat("/dev/null", &sb), 0);
    assert_true(S_ISCHR(sb.st_mode));
}

static void test_atomic_abort_and_replace(void **state)
{
    (void)state;
    char dir[256], out[512], pre[600];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/target.txt", dir);
    sq_atomic_file af;
    sq_error e;
    /* the temporary file sits next to the target, named .NAME.tmp.XXXXXX */
    assert_int_equal(sq_atomic_open(&af, out, &e), SQ_OK);
    snprintf(pre, sizeof pre, "%s/.target.txt.tmp.", dir);
    assert_int_equal(strncmp(af.tmp_path, pre, strlen(pre)), 0);
    assert_int_equal(strlen(af.tmp_path), strlen(pre) + 6);
    fputs("partial", af.fp);
    assert_int_equal(io_count_entries(dir), 1);
    sq_atomic_abort(&af);
    assert_int_equal(io_count_entries(dir), 0);
    assert_null(af.fp);
    sq_atomic_abort(&af); /* twice is harmless */

    /* commit replaces an existing file; abort leaves it alone */
    io_write_file(out, "old", 3);
    assert_int_equal(sq_atomic_open(&af, out, &e), SQ_OK);
    fputs("new content", af.fp);
    sq_atomic_abort(&af);
    char *text;
    size_t n;
    assert_int_equal(sq_read_file(out, &text, &n, &e), SQ_OK);
    assert_string_equal(text, "old");
    free(text);
    assert_int_equal(sq_atomic_open(&af, out, &e), SQ_OK);
    fputs("new content", af.fp);
    assert_int_equal(sq_atomic_commit(&af, &e), SQ_OK);
    assert_int_equal(sq_read_file(out, &text, &n, &e), SQ_OK);
    assert_string_equal(text, "new content");
    free(text);
    assert_int_equal(io_count_entries(dir), 1);
    expect_error(sq_atomic_commit(&af, &e), &e, SQ_ERR_ARGUMENT, "file not open");

    /* a relative path: the temporary file goes to the current directory */
    char cwd[4096];
    assert_non_null(getcwd(cwd, sizeof cwd));
    assert_int_equal(chdir(dir), 0);
    assert_int_equal(sq_atomic_open(&af, "rel.txt", &e), SQ_OK);
    assert_int_equal(strncmp(af.tmp_path, ".rel.txt.tmp.", 13), 0);
    fputs("x", af.fp);
    assert_int_equal(sq_atomic_commit(&af, &e), SQ_OK);
    assert_int_equal(chdir(cwd), 0);
    assert_int_equal(io_count_entries(dir), 2);
    io_rmdir(dir);
}

/* rename() fails when the target is a non-empty directory: the error names
 * the target and the temporary file is gone. */
static void test_atomic_rename_failure(void **state)
{
    (void)state;
    char dir[256], out[512], inner[600];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/m.obj", dir);
    assert_int_equal(mkdir(out, 0755), 0);
    snprintf(inner, sizeof inner, "%s/keep", out);
    io_write_file(inner, "k", 1);
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t off[] = {0, 3}, idx[] = {0, 1, 2};
    sq_error e;
    expect_error(sq_write_obj(out, 3, pos, 1, off, idx, 0, NULL, NULL, &e), &e, SQ_ERR_IO,
                 "m.obj: cannot replace it (rename): ");
    assert_int_equal(io_count_entries(dir), 1);
    assert_int_equal(io_count_entries(out), 1);
    io_rmdir(dir);
}

/* A write that fails halfway (file size limit: the same path as a full
 * disk) leaves the old file intact and no temporary file. Runs in a child
 * process because it changes the process's limits. */
static void test_write_fails_halfway(void **state)
{
    (void)state;
    char dir[256], out[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/big.obj", dir);
    io_write_file(out, "old content\n", 12);
    sq_soup s;
    read_or_fail(IO_DATA "cid/elephant.obj", &s);
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {100000, 100000};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(2);
        sq_error e;
        sq_status st = write_obj(out, &s, 0, &e);
        int ok = st == SQ_ERR_IO && strstr(e.msg, "big.obj: cannot write: File too large");
        if (!ok) fprintf(stderr, "child: %s %s\n", sq_status_name(st), e.msg);
        sq_status st2 = write_ply(out, &s, &e);
        ok = ok && st2 == SQ_ERR_IO && strstr(e.msg, "File too large");
        if (!ok) fprintf(stderr, "child: %s %s\n", sq_status_name(st2), e.msg);
        _exit(ok ? 0 : 1);
    }
    int wst;
    assert_int_equal(waitpid(pid, &wst, 0), pid);
    assert_true(WIFEXITED(wst));
    assert_int_equal(WEXITSTATUS(wst), 0);
    char *text;
    size_t n;
    sq_error e;
    assert_int_equal(sq_read_file(out, &text, &n, &e), SQ_OK);
    assert_string_equal(text, "old content\n");
    free(text);
    assert_int_equal(io_count_entries(dir), 1);
    sq_soup_free(&s);
    io_rmdir(dir);
}

static void test_permissions(void **state)
{
    (void)state;
    char dir[256], out[512];
    io_mkdtemp(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/p.obj", dir);
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t off[] = {0, 3}, idx[] = {0, 1, 2};
    sq_error e;
    mode_t old = umask(027);
    assert_int_equal(sq_write_obj(out, 3, pos, 1, off, idx, 0, NULL, NULL, &e), SQ_OK);
    struct stat sb;
    assert_int_equal(stat(out, &sb), 0);
    assert_int_equal(sb.st_mode & 0777, 0640); /* 0666 minus the umask, not mkstemp's 0600 */
    assert_int_equal(chmod(out, 0604), 0);
    assert_int_equal(sq_write_ply(out, 3, pos, 1, off, idx, &e), SQ_OK);
    assert_int_equal(stat(out, &sb), 0);
    assert_int_equal(sb.st_mode & 0777, 0604); /* a replaced file keeps its mode */
    umask(old);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_obj_round_trip),
        cmocka_unit_test(test_obj_face_buffer),
        cmocka_unit_test(test_ply_round_trip),
        cmocka_unit_test(test_obj_uv_round_trip),
        cmocka_unit_test(test_exact_values),
        cmocka_unit_test(test_format_double),
        cmocka_unit_test(test_ply_header),
        cmocka_unit_test(test_obj_text),
        cmocka_unit_test(test_missing_directory),
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_atomic_abort_and_replace), cmocka_unit_test(test_atomic_device),
        cmocka_unit_test(test_atomic_rename_failure),
        cmocka_unit_test(test_write_fails_halfway),
        cmocka_unit_test(test_permissions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
