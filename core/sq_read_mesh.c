/* seamquad: read a mesh file, choosing the parser by the file extension. */
#include "sq_io.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* The extension: the text after the last '.' of the last path component,
 * or NULL when there is none. */
static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? dot + 1 : NULL;
}

static int ext_is(const char *ext, const char *want)
{
    for (; *ext && *want; ext++, want++)
        if (tolower((unsigned char)*ext) != *want) return 0;
    return *ext == '\0' && *want == '\0';
}

sq_file_format sq_format_from_path(const char *path)
{
    const char *ext = path ? extension(path) : NULL;
    if (!ext) return SQ_FORMAT_UNKNOWN;
    if (ext_is(ext, "obj")) return SQ_FORMAT_OBJ;
    if (ext_is(ext, "off")) return SQ_FORMAT_OFF;
    if (ext_is(ext, "ply")) return SQ_FORMAT_PLY;
    return SQ_FORMAT_UNKNOWN;
}

sq_status sq_read_mesh(const char *path, sq_soup *out, sq_error *err)
{
    if (!path || !out) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_read_mesh: NULL argument");
    memset(out, 0, sizeof *out);
    sq_file_format fmt = sq_format_from_path(path);
    if (fmt == SQ_FORMAT_UNKNOWN) {
        const char *ext = extension(path);
        if (ext)
            return sq_error_set(err, SQ_ERR_FORMAT,
                                "%s: unknown mesh file extension '.%s' (supported: .obj, .off, "
                                ".ply)",
                                path, ext);
        return sq_error_set(err, SQ_ERR_FORMAT,
                            "%s: no file extension to tell the format (supported: .obj, .off, "
                            ".ply)",
                            path);
    }
    char *data;
    size_t size;
    sq_status st = sq_read_file(path, &data, &size, err);
    if (st) return st;
    switch (fmt) {
    case SQ_FORMAT_OBJ: st = sq_parse_obj(data, size, path, out, err); break;
    case SQ_FORMAT_OFF: st = sq_parse_off(data, size, path, out, err); break;
    case SQ_FORMAT_PLY: st = sq_parse_ply(data, size, path, out, err); break;
    default: st = sq_error_set(err, SQ_ERR_INTERNAL, "%s: bad format", path); break;
    }
    free(data);
    return st;
}
