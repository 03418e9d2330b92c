#pragma once
// IEEE 754 binary16 <-> binary32 conversion on the CPU, for EXR output and half vertex/texture
// data. Bit-exact (round to nearest even) so CPU-written halves match what the GPU would produce.
#include <cstdint>
#include <cstring>

namespace rayster {

inline uint16_t floatToHalf(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  const uint16_t sign = static_cast<uint16_t>((bits >> 16) & 0x8000u);
  const uint32_t exponent = (bits >> 23) & 0xffu;
  uint32_t mantissa = bits & 0x7fffffu;

  if (exponent == 0xffu) {
    // Keep NaNs NaN (force a quiet bit so a payload that shifts out cannot become inf).
    if (mantissa != 0) return static_cast<uint16_t>(sign | 0x7e00u | (mantissa >> 13));
    return static_cast<uint16_t>(sign | 0x7c00u);
  }
  const int halfExponent = static_cast<int>(exponent) - 127 + 15;
  if (halfExponent >= 31) return static_cast<uint16_t>(sign | 0x7c00u);  // overflow -> inf
  if (halfExponent <= 0) {
    // Denormal half (or zero): shift the mantissa with its implicit 1 into place.
    if (halfExponent < -10) return sign;  // below half the smallest denormal -> signed zero
    mantissa |= 0x800000u;
    const int shift = 14 - halfExponent;
    uint32_t halfMantissa = mantissa >> shift;
    const uint32_t remainder = mantissa & ((1u << shift) - 1u);
    const uint32_t halfway = 1u << (shift - 1);
    if (remainder > halfway || (remainder == halfway && (halfMantissa & 1u))) ++halfMantissa;
    // A carry into bit 10 correctly produces the smallest normal.
    return static_cast<uint16_t>(sign | halfMantissa);
  }
  uint32_t half = (static_cast<uint32_t>(halfExponent) << 10) | (mantissa >> 13);
  const uint32_t remainder = mantissa & 0x1fffu;
  if (remainder > 0x1000u || (remainder == 0x1000u && (half & 1u))) ++half;  // may carry to inf: correct
  return static_cast<uint16_t>(sign | half);
}

inline float halfToFloat(uint16_t half) {
  const uint32_t sign = static_cast<uint32_t>(half & 0x8000u) << 16;
  const uint32_t exponent = (half >> 10) & 0x1fu;
  uint32_t mantissa = half & 0x3ffu;
  uint32_t bits;
  if (exponent == 0x1fu) {
    bits = sign | 0x7f800000u | (mantissa << 13);
  } else if (exponent != 0) {
    bits = sign | ((exponent + 127 - 15) << 23) | (mantissa << 13);
  } else if (mantissa == 0) {
    bits = sign;
  } else {
    // Renormalise a denormal half: every one is exactly representable as a normal float.
    int e = -1;
    do {
      ++e;
      mantissa <<= 1;
    } while ((mantissa & 0x400u) == 0);
    bits = sign | (static_cast<uint32_t>(127 - 15 - e) << 23) | ((mantissa & 0x3ffu) << 13);
  }
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace rayster
