// Lucerna scene reader: typed access to parsed parameters (after pbrt-v4's ParameterDictionary in
// paramdict.cpp). Differences: a parameter of the requested name but another type is an error
// (pbrt-v4 skips it and later reports it unused), and unused parameters are warnings.
#include <cfloat>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>

#include "lucerna/scene/description.h"

namespace lu {

static std::string Decl(const ParsedParameter &p) { return "\"" + p.type + " " + p.name + "\""; }

const ParsedParameter *ParameterDictionary::Lookup(const std::string &name, std::initializer_list<const char *> types,
                                                   const char *expected) const {
    // The last definition wins, as in pbrt-v4 (which reverses the list and takes the first).
    for (auto it = params_.rbegin(); it != params_.rend(); ++it) {
        if (it->name != name) continue;
        for (const char *t : types)
            if (it->type == t) {
                it->lookedUp = true;
                return &*it;
            }
        throw SceneError(it->loc, "parameter " + Decl(*it) + " has the wrong type: expected \"" +
                                      std::string(expected) + " " + name + "\"");
    }
    return nullptr;
}

static void CheckCount(const ParsedParameter &p, size_t count, size_t nPerItem, bool single) {
    if (single && count != nPerItem) {
        std::string what = nPerItem == 1 ? "1 value" : std::to_string(nPerItem) + " values";
        throw SceneError(p.loc, "parameter " + Decl(p) + " needs " + what + ", but " + std::to_string(count) +
                                    (count == 1 ? " was given" : " were given"));
    }
    if (count == 0) throw SceneError(p.loc, "parameter " + Decl(p) + " has no values");
    if (count % nPerItem != 0)
        throw SceneError(p.loc, "parameter " + Decl(p) + " needs a multiple of " + std::to_string(nPerItem) +
                                    " values, but " + std::to_string(count) + " were given");
}

static int ToInt(const ParsedParameter &p, double v) {
    if (!(v >= double(std::numeric_limits<int>::lowest()) && v <= double(std::numeric_limits<int>::max())) ||
        v != std::floor(v))
        throw SceneError(p.loc, "parameter " + Decl(p) + " has a value that is not a 32-bit integer");
    return int(v);
}

// Values must be finite and representable as 32-bit floats (the parser guarantees this for
// parsed scenes; dictionaries built by hand are checked here).
static void CheckFinite(const ParsedParameter &p) {
    for (double v : p.numbers)
        if (!(std::abs(v) <= double(FLT_MAX)))
            throw SceneError(p.loc, "parameter " + Decl(p) + " has a non-finite value");
}

double ParameterDictionary::GetOneFloat(const std::string &name, double def) const {
    const ParsedParameter *p = Lookup(name, {"float"}, "float");
    if (!p) return def;
    CheckCount(*p, p->numbers.size(), 1, true);
    CheckFinite(*p);
    return p->numbers[0];
}

int ParameterDictionary::GetOneInt(const std::string &name, int def) const {
    const ParsedParameter *p = Lookup(name, {"integer"}, "integer");
    if (!p) return def;
    CheckCount(*p, p->numbers.size(), 1, true);
    return ToInt(*p, p->numbers[0]);
}

bool ParameterDictionary::GetOneBool(const std::string &name, bool def) const {
    const ParsedParameter *p = Lookup(name, {"bool"}, "bool");
    if (!p) return def;
    CheckCount(*p, p->bools.size(), 1, true);
    return p->bools[0];
}

std::string ParameterDictionary::GetOneString(const std::string &name, const std::string &def) const {
    const ParsedParameter *p = Lookup(name, {"string"}, "string");
    if (!p) return def;
    CheckCount(*p, p->strings.size(), 1, true);
    return p->strings[0];
}

static std::vector<Vec3f> Vec3Array(const ParsedParameter &p, bool single) {
    CheckCount(p, p.numbers.size(), 3, single);
    CheckFinite(p);
    std::vector<Vec3f> v(p.numbers.size() / 3);
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = Vec3f(Float(p.numbers[3 * i]), Float(p.numbers[3 * i + 1]), Float(p.numbers[3 * i + 2]));
    return v;
}

std::optional<Vec3f> ParameterDictionary::GetOnePoint3f(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"point3", "point"}, "point3");
    if (!p) return std::nullopt;
    return Vec3Array(*p, true)[0];
}

std::optional<Vec3f> ParameterDictionary::GetOneVector3f(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"vector3", "vector"}, "vector3");
    if (!p) return std::nullopt;
    return Vec3Array(*p, true)[0];
}

std::vector<double> ParameterDictionary::GetFloatArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"float"}, "float");
    if (!p) return {};
    CheckCount(*p, p->numbers.size(), 1, false);
    CheckFinite(*p);
    return p->numbers;
}

std::vector<int> ParameterDictionary::GetIntArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"integer"}, "integer");
    if (!p) return {};
    CheckCount(*p, p->numbers.size(), 1, false);
    std::vector<int> v(p->numbers.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = ToInt(*p, p->numbers[i]);
    return v;
}

std::vector<std::string> ParameterDictionary::GetStringArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"string"}, "string");
    if (!p) return {};
    CheckCount(*p, p->strings.size(), 1, false);
    return p->strings;
}

std::vector<Vec3f> ParameterDictionary::GetPoint3fArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"point3", "point"}, "point3");
    return p ? Vec3Array(*p, false) : std::vector<Vec3f>{};
}

std::vector<Vec3f> ParameterDictionary::GetNormal3fArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"normal", "normal3"}, "normal");
    return p ? Vec3Array(*p, false) : std::vector<Vec3f>{};
}

std::vector<Vec3f> ParameterDictionary::GetVector3fArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"vector3", "vector"}, "vector3");
    return p ? Vec3Array(*p, false) : std::vector<Vec3f>{};
}

std::vector<Vec2f> ParameterDictionary::GetPoint2fArray(const std::string &name) const {
    const ParsedParameter *p = Lookup(name, {"point2"}, "point2");
    if (!p) return {};
    CheckCount(*p, p->numbers.size(), 2, false);
    CheckFinite(*p);
    std::vector<Vec2f> v(p->numbers.size() / 2);
    for (size_t i = 0; i < v.size(); ++i) v[i] = Vec2f(Float(p->numbers[2 * i]), Float(p->numbers[2 * i + 1]));
    return v;
}

const ParsedParameter *ParameterDictionary::Find(const std::string &name) const {
    for (auto it = params_.rbegin(); it != params_.rend(); ++it)
        if (it->name == name) {
            it->lookedUp = true;
            return &*it;
        }
    return nullptr;
}

std::string ParameterDictionary::TypeOf(const std::string &name) const {
    for (auto it = params_.rbegin(); it != params_.rend(); ++it)
        if (it->name == name) return it->type;
    return "";
}

void ParameterDictionary::ReportUnused(Diagnostics &diag, const std::string &owner) const {
    // A parameter shadowed by a later one of the same name and type that was used is fine
    // (pbrt-v4); walk backwards remembering the used (name, type) pairs.
    std::set<std::pair<std::string_view, std::string_view>> used;
    std::vector<const ParsedParameter *> unused;
    for (auto it = params_.rbegin(); it != params_.rend(); ++it) {
        if (it->lookedUp) used.emplace(it->name, it->type);
        else if (!used.count({it->name, it->type})) unused.push_back(&*it);
    }
    for (auto it = unused.rbegin(); it != unused.rend(); ++it)
        diag.Warning((*it)->loc, "parameter " + Decl(**it) + " is not used by " + owner);
}

}  // namespace lu
