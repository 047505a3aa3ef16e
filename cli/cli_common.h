/* seamquad CLI: shared helpers (printing, JSON, timing). Only the CLI
 * prints; the library returns codes and messages. */
#ifndef SQ_CLI_COMMON_H
#define SQ_CLI_COMMON_H

#include <stdio.h>

#include "sq_clock.h"
#include "sq_error.h"
#include "sq_mesh.h"

/* Exit codes shared by every subcommand. */
enum {
    SQ_EXIT_OK = 0,
    SQ_EXIT_INVALID_INPUT = 1, /* the input cannot be processed, or an output cannot */
                               /* be written (the message says why)                 */
    SQ_EXIT_USAGE = 2,         /* wrong command line                                */
    SQ_EXIT_FAILURE = 3        /* internal failure: a bug, or out of memory         */
};

int sq_cmd_check(int argc, char **argv);
int sq_cmd_domain(int argc, char **argv);
int sq_cmd_param(int argc, char **argv);
int sq_cmd_cones(int argc, char **argv);
int sq_cmd_smooth(int argc, char **argv);
int sq_cmd_subdiv(int argc, char **argv);
int sq_cmd_quantize(int argc, char **argv);
int sq_cmd_extract(int argc, char **argv);
int sq_cmd_optimize(int argc, char **argv);
int sq_cmd_remesh(int argc, char **argv);

/* Writes the `"error": {"code", "stage", "message"}` member of a --json
 * report (no leading comma or newline) to stdout. */
void sq_json_error(sq_status code, const char *stage, const char *message);

/* Opens the --json report of a command that reads a mesh and a map and
 * writes one output: `{`, then "ok", "mesh", "map" and "output" (no
 * trailing comma or newline). */
void sq_json_open_map_report(sq_status st, const char *mesh, const char *map, const char *out);

/* Puts "PATH: " before err's message unless it starts with PATH already
 * (the library names elements; the command names the file). */
void sq_cli_name_file(sq_error *err, const char *path);

/* Writes x as a JSON number (%.17g), or null if it is not finite. */
void sq_json_double(FILE *f, double x);

/* Writes s as a JSON string literal (with quotes) to f. */
void sq_json_string(FILE *f, const char *s);

/* Monotonic time in seconds. */
/* Reads a cone file for mesh (nv valences into val) and checks that the
 * cones are realizable on its genus; a failure message starts with the
 * cone file's path (the library's messages know vertices, not files). */
sq_status sq_cli_read_cones(const char *path, const sq_mesh *mesh, int32_t *val, sq_error *err);


/* Exit code for a library status. */
int sq_exit_code(sq_status st);

/* An output that cannot be written, found before the work starts: a
 * temporary file is created beside `path` and removed. Leaves nothing. */
sq_status sq_cli_probe_output(const char *path, sq_error *err);

/* The value `val` of option `opt` of command `cmd` as a finite number:
 * 1, or 0 after saying on stderr what was wrong. */
int sq_cli_number_option(const char *cmd, const char *opt, const char *val, double *out);

#endif
