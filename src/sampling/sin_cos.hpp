#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace placement_samplers {

namespace detail {

/// sin and cos of j * pi / 64 for j = 0 .. 31, correctly rounded (computed to 80 digits).
struct SinCosPair {
  double sine;
  double cosine;
};
inline constexpr SinCosPair kSinCosTable[32] = {
    {0x0.0p+0, 0x1.0000000000000p+0},
    {0x1.91f65f10dd814p-5, 0x1.ff621e3796d7ep-1},
    {0x1.917a6bc29b42cp-4, 0x1.fd88da3d12526p-1},
    {0x1.2c8106e8e613ap-3, 0x1.fa7557f08a517p-1},
    {0x1.8f8b83c69a60bp-3, 0x1.f6297cff75cb0p-1},
    {0x1.f19f97b215f1bp-3, 0x1.f0a7efb9230d7p-1},
    {0x1.294062ed59f06p-2, 0x1.e9f4156c62ddap-1},
    {0x1.58f9a75ab1fddp-2, 0x1.e212104f686e5p-1},
    {0x1.87de2a6aea963p-2, 0x1.d906bcf328d46p-1},
    {0x1.b5d1009e15cc0p-2, 0x1.ced7af43cc773p-1},
    {0x1.e2b5d3806f63bp-2, 0x1.c38b2f180bdb1p-1},
    {0x1.073879922ffeep-1, 0x1.b728345196e3ep-1},
    {0x1.1c73b39ae68c8p-1, 0x1.a9b66290ea1a3p-1},
    {0x1.30ff7fce17035p-1, 0x1.9b3e047f38741p-1},
    {0x1.44cf325091dd6p-1, 0x1.8bc806b151741p-1},
    {0x1.57d69348ceca0p-1, 0x1.7b5df226aafafp-1},
    {0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bcdp-1},
    {0x1.7b5df226aafafp-1, 0x1.57d69348ceca0p-1},
    {0x1.8bc806b151741p-1, 0x1.44cf325091dd6p-1},
    {0x1.9b3e047f38741p-1, 0x1.30ff7fce17035p-1},
    {0x1.a9b66290ea1a3p-1, 0x1.1c73b39ae68c8p-1},
    {0x1.b728345196e3ep-1, 0x1.073879922ffeep-1},
    {0x1.c38b2f180bdb1p-1, 0x1.e2b5d3806f63bp-2},
    {0x1.ced7af43cc773p-1, 0x1.b5d1009e15cc0p-2},
    {0x1.d906bcf328d46p-1, 0x1.87de2a6aea963p-2},
    {0x1.e212104f686e5p-1, 0x1.58f9a75ab1fddp-2},
    {0x1.e9f4156c62ddap-1, 0x1.294062ed59f06p-2},
    {0x1.f0a7efb9230d7p-1, 0x1.f19f97b215f1bp-3},
    {0x1.f6297cff75cb0p-1, 0x1.8f8b83c69a60bp-3},
    {0x1.fa7557f08a517p-1, 0x1.2c8106e8e613ap-3},
    {0x1.fd88da3d12526p-1, 0x1.917a6bc29b42cp-4},
    {0x1.ff621e3796d7ep-1, 0x1.91f65f10dd814p-5},
};

}  // namespace detail

/// Angles up to this magnitude [rad] take the fast path of sinCos().
inline constexpr double kSinCosFastLimit = 5e4;

/// Sine and cosine of @p angle [rad] at once: within 2.5 ulp of the exact values (tested), and
/// the same bits with any C library.
///
/// Why our own: every placed object needs one for its rotation, and a scene waits for it;
/// glibc's sincos was about a tenth of a cluttered scene (profile of clutter N = 40). The angle is
/// reduced to the nearest multiple k of pi/64 (pi/64 in three parts, so that k times each of
/// the first two is exact), sin and cos of k pi/64 come from a table and those of the rest
/// (|r| <= pi/128) from short Taylor polynomials; no branch on the angle. Beyond
/// kSinCosFastLimit, NaN and infinities go to std::sin and std::cos.
inline void sinCos(double angle, double& sine, double& cosine) {
  if (!(std::fabs(angle) <= kSinCosFastLimit)) {
    sine = std::sin(angle);
    cosine = std::cos(angle);
    return;
  }
  constexpr double kRound = 0x1.8p52;  // adding it rounds to an integer
  const double k = (angle * 0x1.45f306dc9c883p+4 + kRound) - kRound;  // angle / (pi/64)
  const double r =
      ((angle - k * 0x1.921fb544p-5) - k * 0x1.0b4611a6p-39) - k * 0x1.3198a2e037073p-74;
  const double z = r * r;
  // |r| <= pi/128: the first omitted terms are below 4e-18 relative.
  const double sinR =
      r + r * z * (-0x1.5555555555555p-3 + z * (0x1.1111111111111p-7 + z * -0x1.a01a01a01a01ap-13));
  const double cosRMinus1 = z * (-0.5 + z * (0x1.5555555555555p-5 + z * -0x1.6c16c16c16c17p-10));
  const auto q = static_cast<std::uint64_t>(static_cast<std::int64_t>(k));
  const detail::SinCosPair& b = detail::kSinCosTable[q & 31];
  // sin and cos of (q mod 32) pi/64 + r, the small corrections added last.
  const double sinPart = b.sine + (b.sine * cosRMinus1 + b.cosine * sinR);
  const double cosPart = b.cosine + (b.cosine * cosRMinus1 - b.sine * sinR);
  // Quadrant (q / 32) mod 4: sin = (s, c, -s, -c), cos = (c, -s, -c, s); the swap and the
  // signs on the bits, so that a random quadrant costs no mispredicted branch. The swap is a
  // mask rather than an index into a stored pair, whose reload waited for the store.
  std::uint64_t sBits = 0;
  std::uint64_t cBits = 0;
  std::memcpy(&sBits, &sinPart, sizeof(sinPart));
  std::memcpy(&cBits, &cosPart, sizeof(cosPart));
  const std::uint64_t quadrant = (q >> 5) & 3;
  const std::uint64_t swapped = (sBits ^ cBits) & (0 - (quadrant & 1));  // all bits or none
  sBits ^= swapped;
  cBits ^= swapped;
  sBits ^= (quadrant & 2) << 62;
  cBits ^= ((quadrant + 1) & 2) << 62;
  std::memcpy(&sine, &sBits, sizeof(sine));
  std::memcpy(&cosine, &cBits, sizeof(cosine));
}

}  // namespace placement_samplers
