/* seamquad cones: cones from a smooth cross field, for meshes that come
 * without any (stages/sq_cross_field.h, docs/cones_from_field.md). */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "sq_cones.h"
#include "sq_cross_field.h"
#include "sq_io.h"
#include "sq_mesh.h"

#define CONES_HIST 64


static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad cones MESH -o CONES [--align curvature|smooth]\n"
            "                      [--cancel-radius R] [--json]\n"
            "\n"
            "Computes cones for a closed triangle mesh that has none: the singularities\n"
            "of a smooth 4-direction (cross) field, the globally optimal field of\n"
            "Knoppel, Crane, Pinkall and Schroeder (2013) on the mesh's faces. Each\n"
            "singularity sits on a vertex and has an index in quarter turns; a vertex\n"
            "of index i becomes a cone of valence 4 - i (angle (4 - i)*pi/2).\n"
            "Gauss-Bonnet holds exactly by construction. Then, keeping it:\n"
            "  - singularities of opposite sign closer than R mean edge lengths (along\n"
            "    edges) cancel, one quarter turn at a time, closest first;\n"
            "  - a valence below 2 gives quarter turns to the nearest vertex of valence\n"
            "    3 or more (the construction needs valence >= 2);\n"
            "  - a torus with one valence-3 and one valence-5 cone and nothing else\n"
            "    (no quad mesh exists) loses both, leaving no cones.\n"
            "The result always passes `seamquad check MESH --cones CONES`.\n"
            "\n"
            "options:\n"
            "  -o, --output CONES  where to write the cones (required). A name ending in\n"
            "                      .cones gets a cone list ('VERTEX VALENCE' lines,\n"
            "                      0-based, cones only); any other name a Th_hat file\n"
            "                      (one angle per vertex, radians). Written atomically:\n"
            "                      on failure no file is left.\n"
            "  --align MODE        curvature (default): the field follows principal\n"
            "                      curvature directions where the surface is anisotropic\n"
            "                      and is smooth elsewhere; smooth: the smoothest field,\n"
            "                      ignoring curvature (fewest singularities on organic\n"
            "                      shapes, no feature alignment).\n"
            "  --cancel-radius R   cancel +/- pairs closer than R mean edge lengths\n"
            "                      (default 3; 0 keeps every singularity of the field)\n"
            "  --json              print a machine-readable report on stdout\n"
            "  -h, --help          this help\n"
            "\n"
            "exit code 0 on success; 1 when the mesh cannot be processed or the output\n"
            "cannot be written (the message says why); 2 for a wrong command line; 3 for\n"
            "an internal failure.\n"
            "\n"
            "example:\n"
            "  seamquad cones ../shared/data/libigl/bunny.off -o bunny.cones\n"
            "  seamquad check ../shared/data/libigl/bunny.off --cones bunny.cones\n");
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && !strcmp(s + a - b, suffix);
}

typedef struct cones_run {
    const char *mesh_path, *out_path;
    sq_cones_from_field_options opt;
    int list;
    uint32_t nv, nf;
    int64_t euler, genus;
    sq_cones_from_field_stats st;
    uint32_t hist[CONES_HIST];
    double t_read, t_write;
    int done;
    sq_error err;
    const char *err_stage;
} cones_run;

static void run(cones_run *r)
{
    sq_soup soup = {0};
    sq_mesh mesh = {0};
    int32_t *valence = NULL;
    double t0 = sq_now();
    r->err_stage = "read";
    if (sq_read_mesh(r->mesh_path, &soup, &r->err)) goto done;
    r->err_stage = "validate";
    if (sq_mesh_from_soup(&soup, 0, &mesh, &r->err)) goto done;
    r->t_read = sq_now() - t0;
    r->nv = mesh.nv;
    r->nf = mesh.nf;
    r->euler = sq_mesh_euler(&mesh);
    r->genus = sq_mesh_genus(&mesh);
    r->err_stage = "field";
    valence = malloc((size_t)mesh.nv * sizeof *valence);
    if (!valence) {
        sq_error_set(&r->err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (sq_cones_from_field(&mesh, &r->opt, valence, &r->st, &r->err)) goto done;
    sq_cones_histogram(mesh.nv, valence, r->hist, CONES_HIST);
    r->err_stage = "write";
    double t1 = sq_now();
    if (sq_cones_from_field_write(r->out_path, mesh.nv, valence, r->list, &r->err)) goto done;
    r->t_write = sq_now() - t1;
    r->done = 1;
done:
    free(valence);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static const char *align_name(sq_field_align a)
{
    return a == SQ_FIELD_SMOOTH ? "smooth" : "curvature";
}

static void print_text(const cones_run *r)
{
    const sq_cones_from_field_stats *s = &r->st;
    printf("mesh          %s: %u vertices, %u faces, genus %lld\n", r->mesh_path, r->nv, r->nf,
           (long long)r->genus);
    printf("field         %s-aligned cross field on faces, energy %.4g", align_name(r->opt.field.align),
           s->field.energy);
    if (r->opt.field.align == SQ_FIELD_SMOOTH)
        printf(" (%u inverse iterations)", s->field.iterations);
    printf("\n");
    printf("singularities %u in the field; %u quarter turns cancelled in +/- pairs "
           "(radius %g edges); %u moved off valence <= 1%s\n",
           s->raw_singularities, s->cancelled, r->opt.cancel_radius, s->moved_units,
           s->torus_pair_cancelled ? "; lone torus 3-5 pair removed" : "");
    printf("cones         %u\n", s->cones);
    printf("valences     ");
    for (uint32_t k = 0; k < CONES_HIST; k++)
        if (k != 4 && r->hist[k]) printf(" %s%u:%u", k == CONES_HIST - 1 ? ">=" : "", k, r->hist[k]);
    printf("%s   (valence:count)\n", s->cones ? "" : " none");
    printf("gauss-bonnet  satisfied: sum(4 - k) = 4*chi = %lld; realizable\n",
           (long long)(4 * r->euler));
    printf("time          read %.1f ms, field %.1f ms (assemble %.1f, factor %.1f, solve "
           "%.1f), indices %.1f ms, write %.1f ms\n",
           1e3 * r->t_read, 1e3 * s->t_field, 1e3 * s->field.t_assemble, 1e3 * s->field.t_factor,
           1e3 * s->field.t_solve, 1e3 * s->t_indices, 1e3 * r->t_write);
    printf("wrote         %s (%s)\n", r->out_path, r->list ? "cone list" : "Th_hat");
}

static void print_json(const cones_run *r)
{
    const sq_cones_from_field_stats *s = &r->st;
    printf("{\n  \"ok\": %s,\n  \"mesh\": {\"path\": ", r->done ? "true" : "false");
    sq_json_string(stdout, r->mesh_path);
    if (r->nf) printf(", \"vertices\": %u, \"faces\": %u, \"genus\": %lld, \"euler\": %lld", r->nv,
                      r->nf, (long long)r->genus, (long long)r->euler);
    printf("},\n  \"output\": {\"path\": ");
    sq_json_string(stdout, r->out_path);
    printf(", \"format\": \"%s\", \"written\": %s}", r->list ? "list" : "th_hat",
           r->done ? "true" : "false");
    printf(",\n  \"options\": {\"align\": \"%s\", \"cancel_radius\": %.17g}",
           align_name(r->opt.field.align), r->opt.cancel_radius);
    if (r->done) {
        printf(",\n  \"field\": {\"energy\": %.17g, \"iterations\": %u}", s->field.energy,
               s->field.iterations);
        printf(",\n  \"cones\": {\"count\": %u, \"raw_singularities\": %u, \"cancelled\": %u, "
               "\"moved\": %u, \"torus_pair_cancelled\": %s, \"histogram\": {",
               s->cones, s->raw_singularities, s->cancelled, s->moved_units,
               s->torus_pair_cancelled ? "true" : "false");
        int first = 1;
        for (uint32_t k = 0; k < CONES_HIST; k++) {
            if (k == 4 || !r->hist[k]) continue;
            printf("%s\"%u\": %u", first ? "" : ", ", k, r->hist[k]);
            first = 0;
        }
        printf("}, \"gauss_bonnet\": true, \"realizable\": true}");
        printf(",\n  \"time_ms\": {\"read\": %.3f, \"field\": %.3f, \"assemble\": %.3f, "
               "\"factor\": %.3f, \"solve\": %.3f, \"indices\": %.3f, \"total\": %.3f, "
               "\"write\": %.3f}",
               1e3 * r->t_read, 1e3 * s->t_field, 1e3 * s->field.t_assemble,
               1e3 * s->field.t_factor, 1e3 * s->field.t_solve, 1e3 * s->t_indices,
               1e3 * s->t_total, 1e3 * r->t_write);
    } else {
        printf(",\n  ");
        sq_json_error(r->err.code, r->err_stage, r->err.msg);
    }
    printf("\n}\n");
}

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "seamquad cones: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see seamquad cones --help)\n");
    return SQ_EXIT_USAGE;
}

int sq_cmd_cones(int argc, char **argv)
{
    cones_run r;
    memset(&r, 0, sizeof r);
    sq_cones_from_field_default_options(&r.opt);
    int json = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (i + 1 >= argc) return usage_error("%s needs a file name", a);
            if (r.out_path) return usage_error("%s given twice", a);
            r.out_path = argv[++i];
        } else if (!strcmp(a, "--align")) {
            if (i + 1 >= argc) return usage_error("%s needs curvature or smooth", a);
            const char *v = argv[++i];
            if (!strcmp(v, "curvature")) r.opt.field.align = SQ_FIELD_CURVATURE;
            else if (!strcmp(v, "smooth")) r.opt.field.align = SQ_FIELD_SMOOTH;
            else return usage_error("--align takes curvature or smooth, not '%s'", v);
        } else if (!strcmp(a, "--cancel-radius")) {
            if (i + 1 >= argc) return usage_error("%s needs a number", a);
            const char *v = argv[++i];
            char *end;
            errno = 0;
            double x = strtod(v, &end);
            if (end == v || *end || errno || !(x >= 0) || x > 1e9)
                return usage_error("--cancel-radius takes a number >= 0, not '%s'", v);
            r.opt.cancel_radius = x;
        } else if (a[0] == '-' && a[1]) {
            return usage_error("unknown option '%s'", a);
        } else if (!r.mesh_path) {
            r.mesh_path = a;
        } else {
            return usage_error("more than one mesh given (second: '%s')", a);
        }
    }
    if (!r.mesh_path) {
        help(stderr);
        return SQ_EXIT_USAGE;
    }
    if (!r.out_path) return usage_error("no output file: give -o CONES%s", "");
    if (!*r.out_path) return usage_error("empty output file name%s", "");
    r.list = ends_with(r.out_path, ".cones");
    run(&r);
    if (json) print_json(&r);
    else if (r.done) print_text(&r);
    if (!r.done) {
        fprintf(stderr, "seamquad cones: error: %s\n", r.err.msg);
        return sq_exit_code(r.err.code);
    }
    return SQ_EXIT_OK;
}
