/* seamquad: side-pairing pattern files (docs/domain.md).
 *
 *   # comment
 *   K
 *   P_0 P_1 ... P_{K-1}        partner of each side (0-based), any layout
 *   [S_0 ... S_{K-1}]          optional: 1 if corner i is straight, else 0
 *
 * Whitespace and line breaks are free; `#` starts a comment. */
#ifndef SQ_PATTERN_IO_H
#define SQ_PATTERN_IO_H

#include <stddef.h>

#include "sq_error.h"
#include "sq_pattern.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parses and validates (sq_pattern_validate). pat must be initialized. */
sq_status sq_pattern_parse(const char *data, size_t size, const char *name, sq_pattern *pat,
                           sq_error *err);
sq_status sq_pattern_read(const char *path, sq_pattern *pat, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
