/* seamquad param: seamless, locally injective parametrization of a closed
 * triangle mesh with prescribed cones (seed 7-9; sq_param.h). */
#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "cli_common.h"
#include "sq_cones.h"
#include "sq_domain.h"
#include "sq_seamless_svg.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_omega.h"
#include "sq_param.h"
#include "sq_param_optimize.h"

/* default --attempts */
#define SQ_PARAM_CLI_ATTEMPTS 16

#define MAX_VALENCE_HIST 64

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad param MESH --cones FILE -o OUT.obj [options]\n"
            "\n"
            "Computes a seamless parametrization of a closed triangle mesh with exactly\n"
            "the prescribed cones, by the combinatorial construction of Zhou, Tu, Zorin,\n"
            "Campen (EG 2020, sections 7-9):\n"
            "\n"
            "  cut graph of the surface (4g-2 branches) -> combinatorial domain Q for its\n"
            "  side pattern (seamquad domain) -> cone tree in Q, flat domain Omega ->\n"
            "  the same tree on the surface -> boundary map by arc length, seam UVs on a\n"
            "  dyadic grid -> Omega cut into rectangles, each surface cell mapped onto its\n"
            "  rectangle by a Tutte embedding (bijective onto a convex target)\n"
            "\n"
            "OUT.obj is the input mesh, refined where the method needs Steiner vertices,\n"
            "with a UV per corner (f v/vt). The input's vertices come first, in order and\n"
            "with their coordinates; added vertices lie on the input surface. The map is\n"
            "an integer grid map at unit-square scale, and every result is re-checked\n"
            "before anything is written:\n"
            "  - every UV triangle is positively oriented (exact predicate on the stored\n"
            "    doubles): the map is locally injective;\n"
            "  - across every seam the two UV copies differ by a rotation by a multiple\n"
            "    of 90 degrees plus an integer translation, exactly in floating point,\n"
            "    with one transition per seam curve;\n"
            "  - the UV angle sum is k*pi/2 at a cone of valence k and 2*pi elsewhere;\n"
            "  - the output is a refinement of the input: every triangle lies in the\n"
            "    input triangle it came from (added vertices within 1e-12 of the\n"
            "    diagonal of it) and faces the same way.\n"
            "The independent referee ../shared/tools/check_param.py MESH CONES OUT.obj\n"
            "--integer checks the same.\n"
            "\n"
            "Where cones touch (a ring of adjacent cones around a handle, a vertex walled\n"
            "in by cones) the cut graph's loops cannot pass between them; then every\n"
            "input edge between two cones is split at its midpoint and the attempts run\n"
            "again (seed 9.1; --json \"cone_splits\").\n"
            "\n"
            "The mesh and cones are validated first, as by seamquad check: closed,\n"
            "manifold, connected, oriented, no degenerate face; the cone file matches\n"
            "the mesh; Gauss-Bonnet (sum of 4 - k = 4 * Euler characteristic); no\n"
            "valence-1 cone and not the torus with one 3 and one 5 (no quad mesh exists).\n"
            "\n"
            "options:\n"
            "  --cones FILE        cone file: Th_hat (one angle per vertex) or a cone\n"
            "                      list (VERTEX VALENCE per line); see check --help\n"
            "  -o OUT.obj          the parametrized mesh (v, vt, f v/vt)\n"
            "  --svg OUT.svg       picture of the UV layout: triangles, seams coloured\n"
            "                      per seam curve, cones by valence\n"
            "  --domain-svg OUT.svg  picture of the flat domain Omega: Q's sides, the cone\n"
            "                      tree, cone copies and branch points (seed Fig. 1)\n"
            "  --cut-svg OUT.svg   picture of the cut on the surface: the input mesh in\n"
            "                      three views with the seams (cut graph and cone tree),\n"
            "                      cones and branch points (about 200 bytes per input\n"
            "                      triangle)\n"
            "  --seed N            seed of the cut graph's sampling (default 1): another\n"
            "                      seed gives another valid parametrization\n"
            "  --attempts N        tries before giving up (default %d): when a map fails\n"
            "                      its exact check (a flipped or degenerate UV triangle,\n"
            "                      too many Steiner vertices), try the next cut-graph\n"
            "                      seed (attempt a of each kind of --tree uses seed\n"
            "                      N + a)\n"
            "  --threads N         attempts run at once (default: 2, or 1 on a single\n"
            "                      core): the result is the same as with 1, the lowest\n"
            "                      attempt that passes, found sooner when attempts fail;\n"
            "                      memory grows with the attempts running; with 2 the\n"
            "                      overlay and the simplification use two threads too,\n"
            "                      and the final check runs beside the writing of the\n"
            "                      outputs (renamed into place only once it passed)\n"
            "  --max-memory SIZE   memory an attempt may plan for (default 2G; K, M, G\n"
            "                      suffixes) in the steps whose size the input does not\n"
            "                      bound: Q triangulated by the tree's splits, Omega's\n"
            "                      disk map and the overlay's crossings (at most SIZE /\n"
            "                      %u); an attempt that would need more fails before it\n"
            "                      allocates, naming the limit, and the next one runs;\n"
            "                      with --threads 2 two attempts may run at once\n"
            "  --guide MODE        geometric guidance (seed 9.2): auto (default) is on for\n"
            "                      genus >= 2, off below. on: the cut surface is laid out\n"
            "                      in the unit disk; the cones are taken from its centre\n"
            "                      outwards and each glued where the growing domain's\n"
            "                      layout is closest to it (seed Algorithm 1), and Q's\n"
            "                      corners are matched to the cut graph's at similar\n"
            "                      angles (genus 1: Algorithm 1 for the meta-6-gon, the\n"
            "                      meta-2-gon near the circle; genus 0: only the cone\n"
            "                      matching). off: Q\n"
            "                      with the fewest quads, each cone of Q given the\n"
            "                      nearest free surface cone as the tree reaches it\n"
            "  --refine N          refinement rounds per attempt (default %d): when some\n"
            "                      UV triangles come out flipped or flat (Tutte's map of\n"
            "                      a cell squeezed below double precision), the cells of\n"
            "                      Omega holding them are halved by more chords and the\n"
            "                      map is redone on the same cut and boundary map; each\n"
            "                      round adds Steiner vertices. 0: none\n"
            "  --max-steiner N     Steiner vertices allowed per attempt (default 9 per\n"
            "                      input vertex + 100000); an attempt that needs more\n"
            "                      gives up (and the next seed is tried)\n"
            "  --max-crossings N   crossings of surface and domain edges the overlay may\n"
            "                      make (default: the Steiner budget; with --tree qtri\n"
            "                      400 per input face, at most 10,000,000); each crossing\n"
            "                      costs about two faces before the simplification; a\n"
            "                      walk over every 16th domain triangle comes first, and\n"
            "                      where it expects more than 5/4 of the budget the\n"
            "                      attempt stops there (--json \"crossings_expected\")\n"
            "  --diagnose OUT.svg  when the map fails its orientation check: the last\n"
            "                      attempt is rebuilt keeping its flips, and the cells of\n"
            "                      Omega holding bad triangles are drawn on the surface and\n"
            "                      in UV, worst first, with their rectangle and the surface\n"
            "                      length of each side (also on stderr and in --json); the\n"
            "                      map itself is still not written\n"
            "  --tree MODE         the cone tree (genus >= 1): auto (default) tries qtri\n"
            "                      first, then surface as its fallback (--json\n"
            "                      \"fallback\"): qtri's attempts (4 at most), then\n"
            "                      surface's; the lowest that passes is kept. qtri\n"
            "                      copies the surface tree (seed 9.4: shortest paths\n"
            "                      from the disk centre outwards) into Q triangulated,\n"
            "                      with edge splits where paths need room, always the\n"
            "                      same plane tree; Omega is then made of triangles and\n"
            "                      the interior map is the overlay (genus 1: with\n"
            "                      --guide on); where the cut walls a cone in (genus\n"
            "                      >= 2), the input's edges between two cut vertices or\n"
            "                      cones are split at their midpoints (--json\n"
            "                      \"wall_splits\"). surface replicates\n"
            "                      the surface tree in Q's quad grid (Q's own shortest\n"
            "                      tree where it cannot) and maps the interior as\n"
            "                      --interior says. qtri's maps are as little distorted\n"
            "                      or far less (mpz/helmet 29.5 against 419, mean\n"
            "                      conformal ratio; bench/bench_param_modes.sh); auto\n"
            "                      is surface alone where --guide or --interior is given\n"
            "  --interior MODE     the interior map: cells cuts Omega into rectangles by\n"
            "                      chords replayed on the surface and maps each cell by\n"
            "                      Tutte (with --refine rounds); overlay maps the cut\n"
            "                      surface and Omega onto one disk (same boundary points)\n"
            "                      and takes their common refinement: bijective for any\n"
            "                      Omega, no chords, no rounds, far less distorted, but\n"
            "                      every crossing of the two meshes in the disk is a\n"
            "                      Steiner vertex, and where the domain's shape is far\n"
            "                      from the surface's they exceed --max-steiner; auto\n"
            "                      (default): cells, then the overlay on the same cuts,\n"
            "                      whose map is kept when it passes (docs/param.md, 7');\n"
            "                      overlay tries Omega in unit squares, then in its\n"
            "                      chords' rectangles\n"
            "  --simplify on|off   on (default): the map that passed is simplified: added\n"
            "                      vertices off the seams are removed by edge collapses\n"
            "                      wherever every check still holds and no triangle gets\n"
            "                      more distorted (nothing moves; outputs shrink 2.4 to\n"
            "                      10.7 times; docs/param.md, step 9); off: the map as\n"
            "                      built\n"
            "  --fans on|off       on (default): in the overlay, where an input edge on\n"
            "                      the cut is split at many of Omega's boundary points,\n"
            "                      the fan of thin triangles joining the pieces to the\n"
            "                      opposite vertex is replaced by a graded triangulation\n"
            "                      of the same polygon (--json \"fan_vertices\"): 30%%\n"
            "                      fewer crossings on cid/elephant, 29%% on mpz/elk, the\n"
            "                      same guarantees; off: the fans as they are\n"
            "  --variants N        domains per tree qtri attempt (default 4; 1: the first\n"
            "                      only): Algorithm 1's exact ties (a cone as near to two\n"
            "                      edges of the growing domain) broken another way each\n"
            "                      time, while the overlay's sample expects more than\n"
            "                      --variant-gate crossings per input face (default 100);\n"
            "                      where none is under it, the one expecting the fewest\n"
            "                      (--json \"domain_variant\", \"crossings_expected\"):\n"
            "                      mpz/elk 3.1M -> 0.93M crossings, 7.5 -> 5.6 s\n"
            "  --variant-gate N    see --variants\n"
            "  --optimize on|off   off (default): OUT.obj is the construction's integer-grid\n"
            "                      map. on: its distortion lowered in rounds of 5 optimizer\n"
            "                      iterations (symmetric Dirichlet, projected Newton with\n"
            "                      progressive references; the seams' rotations and the\n"
            "                      cones kept, the translations free), each followed by the\n"
            "                      simplification, which removes far more added vertices\n"
            "                      from the less distorted map; OUT.obj is then a seamless\n"
            "                      map whose translations are real, not integers (quantize\n"
            "                      makes them integer at the size asked; check_param.py\n"
            "                      without --integer), checked exactly before it is written.\n"
            "                      mpz/eight: 5,484 faces at mean conformal ratio 19.4 ->\n"
            "                      1,700 at 1.23 in 0.2 s (--json \"optimize\")\n"
            "  --iterations N      --optimize on: at most N iterations in all (default %u)\n"
            "  --json              machine-readable statistics on stdout: sizes, domain,\n"
            "                      seams, distortion, time per step, peak memory\n"
            "  --quiet             no progress on stderr, no summary on stdout\n"
            "  -h, --help          this help\n"
            "\n"
            "Outputs are written together at the end: on any error none of them is\n"
            "written (an existing file of the same name stays as it was).\n"
            "\n"
            "exit codes: 0 success; 1 the input cannot be processed (the message names\n"
            "the file, line, vertex or face) or an output cannot be written; 2 wrong\n"
            "command line; 3 internal failure (a bug: the result failed its own check,\n"
            "or out of memory).\n"
            "\n"
            "example:\n"
            "  seamquad param ../shared/data/mpz/helmet.obj \\\n"
            "      --cones ../shared/data/mpz/helmet_Th_hat -o helmet.param.obj \\\n"
            "      --svg helmet.uv.svg --domain-svg helmet.omega.svg\n"
            "  python3 ../shared/tools/check_param.py ../shared/data/mpz/helmet.obj \\\n"
            "      ../shared/data/mpz/helmet_Th_hat helmet.param.obj --integer\n",
            SQ_PARAM_CLI_ATTEMPTS, SQ_BYTES_PER_CROSSING, SQ_PARAM_REFINE, SQ_PARAM_OPTIMIZE_ITERATIONS);
}

typedef struct progress_state {
    double t0, t_last;
    int quiet;
    char last[64];
} progress_state;

/* One line when a stage starts, then at most one a second within it. */
static void on_progress(void *ctx, const char *stage, double fraction)
{
    progress_state *p = ctx;
    if (p->quiet) return;
    if (!stage) stage = "";
    double t = sq_now();
    if (!strncmp(p->last, stage, sizeof p->last - 1) && t - p->t_last < 1.0) return;
    if (fraction < 0) fraction = 0;
    if (fraction > 1) fraction = 1;
    fprintf(stderr, "seamquad param: [%3.0f%%] %-24s %7.2f s\n", 100 * fraction, stage, t - p->t0);
    snprintf(p->last, sizeof p->last, "%s", stage);
    p->t_last = t;
}

/* --optimize on: the rounds' iterations as the fraction of the budget */
typedef struct optimize_progress_ctx {
    progress_state *ps;
    uint32_t budget;
} optimize_progress_ctx;

static void optimize_progress(void *user, uint32_t iteration, double energy, double step)
{
    (void)energy, (void)step;
    optimize_progress_ctx *c = user;
    on_progress(c->ps, "optimize", (double)iteration / c->budget);
}

/* Outputs: each is written to a hidden staging file next to its target,
 * and all are renamed over their targets only when every one is complete. */
enum { OUT_OBJ, OUT_SVG, OUT_DOMAIN_SVG, OUT_CUT_SVG, NOUT };

typedef struct output {
    const char *path;
    char *stage;  /* staging path */
    int written;  /* staging file complete */
    int direct;   /* the target is a device or FIFO (/dev/null): written */
                  /* in place, never renamed over or removed            */
} output;

static char *staging_path(const char *path, int k)
{
    const char *slash = strrchr(path, '/');
    size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0;
    const char *base = slash ? slash + 1 : path;
    size_t n = strlen(path) + 64;
    char *s = malloc(n);
    if (s)
        snprintf(s, n, "%.*s.%s.seamquad-%ld-%d.partial", (int)dirlen, path, base, (long)getpid(),
                 k);
    return s;
}


static sq_status write_domain_svg(const sq_param *P, const char *path, sq_error *err)
{
    if (P->domain && P->tree && P->omega)
        return sq_omega_write_svg(P->domain, P->tree, P->omega, path, err);
    if (P->domain) return sq_domain_write_svg(P->domain, NULL, path, err);
    return sq_error_set(err, SQ_ERR_INTERNAL, "%s: the parametrization kept no domain to draw",
                        path);
}

static long peak_rss_kb(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return -1;
    return ru.ru_maxrss; /* kilobytes on Linux */
}

/* The independent check of the map, in a thread of its own beside the
 * writing of the staged outputs (both only read P). */
typedef struct verify_job {
    const sq_param *P;
    sq_status st;
    sq_error err;
    double t;
} verify_job;

static void *verify_thread(void *arg)
{
    verify_job *V = arg;
    double t = sq_now();
    sq_error_clear(&V->err);
    V->st = sq_param_verify(V->P, SQ_PARAM_VERIFY_INTEGER, &V->err);
    V->t = sq_now() - t;
    return NULL;
}

/* The check's outcome, wherever it ran: its time into *t, its failure
 * into err */
static sq_status verify_outcome(const verify_job *V, double *t, sq_error *err)
{
    *t = V->t;
    if (V->st) *err = V->err;
    return V->st;
}

static void print_json(const char *mesh_path, const char *cones_path, const sq_param_stats *s,
                       const uint32_t *hist, double t_read, double t_validate, double t_verify,
                       double t_output, double t_total, const output *out,
                       const sq_param_optimize_report *o, double sd_mean, double sd_max, double t_optimize)
{
    printf("{\n  \"ok\": true,\n  \"mesh\": ");
    sq_json_string(stdout, mesh_path);
    printf(",\n  \"cones_file\": ");
    sq_json_string(stdout, cones_path);
    printf(",\n  \"genus\": %u,\n  \"cones\": %u,\n  \"cone_histogram\": {", s->genus, s->ncones);
    int first = 1;
    for (uint32_t k = 0; k < MAX_VALENCE_HIST; k++) {
        if (k == 4 || !hist[k]) continue;
        printf("%s\"%s%u\": %u", first ? "" : ", ", k == MAX_VALENCE_HIST - 1 ? ">=" : "", k,
               hist[k]);
        first = 0;
    }
    printf("},\n");
    printf("  \"verts_in\": %u,\n  \"faces_in\": %u,\n  \"verts_out\": %u,\n  \"faces_out\": %u,\n"
           "  \"steiner\": %u,\n  \"uv_points\": %u,\n",
           s->verts_in, s->faces_in, s->verts_out, s->faces_out, s->steiner, s->nuv);
    printf("  \"cut_edges\": %u,\n  \"quads_before_padding\": %llu,\n  \"quads_added_by_padding\": "
           "%llu,\n  \"quads\": %llu,\n",
           s->cut_edges, (unsigned long long)s->quads_unpadded, (unsigned long long)s->quads_added,
           (unsigned long long)(s->quads_unpadded + s->quads_added));
    printf("  \"rotation_mismatch_before\": %u,\n  \"rotation_mismatch_after\": %u,\n"
           "  \"rotation_reroutes\": %u,\n",
           s->rot_mismatch_before, s->rot_mismatch_after, s->rot_reroutes);
    printf("  \"attempts\": %u,\n  \"seed_used\": %llu,\n  \"guided\": %s,\n  \"surface_tree\": %s,\n",
           s->attempts, (unsigned long long)s->seed_used, s->guided ? "true" : "false",
           s->surface_tree ? "true" : "false");
    printf("  \"interior\": \"%s\",\n", s->overlay ? "overlay" : "cells");
    printf("  \"tree_qtri\": %s,\n  \"qtri_verts\": %u,\n  \"qtri_steiner\": %u,\n  \"wall_splits\": %u,\n",
           s->tree_qtri ? "true" : "false", s->qtri_verts, s->qtri_steiner, s->wall_splits);
    printf("  \"cone_splits\": %u,\n", s->cone_splits);
    printf("  \"fallback\": %s,\n  \"crossings\": %llu,\n  \"fan_vertices\": %u,\n",
           s->fallback ? "true" : "false", (unsigned long long)s->crossings,
           s->fan_vertices);
    printf("  \"crossings_expected\": %llu,\n  \"domain_variant\": %u,\n", (unsigned long long)s->crossings_expected,
           s->domain_variant);
    printf("  \"simplified\": %u,\n  \"faces_unsimplified\": %u,\n", s->simplified, s->faces_unsimplified);
    printf("  \"refine_rounds\": %u,\n  \"cells_halved\": %u,\n", s->rounds, s->cells_refined);
    printf("  \"tree_edges\": %u,\n  \"tree_segments\": %u,\n  \"chords\": %u,\n  \"cells\": %u,\n"
           "  \"seam_edges\": %u,\n",
           s->tree_edges, s->tree_segments, s->chords, s->cells, s->seam_edges);
    printf("  \"distortion\": {\"sym_dirichlet_mean\": %.9g, \"sym_dirichlet_max\": %.9g, "
           "\"conformal_mean\": %.9g, \"conformal_max\": %.9g},\n",
           s->sym_dirichlet_mean, s->sym_dirichlet_max, s->conformal_mean, s->conformal_max);
    printf("  \"verified\": {\"orientation_exact\": true, \"seams_exact\": true, "
           "\"integer_translations\": true, \"cones_on_grid\": true, \"angle_sums\": true, "
           "\"refinement\": true, \"refinement_max_dist\": %.3g},\n",
           s->refinement_max_dist); /* sq_param_build checked it */
    if (o) { /* the map written: the figures above are the construction's */
        printf("  \"optimize\": {\"iterations\": %u, \"reference_iterations\": %u, \"rounds\": %u, "
               "\"fixed_rounds\": %u, \"removed\": %u, \"faces_before\": %u, \"faces_after\": %u, "
               "\"conformal_before\": %.9g, \"conformal_after\": %.9g, \"sym_dirichlet_mean\": %.9g, "
               "\"sym_dirichlet_max\": %.9g, \"integer_translations\": false, \"seconds\": %.6f, "
               "\"stopped\": ",
               o->iterations, o->reference_iterations, o->rounds, o->fixed_rounds, o->removed,
               o->faces_before, o->faces_after, o->conformal_before, o->conformal_after, sd_mean, sd_max,
               t_optimize);
        sq_json_string(stdout, o->why);
        printf("},\n");
    }
    printf("  \"time_s\": {\"read\": %.6f, \"validate\": %.6f, \"cut\": %.6f, \"domain\": %.6f, "
           "\"omega\": %.6f, \"tree\": %.6f, \"boundary\": %.6f, \"cells\": %.6f, \"tutte\": %.6f, "
           "\"check\": %.6f, \"overlay\": %.6f, \"simplify\": %.6f, \"param_total\": %.6f, "
           "\"verify\": %.6f, \"output\": %.6f, \"total\": %.6f},\n",
           t_read, t_validate, s->t_cut, s->t_domain, s->t_omega, s->t_tree, s->t_boundary,
           s->t_cells, s->t_tutte, s->t_check, s->t_overlay, s->t_simplify, s->t_total, t_verify, t_output,
           t_total);
    printf("  \"peak_rss_mb\": %.1f,\n  \"outputs\": [", peak_rss_kb() / 1024.0);
    first = 1;
    for (int i = 0; i < NOUT; i++) {
        if (!out[i].path) continue;
        printf("%s", first ? "" : ", ");
        sq_json_string(stdout, out[i].path);
        first = 0;
    }
    printf("]\n}\n");
}

static void print_text(const char *mesh_path, const sq_param_stats *s, const uint32_t *hist,
                       double t_read, double t_validate, double t_verify, double t_output,
                       double t_total, const output *out, const sq_param_optimize_report *o,
                       double sd_mean, double t_optimize)
{
    printf("mesh           %s: %u vertices, %u faces, genus %u\n", mesh_path, s->verts_in,
           s->faces_in, s->genus);
    if (!s->ncones) {
        printf("cones          none (every vertex regular)\n");
    } else {
        printf("cones          %u  (", s->ncones);
        int first = 1;
        for (uint32_t k = 0; k < MAX_VALENCE_HIST; k++) {
            if (k == 4 || !hist[k]) continue;
            printf("%s%s%u:%u", first ? "" : " ", k == MAX_VALENCE_HIST - 1 ? ">=" : "", k,
                   hist[k]);
            first = 0;
        }
        printf("; valence:count)\n");
    }
    printf("attempt        %u (cut-graph seed %llu, %s)\n", s->attempts, (unsigned long long)s->seed_used,
           !s->guided      ? "unguided"
           : s->tree_qtri  ? "guided (seed 9.2), the surface cone tree copied into Q triangulated (tree qtri)"
           : s->surface_tree ? "guided (seed 9.2), cone tree from the surface (seed 9.4)"
                             : "guided (seed 9.2), cone tree from the domain");
    printf("cut graph      %u edges\n", s->cut_edges);
    if (s->genus >= 1 && s->rot_mismatch_after == UINT32_MAX)
        printf("rotations      not compared with a smooth cross field's (the mismatch could not "
               "be computed)\n");
    else if (s->genus >= 1)
        printf("rotations      %s (mismatch with the smooth field's %u before steering, %u after; %u "
               "branches rerouted)\n",
               s->rot_mismatch_after ? "differ from a smooth cross field's around some handle"
                                     : "those of a smooth cross field with these cones",
               s->rot_mismatch_before, s->rot_mismatch_after, s->rot_reroutes);
    printf("domain         %llu quads before padding + %llu padding = %llu\n",
           (unsigned long long)s->quads_unpadded, (unsigned long long)s->quads_added,
           (unsigned long long)(s->quads_unpadded + s->quads_added));
    printf("cone tree      %u edges in %u segments\n", s->tree_edges, s->tree_segments);
    if (s->cone_splits)
        printf("cone splits    %u input edges between two cones split at their midpoints: the cut graph's\n"
               "               loops and paths pass between adjacent cones (seed 9.1)\n",
               s->cone_splits);
    if (s->wall_splits)
        printf("walls          %u input edges split at their midpoints: the cut walled a cone in\n", s->wall_splits);
    if (s->overlay)
        printf("interior map   overlay: the cut surface and Omega on one disk, their common "
               "refinement (step 7'); %llu crossings, %u vertices in graded fans\n",
               (unsigned long long)s->crossings, s->fan_vertices);
    else
        printf("interior map   cells: Omega cut into %u rectangles by %u chords, Tutte per cell\n",
               s->cells, s->chords);
    if (s->domain_variant)
        printf("variant        domain %u: Algorithm 1's ties broken another way (the first domain's overlay "
               "expected more crossings; --variants)\n",
               s->domain_variant + 1);
    if (s->rounds)
        printf("refinement     %u rounds: %u cells with bad triangles halved (step 7c)\n", s->rounds,
               s->cells_refined);
    if (s->fallback)
        printf("fallback       tree qtri's attempts failed; the surface tree replicated in Q's quads\n");
    if (s->faces_unsimplified)
        printf("simplified     %u added vertices removed: %u faces -> %u\n", s->simplified,
               s->faces_unsimplified, s->faces_out);
    printf("output         %u vertices (%u Steiner), %u faces, %u UV points, %u seam edges\n",
           s->verts_out, s->steiner, s->faces_out, s->nuv, s->seam_edges);
    printf("distortion     symmetric Dirichlet mean %.4g max %.4g; conformal ratio mean %.4g "
           "max %.4g\n",
           s->sym_dirichlet_mean, s->sym_dirichlet_max, s->conformal_mean, s->conformal_max);
    printf("verified       every UV triangle positive (exact); every seam a rotation by k*90 "
           "degrees plus an integer translation, exactly, one per seam curve; cones on the "
           "integer grid; angle sums = cone angles\n");
    if (o)
        printf("optimized      %u iterations in %u rounds, %u added vertices removed: %u faces -> %u, "
               "conformal ratio mean %.4g -> %.4g, symmetric Dirichlet mean %.4g, %.2f s (%s); the map "
               "written has the same rotations and cones, every triangle positive (exact), real "
               "translations\n",
               o->iterations, o->rounds, o->removed, o->faces_before, o->faces_after, o->conformal_before,
               o->conformal_after, sd_mean, t_optimize, o->why);
    /* the steps are those of the attempt kept; the failed attempts, and a
     * first pass whose cut walled a cone in, only in param's total */
    double steps = s->t_cut + s->t_domain + s->t_omega + s->t_tree + s->t_boundary + s->t_cells + s->t_tutte +
                   s->t_check + s->t_overlay + s->t_simplify;
    double other = s->t_total > steps ? s->t_total - steps : 0.0;
    printf("time           read %.2f s, validate %.2f s, cut %.2f s, domain %.2f s, omega %.2f s, "
           "tree %.2f s, boundary %.2f s, cells %.2f s, tutte %.2f s, check %.2f s, overlay "
           "%.2f s, simplify %.2f s, other attempts and passes %.2f s, verify %.2f s, output %.2f s; "
           "total %.2f s\n",
           t_read, t_validate, s->t_cut, s->t_domain, s->t_omega, s->t_tree, s->t_boundary,
           s->t_cells, s->t_tutte, s->t_check, s->t_overlay, s->t_simplify, other, t_verify, t_output, t_total);
    printf("memory         peak %.1f MB\n", peak_rss_kb() / 1024.0);
    for (int i = 0; i < NOUT; i++)
        if (out[i].path) printf("wrote          %s\n", out[i].path);
}

/* A decimal integer in [lo, hi], nothing else (no sign, no trailing text). */
static int parse_u64(const char *arg, unsigned long long lo, unsigned long long hi,
                     unsigned long long *out)
{
    char *e;
    errno = 0;
    unsigned long long v = strtoull(arg, &e, 10);
    if (e == arg || *e || errno || arg[0] == '-' || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

/* The value of option `name`, or a message naming it (0 returned). */
static int u64_option(const char *name, const char *arg, unsigned long long lo, unsigned long long hi,
                      unsigned long long *out)
{
    if (parse_u64(arg, lo, hi, out)) return 1;
    if (lo == 0 && hi == UINT64_MAX)
        fprintf(stderr, "seamquad param: %s needs a non-negative integer, got '%s'\n", name, arg);
    else
        fprintf(stderr, "seamquad param: %s needs an integer from %llu to %llu, got '%s'\n", name, lo, hi, arg);
    return 0;
}

/* A size in bytes with an optional suffix K, M or G (powers of 1024),
 * from 64M to 1024G, or a message naming the option (0 returned). */
static int size_option(const char *name, const char *arg, unsigned long long *out)
{
    char num[32];
    size_t n = strlen(arg);
    unsigned long long mul = 1, v = 0;
    if (n > 0 && n < sizeof num) {
        memcpy(num, arg, n + 1);
        char c = num[n - 1];
        if (c == 'K' || c == 'k') mul = 1ull << 10;
        else if (c == 'M' || c == 'm') mul = 1ull << 20;
        else if (c == 'G' || c == 'g') mul = 1ull << 30;
        if (mul > 1) num[n - 1] = 0;
    }
    if (n > 0 && n < sizeof num && parse_u64(num, 1, (1024ull << 30) / mul, &v) && v * mul >= (64ull << 20) &&
        v * mul <= (1024ull << 30)) {
        *out = v * mul;
        return 1;
    }
    fprintf(stderr, "seamquad param: %s needs a size from 64M to 1024G (bytes, or a number with K, M or G), got '%s'\n",
            name, arg);
    return 0;
}

/* One of an option's keywords (names[i] -> values[i], n of them) into
 * *out, or a message naming them all (0 returned). */
typedef struct keyword {
    const char *name;
    int value;
} keyword;

static int keyword_option(const char *name, const char *arg, const keyword *k, size_t n, int *out)
{
    for (size_t i = 0; i < n; i++)
        if (!strcmp(arg, k[i].name)) {
            *out = k[i].value;
            return 1;
        }
    fprintf(stderr, "seamquad param: %s takes ", name);
    for (size_t i = 0; i < n; i++) fprintf(stderr, "%s%s", k[i].name, i + 2 < n ? ", " : i + 2 == n ? " or " : "");
    fprintf(stderr, ", got '%s'\n", arg);
    return 0;
}

#define KEYWORDS(...) ((const keyword[]){__VA_ARGS__}), sizeof((const keyword[]){__VA_ARGS__}) / sizeof(keyword)

#define DIAG_CELLS 6

/* --diagnose: the last attempt of the failed run (options `run`) again
 * (its seed and tree, one attempt, no progress), keeping its flips; the
 * cells with bad triangles reported on stderr and drawn. Returns 1 when
 * the picture was written. */
static int diagnose_cells(const sq_mesh *mesh, const int32_t *val, const sq_param_options *run,
                          const sq_param_stats *failed, const char *path, sq_param_cell *cells,
                          uint32_t *ncells)
{
    sq_param_options opt = *run;
    opt.seed = failed->seed_used ? failed->seed_used : run->seed;
    opt.attempts = 1;
    opt.tree = failed->tree_qtri ? SQ_TREE_QTRI : SQ_TREE_SURFACE;
    opt.allow_flips = 1;
    opt.progress = NULL, opt.progress_ctx = NULL;
    sq_param P;
    sq_param_init(&P);
    sq_param_stats st;
    sq_error e;
    sq_error_clear(&e);
    int ok = 0;
    if (sq_param_build(mesh, val, &opt, &P, &st, &e) == SQ_OK &&
        sq_param_bad_cells(&P, cells, DIAG_CELLS, ncells, &e) == SQ_OK &&
        sq_param_write_cells_svg(path, &P, cells, *ncells < DIAG_CELLS ? *ncells : DIAG_CELLS, &e) == SQ_OK) {
        ok = 1;
        fprintf(stderr, "seamquad param: diagnosis (seed %llu): %u cells of Omega hold bad triangles; %s\n",
                (unsigned long long)opt.seed, *ncells, path);
        for (uint32_t i = 0; i < *ncells && i < DIAG_CELLS; i++)
            fprintf(stderr, "  cell %u: %u of %u triangles bad; rectangle %g x %g; surface length of its sides "
                            "(u=min, v=min, u=max, v=max) %.3g %.3g %.3g %.3g; %u runs%s\n",
                    i, cells[i].bad, cells[i].faces, cells[i].umax - cells[i].umin, cells[i].vmax - cells[i].vmin,
                    cells[i].side_len[0], cells[i].side_len[1], cells[i].side_len[2], cells[i].side_len[3],
                    cells[i].runs, cells[i].runs > 4 ? " (a side folds)" : "");
    } else {
        fprintf(stderr, "seamquad param: diagnosis failed: %s\n", e.msg);
    }
    sq_param_free(&P);
    return ok;
}

int sq_cmd_param(int argc, char **argv)
{
    const char *mesh_path = NULL, *cones_path = NULL;
    output out[NOUT];
    memset(out, 0, sizeof out);
    int json = 0, quiet = 0;
    const char *diagnose = NULL;
    unsigned long long seed = 1, attempts = SQ_PARAM_CLI_ATTEMPTS, refine = SQ_PARAM_REFINE, max_steiner = 0;
    unsigned long long max_memory = SQ_PARAM_MAX_MEMORY;
    unsigned long long max_crossings = 0, variants = SQ_VARIANTS, variant_gate = SQ_VARIANT_PER_FACE;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    unsigned long long threads = ncpu > 1 ? 2 : 1;
    int guidance = SQ_GUIDE_AUTO, tree = SQ_TREE_AUTO, interior = SQ_INTERIOR_AUTO;
    int simplify = SQ_SIMPLIFY_ON, fans = SQ_FANS_ON, optimize = 0;
    unsigned long long iterations = SQ_PARAM_OPTIMIZE_ITERATIONS;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--quiet")) {
            quiet = 1;
        } else if (!strcmp(a, "--cones") && has) {
            cones_path = argv[++i];
        } else if (!strcmp(a, "-o") && has) {
            out[OUT_OBJ].path = argv[++i];
        } else if (!strcmp(a, "--svg") && has) {
            out[OUT_SVG].path = argv[++i];
        } else if (!strcmp(a, "--domain-svg") && has) {
            out[OUT_DOMAIN_SVG].path = argv[++i];
        } else if (!strcmp(a, "--cut-svg") && has) {
            out[OUT_CUT_SVG].path = argv[++i];
        } else if (!strcmp(a, "--diagnose") && has) {
            diagnose = argv[++i];
        } else if (!strcmp(a, "--seed") && has) {
            if (!u64_option(a, argv[++i], 0, UINT64_MAX, &seed)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--attempts") && has) {
            if (!u64_option(a, argv[++i], 1, 1000, &attempts)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--threads") && has) {
            if (!u64_option(a, argv[++i], 1, 64, &threads)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--refine") && has) {
            if (!u64_option(a, argv[++i], 0, 64, &refine)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--max-memory") && has) {
            if (!size_option(a, argv[++i], &max_memory)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--max-steiner") && has) {
            if (!u64_option(a, argv[++i], 1, 1000000000ull, &max_steiner)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--max-crossings") && has) {
            if (!u64_option(a, argv[++i], 1, 1000000000ull, &max_crossings)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--variants") && has) {
            if (!u64_option(a, argv[++i], 1, 64, &variants)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--variant-gate") && has) {
            if (!u64_option(a, argv[++i], 1, 1000000, &variant_gate)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--tree") && has) {
            if (!keyword_option(a, argv[++i],
                                KEYWORDS({"auto", SQ_TREE_AUTO}, {"surface", SQ_TREE_SURFACE},
                                         {"qtri", SQ_TREE_QTRI}),
                                &tree))
                return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--interior") && has) {
            if (!keyword_option(a, argv[++i],
                                KEYWORDS({"auto", SQ_INTERIOR_AUTO}, {"cells", SQ_INTERIOR_CELLS},
                                         {"overlay", SQ_INTERIOR_OVERLAY}),
                                &interior))
                return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--simplify") && has) {
            if (!keyword_option(a, argv[++i], KEYWORDS({"on", SQ_SIMPLIFY_ON}, {"off", SQ_SIMPLIFY_OFF}), &simplify))
                return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--optimize") && has) {
            if (!keyword_option(a, argv[++i], KEYWORDS({"on", 1}, {"off", 0}), &optimize)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--iterations") && has) {
            if (!u64_option(a, argv[++i], 1, 1000000, &iterations)) return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--fans") && has) {
            if (!keyword_option(a, argv[++i], KEYWORDS({"on", SQ_FANS_ON}, {"off", SQ_FANS_OFF}), &fans))
                return SQ_EXIT_USAGE;
        } else if (!strcmp(a, "--guide") && has) {
            if (!keyword_option(a, argv[++i],
                                KEYWORDS({"auto", SQ_GUIDE_AUTO}, {"on", SQ_GUIDE_ON}, {"off", SQ_GUIDE_OFF}),
                                &guidance))
                return SQ_EXIT_USAGE;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad param: unknown option or missing value '%s' (see seamquad "
                            "param --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            fprintf(stderr, "seamquad param: unexpected argument '%s' (one mesh only)\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!mesh_path || !cones_path || !out[OUT_OBJ].path) {
        fprintf(stderr, "seamquad param: give MESH, --cones FILE and -o OUT.obj (see seamquad "
                        "param --help)\n");
        return SQ_EXIT_USAGE;
    }
    for (int i = 0; i < NOUT; i++)
        for (int j = 0; j < i; j++)
            if (out[i].path && out[j].path && !strcmp(out[i].path, out[j].path)) {
                fprintf(stderr, "seamquad param: '%s' is given as two outputs\n", out[i].path);
                return SQ_EXIT_USAGE;
            }

    progress_state ps; /* its clock starts with the parametrization */
    memset(&ps, 0, sizeof ps);
    ps.quiet = quiet;
    sq_param_options opt;
    sq_param_options_default(&opt);
    opt.seed = seed;
    opt.attempts = (uint32_t)attempts;
    opt.threads = (uint32_t)threads;
    opt.refine = (uint32_t)refine;
    opt.max_steiner = max_steiner;
    opt.max_memory = max_memory;
    opt.max_crossings = max_crossings;
    opt.guidance = guidance;
    opt.tree = tree;
    opt.interior = interior;
    opt.simplify = simplify;
    opt.fans = fans;
    opt.variants = (uint32_t)variants;
    opt.variant_gate = (uint32_t)variant_gate;
    opt.progress = on_progress;
    opt.progress_ctx = &ps;
    sq_error err;
    sq_error_clear(&err);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    int32_t *val = NULL;
    sq_param P;
    sq_param_init(&P);
    sq_param_stats stats;
    memset(&stats, 0, sizeof stats);
    uint32_t hist[MAX_VALENCE_HIST] = {0};
    int rc = SQ_EXIT_OK;
    const char *stage = "read";
    double t0 = sq_now(), t_read = 0, t_validate = 0, t_verify = 0, t_output = 0;
    int beside = 0; /* the check runs in thread vth (below) */
    pthread_t vth;
    verify_job V;
    memset(&V, 0, sizeof V);
    sq_map M; /* --optimize on: the optimized map written */
    memset(&M, 0, sizeof M);
    sq_param_optimize_report orep;
    memset(&orep, 0, sizeof orep);
    double t_optimize = 0, sd_mean = 0, sd_max = 0;

    /* input, validated before any work */
    if (sq_read_mesh(mesh_path, &soup, &err)) goto fail;
    t_read = sq_now() - t0;
    stage = "validate";
    double t1 = sq_now();
    if (sq_mesh_from_soup(&soup, 0, &mesh, &err)) goto fail;
    t_validate = sq_now() - t1;
    stage = "cones";
    val = malloc((size_t)mesh.nv * sizeof *val);
    if (!val) {
        sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if (sq_cli_read_cones(cones_path, &mesh, val, &err)) goto fail;
    sq_cones_histogram(mesh.nv, val, hist, MAX_VALENCE_HIST);
    stage = "output";
    for (int i = 0; i < NOUT; i++)
        if (out[i].path && sq_cli_probe_output(out[i].path, &err)) goto fail;

    /* the parametrization */
    stage = "param";
    ps.t0 = ps.t_last = sq_now();
    if (sq_param_build(&mesh, val, &opt, &P, &stats, &err)) goto fail;
    /* the library's own check ran inside; this one is independent. With
     * two threads it runs beside the writing of the staged outputs (which
     * are renamed only once it passed); with an output written directly
     * (a special file), or with one thread, before it. */
    beside = opt.threads > 1 && !optimize; /* the check reads P, which the rounds change */
    for (int i = 0; i < NOUT; i++)
        if (out[i].path && sq_is_special_file(out[i].path)) beside = 0;
    V.P = &P;
    if (beside && pthread_create(&vth, NULL, verify_thread, &V) != 0) beside = 0;
    if (!beside) {
        stage = "verify";
        verify_thread(&V);
        if (verify_outcome(&V, &t_verify, &err)) goto fail;
        if (!quiet) on_progress(&ps, "verified", 1.0);
    }

    /* --optimize on: the verified map optimized and simplified in rounds */
    if (optimize) {
        stage = "optimize";
        double t2 = sq_now();
        optimize_progress_ctx pc = {&ps, (uint32_t)iterations};
        sq_optimize_options oo;
        memset(&oo, 0, sizeof oo);
        oo.basis = SQ_OPTIMIZE_FREE_TRANSLATIONS;
        oo.progress = optimize_progress;
        oo.user = &pc;
        if (sq_param_optimize(&mesh, val, &P, &oo, (uint32_t)iterations, &M, &orep, &err)) goto fail;
        sq_optimize_energy(&M, &sd_mean, &sd_max);
        t_optimize = sq_now() - t2;
        if (!quiet) on_progress(&ps, "optimized", 1.0);
    }

    /* outputs: staged, then renamed together */
    stage = "output";
    double t3 = sq_now();
    for (int i = 0; i < NOUT; i++) {
        if (!out[i].path) continue;
        out[i].direct = sq_is_special_file(out[i].path);
        out[i].stage = out[i].direct ? strdup(out[i].path) : staging_path(out[i].path, i);
        if (!out[i].stage) {
            sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
            goto fail;
        }
        sq_status st = i == OUT_OBJ       ? (optimize ? sq_map_write_obj(out[i].stage, &M, &err)
                                                      : sq_param_write_obj(out[i].stage, &P, &err))
                       : i == OUT_SVG     ? sq_param_write_svg(out[i].stage, &P, &err)
                       : i == OUT_CUT_SVG ? sq_param_write_cut_svg(out[i].stage, &mesh, &P, &err)
                                          : write_domain_svg(&P, out[i].stage, &err);
        if (st) {
            /* name the user's file, not the staging file */
            char msg[2 * SQ_ERROR_MSG_MAX];
            const char *at = strstr(err.msg, out[i].stage);
            if (at)
                snprintf(msg, sizeof msg, "%.*s%s%s", (int)(at - err.msg), err.msg, out[i].path,
                         at + strlen(out[i].stage));
            else
                snprintf(msg, sizeof msg, "%s: %s", out[i].path, err.msg);
            sq_error_set(&err, st, "%.*s", SQ_ERROR_MSG_MAX - 1, msg);
            goto fail;
        }
        out[i].written = 1;
    }
    if (beside) {
        pthread_join(vth, NULL);
        beside = 0;
        stage = "verify";
        if (verify_outcome(&V, &t_verify, &err)) goto fail;
        stage = "output";
        if (!quiet) on_progress(&ps, "verified", 1.0);
    }
    for (int i = 0; i < NOUT; i++) {
        if (!out[i].path || out[i].direct) continue;
        if (rename(out[i].stage, out[i].path) != 0) {
            int e = errno;
            sq_error_set(&err, SQ_ERR_IO, "%s: cannot write (rename): %s", out[i].path,
                         strerror(e));
            goto fail;
        }
        out[i].written = 0;
    }
    t_output = sq_now() - t3;

    if (json)
        print_json(mesh_path, cones_path, &stats, hist, t_read, t_validate, t_verify, t_output,
                   sq_now() - t0, out, optimize ? &orep : NULL, sd_mean, sd_max, t_optimize);
    else if (!quiet)
        print_text(mesh_path, &stats, hist, t_read, t_validate, t_verify, t_output, sq_now() - t0,
                   out, optimize ? &orep : NULL, sd_mean, t_optimize);
    goto done;
fail:
    if (beside) pthread_join(vth, NULL); /* an output failed: the check still reads P */
    fprintf(stderr, "seamquad param: error (%s): %s\n", stage, err.msg);
    sq_param_cell cells[DIAG_CELLS];
    uint32_t ncells = 0;
    int diagnosed = 0;
    if (diagnose && !strcmp(stage, "param") && err.code == SQ_ERR_SOLVER && strstr(err.msg, "not injective"))
        diagnosed = diagnose_cells(&mesh, val, &opt, &stats, diagnose, cells, &ncells);
    if (json) {
        printf("{\n  \"ok\": false,\n  ");
        sq_json_error(err.code, stage, err.msg);
        if (!strcmp(stage, "param"))
            /* how far the last attempt got (zeros where it did not) */
            printf(",\n  \"last_attempt\": {\"attempts\": %u, \"seed\": %llu, \"guided\": %s, "
                   "\"surface_tree\": %s, \"genus\": %u, \"cones\": %u, \"quads_before_padding\": %llu, "
                   "\"quads_added_by_padding\": %llu, \"chords\": %u, \"cells\": %u}",
                   stats.attempts, (unsigned long long)stats.seed_used, stats.guided ? "true" : "false",
                   stats.surface_tree ? "true" : "false", stats.genus, stats.ncones, (unsigned long long)stats.quads_unpadded,
                   (unsigned long long)stats.quads_added, stats.chords, stats.cells);
        if (diagnosed) {
            printf(",\n  \"diagnosis\": {\"svg\": ");
            sq_json_string(stdout, diagnose);
            printf(", \"bad_cells\": %u, \"cells\": [", ncells);
            for (uint32_t i = 0; i < ncells && i < DIAG_CELLS; i++)
                printf("%s{\"bad\": %u, \"faces\": %u, \"rect\": [%.17g, %.17g, %.17g, %.17g], "
                       "\"side_length\": [%.6g, %.6g, %.6g, %.6g], \"runs\": %u}",
                       i ? ", " : "", cells[i].bad, cells[i].faces, cells[i].umin, cells[i].vmin, cells[i].umax,
                       cells[i].vmax, cells[i].side_len[0], cells[i].side_len[1], cells[i].side_len[2],
                       cells[i].side_len[3], cells[i].runs);
            printf("]}");
        }
        printf("\n}\n");
    }
    /* the command line was checked above: an argument error from the
     * library here is about the input's content */
    rc = err.code == SQ_ERR_ARGUMENT ? SQ_EXIT_INVALID_INPUT : sq_exit_code(err.code);
done:
    for (int i = 0; i < NOUT; i++) {
        if (out[i].stage && out[i].written && !out[i].direct) unlink(out[i].stage);
        free(out[i].stage);
    }
    sq_map_free(&M);
    sq_param_free(&P);
    free(val);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    return rc;
}
