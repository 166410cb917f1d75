// Lucerna scene builder: the text report of a built scene printed by `lucerna info`.
#include <cstdio>
#include <sstream>

#include "lucerna/scene/builder.h"

namespace lu {

namespace {

std::string Fmt(const char *fmt, double a = 0, double b = 0, double c = 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

std::string Vec(const Vec3f &v) { return Fmt("(%.6g, %.6g, %.6g)", v.x, v.y, v.z); }

// "N (a 1, b 2)"
std::string Counts(const std::map<std::string, int> &m) {
    int total = 0;
    std::string parts;
    for (const auto &[name, n] : m) {
        total += n;
        parts += (parts.empty() ? "" : ", ") + name + " " + std::to_string(n);
    }
    return std::to_string(total) + (parts.empty() ? "" : " (" + parts + ")");
}

}  // namespace

std::string SceneSummary(const HostScene &s, const Diagnostics &diag) {
    const SceneStats &st = s.stats;
    const RenderSettings &rs = s.settings;
    std::ostringstream o;
    o << "resolution: " << s.film.width << " x " << s.film.height << "\n";
    o << "color space: " << GetRGBColorSpace(s.filmColorSpace).name << " (film output)\n";
    o << "camera: " << st.cameraType;
    if (s.camera.kind == CameraKind::Perspective) o << ", fov " << Fmt("%.6g", st.fov) << " deg";
    else if (s.camera.kind == CameraKind::SphericalEqualArea) o << ", equal-area mapping";
    else if (s.camera.kind == CameraKind::SphericalEquirect) o << ", equirectangular mapping";
    else if (s.camera.kind == CameraKind::Realistic && !s.lensElements.empty())
        o << ", " << s.lensElements.size() << " lens interfaces, film "
          << Fmt("%.4g", 1000 * s.lensElements.back().thickness) << " mm behind the rear element, "
          << Fmt("%.4g", 1000 * s.camera.filmDiagonal) << " mm diagonal";
    o << ", position " << Vec(st.cameraPosition)
      << ", direction " << Vec(st.cameraDirection) << "\n";
    o << "film: imaging ratio " << Fmt("%.6g", s.film.imagingRatio) << ", filter " << st.filterType
      << Fmt(" (radius %.6g x %.6g)", s.filter.radiusX, s.filter.radiusY) << "\n";
    o << "integrator: " << (st.integratorAsRead.empty() ? std::string("(none given)") : st.integratorAsRead) << " -> "
      << IntegratorName(rs.integrator) << ", maxdepth " << rs.maxDepth << "\n";
    o << "sampler: " << st.samplerName << ", " << rs.spp << " spp, seed " << rs.seed << "\n";
    o << "settings: " << DescribeRenderSettings(rs) << "\n";
    if (!s.outputFilename.empty()) o << "output: " << s.outputFilename << "\n";
    o << "shapes: " << Counts(st.shapesByType) << "\n";
    o << "triangles: " << st.triangles << "\n";
    if (st.bilinearPatches > 0) o << "bilinear patches: " << st.bilinearPatches << "\n";
    if (st.curveSegments > 0) o << "curve segments: " << st.curveSegments << "\n";
    o << "lights: " << Counts(st.lightsByType) << "\n";
    for (const std::string &l : st.lightProfiles) o << "  " << l << "\n";
    o << "materials: " << Counts(st.materialsByType) << "\n";
    if (!st.mediaByType.empty()) o << "media: " << Counts(st.mediaByType) << "\n";
    o << "textures: " << st.floatTextures << " float, " << st.spectrumTextures << " spectrum\n";
    o << "instances: " << st.instanceDefinitions << " definitions, " << st.instanceUses << " uses";
    if (st.instancedUses > 0)
        o << " (" << st.instancedUses << " kept as instances of " << st.prototypes << " prototypes, the rest flattened)";
    o << "\n";
    if (s.bounds.Empty()) o << "bounds: empty\n";
    else o << "bounds: " << Vec(s.bounds.pMin) << " - " << Vec(s.bounds.pMax) << "\n";
    o << "warnings: " << diag.warnings.size() << "\n";
    for (const std::string &w : diag.warnings) o << "  " << w << "\n";
    o << "unsupported: " << diag.unsupported.size() << "\n";
    for (const std::string &u : diag.unsupported) o << "  " << u << "\n";
    return o.str();
}

}  // namespace lu
