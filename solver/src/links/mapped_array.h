#pragma once
// A growable array of trivially copyable elements in an anonymous mapping of its own: growing
// it remaps its pages (mremap) where std::vector copies its elements to a new block, so the
// element links of a big solve (most of its memory) never stand in memory twice, as they did
// at the moment a vector's links outgrew their block (docs/calibration.md#mappedarray).

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

namespace penumbra::solver {

template <typename T> class MappedArray {
    static_assert(std::is_trivially_copyable_v<T>);

public:
    MappedArray() = default;
    MappedArray(const MappedArray&) = delete;
    MappedArray& operator=(const MappedArray&) = delete;
    MappedArray(MappedArray&& other) noexcept { swap(other); }
    MappedArray& operator=(MappedArray&& other) noexcept {
        if (this != &other) {
            release();
            swap(other);
        }
        return *this;
    }
    ~MappedArray() { release(); }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    T* begin() { return data_; }
    T* end() { return data_ + size_; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }
    std::span<T> span() { return {data_, size_}; }
    std::span<const T> span() const { return {data_, size_}; }

    void reserve(std::size_t n) {
        if (n * sizeof(T) > bytes_)
            remap(n * sizeof(T));
    }
    /// New elements are value-initialised; shrinking keeps the pages (shrink_to_fit drops them).
    void resize(std::size_t n) {
        if (n > size_) {
            grow_to(n);
            for (std::size_t i = size_; i < n; ++i)
                new (data_ + i) T();
        }
        size_ = n;
    }
    template <typename... Args> T& emplace_back(Args&&... args) {
        grow_to(size_ + 1);
        T* p = new (data_ + size_) T(std::forward<Args>(args)...);
        ++size_;
        return *p;
    }
    void push_back(const T& value) { emplace_back(value); }
    void clear() { size_ = 0; }
    void assign(std::span<const T> values) {
        size_ = 0;
        reserve(values.size());
        if (!values.empty())
            std::memcpy(static_cast<void*>(data_), values.data(), values.size() * sizeof(T));
        size_ = values.size();
    }
    /// Gives back the pages past the last element.
    void shrink_to_fit() {
        if (size_ == 0)
            release();
        else if (round_up(size_ * sizeof(T)) < bytes_)
            remap(size_ * sizeof(T));
    }
    void swap(MappedArray& other) noexcept {
        std::swap(data_, other.data_);
        std::swap(size_, other.size_);
        std::swap(bytes_, other.bytes_);
    }

private:
    static std::size_t round_up(std::size_t bytes) {
        static const auto page = std::size_t(::sysconf(_SC_PAGESIZE));
        return (bytes + page - 1) / page * page;
    }
    // Geometric growth costs no copy here, only address space.
    void grow_to(std::size_t n) {
        if (n * sizeof(T) > bytes_)
            remap(std::max(n * sizeof(T), bytes_ + bytes_ / 2));
    }
    void remap(std::size_t bytes) {
        bytes = round_up(bytes);
        void* p = data_ ? ::mremap(data_, bytes_, bytes, MREMAP_MAYMOVE)
                        : ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                                 MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED)
            throw std::bad_alloc();
        data_ = static_cast<T*>(p);
        bytes_ = bytes;
    }
    void release() {
        if (data_)
            ::munmap(data_, bytes_);
        data_ = nullptr;
        size_ = bytes_ = 0;
    }

    T* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t bytes_ = 0; ///< mapped
};

} // namespace penumbra::solver
