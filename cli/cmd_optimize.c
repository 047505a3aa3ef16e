/* seamquad optimize: lower the distortion of a seamless map, keeping its
 * seams, cones and injectivity (quantize/sq_optimize.h, docs/optimize.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_mesh.h"
#include "sq_optimize.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad optimize MESH --map MAP.obj -o OUT.obj [--cones FILE]\n"
            "                         [--translations free|fixed] [--iterations N]\n"
            "                         [--json] [--quiet]\n"
            "\n"
            "Lowers the distortion of a seamless map of the closed triangle mesh MESH\n"
            "while keeping what makes it usable for quad meshing: the seams (every\n"
            "edge's two sides still differ by the same rotation by a multiple of 90\n"
            "degrees), the cones (same angles, same vertices) and injectivity (every UV\n"
            "triangle positive).\n"
            "\n"
            "The energy is the symmetric Dirichlet energy |J|^2 + |J^-1|^2 per triangle\n"
            "(4 for a triangle mapped without distortion; it grows without bound as a\n"
            "triangle degenerates), averaged over the surface area, with the surface\n"
            "scaled to the map's area. The unknowns are a basis of the seamless maps\n"
            "with the input's rotations, so every iterate is seamless by construction.\n"
            "Each projected Newton step is cut to the largest that keeps every triangle\n"
            "positive, shortened until the energy falls, and accepted only if the exact\n"
            "orientation test passes. The result is made exact on a dyadic grid and\n"
            "checked; where that fails (free translations on a map with triangles far\n"
            "thinner than the grid, as param's maps have), rounds with the transitions\n"
            "fixed widen them and the free rounds resume. If it cannot improve the\n"
            "map, OUT.obj is the input map and the report says why.\n"
            "\n"
            "options:\n"
            "  --map MAP.obj        the seamless map (OBJ with f v/vt corners), of MESH or\n"
            "                       of a refinement whose first vertices are MESH's\n"
            "  -o OUT.obj           the optimized map (same mesh as MAP.obj)\n"
            "  --cones FILE         the cones the map must have (Th_hat or cone list)\n"
            "  --translations KIND  free (default): the seams' translations may change\n"
            "                       (before quantization); fixed: they and the cones\n"
            "                       stay, so an integer-grid map stays one\n"
            "  --iterations N       at most N Newton steps (default 100; param's maps\n"
            "                       gain up to a few hundred)\n"
            "  --references K|off   progressive references (default 1000): while a\n"
            "                       triangle's energy is above K, each triangle is\n"
            "                       measured against a shape between its current one\n"
            "                       and its surface shape, within K of the current one,\n"
            "                       so the worst triangles do not cut every step short\n"
            "                       (param's maps: helmet's mean conformal ratio 419 ->\n"
            "                       9.8 in 200 steps, 256 without); off: the surface's\n"
            "                       shapes throughout\n"
            "  --json               statistics on stdout\n"
            "  --quiet              no progress on stderr, no summary on stdout\n"
            "  -h, --help           this help\n"
            "\n"
            "exit codes: 0 success (also when the map could not be improved); 1 the\n"
            "input cannot be processed (the message names the file and element) or an\n"
            "output cannot be written; 2 wrong command line; 3 internal failure. On any\n"
            "error nothing is written.\n"
            "\n"
            "example:\n"
            "  seamquad param eight.obj --cones eight_Th_hat -o eight.map.obj\n"
            "  seamquad optimize eight.obj --map eight.map.obj -o eight.opt.obj\n");
}

static void progress(void *user, uint32_t it, double energy, double step)
{
    (void)user;
    fprintf(stderr, "  iteration %3u  energy %.6g  step %.3g\n", it, energy, step);
}

int sq_cmd_optimize(int argc, char **argv)
{
    const char *mesh_path = NULL, *map_path = NULL, *out_path = NULL, *cones_path = NULL;
    int json = 0, quiet = 0;
    sq_optimize_options opt;
    memset(&opt, 0, sizeof opt);
    opt.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = 1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--cones") ||
                   !strcmp(a, "--map") || !strcmp(a, "--translations") ||
                   !strcmp(a, "--iterations") || !strcmp(a, "--references")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad optimize: %s needs a value\n", a);
                return SQ_EXIT_USAGE;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "--cones")) cones_path = v;
            else if (!strcmp(a, "--map")) map_path = v;
            else if (!strcmp(a, "--translations")) {
                if (!strcmp(v, "free")) opt.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
                else if (!strcmp(v, "fixed")) opt.basis = SQ_OPTIMIZE_FIXED_TRANSITIONS;
                else {
                    fprintf(stderr, "seamquad optimize: --translations is free or fixed, not '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
            } else if (!strcmp(a, "--references")) {
                char *end = NULL;
                double k = strtod(v, &end);
                if (!strcmp(v, "off")) {
                    opt.reference_bound = INFINITY;
                } else if (!end || *end || end == v || !(k > 4) || !isfinite(k)) {
                    fprintf(stderr, "seamquad optimize: --references is off or an energy bound above 4, not '%s'\n", v);
                    return SQ_EXIT_USAGE;
                } else {
                    opt.reference_bound = k;
                }
            } else if (!strcmp(a, "--iterations")) {
                char *end = NULL;
                long n = strtol(v, &end, 10);
                if (!end || *end || n < 1 || n > 100000) {
                    fprintf(stderr, "seamquad optimize: --iterations needs a count from 1 to 100000, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.max_iterations = (uint32_t)n;
            } else out_path = v;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad optimize: unknown option '%s' (see seamquad optimize --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            fprintf(stderr, "seamquad optimize: unexpected argument '%s' (one MESH)\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!mesh_path || !map_path || !out_path) {
        fprintf(stderr, "seamquad optimize: give MESH, --map MAP.obj and -o OUT.obj (see seamquad "
                        "optimize --help)\n");
        return SQ_EXIT_USAGE;
    }
    if (sq_format_from_path(out_path) != SQ_FORMAT_OBJ) {
        fprintf(stderr, "seamquad optimize: the output '%s' must be an .obj file\n", out_path);
        return SQ_EXIT_USAGE;
    }
    const char *ins[3] = {mesh_path, map_path, cones_path};
    for (int k = 0; k < 3; k++)
        if (ins[k] && !strcmp(out_path, ins[k])) {
            fprintf(stderr, "seamquad optimize: the output would overwrite the input '%s'\n", ins[k]);
            return SQ_EXIT_USAGE;
        }
    if (!quiet && !json) opt.progress = progress;

    sq_error err;
    sq_error_clear(&err);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    sq_map M;
    memset(&M, 0, sizeof M);
    sq_map_report mrep;
    memset(&mrep, 0, sizeof mrep);
    sq_optimize_report rep;
    memset(&rep, 0, sizeof rep);
    int32_t *valence = NULL;
    const char *stage = "read";
    double t0 = sq_now(), t_read = 0, t_write = 0;
    sq_status st = sq_read_mesh(mesh_path, &soup, &err);
    if (!st) st = sq_mesh_from_soup(&soup, 0, &mesh, &err);
    if (!st && cones_path) {
        stage = "cones";
        valence = malloc((size_t)mesh.nv * sizeof *valence);
        if (!valence) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        else st = sq_cli_read_cones(cones_path, &mesh, valence, &err);
    }
    if (!st) {
        stage = "map";
        st = sq_map_read(map_path, &mesh, valence, 1e-9, 0, &M, &mrep, &err);
        if (st) sq_cli_name_file(&err, map_path);
    }
    t_read = sq_now() - t0;
    if (!st) {
        stage = "optimize";
        /* free translations: where the snapped result cannot be made
         * exact, rounds with the transitions fixed (sq_optimize_free.c) */
        st = opt.basis == SQ_OPTIMIZE_FREE_TRANSLATIONS ? sq_optimize_map_free_or_fixed(&M, &opt, &rep, &err)
                                                        : sq_optimize_map(&M, &opt, &rep, &err);
    }
    if (!st) {
        stage = "write";
        double t1 = sq_now();
        st = sq_map_write_obj(out_path, &M, &err);
        t_write = sq_now() - t1;
    }
    double t_total = sq_now() - t0;
    if (json) {
        sq_json_open_map_report(st, mesh_path, map_path, out_path);
        printf(",\n  \"translations\": \"%s\"",
               opt.basis == SQ_OPTIMIZE_FIXED_TRANSITIONS ? "fixed" : "free");
        if (M.mesh.nv)
            printf(",\n  \"map_vertices\": %u, \"map_faces\": %u, \"seam_edges\": %u, \"cones\": %u",
                   M.mesh.nv, M.mesh.nf, mrep.seam_edges, mrep.cones);
        if (stage[0] == 'w' || !st) {
            printf(",\n  \"unknowns\": %u, \"held_triangles\": %u, \"iterations\": %u, \"reference_iterations\": %u, "
                   "\"changed\": %s,\n  \"energy_before\": ",
                   rep.unknowns, rep.held_triangles, rep.iterations, rep.reference_iterations,
                   rep.changed ? "true" : "false");
            sq_json_double(stdout, rep.energy_before);
            printf(", \"energy_after\": ");
            sq_json_double(stdout, rep.energy_after);
            printf(", \"max_energy_before\": ");
            sq_json_double(stdout, rep.max_energy_before);
            printf(", \"max_energy_after\": ");
            sq_json_double(stdout, rep.max_energy_after);
            printf(",\n  \"relax\": {\"moves\": %u, \"stretch_before\": ", rep.relax_moves);
            sq_json_double(stdout, rep.relax_stretch_before);
            printf(", \"stretch_after\": ");
            sq_json_double(stdout, rep.relax_stretch_after);
            printf("}");
            printf(",\n  \"rounds\": %u, \"fixed_rounds\": %u", rep.rounds, rep.fixed_rounds);
            printf(",\n  \"stopped\": ");
            sq_json_string(stdout, rep.why);
        }
        printf(",\n  \"time_s\": {\"read\": %.6f, \"basis\": %.6f, \"solve\": %.6f, \"optimize\": %.6f, "
               "\"write\": %.6f, \"total\": %.6f}",
               t_read, rep.seconds_basis, rep.seconds_solve, rep.seconds, t_write, t_total);
        if (st != SQ_OK) {
            printf(",\n  ");
            sq_json_error(st, stage, err.msg);
        }
        printf("\n}\n");
    } else if (!st && !quiet) {
        printf("map           %s: %u vertices, %u faces, %u seam edges, %u cones\n", map_path,
               M.mesh.nv, M.mesh.nf, mrep.seam_edges, mrep.cones);
        printf("energy        symmetric Dirichlet, area mean %.6g -> %.6g; worst triangle %.6g -> %.6g\n",
               rep.energy_before, rep.energy_after, rep.max_energy_before, rep.max_energy_after);
        printf("optimizer     %u unknowns (translations %s), %u iterations: %s%s\n", rep.unknowns,
               opt.basis == SQ_OPTIMIZE_FIXED_TRANSITIONS ? "fixed" : "free", rep.iterations, rep.why,
               rep.changed ? "" : "; the map is unchanged");
        if (rep.fixed_rounds)
            printf("rounds        %u, %u of them with the transitions fixed (the free result could not be\n"
                   "              made exact: triangles far thinner than its grid)\n",
                   rep.rounds, rep.fixed_rounds);
        if (rep.relax_moves)
            printf("relaxed       %u local moves; worst triangle stretch %.3g -> %.3g\n", rep.relax_moves,
                   rep.relax_stretch_before, rep.relax_stretch_after);
        if (rep.reference_iterations)
            printf("references    %u iterations against progressive references (a triangle's energy\n"
                   "              bounded by %g against its reference)\n",
                   rep.reference_iterations,
                   opt.reference_bound > 0 ? opt.reference_bound : SQ_OPTIMIZE_REFERENCE_BOUND);
        if (rep.held_triangles)
            printf("held          %u triangles too distorted or too thin to move (kept as they are)\n",
                   rep.held_triangles);
        printf("verified      every UV triangle positive (exact); every seam exact, with the input's "
               "rotations; the cones' angles kept\n");
        printf("time          read %.3f s, optimize %.3f s (solves %.3f s), write %.3f s; total %.3f s\n",
               t_read, rep.seconds, rep.seconds_solve, t_write, t_total);
        printf("wrote         %s\n", out_path);
    }
    if (st) fprintf(stderr, "seamquad optimize: error (%s): %s\n", stage, err.msg);
    free(valence);
    sq_map_free(&M);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    if (st == SQ_ERR_ARGUMENT) return SQ_EXIT_INVALID_INPUT;
    return sq_exit_code(st);
}
