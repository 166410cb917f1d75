// Lucerna tests: pbrt-v4's Translate, Scale and Rotate as Transforms, for tests that build scenes
// by hand. They come from the scene reader's own double-precision code (scene/transform_math.h),
// rounded once, as the reader rounds them. Header-only; link lucerna_scene.
#pragma once

#include <stdexcept>

#include "lucerna/scene/transform_math.h"

namespace lu::test {

inline Transform ToTransform(const DMatrix &m) {
    DMatrix inv;
    if (!Invert(m, &inv)) throw std::invalid_argument("test transform is singular");
    return Transform(ToMatrix4(m), ToMatrix4(inv));
}
inline Transform Translate(const Vec3f &t) { return ToTransform(TranslateM(t.x, t.y, t.z)); }
inline Transform Scale(Float x, Float y, Float z) { return ToTransform(ScaleM(x, y, z)); }
// Rotation by `degrees` about `axis` (normalized here), counterclockwise looking down the axis.
inline Transform Rotate(Float degrees, Vec3f axis) {
    axis = Normalize(axis);
    return ToTransform(RotateM(degrees, axis.x, axis.y, axis.z));
}

}  // namespace lu::test
