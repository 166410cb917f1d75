// Lucerna CUDA backend: host-side entry points that plain C++ (compiled without nvcc) may call.
// Everything here is defined in lucerna_cuda, which exists only when LUCERNA_HAVE_CUDA is set.
#pragma once

#include <string>

namespace lu {

// True if the CUDA runtime finds at least one usable device; *name (optional) gets the name of
// device 0 with its compute capability, or the reason none is available.
bool CudaDeviceAvailable(std::string *name = nullptr);

}  // namespace lu
