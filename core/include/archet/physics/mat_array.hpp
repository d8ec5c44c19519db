#pragma once
// Storage for the per-MAT arrays the chain loop runs over (positions, T²/m, chain links,
// grounds). Storage index 0 is padding and the loop's rounds start at MAT 1, so the arrays are
// placed with MAT 1 at the start of a 64-byte cache line: every whole-vector store of the loop
// is then aligned, and so is every load but those of x[s + 1] on the AVX2 and plain builds
// (chain_kernel.cpp's next_along(); a straddling AVX-512 load costs two).

#include <cstddef>
#include <new>
#include <vector>

namespace archet {

template <class T>
struct FirstMatAligned {
    using value_type = T;
    static constexpr std::size_t kLine = 64;
    /// Bytes before MAT 1's element: its start falls on a line.
    static constexpr std::size_t kLead = kLine - sizeof(T);

    FirstMatAligned() = default;
    template <class U>
    FirstMatAligned(const FirstMatAligned<U>&) {}

    T* allocate(std::size_t n) {
        void* line = ::operator new (n * sizeof(T) + kLead, std::align_val_t{kLine});
        return reinterpret_cast<T*>(static_cast<char*>(line) + kLead);
    }
    void deallocate(T* p, std::size_t) {
        ::operator delete (reinterpret_cast<char*>(p) - kLead, std::align_val_t{kLine});
    }
    template <class U>
    bool operator==(const FirstMatAligned<U>&) const {
        return true;
    }
};

/// A level's per-MAT array with MAT 1 on a cache line.
using MatArray = std::vector<double, FirstMatAligned<double>>;

}  // namespace archet
