/* seamquad tests: a polygon soup with UVs built triangle by triangle, for
 * hand-made maps. Corners are merged by exact equality of their coordinates
 * (3D positions and UVs separately), so a seam is two UV copies of one
 * vertex. Header-only, for cmocka tests (include <cmocka.h> first). */
#ifndef SQ_TEST_SOUP_H
#define SQ_TEST_SOUP_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"

typedef struct soup_builder {
    sq_soup s;
    uint32_t cap_v, cap_uv, cap_f;
} soup_builder;

/* the index of the vertex at p, appended when new */
static inline uint32_t sb_vertex(soup_builder *b, const double p[3])
{
    for (uint32_t v = 0; v < b->s.nv; v++)
        if (b->s.pos[3 * v] == p[0] && b->s.pos[3 * v + 1] == p[1] && b->s.pos[3 * v + 2] == p[2]) return v;
    if (b->s.nv == b->cap_v) {
        b->cap_v = b->cap_v ? 2 * b->cap_v : 64;
        b->s.pos = realloc(b->s.pos, 3 * (size_t)b->cap_v * sizeof *b->s.pos);
        assert_non_null(b->s.pos);
    }
    memcpy(b->s.pos + 3 * (size_t)b->s.nv, p, 3 * sizeof *p);
    return b->s.nv++;
}

/* the index of the UV point q, appended when new */
static inline uint32_t sb_uv(soup_builder *b, const double q[2])
{
    for (uint32_t i = 0; i < b->s.nuv; i++)
        if (b->s.uv[2 * i] == q[0] && b->s.uv[2 * i + 1] == q[1]) return i;
    if (b->s.nuv == b->cap_uv) {
        b->cap_uv = b->cap_uv ? 2 * b->cap_uv : 64;
        b->s.uv = realloc(b->s.uv, 2 * (size_t)b->cap_uv * sizeof *b->s.uv);
        assert_non_null(b->s.uv);
    }
    memcpy(b->s.uv + 2 * (size_t)b->s.nuv, q, 2 * sizeof *q);
    return b->s.nuv++;
}

/* appends the triangle with vertices v and UV corners t */
static inline void sb_tri(soup_builder *b, const uint32_t v[3], const uint32_t t[3])
{
    if (b->s.nf == b->cap_f) {
        b->cap_f = b->cap_f ? 2 * b->cap_f : 64;
        b->s.face_idx = realloc(b->s.face_idx, 3 * (size_t)b->cap_f * sizeof *b->s.face_idx);
        b->s.face_uv = realloc(b->s.face_uv, 3 * (size_t)b->cap_f * sizeof *b->s.face_uv);
        b->s.face_off = realloc(b->s.face_off, ((size_t)b->cap_f + 1) * sizeof *b->s.face_off);
        assert_non_null(b->s.face_idx), assert_non_null(b->s.face_uv), assert_non_null(b->s.face_off);
    }
    for (int c = 0; c < 3; c++) b->s.face_idx[3 * b->s.nf + c] = v[c], b->s.face_uv[3 * b->s.nf + c] = t[c];
    b->s.face_off[b->s.nf] = 3 * b->s.nf;
    b->s.nf++;
    b->s.face_off[b->s.nf] = 3 * b->s.nf;
}

#endif
