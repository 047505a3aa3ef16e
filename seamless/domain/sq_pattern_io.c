#include "sq_pattern_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"

/* Next integer token; skips whitespace and comments. Returns 0 at the end,
 * -1 on a malformed token (line in *line). */
static int next_int(const char **p, const char *end, long long *out, unsigned *line)
{
    for (;;) {
        while (*p < end && (**p == ' ' || **p == '\t' || **p == '\r' || **p == '\n')) {
            if (**p == '\n') (*line)++;
            (*p)++;
        }
        if (*p < end && **p == '#') {
            while (*p < end && **p != '\n') (*p)++;
            continue;
        }
        break;
    }
    if (*p >= end) return 0;
    char buf[32];
    size_t n = 0;
    while (*p < end && !(**p == ' ' || **p == '\t' || **p == '\r' || **p == '\n' || **p == '#')) {
        if (n + 1 >= sizeof buf) return -1; /* too long for any valid number */
        buf[n++] = **p;
        (*p)++;
    }
    buf[n] = '\0';
    char *e;
    errno = 0;
    long long v = strtoll(buf, &e, 10);
    if (*e || errno || n == 0) return -1;
    *out = v;
    return 1;
}

sq_status sq_pattern_parse(const char *data, size_t size, const char *name, sq_pattern *pat,
                           sq_error *err)
{
    const char *p = data, *end = data + size;
    unsigned line = 1;
    long long v;
    int r = next_int(&p, end, &v, &line);
    if (r <= 0)
        return sq_error_set(err, SQ_ERR_PARSE, "%s:%u: expected the number of sides", name, line);
    if (v < 2 || v > 1000000 || v % 2)
        return sq_error_set(err, SQ_ERR_PARSE, "%s:%u: %lld sides: need an even count >= 2", name,
                            line, v);
    uint32_t k = (uint32_t)v;
    sq_status st = sq_pattern_alloc(pat, k, err);
    if (st) return st;
    for (uint32_t i = 0; i < k; i++) {
        r = next_int(&p, end, &v, &line);
        if (r == 0)
            return sq_error_set(err, SQ_ERR_PARSE, "%s: ends after %u of %u partners", name, i, k);
        if (r < 0 || v < 0 || v >= (long long)k)
            return sq_error_set(err, SQ_ERR_PARSE, "%s:%u: partner of side %u must be in 0..%u",
                                name, line, i, k - 1);
        pat->partner[i] = (uint32_t)v;
    }
    r = next_int(&p, end, &v, &line);
    if (r != 0) {
        for (uint32_t i = 0; i < k; i++) {
            if (i > 0) r = next_int(&p, end, &v, &line);
            if (r <= 0 || (v != 0 && v != 1))
                return sq_error_set(err, SQ_ERR_PARSE,
                                    "%s:%u: straight flag of corner %u must be 0 or 1", name, line,
                                    i);
            pat->straight[i] = (uint8_t)v;
        }
        if (next_int(&p, end, &v, &line) != 0)
            return sq_error_set(err, SQ_ERR_PARSE, "%s:%u: unexpected data after the pattern",
                                name, line);
    }
    st = sq_pattern_validate(pat, NULL, err);
    if (st) {
        char msg[SQ_ERROR_MSG_MAX];
        snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
        return sq_error_set(err, SQ_ERR_PARSE, "%s: invalid pattern: %s", name, msg);
    }
    return SQ_OK;
}

sq_status sq_pattern_read(const char *path, sq_pattern *pat, sq_error *err)
{
    char *data;
    size_t size;
    sq_status st = sq_read_file(path, &data, &size, err);
    if (st) return st;
    st = sq_pattern_parse(data, size, path, pat, err);
    free(data);
    return st;
}
