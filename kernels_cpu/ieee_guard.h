#pragma once
// IEEE float environment for one stretch of CPU work: subnormals kept (FTZ and DAZ off) and
// round-to-nearest. TBB worker threads do not inherit the calling thread's MXCSR reliably, and a
// host application may have set FTZ/DAZ for its own speed; either would change exact-mode bits.
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <xmmintrin.h>
#define SVGF_HAVE_MXCSR 1
#else
#include <cfenv>
#endif

namespace svgf::cpu {

class ScopedIeeeFloat {
 public:
#if defined(SVGF_HAVE_MXCSR)
  // MXCSR: FTZ is bit 15, DAZ bit 6, rounding control bits 13-14 (00 = nearest).
  static constexpr unsigned kFtz = 0x8000u, kDaz = 0x0040u, kRound = 0x6000u;
  ScopedIeeeFloat() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ & ~(kFtz | kDaz | kRound)); }
  ~ScopedIeeeFloat() { _mm_setcsr(saved_); }
#else
  ScopedIeeeFloat() : saved_(std::fegetround()) { std::fesetround(FE_TONEAREST); }
  ~ScopedIeeeFloat() { std::fesetround(saved_); }
#endif
  ScopedIeeeFloat(const ScopedIeeeFloat&) = delete;
  ScopedIeeeFloat& operator=(const ScopedIeeeFloat&) = delete;

 private:
  unsigned saved_;
};

}  // namespace svgf::cpu
