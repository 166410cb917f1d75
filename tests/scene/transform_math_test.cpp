// Tests of the reader's double-precision transformations: inversion (hand-computed inverse,
// pivoting, singular and non-finite input), Rotate about coordinate and diagonal axes, LookAt
// against hand-computed matrices and its degenerate cases, composition order.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lucerna/scene/transform_math.h"

namespace lu {

static DMatrix Make(const double (&e)[4][4]) {
    DMatrix m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = e[i][j];
    return m;
}

static void ExpectNear(const DMatrix &m, const double (&e)[4][4], double tol = 1e-14) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(m.m[i][j], e[i][j], tol) << "entry " << i << "," << j;
}

static const double Id[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

// M applied to the point (x, y, z, 1).
static void Apply(const DMatrix &m, const double p[3], double out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = m.m[i][0] * p[0] + m.m[i][1] * p[1] + m.m[i][2] * p[2] + m.m[i][3];
}

TEST(TransformMath, InverseOfScaleTranslateIsHandComputed) {
    // x' = 2x + 1, y' = 4y + 2, z' = 8z + 3  =>  x = (x' - 1) / 2, ...
    DMatrix a = Make({{2, 0, 0, 1}, {0, 4, 0, 2}, {0, 0, 8, 3}, {0, 0, 0, 1}});
    DMatrix inv;
    ASSERT_TRUE(Invert(a, &inv));
    ExpectNear(inv, {{0.5, 0, 0, -0.5}, {0, 0.25, 0, -0.5}, {0, 0, 0.125, -0.375}, {0, 0, 0, 1}}, 0);
}

TEST(TransformMath, InverseNeedsPivotingAndIsTwoSided) {
    // A zero on the diagonal (a permutation plus shear): Gauss-Jordan without pivoting fails here.
    DMatrix a = Make({{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}});
    DMatrix inv;
    ASSERT_TRUE(Invert(a, &inv));
    ExpectNear(inv, {{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}, 0);
    // A general (projective) matrix: M * M^-1 = M^-1 * M = I.
    DMatrix g = Make({{3, -1, 2, 5}, {0.5, 4, -2, 1}, {1, 1, 7, -3}, {0.1, 0.2, 0.3, 2}});
    ASSERT_TRUE(Invert(g, &inv));
    ExpectNear(Mul(g, inv), Id, 1e-13);
    ExpectNear(Mul(inv, g), Id, 1e-13);
}

TEST(TransformMath, SingularAndNonFiniteMatricesAreNotInverted) {
    DMatrix inv;
    EXPECT_FALSE(Invert(ScaleM(1, 0, 1), &inv));
    EXPECT_FALSE(Invert(Make({{1, 2, 3, 0}, {2, 4, 6, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}), &inv));  // rank 3
    EXPECT_FALSE(Invert(Make({{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}), &inv));
    DMatrix n = TranslateM(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    EXPECT_FALSE(Invert(n, &inv));
    // A pivot below 1e-300 counts as singular.
    EXPECT_FALSE(Invert(ScaleM(1e-300, 1e-300, 1e-300), &inv));
}

TEST(TransformMath, RotateAboutCoordinateAxes) {
    // 90 degrees about +z takes +x to +y and +y to -x (counterclockwise seen from +z).
    DMatrix r = RotateM(90, 0, 0, 1);
    const double x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    double p[3];
    Apply(r, x, p);
    EXPECT_NEAR(p[0], 0, 1e-15);
    EXPECT_NEAR(p[1], 1, 1e-15);
    EXPECT_NEAR(p[2], 0, 1e-15);
    Apply(r, y, p);
    EXPECT_NEAR(p[0], -1, 1e-15);
    EXPECT_NEAR(p[1], 0, 1e-15);
    // 90 degrees about +x takes +y to +z.
    Apply(RotateM(90, 1, 0, 0), y, p);
    EXPECT_NEAR(p[1], 0, 1e-15);
    EXPECT_NEAR(p[2], 1, 1e-15);
}

TEST(TransformMath, RotateAboutTheDiagonalPermutesTheAxes) {
    // 120 degrees about (1,1,1)/sqrt(3) cycles x -> y -> z -> x: the matrix is a permutation.
    double s = 1 / std::sqrt(3.0);
    DMatrix r = RotateM(120, s, s, s);
    ExpectNear(r, {{0, 0, 1, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 1}}, 1e-15);
    // The axis is fixed, and the rotation is orthonormal: R^-1 = R^T = rotation by -120.
    const double axis[3] = {2, 2, 2};
    double p[3];
    Apply(r, axis, p);
    for (double c : p) EXPECT_NEAR(c, 2, 1e-14);
    DMatrix back = RotateM(-120, s, s, s);
    ExpectNear(Mul(back, r), Id, 1e-15);
}

TEST(TransformMath, LookAtIsHandComputed) {
    // Eye (1,2,3) looking along +x with up +z: dir = +x, right = cross(up, dir) = +y, up' = +z.
    // cameraFromWorld has rows right, up', dir and maps the eye to the origin.
    const double eye[3] = {1, 2, 3}, look[3] = {2, 2, 3}, up[3] = {0, 0, 1};
    DMatrix c;
    ASSERT_EQ(LookAtM(eye, look, up, &c), nullptr);
    ExpectNear(c, {{0, 1, 0, -2}, {0, 0, 1, -3}, {1, 0, 0, -1}, {0, 0, 0, 1}});
    // From the origin along +z with up +y: the identity.
    const double o[3] = {0, 0, 0}, z[3] = {0, 0, 5}, y[3] = {0, 3, 0};
    ASSERT_EQ(LookAtM(o, z, y, &c), nullptr);
    ExpectNear(c, Id);
    // A non-orthogonal up is projected: eye (0,0,-5) looking at the origin, up (0,1,1).
    const double e2[3] = {0, 0, -5}, up2[3] = {0, 1, 1};
    ASSERT_EQ(LookAtM(e2, o, up2, &c), nullptr);
    ExpectNear(c, {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 5}, {0, 0, 0, 1}});
}

TEST(TransformMath, DegenerateLookAtIsRefusedAndLeavesTheOutputAlone) {
    const double eye[3] = {0, 0, 0}, look[3] = {0, 0, 1}, up[3] = {0, 1, 0};
    const double zero[3] = {0, 0, 0}, alongDir[3] = {0, 0, 2};
    DMatrix c = ScaleM(7, 7, 7);
    EXPECT_STREQ(LookAtM(eye, eye, up, &c), "the eye and look-at points are the same");
    EXPECT_STREQ(LookAtM(eye, look, zero, &c), "the up vector is zero");
    EXPECT_STREQ(LookAtM(eye, look, alongDir, &c), "the up vector is parallel to the viewing direction");
    EXPECT_TRUE(c == ScaleM(7, 7, 7));
}

TEST(TransformMath, MulAppliesTheRightOperandFirst) {
    // Translate * Scale: scale, then translate.
    DMatrix m = Mul(TranslateM(1, 2, 3), ScaleM(2, 2, 2));
    const double p[3] = {1, 1, 1};
    double q[3];
    Apply(m, p, q);
    EXPECT_EQ(q[0], 3);
    EXPECT_EQ(q[1], 4);
    EXPECT_EQ(q[2], 5);
}

TEST(TransformMath, FloatConversionIsChecked) {
    EXPECT_TRUE(FitsFloat(ScaleM(3e38, 1, 1)));
    EXPECT_FALSE(FitsFloat(ScaleM(4e38, 1, 1)));
    EXPECT_FALSE(FitsFloat(TranslateM(std::numeric_limits<double>::infinity(), 0, 0)));
    Matrix4 f = ToMatrix4(ScaleM(4e38, 0.5, 1));
    EXPECT_TRUE(std::isnan(f.m[0][0]));
    EXPECT_EQ(f.m[1][1], 0.5f);
}

}  // namespace lu
