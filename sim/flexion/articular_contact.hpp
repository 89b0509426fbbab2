#pragma once
/// @brief Contact between the femur's and the tibia's articular surfaces as an elastic foundation
/// (Blankevoort et al., J Biomech 1991;24:1019, as OpenSim-JAM uses it): the femur's surface,
/// sampled at its triangles' centroids with their areas, against the tibia's signed distance.
/// Where a sample comes nearer the tibia than `gap_mm`, the cartilage layers (`thickness_mm`
/// together) are compressed by delta = gap - d and press p = K delta / h, with
/// K = (1 - nu) E / ((1 + nu)(1 - 2 nu)); the energy is K / (2 h) delta^2 per area. A function of
/// the femur's pose alone (both bones rigid), with exact derivatives in its five free coordinates.

#include "common/mesh.hpp"
#include "sim/contact/distance_field.hpp"
#include "sim/kinematics/free_pose.hpp"

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct ArticularSettings {
  double modulus_mpa = 5.0;  ///< cartilage E
  double poisson = 0.45;     ///< cartilage nu
  double thickness_mm = 4.0; ///< the two layers together
  double gap_mm = 0.0;       ///< distance at which the layers meet (0: the surfaces as given are
                             ///< the cartilage's, as the HRA femur's articular sheet)
  /// The knee as built is seated: in each compartment the layers meet at the bones' smallest
  /// separation in the built pose (at least gap_mm; up to kMaxSeatMm), which the cartilage and
  /// menisci a surface atlas leaves out fill.
  bool seated = true;
};

/// A compartment whose bones stand farther apart than this in the built pose is not seated:
/// cartilage and meniscus together are 5-8 mm thick at the plateau's rim, not at its contact.
constexpr double kMaxSeatMm = 5.0;

/// The first setting that cannot work: its key and what is wrong with it.
struct ArticularProblem {
  std::string key;
  std::string what;
};
std::optional<ArticularProblem> articular_problem(const ArticularSettings& settings);

/// Throws InputError naming the first setting that cannot work.
void validate(const ArticularSettings& settings);

/// The contact at one pose: its energy and derivatives in the free coordinates, and what a
/// report needs per compartment.
struct ArticularState {
  double energy_nmm = 0.0;
  Vector5d gradient = Vector5d::Zero();
  Matrix5d hessian = Matrix5d::Zero();
  /// On the femur, from the tibia (N), and where on the tibia it acts (pressure-weighted).
  Eigen::Vector3d medial_force_n = Eigen::Vector3d::Zero();
  Eigen::Vector3d lateral_force_n = Eigen::Vector3d::Zero();
  Eigen::Vector3d medial_centre_mm = Eigen::Vector3d::Constant(NAN);
  Eigen::Vector3d lateral_centre_mm = Eigen::Vector3d::Constant(NAN);
  Eigen::Vector3d moment_nmm = Eigen::Vector3d::Zero(); ///< of the forces about the JCS origin
  double area_mm2 = 0.0;
  double max_pressure_mpa = 0.0;
};

class ArticularContact {
public:
  /// `femur`: its surface in its rest pose (mm, outward); `tibia`: its signed distance (fixed);
  /// `jcs`: the knee's, whose flexion axis tells medial from lateral.
  ArticularContact(const TriangleSurface& femur, const DistanceField& tibia,
                   const JointCoordinateSystem& jcs, const ArticularSettings& settings);

  ArticularState evaluate(const FreePose& pose) const;
  /// Where each compartment's layers meet (mm): gap_mm, or the built pose's separation when
  /// seated; and that separation itself (infinite where the femur has no sample near the tibia).
  struct Seat {
    double medial_gap_mm = 0.0, lateral_gap_mm = 0.0;
    double medial_built_mm = INFINITY, lateral_built_mm = INFINITY;
  };
  const Seat& seat() const { return m_seat; }
  /// Foundation stiffness K / h, N/mm^3.
  double stiffness() const { return m_stiffness; }

private:
  struct Sample {
    Eigen::Vector3d rest_mm;
    double area_mm2;
    bool medial; ///< its compartment, from its rest position
    double gap_mm = 0.0;
  };
  std::vector<Sample> m_samples;
  const DistanceField& m_tibia;
  JointCoordinateSystem m_jcs;
  ArticularSettings m_settings;
  double m_stiffness = 0.0;
  Seat m_seat;
};

} // namespace ligsim::sim
