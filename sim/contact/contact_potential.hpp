#pragma once
/// @brief Ligament-bone contact as an IPC barrier (Li et al. 2020) on the surface nodes:
/// E = kappa sum_o sum_i a_i b(d_o(x_i, t)), b(d) = -(d - d_hat)^2 ln(d / d_hat) for d < d_hat,
/// with d_o the signed distance to obstacle o in its pose at load factor t and a_i the node's
/// area. Exact gradient; Hessian blocks kappa a_i (b'' g g^T + b' R H R^T), exact or projected to
/// positive semi-definite (b' < 0: a convex obstacle's curvature H makes them indefinite).

#include "sim/contact/contact_surface.hpp"
#include "sim/contact/distance_field.hpp"
#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct ContactSettings {
  double d_hat_mm = 0.3; ///< activation distance
  /// kappa: the contact pressure is kappa (-b'(d)), MPa; at d = d_hat / 10 it is 12.2 kappa d_hat.
  double stiffness_mpa_per_mm = 100.0;
};

/// One rigid obstacle: its distance field in the rest frame, moved by `motion` at load factor t
/// (none: fixed), and the nodes that take no contact with it (those bound to it).
struct ContactObstacle {
  std::string name;
  const DistanceField* field = nullptr; ///< not owned
  std::optional<RigidMotion> motion;
  std::vector<int> excluded_nodes;
  /// Added to the distance at load factor 0 and falling linearly to 0 at load factor 1: the
  /// obstacle grows from shrunk by this much to its true surface (>= 0, mm). This is how nodes
  /// that start inside it are pushed out gradually.
  double start_offset_mm = 0.0;
};

/// Per node and per obstacle measures of a state.
struct ContactMeasures {
  std::vector<Eigen::Vector3d> force_n; ///< per obstacle: what it exerts on the body
  std::vector<double> area_mm2;         ///< per obstacle: area of the nodes within d_hat
  std::vector<double> min_gap_mm;       ///< per obstacle: smallest distance of a contact node
  std::vector<int> active_nodes;        ///< per obstacle: nodes within d_hat
  Eigen::VectorXd gap_mm;               ///< per mesh node: distance to the nearest obstacle
  Eigen::VectorXd pressure_mpa;         ///< per mesh node: contact force / area
};

/// Not thread-safe: it caches which nodes are near each obstacle.
class ContactPotential final : public ExtraPotential {
public:
  /// `surface`: the candidate nodes (mesh indices) with their areas, and the faces the contact
  /// area is measured on (may be empty: then the nodes' areas); nodes that the solver holds
  /// (prescribed) must be left out. Throws InputError on bad settings.
  ContactPotential(int node_count, const ContactSurface& surface,
                   std::vector<ContactObstacle> obstacles, const ContactSettings& settings);

  double energy(const Eigen::VectorXd& x, double t, Eigen::VectorXd* gradient) const override;
  void hessian_blocks(const Eigen::VectorXd& x, double t, bool projected,
                      std::vector<NodeBlock>& blocks) const override;
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx, double t) const override;
  int make_admissible(Eigen::VectorXd& x, double t) const override;

  ContactMeasures measure(const Eigen::VectorXd& x, double t) const;

  /// One node's barrier term of one obstacle: its gradient (world, N) and its exact Hessian block
  /// (world, N/mm), and where the node lies in the obstacle's rest frame (mm).
  struct NodeTerm {
    int node = 0;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
    Eigen::Vector3d local_mm = Eigen::Vector3d::Zero();
  };
  /// The nodes obstacle o's barrier acts on at (x, t), with their terms: what the obstacle's own
  /// motion couples to (a moving bone's reaction and its derivatives).
  std::vector<NodeTerm> node_terms(std::size_t o, const Eigen::VectorXd& x, double t) const;

  const ContactSettings& settings() const { return m_settings; }
  const std::vector<ContactObstacle>& obstacles() const { return m_obstacles; }
  /// The signed distance of point `p` (world, mm) to obstacle o at load factor t (with its
  /// offset).
  double distance(std::size_t o, const Eigen::Vector3d& p, double t) const;

private:
  struct Pose {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); ///< rest frame to world
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();        ///< world = R p + shift
    Eigen::Vector3d to_local(const Eigen::Vector3d& world) const
    {
      return rotation.transpose() * (world - shift);
    }
  };
  /// One (obstacle, node) pair that may touch.
  struct Pair {
    int node = 0;
    double area = 0.0;
  };
  /// Where a pair was last classified (local point) and whether it was near then: what every
  /// call reads for every pair, kept apart from the samples so that it stays in cache.
  struct Closeness {
    Eigen::Vector3d p0 = Eigen::Vector3d::Constant(INFINITY);
    bool near = true;
  };
  /// What a near pair was last sampled and bounded at.
  struct PairState {
    Eigen::Vector3d sampled_at = Eigen::Vector3d::Constant(INFINITY);
    DistanceSample sample; ///< at `sampled_at`, with the Hessian
    Eigen::Vector3d bounded_at = Eigen::Vector3d::Constant(INFINITY);
    double bound_mm = 0.0; ///< the field's lower bound at `bounded_at`
  };
  Pose pose(std::size_t o, double t) const;
  /// The distance added to obstacle o's field at load factor t (its start offset, ramped down).
  double offset(std::size_t o, double t) const
  {
    return m_obstacles[o].start_offset_mm * (1.0 - t);
  }
  /// Whether a node at local point p (rest frame of obstacle o) is surely farther than `far`.
  bool surely_farther(std::size_t o, const Eigen::Vector3d& p, double far) const;
  /// Whether pair i of obstacle o, now at local point p, may be within d_hat. A pair found
  /// farther than d_hat + slack is not looked up again until it moved by slack / 2 relative to
  /// the obstacle: the cheap cull that makes far nodes cost a subtraction.
  bool maybe_near(std::size_t o, std::size_t i, const Eigen::Vector3d& p) const;
  /// Whether pair i of obstacle o at local point p is farther than `distance_mm` by the field's
  /// cheap lower bound plus `offset_mm` (cached per point): beyond d_hat its barrier and
  /// derivatives are zero, beyond 0 it is outside, and no sample is needed (most near pairs of a
  /// sweep lie between d_hat and d_hat + slack).
  bool surely_beyond(std::size_t o, std::size_t i, const Eigen::Vector3d& p, double offset_mm,
                     double distance_mm) const;
  /// The field at local point p for pair i of obstacle o, reused when p has not moved (energy,
  /// gradient and Hessian of one state sample once).
  const DistanceSample& pair_sample(std::size_t o, std::size_t i, const Eigen::Vector3d& p) const;
  /// Calls `visit(pair, pose, sample, barrier)` for every pair that may be within d_hat of its
  /// obstacle at (x, t); stops and returns false as soon as `visit` returns false.
  /// Only obstacle `only` when it is not npos.
  template <class Visit>
  bool for_each_near_pair(const Eigen::VectorXd& x, double t, Visit&& visit,
                          std::size_t only = static_cast<std::size_t>(-1)) const;

  int m_node_count = 0;
  std::vector<ContactObstacle> m_obstacles;
  std::vector<std::vector<Pair>> m_pairs; ///< per obstacle
  /// Per obstacle and pair (caches: calls must not run concurrently).
  mutable std::vector<std::vector<Closeness>> m_closeness;
  mutable std::vector<std::vector<PairState>> m_state;
  double m_slack_mm = 0.0;
  ContactSettings m_settings;
  Triangles m_faces;
};

} // namespace ligsim::sim
