/* seamquad: PLY parser (ascii, binary_little_endian, binary_big_endian;
 * version 1.0). Rules: docs/io.md.
 *
 * The header is parsed into a table of elements and properties. Then every
 * element's records are read in file order: the `vertex` element's x, y, z
 * and the `face` element's vertex_indices (or vertex_index) list are kept;
 * every other property and element is read and dropped, which is exact in
 * all three encodings because the header gives each one's type. Binary
 * values are decoded byte by byte, so the host's byte order never matters.
 * Provenance: text line numbers for ascii, 1-based record numbers for
 * binary (line_kind = 1). */
#include "sq_io.h"
#include "sq_text.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum ply_type {
    PLY_NONE = 0, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64
} ply_type;

enum { PLY_ASCII = 0, PLY_LE, PLY_BE };

typedef struct ply_prop {
    sq_span name;
    ply_type type;        /* scalar type; item type of a list            */
    ply_type count_type;  /* PLY_NONE for a scalar property              */
} ply_prop;

typedef struct ply_elem {
    sq_span name;
    uint64_t count;
    uint32_t line;        /* header line of the element statement        */
    size_t first_prop, nprops;
} ply_elem;

typedef struct ply_parser {
    const char *name;
    sq_error *err;
    int format;                       /* PLY_ASCII, PLY_LE, PLY_BE          */
    ply_elem *elems; size_t nelem, elem_cap;
    ply_prop *props; size_t nprop, prop_cap;
    sq_text t;                        /* header; body of an ascii file      */
    const unsigned char *bin, *bin_end; /* body of a binary file            */
    sq_span rest;                     /* ascii: rest of the current record  */
    uint32_t rec_line;                /* ascii: line of the current record  */
    /* roles found in the header */
    size_t vertex_elem, face_elem;    /* index into elems, or SIZE_MAX     */
    size_t px, py, pz, pidx;          /* index into props                  */
} ply_parser;

typedef struct ply_value {
    int is_int;
    int64_t i;
    double d;
} ply_value;

static const struct {
    const char *name;
    ply_type type;
} ply_type_names[] = {
    {"char", PLY_I8},   {"uchar", PLY_U8},   {"short", PLY_I16},  {"ushort", PLY_U16},
    {"int", PLY_I32},   {"uint", PLY_U32},   {"float", PLY_F32},  {"double", PLY_F64},
    {"int8", PLY_I8},   {"uint8", PLY_U8},   {"int16", PLY_I16},  {"uint16", PLY_U16},
    {"int32", PLY_I32}, {"uint32", PLY_U32}, {"float32", PLY_F32}, {"float64", PLY_F64},
};

static ply_type ply_type_from(sq_span s)
{
    for (size_t k = 0; k < sizeof ply_type_names / sizeof ply_type_names[0]; k++)
        if (sq_span_eq(s, ply_type_names[k].name)) return ply_type_names[k].type;
    return PLY_NONE;
}

static const char *ply_type_name(ply_type t)
{
    static const char *const names[] = {"none", "char", "uchar", "short", "ushort",
                                        "int",  "uint", "float", "double"};
    return names[t];
}

static size_t ply_type_size(ply_type t)
{
    static const size_t sizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[t];
}

static int ply_type_is_int(ply_type t)
{
    return t != PLY_NONE && t != PLY_F32 && t != PLY_F64;
}

/* ---- messages --------------------------------------------------------- */

/* "NAME:LINE: ELEM record R" (ascii) or "NAME: ELEM record R" (binary). */
static const char *ply_where(ply_parser *P, const ply_elem *e, uint64_t rec, char *buf, size_t n)
{
    char q[200];
    sq_span_quote(e->name, q, sizeof q);
    if (P->format == PLY_ASCII)
        snprintf(buf, n, "%s:%u: %s record %llu", P->name, P->rec_line, q,
                 (unsigned long long)rec + 1);
    else
        snprintf(buf, n, "%s: %s record %llu", P->name, q, (unsigned long long)rec + 1);
    return buf;
}

static sq_status ply_nomem(ply_parser *P)
{
    return sq_error_set(P->err, SQ_ERR_NOMEM, "%s: out of memory while reading", P->name);
}

/* ---- header ----------------------------------------------------------- */

static sq_status ply_header_error(ply_parser *P, const char *what, sq_span tok)
{
    char q[200];
    return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: %s '%s'", P->name, P->t.line, what,
                        sq_span_quote(tok, q, sizeof q));
}

static sq_status ply_header_element(ply_parser *P, sq_span rest)
{
    sq_span nm, cnt, extra;
    int64_t count;
    if (!sq_span_next_token(&rest, &nm) || !sq_span_next_token(&rest, &cnt) ||
        sq_span_next_token(&rest, &extra))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: expected 'element NAME COUNT'", P->name, P->t.line);
    if (sq_span_to_int(cnt, &count) != 0) return ply_header_error(P, "bad element count", cnt);
    if (count < 0) return ply_header_error(P, "negative element count", cnt);
    if (sq_reserve((void **)&P->elems, &P->elem_cap, P->nelem + 1, sizeof *P->elems))
        return ply_nomem(P);
    ply_elem *e = &P->elems[P->nelem++];
    e->name = nm;
    e->count = (uint64_t)count;
    e->line = P->t.line;
    e->first_prop = P->nprop;
    e->nprops = 0;
    return SQ_OK;
}

static sq_status ply_header_property(ply_parser *P, sq_span rest)
{
    sq_span tok[4];
    int n = 0;
    while (n < 4 && sq_span_next_token(&rest, &tok[n])) n++;
    if (P->nelem == 0)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: 'property' before any 'element'", P->name, P->t.line);
    ply_prop p;
    memset(&p, 0, sizeof p);
    if (n >= 1 && sq_span_eq(tok[0], "list")) {
        if (n != 4)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: expected 'property list COUNT_TYPE ITEM_TYPE NAME'",
                                P->name, P->t.line);
        p.count_type = ply_type_from(tok[1]);
        p.type = ply_type_from(tok[2]);
        p.name = tok[3];
        if (p.count_type == PLY_NONE) return ply_header_error(P, "bad list count type", tok[1]);
        if (p.type == PLY_NONE) return ply_header_error(P, "bad list item type", tok[2]);
        if (!ply_type_is_int(p.count_type))
            return ply_header_error(P, "list count type must be an integer type, not", tok[1]);
    } else {
        if (n != 2)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: expected 'property TYPE NAME'", P->name, P->t.line);
        p.type = ply_type_from(tok[0]);
        p.name = tok[1];
        if (p.type == PLY_NONE) return ply_header_error(P, "bad property type", tok[0]);
    }
    ply_elem *e = &P->elems[P->nelem - 1];
    for (size_t k = e->first_prop; k < e->first_prop + e->nprops; k++)
        if (sq_span_len(P->props[k].name) == sq_span_len(p.name) &&
            memcmp(P->props[k].name.b, p.name.b, sq_span_len(p.name)) == 0)
            return ply_header_error(P, "duplicate property", p.name);
    if (sq_reserve((void **)&P->props, &P->prop_cap, P->nprop + 1, sizeof *P->props))
        return ply_nomem(P);
    P->props[P->nprop++] = p;
    e->nprops++;
    return SQ_OK;
}

static sq_status ply_header_format(ply_parser *P, sq_span rest, int *seen)
{
    sq_span fmt, ver, extra;
    if (*seen)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: second 'format' line", P->name,
                            P->t.line);
    *seen = 1;
    if (!sq_span_next_token(&rest, &fmt) || !sq_span_next_token(&rest, &ver) ||
        sq_span_next_token(&rest, &extra))
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: expected 'format ENCODING 1.0'",
                            P->name, P->t.line);
    if (sq_span_eq(fmt, "ascii"))
        P->format = PLY_ASCII;
    else if (sq_span_eq(fmt, "binary_little_endian"))
        P->format = PLY_LE;
    else if (sq_span_eq(fmt, "binary_big_endian"))
        P->format = PLY_BE;
    else
        return ply_header_error(P, "unknown encoding (expected ascii, binary_little_endian or "
                                   "binary_big_endian)", fmt);
    if (!sq_span_eq(ver, "1.0")) return ply_header_error(P, "unsupported PLY version", ver);
    return SQ_OK;
}

/* Finds the vertex and face elements and the properties we keep. */
static sq_status ply_find_roles(ply_parser *P)
{
    char q[200];
    P->vertex_elem = P->face_elem = SIZE_MAX;
    P->px = P->py = P->pz = P->pidx = SIZE_MAX;
    for (size_t k = 0; k < P->nelem; k++) {
        ply_elem *e = &P->elems[k];
        size_t *slot = sq_span_eq(e->name, "vertex") ? &P->vertex_elem
                       : sq_span_eq(e->name, "face") ? &P->face_elem
                                                     : NULL;
        if (!slot) continue;
        if (*slot != SIZE_MAX)
            return sq_error_set(P->err, SQ_ERR_PARSE, "%s:%u: second '%s' element", P->name,
                                e->line, sq_span_quote(e->name, q, sizeof q));
        *slot = k;
    }
    if (P->vertex_elem == SIZE_MAX)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: the header declares no 'vertex' element",
                            P->name);
    if (P->face_elem == SIZE_MAX)
        return sq_error_set(P->err, SQ_ERR_EMPTY,
                            "%s: the header declares no 'face' element (a point cloud has no "
                            "surface)",
                            P->name);
    const ply_elem *ve = &P->elems[P->vertex_elem], *fe = &P->elems[P->face_elem];
    for (size_t k = ve->first_prop; k < ve->first_prop + ve->nprops; k++) {
        size_t *slot = sq_span_eq(P->props[k].name, "x")   ? &P->px
                       : sq_span_eq(P->props[k].name, "y") ? &P->py
                       : sq_span_eq(P->props[k].name, "z") ? &P->pz
                                                           : NULL;
        if (!slot) continue;
        if (P->props[k].count_type != PLY_NONE)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: vertex property '%s' is a list; coordinates must be "
                                "scalars",
                                P->name, ve->line, sq_span_quote(P->props[k].name, q, sizeof q));
        *slot = k;
    }
    if (P->px == SIZE_MAX || P->py == SIZE_MAX || P->pz == SIZE_MAX)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: the vertex element lacks property %s", P->name, ve->line,
                            P->px == SIZE_MAX ? "x" : P->py == SIZE_MAX ? "y" : "z");
    for (size_t k = fe->first_prop; k < fe->first_prop + fe->nprops; k++) {
        const ply_prop *p = &P->props[k];
        if (!sq_span_eq(p->name, "vertex_indices") && !sq_span_eq(p->name, "vertex_index"))
            continue;
        if (P->pidx != SIZE_MAX)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: the face element has both vertex_indices and "
                                "vertex_index",
                                P->name, fe->line);
        if (p->count_type == PLY_NONE)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face property '%s' must be a list", P->name, fe->line,
                                sq_span_quote(p->name, q, sizeof q));
        if (!ply_type_is_int(p->type))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: face vertex indices have type %s; an integer type is "
                                "required",
                                P->name, fe->line, ply_type_name(p->type));
        P->pidx = k;
    }
    if (P->pidx == SIZE_MAX)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: the face element has no vertex_indices (or vertex_index) "
                            "list",
                            P->name, fe->line);
    if (ve->count > UINT32_MAX - 1 || fe->count > UINT32_MAX - 1)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s: %llu vertices and %llu faces exceed the limit of %u", P->name,
                            (unsigned long long)ve->count, (unsigned long long)fe->count,
                            UINT32_MAX - 1);
    if (ve->count == 0 || fe->count == 0)
        return sq_error_set(P->err, SQ_ERR_EMPTY,
                            "%s: the header declares %llu vertices and %llu faces: empty mesh",
                            P->name, (unsigned long long)ve->count, (unsigned long long)fe->count);
    return SQ_OK;
}

static sq_status ply_header(ply_parser *P)
{
    sq_span line, kw;
    if (!sq_text_next_line(&P->t, &line))
        return sq_error_set(P->err, SQ_ERR_EMPTY, "%s: empty file", P->name);
    sq_span first = line;
    if (!sq_span_next_token(&first, &kw) || !sq_span_eq(kw, "ply") || !sq_span_is_blank(first)) {
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:1: not a PLY file: the first line must be 'ply'", P->name);
    }
    int have_format = 0;
    for (;;) {
        if (!sq_text_next_line(&P->t, &line))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: the header ends without 'end_header'", P->name,
                                P->t.line);
        sq_span rest = line;
        if (!sq_span_next_token(&rest, &kw))
            continue; /* blank header lines carry nothing */
        sq_status st = SQ_OK;
        if (sq_span_eq(kw, "comment") || sq_span_eq(kw, "obj_info"))
            continue;
        else if (sq_span_eq(kw, "format"))
            st = ply_header_format(P, rest, &have_format);
        else if (sq_span_eq(kw, "element"))
            st = ply_header_element(P, rest);
        else if (sq_span_eq(kw, "property"))
            st = ply_header_property(P, rest);
        else if (sq_span_eq(kw, "end_header")) {
            if (!sq_span_is_blank(rest))
                return sq_error_set(P->err, SQ_ERR_PARSE,
                                    "%s:%u: text after 'end_header'", P->name, P->t.line);
            break;
        } else if (sq_span_has_binary(line))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s:%u: binary data inside the header (missing 'end_header'?)",
                                P->name, P->t.line);
        else
            st = ply_header_error(P, "unknown header statement", kw);
        if (st) return st;
    }
    if (!have_format)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: the header has no 'format' line",
                            P->name);
    return ply_find_roles(P);
}

/* ---- values ----------------------------------------------------------- */

static uint64_t ply_load(const unsigned char *b, size_t n, int big)
{
    uint64_t v = 0;
    for (size_t k = 0; k < n; k++) v |= (uint64_t)b[big ? k : n - 1 - k] << (8 * (n - 1 - k));
    return v;
}

/* Decodes one binary value; the caller has checked that it fits. */
static void ply_decode(const unsigned char *b, ply_type t, int big, ply_value *v)
{
    uint64_t u = ply_load(b, ply_type_size(t), big);
    v->is_int = 1;
    switch (t) {
    case PLY_I8: v->i = (int8_t)(uint8_t)u; break;
    case PLY_U8: v->i = (uint8_t)u; break;
    case PLY_I16: v->i = (int16_t)(uint16_t)u; break;
    case PLY_U16: v->i = (uint16_t)u; break;
    case PLY_I32: v->i = (int32_t)(uint32_t)u; break;
    case PLY_U32: v->i = (uint32_t)u; break;
    case PLY_F32: {
        uint32_t w = (uint32_t)u;
        float f;
        memcpy(&f, &w, sizeof f);
        v->is_int = 0;
        v->d = f;
        return;
    }
    case PLY_F64:
        memcpy(&v->d, &u, sizeof v->d);
        v->is_int = 0;
        return;
    default: assert(0 && "bad ply type"); break;
    }
    v->d = (double)v->i;
}

/* Range of each integer type, for ascii values. */
static int ply_int_in_range(ply_type t, int64_t i)
{
    switch (t) {
    case PLY_I8: return i >= INT8_MIN && i <= INT8_MAX;
    case PLY_U8: return i >= 0 && i <= UINT8_MAX;
    case PLY_I16: return i >= INT16_MIN && i <= INT16_MAX;
    case PLY_U16: return i >= 0 && i <= UINT16_MAX;
    case PLY_I32: return i >= INT32_MIN && i <= INT32_MAX;
    case PLY_U32: return i >= 0 && i <= (int64_t)UINT32_MAX;
    default: return 0;
    }
}

/* Reads the next value of type t from the current record. `what` names the
 * property for messages. */
static sq_status ply_read(ply_parser *P, ply_type t, ply_value *v, const ply_elem *e,
                          uint64_t rec, const ply_prop *p)
{
    char w[400], q[200], pn[200];
    if (P->format != PLY_ASCII) {
        size_t n = ply_type_size(t);
        if ((size_t)(P->bin_end - P->bin) < n)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s: the file ends inside property '%s' (truncated file)",
                                ply_where(P, e, rec, w, sizeof w),
                                sq_span_quote(p->name, pn, sizeof pn));
        ply_decode(P->bin, t, P->format == PLY_BE, v);
        P->bin += n;
        return SQ_OK;
    }
    sq_span tok;
    if (!sq_span_next_token(&P->rest, &tok))
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s: the line ends before property '%s' (one record per line "
                            "expected)",
                            ply_where(P, e, rec, w, sizeof w),
                            sq_span_quote(p->name, pn, sizeof pn));
    if (ply_type_is_int(t)) {
        v->is_int = 1;
        if (sq_span_to_int(tok, &v->i) != 0)
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s: property '%s': '%s' is not an integer (type %s)",
                                ply_where(P, e, rec, w, sizeof w),
                                sq_span_quote(p->name, pn, sizeof pn),
                                sq_span_quote(tok, q, sizeof q), ply_type_name(t));
        if (!ply_int_in_range(t, v->i))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s: property '%s': %s is out of range for type %s",
                                ply_where(P, e, rec, w, sizeof w),
                                sq_span_quote(p->name, pn, sizeof pn),
                                sq_span_quote(tok, q, sizeof q), ply_type_name(t));
        v->d = (double)v->i;
        return SQ_OK;
    }
    v->is_int = 0;
    if (sq_span_to_double(tok, &v->d) != 0)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: property '%s': bad number '%s'",
                            ply_where(P, e, rec, w, sizeof w),
                            sq_span_quote(p->name, pn, sizeof pn), sq_span_quote(tok, q, sizeof q));
    return SQ_OK;
}

/* ---- body ------------------------------------------------------------- */

/* Smallest number of bytes one record of e can take: binary, a value per
 * scalar and the count of each list; ascii, one digit and one separator
 * per value. Used to reject counts the remaining data cannot hold before
 * allocating anything for them. */
static uint64_t ply_min_record_bytes(const ply_parser *P, const ply_elem *e)
{
    uint64_t n = 0;
    for (size_t k = e->first_prop; k < e->first_prop + e->nprops; k++) {
        const ply_prop *p = &P->props[k];
        if (P->format == PLY_ASCII)
            n += 2;
        else
            n += ply_type_size(p->count_type != PLY_NONE ? p->count_type : p->type);
    }
    return n;
}

static sq_status ply_check_count(ply_parser *P, const ply_elem *e)
{
    char q[200];
    uint64_t left = P->format == PLY_ASCII ? (uint64_t)(P->t.end - P->t.p) + 1
                                           : (uint64_t)(P->bin_end - P->bin);
    uint64_t rec = ply_min_record_bytes(P, e);
    assert(rec > 0);
    if (e->count > left / rec)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s:%u: element '%s' declares %llu records of at least %llu bytes "
                            "each, but only %llu bytes of data are left (wrong count or "
                            "truncated file)",
                            P->name, e->line, sq_span_quote(e->name, q, sizeof q),
                            (unsigned long long)e->count, (unsigned long long)rec,
                            (unsigned long long)(P->format == PLY_ASCII ? left - 1 : left));
    return SQ_OK;
}

/* Reads one list property: the count, then the items. Face indices are
 * appended to the soup; other lists are skipped. */
static sq_status ply_read_list(ply_parser *P, const ply_elem *e, uint64_t rec, size_t k,
                               sq_soup *out, size_t *idx_cap, size_t *nc)
{
    char w[400], pn[200];
    const ply_prop *p = &P->props[k];
    ply_value v;
    sq_status st = ply_read(P, p->count_type, &v, e, rec, p);
    if (st) return st;
    assert(v.is_int);
    if (v.i < 0)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: list '%s' has negative count %lld",
                            ply_where(P, e, rec, w, sizeof w),
                            sq_span_quote(p->name, pn, sizeof pn), (long long)v.i);
    uint64_t n = (uint64_t)v.i;
    /* the items must fit in what is left: bounds allocation and skipping */
    uint64_t left = P->format == PLY_ASCII ? (uint64_t)(P->rest.e - P->rest.b)
                                           : (uint64_t)(P->bin_end - P->bin);
    uint64_t item = P->format == PLY_ASCII ? 1 : ply_type_size(p->type);
    if (n > left / item)
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s: list '%s' has %llu items, more than the %s holds (truncated "
                            "file or wrong count)",
                            ply_where(P, e, rec, w, sizeof w),
                            sq_span_quote(p->name, pn, sizeof pn), (unsigned long long)n,
                            P->format == PLY_ASCII ? "line" : "rest of the file");
    if (k != P->pidx) {
        if (P->format != PLY_ASCII) {
            P->bin += n * item;
            return SQ_OK;
        }
        for (uint64_t j = 0; j < n; j++) {
            st = ply_read(P, p->type, &v, e, rec, p);
            if (st) return st;
        }
        return SQ_OK;
    }
    if (n < 3)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: face has %llu corners; a face needs at "
                            "least 3",
                            ply_where(P, e, rec, w, sizeof w), (unsigned long long)n);
    if (*nc + n > UINT32_MAX - 1)
        return sq_error_set(P->err, SQ_ERR_PARSE, "%s: too many face corners in the file",
                            ply_where(P, e, rec, w, sizeof w));
    if (sq_reserve((void **)&out->face_idx, idx_cap, *nc + (size_t)n, sizeof *out->face_idx))
        return ply_nomem(P);
    for (uint64_t j = 0; j < n; j++) {
        st = ply_read(P, p->type, &v, e, rec, p);
        if (st) return st;
        if (v.i < 0 || v.i >= (int64_t)out->nv)
            return sq_error_set(P->err, SQ_ERR_INDEX,
                                "%s: corner %llu: vertex index %lld out of range (the file has "
                                "%u vertices, numbered from 0)",
                                ply_where(P, e, rec, w, sizeof w), (unsigned long long)j + 1,
                                (long long)v.i, out->nv);
        out->face_idx[(*nc)++] = (uint32_t)v.i;
    }
    return SQ_OK;
}

/* Reads all records of element e. */
static sq_status ply_read_element(ply_parser *P, size_t ei, sq_soup *out, size_t *idx_cap,
                                  size_t *nc)
{
    char w[400], q[200];
    const ply_elem *e = &P->elems[ei];
    if (e->nprops == 0) return SQ_OK; /* records without properties take no bytes */
    sq_status st = ply_check_count(P, e);
    if (st) return st;
    int is_vertex = ei == P->vertex_elem, is_face = ei == P->face_elem;
    for (uint64_t r = 0; r < e->count; r++) {
        if (P->format == PLY_ASCII) {
            sq_span line;
            do {
                if (!sq_text_next_line(&P->t, &line))
                    return sq_error_set(P->err, SQ_ERR_PARSE,
                                        "%s:%u: expected %llu '%s' records, file ends after %llu",
                                        P->name, P->t.line, (unsigned long long)e->count,
                                        sq_span_quote(e->name, q, sizeof q),
                                        (unsigned long long)r);
            } while (sq_span_is_blank(line));
            P->rest = line;
            P->rec_line = P->t.line;
        }
        for (size_t k = e->first_prop; k < e->first_prop + e->nprops; k++) {
            const ply_prop *p = &P->props[k];
            if (p->count_type != PLY_NONE) {
                st = ply_read_list(P, e, r, k, out, idx_cap, nc);
                if (st) return st;
                continue;
            }
            ply_value v;
            st = ply_read(P, p->type, &v, e, r, p);
            if (st) return st;
            if (is_vertex && (k == P->px || k == P->py || k == P->pz))
                out->pos[3 * r + (k == P->px ? 0 : k == P->py ? 1 : 2)] = v.d;
        }
        if (P->format == PLY_ASCII && !sq_span_is_blank(P->rest))
            return sq_error_set(P->err, SQ_ERR_PARSE,
                                "%s: the line has more values than the element's properties "
                                "(one record per line expected)",
                                ply_where(P, e, r, w, sizeof w));
        uint32_t prov = P->format == PLY_ASCII ? P->rec_line : (uint32_t)(r + 1);
        if (is_vertex) out->vert_line[r] = prov;
        if (is_face) {
            out->face_line[r] = prov;
            out->face_off[r + 1] = (uint32_t)*nc;
        }
    }
    return SQ_OK;
}

static sq_status ply_body(ply_parser *P, sq_soup *out)
{
    const ply_elem *ve = &P->elems[P->vertex_elem], *fe = &P->elems[P->face_elem];
    out->nv = (uint32_t)ve->count;
    out->nf = (uint32_t)fe->count;
    /* Sizes are bounded by the data before allocating (ply_check_count),
     * so check both elements first. */
    sq_status st = ply_check_count(P, ve);
    if (!st) st = ply_check_count(P, fe);
    if (st) return st;
    size_t idx_cap = 3 * (size_t)out->nf, nc = 0;
    out->pos = malloc(3 * (size_t)out->nv * sizeof *out->pos);
    out->vert_line = malloc((size_t)out->nv * sizeof *out->vert_line);
    out->face_off = malloc(((size_t)out->nf + 1) * sizeof *out->face_off);
    out->face_line = malloc((size_t)out->nf * sizeof *out->face_line);
    out->face_idx = malloc(idx_cap * sizeof *out->face_idx);
    if (!out->pos || !out->vert_line || !out->face_off || !out->face_line || !out->face_idx)
        return ply_nomem(P);
    out->face_off[0] = 0;
    for (size_t ei = 0; ei < P->nelem; ei++) {
        st = ply_read_element(P, ei, out, &idx_cap, &nc);
        if (st) return st;
    }
    if (P->format == PLY_ASCII) {
        sq_span line;
        while (sq_text_next_line(&P->t, &line))
            if (!sq_span_is_blank(line))
                return sq_error_set(P->err, SQ_ERR_PARSE,
                                    "%s:%u: unexpected content after the last element",
                                    P->name, P->t.line);
    } else if (P->bin != P->bin_end) {
        return sq_error_set(P->err, SQ_ERR_PARSE,
                            "%s: %llu bytes of unexpected data after the last element", P->name,
                            (unsigned long long)(P->bin_end - P->bin));
    }
    out->face_idx = sq_shrink(out->face_idx, nc, sizeof *out->face_idx);
    assert(out->face_off[out->nf] == nc);
    return SQ_OK;
}

sq_status sq_parse_ply(const char *data, size_t size, const char *name, sq_soup *out, sq_error *err)
{
    if (!out || (!data && size))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_parse_ply: NULL argument");
    memset(out, 0, sizeof *out);
    if (!data) data = ""; /* size is 0: avoid arithmetic on NULL */
    ply_parser P;
    memset(&P, 0, sizeof P);
    P.name = name ? name : "(buffer)";
    P.err = err;
    sq_text_init(&P.t, data, size);

    sq_status st = ply_header(&P);
    if (!st) {
        P.bin = (const unsigned char *)P.t.p;
        P.bin_end = (const unsigned char *)P.t.end;
        out->line_kind = P.format == PLY_ASCII ? 0 : 1;
        st = ply_body(&P, out);
    }
    if (!st && sq_strdup_opt(name, &out->path)) st = ply_nomem(&P);
    free(P.elems);
    free(P.props);
    if (st) {
        sq_soup_free(out);
        return st;
    }
    sq_error_clear(err);
    return SQ_OK;
}
