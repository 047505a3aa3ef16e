/* seamquad: halfedge mesh construction with full validation (see sq_mesh.h).
 *
 * Twins are found without hashing: halfedges are bucketed by the smaller
 * endpoint (counting sort, O(nh)), then each bucket is ordered by the larger
 * endpoint (insertion sort for the usual small buckets, qsort for the rare
 * high-valence vertex). Equal keys are then adjacent, and every group of
 * equal keys is one undirected edge whose size and directions classify it:
 * 1 halfedge = boundary, 2 opposite = manifold, 2 equal = orientation flip,
 * more = non-manifold. */
#include "sq_mesh.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_predicates.h"

#define WHERE_MAX 600

void sq_mesh_free(sq_mesh *m)
{
    if (!m) return;
    free(m->pos);
    free(m->he_next);
    free(m->he_twin);
    free(m->he_vert);
    free(m->he_face);
    free(m->v_he);
    free(m->f_he);
    memset(m, 0, sizeof *m);
}

int64_t sq_mesh_euler(const sq_mesh *m)
{
    return (int64_t)m->nv - (int64_t)(m->nh / 2) + (int64_t)m->nf;
}

int64_t sq_mesh_genus(const sq_mesh *m)
{
    return (2 - sq_mesh_euler(m)) / 2;
}

uint32_t sq_mesh_vertex_valence(const sq_mesh *m, uint32_t v)
{
    uint32_t h0 = m->v_he[v], h = h0, n = 0;
    do {
        n++;
        h = m->he_next[m->he_twin[h]];
    } while (h != h0);
    return n;
}

/* "FILE:LINE: " prefix for face f, or "" without provenance. */
static const char *face_prefix(const sq_soup *s, uint32_t f, char *buf)
{
    char w[WHERE_MAX - 4];
    sq_soup_where_face(s, f, w, sizeof w);
    if (w[0]) snprintf(buf, WHERE_MAX, "%s: ", w);
    else buf[0] = '\0';
    return buf;
}

static const char *vertex_prefix(const sq_soup *s, uint32_t v, char *buf)
{
    char w[WHERE_MAX - 4];
    sq_soup_where_vertex(s, v, w, sizeof w);
    if (w[0]) snprintf(buf, WHERE_MAX, "%s: ", w);
    else buf[0] = '\0';
    return buf;
}

/* " (and N more)" or "" */
static const char *more(uint32_t n, char *buf, size_t size, const char *what)
{
    if (n > 0) snprintf(buf, size, " (and %u more %s)", n, what);
    else buf[0] = '\0';
    return buf;
}

/* "face F (line L)" / "face F (record R)" / "face F" for use after a file
 * prefix. */
static const char *face_ref(const sq_soup *s, uint32_t f, char *buf, size_t n)
{
    if (s->face_line)
        snprintf(buf, n, "%u (%s %u)", f, s->line_kind == 1 ? "record" : "line", s->face_line[f]);
    else
        snprintf(buf, n, "%u", f);
    return buf;
}

static const char *file_prefix(const sq_soup *s, char *buf)
{
    if (s->path) snprintf(buf, WHERE_MAX, "%s: ", s->path);
    else buf[0] = '\0';
    return buf;
}

/* ---- step 1: per-element checks -------------------------------------- */

static sq_status check_vertices(const sq_soup *s, sq_error *err)
{
    uint32_t bad = 0, first = 0;
    for (uint32_t v = 0; v < s->nv; v++) {
        const double *p = s->pos + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            if (bad++ == 0) first = v;
        }
    }
    if (bad) {
        char pre[WHERE_MAX], m[64];
        const double *p = s->pos + 3 * (size_t)first;
        return sq_error_set(err, SQ_ERR_NOT_FINITE,
                            "%svertex %u has a non-finite coordinate (%g, %g, %g)%s",
                            vertex_prefix(s, first, pre), first, p[0], p[1], p[2],
                            more(bad - 1, m, sizeof m, "such vertices"));
    }
    return SQ_OK;
}

static sq_status check_faces(const sq_soup *s, unsigned flags, sq_error *err)
{
    char pre[WHERE_MAX];
    for (uint32_t f = 0; f < s->nf; f++) {
        uint32_t b = s->face_off[f], e = s->face_off[f + 1], deg = e - b;
        if (deg < 3 || (!(flags & SQ_MESH_ALLOW_POLYGONS) && deg != 3)) {
            uint32_t polys = 0;
            for (uint32_t g = f + 1; g < s->nf; g++) {
                uint32_t dg = s->face_off[g + 1] - s->face_off[g];
                if (dg < 3 || (!(flags & SQ_MESH_ALLOW_POLYGONS) && dg != 3)) polys++;
            }
            char m[64];
            if (flags & SQ_MESH_ALLOW_POLYGONS)
                return sq_error_set(err, SQ_ERR_POLYGON,
                                    "%sface %u has %u vertices; faces need at least 3%s",
                                    face_prefix(s, f, pre), f, deg,
                                    more(polys, m, sizeof m, "such faces"));
            return sq_error_set(err, SQ_ERR_POLYGON,
                                "%sface %u is a polygon with %u vertices; the input must be a "
                                "triangle mesh%s",
                                face_prefix(s, f, pre), f, deg,
                                more(polys, m, sizeof m, "non-triangles"));
        }
        for (uint32_t c = b; c < e; c++) {
            if (s->face_idx[c] >= s->nv)
                return sq_error_set(err, SQ_ERR_INDEX,
                                    "%sface %u uses vertex %u, but there are only %u vertices",
                                    face_prefix(s, f, pre), f, s->face_idx[c], s->nv);
        }
        for (uint32_t c = b; c < e; c++) {
            for (uint32_t d = c + 1; d < e; d++) {
                if (s->face_idx[c] == s->face_idx[d])
                    return sq_error_set(err, SQ_ERR_REPEATED_VERTEX,
                                        "%sface %u uses vertex %u twice",
                                        face_prefix(s, f, pre), f, s->face_idx[c]);
            }
        }
    }
    return SQ_OK;
}

static sq_status check_referenced(const sq_soup *s, sq_error *err)
{
    uint8_t *used = calloc(s->nv, 1);
    if (!used) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (%u vertices)", s->nv);
    for (uint32_t c = 0; c < s->face_off[s->nf]; c++) used[s->face_idx[c]] = 1;
    uint32_t unused = 0, first = 0;
    for (uint32_t v = 0; v < s->nv; v++) {
        if (!used[v] && unused++ == 0) first = v;
    }
    free(used);
    if (unused) {
        char pre[WHERE_MAX], m[64];
        return sq_error_set(err, SQ_ERR_UNREFERENCED,
                            "%svertex %u is not used by any face%s; every vertex must belong "
                            "to the surface",
                            vertex_prefix(s, first, pre), first,
                            more(unused - 1, m, sizeof m, "unused vertices"));
    }
    return SQ_OK;
}

/* ---- step 2: twins -------------------------------------------------- */

typedef struct edge_key {
    uint32_t hi;   /* larger endpoint */
    uint32_t h;    /* halfedge */
} edge_key;

static int cmp_edge_key(const void *a, const void *b)
{
    const edge_key *x = a, *y = b;
    if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
    return x->h < y->h ? -1 : (x->h > y->h);
}

static void sort_bucket(edge_key *k, uint32_t n)
{
    if (n > 32) {
        qsort(k, n, sizeof *k, cmp_edge_key);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        edge_key t = k[i];
        uint32_t j = i;
        while (j > 0 && cmp_edge_key(&k[j - 1], &t) > 0) {
            k[j] = k[j - 1];
            j--;
        }
        k[j] = t;
    }
}

static inline uint32_t he_dst(const sq_mesh *m, uint32_t h)
{
    return m->he_vert[m->he_next[h]];
}

/* Sorts halfedges by undirected edge; fills keys (nh) and bucket offsets
 * start (nv+1) by smaller endpoint. */
static sq_status bucket_edges(const sq_mesh *m, edge_key **keys_out, uint32_t **start_out,
                              sq_error *err)
{
    uint32_t *start = calloc((size_t)m->nv + 1, sizeof *start);
    edge_key *keys = malloc((size_t)m->nh * sizeof *keys);
    uint32_t *fill = malloc((size_t)m->nv * sizeof *fill);
    if (!start || !keys || !fill) {
        free(start);
        free(keys);
        free(fill);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (%u halfedges)", m->nh);
    }
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t a = m->he_vert[h], b = he_dst(m, h);
        start[(a < b ? a : b) + 1]++;
    }
    for (uint32_t v = 0; v < m->nv; v++) start[v + 1] += start[v];
    memcpy(fill, start, (size_t)m->nv * sizeof *fill);
    for (uint32_t h = 0; h < m->nh; h++) {
        uint32_t a = m->he_vert[h], b = he_dst(m, h);
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
        keys[fill[lo]++] = (edge_key){hi, h};
    }
    free(fill);
    for (uint32_t v = 0; v < m->nv; v++) sort_bucket(keys + start[v], start[v + 1] - start[v]);
    *keys_out = keys;
    *start_out = start;
    return SQ_OK;
}

typedef struct edge_problems {
    uint32_t count, first_lo, first_at, first_n;   /* first_at: index into keys */
} edge_problems;

static sq_status match_twins(const sq_soup *s, sq_mesh *m, sq_error *err)
{
    edge_key *keys = NULL;
    uint32_t *start = NULL;
    sq_status st = bucket_edges(m, &keys, &start, err);
    if (st) return st;

    edge_problems nonman = {0}, flip = {0}, open = {0};
    for (uint32_t lo = 0; lo < m->nv; lo++) {
        uint32_t i = start[lo], e = start[lo + 1];
        while (i < e) {
            uint32_t j = i + 1;
            while (j < e && keys[j].hi == keys[i].hi) j++;
            uint32_t n = j - i;
            edge_problems *p = NULL;
            if (n == 1) {
                p = &open;
            } else if (n > 2) {
                p = &nonman;
            } else {
                uint32_t h0 = keys[i].h, h1 = keys[i + 1].h;
                if (m->he_vert[h0] == m->he_vert[h1]) {
                    p = &flip;
                } else {
                    m->he_twin[h0] = h1;
                    m->he_twin[h1] = h0;
                }
            }
            if (p && p->count++ == 0) {
                p->first_lo = lo;
                p->first_at = i;
                p->first_n = n;
            }
            i = j;
        }
    }

    char pre[WHERE_MAX], fa[WHERE_MAX], fb[WHERE_MAX], m1[64];
    if (nonman.count) {
        const edge_key *k = keys + nonman.first_at;
        char faces[WHERE_MAX];
        size_t len = 0;
        faces[0] = '\0';
        for (uint32_t t = 0; t < nonman.first_n && t < 4 && len < sizeof faces; t++) {
            char fr[64];
            len += (size_t)snprintf(faces + len, sizeof faces - len, "%s%s", t ? ", " : "",
                                    face_ref(s, m->he_face[k[t].h], fr, sizeof fr));
        }
        st = sq_error_set(err, SQ_ERR_NONMANIFOLD_EDGE,
                          "%snon-manifold edge (%u, %u): shared by %u faces (faces %s%s)%s",
                          file_prefix(s, pre), nonman.first_lo, k->hi, nonman.first_n, faces,
                          nonman.first_n > 4 ? ", ..." : "",
                          more(nonman.count - 1, m1, sizeof m1, "non-manifold edges"));
    } else if (flip.count) {
        const edge_key *k = keys + flip.first_at;
        face_ref(s, m->he_face[k[0].h], fa, sizeof fa);
        face_ref(s, m->he_face[k[1].h], fb, sizeof fb);
        st = sq_error_set(err, SQ_ERR_ORIENTATION,
                          "%sinconsistent orientation: faces %s and %s both traverse edge "
                          "%u -> %u in the same direction (a flipped face?)%s",
                          file_prefix(s, pre), fa, fb, m->he_vert[k[0].h], he_dst(m, k[0].h),
                          more(flip.count - 1, m1, sizeof m1, "such edges"));
    } else if (open.count) {
        const edge_key *k = keys + open.first_at;
        uint32_t f = m->he_face[k->h];
        st = sq_error_set(err, SQ_ERR_BOUNDARY,
                          "%sthe mesh is open: boundary edge (%u, %u) of face %u has no "
                          "neighbouring face; %u boundary edges in total (the surface must be "
                          "closed)",
                          face_prefix(s, f, pre), m->he_vert[k->h], he_dst(m, k->h), f,
                          open.count);
    }
    free(keys);
    free(start);
    return st;
}

/* ---- step 3: vertex manifoldness -------------------------------------- */

static sq_status check_vertex_fans(const sq_soup *s, sq_mesh *m, unsigned flags, sq_error *err)
{
    uint32_t *outdeg = calloc(m->nv, sizeof *outdeg);
    if (!outdeg) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t h = 0; h < m->nh; h++) {
        outdeg[m->he_vert[h]]++;
        m->v_he[m->he_vert[h]] = h;
    }
    uint32_t bad = 0, first = 0, first_fan = 0;
    for (uint32_t v = 0; v < m->nv; v++) {
        uint32_t h0 = m->v_he[v], h = h0, fan = 0;
        do {
            fan++;
            h = m->he_next[m->he_twin[h]];
        } while (h != h0 && fan <= outdeg[v]);
        assert(fan <= outdeg[v]);
        if (fan != outdeg[v] && bad++ == 0) {
            first = v;
            first_fan = fan;
        }
    }
    sq_status st = SQ_OK;
    /* In a closed manifold triangle mesh a vertex with two faces means the
     * two faces share all three corners (a two-triangle "pillow"): no cone
     * set and no quad mesh can live on that. Quad meshes may have valence-2
     * vertices (valence-2 cones). */
    if (!bad && !(flags & SQ_MESH_ALLOW_POLYGONS)) {
        for (uint32_t v = 0; v < m->nv; v++) {
            if (outdeg[v] >= 3) continue;
            char pre[WHERE_MAX];
            uint32_t h = m->v_he[v];
            st = sq_error_set(err, SQ_ERR_DEGENERATE,
                              "%svertex %u has only %u faces: faces %u and %u share all three "
                              "corners, a degenerate two-sided surface piece",
                              vertex_prefix(s, v, pre), v, outdeg[v], m->he_face[h],
                              m->he_face[m->he_twin[h]]);
            break;
        }
    }
    if (bad) {
        char pre[WHERE_MAX], m1[64];
        st = sq_error_set(err, SQ_ERR_NONMANIFOLD_VERTEX,
                          "%snon-manifold vertex %u: its %u faces form more than one fan "
                          "(one fan has %u faces; a bow-tie)%s",
                          vertex_prefix(s, first, pre), first, outdeg[first], first_fan,
                          more(bad - 1, m1, sizeof m1, "non-manifold vertices"));
    }
    free(outdeg);
    return st;
}

/* ---- step 4: connected components (over faces, via twins) ------------ */

static sq_status check_connected(const sq_soup *s, const sq_mesh *m, sq_error *err)
{
    uint32_t *comp = malloc((size_t)m->nf * sizeof *comp);
    uint32_t *stack = malloc((size_t)m->nf * sizeof *stack);
    if (!comp || !stack) {
        free(comp);
        free(stack);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    }
    for (uint32_t f = 0; f < m->nf; f++) comp[f] = SQ_NONE;
    uint32_t ncomp = 0, second = SQ_NONE, size0 = 0;
    for (uint32_t seed = 0; seed < m->nf; seed++) {
        if (comp[seed] != SQ_NONE) continue;
        uint32_t top = 0, size = 0;
        comp[seed] = ncomp;
        stack[top++] = seed;
        while (top) {
            uint32_t f = stack[--top];
            size++;
            uint32_t h0 = m->f_he[f], h = h0;
            do {
                uint32_t g = m->he_face[m->he_twin[h]];
                if (comp[g] == SQ_NONE) {
                    comp[g] = ncomp;
                    stack[top++] = g;
                }
                h = m->he_next[h];
            } while (h != h0);
        }
        if (ncomp == 0) size0 = size;
        if (ncomp == 1) second = seed;
        ncomp++;
    }
    free(comp);
    free(stack);
    if (ncomp > 1) {
        char pre[WHERE_MAX];
        return sq_error_set(err, SQ_ERR_COMPONENTS,
                            "%sthe mesh has %u connected components; face %u is not connected "
                            "to face 0 (whose component has %u of the %u faces); seamquad "
                            "needs one connected surface",
                            face_prefix(s, second, pre), ncomp, second, size0, m->nf);
    }
    return SQ_OK;
}

/* ---- step 5: exactly degenerate triangles ----------------------------- */

static sq_status check_degenerate(const sq_soup *s, const sq_mesh *m, sq_error *err)
{
    uint32_t bad = 0, first = 0;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t b = s->face_off[f];
        if (s->face_off[f + 1] - b != 3) continue;
        const double *p = m->pos;
        if (sq_collinear3d(p + 3 * (size_t)s->face_idx[b], p + 3 * (size_t)s->face_idx[b + 1],
                           p + 3 * (size_t)s->face_idx[b + 2]) &&
            bad++ == 0)
            first = f;
    }
    if (bad) {
        char pre[WHERE_MAX], m1[64];
        const uint32_t *c = s->face_idx + s->face_off[first];
        return sq_error_set(err, SQ_ERR_DEGENERATE,
                            "%sdegenerate face %u: its corners %u, %u, %u are exactly "
                            "collinear (zero area)%s",
                            face_prefix(s, first, pre), first, c[0], c[1], c[2],
                            more(bad - 1, m1, sizeof m1, "degenerate faces"));
    }
    return SQ_OK;
}

sq_status sq_mesh_from_soup(const sq_soup *s, unsigned flags, sq_mesh *out, sq_error *err)
{
    char pre[WHERE_MAX];
    memset(out, 0, sizeof *out);
    if (s->nv == 0)
        return sq_error_set(err, SQ_ERR_EMPTY, "%sthe mesh has no vertices", file_prefix(s, pre));
    if (s->nf == 0)
        return sq_error_set(err, SQ_ERR_EMPTY, "%sthe mesh has no faces", file_prefix(s, pre));

    sq_status st;
    if ((st = check_vertices(s, err))) return st;
    if ((st = check_faces(s, flags, err))) return st;
    if ((st = check_referenced(s, err))) return st;

    sq_mesh m = {0};
    m.nv = s->nv;
    m.nf = s->nf;
    m.nh = s->face_off[s->nf];
    m.pos = malloc((size_t)m.nv * 3 * sizeof *m.pos);
    m.he_next = malloc((size_t)m.nh * sizeof(uint32_t));
    m.he_twin = malloc((size_t)m.nh * sizeof(uint32_t));
    m.he_vert = malloc((size_t)m.nh * sizeof(uint32_t));
    m.he_face = malloc((size_t)m.nh * sizeof(uint32_t));
    m.v_he = malloc((size_t)m.nv * sizeof(uint32_t));
    m.f_he = malloc((size_t)m.nf * sizeof(uint32_t));
    if (!m.pos || !m.he_next || !m.he_twin || !m.he_vert || !m.he_face || !m.v_he || !m.f_he) {
        sq_mesh_free(&m);
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory for a mesh of %u faces", s->nf);
    }
    memcpy(m.pos, s->pos, (size_t)m.nv * 3 * sizeof *m.pos);
    for (uint32_t f = 0; f < m.nf; f++) {
        uint32_t b = s->face_off[f], e = s->face_off[f + 1];
        m.f_he[f] = b;
        for (uint32_t c = b; c < e; c++) {
            m.he_vert[c] = s->face_idx[c];
            m.he_face[c] = f;
            m.he_next[c] = c + 1 < e ? c + 1 : b;
            m.he_twin[c] = SQ_NONE;
        }
    }

    if ((st = match_twins(s, &m, err)) || (st = check_vertex_fans(s, &m, flags, err)) ||
        (st = check_connected(s, &m, err)) ||
        (!(flags & SQ_MESH_SKIP_DEGENERATE) && (st = check_degenerate(s, &m, err)))) {
        sq_mesh_free(&m);
        return st;
    }
    *out = m;
    return SQ_OK;
}

double sq_mesh_face_area(const sq_mesh *m, uint32_t f)
{
    const uint32_t h = m->f_he[f];
    const double *a = m->pos + 3 * (size_t)m->he_vert[h];
    const double *b = m->pos + 3 * (size_t)m->he_vert[m->he_next[h]];
    const double *c = m->pos + 3 * (size_t)m->he_vert[m->he_next[m->he_next[h]]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

double sq_mesh_area(const sq_mesh *m)
{
    double area = 0;
    for (uint32_t f = 0; f < m->nf; f++) area += sq_mesh_face_area(m, f);
    return area;
}

double sq_bbox_diagonal(uint32_t nv, const double *pos)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < nv; v++)
        for (int i = 0; i < 3; i++)
            lo[i] = fmin(lo[i], pos[3 * (size_t)v + i]), hi[i] = fmax(hi[i], pos[3 * (size_t)v + i]);
    if (!nv) return 0.0;
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

uint32_t *sq_mesh_triangles(const sq_mesh *m)
{
    uint32_t *tri = malloc(3 * ((size_t)m->nf + 1) * sizeof *tri);
    if (!tri) return NULL;
    for (uint32_t f = 0; f < m->nf; f++) {
        uint32_t h = m->f_he[f];
        for (int c = 0; c < 3; c++, h = m->he_next[h]) tri[3 * (size_t)f + c] = m->he_vert[h];
    }
    return tri;
}

void sq_area_weighted_normals(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri, double *vn)
{
    memset(vn, 0, 3 * (size_t)nv * sizeof *vn);
    for (uint32_t t = 0; t < nt; t++) {
        const uint32_t *c = tri + 3 * (size_t)t;
        const double *a = pos + 3 * (size_t)c[0], *b = pos + 3 * (size_t)c[1], *d = pos + 3 * (size_t)c[2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) vn[3 * (size_t)c[j] + k] += n[k];
    }
}

double *sq_mesh_vertex_normals(const sq_mesh *m)
{
    uint32_t *tri = sq_mesh_triangles(m);
    double *vn = malloc(3 * ((size_t)m->nv + 1) * sizeof *vn);
    if (!tri || !vn) {
        free(tri), free(vn);
        return NULL;
    }
    sq_area_weighted_normals(m->nv, m->pos, m->nf, tri, vn);
    free(tri);
    for (uint32_t v = 0; v < m->nv; v++) {
        double *n = vn + 3 * (size_t)v, l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
    }
    return vn;
}

void sq_mesh_normal_at(const sq_mesh *m, const double *vn, uint32_t f, const double bary[3], double n[3])
{
    uint32_t h = m->f_he[f];
    n[0] = n[1] = n[2] = 0.0;
    for (int k = 0; k < 3; k++, h = m->he_next[h])
        for (int i = 0; i < 3; i++) n[i] += bary[k] * vn[3 * (size_t)m->he_vert[h] + i];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
}
