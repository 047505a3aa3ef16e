/* seamquad: mesh writers (OBJ text, PLY binary little-endian).
 *
 * Both write through sq_atomic_file: on any failure the target is left as
 * it was and no temporary file remains. Arguments are validated before the
 * file is created, so a bad index never produces a file at all. Doubles
 * are written exactly: in OBJ the shortest decimal that strtod reads back
 * as the same bits (sq_format_double), raw IEEE-754 bytes in PLY. */
#include "sq_format_double.h"
#include "sq_io.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

/* A write failed: errno still holds the reason (the loops stop at the
 * first failure). Removes the temporary file. */
static sq_status write_failed(sq_atomic_file *af, const char *path, sq_error *err)
{
    int e = errno;
    char msg[256];
    if (e == 0 || strerror_r(e, msg, sizeof msg) != 0) snprintf(msg, sizeof msg, "write error");
    sq_atomic_abort(af);
    return sq_error_set(err, SQ_ERR_IO, "%s: cannot write: %s", path, msg);
}

static sq_status check_faces(const char *path, uint32_t nv, const double *pos, uint32_t nf,
                             const uint32_t *face_off, const uint32_t *face_idx, sq_error *err)
{
    if (!path) return sq_error_set(err, SQ_ERR_ARGUMENT, "mesh writer: NULL path");
    if ((nv && !pos) || (nf && (!face_off || !face_idx)))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: NULL mesh array", path);
    if (nv == UINT32_MAX)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: too many vertices", path);
    if (nf && face_off[0] != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: face_off[0] is %" PRIu32 ", not 0", path,
                            face_off[0]);
    for (uint32_t f = 0; f < nf; f++) {
        if (face_off[f + 1] < face_off[f] || face_off[f + 1] - face_off[f] < 3)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "%s: face %" PRIu32 " has fewer than 3 corners", path, f);
        for (uint32_t c = face_off[f]; c < face_off[f + 1]; c++)
            if (face_idx[c] >= nv)
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "%s: face %" PRIu32 " uses vertex %" PRIu32
                                    ", but there are %" PRIu32 " vertices",
                                    path, f, face_idx[c], nv);
    }
    return SQ_OK;
}

/* The decimal digits of v at q (no terminator); returns the end. */
static char *put_decimal(char *q, uint64_t v)
{
    char d[24];
    int n = 0;
    do {
        d[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (n) *q++ = d[--n];
    return q;
}

/* Room for one more face token (at most 22 characters) and a line's end
 * in buf (cap bytes, used of them filled): written out when short of it.
 * Returns the bytes still in buf. */
static size_t face_room(FILE *fp, char *buf, size_t cap, size_t used)
{
    if (used + 24 <= cap) return used;
    fwrite(buf, 1, used, fp);
    return 0;
}

/* One "tag x y [z]" line, each real exact (sq_format_double). */
static void write_reals(FILE *fp, const char *tag, const double *x, int n)
{
    char line[8 + 3 * (SQ_FORMAT_DOUBLE_CAP + 1)], *q = line;
    while (*tag) *q++ = *tag++;
    for (int i = 0; i < n; i++) {
        *q++ = ' ';
        q += sq_format_double(x[i], q);
    }
    *q++ = '\n';
    fwrite(line, 1, (size_t)(q - line), fp);
}

sq_status sq_write_obj(const char *path, uint32_t nv, const double *pos,
                       uint32_t nf, const uint32_t *face_off, const uint32_t *face_idx,
                       uint32_t nuv, const double *uv, const uint32_t *face_uv,
                       sq_error *err)
{
    sq_status st = check_faces(path, nv, pos, nf, face_off, face_idx, err);
    if (st) return st;
    if (uv && !face_uv && nf)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: uv given without face_uv", path);
    if (nuv && !uv) return sq_error_set(err, SQ_ERR_ARGUMENT, "%s: nuv > 0 but uv is NULL", path);
    if (uv) {
        for (uint32_t c = 0; nf && c < face_off[nf]; c++)
            if (face_uv[c] != SQ_NONE && face_uv[c] >= nuv)
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "%s: corner %" PRIu32 " uses uv %" PRIu32
                                    ", but there are %" PRIu32,
                                    path, c, face_uv[c], nuv);
    }

    sq_atomic_file af;
    st = sq_atomic_open(&af, path, err);
    if (st) return st;
    errno = 0;
    FILE *fp = af.fp;
    fprintf(fp, "# written by seamquad: %" PRIu32 " vertices, %" PRIu32 " faces\n", nv, nf);
    for (uint32_t v = 0; v < nv && !ferror(fp); v++) write_reals(fp, "v", pos + 3 * (size_t)v, 3);
    for (uint32_t t = 0; uv && t < nuv && !ferror(fp); t++) write_reals(fp, "vt", uv + 2 * (size_t)t, 2);
    /* face lines: integers only, formatted by hand (fprintf per index was
     * a third of the time of writing a large mesh) into one buffer written
     * when the next corner might not fit (one stdio call per token was a
     * quarter of what remained); a token takes at most 22 characters
     * (" " + 10 digits + "/" + 10 digits), a line's end one more */
    char buf[4096];
    size_t used = 0;
    for (uint32_t f = 0; f < nf && !ferror(fp); f++) {
        used = face_room(fp, buf, sizeof buf, used);
        buf[used++] = 'f';
        for (uint32_t c = face_off[f]; c < face_off[f + 1]; c++) {
            used = face_room(fp, buf, sizeof buf, used);
            char *q = buf + used;
            *q++ = ' ';
            q = put_decimal(q, face_idx[c] + 1);
            if (uv && face_uv[c] != SQ_NONE) {
                *q++ = '/';
                q = put_decimal(q, face_uv[c] + 1);
            }
            used = (size_t)(q - buf);
        }
        buf[used++] = '\n';
    }
    if (used && !ferror(fp)) fwrite(buf, 1, used, fp);
    if (ferror(fp)) return write_failed(&af, path, err);
    return sq_atomic_commit(&af, err);
}

/* Little-endian encoders into a byte buffer. */
static unsigned char *put_u32(unsigned char *p, uint32_t v)
{
    for (int k = 0; k < 4; k++) p[k] = (unsigned char)(v >> (8 * k));
    return p + 4;
}

static unsigned char *put_f64(unsigned char *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    for (int k = 0; k < 8; k++) p[k] = (unsigned char)(v >> (8 * k));
    return p + 8;
}

enum { PLY_CHUNK = 1 << 16 };

/* Flushes the chunk when fewer than 8 bytes (one value) are free; returns
 * where to write next. */
static unsigned char *ply_room(FILE *fp, unsigned char *buf, size_t cap, unsigned char *p)
{
    if ((size_t)(buf + cap - p) >= 8) return p;
    fwrite(buf, 1, (size_t)(p - buf), fp);
    return buf;
}

sq_status sq_write_ply(const char *path, uint32_t nv, const double *pos,
                       uint32_t nf, const uint32_t *face_off, const uint32_t *face_idx,
                       sq_error *err)
{
    sq_status st = check_faces(path, nv, pos, nf, face_off, face_idx, err);
    if (st) return st;
    uint32_t max_valence = 0;
    for (uint32_t f = 0; f < nf; f++)
        if (face_off[f + 1] - face_off[f] > max_valence) max_valence = face_off[f + 1] - face_off[f];
    /* uchar counts and int indices, what every PLY reader knows; wider
     * types only where the mesh needs them */
    const char *count_type = max_valence <= 255 ? "uchar" : "uint";
    const char *index_type = nv <= INT32_MAX ? "int" : "uint";

    sq_atomic_file af;
    st = sq_atomic_open(&af, path, err);
    if (st) return st;
    errno = 0;
    FILE *fp = af.fp;
    fprintf(fp,
            "ply\nformat binary_little_endian 1.0\ncomment written by seamquad\n"
            "element vertex %" PRIu32 "\nproperty double x\nproperty double y\n"
            "property double z\nelement face %" PRIu32 "\nproperty list %s %s vertex_indices\n"
            "end_header\n",
            nv, nf, count_type, index_type);

    /* encode into a chunk, flushed whenever fewer than 8 bytes are free */
    unsigned char buf[PLY_CHUNK];
    unsigned char *p = buf;
    for (uint32_t v = 0; v < nv && !ferror(fp); v++) {
        for (int k = 0; k < 3; k++) {
            p = ply_room(fp, buf, sizeof buf, p);
            p = put_f64(p, pos[3 * (size_t)v + (size_t)k]);
        }
    }
    for (uint32_t f = 0; f < nf && !ferror(fp); f++) {
        uint32_t n = face_off[f + 1] - face_off[f];
        p = ply_room(fp, buf, sizeof buf, p);
        if (max_valence <= 255)
            *p++ = (unsigned char)n;
        else
            p = put_u32(p, n);
        for (uint32_t c = face_off[f]; c < face_off[f + 1]; c++) {
            p = ply_room(fp, buf, sizeof buf, p);
            p = put_u32(p, face_idx[c]);
        }
    }
    fwrite(buf, 1, (size_t)(p - buf), fp);
    if (ferror(fp)) return write_failed(&af, path, err);
    return sq_atomic_commit(&af, err);
}
