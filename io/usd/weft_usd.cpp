// weft_usd.so: writes a cloth cache as a USD layer with OpenUSD's own Sdf library (the pxr-sdf-dev wheels;
// cmake/WeftUsd.cmake). One prim, /cloth, of type Mesh with UsdGeomMesh's attributes: points, velocities and
// extent time-sampled at each frame, the triangles as faceVertexCounts/faceVertexIndices. Sdf knows no
// schemas, so the attribute names and types are UsdGeom's, spelled out here. docs/formats.md ("USD").
#include "io/usd/weft_usd.hpp"

#include <pxr/gf/vec3f.h>
#include <pxr/plug/registry.h>
#include <pxr/sdf/attributeSpec.h>
#include <pxr/sdf/layer.h>
#include <pxr/sdf/path.h>
#include <pxr/sdf/primSpec.h>
#include <pxr/sdf/types.h>
#include <pxr/tf/errorMark.h>
#include <pxr/tf/token.h>
#include <pxr/vt/array.h>
#include <pxr/vt/dictionary.h>
#include <pxr/vt/value.h>
#include <pxr/work/threadLimits.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#ifndef WEFT_USD_PLUGINFO
#error "WEFT_USD_PLUGINFO: the plugInfo.json files cmake/WeftUsd.cmake writes for Sdf and Ar"
#endif

namespace {

using namespace pxr;
using weft::io::usd::MeshCache;

// The wheels' plugInfo.json files name their libraries at a layout they do not install, and Plug (which Sdf
// asks for file formats and Ar for its resolver) finds none on its own: register the copies that the build
// wrote with the libraries' real paths. Once per process; a plug-in registered again is ignored.
// Work runs on one thread: with more, Sdf hands a dropped layer's data to a detached TBB task whose thread
// can still be inside TBB while weft exits and TBB's statics go (a crash after the file is written, about one
// export in eight). One mesh layer gains nothing from threads.
void register_plugins() {
  static const bool done = [] {
    WorkSetConcurrencyLimit(1);
    PlugRegistry::GetInstance().RegisterPlugins(std::string(WEFT_USD_PLUGINFO) + "/*/resources/");
    return true;
  }();
  (void)done;
}

// The errors Sdf posted since `mark`, one a line; clears them so that Tf does not print them too.
std::string errors(TfErrorMark& mark) {
  std::string text;
  for (auto it = mark.GetBegin(); it != mark.GetEnd(); ++it) {
    if (!text.empty()) text += "; ";
    text += it->GetCommentary();
  }
  mark.Clear();
  return text;
}

SdfAttributeSpecHandle attribute(const SdfPrimSpecHandle& prim, const char* name, const SdfValueTypeName& type,
                                 SdfVariability variability = SdfVariabilityVarying) {
  SdfAttributeSpecHandle a = SdfAttributeSpec::New(prim, name, type, variability);
  if (!a) throw std::runtime_error(std::string("cannot create the attribute ") + name);
  return a;
}

VtVec3fArray vec3f_array(const std::vector<float>& xyz) {
  VtVec3fArray a(xyz.size() / 3);
  for (size_t i = 0; i < a.size(); ++i) a[i] = GfVec3f(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return a;
}

std::string write(const MeshCache& mesh, const std::string& path) {
  register_plugins();
  TfErrorMark mark;
  SdfLayerRefPtr layer = SdfLayer::CreateNew(path);
  if (!layer) {
    const std::string why = errors(mark);
    return "cannot create the USD layer" + (why.empty() ? std::string() : ": " + why);
  }
  const double first = mesh.frames.empty() ? 0 : mesh.frames.front();
  const double last = mesh.frames.empty() ? 0 : mesh.frames.back();
  layer->SetDocumentation("cloth cache written by " + mesh.generator + " from " + mesh.source);
  layer->SetStartTimeCode(first);
  layer->SetEndTimeCode(last);
  layer->SetTimeCodesPerSecond(mesh.fps);
  layer->SetFramesPerSecond(mesh.fps);
  // UsdGeom's stage metrics: weft's scenes are Y-up, in metres.
  layer->SetField(SdfPath::AbsoluteRootPath(), TfToken("upAxis"), VtValue(TfToken("Y")));
  layer->SetField(SdfPath::AbsoluteRootPath(), TfToken("metersPerUnit"), VtValue(1.0));
  VtDictionary weft;
  weft["generator"] = VtValue(mesh.generator);
  weft["scene"] = VtValue(mesh.scene);
  weft["cache"] = VtValue(mesh.source);
  VtDictionary custom;
  custom["weft"] = VtValue(weft);
  layer->SetCustomLayerData(custom);

  SdfPrimSpecHandle prim = SdfPrimSpec::New(layer->GetPseudoRoot(), "cloth", SdfSpecifierDef, "Mesh");
  if (!prim) return "cannot create the prim /cloth: " + errors(mark);
  layer->SetDefaultPrim(TfToken("cloth"));

  // Topology: every face a triangle, counter-clockwise from the front (rightHanded), no subdivision.
  VtIntArray counts(mesh.triangles.size(), 3), indices(3 * mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) indices[3 * t + c] = mesh.triangles[t][c];
  attribute(prim, "faceVertexCounts", SdfValueTypeNames->IntArray)->SetDefaultValue(VtValue(counts));
  attribute(prim, "faceVertexIndices", SdfValueTypeNames->IntArray)->SetDefaultValue(VtValue(indices));
  attribute(prim, "subdivisionScheme", SdfValueTypeNames->Token, SdfVariabilityUniform)
      ->SetDefaultValue(VtValue(TfToken("none")));
  attribute(prim, "orientation", SdfValueTypeNames->Token, SdfVariabilityUniform)
      ->SetDefaultValue(VtValue(TfToken("rightHanded")));
  attribute(prim, "doubleSided", SdfValueTypeNames->Bool, SdfVariabilityUniform)->SetDefaultValue(VtValue(true));

  const SdfPath points = attribute(prim, "points", SdfValueTypeNames->Point3fArray)->GetPath();
  const SdfPath velocities = attribute(prim, "velocities", SdfValueTypeNames->Vector3fArray)->GetPath();
  const SdfPath extent = attribute(prim, "extent", SdfValueTypeNames->Float3Array)->GetPath();
  std::vector<float> x, v;
  for (size_t k = 0; k < mesh.frames.size(); ++k) {
    mesh.frame(k, x, v);
    if (x.size() != 3 * mesh.points || v.size() != 3 * mesh.points)
      return "frame " + std::to_string(mesh.frames[k]) + " has the wrong number of points";
    const double time = mesh.frames[k];
    VtVec3fArray p = vec3f_array(x);
    GfVec3f lo(0.f), hi(0.f);
    if (!p.empty()) {
      lo = hi = p[0];
      for (const GfVec3f& q : p)
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], q[c]), hi[c] = std::max(hi[c], q[c]);
    }
    layer->SetTimeSample(points, time, p);
    layer->SetTimeSample(velocities, time, vec3f_array(v));
    layer->SetTimeSample(extent, time, VtVec3fArray{lo, hi});
  }
  if (!mark.IsClean()) return errors(mark);
  if (!layer->Save()) {
    const std::string why = errors(mark);
    return "cannot save the USD layer" + (why.empty() ? std::string() : ": " + why);
  }
  return errors(mark);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) std::string weft_usd_write_v1(const MeshCache& mesh,
                                                                                 const std::string& path) {
  try {
    return write(mesh, path);
  } catch (const std::exception& e) {
    return e.what();
  }
}

static_assert(std::is_same_v<decltype(&weft_usd_write_v1), weft::io::usd::WriterFn>);
