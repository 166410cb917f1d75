// Lucerna scene reader: the pbrt-v4 text-format parser. Directive syntax follows pbrt-v4's
// parser.cpp; the graphics state (CTM, attributes, materials, area lights, instancing, named
// coordinate systems) follows BasicSceneBuilder in pbrt-v4's scene.cpp, with every bad input a
// SceneError at its file:line:col instead of an exit.
#include "lucerna/scene/parser.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <unordered_map>

#include "lucerna/scene/tokenizer.h"

namespace lu {

// ---- Paths ----

std::string DirectoryOf(const std::string &path) {
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return "";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

std::string ResolvePath(const std::string &dir, const std::string &path) {
    if (path.empty() || path[0] == '/' || dir.empty()) return path;
    if (dir.back() == '/') return dir + path;
    return dir + "/" + path;
}

static std::string CanonicalPath(const std::string &path) {
    std::error_code ec;
    std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

static bool FileExists(const std::string &path) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

namespace {

// ---- Transforms in double precision (pbrt-v4's transform.cpp conventions) ----

struct DMatrix {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    bool operator==(const DMatrix &o) const { return std::memcmp(m, o.m, sizeof(m)) == 0; }
};

DMatrix Mul(const DMatrix &a, const DMatrix &b) {
    DMatrix r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

// Gauss-Jordan with partial pivoting; false if singular or not finite.
bool Invert(const DMatrix &a, DMatrix *out) {
    double m[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            if (!std::isfinite(a.m[i][j])) return false;
            m[i][j] = a.m[i][j];
            m[i][j + 4] = i == j;
        }
    double scale = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) scale = std::max(scale, std::abs(a.m[i][j]));
    if (scale == 0) return false;
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
        if (std::abs(m[piv][c]) <= 1e-300) return false;
        if (piv != c)
            for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[piv][j]);
        double inv = 1 / m[c][c];
        for (int j = 0; j < 8; ++j) m[c][j] *= inv;
        for (int r = 0; r < 4; ++r)
            if (r != c && m[r][c] != 0) {
                double f = m[r][c];
                for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
            }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            out->m[i][j] = m[i][j + 4];
            if (!std::isfinite(out->m[i][j])) return false;
        }
    return true;
}

// True if every entry is finite and representable as a Float.
bool FitsFloat(const DMatrix &d) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!(std::abs(d.m[i][j]) <= double(FLT_MAX))) return false;
    return true;
}

Matrix4 ToMatrix4(const DMatrix &d) {  // callers check FitsFloat (NaN passes through)
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double x = d.m[i][j];
            r.m[i][j] = std::abs(x) <= double(FLT_MAX) ? Float(x) : std::numeric_limits<Float>::quiet_NaN();
        }
    return r;
}

DMatrix TranslateM(double x, double y, double z) {
    DMatrix r;
    r.m[0][3] = x;
    r.m[1][3] = y;
    r.m[2][3] = z;
    return r;
}

DMatrix ScaleM(double x, double y, double z) {
    DMatrix r;
    r.m[0][0] = x;
    r.m[1][1] = y;
    r.m[2][2] = z;
    return r;
}

// Rotation by theta degrees about a normalized axis (right-handed sense, as pbrt-v4's Rotate).
DMatrix RotateM(double thetaDeg, double ax, double ay, double az) {
    double theta = thetaDeg * (3.14159265358979323846 / 180);
    double s = std::sin(theta), c = std::cos(theta);
    DMatrix r;
    r.m[0][0] = ax * ax + (1 - ax * ax) * c;
    r.m[0][1] = ax * ay * (1 - c) - az * s;
    r.m[0][2] = ax * az * (1 - c) + ay * s;
    r.m[1][0] = ax * ay * (1 - c) + az * s;
    r.m[1][1] = ay * ay + (1 - ay * ay) * c;
    r.m[1][2] = ay * az * (1 - c) - ax * s;
    r.m[2][0] = ax * az * (1 - c) - ay * s;
    r.m[2][1] = ay * az * (1 - c) + ax * s;
    r.m[2][2] = az * az + (1 - az * az) * c;
    return r;
}

struct TransformPair { DMatrix m[2]; };

struct Triple { double x, y, z; };
Triple Sub(Triple a, Triple b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Triple CrossT(Triple a, Triple b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double LengthT(Triple a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
Triple NormalizeT(Triple a) { double l = LengthT(a); return {a.x / l, a.y / l, a.z / l}; }

// ---- Graphics state (BasicSceneBuilder::GraphicsState) ----

using ParamList = std::vector<ParsedParameter>;
using SharedParams = std::shared_ptr<const ParamList>;

// Attribute defaults as a chain of the Attribute directives in effect (newest last), so that
// pushing the graphics state and adding defaults are O(1).
struct AttributeNode {
    ParamList params;
    std::shared_ptr<const AttributeNode> prev;
    size_t cost = 0;  // budget units of this node and all before it
};
using Attributes = std::shared_ptr<const AttributeNode>;

struct GraphicsState {
    DMatrix ctm[2];                     // start and end time (pbrt's TransformSet)
    bool activeStart = true, activeEnd = true;
    bool reverseOrientation = false;
    int materialIndex = -1;
    std::string materialName;
    FileLoc materialLoc;
    std::string areaLightName;
    SharedParams areaLightParams;
    FileLoc areaLightLoc;
    std::string insideMedium, outsideMedium;
    Attributes shapeAttributes, lightAttributes, materialAttributes, mediumAttributes, textureAttributes;
};

struct PushedState {
    char kind;  // 'a' AttributeBegin/TransformBegin, 'o' ObjectBegin
    FileLoc loc;
    GraphicsState state;
};

const char *const KnownDirectives[] = {
    "Accelerator", "ActiveTransform", "AreaLightSource", "Attribute", "AttributeBegin", "AttributeEnd", "Camera",
    "ColorSpace", "ConcatTransform", "CoordSysTransform", "CoordinateSystem", "Film", "Identity", "Import",
    "Include", "Integrator", "LightSource", "LookAt", "MakeNamedMaterial", "MakeNamedMedium", "Material",
    "MediumInterface", "NamedMaterial", "ObjectBegin", "ObjectEnd", "ObjectInstance", "Option", "PixelFilter",
    "ReverseOrientation", "Rotate", "Sampler", "Scale", "Shape", "Texture", "Transform", "TransformBegin",
    "TransformEnd", "TransformTimes", "Translate", "WorldBegin", "WorldEnd"};

bool IsDirectiveName(std::string_view w) {
    for (const char *d : KnownDirectives)
        if (w == d) return true;
    return false;
}

// A token as shown in messages: strings keep their quotes, long ones are shortened.
std::string Show(const Token &t) {
    std::string s(t.raw);
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    if (t.kind == Token::Word) return "\"" + s + "\"";
    return s;
}

enum class NumErr { Ok, NotANumber, NonFinite, OutOfRange };

// Parses a whole token as a floating-point number (decimal, or hexadecimal as pbrt-v4 allows).
NumErr ParseNumber(std::string_view s, double *v) {
    if (s.empty()) return NumErr::NotANumber;
    const char *b = s.data(), *e = s.data() + s.size();
    bool neg = false;
    if (*b == '+' || *b == '-') {
        neg = *b == '-';
        ++b;
        if (b == e || *b == '+' || *b == '-') return NumErr::NotANumber;
    }
    std::chars_format fmt = std::chars_format::general;
    if (e - b > 2 && b[0] == '0' && (b[1] == 'x' || b[1] == 'X')) {
        b += 2;
        fmt = std::chars_format::hex;
    }
    double x = 0;
    auto r = std::from_chars(b, e, x, fmt);
    if (r.ptr != e) return NumErr::NotANumber;
    if (r.ec == std::errc::result_out_of_range) {
        // Underflow is fine (rounds toward zero, as strtod does); overflow is not.
        std::string copy(b, e);
        double y = fmt == std::chars_format::hex ? std::strtod(("0x" + copy).c_str(), nullptr)
                                                 : std::strtod(copy.c_str(), nullptr);
        if (!std::isfinite(y) || std::abs(y) > 1) return NumErr::OutOfRange;
        x = y;
    } else if (r.ec != std::errc()) {
        return NumErr::NotANumber;
    }
    if (std::isnan(x) || std::isinf(x)) return NumErr::NonFinite;
    if (std::abs(x) > double(FLT_MAX)) return NumErr::OutOfRange;
    *v = neg ? -x : x;
    return NumErr::Ok;
}

// Integers as pbrt-v4's parseInt: optional sign, decimal digits, 32-bit range.
bool ParseInteger(std::string_view s, double *v) {
    size_t i = 0;
    bool neg = false;
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) { neg = s[0] == '-'; i = 1; }
    if (i >= s.size()) return false;
    int64_t value = 0;
    for (; i < s.size(); ++i) {
        if (s[i] < '0' || s[i] > '9') return false;
        value = value * 10 + (s[i] - '0');
        if (value > int64_t(1) << 31) return false;
    }
    if (neg) value = -value;
    if (value > INT32_MAX || value < INT32_MIN) return false;
    *v = double(value);
    return true;
}

std::string NumErrText(NumErr e, const Token &t) {
    switch (e) {
    case NumErr::NonFinite: return "non-finite number " + Show(t);
    case NumErr::OutOfRange: return "number " + Show(t) + " is out of range";
    default: return Show(t) + " is not a number";
    }
}

enum class ValueKind { Numbers, Integers, Bools, Strings, Spectrum };

struct TypeInfo {
    const char *name;
    ValueKind kind;
    int nPerItem;   // values per item (count must be a positive multiple)
    int exactly;    // 0: any multiple; else the exact count
};

const TypeInfo ParamTypes[] = {
    {"integer", ValueKind::Integers, 1, 0}, {"float", ValueKind::Numbers, 1, 0},
    {"point2", ValueKind::Numbers, 2, 0},   {"vector2", ValueKind::Numbers, 2, 0},
    {"point3", ValueKind::Numbers, 3, 0},   {"point", ValueKind::Numbers, 3, 0},
    {"vector3", ValueKind::Numbers, 3, 0},  {"vector", ValueKind::Numbers, 3, 0},
    {"normal", ValueKind::Numbers, 3, 0},   {"normal3", ValueKind::Numbers, 3, 0},
    {"bool", ValueKind::Bools, 1, 0},       {"string", ValueKind::Strings, 1, 0},
    {"rgb", ValueKind::Numbers, 3, 3},      {"blackbody", ValueKind::Numbers, 1, 1},
    {"spectrum", ValueKind::Spectrum, 2, 0}, {"texture", ValueKind::Strings, 1, 1},
};

const TypeInfo *FindType(std::string_view t) {
    for (const TypeInfo &ti : ParamTypes)
        if (t == ti.name) return &ti;
    return nullptr;
}

// ---- Token stream of one file, with one token of lookahead ----

class TokenStream {
  public:
    explicit TokenStream(Tokenizer &t) : tok_(t) {}
    bool Next(Token *t) {
        if (havePeek_) {
            *t = peek_;
            havePeek_ = false;
            return true;
        }
        return tok_.Next(t);
    }
    bool Peek(Token *t) {
        if (!havePeek_) {
            if (!tok_.Next(&peek_)) return false;
            havePeek_ = true;
        }
        *t = peek_;
        return true;
    }
    Tokenizer &Source() { return tok_; }
    [[noreturn]] void Fail(const FileLoc &loc, const std::string &msg) { tok_.Fail(loc.line, loc.col, msg); }
    [[noreturn]] void Fail(const Token &t, const std::string &msg) { tok_.Fail(t.line, t.col, msg); }

  private:
    Tokenizer &tok_;
    Token peek_;
    bool havePeek_ = false;
};

// ---- The parser ----

class Parser {
  public:
    Parser(Diagnostics &diag, const ParseOptions &opt) : diag_(diag), opt_(opt) {}

    void ParseTop(Tokenizer &tz, const std::string &path) {
        mainDir_ = DirectoryOf(path);
        desc_.baseDirectory = mainDir_;
        includeChain_.push_back(CanonicalPath(path));
        ParseFile(tz, mainDir_);
        includeChain_.pop_back();
    }

    SceneDescription Finish();

  private:
    // ---- statements ----
    void ParseFile(Tokenizer &tz, const std::string &dir);
    void Statement(TokenStream &ts, const Token &dir, const std::string &fileDir);

    // ---- argument helpers ----
    double ReadNumber(TokenStream &ts, const Token &directive, int count);
    void ReadNumbers(TokenStream &ts, const Token &directive, double *v, int n, bool allowBrackets);
    std::string ReadString(TokenStream &ts, const Token &directive, const char *what);
    ParamList ReadParams(TokenStream &ts);
    void ReadValues(TokenStream &ts, ParsedParameter &p, const TypeInfo &ti, const Token &decl);

    // ---- state helpers ----
    void RequireWorld(TokenStream &ts, const Token &dir) {
        if (!inWorld_) ts.Fail(dir, "\"" + std::string(dir.raw) + "\" is not allowed before WorldBegin");
    }
    void RequireOptions(TokenStream &ts, const Token &dir) {
        if (inWorld_) ts.Fail(dir, "\"" + std::string(dir.raw) + "\" is not allowed after WorldBegin");
    }
    void ApplyTransform(TokenStream &ts, const Token &dir, const DMatrix &m, bool replace) {
        DMatrix r[2] = {state_.ctm[0], state_.ctm[1]};
        for (int i = 0; i < 2; ++i)
            if (i == 0 ? state_.activeStart : state_.activeEnd) r[i] = replace ? m : Mul(state_.ctm[i], m);
        if (!FitsFloat(r[0]) || !FitsFloat(r[1]))
            ts.Fail(dir, "\"" + std::string(dir.raw) + "\" makes the transformation overflow");
        state_.ctm[0] = r[0];
        state_.ctm[1] = r[1];
    }
    Transform CurrentTransform(const FileLoc &loc, const char *what);
    ParameterDictionary MakeDict(ParamList params, const Attributes &attributes, const FileLoc &loc);
    void CountValues(size_t n, const FileLoc &loc) {
        totalValues_ += n;
        if (totalValues_ > opt_.maxTotalValues)
            throw SceneError(loc, "the scene has more than " + std::to_string(opt_.maxTotalValues) +
                                      " parameter values; refusing to read further");
    }
    // Budget units: one per value and one per parameter.
    static size_t Cost(const ParsedParameter &p) { return 1 + p.numbers.size() + p.strings.size() + p.bools.size(); }
    static size_t ValueCount(const ParamList &ps) {
        size_t n = 0;
        for (const ParsedParameter &p : ps) n += Cost(p);
        return n;
    }
    void Push(TokenStream &ts, char kind, const Token &dir) {
        if ((int)pushed_.size() >= opt_.maxAttributeDepth)
            ts.Fail(dir, "\"" + std::string(dir.raw) + "\" nested more than " + std::to_string(opt_.maxAttributeDepth) +
                             " deep");
        pushed_.push_back(PushedState{kind, dir.Loc(), state_});
    }
    static std::string OpenName(const PushedState &p) { return p.kind == 'o' ? "ObjectBegin" : "AttributeBegin"; }
    static std::string Where(const FileLoc &loc) {
        return "line " + std::to_string(loc.line) + (loc.file ? " of " + *loc.file : "");
    }
    void IncludeFile(TokenStream &ts, const Token &dir, const std::string &fileDir, bool isImport);

    Diagnostics &diag_;
    ParseOptions opt_;
    SceneDescription desc_;
    GraphicsState state_;
    std::vector<PushedState> pushed_;
    size_t pushFloor_ = 0;  // pushes below this belong to an importing file
    bool inWorld_ = false, sawDirective_ = false;
    std::map<std::string, TransformPair> namedCoordinateSystems_;
    std::string activeInstance_;  // name of the ObjectBegin being defined, "" if none
    std::set<std::string> floatTextureNames_, spectrumTextureNames_, mediumNames_;
    std::vector<std::pair<std::string, FileLoc>> namedMaterialUses_;  // (name, NamedMaterial loc) per shape
    std::string mainDir_;
    std::vector<std::string> includeChain_;
    size_t totalValues_ = 0;
    bool warnedTransformBegin_ = false, warnedMotion_ = false, warnedTransformTimes_ = false, warnedActiveTransform_ = false;
    bool colorSpaceSet_ = false, rgbSeen_ = false;
};

void Parser::ParseFile(Tokenizer &tz, const std::string &dir) {
    TokenStream ts(tz);
    Token t;
    while (ts.Next(&t)) {
        if (t.kind != Token::Word) {
            if (t.kind == Token::String)
                ts.Fail(t, "unexpected string " + Show(t) + " where a directive was expected");
            ts.Fail(t, "unexpected '" + std::string(t.raw) + "' where a directive was expected");
        }
        sawDirective_ = true;
        Statement(ts, t, dir);
    }
}

double Parser::ReadNumber(TokenStream &ts, const Token &directive, int count) {
    Token t;
    if (!ts.Next(&t))
        ts.Fail(directive, "unexpected end of file: \"" + std::string(directive.raw) + "\" needs " +
                               std::to_string(count) + (count == 1 ? " number" : " numbers"));
    double v = 0;
    NumErr e = t.kind == Token::Word ? ParseNumber(t.raw, &v) : NumErr::NotANumber;
    if (e != NumErr::Ok)
        ts.Fail(t, "\"" + std::string(directive.raw) + "\" needs " + std::to_string(count) +
                       (count == 1 ? " number" : " numbers") + ": " + NumErrText(e, t));
    return v;
}

void Parser::ReadNumbers(TokenStream &ts, const Token &directive, double *v, int n, bool allowBrackets) {
    Token t;
    bool bracket = false;
    if (allowBrackets && ts.Peek(&t) && t.kind == Token::OpenBracket) {
        ts.Next(&t);
        bracket = true;
    }
    Token open = t;
    for (int i = 0; i < n; ++i) v[i] = ReadNumber(ts, directive, n);
    if (bracket) {
        if (!ts.Next(&t)) ts.Fail(open, "unterminated '[': missing ']' before the end of the file");
        if (t.kind != Token::CloseBracket)
            ts.Fail(t, "\"" + std::string(directive.raw) + "\" needs exactly " + std::to_string(n) +
                           " numbers; expected ']' but got " + Show(t));
    }
}

std::string Parser::ReadString(TokenStream &ts, const Token &directive, const char *what) {
    Token t;
    if (!ts.Next(&t))
        ts.Fail(directive, "unexpected end of file: \"" + std::string(directive.raw) + "\" needs a quoted " + what);
    if (t.kind != Token::String)
        ts.Fail(t, "\"" + std::string(directive.raw) + "\" needs a quoted " + what + ", but got " + Show(t));
    return t.Text();
}

ParamList Parser::ReadParams(TokenStream &ts) {
    ParamList params;
    Token t;
    while (ts.Peek(&t) && t.kind == Token::String) {
        ts.Next(&t);
        std::string decl = t.Text();
        // "type name": exactly two words separated by spaces or tabs.
        std::vector<std::string> words;
        size_t i = 0;
        while (i < decl.size()) {
            while (i < decl.size() && (decl[i] == ' ' || decl[i] == '\t')) ++i;
            size_t b = i;
            while (i < decl.size() && decl[i] != ' ' && decl[i] != '\t') ++i;
            if (i > b) words.push_back(decl.substr(b, i - b));
        }
        if (words.size() != 2)
            ts.Fail(t, "bad parameter declaration " + Show(t) + ": expected \"type name\", like \"float radius\"");
        const TypeInfo *ti = FindType(words[0]);
        if (!ti) {
            std::string hint = words[0] == "color" ? " (pbrt-v3 syntax: use \"rgb\")" : "";
            ts.Fail(t, "unknown parameter type \"" + words[0] + "\" in " + Show(t) + hint);
        }
        ParsedParameter p;
        p.type = words[0];
        p.name = words[1];
        p.loc = t.Loc();
        ReadValues(ts, p, *ti, t);
        CountValues(Cost(p), p.loc);
        if (p.type == "rgb") rgbSeen_ = true;
        params.push_back(std::move(p));
    }
    return params;
}

void Parser::ReadValues(TokenStream &ts, ParsedParameter &p, const TypeInfo &ti, const Token &decl) {
    const std::string what = "parameter \"" + p.type + " " + p.name + "\"";
    // Value errors are reported at the parameter's loc; the value's position is added when it is
    // on another line.
    auto valueError = [&](const Token &v, const std::string &msg) {
        std::string at = v.line != decl.line ? " (at line " + std::to_string(v.line) + ", column " +
                                                   std::to_string(v.col) + ")"
                                             : "";
        ts.Fail(decl, what + ": " + msg + at);
    };
    bool spectrumStrings = false;
    auto addValue = [&](const Token &v, const Token *open) {
        ValueKind kind = ti.kind;
        if (kind == ValueKind::Spectrum) {
            if (p.numbers.empty() && p.strings.empty()) spectrumStrings = v.kind == Token::String;
            kind = spectrumStrings ? ValueKind::Strings : ValueKind::Numbers;
        }
        switch (kind) {
        case ValueKind::Numbers:
        case ValueKind::Integers: {
            if (v.kind == Token::String) valueError(v, "expected a number, but got the string " + Show(v));
            double x = 0;
            if (kind == ValueKind::Integers) {
                if (!ParseInteger(v.raw, &x)) {
                    NumErr e = ParseNumber(v.raw, &x);
                    if (e == NumErr::Ok) valueError(v, "expected an integer, but got " + Show(v));
                    std::string hint = open && IsDirectiveName(v.raw)
                                           ? " (missing ']' for the '[' at line " + std::to_string(open->line) + "?)"
                                           : "";
                    if (e == NumErr::NotANumber) valueError(v, "expected an integer, but got " + Show(v) + hint);
                    valueError(v, NumErrText(e, v));
                }
            } else {
                NumErr e = ParseNumber(v.raw, &x);
                if (e != NumErr::Ok) {
                    std::string hint = open && IsDirectiveName(v.raw)
                                           ? " (missing ']' for the '[' at line " + std::to_string(open->line) + "?)"
                                           : "";
                    if (e == NumErr::NotANumber) valueError(v, "expected a number, but got " + Show(v) + hint);
                    valueError(v, NumErrText(e, v));
                }
            }
            p.numbers.push_back(x);
            break;
        }
        case ValueKind::Bools: {
            std::string_view s = v.raw;
            if (v.kind == Token::String) s = s.substr(1, s.size() - 2);
            if (s == "true") p.bools.push_back(true);
            else if (s == "false") p.bools.push_back(false);
            else valueError(v, "expected true or false, but got " + Show(v));
            break;
        }
        case ValueKind::Strings:
            if (v.kind != Token::String) valueError(v, "expected a quoted string, but got " + Show(v));
            p.strings.push_back(v.Text());
            break;
        case ValueKind::Spectrum: break;
        }
    };

    Token v;
    if (!ts.Next(&v)) ts.Fail(decl, what + " has no value before the end of the file");
    if (v.kind == Token::OpenBracket) {
        Token open = v;
        while (true) {
            if (!ts.Next(&v)) ts.Fail(open, "unterminated '[': missing ']' before the end of the file");
            if (v.kind == Token::CloseBracket) break;
            if (v.kind == Token::OpenBracket) valueError(v, "unexpected '[' inside a value list");
            addValue(v, &open);
            if (p.numbers.size() + p.strings.size() + p.bools.size() + totalValues_ > opt_.maxTotalValues)
                CountValues(p.numbers.size() + p.strings.size() + p.bools.size(), p.loc);
        }
    } else if (v.kind == Token::CloseBracket) {
        valueError(v, "unexpected ']'");
    } else {
        addValue(v, nullptr);
    }

    // Counts by type.
    size_t n = p.numbers.size() + p.strings.size() + p.bools.size();
    if (n == 0) ts.Fail(decl, what + " has no values");
    if (ti.kind == ValueKind::Spectrum) {
        if (spectrumStrings && p.strings.size() != 1)
            ts.Fail(decl, what + " needs one named spectrum or file name, but " + std::to_string(n) + " were given");
        if (!spectrumStrings && p.numbers.size() % 2 != 0)
            ts.Fail(decl, what + " needs (wavelength, value) pairs, but " + std::to_string(n) +
                              (n == 1 ? " value was given" : " values were given"));
        return;
    }
    if (ti.exactly && n != size_t(ti.exactly))
        ts.Fail(decl, what + " needs " + std::to_string(ti.exactly) + (ti.exactly == 1 ? " value" : " values") +
                          ", but " + std::to_string(n) + (n == 1 ? " was given" : " were given"));
    if (n % ti.nPerItem != 0)
        ts.Fail(decl, what + " needs a multiple of " + std::to_string(ti.nPerItem) + " values, but " +
                          std::to_string(n) + (n == 1 ? " was given" : " were given"));
}

Transform Parser::CurrentTransform(const FileLoc &loc, const char *what) {
    if (!(state_.ctm[0] == state_.ctm[1]) && !warnedMotion_) {
        warnedMotion_ = true;
        diag_.Unsupported(loc, "motion blur (ActiveTransform)",
                          "the start-time transform is used");
    }
    const DMatrix &m = state_.ctm[0];
    DMatrix inv;
    Transform t;
    t.m = ToMatrix4(m);
    if (Invert(m, &inv) && FitsFloat(inv)) {
        t.mInv = ToMatrix4(inv);
    } else {
        diag_.Warning(loc, std::string("the transformation of this ") + what + " is not invertible");
        for (auto &row : t.mInv.m)
            for (Float &x : row) x = std::numeric_limits<Float>::quiet_NaN();
    }
    return t;
}

ParameterDictionary Parser::MakeDict(ParamList params, const Attributes &attributes, const FileLoc &loc) {
    if (!attributes) return ParameterDictionary(std::move(params));
    // Attribute defaults come first (oldest first) so that later ones and the entity's own
    // parameters win; they may be unused without a warning (pbrt-v4's mayBeUnused).
    CountValues(attributes->cost, loc);
    std::vector<const AttributeNode *> chain;
    for (const AttributeNode *n = attributes.get(); n; n = n->prev.get()) chain.push_back(n);
    ParamList all;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        for (const ParsedParameter &a : (*it)->params) {
            all.push_back(a);
            all.back().lookedUp = true;
        }
    for (ParsedParameter &p : params) all.push_back(std::move(p));
    return ParameterDictionary(std::move(all));
}

void Parser::IncludeFile(TokenStream &ts, const Token &dir, const std::string &fileDir, bool isImport) {
    std::string name = ReadString(ts, dir, "file name");
    if (!opt_.allowFileAccess) ts.Fail(dir, "\"" + std::string(dir.raw) + "\" is disabled (no file access)");
    if (name.empty()) ts.Fail(dir, "\"" + std::string(dir.raw) + "\" needs a file name");
    if ((int)includeChain_.size() > opt_.maxIncludeDepth)
        ts.Fail(dir, "\"" + std::string(dir.raw) + "\" nested more than " + std::to_string(opt_.maxIncludeDepth) +
                         " files deep");
    // Relative to the including file's directory; then, as pbrt-v4 does, to the main file's.
    std::string path = ResolvePath(fileDir, name);
    if (!FileExists(path) && name[0] != '/' && FileExists(ResolvePath(mainDir_, name)))
        path = ResolvePath(mainDir_, name);
    if (!FileExists(path))
        ts.Fail(dir, "cannot open " + std::string(isImport ? "imported" : "included") + " file \"" + name +
                         "\" (looked for \"" + path + "\")");
    std::string canonical = CanonicalPath(path);
    for (size_t i = 0; i < includeChain_.size(); ++i)
        if (includeChain_[i] == canonical) {
            std::string chain;
            for (size_t j = i; j < includeChain_.size(); ++j) chain += includeChain_[j] + " -> ";
            ts.Fail(dir, std::string(isImport ? "Import" : "Include") + " cycle: " + chain + canonical);
        }
    std::string text;
    std::string why = ReadFileBytes(path, &text, MaxSceneFileBytes);
    if (!why.empty())
        ts.Fail(dir, "cannot read " + std::string(isImport ? "imported" : "included") + " file \"" + path + "\": " + why);
    auto sub = std::make_unique<Tokenizer>(std::move(text), path);
    includeChain_.push_back(canonical);
    if (!isImport) {
        ParseFile(*sub, DirectoryOf(path));
    } else {
        // Import: the imported file sees a copy of the graphics state and cannot change ours;
        // its AttributeBegin/End must balance (pbrt-v4's CopyForImport / MergeImported).
        GraphicsState saved = state_;
        size_t savedFloor = pushFloor_;
        pushFloor_ = pushed_.size();
        ParseFile(*sub, DirectoryOf(path));
        if (pushed_.size() > pushFloor_) {
            const PushedState &open = pushed_.back();
            throw SceneError(open.loc, OpenName(open) + " without a matching " +
                                           (open.kind == 'o' ? "ObjectEnd" : "AttributeEnd") +
                                           " in the imported file");
        }
        pushFloor_ = savedFloor;
        state_ = std::move(saved);
    }
    includeChain_.pop_back();
}

void Parser::Statement(TokenStream &ts, const Token &dir, const std::string &fileDir) {
    const std::string_view d = dir.raw;
    const FileLoc loc = dir.Loc();
    // Reads `"type" params...` into e, the attribute defaults of the state first.
    auto entity = [&](SceneEntity &e, const Attributes &attributes) {
        e.name = ReadString(ts, dir, "type name");
        e.loc = loc;
        e.params = MakeDict(ReadParams(ts), attributes, loc);
    };
    double v[16];

    // ---- transformations ----
    if (d == "Identity") {
        ApplyTransform(ts, dir, DMatrix(), true);
    } else if (d == "Translate") {
        ReadNumbers(ts, dir, v, 3, false);
        ApplyTransform(ts, dir, TranslateM(v[0], v[1], v[2]), false);
    } else if (d == "Scale") {
        ReadNumbers(ts, dir, v, 3, false);
        ApplyTransform(ts, dir, ScaleM(v[0], v[1], v[2]), false);
    } else if (d == "Rotate") {
        ReadNumbers(ts, dir, v, 4, false);
        double len = std::sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
        if (!(len > 0) || !std::isfinite(len)) ts.Fail(dir, "\"Rotate\" needs a nonzero rotation axis");
        ApplyTransform(ts, dir, RotateM(v[0], v[1] / len, v[2] / len, v[3] / len), false);
    } else if (d == "LookAt") {
        ReadNumbers(ts, dir, v, 9, false);
        Triple eye{v[0], v[1], v[2]}, look{v[3], v[4], v[5]}, up{v[6], v[7], v[8]};
        Triple dirv = Sub(look, eye);
        if (!(LengthT(dirv) > 0)) ts.Fail(dir, "\"LookAt\": the eye and look-at points are the same");
        if (!(LengthT(up) > 0)) ts.Fail(dir, "\"LookAt\": the up vector is zero");
        dirv = NormalizeT(dirv);
        Triple right = CrossT(NormalizeT(up), dirv);
        if (!(LengthT(right) > 1e-12) || !std::isfinite(LengthT(right)))
            ts.Fail(dir, "\"LookAt\": the up vector is parallel to the viewing direction");
        right = NormalizeT(right);
        Triple newUp = CrossT(dirv, right);
        // worldFromCamera has columns right, up, dir, eye (pbrt-v4's LookAt); the CTM gets its inverse.
        DMatrix worldFromCamera;
        const Triple cols[4] = {right, newUp, dirv, eye};
        for (int c = 0; c < 4; ++c) {
            worldFromCamera.m[0][c] = cols[c].x;
            worldFromCamera.m[1][c] = cols[c].y;
            worldFromCamera.m[2][c] = cols[c].z;
        }
        DMatrix cameraFromWorld;
        if (!Invert(worldFromCamera, &cameraFromWorld)) ts.Fail(dir, "\"LookAt\": degenerate viewing transformation");
        ApplyTransform(ts, dir, cameraFromWorld, false);
    } else if (d == "Transform" || d == "ConcatTransform") {
        ReadNumbers(ts, dir, v, 16, true);
        // The 16 numbers are the matrix in column-major order (translation in elements 12-14).
        DMatrix m;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) m.m[i][j] = v[j * 4 + i];
        ApplyTransform(ts, dir, m, d == "Transform");
    } else if (d == "CoordinateSystem") {
        std::string name = ReadString(ts, dir, "name");
        namedCoordinateSystems_[name].m[0] = state_.ctm[0];
        namedCoordinateSystems_[name].m[1] = state_.ctm[1];
    } else if (d == "CoordSysTransform") {
        std::string name = ReadString(ts, dir, "name");
        auto it = namedCoordinateSystems_.find(name);
        if (it == namedCoordinateSystems_.end()) {
            diag_.Warning(loc, "unknown coordinate system \"" + name + "\"; the transformation is unchanged");
        } else {
            state_.ctm[0] = it->second.m[0];
            state_.ctm[1] = it->second.m[1];
        }
    } else if (d == "ActiveTransform") {
        Token t;
        if (!ts.Next(&t)) ts.Fail(dir, "unexpected end of file: \"ActiveTransform\" needs All, StartTime or EndTime");
        if (!t.Is("All") && !warnedActiveTransform_) {
            warnedActiveTransform_ = true;
            diag_.Warning(loc, "ActiveTransform: motion blur is not supported; the start-time transformation is used");
        }
        if (t.Is("All")) state_.activeStart = state_.activeEnd = true;
        else if (t.Is("StartTime")) { state_.activeStart = true; state_.activeEnd = false; }
        else if (t.Is("EndTime")) { state_.activeStart = false; state_.activeEnd = true; }
        else ts.Fail(t, "\"ActiveTransform\" needs All, StartTime or EndTime, but got " + Show(t));
    } else if (d == "TransformTimes") {
        RequireOptions(ts, dir);
        ReadNumbers(ts, dir, v, 2, false);
        if (!warnedTransformTimes_) {
            warnedTransformTimes_ = true;
            diag_.Warning(loc, "TransformTimes is ignored: motion blur is not supported");
        }
    } else if (d == "TransformBegin" || d == "AttributeBegin") {
        if (d == "TransformBegin" && !warnedTransformBegin_) {
            warnedTransformBegin_ = true;
            diag_.Warning(loc, "TransformBegin/End are deprecated and should be replaced with AttributeBegin/End");
        }
        Push(ts, 'a', dir);
    } else if (d == "TransformEnd" || d == "AttributeEnd") {
        if (pushed_.size() <= pushFloor_) ts.Fail(dir, "unmatched \"" + std::string(d) + "\"");
        if (pushed_.back().kind != 'a')
            ts.Fail(dir, "\"" + std::string(d) + "\" closes the ObjectBegin at " + Where(pushed_.back().loc));
        state_ = std::move(pushed_.back().state);
        pushed_.pop_back();
    }
    // ---- rendering options ----
    else if (d == "Camera") {
        RequireOptions(ts, dir);
        SceneEntity e;
        e.name = ReadString(ts, dir, "type name");
        ParamList params = ReadParams(ts);
        DMatrix cameraFromWorld = state_.ctm[0], worldFromCamera;
        if (!Invert(cameraFromWorld, &worldFromCamera) || !FitsFloat(worldFromCamera))
            ts.Fail(dir, "the camera transformation (the CTM at \"Camera\") is not invertible");
        desc_.camera.name = e.name;
        desc_.camera.loc = loc;
        desc_.camera.params = ParameterDictionary(std::move(params));
        desc_.camera.worldFromCamera = Transform(ToMatrix4(worldFromCamera), ToMatrix4(cameraFromWorld));
        desc_.camera.medium = state_.outsideMedium;
        DMatrix inv1;
        if (!Invert(state_.ctm[1], &inv1)) inv1 = worldFromCamera;
        namedCoordinateSystems_["camera"].m[0] = worldFromCamera;
        namedCoordinateSystems_["camera"].m[1] = inv1;
    } else if (d == "Film" || d == "Sampler" || d == "Integrator" || d == "PixelFilter" || d == "Accelerator") {
        RequireOptions(ts, dir);
        SceneEntity e;
        e.name = ReadString(ts, dir, "type name");
        e.loc = loc;
        e.params = ParameterDictionary(ReadParams(ts));
        SceneEntity &target = d == "Film" ? desc_.film
                              : d == "Sampler" ? desc_.sampler
                              : d == "Integrator" ? desc_.integrator
                              : d == "PixelFilter" ? desc_.filter
                                                   : desc_.accelerator;
        target = std::move(e);
    } else if (d == "ColorSpace") {
        std::string name = ReadString(ts, dir, "color space name");
        if (name != "srgb" && name != "rec2020" && name != "aces2065-1" && name != "dci-p3")
            ts.Fail(dir, "unknown color space \"" + name + "\" (known: srgb, rec2020, aces2065-1, dci-p3)");
        if (name != desc_.colorSpace) {
            if (colorSpaceSet_ || rgbSeen_)
                diag_.Unsupported(loc, "ColorSpace \"" + name + "\"",
                                  "one color space per scene; \"" + desc_.colorSpace + "\" is kept");
            else
                desc_.colorSpace = name;
        }
        colorSpaceSet_ = true;
    } else if (d == "Option") {
        Token valueTok;
        std::string name = ReadString(ts, dir, "option name");
        if (!ts.Next(&valueTok)) ts.Fail(dir, "unexpected end of file: \"Option\" needs a value");
        if (valueTok.kind == Token::OpenBracket || valueTok.kind == Token::CloseBracket)
            ts.Fail(valueTok, "\"Option\" needs a single value, but got " + Show(valueTok));
        desc_.options.emplace_back(name + " " + std::string(valueTok.raw), loc);
    } else if (d == "WorldBegin") {
        RequireOptions(ts, dir);
        if (!pushed_.empty())
            ts.Fail(dir, "\"WorldBegin\" inside the " + OpenName(pushed_.back()) + " at " + Where(pushed_.back().loc));
        inWorld_ = true;
        state_.ctm[0] = state_.ctm[1] = DMatrix();
        state_.activeStart = state_.activeEnd = true;
        namedCoordinateSystems_["world"].m[0] = DMatrix();
        namedCoordinateSystems_["world"].m[1] = DMatrix();
    } else if (d == "WorldEnd") {
        diag_.Warning(loc, "\"WorldEnd\" is pbrt-v3 syntax; ignored");
    }
    // ---- attributes ----
    else if (d == "Attribute") {
        std::string target = ReadString(ts, dir, "target");
        ParamList params = ReadParams(ts);
        Attributes *slot = target == "shape"      ? &state_.shapeAttributes
                             : target == "light"    ? &state_.lightAttributes
                             : target == "material" ? &state_.materialAttributes
                             : target == "medium"   ? &state_.mediumAttributes
                             : target == "texture"  ? &state_.textureAttributes
                                                    : nullptr;
        if (!slot)
            ts.Fail(dir, "unknown Attribute target \"" + target +
                             "\": must be \"shape\", \"light\", \"material\", \"medium\" or \"texture\"");
        if (!params.empty()) {
            auto node = std::make_shared<AttributeNode>();
            node->cost = ValueCount(params) + (*slot ? (*slot)->cost : 0);
            node->params = std::move(params);
            node->prev = *slot;
            *slot = std::move(node);
        }
    } else if (d == "ReverseOrientation") {
        RequireWorld(ts, dir);
        state_.reverseOrientation = !state_.reverseOrientation;
    } else if (d == "MediumInterface") {
        std::string inside = ReadString(ts, dir, "medium name");
        std::string outside = inside;
        Token t;
        if (ts.Peek(&t) && t.kind == Token::String) {
            ts.Next(&t);
            outside = t.Text();
        }
        state_.insideMedium = inside;
        state_.outsideMedium = outside;
    } else if (d == "MakeNamedMedium") {
        MediumEntity e;
        e.name = ReadString(ts, dir, "medium name");
        e.loc = loc;
        ParamList params = ReadParams(ts);
        if (!mediumNames_.insert(e.name).second) ts.Fail(dir, "named medium \"" + e.name + "\" is already defined");
        e.params = MakeDict(std::move(params), state_.mediumAttributes, loc);
        e.renderFromObject = CurrentTransform(loc, "MakeNamedMedium");
        desc_.media.push_back(std::move(e));
    }
    // ---- materials and textures ----
    else if (d == "Material") {
        RequireWorld(ts, dir);
        SceneEntity e;
        entity(e, state_.materialAttributes);
        desc_.materials.push_back(std::move(e));
        state_.materialIndex = int(desc_.materials.size()) - 1;
        state_.materialName.clear();
    } else if (d == "MakeNamedMaterial") {
        RequireWorld(ts, dir);
        std::string name = ReadString(ts, dir, "material name");
        ParamList params = ReadParams(ts);
        if (desc_.namedMaterials.count(name)) ts.Fail(dir, "named material \"" + name + "\" is already defined");
        SceneEntity e;
        e.loc = loc;
        e.params = MakeDict(std::move(params), state_.materialAttributes, loc);
        const ParsedParameter *type = nullptr;
        for (const ParsedParameter &p : e.params.All())
            if (p.name == "type") type = &p;
        if (!type) ts.Fail(dir, "named material \"" + name + "\" has no \"string type\" parameter");
        if (type->type != "string" || type->strings.size() != 1)
            ts.Fail(type->loc, "named material \"" + name + "\": \"type\" must be one string, like \"string type\" \"diffuse\"");
        type->lookedUp = true;
        e.name = type->strings[0];
        desc_.namedMaterials.emplace(name, std::move(e));
    } else if (d == "NamedMaterial") {
        RequireWorld(ts, dir);
        std::string name = ReadString(ts, dir, "material name");
        state_.materialName = name;
        state_.materialIndex = -1;
        state_.materialLoc = loc;
    } else if (d == "Texture") {
        RequireWorld(ts, dir);
        TextureEntity e;
        e.textureName = ReadString(ts, dir, "texture name");
        e.valueType = ReadString(ts, dir, "texture type (\"float\" or \"spectrum\")");
        e.name = ReadString(ts, dir, "texture class");
        e.loc = loc;
        ParamList params = ReadParams(ts);
        if (e.valueType != "float" && e.valueType != "spectrum")
            ts.Fail(dir, "texture type \"" + e.valueType + "\" is unknown: must be \"float\" or \"spectrum\"");
        auto &names = e.valueType == "float" ? floatTextureNames_ : spectrumTextureNames_;
        if (!names.insert(e.textureName).second)
            ts.Fail(dir, e.valueType + " texture \"" + e.textureName + "\" is already defined");
        e.params = MakeDict(std::move(params), state_.textureAttributes, loc);
        e.renderFromObject = CurrentTransform(loc, "Texture");
        e.baseDirectory = fileDir;
        (e.valueType == "float" ? desc_.floatTextures : desc_.spectrumTextures).push_back(std::move(e));
    }
    // ---- lights and shapes ----
    else if (d == "LightSource") {
        RequireWorld(ts, dir);
        LightEntity e;
        entity(e, state_.lightAttributes);
        e.renderFromObject = CurrentTransform(loc, "LightSource");
        e.outsideMedium = state_.outsideMedium;
        desc_.lights.push_back(std::move(e));
    } else if (d == "AreaLightSource") {
        RequireWorld(ts, dir);
        std::string name = ReadString(ts, dir, "type name");
        ParamList params = ReadParams(ts);
        state_.areaLightName = name;
        state_.areaLightLoc = loc;
        // The light attribute defaults in effect now apply (as pbrt-v4's AreaLightSource).
        state_.areaLightParams = std::make_shared<ParamList>(MakeDict(std::move(params), state_.lightAttributes, loc).All());
    } else if (d == "Shape") {
        RequireWorld(ts, dir);
        ShapeEntity e;
        entity(e, state_.shapeAttributes);
        e.renderFromObject = CurrentTransform(loc, "Shape");
        e.reverseOrientation = state_.reverseOrientation;
        e.materialIndex = state_.materialIndex;
        e.materialName = state_.materialName;
        e.insideMedium = state_.insideMedium;
        e.outsideMedium = state_.outsideMedium;
        e.baseDirectory = fileDir;
        if (!state_.areaLightName.empty()) {
            SceneEntity light;
            light.name = state_.areaLightName;
            light.loc = state_.areaLightLoc;
            ParamList lp = state_.areaLightParams ? *state_.areaLightParams : ParamList();
            CountValues(ValueCount(lp), loc);
            light.params = ParameterDictionary(std::move(lp));
            desc_.areaLights.push_back(std::move(light));
            e.areaLightIndex = int(desc_.areaLights.size()) - 1;
            if (!activeInstance_.empty()) diag_.Warning(loc, "area lights are not supported with object instancing");
        }
        if (!e.materialName.empty()) namedMaterialUses_.emplace_back(e.materialName, state_.materialLoc);
        if (!activeInstance_.empty()) desc_.instanceDefinitions[activeInstance_].shapes.push_back(std::move(e));
        else desc_.shapes.push_back(std::move(e));
    }
    // ---- object instancing ----
    else if (d == "ObjectBegin") {
        RequireWorld(ts, dir);
        std::string name = ReadString(ts, dir, "object name");
        if (!activeInstance_.empty())
            ts.Fail(dir, "\"ObjectBegin\" inside the definition of object \"" + activeInstance_ + "\"");
        if (desc_.instanceDefinitions.count(name)) ts.Fail(dir, "object \"" + name + "\" is already defined");
        Push(ts, 'o', dir);
        activeInstance_ = name;
        InstanceDefinition &def = desc_.instanceDefinitions[name];
        def.name = name;
        def.loc = loc;
    } else if (d == "ObjectEnd") {
        RequireWorld(ts, dir);
        if (activeInstance_.empty() || pushed_.size() <= pushFloor_) ts.Fail(dir, "unmatched \"ObjectEnd\"");
        if (pushed_.back().kind != 'o')
            ts.Fail(dir, "\"ObjectEnd\" closes the AttributeBegin at " + Where(pushed_.back().loc));
        state_ = std::move(pushed_.back().state);
        pushed_.pop_back();
        activeInstance_.clear();
    } else if (d == "ObjectInstance") {
        RequireWorld(ts, dir);
        std::string name = ReadString(ts, dir, "object name");
        if (!activeInstance_.empty())
            ts.Fail(dir, "\"ObjectInstance\" inside the definition of object \"" + activeInstance_ + "\"");
        InstanceUse use;
        use.name = name;
        use.loc = loc;
        use.renderFromInstance = CurrentTransform(loc, "ObjectInstance");
        desc_.instances.push_back(std::move(use));
    }
    // ---- files ----
    else if (d == "Include") {
        IncludeFile(ts, dir, fileDir, false);
    } else if (d == "Import") {
        RequireWorld(ts, dir);
        IncludeFile(ts, dir, fileDir, true);
    } else {
        ts.Fail(dir, "unknown directive \"" + std::string(d) + "\"");
    }
}

SceneDescription Parser::Finish() {
    if (!pushed_.empty()) {
        const PushedState &open = pushed_.back();
        throw SceneError(open.loc, OpenName(open) + " without a matching " +
                                       (open.kind == 'o' ? "ObjectEnd" : "AttributeEnd"));
    }
    for (const auto &[name, loc] : namedMaterialUses_)
        if (!desc_.namedMaterials.count(name))
            throw SceneError(loc, "named material \"" + name + "\" is not defined (no MakeNamedMaterial \"" + name + "\")");
    for (const InstanceUse &use : desc_.instances)
        if (!desc_.instanceDefinitions.count(use.name))
            throw SceneError(use.loc, "object \"" + use.name + "\" is not defined (no ObjectBegin \"" + use.name + "\")");
    if (sawDirective_ && !inWorld_) diag_.Warning(FileLoc{}, "the scene has no WorldBegin");
    return std::move(desc_);
}

// Attaches the source line to errors thrown outside a tokenizer (Finish, ply, ...) when the error's
// file is the in-memory main text.
SceneDescription Run(Tokenizer &tz, const std::string &path, Diagnostics &diag, const ParseOptions &options) {
    try {
        Parser parser(diag, options);
        parser.ParseTop(tz, path);
        SceneDescription desc = parser.Finish();
        desc.filename = path;
        return desc;
    } catch (SceneError &e) {
        if (e.SourceLine().empty() && e.Loc().file == tz.File()) e.SetSourceLine(tz.SourceLine(e.Loc().line));
        throw;
    }
}

}  // namespace

SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag, const ParseOptions &options) {
    std::unique_ptr<Tokenizer> tz = Tokenizer::FromFile(filename, FileLoc{});
    return Run(*tz, filename, diag, options);
}

SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag,
                                  const ParseOptions &options) {
    Tokenizer tz(text, filename);
    return Run(tz, filename, diag, options);
}

SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag) {
    return ParseSceneFile(filename, diag, ParseOptions());
}

SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag) {
    return ParseSceneString(text, filename, diag, ParseOptions());
}

}  // namespace lu
