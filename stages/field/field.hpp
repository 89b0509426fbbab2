#pragma once
/// @brief Stage 4: the diffusion field D, 0 on the centerline and 1 on the boundary.

#include "stages/geometry/grid.hpp"

#include <string>

namespace ligsim {
class Polyline;
class SurfaceQuery;
} // namespace ligsim

namespace ligsim::field {

enum class Method {
  /// The paper's construction: D(x) = |x - C(x)| / |B(x) - C(x)|, with C(x) the closest
  /// centerline point and B(x) where the ray from C(x) through x leaves the surface.
  geometric,
  /// The classical Dirichlet problem: Laplace's equation on the inside voxels, D = 0 on the
  /// voxels the centerline passes through, D = 1 on the surface, except on the end faces the
  /// centerline runs into, where the normal derivative vanishes.
  laplace,
};

Method parse_method(const std::string& name);
std::string to_string(Method method);

struct Parameters {
  Method method = Method::geometric;
  double laplace_tolerance = 1e-8; ///< relative residual of the CG solve
  int laplace_max_iterations = 20000;
};

struct Field {
  ScalarGrid values;     ///< D inside, 1 outside
  int rays_missed = 0;   ///< geometric: rays from C(x) that found no boundary (D = 1 used)
  int clamped = 0;       ///< geometric: voxels hidden behind a fold of the surface (D > 1, clamped)
  int iterations = 0;    ///< laplace: CG iterations
  double residual = 0.0; ///< laplace: final relative residual
};

Field diffusion_field(const Mask& mask, const Polyline& centerline, const SurfaceQuery& surface,
                      const Parameters& parameters);

} // namespace ligsim::field
