/* seamquad: STEP AP214 (ISO 10303-21) writer for bicubic B-spline patches.
 *
 * Each patch becomes an ADVANCED_FACE on its B_SPLINE_SURFACE_WITH_KNOTS
 * (degree 3x3, 4x4 control points, uniform knots -3..4, so the surface's
 * domain is [0,1]^2, the patch's own parameter square), bounded by one
 * EDGE_LOOP of its four boundary curves, which are the exact cubic B-spline
 * curves of the surface's sides. The faces form one OPEN_SHELL of a
 * SHELL_BASED_SURFACE_MODEL in a MANIFOLD_SURFACE_SHAPE_REPRESENTATION with
 * the usual product structure, so CAD systems import it as a surface body.
 * Faces do not share edges: patches of different refinement depth meet in
 * T-junctions, and each face stays an independent, exact patch. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "sq_io.h"
#include "sq_subdiv.h"

/* Uniform cubic B-spline weights at the ends of the domain: t = 0 and 1. */
static const double W0[4] = {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0};
static const double W1[4] = {0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};

static void emit_point(FILE *fp, unsigned long id, const double *p)
{
    char a[32], b[32], c[32];
    fprintf(fp, "#%lu=CARTESIAN_POINT('',(%s,%s,%s));\n", id, sq_cad_real(p[0], a),
            sq_cad_real(p[1], b), sq_cad_real(p[2], c));
}

static void step_string(FILE *fp, const char *s)
{
    fputc('\'', fp);
    for (; *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '\'') fputs("''", fp);
        else if (ch == '\\') fputs("\\\\", fp);
        else if (ch >= 32 && ch < 127) fputc(ch, fp);
        else fputc('_', fp);
    }
    fputc('\'', fp);
}

static const char *KNOTS = "(1,1,1,1,1,1,1,1),(-3.,-2.,-1.,0.,1.,2.,3.,4.)";

sq_status sq_cad_write_step(const char *path, const char *name, uint32_t np, const double *cv,
                            double scale, sq_error *err)
{
    if (np == 0) return sq_error_set(err, SQ_ERR_EMPTY, "no patches to write to %s", path);
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *fp = af.fp;
    char stamp[32] = "1970-01-01T00:00:00";
    time_t now = time(NULL);
    struct tm tmv;
    if (gmtime_r(&now, &tmv)) strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &tmv);
    char tol[32];
    sq_cad_real(1e-7 * (scale > 0 ? scale : 1.0), tol);
    fputs("ISO-10303-21;\nHEADER;\n", fp);
    fputs("FILE_DESCRIPTION(('Catmull-Clark surface as bicubic B-spline patches'),'2;1');\n",
          fp);
    fputs("FILE_NAME(", fp);
    step_string(fp, name ? name : "seamquad");
    fprintf(fp, ",'%s',('seamquad'),(''),'seamquad 0.1.0','seamquad','');\n", stamp);
    fputs("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n", fp);
    fputs("#1=APPLICATION_CONTEXT('core data for automotive mechanical design processes');\n"
          "#2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',"
          "2000,#1);\n"
          "#3=PRODUCT_CONTEXT('',#1,'mechanical');\n",
          fp);
    fputs("#4=PRODUCT(", fp);
    step_string(fp, name ? name : "seamquad");
    fputs(",", fp);
    step_string(fp, name ? name : "seamquad");
    fputs(",'',(#3));\n", fp);
    fprintf(fp,
            "#5=PRODUCT_DEFINITION_FORMATION('','',#4);\n"
            "#6=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n"
            "#7=PRODUCT_DEFINITION('design','',#5,#6);\n"
            "#8=PRODUCT_DEFINITION_SHAPE('','',#7);\n"
            "#9=SHAPE_DEFINITION_REPRESENTATION(#8,#20);\n"
            "#10=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n"
            "#11=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n"
            "#12=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());\n"
            "#13=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(%s),#10,'distance_accuracy_value',"
            "'confusion accuracy');\n"
            "#14=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#13))"
            "GLOBAL_UNIT_ASSIGNED_CONTEXT((#10,#11,#12))REPRESENTATION_CONTEXT('Context #1',"
            "'3D Context with UNIT and UNCERTAINTY'));\n"
            "#15=CARTESIAN_POINT('',(0.,0.,0.));\n"
            "#16=DIRECTION('',(0.,0.,1.));\n"
            "#17=DIRECTION('',(1.,0.,0.));\n"
            "#18=AXIS2_PLACEMENT_3D('',#15,#16,#17);\n"
            "#19=SHELL_BASED_SURFACE_MODEL('',(#21));\n"
            "#20=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#18,#19),#14);\n",
            tol);
    /* Per patch, ids from base b: 16 control points, surface, 4 corner
     * points + 4 vertices, 4x(4 curve points + curve + edge + oriented
     * edge), loop, bound, face: 16+1+8+28+3 = 56 entities. */
    const unsigned long per = 56, first = 100;
    fputs("#21=OPEN_SHELL('',(", fp);
    for (uint32_t p = 0; p < np; p++)
        fprintf(fp, "%s#%lu", p ? "," : "", first + per * p + per - 1);
    fputs("));\n", fp);
    for (uint32_t p = 0; p < np && !ferror(fp); p++) {
        const double *c = cv + 48 * (size_t)p;
        unsigned long b = first + per * p;
        for (int k = 0; k < 16; k++) emit_point(fp, b + (unsigned long)k, c + 3 * k);
        /* control_points_list[i][j]: i along u. cv index 4*j + i. */
        fprintf(fp, "#%lu=B_SPLINE_SURFACE_WITH_KNOTS('',3,3,(", b + 16);
        for (int i = 0; i < 4; i++) {
            fprintf(fp, "%s(", i ? "," : "");
            for (int j = 0; j < 4; j++) fprintf(fp, "%s#%lu", j ? "," : "", b + 4 * j + i);
            fputs(")", fp);
        }
        fputs("),.UNSPECIFIED.,.F.,.F.,.F.,(1,1,1,1,1,1,1,1),(1,1,1,1,1,1,1,1),"
              "(-3.,-2.,-1.,0.,1.,2.,3.,4.),(-3.,-2.,-1.,0.,1.,2.,3.,4.),.UNSPECIFIED.);\n",
              fp);
        /* corners (s,t) = (0,0), (1,0), (1,1), (0,1) */
        const double *Ws[4] = {W0, W1, W1, W0}, *Wt[4] = {W0, W0, W1, W1};
        for (int k = 0; k < 4; k++) {
            double q[3] = {0, 0, 0};
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 4; i++)
                    for (int d = 0; d < 3; d++) q[d] += Ws[k][i] * Wt[k][j] * c[3 * (4 * j + i) + d];
            emit_point(fp, b + 17 + (unsigned long)k, q);
            fprintf(fp, "#%lu=VERTEX_POINT('',#%lu);\n", b + 21 + (unsigned long)k,
                    b + 17 + (unsigned long)k);
        }
        /* sides: 0: t=0 along s (v0->v1), 1: s=1 along t (v1->v2),
         * 2: t=1 along s (v3->v2, used reversed), 3: s=0 along t (v0->v3,
         * used reversed) */
        static const int from[4] = {0, 1, 3, 0}, to[4] = {1, 2, 2, 3};
        unsigned long oe[4];
        for (int e = 0; e < 4; e++) {
            unsigned long eb = b + 25 + 7 * (unsigned long)e;
            for (int a = 0; a < 4; a++) {
                double q[3] = {0, 0, 0};
                for (int r = 0; r < 4; r++) {
                    int i, j;
                    double w;
                    if (e == 0 || e == 2) { /* curve index a along s; rows r along t */
                        i = a;
                        j = r;
                        w = e == 0 ? W0[r] : W1[r];
                    } else {
                        i = r;
                        j = a;
                        w = e == 3 ? W0[r] : W1[r];
                    }
                    for (int d = 0; d < 3; d++) q[d] += w * c[3 * (4 * j + i) + d];
                }
                emit_point(fp, eb + (unsigned long)a, q);
            }
            fprintf(fp, "#%lu=B_SPLINE_CURVE_WITH_KNOTS('',3,(#%lu,#%lu,#%lu,#%lu),"
                        ".UNSPECIFIED.,.F.,.F.,%s,.UNSPECIFIED.);\n",
                    eb + 4, eb, eb + 1, eb + 2, eb + 3, KNOTS);
            fprintf(fp, "#%lu=EDGE_CURVE('',#%lu,#%lu,#%lu,.T.);\n", eb + 5,
                    b + 21 + (unsigned long)from[e], b + 21 + (unsigned long)to[e], eb + 4);
            fprintf(fp, "#%lu=ORIENTED_EDGE('',*,*,#%lu,%s);\n", eb + 6, eb + 5,
                    e < 2 ? ".T." : ".F.");
            oe[e] = eb + 6;
        }
        fprintf(fp, "#%lu=EDGE_LOOP('',(#%lu,#%lu,#%lu,#%lu));\n", b + 53, oe[0], oe[1], oe[2],
                oe[3]);
        fprintf(fp, "#%lu=FACE_OUTER_BOUND('',#%lu,.T.);\n", b + 54, b + 53);
        fprintf(fp, "#%lu=ADVANCED_FACE('',(#%lu),#%lu,.T.);\n", b + 55, b + 54, b + 16);
    }
    fputs("ENDSEC;\nEND-ISO-10303-21;\n", fp);
    if (ferror(fp)) {
        sq_atomic_abort(&af);
        return sq_error_set(err, SQ_ERR_IO, "%s: write failed", path);
    }
    return sq_atomic_commit(&af, err);
}
