#pragma once
/// @brief Knee flexion axis estimated from the femur surface: a least-squares cylinder fitted
/// to the posterior femoral condyles (the "cylindrical axis" or geometric centre axis).
///
/// Method. Outward area-weighted vertex normals (flipped if the signed volume is negative).
/// Candidates: vertices of the distal 50 mm, in the posterior half of that slab, whose normal
/// lies 15-165 degrees from distal toward posterior and within 45 degrees of the sagittal plane.
/// Start: axis = proximal x posterior, centre and radius from p_i - r n_i = centre (linear least
/// squares). Then MINPACK's Levenberg-Marquardt (Eigen's unsupported module) on the
/// point-to-cylinder distances (axis 2 dof, point on it 2 dof, radius), alternated with trimming to
/// the points within 2.5 robust sigmas (1.4826 median |residual|) until the kept set is stable:
/// notch, trochlea and sides drop out.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::sim {

/// A knee flexion axis.
struct FlexionAxis {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();   ///< on the axis: the middle of the fitted
                                                        ///< condyle points along it
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX(); ///< unit; a positive rotation about it
                                                        ///< (right-hand rule) flexes the knee
};

/// The fitted cylinder and how it was obtained.
struct CondyleAxisFit {
  FlexionAxis axis;
  double radius_mm = 0;           ///< fitted cylinder radius
  double rms_residual_mm = 0;     ///< RMS distance of the used points to the cylinder
  double span_mm = 0;             ///< extent of the used points along the axis
  int points_used = 0;            ///< vertices that entered the final fit
  int points_considered = 0;      ///< posterior-facing candidates
  int iterations = 0;             ///< Levenberg-Marquardt iterations, all trimming rounds together
  int trimming_rounds = 0;        ///< fits on a new set of kept points
  std::vector<int> used_vertices; ///< indices into femur.V of the points_used vertices
};

/// Fits the flexion axis to the posterior condyles of `femur`.
/// @param femur closed triangle surface (mm): the femur or the distal femoral cartilage
/// @param proximal unit vector pointing up the femur (from the tibia toward the femur)
/// @param posterior approximate posterior direction (need not be perpendicular to `proximal`)
/// The direction satisfies direction . (proximal x posterior) > 0: positive flexion with the
/// tibia fixed moves the femoral shaft posteriorly. That is lateral for a right knee and medial
/// for a left one. Throws InputError with a one-line message when the hints are zero, parallel
/// or non-finite, a vertex is non-finite or a face refers to a missing vertex, the surface has
/// too few posterior-facing vertices, or the fit does not converge, runs off to a plane or ends
/// more than 45 degrees from proximal x posterior.
CondyleAxisFit fit_condyle_axis(const TriangleSurface& femur, const Eigen::Vector3d& proximal,
                                const Eigen::Vector3d& posterior);

} // namespace ligsim::sim
