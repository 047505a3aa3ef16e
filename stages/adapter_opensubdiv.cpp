// seamquad: OpenSubdiv adapter (see sq_osd_adapter.h). Thin wrapper only:
// topology in, OpenSubdiv's patches, evaluations and refinements out.
#include "sq_osd_adapter.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

using namespace OpenSubdiv;

namespace {

struct Point {
    double p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(Point const &s, double w)
    {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
        p[2] += w * s.p[2];
    }
};

typedef Far::TopologyDescriptor Descriptor;

Far::TopologyRefiner *make_refiner(uint32_t nv, uint32_t nf, const uint32_t *face_off,
                                   const uint32_t *face_idx, std::vector<int> &valence)
{
    valence.resize(nf);
    for (uint32_t f = 0; f < nf; f++) valence[f] = (int)(face_off[f + 1] - face_off[f]);
    Descriptor desc;
    desc.numVertices = (int)nv;
    desc.numFaces = (int)nf;
    desc.numVertsPerFace = valence.data();
    desc.vertIndicesPerFace = reinterpret_cast<const Far::Index *>(face_idx);
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    return Far::TopologyRefinerFactory<Descriptor>::Create(
        desc, Far::TopologyRefinerFactory<Descriptor>::Options(Sdc::SCHEME_CATMARK, sdc));
}

// Positions of every vertex of every level of the refiner, base level first.
void interpolate_all(const Far::TopologyRefiner &r, const double *pos, std::vector<Point> &out)
{
    out.resize((size_t)r.GetNumVerticesTotal());
    int nbase = r.GetLevel(0).GetNumVertices();
    std::memcpy(out.data(), pos, sizeof(Point) * (size_t)nbase);
    Far::PrimvarRefinerReal<double> pr(r);
    Point *src = out.data();
    for (int level = 1; level <= r.GetMaxLevel(); level++) {
        Point *dst = src + r.GetLevel(level - 1).GetNumVertices();
        pr.Interpolate(level, src, dst);
        src = dst;
    }
}

}  // namespace

static_assert(sizeof(Point) == 3 * sizeof(double), "Point must be 3 packed doubles");
static_assert(sizeof(Far::Index) == sizeof(uint32_t), "Far::Index must be 32 bits");

struct sq_osd {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> table;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Point> verts;  // refined vertices, then local (end cap) points
    std::vector<Far::PatchTable::PatchHandle> handles;
};

extern "C" sq_status sq_osd_create(uint32_t nv, const double *pos, uint32_t nf,
                                   const uint32_t *face_off, const uint32_t *face_idx,
                                   int isolation, sq_osd **out, sq_error *err)
{
    *out = nullptr;
    if (isolation < 1 || isolation > 10)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "isolation level %d outside 1..10", isolation);
    for (uint32_t f = 0; f < nf; f++)
        if (face_off[f + 1] - face_off[f] != 4)
            return sq_error_set(err, SQ_ERR_POLYGON, "face %u has %u corners: not a quad", f,
                                face_off[f + 1] - face_off[f]);
    try {
        std::unique_ptr<sq_osd> o(new sq_osd);
        std::vector<int> valence;
        o->refiner.reset(make_refiner(nv, nf, face_off, face_idx, valence));
        if (!o->refiner)
            return sq_error_set(err, SQ_ERR_INTERNAL, "OpenSubdiv rejected the mesh topology");
        Far::PatchTableFactory::Options po((unsigned)isolation);
        po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
        po.SetPatchPrecision<double>();
        po.generateVaryingTables = false;
        po.generateVaryingLocalPoints = false;
        o->refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
        o->table.reset(Far::PatchTableFactory::Create(*o->refiner, po));
        interpolate_all(*o->refiner, pos, o->verts);
        size_t nref = o->verts.size();
        o->verts.resize(nref + (size_t)o->table->GetNumLocalPoints());
        if (o->table->GetNumLocalPoints())
            o->table->GetLocalPointStencilTable<double>()->UpdateValues(o->verts.data(),
                                                                        o->verts.data() + nref);
        for (int a = 0; a < o->table->GetNumPatchArrays(); a++) {
            Far::PatchDescriptor d = o->table->GetPatchArrayDescriptor(a);
            if (d.GetType() != Far::PatchDescriptor::REGULAR || d.GetNumControlVertices() != 16)
                return sq_error_set(err, SQ_ERR_INTERNAL,
                                    "OpenSubdiv made a patch of type %d, not a regular B-spline",
                                    (int)d.GetType());
            for (int j = 0; j < o->table->GetNumPatches(a); j++) {
                Far::PatchTable::PatchHandle h;
                h.arrayIndex = a;
                h.patchIndex = (Far::Index)o->handles.size();
                h.vertIndex = j * 16;
                Far::PatchParam pp = o->table->GetPatchParam(h);
                if (pp.GetBoundary() != 0 || pp.NonQuadRoot())
                    return sq_error_set(err, SQ_ERR_INTERNAL,
                                        "OpenSubdiv made a boundary patch on a closed mesh");
                o->handles.push_back(h);
            }
        }
        o->map.reset(new Far::PatchMap(*o->table));
        *out = o.release();
        return SQ_OK;
    } catch (const std::bad_alloc &) {
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory in OpenSubdiv");
    } catch (...) {
        return sq_error_set(err, SQ_ERR_INTERNAL, "OpenSubdiv failed");
    }
}

extern "C" void sq_osd_free(sq_osd *o) { delete o; }

extern "C" uint32_t sq_osd_patch_count(const sq_osd *o) { return (uint32_t)o->handles.size(); }

extern "C" void sq_osd_patch(const sq_osd *o, uint32_t p, double cv[48], uint32_t *face,
                             double dom[4])
{
    const Far::PatchTable::PatchHandle &h = o->handles[p];
    Far::ConstIndexArray idx = o->table->GetPatchVertices(h);
    for (int k = 0; k < 16; k++)
        for (int c = 0; c < 3; c++) cv[3 * k + c] = o->verts[(size_t)idx[k]].p[c];
    Far::PatchParam pp = o->table->GetPatchParam(h);
    *face = (uint32_t)pp.GetFaceId();
    double u0 = 0.0, v0 = 0.0, u1 = 1.0, v1 = 1.0;
    pp.Unnormalize(u0, v0);
    pp.Unnormalize(u1, v1);
    dom[0] = u0;
    dom[1] = v0;
    dom[2] = u1;
    dom[3] = v1;
}

extern "C" void sq_osd_eval(const sq_osd *o, uint32_t face, uint32_t patch, double u, double v,
                            double P[3], double Pu[3], double Pv[3])
{
    const Far::PatchTable::PatchHandle *h =
        patch == UINT32_MAX ? o->map->FindPatch((int)face, u, v) : &o->handles[patch];
    double w[16], wu[16], wv[16];
    o->table->EvaluateBasis(*h, u, v, w, wu, wv);
    Far::ConstIndexArray idx = o->table->GetPatchVertices(*h);
    double acc[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int k = 0; k < idx.size(); k++) {
        const double *q = o->verts[(size_t)idx[k]].p;
        for (int c = 0; c < 3; c++) {
            acc[0][c] += w[k] * q[c];
            acc[1][c] += wu[k] * q[c];
            acc[2][c] += wv[k] * q[c];
        }
    }
    for (int c = 0; c < 3; c++) {
        P[c] = acc[0][c];
        if (Pu) Pu[c] = acc[1][c];
        if (Pv) Pv[c] = acc[2][c];
    }
}

extern "C" sq_status sq_osd_refine_uniform(uint32_t nv, const double *pos, uint32_t nf,
                                           const uint32_t *face_off, const uint32_t *face_idx,
                                           int levels, uint32_t *out_nv, double **out_pos,
                                           uint32_t *out_nf, uint32_t **out_face_off,
                                           uint32_t **out_face_idx, sq_error *err)
{
    *out_pos = nullptr;
    *out_face_off = *out_face_idx = nullptr;
    if (levels < 1 || levels > 6)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "refinement levels %d outside 1..6", levels);
    try {
        std::vector<int> valence;
        std::unique_ptr<Far::TopologyRefiner> r(make_refiner(nv, nf, face_off, face_idx, valence));
        if (!r) return sq_error_set(err, SQ_ERR_INTERNAL, "OpenSubdiv rejected the mesh topology");
        r->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
        std::vector<Point> all;
        interpolate_all(*r, pos, all);
        const Far::TopologyLevel &last = r->GetLevel(levels);
        size_t first = all.size() - (size_t)last.GetNumVertices();
        uint32_t n = (uint32_t)last.GetNumVertices(), m = (uint32_t)last.GetNumFaces();
        double *p = (double *)std::malloc(sizeof(double) * 3 * (size_t)n);
        uint32_t *fo = (uint32_t *)std::malloc(sizeof(uint32_t) * ((size_t)m + 1));
        uint32_t *fi = (uint32_t *)std::malloc(sizeof(uint32_t) * 4 * (size_t)m);
        if (!p || !fo || !fi) {
            std::free(p);
            std::free(fo);
            std::free(fi);
            return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        }
        std::memcpy(p, all.data() + first, sizeof(double) * 3 * (size_t)n);
        fo[0] = 0;
        for (uint32_t f = 0; f < m; f++) {
            Far::ConstIndexArray fv = last.GetFaceVertices((Far::Index)f);
            for (int k = 0; k < fv.size(); k++) fi[fo[f] + (uint32_t)k] = (uint32_t)fv[k];
            fo[f + 1] = fo[f] + (uint32_t)fv.size();
        }
        *out_nv = n;
        *out_nf = m;
        *out_pos = p;
        *out_face_off = fo;
        *out_face_idx = fi;
        return SQ_OK;
    } catch (const std::bad_alloc &) {
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory in OpenSubdiv");
    } catch (...) {
        return sq_error_set(err, SQ_ERR_INTERNAL, "OpenSubdiv failed");
    }
}
