// Lucerna: host construction of the cameras' raster-to-camera transforms, as pbrt-v4's
// ProjectiveCamera / PerspectiveCamera (Perspective(fov, 1e-2, 1000)) / OrthographicCamera
// (Orthographic(0, 1)) constructors, and the spherical camera.
#include "lucerna/scene/camera_build.h"

namespace lu {

static Matrix4 ScaleMatrix(double x, double y, double z) {
    Matrix4 m;
    m.m[0][0] = Float(x);
    m.m[1][1] = Float(y);
    m.m[2][2] = Float(z);
    return m;
}

static Matrix4 TranslateMatrix(double x, double y, double z) {
    Matrix4 m;
    m.m[0][3] = Float(x);
    m.m[1][3] = Float(y);
    m.m[2][3] = Float(z);
    return m;
}

namespace {

// pbrt-v4's default screen window ([-a, a] x [-1, 1] for aspect a > 1, else [-1, 1] x [-1/a, 1/a])
// or the given one, and rasterFromScreen for it.
Matrix4 RasterFromScreen(int width, int height, const Float *screenWindow, Float frameAspectRatio) {
    Float frame = frameAspectRatio > 0 ? frameAspectRatio : Float(width) / Float(height);
    Float sx0, sx1, sy0, sy1;
    if (frame > 1) { sx0 = -frame; sx1 = frame; sy0 = -1; sy1 = 1; }
    else { sx0 = -1; sx1 = 1; sy0 = -1 / frame; sy1 = 1 / frame; }
    if (screenWindow) { sx0 = screenWindow[0]; sx1 = screenWindow[1]; sy0 = screenWindow[2]; sy1 = screenWindow[3]; }
    // rasterFromScreen = Scale(w, -h, 1) * Scale(1/(x1-x0), 1/(y1-y0), 1) * Translate(-x0, -y1, 0).
    return Mul(Mul(ScaleMatrix(width, -height, 1), ScaleMatrix(1.0 / (double(sx1) - sx0), 1.0 / (double(sy1) - sy0), 1)),
               TranslateMatrix(-sx0, -sy1, 0));
}

CameraData ProjectiveCamera(CameraKind kind, const Transform &renderFromCamera, int width, int height,
                            const Matrix4 &screenFromCamera, Float lensRadius, Float focalDistance,
                            const Float *screenWindow, Float frameAspectRatio) {
    CameraData c;
    c.kind = kind;
    c.renderFromCamera = renderFromCamera;
    c.width = width;
    c.height = height;
    c.lensRadius = lensRadius;
    c.focalDistance = focalDistance;
    Matrix4 rasterFromScreen = RasterFromScreen(width, height, screenWindow, frameAspectRatio);
    Matrix4 screenFromRaster, cameraFromScreen;
    Inverse(rasterFromScreen, &screenFromRaster);
    Inverse(screenFromCamera, &cameraFromScreen);
    Matrix4 cameraFromRaster = Mul(cameraFromScreen, screenFromRaster);
    Matrix4 rasterFromCamera = Mul(rasterFromScreen, screenFromCamera);
    c.cameraFromRaster = Transform(cameraFromRaster, rasterFromCamera);
    return c;
}

}  // namespace

CameraData MakePerspectiveCamera(const Transform &renderFromCamera, int width, int height, Float fovDeg,
                                 Float lensRadius, Float focalDistance, const Float *screenWindow,
                                 Float frameAspectRatio) {
    // screenFromCamera = Scale(1/tan(fov/2), 1/tan(fov/2), 1) * Perspective(near, far).
    const double n = 1e-2, f = 1000;
    Matrix4 persp;
    persp.m[2][2] = Float(f / (f - n));
    persp.m[2][3] = Float(-f * n / (f - n));
    persp.m[3][2] = 1;
    persp.m[3][3] = 0;
    double invTan = 1 / std::tan(double(Radians(fovDeg)) / 2);
    Matrix4 screenFromCamera = Mul(ScaleMatrix(invTan, invTan, 1), persp);
    return ProjectiveCamera(CameraKind::Perspective, renderFromCamera, width, height, screenFromCamera, lensRadius,
                            focalDistance, screenWindow, frameAspectRatio);
}

CameraData MakeOrthographicCamera(const Transform &renderFromCamera, int width, int height, Float lensRadius,
                                  Float focalDistance, const Float *screenWindow, Float frameAspectRatio) {
    return ProjectiveCamera(CameraKind::Orthographic, renderFromCamera, width, height, Matrix4(), lensRadius,
                            focalDistance, screenWindow, frameAspectRatio);
}

CameraData MakeSphericalCamera(const Transform &renderFromCamera, int width, int height, CameraKind kind) {
    CameraData c;
    c.kind = kind;
    c.renderFromCamera = renderFromCamera;
    c.width = width;
    c.height = height;
    return c;
}


void SetPixelFootprint(CameraData &c) {
    c.pixelWidth = 0;
    c.pixelSpread = 1 / Float(Max(1, Max(c.width, c.height)));   // if no ray gets through: a radian per image
    Vec2f centre(Float(c.width) / 2, Float(c.height) / 2);
    const Vec2f lens[] = {Vec2f(0.5f, 0.5f), Vec2f(0.3f, 0.5f), Vec2f(0.5f, 0.3f), Vec2f(0.7f, 0.6f)};
    for (Vec2f uLens : lens) {
        Ray r0, rx, ry;
        if (!GenerateRay(c, centre, uLens, &r0) || !GenerateRay(c, centre + Vec2f(1, 0), uLens, &rx) ||
            !GenerateRay(c, centre + Vec2f(0, 1), uLens, &ry))
            continue;
        Vec3f d0 = Normalize(r0.d);
        auto angle = [&](const Ray &r) { return 2 * std::asin(Min(Float(1), Length(Normalize(r.d) - d0) / 2)); };
        auto offset = [&](const Ray &r) {   // the origins' offset across the central ray
            Vec3f o = r.o - r0.o;
            return Length(o - d0 * Dot(o, d0));
        };
        c.pixelSpread = Max(angle(rx), angle(ry));
        c.pixelWidth = Max(offset(rx), offset(ry));
        if (c.lensRadius > 0) c.pixelWidth = 0;   // the thin lens's origins move with the lens sample, not the pixel
        return;
    }
}
}  // namespace lu
