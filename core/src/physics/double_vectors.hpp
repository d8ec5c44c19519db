#pragma once
// Vectors of 2, 4 or 8 doubles for the loops built once per instruction set (chain_kernel.cpp,
// modal_kernel.cpp): each lane computes what the scalar scheme does, so every build gives the
// same bits. Private to the physics sources.

#include <cstring>
#include <type_traits>

// Whole 512-bit vectors: GCC and clang otherwise split them into halves on AVX-512.
#if defined(__clang__)
#define ARCHET_TARGET_AVX512 __attribute__((target("avx512f"), min_vector_width(512)))
#else
#define ARCHET_TARGET_AVX512 __attribute__((target("avx512f,prefer-vector-width=512")))
#endif

namespace archet::double_vectors {

typedef double Doubles8 __attribute__((vector_size(64)));
typedef double Doubles4 __attribute__((vector_size(32)));
typedef double Doubles2 __attribute__((vector_size(16)));

template <int W>
using Doubles =
    std::conditional_t<W == 8, Doubles8, std::conditional_t<W == 4, Doubles4, Doubles2>>;

template <class V>
[[gnu::always_inline]] inline V load(const double* p) {
    if constexpr (std::is_same_v<V, double>) {
        return *p;
    } else {
        V v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
}

template <class V>
[[gnu::always_inline]] inline void store(double* p, V v) {
    std::memcpy(p, &v, sizeof v);
}

template <class V>
[[gnu::always_inline]] inline V broadcast(double value) {
    V v;
    for (int lane = 0; lane < static_cast<int>(sizeof v / sizeof value); ++lane) v[lane] = value;
    return v;
}

}  // namespace archet::double_vectors
