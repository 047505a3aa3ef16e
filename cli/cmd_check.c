/* seamquad check: can this mesh and cone set be processed? */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "sq_cones.h"
#include "sq_io.h"
#include "sq_mesh.h"

#define MAX_VALENCE_HIST 64

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad check MESH [--cones FILE] [--json]\n"
            "\n"
            "Reads MESH (OBJ, OFF or PLY) and tells whether seamquad can process it:\n"
            "a closed, connected, edge- and vertex-manifold, consistently oriented\n"
            "triangle mesh with finite coordinates, every vertex used, and no face whose\n"
            "corners are exactly collinear (decided with exact arithmetic). Reports the\n"
            "counts, Euler characteristic and genus.\n"
            "\n"
            "With --cones FILE it also reads the cones and checks them:\n"
            "  - a Th_hat file: one angle (radians) per vertex, in vertex order; each is\n"
            "    rounded to the nearest k*pi/2 (off by more than 1e-6 is an error);\n"
            "  - a cone list: 'VERTEX VALENCE' per line, 0-based vertex index, only the\n"
            "    cones (a cone of angle k*pi/2 has valence k; unlisted vertices are 4).\n"
            "  The two are told apart by content: one number per line is Th_hat, two\n"
            "  integers per line is a cone list. Then: the cone histogram, Gauss-Bonnet\n"
            "  (sum of 4 - k over vertices = 4 * Euler characteristic), and what the\n"
            "  construction cannot take (valence 1; a torus with one 3 and one 5 cone).\n"
            "\n"
            "Messages name the element (0-based vertex and face indices) and the file\n"
            "and line it came from.\n"
            "\n"
            "options:\n"
            "  --cones FILE  cone file (Th_hat or cone list)\n"
            "  --json        print a machine-readable report on stdout\n"
            "  -h, --help    this help\n"
            "\n"
            "exit code 0 only when the input can be processed; 1 when it cannot (the\n"
            "message says why); 2 for a wrong command line; 3 for an internal failure.\n"
            "\n"
            "example:\n"
            "  seamquad check ../shared/data/cid/elephant.obj \\\n"
            "      --cones ../shared/data/cid/elephant_Th_hat\n");
}

typedef struct check_report {
    const char *mesh_path, *cones_path;
    int mesh_read, mesh_valid, cones_read, gauss_bonnet, realizable;
    uint32_t nv, nf, ne;
    int64_t euler, genus;
    double t_read, t_validate, t_cones;
    sq_cone_format cone_format;
    uint32_t ncones;
    uint32_t hist[MAX_VALENCE_HIST];
    int64_t defect_sum;
    sq_error err;         /* first error, if any */
    const char *err_stage;
} check_report;

static const char *format_name(const char *path)
{
    switch (sq_format_from_path(path)) {
    case SQ_FORMAT_OBJ: return "OBJ";
    case SQ_FORMAT_OFF: return "OFF";
    case SQ_FORMAT_PLY: return "PLY";
    default: return "unknown";
    }
}

static void print_text(const check_report *r)
{
    printf("mesh          %s (%s)\n", r->mesh_path, format_name(r->mesh_path));
    if (r->mesh_read) printf("vertices      %u\nfaces         %u\n", r->nv, r->nf);
    if (r->mesh_valid) {
        printf("edges         %u\n", r->ne);
        printf("euler         %lld\n", (long long)r->euler);
        printf("genus         %lld\n", (long long)r->genus);
        printf("surface       closed, connected, manifold, oriented, no degenerate face\n");
        printf("time          read %.1f ms, validate %.1f ms\n", 1e3 * r->t_read,
               1e3 * r->t_validate);
    }
    if (r->cones_path) {
        printf("cones file    %s", r->cones_path);
        if (r->cones_read)
            printf(" (%s)", r->cone_format == SQ_CONES_TH_HAT ? "Th_hat" : "cone list");
        printf("\n");
    }
    if (r->cones_read) {
        printf("cones         %u\n", r->ncones);
        printf("valences     ");
        for (uint32_t k = 0; k < MAX_VALENCE_HIST; k++) {
            if (k == 4 || !r->hist[k]) continue;
            printf(" %s%u:%u", k == MAX_VALENCE_HIST - 1 ? ">=" : "", k, r->hist[k]);
        }
        printf("%s   (valence:count; a cone of angle k*pi/2 has valence k)\n",
               r->ncones ? "" : " none");
        printf("gauss-bonnet  %s: sum(4 - k) = %lld, 4*chi = %lld\n",
               r->gauss_bonnet ? "satisfied" : "VIOLATED", (long long)r->defect_sum,
               (long long)(4 * r->euler));
        if (r->gauss_bonnet) printf("realizable    %s\n", r->realizable ? "yes" : "NO");
    }
    if (r->err.code == SQ_OK)
        printf("result        OK: seamquad can process this input\n");
    else
        printf("result        cannot be processed (%s): see the error below\n",
               sq_status_name(r->err.code));
}

static void print_json(const check_report *r)
{
    printf("{\n  \"ok\": %s,\n  \"mesh\": {\"path\": ", r->err.code == SQ_OK ? "true" : "false");
    sq_json_string(stdout, r->mesh_path);
    printf(", \"format\": \"%s\"", format_name(r->mesh_path));
    if (r->mesh_read) printf(", \"vertices\": %u, \"faces\": %u", r->nv, r->nf);
    printf(", \"valid\": %s", r->mesh_valid ? "true" : "false");
    if (r->mesh_valid)
        printf(", \"edges\": %u, \"euler\": %lld, \"genus\": %lld, \"closed\": true, "
               "\"manifold\": true, \"components\": 1, \"read_ms\": %.3f, \"validate_ms\": %.3f",
               r->ne, (long long)r->euler, (long long)r->genus, 1e3 * r->t_read,
               1e3 * r->t_validate);
    printf("}");
    if (r->cones_path) {
        printf(",\n  \"cones\": {\"path\": ");
        sq_json_string(stdout, r->cones_path);
        if (r->cones_read) {
            printf(", \"format\": \"%s\", \"count\": %u, \"histogram\": {",
                   r->cone_format == SQ_CONES_TH_HAT ? "th_hat" : "list", r->ncones);
            int first = 1;
            for (uint32_t k = 0; k < MAX_VALENCE_HIST; k++) {
                if (k == 4 || !r->hist[k]) continue;
                printf("%s\"%s%u\": %u", first ? "" : ", ", k == MAX_VALENCE_HIST - 1 ? ">=" : "",
                       k, r->hist[k]);
                first = 0;
            }
            printf("}, \"gauss_bonnet\": {\"ok\": %s, \"sum_4_minus_k\": %lld, \"required\": %lld}",
                   r->gauss_bonnet ? "true" : "false", (long long)r->defect_sum,
                   (long long)(4 * r->euler));
            if (r->gauss_bonnet) printf(", \"realizable\": %s", r->realizable ? "true" : "false");
            else printf(", \"realizable\": null");
        }
        printf("}");
    }
    if (r->err.code != SQ_OK) {
        printf(",\n  ");
        sq_json_error(r->err.code, r->err_stage, r->err.msg);
    }
    printf("\n}\n");
}

static void run_check(check_report *r)
{
    sq_soup soup = {0};
    sq_mesh mesh = {0};
    int32_t *valence = NULL;
    double t0 = sq_now();
    r->err_stage = "read";
    if (sq_read_mesh(r->mesh_path, &soup, &r->err)) goto done;
    r->mesh_read = 1;
    r->nv = soup.nv;
    r->nf = soup.nf;
    double t1 = sq_now();
    r->t_read = t1 - t0;
    r->err_stage = "validate";
    if (sq_mesh_from_soup(&soup, 0, &mesh, &r->err)) goto done;
    r->t_validate = sq_now() - t1;
    r->mesh_valid = 1;
    r->ne = mesh.nh / 2;
    r->euler = sq_mesh_euler(&mesh);
    r->genus = sq_mesh_genus(&mesh);
    if (!r->cones_path) goto done;

    r->err_stage = "cones";
    valence = malloc((size_t)mesh.nv * sizeof *valence);
    if (!valence) {
        sq_error_set(&r->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (sq_cones_read(r->cones_path, mesh.nv, valence, &r->cone_format, &r->err)) goto done;
    r->cones_read = 1;
    r->ncones = sq_cones_histogram(mesh.nv, valence, r->hist, MAX_VALENCE_HIST);
    r->defect_sum = 0;
    for (uint32_t v = 0; v < mesh.nv; v++) r->defect_sum += 4 - (int64_t)valence[v];
    r->err_stage = "gauss-bonnet";
    if (sq_cones_check_gauss_bonnet(mesh.nv, valence, r->euler, &r->err)) goto cone_error;
    r->gauss_bonnet = 1;
    r->err_stage = "realizability";
    if (sq_cones_check_realizable(mesh.nv, valence, r->genus, &r->err)) goto cone_error;
    r->realizable = 1;
    goto done;
cone_error: {
        /* name the cone file: the library message only knows vertices */
        char msg[SQ_ERROR_MSG_MAX];
        snprintf(msg, sizeof msg, "%s", r->err.msg);
        sq_error_set(&r->err, r->err.code, "%s: %s", r->cones_path, msg);
    }
done:
    free(valence);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

int sq_cmd_check(int argc, char **argv)
{
    check_report r;
    memset(&r, 0, sizeof r);
    int json = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--cones")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad check: --cones needs a file\n");
                return SQ_EXIT_USAGE;
            }
            r.cones_path = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad check: unknown option '%s' (see seamquad check --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!r.mesh_path) {
            r.mesh_path = a;
        } else {
            fprintf(stderr, "seamquad check: more than one mesh given ('%s', '%s')\n",
                    r.mesh_path, a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!r.mesh_path) {
        help(stderr);
        return SQ_EXIT_USAGE;
    }
    run_check(&r);
    if (json) print_json(&r);
    else print_text(&r);
    if (r.err.code != SQ_OK) {
        fprintf(stderr, "seamquad check: error: %s\n", r.err.msg);
        return sq_exit_code(r.err.code);
    }
    return SQ_EXIT_OK;
}
