// seamquad test helper: an independent CAD kernel (OpenCASCADE) imports a
// STEP or IGES file written by seamquad subdiv and checks it. Test-only
// adapter-like program: no seamquad code, no algorithm beyond sampling.
//
// usage: occt_check FILE.step|FILE.igs [SAMPLES]
// SAMPLES: lines "PATCH S T X Y Z": the limit point of patch PATCH at its
// own parameters (S, T) as OpenSubdiv evaluates it; (0.5, 0.5) must be among
// them. Each patch is matched to an imported face by that centre sample,
// then the face's surface is evaluated at every (S, T) and compared.
// bad_index counts samples of patches that matched no face.
// Prints one line: format, face count, validity, B-spline face count,
// samples and the max deviation. Exit 0 when the file was read, 1 if not.
#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: occt_check FILE.step|FILE.igs [SAMPLES]\n");
        return 2;
    }
    const char *path = argv[1];
    size_t n = std::strlen(path);
    bool iges = n > 4 && (!std::strcmp(path + n - 4, ".igs") || !std::strcmp(path + n - 5, ".iges"));
    // Silence OpenCASCADE's own messages: stdout carries only our report.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    TopoDS_Shape shape;
    if (iges) {
        IGESControl_Reader r;
        if (r.ReadFile(path) != IFSelect_RetDone) {
            std::printf("format iges read_failed\n");
            return 1;
        }
        r.TransferRoots();
        shape = r.OneShape();
    } else {
        STEPControl_Reader r;
        if (r.ReadFile(path) != IFSelect_RetDone) {
            std::printf("format step read_failed\n");
            return 1;
        }
        r.TransferRoots();
        shape = r.OneShape();
    }
    std::vector<TopoDS_Face> faces;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
        faces.push_back(TopoDS::Face(ex.Current()));
    int valid = !shape.IsNull() && BRepCheck_Analyzer(shape).IsValid() ? 1 : 0;
    int bspline = 0;
    for (const TopoDS_Face &f : faces)
        if (BRepAdaptor_Surface(f).GetType() == GeomAbs_BSplineSurface) bspline++;
    // Faces may come in any order: each patch is matched to the face whose
    // centre (parameters 0.5, 0.5) is nearest to the patch's sample at
    // (0.5, 0.5); then every sample of the patch is compared with that face.
    struct Sample {
        long p;
        double s, t, x, y, z;
    };
    std::vector<Sample> all;
    long samples = 0, bad_index = 0;
    double maxdev = 0.0;
    if (argc > 2) {
        FILE *fp = std::fopen(argv[2], "r");
        if (!fp) {
            std::printf("format %s cannot_open_samples\n", iges ? "iges" : "step");
            return 1;
        }
        Sample a;
        while (std::fscanf(fp, "%ld %lf %lf %lf %lf %lf", &a.p, &a.s, &a.t, &a.x, &a.y, &a.z) == 6)
            all.push_back(a);
        std::fclose(fp);
    }
    std::vector<BRepAdaptor_Surface> surf(faces.size());
    std::vector<std::pair<double, size_t>> byx(faces.size());
    std::vector<gp_Pnt> centre(faces.size());
    for (size_t i = 0; i < faces.size(); i++) {
        surf[i].Initialize(faces[i]);
        centre[i] = surf[i].Value(0.5, 0.5);
        byx[i] = std::make_pair(centre[i].X(), i);
    }
    std::sort(byx.begin(), byx.end());
    long npatch = 0;
    for (const Sample &a : all) npatch = std::max(npatch, a.p + 1);
    std::vector<long> face_of((size_t)npatch, -1);
    std::vector<char> used(faces.size(), 0);
    for (const Sample &a : all) {
        if (a.s != 0.5 || a.t != 0.5 || a.p < 0) continue;
        gp_Pnt q(a.x, a.y, a.z);
        double best = HUGE_VAL, window = 1e-6 * (1.0 + std::fabs(a.x));
        long bi = -1;
        auto it = std::lower_bound(byx.begin(), byx.end(), std::make_pair(a.x - window, (size_t)0));
        for (; it != byx.end() && it->first <= a.x + window; ++it) {
            double d = centre[it->second].Distance(q);
            if (d < best && !used[it->second]) {
                best = d;
                bi = (long)it->second;
            }
        }
        if (bi >= 0) {
            face_of[(size_t)a.p] = bi;
            used[(size_t)bi] = 1;
        }
    }
    for (const Sample &a : all) {
        if (a.p < 0 || a.p >= npatch || face_of[(size_t)a.p] < 0) {
            bad_index++;
            continue;
        }
        gp_Pnt q = surf[(size_t)face_of[(size_t)a.p]].Value(a.s, a.t);
        double d = q.Distance(gp_Pnt(a.x, a.y, a.z));
        if (!(d <= maxdev)) maxdev = d;  // NaN propagates as a failure
        samples++;
    }
    std::printf("format %s faces %zu valid %d bspline %d samples %ld bad_index %ld max_dev %.6e\n",
                iges ? "iges" : "step", faces.size(), valid, bspline, samples, bad_index, maxdev);
    return 0;
}
