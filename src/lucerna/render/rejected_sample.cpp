// Lucerna: the first rejected sample of a render in words (render/rejected_sample.h).
#include "lucerna/render/rejected_sample.h"

namespace lu {

const char *BadValueName(BadValue v) {
    switch (v) {
    case BadValue::NaN: return "NaN";
    case BadValue::Infinite: return "an infinite value";
    case BadValue::Negative: return "a negative value";
    }
    return "a bad value";
}

const char *RejectCauseName(RejectCause c) {
    switch (c) {
    case RejectCause::None: return "none";
    case RejectCause::Emission: return "emission";
    case RejectCause::Direct: return "light connection";
    case RejectCause::Scatter: return "scattering";
    case RejectCause::Medium: return "medium";
    case RejectCause::Film: return "film";
    }
    return "unknown";
}

namespace {

std::string Or(const std::string &s, const std::string &fallback) { return s.empty() ? fallback : s; }

std::string Index(const char *what, uint32_t i) {
    return i == NoIndex ? std::string("an unidentified ") + what : std::string(what) + " #" + std::to_string(i);
}

}  // namespace

std::string RejectedSource(const HostScene &scene, const RejectedSample &r) {
    switch (r.cause) {
    case RejectCause::Emission: return Or(scene.OriginOf(scene.lightOrigin, r.entity), Index("light", r.entity));
    case RejectCause::Direct:
    case RejectCause::Scatter: return Or(scene.OriginOf(scene.materialOrigin, r.entity), Index("material", r.entity));
    case RejectCause::Medium: return Or(scene.OriginOf(scene.mediumOrigin, r.entity), Index("medium", r.entity));
    default: return "";
    }
}

std::string DescribeRejectedSample(const HostScene &scene, const RejectedSample &r) {
    if (!r.Valid()) return "";
    std::string s = "at pixel (" + std::to_string(r.x) + ", " + std::to_string(r.y) + "), depth " + std::to_string(r.depth) +
                    ": " + BadValueName(r.badValue);
    std::string src = RejectedSource(scene, r);
    switch (r.cause) {
    case RejectCause::Emission: return s + " in the radiance emitted by " + src;
    case RejectCause::Direct:
        return s + " in a light connection at a surface of " + src + " (its BSDF, its textures or the light's radiance)";
    case RejectCause::Scatter: return s + " in the path throughput after sampling the BSDF of " + src + " (or its textures)";
    case RejectCause::Medium: return s + " in " + src + " (its density, albedo or emission, or a light seen from it)";
    case RejectCause::Film:
        return s + " at the film: the path's contributions were finite and non-negative, their XYZ value or the filter "
                   "weight was not (overflow)";
    case RejectCause::None: break;
    }
    return s;
}

}  // namespace lu
