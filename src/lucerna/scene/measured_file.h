// Lucerna scene builder: RGL's tensor file format (the .bsdf files of Dupuy & Jakob 2018, read by
// pbrt-v4's util/tensor and MeasuredBRDF::Create) and the PiecewiseLinear2D tables built from it
// into SceneView::measuredData (host only).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "lucerna/core/scene_data.h"

namespace lu {

// A tensor file: "tensor_file\0", version 1.0 (two bytes), uint32 field count, then per field
// uint16 name length, the name, uint16 ndim, uint8 dtype, uint64 data offset, ndim uint64
// extents; each field's data (little endian, C order) at its offset.
enum class TensorType : uint8_t { Invalid, UInt8, Int8, UInt16, Int16, UInt32, Int32, UInt64, Int64, Float16, Float32, Float64 };

struct TensorField {
    TensorType dtype = TensorType::Invalid;
    std::vector<uint64_t> shape;
    std::vector<uint8_t> bytes;   // the field's data, prod(shape) elements
};

struct TensorFile {
    std::map<std::string, TensorField> fields;
};

// A malformed or truncated file: the message names the file (quoted) and what is wrong.
struct MeasuredFileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Reads and bounds-checks the whole file; throws MeasuredFileError.
TensorFile ReadTensorFile(const std::string &path);
// Parses a tensor file held in memory (path only names it in messages); throws MeasuredFileError.
TensorFile ParseTensorFile(const std::vector<uint8_t> &bytes, const std::string &path);

// pbrt-v4's MeasuredBRDF::Create: checks the fields (description, jacobian, theta_i, phi_i, ndf,
// sigma, vndf, luminance, spectra, wavelengths: names, types and shapes; other fields such as
// "rgb" are ignored) and appends the tables to data. Throws MeasuredFileError.
MeasuredBRDFData BuildMeasuredBRDF(const TensorFile &file, const std::string &path, std::vector<Float> &data);

// pbrt-v4's PiecewiseLinear2D constructor: appends a table of nx x ny vertices per slice (the
// slices of the parameter grid paramSize[0] x ... outermost first, values in paramValues) to
// data. normalize: each slice scaled to integrate to 1 over [0,1]^2, with cdfs for sampling;
// otherwise PLEvaluate returns the input values.
PiecewiseLinear2DTable AddPiecewiseLinear2D(std::vector<Float> &data, const float *values, uint32_t nx, uint32_t ny,
                                            uint32_t nParams, const uint32_t *paramSize,
                                            const float *const *paramValues, bool normalize);

}  // namespace lu
