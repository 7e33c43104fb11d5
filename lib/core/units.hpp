#pragma once
// The thesis mixes inch, mm, rpm, MPa and us; the library works in SI. Studies convert each thesis
// number once, by multiplying with one of these named factors (e.g. `4.5 * units::inch`).
#include <numbers>

namespace fem::units {

inline constexpr double inch = 0.0254;                 // m
inline constexpr double mm = 1e-3;                     // m
inline constexpr double cm = 1e-2;                     // m
inline constexpr double us = 1e-6;                     // s (microsecond)
inline constexpr double ms = 1e-3;                     // s
inline constexpr double MPa = 1e6;                     // Pa
inline constexpr double GPa = 1e9;                     // Pa
inline constexpr double kPa = 1e3;                     // Pa
inline constexpr double rpm = 2.0 * std::numbers::pi / 60.0;  // rad/s per revolution per minute
inline constexpr double deg = std::numbers::pi / 180.0;       // rad
inline constexpr double inch_per_s = inch;             // m/s

}  // namespace fem::units
