/* seamquad smooth: improve quad shapes on the input surface (docs/smooth.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_smooth.h"


static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad smooth QUADS --surface MESH -o OUT.obj [--iterations N]\n"
            "                       [--pin-threshold T] [--json]\n"
            "\n"
            "Moves the vertices of the closed quad mesh QUADS so that corner angles get\n"
            "closer to 90 degrees and edge lengths become locally uniform, while every\n"
            "vertex stays ON the triangle surface MESH (it ends as the closest surface\n"
            "point, a combination of one triangle's corners) and the connectivity is\n"
            "unchanged. Steps:\n"
            "  1. project every vertex onto MESH;\n"
            "  2. untangle: while some quad is folded (both of its triangulations bend\n"
            "     by more than ~90 degrees), optimize an untangling objective that may\n"
            "     not fold any other quad;\n"
            "  3. smooth: N outer iterations of Ceres (Levenberg-Marquardt, each step\n"
            "     by at most 10 conjugate-gradient iterations) in each vertex's tangent\n"
            "     plane, then re-projection. A step\n"
            "     that would fold a quad or raise the energy is halved and, if that\n"
            "     does not help, rejected (the report says so). Once a step fails\n"
            "     or stalls early, the later ones start Levenberg-Marquardt from a\n"
            "     small trust region (\"cautious\" in --json), and only if they fail\n"
            "     too, solve as thoroughly as untangling (\"thorough\").\n"
            "     From the second half of the iterations on, every vertex of MESH\n"
            "     that the quads miss by more than T times the local edge length\n"
            "     (and by at least half the widest such gap: a horn's tip, a corner)\n"
            "     gets the nearest quad vertex moved onto it and held there, where\n"
            "     that folds nothing and keeps the quality promise below; smoothing\n"
            "     alone would slide the vertices off such points.\n"
            "\n"
            "options:\n"
            "  --surface MESH     the closed triangle mesh (OBJ, OFF, PLY) to stay on\n"
            "  -o, --output OUT   output quad mesh (OBJ); written only on success\n"
            "  --iterations N     outer smoothing iterations (default 10; 0 = only\n"
            "                     project and untangle)\n"
            "  --solver-iterations N  Ceres iterations per outer iteration (default 5;\n"
            "                     untangling: 20)\n"
            "  --pin-threshold T  the pins' gap, in local edge lengths (default 0.3;\n"
            "                     0 = no pins: squarer quads, farther from MESH's\n"
            "                     sharp points)\n"
            "  --threads N        Ceres threads (default 1)\n"
            "  --json             machine-readable report on stdout\n"
            "  -q, --quiet        no progress on stderr\n"
            "  -h, --help         this help\n"
            "\n"
            "Quality is reported before and after: mean |corner angle - 90| (degrees),\n"
            "minimum and mean scaled Jacobian, mean and max edge ratio (longest/shortest\n"
            "edge of a quad), folded quads, and the largest vertex-to-surface distance\n"
            "relative to the surface's bounding-box diagonal. After untangling, no step\n"
            "or pin raises the mean |angle - 90| or the mean edge ratio or lowers the\n"
            "minimum scaled Jacobian.\n"
            "\n"
            "exit code 0 on success; 1 for unusable input; 2 for a wrong command line;\n"
            "3 when untangling fails or on an internal failure.\n"
            "\n"
            "example:\n"
            "  seamquad smooth ../shared/data/quads/bunny_quadriflow5k.obj \\\n"
            "      --surface ../shared/data/libigl/bunny.off -o bunny_smooth.obj\n");
}

typedef struct progress_ctx {
    int enabled;
} progress_ctx;

static void progress(void *user, const char *phase, int it, double energy, uint32_t folded)
{
    const progress_ctx *p = user;
    if (!p->enabled) return;
    if (!strcmp(phase, "untangle"))
        fprintf(stderr, "seamquad smooth: untangle %d: %u quads folded or nearly folded\n", it, folded);
    else
        fprintf(stderr, "seamquad smooth: iteration %d: energy %.6g\n", it, energy);
}

static void print_quality_json(const char *name, const sq_quad_quality *q, double dist)
{
    printf("  \"%s\": {\"angle_mean_abs_dev_from_90_deg\": %.17g, \"angle_min_deg\": %.17g, "
           "\"angle_max_deg\": %.17g, \"scaled_jacobian_min\": %.17g, \"scaled_jacobian_mean\": %.17g, "
           "\"edge_ratio_mean\": %.17g, \"edge_ratio_max\": %.17g, \"folded\": %u, "
           "\"fold_margin_min\": %.17g",
           name, q->angle_mean_dev_deg, q->angle_min_deg, q->angle_max_deg, q->sjac_min, q->sjac_mean,
           q->edge_ratio_mean, q->edge_ratio_max, q->folded, q->fold_margin_min);
    if (dist >= 0.0) printf(", \"max_surface_distance_rel\": %.17g", dist);
    printf("},\n");
}

static void print_quality_text(const char *name, const sq_quad_quality *q)
{
    printf("%-10s mean|a-90| %7.3f deg  angles [%6.2f, %6.2f]  sJ min %8.5f mean %.5f  edge ratio mean "
           "%.4f max %.3g  folded %u\n",
           name, q->angle_mean_dev_deg, q->angle_min_deg, q->angle_max_deg, q->sjac_min, q->sjac_mean,
           q->edge_ratio_mean, q->edge_ratio_max, q->folded);
}

static sq_status load_quads(const char *path, sq_soup *soup, sq_mesh *mesh, sq_error *err)
{
    sq_status st = sq_read_mesh(path, soup, err);
    if (st != SQ_OK) return st;
    for (uint32_t f = 0; f < soup->nf; f++) {
        uint32_t n = soup->face_off[f + 1] - soup->face_off[f];
        if (n != 4) {
            char where[256];
            sq_soup_where_face(soup, f, where, sizeof where);
            return sq_error_set(err, SQ_ERR_POLYGON, "%s: face %u has %u corners: smooth needs a pure quad mesh",
                                where[0] ? where : path, f, n);
        }
    }
    return sq_mesh_from_soup(soup, SQ_MESH_ALLOW_POLYGONS, mesh, err);
}

int sq_cmd_smooth(int argc, char **argv)
{
    const char *in = NULL, *surface = NULL, *out = NULL;
    int json = 0, quiet = 0;
    sq_smooth_options opt;
    sq_smooth_options_default(&opt);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            quiet = 1;
        } else if ((!strcmp(a, "--surface") || !strcmp(a, "-o") || !strcmp(a, "--output") ||
                    !strcmp(a, "--iterations") || !strcmp(a, "--solver-iterations") ||
                    !strcmp(a, "--threads") || !strcmp(a, "--pin-threshold")) && i + 1 < argc) {
            const char *v = argv[++i];
            if (!strcmp(a, "--surface")) surface = v;
            else if (!strcmp(a, "--pin-threshold")) {
                char *end;
                double t = strtod(v, &end);
                if (*end || end == v || !(t >= 0.0 && t <= 1e6)) {
                    fprintf(stderr, "seamquad smooth: --pin-threshold needs a number >= 0, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.pin_threshold = t;
            }
            else if (!strcmp(a, "-o") || !strcmp(a, "--output")) out = v;
            else {
                char *end;
                long n = strtol(v, &end, 10);
                if (*end || end == v || n < 0 || n > 100000 || (strcmp(a, "--iterations") && n < 1)) {
                    fprintf(stderr, "seamquad smooth: %s needs a %s integer, got '%s'\n", a,
                            strcmp(a, "--iterations") ? "positive" : "non-negative", v);
                    return SQ_EXIT_USAGE;
                }
                if (!strcmp(a, "--iterations")) opt.iterations = (int)n;
                else if (!strcmp(a, "--solver-iterations")) opt.solver_iterations = (int)n;
                else opt.num_threads = (int)n;
            }
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad smooth: unknown or incomplete option '%s' (see --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!in) {
            in = a;
        } else {
            fprintf(stderr, "seamquad smooth: more than one quad mesh given ('%s', '%s')\n", in, a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!in || !surface || !out) {
        fprintf(stderr, "seamquad smooth: need QUADS, --surface MESH and -o OUT (see --help)\n");
        return SQ_EXIT_USAGE;
    }
    if (sq_format_from_path(out) != SQ_FORMAT_OBJ) {
        fprintf(stderr, "seamquad smooth: output '%s' must be an .obj file\n", out);
        return SQ_EXIT_USAGE;
    }
    progress_ctx pc = {!quiet && isatty(2)};
    opt.progress = progress, opt.progress_user = &pc;

    sq_error err;
    sq_error_clear(&err);
    sq_soup ssoup = {0}, qsoup = {0};
    sq_mesh smesh = {0}, qmesh = {0};
    sq_smooth_stats stats;
    memset(&stats, 0, sizeof stats);
    uint32_t *tri = NULL, *quads = NULL;
    const char *stage = "surface";
    double t0 = sq_now();
    sq_status st = sq_read_mesh(surface, &ssoup, &err);
    if (st == SQ_OK) st = sq_mesh_from_soup(&ssoup, 0, &smesh, &err);
    if (st == SQ_OK) stage = "quads", st = load_quads(in, &qsoup, &qmesh, &err);
    if (st == SQ_OK) {
        tri = malloc(3 * (size_t)ssoup.nf * sizeof(uint32_t));
        quads = malloc(4 * (size_t)qsoup.nf * sizeof(uint32_t));
        if (!tri || !quads) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
    }
    if (st == SQ_OK) {
        memcpy(tri, ssoup.face_idx, 3 * (size_t)ssoup.nf * sizeof(uint32_t));
        memcpy(quads, qsoup.face_idx, 4 * (size_t)qsoup.nf * sizeof(uint32_t));
        stage = "smooth";
        st = sq_smooth_quads(ssoup.nv, ssoup.pos, ssoup.nf, tri, qsoup.nv, qsoup.pos, qsoup.nf, quads, &opt,
                             &stats, &err);
    }
    if (st == SQ_OK) {
        stage = "write";
        uint32_t *off = malloc(((size_t)qsoup.nf + 1) * sizeof(uint32_t));
        if (!off) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        else {
            for (uint32_t f = 0; f <= qsoup.nf; f++) off[f] = 4 * f;
            st = sq_write_obj(out, qsoup.nv, qsoup.pos, qsoup.nf, off, quads, 0, NULL, NULL, &err);
            free(off);
        }
    }
    double total = sq_now() - t0;
    int ran = stats.before.nq > 0;
    if (json) {
        printf("{\n  \"ok\": %s,\n  \"input\": ", st == SQ_OK ? "true" : "false");
        sq_json_string(stdout, in);
        printf(",\n  \"surface\": ");
        sq_json_string(stdout, surface);
        printf(",\n  \"output\": ");
        sq_json_string(stdout, out);
        printf(",\n  \"vertices\": %u, \"quads\": %u,\n", qsoup.nv, qsoup.nf);
        if (ran) {
            print_quality_json("before", &stats.before, stats.dist_before_rel);
            print_quality_json("projected", &stats.projected, -1.0);
            print_quality_json("untangled", &stats.untangled, -1.0);
            print_quality_json("after", &stats.after, stats.dist_after_rel);
            printf("  \"untangle_iterations\": %d, \"iterations\": %d, \"solver_iterations\": %ld, "
                   "\"solver_rejected_steps\": %ld, \"fold_rejections\": %ld, \"backtracks\": %d, "
                   "\"steps_rejected\": %d, \"pinned\": %u, \"cautious\": %s, \"thorough\": %s,\n  \"energy_before\": %.17g, \"energy_after\": %.17g, "
                   "\"linear_solver\": \"%s\", \"stop_reason\": ",
                   stats.untangle_iterations, stats.iterations, stats.solver_iterations, stats.solver_rejected,
                   stats.fold_rejections, stats.backtracks, stats.steps_rejected, stats.pinned,
                   stats.cautious ? "true" : "false", stats.thorough ? "true" : "false", stats.energy_before,
                   stats.energy_after, stats.linear_solver);
            sq_json_string(stdout, stats.stop_reason);
            printf(",\n  \"smooth_s\": %.3f,\n", stats.seconds);
        }
        printf("  \"total_s\": %.3f", total);
        if (st != SQ_OK) {
            printf(",\n  ");
            sq_json_error(st, stage, err.msg);
        }
        printf("\n}\n");
    } else if (ran) {
        printf("quad mesh  %s: %u vertices, %u quads\n", in, qsoup.nv, qsoup.nf);
        print_quality_text("before", &stats.before);
        print_quality_text("projected", &stats.projected);
        print_quality_text("untangled", &stats.untangled);
        print_quality_text("after", &stats.after);
        printf("surface    max distance/diagonal: before %.3g, after %.3g\n", stats.dist_before_rel,
               stats.dist_after_rel);
        printf("solver     %d untangle + %d smoothing iterations, %ld Ceres iterations (%s), %ld Ceres steps "
               "rejected (%ld trial states would fold a quad), %d backtracks, %d steps rejected%s%s\n",
               stats.untangle_iterations, stats.iterations, stats.solver_iterations, stats.linear_solver,
               stats.solver_rejected, stats.fold_rejections, stats.backtracks, stats.steps_rejected,
               stats.cautious ? " (a quick step failed or stalled: the later ones from a small trust region)" : "",
               stats.thorough ? " (quick steps failed or stalled: then solved as thoroughly as untangling)" : "");
        printf("stop       %s\n", stats.stop_reason);
        printf("energy     %.6g -> %.6g\ntime       %.2f s\n", stats.energy_before, stats.energy_after, total);
        if (st == SQ_OK) printf("output     %s\n", out);
    }
    if (st != SQ_OK) fprintf(stderr, "seamquad smooth: %s\n", err.msg);
    free(tri), free(quads);
    sq_mesh_free(&smesh), sq_mesh_free(&qmesh);
    sq_soup_free(&ssoup), sq_soup_free(&qsoup);
    return sq_exit_code(st);
}
