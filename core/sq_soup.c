#include "sq_soup.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sq_soup_free(sq_soup *s)
{
    if (!s) return;
    free(s->pos);
    free(s->face_off);
    free(s->face_idx);
    free(s->uv);
    free(s->face_uv);
    free(s->vert_line);
    free(s->face_line);
    free(s->path);
    memset(s, 0, sizeof *s);
}

static const char *where(const sq_soup *s, const uint32_t *lines, uint32_t i,
                         char *buf, size_t n)
{
    if (n == 0) return buf;
    buf[0] = '\0';
    if (!s->path) return buf;
    if (!lines)
        snprintf(buf, n, "%s", s->path);
    else if (s->line_kind == 1)
        snprintf(buf, n, "%s record %u", s->path, lines[i]);
    else
        snprintf(buf, n, "%s:%u", s->path, lines[i]);
    return buf;
}

const char *sq_soup_where_vertex(const sq_soup *s, uint32_t v, char *buf, size_t n)
{
    return where(s, s->vert_line, v, buf, n);
}

const char *sq_soup_where_face(const sq_soup *s, uint32_t f, char *buf, size_t n)
{
    return where(s, s->face_line, f, buf, n);
}
