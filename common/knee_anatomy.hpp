#pragma once
/// @brief What a model knows of the knee's anatomy, kept beside it in `anatomy.json`: its side,
/// its anatomical directions and its landmarks, each with where it came from. `ligsim build`
/// writes it; the flexion and the exporters read it.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ligsim {

struct KneeLandmark {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  std::string source; ///< "given", or the surface whose centroid it is
};

struct KneeAnatomy {
  std::string side;                         ///< "left", "right", or empty: not known
  std::optional<Eigen::Vector3d> proximal;  ///< unit, up the leg
  std::optional<Eigen::Vector3d> posterior; ///< unit
  std::string frame_source;                 ///< where the directions came from
  std::string side_source;                  ///< what told the side
  /// By name: "medial_epicondyle", "lateral_epicondyle", "intercondylar_notch",
  /// "tibial_plateau_centre", "medial_tibial_plateau", "lateral_tibial_plateau", "fibular_head".
  std::map<std::string, KneeLandmark> landmarks;
  /// What could not be found, and why (one line each).
  std::vector<std::string> not_found;

  /// +1 for a right knee, -1 for a left one, 0 when not known.
  int side_sign() const { return side == "right" ? 1 : side == "left" ? -1 : 0; }
};

inline constexpr const char* knee_anatomy_file = "anatomy.json";

nlohmann::json to_json(const KneeAnatomy& anatomy);
/// Throws InputError naming `where` on a malformed document.
KneeAnatomy knee_anatomy_from_json(const nlohmann::json& json, const std::string& where);
/// The anatomy of the model folder `dir`; empty (nothing known) when it has no anatomy.json.
KneeAnatomy read_knee_anatomy(const std::filesystem::path& dir);

} // namespace ligsim
