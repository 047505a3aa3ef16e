/* seamquad: read a whole file into memory. */
#include "sq_io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static sq_status read_fail(const char *path, const char *what, int e, sq_error *err)
{
    char msg[256];
    if (strerror_r(e, msg, sizeof msg) != 0) snprintf(msg, sizeof msg, "error %d", e);
    return sq_error_set(err, SQ_ERR_IO, "%s: cannot %s: %s", path, what, msg);
}

sq_status sq_read_file(const char *path, char **data, size_t *size, sq_error *err)
{
    if (!path || !data || !size)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_read_file: NULL argument");
    *data = NULL;
    *size = 0;
    int fd;
    do {
        fd = open(path, O_RDONLY | O_CLOEXEC);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) return read_fail(path, "open", errno, err);
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        int e = errno;
        close(fd);
        return read_fail(path, "stat", e, err);
    }
    if (S_ISDIR(sb.st_mode)) {
        close(fd);
        return read_fail(path, "read", EISDIR, err);
    }
    /* Regular files: one allocation of the stated size (+1 for the NUL);
     * pipes and devices, or files that grow meanwhile, are read in growing
     * chunks. */
    size_t cap = S_ISREG(sb.st_mode) && (uint64_t)sb.st_size < SIZE_MAX - 1
                     ? (size_t)sb.st_size + 1
                     : 65536;
    char *buf = malloc(cap);
    size_t n = 0;
    if (!buf) {
        close(fd);
        return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory (%zu bytes)", path, cap);
    }
    for (;;) {
        if (n + 1 == cap) {
            if (cap > SIZE_MAX / 2) {
                free(buf);
                close(fd);
                return sq_error_set(err, SQ_ERR_NOMEM, "%s: file too large", path);
            }
            char *b2 = realloc(buf, cap * 2);
            if (!b2) {
                free(buf);
                close(fd);
                return sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory (%zu bytes)", path,
                                    cap * 2);
            }
            buf = b2;
            cap *= 2;
        }
        ssize_t r = read(fd, buf + n, cap - 1 - n);
        if (r < 0) {
            if (errno == EINTR) continue;
            int e = errno;
            free(buf);
            close(fd);
            return read_fail(path, "read", e, err);
        }
        if (r == 0) break;
        n += (size_t)r;
    }
    close(fd);
    buf[n] = '\0';
    *data = buf;
    *size = n;
    sq_error_clear(err);
    return SQ_OK;
}
