#pragma once
/// @brief A config's parameters as JSON (summary.json's parameters), written by walking the same
/// parameter list (visit_* functions) its reader walks: `visit_fields(parameters,
/// FieldJsonWriter{json})`; and read back from such JSON the same way (FieldJsonReader).

#include "common/config_choice.hpp"
#include "common/config_field_kinds.hpp"
#include "common/error.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

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

/// A parameter list's values as one JSON object.
template <class P, class VisitFields>
nlohmann::json as_json(const P& parameters, VisitFields visit_fields)
{
  nlohmann::json json = nlohmann::json::object();
  visit_fields(parameters, FieldJsonWriter{json});
  return json;
}

/// The writer's inverse: reads each visited parameter from `json`, which must have every key
/// (a file ligsim wrote); `where` names the file in errors.
struct FieldJsonReader {
  const nlohmann::json& json;
  const std::string& where;

  template <class T> void operator()(const char* key, T& value)
  {
    try {
      value = json.at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
      fail("{}: '{}': {}", where, key, e.what());
    }
  }

  template <class T> void operator()(const char* key, Required<T> required)
  {
    (*this)(key, required.value);
  }

  template <class D> void operator()(const char* key, Degrees<D> angle)
  {
    double degrees = 0.0;
    (*this)(key, degrees);
    angle.radians = Degrees<D>::to_radians(degrees);
  }

  template <class E> void operator()(const char* key, Choice<E> choice)
  {
    std::string text;
    (*this)(key, text);
    const auto value = choice.parse(text);
    if (!value)
      fail("{}: '{}': expected {}, got \"{}\"", where, key, choice.expected(), text);
    choice.value = *value;
  }
};

} // namespace ligsim
