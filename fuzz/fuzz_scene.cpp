// libFuzzer target: the pbrt-v4 scene parser and ParameterDictionary must never crash, leak or
// hit undefined behavior; bad input may only throw SceneError. File access is disabled.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "lucerna/scene/parser.h"

using namespace lu;

// Calls the getter that matches each parameter's type, and one that does not.
static void Exercise(const ParameterDictionary &dict) {
    for (const ParsedParameter &p : dict.All()) {
        auto attempt = [&](auto &&f) {
            try {
                f();
            } catch (const SceneError &e) {
                (void)e.Message();
            }
        };
        const std::string &t = p.type;
        if (t == "float") attempt([&] { dict.GetOneFloat(p.name, 0); }), attempt([&] { dict.GetFloatArray(p.name); });
        else if (t == "integer") attempt([&] { dict.GetOneInt(p.name, 0); }), attempt([&] { dict.GetIntArray(p.name); });
        else if (t == "bool") attempt([&] { dict.GetOneBool(p.name, false); });
        else if (t == "string") attempt([&] { dict.GetOneString(p.name, ""); }), attempt([&] { dict.GetStringArray(p.name); });
        else if (t == "point3" || t == "point") attempt([&] { dict.GetOnePoint3f(p.name); }), attempt([&] { dict.GetPoint3fArray(p.name); });
        else if (t == "vector3" || t == "vector") attempt([&] { dict.GetOneVector3f(p.name); }), attempt([&] { dict.GetVector3fArray(p.name); });
        else if (t == "normal" || t == "normal3") attempt([&] { dict.GetNormal3fArray(p.name); });
        else if (t == "point2") attempt([&] { dict.GetPoint2fArray(p.name); });
        else (void)dict.Find(p.name);
        attempt([&] { dict.GetOneFloat(p.name, 0); });
    }
    Diagnostics diag;
    diag.quiet = true;
    dict.ReportUnused(diag, "fuzz");
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::string text(reinterpret_cast<const char *>(data), size);
    Diagnostics diag;
    diag.quiet = true;
    ParseOptions options;
    options.allowFileAccess = false;
    options.maxTotalValues = size_t(1) << 20;
    try {
        SceneDescription d = ParseSceneString(text, "fuzz.pbrt", diag, options);
        // Invariants of the description.
        for (const ShapeEntity &s : d.shapes) {
            if (s.materialIndex >= int(d.materials.size()) || s.materialIndex < -1) std::abort();
            if (s.areaLightIndex >= int(d.areaLights.size()) || s.areaLightIndex < -1) std::abort();
            if (!s.materialName.empty() && !d.namedMaterials.count(s.materialName)) std::abort();
            Exercise(s.params);
        }
        for (const InstanceUse &u : d.instances) {
            if (u.object >= d.objectNames.size() || u.file >= d.instanceFiles.size()) std::abort();
            if (u.projective != 0xffffffffu && u.projective >= d.projectiveInstanceTransforms.size())
                std::abort();
            if (!d.instanceDefinitions.count(d.ObjectName(u))) std::abort();
        }
        for (const auto &l : d.lights) Exercise(l.params);
        for (const auto &m : d.materials) Exercise(m.params);
        for (const auto &[name, m] : d.namedMaterials) Exercise(m.params);
        for (const auto &a : d.areaLights) Exercise(a.params);
        Exercise(d.camera.params);
        Exercise(d.film.params);
    } catch (const SceneError &e) {
        (void)e.Format();
    }
    return 0;
}
