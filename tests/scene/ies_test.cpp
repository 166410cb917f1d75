// Tests of goniometric lights and IES LM-63 profiles: the reader's evaluation and symmetry
// unfolding against the generating functions, the irradiance on a plane below a cosine and a
// batwing luminaire against E = I(theta) cos(theta) / d^2 (shared SampleLi), the axis convention,
// pbrt-v4's goniometric image lookup and y/z swap, "power" normalizations, one test per malformed
// file class (FILE:LINE and the referencing statement), `lucerna info` and the CLI's exit code.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "lucerna/image/image.h"
#include "lucerna/lights/lights.h"
#include "lucerna/scene/builder.h"
#include "lucerna/scene/ies.h"
#include "lucerna/scene/light_build.h"
#include "support/test_support.h"

namespace lu {
namespace {

constexpr double kPi = 3.14159265358979323846;
double Rad(double deg) { return deg * kPi / 180; }
bool Contains(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

std::vector<double> Range(double a, double b, double step) {
    std::vector<double> v;
    for (double x = a; x <= b + 1e-9; x += step) v.push_back(x);
    return v;
}

// An LM-63-2002 file with a fixed layout: line 4 is TILT, 5 and 6 the counts and factors, 7 the
// vertical angles, 8 the horizontal ones, 9.. one line of candela values per horizontal angle.
struct IESFile {
    std::vector<double> vertical, horizontal;
    std::function<double(double, double)> candela;   // (vertical, horizontal) degrees
    double multiplier = 1;
    int type = 1;                                    // 1: C, 2: B, 3: A
    std::string tilt = "TILT=NONE";

    std::vector<std::string> Lines() const {
        std::vector<std::string> l = {"IESNA:LM-63-2002", "[TEST] lucerna", "[MANUFAC] none", tilt};
        std::ostringstream o;
        o.precision(10);
        o << "1 -1 " << multiplier << " " << vertical.size() << " " << horizontal.size() << " " << type << " 2 0 0 0";
        l.push_back(o.str());
        l.push_back("1.0 1.0 0");
        auto join = [](const std::vector<double> &v) {
            std::ostringstream s;
            s.precision(10);
            for (size_t i = 0; i < v.size(); ++i) s << (i ? " " : "") << v[i];
            return s.str();
        };
        l.push_back(join(vertical));
        l.push_back(join(horizontal));
        for (double h : horizontal) {
            std::vector<double> c;
            for (double v : vertical) c.push_back(candela(v, h));
            l.push_back(join(c));
        }
        return l;
    }
};

std::string JoinLines(const std::vector<std::string> &lines) {
    std::string s;
    for (const std::string &l : lines) s += l + "\n";
    return s;
}

void WriteText(const std::string &path, const std::string &text) { std::ofstream(path, std::ios::binary) << text; }

// I0 cos(theta) over the lower hemisphere (theta: the vertical angle from nadir).
IESFile CosineFile() {
    IESFile f;
    f.vertical = Range(0, 90, 2.5);
    f.horizontal = {0};
    f.candela = [](double v, double) { return 1000 * std::cos(Rad(v)); };
    return f;
}

// A batwing, I0 cos(theta) (1 + 2 sin^2(theta) cos^2(phi)), tabulated over 0-90 (quadrant symmetry).
double Batwing(double v, double h) {
    double s = std::sin(Rad(v)), c = std::cos(Rad(h));
    return 500 * std::cos(Rad(v)) * (1 + 2 * s * s * c * c);
}
IESFile BatwingFile() {
    IESFile f;
    f.vertical = Range(0, 90, 2.5);
    f.horizontal = Range(0, 90, 5);
    f.candela = Batwing;
    return f;
}

// ---- Types B and A: one distribution over the forward hemisphere, in both angle systems ----

// g over directions d of the IES frame (docs/lights.md: the photometric axis (0, 0) is -z,
// vertical +90 is +x, horizontal +90 is +y): linear in d, so that every web samples it smoothly;
// 0 behind the luminaire (d.z > 0), where types A and B have no angles.
double G_AB(double x, double y, double z, bool lateralTerm = true) {
    return z > 0 ? 0 : 200 + 40 * x + (lateralTerm ? 25 * y : 0) - 100 * z;
}
// The direction of (v, h) written out from LM-75's definitions, independently of the reader.
// Type B: planes of constant v through the lateral (y) axis, h the elevation towards +y out of them.
// Type A: planes of constant h through the vertical (x) axis, v the elevation towards +x.
Vec3f DirectionAB(int type, double v, double h) {
    double cv = std::cos(Rad(v)), sv = std::sin(Rad(v)), ch = std::cos(Rad(h)), sh = std::sin(Rad(h));
    if (type == 2) return Vec3f(Float(ch * sv), Float(sh), Float(-ch * cv));
    return Vec3f(Float(sv), Float(cv * sh), Float(-cv * ch));
}
IESFile FileAB(int type, bool lateralSymmetric) {
    IESFile f;
    f.type = type;
    f.vertical = Range(-90, 90, 2.5);
    f.horizontal = Range(lateralSymmetric ? 0 : -90, 90, 2.5);
    f.candela = [type, lateralSymmetric](double v, double h) {
        Vec3f d = DirectionAB(type, v, h);
        return G_AB(d.x, d.y, d.z, !lateralSymmetric);
    };
    return f;
}

const char *kHeader = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                      "Camera \"perspective\"\nWorldBegin\n";

// Writes scene.pbrt (kHeader + world: the world starts on line 4) in dir and loads it.
std::unique_ptr<HostScene> LoadWorld(const std::string &dir, const std::string &world, Diagnostics *diagOut = nullptr) {
    WriteText(dir + "/scene.pbrt", std::string(kHeader) + world);
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    if (diagOut) *diagOut = diag;
    return s;
}

// The luminous intensity (cd) light `li` sends towards p, from the shared SampleLi: L d^2 divided
// by the light's spectrum at one wavelength, times Y (a "scale" / SpectrumToPhotometric light of
// 1 cd has l.scale = 1 / CIE_Y_integral for the default illuminant).
double Candela(const HostScene &s, uint32_t li, Vec3f p, Vec3f *wi = nullptr) {
    SceneView v = s.View();
    const Light &l = v.lights[li];
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.37f);
    LightSampleContext ctx{p, Vec3f(0, 1, 0), Vec3f(0, 1, 0)};
    LightLiSample ls;
    if (!SampleLi(l, v, ctx, Vec2f(0.5f, 0.5f), lambda, &ls)) return 0;
    EXPECT_TRUE(ls.isDelta);
    EXPECT_EQ(ls.pdf, 1);
    if (wi) *wi = ls.wi;
    double spectrum = SampleSpectrum(l.spectrum, lambda, v.spectra)[0];
    return double(ls.L[0]) * double(LengthSquared(l.position - p)) / spectrum * CIE_Y_integral;
}

// ---- The reader's evaluation ----

TEST(IESReader, ParsesTheHeaderAndEvaluatesBilinearly) {
    IESFile f = CosineFile();
    f.multiplier = 2;
    IESProfile p = ParseIES(JoinLines(f.Lines()), "cos.ies", "");
    EXPECT_EQ(p.format, "LM-63-2002");
    EXPECT_EQ(p.tilt, "NONE");
    EXPECT_EQ(p.vertical.size(), 37u);
    EXPECT_EQ(p.symmetry, IESSymmetry::Rotational);
    EXPECT_DOUBLE_EQ(p.Evaluate(0, 123), 2000);
    // Halfway between 10 and 12.5 degrees: the mean of the two tabulated values (linear in angle).
    EXPECT_NEAR(p.Evaluate(11.25, 0), 1000 * (std::cos(Rad(10)) + std::cos(Rad(12.5))), 1e-6);
    EXPECT_EQ(p.Evaluate(95, 0), 0);   // above the tabulated range: dark
    EXPECT_NEAR(p.MaxCandela(), 2000, 1e-9);
    EXPECT_TRUE(Contains(p.Describe(), "37 vertical x 1 horizontal angles (rotationally symmetric)")) << p.Describe();
}

// Each symmetry class unfolds to the full circle: the evaluation at any horizontal angle equals the
// generating function (which has that symmetry) within the interpolation error.
TEST(IESReader, UnfoldsEachHorizontalSymmetry) {
    struct Case {
        std::vector<double> h;
        std::function<double(double, double)> f;
        IESSymmetry sym;
    };
    auto quadrant = [](double v, double h) { return 100 + 50 * std::sin(Rad(v)) * std::cos(Rad(2 * h)); };
    auto half0 = [](double v, double h) { return 100 + 50 * std::sin(Rad(v)) * std::cos(Rad(h)); };   // I(h) = I(-h)
    auto half90 = [](double v, double h) { return 100 + 50 * std::sin(Rad(v)) * std::sin(Rad(h)); };  // I(h) = I(180-h)
    auto full = [](double v, double h) {
        return 100 + 50 * std::sin(Rad(v)) * std::cos(Rad(h)) + 30 * std::sin(Rad(v)) * std::sin(Rad(h));
    };
    std::vector<Case> cases = {{Range(0, 90, 2.5), quadrant, IESSymmetry::Quadrant},
                               {Range(0, 180, 2.5), half0, IESSymmetry::Half0To180},
                               {Range(90, 270, 2.5), half90, IESSymmetry::Half90To270},
                               {Range(0, 360, 2.5), full, IESSymmetry::Full}};
    for (const Case &c : cases) {
        IESFile f;
        f.vertical = Range(0, 180, 2.5);
        f.horizontal = c.h;
        f.candela = c.f;
        IESProfile p = ParseIES(JoinLines(f.Lines()), "sym.ies", "");
        EXPECT_EQ(p.symmetry, c.sym);
        double worst = 0;
        for (double h = -180; h <= 720; h += 7.3)
            for (double v = 1; v < 180; v += 11.1) worst = std::max(worst, std::abs(p.Evaluate(v, h) - c.f(v, h)));
        EXPECT_LT(worst, 0.1) << "symmetry " << int(c.sym);   // values ~100, step 2.5 deg: ~0.03
    }
}

TEST(IESReader, TiltIncludeAndOlderFormats) {
    IESFile f = CosineFile();
    std::vector<std::string> l = f.Lines();
    l[0] = "IESNA:LM-63-1995";
    l[3] = "TILT=INCLUDE";
    l.insert(l.begin() + 4, {"1", "3", "0 45 90", "1.0 0.9 0.8"});
    IESProfile p = ParseIES(JoinLines(l), "tilt.ies", "");
    EXPECT_EQ(p.format, "LM-63-1995");
    EXPECT_EQ(p.tilt, "INCLUDE");
    EXPECT_NEAR(p.Evaluate(0, 0), 1000, 1e-9);
    // LM-63-1986: free text before TILT.
    l = f.Lines();
    l[0] = "Some luminaire, measured 1987";
    EXPECT_EQ(ParseIES(JoinLines(l), "old.ies", "").format, "LM-63-1986");
    // Commas between numbers, and values wrapped over several lines, are read as a stream.
    l = f.Lines();
    std::string cd = l[8];
    for (char &c : cd) if (c == ' ') c = ',';
    cd[cd.find(',', cd.size() / 2)] = '\n';
    l[8] = cd;
    EXPECT_NEAR(ParseIES(JoinLines(l), "comma.ies", "").Evaluate(60, 0), 500, 1e-6);
}

// Types B and A: Evaluate at off-grid angles reproduces g; the angles of a direction invert
// DirectionAB; a laterally symmetric (0-90) web equals the full (-90-90) one of the same function.
TEST(IESReader, TypesBAndAEvaluateTheWeb) {
    for (int type : {2, 3}) {
        SCOPED_TRACE(type);
        IESProfile p = ParseIES(JoinLines(FileAB(type, false).Lines()), "ab.ies", "");
        EXPECT_EQ(p.photometricType, type);
        EXPECT_EQ(p.symmetry, IESSymmetry::LateralFull);
        double worst = 0, worstAngles = 0;
        for (double v = -89.3; v < 90; v += 3.7)
            for (double h = -89.1; h < 90; h += 4.3) {
                Vec3f d = DirectionAB(type, v, h);
                worst = std::max(worst, std::abs(p.Evaluate(v, h) - G_AB(d.x, d.y, d.z)));
                double v2, h2;
                IESAnglesOfDirection(d.x, d.y, d.z, &v2, &h2, type);
                worstAngles = std::max({worstAngles, std::abs(v2 - v), std::abs(h2 - h)});
            }
        EXPECT_LT(worst, 0.1);   // values ~200, 2.5 degree steps: ~0.03
        EXPECT_LT(worstAngles, 2e-3);   // float directions near the poles
        EXPECT_EQ(p.Evaluate(95, 0), 0);    // outside [-90, 90]: dark
        EXPECT_EQ(p.Evaluate(0, -100), 0);
        double v, h;   // behind the luminaire: outside the web's angles
        IESAnglesOfDirection(0.1f, 0.2f, 0.97f, &v, &h, type);
        EXPECT_EQ(p.Evaluate(v, h), 0) << v << " " << h;

        IESProfile full = ParseIES(JoinLines([&] { IESFile f = FileAB(type, false); f.candela = FileAB(type, true).candela; return f; }().Lines()), "full.ies", "");
        IESProfile half = ParseIES(JoinLines(FileAB(type, true).Lines()), "half.ies", "");
        EXPECT_EQ(half.symmetry, IESSymmetry::Lateral);
        double diff = 0;
        for (double v = -90; v <= 90; v += 1.3)
            for (double h = -90; h <= 90; h += 1.7) diff = std::max(diff, std::abs(full.Evaluate(v, h) - half.Evaluate(v, h)));
        EXPECT_LT(diff, 1e-9);
        std::vector<float> a = IESEqualAreaTable(full, 64), b = IESEqualAreaTable(half, 64);
        double tdiff = 0;
        for (size_t i = 0; i < a.size(); ++i) tdiff = std::max(tdiff, double(std::abs(a[i] - b[i])));
        EXPECT_LT(tdiff, 1e-3);
        EXPECT_TRUE(Contains(half.Describe(), std::string("type ") + (type == 2 ? "B" : "A") +
                                                  ", TILT=NONE, 73 vertical x 37 horizontal angles (horizontal 0 to 90, "
                                                  "laterally symmetric), vertical -90 to 90"))
            << half.Describe();
    }
}

// ---- TILT: the factor of the tilt table at "iestilt", included or in a separate file ----

std::vector<std::string> TiltedCosine(const std::string &tiltLine, bool include) {
    std::vector<std::string> l = CosineFile().Lines();
    l[3] = tiltLine;
    if (include) l.insert(l.begin() + 4, {"1", "3", "0 45 90", "1.0 0.8 0.5"});
    return l;
}

TEST(IESTilt, FactorInterpolatedInTheTiltTable) {
    IESProfile p = ParseIES(JoinLines(TiltedCosine("TILT=INCLUDE", true)), "tilt.ies", "");
    EXPECT_EQ(p.tiltGeometry, 1);
    double f = 0;
    ASSERT_TRUE(p.TiltFactorAt(30, &f));
    EXPECT_NEAR(f, 1 - 0.2 * 30 / 45, 1e-12);
    ASSERT_TRUE(p.TiltFactorAt(60, &f));
    EXPECT_NEAR(f, 0.8 - 0.3 * 15 / 45, 1e-12);
    ASSERT_TRUE(p.TiltFactorAt(90, &f));
    EXPECT_NEAR(f, 0.5, 1e-12);
    EXPECT_FALSE(p.TiltFactorAt(90.5, &f));
    EXPECT_FALSE(p.TiltFactorAt(-1, &f));
    EXPECT_NEAR(p.Evaluate(20, 0), 1000 * std::cos(Rad(20)), 1e-6);   // not tilted: as measured (10 digits)
    p.SetTilt(30);
    EXPECT_NEAR(p.Evaluate(20, 0), (1 - 0.2 * 30 / 45) * 1000 * std::cos(Rad(20)), 1e-6);
    EXPECT_NEAR(p.MaxCandela(), (1 - 0.2 * 30 / 45) * 1000, 1e-9);
    EXPECT_TRUE(Contains(p.Describe(), "type C, TILT=INCLUDE (lamp geometry 1, 3 tilt angles 0-90; tilted 30 degrees: factor 0.866"))
        << p.Describe();
    EXPECT_FALSE(ParseIES(JoinLines(CosineFile().Lines()), "none.ies", "").TiltFactorAt(0, &f));
}

TEST(IESTilt, IestiltOnLightsAndTiltFiles) {
    std::string dir = test::TempDir("ies_tilt");
    WriteText(dir + "/inc.ies", JoinLines(TiltedCosine("TILT=INCLUDE", true)));
    std::filesystem::create_directories(dir + "/lum");
    WriteText(dir + "/lum/file.ies", JoinLines(TiltedCosine("TILT=lamp.tlt", false)));   // relative to lum/
    WriteText(dir + "/lum/lamp.tlt", "1\n3\n0 45 90\n1.0 0.8 0.5\n");
    WriteText(dir + "/cos.ies", JoinLines(CosineFile().Lines()));
    IESProfile inc = ReadIES(dir + "/inc.ies", FileLoc{}, ""), file = ReadIES(dir + "/lum/file.ies", FileLoc{}, "");
    EXPECT_EQ(file.tilt, "lamp.tlt");
    EXPECT_EQ(file.tiltFile, dir + "/lum/lamp.tlt");
    EXPECT_EQ(file.tiltGeometry, inc.tiltGeometry);
    EXPECT_EQ(file.tiltAngles, inc.tiltAngles);
    EXPECT_EQ(file.tiltFactors, inc.tiltFactors);
    const double want = (1 - 0.2 * 30 / 45) * 1000;
    for (std::string ies : {"inc.ies", "lum/file.ies"}) {
        SCOPED_TRACE(ies);
        for (std::string light : {"point", "goniometric"}) {
            std::string ref = "LightSource \"" + light + "\" \"string " + (light == "point" ? "iesfile" : "filename") + "\" \"" + ies + "\"";
            auto s = LoadWorld(dir, ref + " \"float iestilt\" 30\n" + ref + "\n");
            ASSERT_EQ(s->lights.size(), 2u);
            EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -2, 0)), want, 0.5);   // tilted 30 degrees
            EXPECT_NEAR(Candela(*s, 1, Vec3f(0, -2, 0)), 1000, 0.5);   // no iestilt: as measured
        }
    }
    auto s = LoadWorld(dir, "LightSource \"spot\" \"point3 to\" [0 -1 0] \"float coneangle\" 60 \"string iesfile\" \"lum/file.ies\" "
                            "\"float iestilt\" 90\n");
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -2, 0)), 500, 0.5);
    EXPECT_NE(std::find(s->inputFiles.begin(), s->inputFiles.end(), dir + "/lum/lamp.tlt"), s->inputFiles.end());
    auto error = [&](const std::string &world) -> std::string {
        try {
            LoadWorld(dir, world);
        } catch (const SceneError &e) {
            EXPECT_EQ(e.Loc().Filename(), dir + "/scene.pbrt") << e.Format();
            EXPECT_EQ(e.Loc().line, 4) << e.Format();
            return e.Message();
        }
        ADD_FAILURE() << "no error for " << world;
        return "";
    };
    EXPECT_TRUE(Contains(error("LightSource \"point\" \"string iesfile\" \"cos.ies\" \"float iestilt\" 0\n"),
                         "\"iestilt\" is meaningless: \"cos.ies\" has TILT=NONE"));
    EXPECT_TRUE(Contains(error("LightSource \"point\" \"string iesfile\" \"inc.ies\" \"float iestilt\" 95\n"),
                         "\"iestilt\" 95 is outside the tilt angles of \"inc.ies\" (0-90 degrees"));
}

// ---- The equal-area table and its bilinear lookup ----

TEST(IESTable, BilinearLookupMatchesTheWebEverywhere) {
    IESFile f;
    f.vertical = Range(0, 180, 2.5);
    f.horizontal = Range(0, 360, 5);
    f.candela = [](double v, double h) {
        return 200 + 100 * std::cos(Rad(v)) + 50 * std::sin(Rad(v)) * std::cos(Rad(h - 30));
    };
    std::string dir = test::TempDir("ies_table");
    WriteText(dir + "/web.ies", JoinLines(f.Lines()));
    auto s = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"web.ies\"\n");
    IESProfile p = ReadIES(dir + "/web.ies", FileLoc{}, "");
    ASSERT_EQ(s->lights.size(), 1u);
    SceneView v = s->View();
    const Light &l = v.lights[0];
    EXPECT_TRUE(l.profileVertices);
    // Directions all over the sphere, seams and poles of the octahedral map included.
    std::vector<Vec3f> dirs = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                               {1, 1, 0.001f}, {-1, 1, -0.001f}, {0.3f, -0.2f, -0.93f}, {-0.01f, 0.01f, -1}};
    for (int i = 0; i < 200; ++i) {
        Float a = Float(i) * 0.61803398f, b = Float(i) / 200;
        dirs.push_back(EqualAreaSquareToSphere(Vec2f(a - std::floor(a), b)));
    }
    double worst = 0;
    for (Vec3f w : dirs) {
        w = Normalize(w);
        double vert, hor;
        IESAnglesOfDirection(w.x, w.y, w.z, &vert, &hor);
        double want = p.Evaluate(vert, hor), got = ProfileValue(l, v, w);
        worst = std::max(worst, std::abs(got / want - 1));
    }
    // Measured: 6e-5 (a texel-centered bilinear table: 2.4e-3, along the map's folds).
    EXPECT_LT(worst, 1e-3);
    std::printf("vertex table vs IES evaluation: worst relative difference %.2e\n", worst);
}

// Types B and A: the vertex table against g at directions all over the sphere (not via the
// reader's angles), and the sides in the light's frame: vertical +90 towards +x, horizontal +90
// towards +z (after the y/z swap), the photometric axis -y, nothing behind (+y).
TEST(IESTable, TypesBAndAAxesAndTable) {
    for (int type : {2, 3}) {
        SCOPED_TRACE(type);
        std::string dir = test::TempDir(std::string("ies_table_ab") + char('0' + type));
        WriteText(dir + "/ab.ies", JoinLines(FileAB(type, false).Lines()));
        auto s = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"ab.ies\"\n");
        SceneView v = s->View();
        const Light &l = v.lights[0];
        double worst = 0;
        int n = 0;
        for (int i = 0; i < 4000; ++i) {
            Float a = Float(i) * 0.61803398f, b = (Float(i) + 0.5f) / 4000;
            Vec3f w = EqualAreaSquareToSphere(Vec2f(a - std::floor(a), b));
            if (std::abs(w.z) < 0.02f) continue;   // the lit hemisphere's edge: a step, within a cell
            double want = G_AB(w.x, w.y, w.z), got = ProfileValue(l, v, w);
            worst = std::max(worst, want == 0 ? std::abs(got) : std::abs(got / want - 1));
            ++n;
        }
        EXPECT_GT(n, 3800);
        EXPECT_LT(worst, 1e-3);
        std::printf("type %c: vertex table vs g: worst relative difference %.2e over %d directions\n", type == 2 ? 'B' : 'A',
                    worst, n);
        const double r = std::sqrt(0.5);
        auto light = [&](double x, double y, double z) { return Candela(*s, 0, Vec3f(Float(x), Float(y), Float(z)) * 4); };
        EXPECT_NEAR(light(0, -1, 0), 300, 0.1);                                   // (0, 0): light -y
        EXPECT_NEAR(light(0, -r, r), 200 + 25 * r + 100 * r, 0.1);               // horizontal +45: +z
        EXPECT_NEAR(light(0, -r, -r), 200 - 25 * r + 100 * r, 0.1);
        EXPECT_NEAR(light(r, -r, 0), 200 + 40 * r + 100 * r, 0.1);               // vertical +45: +x
        EXPECT_NEAR(light(-r, -r, 0), 200 - 40 * r + 100 * r, 0.1);
        EXPECT_EQ(light(0, 1, 0), 0);
        EXPECT_EQ(light(0.3, 0.9, 0.2), 0);
        // A lobe at horizontal +30 (vertical 0) lands on the +z side: cos(30) (-y) + sin(30) (+z).
        IESFile f = FileAB(type, false);
        f.candela = [](double v, double h) { return 10 + 1000 * std::exp(-((h - 30) * (h - 30) + v * v) / 50); };
        WriteText(dir + "/lobe.ies", JoinLines(f.Lines()));
        auto lobe = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"lobe.ies\"\n");
        double plus = Candela(*lobe, 0, Vec3f(0, -Float(std::cos(Rad(30))), Float(std::sin(Rad(30)))) * 3);
        double minus = Candela(*lobe, 0, Vec3f(0, -Float(std::cos(Rad(30))), -Float(std::sin(Rad(30)))) * 3);
        double up = Candela(*lobe, 0, Vec3f(Float(std::sin(Rad(30))), -Float(std::cos(Rad(30))), 0) * 3);
        EXPECT_NEAR(plus, 1010, 10);   // the peak, in 0.4 degree table cells: measured 1003.6
        EXPECT_NEAR(minus, 10, 0.5);
        EXPECT_LT(up, 12);
    }
}

// ---- Irradiance on a plane below the luminaire: E = I(theta, phi) cos(theta) / d^2 ----

// Light 0 of s at height 3 above the plane y = 0 (nadir: -y); E from SampleLi at points of the
// plane against the analytic expression, within 1% where E is not tiny.
void ExpectPlaneIrradiance(const HostScene &s, const std::function<double(double, double)> &intensity, double maxTheta,
                           int minPoints = 100) {
    double worst = 0, wx = 0, wz = 0;
    int n = 0;
    for (double x = -6; x <= 6; x += 0.75)
        for (double z = -6; z <= 6; z += 0.75) {
            Vec3f p(Float(x), 0, Float(z));
            double d2 = x * x + 9 + z * z, cosT = 3 / std::sqrt(d2);
            double theta = std::acos(cosT) * 180 / kPi;
            if (theta > maxTheta) continue;
            // C0 along +x, C90 along -z (docs/lights.md).
            double phi = std::atan2(-z, x) * 180 / kPi;
            if (phi < 0) phi += 360;
            Vec3f wi;
            double I = Candela(s, 0, p, &wi);
            double E = I * double(Dot(wi, Vec3f(0, 1, 0))) / d2;
            double want = intensity(theta, phi) * cosT / d2;
            if (std::abs(E / want - 1) > worst) {
                worst = std::abs(E / want - 1);
                wx = x;
                wz = z;
            }
            ++n;
        }
    EXPECT_GT(n, minPoints);
    EXPECT_LT(worst, 0.01);
    std::printf("plane irradiance: %d points, worst relative error %.2e at (%g, 0, %g)\n", n, worst, wx, wz);
}

TEST(IESIrradiance, CosineLuminaireOnAPlane) {
    std::string dir = test::TempDir("ies_cos");
    WriteText(dir + "/cos.ies", JoinLines(CosineFile().Lines()));
    for (const char *light : {"LightSource \"goniometric\" \"string filename\" \"cos.ies\"",
                              "LightSource \"point\" \"string iesfile\" \"cos.ies\""}) {
        SCOPED_TRACE(light);
        auto s = LoadWorld(dir, std::string("AttributeBegin\nTranslate 0 3 0\n") + light + "\nAttributeEnd\n");
        ASSERT_EQ(s->lights.size(), 1u);
        EXPECT_EQ(s->lights[0].kind, LightKind::Goniometric);
        EXPECT_NEAR(s->lights[0].position.y, 3, 1e-6);
        ExpectPlaneIrradiance(*s, [](double t, double) { return 1000 * std::cos(Rad(t)); }, 80);
        // Nothing above the luminaire's horizon (the web ends at 90 degrees).
        EXPECT_EQ(Candela(*s, 0, Vec3f(0, 6, 0)), 0);
    }
}

TEST(IESIrradiance, BatwingLuminaireOnAPlane) {
    std::string dir = test::TempDir("ies_batwing");
    WriteText(dir + "/bat.ies", JoinLines(BatwingFile().Lines()));
    auto s = LoadWorld(dir, "LightSource \"point\" \"point3 from\" [0 3 0] \"string iesfile\" \"bat.ies\"\n");
    ExpectPlaneIrradiance(*s, Batwing, 80);
    // The batwing's wings lie in the C0-C180 plane, which is the x axis: brighter along x than z.
    EXPECT_GT(Candela(*s, 0, Vec3f(3, 0, 0)), 1.4 * Candela(*s, 0, Vec3f(0, 0, 3)));
}

// A web lit only in the C90 half (0-360 file): the axis convention's handedness. With the light's
// +y up, C90 is -z (counterclockwise from +x seen from above); a mirrored frame would light +z.
TEST(IESIrradiance, AxisConventionC0AlongXC90AlongMinusZ) {
    IESFile f;
    f.vertical = Range(0, 180, 5);
    f.horizontal = Range(0, 360, 5);
    f.candela = [](double v, double h) { return 10 + 100 * std::sin(Rad(v)) * std::max(0.0, std::sin(Rad(h))); };
    std::string dir = test::TempDir("ies_axes");
    WriteText(dir + "/c90.ies", JoinLines(f.Lines()));
    auto s = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"c90.ies\"\n");
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, 0, -5)), 110, 0.5);   // C90, vertical 90
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, 0, 5)), 10, 0.5);     // C270
    EXPECT_NEAR(Candela(*s, 0, Vec3f(5, 0, 0)), 10, 0.5);     // C0
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -5, 0)), 10, 0.5);    // nadir: -y
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -5, -5)), 10 + 100 * std::sin(Rad(45)), 0.5);
    // The CTM turns the luminaire: rotated 90 degrees about x, its nadir (-y) becomes -z.
    auto r = LoadWorld(dir, "Rotate 90 1 0 0\nLightSource \"goniometric\" \"string filename\" \"c90.ies\"\n");
    // Rotate 90 about x maps (x, y, z) to (x, -z, y): C90 (-z) goes to +y, C270 (+z) to -y.
    EXPECT_NEAR(Candela(*r, 0, Vec3f(0, 0, -5)), 10, 0.5);   // nadir
    EXPECT_NEAR(Candela(*r, 0, Vec3f(0, 5, 0)), 110, 0.5);   // C90
    EXPECT_NEAR(Candela(*r, 0, Vec3f(0, -5, 0)), 10, 0.5);   // C270
}

// A spot light with an IES profile: the nadir is the spot axis, the cone falloff multiplies.
TEST(IESIrradiance, SpotWithProfile) {
    std::string dir = test::TempDir("ies_spot");
    WriteText(dir + "/cos.ies", JoinLines(CosineFile().Lines()));
    auto s = LoadWorld(dir, "LightSource \"spot\" \"point3 from\" [0 3 0] \"point3 to\" [0 0 0] \"float coneangle\" 50 "
                            "\"float conedeltaangle\" 20 \"string iesfile\" \"cos.ies\"\n");
    ASSERT_EQ(s->lights[0].kind, LightKind::Spot);
    double cosEnd = std::cos(Rad(50)), cosStart = std::cos(Rad(30));
    ExpectPlaneIrradiance(*s, [&](double t, double) {
        double c = std::cos(Rad(t));
        double x = std::clamp((c - cosEnd) / (cosStart - cosEnd), 0.0, 1.0);
        return 1000 * c * x * x * (3 - 2 * x);
    }, 48, 40);
    EXPECT_EQ(Candela(*s, 0, Vec3f(5, 0, 0)), 0);   // outside the cone
}

// ---- pbrt-v4's goniometric light with an image ----

// g(w) over object-space directions; the image holds g at each texel center's direction, with
// pbrt-v4's frame: image (x, y, z) is object (x, z, y).
double G(Vec3f w) { return 1 + 0.8 * w.y + 0.4 * w.z + 0.2 * w.x; }

void WriteGImage(const std::string &path, int n, bool rgb) {
    Image img = MakeImage(n, n, rgb ? 3 : 1);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            Vec3f wi = EqualAreaSquareToSphere(Vec2f((x + 0.5f) / n, (y + 0.5f) / n));
            double g = G(Vec3f(wi.x, wi.z, wi.y));
            if (rgb) {
                img.At(x, y, 0) = float(g * 0.6);
                img.At(x, y, 1) = float(g * 0.9);
                img.At(x, y, 2) = float(g * 1.5);
            } else {
                img.At(x, y, 0) = float(g);
            }
        }
    WriteEXR(path, img);
}

TEST(Goniometric, ImageIntensityAlongDirections) {
    std::string dir = test::TempDir("gonio_image");
    const int n = 64;
    WriteGImage(dir + "/g.exr", n, true);
    auto s = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"g.exr\" \"float scale\" 2\n");
    ASSERT_EQ(s->lights.size(), 1u);
    const Light &l = s->lights[0];
    EXPECT_EQ(l.kind, LightKind::Goniometric);
    EXPECT_FALSE(l.profileVertices);
    EXPECT_NEAR(l.scale * CIE_Y_integral, 2, 2e-3);   // scale / SpectrumToPhotometric(I)
    // Towards the texel centers the nearest lookup returns the texel: 2 g exactly (RGB averaged).
    for (Vec2f uv : {Vec2f(0.5f / n, 0.5f / n), Vec2f(31.5f / n, 31.5f / n), Vec2f(10.5f / n, 50.5f / n),
                     Vec2f(60.5f / n, 3.5f / n), Vec2f(33.5f / n, 40.5f / n)}) {
        Vec3f wi = EqualAreaSquareToSphere(uv);
        Vec3f w(wi.x, wi.z, wi.y);
        EXPECT_NEAR(Candela(*s, 0, w * 4), 2 * G(w), 2e-3 * G(w)) << uv.x << " " << uv.y;
    }
    // Anywhere: g within the nearest texel's variation (texels ~3.2 degrees wide).
    for (Vec3f w : {Vec3f(0, 1, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1), Vec3f(0, 0, -1), Vec3f(1, 0, 0), Vec3f(-0.3f, 0.5f, 0.8f)}) {
        w = Normalize(w);
        EXPECT_NEAR(Candela(*s, 0, w * 3), 2 * G(w), 2 * 0.06) << w.x << " " << w.y << " " << w.z;
    }
    // Power: scale so that the luminous flux is "power": the mean of g is 1, so I = P / (4 pi) g.
    auto p = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"g.exr\" \"float power\" 100\n");
    double k_e = ProfileIntegral(p->images[p->lights[0].profile], p->texels.data(), false);
    EXPECT_NEAR(k_e / (4 * kPi), 1, 2e-3);
    EXPECT_NEAR(p->lights[0].scale * CIE_Y_integral * k_e, 100, 0.05);
    EXPECT_NEAR(Candela(*p, 0, Vec3f(0, 5, 0)), 100 / (4 * kPi) * G(Vec3f(0, 1, 0)), 0.3);
    // The light sampler sees pbrt-v4's Phi: twice the power, twice the pick probability.
    auto two = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"g.exr\" \"float power\" 100\n"
                              "LightSource \"goniometric\" \"string filename\" \"g.exr\" \"float power\" 200\n");
    ASSERT_EQ(two->lightCdf.size(), 3u);
    EXPECT_NEAR(two->lightCdf[1], 1.0 / 3, 1e-3);
}

TEST(Goniometric, OneChannelImageAndErrors) {
    std::string dir = test::TempDir("gonio_y");
    WriteGImage(dir + "/y.exr", 32, false);
    auto s = LoadWorld(dir, "LightSource \"goniometric\" \"string filename\" \"y.exr\"\n");
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, 7, 0)), G(Vec3f(0, 1, 0)), 0.12);
    auto error = [&](const std::string &world) -> std::string {
        try {
            LoadWorld(dir, world);
        } catch (const SceneError &e) {
            EXPECT_EQ(e.Loc().line, 4) << e.Format();
            return e.Message();
        }
        ADD_FAILURE() << "no error for " << world;
        return "";
    };
    EXPECT_TRUE(Contains(error("LightSource \"goniometric\"\n"), "\"string filename\" must name")) ;
    WriteEXR(dir + "/rect.exr", MakeImage(8, 4, 3, 1));
    EXPECT_TRUE(Contains(error("LightSource \"goniometric\" \"string filename\" \"rect.exr\"\n"), "non-square"));
    WriteEXR(dir + "/neg.exr", MakeImage(4, 4, 1, -1));
    EXPECT_TRUE(Contains(error("LightSource \"goniometric\" \"string filename\" \"neg.exr\"\n"), "negative value"));
    WriteEXR(dir + "/black.exr", MakeImage(4, 4, 1, 0));
    EXPECT_TRUE(Contains(error("LightSource \"goniometric\" \"string filename\" \"black.exr\" \"float power\" 5\n"),
                         "zero everywhere"));
    EXPECT_TRUE(Contains(error("LightSource \"goniometric\" \"string filename\" \"missing.exr\"\n"), "missing.exr"));
}

// ---- "power" with IES profiles ----

TEST(IESPower, GoniometricPointAndSpot) {
    std::string dir = test::TempDir("ies_power");
    WriteText(dir + "/cos.ies", JoinLines(CosineFile().Lines()));
    // The cosine web's flux is pi I0: "power" 100 gives 100 / pi cd at nadir.
    for (const char *light : {"LightSource \"goniometric\" \"string filename\" \"cos.ies\" \"float power\" 100",
                              "LightSource \"point\" \"string iesfile\" \"cos.ies\" \"float power\" 100"}) {
        SCOPED_TRACE(light);
        auto s = LoadWorld(dir, std::string(light) + "\n");
        EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -2, 0)) / (100 / kPi), 1, 3e-3);
    }
    // Spot: the flux of the profile inside the cone, integrated here over the polar angle.
    auto s = LoadWorld(dir, "LightSource \"spot\" \"point3 to\" [0 -1 0] \"float coneangle\" 40 \"float conedeltaangle\" 15 "
                            "\"string iesfile\" \"cos.ies\" \"float power\" 100\n");
    double cosEnd = std::cos(Rad(40)), cosStart = std::cos(Rad(25)), flux = 0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i) {
        double t = (i + 0.5) / steps * kPi / 2, c = std::cos(t);
        double x = std::clamp((c - cosEnd) / (cosStart - cosEnd), 0.0, 1.0);
        flux += 2 * kPi * c * x * x * (3 - 2 * x) * std::sin(t) * (kPi / 2 / steps);
    }
    EXPECT_NEAR(Candela(*s, 0, Vec3f(0, -2, 0)) / (100 / flux), 1, 3e-3);
}

// ---- Malformed IES files: one test per class, at FILE:LINE, naming the referencing statement ----

struct IESErrorCase {
    const char *name;
    std::function<void(std::vector<std::string> &)> edit;
    int line;            // 0: the last line of the edited file
    const char *needle;
    const char *tiltText = nullptr;   // written to lamp.tlt (the edit says TILT=lamp.tlt): the error is there
};

class MalformedIES : public ::testing::TestWithParam<IESErrorCase> {};

TEST_P(MalformedIES, IsAnErrorAtFileAndLine) {
    const IESErrorCase &c = GetParam();
    std::string dir = test::TempDir(std::string("ies_bad_") + c.name);
    std::vector<std::string> lines = CosineFile().Lines();
    if (std::string(c.name) == "HorizontalNotIncreasing" || std::string(c.name) == "HorizontalRange" ||
        std::string(c.name) == "Full360Mismatch")
        lines = [] {   // a 0-360 web: 5 horizontal angles on line 8, candela lines 9-13
            IESFile f = CosineFile();
            f.horizontal = Range(0, 360, 90);
            f.candela = [](double v, double h) { return 100 + v + (h == 90 ? 10 : 0); };
            return f.Lines();
        }();
    c.edit(lines);
    WriteText(dir + "/bad.ies", JoinLines(lines));
    if (c.tiltText) WriteText(dir + "/lamp.tlt", c.tiltText);
    const std::string file = dir + (c.tiltText ? "/lamp.tlt" : "/bad.ies");
    int line = c.line ? c.line : int(lines.size());
    std::string world = "AttributeBegin\nLightSource \"goniometric\" \"string filename\" \"bad.ies\"\nAttributeEnd\n";
    try {
        LoadWorld(dir, world);
        ADD_FAILURE() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().Filename(), file) << e.Format();
        EXPECT_EQ(e.Loc().line, line) << e.Format();
        EXPECT_TRUE(Contains(e.Message(), c.needle)) << e.Message();
        EXPECT_TRUE(Contains(e.Message(), "scene.pbrt:5:")) << e.Message();   // the LightSource statement
        EXPECT_TRUE(Contains(e.Format(), file + ":" + std::to_string(line) + ": error: ")) << e.Format();
        if (c.tiltText) {
            EXPECT_TRUE(Contains(e.Message(), "tilt file of " + dir + "/bad.ies:4")) << e.Message();
        }
    }
}

const IESErrorCase kIESErrors[] = {
    {"MissingTilt", [](auto &l) { l.erase(l.begin() + 3); }, 0, "no \"TILT=\" line"},
    {"TiltFileMissing", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 4, "cannot open the tilt file \""},
    {"ExtraNumbers", [](auto &l) { l.push_back("7 8"); }, 10, "more number(s) after the last candela value"},
    {"Truncated", [](auto &l) { l.back() = l.back().substr(0, l.back().rfind(' ')); }, 9, "ends after 36 of the 37 candela values"},
    {"TruncatedHeader", [](auto &l) { l.resize(5); l[4] = "1 -1 1 37"; }, 5, "ends before the number of horizontal angles"},
    {"VerticalNotIncreasing", [](auto &l) { l[6] = "0 5 2.5" + l[6].substr(l[6].find(" 7.5")); }, 7, "vertical angles must increase"},
    {"VerticalOutOfRange", [](auto &l) { l[6] = l[6].substr(0, l[6].rfind(' ')) + " 190"; }, 7, "outside [0, 180]"},
    {"HorizontalNotIncreasing", [](auto &l) { l[7] = "0 180 90 270 360"; }, 8, "horizontal angles must increase"},
    {"HorizontalRange", [](auto &l) { l[7] = "0 90 180 270 300"; }, 8, "horizontal angles must run"},
    {"Full360Mismatch", [](auto &l) { l.back() = "1" + l.back(); }, 0, "horizontal 0 and 360"},
    {"NegativeCandela", [](auto &l) { l[8] = "-5" + l[8].substr(l[8].find(' ')); }, 9, "negative candela value -5 (vertical 0, horizontal 0)"},
    {"NaN", [](auto &l) { l[8] = "nan" + l[8].substr(l[8].find(' ')); }, 9, "not a finite number"},
    {"NotANumber", [](auto &l) { l[8] = "12x" + l[8].substr(l[8].find(' ')); }, 9, "\"12x\" (not a number)"},
    {"CountMismatch", [](auto &l) { l[4] = "1 -1 1 38 1 1 2 0 0 0"; l[6] += " 92.5"; }, 9,
     "ends after 37 of the 38 candela values (38 vertical x 1 horizontal angles)"},
    {"PhotometricType", [](auto &l) { l[4] = "1 -1 1 37 1 4 2 0 0 0"; }, 5, "must be 1 (C), 2 (B) or 3 (A) (got 4)"},
    {"TypeCVerticalNegative", [](auto &l) { l[6] = "-2.5" + l[6].substr(l[6].find(' ')); }, 7, "vertical angle -2.5 is outside [0, 180] degrees (type C)"},
    // Types B and A: vertical and horizontal angles in [-90, 90]; horizontal -90..90 or 0..90.
    {"TypeBVerticalRange", [](auto &l) { l = FileAB(2, false).Lines(); l[6] = "-92.5" + l[6].substr(l[6].find(' ')); }, 7,
     "vertical angle -92.5 is outside [-90, 90] degrees (type B)"},
    {"TypeAVertical180", [](auto &l) { IESFile f = FileAB(3, true); f.vertical = Range(0, 180, 5); l = f.Lines(); }, 7,
     "vertical angle 95 is outside [-90, 90] degrees (type A)"},
    {"TypeAHorizontal0To180", [](auto &l) { IESFile f = FileAB(3, true); f.horizontal = Range(0, 180, 10); l = f.Lines(); }, 8,
     "horizontal angles must run from -90 to 90 degrees, or from 0 to 90 (laterally symmetric) (type A); got 0 to 180"},
    {"TypeBHorizontalHalf", [](auto &l) { IESFile f = FileAB(2, true); f.horizontal = Range(-45, 90, 5); l = f.Lines(); }, 8,
     "(type B); got -45 to 90"},
    {"TypeBSingleHorizontal", [](auto &l) { IESFile f = FileAB(2, true); f.horizontal = {0}; l = f.Lines(); }, 8,
     "(type B); got the single angle 0"},
    {"TypeACountMismatch", [](auto &l) { l = FileAB(3, true).Lines(); l.pop_back(); }, 0,
     "ends after 2628 of the 2701 candela values (73 vertical x 37 horizontal angles)"},
    // TILT=INCLUDE and TILT=<file>.
    {"TiltGeometry", [](auto &l) { l[3] = "TILT=INCLUDE"; l.insert(l.begin() + 4, {"4", "1", "0", "1"}); }, 5,
     "lamp-to-luminaire geometry must be 1, 2 or 3 (got 4)"},
    {"TiltCount", [](auto &l) { l[3] = "TILT=INCLUDE"; l.insert(l.begin() + 4, {"2", "0", "0", "1"}); }, 6,
     "the number of tilt angles must be at least 1 (got 0)"},
    {"TiltNegativeFactor", [](auto &l) { l[3] = "TILT=INCLUDE"; l.insert(l.begin() + 4, {"3", "2", "0 90", "1 -0.5"}); }, 8,
     "negative tilt multiplying factor -0.5"},
    {"TiltFileGeometry", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 2, "lamp-to-luminaire geometry must be 1, 2 or 3 (got 0)",
     "\n0\n1\n0\n1\n"},
    {"TiltFileTruncated", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 4, "the file ends before tilt multiplying factor 3 of 3",
     "1\n3\n0 45 90\n1 0.9\n"},
    {"TiltFileExtraNumbers", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 5,
     "1 more number(s) after the last tilt multiplying factor (2 tilt angles)", "1\n2\n0 90\n1 0.5\n7\n"},
    {"TiltFileNotANumber", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 3, "\"4x\" (not a number)", "1\n2\n0 4x\n1 0.5\n"},
    {"TiltFileAnglesOutOfRange", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 3, "tilt angle 120 is outside [0, 90] degrees",
     "2 2\n0\n120\n1 0.5\n"},
    {"TiltFileEmpty", [](auto &l) { l[3] = "TILT=lamp.tlt"; }, 1, "the file ends before the lamp-to-luminaire geometry", ""},
    {"BadMultiplier", [](auto &l) { l[4] = "1 -1 0 37 1 1 2 0 0 0"; }, 5, "candela multiplier must be positive"},
    {"FractionalCount", [](auto &l) { l[4] = "1 -1 1 36.5 1 1 2 0 0 0"; }, 5, "as an integer"},
    {"BadTiltInclude", [](auto &l) { l[3] = "TILT=INCLUDE"; l.insert(l.begin() + 4, {"1", "3", "0 90", "1 0.9 0.8"}); }, 8,
     "tilt angles must increase: 1 follows 90"},
    {"Empty", [](auto &l) { l.clear(); }, 1, "empty file"},
};

INSTANTIATE_TEST_SUITE_P(All, MalformedIES, ::testing::ValuesIn(kIESErrors),
                         [](const ::testing::TestParamInfo<IESErrorCase> &i) { return std::string(i.param.name); });

TEST(MalformedIESFile, MissingFileIsAnErrorAtTheStatement) {
    std::string dir = test::TempDir("ies_missing");
    try {
        LoadWorld(dir, "LightSource \"spot\" \"string iesfile\" \"nope.ies\"\n");
        ADD_FAILURE() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().line, 4);
        EXPECT_TRUE(Contains(e.Message(), "nope.ies\": cannot open")) << e.Message();
    }
}

// ---- The CLI: `lucerna info` lists the profiles; a malformed file is exit 2 at FILE:LINE ----

TEST(IESCommandLine, InfoListsProfilesAndBadFilesExitTwo) {
    std::string dir = test::TempDir("ies_cli");
    WriteText(dir + "/cos.ies", JoinLines(CosineFile().Lines()));
    WriteText(dir + "/bat.ies", JoinLines(BatwingFile().Lines()));
    WriteGImage(dir + "/g.exr", 16, false);
    WriteText(dir + "/scene.pbrt", std::string(kHeader) +
                                       "LightSource \"goniometric\" \"string filename\" \"cos.ies\"\n"
                                       "LightSource \"point\" \"string iesfile\" \"bat.ies\"\n"
                                       "LightSource \"spot\" \"string iesfile\" \"cos.ies\"\n"
                                       "LightSource \"goniometric\" \"string filename\" \"g.exr\"\n"
                                       "LightSource \"point\"\n");
    test::ProcessResult r = test::RunProcess({test::LucernaBinary(), "info", dir + "/scene.pbrt"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(Contains(r.output, "lights: 5 (goniometric 2, point 2, spot 1)")) << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 0: goniometric \"cos.ies\": LM-63-2002, type C, TILT=NONE, 37 vertical x 1 "
                                   "horizontal angles (rotationally symmetric), vertical 0-90, peak 1000 cd\n"))
        << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 1: point \"bat.ies\": LM-63-2002, type C, TILT=NONE, 37 vertical x 19 "
                                   "horizontal angles (horizontal 0-90, quadrant symmetry)"))
        << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 2: spot \"cos.ies\": LM-63-2002")) << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 3: goniometric \"g.exr\": 16 x 16 equal-area image (Y)")) << r.output;
    EXPECT_FALSE(Contains(r.output, "light 4:")) << r.output;
    // Types B and A and the tilt.
    WriteText(dir + "/b.ies", JoinLines(FileAB(2, true).Lines()));
    WriteText(dir + "/tilt.ies", JoinLines(TiltedCosine("TILT=INCLUDE", true)));
    WriteText(dir + "/ab.pbrt", std::string(kHeader) + "LightSource \"point\" \"string iesfile\" \"b.ies\"\n"
                                                       "LightSource \"point\" \"string iesfile\" \"tilt.ies\" \"float iestilt\" 45\n");
    r = test::RunProcess({test::LucernaBinary(), "info", dir + "/ab.pbrt"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 0: point \"b.ies\": LM-63-2002, type B, TILT=NONE, 73 vertical x 37 horizontal angles "
                                   "(horizontal 0 to 90, laterally symmetric), vertical -90 to 90, peak "))
        << r.output;
    EXPECT_TRUE(Contains(r.output, "  light 1: point \"tilt.ies\": LM-63-2002, type C, TILT=INCLUDE (lamp geometry 1, 3 tilt "
                                   "angles 0-90; tilted 45 degrees: factor 0.8), 37 vertical"))
        << r.output;

    std::vector<std::string> bad = CosineFile().Lines();
    bad[10 - 2] = "3 -4 5";   // line 9: the candela values
    WriteText(dir + "/bad.ies", JoinLines(bad));
    WriteText(dir + "/bad.pbrt", std::string(kHeader) + "LightSource \"point\" \"string iesfile\" \"bad.ies\"\n");
    for (const char *cmd : {"info", "render"}) {
        test::ProcessResult b = test::RunProcess({test::LucernaBinary(), cmd, dir + "/bad.pbrt", "-o", dir + "/bad.exr"});
        if (std::string(cmd) == "info") b = test::RunProcess({test::LucernaBinary(), cmd, dir + "/bad.pbrt"});
        EXPECT_EQ(b.exitCode, 2) << b.output;
        EXPECT_TRUE(Contains(b.output, dir + "/bad.ies:9: error: negative candela value -4")) << b.output;
        EXPECT_TRUE(Contains(b.output, "LightSource \"point\" at " + dir + "/bad.pbrt:4:")) << b.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.exr"));
}

}  // namespace
}  // namespace lu
