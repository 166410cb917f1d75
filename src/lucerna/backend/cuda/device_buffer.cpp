// Lucerna CUDA backend: device memory and the device query (CUDA runtime API).
#include "lucerna/backend/cuda/device_buffer.h"

#include <cuda_runtime.h>

#include "lucerna/backend/cuda/cuda_api.h"

namespace lu {

namespace {
void Check(cudaError_t err, const char *what) {
    if (err != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(err));
}
}  // namespace

void *CudaMalloc(size_t bytes) {
    void *p = nullptr;
    Check(cudaMalloc(&p, bytes), "cudaMalloc");
    return p;
}

void CudaFree(void *ptr) noexcept { cudaFree(ptr); }

void CudaCopyToDevice(void *dst, const void *src, size_t bytes) {
    Check(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice), "cudaMemcpy (host to device)");
}

void CudaCopyToHost(void *dst, const void *src, size_t bytes) {
    Check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost), "cudaMemcpy (device to host)");
}

bool CudaDeviceAvailable(std::string *name) {
    int count = 0;
    cudaError_t err = cudaGetDeviceCount(&count);
    if (err != cudaSuccess || count == 0) {
        if (name) *name = err != cudaSuccess ? std::string("no CUDA device: ") + cudaGetErrorString(err)
                                             : std::string("no CUDA device");
        cudaGetLastError();   // clear the sticky error state of the failed query
        return false;
    }
    cudaDeviceProp prop;
    err = cudaGetDeviceProperties(&prop, 0);
    if (err != cudaSuccess) {
        if (name) *name = std::string("cudaGetDeviceProperties: ") + cudaGetErrorString(err);
        return false;
    }
    std::string desc = std::string(prop.name) + " (sm_" + std::to_string(prop.major) + std::to_string(prop.minor) + ")";
    if (prop.major < 8) {   // lucerna_cuda is built for sm_80 and newer
        if (name) *name = desc + " is older than sm_80";
        return false;
    }
    if (name) *name = desc;
    return true;
}

}  // namespace lu
