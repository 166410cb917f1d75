// Lucerna: manifold next-event estimation. The solver against analytic chains (a glass slab, a
// glass sphere, a thin sheet), its generalized geometry term against finite differences, the
// issue's point light under a thin sheet (the transmittance product), and the MIS between MNEE and
// BSDF sampling: MNEE alone, BSDF sampling alone and their combination render the same caustic.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/render_helpers.h"
#include "lucerna/backend/cpu/embree_scene.h"
#include "lucerna/integrators/mnee.h"

namespace lu::test {
namespace {

const char *kHead =
    "LookAt 0 0 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 6 ]\n"
    "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nWorldBegin\n";

// A horizontal quad at height z, facing +z (up) or -z.
std::string Quad(double z, double half, bool up) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "Shape \"trianglemesh\" \"integer indices\" [ %s ] \"point3 P\" [ %g %g %g  %g %g %g  %g %g %g  %g %g %g ]\n",
                  up ? "0 1 2 0 2 3" : "0 2 1 0 3 2", -half, -half, z, half, -half, z, half, half, z, -half, half, z);
    return buf;
}
// A glass slab between heights z0 < z1 (its two large faces, outward normals).
std::string Slab(double z0, double z1) {
    return "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\n" + Quad(z1, 4, true) + Quad(z0, 4, false) +
           "AttributeEnd\n";
}

struct Fixture {
    std::unique_ptr<HostScene> scene;
    SceneView view;
    std::unique_ptr<EmbreeScene> embree;
    EmbreeTracer tracer;
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    explicit Fixture(const std::string &name, const std::string &world) {
        scene = LoadSceneText(name, std::string(kHead) + world);
        view = scene->View();
        embree = std::make_unique<EmbreeScene>(view);
        tracer = EmbreeTracer{embree.get()};
    }
    bool Find(Vec3f x0, Vec3f n0, Vec3f y, Vec3f nY, MneeChain *ch, MneeThroughput *tp) const {
        return FindMneeChain(view, tracer, x0, n0, y, nY, lambda, ch, tp);
    }
};

// Refraction of the unit direction d (travelling towards the surface) at unit normal n, relative
// index eta = n_out / n_in... written out in double, independent of the renderer's Refract.
bool RefractD(const double d[3], const double nIn[3], double eta, double out[3]) {
    double n[3] = {nIn[0], nIn[1], nIn[2]};
    double c = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
    if (c < 0) { for (double &v : n) v = -v; c = -c; }
    double r = 1 / eta, k = 1 - r * r * (1 - c * c);
    if (k < 0) return false;
    for (int i = 0; i < 3; ++i) out[i] = r * d[i] + (r * c - std::sqrt(k)) * n[i];
    return true;
}
double AngleBetween(const double a[3], const double b[3]) {
    double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    return std::acos(std::min(1.0, std::max(-1.0, c)));
}
// Snell's law at every vertex of a chain through glass of index 1.5 entered from air, checked by
// refracting the incoming segment and comparing with the outgoing one (radians).
double WorstSnellError(const MneeChain &ch, const Vec3f &sphereCenter, bool sphere) {
    double worst = 0;
    for (int i = 0; i < ch.k; ++i) {
        Vec3f a = i == 0 ? ch.x0 : ch.v[i - 1].p, p = ch.v[i].p, b = i == ch.k - 1 ? ch.y : ch.v[i + 1].p;
        double d[3] = {double(p.x - a.x), double(p.y - a.y), double(p.z - a.z)};
        double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (double &v : d) v /= l;
        double n[3];
        if (sphere) {
            Vec3f nn = Normalize(p - sphereCenter);
            n[0] = nn.x; n[1] = nn.y; n[2] = nn.z;
        } else {
            n[0] = 0; n[1] = 0; n[2] = 1;
        }
        double eta = (i % 2 == 0) ? 1.5 : 1 / 1.5;   // in, out, in, out ...
        double r[3], o[3] = {double(b.x - p.x), double(b.y - p.y), double(b.z - p.z)};
        if (!RefractD(d, n, eta, r)) return 1e9;
        worst = std::max(worst, AngleBetween(r, o));
    }
    return worst;
}

// Unpolarized Fresnel reflectance entering glass of index eta from air at cos theta_i.
double FresnelR(double cosI, double eta) {
    double sinT = std::sqrt(std::max(0.0, 1 - cosI * cosI)) / eta, cosT = std::sqrt(1 - sinT * sinT);
    double rs = (cosI - eta * cosT) / (cosI + eta * cosT), rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

}  // namespace

// The chain through a slab between z = 0.4 and 0.5, from x0 on the floor to a light point at
// height 1: the lateral offsets of a parallel slab, h tan theta_air + t tan theta_glass.
TEST(Mnee, SolvesASlabChainToTheAnalyticOffsets) {
    Fixture f("mnee_slab", Slab(0.4, 0.5));
    for (double D : {0.0, 0.2, 0.6, 1.5}) {
        MneeChain ch;
        MneeThroughput tp;
        Vec3f x0(0.05f, -0.1f, 0), y(0.05f + float(D), -0.1f, 1);
        ASSERT_TRUE(f.Find(x0, Vec3f(0, 0, 1), y, Vec3f(0, 0, -1), &ch, &tp)) << D;
        ASSERT_EQ(ch.k, 2);
        // Solve D = (0.4 + 0.5) tan a + 0.1 tan g, sin a = 1.5 sin g, by bisection on a.
        double lo = 0, hi = M_PI / 2 - 1e-9;
        for (int it = 0; it < 200; ++it) {
            double a = 0.5 * (lo + hi), g = std::asin(std::sin(a) / 1.5);
            ((0.9 * std::tan(a) + 0.1 * std::tan(g)) < D ? lo : hi) = a;
        }
        double a = 0.5 * (lo + hi), g = std::asin(std::sin(a) / 1.5);
        EXPECT_NEAR(ch.v[0].p.x, 0.05 + 0.4 * std::tan(a), 2e-4) << D;
        EXPECT_NEAR(ch.v[0].p.z, 0.4, 1e-5);
        EXPECT_NEAR(ch.v[1].p.x, 0.05 + 0.4 * std::tan(a) + 0.1 * std::tan(g), 2e-4) << D;
        EXPECT_NEAR(ch.v[1].p.y, -0.1, 1e-4);
        EXPECT_LT(WorstSnellError(ch, Vec3f(), false), 1e-3) << D;
        EXPECT_LT(ch.iterations, MaxMneeIterations);
        // Through the slab: two Fresnel transmissions (equal, by reciprocity), and the radiance's
        // 1/eta^2 going in and eta^2 coming out cancel.
        EXPECT_NEAR(tp.weight[0], Sqr(1 - FresnelR(std::cos(a), 1.5)), 1e-3) << D;
    }
}

// Through a glass ball: two refractions with curved normals (dn/ds = 1/R). The light points are
// made by tracing rays from x0 through the ball (double precision, analytic refraction), so each
// has a chain; MNEE from the straight seed must find one for nearly all (near the ball's caustic
// several chains meet and Newton may fail: the regularized connection keeps those), and every
// chain it returns must obey Snell's law; where it finds the traced one, at the traced positions.
TEST(Mnee, SolvesSphereChains) {
    Fixture f("mnee_sphere", "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0 0.5\n"
                             "Shape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n");
    const double c[3] = {0, 0, 0.5}, R = 0.3, x0[3] = {0.05, 0, 0};
    auto hitSphere = [&](const double o[3], const double d[3], bool farSide, double out[3]) {
        double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
        double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2], cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - R * R;
        double disc = b * b - cc;
        if (disc < 0) return false;
        double t = farSide ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
        if (t <= 1e-9) return false;
        for (int i = 0; i < 3; ++i) out[i] = o[i] + t * d[i];
        return true;
    };
    int solved = 0, tried = 0, same = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 8; ++j) {
            // A direction from x0 towards the ball, within 25 degrees of the centre's direction.
            double th = 0.44 * (i + 0.5) / 6, ph = 2 * M_PI * j / 8;
            double toC[3] = {c[0] - x0[0], c[1] - x0[1], c[2] - x0[2]};
            double l = std::sqrt(toC[0] * toC[0] + toC[1] * toC[1] + toC[2] * toC[2]);
            for (double &v : toC) v /= l;
            double a[3] = {1, 0, 0}, b[3];
            // b = toC x a, a = b x toC (an orthonormal pair around toC)
            b[0] = toC[1] * a[2] - toC[2] * a[1]; b[1] = toC[2] * a[0] - toC[0] * a[2]; b[2] = toC[0] * a[1] - toC[1] * a[0];
            double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            for (double &v : b) v /= lb;
            a[0] = b[1] * toC[2] - b[2] * toC[1]; a[1] = b[2] * toC[0] - b[0] * toC[2]; a[2] = b[0] * toC[1] - b[1] * toC[0];
            double d0[3];
            for (int k = 0; k < 3; ++k) d0[k] = std::cos(th) * toC[k] + std::sin(th) * (std::cos(ph) * a[k] + std::sin(ph) * b[k]);
            double p1[3], p2[3], d1[3], d2[3], n1[3], n2[3];
            if (!hitSphere(x0, d0, false, p1)) continue;
            for (int k = 0; k < 3; ++k) n1[k] = (p1[k] - c[k]) / R;
            if (!RefractD(d0, n1, 1.5, d1) || !hitSphere(p1, d1, true, p2)) continue;
            for (int k = 0; k < 3; ++k) n2[k] = (p2[k] - c[k]) / R;
            if (!RefractD(d1, n2, 1 / 1.5, d2) || d2[2] <= 0) continue;
            double t = (1.2 - p2[2]) / d2[2];
            Vec3f y(float(p2[0] + t * d2[0]), float(p2[1] + t * d2[1]), 1.2f);
            MneeChain ch;
            MneeThroughput tp;
            ++tried;
            if (!f.Find(Vec3f(0.05f, 0, 0), Vec3f(0, 0, 1), y, Vec3f(0, 0, -1), &ch, &tp)) continue;
            ++solved;
            ASSERT_EQ(ch.k, 2);
            EXPECT_LT(WorstSnellError(ch, Vec3f(0, 0, 0.5f), true), 1e-3) << i << " " << j;
            for (int v = 0; v < 2; ++v) EXPECT_NEAR(Length(ch.v[v].p - Vec3f(0, 0, 0.5f)), 0.3f, 1e-4f);
            double dx = ch.v[0].p.x - p1[0], dy = ch.v[0].p.y - p1[1], dz = ch.v[0].p.z - p1[2];
            if (std::sqrt(dx * dx + dy * dy + dz * dz) < 1e-3) ++same;
        }
    std::printf("sphere chains: %d traced, %d solved, %d the traced one\n", tried, solved, same);
    ASSERT_GT(tried, 30);
    EXPECT_GE(solved, tried * 9 / 10) << "the solver missed chains through the ball";
    EXPECT_GE(same, solved * 3 / 4) << "(the others found another valid chain: near the caustic there are several)";
}

// The constraint Jacobian A = dC/dX against central differences on a ball, away from the
// solution (the seed chain): each vertex moved along its tangent coordinates and re-projected onto
// the sphere, the constraint frame carried along without twist (as the linearization assumes).
TEST(Mnee, ConstraintJacobianMatchesFiniteDifferences) {
    Fixture f("mnee_jac", "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0 0.5\n"
                          "Shape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n");
    const Vec3f c(0, 0, 0.5f);
    MneeChain ch;
    ASSERT_TRUE(SeedMneeChain(f.view, f.tracer, Vec3f(0.05f, 0, 0), Vec3f(0, 0, 1), Vec3f(-0.12f, -0.12f, 1.2f),
                              Vec3f(0, 0, -1), f.lambda, &ch));
    ASSERT_EQ(ch.k, 2);
    Float C[4], A[16];
    MneeConstraintState cs[2];
    ASSERT_LT(MneeConstraints(ch, C, cs), 1.f);
    MneeJacobian(ch, cs, A);
    const Float h = 1e-3f;
    for (int j = 0; j < 2; ++j)
        for (int e = 0; e < 2; ++e) {
            Float Cp[2][4];
            for (int sgn = 0; sgn < 2; ++sgn) {
                MneeChain m = ch;
                MneeVertex &v = m.v[j];
                Vec3f p = v.p + (e == 0 ? v.ps : v.pt) * (sgn == 0 ? h : -h);
                v.p = c + Normalize(p - c) * 0.3f;
                v.n = Normalize(v.p - c);
                v.s = Normalize(v.s - v.n * Dot(v.n, v.s));
                v.t = Cross(v.n, v.s);
                MneeConstraintState t[2];
                MneeConstraints(m, Cp[sgn], t);
            }
            for (int r = 0; r < 4; ++r) {
                double fd = (double(Cp[0][r]) - Cp[1][r]) / (2 * h), an = A[r * 4 + 2 * j + e];
                EXPECT_NEAR(an, fd, 2e-2 * std::max(1.0, std::abs(fd))) << "row " << r << " vertex " << j << " dir " << e;
            }
        }
}

// A thin sheet bends nothing: no vertex to solve, its transmittance (1 - R) / (1 + R) per crossing.
TEST(Mnee, CrossesAThinSheetStraight) {
    Fixture f("mnee_thin", "AttributeBegin\nMaterial \"thindielectric\" \"float eta\" [ 1.5 ]\n" + Quad(0.5, 4, true) +
                               "AttributeEnd\n");
    MneeChain ch;
    MneeThroughput tp;
    ASSERT_TRUE(f.Find(Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec3f(0, 0, 1), Vec3f(0, 0, -1), &ch, &tp));
    EXPECT_EQ(ch.k, 0);
    double R = 0.04;   // normal incidence, eta 1.5
    EXPECT_NEAR(tp.weight[0], (1 - R) / (1 + R), 1e-4);
    EXPECT_NEAR(MneeGeometry(ch, true), 1.0, 1e-5);   // cos / d^2 with d = 1
    // A diffuse blocker ends the chain.
    Fixture g("mnee_block", "AttributeBegin\nMaterial \"diffuse\"\n" + Quad(0.5, 4, true) + "AttributeEnd\n");
    EXPECT_FALSE(g.Find(Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec3f(0, 0, 1), Vec3f(0, 0, -1), &ch, &tp));
}

// |d omega_0 / dA_y| and |d omega_y / dA_x0| from the implicit function theorem against central
// differences of re-solved chains, for the slab and the ball.
TEST(Mnee, GeometryTermMatchesFiniteDifferences) {
    struct Case {
        std::string world;
        Vec3f x0, y;
    };
    std::vector<Case> cases = {
        {Slab(0.4, 0.5), Vec3f(0, 0, 0), Vec3f(0.5f, 0.2f, 1)},
        {"AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0 0.5\n"
         "Shape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n",
         Vec3f(0.05f, 0, 0), Vec3f(-0.1f, 0.05f, 1.2f)},
    };
    int idx = 0;
    for (const Case &c : cases) {
        Fixture f("mnee_fd" + std::to_string(idx++), c.world);
        Vec3f n0(0, 0, 1), nY(0, 0, -1);
        MneeChain ch;
        MneeThroughput tp;
        ASSERT_TRUE(f.Find(c.x0, n0, c.y, nY, &ch, &tp));
        for (bool atX0 : {true, false}) {
            // Move the far endpoint along its tangent basis, watch the direction at the near one.
            Vec3f a, b;
            CoordinateSystem(atX0 ? nY : n0, &a, &b);
            const double h = 2e-3;
            Vec3f dw[2];
            for (int e = 0; e < 2; ++e) {
                Vec3f dir = e == 0 ? a : b, w[2];
                for (int s = 0; s < 2; ++s) {
                    Float sg = s == 0 ? Float(h) : Float(-h);
                    Vec3f x0 = c.x0, y = c.y;
                    if (atX0) y += dir * sg;
                    else x0 += dir * sg;
                    MneeChain c2;
                    ASSERT_TRUE(f.Find(x0, n0, y, nY, &c2, &tp));
                    w[s] = atX0 ? Normalize(c2.v[0].p - x0) : Normalize(c2.v[c2.k - 1].p - y);
                }
                dw[e] = (w[0] - w[1]) / Float(2 * h);
            }
            Vec3f w = atX0 ? Normalize(ch.v[0].p - ch.x0) : Normalize(ch.v[ch.k - 1].p - ch.y), u, v;
            CoordinateSystem(w, &u, &v);
            double fd = std::abs(double(Dot(u, dw[0])) * Dot(v, dw[1]) - double(Dot(u, dw[1])) * Dot(v, dw[0]));
            double an = MneeGeometry(ch, atX0);
            EXPECT_NEAR(an / fd, 1.0, 0.02) << "case " << idx << " atX0 " << atX0 << ": " << an << " vs " << fd;
        }
    }
}

// The check: a point light at (0.3, 0, 1) over a table at z = 0 under a thin glass sheet
// at z = 0.5 (eta 1.5), seen from above through the sheet. The table is lit through the sheet
// (MNEE crosses it) and seen through it: T_light T_camera = ((1 - R)/(1 + R))^2 = 0.852 of the
// bare table at normal incidence. Path tracing cannot light it at all.
TEST(Mnee, PointLightUnderAThinSheetGetsTheTransmittanceProduct) {
    std::string light = "LightSource \"point\" \"point3 from\" [ 0.3 0 1 ] \"rgb I\" [ 1 1 1 ]\n";
    std::string table = "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n" + Quad(0, 4, true) +
                        "AttributeEnd\n";
    std::string sheet = "AttributeBegin\nMaterial \"thindielectric\" \"float eta\" [ 1.5 ]\n" + Quad(0.5, 4, true) +
                        "AttributeEnd\n";
    auto bare = LoadSceneText("mnee_sheet_bare", std::string(kHead) + light + table);
    auto glass = LoadSceneText("mnee_sheet", std::string(kHead) + light + table + sheet);
    // maxdepth 3: camera - sheet - table - sheet - light, and no light reflected between table
    // and sheet (that needs a fourth vertex). The regularized connection at the sheet's upper
    // crossing reaches the light too, and must leave it to MNEE (or the ratio would be too high).
    auto b = RenderScene(*bare, 64, 3, 1, 0, 0, true, 1e-2);
    auto g = RenderScene(*glass, 64, 3, 1, 0, 0, true, 1e-2);
    auto p = RenderScene(*glass, 64, 3, 1, 0, 0, false);
    MeanSE mb = RegionMean(b.image, 1, 4, 4, 28, 28), mg = RegionMean(g.image, 1, 4, 4, 28, 28);
    MeanSE mp = RegionMean(p.image, 1, 4, 4, 28, 28);
    ASSERT_GT(mb.mean, 0);
    EXPECT_LT(mp.mean, 1e-3 * mb.mean) << "path tracing cannot light the table through the sheet";
    EXPECT_GT(g.stats.mneeConnections, 0u);
    // Unpolarized Fresnel at the two angles (camera ray ~ normal, light ray at 16.7 degrees).
    auto thinT = [](double cosI) {
        double R = FresnelR(cosI, 1.5);
        return (1 - R) / (1 + R);
    };
    double expected = thinT(1.0) * thinT(1 / std::sqrt(1.09));
    double ratio = mg.mean / mb.mean;
    EXPECT_NEAR(ratio, expected, 0.01 * expected) << "sheet/bare " << ratio;
    EXPECT_NEAR(ratio, 0.852, 0.01 * 0.852);
}

// MNEE and BSDF sampling share the paths through a glass slab to an area light: MNEE alone
// (light-strategy nee), BSDF sampling alone (bsdf) and both under MIS must estimate the same
// image (weights that do not sum to one shift the MIS image). Block means, z-tests. halfSize: the
// light's half width at height 1.2 (the same power at every size); mneeUnderMis: whether MNEE's
// selectivity (MneeTargetsLight, 0.01 sr) lets it run under MIS there.
void ExpectMneeMisUnbiased(const char *name, double halfSize, bool mneeUnderMis, uint64_t seed) {
    char light[400];
    std::snprintf(light, sizeof light,
                  "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ %g %g %g ]\n"
                  "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 ] \"point3 P\" [ %g %g 1.2  %g %g 1.2  %g %g 1.2  %g %g 1.2 ]\n"
                  "AttributeEnd\n",
                  60 * Sqr(0.1 / halfSize), 60 * Sqr(0.1 / halfSize), 60 * Sqr(0.1 / halfSize), -halfSize, -halfSize,
                  halfSize, -halfSize, halfSize, halfSize, -halfSize, halfSize);
    std::string world = std::string(light) +
        "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n" + Quad(0, 4, true) + "AttributeEnd\n" +
        Slab(0.4, 0.5);
    auto scene = LoadSceneText(name, "LookAt 0 -0.3 2.5  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
                                     "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\nWorldBegin\n" + world);
    // regpath with a negligible kernel (what MNEE leaves to the regularized connection is ~0 here).
    // maxdepth 6: camera - slab (2) - floor - slab (2) - light is within it; MNEE adds exactly the
    // paths BSDF sampling can find.
    auto mis = RenderScene(*scene, 256, 6, seed, 0, int(LightStrategy::MIS), true, 1e-5);
    auto nee = RenderScene(*scene, 256, 6, seed + 1, 0, int(LightStrategy::NEEOnly), true, 1e-5);
    auto bsdf = RenderScene(*scene, 1024, 6, seed + 2, 0, int(LightStrategy::BSDFOnly), false);
    if (mneeUnderMis)
        EXPECT_GT(mis.stats.mneeConnections, 0u);
    else
        EXPECT_EQ(mis.stats.mneeConnections, 0u);
    EXPECT_GT(nee.stats.mneeConnections, 0u);   // under NEE alone MNEE takes every light
    int blocks = 0, bad = 0;
    for (int by = 0; by < 24; by += 6)
        for (int bx = 0; bx < 24; bx += 6) {
            MeanSE a = RegionMean(mis.image, 1, bx, by, bx + 6, by + 6), n = RegionMean(nee.image, 1, bx, by, bx + 6, by + 6),
                   s = RegionMean(bsdf.image, 1, bx, by, bx + 6, by + 6);
            for (const MeanSE *o : {&n, &s}) {
                double z = (a.mean - o->mean) / std::sqrt(a.se * a.se + o->se * o->se + 1e-30);
                ++blocks;
                // Sidak-corrected two-sided 1% over the 32 comparisons: |z| > 3.8.
                if (std::abs(z) > 3.8) ++bad;
                if (std::abs(z) > 3.8)
                    std::printf("block %d %d: mis %.4g +- %.2g  nee %.4g +- %.2g  bsdf %.4g +- %.2g\n", bx, by, a.mean, a.se,
                                n.mean, n.se, s.mean, s.se);
            }
        }
    EXPECT_EQ(bad, 0) << bad << " of " << blocks << " block means disagree";
}

// A 6 cm light (under 0.004 sr from the floor): MNEE runs under MIS.
TEST(Mnee, MisWithBsdfSamplingIsUnbiased) { ExpectMneeMisUnbiased("mnee_mis", 0.03, true, 11); }

// A 20 cm light (0.044 sr from the floor): under MIS MNEE leaves it to BSDF sampling and the
// regularized connection, on both sides of the MIS (an implicit hit that still took MNEE as its
// partner would darken the caustic; an MNEE sample that still ran would brighten it).
TEST(Mnee, LargeAreaLightsAreLeftToBsdfSampling) { ExpectMneeMisUnbiased("mnee_mis_large", 0.1, false, 31); }

}  // namespace lu::test

namespace lu::test {

// MNEE's chains carry the transmittance of the media they cross: a point light over a glass slab
// whose inside absorbs (sigma_a 4, gray), seen from above. Both the camera ray and the light's
// chain cross the 0.1-thick slab about vertically, so the table is exp(-4 (0.1 + 0.1)) = 0.449 of
// the same scene with a clear slab (Fresnel cancels; 1.003 for the obliquity of the rays in the
// image). Without the chain's transmittance the ratio would be exp(-0.4) = 0.67.
TEST(Mnee, ChainsCarryTheTransmittanceOfTheMediaTheyCross) {
    std::string light = "LightSource \"point\" \"point3 from\" [ 0 0 1 ] \"rgb I\" [ 1 1 1 ]\n";
    std::string table = "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n" + Quad(0, 4, true) +
                        "AttributeEnd\n";
    std::string medium = "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 4 4 4 ] "
                         "\"rgb sigma_s\" [ 0 0 0 ]\n";
    std::string inside = "MediumInterface \"ink\" \"\"\n";
    auto clear = LoadSceneText("mnee_slab_clear", std::string(kHead) + light + table + Slab(0.4, 0.5));
    auto ink = LoadSceneText("mnee_slab_ink", std::string(kHead) + medium + light + table + "AttributeBegin\n" + inside +
                                                  Slab(0.4, 0.5) + "AttributeEnd\n");
    ASSERT_EQ(ink->media.size(), 1u);
    // maxdepth 5: camera - slab (2) - table - slab (2) - light.
    auto c = RenderScene(*clear, 64, 5, 1, 0, 0, true, 1e-5);
    auto k = RenderScene(*ink, 64, 5, 2, 0, 0, true, 1e-5);
    EXPECT_GT(k.stats.mneeConnections, 0u);
    for (int ch = 0; ch < 3; ++ch) {
        MeanSE mc = RegionMean(c.image, ch, 2, 2, 30, 30), mk = RegionMean(k.image, ch, 2, 2, 30, 30);
        ASSERT_GT(mc.mean, 0);
        double ratio = mk.mean / mc.mean, expected = std::exp(-4 * 0.2 * 1.003);
        EXPECT_NEAR(ratio, expected, 0.015 * expected) << "channel " << ch << ": ink/clear " << ratio;
    }
}

// The same in a chromatic fog that fills the scene: MNEE also starts at medium vertices (the
// volumetric caustic under the slab) and carries the fog's transmittance along its chains, and
// its weights over techniques and wavelengths (WavelengthPdfs::lChain on the implicit side) must
// still sum to one: MNEE alone, phase/BSDF sampling alone and MIS agree in block means, per channel.
TEST(Mnee, MisWithPhaseAndBsdfSamplingIsUnbiasedInFog) {
    std::string fog =
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.02 0.05 0.1 ] "
        "\"rgb sigma_s\" [ 0.5 0.3 0.2 ] \"float g\" [ 0.3 ]\nMediumInterface \"fog\" \"fog\"\n";
    std::string world =
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 450 450 450 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 ] \"point3 P\" [ -0.04 -0.04 1.2  0.04 -0.04 1.2  0.04 0.04 1.2  -0.04 0.04 1.2 ]\n"
        "AttributeEnd\n"
        "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n" + Quad(0, 4, true) + "AttributeEnd\n" +
        Slab(0.4, 0.5);
    auto scene = LoadSceneText("mnee_mis_fog", fog + "LookAt 0 -0.3 2.5  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
                                               "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\nWorldBegin\n"
                                               "MediumInterface \"fog\" \"fog\"\n" + world);
    ASSERT_GT(scene->media.size(), 0u);
    auto mis = RenderScene(*scene, 256, 6, 21, 0, int(LightStrategy::MIS), true, 1e-5);
    auto nee = RenderScene(*scene, 256, 6, 22, 0, int(LightStrategy::NEEOnly), true, 1e-5);
    auto bsdf = RenderScene(*scene, 1024, 6, 23, 0, int(LightStrategy::BSDFOnly), false);
    EXPECT_GT(mis.stats.mneeConnections, 0u);
    EXPECT_GT(nee.stats.mneeConnections, 0u);
    EXPECT_EQ(mis.stats.rejected + nee.stats.rejected + bsdf.stats.rejected, 0u);
    int blocks = 0, bad = 0;
    for (int c = 0; c < 3; ++c)
        for (int by = 0; by < 24; by += 6)
            for (int bx = 0; bx < 24; bx += 6) {
                MeanSE a = RegionMean(mis.image, c, bx, by, bx + 6, by + 6), n = RegionMean(nee.image, c, bx, by, bx + 6, by + 6),
                       s = RegionMean(bsdf.image, c, bx, by, bx + 6, by + 6);
                for (const MeanSE *o : {&n, &s}) {
                    double z = (a.mean - o->mean) / std::sqrt(a.se * a.se + o->se * o->se + 1e-30);
                    ++blocks;
                    // Sidak-corrected two-sided 1% over the 96 comparisons: |z| > 4.1.
                    if (std::abs(z) > 4.1) {
                        ++bad;
                        std::printf("channel %d block %d %d: mis %.4g +- %.2g  nee %.4g +- %.2g  bsdf %.4g +- %.2g\n", c, bx,
                                    by, a.mean, a.se, n.mean, n.se, s.mean, s.se);
                    }
                }
            }
    EXPECT_EQ(bad, 0) << bad << " of " << blocks << " block means disagree";
}

}  // namespace lu::test
