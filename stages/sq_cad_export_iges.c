/* seamquad: IGES 5.3 writer for bicubic B-spline patches.
 *
 * Each patch is one independent entity 128 (rational B-spline surface, form
 * 0) with degree 3x3, 4x4 control points, all weights 1 (PROP3 = 1:
 * polynomial), uniform knots -3..4 and parameter range [0,1]^2, untrimmed.
 * Fixed 80-column records: Start, Global, Directory Entry (two lines per
 * entity), Parameter Data (64 columns of data, back pointer to the entity's
 * directory entry) and Terminate sections. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sq_io.h"
#include "sq_subdiv.h"

typedef struct pwriter {
    FILE *fp;
    char line[80];
    size_t len;
    unsigned long seq;  /* lines written in this section */
    unsigned long de;   /* back pointer (P section), 0 for G */
    char sect;
} pwriter;

static void pw_flush(pwriter *w)
{
    if (w->sect == 'P') fprintf(w->fp, "%-64.64s %7lu%c%7lu\n", w->line, w->de, 'P', ++w->seq);
    else fprintf(w->fp, "%-72.72s%c%7lu\n", w->line, w->sect, ++w->seq);
    w->len = 0;
    w->line[0] = '\0';
}

/* Appends a token followed by its delimiter; never splits a token. */
static void pw_token(pwriter *w, const char *tok, char delim)
{
    size_t width = w->sect == 'P' ? 64 : 72, n = strlen(tok) + 1;
    if (w->len + n > width) pw_flush(w);
    memcpy(w->line + w->len, tok, n - 1);
    w->line[w->len + n - 1] = delim;
    w->len += n;
    w->line[w->len] = '\0';
}

static void pw_hollerith(pwriter *w, const char *s, char delim)
{
    char tok[80];
    size_t n = strlen(s);
    if (n > 60) n = 60;
    int k = snprintf(tok, sizeof tok, "%zuH", n);
    memcpy(tok + k, s, n);
    tok[k + (int)n] = '\0';
    for (char *c = tok + k; *c; c++)
        if ((unsigned char)*c < 32 || (unsigned char)*c > 126) *c = '_';
    pw_token(w, tok, delim);
}

static void pw_real(pwriter *w, double x, char delim)
{
    char buf[32];
    pw_token(w, sq_cad_real(x, buf), delim);
}

static void pw_int(pwriter *w, long x, char delim)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%ld", x);
    pw_token(w, buf, delim);
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

sq_status sq_cad_write_iges(const char *path, const char *name, uint32_t np, const double *cv,
                            double scale, sq_error *err)
{
    if (np == 0) return sq_error_set(err, SQ_ERR_EMPTY, "no patches to write to %s", path);
    if (np > 4000000)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "%u patches exceed IGES's 7-digit sequence numbers", np);
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *fp = af.fp;
    /* The parameter section goes to a temporary stream first: the directory
     * entries need each entity's first parameter line and line count. */
    FILE *pd = tmpfile();
    unsigned long *pstart = malloc(sizeof(unsigned long) * 2 * (size_t)np);
    if (!pd || !pstart) {
        if (pd) fclose(pd);
        free(pstart);
        sq_atomic_abort(&af);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory or no temporary file for %s", path);
    }
    pwriter w = {.fp = pd, .sect = 'P'};
    for (uint32_t p = 0; p < np; p++) {
        const double *c = cv + 48 * (size_t)p;
        pstart[2 * p] = w.seq + 1;
        w.de = 2 * (unsigned long)p + 1;
        pw_int(&w, 128, ',');
        pw_int(&w, 3, ','); /* K1: upper index of u control points */
        pw_int(&w, 3, ','); /* K2 */
        pw_int(&w, 3, ','); /* M1: degree */
        pw_int(&w, 3, ','); /* M2 */
        pw_int(&w, 0, ','); /* PROP1: not closed in u */
        pw_int(&w, 0, ','); /* PROP2 */
        pw_int(&w, 1, ','); /* PROP3: polynomial (all weights equal) */
        pw_int(&w, 0, ','); /* PROP4: not periodic in u */
        pw_int(&w, 0, ','); /* PROP5 */
        for (int d = 0; d < 2; d++)
            for (int k = -3; k <= 4; k++) pw_real(&w, (double)k, ',');
        for (int k = 0; k < 16; k++) pw_real(&w, 1.0, ',');
        /* control points: first index (u) varies fastest: cv[4*j + i] order */
        for (int k = 0; k < 16; k++)
            for (int d = 0; d < 3; d++) pw_real(&w, c[3 * k + d], ',');
        pw_real(&w, 0.0, ',');
        pw_real(&w, 1.0, ',');
        pw_real(&w, 0.0, ',');
        pw_real(&w, 1.0, ';');
        pw_flush(&w);
        pstart[2 * p + 1] = w.seq + 1 - pstart[2 * p];
    }
    unsigned long nplines = w.seq;
    /* Start section */
    pwriter s = {.fp = fp, .sect = 'S'};
    snprintf(s.line, sizeof s.line, "seamquad: Catmull-Clark surface, %u bicubic B-spline patches", np);
    pw_flush(&s);
    /* Global section */
    char stamp[32] = "19700101.000000";
    time_t now = time(NULL);
    struct tm tmv;
    if (gmtime_r(&now, &tmv)) strftime(stamp, sizeof stamp, "%Y%m%d.%H%M%S", &tmv);
    pwriter g = {.fp = fp, .sect = 'G'};
    pw_token(&g, "1H,", ',');
    pw_token(&g, "1H;", ',');
    pw_hollerith(&g, name ? name : "seamquad", ',');       /* sender product id */
    pw_hollerith(&g, base_name(path), ',');                /* file name */
    pw_hollerith(&g, "seamquad", ',');                     /* native system */
    pw_hollerith(&g, "seamquad 0.1.0", ',');               /* preprocessor version */
    pw_int(&g, 32, ',');                                   /* integer bits */
    pw_int(&g, 38, ',');                                   /* single: max power */
    pw_int(&g, 6, ',');                                    /* single: digits */
    pw_int(&g, 308, ',');                                  /* double: max power */
    pw_int(&g, 15, ',');                                   /* double: digits */
    pw_hollerith(&g, name ? name : "seamquad", ',');       /* receiver product id */
    pw_real(&g, 1.0, ',');                                 /* model space scale */
    pw_int(&g, 2, ',');                                    /* units: millimetres */
    pw_hollerith(&g, "MM", ',');
    pw_int(&g, 1, ',');                                    /* line weight gradations */
    pw_real(&g, 1.0, ',');                                 /* max line width */
    pw_hollerith(&g, stamp, ',');                          /* file date */
    pw_real(&g, 1e-7 * (scale > 0 ? scale : 1.0), ',');    /* resolution */
    pw_real(&g, 0.0, ',');                                 /* max coordinate: unknown */
    pw_hollerith(&g, "seamquad", ',');                     /* author */
    pw_hollerith(&g, "seamquad", ',');                     /* organization */
    pw_int(&g, 11, ',');                                   /* IGES 5.3 */
    pw_int(&g, 0, ',');                                    /* drafting standard */
    pw_hollerith(&g, stamp, ';');                          /* model date */
    pw_flush(&g);
    /* Directory entries */
    for (uint32_t p = 0; p < np; p++) {
        unsigned long d = 2 * (unsigned long)p + 1;
        fprintf(fp, "%8d%8lu%8d%8d%8d%8d%8d%8d%8s%c%7lu\n", 128, pstart[2 * p], 0, 0, 0, 0, 0, 0,
                "00000000", 'D', d);
        fprintf(fp, "%8d%8d%8d%8lu%8d%8s%8s%8s%8d%c%7lu\n", 128, 0, 0, pstart[2 * p + 1], 0, "",
                "", "PATCH", (int)(p % 100000000), 'D', d + 1);
    }
    /* Parameter data */
    rewind(pd);
    char buf[1 << 14];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pd)) > 0) fwrite(buf, 1, n, fp);
    int bad = ferror(pd);
    fclose(pd);
    free(pstart);
    /* Terminate */
    fprintf(fp, "S%7luG%7luD%7luP%7lu%40s%c%7d\n", s.seq, g.seq, 2 * (unsigned long)np, nplines,
            "", 'T', 1);
    if (bad || ferror(fp)) {
        sq_atomic_abort(&af);
        return sq_error_set(err, SQ_ERR_IO, "%s: write failed", path);
    }
    return sq_atomic_commit(&af, err);
}
