// Lucerna CUDA backend: an owning buffer of device memory (cudaMalloc, never managed memory).
// A plain header: the CUDA runtime calls live in device_buffer.cpp, so host code compiled
// without nvcc can hold and fill buffers.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "lucerna/core/scene_data.h"

namespace lu {

// Thrown on any CUDA runtime failure (message: the call and cudaGetErrorString).
struct CudaError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void *CudaMalloc(size_t bytes);
void CudaFree(void *ptr) noexcept;
void CudaCopyToDevice(void *dst, const void *src, size_t bytes);
void CudaCopyToHost(void *dst, const void *src, size_t bytes);

template <typename T>
class DeviceBuffer {
  public:
    DeviceBuffer() = default;
    explicit DeviceBuffer(size_t count) { Allocate(count); }
    DeviceBuffer(const T *host, size_t count) { Upload(host, count); }
    explicit DeviceBuffer(const std::vector<T> &host) { Upload(host.data(), host.size()); }
    ~DeviceBuffer() { Free(); }
    DeviceBuffer(const DeviceBuffer &) = delete;
    DeviceBuffer &operator=(const DeviceBuffer &) = delete;
    DeviceBuffer(DeviceBuffer &&o) noexcept : ptr_(o.ptr_), count_(o.count_) { o.ptr_ = nullptr; o.count_ = 0; }
    DeviceBuffer &operator=(DeviceBuffer &&o) noexcept {
        if (this != &o) {
            Free();
            ptr_ = o.ptr_; count_ = o.count_;
            o.ptr_ = nullptr; o.count_ = 0;
        }
        return *this;
    }

    void Allocate(size_t count) {
        Free();
        if (count) ptr_ = static_cast<T *>(CudaMalloc(count * sizeof(T)));
        count_ = count;
    }
    void Upload(const T *host, size_t count) {
        Allocate(count);
        if (count) CudaCopyToDevice(ptr_, host, count * sizeof(T));
    }
    void Download(T *host, size_t count) const {
        if (count > count_) throw CudaError("DeviceBuffer::Download: more elements than the buffer holds");
        if (count) CudaCopyToHost(host, ptr_, count * sizeof(T));
    }
    std::vector<T> Download() const {
        std::vector<T> v(count_);
        Download(v.data(), count_);
        return v;
    }
    void Free() noexcept {
        if (ptr_) CudaFree(ptr_);
        ptr_ = nullptr;
        count_ = 0;
    }

    T *Data() const { return ptr_; }
    size_t Size() const { return count_; }
    size_t Bytes() const { return count_ * sizeof(T); }
    Span<T> View() const { return Span<T>{ptr_, uint32_t(count_)}; }

  private:
    T *ptr_ = nullptr;
    size_t count_ = 0;
};

}  // namespace lu
