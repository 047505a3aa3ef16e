#include "cli_common.h"

#include <math.h>
#include <stdlib.h>

#include <string.h>

#include "sq_cones.h"
#include "sq_extract.h"
#include "sq_io.h"

void sq_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            if (*p < 0x20) fprintf(f, "\\u%04x", *p);
            else fputc(*p, f);
        }
    }
    fputc('"', f);
}

void sq_json_error(sq_status code, const char *stage, const char *message)
{
    printf("\"error\": {\"code\": \"%s\", \"stage\": ", sq_status_name(code));
    sq_json_string(stdout, stage);
    printf(", \"message\": ");
    sq_json_string(stdout, message);
    printf("}");
}

int sq_exit_code(sq_status st)
{
    switch (st) {
    case SQ_OK: return SQ_EXIT_OK;
    case SQ_ERR_NOMEM:
    case SQ_ERR_SOLVER:
    case SQ_ERR_INTERNAL: return SQ_EXIT_FAILURE;
    case SQ_ERR_ARGUMENT: return SQ_EXIT_USAGE;
    default: return SQ_EXIT_INVALID_INPUT;
    }
}

sq_status sq_cli_read_cones(const char *path, const sq_mesh *mesh, int32_t *val, sq_error *err)
{
    sq_status st = sq_cones_read(path, mesh->nv, val, NULL, err);
    if (st) return st;
    st = sq_cones_check_realizable(mesh->nv, val, sq_mesh_genus(mesh), err);
    if (st) {
        char msg[SQ_ERROR_MSG_MAX];
        snprintf(msg, sizeof msg, "%s", err->msg);
        sq_error_set(err, st, "%s: %s", path, msg);
    }
    return st;
}

void sq_json_open_map_report(sq_status st, const char *mesh, const char *map, const char *out)
{
    printf("{\n  \"ok\": %s,\n  \"mesh\": ", st == SQ_OK ? "true" : "false");
    sq_json_string(stdout, mesh);
    printf(",\n  \"map\": ");
    sq_json_string(stdout, map);
    printf(",\n  \"output\": ");
    sq_json_string(stdout, out);
}

void sq_json_double(FILE *f, double x)
{
    if (isfinite(x)) fprintf(f, "%.17g", x);
    else fputs("null", f);
}

void sq_cli_name_file(sq_error *err, const char *path)
{
    if (!err || !path || !strncmp(err->msg, path, strlen(path))) return;
    char msg[SQ_ERROR_MSG_MAX];
    snprintf(msg, sizeof msg, "%s", err->msg);
    sq_error_set(err, err->code, "%s: %s", path, msg);
}


sq_status sq_cli_probe_output(const char *path, sq_error *err)
{
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (!st) sq_atomic_abort(&af);
    return st;
}

int sq_cli_number_option(const char *cmd, const char *opt, const char *val, double *out)
{
    char *end = NULL;
    double x = strtod(val, &end);
    if (!end || *end || end == val || !isfinite(x)) {
        fprintf(stderr, "seamquad %s: %s needs a number, got '%s'\n", cmd, opt, val);
        return 0;
    }
    *out = x;
    return 1;
}
