// Lucerna scene reader: a bounds-checked PLY mesh reader (ASCII, binary little/big endian).
// Written from the PLY format description (Turk 1994); the properties read match pbrt-v4's
// TriQuadMesh::ReadPLY (util/mesh.cpp): x y z, nx ny nz, u v / s t / texture_u texture_v /
// texture_s texture_t, vertex_indices / vertex_index, face_indices.
#include "lucerna/scene/ply.h"

#include <charconv>
#include <cmath>
#include <cfloat>
#include <cstdio>
#include <cstring>

#include "lucerna/scene/gzip.h"
#include "lucerna/scene/tokenizer.h"

namespace lu {

namespace {

enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

int SizeOf(PlyType t) {
    switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 1;
}

bool IsInteger(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

bool ParseType(std::string_view s, PlyType *t) {
    struct { const char *name; PlyType type; } table[] = {
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},     {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},   {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16}, {"int", PlyType::Int32},
        {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},   {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (auto &e : table)
        if (s == e.name) { *t = e.type; return true; }
    return false;
}

struct Property {
    std::string name;
    PlyType type = PlyType::Float32;
    bool isList = false;
    PlyType countType = PlyType::UInt8;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

std::vector<std::string_view> SplitWords(std::string_view line) {
    std::vector<std::string_view> w;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        size_t b = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > b) w.push_back(line.substr(b, i - b));
    }
    return w;
}

// double -> float without undefined behavior: false if out of float range or not finite.
bool ToFloat(double d, Float *f) {
    if (!(std::abs(d) <= double(FLT_MAX))) return false;
    *f = Float(d);
    return true;
}

std::string ShowIndex(double v) {
    if (std::abs(v) < 1e15 && v == std::floor(v)) return std::to_string((long long)v);
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

std::string Shorten(std::string_view s) {
    std::string r;
    for (char c : s.substr(0, 40)) r.push_back((unsigned char)c >= 0x20 && (unsigned char)c < 0x7f ? c : '?');
    if (s.size() > 40) r += "...";
    return r;
}

class PlyReader {
  public:
    PlyReader(std::string_view data, const std::string &name, const FileLoc &from, Diagnostics *diag)
        : data_(data), name_(name), from_(from), diag_(diag) {}

    PlyMesh Read() {
        ParseHeader();
        for (const Element &e : elements_) {
            if (&e == vertexElement_) ReadVertices(e);
            else if (&e == faceElement_) ReadFaces(e);
            else SkipElement(e);
        }
        // Indices were checked against the vertex element's declared count as they were read.
        if (skippedFaces_ && diag_)
            diag_->Warning(from_, "PLY file \"" + name_ + "\": skipped " + std::to_string(skippedFaces_) +
                                      " faces with fewer than 3 vertices");
        if (mesh_.polygonCount && diag_)
            diag_->Warning(from_, "PLY file \"" + name_ + "\": " + std::to_string(mesh_.polygonCount) +
                                      " faces with more than 4 vertices were triangulated as fans");
        return std::move(mesh_);
    }

  private:
    [[noreturn]] void Fail(const std::string &msg) const {
        throw SceneError(from_, "PLY file \"" + name_ + "\": " + msg);
    }

    // ---- header ----
    void ParseHeader() {
        if (data_.size() >= 2 && (unsigned char)data_[0] == 0x1f && (unsigned char)data_[1] == 0x8b)
            Fail("the file is gzip-compressed, which is not supported; decompress it first (gunzip)");
        constexpr size_t maxHeader = size_t(1) << 20;
        size_t pos = 0;
        int lineNo = 0;
        bool haveFormat = false;
        while (true) {
            size_t nl = data_.find('\n', pos);
            if (nl == std::string_view::npos || nl > maxHeader) {
                if (lineNo == 0 && data_.substr(0, 3) != "ply") Fail("not a PLY file (the first line is not \"ply\")");
                Fail("corrupt header: no \"end_header\" line" +
                     std::string(nl == std::string_view::npos ? " before the end of the file" : " in the first 1 MiB"));
            }
            std::string_view line = data_.substr(pos, nl - pos);
            pos = nl + 1;
            ++lineNo;
            for (char c : line)
                if ((unsigned char)c < 0x20 && c != '\t' && c != '\r')
                    Fail(lineNo == 1 ? "not a PLY file (the first line is not \"ply\")"
                                     : "corrupt header at line " + std::to_string(lineNo) + ": control character");
            std::vector<std::string_view> w = SplitWords(line);
            if (lineNo == 1) {
                if (w.size() != 1 || w[0] != "ply") Fail("not a PLY file (the first line is not \"ply\")");
                continue;
            }
            auto corrupt = [&](const std::string &why) {
                Fail("corrupt header at line " + std::to_string(lineNo) + ": " + why);
            };
            if (w.empty()) continue;
            if (w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") {
                if (!haveFormat) corrupt("no \"format\" line before \"end_header\"");
                bodyStart_ = pos;
                break;
            }
            if (w[0] == "format") {
                if (w.size() != 3) corrupt("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
                if (w[1] == "ascii") format_ = Format::Ascii;
                else if (w[1] == "binary_little_endian") format_ = Format::BinaryLE;
                else if (w[1] == "binary_big_endian") format_ = Format::BinaryBE;
                else corrupt("unknown format \"" + Shorten(w[1]) + "\"");
                haveFormat = true;
            } else if (w[0] == "element") {
                if (w.size() != 3) corrupt("expected \"element NAME COUNT\"");
                Element e;
                e.name = std::string(w[1]);
                uint64_t count = 0;
                auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), count);
                if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size() || count > (uint64_t(1) << 40))
                    corrupt("bad element count \"" + Shorten(w[2]) + "\"");
                e.count = count;
                for (const Element &o : elements_)
                    if (o.name == e.name) corrupt("element \"" + Shorten(e.name) + "\" is declared twice");
                elements_.push_back(std::move(e));
            } else if (w[0] == "property") {
                if (elements_.empty()) corrupt("\"property\" before any \"element\"");
                Property p;
                if (w.size() == 5 && w[1] == "list") {
                    p.isList = true;
                    if (!ParseType(w[2], &p.countType)) corrupt("unknown type \"" + Shorten(w[2]) + "\"");
                    if (!IsInteger(p.countType)) corrupt("list count type must be an integer type");
                    if (!ParseType(w[3], &p.type)) corrupt("unknown type \"" + Shorten(w[3]) + "\"");
                    p.name = std::string(w[4]);
                } else if (w.size() == 3) {
                    if (!ParseType(w[1], &p.type)) corrupt("unknown type \"" + Shorten(w[1]) + "\"");
                    p.name = std::string(w[2]);
                } else {
                    corrupt("expected \"property TYPE NAME\" or \"property list COUNTTYPE TYPE NAME\"");
                }
                elements_.back().props.push_back(std::move(p));
            } else {
                corrupt("unknown keyword \"" + Shorten(w[0]) + "\"");
            }
        }
        for (Element &e : elements_) {
            if (e.name == "vertex") vertexElement_ = &e;
            if (e.name == "face") faceElement_ = &e;
        }
        if (!vertexElement_) Fail("no \"element vertex\"");
        if (vertexElement_->count > UINT32_MAX) Fail("too many vertices");
        if (!faceElement_) Fail("no \"element face\"");
        pos_ = bodyStart_;
    }

    // ---- body values ----
    void CheckFits(const Element &e) {
        size_t remaining = data_.size() - pos_;
        uint64_t minRecord = 0;
        for (const Property &p : e.props) minRecord += p.isList ? SizeOf(p.countType) : SizeOf(p.type);
        if (format_ == Format::Ascii) minRecord = e.props.size() * 2;  // a digit and a separator each
        if (minRecord == 0 || e.count == 0) return;
        // An ASCII record's last separator may be missing at the very end of the file.
        if (e.count > (remaining + (format_ == Format::Ascii ? 1 : 0)) / minRecord)
            Fail("element \"" + Shorten(e.name) + "\" declares " + std::to_string(e.count) + " records, more than the " +
                 std::to_string(remaining) + " bytes of data after the header can hold");
    }

    [[noreturn]] void Truncated() const {
        Fail("truncated: the file ends inside element \"" + Shorten(cur_->name) + "\" (record " +
             std::to_string(record_ + 1) + " of " + std::to_string(cur_->count) + ")");
    }

    double ReadValue(PlyType t) {
        if (format_ == Format::Ascii) return ReadAscii(t);
        int n = SizeOf(t);
        if (data_.size() - pos_ < size_t(n)) Truncated();
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, n);
        pos_ += n;
        if (format_ == Format::BinaryBE)
            for (int i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
        case PlyType::Int8: { int8_t v; std::memcpy(&v, b, 1); return v; }
        case PlyType::UInt8: return b[0];
        case PlyType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
        case PlyType::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
        case PlyType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
        case PlyType::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
        case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
        case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0;
    }

    double ReadAscii(PlyType t) {
        const char *s = data_.data();
        size_t n = data_.size();
        while (pos_ < n && (s[pos_] == ' ' || s[pos_] == '\t' || s[pos_] == '\r' || s[pos_] == '\n')) ++pos_;
        if (pos_ >= n) Truncated();
        size_t b = pos_;
        while (pos_ < n && s[pos_] != ' ' && s[pos_] != '\t' && s[pos_] != '\r' && s[pos_] != '\n') ++pos_;
        std::string_view tok(s + b, pos_ - b);
        const char *first = tok.data(), *last = tok.data() + tok.size();
        if (first != last && *first == '+') ++first;
        double v = 0;
        auto r = std::from_chars(first, last, v);
        bool ok = r.ptr == last && (r.ec == std::errc() || r.ec == std::errc::result_out_of_range);
        if (r.ec == std::errc::result_out_of_range) v = std::strtod(std::string(first, last).c_str(), nullptr);
        if (!ok || (IsInteger(t) && v != std::floor(v)))
            Fail("corrupt data: \"" + Shorten(tok) + "\" is not " + (IsInteger(t) ? "an integer" : "a number") +
                 " (element \"" + Shorten(cur_->name) + "\", record " + std::to_string(record_ + 1) + ")");
        return v;
    }

    // Reads a list's length and checks that that many values can follow.
    uint64_t ReadListCount(const Property &p) {
        double c = ReadValue(p.countType);
        if (!(c >= 0)) Fail("corrupt data: negative list length in element \"" + Shorten(cur_->name) + "\"");
        if (c > double(data_.size())) Truncated();
        uint64_t n = uint64_t(c);
        size_t remaining = data_.size() - pos_;
        uint64_t minBytes = format_ == Format::Ascii ? 1 : SizeOf(p.type);
        if (n > 0 && n > remaining / minBytes + 1) Truncated();
        return n;
    }

    void SkipValues(PlyType t, uint64_t n) {
        if (format_ != Format::Ascii) {
            uint64_t bytes = n * SizeOf(t);
            if (bytes > data_.size() - pos_) Truncated();
            pos_ += bytes;
        } else {
            for (uint64_t i = 0; i < n; ++i) ReadAscii(t);
        }
    }

    void SkipElement(const Element &e) {
        cur_ = &e;
        if (e.props.empty()) return;
        CheckFits(e);
        for (record_ = 0; record_ < e.count; ++record_)
            for (const Property &p : e.props) SkipValues(p.type, p.isList ? ReadListCount(p) : 1);
    }

    // ---- vertices ----
    void ReadVertices(const Element &e) {
        cur_ = &e;
        CheckFits(e);
        enum Slot { None = -1, X, Y, Z, NX, NY, NZ, U, V, NumSlots };
        std::vector<int> slot(e.props.size(), None);
        bool have[NumSlots] = {};
        for (size_t i = 0; i < e.props.size(); ++i) {
            const std::string &n = e.props[i].name;
            int s = n == "x" ? X : n == "y" ? Y : n == "z" ? Z : n == "nx" ? NX : n == "ny" ? NY : n == "nz" ? NZ
                  : (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") ? U
                  : (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") ? V
                                                                                     : None;
            if (s != None && (e.props[i].isList || have[s])) s = None;  // lists and duplicates are skipped
            if (s != None) have[s] = true;
            slot[i] = s;
        }
        if (!have[X] || !have[Y] || !have[Z]) Fail("the vertex element has no x, y and z properties");
        bool normals = have[NX] && have[NY] && have[NZ], uvs = have[U] && have[V];
        mesh_.P.resize(e.count);
        if (normals) mesh_.N.resize(e.count);
        if (uvs) mesh_.uv.resize(e.count);
        double val[NumSlots] = {};
        for (record_ = 0; record_ < e.count; ++record_) {
            for (size_t i = 0; i < e.props.size(); ++i) {
                const Property &p = e.props[i];
                if (p.isList) SkipValues(p.type, ReadListCount(p));
                else if (slot[i] == None) SkipValues(p.type, 1);
                else val[slot[i]] = ReadValue(p.type);
            }
            Vec3f &P = mesh_.P[record_];
            if (!ToFloat(val[X], &P.x) || !ToFloat(val[Y], &P.y) || !ToFloat(val[Z], &P.z))
                Fail("vertex " + std::to_string(record_) + " has a non-finite coordinate");
            if (normals) {
                Vec3f &N = mesh_.N[record_];
                if (!ToFloat(val[NX], &N.x) || !ToFloat(val[NY], &N.y) || !ToFloat(val[NZ], &N.z))
                    Fail("vertex " + std::to_string(record_) + " has a non-finite normal");
            }
            if (uvs) {
                Vec2f &uv = mesh_.uv[record_];
                if (!ToFloat(val[U], &uv.x) || !ToFloat(val[V], &uv.y))
                    Fail("vertex " + std::to_string(record_) + " has a non-finite texture coordinate");
            }
        }
    }

    // ---- faces ----
    void ReadFaces(const Element &e) {
        cur_ = &e;
        CheckFits(e);
        int indexProp = -1, faceIndexProp = -1;
        for (size_t i = 0; i < e.props.size(); ++i) {
            const Property &p = e.props[i];
            if ((p.name == "vertex_indices" || p.name == "vertex_index") && indexProp < 0) {
                if (!p.isList) Fail("the face property \"" + p.name + "\" is not a list");
                if (!IsInteger(p.type)) Fail("the face property \"" + p.name + "\" has a non-integer type");
                indexProp = int(i);
            } else if (p.name == "face_indices" && !p.isList && IsInteger(p.type) && faceIndexProp < 0) {
                faceIndexProp = int(i);
            }
        }
        if (indexProp < 0) Fail("the face element has no \"vertex_indices\" list");
        const uint64_t nVertices = vertexElement_->count;
        if (format_ != Format::Ascii) mesh_.indices.reserve(e.count * 3);
        std::vector<uint32_t> poly;
        for (record_ = 0; record_ < e.count; ++record_) {
            int faceIndex = 0;
            poly.clear();
            for (size_t i = 0; i < e.props.size(); ++i) {
                const Property &p = e.props[i];
                if (int(i) == indexProp) {
                    uint64_t n = ReadListCount(p);
                    for (uint64_t k = 0; k < n; ++k) {
                        double idx = ReadValue(p.type);
                        if (!(idx >= 0 && idx < double(nVertices)))
                            Fail("face " + std::to_string(record_) + ": vertex index " +
                                 ShowIndex(idx) + " is out of range (the file has " +
                                 std::to_string(nVertices) + " vertices)");
                        poly.push_back(uint32_t(idx));
                    }
                } else if (int(i) == faceIndexProp) {
                    double fi = ReadValue(p.type);
                    faceIndex = fi >= INT32_MIN && fi <= INT32_MAX ? int(fi) : 0;
                } else {
                    SkipValues(p.type, p.isList ? ReadListCount(p) : 1);
                }
            }
            if (poly.size() < 3) {
                ++skippedFaces_;
                continue;
            }
            if (poly.size() == 4) ++mesh_.quadCount;
            if (poly.size() > 4) ++mesh_.polygonCount;
            for (size_t k = 1; k + 1 < poly.size(); ++k) {
                mesh_.indices.push_back(poly[0]);
                mesh_.indices.push_back(poly[k]);
                mesh_.indices.push_back(poly[k + 1]);
                if (faceIndexProp >= 0) mesh_.faceIndices.push_back(faceIndex);
            }
        }
    }

    std::string_view data_;
    std::string name_;
    FileLoc from_;
    Diagnostics *diag_;
    std::vector<Element> elements_;
    const Element *vertexElement_ = nullptr, *faceElement_ = nullptr;
    Format format_ = Format::Ascii;
    size_t bodyStart_ = 0, pos_ = 0;
    const Element *cur_ = nullptr;
    uint64_t record_ = 0;
    size_t skippedFaces_ = 0;
    PlyMesh mesh_;
};

}  // namespace

PlyMesh ReadPlyMeshFromMemory(std::string_view data, const std::string &name, const FileLoc &referencedFrom,
                              Diagnostics *diag) {
    return PlyReader(data, name, referencedFrom, diag).Read();
}

PlyMesh ReadPlyMesh(const std::string &path, const FileLoc &referencedFrom, Diagnostics *diag) {
    std::string data;
    bool corrupt = false;
    std::string why = ReadFileGunzipped(path, &data, MaxPlyFileBytes, &corrupt);
    if (!why.empty())
        throw SceneError(referencedFrom, "PLY file \"" + path + "\": " + (corrupt ? "" : "cannot open: ") + why);
    return ReadPlyMeshFromMemory(data, path, referencedFrom, diag);
}

}  // namespace lu
