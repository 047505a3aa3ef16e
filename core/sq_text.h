/* seamquad: private helpers for the text mesh readers (OBJ, OFF, ASCII PLY).
 *
 * Not part of the public API. Everything here works on a buffer given as
 * [begin, end): nothing ever reads past `end` and nothing needs a NUL
 * terminator, so the parsers are safe on the raw inputs of the fuzz targets.
 *
 * A line is the bytes up to (not including) '\n'; one '\r' before the '\n'
 * (CRLF files) is dropped. A missing final newline is fine. Tokens are runs
 * of bytes other than the blanks ' ', '\t', '\r', '\v', '\f'. */
#ifndef SQ_TEXT_H
#define SQ_TEXT_H

#include <assert.h>
#include <float.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A byte range [b, e). */
typedef struct sq_span {
    const char *b;
    const char *e;
} sq_span;

/* Cursor over a text buffer, line by line. */
typedef struct sq_text {
    const char *p;    /* first byte not yet returned                     */
    const char *end;  /* end of the buffer                               */
    uint32_t line;    /* 1-based number of the line returned last        */
} sq_text;

static inline void sq_text_init(sq_text *t, const char *data, size_t size)
{
    t->p = data;
    t->end = data + size;
    t->line = 0;
}

/* Next line into *line (without "\n" or "\r\n"). Returns 0 at the end of the
 * buffer. Line numbers saturate at UINT32_MAX (a 4-billion-line file would
 * only get imprecise provenance, never wrong data). */
static inline int sq_text_next_line(sq_text *t, sq_span *line)
{
    if (t->p >= t->end) return 0;
    const char *nl = memchr(t->p, '\n', (size_t)(t->end - t->p));
    const char *e = nl ? nl : t->end;
    line->b = t->p;
    line->e = e;
    if (e > line->b && e[-1] == '\r') line->e = e - 1;
    t->p = nl ? nl + 1 : t->end;
    if (t->line < UINT32_MAX) t->line++;
    return 1;
}

static inline int sq_is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Cuts the line at its first '#' (a comment runs to the end of the line). */
static inline void sq_span_strip_comment(sq_span *line)
{
    const char *h = memchr(line->b, '#', (size_t)(line->e - line->b));
    if (h) line->e = h;
}

/* Next token of *rest into *tok, consuming it from *rest. Returns 0 when
 * only blanks are left. */
static inline int sq_span_next_token(sq_span *rest, sq_span *tok)
{
    const char *p = rest->b;
    while (p < rest->e && sq_is_blank(*p)) p++;
    if (p == rest->e) {
        rest->b = p;
        tok->b = tok->e = p;
        return 0;
    }
    tok->b = p;
    while (p < rest->e && !sq_is_blank(*p)) p++;
    tok->e = p;
    rest->b = p;
    return 1;
}

/* 1 when the span holds only blanks. */
static inline int sq_span_is_blank(sq_span s)
{
    sq_span tok;
    return !sq_span_next_token(&s, &tok);
}

static inline size_t sq_span_len(sq_span s)
{
    return (size_t)(s.e - s.b);
}

/* 1 when the span equals the NUL-terminated word w. */
static inline int sq_span_eq(sq_span s, const char *w)
{
    size_t n = strlen(w);
    return sq_span_len(s) == n && memcmp(s.b, w, n) == 0;
}

/* Copies the span into buf for a message: at most 40 bytes, with bytes that
 * are not printable ASCII written as \xHH so a binary file cannot garble a
 * terminal. Returns buf. */
static inline const char *sq_span_quote(sq_span s, char *buf, size_t n)
{
    static const char hex[] = "0123456789abcdef";
    size_t o = 0;
    assert(n >= 8);
    for (const char *p = s.b; p < s.e; p++) {
        unsigned char c = (unsigned char)*p;
        if (p - s.b >= 40) {
            if (o + 4 > n) break;
            memcpy(buf + o, "...", 3);
            o += 3;
            break;
        }
        if (c >= 0x20 && c < 0x7f) {
            if (o + 2 > n) break;
            buf[o++] = (char)c;
        } else {
            if (o + 5 > n) break;
            buf[o++] = '\\';
            buf[o++] = 'x';
            buf[o++] = hex[c >> 4];
            buf[o++] = hex[c & 15];
        }
    }
    buf[o] = '\0';
    return buf;
}

/* 1 when the span holds a byte that never occurs in a text file (control
 * characters other than blanks, DEL): the sign of binary data. */
static inline int sq_span_has_binary(sq_span s)
{
    for (const char *p = s.b; p < s.e; p++) {
        unsigned char c = (unsigned char)*p;
        if ((c < 0x20 && !sq_is_blank((char)c) && c != '\n') || c == 0x7f) return 1;
    }
    return 0;
}

#define SQ_NUMBER_MAX_LEN 127

/* Fast exact path for plain decimals such as "-0.300072" or "1.5e-3":
 * when the significant digits form an integer m <= 2^53 and the decimal
 * exponent k satisfies |k| <= 22, both m and 10^|k| are exact doubles, so
 * the one IEEE multiplication or division m * 10^k rounds correctly and
 * gives the very bits strtod gives (Clinger's observation). Returns 0 and
 * sets *out on success, -1 when the token needs the general strtod path
 * (more digits, large exponents, hex, nan, inf, or not a number at all). */
static inline int sq_decimal_fast(sq_span tok, double *out)
{
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    static const double pow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char *p = tok.b, *e = tok.e;
    int neg = 0;
    if (p < e && (*p == '+' || *p == '-')) neg = *p++ == '-';
    uint64_t m = 0;
    int sig = 0, frac = 0, any = 0;
    for (; p < e && *p >= '0' && *p <= '9'; p++, any = 1) {
        if (m == 0 && *p == '0') continue; /* leading zeros are not significant */
        if (++sig > 19) return -1;
        m = m * 10 + (uint64_t)(*p - '0');
    }
    if (p < e && *p == '.') {
        for (p++; p < e && *p >= '0' && *p <= '9'; p++, any = 1) {
            frac++;
            if (m == 0 && *p == '0') continue;
            if (++sig > 19) return -1;
            m = m * 10 + (uint64_t)(*p - '0');
        }
    }
    if (!any) return -1;
    int exp10 = 0;
    if (p < e && (*p == 'e' || *p == 'E')) {
        int eneg = 0, edig = 0;
        p++;
        if (p < e && (*p == '+' || *p == '-')) eneg = *p++ == '-';
        for (; p < e && *p >= '0' && *p <= '9'; p++) {
            if (++edig > 4) return -1;
            exp10 = exp10 * 10 + (*p - '0');
        }
        if (edig == 0) return -1;
        if (eneg) exp10 = -exp10;
    }
    if (p != e) return -1;
    exp10 -= frac;
    if (m > ((uint64_t)1 << 53) || exp10 < -22 || exp10 > 22) return -1;
    double d = (double)m;
    d = exp10 < 0 ? d / pow10[-exp10] : d * pow10[exp10];
    *out = neg ? -d : d;
    return 0;
#else
    (void)tok;
    (void)out;
    return -1;
#endif
}

/* Parses the whole token as a double: plain decimals by sq_decimal_fast,
 * everything else by strtod (C locale assumed: the library never calls
 * setlocale); both give the same bits. Accepts what strtod accepts, including
 * "nan" and "inf" (the mesh builder rejects non-finite coordinates with the
 * line number); overflow gives +-inf, underflow the nearest representable
 * value. Returns 0 on success, -1 if the token is not exactly one number
 * (garbage, trailing junk, or longer than SQ_NUMBER_MAX_LEN bytes). */
static inline int sq_span_to_double(sq_span tok, double *out)
{
    char buf[SQ_NUMBER_MAX_LEN + 1];
    size_t n = sq_span_len(tok);
    if (n == 0 || n > SQ_NUMBER_MAX_LEN) return -1;
    if (sq_decimal_fast(tok, out) == 0) return 0;
    /* strtod skips leading blanks; a token never has them, but be explicit */
    if (sq_is_blank(tok.b[0]) || tok.b[0] == '\n') return -1;
    memcpy(buf, tok.b, n);
    buf[n] = '\0';
    char *end = NULL;
    *out = strtod(buf, &end);
    return end == buf + n ? 0 : -1;
}

/* Parses the whole token as a decimal integer with an optional sign.
 * Values beyond +-2^62 saturate there (callers range-check anyway, and
 * report the token text). Returns 0 on success, -1 if not an integer. */
static inline int sq_span_to_int(sq_span tok, int64_t *out)
{
    const int64_t cap = (int64_t)1 << 62;
    const char *p = tok.b;
    int neg = 0;
    if (p < tok.e && (*p == '+' || *p == '-')) {
        neg = *p == '-';
        p++;
    }
    if (p == tok.e) return -1;
    int64_t v = 0;
    for (; p < tok.e; p++) {
        if (*p < '0' || *p > '9') return -1;
        v = v <= (cap - 9) / 10 ? v * 10 + (*p - '0') : cap;
    }
    *out = neg ? -v : v;
    return 0;
}

/* Growable array: makes room for `need` elements of `elem` bytes in *p,
 * doubling the capacity. Returns 0, or -1 when out of memory (then *p is
 * unchanged and still owned by the caller). */
static inline int sq_reserve(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 256;
    while (c < need) {
        if (c > SIZE_MAX / 2 / elem) return -1;
        c *= 2;
    }
    void *q = realloc(*p, c * elem);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}

/* Shrinks an array to exactly n elements (best effort: keeps the larger
 * block if realloc fails). */
static inline void *sq_shrink(void *p, size_t n, size_t elem)
{
    if (!p || n == 0) return p;
    void *q = realloc(p, n * elem);
    return q ? q : p;
}

/* Copies a NUL-terminated string; NULL stays NULL. Returns -1 when out of
 * memory. */
static inline int sq_strdup_opt(const char *s, char **out)
{
    *out = NULL;
    if (!s) return 0;
    size_t n = strlen(s) + 1;
    *out = malloc(n);
    if (!*out) return -1;
    memcpy(*out, s, n);
    return 0;
}

#endif
