// Lucerna (host): the IES LM-63 reader (header, TILT data included or in a separate file, the
// photometric web as a stream of numbers with their line numbers), the bilinear evaluation of the
// web for types C, B and A and its equal-area table (ANSI/IESNA LM-63-2002; axes: docs/lights.md).
#include "lucerna/scene/ies.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "lucerna/lights/equal_area.h"

namespace lu {

namespace {

std::string_view Trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

bool StartsWith(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

struct Token {
    std::string_view text;
    int line = 0;
};

class IESReader {
  public:
    IESReader(std::string_view text, const std::string &filename, const std::string &context)
        : text_(text), file_(std::make_shared<const std::string>(filename)), context_(context) {}

    IESProfile Read() {
        IESProfile p;
        p.filename = *file_;
        SplitLines();
        if (lines_.empty() || (lines_.size() == 1 && Trim(lines_[0]).empty())) Fail(1, "empty file (not an IES LM-63 file)");
        std::string_view first = Trim(lines_[0]);
        if (StartsWith(first, "IESNA:LM-63-2002")) p.format = "LM-63-2002";
        else if (StartsWith(first, "IESNA:LM-63-1995")) p.format = "LM-63-1995";
        else if (StartsWith(first, "IESNA91")) p.format = "LM-63-1991";
        else p.format = "LM-63-1986";
        // The header (first line, keyword lines, free text in LM-63-1986) ends at the TILT line.
        size_t tiltLine = lines_.size();
        for (size_t i = 0; i < lines_.size(); ++i) {
            std::string_view l = Trim(lines_[i]);
            if (StartsWith(l, "TILT")) {
                std::string_view rest = Trim(l.substr(4));
                if (!rest.empty() && rest.front() == '=') {
                    tiltLine = i;
                    break;
                }
            }
        }
        if (tiltLine == lines_.size())
            Fail(int(lines_.size()), "no \"TILT=\" line: an IES LM-63 file has one (TILT=NONE or TILT=INCLUDE) "
                                     "between its header and the photometric data");
        std::string_view tilt = Trim(Trim(Trim(lines_[tiltLine]).substr(4)).substr(1));
        int tiltLineNo = int(tiltLine) + 1;
        Tokenize(tiltLine + 1);
        if (tilt == "NONE") {
            p.tilt = "NONE";
        } else if (tilt == "INCLUDE") {
            p.tilt = "INCLUDE";
            ReadTilt(p, " (TILT=INCLUDE)");
        } else if (!tilt.empty()) {
            // TILT=<file>: the same numbers in a file of their own, next to the IES file.
            p.tilt = std::string(tilt);
            std::filesystem::path tp(p.tilt);
            if (tp.is_relative()) tp = std::filesystem::path(*file_).parent_path() / tp;
            p.tiltFile = tp.string();
            std::error_code ec;
            std::ifstream in;
            if (std::filesystem::is_regular_file(tp, ec)) in.open(p.tiltFile, std::ios::binary);   // not a device or folder
            if (!in.is_open()) Fail(tiltLineNo, "\"TILT=" + p.tilt + "\": cannot open the tilt file \"" + p.tiltFile + "\"");
            if (std::filesystem::file_size(tp, ec) > (uintmax_t(1) << 24))
                Fail(tiltLineNo, "\"TILT=" + p.tilt + "\": the tilt file \"" + p.tiltFile + "\" is over 16 MiB");
            std::ostringstream s;
            s << in.rdbuf();
            std::string text = s.str();
            if (in.bad()) Fail(tiltLineNo, "\"TILT=" + p.tilt + "\": read error in the tilt file \"" + p.tiltFile + "\"");
            IESReader tiltReader(text, p.tiltFile,
                                 "tilt file of " + *file_ + ":" + std::to_string(tiltLineNo) + (context_.empty() ? "" : ", " + context_));
            tiltReader.SplitLines();
            tiltReader.Tokenize(0);
            tiltReader.ReadTilt(p, "");
            if (tiltReader.pos_ < tiltReader.tokens_.size())
                tiltReader.Fail(tiltReader.tokens_[tiltReader.pos_].line,
                                std::to_string(tiltReader.tokens_.size() - tiltReader.pos_) +
                                    " more number(s) after the last tilt multiplying factor (" +
                                    std::to_string(p.tiltAngles.size()) + " tilt angles)");
        } else {
            Fail(tiltLineNo, "\"TILT=\" without a value (NONE, INCLUDE or a file name)");
        }
        p.lamps = Int("the number of lamps");
        if (p.lamps < 1) FailAtLast("the number of lamps must be at least 1 (got " + FormatNumber(p.lamps) + ")");
        p.lumensPerLamp = Number("the lumens per lamp");
        if (!(p.lumensPerLamp > 0 || p.lumensPerLamp == -1))
            FailAtLast("lumens per lamp must be positive, or -1 for absolute photometry (got " + FormatNumber(p.lumensPerLamp) + ")");
        p.candelaMultiplier = Number("the candela multiplier");
        if (!(p.candelaMultiplier > 0)) FailAtLast("the candela multiplier must be positive (got " + FormatNumber(p.candelaMultiplier) + ")");
        int nv = Int("the number of vertical angles");
        if (nv < 2) FailAtLast("at least 2 vertical angles are needed (got " + FormatNumber(nv) + ")");
        int nh = Int("the number of horizontal angles");
        if (nh < 1) FailAtLast("at least 1 horizontal angle is needed (got " + FormatNumber(nh) + ")");
        if (double(nv) * double(nh) > 1e7) FailAtLast("the web has " + FormatNumber(double(nv) * nh) + " candela values (more than 10^7)");
        p.photometricType = Int("the photometric type");
        if (p.photometricType < 1 || p.photometricType > 3) FailAtLast("the photometric type must be 1 (C), 2 (B) or 3 (A) (got " + FormatNumber(p.photometricType) + ")");
        int units = Int("the units type");
        if (units != 1 && units != 2) FailAtLast("the units type must be 1 (feet) or 2 (meters) (got " + FormatNumber(units) + ")");
        Number("the luminous opening's width");
        Number("the luminous opening's length");
        Number("the luminous opening's height");
        p.ballastFactor = Number("the ballast factor");
        if (!(p.ballastFactor > 0)) FailAtLast("the ballast factor must be positive (got " + FormatNumber(p.ballastFactor) + ")");
        p.ballastLampFactor = Number(p.format == "LM-63-2002" ? "the \"future use\" field after the ballast factor"
                                                              : "the ballast-lamp photometric factor");
        if (!(p.ballastLampFactor > 0))
            FailAtLast("the ballast-lamp photometric factor must be positive (got " + FormatNumber(p.ballastLampFactor) + ")");
        p.inputWatts = Number("the input watts");
        if (p.inputWatts < 0) FailAtLast("the input watts must not be negative (got " + FormatNumber(p.inputWatts) + ")");

        // Type C: vertical from nadir (0) to zenith (180). Types A and B: elevation from the photometric
        // axis, -90..90 (LM-63-2002: first -90 or 0, last 90; sub-ranges are read, dark outside).
        const bool typeC = p.photometricType == 1;
        const std::string type = std::string("type ") + p.TypeLetter();
        const double vLo = typeC ? 0 : -90, vHi = typeC ? 180 : 90;
        ReadAngles(p.vertical, nv, "vertical");
        for (size_t i = 0; i < p.vertical.size(); ++i)
            if (p.vertical[i] < vLo || p.vertical[i] > vHi)
                FailAt(angleLine_[i], "vertical angle " + FormatNumber(p.vertical[i]) + " is outside [" + FormatNumber(vLo) + ", " +
                                          FormatNumber(vHi) + "] degrees (" + type + ")");
        ReadAngles(p.horizontal, nh, "horizontal");
        double h0 = p.horizontal.front(), h1 = p.horizontal.back();
        int hLine = angleLine_.back();
        if (!typeC) {
            // LM-63-2002, section 4: 0..90 for a luminaire laterally symmetric about its vertical reference
            // plane, -90..90 otherwise.
            if (nh >= 2 && h0 == 0 && h1 == 90) p.symmetry = IESSymmetry::Lateral;
            else if (nh >= 2 && h0 == -90 && h1 == 90) p.symmetry = IESSymmetry::LateralFull;
            else
                FailAt(hLine, "horizontal angles must run from -90 to 90 degrees, or from 0 to 90 (laterally symmetric) (" + type +
                                  "); got " + (nh == 1 ? "the single angle " + FormatNumber(h0) : FormatNumber(h0) + " to " + FormatNumber(h1)));
        } else if (nh == 1) {
            if (h0 != 0) FailAt(hLine, "a single horizontal angle must be 0 (got " + FormatNumber(h0) + ")");
            p.symmetry = IESSymmetry::Rotational;
        } else if (h0 == 0 && h1 == 90) p.symmetry = IESSymmetry::Quadrant;
        else if (h0 == 0 && h1 == 180) p.symmetry = IESSymmetry::Half0To180;
        else if (h0 == 90 && h1 == 270) p.symmetry = IESSymmetry::Half90To270;
        else if (h0 == 0 && h1 == 360) p.symmetry = IESSymmetry::Full;
        else
            FailAt(hLine, "horizontal angles must run 0-90, 0-180, 90-270 or 0-360 degrees, or be the single angle 0 "
                          "(type C symmetry); got " + FormatNumber(h0) + "-" + FormatNumber(h1));

        size_t count = size_t(nv) * size_t(nh);
        p.candela.resize(count);
        for (size_t i = 0; i < count; ++i) {
            int h = int(i / size_t(nv)), v = int(i % size_t(nv));
            if (pos_ >= tokens_.size())
                FailAtLast("the file ends after " + std::to_string(i) + " of the " + std::to_string(count) +
                           " candela values (" + std::to_string(nv) + " vertical x " + std::to_string(nh) + " horizontal angles)");
            double c = Number("a candela value");
            if (c < 0)
                FailAtLast("negative candela value " + FormatNumber(c) + " (vertical " + FormatNumber(p.vertical[size_t(v)]) + ", horizontal " +
                           FormatNumber(p.horizontal[size_t(h)]) + ")");
            p.candela[i] = c;
        }
        if (pos_ < tokens_.size())
            FailAt(tokens_[pos_].line, std::to_string(tokens_.size() - pos_) + " more number(s) after the last candela value: " +
                                           std::to_string(nv) + " vertical x " + std::to_string(nh) + " horizontal angles make " +
                                           std::to_string(count) + " candela values");
        if (p.symmetry == IESSymmetry::Full)
            for (int v = 0; v < nv; ++v) {
                double a = p.candela[size_t(v)], b = p.candela[size_t(nh - 1) * size_t(nv) + size_t(v)];
                if (std::abs(a - b) > 1e-6 * std::max(std::abs(a), std::abs(b)) + 1e-9)
                    FailAt(tokens_.back().line, "the candela values at horizontal 0 and 360 (the same plane) differ at vertical " +
                                                FormatNumber(p.vertical[size_t(v)]) + ": " + FormatNumber(a) + " vs " + FormatNumber(b));
            }
        return p;
    }

  private:
    // Lamp-to-luminaire geometry, the number of tilt angles, the angles and their multiplying factors
    // (LM-63-2002, section 4), from this reader's numbers: those after TILT=INCLUDE or a tilt file's.
    void ReadTilt(IESProfile &p, const std::string &where) {
        p.tiltGeometry = Int("the lamp-to-luminaire geometry" + where);
        if (p.tiltGeometry < 1 || p.tiltGeometry > 3)
            FailAtLast("lamp-to-luminaire geometry must be 1, 2 or 3 (got " + FormatNumber(p.tiltGeometry) + ")");
        int n = Int("the number of tilt angles");
        if (n < 1) FailAtLast("the number of tilt angles must be at least 1 (got " + FormatNumber(n) + ")");
        if (n > 100000) FailAtLast("the number of tilt angles is over 100000 (got " + FormatNumber(n) + ")");
        p.tiltAngles.clear();
        p.tiltFactors.clear();
        for (int i = 0; i < n; ++i) {
            double a = Number("tilt angle " + std::to_string(i + 1) + " of " + std::to_string(n));
            if (a < 0 || a > 90) FailAtLast("tilt angle " + FormatNumber(a) + " is outside [0, 90] degrees");
            if (!p.tiltAngles.empty() && !(a > p.tiltAngles.back()))
                FailAtLast("tilt angles must increase: " + FormatNumber(a) + " follows " + FormatNumber(p.tiltAngles.back()));
            p.tiltAngles.push_back(a);
        }
        for (int i = 0; i < n; ++i) {
            double f = Number("tilt multiplying factor " + std::to_string(i + 1) + " of " + std::to_string(n));
            if (f < 0) FailAtLast("negative tilt multiplying factor " + FormatNumber(f));
            p.tiltFactors.push_back(f);
        }
    }

    [[noreturn]] void Fail(int line, const std::string &msg) const {
        FileLoc loc;
        loc.file = file_;
        loc.line = line;
        throw SceneError(loc, msg + (context_.empty() ? std::string() : " (" + context_ + ")"));
    }
    [[noreturn]] void FailAt(int line, const std::string &msg) const { Fail(line, msg); }
    // At the line of the last token read (or of the TILT line when none was).
    [[noreturn]] void FailAtLast(const std::string &msg) const {
        int line = pos_ > 0 ? tokens_[pos_ - 1].line : (tokens_.empty() ? int(lines_.size()) : tokens_[0].line);
        Fail(std::max(line, 1), msg);
    }

    void SplitLines() {
        size_t start = 0;
        while (start <= text_.size()) {
            size_t end = text_.find('\n', start);
            if (end == std::string_view::npos) {
                if (start < text_.size()) lines_.push_back(text_.substr(start));
                break;
            }
            lines_.push_back(text_.substr(start, end - start));
            start = end + 1;
        }
    }

    void Tokenize(size_t fromLine) {
        for (size_t i = fromLine; i < lines_.size(); ++i) {
            std::string_view l = lines_[i];
            size_t j = 0;
            while (j < l.size()) {
                while (j < l.size() && (l[j] == ' ' || l[j] == '\t' || l[j] == ',' || l[j] == '\r' || l[j] == '\f' || l[j] == '\v')) ++j;
                size_t k = j;
                while (k < l.size() && !(l[k] == ' ' || l[k] == '\t' || l[k] == ',' || l[k] == '\r' || l[k] == '\f' || l[k] == '\v')) ++k;
                if (k > j) tokens_.push_back({l.substr(j, k - j), int(i) + 1});
                j = k;
            }
        }
    }

    double Number(const std::string &what) {
        if (pos_ >= tokens_.size()) FailAtLast("the file ends before " + what);
        const Token &t = tokens_[pos_++];
        std::string s(t.text);
        char *end = nullptr;
        double v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0') Fail(t.line, "expected " + what + ", got \"" + s + "\" (not a number)");
        if (!std::isfinite(v)) Fail(t.line, "expected " + what + ", got \"" + s + "\" (not a finite number)");
        return v;
    }

    int Int(const std::string &what) {
        double v = Number(what);
        if (v != std::floor(v) || std::abs(v) > 1e9)
            FailAtLast("expected " + what + " as an integer, got " + std::string(tokens_[pos_ - 1].text));
        return int(v);
    }

    void ReadAngles(std::vector<double> &out, int n, const char *kind) {
        out.clear();
        angleLine_.clear();
        for (int i = 0; i < n; ++i) {
            if (pos_ >= tokens_.size())
                FailAtLast("the file ends after " + std::to_string(i) + " of the " + std::to_string(n) + " " + kind + " angles");
            double a = Number(std::string("a ") + kind + " angle");
            if (!out.empty() && !(a > out.back()))
                FailAtLast(std::string(kind) + " angles must increase: " + FormatNumber(a) + " follows " + FormatNumber(out.back()) +
                           " (angle " + std::to_string(i + 1) + " of " + std::to_string(n) + ")");
            out.push_back(a);
            angleLine_.push_back(tokens_[pos_ - 1].line);
        }
    }

    std::string_view text_;
    std::shared_ptr<const std::string> file_;
    std::string context_;
    std::vector<std::string_view> lines_;
    std::vector<Token> tokens_;
    size_t pos_ = 0;
    std::vector<int> angleLine_;
};

// Index i with a[i] <= x <= a[i + 1] (x clamped to [a.front(), a.back()]) and the fraction t.
void FindInterval(const std::vector<double> &a, double x, size_t *i, double *t) {
    x = std::clamp(x, a.front(), a.back());
    size_t hi = size_t(std::upper_bound(a.begin(), a.end(), x) - a.begin());
    size_t lo = hi == 0 ? 0 : std::min(hi - 1, a.size() - 2);
    *i = lo;
    *t = std::clamp((x - a[lo]) / (a[lo + 1] - a[lo]), 0.0, 1.0);
}

}  // namespace

double IESProfile::Evaluate(double v, double h) const {
    if (vertical.size() < 2 || !(v >= vertical.front() && v <= vertical.back())) return 0;
    size_t nv = vertical.size(), iv;
    double tv;
    FindInterval(vertical, v, &iv, &tv);
    auto column = [&](size_t hIndex) {
        const double *c = candela.data() + hIndex * nv;
        return c[iv] * (1 - tv) + c[iv + 1] * tv;
    };
    double value;
    if (horizontal.size() == 1) {
        value = column(0);
    } else if (photometricType != 1) {
        if (symmetry == IESSymmetry::Lateral) h = std::abs(h);
        if (!(h >= horizontal.front() && h <= horizontal.back())) return 0;
        size_t ih;
        double th;
        FindInterval(horizontal, h, &ih, &th);
        value = column(ih) * (1 - th) + column(ih + 1) * th;
    } else {
        h = std::fmod(h, 360.0);
        if (h < 0) h += 360;
        switch (symmetry) {
        case IESSymmetry::Quadrant:
            if (h > 180) h = 360 - h;
            if (h > 90) h = 180 - h;
            break;
        case IESSymmetry::Half0To180:
            if (h > 180) h = 360 - h;
            break;
        case IESSymmetry::Half90To270:
            if (h < 90) h = 180 - h;
            else if (h > 270) h = 540 - h;
            break;
        default: break;
        }
        size_t ih;
        double th;
        FindInterval(horizontal, h, &ih, &th);
        value = column(ih) * (1 - th) + column(ih + 1) * th;
    }
    return value * Factor();
}

bool IESProfile::TiltFactorAt(double degrees, double *factor) const {
    if (tiltAngles.empty() || !(degrees >= tiltAngles.front() && degrees <= tiltAngles.back())) return false;
    if (tiltAngles.size() == 1) {
        *factor = tiltFactors[0];
        return true;
    }
    size_t i;
    double t;
    FindInterval(tiltAngles, degrees, &i, &t);
    *factor = tiltFactors[i] * (1 - t) + tiltFactors[i + 1] * t;
    return true;
}

void IESProfile::SetTilt(double degrees) {
    double f = 1;
    TiltFactorAt(degrees, &f);
    tiltAngle = degrees;
    tiltFactor = f;
    tiltApplied = true;
}

double IESProfile::MaxCandela() const {
    double m = 0;
    for (double c : candela) m = std::max(m, c);
    return m * Factor();
}

std::string IESProfile::Describe() const {
    const char *sym = "";
    switch (symmetry) {
    case IESSymmetry::Rotational: sym = "rotationally symmetric"; break;
    case IESSymmetry::Quadrant: sym = "horizontal 0-90, quadrant symmetry"; break;
    case IESSymmetry::Half0To180: sym = "horizontal 0-180, symmetric about the 0-180 plane"; break;
    case IESSymmetry::Half90To270: sym = "horizontal 90-270, symmetric about the 90-270 plane"; break;
    case IESSymmetry::Full: sym = "horizontal 0-360"; break;
    case IESSymmetry::Lateral: sym = "horizontal 0 to 90, laterally symmetric"; break;
    case IESSymmetry::LateralFull: sym = "horizontal -90 to 90"; break;
    }
    std::ostringstream o;
    o << format << ", type " << TypeLetter() << ", TILT=" << tilt;
    if (tiltGeometry) {
        o << " (lamp geometry " << tiltGeometry << ", " << tiltAngles.size() << " tilt angles " << FormatNumber(tiltAngles.front())
          << "-" << FormatNumber(tiltAngles.back());
        if (tiltApplied) o << "; tilted " << FormatNumber(tiltAngle) << " degrees: factor " << FormatNumber(tiltFactor) << ")";
        else o << "; not tilted)";
    }
    o << ", " << vertical.size() << " vertical x " << horizontal.size() << " horizontal angles (" << sym << "), vertical "
      << FormatNumber(vertical.front()) << (vertical.front() < 0 ? " to " : "-") << FormatNumber(vertical.back()) << ", peak "
      << FormatNumber(MaxCandela()) << " cd";
    return o.str();
}

IESProfile ParseIES(std::string_view text, const std::string &filename, const std::string &context) {
    return IESReader(text, filename, context).Read();
}

IESProfile ReadIES(const std::string &path, const FileLoc &referencedFrom, const std::string &context) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(referencedFrom, "IES file \"" + path + "\": cannot open it");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw SceneError(referencedFrom, "IES file \"" + path + "\": read error");
    std::string text = s.str();
    if (text.size() > (size_t(1) << 28)) throw SceneError(referencedFrom, "IES file \"" + path + "\": larger than 256 MiB");
    return ParseIES(text, path, context);
}

void IESAnglesOfDirection(float wx, float wy, float wz, double *vertical, double *horizontal, int type) {
    const double toDeg = 180.0 / 3.14159265358979323846;
    const double x = wx, y = wy, z = wz;
    if (type == 2) {
        // Type B: polar axis y (lateral); vertical = the plane's rotation about it from the axis -z
        // towards +x, horizontal = the elevation out of that plane towards +y.
        *vertical = (x == 0 && z == 0) ? 0.0 : std::atan2(x, -z) * toDeg;
        *horizontal = std::atan2(y, std::hypot(x, z)) * toDeg;
        return;
    }
    if (type == 3) {
        // Type A: polar axis x (vertical); horizontal = the plane's rotation about it from -z towards
        // +y, vertical = the elevation out of that plane towards +x.
        *vertical = std::atan2(x, std::hypot(y, z)) * toDeg;
        *horizontal = (y == 0 && z == 0) ? 0.0 : std::atan2(y, -z) * toDeg;
        return;
    }
    *vertical = std::acos(std::clamp(-double(wz), -1.0, 1.0)) * toDeg;
    double h = (wx == 0 && wy == 0) ? 0.0 : std::atan2(-double(wy), double(wx)) * toDeg;
    if (h < 0) h += 360;
    *horizontal = h;
}

std::vector<float> IESEqualAreaTable(const IESProfile &profile, int n) {
    size_t m = size_t(n) + 1;
    std::vector<float> t(m * m);
    for (size_t y = 0; y < m; ++y)
        for (size_t x = 0; x < m; ++x) {
            Vec3f w = EqualAreaSquareToSphere(Vec2f(Float(x) / Float(n), Float(y) / Float(n)));
            double v, h;
            IESAnglesOfDirection(w.x, w.y, w.z, &v, &h, profile.photometricType);
            t[y * m + x] = float(profile.Evaluate(v, h));
        }
    return t;
}

}  // namespace lu
