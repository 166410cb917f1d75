// Lucerna: host-side filter construction (pbrt-v4 names and defaults) and the tabulated
// importance-sampling distribution of gaussian and mitchell filters (pbrt-v4's FilterSampler).
#include "lucerna/scene/camera_build.h"
#include "lucerna/scene/distribution_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lu {

FilterData MakeFilter(const std::string &name, Float xradius, Float yradius, Float sigma, Float B, Float C,
                      Float tau) {
    FilterData f;
    Float defRadius;
    if (name == "gaussian") { f.kind = FilterKind::Gaussian; defRadius = 1.5f; }
    else if (name == "box") { f.kind = FilterKind::Box; defRadius = 0.5f; }
    else if (name == "triangle") { f.kind = FilterKind::Triangle; defRadius = 2.f; }
    else if (name == "mitchell") { f.kind = FilterKind::Mitchell; defRadius = 2.f; }
    else if (name == "sinc") { f.kind = FilterKind::LanczosSinc; defRadius = 4.f; }
    else throw std::invalid_argument("unknown filter \"" + name + "\"");
    f.radiusX = xradius > 0 ? xradius : defRadius;
    f.radiusY = yradius > 0 ? yradius : defRadius;
    f.sigma = sigma > 0 ? sigma : 0.5f;
    f.B = std::isnan(B) ? 1.f / 3.f : B;
    f.C = std::isnan(C) ? 1.f / 3.f : C;
    f.tau = tau > 0 ? tau : 3.f;
    f.distribution = NoIndex;
    return f;
}

void BuildFilterDistribution(FilterData &f, std::vector<Distribution2D> &dists, std::vector<Float> &distData) {
    f.distribution = NoIndex;
    if (f.kind == FilterKind::Box || f.kind == FilterKind::Triangle) return;
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

namespace lu {

Float FilterWeightFloor(const FilterData &f, const std::vector<Distribution2D> &dists) {
    if (f.kind != FilterKind::Mitchell && f.kind != FilterKind::LanczosSinc) return 0;
    // A sample's expected weight: with the table, f_cell / pdf has the table's signed integral as
    // its mean; without one (uniform over the support, weight f * area), the filter's integral.
    double expected = FilterIntegral(f);
    if (f.distribution != NoIndex) {
        const Distribution2D &d = dists[f.distribution];
        double sum = 0;
        for (int y = 0; y < int(d.ny); ++y)
            for (int x = 0; x < int(d.nx); ++x) sum += FilterTableValue(f, x, y, int(d.nx), int(d.ny));
        expected = sum * (4.0 * f.radiusX * f.radiusY) / (double(d.nx) * d.ny);
    }
    return Float(std::max(0.0, 0.5 * expected));
}

}  // namespace lu
