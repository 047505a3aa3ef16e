#include "sq_error.h"

#include <stdarg.h>
#include <stdio.h>

sq_status sq_error_set(sq_error *err, sq_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return code;
}

void sq_error_clear(sq_error *err)
{
    if (err) {
        err->code = SQ_OK;
        err->msg[0] = '\0';
    }
}

const char *sq_status_name(sq_status code)
{
    static const char *const names[SQ_STATUS_COUNT] = {
        [SQ_OK] = "ok",
        [SQ_ERR_IO] = "io",
        [SQ_ERR_NOMEM] = "out-of-memory",
        [SQ_ERR_PARSE] = "parse",
        [SQ_ERR_FORMAT] = "format",
        [SQ_ERR_EMPTY] = "empty",
        [SQ_ERR_INDEX] = "index-out-of-range",
        [SQ_ERR_NOT_FINITE] = "not-finite",
        [SQ_ERR_POLYGON] = "polygon",
        [SQ_ERR_REPEATED_VERTEX] = "repeated-vertex",
        [SQ_ERR_UNREFERENCED] = "unreferenced-vertex",
        [SQ_ERR_NONMANIFOLD_EDGE] = "non-manifold-edge",
        [SQ_ERR_ORIENTATION] = "orientation",
        [SQ_ERR_BOUNDARY] = "boundary",
        [SQ_ERR_NONMANIFOLD_VERTEX] = "non-manifold-vertex",
        [SQ_ERR_COMPONENTS] = "components",
        [SQ_ERR_DEGENERATE] = "degenerate-face",
        [SQ_ERR_CONE_COUNT] = "cone-count",
        [SQ_ERR_CONE_VALUE] = "cone-value",
        [SQ_ERR_GAUSS_BONNET] = "gauss-bonnet",
        [SQ_ERR_UNREALIZABLE] = "unrealizable",
        [SQ_ERR_SOLVER] = "solver",
        [SQ_ERR_ARGUMENT] = "argument",
        [SQ_ERR_INTERNAL] = "internal",
    };
    if ((unsigned)code >= SQ_STATUS_COUNT || !names[code]) return "unknown";
    return names[code];
}
