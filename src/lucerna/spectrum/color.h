// Lucerna: sampled spectrum -> sensor XYZ -> linear sRGB, shared by host and device. Follows
// pbrt-v4's RGBFilm with the default "cie1931" PixelSensor (no white balance): ToSensorRGB is
// imagingRatio * mean_i(xbar(l_i) L_i / pdf_i), with xbar/ybar/zbar DenselySampledSpectrum
// lookups (nearest nm), and the sensor's XYZ goes through the sRGB RGBFromXYZ matrix. There is no
// 1/CIE_Y_integral: lights carry it in their 1/SpectrumToPhotometric scale.
#pragma once

#include "lucerna/spectrum/spectrum.h"

namespace lu {

// Index of the nearest integer wavelength, lround(lambda) - 360, in a 471-entry table; -1 outside
// [360, 830]. For lambda >= 1, trunc(lambda + 0.5f) is exact and equals lround.
LU_INLINE int DenseNearestOffset(Float lambda) {
    if (!(lambda >= LambdaMin - 0.5f && lambda < LambdaMax + 0.5f)) return -1;
    return int(lambda + 0.5f) - int(LambdaMin);
}

// pbrt-v4 DenselySampledSpectrum lookup: value at the nearest integer wavelength, 0 outside
// [360, 830]. t: one 471-entry table.
LU_INLINE Float LookupDenseNearest(const Float *t, Float lambda) {
    int offset = DenseNearestOffset(lambda);
    return offset < 0 ? 0 : t[offset];
}

// Sensor XYZ of one radiance sample (pbrt-v4 PixelSensor::ToSensorRGB, cie1931). Tables 0..2 of
// tab must be CIE X, Y, Z (SpectrumRegistry reserves them). Wavelengths with pdf 0 (terminated
// secondaries) contribute 0 but still count in the mean, as pbrt-v4's SafeDiv + Average.
LU_INLINE void SensorXYZ(const SampledSpectrum &L, const SampledWavelengths &lambda, const SpectrumTables &tab,
                         Float imagingRatio, Float xyz[3]) {
    Float sum[3] = {0, 0, 0};
    for (int i = 0; i < NSpectrumSamples; ++i) {
        Float v = lambda.pdf[i] != 0 ? L[i] / lambda.pdf[i] : 0;
        // LookupDenseNearest's offset, once for the three tables.
        int offset = DenseNearestOffset(lambda.lambda[i]);
        bool inside = offset >= 0;
        for (int c = 0; c < 3; ++c)
            sum[c] += (inside ? tab.data[size_t(c) * TabulatedSpectrumSize + offset] : Float(0)) * v;
    }
    for (int c = 0; c < 3; ++c) xyz[c] = imagingRatio * (sum[c] / NSpectrumSamples);
}

// XYZ <-> linear sRGB, pbrt-v4's RGBColorSpace::sRGB matrices: built from the sRGB primaries
// and the white point of its 1 nm D65 table (xy 0.312727, 0.329023; not the rounded 0.3127, 0.3290). The spectrum
// tests check these literals against the matrices SpectrumRegistry computes.
LU_INLINE void XYZToLinearSRGB(const Float xyz[3], Float rgb[3]) {
    const Float m[3][3] = {{3.24044967f, -1.53713632f, -0.498530686f},
                           {-0.969266236f, 1.87601113f, 0.0415560268f},
                           {0.055643566f, -0.204026401f, 1.05722773f}};
    for (int r = 0; r < 3; ++r) rgb[r] = m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2];
}
LU_INLINE void LinearSRGBToXYZ(const Float rgb[3], Float xyz[3]) {
    const Float m[3][3] = {{0.412457019f, 0.357576013f, 0.180437058f},
                           {0.212673157f, 0.715152025f, 0.0721748173f},
                           {0.0193339232f, 0.119192004f, 0.950301826f}};
    for (int r = 0; r < 3; ++r) xyz[r] = m[r][0] * rgb[0] + m[r][1] * rgb[1] + m[r][2] * rgb[2];
}

// Sensor response of one sample straight to linear sRGB (pbrt-v4 RGBFilm::ToOutputRGB).
LU_INLINE void SensorLinearSRGB(const SampledSpectrum &L, const SampledWavelengths &lambda, const SpectrumTables &tab,
                                Float imagingRatio, Float rgb[3]) {
    Float xyz[3];
    SensorXYZ(L, lambda, tab, imagingRatio, xyz);
    XYZToLinearSRGB(xyz, rgb);
}

}  // namespace lu
