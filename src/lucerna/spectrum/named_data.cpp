// Lucerna: measured spectral data for pbrt-v4's named spectra (metal-*-eta/-k, glass-*).
#include "lucerna/spectrum/cie_data.h"

namespace lu::data {

const InterleavedSpectrumData MeasuredSpectra[] = {{nullptr, 0, nullptr}};
const int NumMeasuredSpectra = 0;

}  // namespace lu::data
