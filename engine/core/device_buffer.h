#pragma once
// A typed cudaMalloc'd array that frees itself; moves, never copies.
#include <span>
#include <utility>

#include "engine/core/cuda_check.h"

namespace rtrt {

template <typename T>
class DeviceBuffer {
  public:
    DeviceBuffer() = default;
    explicit DeviceBuffer(std::span<const T> host) { Upload(host); }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&& o) noexcept
        : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
    DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        return *this;
    }
    ~DeviceBuffer() {
        if (data_) cudaFree(data_);
    }

    void Resize(size_t count) {
        if (count == size_) return;
        if (data_) RT_CUDA_CHECK(cudaFree(data_));
        data_ = nullptr;
        size_ = 0;  // until the allocation succeeds: a failed one leaves an empty buffer
        if (count) RT_CUDA_CHECK(cudaMalloc(&data_, count * sizeof(T)));
        size_ = count;
    }
    // Resizes to at least count, keeping the contents (a copy on the device).
    void GrowTo(size_t count) {
        if (count <= size_) return;
        T* grown = nullptr;
        RT_CUDA_CHECK(cudaMalloc(&grown, count * sizeof(T)));
        if (data_) {
            RT_CUDA_CHECK(cudaMemcpy(grown, data_, size_ * sizeof(T), cudaMemcpyDeviceToDevice));
            RT_CUDA_CHECK(cudaFree(data_));
        }
        data_ = grown;
        size_ = count;
    }
    void Upload(std::span<const T> host) {
        Resize(host.size());
        if (!host.empty())
            RT_CUDA_CHECK(
                cudaMemcpy(data_, host.data(), host.size_bytes(), cudaMemcpyHostToDevice));
    }
    void Download(std::span<T> host) const {
        RT_CUDA_CHECK(cudaMemcpy(host.data(), data_, std::min(host.size(), size_) * sizeof(T),
                                 cudaMemcpyDeviceToHost));
    }
    T* Data() const { return data_; }
    size_t Size() const { return size_; }

  private:
    T* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace rtrt
