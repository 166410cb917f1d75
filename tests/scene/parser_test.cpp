// Tests of the pbrt-v4 parser: transformations (LookAt against a hand-computed matrix, Transform
// column-major), the graphics state, materials, lights, instancing, Include/Import, and that the
// shared scenes parse (with the water-caustic parse + PLY time measured).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "lucerna/scene/parser.h"
#include "lucerna/scene/ply.h"
#include "support/test_support.h"

namespace lu {

static SceneDescription Parse(const std::string &text, Diagnostics *diagOut = nullptr) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneString(text, "t.pbrt", diagOut ? *diagOut : diag);
    return d;
}

static void WriteFile(const std::string &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

static void ExpectPoint(const Transform &t, Vec3f p, Vec3f expected) {
    Vec3f q = t.ApplyPoint(p);
    EXPECT_NEAR(q.x, expected.x, 1e-5f);
    EXPECT_NEAR(q.y, expected.y, 1e-5f);
    EXPECT_NEAR(q.z, expected.z, 1e-5f);
}

static void ExpectMatrix(const Matrix4 &m, const double (&e)[4][4]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(m.m[i][j], e[i][j], 1e-6) << "entry " << i << "," << j;
}

// ---- transformations ----

TEST(Parser, LookAtIsLeftHandedAsPbrt) {
    // Eye (1,2,3) looking along +x with up +z. pbrt-v4's LookAt: dir = (1,0,0),
    // right = normalize(cross(up, dir)) = (0,1,0), newUp = cross(dir, right) = (0,0,1);
    // worldFromCamera has columns right, newUp, dir, eye.
    SceneDescription d = Parse("LookAt 1 2 3  2 2 3  0 0 1\nCamera \"perspective\"\nWorldBegin\n");
    const double worldFromCamera[4][4] = {{0, 0, 1, 1}, {1, 0, 0, 2}, {0, 1, 0, 3}, {0, 0, 0, 1}};
    ExpectMatrix(d.camera.worldFromCamera.m, worldFromCamera);
    const double cameraFromWorld[4][4] = {{0, 1, 0, -2}, {0, 0, 1, -3}, {1, 0, 0, -1}, {0, 0, 0, 1}};
    ExpectMatrix(d.camera.worldFromCamera.mInv, cameraFromWorld);
    // Camera +x (right on the image) is world +y: a left-handed camera space (x = up x dir).
    ExpectPoint(d.camera.worldFromCamera, Vec3f(1, 0, 0), Vec3f(1, 3, 3));
    EXPECT_EQ(d.camera.name, "perspective");
}

TEST(Parser, TransformIsColumnMajor) {
    SceneDescription d = Parse("WorldBegin\nTransform [ 2 0 0 0  0 3 0 0  0 0 4 0  5 6 7 1 ]\nShape \"sphere\"\n");
    ASSERT_EQ(d.shapes.size(), 1u);
    const double m[4][4] = {{2, 0, 0, 5}, {0, 3, 0, 6}, {0, 0, 4, 7}, {0, 0, 0, 1}};
    ExpectMatrix(d.shapes[0].renderFromObject.m, m);
    ExpectPoint(d.shapes[0].renderFromObject.Inverted(), Vec3f(7, 9, 11), Vec3f(1, 1, 1));
    // Also without brackets (pbrt-v3 style), and a non-affine column.
    SceneDescription e = Parse("WorldBegin\nTransform 1 0 0 0  0 1 0 0  0 0 1 0.5  0 0 0 1\nShape \"sphere\"\n");
    EXPECT_FLOAT_EQ(e.shapes[0].renderFromObject.m.m[3][2], 0.5f);
}

TEST(Parser, TransformsComposeLikePbrt) {
    // CTM = Translate * ConcatTransform(scale 2) * Rotate: a point is rotated, scaled, translated.
    SceneDescription d = Parse(
        "WorldBegin\nTranslate 1 0 0\nConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]\nRotate 90 0 0 1\n"
        "Shape \"sphere\"\nIdentity\nScale 1 2 3\nShape \"sphere\"\n");
    ASSERT_EQ(d.shapes.size(), 2u);
    ExpectPoint(d.shapes[0].renderFromObject, Vec3f(1, 0, 0), Vec3f(1, 2, 0));
    ExpectPoint(d.shapes[1].renderFromObject, Vec3f(1, 1, 1), Vec3f(1, 2, 3));
    // Normals use the inverse transpose.
    Vec3f n = d.shapes[1].renderFromObject.ApplyNormal(Vec3f(0, 0, 1));
    EXPECT_NEAR(n.z, 1.0f / 3.0f, 1e-6f);
}

TEST(Parser, AttributeBlocksRestoreTheGraphicsState) {
    SceneDescription d = Parse(
        "WorldBegin\nMaterial \"diffuse\"\nAttributeBegin\n Translate 0 0 5\n ReverseOrientation\n"
        " Material \"conductor\"\n AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n Shape \"sphere\"\nAttributeEnd\n"
        "Shape \"disk\"\n");
    ASSERT_EQ(d.shapes.size(), 2u);
    const ShapeEntity &in = d.shapes[0], &out = d.shapes[1];
    ExpectPoint(in.renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 5));
    EXPECT_TRUE(in.reverseOrientation);
    EXPECT_EQ(in.materialIndex, 1);
    EXPECT_EQ(in.areaLightIndex, 0);
    ExpectPoint(out.renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 0));
    EXPECT_FALSE(out.reverseOrientation);
    EXPECT_EQ(out.materialIndex, 0);
    EXPECT_EQ(out.areaLightIndex, -1);
    ASSERT_EQ(d.areaLights.size(), 1u);
    EXPECT_EQ(d.areaLights[0].name, "diffuse");
    EXPECT_EQ(d.materials[1].name, "conductor");
}

TEST(Parser, TransformBeginIsDeprecatedAndWarnsOnce) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = Parse(
        "WorldBegin\nTransformBegin\nTranslate 1 0 0\nShape \"a\"\nTransformEnd\nTransformBegin\nTransformEnd\n"
        "Shape \"b\"\n",
        &diag);
    ExpectPoint(d.shapes[1].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 0));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_EQ(diag.warnings[0],
              "t.pbrt:2:1: warning: TransformBegin/End are deprecated and should be replaced with AttributeBegin/End");
}

TEST(Parser, WorldBeginResetsTheCtmAndNamedCoordinateSystems) {
    SceneDescription d = Parse(
        "Scale -1 1 1\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\nWorldBegin\n"
        "Translate 0 1 0\nCoordinateSystem \"up\"\nIdentity\nShape \"a\"\nCoordSysTransform \"up\"\nShape \"b\"\n"
        "CoordSysTransform \"camera\"\nShape \"c\"\nCoordSysTransform \"world\"\nShape \"d\"\n");
    ASSERT_EQ(d.shapes.size(), 4u);
    ExpectPoint(d.shapes[0].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 0));
    ExpectPoint(d.shapes[1].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 1, 0));
    // "camera" is worldFromCamera: the camera origin is the eye.
    ExpectPoint(d.shapes[2].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, -5));
    ExpectPoint(d.shapes[2].renderFromObject, Vec3f(0, 0, 1), Vec3f(0, 0, -4));
    ExpectPoint(d.shapes[3].renderFromObject, Vec3f(1, 2, 3), Vec3f(1, 2, 3));
    // The Scale -1 1 1 before LookAt mirrors the image (camera x flips).
    ExpectPoint(d.camera.worldFromCamera, Vec3f(1, 0, 0), Vec3f(-1, 0, -5));
    EXPECT_DOUBLE_EQ(d.camera.params.GetOneFloat("fov", 90), 45);
}

// ---- materials, textures, lights, shapes ----

TEST(Parser, MaterialsAndNamedMaterials) {
    SceneDescription d = Parse(
        "WorldBegin\nShape \"default\"\nMakeNamedMaterial \"glass\" \"string type\" \"dielectric\" \"float eta\" 1.5\n"
        "NamedMaterial \"glass\"\nShape \"a\"\nMaterial \"diffuse\" \"rgb reflectance\" [.5 .5 .5]\nShape \"b\"\n");
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[0].materialIndex, -1);  // pbrt-v4's default: diffuse
    EXPECT_EQ(d.shapes[0].materialName, "");
    EXPECT_EQ(d.shapes[1].materialName, "glass");
    EXPECT_EQ(d.shapes[1].materialIndex, -1);
    EXPECT_EQ(d.shapes[2].materialIndex, 0);
    EXPECT_EQ(d.shapes[2].materialName, "");
    const SceneEntity &glass = d.namedMaterials.at("glass");
    EXPECT_EQ(glass.name, "dielectric");
    EXPECT_EQ(glass.params.GetOneString("type", ""), "dielectric");
    EXPECT_DOUBLE_EQ(glass.params.GetOneFloat("eta", 1), 1.5);
}

TEST(Parser, NamedMaterialMayBeDefinedLater) {
    // pbrt-v4 resolves named materials after parsing; so do we.
    SceneDescription d = Parse("WorldBegin\nNamedMaterial \"m\"\nShape \"a\"\nMakeNamedMaterial \"m\" \"string type\" \"diffuse\"\n");
    EXPECT_EQ(d.shapes[0].materialName, "m");
}

TEST(Parser, TexturesLightsAndMedia) {
    SceneDescription d = Parse(
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\nWorldBegin\n"
        "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 4\nTexture \"r\" \"float\" \"constant\"\n"
        "LightSource \"point\" \"rgb I\" [1 2 3]\nMediumInterface \"fog\" \"\"\nShape \"a\"\nMediumInterface \"fog\"\n"
        "LightSource \"spot\"\n");
    ASSERT_EQ(d.spectrumTextures.size(), 1u);
    EXPECT_EQ(d.spectrumTextures[0].textureName, "checks");
    EXPECT_EQ(d.spectrumTextures[0].name, "checkerboard");
    EXPECT_EQ(d.spectrumTextures[0].valueType, "spectrum");
    ASSERT_EQ(d.floatTextures.size(), 1u);
    ASSERT_EQ(d.lights.size(), 2u);
    EXPECT_EQ(d.lights[0].name, "point");
    EXPECT_EQ(d.lights[0].outsideMedium, "");
    EXPECT_EQ(d.lights[1].outsideMedium, "fog");
    EXPECT_EQ(d.shapes[0].insideMedium, "fog");
    EXPECT_EQ(d.shapes[0].outsideMedium, "");
    ASSERT_EQ(d.media.size(), 1u);
    EXPECT_EQ(d.media[0].name, "fog");
}

TEST(Parser, AttributeDefaultsApplyAndExplicitParametersWin) {
    SceneDescription d = Parse(
        "WorldBegin\nAttributeBegin\nAttribute \"shape\" \"float radius\" 2 \"float zmax\" 1\n"
        "Shape \"sphere\"\nShape \"sphere\" \"float radius\" 3\nAttributeEnd\nShape \"sphere\"\n");
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[0].params.GetOneFloat("radius", 1), 2);
    EXPECT_EQ(d.shapes[1].params.GetOneFloat("radius", 1), 3);
    EXPECT_EQ(d.shapes[2].params.GetOneFloat("radius", 1), 1);
    // Unused attribute defaults are not reported.
    Diagnostics diag;
    diag.quiet = true;
    d.shapes[1].params.ReportUnused(diag, "Shape");
    EXPECT_TRUE(diag.warnings.empty());
}

TEST(Parser, ObjectInstancing) {
    SceneDescription d = Parse(
        "WorldBegin\nObjectBegin \"tree\"\nShape \"trianglemesh\"\nShape \"sphere\"\nObjectEnd\n"
        "Translate 1 0 0\nObjectInstance \"tree\"\nObjectInstance \"tree\"\n");
    EXPECT_TRUE(d.shapes.empty());
    ASSERT_EQ(d.instanceDefinitions.count("tree"), 1u);
    EXPECT_EQ(d.instanceDefinitions.at("tree").shapes.size(), 2u);
    ASSERT_EQ(d.instances.size(), 2u);
    ExpectPoint(d.RenderFromInstance(d.instances[0]), Vec3f(0, 0, 0), Vec3f(1, 0, 0));
    // The compact use record: the object by index, the location as (file, line, col).
    EXPECT_EQ(d.ObjectName(d.instances[1]), "tree");
    EXPECT_EQ(d.Loc(d.instances[1]).line, 8);
    EXPECT_EQ(d.Loc(d.instances[1]).col, 1);
    EXPECT_EQ(d.instances[0].projective, 0xffffffffu);
}

TEST(Parser, ProjectiveObjectInstanceKeepsItsTransform) {
    SceneDescription d = Parse(
        "WorldBegin\nObjectBegin \"a\"\nShape \"sphere\"\nObjectEnd\n"
        "Transform [1 0 0 0  0 1 0 0  0 0 1 0.5  0 0 0 1]\nObjectInstance \"a\"\n");
    ASSERT_EQ(d.instances.size(), 1u);
    ASSERT_NE(d.instances[0].projective, 0xffffffffu);
    Transform t = d.RenderFromInstance(d.instances[0]);
    EXPECT_EQ(t.m.m[3][2], 0.5f);
}

TEST(Parser, OptionsColorSpaceAndSceneWideEntities) {
    SceneDescription d = Parse(
        "Option \"disablepixeljitter\" true\nColorSpace \"rec2020\"\nFilm \"rgb\" \"integer xresolution\" 64\n"
        "Sampler \"zsobol\"\nIntegrator \"path\" \"integer maxdepth\" 5\nPixelFilter \"box\"\nAccelerator \"bvh\"\n"
        "WorldBegin\n");
    ASSERT_EQ(d.options.size(), 1u);
    EXPECT_EQ(d.options[0].name, "disablepixeljitter");
    EXPECT_EQ(d.options[0].value, "true");
    EXPECT_EQ(d.options[0].loc.line, 1);
    EXPECT_EQ(d.film.colorSpace, uint8_t(ColorSpaceId::Rec2020));  // the ColorSpace in effect at Film
    EXPECT_EQ(d.film.name, "rgb");
    EXPECT_EQ(d.film.params.GetOneInt("xresolution", 0), 64);
    EXPECT_EQ(d.sampler.name, "zsobol");
    EXPECT_EQ(d.integrator.params.GetOneInt("maxdepth", 0), 5);
    EXPECT_EQ(d.filter.name, "box");
    EXPECT_EQ(d.accelerator.name, "bvh");
    EXPECT_EQ(d.camera.name, "");  // absent: defaults apply
}

TEST(Parser, MotionTransformsAreReportedUnsupported) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = Parse(
        "WorldBegin\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\nShape \"a\"\n", &diag);
    ExpectPoint(d.shapes[0].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 0));  // the start transform
    ASSERT_EQ(diag.unsupported.size(), 1u);
    EXPECT_EQ(diag.unsupported[0], "motion blur (ActiveTransform)");
    ASSERT_EQ(diag.warnings.size(), 2u);
    EXPECT_EQ(diag.warnings[0], "t.pbrt:2:1: warning: ActiveTransform: motion blur is not supported; the start-time "
                                "transformation is used");
    EXPECT_EQ(diag.warnings[1], "t.pbrt:5:1: warning: motion blur (ActiveTransform) is not supported: the start-time "
                                "transform is used");
    // Without a difference between the start and end transformations nothing is unsupported.
    Diagnostics quiet;
    quiet.quiet = true;
    Parse("WorldBegin\nActiveTransform StartTime\nActiveTransform All\nShape \"a\"\n", &quiet);
    EXPECT_TRUE(quiet.unsupported.empty());
}

// ---- files ----

TEST(Parser, IncludeAndImportResolveRelativeToTheIncludingFile) {
    std::string dir = test::TempDir("parser_include");
    std::filesystem::create_directories(dir + "/sub");
    WriteFile(dir + "/main.pbrt",
              "Include \"sub/cam.pbrt\"\nWorldBegin\nImport \"sub/geo.pbrt\"\nShape \"after\"\n");
    WriteFile(dir + "/sub/cam.pbrt", "Camera \"orthographic\"\n");
    // The imported file's state changes (transform, material) do not leak back.
    WriteFile(dir + "/sub/geo.pbrt",
              "Translate 0 0 1\nMaterial \"conductor\"\nInclude \"more.pbrt\"\nShape \"plymesh\" \"string filename\" \"m.ply\"\n");
    WriteFile(dir + "/sub/more.pbrt", "Shape \"sphere\"\n");
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneFile(dir + "/main.pbrt", diag);
    EXPECT_EQ(d.camera.name, "orthographic");
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[0].name, "sphere");
    EXPECT_EQ(d.shapes[1].baseDirectory, dir + "/sub");
    ExpectPoint(d.shapes[1].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 1));
    EXPECT_EQ(d.shapes[1].materialIndex, 0);
    EXPECT_EQ(d.shapes[2].name, "after");
    ExpectPoint(d.shapes[2].renderFromObject, Vec3f(0, 0, 0), Vec3f(0, 0, 0));
    EXPECT_EQ(d.shapes[2].materialIndex, -1);
    EXPECT_EQ(d.baseDirectory, dir);
}

TEST(Parser, FileAccessCanBeDisabled) {
    Diagnostics diag;
    diag.quiet = true;
    ParseOptions opt;
    opt.allowFileAccess = false;
    try {
        ParseSceneString("Include \"/etc/hostname\"\n", "t.pbrt", diag, opt);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "\"Include\" is disabled (no file access)");
    }
}

// ---- the shared scenes ----

TEST(Parser, SharedScenesParse) {
    const char *scenes[] = {
        "bitterli-cornell-box/scene-v4.pbrt",        "bitterli-veach-mis/scene-v4.pbrt",
        "bitterli-veach-bidir/scene-v4.pbrt",        "bitterli-volumetric-caustic/scene-v4-nomedium.pbrt",
        "bitterli-water-caustic/scene-v4.pbrt",      "pbrt-v3-caustic-glass/scene-v4.pbrt",
        "smallvcm-cornell/smallvcm-bs_c.pbrt",       "smallvcm-cornell/smallvcm-bs_p.pbrt",
        "bitterli-volumetric-caustic/scene-v4.pbrt", "bitterli-volumetric-caustic/scene-v4.gonsolo.pbrt"};
    for (const char *s : scenes) {
        SCOPED_TRACE(s);
        Diagnostics diag;
        diag.quiet = true;
        SceneDescription d;
        try {
            d = ParseSceneFile(test::SharedPath(std::string("scenes/") + s), diag);
        } catch (SceneError &e) {
            FAIL() << e.Format();
        }
        EXPECT_FALSE(d.shapes.empty());
        EXPECT_FALSE(d.camera.name.empty());
        EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
        // Every named material used is defined and every plymesh loads.
        for (const ShapeEntity &sh : d.shapes) {
            if (!sh.materialName.empty()) { EXPECT_EQ(d.namedMaterials.count(sh.materialName), 1u); }
            if (sh.name == "plymesh") {
                PlyMesh m = ReadPlyMesh(ResolvePath(sh.baseDirectory, sh.params.GetOneString("filename", "")), sh.loc);
                EXPECT_GT(m.indices.size(), 0u);
            }
        }
        bool media = std::string(s).find("nomedium") == std::string::npos &&
                     std::string(s).find("volumetric") != std::string::npos;
        EXPECT_EQ(!d.media.empty(), media);
    }
}

TEST(Parser, WaterCausticParsesQuickly) {
    // Parse + PLY loading of the 100k-triangle scene; best of 3 to reduce noise.
    double best = 1e9;
    size_t triangles = 0;
    for (int rep = 0; rep < 3; ++rep) {
        auto t0 = std::chrono::steady_clock::now();
        Diagnostics diag;
        diag.quiet = true;
        SceneDescription d = ParseSceneFile(test::SharedPath("scenes/bitterli-water-caustic/scene-v4.pbrt"), diag);
        triangles = 0;
        for (const ShapeEntity &sh : d.shapes)
            if (sh.name == "plymesh")
                triangles += ReadPlyMesh(ResolvePath(sh.baseDirectory, sh.params.GetOneString("filename", "")), sh.loc)
                                 .indices.size() / 3;
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    EXPECT_EQ(triangles, 103451u);
    std::printf("[ timing ] water-caustic parse + PLY: %.1f ms (%zu PLY triangles)\n", best * 1e3, triangles);
#ifdef NDEBUG
    EXPECT_LT(best, 0.5);
#endif
}

}  // namespace lu
