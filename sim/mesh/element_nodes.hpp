#pragma once
/// @brief The check every element mesh passes before its rest shapes are computed.

#include "common/error.hpp"
#include "common/mesh.hpp"

#include <Eigen/Core>

namespace ligsim::sim {

/// Throws InputError naming the first node of `V` with a non-finite coordinate, the first
/// element of `T` (one row of node indices per element) that names a node V does not have, or
/// a mesh without elements.
template <class ElementsT> void check_element_nodes(const Points& V, const ElementsT& T)
{
  const Eigen::Index node_count = V.rows();
  for (Eigen::Index n = 0; n < node_count; ++n)
    if (!V.row(n).allFinite())
      fail("node {} has a non-finite coordinate ({}, {}, {})", n, V(n, 0), V(n, 1), V(n, 2));
  if (T.rows() == 0)
    fail("the mesh has no tetrahedra");
  for (Eigen::Index e = 0; e < T.rows(); ++e)
    for (Eigen::Index i = 0; i < T.cols(); ++i)
      if (T(e, i) < 0 || T(e, i) >= node_count)
        fail("element {} refers to node {}, but the mesh has {} nodes", e, T(e, i), node_count);
}

} // namespace ligsim::sim
