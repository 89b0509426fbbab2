#include "pipeline/stage_graph/companion_size_search.hpp"

#include <algorithm>
#include <cmath>

namespace ligsim::pipeline {

SizeSearch search_size_factor(double first, double target,
                              const std::function<SizeTry(double)>& mesh_at)
{
  constexpr int kMaxMeshed = 4, kMaxMeshings = 6;
  constexpr double kMaxScale = 8.0, kTolerance = 0.05;
  double meshed_at = 1.0;      // the factor of the last mesh made (1: the model's)
  double failed_at = INFINITY; // the smallest factor whose mesh failed
  int meshed = 0;
  SizeSearch search;
  search.scale = first;
  for (search.meshings = 1;; ++search.meshings) {
    SizeTry tried;
    try {
      tried = mesh_at(search.scale);
    } catch (const std::exception&) {
      if (search.meshings == kMaxMeshings || !(search.scale > meshed_at))
        throw;
      failed_at = search.scale;
      search.scale = std::sqrt(meshed_at * failed_at);
      continue;
    }
    search.size_ratio = tried.size_ratio;
    meshed_at = search.scale;
    ++meshed;
    if ((search.meshings == 1 && tried.reused) ||
        !(std::abs(std::log(search.size_ratio / target)) > std::log1p(kTolerance)) ||
        meshed == kMaxMeshed || search.meshings == kMaxMeshings || search.scale >= kMaxScale)
      return search;
    const double growth = std::log(search.size_ratio) / std::log(search.scale);
    // Toward a factor whose mesh failed, halfway at most (in log).
    search.scale = std::min({std::exp(std::log(target) / std::max(growth, 0.1)), kMaxScale,
                             std::sqrt(search.scale * failed_at)});
  }
}

} // namespace ligsim::pipeline
