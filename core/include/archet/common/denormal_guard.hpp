#pragma once
// A decaying string ends up in denormal numbers (about 1e-308 and below), which x86 handles
// dozens of times slower: a silent model would cost a third more than a playing one. Every
// thread that steps a simulation holds this guard, which flushes denormals to zero (FTZ and
// DAZ) and restores the previous mode when it goes. Results differ only below 1e-308 m.

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace archet {

class DenormalGuard {
  public:
    DenormalGuard() {
#if defined(__SSE__) || defined(__x86_64__)
        saved_ = _mm_getcsr();
        _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
#endif
    }
    ~DenormalGuard() {
#if defined(__SSE__) || defined(__x86_64__)
        _mm_setcsr(saved_);
#endif
    }
    DenormalGuard(const DenormalGuard&) = delete;
    DenormalGuard& operator=(const DenormalGuard&) = delete;

  private:
    static constexpr unsigned kFlushToZero = 0x8000;
    static constexpr unsigned kDenormalsAreZero = 0x0040;
    unsigned saved_ = 0;
};

}  // namespace archet
