/* seamquad: polygon soup, the raw content of a mesh file.
 *
 * Readers produce a soup exactly as the file states it: no vertex is merged,
 * moved, dropped or added, and no face is split or reordered. Validation and
 * halfedge construction happen later (sq_mesh.h), so every error can still
 * name the file and line of the offending element. */
#ifndef SQ_SOUP_H
#define SQ_SOUP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SQ_NONE UINT32_MAX

typedef struct sq_soup {
    uint32_t nv;          /* vertices                                       */
    double *pos;          /* 3*nv coordinates                               */
    uint32_t nf;          /* faces (polygons)                               */
    uint32_t *face_off;   /* nf+1 offsets into face_idx                     */
    uint32_t *face_idx;   /* face_off[nf] 0-based vertex indices            */
    uint32_t nuv;         /* texture coordinates (OBJ `vt`), may be 0       */
    double *uv;           /* 2*nuv                                          */
    uint32_t *face_uv;    /* face_off[nf] 0-based uv indices, or NULL when  */
                          /* no face has uv; SQ_NONE at corners without one */
    /* Provenance for messages: 1-based line of each element in its file
     * (for binary PLY: the element's 1-based record number, see line_kind).
     * NULL when the soup was not read from a file. */
    uint32_t *vert_line;  /* nv  */
    uint32_t *face_line;  /* nf  */
    int line_kind;        /* 0: text line numbers, 1: binary record numbers */
    char *path;           /* file the soup was read from, or NULL           */
} sq_soup;

/* Frees every array of the soup and zeroes it. Safe on a zeroed soup. */
void sq_soup_free(sq_soup *s);

/* Formats "FILE:LINE" (or "FILE record N" for binary input, or "" when the
 * soup has no provenance) for vertex v / face f into buf. Returns buf. */
const char *sq_soup_where_vertex(const sq_soup *s, uint32_t v, char *buf, size_t n);
const char *sq_soup_where_face(const sq_soup *s, uint32_t f, char *buf, size_t n);

#ifdef __cplusplus
}
#endif
#endif
