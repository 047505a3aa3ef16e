/* Shared body of the libFuzzer targets: parse the input with one reader;
 * on success check the soup invariants every reader promises and run the
 * mesh builder over it; on failure check that the soup was released and
 * that the message starts with the file name. Any violation aborts, which
 * libFuzzer reports as a crash. */
#ifndef SQ_FUZZ_COMMON_H
#define SQ_FUZZ_COMMON_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sq_io.h"
#include "sq_mesh.h"

#define FUZZ_CHECK(cond) \
    do {                 \
        if (!(cond)) abort(); \
    } while (0)

static void fuzz_check_soup(const sq_soup *s, const char *name)
{
    FUZZ_CHECK(s->nv > 0 && s->nf > 0);
    FUZZ_CHECK(s->pos && s->face_off && s->face_idx && s->vert_line && s->face_line);
    FUZZ_CHECK(s->path && strcmp(s->path, name) == 0);
    FUZZ_CHECK(s->nv != SQ_NONE && s->nuv != SQ_NONE);
    FUZZ_CHECK(s->face_off[0] == 0);
    for (uint32_t f = 0; f < s->nf; f++) {
        FUZZ_CHECK(s->face_off[f + 1] > s->face_off[f]);
        FUZZ_CHECK(s->face_off[f + 1] - s->face_off[f] >= 3);
        FUZZ_CHECK(s->face_line[f] >= 1);
        if (f > 0 && s->line_kind == 0) FUZZ_CHECK(s->face_line[f] > s->face_line[f - 1]);
    }
    for (uint32_t c = 0; c < s->face_off[s->nf]; c++) {
        FUZZ_CHECK(s->face_idx[c] < s->nv);
        if (s->face_uv) FUZZ_CHECK(s->face_uv[c] == SQ_NONE || s->face_uv[c] < s->nuv);
    }
    for (uint32_t v = 0; v < s->nv; v++) {
        FUZZ_CHECK(s->vert_line[v] >= 1);
        /* touch every coordinate so ASan sees the whole array */
        volatile double x = s->pos[3 * (size_t)v] + s->pos[3 * (size_t)v + 1] +
                            s->pos[3 * (size_t)v + 2];
        (void)x;
    }
    for (uint32_t t = 0; t < s->nuv; t++) {
        volatile double u = s->uv[2 * (size_t)t] + s->uv[2 * (size_t)t + 1];
        (void)u;
    }
}

static int fuzz_one(sq_status (*parse)(const char *, size_t, const char *, sq_soup *, sq_error *),
                    const char *name, const uint8_t *data, size_t size)
{
    sq_soup s;
    sq_error e;
    memset(&e, 0, sizeof e);
    sq_status st = parse((const char *)data, size, name, &s, &e);
    if (st != SQ_OK) {
        /* a failed parse leaves a zeroed soup and a message naming the file */
        FUZZ_CHECK(st == e.code);
        FUZZ_CHECK(st == SQ_ERR_PARSE || st == SQ_ERR_INDEX || st == SQ_ERR_EMPTY ||
                   st == SQ_ERR_FORMAT || st == SQ_ERR_NOMEM);
        FUZZ_CHECK(strncmp(e.msg, name, strlen(name)) == 0);
        FUZZ_CHECK(!s.pos && !s.face_off && !s.face_idx && !s.path && s.nv == 0 && s.nf == 0);
        return 0;
    }
    fuzz_check_soup(&s, name);
    sq_mesh m;
    if (sq_mesh_from_soup(&s, SQ_MESH_ALLOW_POLYGONS, &m, &e) == SQ_OK) sq_mesh_free(&m);
    sq_soup_free(&s);
    return 0;
}

#endif
