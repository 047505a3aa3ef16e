/* sq_bench_io: time reading a mesh file (sq_read_mesh) and validating it
 * into a halfedge mesh (sq_mesh_from_soup), separately and together, and
 * measure the peak resident memory per file.
 *
 * Each file is measured in its own child process (fork), so that the peak
 * resident set size (getrusage ru_maxrss) belongs to that file alone. The
 * child runs `warmup` untimed repetitions (to load the file into the page
 * cache), then `reps` timed ones; each repetition reads, builds, and frees
 * everything again. Times come from clock_gettime(CLOCK_MONOTONIC).
 *
 * Usage: sq_bench_io [--reps N] [--warmup N] [--json] [FILE...] */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sq_io.h"
#include "sq_mesh.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

enum { PHASE_READ, PHASE_BUILD, PHASE_TOTAL, PHASE_COUNT };
static const char *const phase_name[PHASE_COUNT] = {"read", "build", "total"};

/* What a child sends back to the parent through a pipe. */
typedef struct bench_result {
    int ok;
    uint32_t nv, nf;
    double median_ms[PHASE_COUNT];
    double min_ms[PHASE_COUNT];
    long base_rss_kb;   /* ru_maxrss before the first read */
    long peak_rss_kb;   /* ru_maxrss at the end             */
    char msg[SQ_ERROR_MSG_MAX + 64];
} bench_result;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static long max_rss_kb(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return -1;
    return ru.ru_maxrss; /* kilobytes on Linux */
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of n values (sorts them). */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int soup_has_polygons(const sq_soup *s)
{
    for (uint32_t f = 0; f < s->nf; f++)
        if (s->face_off[f + 1] - s->face_off[f] != 3) return 1;
    return 0;
}

/* One read + build. times[] gets the phase durations. */
static int run_once(const char *path, double times[PHASE_COUNT], bench_result *res)
{
    sq_soup soup;
    sq_mesh mesh;
    sq_error err;
    memset(&soup, 0, sizeof soup);
    memset(&mesh, 0, sizeof mesh);

    double t0 = now_ms();
    sq_status st = sq_read_mesh(path, &soup, &err);
    double t1 = now_ms();
    if (st != SQ_OK) {
        snprintf(res->msg, sizeof res->msg, "read failed: %s", err.msg);
        return -1;
    }
    /* quad meshes are benchmarked as polygon meshes; the check is outside
     * the timed phases */
    unsigned flags = soup_has_polygons(&soup) ? SQ_MESH_ALLOW_POLYGONS : 0;
    double t2 = now_ms();
    st = sq_mesh_from_soup(&soup, flags, &mesh, &err);
    double t3 = now_ms();
    if (st != SQ_OK) {
        snprintf(res->msg, sizeof res->msg, "validation failed: %s", err.msg);
        sq_soup_free(&soup);
        return -1;
    }
    res->nv = soup.nv;
    res->nf = soup.nf;
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    times[PHASE_READ] = t1 - t0;
    times[PHASE_BUILD] = t3 - t2;
    times[PHASE_TOTAL] = (t1 - t0) + (t3 - t2);
    return 0;
}

/* Runs in the child: measure one file. */
static void measure(const char *path, int reps, int warmup, bench_result *res)
{
    memset(res, 0, sizeof *res);
    double *t[PHASE_COUNT];
    for (int p = 0; p < PHASE_COUNT; p++) {
        t[p] = calloc((size_t)reps, sizeof *t[p]);
        if (!t[p]) {
            snprintf(res->msg, sizeof res->msg, "out of memory");
            return;
        }
    }
    res->base_rss_kb = max_rss_kb();
    double one[PHASE_COUNT];
    int failed = 0;
    for (int i = 0; i < warmup && !failed; i++) failed = run_once(path, one, res) != 0;
    for (int i = 0; i < reps && !failed; i++) {
        failed = run_once(path, one, res) != 0;
        for (int p = 0; p < PHASE_COUNT; p++) t[p][i] = one[p];
    }
    res->peak_rss_kb = max_rss_kb();
    if (!failed) {
        for (int p = 0; p < PHASE_COUNT; p++) {
            res->median_ms[p] = median(t[p], reps);
            res->min_ms[p] = t[p][0]; /* sorted by median() */
        }
        res->ok = 1;
    }
    for (int p = 0; p < PHASE_COUNT; p++) free(t[p]);
}

static int write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static int read_all(int fd, void *buf, size_t n)
{
    char *p = buf;
    while (n) {
        ssize_t k = read(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* Measures `path` in a fresh child process. */
static void measure_in_child(const char *path, int reps, int warmup, bench_result *res)
{
    memset(res, 0, sizeof *res);
    int fd[2];
    if (pipe(fd) != 0) {
        snprintf(res->msg, sizeof res->msg, "pipe: %s", strerror(errno));
        return;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(res->msg, sizeof res->msg, "fork: %s", strerror(errno));
        close(fd[0]);
        close(fd[1]);
        return;
    }
    if (pid == 0) {
        close(fd[0]);
        bench_result r;
        measure(path, reps, warmup, &r);
        _exit(write_all(fd[1], &r, sizeof r) == 0 ? 0 : 1);
    }
    close(fd[1]);
    int got = read_all(fd[0], res, sizeof *res);
    close(fd[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (got != 0) {
        memset(res, 0, sizeof *res);
        if (WIFSIGNALED(status))
            snprintf(res->msg, sizeof res->msg, "child killed by signal %d", WTERMSIG(status));
        else
            snprintf(res->msg, sizeof res->msg, "child exited with status %d and no result",
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
}

static void json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(out, "\\%c", c);
        else if (c < 0x20) fprintf(out, "\\u%04x", c);
        else fputc(c, out);
    }
    fputc('"', out);
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: sq_bench_io [--reps N] [--warmup N] [--json] [FILE...]\n"
            "\n"
            "Times reading a mesh file (sq_read_mesh) and validating it into a\n"
            "halfedge mesh (sq_mesh_from_soup), each phase and both together,\n"
            "and reports the median and minimum over N repetitions in\n"
            "milliseconds, plus the peak resident memory. Every file runs in its\n"
            "own child process, so the peak memory is that file's alone.\n"
            "\n"
            "  --reps N     timed repetitions per file (default 15)\n"
            "  --warmup N   untimed repetitions first (default 1: page cache)\n"
            "  --json       one JSON object on stdout instead of a table\n"
            "  -h, --help   this text\n"
            "\n"
            "Default files: %s/data/cid/elephant.obj and\n"
            "               %s/data/cggs/rolling_stage.off\n",
            SQ_SHARED_DIR, SQ_SHARED_DIR);
}

static int parse_count(const char *opt, const char *s, int min, int *out)
{
    char *end;
    errno = 0;
    long v = s ? strtol(s, &end, 10) : 0;
    if (!s || errno || *end != '\0' || v < min || v > 1000000) {
        fprintf(stderr, "sq_bench_io: %s needs an integer >= %d, got '%s'\n", opt, min, s ? s : "");
        return -1;
    }
    *out = (int)v;
    return 0;
}

int main(int argc, char **argv)
{
    int reps = 15, warmup = 1, json = 0;
    const char **files = calloc((size_t)argc + 2, sizeof *files);
    int nfiles = 0;
    if (!files) return 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--reps") == 0) {
            if (parse_count(a, i + 1 < argc ? argv[++i] : NULL, 1, &reps)) return 2;
        } else if (strcmp(a, "--warmup") == 0) {
            if (parse_count(a, i + 1 < argc ? argv[++i] : NULL, 0, &warmup)) return 2;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "sq_bench_io: unknown option '%s'\n\n", a);
            usage(stderr);
            return 2;
        } else {
            files[nfiles++] = a;
        }
    }
    if (nfiles == 0) {
        files[nfiles++] = SQ_SHARED_DIR "/data/cid/elephant.obj";
        files[nfiles++] = SQ_SHARED_DIR "/data/cggs/rolling_stage.off";
    }

    int failures = 0;
    if (json) printf("{\"reps\": %d, \"warmup\": %d, \"files\": [", reps, warmup);
    else
        printf("%-44s %7s %7s | %-17s | %-17s | %-17s | %8s\n"
               "%-44s %7s %7s | %-17s | %-17s | %-17s | %8s\n",
               "file", "V", "F", "read ms", "build ms", "total ms", "peak RSS",
               "", "", "", "median      min", "median      min", "median      min", "MiB");
    for (int i = 0; i < nfiles; i++) {
        bench_result r;
        measure_in_child(files[i], reps, warmup, &r);
        if (!r.ok) {
            failures++;
            fprintf(stderr, "sq_bench_io: %s: %s\n", files[i], r.msg);
        }
        if (json) {
            printf("%s\n  {\"file\": ", i ? "," : "");
            json_string(stdout, files[i]);
            printf(", \"ok\": %s", r.ok ? "true" : "false");
            if (r.ok) {
                printf(", \"nv\": %u, \"nf\": %u", r.nv, r.nf);
                for (int p = 0; p < PHASE_COUNT; p++)
                    printf(", \"%s_ms\": {\"median\": %.3f, \"min\": %.3f}", phase_name[p],
                           r.median_ms[p], r.min_ms[p]);
                printf(", \"base_rss_kb\": %ld, \"peak_rss_kb\": %ld", r.base_rss_kb, r.peak_rss_kb);
            } else {
                printf(", \"error\": ");
                json_string(stdout, r.msg);
            }
            printf("}");
        } else if (r.ok) {
            /* shared meshes are shown as in MANIFEST.tsv */
            const char *name = files[i];
            const char *shared = SQ_SHARED_DIR "/data/";
            if (strncmp(name, shared, strlen(shared)) == 0) name += strlen(shared);
            printf("%-44s %7u %7u |", name, r.nv, r.nf);
            for (int p = 0; p < PHASE_COUNT; p++) printf(" %7.2f  %7.2f |", r.median_ms[p], r.min_ms[p]);
            printf(" %8.1f\n", (double)r.peak_rss_kb / 1024.0);
        }
        fflush(stdout);
    }
    if (json) printf("\n]}\n");
    else
        printf("\n%d timed repetitions per file after %d warm-up; each file in a fresh child process.\n",
               reps, warmup);
    free(files);
    return failures ? 1 : 0;
}
