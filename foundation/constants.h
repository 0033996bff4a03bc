#pragma once
// The physical and mathematical constants, written once. Float and double forms are both
// given because the hot loops compute in float and the set-up in double: mixing them would
// silently promote float arithmetic (and change every image by a rounding).
namespace sl {

inline constexpr double kPiDouble = 3.14159265358979323846;
inline constexpr float kPi = static_cast<float>(kPiDouble);
inline constexpr float kInv4Pi = static_cast<float>(1.0 / (4.0 * kPiDouble));

// The speed of light in vacuum: 299 792 458 m/s exactly, i.e. metres per nanosecond.
inline constexpr double kSpeedOfLight = 0.299792458;

}  // namespace sl
