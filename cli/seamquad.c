/* seamquad command-line tool: one subcommand per pipeline stage. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "sq_version.h"

typedef struct subcommand {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} subcommand;

static const subcommand commands[] = {
    {"check", sq_cmd_check, "validate a mesh and its cones: can seamquad process them?"},
    {"cones", sq_cmd_cones, "compute cones from a smooth cross field"},
    {"domain", sq_cmd_domain, "build the combinatorial seamless domain of a cone set"},
    {"param", sq_cmd_param, "seamless, locally injective parametrization of a mesh with its cones"},
    {"optimize", sq_cmd_optimize, "lower a seamless map's distortion, keeping seams, cones, injectivity"},
    {"quantize", sq_cmd_quantize, "an integer-grid map at the size asked, from a seamless map"},
    {"extract", sq_cmd_extract, "the closed pure-quad mesh of an integer-grid map"},
    {"smooth", sq_cmd_smooth, "smooth a quad mesh on the input surface with Ceres"},
    {"subdiv", sq_cmd_subdiv, "Catmull-Clark limit surface; STEP and IGES B-spline export"},
    {"remesh", sq_cmd_remesh, "the whole pipeline: triangle mesh in, quad mesh out"},
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void usage(FILE *f)
{
    fprintf(f,
            "seamquad %s: quad meshes with guaranteed validity from closed triangle meshes\n"
            "\n"
            "usage: seamquad COMMAND [ARGS]   (seamquad COMMAND --help for details)\n"
            "\n"
            "commands:\n",
            sq_version());
    for (size_t i = 0; i < NCOMMANDS; i++)
        fprintf(f, "  %-9s %s\n", commands[i].name, commands[i].summary);
    fprintf(f,
            "\n"
            "The pipeline: a closed manifold triangle mesh and its cones (prescribed\n"
            "irregular vertices) become a seamless parametrization whose domain is built\n"
            "combinatorially (Zhou, Tu, Zorin, Campen, EG 2020), then an integer grid\n"
            "map, a closed pure-quad mesh whose irregular vertices are exactly the cones,\n"
            "and a Catmull-Clark surface exported as B-spline patches for CAD.\n"
            "\n"
            "Start with:  seamquad check MESH --cones CONES\n"
            "\n"
            "exit codes: 0 success, 1 the input cannot be processed or an output cannot\n"
            "be written (the message says why and where), 2 wrong command line,\n"
            "3 internal failure (a bug, or out of memory).\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return SQ_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return SQ_EXIT_OK;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "-V")) {
        printf("seamquad %s\n", sq_version());
        return SQ_EXIT_OK;
    }
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (strcmp(cmd, commands[i].name)) continue;
        if (!commands[i].run) {
            fprintf(stderr, "seamquad: '%s' is planned but not built yet: %s\n", cmd,
                    commands[i].summary);
            return SQ_EXIT_USAGE;
        }
        return commands[i].run(argc - 1, argv + 1);
    }
    fprintf(stderr, "seamquad: unknown command '%s' (see seamquad --help)\n", cmd);
    return SQ_EXIT_USAGE;
}
