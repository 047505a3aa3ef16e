/* Cross-check of our hand-written mesh readers (sq_read_mesh) against
 * OpenMesh 9.0's readers, on every mesh of ../shared/data/MANIFEST.tsv.
 *
 * Three readings of each file are compared:
 *   - seamquad: sq_read_mesh (the product's reader);
 *   - OpenMesh: OpenMesh::IO::read_mesh through core/sq_openmesh_adapter.h;
 *   - the file itself: a deliberately naive line reader in this test that
 *     hands each number token to libc's strtod and strtof. It is the
 *     referee: when the two tools disagree, it says which one is right.
 *
 * What OpenMesh 9.0 does with these files (found with this test):
 *   - Precision. Its OBJ and ASCII OFF readers parse coordinates (and `vt`)
 *     as float (`stream >> float`), then widen them into the mesh, so a
 *     mesh with double points still holds float values: 958,465 of the
 *     963,861 coordinates of the shared meshes are not float values and
 *     OpenMesh changes each of them, by up to 2^-24 relative (the mpz files
 *     print 17 significant digits; OFF files lose too). So OpenMesh can only
 *     confirm our coordinates at float precision: we require OpenMesh to be
 *     bit-identical to strtof(token) and seamquad to be bit-identical to
 *     strtod(token), for every coordinate of every vertex. Where
 *     (float)strtod(token) != strtof(token) (double rounding) the tools
 *     cannot agree bit for bit although both are right; such coordinates
 *     are counted and reported, not failed.
 *   - Texture coordinates. The mpz files carry a seamless UV (`f v/vt`,
 *     more `vt` than `v`: corners of one vertex have different UVs across
 *     seams). OpenMesh 9.0 does NOT split vertices for them, neither with
 *     its default options (it ignores `vt`) nor when UVs are requested
 *     (it stores them per halfedge): vertex and face sets stay those of the
 *     file. The test reads every file with `vt` both ways and checks this,
 *     and checks OpenMesh's per-corner UVs against ours at float precision.
 *   - Face order and corners: faces keep the file's order and, on these
 *     files, OpenMesh lists every face from the file's first corner. As its
 *     face circulator starts wherever the face's halfedge points, faces are
 *     compared as cyclic sequences (rotation allowed, reversal not). Our
 *     reader must reproduce the file's face exactly.
 *   - Altered input. On non-manifold or inconsistently oriented input,
 *     OpenMesh's importer re-attaches the face it cannot add to fresh
 *     copies of its vertices (flagged "fixed non-manifold"), and its OBJ
 *     reader drops a face whose corners repeat a vertex down to fewer than
 *     3; it reports neither as an error. None of the shared meshes triggers
 *     this (they are manifold and consistently oriented), but the test
 *     proves on tests/data/broken/ that each alteration is detected,
 *     counted and blamed on OpenMesh, and that a fault planted in our own
 *     soup is blamed on seamquad.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_openmesh_adapter.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif
#ifndef SQ_TEST_DATA_DIR
#define SQ_TEST_DATA_DIR "tests/data"
#endif

/* ------------------------------------------------------------------------
 * Growable arrays (test helper).
 * ------------------------------------------------------------------------ */

static int grow(void **p, size_t *cap, size_t need, size_t elt)
{
    if (need <= *cap) return 0;
    size_t n = *cap ? *cap : 64;
    while (n < need) n *= 2;
    void *q = realloc(*p, n * elt);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

/* ------------------------------------------------------------------------
 * The referee: what the file says, read as naively as possible.
 * Supports the OBJ and OFF layouts of the shared data: one element per
 * line, `#` comments. Each coordinate token goes to strtod and to strtof.
 * ------------------------------------------------------------------------ */

typedef struct ref_mesh {
    uint32_t nv, nf, nuv;
    double *pd;             /* 3*nv: strtod of each coordinate token  */
    float *pf;              /* 3*nv: strtof of the same tokens        */
    uint32_t *vline;        /* nv                                     */
    double *uvd;            /* 2*nuv                                  */
    float *uvf;             /* 2*nuv                                  */
    uint32_t *foff;         /* nf+1                                   */
    uint32_t *fidx;         /* corners: 0-based position index        */
    uint32_t *fuv;          /* corners: 0-based uv index or SQ_NONE   */
    uint32_t *fline;        /* nf                                     */
    int any_face_uv;
    size_t cap_p, cap_f, cap_vl, cap_uvd, cap_uvf, cap_fo, cap_fi, cap_fu, cap_fl;
    char msg[512];
} ref_mesh;

static void ref_free(ref_mesh *r)
{
    free(r->pd); free(r->pf); free(r->vline); free(r->uvd); free(r->uvf);
    free(r->foff); free(r->fidx); free(r->fuv); free(r->fline);
    memset(r, 0, sizeof *r);
}

static int ref_fail(ref_mesh *r, const char *path, unsigned line, const char *what)
{
    snprintf(r->msg, sizeof r->msg, "referee: %s:%u: %s", path, line, what);
    return -1;
}

/* Parses n numbers from *s with strtod and strtof, which must consume the
 * same characters. Returns 0 on success. */
static int ref_numbers(char **s, int n, double *d, float *f)
{
    for (int k = 0; k < n; k++) {
        char *e1, *e2;
        d[k] = strtod(*s, &e1);
        f[k] = strtof(*s, &e2);
        if (e1 == *s || e1 != e2) return -1;
        *s = e1;
    }
    return 0;
}

static int ref_add_vertex(ref_mesh *r, const double *d, const float *f, uint32_t line)
{
    size_t n = (size_t)r->nv + 1;
    if (grow((void **)&r->pd, &r->cap_p, 3 * n, sizeof *r->pd) ||
        grow((void **)&r->pf, &r->cap_f, 3 * n, sizeof *r->pf) ||
        grow((void **)&r->vline, &r->cap_vl, n, sizeof *r->vline))
        return -1;
    memcpy(r->pd + 3 * r->nv, d, 3 * sizeof *d);
    memcpy(r->pf + 3 * r->nv, f, 3 * sizeof *f);
    r->vline[r->nv++] = line;
    return 0;
}

static int ref_begin_face(ref_mesh *r, uint32_t line)
{
    size_t n = (size_t)r->nf + 2;
    if (grow((void **)&r->foff, &r->cap_fo, n, sizeof *r->foff) ||
        grow((void **)&r->fline, &r->cap_fl, n, sizeof *r->fline))
        return -1;
    if (r->nf == 0) r->foff[0] = 0;
    r->fline[r->nf] = line;
    return 0;
}

/* Appends a corner to the face being built; foff[nf+1] is its running end. */
static int ref_push_corner(ref_mesh *r, uint32_t *end, uint32_t v, uint32_t uv)
{
    size_t n = (size_t)*end + 1;
    if (grow((void **)&r->fidx, &r->cap_fi, n, sizeof *r->fidx) ||
        grow((void **)&r->fuv, &r->cap_fu, n, sizeof *r->fuv))
        return -1;
    r->fidx[*end] = v;
    r->fuv[*end] = uv;
    (*end)++;
    return 0;
}

/* OBJ index: 1-based, or negative relative to the `count` elements seen so
 * far. Returns SQ_NONE when invalid. */
static uint32_t ref_obj_index(long i, uint32_t count)
{
    if (i > 0 && (unsigned long)i <= count) return (uint32_t)(i - 1);
    if (i < 0 && (unsigned long)(-i) <= count) return (uint32_t)((long)count + i);
    return SQ_NONE;
}

static int ref_read_obj(ref_mesh *r, FILE *fp, const char *path)
{
    char *buf = NULL;
    size_t bufcap = 0;
    ssize_t len;
    uint32_t line = 0;
    int rc = 0;
    while (rc == 0 && (len = getline(&buf, &bufcap, fp)) >= 0) {
        line++;
        char *s = buf;
        while (*s == ' ' || *s == '\t') s++;
        if (s[0] == 'v' && (s[1] == ' ' || s[1] == '\t')) {
            double d[3];
            float f[3];
            s += 2;
            if (ref_numbers(&s, 3, d, f)) rc = ref_fail(r, path, line, "bad vertex");
            else if (ref_add_vertex(r, d, f, line)) rc = ref_fail(r, path, line, "out of memory");
        } else if (s[0] == 'v' && s[1] == 't' && (s[2] == ' ' || s[2] == '\t')) {
            double d[2];
            float f[2];
            s += 3;
            size_t n = (size_t)r->nuv + 1;
            if (ref_numbers(&s, 2, d, f)) rc = ref_fail(r, path, line, "bad texture coordinate");
            else if (grow((void **)&r->uvd, &r->cap_uvd, 2 * n, sizeof *r->uvd) ||
                     grow((void **)&r->uvf, &r->cap_uvf, 2 * n, sizeof *r->uvf))
                rc = ref_fail(r, path, line, "out of memory");
            else {
                memcpy(r->uvd + 2 * r->nuv, d, sizeof d);
                memcpy(r->uvf + 2 * r->nuv, f, sizeof f);
                r->nuv++;
            }
        } else if (s[0] == 'f' && (s[1] == ' ' || s[1] == '\t')) {
            s += 2;
            if (ref_begin_face(r, line)) {
                rc = ref_fail(r, path, line, "out of memory");
                break;
            }
            uint32_t end = r->foff[r->nf];
            for (;;) {
                while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
                if (*s == '\0') break;
                char *e;
                long vi = strtol(s, &e, 10);
                if (e == s) {
                    rc = ref_fail(r, path, line, "bad face corner");
                    break;
                }
                uint32_t uv = SQ_NONE;
                s = e;
                if (*s == '/') {
                    s++;
                    if (*s != '/') {
                        long ti = strtol(s, &e, 10);
                        if (e == s) {
                            rc = ref_fail(r, path, line, "bad texture index");
                            break;
                        }
                        uv = ref_obj_index(ti, r->nuv);
                        r->any_face_uv = 1;
                        s = e;
                    }
                    if (*s == '/') {
                        s++;
                        (void)strtol(s, &e, 10);
                        s = e;
                    }
                }
                /* Forward references are legal in OBJ: keep raw 1-based
                 * positive indices and resolve them after the file. */
                uint32_t v = vi < 0 ? ref_obj_index(vi, r->nv) : (uint32_t)(vi - 1);
                if (vi == 0 || v == SQ_NONE) {
                    rc = ref_fail(r, path, line, "vertex index out of range");
                    break;
                }
                if (ref_push_corner(r, &end, v, uv)) {
                    rc = ref_fail(r, path, line, "out of memory");
                    break;
                }
            }
            if (rc == 0) r->foff[++r->nf] = end;
        }
        /* everything else (vn, o, g, s, usemtl, mtllib, comments) is not
         * part of the surface */
    }
    free(buf);
    if (rc == 0 && r->nf == 0) {
        r->foff = calloc(1, sizeof *r->foff);
        if (!r->foff) rc = ref_fail(r, path, line, "out of memory");
    }
    for (uint32_t c = 0; rc == 0 && r->nf && c < r->foff[r->nf]; c++)
        if (r->fidx[c] >= r->nv) rc = ref_fail(r, path, 0, "face refers past the last vertex");
    return rc;
}

/* Next line that is not blank and not a comment; NULL at end of file. */
static char *ref_off_line(FILE *fp, char **buf, size_t *cap, uint32_t *line)
{
    while (getline(buf, cap, fp) >= 0) {
        (*line)++;
        char *s = *buf;
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
        if (*s != '\0' && *s != '#') return s;
    }
    return NULL;
}

static int ref_read_off(ref_mesh *r, FILE *fp, const char *path)
{
    char *buf = NULL;
    size_t cap = 0;
    uint32_t line = 0;
    int rc = 0;
    char *s = ref_off_line(fp, &buf, &cap, &line);
    if (!s || strncmp(s, "OFF", 3) != 0) {
        free(buf);
        return ref_fail(r, path, line, "no OFF header");
    }
    s += 3;
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
    if (*s == '\0' || *s == '#') s = ref_off_line(fp, &buf, &cap, &line);
    char *e;
    long nv = s ? strtol(s, &e, 10) : -1;
    long nf = s ? strtol(e, &e, 10) : -1;
    if (nv < 0 || nf < 0) {
        free(buf);
        return ref_fail(r, path, line, "bad OFF counts");
    }
    for (long i = 0; rc == 0 && i < nv; i++) {
        double d[3];
        float f[3];
        s = ref_off_line(fp, &buf, &cap, &line);
        if (!s || ref_numbers(&s, 3, d, f)) rc = ref_fail(r, path, line, "bad vertex");
        else if (ref_add_vertex(r, d, f, line)) rc = ref_fail(r, path, line, "out of memory");
    }
    r->foff = calloc(1, sizeof *r->foff);
    if (!r->foff && rc == 0) rc = ref_fail(r, path, line, "out of memory");
    for (long i = 0; rc == 0 && i < nf; i++) {
        s = ref_off_line(fp, &buf, &cap, &line);
        long k = s ? strtol(s, &e, 10) : -1;
        if (k < 1) {
            rc = ref_fail(r, path, line, "bad face valence");
            break;
        }
        if (ref_begin_face(r, line)) {
            rc = ref_fail(r, path, line, "out of memory");
            break;
        }
        uint32_t end = r->foff[r->nf];
        for (long j = 0; j < k; j++) {
            char *e2;
            long vi = strtol(e, &e2, 10);
            if (e2 == e || vi < 0 || vi >= nv) {
                rc = ref_fail(r, path, line, "bad face index");
                break;
            }
            e = e2;
            if (ref_push_corner(r, &end, (uint32_t)vi, SQ_NONE)) {
                rc = ref_fail(r, path, line, "out of memory");
                break;
            }
        }
        if (rc == 0) r->foff[++r->nf] = end;
    }
    free(buf);
    return rc;
}

static int ref_read(const char *path, ref_mesh *r)
{
    memset(r, 0, sizeof *r);
    FILE *fp = fopen(path, "r");
    if (!fp) {
        snprintf(r->msg, sizeof r->msg, "referee: cannot open %s: %s", path, strerror(errno));
        return -1;
    }
    size_t n = strlen(path);
    int rc;
    if (n > 4 && strcmp(path + n - 4, ".obj") == 0) rc = ref_read_obj(r, fp, path);
    else if (n > 4 && strcmp(path + n - 4, ".off") == 0) rc = ref_read_off(r, fp, path);
    else rc = ref_fail(r, path, 0, "the referee reads only .obj and .off");
    fclose(fp);
    if (rc) {
        char keep[sizeof r->msg];
        memcpy(keep, r->msg, sizeof keep);
        ref_free(r);
        memcpy(r->msg, keep, sizeof keep);
    }
    return rc;
}

/* ------------------------------------------------------------------------
 * The comparison. Every finding names the file, line and element, and
 * which tool disagrees with the file.
 * ------------------------------------------------------------------------ */

#define XC_LOG_MAX 24

typedef struct xc_result {
    /* disagreements with the file */
    uint32_t ours_wrong;        /* elements seamquad read differently      */
    uint32_t om_wrong;          /* elements OpenMesh read differently      */
    /* what OpenMesh changed, by kind */
    uint32_t om_added_vertices; /* vertices beyond the file's              */
    uint32_t om_dropped_faces;  /* file faces missing from OpenMesh        */
    uint32_t om_reattached;     /* faces moved onto copies of vertices     */
    uint32_t om_changed_faces;  /* faces with other corners                */
    uint32_t om_extra_faces;    /* faces the file does not have            */
    /* information */
    uint64_t coords;            /* coordinates compared                    */
    uint64_t coords_not_float;  /* file coordinate not a float value       */
    uint64_t double_rounding;   /* (float)strtod != strtof                 */
    uint32_t rotated_faces;     /* OpenMesh starts the face elsewhere      */
    uint64_t uv_checked;        /* OpenMesh corner UVs compared            */
    int nlog;
    char log[XC_LOG_MAX * 256];
    size_t loglen;
} xc_result;

static void xc_note(xc_result *x, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void xc_note(xc_result *x, const char *fmt, ...)
{
    if (x->nlog++ >= XC_LOG_MAX) return;
    size_t room = sizeof x->log - x->loglen;
    if (room < 2) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(x->log + x->loglen, room - 1, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    x->loglen += (size_t)n < room - 1 ? (size_t)n : room - 2;
    x->log[x->loglen++] = '\n';
    x->log[x->loglen] = '\0';
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static const char *axis_name(int k)
{
    return k == 0 ? "x" : k == 1 ? "y" : "z";
}

static void xc_vertices(const char *name, const ref_mesh *r, const sq_soup *s,
                        const sq_om_mesh *om, xc_result *x)
{
    if (s->nv != r->nv) {
        x->ours_wrong++;
        xc_note(x, "%s: the file has %u vertices, seamquad read %u", name, r->nv, s->nv);
    }
    if (om->nv != r->nv) {
        x->om_wrong++;
        xc_note(x, "%s: the file has %u vertices, OpenMesh has %u (%u flagged by OpenMesh as copies it made)",
                name, r->nv, om->nv, om->n_vert_fixed);
    }
    for (uint32_t v = 0; v < r->nv; v++) {
        for (int k = 0; k < 3; k++) {
            double fd = r->pd[3 * v + k];
            double ff = (double)r->pf[3 * v + k];
            x->coords++;
            if (!same_bits(fd, ff)) x->coords_not_float++;
            if (!same_bits((double)(float)fd, ff)) x->double_rounding++;
            if (v < s->nv && !same_bits(s->pos[3 * v + k], fd)) {
                x->ours_wrong++;
                xc_note(x, "%s:%u: vertex %u %s: file says %.17g, seamquad read %.17g (wrong), "
                        "OpenMesh %.9g", name, r->vline[v], v, axis_name(k), fd,
                        s->pos[3 * v + k], v < om->nv ? om->pos[3 * v + k] : 0.0);
            }
            if (v < om->nv && !same_bits(om->pos[3 * v + k], ff)) {
                x->om_wrong++;
                xc_note(x, "%s:%u: vertex %u %s: file says %.17g (float %.9g), OpenMesh read %.17g (wrong), "
                        "seamquad %.17g", name, r->vline[v], v, axis_name(k), fd, ff,
                        om->pos[3 * v + k], v < s->nv ? s->pos[3 * v + k] : 0.0);
            }
        }
        if (s->vert_line && v < s->nv && s->vert_line[v] != r->vline[v]) {
            x->ours_wrong++;
            xc_note(x, "%s:%u: vertex %u: seamquad records it at line %u", name, r->vline[v], v,
                    s->vert_line[v]);
        }
    }
    for (uint32_t v = r->nv; v < om->nv; v++) {
        x->om_added_vertices++;
        xc_note(x, "%s: OpenMesh vertex %u (%.9g %.9g %.9g) is not in the file%s", name, v,
                om->pos[3 * v], om->pos[3 * v + 1], om->pos[3 * v + 2],
                om->vert_fixed[v] ? " (OpenMesh flags it as a copy it made: fixed non-manifold)" : "");
    }
}

/* Rotation r such that OpenMesh face k, started r corners later, equals
 * file face j; with `copies`, a corner may instead be a vertex OpenMesh
 * added beyond the file's that sits exactly where the file's vertex sits in
 * OpenMesh. Returns -1 when there is none. */
static int om_face_rotation(const ref_mesh *r, uint32_t j, const sq_om_mesh *om, uint32_t k,
                            int copies)
{
    uint32_t n = r->foff[j + 1] - r->foff[j];
    if (om->face_off[k + 1] - om->face_off[k] != n) return -1;
    const uint32_t *a = r->fidx + r->foff[j];
    const uint32_t *b = om->face_idx + om->face_off[k];
    for (uint32_t rot = 0; rot < n; rot++) {
        uint32_t c;
        for (c = 0; c < n; c++) {
            uint32_t fv = a[c], ov = b[(c + rot) % n];
            if (ov == fv) continue;
            if (copies && ov >= r->nv && ov < om->nv && fv < om->nv &&
                same_bits(om->pos[3 * ov], om->pos[3 * fv]) &&
                same_bits(om->pos[3 * ov + 1], om->pos[3 * fv + 1]) &&
                same_bits(om->pos[3 * ov + 2], om->pos[3 * fv + 2]))
                continue;
            break;
        }
        if (c == n) return (int)rot;
    }
    return -1;
}

static void face_text(char *buf, size_t n, const uint32_t *idx, uint32_t cnt)
{
    size_t used = 0;
    buf[0] = '\0';
    for (uint32_t c = 0; c < cnt && used + 12 < n; c++)
        used += (size_t)snprintf(buf + used, n - used, c ? " %u" : "%u", idx[c]);
}

static void xc_ours_faces(const char *name, const ref_mesh *r, const sq_soup *s, xc_result *x)
{
    if (s->nf != r->nf) {
        x->ours_wrong++;
        xc_note(x, "%s: the file has %u faces, seamquad read %u", name, r->nf, s->nf);
    }
    uint32_t nf = s->nf < r->nf ? s->nf : r->nf;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t n = r->foff[f + 1] - r->foff[f];
        int same = s->face_off[f + 1] - s->face_off[f] == n &&
                   memcmp(s->face_idx + s->face_off[f], r->fidx + r->foff[f], n * sizeof(uint32_t)) == 0;
        if (!same) {
            char a[128], b[128];
            face_text(a, sizeof a, r->fidx + r->foff[f], n);
            face_text(b, sizeof b, s->face_idx + s->face_off[f], s->face_off[f + 1] - s->face_off[f]);
            x->ours_wrong++;
            xc_note(x, "%s:%u: face %u: file says (0-based %s), seamquad read (%s) (wrong)", name,
                    r->fline[f], f, a, b);
        }
        if (s->face_line && s->face_line[f] != r->fline[f]) {
            x->ours_wrong++;
            xc_note(x, "%s:%u: face %u: seamquad records it at line %u", name, r->fline[f], f,
                    s->face_line[f]);
        }
        /* texture coordinates of the corners */
        if (same && r->any_face_uv) {
            for (uint32_t c = 0; c < n; c++) {
                uint32_t ru = r->fuv[r->foff[f] + c];
                uint32_t su = s->face_uv ? s->face_uv[s->face_off[f] + c] : SQ_NONE;
                if (ru != su) {
                    x->ours_wrong++;
                    xc_note(x, "%s:%u: face %u corner %u: file uses uv %d, seamquad %d", name,
                            r->fline[f], f, c, ru == SQ_NONE ? -1 : (int)ru, su == SQ_NONE ? -1 : (int)su);
                }
            }
        }
    }
    if (s->nuv != r->nuv) {
        x->ours_wrong++;
        xc_note(x, "%s: the file has %u texture coordinates, seamquad read %u", name, r->nuv, s->nuv);
    }
    for (uint32_t t = 0; t < r->nuv && t < s->nuv; t++)
        for (int k = 0; k < 2; k++)
            if (!same_bits(s->uv[2 * t + k], r->uvd[2 * t + k])) {
                x->ours_wrong++;
                xc_note(x, "%s: texture coordinate %u: file says %.17g, seamquad read %.17g", name, t,
                        r->uvd[2 * t + k], s->uv[2 * t + k]);
            }
}

static void xc_om_faces(const char *name, const ref_mesh *r, const sq_om_mesh *om, xc_result *x)
{
    uint32_t j = 0, k = 0;
    char a[128], b[128];
    while (j < r->nf && k < om->nf) {
        int rot = om_face_rotation(r, j, om, k, 0);
        if (rot >= 0) {
            if (rot) x->rotated_faces++;
            if (om->corner_uv) {
                uint32_t n = r->foff[j + 1] - r->foff[j];
                for (uint32_t c = 0; c < n; c++) {
                    uint32_t ru = r->fuv[r->foff[j] + c];
                    uint32_t oc = om->face_off[k] + (c + (uint32_t)rot) % n;
                    if (ru == SQ_NONE) continue;
                    x->uv_checked++;
                    for (int q = 0; q < 2; q++)
                        if (!same_bits(om->corner_uv[2 * oc + q], (double)r->uvf[2 * ru + q])) {
                            x->om_wrong++;
                            xc_note(x, "%s:%u: face %u corner %u: file's uv %u is %.9g, OpenMesh has %.9g",
                                    name, r->fline[j], j, c, ru, (double)r->uvf[2 * ru + q],
                                    om->corner_uv[2 * oc + q]);
                        }
                }
            }
            j++, k++;
            continue;
        }
        face_text(a, sizeof a, r->fidx + r->foff[j], r->foff[j + 1] - r->foff[j]);
        face_text(b, sizeof b, om->face_idx + om->face_off[k], om->face_off[k + 1] - om->face_off[k]);
        x->om_wrong++;
        if (om_face_rotation(r, j, om, k, 1) >= 0) {
            x->om_reattached++;
            xc_note(x, "%s:%u: face %u (0-based %s): OpenMesh re-attached it to new vertex copies (%s)%s",
                    name, r->fline[j], j, a, b,
                    om->face_fixed[k] ? ", flagged fixed non-manifold" : "");
            j++, k++;
        } else if (j + 1 < r->nf && om_face_rotation(r, j + 1, om, k, 1) >= 0) {
            x->om_dropped_faces++;
            xc_note(x, "%s:%u: face %u (0-based %s): missing in OpenMesh (dropped)", name, r->fline[j], j, a);
            j++;
        } else {
            x->om_changed_faces++;
            xc_note(x, "%s:%u: face %u: file says (0-based %s), OpenMesh has (%s)", name, r->fline[j], j, a, b);
            j++, k++;
        }
    }
    for (; j < r->nf; j++) {
        face_text(a, sizeof a, r->fidx + r->foff[j], r->foff[j + 1] - r->foff[j]);
        x->om_wrong++;
        x->om_dropped_faces++;
        xc_note(x, "%s:%u: face %u (0-based %s): missing in OpenMesh (dropped)", name, r->fline[j], j, a);
    }
    for (; k < om->nf; k++) {
        face_text(b, sizeof b, om->face_idx + om->face_off[k], om->face_off[k + 1] - om->face_off[k]);
        x->om_wrong++;
        x->om_extra_faces++;
        xc_note(x, "%s: OpenMesh face %u (0-based %s) is not in the file", name, k, b);
    }
}

static void xc_compare(const char *name, const ref_mesh *r, const sq_soup *s, const sq_om_mesh *om,
                       xc_result *x)
{
    memset(x, 0, sizeof *x);
    xc_vertices(name, r, s, om, x);
    xc_ours_faces(name, r, s, x);
    xc_om_faces(name, r, om, x);
}

/* The verdict line for a comparison. */
static const char *xc_verdict(const xc_result *x)
{
    if (!x->ours_wrong && !x->om_wrong) return "both agree with the file";
    if (!x->ours_wrong) return "seamquad agrees with the file, OpenMesh does not";
    if (!x->om_wrong) return "OpenMesh agrees with the file, seamquad does not";
    return "neither agrees with the file";
}

/* cmocka formats each message into a fixed buffer, so a long log is
 * printed one line at a time. */
static void print_log(const xc_result *x, int as_error)
{
    const char *p = x->log;
    while (*p) {
        int n = (int)strcspn(p, "\n");
        if (as_error) print_error("  %.*s\n", n, p);
        else print_message("  %.*s\n", n, p);
        p += n;
        if (*p == '\n') p++;
    }
    if (x->nlog > XC_LOG_MAX) {
        if (as_error) print_error("  (%d more findings not shown)\n", x->nlog - XC_LOG_MAX);
        else print_message("  (%d more findings not shown)\n", x->nlog - XC_LOG_MAX);
    }
}

/* Reads `path` three ways and compares. Returns 0 when every reading
 * worked (the comparison is in *x), else prints why and returns -1. */
static int xc_file(const char *path, const char *name, unsigned om_flags, sq_soup *s,
                   sq_om_mesh *om, ref_mesh *r, xc_result *x)
{
    sq_error err;
    memset(s, 0, sizeof *s);
    memset(om, 0, sizeof *om);
    if (ref_read(path, r) != 0) {
        print_error("%s\n", r->msg);
        return -1;
    }
    if (sq_read_mesh(path, s, &err) != SQ_OK) {
        print_error("%s: seamquad cannot read it: %s\n", name, err.msg);
        ref_free(r);
        return -1;
    }
    if (sq_openmesh_read(path, om_flags, om, &err) != SQ_OK) {
        print_error("%s: OpenMesh cannot read it: %s\n", name, err.msg);
        sq_soup_free(s);
        ref_free(r);
        return -1;
    }
    xc_compare(name, r, s, om, x);
    return 0;
}

/* ------------------------------------------------------------------------
 * The manifest.
 * ------------------------------------------------------------------------ */

typedef struct manifest {
    char **file;
    size_t n;
} manifest;

static void manifest_free(manifest *m)
{
    for (size_t i = 0; i < m->n; i++) free(m->file[i]);
    free(m->file);
    memset(m, 0, sizeof *m);
}

static void manifest_read(manifest *m)
{
    const char *path = SQ_SHARED_DIR "/data/MANIFEST.tsv";
    FILE *fp = fopen(path, "r");
    if (!fp) fail_msg("cannot open %s: %s", path, strerror(errno));
    char *buf = NULL;
    size_t cap = 0, mcap = 0;
    int col = -1;
    memset(m, 0, sizeof *m);
    while (getline(&buf, &cap, fp) >= 0) {
        buf[strcspn(buf, "\r\n")] = '\0';
        if (buf[0] == '\0') continue;
        /* field number `col` of this tab-separated line */
        char *field = buf;
        if (col < 0) {
            int i = 0;
            for (char *t = buf; t; i++) {
                char *tab = strchr(t, '\t');
                size_t len = tab ? (size_t)(tab - t) : strlen(t);
                if (len == 4 && strncmp(t, "file", 4) == 0) col = i;
                t = tab ? tab + 1 : NULL;
            }
            if (col < 0) fail_msg("%s: no column named 'file'", path);
            continue;
        }
        for (int i = 0; i < col && field; i++) {
            field = strchr(field, '\t');
            if (field) field++;
        }
        if (!field) continue;
        field[strcspn(field, "\t")] = '\0';
        if (grow((void **)&m->file, &mcap, m->n + 1, sizeof *m->file)) fail_msg("out of memory");
        m->file[m->n] = strdup(field);
        assert_non_null(m->file[m->n]);
        m->n++;
    }
    free(buf);
    fclose(fp);
    if (m->n == 0) fail_msg("%s lists no files", path);
}

static int has_mesh_extension(const char *f)
{
    size_t n = strlen(f);
    return n > 4 && (strcmp(f + n - 4, ".obj") == 0 || strcmp(f + n - 4, ".off") == 0 ||
                     strcmp(f + n - 4, ".ply") == 0);
}

/* ------------------------------------------------------------------------
 * Tests.
 * ------------------------------------------------------------------------ */

/* Every shared mesh: both tools must read exactly what the file says
 * (OpenMesh at float precision), and therefore agree with each other. Files
 * with texture coordinates are read by OpenMesh a second time with UVs
 * requested, which must not change its vertices or faces. */
static void test_manifest_meshes(void **state)
{
    (void)state;
    manifest m;
    manifest_read(&m);
    int failures = 0;
    size_t checked = 0;
    uint64_t coords = 0, not_float = 0, dr = 0, uvs = 0;
    for (size_t i = 0; i < m.n; i++) {
        if (!has_mesh_extension(m.file[i])) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/data/%s", SQ_SHARED_DIR, m.file[i]);
        for (unsigned pass = 0; pass < 2; pass++) {
            sq_soup s;
            sq_om_mesh om;
            ref_mesh r;
            xc_result x;
            unsigned flags = pass ? SQ_OM_READ_TEXCOORDS : 0;
            if (xc_file(path, m.file[i], flags, &s, &om, &r, &x) != 0) {
                failures++;
                break;
            }
            int has_uv = r.any_face_uv;
            const char *mode = pass ? " [OpenMesh with UVs]" : "";
            if (x.ours_wrong || x.om_wrong) {
                failures++;
                print_error("%s%s: %s (seamquad: %u differences, OpenMesh: %u; OpenMesh added %u vertices, "
                            "dropped %u faces, re-attached %u, changed %u, added %u)\n",
                            m.file[i], mode, xc_verdict(&x), x.ours_wrong, x.om_wrong,
                            x.om_added_vertices, x.om_dropped_faces, x.om_reattached,
                            x.om_changed_faces, x.om_extra_faces);
                print_log(&x, 1);
            } else {
                print_message("%-36s%s V %6u F %6u uv %6u: %s; coordinates not floats: %llu of %llu, "
                              "double-rounding cases: %llu, faces rotated by OpenMesh: %u, OpenMesh "
                              "corner UVs checked: %llu\n",
                              m.file[i], mode, r.nv, r.nf, r.nuv, xc_verdict(&x),
                              (unsigned long long)x.coords_not_float, (unsigned long long)x.coords,
                              (unsigned long long)x.double_rounding, x.rotated_faces,
                              (unsigned long long)x.uv_checked);
            }
            if (pass == 1 && has_uv && x.uv_checked == 0) {
                failures++;
                print_error("%s: OpenMesh returned no corner UVs although the file has them\n", m.file[i]);
            }
            if (!pass) {
                checked++;
                coords += x.coords;
                not_float += x.coords_not_float;
                dr += x.double_rounding;
            } else {
                uvs += x.uv_checked;
            }
            sq_om_mesh_free(&om);
            sq_soup_free(&s);
            ref_free(&r);
            if (!has_uv) break;
        }
    }
    print_message("%zu meshes; %llu coordinates, %llu of them not representable as float "
                  "(OpenMesh keeps the float), %llu double-rounding cases; %llu OpenMesh corner UVs\n",
                  checked, (unsigned long long)coords, (unsigned long long)not_float,
                  (unsigned long long)dr, (unsigned long long)uvs);
    manifest_free(&m);
    assert_true(checked > 0);
    assert_int_equal(failures, 0);
}

/* What OpenMesh does to input it cannot represent, and that the comparison
 * sees it and blames OpenMesh. Expected counts come from the files: each
 * re-attached face gets copies of all its corners. */
typedef struct altered_case {
    const char *file;
    uint32_t added_vertices, reattached, dropped;
} altered_case;

static void test_detects_openmesh_alterations(void **state)
{
    (void)state;
    static const altered_case cases[] = {
        /* two tetrahedra sharing vertex 0: 3 faces of the second cannot be
         * attached to vertex 0's fan */
        {"bowtie.obj", 9, 3, 0},
        /* a second tetrahedron on edge (0, 1) of the first: its two faces
         * at that edge find both halfedges taken, its other two faces meet
         * vertices 0 and 1 whose fans are already closed: all 4 faces get
         * copies of their 3 corners */
        {"nonmanifold_edge.obj", 12, 4, 0},
        /* one face against the orientation of its neighbours */
        {"flipped_face.obj", 3, 1, 0},
        /* `f 2 3 3`: OpenMesh's OBJ reader removes the repeated corner and
         * then skips the face with 2 corners left */
        {"repeated_vertex.obj", 0, 0, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/broken/%s", SQ_TEST_DATA_DIR, cases[i].file);
        sq_soup s;
        sq_om_mesh om;
        ref_mesh r;
        xc_result x;
        assert_int_equal(xc_file(path, cases[i].file, 0, &s, &om, &r, &x), 0);
        print_message("%s: %s; OpenMesh added %u vertices, re-attached %u faces, dropped %u\n",
                      cases[i].file, xc_verdict(&x), x.om_added_vertices, x.om_reattached,
                      x.om_dropped_faces);
        print_log(&x, x.ours_wrong != 0);
        assert_int_equal(x.ours_wrong, 0);
        assert_true(x.om_wrong > 0);
        assert_int_equal(x.om_added_vertices, cases[i].added_vertices);
        assert_int_equal(x.om_reattached, cases[i].reattached);
        assert_int_equal(x.om_dropped_faces, cases[i].dropped);
        assert_int_equal(x.om_changed_faces, 0);
        assert_int_equal(x.om_extra_faces, 0);
        /* OpenMesh's own flags agree with what the comparison found */
        assert_int_equal(om.n_vert_fixed, x.om_added_vertices);
        assert_int_equal(om.n_face_fixed, x.om_reattached);
        assert_true(strstr(xc_verdict(&x), "seamquad agrees") != NULL);
        sq_om_mesh_free(&om);
        sq_soup_free(&s);
        ref_free(&r);
    }
}

/* A fault planted in our soup is found and blamed on seamquad: one bit of
 * one coordinate, and one face with two corners swapped. */
static void test_detects_fault_in_our_reader(void **state)
{
    (void)state;
    const char *path = SQ_SHARED_DIR "/data/mpz/knot1.obj";
    sq_soup s;
    sq_om_mesh om;
    ref_mesh r;
    xc_result x;
    assert_int_equal(xc_file(path, "mpz/knot1.obj", 0, &s, &om, &r, &x), 0);
    assert_int_equal(x.ours_wrong, 0);
    assert_int_equal(x.om_wrong, 0);

    uint64_t bits;
    memcpy(&bits, &s.pos[3 * 17 + 1], sizeof bits);
    bits ^= 1u; /* last bit of the mantissa: invisible at float precision */
    memcpy(&s.pos[3 * 17 + 1], &bits, sizeof bits);
    uint32_t *f = s.face_idx + s.face_off[42];
    uint32_t t = f[1];
    f[1] = f[2];
    f[2] = t;

    xc_compare("mpz/knot1.obj", &r, &s, &om, &x);
    print_message("planted faults: %s\n", xc_verdict(&x));
    print_log(&x, 0);
    assert_int_equal(x.ours_wrong, 2);
    assert_int_equal(x.om_wrong, 0);
    assert_non_null(strstr(x.log, "vertex 17 y"));
    assert_non_null(strstr(x.log, "face 42"));
    sq_om_mesh_free(&om);
    sq_soup_free(&s);
    ref_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_manifest_meshes),
        cmocka_unit_test(test_detects_openmesh_alterations),
        cmocka_unit_test(test_detects_fault_in_our_reader),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
