/* seamquad: OFF parser (Geomview object file format, ASCII). Rules:
 * docs/io.md.
 *
 * Line based: the header keyword, the counts line, one vertex per line and
 * one face per line; '#' starts a comment anywhere and blank lines are
 * skipped. Arrays are sized from the counts only after checking that the
 * rest of the file is long enough to hold that many elements, so a lying
 * header cannot make us allocate more than a small multiple of the file. */
#include "sq_io.h"
#include "sq_text.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* Shortest possible element lines: "0 0 0\n" and "3 0 0 0\n". */
#define OFF_MIN_VERTEX_BYTES 6
#define OFF_MIN_FACE_BYTES 8

typedef struct off_parser {
    const char *name;
    sq_error *err;
    sq_text t;
    /* per-vertex values after x y z allowed by the header keyword */
    int extra_min, extra_max;
    char keyword[8];
} off_parser;

/* Next line that is not blank after removing its comment; 0 at the end. */
static int off_next_content_line(off_parser *P, sq_span *line)
{
    while (sq_text_next_line(&P->t, line)) {
        sq_span_strip_comment(line);
        if (!sq_span_is_blank(*line)) return 1;
    }
    return 0;
}

/* Header keyword [ST][C][N]OFF. Returns 0 and sets the extra value counts,
 * or -1 for anything else. */
static int off_keyword(off_parser *P, sq_span kw)
{
    const char *p = kw.b;
    int st = 0, c = 0, n = 0;
    if (kw.e - p >= 2 && p[0] == 'S' && p[1] == 'T') { st = 1; p += 2; }
    if (p < kw.e && *p == 'C') { c = 1; p++; }
    if (p < kw.e && *p == 'N') { n = 1; p++; }
    if (kw.e - p != 3 || memcmp(p, "OFF", 3) != 0) return -1;
    /* order on a vertex line: x y z [nx ny nz] [r g b [a]] [s t] */
    P->extra_min = 3 * n + 3 * c + 2 * st;
    P->extra_max = P->extra_min + c;
    size_t len = sq_span_len(kw);
    memcpy(P->keyword, kw.b, len);
    P->keyword[len] = '\0';
    return 0;
}

/* Parses a count token (a non-negative integer). */
static sq_status off_count(off_parser *P, sq_span tok, const char *what, int64_t *out)
{
    char q[200];
    if (sq_span_to_int(tok, out) != 0)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: bad %s count '%s'", P->name,
                            P->t.line, what, sq_span_quote(tok, q, sizeof q));
    if (*out < 0)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: negative %s count %s", P->name,
                            P->t.line, what, sq_span_quote(tok, q, sizeof q));
    return SQ_OK;
}

/* `nv nf [ne]` from the rest of a line (ne is not used: edges are implied
 * by the faces, and many files write 0 there). */
static sq_status off_counts(off_parser *P, sq_span rest, int64_t *nv, int64_t *nf)
{
    sq_span tok[4];
    int n = 0;
    while (n < 4 && sq_span_next_token(&rest, &tok[n])) n++;
    if (n < 2 || n > 3)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: expected the counts 'vertices faces [edges]', found %s%d "
                            "values",
                            P->name, P->t.line, n == 4 ? "more than " : "", n == 4 ? 3 : n);
    int64_t ne;
    sq_status st = off_count(P, tok[0], "vertex", nv);
    if (!st) st = off_count(P, tok[1], "face", nf);
    if (!st && n == 3) st = off_count(P, tok[2], "edge", &ne);
    if (st) return st;
    if (*nv > (int64_t)UINT32_MAX - 1 || *nf > (int64_t)UINT32_MAX - 1)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: counts %lld vertices, %lld faces "
                            "exceed the limit of %u",
                            P->name, P->t.line, (long long)*nv, (long long)*nf, UINT32_MAX - 1);
    /* never allocate for elements the file cannot contain */
    uint64_t left = (uint64_t)(P->t.end - P->t.p);
    uint64_t need = (uint64_t)*nv * OFF_MIN_VERTEX_BYTES + (uint64_t)*nf * OFF_MIN_FACE_BYTES;
    if (need > left + 1) /* +1: the last line may lack its newline */
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: header declares %lld vertices and %lld faces, but only %llu "
                            "bytes follow (at least %llu needed): counts are wrong or the file "
                            "is truncated",
                            P->name, P->t.line, (long long)*nv, (long long)*nf,
                            (unsigned long long)left, (unsigned long long)need);
    return SQ_OK;
}

static sq_status off_vertex(off_parser *P, sq_span line, double *xyz, uint32_t v)
{
    char q[200];
    sq_span tok;
    int n = 0;
    while (sq_span_next_token(&line, &tok)) {
        double d;
        if (sq_span_to_double(tok, &d) != 0)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: bad number '%s' (value %d of vertex %u)", P->name,
                                P->t.line, sq_span_quote(tok, q, sizeof q), n + 1, v);
        if (n < 3) xyz[n] = d;
        n++;
    }
    if (n < 3 + P->extra_min || n > 3 + P->extra_max) {
        if (P->extra_min == P->extra_max)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: vertex %u has %d values, expected %d (header %s)",
                                P->name, P->t.line, v, n, 3 + P->extra_min, P->keyword);
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: vertex %u has %d values, expected %d or %d (header %s)",
                            P->name, P->t.line, v, n, 3 + P->extra_min, 3 + P->extra_max,
                            P->keyword);
    }
    return SQ_OK;
}

/* `n i0 ... i(n-1) [colour]`: up to 4 colour values (a colour map index,
 * RGB or RGBA) may follow and are ignored after checking they are numbers.
 * Appends the indices to idx[*nc...]; *cap grows as needed. */
static sq_status off_face(off_parser *P, sq_span line, uint32_t f, uint32_t nv,
                          uint32_t **idx, size_t *cap, size_t *nc)
{
    char q[200];
    sq_span tok;
    int64_t n;
    int ok = sq_span_next_token(&line, &tok);
    assert(ok);
    (void)ok;
    if (sq_span_to_int(tok, &n) != 0)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: face %u: bad corner count '%s'", P->name, P->t.line, f,
                            sq_span_quote(tok, q, sizeof q));
    if (n < 3)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: face %u has %lld corners; a face needs at least 3", P->name,
                            P->t.line, f, (long long)n);
    /* a line of L bytes holds at most L/2 indices: bounds the reservation */
    if (n > (int64_t)sq_span_len(line))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: face %u declares %lld corners, more than the line holds",
                            P->name, P->t.line, f, (long long)n);
    if (*nc + (size_t)n > UINT32_MAX - 1)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: too many face corners in the file",
                            P->name, P->t.line);
    if (sq_reserve((void **)idx, cap, *nc + (size_t)n, sizeof **idx))
        return sq_error_set(P->err, SQ_ERR_NOMEM, "%s: out of memory while reading", P->name);
    for (int64_t k = 0; k < n; k++) {
        int64_t i;
        if (!sq_span_next_token(&line, &tok))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face %u declares %lld corners but the line has only "
                                "%lld indices",
                                P->name, P->t.line, f, (long long)n, (long long)k);
        if (sq_span_to_int(tok, &i) != 0)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face %u: bad vertex index '%s' in corner %lld", P->name,
                                P->t.line, f, sq_span_quote(tok, q, sizeof q), (long long)k + 1);
        if (i < 0 || i >= (int64_t)nv)
            return sq_error_set(P->err, SQ_ERR_INDEX,
                                "%s:%u: face %u corner %lld: vertex index %s out of range (the "
                                "file has %u vertices, numbered from 0)",
                                P->name, P->t.line, f, (long long)k + 1,
                                sq_span_quote(tok, q, sizeof q), nv);
        (*idx)[(*nc)++] = (uint32_t)i;
    }
    int ncol = 0;
    while (sq_span_next_token(&line, &tok)) {
        double d;
        if (++ncol > 4)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face %u has more than 4 values after its %lld corner "
                                "indices (only a colour may follow them)",
                                P->name, P->t.line, f, (long long)n);
        if (sq_span_to_double(tok, &d) != 0)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face %u: bad colour value '%s' after the indices",
                                P->name, P->t.line, f, sq_span_quote(tok, q, sizeof q));
    }
    return SQ_OK;
}

sq_status sq_parse_off(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err)
{
    char q[200];
    if (!out || (!data && size))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_parse_off: NULL argument");
    memset(out, 0, sizeof *out);
    if (!data) data = ""; /* size is 0: avoid arithmetic on NULL */
    off_parser P;
    memset(&P, 0, sizeof P);
    P.name = name ? name : "(buffer)";
    P.err = err;
    sq_text_init(&P.t, data, size);
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) P.t.p += 3; /* UTF-8 BOM */

    /* header keyword, optionally followed by the counts on the same line */
    sq_span line, kw;
    if (!off_next_content_line(&P, &line))
        return sq_error_set(err, SQ_ERR_EMPTY, "%s: empty file (no OFF header)", P.name);
    sq_span rest = line;
    sq_span_next_token(&rest, &kw);
    if (off_keyword(&P, kw) != 0) {
        if (sq_span_has_binary(line))
            return sq_error_set(err, SQ_ERR_PARSE,
                                "%s:%u: binary data where the OFF header belongs: not an OFF "
                                "file",
                                P.name, P.t.line);
        return sq_error_set(err, SQ_ERR_PARSE,
                            "%s:%u: expected the header 'OFF' (or COFF, NOFF, CNOFF, STOFF), "
                            "found '%s'",
                            P.name, P.t.line, sq_span_quote(kw, q, sizeof q));
    }
    sq_span tok;
    sq_span probe = rest;
    if (sq_span_next_token(&probe, &tok) && sq_span_eq(tok, "BINARY"))
        return sq_error_set(err, SQ_ERR_FORMAT, "%s:%u: binary OFF is not supported", P.name,
                            P.t.line);
    if (sq_span_is_blank(rest)) {
        if (!off_next_content_line(&P, &line))
            return sq_error_set(err, SQ_ERR_PARSE,
                                "%s:%u: file ends after the header; expected the counts "
                                "'vertices faces edges'",
                                P.name, P.t.line);
        rest = line;
    }
    int64_t nv64, nf64;
    sq_status st = off_counts(&P, rest, &nv64, &nf64);
    if (st) return st;
    uint32_t header_line = P.t.line;
    if (nv64 == 0 || nf64 == 0)
        return sq_error_set(err, SQ_ERR_EMPTY, "%s:%u: header declares %lld vertices and %lld "
                            "faces: empty mesh",
                            P.name, header_line, (long long)nv64, (long long)nf64);
    uint32_t nv = (uint32_t)nv64, nf = (uint32_t)nf64;

    out->nv = nv;
    out->nf = nf;
    out->pos = malloc(3 * (size_t)nv * sizeof *out->pos);
    out->vert_line = malloc((size_t)nv * sizeof *out->vert_line);
    out->face_off = malloc(((size_t)nf + 1) * sizeof *out->face_off);
    out->face_line = malloc((size_t)nf * sizeof *out->face_line);
    size_t idx_cap = 3 * (size_t)nf, nc = 0;
    out->face_idx = malloc(idx_cap * sizeof *out->face_idx);
    if (!out->pos || !out->vert_line || !out->face_off || !out->face_line || !out->face_idx ||
        sq_strdup_opt(name, &out->path)) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "%s: out of memory while reading", P.name);
        goto fail;
    }

    for (uint32_t v = 0; v < nv; v++) {
        if (!off_next_content_line(&P, &line)) {
            st = sq_error_set(err, SQ_ERR_PARSE,
                              "%s:%u: expected %u vertices, file ends after %u", P.name,
                              P.t.line, nv, v);
            goto fail;
        }
        st = off_vertex(&P, line, out->pos + 3 * (size_t)v, v);
        if (st) goto fail;
        out->vert_line[v] = P.t.line;
    }
    out->face_off[0] = 0;
    for (uint32_t f = 0; f < nf; f++) {
        if (!off_next_content_line(&P, &line)) {
            st = sq_error_set(err, SQ_ERR_PARSE, "%s:%u: expected %u faces, file ends after %u",
                              P.name, P.t.line, nf, f);
            goto fail;
        }
        st = off_face(&P, line, f, nv, &out->face_idx, &idx_cap, &nc);
        if (st) goto fail;
        out->face_off[f + 1] = (uint32_t)nc;
        out->face_line[f] = P.t.line;
    }
    if (off_next_content_line(&P, &line)) {
        st = sq_error_set(err, SQ_ERR_PARSE,
                          "%s:%u: unexpected content after the last of the %u faces declared at "
                          "line %u",
                          P.name, P.t.line, nf, header_line);
        goto fail;
    }
    out->face_idx = sq_shrink(out->face_idx, nc, sizeof *out->face_idx);
    out->line_kind = 0;
    sq_error_clear(err);
    return SQ_OK;

fail:
    sq_soup_free(out);
    return st;
}
