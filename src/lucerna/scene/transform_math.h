// Lucerna scene reader: 4x4 transformations in double precision for the graphics state (host only).
// The reader composes the CTM in double and rounds to Float once per entity; conventions are
// pbrt-v4's transform.cpp (row-major m[row][col], column vectors, Rotate and LookAt as there).
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

struct DMatrix {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};  // identity
    bool operator==(const DMatrix &o) const;  // bitwise, entry by entry
};

// a * b (b applies first to a column vector).
DMatrix Mul(const DMatrix &a, const DMatrix &b);
// Gauss-Jordan inversion with partial pivoting; false (and *out unspecified) if a is singular or
// any entry of a or of the inverse is not finite.
bool Invert(const DMatrix &a, DMatrix *out);
// True if every entry is finite and within Float range.
bool FitsFloat(const DMatrix &d);
// Rounds to Float; entries out of Float range become NaN (callers check FitsFloat first).
Matrix4 ToMatrix4(const DMatrix &d);

DMatrix TranslateM(double x, double y, double z);
DMatrix ScaleM(double x, double y, double z);
// Rotation by thetaDeg degrees about the axis (ax, ay, az), which must be normalized; the sense
// is pbrt-v4's Rotate (counterclockwise looking down the axis toward the origin).
DMatrix RotateM(double thetaDeg, double ax, double ay, double az);
// pbrt-v4's LookAt: *cameraFromWorld maps eye to the origin and the viewing direction to +z, with
// camera +x = normalize(cross(up, dir)) (a left-handed camera space) and +y the projected up.
// Returns nullptr on success, else why the arguments are degenerate (*cameraFromWorld untouched).
const char *LookAtM(const double eye[3], const double look[3], const double up[3], DMatrix *cameraFromWorld);

}  // namespace lu
