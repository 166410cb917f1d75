// Lucerna scene reader: double-precision 4x4 transformations (pbrt-v4's transform.cpp conventions).
#include "lucerna/scene/transform_math.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace lu {

bool DMatrix::operator==(const DMatrix &o) const { return std::memcmp(m, o.m, sizeof(m)) == 0; }

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

bool FitsFloat(const DMatrix &d) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!(std::abs(d.m[i][j]) <= double(FLT_MAX))) return false;
    return true;
}

Matrix4 ToMatrix4(const DMatrix &d) {
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

namespace {

struct Triple { double x, y, z; };
Triple Sub(Triple a, Triple b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Triple Cross(Triple a, Triple b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double Length(Triple a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
Triple Normalize(Triple a) {
    double l = Length(a);
    return {a.x / l, a.y / l, a.z / l};
}

}  // namespace

const char *LookAtM(const double eye[3], const double look[3], const double up[3], DMatrix *cameraFromWorld) {
    Triple e{eye[0], eye[1], eye[2]}, l{look[0], look[1], look[2]}, u{up[0], up[1], up[2]};
    Triple dir = Sub(l, e);
    if (!(Length(dir) > 0)) return "the eye and look-at points are the same";
    if (!(Length(u) > 0)) return "the up vector is zero";
    dir = Normalize(dir);
    Triple right = Cross(Normalize(u), dir);
    if (!(Length(right) > 1e-12) || !std::isfinite(Length(right)))
        return "the up vector is parallel to the viewing direction";
    right = Normalize(right);
    Triple newUp = Cross(dir, right);
    // worldFromCamera has columns right, up, dir, eye; the result is its inverse.
    DMatrix worldFromCamera;
    const Triple cols[4] = {right, newUp, dir, e};
    for (int c = 0; c < 4; ++c) {
        worldFromCamera.m[0][c] = cols[c].x;
        worldFromCamera.m[1][c] = cols[c].y;
        worldFromCamera.m[2][c] = cols[c].z;
    }
    DMatrix inverse;
    if (!Invert(worldFromCamera, &inverse)) return "degenerate viewing transformation";
    *cameraFromWorld = inverse;
    return nullptr;
}

}  // namespace lu
