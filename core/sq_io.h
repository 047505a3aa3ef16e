/* seamquad: mesh file readers and writers (hand-written C; see docs/io.md).
 *
 * Readers fill a caller-provided sq_soup (free it with sq_soup_free) and
 * never alter content: see sq_soup.h. Writers write to a temporary file in
 * the target's directory and rename it over the target only on success, so
 * a failure leaves no half-written output. */
#ifndef SQ_IO_H
#define SQ_IO_H

#include "sq_error.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sq_file_format {
    SQ_FORMAT_UNKNOWN = 0,
    SQ_FORMAT_OBJ,
    SQ_FORMAT_OFF,
    SQ_FORMAT_PLY
} sq_file_format;

/* Format from the file name's extension (case-insensitive). */
sq_file_format sq_format_from_path(const char *path);

/* Reads OBJ, OFF or PLY chosen by extension. */
sq_status sq_read_mesh(const char *path, sq_soup *out, sq_error *err);

/* Parsers over an in-memory buffer (used by the file readers and by the
 * fuzz targets). `name` is used in messages and stored in out->path. */
sq_status sq_parse_obj(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err);
sq_status sq_parse_off(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err);
sq_status sq_parse_ply(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err);

/* Reads a whole file into a malloc'ed, NUL-terminated buffer. */
sq_status sq_read_file(const char *path, char **data, size_t *size, sq_error *err);

/* OBJ writer: `v` lines (%.17g, exact round trip), optional `vt` lines and
 * faces of any valence. With uv != NULL, corner c of the face list uses
 * uv index face_uv[c] and faces are written as `f v/vt`. */
sq_status sq_write_obj(const char *path, uint32_t nv, const double *pos,
                       uint32_t nf, const uint32_t *face_off, const uint32_t *face_idx,
                       uint32_t nuv, const double *uv, const uint32_t *face_uv,
                       sq_error *err);

/* PLY writer (binary little-endian, double coordinates, int32 indices,
 * faces of any valence). */
sq_status sq_write_ply(const char *path, uint32_t nv, const double *pos,
                       uint32_t nf, const uint32_t *face_off, const uint32_t *face_idx,
                       sq_error *err);

/* 1 if `path` exists and is neither a regular file nor a directory (a
 * device such as /dev/null, a FIFO): written in place, never renamed over. */
int sq_is_special_file(const char *path);

/* Atomic output: open a temporary file next to `path`; commit renames it
 * over `path`; abort removes it. An existing target that is neither a
 * regular file nor a directory (/dev/null, a FIFO) is written directly
 * (tmp_path NULL), never replaced. */
typedef struct sq_atomic_file {
    void *fp;          /* FILE *                                   */
    char *tmp_path;
    char *path;
} sq_atomic_file;

sq_status sq_atomic_open(sq_atomic_file *af, const char *path, sq_error *err);
sq_status sq_atomic_commit(sq_atomic_file *af, sq_error *err);
void sq_atomic_abort(sq_atomic_file *af);

#ifdef __cplusplus
}
#endif
#endif
