/* seamquad: error reporting shared by every stage.
 *
 * The library never prints and never exits. Every fallible function takes a
 * caller-owned `sq_error *` (may be NULL) and returns an `sq_status`. On
 * failure the message names the problem and, where known, the element and
 * the file and line it came from. */
#ifndef SQ_ERROR_H
#define SQ_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sq_status {
    SQ_OK = 0,
    SQ_ERR_IO,              /* cannot open, read, write or rename a file     */
    SQ_ERR_NOMEM,           /* allocation failed                             */
    SQ_ERR_PARSE,           /* malformed file: bad token, truncated, garbage */
    SQ_ERR_FORMAT,          /* unknown or unsupported file format            */
    SQ_ERR_EMPTY,           /* no vertices or no faces                       */
    SQ_ERR_INDEX,           /* vertex index out of range                     */
    SQ_ERR_NOT_FINITE,      /* NaN or infinite coordinate                    */
    SQ_ERR_POLYGON,         /* a face that is not a triangle                 */
    SQ_ERR_REPEATED_VERTEX, /* a face uses one vertex twice                  */
    SQ_ERR_UNREFERENCED,    /* a vertex used by no face                      */
    SQ_ERR_NONMANIFOLD_EDGE,/* an edge with more than two faces              */
    SQ_ERR_ORIENTATION,     /* neighbouring faces oriented inconsistently    */
    SQ_ERR_BOUNDARY,        /* open mesh: an edge with only one face         */
    SQ_ERR_NONMANIFOLD_VERTEX, /* bow-tie: faces around a vertex form >1 fan */
    SQ_ERR_COMPONENTS,      /* more than one connected component             */
    SQ_ERR_DEGENERATE,      /* a face whose corners are exactly collinear    */
    SQ_ERR_CONE_COUNT,      /* cone file with the wrong number of entries    */
    SQ_ERR_CONE_VALUE,      /* cone angle not a multiple of pi/2, or <= 0    */
    SQ_ERR_GAUSS_BONNET,    /* cones violate Gauss-Bonnet                    */
    SQ_ERR_UNREALIZABLE,    /* admissible by Gauss-Bonnet but not realizable */
    SQ_ERR_SOLVER,          /* a numerical solver failed                     */
    SQ_ERR_ARGUMENT,        /* invalid argument to a library function        */
    SQ_ERR_INTERNAL,        /* a broken invariant: a bug in seamquad         */
    SQ_STATUS_COUNT
} sq_status;

#define SQ_ERROR_MSG_MAX 1024

typedef struct sq_error {
    sq_status code;
    char msg[SQ_ERROR_MSG_MAX];
} sq_error;

/* Sets err (if not NULL) and returns code. printf-style message. */
sq_status sq_error_set(sq_error *err, sq_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Clears err to SQ_OK with an empty message. */
void sq_error_clear(sq_error *err);

/* Short stable name of a status, e.g. "boundary" for SQ_ERR_BOUNDARY. */
const char *sq_status_name(sq_status code);

#ifdef __cplusplus
}
#endif
#endif
