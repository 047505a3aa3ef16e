/* seamquad: atomic file output.
 *
 * sq_atomic_open creates `.NAME.tmp.XXXXXX` with mkstemp in the target's
 * directory (so the final rename stays within one file system and is
 * atomic). sq_atomic_commit flushes, fsyncs and closes the temporary file,
 * checking each step, then renames it over the target; any failure removes
 * the temporary file. Readers of the target thus see either the old file or
 * the complete new one, never a partial write, and a failed run leaves no
 * debris. The new file gets the permissions of the file it replaces, or
 * 0666 minus the umask for a new file (mkstemp alone would give 0600).
 *
 * A target that exists and is neither a regular file nor a directory (a
 * device such as /dev/null or /dev/stdout, a FIFO) is written directly:
 * renaming over it would replace the device by a regular file. Such a
 * write cannot be atomic; tmp_path stays NULL. */
#include "sq_io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static sq_status atomic_fail(sq_error *err, const char *what, const char *path, int e)
{
    char msg[256];
    if (strerror_r(e, msg, sizeof msg) != 0) snprintf(msg, sizeof msg, "error %d", e);
    return sq_error_set(err, SQ_ERR_IO, "%s: cannot %s: %s", path, what, msg);
}

/* The process umask, read without changing it (umask(2) can only be read by
 * setting it, which would race with other threads). Linux reports it in
 * /proc/self/status; elsewhere assume the common 022. */
static mode_t current_umask(void)
{
    mode_t m = 022;
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return m;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        unsigned u;
        if (sscanf(line, "Umask: %o", &u) == 1) {
            m = (mode_t)(u & 0777);
            break;
        }
    }
    fclose(f);
    return m;
}

int sq_is_special_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode);
}

sq_status sq_atomic_open(sq_atomic_file *af, const char *path, sq_error *err)
{
    if (!af || !path || !*path)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_atomic_open: missing path");
    memset(af, 0, sizeof *af);
    size_t len = strlen(path);
    if (path[len - 1] == '/')
        return sq_error_set(err, SQ_ERR_IO, "%s: cannot write: the path names a directory", path);
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0; /* keeps the '/' */
    static const char suffix[] = ".tmp.XXXXXX";
    size_t tlen = dirlen + 1 + strlen(base) + sizeof suffix;
    af->tmp_path = malloc(tlen);
    af->path = malloc(len + 1);
    if (!af->tmp_path || !af->path) {
        free(af->tmp_path);
        free(af->path);
        memset(af, 0, sizeof *af);
        return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory", path);
    }
    memcpy(af->path, path, len + 1);
    snprintf(af->tmp_path, tlen, "%.*s.%s%s", (int)dirlen, path, base, suffix);
    if (sq_is_special_file(path)) {
        free(af->tmp_path);
        af->tmp_path = NULL;
        FILE *fp = fopen(path, "wb");
        if (!fp) {
            int e = errno;
            free(af->path);
            memset(af, 0, sizeof *af);
            return atomic_fail(err, "open it for writing", path, e);
        }
        af->fp = fp;
        return SQ_OK;
    }

    int fd = mkstemp(af->tmp_path);
    if (fd < 0) {
        int e = errno;
        sq_status st = atomic_fail(err, "create a temporary file next to it", path, e);
        free(af->tmp_path);
        free(af->path);
        memset(af, 0, sizeof *af);
        return st;
    }
    struct stat sb;
    mode_t mode = stat(path, &sb) == 0 && S_ISREG(sb.st_mode) ? (sb.st_mode & 07777)
                                                             : (0666 & ~current_umask());
    (void)fchmod(fd, mode); /* best effort: the content matters more */
    FILE *fp = fdopen(fd, "wb");
    if (!fp) {
        int e = errno;
        close(fd);
        sq_atomic_abort(af);
        return atomic_fail(err, "open the temporary file", path, e);
    }
    af->fp = fp;
    return SQ_OK;
}

sq_status sq_atomic_commit(sq_atomic_file *af, sq_error *err)
{
    if (!af || !af->fp || !af->path)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_atomic_commit: file not open");
    FILE *fp = af->fp;
    sq_status st = SQ_OK;
    if (!af->tmp_path) { /* a device or FIFO, written directly */
        int bad = ferror(fp);
        if (fflush(fp) != 0 && st == SQ_OK) st = atomic_fail(err, "write", af->path, errno);
        else if (bad) st = sq_error_set(err, SQ_ERR_IO, "%s: cannot write: a write failed", af->path);
        af->fp = NULL;
        if (fclose(fp) != 0 && st == SQ_OK) st = atomic_fail(err, "close", af->path, errno);
        free(af->path);
        memset(af, 0, sizeof *af);
        if (st == SQ_OK) sq_error_clear(err);
        return st;
    }
    int had_error = ferror(fp);
    if (fflush(fp) != 0)
        st = atomic_fail(err, "write", af->path, errno);
    else if (had_error)
        st = sq_error_set(err, SQ_ERR_IO, "%s: cannot write: a write to %s failed", af->path,
                          af->tmp_path);
    else if (fsync(fileno(fp)) != 0)
        st = atomic_fail(err, "sync to disk", af->path, errno);
    af->fp = NULL;
    if (fclose(fp) != 0 && st == SQ_OK) st = atomic_fail(err, "close", af->path, errno);
    if (st == SQ_OK && rename(af->tmp_path, af->path) != 0)
        st = atomic_fail(err, "replace it (rename)", af->path, errno);
    if (st != SQ_OK) {
        sq_atomic_abort(af);
        return st;
    }
    /* Make the rename itself durable: sync the directory (best effort; some
     * file systems refuse fsync on directories). */
    const char *slash = strrchr(af->path, '/');
    char *dir = NULL;
    if (slash) {
        size_t n = slash == af->path ? 1 : (size_t)(slash - af->path);
        dir = malloc(n + 1);
        if (dir) {
            memcpy(dir, af->path, n);
            dir[n] = '\0';
        }
    }
    const char *d = slash ? dir : ".";
    int dfd = d ? open(d, O_RDONLY | O_CLOEXEC) : -1;
    if (dfd >= 0) {
        (void)fsync(dfd);
        close(dfd);
    }
    free(dir);
    free(af->tmp_path);
    free(af->path);
    memset(af, 0, sizeof *af);
    sq_error_clear(err);
    return SQ_OK;
}

void sq_atomic_abort(sq_atomic_file *af)
{
    if (!af) return;
    if (af->fp) fclose(af->fp);
    if (af->tmp_path) unlink(af->tmp_path);
    free(af->tmp_path);
    free(af->path);
    memset(af, 0, sizeof *af);
}
