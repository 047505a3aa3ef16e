/* seamquad quantize: an integer-grid map at the user's scale from a
 * seamless map (quantize/sq_quantize.h, docs/quantize.md). */
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
#include "sq_quantize.h"
#include "sq_tmesh.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad quantize MESH --map MAP.obj (--quads N | --edge-length L)\n"
            "                         -o IGM.obj [--cones FILE] [--targets surface|map]\n"
            "                         [--prepare on|off] [--prepare-iterations N]\n"
            "                         [--optimize on|off] [--svg TMESH.svg] [--json] [--quiet]\n"
            "\n"
            "Turns a seamless map of the closed triangle mesh MESH into an integer-grid\n"
            "map (IGM) with about N quads, from which `seamquad extract` builds the quad\n"
            "mesh.\n"
            "\n"
            "MAP.obj gives every face corner of MESH (or of a refinement of it whose\n"
            "first vertices are MESH's, as `seamquad param` writes) a UV point; across\n"
            "every edge the two sides must differ by a rotation by a multiple of 90\n"
            "degrees plus a translation (1e-9 of the UV size), every UV triangle must be\n"
            "positive. A map that is seamless only up to rounding (published maps are,\n"
            "to about 1e-13) is first made exact on a dyadic grid 2^-40 of its size;\n"
            "a folded or broken map is refused with the face or seam named, never\n"
            "repaired.\n"
            "\n"
            "Steps: (0) the map's distortion is lowered first, its rotations and cones\n"
            "kept, its translations free (as `seamquad optimize` does; up to a few\n"
            "seconds on published maps, minutes on param's largest): quantization\n"
            "follows the map's shape, and quads made from a very distorted map (as\n"
            "param's are) come out skewed, folded or upside down; (1) the T-mesh:\n"
            "from every cone the iso-lines along the axes are traced, exactly, until\n"
            "they meet a cone or another trace (the motorcycle graph of Quantized\n"
            "Global Parametrization); they cut the surface into rectangles; (2) the\n"
            "map's triangles are split along the traces; (3) every arc (piece of a\n"
            "trace between two nodes) gets an integer length >= 1, opposite sides of\n"
            "every rectangle equal, close to targets scaled to the size asked (a\n"
            "min-cost flow, LEMON's network simplex); (4) every rectangle is\n"
            "re-embedded onto its integer rectangle, and the result is checked\n"
            "exactly as an integer-grid map; (5) the integer-grid map's distortion is\n"
            "lowered with its transitions and cones fixed (symmetric Dirichlet,\n"
            "projected Newton, at most 20 steps; docs/optimize.md): the quads come out\n"
            "closer to squares, the layout and the quad count stay.\n"
            "\n"
            "Guarantees of IGM.obj (written only when all hold): every UV triangle is\n"
            "positive (exact predicate); across every edge a rotation by k x 90 degrees\n"
            "plus an integer translation, exactly; every cone on an integer point with\n"
            "its angle; the first vertices are MESH's. No two cones or T-junctions\n"
            "merge and no rectangle collapses: every arc is at least 1 long.\n"
            "\n"
            "options:\n"
            "  --map MAP.obj        the seamless map (OBJ with f v/vt corners)\n"
            "  --quads N            about N quads (1 <= N <= 1e8); below the fewest the\n"
            "                       T-mesh allows, that fewest is built and reported\n"
            "  --edge-length L      quad edges of about L on the surface instead\n"
            "  -o IGM.obj           the integer-grid map (a refinement of the map)\n"
            "  --cones FILE         the cones the map must have (Th_hat or cone list);\n"
            "                       without it, the map's angle sums decide\n"
            "  --targets KIND       arc lengths aimed at from their length on the\n"
            "                       surface (surface) or in the map (map, the default:\n"
            "                       the map's own proportions, least re-embedding)\n"
            "  --prepare on|off     step (0) (default on; off: the map as it is, the fast\n"
            "                       path for maps already close to conformal)\n"
            "  --prepare-iterations N\n"
            "                       step (0)'s budget of Newton steps (default 600)\n"
            "  --optimize on|off    step (5) (default on; off: the re-embedded map as is)\n"
            "  --svg TMESH.svg      the traces over the UV layout (cones red,\n"
            "                       T-junctions blue)\n"
            "  --json               statistics on stdout: T-mesh, sizes, times\n"
            "  --quiet              no summary on stdout\n"
            "  -h, --help           this help\n"
            "\n"
            "exit codes: 0 success; 1 the input cannot be processed (the message names\n"
            "the file and element) or an output cannot be written; 2 wrong command\n"
            "line; 3 internal failure. On any error nothing is written.\n"
            "\n"
            "example:\n"
            "  seamquad quantize ../shared/data/mpz/eight.obj --map ../shared/data/mpz/eight.obj \\\n"
            "      --cones ../shared/data/mpz/eight_Th_hat --quads 5000 -o eight.igm.obj\n"
            "  seamquad extract ../shared/data/mpz/eight.obj eight.igm.obj -o eight.quads.obj\n");
}

static void progress(void *user, uint32_t it, double energy, double step)
{
    (void)user;
    fprintf(stderr, "  prepare: iteration %3u  energy %.6g  step %.3g\n", it, energy, step);
}

typedef struct report {
    const char *mesh_path, *map_path, *out_path, *cones_path, *svg_path;
    double quads, edge_length;
    int targets, optimize, prepare, prepared;
    uint32_t prepare_iterations;
    uint32_t nv, nf, map_nv, map_nf, igm_nv, igm_nf;
    int64_t genus;
    sq_map_report map;
    sq_quantize_prepare_report pre;
    sq_quantize_stats st;
    double t_read, t_map, t_write, t_total;
    int done;
} report;

static void print_text(const report *r)
{
    const sq_quantize_stats *s = &r->st;
    printf("mesh          %s: %u vertices, %u faces, genus %lld\n", r->mesh_path, r->nv, r->nf,
           (long long)r->genus);
    printf("map           %s: %u vertices, %u faces, %u seam edges in %u curves, %u cones\n",
           r->map_path, r->map_nv, r->map_nf, r->map.seam_edges, r->map.seam_curves, r->map.cones);
    if (r->map.grid > 0)
        printf("made exact    seams off by up to %.2g of the UV diagonal; %u UV values moved to "
               "the grid %.3g\n",
               r->map.max_seam_error, r->map.moved_uv, r->map.grid);
    else
        printf("made exact    already exact\n");
    if (r->prepared) {
        const sq_optimize_report *o = &r->pre.optimize;
        printf("prepared      mean conformal ratio %.4g -> %.4g (symmetric Dirichlet %.4g -> %.4g), %u "
               "iterations%s, %.3f s: %s\n",
               r->pre.conformal_before, r->pre.conformal_after, o->energy_before, o->energy_after,
               o->iterations, o->fixed_rounds ? " (rounds with the transitions fixed where free was not exact)" : "",
               o->seconds, o->why);
    }
    printf("T-mesh        %u nodes, %u arcs, %u rectangles\n", s->nodes, s->arcs, s->faces);
    printf("split         %u vertices, %u triangles\n", s->split_vertices, s->split_triangles);
    if (r->quads > 0) {
        printf("quads         %.0f (asked %.0f", s->quads, r->quads);
        if (r->quads < s->min_quads)
            printf("; the fewest this T-mesh allows is about %.0f: built that", s->min_quads);
        printf(")\n");
    } else {
        printf("quads         %.0f (edge length %g)\n", s->quads, r->edge_length);
    }
    printf("re-embedded   %u rectangles by the surface's mean-value map, %u by a fallback\n", s->faces - s->fallback_faces,
           s->fallback_faces);
    if (s->refine_rounds)
        printf("refined       %u rectangles cut along their kink lines and grids first (%u rounds)\n",
               s->refined_faces, s->refine_rounds);
    if (r->optimize)
        printf("optimized     symmetric Dirichlet %.4g -> %.4g (worst triangle %.4g -> %.4g), %u "
               "iterations, %.3f s: %s\n",
               r->st.optimize.energy_before, r->st.optimize.energy_after, r->st.optimize.max_energy_before,
               r->st.optimize.max_energy_after, r->st.optimize.iterations, r->st.optimize.seconds, r->st.optimize.why);
    printf("verified      every UV triangle positive (exact); every seam a rotation by k*90\n"
           "              degrees plus an integer translation, exactly; cones on integer points\n");
    printf("time          read %.3f s, map %.3f s, prepare %.3f s, T-mesh %.3f s, split %.3f s, layout %.3f s, "
           "lengths %.3f s, embed %.3f s, write %.3f s; total %.3f s\n",
           r->t_read, r->t_map, r->pre.optimize.seconds, s->seconds_tmesh, s->seconds_split, s->seconds_layout,
           s->seconds_lengths, s->seconds_embed, r->t_write, r->t_total);
    printf("wrote         %s (%u vertices, %u faces)%s%s\n", r->out_path, r->igm_nv, r->igm_nf,
           r->svg_path ? ", " : "", r->svg_path ? r->svg_path : "");
}

static void print_json(const report *r, sq_status st, const char *stage, const char *msg)
{
    const sq_quantize_stats *s = &r->st;
    sq_json_open_map_report(st, r->mesh_path, r->map_path, r->out_path);
    if (r->quads > 0) printf(",\n  \"quads_asked\": %.0f", r->quads);
    else printf(",\n  \"edge_length\": %.17g", r->edge_length);
    printf(",\n  \"targets\": \"%s\"", r->targets == SQ_TARGETS_MAP ? "map" : "surface");
    if (r->nv) printf(",\n  \"mesh_vertices\": %u, \"mesh_faces\": %u, \"genus\": %lld", r->nv, r->nf, (long long)r->genus);
    if (r->map_nv)
        printf(",\n  \"map_vertices\": %u, \"map_faces\": %u, \"seam_edges\": %u, \"seam_curves\": %u, "
               "\"cones\": %u, \"seam_error\": %.3g, \"grid\": %.17g, \"moved_uv\": %u",
               r->map_nv, r->map_nf, r->map.seam_edges, r->map.seam_curves, r->map.cones,
               r->map.max_seam_error, r->map.grid, r->map.moved_uv);
    if (r->prepared) {
        const sq_optimize_report *o = &r->pre.optimize;
        printf(",\n  \"prepare\": {\"conformal_before\": ");
        sq_json_double(stdout, r->pre.conformal_before);
        printf(", \"conformal_after\": ");
        sq_json_double(stdout, r->pre.conformal_after);
        printf(", \"energy_before\": ");
        sq_json_double(stdout, o->energy_before);
        printf(", \"energy_after\": ");
        sq_json_double(stdout, o->energy_after);
        printf(", \"iterations\": %u, \"rounds\": %u, \"fixed_rounds\": %u, \"stopped\": ", o->iterations,
               o->rounds, o->fixed_rounds);
        sq_json_string(stdout, o->why);
        printf("}");
    }
    if (r->done)
        printf(",\n  \"tmesh\": {\"nodes\": %u, \"arcs\": %u, \"faces\": %u},\n  \"split_vertices\": %u, "
               "\"split_triangles\": %u, \"fallback_faces\": %u, \"refined_faces\": %u, \"refine_rounds\": %u,\n  "
               "\"quads\": %.0f, \"min_quads\": %.0f, \"igm_vertices\": %u, \"igm_faces\": %u",
               s->nodes, s->arcs, s->faces, s->split_vertices, s->split_triangles, s->fallback_faces,
               s->refined_faces, s->refine_rounds, s->quads, s->min_quads, r->igm_nv, r->igm_nf);
    if (r->done && r->optimize) {
        printf(",\n  \"optimize\": {\"iterations\": %u, \"changed\": %s, \"energy_before\": ",
               r->st.optimize.iterations, r->st.optimize.changed ? "true" : "false");
        sq_json_double(stdout, r->st.optimize.energy_before);
        printf(", \"energy_after\": ");
        sq_json_double(stdout, r->st.optimize.energy_after);
        printf(", \"max_energy_before\": ");
        sq_json_double(stdout, r->st.optimize.max_energy_before);
        printf(", \"max_energy_after\": ");
        sq_json_double(stdout, r->st.optimize.max_energy_after);
        printf(", \"seconds\": %.6f, \"stopped\": ", r->st.optimize.seconds);
        sq_json_string(stdout, r->st.optimize.why);
        printf("}");
    }
    printf(",\n  \"time_s\": {\"read\": %.6f, \"map\": %.6f, \"prepare\": %.6f, \"tmesh\": %.6f, \"split\": %.6f, "
           "\"layout\": %.6f, \"lengths\": %.6f, \"embed\": %.6f, \"write\": %.6f, \"total\": %.6f}",
           r->t_read, r->t_map, r->pre.optimize.seconds, s->seconds_tmesh, s->seconds_split,
           s->seconds_layout, s->seconds_lengths, s->seconds_embed, r->t_write, r->t_total);
    if (st != SQ_OK) {
        printf(",\n  ");
        sq_json_error(st, stage, msg);
    }
    printf("\n}\n");
}

int sq_cmd_quantize(int argc, char **argv)
{
    report r;
    memset(&r, 0, sizeof r);
    r.targets = SQ_TARGETS_MAP;
    r.optimize = 1;
    r.prepare = 1;
    int json = 0, quiet = 0, have_quads = 0, have_len = 0;
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
                   !strcmp(a, "--map") || !strcmp(a, "--svg") || !strcmp(a, "--quads") ||
                   !strcmp(a, "--edge-length") || !strcmp(a, "--targets") || !strcmp(a, "--optimize") ||
                   !strcmp(a, "--prepare") || !strcmp(a, "--prepare-iterations")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad quantize: %s needs a value\n", a);
                return SQ_EXIT_USAGE;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "--cones")) r.cones_path = v;
            else if (!strcmp(a, "--map")) r.map_path = v;
            else if (!strcmp(a, "--svg")) r.svg_path = v;
            else if (!strcmp(a, "--quads")) {
                if (!sq_cli_number_option("quantize", a, v, &r.quads)) return SQ_EXIT_USAGE;
                have_quads = 1;
            } else if (!strcmp(a, "--edge-length")) {
                if (!sq_cli_number_option("quantize", a, v, &r.edge_length)) return SQ_EXIT_USAGE;
                have_len = 1;
            } else if (!strcmp(a, "--optimize")) {
                if (!strcmp(v, "on")) r.optimize = 1;
                else if (!strcmp(v, "off")) r.optimize = 0;
                else {
                    fprintf(stderr, "seamquad quantize: --optimize is on or off, not '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
            } else if (!strcmp(a, "--prepare")) {
                if (!strcmp(v, "on")) r.prepare = 1;
                else if (!strcmp(v, "off")) r.prepare = 0;
                else {
                    fprintf(stderr, "seamquad quantize: --prepare is on or off, not '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
            } else if (!strcmp(a, "--prepare-iterations")) {
                double n;
                if (!sq_cli_number_option("quantize", a, v, &n)) return SQ_EXIT_USAGE;
                if (!(n >= 1 && n <= 1e6 && n == floor(n))) {
                    fprintf(stderr, "seamquad quantize: --prepare-iterations %s: a whole number from 1 to 1e6\n", v);
                    return SQ_EXIT_USAGE;
                }
                r.prepare_iterations = (uint32_t)n;
            } else if (!strcmp(a, "--targets")) {
                if (!strcmp(v, "surface")) r.targets = SQ_TARGETS_SURFACE;
                else if (!strcmp(v, "map")) r.targets = SQ_TARGETS_MAP;
                else {
                    fprintf(stderr, "seamquad quantize: --targets is surface or map, not '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
            } else r.out_path = v;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad quantize: unknown option '%s' (see seamquad quantize --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!r.mesh_path) {
            r.mesh_path = a;
        } else {
            fprintf(stderr, "seamquad quantize: unexpected argument '%s' (one MESH)\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!r.mesh_path || !r.map_path || !r.out_path || have_quads == have_len) {
        fprintf(stderr, "seamquad quantize: give MESH, --map MAP.obj, one of --quads N or "
                        "--edge-length L, and -o IGM.obj (see seamquad quantize --help)\n");
        return SQ_EXIT_USAGE;
    }
    if (have_quads && !(r.quads >= 1 && r.quads <= 1e8)) {
        fprintf(stderr, "seamquad quantize: --quads %g: the quad count must be between 1 and 1e8\n",
                r.quads);
        return SQ_EXIT_USAGE;
    }
    if (have_len && !(r.edge_length > 0)) {
        fprintf(stderr, "seamquad quantize: --edge-length %g: the edge length must be positive\n",
                r.edge_length);
        return SQ_EXIT_USAGE;
    }
    if (sq_format_from_path(r.out_path) != SQ_FORMAT_OBJ) {
        fprintf(stderr, "seamquad quantize: the output '%s' must be an .obj file\n", r.out_path);
        return SQ_EXIT_USAGE;
    }
    const char *ins[3] = {r.mesh_path, r.map_path, r.cones_path};
    for (int k = 0; k < 3; k++)
        if (ins[k] && (!strcmp(r.out_path, ins[k]) || (r.svg_path && !strcmp(r.svg_path, ins[k])))) {
            fprintf(stderr, "seamquad quantize: an output would overwrite the input '%s'\n", ins[k]);
            return SQ_EXIT_USAGE;
        }

    sq_error err;
    sq_error_clear(&err);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    sq_map M, igm;
    memset(&M, 0, sizeof M);
    memset(&igm, 0, sizeof igm);
    int32_t *valence = NULL;
    const char *stage = "read";
    double t0 = sq_now();
    sq_status st = sq_read_mesh(r.mesh_path, &soup, &err);
    if (!st) st = sq_mesh_from_soup(&soup, 0, &mesh, &err);
    if (!st) {
        r.nv = mesh.nv, r.nf = mesh.nf, r.genus = sq_mesh_genus(&mesh);
        if (r.cones_path) {
            stage = "cones";
            valence = malloc((size_t)mesh.nv * sizeof *valence);
            if (!valence) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
            else st = sq_cli_read_cones(r.cones_path, &mesh, valence, &err);
        }
        r.t_read = sq_now() - t0;
    }
    if (!st) {
        double t1 = sq_now();
        stage = "map";
        st = sq_map_read(r.map_path, &mesh, valence, 1e-9, 0, &M, &r.map, &err);
        r.t_map = sq_now() - t1;
        if (st) sq_cli_name_file(&err, r.map_path);
    }
    if (!st) r.map_nv = M.mesh.nv, r.map_nf = M.mesh.nf;
    if (!st && r.prepare) {
        stage = "prepare";
        sq_quantize_prepare_options po = {r.prepare_iterations, NULL, NULL};
        if (!quiet && !json) po.progress = progress;
        st = sq_quantize_prepare(&M, &po, &r.pre, &err);
        r.prepared = !st;
    }
    if (!st) {
        stage = "quantize";
        sq_quantize_options opt = {have_quads ? r.quads : 0, have_len ? r.edge_length : 0, r.targets,
                                   r.optimize, 0};
        st = sq_quantize(&M, &opt, &igm, &r.st, &err);
    }
    if (!st) {
        r.done = 1;
        r.igm_nv = igm.mesh.nv, r.igm_nf = igm.mesh.nf;
        stage = "write";
        double t1 = sq_now();
        if (r.svg_path) {
            sq_tmesh T;
            st = sq_tmesh_build(&M, &T, NULL, &err);
            if (!st) st = sq_tmesh_write_svg(r.svg_path, &M, &T, &err);
            if (!st) sq_tmesh_free(&T);
        }
        if (!st) st = sq_map_write_obj(r.out_path, &igm, &err);
        if (st && r.svg_path) remove(r.svg_path);
        r.t_write = sq_now() - t1;
    }
    r.t_total = sq_now() - t0;
    if (json) print_json(&r, st, stage, err.msg);
    else if (!st && !quiet) print_text(&r);
    if (st) fprintf(stderr, "seamquad quantize: error (%s): %s\n", stage, err.msg);
    free(valence);
    sq_map_free(&igm);
    sq_map_free(&M);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    if (st == SQ_ERR_ARGUMENT) return SQ_EXIT_INVALID_INPUT;
    return sq_exit_code(st);
}
