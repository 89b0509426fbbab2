#pragma once
/// @brief A config's parameters as JSON (summary.json's parameters), written by walking the same
/// parameter list (visit_* functions) its reader walks: `visit_fields(parameters,
/// FieldJsonWriter{json})`.

#include "common/config_choice.hpp"
#include "common/config_field_kinds.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>

namespace ligsim {

struct FieldJsonWriter {
  nlohmann::json& json;

  template <class T> void operator()(const char* key, const T& value) { json[key] = value; }

  void operator()(const char* key, const Eigen::Vector3d& value)
  {
    json[key] = {value.x(), value.y(), value.z()};
  }

  void operator()(const char* key, const std::optional<bool>& value)
  {
    json[key] = value ? nlohmann::json(*value) : nlohmann::json();
  }

  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    json[key] = choice.name(choice.value);
  }

  template <class T> void operator()(const char* key, Required<T> required)
  {
    (*this)(key, required.value);
  }

  template <class D> void operator()(const char* key, Degrees<D> angle)
  {
    json[key] = Degrees<D>::to_degrees(angle.radians);
  }
};

} // namespace ligsim
