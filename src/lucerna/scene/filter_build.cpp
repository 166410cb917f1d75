// Lucerna: host-side filter construction (pbrt-v4 names and defaults) and the tabulated
// importance-sampling distribution of gaussian and mitchell filters (pbrt-v4's FilterSampler).
#include "lucerna/scene/camera_build.h"
#include "lucerna/scene/distribution_build.h"

#include <cmath>
#include <stdexcept>

namespace lu {

FilterData MakeFilter(const std::string &name, Float xradius, Float yradius, Float sigma, Float B, Float C) {
    FilterData f;
    Float defRadius;
    if (name == "gaussian") { f.kind = FilterKind::Gaussian; defRadius = 1.5f; }
    else if (name == "box") { f.kind = FilterKind::Box; defRadius = 0.5f; }
    else if (name == "triangle") { f.kind = FilterKind::Triangle; defRadius = 2.f; }
    else if (name == "mitchell") { f.kind = FilterKind::Mitchell; defRadius = 2.f; }
    else throw std::invalid_argument("unknown filter \"" + name + "\"");
    f.radiusX = xradius > 0 ? xradius : defRadius;
    f.radiusY = yradius > 0 ? yradius : defRadius;
    f.sigma = sigma > 0 ? sigma : 0.5f;
    f.B = std::isnan(B) ? 1.f / 3.f : B;
    f.C = std::isnan(C) ? 1.f / 3.f : C;
    f.distribution = NoIndex;
    return f;
}

void BuildFilterDistribution(FilterData &f, std::vector<Distribution2D> &dists, std::vector<Float> &distData) {
    f.distribution = NoIndex;
    if (f.kind != FilterKind::Gaussian && f.kind != FilterKind::Mitchell) return;
    int nx = FilterTableSize(f.radiusX), ny = FilterTableSize(f.radiusY);
    if (nx < 1 || ny < 1) return;
    std::vector<float> table(size_t(nx) * ny);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) table[size_t(y) * nx + x] = FilterTableValue(f, x, y, nx, ny);
    Distribution2D d = BuildDistribution2D(table.data(), nx, ny, distData);
    f.distribution = uint32_t(dists.size());
    dists.push_back(d);
}

}  // namespace lu
