// Lucerna scene reader: the pbrt-v4 text-format parser. Directive syntax follows pbrt-v4's
// parser.cpp: the parser reads arguments and parameter lists, follows Include/Import, and hands
// each directive to a ParserTarget; every syntax error is a SceneError at its file:line:col.
#include "lucerna/scene/parser.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "lucerna/scene/gzip.h"
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

// ---- The value budget ----

void ValueBudget::Spend(size_t n, const FileLoc &loc) {
    used_ += n;
    if (used_ > limit_)
        throw SceneError(loc, "the scene has more than " + std::to_string(limit_) +
                                  " parameter values; refusing to read further");
}

size_t ValueBudget::Cost(const std::vector<ParsedParameter> &ps) {
    size_t n = 0;
    for (const ParsedParameter &p : ps) n += Cost(p);
    return n;
}

namespace {

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
    [[noreturn]] void Fail(const Token &t, const std::string &msg) { tok_.Fail(t.line, t.col, msg); }

  private:
    Tokenizer &tok_;
    Token peek_;
    bool havePeek_ = false;
};

// Attaches tz's copy of the offending line to an error located in tz's file that has none (errors
// thrown by the target), so that in-memory and compressed files show it too.
void AttachSourceLine(SceneError &e, const Tokenizer &tz) {
    if (e.SourceLine().empty() && e.Loc().file && e.Loc().file == tz.File())
        e.SetSourceLine(tz.SourceLine(e.Loc().line));
}

// Reads a scene file, decompressing it if it is gzip data: "" on success, else why.
std::string ReadSceneText(const std::string &path, std::string *text, bool *corrupt = nullptr) {
    return ReadFileGunzipped(path, text, MaxSceneFileBytes, corrupt);
}

// ---- The parser ----

class Parser {
  public:
    Parser(ParserTarget &target, const ParseOptions &opt, ValueBudget &budget)
        : target_(target), opt_(opt), budget_(budget) {}

    // Parses the main file and calls EndOfFiles.
    void ParseMain(Tokenizer &tz, const std::string &path) {
        mainDir_ = DirectoryOf(path);
        includeChain_.push_back(CanonicalPath(path));
        try {
            ParseFile(tz, mainDir_);
            includeChain_.pop_back();
            target_.EndOfFiles();
        } catch (SceneError &e) {
            AttachSourceLine(e, tz);
            throw;
        }
    }

  private:
    void ParseFile(Tokenizer &tz, const std::string &dir);
    void Statement(TokenStream &ts, const Token &dir, const std::string &fileDir);
    void IncludeFile(TokenStream &ts, const Token &dir, const std::string &fileDir, bool isImport);

    // ---- argument readers ----
    double ReadNumber(TokenStream &ts, const Token &directive, int count);
    void ReadNumbers(TokenStream &ts, const Token &directive, double *v, int n, bool allowBrackets);
    std::string ReadString(TokenStream &ts, const Token &directive, const char *what);
    ParsedParameterVector ReadParams(TokenStream &ts);
    void ReadValues(TokenStream &ts, ParsedParameter &p, const TypeInfo &ti, const Token &decl);

    ParserTarget &target_;
    ParseOptions opt_;
    ValueBudget &budget_;
    std::string mainDir_;
    std::vector<std::string> includeChain_;  // canonical paths of the files being read
};

void Parser::ParseFile(Tokenizer &tz, const std::string &dir) {
    TokenStream ts(tz);
    Token t;
    try {
        while (ts.Next(&t)) {
            if (t.kind != Token::Word) {
                if (t.kind == Token::String)
                    ts.Fail(t, "unexpected string " + Show(t) + " where a directive was expected");
                ts.Fail(t, "unexpected '" + std::string(t.raw) + "' where a directive was expected");
            }
            Statement(ts, t, dir);
        }
    } catch (SceneError &e) {
        AttachSourceLine(e, tz);
        throw;
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

ParsedParameterVector Parser::ReadParams(TokenStream &ts) {
    ParsedParameterVector params;
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
        budget_.Spend(ValueBudget::Cost(p), p.loc);
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
            // A long list fails as soon as it exceeds the budget, before it is complete.
            size_t n = p.numbers.size() + p.strings.size() + p.bools.size();
            if (budget_.Exceeds(n)) budget_.Spend(n, p.loc);
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

void Parser::IncludeFile(TokenStream &ts, const Token &dir, const std::string &fileDir, bool isImport) {
    std::string name = ReadString(ts, dir, "file name");
    const FileLoc loc = dir.Loc();
    target_.IncludeBegin(isImport, loc);
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
    std::string why = ReadSceneText(path, &text);
    if (!why.empty())
        ts.Fail(dir, "cannot read " + std::string(isImport ? "imported" : "included") + " file \"" + path + "\": " + why);
    Tokenizer sub(std::move(text), path, loc);
    includeChain_.push_back(canonical);
    ParseFile(sub, DirectoryOf(path));
    includeChain_.pop_back();
    target_.IncludeEnd(isImport, loc);
}

void Parser::Statement(TokenStream &ts, const Token &dir, const std::string &fileDir) {
    const std::string_view d = dir.raw;
    const FileLoc loc = dir.Loc();
    auto str = [&](const char *what) { return ReadString(ts, dir, what); };
    double v[16];

    // ---- transformations ----
    if (d == "Identity") {
        target_.Identity(loc);
    } else if (d == "Translate") {
        ReadNumbers(ts, dir, v, 3, false);
        target_.Translate(v[0], v[1], v[2], loc);
    } else if (d == "Scale") {
        ReadNumbers(ts, dir, v, 3, false);
        target_.Scale(v[0], v[1], v[2], loc);
    } else if (d == "Rotate") {
        ReadNumbers(ts, dir, v, 4, false);
        target_.Rotate(v[0], v[1], v[2], v[3], loc);
    } else if (d == "LookAt") {
        ReadNumbers(ts, dir, v, 9, false);
        target_.LookAt(v, v + 3, v + 6, loc);
    } else if (d == "Transform" || d == "ConcatTransform") {
        ReadNumbers(ts, dir, v, 16, true);
        if (d == "Transform") target_.Transform(v, loc);
        else target_.ConcatTransform(v, loc);
    } else if (d == "CoordinateSystem") {
        target_.CoordinateSystem(str("name"), loc);
    } else if (d == "CoordSysTransform") {
        target_.CoordSysTransform(str("name"), loc);
    } else if (d == "ActiveTransform") {
        Token t;
        if (!ts.Next(&t)) ts.Fail(dir, "unexpected end of file: \"ActiveTransform\" needs All, StartTime or EndTime");
        if (t.Is("All")) target_.ActiveTransformAll(loc);
        else if (t.Is("StartTime")) target_.ActiveTransformStartTime(loc);
        else if (t.Is("EndTime")) target_.ActiveTransformEndTime(loc);
        else ts.Fail(t, "\"ActiveTransform\" needs All, StartTime or EndTime, but got " + Show(t));
    } else if (d == "TransformTimes") {
        ReadNumbers(ts, dir, v, 2, false);
        target_.TransformTimes(v[0], v[1], loc);
    } else if (d == "TransformBegin") {
        target_.TransformBegin(loc);
    } else if (d == "TransformEnd") {
        target_.TransformEnd(loc);
    } else if (d == "AttributeBegin") {
        target_.AttributeBegin(loc);
    } else if (d == "AttributeEnd") {
        target_.AttributeEnd(loc);
    }
    // ---- rendering options ----
    else if (d == "Camera" || d == "Film" || d == "Sampler" || d == "Integrator" || d == "PixelFilter" ||
             d == "Accelerator") {
        std::string name = str("type name");
        ParsedParameterVector params = ReadParams(ts);
        if (d == "Camera") target_.Camera(name, std::move(params), loc);
        else if (d == "Film") target_.Film(name, std::move(params), loc);
        else if (d == "Sampler") target_.Sampler(name, std::move(params), loc);
        else if (d == "Integrator") target_.Integrator(name, std::move(params), loc);
        else if (d == "PixelFilter") target_.PixelFilter(name, std::move(params), loc);
        else target_.Accelerator(name, std::move(params), loc);
    } else if (d == "ColorSpace") {
        target_.ColorSpace(str("color space name"), loc);
    } else if (d == "Option") {
        std::string name = str("option name");
        Token value;
        if (!ts.Next(&value)) ts.Fail(dir, "unexpected end of file: \"Option\" needs a value");
        if (value.kind == Token::OpenBracket || value.kind == Token::CloseBracket)
            ts.Fail(value, "\"Option\" needs a single value, but got " + Show(value));
        target_.Option(name, std::string(value.raw), loc);
    } else if (d == "WorldBegin") {
        target_.WorldBegin(loc);
    } else if (d == "WorldEnd") {
        target_.WorldEnd(loc);
    }
    // ---- graphics state ----
    else if (d == "Attribute") {
        std::string target = str("target");
        target_.Attribute(target, ReadParams(ts), loc);
    } else if (d == "ReverseOrientation") {
        target_.ReverseOrientation(loc);
    } else if (d == "MediumInterface") {
        std::string inside = str("medium name");
        std::string outside = inside;
        Token t;
        if (ts.Peek(&t) && t.kind == Token::String) {
            ts.Next(&t);
            outside = t.Text();
        }
        target_.MediumInterface(inside, outside, loc);
    } else if (d == "MakeNamedMedium") {
        std::string name = str("medium name");
        target_.MakeNamedMedium(name, ReadParams(ts), loc);
    }
    // ---- materials, textures, lights, shapes ----
    else if (d == "Material") {
        std::string name = str("type name");
        target_.Material(name, ReadParams(ts), loc);
    } else if (d == "MakeNamedMaterial") {
        std::string name = str("material name");
        target_.MakeNamedMaterial(name, ReadParams(ts), loc);
    } else if (d == "NamedMaterial") {
        target_.NamedMaterial(str("material name"), loc);
    } else if (d == "Texture") {
        std::string name = str("texture name");
        std::string type = str("texture type (\"float\" or \"spectrum\")");
        std::string texClass = str("texture class");
        target_.Texture(name, type, texClass, ReadParams(ts), loc);
    } else if (d == "LightSource") {
        std::string name = str("type name");
        target_.LightSource(name, ReadParams(ts), loc);
    } else if (d == "AreaLightSource") {
        std::string name = str("type name");
        target_.AreaLightSource(name, ReadParams(ts), loc);
    } else if (d == "Shape") {
        std::string name = str("type name");
        target_.Shape(name, ReadParams(ts), loc);
    }
    // ---- object instancing ----
    else if (d == "ObjectBegin") {
        target_.ObjectBegin(str("object name"), loc);
    } else if (d == "ObjectEnd") {
        target_.ObjectEnd(loc);
    } else if (d == "ObjectInstance") {
        target_.ObjectInstance(str("object name"), loc);
    }
    // ---- files ----
    else if (d == "Include" || d == "Import") {
        IncludeFile(ts, dir, fileDir, d == "Import");
    } else {
        ts.Fail(dir, "unknown directive \"" + std::string(d) + "\"");
    }
}

}  // namespace

void ParseFile(ParserTarget &target, const std::string &filename, const ParseOptions &options, ValueBudget &budget) {
    std::string text;
    bool corrupt = false;
    std::string why = ReadSceneText(filename, &text, &corrupt);
    // A corrupt compressed file is located at the file itself ("scene.pbrt.gz: error: ...").
    if (corrupt) throw SceneError(FileLoc{std::make_shared<const std::string>(filename), 0, 0}, why);
    if (!why.empty()) throw SceneError(FileLoc{}, "cannot read scene file \"" + filename + "\": " + why);
    Tokenizer tz(std::move(text), filename);
    Parser(target, options, budget).ParseMain(tz, filename);
}

void ParseString(ParserTarget &target, const std::string &text, const std::string &filename,
                 const ParseOptions &options, ValueBudget &budget) {
    Tokenizer tz(text, filename);
    Parser(target, options, budget).ParseMain(tz, filename);
}

}  // namespace lu
