/* seamquad: cone files and cone admissibility (see sq_cones.h, docs/cones.md). */
#include "sq_cones.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"

#define SQ_HALF_PI 1.57079632679489661923
#define CONE_ANGLE_TOL 1e-6

/* One data line: up to three whitespace-separated fields (a third one only
 * tells us the line fits neither format). */
typedef struct cone_line {
    uint32_t line;
    int nfields;
    const char *field[3];
    size_t len[3];
} cone_line;

/* Splits [p, end) at the next newline; strips a '#' comment; fills fields. */
static const char *next_line(const char *p, const char *end, cone_line *cl)
{
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    const char *stop = eol;
    const char *hash = memchr(p, '#', (size_t)(eol - p));
    if (hash) stop = hash;
    cl->nfields = 0;
    const char *q = p;
    while (q < stop) {
        while (q < stop && (*q == ' ' || *q == '\t' || *q == '\r')) q++;
        if (q >= stop) break;
        const char *t = q;
        while (q < stop && !(*q == ' ' || *q == '\t' || *q == '\r')) q++;
        if (cl->nfields < 3) {
            cl->field[cl->nfields] = t;
            cl->len[cl->nfields] = (size_t)(q - t);
        }
        cl->nfields++;
    }
    return eol < end ? eol + 1 : end;
}

/* Parses a whole field as a finite double. */
static int field_double(const char *t, size_t len, double *out)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf) return 0;
    memcpy(buf, t, len);
    buf[len] = '\0';
    char *e;
    errno = 0;
    double d = strtod(buf, &e);
    if (*e != '\0' || !isfinite(d)) return 0;
    *out = d;
    return 1;
}

/* Parses a whole field as a decimal integer in [INT64_MIN/2, INT64_MAX/2]. */
static int field_int(const char *t, size_t len, long long *out)
{
    char buf[32];
    if (len == 0 || len >= sizeof buf) return 0;
    memcpy(buf, t, len);
    buf[len] = '\0';
    char *e;
    errno = 0;
    long long v = strtoll(buf, &e, 10);
    if (*e != '\0' || errno) return 0;
    *out = v;
    return 1;
}

static sq_status parse_th_hat_value(const cone_line *cl, const char *name, uint32_t v,
                                    int32_t *valence, sq_error *err)
{
    double a;
    if (!field_double(cl->field[0], cl->len[0], &a))
        return sq_error_set(err, SQ_ERR_PARSE, "%s:%u: '%.*s' is not a finite number", name,
                            cl->line, (int)(cl->len[0] > 40 ? 40 : cl->len[0]), cl->field[0]);
    double k = nearbyint(a / SQ_HALF_PI);
    if (fabs(a - k * SQ_HALF_PI) > CONE_ANGLE_TOL)
        return sq_error_set(err, SQ_ERR_CONE_VALUE,
                            "%s:%u: angle %.17g of vertex %u is not a multiple of pi/2 (nearest "
                            "is %g*pi/2, off by %.3g > %g)",
                            name, cl->line, a, v, k, fabs(a - k * SQ_HALF_PI), CONE_ANGLE_TOL);
    if (k < 1)
        return sq_error_set(err, SQ_ERR_CONE_VALUE,
                            "%s:%u: angle %.17g of vertex %u is not positive; a cone angle must "
                            "be k*pi/2 with k >= 1",
                            name, cl->line, a, v);
    if (k > 1e6)
        return sq_error_set(err, SQ_ERR_CONE_VALUE, "%s:%u: angle %.17g of vertex %u is absurdly large",
                            name, cl->line, a, v);
    valence[v] = (int32_t)k;
    return SQ_OK;
}

sq_status sq_cones_parse(const char *data, size_t size, const char *name, uint32_t nv,
                         int32_t *valence, sq_cone_format *format, sq_error *err)
{
    const char *p = data, *end = data + size;
    if (!name) name = "<cones>";
    if (memchr(data, '\0', size))
        return sq_error_set(err, SQ_ERR_PARSE, "%s: contains NUL bytes: not a text cone file", name);

    /* Pass 1: decide the format from the first data line, check that every
     * data line has the same shape, and count the lines. */
    int fmt = 0;
    uint32_t ndata = 0, first_line = 0;
    cone_line cl = {0};
    for (uint32_t line = 1; p < end; line++) {
        p = next_line(p, end, &cl);
        cl.line = line;
        if (cl.nfields == 0) continue;
        int this_fmt = cl.nfields == 1 ? SQ_CONES_TH_HAT : cl.nfields == 2 ? SQ_CONES_LIST : 0;
        if (!this_fmt)
            return sq_error_set(err, SQ_ERR_PARSE,
                                "%s:%u: %d fields; a cone file has either one angle per line "
                                "(Th_hat) or 'VERTEX VALENCE' per line (cone list)",
                                name, line, cl.nfields);
        if (!fmt) {
            fmt = this_fmt;
            first_line = line;
        } else if (fmt != this_fmt) {
            return sq_error_set(err, SQ_ERR_PARSE,
                                "%s:%u: %d field(s), but line %u made this a %s file (%s per line)",
                                name, line, cl.nfields, first_line,
                                fmt == SQ_CONES_TH_HAT ? "Th_hat" : "cone list",
                                fmt == SQ_CONES_TH_HAT ? "one angle" : "'VERTEX VALENCE'");
        }
        ndata++;
    }
    if (!fmt) fmt = SQ_CONES_LIST; /* no data lines: a cone list with no cones */
    if (format) *format = (sq_cone_format)fmt;

    if (fmt == SQ_CONES_TH_HAT && ndata != nv)
        return sq_error_set(err, SQ_ERR_CONE_COUNT,
                            "%s: %u angles for a mesh with %u vertices; a Th_hat file needs one "
                            "angle per vertex, in vertex order",
                            name, ndata, nv);

    /* Pass 2: values. */
    for (uint32_t v = 0; v < nv; v++) valence[v] = 4;
    uint8_t *seen = NULL;
    if (fmt == SQ_CONES_LIST) {
        seen = calloc(nv ? nv : 1, 1);
        if (!seen) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    sq_status st = SQ_OK;
    uint32_t v = 0;
    p = data;
    for (uint32_t line = 1; p < end && st == SQ_OK; line++) {
        p = next_line(p, end, &cl);
        cl.line = line;
        if (cl.nfields == 0) continue;
        if (fmt == SQ_CONES_TH_HAT) {
            st = parse_th_hat_value(&cl, name, v++, valence, err);
            continue;
        }
        long long vi, k;
        if (!field_int(cl.field[0], cl.len[0], &vi) || !field_int(cl.field[1], cl.len[1], &k)) {
            st = sq_error_set(err, SQ_ERR_PARSE,
                              "%s:%u: expected two integers 'VERTEX VALENCE' (0-based vertex "
                              "index, valence k for a cone of angle k*pi/2)",
                              name, line);
        } else if (vi < 0 || vi >= (long long)nv) {
            st = sq_error_set(err, SQ_ERR_INDEX,
                              "%s:%u: vertex %lld is out of range: the mesh has %u vertices "
                              "(indices are 0-based)",
                              name, line, vi, nv);
        } else if (k < 1 || k > 1000000) {
            st = sq_error_set(err, SQ_ERR_CONE_VALUE,
                              "%s:%u: valence %lld of vertex %lld is not a positive count "
                              "(a cone of angle k*pi/2 has valence k >= 1)",
                              name, line, k, vi);
        } else if (seen[vi]) {
            st = sq_error_set(err, SQ_ERR_CONE_VALUE, "%s:%u: vertex %lld is listed twice", name,
                              line, vi);
        } else {
            seen[vi] = 1;
            valence[vi] = (int32_t)k;
        }
    }
    free(seen);
    return st;
}

sq_status sq_cones_read(const char *path, uint32_t nv, int32_t *valence,
                        sq_cone_format *format, sq_error *err)
{
    char *data;
    size_t size;
    sq_status st = sq_read_file(path, &data, &size, err);
    if (st) return st;
    st = sq_cones_parse(data, size, path, nv, valence, format, err);
    free(data);
    return st;
}

uint32_t sq_cones_histogram(uint32_t nv, const int32_t *valence, uint32_t *hist, uint32_t nhist)
{
    uint32_t cones = 0;
    if (nhist) memset(hist, 0, nhist * sizeof *hist);
    for (uint32_t v = 0; v < nv; v++) {
        int32_t k = valence[v];
        if (k != 4) cones++;
        if (nhist && k >= 0) hist[(uint32_t)k < nhist ? (uint32_t)k : nhist - 1]++;
    }
    return cones;
}

static int64_t defect_sum(uint32_t n, const int32_t *valence)
{
    int64_t s = 0;
    for (uint32_t i = 0; i < n; i++) s += 4 - (int64_t)valence[i];
    return s;
}

sq_status sq_cones_check_gauss_bonnet(uint32_t nv, const int32_t *valence, int64_t euler,
                                      sq_error *err)
{
    int64_t s = defect_sum(nv, valence);
    if (s != 4 * euler)
        return sq_error_set(err, SQ_ERR_GAUSS_BONNET,
                            "the cones violate Gauss-Bonnet: sum over vertices of (4 - valence) "
                            "is %lld, but a closed surface of genus %lld (Euler characteristic "
                            "%lld) needs 4*chi = %lld; the cone angles are off by %lld*pi/2 in "
                            "total",
                            (long long)s, (long long)((2 - euler) / 2), (long long)euler,
                            (long long)(4 * euler), (long long)(4 * euler - s));
    return SQ_OK;
}

/* Shared admissibility rules on a valence multiset; `vertex` maps the i-th
 * entry to a mesh vertex for messages (NULL: no vertices). */
static sq_status check_realizable(uint32_t n, const int32_t *valence, const uint32_t *index_is_vertex,
                                  int64_t genus, sq_error *err)
{
    for (uint32_t i = 0; i < n; i++) {
        if (valence[i] >= 2) continue;
        char who[48] = "the cone set has";
        if (index_is_vertex) snprintf(who, sizeof who, "vertex %u has", i);
        if (valence[i] == 1)
            return sq_error_set(err, SQ_ERR_UNREALIZABLE,
                                "%s a cone of valence 1 (angle pi/2): valence 1 is outside "
                                "the construction (seed Def. 5.4 needs valence >= 2, and a quad "
                                "mesh vertex of valence 1 repeats a vertex in its quad); merge "
                                "it with a neighbouring cone or move its curvature elsewhere",
                                who);
        return sq_error_set(err, SQ_ERR_CONE_VALUE,
                            "%s a cone of valence %d: a cone of angle k*pi/2 needs k >= 1", who,
                            (int)valence[i]);
    }
    int64_t s = defect_sum(n, valence);
    int64_t need = 4 * (2 - 2 * genus);
    if (s != need)
        return sq_error_set(err, SQ_ERR_GAUSS_BONNET,
                            "the cones violate Gauss-Bonnet: sum of (4 - valence) is %lld, but "
                            "genus %lld needs %lld",
                            (long long)s, (long long)genus, (long long)need);
    if (genus == 1) {
        uint32_t n3 = 0, n5 = 0, other = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (valence[i] == 3) n3++;
            else if (valence[i] == 5) n5++;
            else if (valence[i] != 4) other++;
        }
        if (n3 == 1 && n5 == 1 && other == 0)
            return sq_error_set(err, SQ_ERR_UNREALIZABLE,
                                "a torus with exactly one valence-3 and one valence-5 cone has "
                                "no quad mesh (Jucovic and Trenkler 1973); no seamless "
                                "parametrization with these cones exists");
    }
    return SQ_OK;
}

sq_status sq_cones_check_realizable(uint32_t nv, const int32_t *valence, int64_t genus,
                                    sq_error *err)
{
    static const uint32_t yes = 1;
    return check_realizable(nv, valence, &yes, genus, err);
}

sq_status sq_valences_check_realizable(uint32_t n, const int32_t *valences, int64_t genus,
                                       sq_error *err)
{
    return check_realizable(n, valences, NULL, genus, err);
}
