// Lucerna: the "nanovdb" medium. Grids are made here with NanoVDB's own GridBuilder and written
// as .nvdb files; the scene builder must reproduce pbrt-v4's lookups (NanoVDB's trilinear sampler
// in index space, through the grid's map and the CTM) and refuse bad files at file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/media/medium.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

// A smooth positive density over the index box [lo, hi] (background 0 outside).
float Density(const nanovdb::Coord &c) {
    return 0.5f + 0.4f * std::sin(0.7f * c[0]) * std::cos(0.45f * c[1]) + 0.05f * (c[2] & 3);
}

const nanovdb::CoordBBox kBox(nanovdb::Coord(-3, 2, -5), nanovdb::Coord(4, 9, 0));

// A fog-volume grid named `name` with map index -> world = R * (voxelSize * i) + origin, R a rotation
// by `degrees` about z.
nanovdb::GridHandle<> MakeGrid(const std::string &name, double voxelSize, nanovdb::Vec3d origin, double degrees,
                               float (*f)(const nanovdb::Coord &) = Density,
                               nanovdb::GridClass cls = nanovdb::GridClass::FogVolume) {
    nanovdb::GridBuilder<float> builder(0.0f, cls);
    builder([&](const nanovdb::Coord &c) { return f(c); }, kBox);
    double a = degrees * 3.14159265358979323846 / 180, c = std::cos(a), s = std::sin(a);
    double mat[3][3] = {{c * voxelSize, -s * voxelSize, 0}, {s * voxelSize, c * voxelSize, 0}, {0, 0, voxelSize}};
    double inv[3][3] = {{c / voxelSize, s / voxelSize, 0}, {-s / voxelSize, c / voxelSize, 0}, {0, 0, 1 / voxelSize}};
    nanovdb::Map map;
    map.set(mat, inv, origin, 1.0);
    return builder.getHandle<nanovdb::AbsDiff>(map, name);
}

// The handles are move-only: a vector of them built by moving.
template <typename... G>
std::vector<nanovdb::GridHandle<>> Grids(G &&...g) {
    std::vector<nanovdb::GridHandle<>> v;
    (v.push_back(std::move(g)), ...);
    return v;
}

std::string WriteGrids(const std::string &dir, const std::vector<nanovdb::GridHandle<>> &grids) {
    std::string path = dir + "/grid.nvdb";
    nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(path, grids);
    return path;
}

std::unique_ptr<HostScene> Load(const std::string &dir, const std::string &world, Diagnostics *diagOut = nullptr) {
    std::string path = dir + "/scene.pbrt";
    std::ofstream(path) << "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                           "Camera \"perspective\"\nWorldBegin\n"
                        << world;
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(path, diag, {});
    if (diagOut) *diagOut = diag;
    return s;
}

// Medium-space density times sigma, pbrt-v4's way: NanoVDB's trilinear sampler at worldToIndexF.
float PbrtDensity(const nanovdb::FloatGrid &g, const Vec3f &pMedium) {
    nanovdb::SampleFromVoxels<nanovdb::FloatGrid::TreeType, 1, false> sampler(g.tree());
    return sampler(g.worldToIndexF(nanovdb::Vec3f(pMedium.x, pMedium.y, pMedium.z)));
}

void ExpectMatchesPbrt(double degrees) {
    std::string dir = test::TempDir("nanovdb_match");
    nanovdb::Vec3d origin(0.5, -1, 2);
    auto grid = MakeGrid("density", 0.25, origin, degrees);
    WriteGrids(dir, Grids(MakeGrid("density", 0.25, origin, degrees)));
    auto scene = Load(dir, "AttributeBegin\nTranslate 1 2 3\nMakeNamedMedium \"smoke\" \"string type\" \"nanovdb\"\n"
                           "  \"string filename\" \"grid.nvdb\" \"spectrum sigma_a\" [ 400 2 700 2 ] \"float scale\" 3\n"
                           "AttributeEnd\n");
    ASSERT_EQ(scene->media.size(), 1u);
    const Medium &m = scene->media[0];
    SceneView v = scene->View();
    const nanovdb::FloatGrid &g = *grid.grid<float>();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    int compared = 0, nonzero = 0;
    for (int i = 0; i < 4000; ++i) {
        // Index-space points from half a voxel inside the lower faces (where pbrt-v4's box starts
        // cutting) to one voxel past the upper ones.
        Vec3f f(kBox.min()[0] + (kBox.dim()[0] + 1) * u(rng), kBox.min()[1] + (kBox.dim()[1] + 1) * u(rng),
                kBox.min()[2] + (kBox.dim()[2] + 1) * u(rng));
        nanovdb::Vec3d w = g.indexToWorld(nanovdb::Vec3d(f.x, f.y, f.z));
        Vec3f pMedium{float(w[0]), float(w[1]), float(w[2])};
        Vec3f pRender = pMedium + Vec3f(1, 2, 3);
        float expected = 3 * 2 * PbrtDensity(g, pMedium);
        MediumProperties mp = SampleMediumPoint(v, m, pRender, lambda);
        EXPECT_NEAR(mp.sigmaA[0], expected, 2e-4f * (1 + expected)) << "index point " << f.x << " " << f.y << " " << f.z;
        EXPECT_NEAR(mp.sigmaS[0], 3 * PbrtDensity(g, pMedium), 2e-4f * (1 + expected));   // sigma_s default 1
        ++compared;
        nonzero += expected > 0.1f;
    }
    EXPECT_GT(nonzero, compared / 2);
    // Majorants bound the density everywhere they are used.
    EXPECT_GT(m.majorant.nx, 0u);
}

TEST(NanoVDBMedium, DensityMatchesNanoVDBSampler) { ExpectMatchesPbrt(0); }
TEST(NanoVDBMedium, RotatedMapMatchesNanoVDBSampler) { ExpectMatchesPbrt(30); }

TEST(NanoVDBMedium, TemperatureGridMakesItEmissive) {
    std::string dir = test::TempDir("nanovdb_temp");
    auto hot = [](const nanovdb::Coord &) { return 1500.f; };
    WriteGrids(dir, Grids(MakeGrid("density", 0.1, nanovdb::Vec3d(0), 0), MakeGrid("temperature", 0.1, nanovdb::Vec3d(0), 0, hot)));
    auto scene = Load(dir, "MakeNamedMedium \"fire\" \"string type\" \"nanovdb\" \"string filename\" \"grid.nvdb\"\n"
                           "  \"float Lescale\" 2 \"float temperaturecutoff\" 500\n");
    const Medium &m = scene->media[0];
    EXPECT_TRUE(m.emissive);
    SceneView v = scene->View();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    // An interior voxel: Le = Lescale * normalized blackbody at (1500 - 500) K.
    MediumProperties mp = SampleMediumPoint(v, m, Vec3f(0.05f, 0.45f, -0.25f), lambda);
    for (int i = 0; i < NSpectrumSamples; ++i)
        EXPECT_NEAR(mp.Le[i], 2 * NormalizedBlackbody(lambda.lambda[i], 1000), 1e-4f);
    // No temperature grid: not emissive.
    std::string dir2 = test::TempDir("nanovdb_cold");
    WriteGrids(dir2, Grids(MakeGrid("density", 0.1, nanovdb::Vec3d(0), 0)));
    auto cold = Load(dir2, "MakeNamedMedium \"smoke\" \"string type\" \"nanovdb\" \"string filename\" \"grid.nvdb\"\n");
    EXPECT_FALSE(cold->media[0].emissive);
}

// Issue 13's memory case: a dense 256^3 grid (every voxel active) is read, stored (257^3 floats
// with the background layer, 68 MB) and rendered; its lookups still match NanoVDB's sampler.
TEST(NanoVDBMedium, Dense256CubedGridRenders) {
    std::string dir = test::TempDir("nanovdb_256");
    {
        nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
        builder([](const nanovdb::Coord &c) { return 0.2f + 0.001f * float((c[0] + 2 * c[1] + 3 * c[2]) % 700); },
                nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(255)));
        WriteGrids(dir, Grids(builder.getHandle<nanovdb::AbsDiff>(1.0 / 256, nanovdb::Vec3d(-0.5), "density")));
    }
    auto scene = Load(dir, "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                           "AttributeBegin\nTranslate 0 0 1.2\n"
                           "MakeNamedMedium \"smoke\" \"string type\" \"nanovdb\" \"string filename\" \"grid.nvdb\" \"float scale\" 4\n"
                           "MediumInterface \"smoke\" \"\"\nMaterial \"interface\"\nShape \"sphere\" \"float radius\" 0.45\n"
                           "AttributeEnd\n");
    const Medium &m = scene->media[0];
    EXPECT_EQ(m.density.nx, 257u);
    EXPECT_EQ(m.density.nz, 257u);
    EXPECT_GE(scene->mediumData.size(), size_t(257) * 257 * 257);
    RenderSettings rs = scene->settings;
    rs.spp = 1;
    rs.progress = false;
    FilmAccumulator film;
    RenderStats st = RenderCPU(*scene, rs, film);
    EXPECT_EQ(st.rejected, 0u);
    Image img = film.Resolve(scene->View().film);
    // The centre looks through the ball (transmittance < 1), the corner sees the sky (radiance 1).
    float centre = img.At(4, 4, 1), corner = img.At(0, 0, 1);
    EXPECT_NEAR(corner, 1.0f, 0.05f);
    EXPECT_LT(centre, 0.9f * corner);
    for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
}

float WithNaN(const nanovdb::Coord &c) { return c == nanovdb::Coord(1, 5, -2) ? std::nanf("") : 1.f; }
float Negative(const nanovdb::Coord &c) { return c == nanovdb::Coord(0, 3, -1) ? -0.5f : 1.f; }

// Bad files are errors at the medium's "filename" (line 5 of the scene), naming what is wrong.
TEST(NanoVDBMedium, BadFilesAreLocatedErrors) {
    struct Case {
        std::vector<nanovdb::GridHandle<>> grids;
        std::string params;
        const char *what;
    };
    std::vector<Case> cases;
    cases.push_back({Grids(), "\"string filename\" \"nothere.nvdb\"", "cannot read NanoVDB file"});
    {
        std::vector<nanovdb::GridHandle<>> g;
        g.push_back(MakeGrid("smoke", 1, nanovdb::Vec3d(0), 0));
        cases.push_back({std::move(g), "\"string filename\" \"grid.nvdb\"", "has no grid \"density\" (it has \"smoke\")"});
    }
    {
        std::vector<nanovdb::GridHandle<>> g;
        g.push_back(MakeGrid("density", 1, nanovdb::Vec3d(0), 0, Density, nanovdb::GridClass::LevelSet));
        cases.push_back({std::move(g), "\"string filename\" \"grid.nvdb\"", "is not a fog volume"});
    }
    {
        std::vector<nanovdb::GridHandle<>> g;
        g.push_back(MakeGrid("density", 1, nanovdb::Vec3d(0), 0, WithNaN));
        cases.push_back({std::move(g), "\"string filename\" \"grid.nvdb\"", "density voxel (1, 5, -2)"});
    }
    {
        std::vector<nanovdb::GridHandle<>> g;
        g.push_back(MakeGrid("density", 1, nanovdb::Vec3d(0), 0, Negative));
        cases.push_back({std::move(g), "\"string filename\" \"grid.nvdb\"", "density voxel (0, 3, -1)"});
    }
    int k = 0;
    for (Case &c : cases) {
        std::string dir = test::TempDir("nanovdb_bad" + std::to_string(k++));
        if (!c.grids.empty()) WriteGrids(dir, c.grids);
        try {
            Load(dir, "MakeNamedMedium \"fog\" \"string type\" \"nanovdb\"\n  " + c.params + "\n");
            ADD_FAILURE() << "no error for " << c.what;
        } catch (const SceneError &e) {
            EXPECT_NE(e.Message().find(c.what), std::string::npos) << e.Message();
            EXPECT_EQ(e.Loc().line, 5) << e.Message();
        }
    }
    // Not a NanoVDB file at all.
    std::string dir = test::TempDir("nanovdb_garbage");
    std::ofstream(dir + "/grid.nvdb") << "this is not a grid";
    try {
        Load(dir, "MakeNamedMedium \"fog\" \"string type\" \"nanovdb\"\n  \"string filename\" \"grid.nvdb\"\n");
        ADD_FAILURE() << "garbage accepted";
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find("cannot read NanoVDB file"), std::string::npos) << e.Message();
        EXPECT_EQ(e.Loc().line, 5);
    }
}

}  // namespace
}  // namespace lu
