/* seamquad: Wavefront OBJ parser (polygon subset). Rules: docs/io.md.
 *
 * One pass over the lines, appending to growable arrays (no per-line
 * allocation). Positive indices may refer forward and are range-checked
 * once the whole file is read; negative (relative) indices are resolved
 * against the elements defined before their line, as the format says. */
#include "sq_io.h"
#include "sq_text.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#define OBJ_MAX_COUNT (UINT32_MAX - 1) /* SQ_NONE is reserved */

typedef struct obj_parser {
    const char *name;   /* for messages */
    sq_error *err;

    uint32_t nv, nuv, nvn, nf;
    size_t ncorner;

    double *pos;        size_t pos_cap;      /* 3 per vertex        */
    uint32_t *vline;    size_t vline_cap;
    double *uv;         size_t uv_cap;       /* 2 per uv            */
    uint32_t *foff;     size_t foff_cap;     /* nf+1                */
    uint32_t *fline;    size_t fline_cap;
    uint32_t *fidx;     size_t fidx_cap;
    uint32_t *fuv;      size_t fuv_cap;
    int any_uv;

    /* largest normal index used (1-based) and where, checked at the end */
    uint64_t max_normal;
    uint32_t max_normal_line;
} obj_parser;

static sq_status obj_nomem(obj_parser *P)
{
    return sq_error_set(P->err, SQ_ERR_NOMEM, "%s: out of memory while reading", P->name);
}

static sq_status obj_bad_number(obj_parser *P, uint32_t line, sq_span tok,
                                int k, const char *what)
{
    char q[200];
    return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: bad number '%s' (value %d of %s)",
                        P->name, line, sq_span_quote(tok, q, sizeof q), k, what);
}

/* Reads up to `max` numbers from the rest of a line. *n is the count read;
 * more than `max` values is reported as an error by the caller through
 * *too_many. */
static sq_status obj_numbers(obj_parser *P, sq_span rest, uint32_t line, const char *what,
                             double *vals, int max, int *n, int *too_many)
{
    sq_span tok;
    *n = 0;
    *too_many = 0;
    while (sq_span_next_token(&rest, &tok)) {
        if (*n == max) {
            *too_many = 1;
            return SQ_OK;
        }
        if (sq_span_to_double(tok, &vals[*n]) != 0) return obj_bad_number(P, line, tok, *n + 1, what);
        (*n)++;
    }
    return SQ_OK;
}

/* `v x y z`, `v x y z w` (w must be 1) or `v x y z r g b` (colour ignored). */
static sq_status obj_vertex(obj_parser *P, sq_span rest, uint32_t line)
{
    double val[7];
    int n, too_many;
    sq_status st = obj_numbers(P, rest, line, "the vertex", val, 7, &n, &too_many);
    if (st) return st;
    if (too_many || (n != 3 && n != 4 && n != 6))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: vertex has %s%d values; expected 'v x y z', 'v x y z w' "
                            "or 'v x y z r g b'",
                            P->name, line, too_many ? "more than " : "", n);
    if (n == 4 && val[3] != 1.0)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: vertex has homogeneous weight w = %g; only w = 1 is "
                            "supported (dividing by w would change the coordinates)",
                            P->name, line, val[3]);
    if (P->nv == OBJ_MAX_COUNT)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many vertices (limit %u)",
                            P->name, line, OBJ_MAX_COUNT);
    if (sq_reserve((void **)&P->pos, &P->pos_cap, 3 * (size_t)P->nv + 3, sizeof *P->pos) ||
        sq_reserve((void **)&P->vline, &P->vline_cap, (size_t)P->nv + 1, sizeof *P->vline))
        return obj_nomem(P);
    memcpy(P->pos + 3 * (size_t)P->nv, val, 3 * sizeof(double));
    P->vline[P->nv++] = line;
    return SQ_OK;
}

/* `vt u [v [w]]`: v defaults to 0, w is not stored (uv is 2D). */
static sq_status obj_texcoord(obj_parser *P, sq_span rest, uint32_t line)
{
    double val[3];
    int n, too_many;
    sq_status st = obj_numbers(P, rest, line, "the texture coordinate", val, 3, &n, &too_many);
    if (st) return st;
    if (too_many || n == 0)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: texture coordinate has %s%d values; expected 'vt u [v [w]]'",
                            P->name, line, too_many ? "more than " : "", n);
    if (P->nuv == OBJ_MAX_COUNT)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many texture coordinates",
                            P->name, line);
    if (sq_reserve((void **)&P->uv, &P->uv_cap, 2 * (size_t)P->nuv + 2, sizeof *P->uv))
        return obj_nomem(P);
    P->uv[2 * (size_t)P->nuv] = val[0];
    P->uv[2 * (size_t)P->nuv + 1] = n >= 2 ? val[1] : 0.0;
    P->nuv++;
    return SQ_OK;
}

/* `vn x y z`: checked and counted (faces may refer to normals), not stored. */
static sq_status obj_normal(obj_parser *P, sq_span rest, uint32_t line)
{
    double val[3];
    int n, too_many;
    sq_status st = obj_numbers(P, rest, line, "the normal", val, 3, &n, &too_many);
    if (st) return st;
    if (too_many || n != 3)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: normal has %s%d values; expected 'vn x y z'", P->name,
                            line, too_many ? "more than " : "", n);
    if (P->nvn == OBJ_MAX_COUNT)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many normals", P->name, line);
    P->nvn++;
    return SQ_OK;
}

/* Resolves one index of a face corner to 0-based. `defined` is how many
 * elements of that kind precede this line (for relative indices). Positive
 * indices are only checked against OBJ_MAX_COUNT here; the range check
 * against the final count happens in obj_check_indices. */
static sq_status obj_index(obj_parser *P, sq_span tok, uint32_t defined, const char *kind,
                           uint32_t line, size_t corner, uint64_t *out)
{
    char q[200];
    int64_t k;
    if (sq_span_to_int(tok, &k) != 0)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: bad %s index '%s' in face corner %zu",
                            P->name, line, kind, sq_span_quote(tok, q, sizeof q), corner);
    if (k == 0)
        return sq_error_set(P->err, SQ_ERR_INDEX,
                            "%s:%u: %s index 0 in face corner %zu (OBJ indices start at 1)",
                            P->name, line, kind, corner);
    if (k < 0) {
        if (-k > (int64_t)defined)
            return sq_error_set(P->err, SQ_ERR_INDEX,
                                "%s:%u: relative %s index %s in face corner %zu reaches before "
                                "the first %s (%u defined before this line)",
                                P->name, line, kind, sq_span_quote(tok, q, sizeof q), corner,
                                kind, defined);
        *out = (uint64_t)((int64_t)defined + k);
        return SQ_OK;
    }
    if (k > (int64_t)OBJ_MAX_COUNT)
        return sq_error_set(P->err, SQ_ERR_INDEX,
                            "%s:%u: %s index %s in face corner %zu is out of range", P->name,
                            line, kind, sq_span_quote(tok, q, sizeof q), corner);
    *out = (uint64_t)(k - 1);
    return SQ_OK;
}

/* Splits a corner `a`, `a/b`, `a/b/c` or `a//c` into its parts. Returns the
 * number of parts (1..3), or 0 when there are more than two slashes. */
static int obj_split_corner(sq_span tok, sq_span part[3])
{
    int np = 0;
    const char *b = tok.b;
    for (const char *p = tok.b; p <= tok.e; p++) {
        if (p == tok.e || *p == '/') {
            if (np == 3) return 0;
            part[np].b = b;
            part[np].e = p;
            np++;
            b = p + 1;
        }
    }
    return np;
}

/* `f c1 c2 c3 ...` with corners as in obj_split_corner. */
static sq_status obj_face(obj_parser *P, sq_span rest, uint32_t line)
{
    char q[200];
    size_t first = P->ncorner;
    sq_span tok;
    while (sq_span_next_token(&rest, &tok)) {
        size_t corner = P->ncorner - first + 1;
        sq_span part[3];
        int np = obj_split_corner(tok, part);
        int bad = np == 0 || sq_span_len(part[0]) == 0 ||
                  (np == 2 && sq_span_len(part[1]) == 0) ||
                  (np == 3 && sq_span_len(part[2]) == 0);
        if (bad)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: bad face corner '%s' (corner %zu); expected v, v/vt, "
                                "v/vt/vn or v//vn",
                                P->name, line, sq_span_quote(tok, q, sizeof q), corner);
        uint64_t vi, ti = SQ_NONE, ni;
        sq_status st = obj_index(P, part[0], P->nv, "vertex", line, corner, &vi);
        if (st) return st;
        if (np >= 2 && sq_span_len(part[1]) > 0) {
            st = obj_index(P, part[1], P->nuv, "texture coordinate", line, corner, &ti);
            if (st) return st;
            P->any_uv = 1;
        }
        if (np == 3) {
            st = obj_index(P, part[2], P->nvn, "normal", line, corner, &ni);
            if (st) return st;
            if (ni + 1 > P->max_normal) {
                P->max_normal = ni + 1;
                P->max_normal_line = line;
            }
        }
        if (P->ncorner == OBJ_MAX_COUNT)
            return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many face corners in the file",
                                P->name, line);
        if (sq_reserve((void **)&P->fidx, &P->fidx_cap, P->ncorner + 1, sizeof *P->fidx) ||
            sq_reserve((void **)&P->fuv, &P->fuv_cap, P->ncorner + 1, sizeof *P->fuv))
            return obj_nomem(P);
        P->fidx[P->ncorner] = (uint32_t)vi;
        P->fuv[P->ncorner] = (uint32_t)ti;
        P->ncorner++;
    }
    size_t n = P->ncorner - first;
    if (n < 3)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: face has %zu corner%s; a face needs at least 3", P->name, line,
                            n, n == 1 ? "" : "s");
    if (P->nf == OBJ_MAX_COUNT)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many faces", P->name, line);
    if (sq_reserve((void **)&P->foff, &P->foff_cap, (size_t)P->nf + 2, sizeof *P->foff) ||
        sq_reserve((void **)&P->fline, &P->fline_cap, (size_t)P->nf + 1, sizeof *P->fline))
        return obj_nomem(P);
    P->foff[0] = 0;
    P->foff[P->nf + 1] = (uint32_t)P->ncorner;
    P->fline[P->nf] = line;
    P->nf++;
    return SQ_OK;
}

/* After the whole file: every positive index must name an existing element. */
static sq_status obj_check_indices(obj_parser *P)
{
    for (uint32_t f = 0; f < P->nf; f++) {
        for (uint32_t c = P->foff[f]; c < P->foff[f + 1]; c++) {
            uint32_t corner = c - P->foff[f] + 1;
            if (P->fidx[c] >= P->nv)
                return sq_error_set(P->err, SQ_ERR_INDEX,
                                    "%s:%u: face corner %u refers to vertex %llu, but the file "
                                    "has only %u vertices",
                                    P->name, P->fline[f], corner,
                                    (unsigned long long)P->fidx[c] + 1, P->nv);
            if (P->fuv[c] != SQ_NONE && P->fuv[c] >= P->nuv)
                return sq_error_set(P->err, SQ_ERR_INDEX,
                                    "%s:%u: face corner %u refers to texture coordinate %llu, "
                                    "but the file has only %u",
                                    P->name, P->fline[f], corner,
                                    (unsigned long long)P->fuv[c] + 1, P->nuv);
        }
    }
    if (P->max_normal > P->nvn)
        return sq_error_set(P->err, SQ_ERR_INDEX,
                            "%s:%u: a face corner refers to normal %llu, but the file has only "
                            "%u normals",
                            P->name, P->max_normal_line, (unsigned long long)P->max_normal,
                            P->nvn);
    return SQ_OK;
}

static void obj_free(obj_parser *P)
{
    free(P->pos);
    free(P->vline);
    free(P->uv);
    free(P->foff);
    free(P->fline);
    free(P->fidx);
    free(P->fuv);
}

/* Statements whose content cannot change the surface (object and group
 * names, smoothing groups, materials): skipped without parsing. */
static int obj_ignored_keyword(sq_span kw)
{
    return sq_span_eq(kw, "o") || sq_span_eq(kw, "g") || sq_span_eq(kw, "s") ||
           sq_span_eq(kw, "usemtl") || sq_span_eq(kw, "mtllib");
}

static sq_status obj_unknown(obj_parser *P, sq_span kw, sq_span line, uint32_t lineno)
{
    char q[200];
    if (sq_span_has_binary(line))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: line holds binary data (bytes that never occur in text): "
                            "not an OBJ file",
                            P->name, lineno);
    if (sq_span_eq(kw, "l") || sq_span_eq(kw, "p"))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: '%s' (%s element) is not supported: a surface mesh file "
                            "must contain only faces",
                            P->name, lineno, kw.b[0] == 'l' ? "l" : "p",
                            kw.b[0] == 'l' ? "line" : "point");
    return sq_error_set(P->err, SQ_ERR_PARSE,
                        "%s:%u: unknown or unsupported OBJ statement '%s' (supported: v, vt, vn, "
                        "f, and ignored o, g, s, usemtl, mtllib, #)",
                        P->name, lineno, sq_span_quote(kw, q, sizeof q));
}

sq_status sq_parse_obj(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err)
{
    if (!out || (!data && size))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_parse_obj: NULL argument");
    memset(out, 0, sizeof *out);
    if (!data) data = ""; /* size is 0: avoid arithmetic on NULL */
    obj_parser P;
    memset(&P, 0, sizeof P);
    P.name = name ? name : "(buffer)";
    P.err = err;

    sq_text t;
    sq_text_init(&t, data, size);
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) t.p += 3; /* UTF-8 BOM */

    sq_status st = SQ_OK;
    sq_span line;
    while (st == SQ_OK && sq_text_next_line(&t, &line)) {
        sq_span rest = line, kw;
        sq_span_strip_comment(&rest);
        if (!sq_span_next_token(&rest, &kw)) continue;
        if (sq_span_eq(kw, "v"))
            st = obj_vertex(&P, rest, t.line);
        else if (sq_span_eq(kw, "f"))
            st = obj_face(&P, rest, t.line);
        else if (sq_span_eq(kw, "vt"))
            st = obj_texcoord(&P, rest, t.line);
        else if (sq_span_eq(kw, "vn"))
            st = obj_normal(&P, rest, t.line);
        else if (!obj_ignored_keyword(kw))
            st = obj_unknown(&P, kw, line, t.line);
    }
    if (st == SQ_OK && P.nv == 0 && P.nf == 0)
        st = sq_error_set(err, SQ_ERR_EMPTY, "%s: no vertices and no faces (empty OBJ file)",
                          P.name);
    if (st == SQ_OK) st = obj_check_indices(&P);
    if (st == SQ_OK && P.nf == 0)
        st = sq_error_set(err, SQ_ERR_EMPTY, "%s: no faces ('f' lines); %u vertices", P.name,
                          P.nv);
    if (st == SQ_OK && sq_strdup_opt(name, &out->path)) st = obj_nomem(&P);
    if (st != SQ_OK) {
        obj_free(&P);
        sq_soup_free(out);
        return st;
    }

    assert(P.foff && P.foff[0] == 0 && P.foff[P.nf] == P.ncorner);
    out->nv = P.nv;
    out->pos = sq_shrink(P.pos, 3 * (size_t)P.nv, sizeof *P.pos);
    out->vert_line = sq_shrink(P.vline, P.nv, sizeof *P.vline);
    out->nf = P.nf;
    out->face_off = sq_shrink(P.foff, (size_t)P.nf + 1, sizeof *P.foff);
    out->face_line = sq_shrink(P.fline, P.nf, sizeof *P.fline);
    out->face_idx = sq_shrink(P.fidx, P.ncorner, sizeof *P.fidx);
    out->nuv = P.nuv;
    out->uv = sq_shrink(P.uv, 2 * (size_t)P.nuv, sizeof *P.uv);
    if (P.any_uv) {
        out->face_uv = sq_shrink(P.fuv, P.ncorner, sizeof *P.fuv);
    } else {
        free(P.fuv);
        out->face_uv = NULL;
    }
    out->line_kind = 0;
    sq_error_clear(err);
    return SQ_OK;
}
