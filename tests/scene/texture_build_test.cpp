// The texture builder (scene/build_textures.cpp): every pbrt-v4 texture type and mapping read
// from a scene with its parameters, pbrt-v4's scale folding and dots quirk, image encodings and
// channel rules, the approximations warned about, and an error for each kind of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "lucerna/image/image.h"
#include "lucerna/materials/texture.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

const char *kHeader =
    "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 16 ]\n"
    "Camera \"perspective\" \"float fov\" [ 45 ]\n"
    "WorldBegin\n";
// After the world under test, so that line numbers in it count from the header; a light keeps the
// builder's "no light sources" warning out of the warning counts below.
const char *kLight = "\nLightSource \"point\"\n";

std::unique_ptr<HostScene> BuildWorld(const std::string &world, Diagnostics &diag) {
    diag.quiet = true;
    SceneDescription desc = ParseSceneString(std::string(kHeader) + world + kLight, "test.pbrt", diag);
    return BuildScene(desc, diag, BuildOptions{});
}

// A scene file in its own folder (for image textures).
std::unique_ptr<HostScene> BuildFile(const std::string &dir, const std::string &world, Diagnostics &diag) {
    diag.quiet = true;
    std::ofstream(dir + "/scene.pbrt") << std::string(kHeader) << world << kLight;
    return LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
}

SceneError ErrorOfWorld(const std::string &world) {
    Diagnostics diag;
    try {
        BuildWorld(world, diag);
    } catch (const SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no SceneError for:\n" << world;
    return SceneError(FileLoc{}, "");
}

void ExpectError(const std::string &world, int line, const std::string &needle) {
    SceneError e = ErrorOfWorld(world);
    EXPECT_NE(e.Message().find(needle), std::string::npos) << e.Message();
    EXPECT_EQ(e.Loc().line, line) << e.Format();
}

bool AnyContains(const std::vector<std::string> &v, const std::string &needle) {
    for (const std::string &s : v)
        if (s.find(needle) != std::string::npos) return true;
    return false;
}

TextureEvalContext At(Vec3f p, Vec2f uv = Vec2f(0, 0), Vec3f n = Vec3f(0, 0, 1)) {
    TextureEvalContext c; c.p = p; c.uv = uv; c.n = n; return c;
}

// The first material's reflectance (a spectrum texture) and its scene.
const Material &MaterialOf(const HostScene &s, int shape) { return s.materials[s.shapes[shape].material]; }

TEST(TextureBuild, EveryTypeBuildsWithoutUnsupportedOrWarnings) {
    Diagnostics diag;
    auto s = BuildWorld(
        "Texture \"f1\" \"float\" \"constant\" \"float value\" 0.3\n"
        "Texture \"f2\" \"float\" \"bilerp\" \"float v00\" 0.1 \"float v11\" 0.7\n"
        "Texture \"f3\" \"float\" \"checkerboard\" \"integer dimension\" 3 \"texture tex1\" \"f1\" \"float tex2\" 0.9\n"
        "Texture \"f4\" \"float\" \"dots\" \"texture inside\" \"f2\" \"float outside\" 0.2 \"float uscale\" 4\n"
        "Texture \"f5\" \"float\" \"fbm\" \"integer octaves\" 4 \"float roughness\" 0.6\n"
        "Texture \"f6\" \"float\" \"wrinkled\" \"integer octaves\" 3\n"
        "Texture \"f7\" \"float\" \"windy\"\n"
        "Texture \"f8\" \"float\" \"mix\" \"texture tex1\" \"f5\" \"texture tex2\" \"f6\" \"texture amount\" \"f7\"\n"
        "Texture \"f9\" \"float\" \"directionmix\" \"texture tex1\" \"f8\" \"float tex2\" 0.5 \"vector3 dir\" [0 0 1]\n"
        "Texture \"f10\" \"float\" \"scale\" \"texture tex\" \"f9\" \"texture scale\" \"f3\"\n"
        "Texture \"s1\" \"spectrum\" \"constant\" \"rgb value\" [0.2 0.3 0.4]\n"
        "Texture \"s2\" \"spectrum\" \"bilerp\" \"rgb v00\" [1 0 0] \"rgb v11\" [0 0 1] \"string mapping\" \"planar\"\n"
        "Texture \"s3\" \"spectrum\" \"checkerboard\" \"texture tex1\" \"s1\" \"texture tex2\" \"s2\"\n"
        "Texture \"s4\" \"spectrum\" \"dots\" \"texture inside\" \"s3\" \"rgb outside\" [0.1 0.1 0.1]\n"
        "Texture \"s5\" \"spectrum\" \"marble\" \"float scale\" 3 \"float variation\" 0.4 \"integer octaves\" 6\n"
        "Texture \"s6\" \"spectrum\" \"mix\" \"texture tex1\" \"s4\" \"texture tex2\" \"s5\" \"texture amount\" \"f10\"\n"
        "Texture \"s7\" \"spectrum\" \"directionmix\" \"texture tex1\" \"s6\" \"rgb tex2\" [0.5 0.5 0.5]\n"
        "Texture \"s8\" \"spectrum\" \"scale\" \"texture tex\" \"s7\" \"float scale\" 0.5\n"
        "Material \"diffuse\" \"texture reflectance\" \"s8\"\nShape \"sphere\"\n"
        "Material \"conductor\" \"texture roughness\" \"f10\"\nShape \"sphere\"\n",
        diag);
    EXPECT_TRUE(diag.unsupported.empty());
    EXPECT_TRUE(diag.warnings.empty()) << (diag.warnings.empty() ? "" : diag.warnings[0]);
    EXPECT_EQ(s->stats.floatTextures, 10);
    EXPECT_EQ(s->stats.spectrumTextures, 8);
    const SpectrumTexture &r = MaterialOf(*s, 0).reflectance;
    ASSERT_EQ(r.kind, TextureKind::Scale);
    EXPECT_FALSE(r.unbounded);
    const SpectrumTexture &dm = s->spectrumTextures[r.tex[0]];
    ASSERT_EQ(dm.kind, TextureKind::DirectionMix);
    const SpectrumTexture &mix = s->spectrumTextures[dm.tex[0]];
    ASSERT_EQ(mix.kind, TextureKind::Mix);
    EXPECT_EQ(s->floatTextures[mix.amount].kind, TextureKind::Scale);
    EXPECT_EQ(s->spectrumTextures[mix.tex[1]].kind, TextureKind::Marble);
    EXPECT_EQ(s->spectrumTextures[mix.tex[1]].octaves, 6);
    EXPECT_FLOAT_EQ(s->spectrumTextures[mix.tex[1]].variation, 0.4f);
    EXPECT_EQ(s->spectrumTextures[mix.tex[0]].kind, TextureKind::Dots);
    const FloatTexture &rough = MaterialOf(*s, 1).uRoughness;
    EXPECT_EQ(rough.kind, TextureKind::Scale);
    // The whole graph evaluates to finite values (materials clamp reflectances to [0, 1]).
    SceneView view = s->View();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.4f);
    for (int i = 0; i < 200; ++i) {
        Float x = 0.37f * i - 30, y = 0.11f * i, z = 5 - 0.23f * i;
        Vec3f n = Normalize(Vec3f(std::sin(x), 1, std::cos(y)));
        TextureEvalContext ctx = At(Vec3f(x, y, z), Vec2f(0.013f * i, 0.007f * i), n);
        SampledSpectrum v = EvalSpectrumTexture(r, ctx, lambda, view);
        ASSERT_TRUE(v.IsFinite());   // may be negative: the mix amount is an FBm product
        ASSERT_TRUE(std::isfinite(EvalFloatTexture(rough, ctx, view)));
    }
}

TEST(TextureBuild, MappingsUseTheTextureTransform) {
    Diagnostics diag;
    auto s = BuildWorld(
        "AttributeBegin\nTranslate 1 2 3\n"
        "Texture \"sph\" \"float\" \"bilerp\" \"string mapping\" \"spherical\"\n"
        "Texture \"cyl\" \"float\" \"bilerp\" \"string mapping\" \"cylindrical\"\nAttributeEnd\n"
        "AttributeBegin\nScale 2 2 2\n"
        "Texture \"pl\" \"float\" \"bilerp\" \"string mapping\" \"planar\" \"vector3 v1\" [0 1 0] \"vector3 v2\" [0 0 1]\n"
        "  \"float udelta\" 0.5 \"float vdelta\" -1\n"
        "Texture \"pt\" \"float\" \"fbm\"\nAttributeEnd\n"
        "Texture \"uv\" \"float\" \"bilerp\" \"float uscale\" 2 \"float vscale\" 3 \"float udelta\" 0.1 \"float vdelta\" 0.2\n"
        "Material \"conductor\" \"texture uroughness\" \"sph\" \"texture vroughness\" \"cyl\"\nShape \"sphere\"\n"
        "Material \"conductor\" \"texture uroughness\" \"pl\" \"texture vroughness\" \"pt\"\nShape \"sphere\"\n"
        "Material \"conductor\" \"texture uroughness\" \"uv\"\nShape \"sphere\"\n",
        diag);
    EXPECT_TRUE(diag.warnings.empty()) << (diag.warnings.empty() ? "" : diag.warnings[0]);
    const TextureMapping &sph = MaterialOf(*s, 0).uRoughness.mapping;
    ASSERT_EQ(sph.kind, TextureMappingKind::Spherical);
    Vec2f st = Map2D(sph, At(Vec3f(1, 3, 3)));   // +y of the centre (1, 2, 3)
    EXPECT_NEAR(st.x, 0.5f, 1e-6f);
    EXPECT_NEAR(st.y, 0.25f, 1e-6f);
    const TextureMapping &cyl = MaterialOf(*s, 0).vRoughness.mapping;
    ASSERT_EQ(cyl.kind, TextureMappingKind::Cylindrical);
    st = Map2D(cyl, At(Vec3f(0, 2, 4.5f)));      // -x of the axis, 1.5 above the centre
    EXPECT_NEAR(st.x, 1.0f, 1e-6f);
    EXPECT_NEAR(st.y, 1.5f, 1e-6f);
    const TextureMapping &pl = MaterialOf(*s, 1).uRoughness.mapping;
    ASSERT_EQ(pl.kind, TextureMappingKind::Planar);
    st = Map2D(pl, At(Vec3f(8, 4, 6)));          // texture space (4, 2, 3)
    EXPECT_FLOAT_EQ(st.x, 2.5f);
    EXPECT_FLOAT_EQ(st.y, 2.0f);
    const TextureMapping &pt = MaterialOf(*s, 1).vRoughness.mapping;
    ASSERT_EQ(pt.kind, TextureMappingKind::Point);
    EXPECT_EQ(Map3D(pt, At(Vec3f(2, 4, -6))), Vec3f(1, 2, -3));
    const TextureMapping &uv = MaterialOf(*s, 2).uRoughness.mapping;
    ASSERT_EQ(uv.kind, TextureMappingKind::UV);
    st = Map2D(uv, At(Vec3f(0, 0, 0), Vec2f(0.5f, 0.5f)));
    EXPECT_FLOAT_EQ(st.x, 1.1f);
    EXPECT_FLOAT_EQ(st.y, 1.7f);
}

TEST(TextureBuild, ParametersOfOtherMappingsAreReportedUnused) {
    Diagnostics diag;
    BuildWorld("Texture \"t\" \"float\" \"bilerp\" \"string mapping\" \"spherical\" \"float uscale\" 2\n", diag);
    EXPECT_TRUE(AnyContains(diag.warnings, "uscale")) << (diag.warnings.empty() ? "none" : diag.warnings[0]);
}

TEST(TextureBuild, DirectionMixDirectionIsInRenderSpace) {
    Diagnostics diag;
    auto s = BuildWorld("Rotate 90 0 0 1\n"
                        "Texture \"d\" \"float\" \"directionmix\" \"float tex1\" 1 \"float tex2\" 0 \"vector3 dir\" [0 2 0]\n"
                        "Material \"conductor\" \"texture roughness\" \"d\"\nShape \"sphere\"\n",
                        diag);
    const FloatTexture &d = MaterialOf(*s, 0).uRoughness;
    ASSERT_EQ(d.kind, TextureKind::DirectionMix);
    EXPECT_NEAR(d.dir.x, -1, 1e-6f);
    EXPECT_NEAR(d.dir.y, 0, 1e-6f);
    SceneView v = s->View();
    EXPECT_NEAR(EvalFloatTexture(d, At(Vec3f(0, 0, 0), Vec2f(0, 0), Vec3f(1, 0, 0)), v), 1, 1e-6f);
    EXPECT_NEAR(EvalFloatTexture(d, At(Vec3f(0, 0, 0), Vec2f(0, 0), Vec3f(0, 1, 0)), v), 0, 1e-6f);
}

// pbrt-v4's FloatScaledTexture::Create: factor 1 returns the other texture; a constant factor of
// an image map folds into the image's scale; otherwise the product.
TEST(TextureBuild, ScaleFoldsConstantsAsPbrt) {
    std::string dir = test::TempDir("texbuild_scale");
    WritePNG(dir + "/g.png", MakeImage(2, 2, 1, 0.5f));
    Diagnostics diag;
    auto s = BuildFile(dir,
                       "Texture \"img\" \"float\" \"imagemap\" \"string filename\" \"g.png\" \"float scale\" 3\n"
                       "Texture \"fb\" \"float\" \"fbm\"\n"
                       "Texture \"one\" \"float\" \"scale\" \"texture tex\" \"fb\" \"float scale\" 1\n"
                       "Texture \"oneL\" \"float\" \"scale\" \"float tex\" 1 \"texture scale\" \"fb\"\n"
                       "Texture \"fold\" \"float\" \"scale\" \"texture tex\" \"img\" \"float scale\" 0.5\n"
                       "Texture \"foldL\" \"float\" \"scale\" \"float tex\" 0.25 \"texture scale\" \"img\"\n"
                       "Texture \"prod\" \"float\" \"scale\" \"texture tex\" \"fb\" \"float scale\" 2\n"
                       "Texture \"simg\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\"\n"
                       "Texture \"sfold\" \"spectrum\" \"scale\" \"texture tex\" \"simg\" \"float scale\" 4\n"
                       "Material \"conductor\" \"texture uroughness\" \"one\" \"texture vroughness\" \"oneL\"\nShape \"sphere\"\n"
                       "Material \"conductor\" \"texture uroughness\" \"fold\" \"texture vroughness\" \"foldL\"\nShape \"sphere\"\n"
                       "Material \"conductor\" \"texture uroughness\" \"prod\" \"texture reflectance\" \"sfold\"\nShape \"sphere\"\n",
                       diag);
    EXPECT_EQ(MaterialOf(*s, 0).uRoughness.kind, TextureKind::FBm);
    EXPECT_EQ(MaterialOf(*s, 0).vRoughness.kind, TextureKind::FBm);
    EXPECT_EQ(MaterialOf(*s, 1).uRoughness.kind, TextureKind::ImageMap);
    EXPECT_FLOAT_EQ(MaterialOf(*s, 1).uRoughness.scale, 1.5f);
    EXPECT_EQ(MaterialOf(*s, 1).vRoughness.kind, TextureKind::ImageMap);
    EXPECT_FLOAT_EQ(MaterialOf(*s, 1).vRoughness.scale, 0.75f);
    const FloatTexture &prod = MaterialOf(*s, 2).uRoughness;
    ASSERT_EQ(prod.kind, TextureKind::Scale);
    SceneView v = s->View();
    Vec3f p(0.3f, 1.7f, -0.4f);
    EXPECT_FLOAT_EQ(EvalFloatTexture(prod, At(p), v), 2 * FBm(p, 0.5f, 8));
    EXPECT_EQ(MaterialOf(*s, 2).reflectance.kind, TextureKind::ImageMap);
    EXPECT_FLOAT_EQ(MaterialOf(*s, 2).reflectance.scale, 4);
}

// pbrt-v4's dots textures hand "inside" to the constructor's outsideDot: the "outside" value
// shows inside the dots. Lucerna keeps that so scenes look as in pbrt-v4.
TEST(TextureBuild, DotsShowOutsideInsideTheDotsAsPbrt) {
    Diagnostics diag;
    auto s = BuildWorld("Texture \"d\" \"float\" \"dots\" \"float inside\" 0.9 \"float outside\" 0.1\n"
                        "Material \"conductor\" \"texture roughness\" \"d\"\nShape \"sphere\"\n",
                        diag);
    const FloatTexture &d = MaterialOf(*s, 0).uRoughness;
    ASSERT_EQ(d.kind, TextureKind::Dots);
    SceneView v = s->View();
    int cs = 0;
    while (!(Noise(cs + .5f, .5f, .5f) > 0)) ++cs;   // a cell with a dot
    EXPECT_FLOAT_EQ(EvalFloatTexture(d, At(Vec3f(0, 0, 0), Vec2f(Float(cs), 0)), v), 0.1f);
    EXPECT_FLOAT_EQ(EvalFloatTexture(d, At(Vec3f(0, 0, 0), Vec2f(cs + 0.49f, 0.49f)), v), 0.9f);
}

TEST(TextureBuild, NamedChildIsStoredOnce) {
    Diagnostics diag;
    auto s = BuildWorld("Texture \"n\" \"float\" \"fbm\"\n"
                        "Texture \"m\" \"float\" \"mix\" \"texture tex1\" \"n\" \"texture tex2\" \"n\" \"texture amount\" \"n\"\n"
                        "Material \"conductor\" \"texture roughness\" \"m\"\nShape \"sphere\"\n",
                        diag);
    const FloatTexture &m = MaterialOf(*s, 0).uRoughness;
    EXPECT_EQ(m.tex[0], m.tex[1]);
    EXPECT_EQ(m.tex[0], m.amount);
}

TEST(TextureBuild, NestingDepthLimit) {
    auto chain = [](int n) {
        std::string w = "Texture \"t0\" \"float\" \"constant\" \"float value\" 0.5\n";
        for (int i = 1; i <= n; ++i)
            w += "Texture \"t" + std::to_string(i) + "\" \"float\" \"scale\" \"texture tex\" \"t" + std::to_string(i - 1) +
                 "\" \"float scale\" 2\n";
        return w + "Material \"conductor\" \"texture roughness\" \"t" + std::to_string(n) + "\"\nShape \"sphere\"\n";
    };
    Diagnostics diag;
    auto s = BuildWorld(chain(MaxTextureDepth), diag);
    SceneView v = s->View();
    EXPECT_FLOAT_EQ(EvalFloatTexture(MaterialOf(*s, 0).uRoughness, At(Vec3f(0, 0, 0)), v), 0.5f * (1 << MaxTextureDepth));
    // One more level: refused at the texture that exceeds the limit (line 4 + MaxTextureDepth + 1).
    ExpectError(chain(MaxTextureDepth + 1), 4 + MaxTextureDepth + 1, "more than 8 levels");
}

// ---- Image maps ----

TEST(TextureBuild, ImageEncodingsAndFloatChannels) {
    std::string dir = test::TempDir("texbuild_images");
    Image rgb = MakeImage(1, 1, 3);
    rgb.At(0, 0, 0) = SRGBToLinear(200 / 255.f);
    rgb.At(0, 0, 1) = SRGBToLinear(100 / 255.f);
    rgb.At(0, 0, 2) = SRGBToLinear(30 / 255.f);
    WritePNG(dir + "/rgb.png", rgb);
    Image rgba = MakeImage(1, 1, 4);
    for (int c = 0; c < 3; ++c) rgba.At(0, 0, c) = rgb.At(0, 0, c);
    rgba.At(0, 0, 3) = 64 / 255.f;
    WritePNG(dir + "/rgba.png", rgba);
    Image opaque = rgba;
    opaque.At(0, 0, 3) = 1;
    WritePNG(dir + "/opaque.png", opaque);
    Diagnostics diag;
    auto s = BuildFile(dir,
                       "Texture \"g\" \"spectrum\" \"imagemap\" \"string filename\" \"rgb.png\" \"string encoding\" \"gamma 2.2\"\n"
                       "Texture \"l\" \"spectrum\" \"imagemap\" \"string filename\" \"rgb.png\" \"string encoding\" \"linear\"\n"
                       "Texture \"srgb\" \"spectrum\" \"imagemap\" \"string filename\" \"rgb.png\"\n"
                       "Texture \"avg\" \"float\" \"imagemap\" \"string filename\" \"rgb.png\" \"string encoding\" \"linear\"\n"
                       "Texture \"alpha\" \"float\" \"imagemap\" \"string filename\" \"rgba.png\"\n"
                       "Texture \"opq\" \"float\" \"imagemap\" \"string filename\" \"opaque.png\" \"string encoding\" \"linear\"\n"
                       "Texture \"pt\" \"float\" \"imagemap\" \"string filename\" \"rgb.png\" \"string filter\" \"point\"\n"
                       "Material \"diffuse\" \"texture reflectance\" \"g\"\nShape \"sphere\"\n"
                       "Material \"diffuse\" \"texture reflectance\" \"l\"\nShape \"sphere\"\n"
                       "Material \"diffuse\" \"texture reflectance\" \"srgb\"\nShape \"sphere\"\n"
                       "Material \"conductor\" \"texture uroughness\" \"avg\" \"texture vroughness\" \"alpha\"\nShape \"sphere\"\n"
                       "Material \"conductor\" \"texture uroughness\" \"opq\" \"texture vroughness\" \"pt\"\nShape \"sphere\"\n",
                       diag);
    EXPECT_TRUE(diag.warnings.empty()) << (diag.warnings.empty() ? "" : diag.warnings[0]);
    auto texel = [&](uint32_t image, int c) {
        const ImageData &im = s->images[image];
        return s->texels[im.offset + c];
    };
    const uint32_t g = MaterialOf(*s, 0).reflectance.image, l = MaterialOf(*s, 1).reflectance.image,
                   sr = MaterialOf(*s, 2).reflectance.image;
    EXPECT_EQ(s->images[g].channels, 3u);
    EXPECT_NEAR(texel(g, 0), std::pow(200 / 255.f, 2.2f), 1e-6f);
    EXPECT_NEAR(texel(g, 2), std::pow(30 / 255.f, 2.2f), 1e-6f);
    EXPECT_NEAR(texel(l, 1), 100 / 255.f, 1e-6f);
    EXPECT_NEAR(texel(sr, 0), SRGBToLinear(200 / 255.f), 1e-6f);
    // Float textures: RGB -> average; RGBA with alpha != 1 -> alpha; opaque RGBA -> average;
    // "point" -> channel 0 (pbrt-v4's MIPMap::Texel<Float>).
    const Material &m3 = MaterialOf(*s, 3), &m4 = MaterialOf(*s, 4);
    EXPECT_EQ(s->images[m3.uRoughness.image].channels, 1u);
    EXPECT_NEAR(texel(m3.uRoughness.image, 0), (200 + 100 + 30) / 255.f / 3, 1e-6f);
    EXPECT_NEAR(texel(m3.vRoughness.image, 0), 64 / 255.f, 1e-6f);
    EXPECT_NEAR(texel(m4.uRoughness.image, 0), (200 + 100 + 30) / 255.f / 3, 1e-6f);
    EXPECT_TRUE(m4.vRoughness.pointFilter);
    EXPECT_NEAR(texel(m4.vRoughness.image, 0), SRGBToLinear(200 / 255.f), 1e-6f);
}

TEST(TextureBuild, FootprintFiltersWarnOnce) {
    std::string dir = test::TempDir("texbuild_filters");
    WritePNG(dir + "/g.png", MakeImage(2, 2, 3, 0.5f));
    Diagnostics diag;
    auto s = BuildFile(dir,
                       "Texture \"a\" \"spectrum\" \"imagemap\" \"string filename\" \"g.png\" \"float maxanisotropy\" 16\n"
                       "Texture \"b\" \"float\" \"imagemap\" \"string filename\" \"g.png\" \"string filter\" \"trilinear\"\n"
                       "Texture \"c\" \"float\" \"imagemap\" \"string filename\" \"g.png\" \"string filter\" \"EWA\"\n",
                       diag);
    ASSERT_EQ(diag.warnings.size(), 3u);   // once each, though "a" is built for two spectrum types
    EXPECT_TRUE(AnyContains(diag.warnings, "maxanisotropy"));
    EXPECT_TRUE(AnyContains(diag.warnings, "\"trilinear\""));
    EXPECT_TRUE(AnyContains(diag.warnings, "\"EWA\""));
    EXPECT_TRUE(diag.unsupported.empty());
}

// ---- Errors ----

TEST(TextureBuild, Errors) {
    ExpectError("Texture \"p\" \"spectrum\" \"ptex\" \"string filename\" \"x.ptx\"\n", 4, "\"ptex\" is not supported");
    ExpectError("Texture \"p\" \"float\" \"ptex\"\n", 4, "Ptex");
    ExpectError("Texture \"m\" \"float\" \"marble\"\n", 4, "spectrum texture");
    ExpectError("Texture \"f\" \"spectrum\" \"fbm\"\n", 4, "float texture");
    ExpectError("Texture \"w\" \"spectrum\" \"windy\"\n", 4, "float texture");
    ExpectError("Texture \"b\" \"float\" \"bilerp\"\n  \"string mapping\" \"toroidal\"\n", 5, "\"toroidal\"");
    ExpectError("Texture \"c\" \"float\" \"checkerboard\"\n  \"integer dimension\" 4\n", 5, "4 dimensional");
    ExpectError("Texture \"f\" \"float\" \"fbm\"\n  \"integer octaves\" -1\n", 5, "octaves");
    ExpectError("Texture \"f\" \"float\" \"wrinkled\" \"integer octaves\" 40\n", 4, "octaves");
    ExpectError("Texture \"d\" \"float\" \"directionmix\"\n  \"vector3 dir\" [0 0 0]\n", 5, "nonzero");
    ExpectError("Texture \"s\" \"spectrum\" \"bilerp\"\n  \"texture v00\" \"x\"\n", 5, "not a texture");
    ExpectError("Scale 0 1 1\nTexture \"s\" \"float\" \"fbm\"\n", 5, "singular");
    ExpectError("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"none.png\"\n  \"string encoding\" \"gamma x\"\n", 5,
                "unknown color encoding");
    ExpectError("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"none.png\"\n  \"string filter\" \"gaussian\"\n", 5,
                "unknown texture filter");
    ExpectError("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"none.png\"\n  \"string wrap\" \"octahedral\"\n",
                5, "unknown wrap mode");
    ExpectError("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"none.png\"\n", 4, "none.png");
    ExpectError("Texture \"m\" \"float\" \"mix\"\n  \"texture amount\" \"nothing\"\n", 5, "nothing");
    ExpectError("Texture \"m\" \"spectrum\" \"mix\"\n  \"texture amount\" \"sp\"\nTexture \"sp\" \"spectrum\" \"constant\"\n", 5,
                "float texture named \"sp\"");
    ExpectError("Texture \"a\" \"float\" \"scale\" \"texture tex\" \"b\"\nTexture \"b\" \"float\" \"scale\" \"texture tex\" \"a\"\n",
                4, "refers to itself");
}

}  // namespace
}  // namespace lu
