// Lucerna scene builder: textures, after pbrt-v4's textures.cpp Create() functions,
// TextureMapping2D/3D::Create and TextureParameterDictionary (paramdict.cpp). A texture is a
// root node (held by value by materials) whose children are appended to HostScene::floatTextures
// and spectrumTextures and referenced by index.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "lucerna/image/image.h"
#include "lucerna/scene/build_internal.h"

namespace lu::build {

namespace {

std::string Owner(const TextureEntity &te) { return "Texture " + Quoted(te.textureName) + " (" + Quoted(te.name) + ")"; }

// ---- Mappings ----

Matrix4 TextureFromRender(const TextureEntity &te) {
    Matrix4 inv;
    if (!Inverse(te.renderFromObject.m, &inv))
        Fail(te.loc, "texture " + Quoted(te.textureName) + ": the current transform is singular (no texture space)");
    return inv;
}

// pbrt-v4's TextureMapping2D::Create.
TextureMapping ReadMapping2D(const TextureEntity &te) {
    const ParameterDictionary &p = te.params;
    std::string type = p.GetOneString("mapping", "uv");
    TextureMapping m;
    if (type == "uv") {
        m.kind = TextureMappingKind::UV;
        m.su = Float(p.GetOneFloat("uscale", 1));
        m.sv = Float(p.GetOneFloat("vscale", 1));
        m.du = Float(p.GetOneFloat("udelta", 0));
        m.dv = Float(p.GetOneFloat("vdelta", 0));
    } else if (type == "spherical") {
        m.kind = TextureMappingKind::Spherical;
        m.textureFromRender = TextureFromRender(te);
    } else if (type == "cylindrical") {
        m.kind = TextureMappingKind::Cylindrical;
        m.textureFromRender = TextureFromRender(te);
    } else if (type == "planar") {
        m.kind = TextureMappingKind::Planar;
        m.textureFromRender = TextureFromRender(te);
        m.vs = p.GetOneVector3f("v1").value_or(Vec3f(1, 0, 0));
        m.vt = p.GetOneVector3f("v2").value_or(Vec3f(0, 1, 0));
        m.du = Float(p.GetOneFloat("udelta", 0));
        m.dv = Float(p.GetOneFloat("vdelta", 0));
    } else {
        Fail(ParamLoc(p, "mapping", te.loc), "2D texture mapping " + Quoted(type) +
                                                 " unknown: must be \"uv\", \"spherical\", \"cylindrical\" or \"planar\"");
    }
    return m;
}

// pbrt-v4's TextureMapping3D::Create: the point in texture space (no parameters).
TextureMapping ReadMapping3D(const TextureEntity &te) {
    TextureMapping m;
    m.kind = TextureMappingKind::Point;
    m.textureFromRender = TextureFromRender(te);
    return m;
}

// ---- Image maps ----

enum class ImageReduce { RGB, Average, Channel0 };  // what a texture keeps of the file's channels

struct Encoding {
    enum Kind { SRGB, Linear, Gamma } kind = SRGB;
    float gamma = 1;
};

// pbrt-v4's ColorEncoding::Get: "linear", "sRGB" or "gamma G".
Encoding ParseEncoding(const std::string &s, const FileLoc &loc) {
    Encoding e;
    if (s == "sRGB") return e;
    if (s == "linear") {
        e.kind = Encoding::Linear;
        return e;
    }
    float g = 0;
    char extra = 0;
    if (s.rfind("gamma ", 0) == 0 && std::sscanf(s.c_str() + 6, "%f %c", &g, &extra) == 1 && std::isfinite(g) && g > 0) {
        e.kind = Encoding::Gamma;
        e.gamma = g;
        return e;
    }
    Fail(loc, Quoted(s) + ": unknown color encoding (must be \"sRGB\", \"linear\" or \"gamma G\" with G > 0)");
}

// Reads a texture image and keeps what the texture looks up: RGB (1 or 3 channels; alpha is
// dropped) for spectrum textures; for float textures pbrt-v4's MIPMap rules: one channel as it
// is, RGB averaged, RGBA whose alpha is not all one: the alpha; the "point" filter reads
// channel 0 (MIPMap::Texel<Float>). 8-bit and 16-bit PNG values are decoded by `enc`.
LoadedImage LoadTextureImage(BuildContext &ctx, const std::string &path, bool isPNG, const Encoding &enc,
                             ImageReduce reduce, const FileLoc &loc) {
    std::string key = path + '\n' + std::to_string(int(enc.kind)) + ' ' + std::to_string(enc.gamma) + ' ' +
                      std::to_string(int(reduce));
    if (auto it = ctx.textureImageCache.find(key); it != ctx.textureImageCache.end()) return it->second;
    ctx.scene.inputFiles.push_back(path);
    Image img;
    try {
        img = ReadImage(path, enc.kind != Encoding::SRGB);
    } catch (const std::exception &e) {
        Fail(loc, e.what());
    }
    if (img.width <= 0 || img.height <= 0 || img.channels <= 0) Fail(loc, Quoted(path) + ": empty image");
    if (img.channels == 2) Fail(loc, Quoted(path) + ": two-channel images are not supported (need Y, RGB or RGBA)");
    if (CountNonFinite(img) > 0) Fail(loc, Quoted(path) + ": image has infinite or not-a-number pixel values");
    int colorChannels = img.channels == 1 ? 1 : 3;
    if (isPNG && enc.kind == Encoding::Gamma)
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                for (int c = 0; c < colorChannels; ++c) img.At(x, y, c) = std::pow(img.At(x, y, c), enc.gamma);
    bool useAlpha = false;
    if (reduce == ImageReduce::Average && img.channels == 4) {
        for (size_t i = 3; i < img.pixels.size() && !useAlpha; i += 4) useAlpha = img.pixels[i] != 1;
    }
    LoadedImage li;
    li.width = uint32_t(img.width);
    li.height = uint32_t(img.height);
    li.channels = reduce == ImageReduce::RGB ? uint32_t(colorChannels) : 1;
    li.offset = ctx.scene.texels.size();
    std::vector<Float> &texels = ctx.scene.texels;
    texels.reserve(texels.size() + size_t(img.width) * img.height * li.channels);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            if (li.channels == uint32_t(colorChannels)) {
                for (int c = 0; c < colorChannels; ++c) texels.push_back(Float(img.At(x, y, c)));
            } else if (reduce == ImageReduce::Channel0) {
                texels.push_back(Float(img.At(x, y, 0)));
            } else if (useAlpha) {
                texels.push_back(Float(img.At(x, y, 3)));
            } else {
                texels.push_back(Float((img.At(x, y, 0) + img.At(x, y, 1) + img.At(x, y, 2)) / 3));
            }
        }
    ctx.textureImageCache[key] = li;
    return li;
}

struct ImageTexParams {
    uint32_t image = NoIndex;
    Float scale = 1;
    bool invert = false, point = false;
};

// pbrt-v4's FloatImageTexture / SpectrumImageTexture::Create parameters.
// `warn`: report the approximations (false when a spectrum texture is built again for another
// spectrum type).
ImageTexParams ReadImageTexture(BuildContext &ctx, const TextureEntity &te, bool isFloat, bool warn) {
    const ParameterDictionary &p = te.params;
    ImageTexParams r;
    // Filtering: Lucerna point-samples textures (no ray differentials): every pbrt-v4 filter at a
    // zero-width footprint is a lookup in the finest level, bilinear except for "point".
    if (p.Has("maxanisotropy")) {
        (void)p.GetOneFloat("maxanisotropy", 8);
        if (warn)
            ctx.diag.Warning(ParamLoc(p, "maxanisotropy", te.loc),
                         "\"maxanisotropy\" is ignored: Lucerna has no ray differentials (textures are point-sampled)");
    }
    std::string filter = p.GetOneString("filter", "bilinear");
    if (filter == "point") r.point = true;
    else if (filter == "trilinear" || filter == "ewa" || filter == "EWA") {
        if (warn)
            ctx.diag.Warning(ParamLoc(p, "filter", te.loc),
                         "texture filter " + Quoted(filter) +
                             " needs ray differentials, which Lucerna does not have: bilinear lookups in the finest "
                             "level (pbrt-v4's result for a zero-width footprint)");
    } else if (filter != "bilinear")
        Fail(ParamLoc(p, "filter", te.loc), Quoted(filter) +
                                                ": unknown texture filter function (must be \"point\", \"bilinear\", "
                                                "\"trilinear\" or \"ewa\")");
    std::string wrapString = p.GetOneString("wrap", "repeat");
    WrapMode wrap;
    if (wrapString == "repeat") wrap = WrapMode::Repeat;
    else if (wrapString == "clamp") wrap = WrapMode::Clamp;
    else if (wrapString == "black") wrap = WrapMode::Black;
    else if (wrapString == "octahedralsphere") wrap = WrapMode::OctahedralSphere;
    else
        Fail(ParamLoc(p, "wrap", te.loc), Quoted(wrapString) + ": unknown wrap mode");
    r.scale = Float(p.GetOneFloat("scale", 1));
    r.invert = p.GetOneBool("invert", false);
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty()) Fail(te.loc, "\"string filename\" not provided for image texture " + Quoted(te.textureName));
    std::string path = ResolveScenePath(ctx, te.baseDirectory, filename);
    std::string ext = std::filesystem::path(filename).extension().string();
    for (char &c : ext) c = char(std::tolower((unsigned char)c));
    bool isPNG = ext == ".png";
    FileLoc encLoc = ParamLoc(p, "encoding", te.loc);
    Encoding enc = ParseEncoding(p.GetOneString("encoding", isPNG ? "sRGB" : "linear"), encLoc);
    if (!isPNG && enc.kind != Encoding::Linear) {
        if (warn)
            ctx.diag.Warning(encLoc, "\"encoding\" only applies to 8-bit (PNG) images; " + Quoted(filename) +
                                     " is read as linear");
        enc = Encoding{Encoding::Linear, 1};
    }
    ImageReduce reduce = !isFloat ? ImageReduce::RGB : (r.point ? ImageReduce::Channel0 : ImageReduce::Average);
    LoadedImage img = LoadTextureImage(ctx, path, isPNG, enc, reduce, te.loc);
    r.image = AddImageData(ctx, img, wrap);
    return r;
}

// ---- References between textures ----

const TextureEntity *FindTexture(const std::map<std::string, const TextureEntity *> &m, const std::string &name) {
    auto it = m.find(name);
    return it == m.end() ? nullptr : it->second;
}

const ParsedParameter &TextureReference(const ParameterDictionary &params, const std::string &name) {
    const ParsedParameter *p = params.Find(name);
    if (p->strings.size() != 1) Fail(p->loc, "parameter \"texture " + name + "\" needs exactly one texture name");
    return *p;
}

FloatTexture BuildFloatTexture(BuildContext &ctx, const TextureEntity &te);
SpectrumTexture BuildSpectrumTexture(BuildContext &ctx, const TextureEntity &te, SpectrumType type);

const TextureEntity &FloatTextureEntity(BuildContext &ctx, const std::string &texName, const ParsedParameter &p) {
    const TextureEntity *te = FindTexture(ctx.floatTextures, texName);
    if (!te) Fail(p.loc, "couldn't find float texture named " + Quoted(texName) + " for parameter " + Quoted(p.name));
    return *te;
}

const TextureEntity &SpectrumTextureEntity(BuildContext &ctx, const std::string &texName, const ParsedParameter &p) {
    const TextureEntity *te = FindTexture(ctx.spectrumTextures, texName);
    if (!te) Fail(p.loc, "couldn't find spectrum texture named " + Quoted(texName) + " for parameter " + Quoted(p.name));
    return *te;
}

uint32_t AddFloatNode(BuildContext &ctx, const FloatTexture &t) {
    ctx.scene.floatTextures.push_back(t);
    return uint32_t(ctx.scene.floatTextures.size() - 1);
}

uint32_t AddSpectrumNode(BuildContext &ctx, const SpectrumTexture &t) {
    ctx.scene.spectrumTextures.push_back(t);
    return uint32_t(ctx.scene.spectrumTextures.size() - 1);
}

// A float texture parameter as a child node: a named texture is stored once, a constant per use.
uint32_t FloatChild(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def) {
    if (params.TypeOf(name) == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        const std::string &texName = p.strings[0];
        if (auto it = ctx.floatTextureNodes.find(texName); it != ctx.floatTextureNodes.end()) return it->second;
        FloatTexture t = BuildFloatTexture(ctx, FloatTextureEntity(ctx, texName, p));
        return ctx.floatTextureNodes[texName] = AddFloatNode(ctx, t);
    }
    return AddFloatNode(ctx, GetFloatTexture(ctx, params, name, def));
}

uint32_t SpectrumChild(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, SpectrumType type,
                       const Spectrum &def) {
    if (params.TypeOf(name) == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        auto key = std::make_pair(p.strings[0], int(type));
        if (auto it = ctx.spectrumTextureNodes.find(key); it != ctx.spectrumTextureNodes.end()) return it->second;
        SpectrumTexture t = BuildSpectrumTexture(ctx, SpectrumTextureEntity(ctx, p.strings[0], p), type);
        return ctx.spectrumTextureNodes[key] = AddSpectrumNode(ctx, t);
    }
    return AddSpectrumNode(ctx, GetSpectrumTexture(ctx, params, name, type, def));
}

// ---- Nesting depth (materials/texture.h evaluates at most MaxTextureDepth levels) ----

bool IsComposite(TextureKind k) {
    return k == TextureKind::Scale || k == TextureKind::Mix || k == TextureKind::DirectionMix ||
           k == TextureKind::Checkerboard || k == TextureKind::Dots;
}

// Levels below t (0 for a leaf); the walk stops once it passes `cutoff`.
int FloatDepth(const HostScene &s, const FloatTexture &t, int cutoff) {
    if (!IsComposite(t.kind) || cutoff <= 0) return 0;
    int d = 0;
    for (uint32_t c : {t.tex[0], t.tex[1], t.amount})
        if (c != NoIndex) d = Max(d, 1 + FloatDepth(s, s.floatTextures[c], cutoff - 1));
    return d;
}

int SpectrumDepth(const HostScene &s, const SpectrumTexture &t, int cutoff) {
    if ((!IsComposite(t.kind) && t.kind != TextureKind::Bilerp) || cutoff <= 0) return 0;
    int d = 0;
    for (uint32_t c : t.tex)
        if (c != NoIndex) d = Max(d, 1 + SpectrumDepth(s, s.spectrumTextures[c], cutoff - 1));
    if (t.amount != NoIndex) d = Max(d, 1 + FloatDepth(s, s.floatTextures[t.amount], cutoff - 1));
    return d;
}

void CheckDepth(int depth, const TextureEntity &te) {
    if (depth > MaxTextureDepth)
        FailUnsupported(te.loc, "texture " + Quoted(te.textureName) + " nesting more than " +
                                    std::to_string(MaxTextureDepth) + " levels of textures");
}

// ---- Noise parameters ----

int ReadOctaves(const TextureEntity &te) {
    int n = te.params.GetOneInt("octaves", 8);
    if (n < 0 || n > 32)
        Fail(ParamLoc(te.params, "octaves", te.loc), "\"octaves\" must be in [0, 32] (got " + std::to_string(n) + ")");
    return n;
}

Vec3f ReadDirection(const TextureEntity &te) {
    Vec3f dir = te.params.GetOneVector3f("dir").value_or(Vec3f(0, 1, 0));
    Vec3f d = te.renderFromObject.ApplyVector(dir);
    if (!(LengthSquared(d) > 0) || !IsFinite(d))
        Fail(ParamLoc(te.params, "dir", te.loc), "\"dir\" of a directionmix texture must be a nonzero direction");
    return Normalize(d);
}

bool IsFloatOnly(const std::string &t) { return t == "fbm" || t == "wrinkled" || t == "windy"; }

[[noreturn]] void FailPtex(const TextureEntity &te) {
    FailUnsupported(te.loc, "Texture type \"ptex\"", "Lucerna has no Ptex reader: Debian 12 packages no Ptex library");
}

// ---- Float textures (pbrt-v4's FloatTexture::Create) ----

FloatTexture BuildFloatTexture(BuildContext &ctx, const TextureEntity &te) {
    if (auto it = ctx.floatTextureCache.find(te.textureName); it != ctx.floatTextureCache.end()) return it->second;
    std::string key = "float:" + te.textureName;
    if (ctx.texturesBuilding.count(key)) Fail(te.loc, "texture " + Quoted(te.textureName) + " refers to itself");
    ctx.texturesBuilding.insert(key);
    const ParameterDictionary &p = te.params;
    FloatTexture ft;
    const std::string &type = te.name;
    if (type == "constant") {
        ft.kind = TextureKind::Constant;
        ft.value = Float(p.GetOneFloat("value", 1));
    } else if (type == "scale") {
        // pbrt-v4's FloatScaledTexture::Create: a constant 1 factor returns the other texture; a
        // constant factor of an image map folds into the image's scale.
        uint32_t tex = FloatChild(ctx, p, "tex", 1), scale = FloatChild(ctx, p, "scale", 1);
        const std::vector<FloatTexture> &nodes = ctx.scene.floatTextures;
        bool folded = false;
        for (int i = 0; i < 2 && !folded; ++i) {
            if (nodes[scale].kind == TextureKind::Constant) {
                Float cs = nodes[scale].value;
                if (cs == 1) {
                    ft = nodes[tex];
                    folded = true;
                } else if (nodes[tex].kind == TextureKind::ImageMap) {
                    ft = nodes[tex];
                    ft.scale *= cs;
                    folded = true;
                }
            }
            std::swap(tex, scale);
        }
        if (!folded) {
            // pbrt-v4 swaps once more: the product's first factor (checked for 0) is "tex".
            ft.kind = TextureKind::Scale;
            ft.tex[0] = scale;
            ft.amount = tex;
        }
    } else if (type == "mix") {
        ft.kind = TextureKind::Mix;
        ft.tex[0] = FloatChild(ctx, p, "tex1", 0);
        ft.tex[1] = FloatChild(ctx, p, "tex2", 1);
        ft.amount = FloatChild(ctx, p, "amount", 0.5f);
    } else if (type == "directionmix") {
        ft.kind = TextureKind::DirectionMix;
        ft.dir = ReadDirection(te);
        ft.tex[0] = FloatChild(ctx, p, "tex1", 0);
        ft.tex[1] = FloatChild(ctx, p, "tex2", 1);
    } else if (type == "bilerp") {
        ft.kind = TextureKind::Bilerp;
        ft.mapping = ReadMapping2D(te);
        ft.v00 = Float(p.GetOneFloat("v00", 0));
        ft.v01 = Float(p.GetOneFloat("v01", 1));
        ft.v10 = Float(p.GetOneFloat("v10", 0));
        ft.v11 = Float(p.GetOneFloat("v11", 1));
    } else if (type == "imagemap") {
        ft.kind = TextureKind::ImageMap;
        ft.mapping = ReadMapping2D(te);
        ImageTexParams ip = ReadImageTexture(ctx, te, true, true);
        ft.image = ip.image;
        ft.scale = ip.scale;
        ft.invert = ip.invert;
        ft.pointFilter = ip.point;
    } else if (type == "checkerboard") {
        int dim = p.GetOneInt("dimension", 2);
        if (dim != 2 && dim != 3)
            Fail(ParamLoc(p, "dimension", te.loc), std::to_string(dim) + " dimensional checkerboard texture not supported");
        ft.kind = TextureKind::Checkerboard;
        ft.tex[0] = FloatChild(ctx, p, "tex1", 1);
        ft.tex[1] = FloatChild(ctx, p, "tex2", 0);
        ft.mapping = dim == 2 ? ReadMapping2D(te) : ReadMapping3D(te);
    } else if (type == "dots") {
        // pbrt-v4's FloatDotsTexture::Create passes "inside" as the constructor's outsideDot and
        // "outside" as insideDot: the "outside" texture shows inside the dots. Kept, so that
        // scenes look as they do in pbrt-v4.
        ft.kind = TextureKind::Dots;
        ft.mapping = ReadMapping2D(te);
        uint32_t inside = FloatChild(ctx, p, "inside", 1), outside = FloatChild(ctx, p, "outside", 0);
        ft.tex[0] = outside;
        ft.tex[1] = inside;
    } else if (type == "fbm" || type == "wrinkled") {
        ft.kind = type == "fbm" ? TextureKind::FBm : TextureKind::Wrinkled;
        ft.mapping = ReadMapping3D(te);
        ft.octaves = ReadOctaves(te);
        ft.omega = Float(p.GetOneFloat("roughness", .5f));
    } else if (type == "windy") {
        ft.kind = TextureKind::Windy;
        ft.mapping = ReadMapping3D(te);
    } else if (type == "ptex") {
        FailPtex(te);
    } else if (type == "marble") {
        Fail(te.loc, "\"marble\" is a spectrum texture in pbrt-v4: there is no float \"marble\" texture");
    } else {
        Fail(te.loc, "unknown texture type " + Quoted(type));
    }
    CheckDepth(FloatDepth(ctx.scene, ft, MaxTextureDepth + 1), te);
    p.ReportUnused(ctx.diag, Owner(te));
    ctx.texturesBuilding.erase(key);
    ctx.floatTextureCache[te.textureName] = ft;
    return ft;
}

// ---- Spectrum textures (pbrt-v4's SpectrumTexture::Create) ----

SpectrumTexture BuildSpectrumTexture(BuildContext &ctx, const TextureEntity &te, SpectrumType type) {
    auto ckey = std::make_pair(te.textureName, int(type));
    if (auto it = ctx.spectrumTextureCache.find(ckey); it != ctx.spectrumTextureCache.end()) return it->second;
    std::string key = "spectrum:" + te.textureName;
    if (ctx.texturesBuilding.count(key)) Fail(te.loc, "texture " + Quoted(te.textureName) + " refers to itself");
    ctx.texturesBuilding.insert(key);
    // Parameters are read once per spectrum type; warn and report unused on the first.
    bool first = true;
    for (auto &[k, v] : ctx.spectrumTextureCache)
        if (k.first == te.textureName) first = false;
    const ParameterDictionary &p = te.params;
    SpectrumTexture st;
    st.unbounded = type != SpectrumType::Albedo;
    const Spectrum zero = Spectrum::Const(0), one = Spectrum::Const(1);
    const std::string &name = te.name;
    if (name == "constant") {
        st = GetSpectrumTexture(ctx, p, "value", type, one);
        if (st.kind != TextureKind::Constant) FailUnsupported(te.loc, "constant texture whose \"value\" is a texture");
    } else if (name == "scale") {
        // pbrt-v4's SpectrumScaledTexture::Create: a constant factor 1 returns "tex"; a constant
        // factor of an image map folds into the image's scale.
        uint32_t tex = SpectrumChild(ctx, p, "tex", type, one);
        uint32_t scale = FloatChild(ctx, p, "scale", 1);
        const FloatTexture &sc = ctx.scene.floatTextures[scale];
        const SpectrumTexture &tx = ctx.scene.spectrumTextures[tex];
        if (sc.kind == TextureKind::Constant && sc.value == 1) {
            st = tx;
        } else if (sc.kind == TextureKind::Constant && tx.kind == TextureKind::ImageMap) {
            Float cs = sc.value;
            st = tx;
            st.scale *= cs;
        } else {
            st.kind = TextureKind::Scale;
            st.tex[0] = tex;
            st.amount = scale;
        }
    } else if (name == "mix") {
        st.kind = TextureKind::Mix;
        st.tex[0] = SpectrumChild(ctx, p, "tex1", type, zero);
        st.tex[1] = SpectrumChild(ctx, p, "tex2", type, one);
        st.amount = FloatChild(ctx, p, "amount", 0.5f);
    } else if (name == "directionmix") {
        st.kind = TextureKind::DirectionMix;
        st.dir = ReadDirection(te);
        st.tex[0] = SpectrumChild(ctx, p, "tex1", type, zero);
        st.tex[1] = SpectrumChild(ctx, p, "tex2", type, one);
    } else if (name == "bilerp") {
        // The four corner spectra (pbrt-v4 reads them as spectra, not textures) become constant
        // children.
        st.kind = TextureKind::Bilerp;
        st.mapping = ReadMapping2D(te);
        const char *corners[4] = {"v00", "v01", "v10", "v11"};
        const Spectrum defaults[4] = {zero, one, zero, one};
        for (int i = 0; i < 4; ++i) {
            if (p.TypeOf(corners[i]) == "texture")
                Fail(ParamLoc(p, corners[i], te.loc), std::string("\"") + corners[i] +
                                                          "\" of a bilerp texture is a spectrum value, not a texture");
            std::optional<Spectrum> s = GetSpectrum(ctx, p, corners[i], type);
            st.tex[i] = AddSpectrumNode(ctx, ConstantSpectrumTexture(s ? *s : defaults[i], type));
        }
    } else if (name == "imagemap") {
        st.kind = TextureKind::ImageMap;
        st.mapping = ReadMapping2D(te);
        ImageTexParams ip = ReadImageTexture(ctx, te, false, first);
        st.image = ip.image;
        st.scale = ip.scale;
        st.invert = ip.invert;
        st.pointFilter = ip.point;
    } else if (name == "checkerboard") {
        int dim = p.GetOneInt("dimension", 2);
        if (dim != 2 && dim != 3)
            Fail(ParamLoc(p, "dimension", te.loc), std::to_string(dim) + " dimensional checkerboard texture not supported");
        st.kind = TextureKind::Checkerboard;
        st.tex[0] = SpectrumChild(ctx, p, "tex1", type, one);
        st.tex[1] = SpectrumChild(ctx, p, "tex2", type, zero);
        st.mapping = dim == 2 ? ReadMapping2D(te) : ReadMapping3D(te);
    } else if (name == "dots") {
        // As pbrt-v4 (see the float dots texture): "outside" shows inside the dots.
        st.kind = TextureKind::Dots;
        st.mapping = ReadMapping2D(te);
        uint32_t inside = SpectrumChild(ctx, p, "inside", type, one);
        uint32_t outside = SpectrumChild(ctx, p, "outside", type, zero);
        st.tex[0] = outside;
        st.tex[1] = inside;
    } else if (name == "marble") {
        st.kind = TextureKind::Marble;
        st.unbounded = false;  // pbrt-v4's marble is an RGBAlbedoSpectrum whatever the use
        st.mapping = ReadMapping3D(te);
        st.octaves = ReadOctaves(te);
        st.omega = Float(p.GetOneFloat("roughness", .5f));
        st.scale = Float(p.GetOneFloat("scale", 1));
        st.variation = Float(p.GetOneFloat("variation", .2f));
    } else if (name == "ptex") {
        FailPtex(te);
    } else if (IsFloatOnly(name)) {
        Fail(te.loc, Quoted(name) + " is a float texture in pbrt-v4: there is no spectrum " + Quoted(name) + " texture");
    } else {
        Fail(te.loc, "unknown texture type " + Quoted(name));
    }
    CheckDepth(SpectrumDepth(ctx.scene, st, MaxTextureDepth + 1), te);
    if (first) p.ReportUnused(ctx.diag, Owner(te));
    ctx.texturesBuilding.erase(key);
    ctx.spectrumTextureCache[ckey] = st;
    return st;
}

}  // namespace

uint32_t GetFloatTextureNode(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def) {
    return FloatChild(ctx, params, name, def);
}

// ---- Texture parameters of materials and textures (pbrt-v4's TextureParameterDictionary) ----

std::optional<FloatTexture> GetFloatTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                  const std::string &name) {
    std::string t = params.TypeOf(name);
    if (t.empty()) return std::nullopt;
    if (t == "float") {
        FloatTexture ft;
        ft.kind = TextureKind::Constant;
        ft.value = Float(params.GetOneFloat(name, 0));
        return ft;
    }
    if (t == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        return BuildFloatTexture(ctx, FloatTextureEntity(ctx, p.strings[0], p));
    }
    Fail(ParamLoc(params, name, {}), "parameter " + Quoted(t + " " + name) + " has the wrong type: expected \"float\" or \"texture\"");
}

FloatTexture GetFloatTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def) {
    if (auto t = GetFloatTextureOrNull(ctx, params, name)) return *t;
    FloatTexture ft;
    ft.kind = TextureKind::Constant;
    ft.value = def;
    return ft;
}

SpectrumTexture ConstantSpectrumTexture(const Spectrum &s, SpectrumType type) {
    SpectrumTexture st;
    st.kind = TextureKind::Constant;
    st.value = s;
    st.unbounded = type != SpectrumType::Albedo;
    return st;
}

std::optional<SpectrumTexture> GetSpectrumTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                        const std::string &name, SpectrumType type) {
    std::string t = params.TypeOf(name);
    if (t.empty()) return std::nullopt;
    if (t == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        return BuildSpectrumTexture(ctx, SpectrumTextureEntity(ctx, p.strings[0], p), type);
    }
    std::optional<Spectrum> s = GetSpectrum(ctx, params, name, type);
    if (!s) return std::nullopt;
    return ConstantSpectrumTexture(*s, type);
}

SpectrumTexture GetSpectrumTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name,
                                   SpectrumType type, const Spectrum &def) {
    if (auto t = GetSpectrumTextureOrNull(ctx, params, name, type)) return *t;
    return ConstantSpectrumTexture(def, type);
}

void IndexTextures(BuildContext &ctx) {
    for (const TextureEntity &te : ctx.desc.floatTextures) {
        if (ctx.floatTextures.count(te.textureName)) Fail(te.loc, "redefining texture " + Quoted(te.textureName));
        ctx.floatTextures[te.textureName] = &te;
    }
    for (const TextureEntity &te : ctx.desc.spectrumTextures) {
        if (ctx.spectrumTextures.count(te.textureName)) Fail(te.loc, "redefining texture " + Quoted(te.textureName));
        ctx.spectrumTextures[te.textureName] = &te;
    }
    ctx.scene.stats.floatTextures = int(ctx.desc.floatTextures.size());
    ctx.scene.stats.spectrumTextures = int(ctx.desc.spectrumTextures.size());
    // pbrt-v4 creates every texture, used or not (spectrum textures in each spectrum type), so
    // errors in unused ones surface too.
    for (const TextureEntity &te : ctx.desc.floatTextures) ctx.Collect([&] { BuildFloatTexture(ctx, te); });
    for (const TextureEntity &te : ctx.desc.spectrumTextures)
        ctx.Collect([&] {
            BuildSpectrumTexture(ctx, te, SpectrumType::Albedo);
            BuildSpectrumTexture(ctx, te, SpectrumType::Unbounded);
        });
}

}  // namespace lu::build
