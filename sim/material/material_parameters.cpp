#include "sim/material/material_parameters.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::sim {

MaterialParameters mcl_material()
{
  MaterialParameters parameters;
  parameters.fiber = FiberParameters{};
  return parameters;
}

namespace {

void require_positive(double value, const char* name)
{
  if (!std::isfinite(value) || value <= 0.0)
    fail("material parameter {} must be finite and positive, got {}", name, value);
}

} // namespace

void validate(const MaterialParameters& parameters)
{
  require_positive(parameters.mu_mpa, "mu_mpa");
  require_positive(parameters.bulk_modulus_mpa, "k_mpa");
  if (!parameters.fiber)
    return;
  const FiberParameters& fiber = *parameters.fiber;
  require_positive(fiber.c3_mpa, "c3_mpa");
  require_positive(fiber.c4, "c4");
  require_positive(fiber.c5_mpa, "c5_mpa");
  if (!std::isfinite(fiber.lambda_star) || fiber.lambda_star <= 1.0)
    fail("material parameter lambda_star must be finite and above 1, got {}", fiber.lambda_star);
}

FiberConvention parse_fiber_convention(const std::string& text, const std::string& where)
{
  if (text == "paper")
    return FiberConvention::paper;
  if (text == "weiss")
    return FiberConvention::weiss;
  fail("{}: fiber convention must be \"paper\" or \"weiss\", got \"{}\"", where, text);
}

VolumetricLaw parse_volumetric_law(const std::string& text, const std::string& where)
{
  if (text == "jm1")
    return VolumetricLaw::jm1;
  if (text == "lnj")
    return VolumetricLaw::lnj;
  fail("{}: volumetric law must be \"jm1\" or \"lnj\", got \"{}\"", where, text);
}

std::string to_string(FiberConvention convention)
{
  return convention == FiberConvention::paper ? "paper" : "weiss";
}

std::string to_string(VolumetricLaw law)
{
  return law == VolumetricLaw::jm1 ? "jm1" : "lnj";
}

} // namespace ligsim::sim
