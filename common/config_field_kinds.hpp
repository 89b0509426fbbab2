#pragma once
/// @brief Two kinds of config parameter besides plain values and choices (config_choice.hpp),
/// for the parameter lists (the visit_* functions) that readers and writers walk: one the config
/// must give, and an angle the config gives in degrees and the code holds in radians.

namespace ligsim {

/// A parameter with no default: the config must give it.
template <class T> struct Required {
  T& value;
};

template <class T> Required<T> required(T& value)
{
  return {value};
}

/// An angle: degrees in the config and in summary.json, radians in the code.
template <class D> struct Degrees {
  static constexpr double pi = 3.14159265358979323846;
  static double to_radians(double degrees) { return degrees * (pi / 180.0); }
  static double to_degrees(double radians) { return radians * 180.0 / pi; }
  D& radians;
};

template <class D> Degrees<D> degrees(D& radians)
{
  return {radians};
}

} // namespace ligsim
