#pragma once
/// @brief The factor on the model's mesh sizes that gives the companion elements a target times
/// as large as the model's.

#include <functional>

namespace ligsim::pipeline {

/// Where the search ended: the factor of the last mesh made, and its elements' size over the
/// model's.
struct SizeSearch {
  double scale = 0.0;
  double size_ratio = 0.0;
  int meshings = 0; ///< meshes made, failed ones included
};

/// One mesh of the search: its elements' size over the model's, and whether it was the previous
/// build's, current and reused.
struct SizeTry {
  double size_ratio = 0.0;
  bool reused = false;
};

/// Meshes at factors on the model's sizes (`mesh_at(factor)` meshes, or throws where the sizes
/// give no mesh or no model: nothing kept by the mesher, no node on a footprint) until the
/// elements' size over the model's is `target` within 5 %: a thin band keeps its tets across its
/// thickness as the sizes grow (sizes 1.5 times the HRA MCL's 10-node mesh gave elements 1.12
/// times as large). The first mesh takes `first`; each next one corrects the factor on the line
/// through (1, 1) and the last mesh in log-log, the factor at most 8. A mesh that fails (sizes
/// too coarse for the ligament) sends the factor halfway back, in log, to the last one that
/// meshed, and later factors go at most halfway from the last mesh to it. At most four meshes
/// that succeed and six in all; the last mesh made stands. A first mesh that was reused (the
/// previous build's factor, its companion current) stands as it is, so an unchanged rebuild
/// changes nothing. Throws what the last mesh threw when it failed.
SizeSearch search_size_factor(double first, double target,
                              const std::function<SizeTry(double)>& mesh_at);

} // namespace ligsim::pipeline
