// Lucerna build tool: fits the Jakob & Hanika 2019 RGB -> sigmoid-polynomial table for one of
// pbrt-v4's RGB color spaces (srgb, dci-p3, rec2020, aces2065-1; spectra/color_space_data.h)
// (Gauss-Newton in CIELAB with an analytic Jacobian, the setup of pbrt-v4's rgb2spec_opt: 5 nm CIE 1931 data, the space's illuminant, Simpson
// 3/8 quadrature on a 5/3 nm grid, z nodes smoothstep(smoothstep(k / (res - 1)))) and writes it
// as a raw binary: u32 magic 'LUR2', u32 res, u32 0, u32 0, f32 zNodes[res],
// f32 coeffs[3][res][res][res][3] ([max component][z][y][x][c0 c1 c2], polynomial in nm).
// sRGB uses the standard 6-digit matrices and the D65 normalization of rgb2spec_opt (the table the
// renderer has always shipped); the other spaces derive RGB <-> XYZ from their chromaticities and
// the XYZ of their illuminant at 1 nm, as the renderer does (pbrt-v4's RGBColorSpace constructor).
// Usage: lucerna_rgb2spec_gen <res> <output.bin> [color space, default srgb]
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <thread>
#include <vector>

#include "lucerna/spectra/cie_data.h"
#include "lucerna/spectra/color_space_data.h"

namespace {

constexpr double LambdaMin = 360, LambdaMax = 830;
constexpr int CoarseSamples = 95;                          // 5 nm
constexpr int FineSamples = (CoarseSamples - 1) * 3 + 1;   // Simpson 3/8 nodes
// Normalization of the 5 nm D65 table (100 at 560 nm) to unit luminance, as in rgb2spec_opt.
constexpr double D65Norm = 10566.864005283874576;

// sRGB <-> XYZ (D65), the standard 6-digit matrices.
const double XYZToSRGBStd[3][3] = {{3.240479, -1.537150, -0.498535},
                                {-0.969256, 1.875991, 0.041556},
                                {0.055648, -0.204043, 1.057311}};
const double SRGBToXYZStd[3][3] = {{0.412453, 0.357580, 0.180423},
                                {0.212671, 0.715160, 0.072169},
                                {0.019334, 0.119193, 0.950227}};

// The color space being fitted: its matrices and its illuminant (5 nm table, normalization).
struct Gamut {
    double xyzToRGB[3][3], rgbToXYZ[3][3];
    const lu::data::UniformSpectrumData *illum = nullptr;
    double illumNorm = 0;  // 0: normalize to unit luminance with the quadrature below
};

void Invert3(const double m[3][3], double r[3][3]) {
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
        }
}

const lu::data::UniformSpectrumData *FindIlluminant(const char *name) {
    for (const auto &il : lu::data::Illuminants)
        if (std::string_view(il.name) == name) return &il;
    std::fprintf(stderr, "rgb2spec_gen: no illuminant table %s\n", name);
    std::exit(1);
}

// Linear interpolation of a 5 nm illuminant table at a wavelength inside it.
double IllumAt(const lu::data::UniformSpectrumData &il, double lambda) {
    double x = (lambda - il.lambda0) / il.step;
    int i = std::clamp(int(x), 0, il.n - 2);
    double w = x - i;
    return (1 - w) * il.values[i] + w * il.values[i + 1];
}

Gamut MakeGamut(int index) {
    const lu::data::ColorSpaceDefinition &cs = lu::data::ColorSpaces[index];
    Gamut g;
    g.illum = FindIlluminant(cs.illuminant);
    if (index == int(lu::ColorSpaceId::SRGB)) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                g.xyzToRGB[i][j] = XYZToSRGBStd[i][j];
                g.rgbToXYZ[i][j] = SRGBToXYZStd[i][j];
            }
        g.illumNorm = D65Norm;
        return g;
    }
    // White point: XYZ of the illuminant at 1 nm (linear between its 5 nm samples), Y = 1.
    double W[3] = {0, 0, 0};
    for (int i = 0; i < lu::data::CIESamples; ++i) {
        double v = IllumAt(*g.illum, 360.0 + i);
        W[0] += lu::data::CIE_X[i] * v;
        W[1] += lu::data::CIE_Y[i] * v;
        W[2] += lu::data::CIE_Z[i] * v;
    }
    W[0] /= W[1];
    W[2] /= W[1];
    W[1] = 1;
    // Columns: XYZ of the primaries with Y = 1, scaled so that rgb (1, 1, 1) maps to W.
    const double *prim[3] = {cs.r, cs.g, cs.b};
    double P[3][3], Pinv[3][3];
    for (int c = 0; c < 3; ++c) {
        P[0][c] = prim[c][0] / prim[c][1];
        P[1][c] = 1;
        P[2][c] = (1 - prim[c][0] - prim[c][1]) / prim[c][1];
    }
    Invert3(P, Pinv);
    for (int c = 0; c < 3; ++c) {
        double s = Pinv[c][0] * W[0] + Pinv[c][1] * W[1] + Pinv[c][2] * W[2];
        for (int r = 0; r < 3; ++r) g.rgbToXYZ[r][c] = P[r][c] * s;
    }
    Invert3(g.rgbToXYZ, g.xyzToRGB);
    return g;
}

struct Tables {
    double cmf[3][CoarseSamples], illum[CoarseSamples];
    double lambdaNorm[FineSamples];       // (lambda - 360) / 470
    double rgbWeights[3][FineSamples];    // quadrature weight * illuminant * (XYZ->RGB of CMFs)
    double rgbWeightsL[3][FineSamples], rgbWeightsL2[3][FineSamples];  // times l and l^2
    double whitepoint[3];                 // XYZ of the illuminant
    const double (*rgbToXYZ)[3];          // the gamut's matrix
};

double Interp5nm(const double *data, double lambda) {
    double x = (lambda - LambdaMin) * (CoarseSamples - 1) / (LambdaMax - LambdaMin);
    int i = std::clamp(int(x), 0, CoarseSamples - 2);
    double w = x - i;
    return (1 - w) * data[i] + w * data[i + 1];
}

void InitTables(Tables &t, const Gamut &g) {
    t.rgbToXYZ = g.rgbToXYZ;
    double h = (LambdaMax - LambdaMin) / (FineSamples - 1);
    auto simpson = [&](int i) {  // composite Simpson 3/8: weights 1 3 3 2 3 3 2 ... 3 3 1, times 3h/8
        double w = 3.0 / 8.0 * h;
        if (i != 0 && i != FineSamples - 1) w *= (i % 3 == 0) ? 2 : 3;
        return w;
    };
    for (int i = 0; i < CoarseSamples; ++i) {
        double lambda = LambdaMin + 5 * i;
        t.cmf[0][i] = lu::data::CIE_X[5 * i];
        t.cmf[1][i] = lu::data::CIE_Y[5 * i];
        t.cmf[2][i] = lu::data::CIE_Z[5 * i];
        int j = int(std::lround((lambda - g.illum->lambda0) / g.illum->step));
        t.illum[i] = double(g.illum->values[j]);
    }
    double norm = g.illumNorm;
    if (norm == 0) {  // unit luminance with the quadrature used for the fit
        for (int i = 0; i < FineSamples; ++i) {
            double lambda = LambdaMin + i * h;
            norm += Interp5nm(t.cmf[1], lambda) * Interp5nm(t.illum, lambda) * simpson(i);
        }
    }
    for (int i = 0; i < CoarseSamples; ++i) t.illum[i] /= norm;
    for (int c = 0; c < 3; ++c) t.whitepoint[c] = 0;
    for (int i = 0; i < FineSamples; ++i) {
        double lambda = LambdaMin + i * h;
        double xyz[3] = {Interp5nm(t.cmf[0], lambda), Interp5nm(t.cmf[1], lambda), Interp5nm(t.cmf[2], lambda)};
        double I = Interp5nm(t.illum, lambda);
        double w = simpson(i);
        t.lambdaNorm[i] = (lambda - LambdaMin) / (LambdaMax - LambdaMin);
        for (int k = 0; k < 3; ++k) {
            t.rgbWeights[k][i] = 0;
            for (int j = 0; j < 3; ++j) t.rgbWeights[k][i] += g.xyzToRGB[k][j] * xyz[j] * I * w;
        }
        for (int k = 0; k < 3; ++k) {
            t.rgbWeightsL[k][i] = t.rgbWeights[k][i] * t.lambdaNorm[i];
            t.rgbWeightsL2[k][i] = t.rgbWeightsL[k][i] * t.lambdaNorm[i];
        }
        for (int k = 0; k < 3; ++k) t.whitepoint[k] += xyz[k] * I * w;
    }
}

// CIE L*a*b* nonlinearity and its derivative.
constexpr double LabDelta = 6.0 / 29.0;
double LabF(double v) {
    return v > LabDelta * LabDelta * LabDelta ? std::cbrt(v) : v / (LabDelta * LabDelta * 3.0) + 4.0 / 29.0;
}
double LabFDeriv(double v) {
    if (v > LabDelta * LabDelta * LabDelta) {
        double c = std::cbrt(v);
        return 1.0 / (3.0 * c * c);
    }
    return 1.0 / (LabDelta * LabDelta * 3.0);
}

// Linear RGB of the gamut -> CIELAB relative to the illuminant's white point (in place); if dLab is given,
// also the Jacobian dLab/drgb.
void RGBToLab(const Tables &t, double p[3], double dLab[3][3] = nullptr) {
    double xyz[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) xyz[i] += t.rgbToXYZ[i][j] * p[j];
    double f[3], df[3];
    for (int i = 0; i < 3; ++i) {
        f[i] = LabF(xyz[i] / t.whitepoint[i]);
        df[i] = LabFDeriv(xyz[i] / t.whitepoint[i]) / t.whitepoint[i];
    }
    p[0] = 116.0 * f[1] - 16.0;
    p[1] = 500.0 * (f[0] - f[1]);
    p[2] = 200.0 * (f[1] - f[2]);
    if (dLab) {
        const double D[3][3] = {{0, 116, 0}, {500, -500, 0}, {0, 200, -200}};  // dLab / df
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                dLab[i][j] = 0;
                for (int k = 0; k < 3; ++k) dLab[i][j] += D[i][k] * df[k] * t.rgbToXYZ[k][j];
            }
    }
}

// Residual Lab(target) - Lab(reflectance s(c0 l^2 + c1 l + c2) under the illuminant), l in
// [0,1], and its Jacobian J = dres/dc (analytic; the sigmoid s(x) = 1/2 + x / (2 sqrt(1 + x^2))
// has s'(x) = 1 / (2 (1 + x^2)^(3/2))).
void ResidualAndJacobian(const Tables &t, const double c[3], const double targetLab[3], double res[3],
                         double J[3][3]) {
    // Two passes so that both vectorize: the sigmoid and its derivative, then 12 dot products.
    alignas(64) double sv[FineSamples], dsv[FineSamples];
    for (int i = 0; i < FineSamples; ++i) {
        double l = t.lambdaNorm[i];
        double x = (c[0] * l + c[1]) * l + c[2];
        double q = 1.0 / std::sqrt(1.0 + x * x);
        sv[i] = 0.5 * x * q + 0.5;
        dsv[i] = 0.5 * q * q * q;
    }
    double out[3], dout[3][3];
    for (int k = 0; k < 3; ++k) {
        double o = 0, d0 = 0, d1 = 0, d2 = 0;
        for (int i = 0; i < FineSamples; ++i) {
            o += t.rgbWeights[k][i] * sv[i];
            d0 += t.rgbWeightsL2[k][i] * dsv[i];
            d1 += t.rgbWeightsL[k][i] * dsv[i];
            d2 += t.rgbWeights[k][i] * dsv[i];
        }
        out[k] = o;
        dout[k][0] = d0;
        dout[k][1] = d1;
        dout[k][2] = d2;
    }
    double dLab[3][3];
    RGBToLab(t, out, dLab);
    for (int j = 0; j < 3; ++j) {
        res[j] = targetLab[j] - out[j];
        for (int m = 0; m < 3; ++m) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d += dLab[j][k] * dout[k][m];
            J[j][m] = -d;
        }
    }
}

// Solves A x = b for 3x3 A by Gaussian elimination with partial pivoting; false if singular.
bool Solve3(double A[3][3], double b[3], double x[3]) {
    int perm[3] = {0, 1, 2};
    for (int col = 0; col < 3; ++col) {
        int piv = col;
        for (int r = col + 1; r < 3; ++r)
            if (std::abs(A[perm[r]][col]) > std::abs(A[perm[piv]][col])) piv = r;
        std::swap(perm[col], perm[piv]);
        double p = A[perm[col]][col];
        if (std::abs(p) < 1e-15) return false;
        for (int r = col + 1; r < 3; ++r) {
            double f = A[perm[r]][col] / p;
            A[perm[r]][col] = f;
            for (int k = col + 1; k < 3; ++k) A[perm[r]][k] -= f * A[perm[col]][k];
        }
    }
    double y[3];
    for (int i = 0; i < 3; ++i) {
        y[i] = b[perm[i]];
        for (int k = 0; k < i; ++k) y[i] -= A[perm[i]][k] * y[k];
    }
    for (int i = 2; i >= 0; --i) {
        for (int k = i + 1; k < 3; ++k) y[i] -= A[perm[i]][k] * x[k];
        x[i] = y[i] / A[perm[i]][i];
    }
    return true;
}

// Gauss-Newton iterations on the CIELAB residual (at most 15), warm-started from c.
void GaussNewton(const Tables &t, const double rgb[3], double c[3]) {
    double targetLab[3] = {rgb[0], rgb[1], rgb[2]};
    RGBToLab(t, targetLab);
    for (int it = 0; it < 15; ++it) {
        double res[3], J[3][3];
        ResidualAndJacobian(t, c, targetLab, res, J);
        double dx[3];
        if (!Solve3(J, res, dx)) {
            std::fprintf(stderr, "rgb2spec_gen: singular Jacobian at rgb (%g %g %g)\n", rgb[0], rgb[1], rgb[2]);
            std::exit(1);
        }
        double r2 = 0;
        for (int j = 0; j < 3; ++j) {
            c[j] -= dx[j];
            r2 += res[j] * res[j];
        }
        double m = std::max({c[0], c[1], c[2]});
        if (m > 200)
            for (int j = 0; j < 3; ++j) c[j] *= 200 / m;
        if (r2 < 1e-6) break;
    }
}

float SmoothStep(float x) { return x * x * (3.0f - 2.0f * x); }

}  // namespace

int main(int argc, char **argv) {
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: %s <resolution> <output.bin> [srgb|dci-p3|rec2020|aces2065-1]\n", argv[0]);
        return 1;
    }
    int gamut = argc == 4 ? lu::data::ColorSpaceIndex(argv[3]) : int(lu::ColorSpaceId::SRGB);
    if (gamut < 0) { std::fprintf(stderr, "rgb2spec_gen: unknown color space %s\n", argv[3]); return 1; }
    const int res = std::atoi(argv[1]);
    if (res < 2) { std::fprintf(stderr, "rgb2spec_gen: bad resolution\n"); return 1; }
    const Gamut g = MakeGamut(gamut);  // outlives t (t points at its matrix)
    Tables t;
    InitTables(t, g);

    std::vector<float> zNodes(res);
    for (int k = 0; k < res; ++k) zNodes[k] = float(SmoothStep(SmoothStep(float(k / double(res - 1)))));
    std::vector<float> coeffs(size_t(3) * res * res * res * 3);

    // Each (max component l, y index j) row is independent: sweep x, and for each x walk z up
    // from res/5 and then down, warm-starting every fit from the previous brightness.
    std::atomic<int> next{0};
    auto worker = [&]() {
        for (int row; (row = next.fetch_add(1)) < 3 * res;) {
            int l = row / res, j = row % res;
            double y = j / double(res - 1);
            for (int i = 0; i < res; ++i) {
                double x = i / double(res - 1);
                int start = res / 5;
                auto fit = [&](int k, double c[3]) {
                    double b = zNodes[k], rgb[3];
                    rgb[l] = b;
                    rgb[(l + 1) % 3] = x * b;
                    rgb[(l + 2) % 3] = y * b;
                    GaussNewton(t, rgb, c);
                    // Rescale the polynomial from normalized wavelength to nanometers.
                    const double c0 = LambdaMin, c1 = 1.0 / (LambdaMax - LambdaMin);
                    double A = c[0], B = c[1], C = c[2];
                    size_t idx = ((size_t(l) * res + k) * res + j) * res + i;
                    coeffs[3 * idx + 0] = float(A * c1 * c1);
                    coeffs[3 * idx + 1] = float(B * c1 - 2 * A * c0 * c1 * c1);
                    coeffs[3 * idx + 2] = float(C - B * c0 * c1 + A * c0 * c0 * c1 * c1);
                };
                double c[3] = {0, 0, 0};
                for (int k = start; k < res; ++k) fit(k, c);
                c[0] = c[1] = c[2] = 0;
                for (int k = start; k >= 0; --k) fit(k, c);
            }
        }
    };
    unsigned nThreads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> threads;
    for (unsigned i = 1; i < nThreads; ++i) threads.emplace_back(worker);
    worker();
    for (auto &th : threads) th.join();

    std::FILE *f = std::fopen(argv[2], "wb");
    if (!f) { std::perror(argv[2]); return 1; }
    uint32_t header[4] = {0x3252554Cu /* "LUR2" */, uint32_t(res), 0, 0};
    bool ok = std::fwrite(header, sizeof(header), 1, f) == 1 &&
              std::fwrite(zNodes.data(), sizeof(float), zNodes.size(), f) == zNodes.size() &&
              std::fwrite(coeffs.data(), sizeof(float), coeffs.size(), f) == coeffs.size();
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) { std::fprintf(stderr, "rgb2spec_gen: write failed\n"); return 1; }
    return 0;
}
