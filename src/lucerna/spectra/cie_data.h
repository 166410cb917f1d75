// Lucerna: raw tabulated spectral data (CIE observer, standard illuminants, measured metals,
// glass indices) compiled into lucerna_spectra; the registry turns them into 1 nm tables.
#pragma once

namespace lu::data {

constexpr int CIESamples = 471;  // 360..830 nm at 1 nm
extern const float CIE_X[CIESamples], CIE_Y[CIESamples], CIE_Z[CIESamples];

// A spectrum sampled uniformly: values[i] at lambda0 + i * step (nm).
struct UniformSpectrumData {
    const char *name;
    float lambda0, step;
    int n;
    const float *values;
};
constexpr int NumIlluminants = 16;
extern const UniformSpectrumData Illuminants[NumIlluminants];  // stdillum-*, illum-acesD60

// A spectrum given as (lambda, value) pairs, interleaved: l0 v0 l1 v1 ...
struct InterleavedSpectrumData {
    const char *name;
    int n;  // number of pairs
    const float *lv;
};
extern const InterleavedSpectrumData MeasuredSpectra[];  // metal-*-eta / -k, glass-*
extern const int NumMeasuredSpectra;

}  // namespace lu::data
