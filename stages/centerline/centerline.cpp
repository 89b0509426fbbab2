#include "stages/centerline/centerline.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "stages/geometry/interpolate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace ligsim::centerline {

namespace {

/// Distances below this fraction of a voxel are clamped, so 1/d^2 stays finite on the surface.
constexpr double kMinDistanceVoxels = 0.1;

struct CostModel {
  double alpha;
  double d_max;
  double d_min;
  /// The medial weight 1/dn^2 at a distance d (mm).
  double medial(double d) const
  {
    const double dn = std::max(d, d_min) / d_max;
    return 1.0 / (dn * dn);
  }
  double step(double length, double d_a, double d_b) const
  {
    return length * (alpha * 0.5 * (medial(d_a) + medial(d_b)) + (1.0 - alpha));
  }
  /// The integrand of eq. 25 at a distance d (mm).
  double density(double d) const { return alpha * medial(d) + (1.0 - alpha); }
};

CostModel cost_model(const ScalarGrid& distance, double alpha)
{
  float d_max = distance.background();
  distance.for_each_stored([&](const Eigen::Vector3i&, float d) { d_max = std::max(d_max, d); });
  if (!(d_max > 0.0f))
    fail("the distance image has no inside voxel");
  return {alpha, d_max, kMinDistanceVoxels * distance.spacing};
}

/// The inside voxel whose centre is nearest `p`: searched in growing cubes around p's voxel
/// (points on or near the surface find one within a few voxels), else over all inside voxels.
Eigen::Vector3i nearest_inside(const Mask& mask, const Eigen::Vector3d& p)
{
  Eigen::Vector3i best(-1, -1, -1);
  double best_d = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3i& v) {
    const double d = (mask.point_of(v) - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = v;
    }
  };
  const Eigen::Vector3i c = mask.voxel_coordinates(p).array().round().cast<int>();
  for (int r = 1; r <= 4 && best.x() < 0; ++r) {
    // A voxel found within radius r may still lose to one in radius r + 1: search one more.
    for (int rr = r; rr <= r + 1; ++rr)
      for (int k = c.z() - rr; k <= c.z() + rr; ++k)
        for (int j = c.y() - rr; j <= c.y() + rr; ++j)
          for (int i = c.x() - rr; i <= c.x() + rr; ++i)
            if (mask.contains(i, j, k) && mask(i, j, k))
              consider({i, j, k});
  }
  if (best.x() < 0)
    mask.for_each_stored([&](const Eigen::Vector3i& v, std::uint8_t inside) {
      if (inside)
        consider(v);
    });
  if (best.x() < 0)
    fail("the voxel image has no inside voxel");
  return best;
}

/// The inside voxels nearest each point, as linear indices, sorted, without repeats.
std::vector<std::size_t> nearest_inside_voxels(const Mask& mask, const Points& points)
{
  std::vector<std::size_t> voxels;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3i v = nearest_inside(mask, points.row(i).transpose());
    voxels.push_back(mask.index(v.x(), v.y(), v.z()));
  }
  std::sort(voxels.begin(), voxels.end());
  voxels.erase(std::unique(voxels.begin(), voxels.end()), voxels.end());
  return voxels;
}

/// Marks a voxel Dijkstra has not reached.
constexpr std::uint8_t kNoStep = 255;

/// Dijkstra's result from one source over the inside voxels, stored sparsely on the mask's
/// bricks: the path cost and the step back towards the source (an index into
/// neighbourhood_26()), 5 bytes per stored voxel.
struct ShortestPaths {
  Eigen::Vector3i source = Eigen::Vector3i::Zero(); // Eigen leaves a default vector unset
  ScalarGrid cost;
  Grid<std::uint8_t> step_back;
  bool reaches(const Eigen::Vector3i& v) const { return v == source || step_back(v) != kNoStep; }
};

/// Minimal-cost paths over the inside voxels of `mask` (26-neighbourhood, eq. 25's step costs)
/// from `source`: Dijkstra with a binary heap of (cost, voxel) entries; entries made stale by a
/// cheaper path are skipped when they come up. No graph is stored: a voxel's neighbours are
/// looked up in the mask.
ShortestPaths shortest_paths(const Mask& mask, const ScalarGrid& distance,
                             const Eigen::Vector3i& source, const CostModel& model)
{
  ShortestPaths result{source,
                       ScalarGrid::with_bricks_of(mask, std::numeric_limits<float>::infinity()),
                       Grid<std::uint8_t>::with_bricks_of(mask, kNoStep)};
  const std::vector<Eigen::Vector3i>& offsets = neighbourhood_26();
  std::vector<double> lengths;
  for (const Eigen::Vector3i& o : offsets)
    lengths.push_back(mask.spacing * o.cast<double>().norm());
  using Entry = std::pair<float, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  *result.cost.find(source.x(), source.y(), source.z()) = 0.0f;
  queue.push({0.0f, mask.index(source.x(), source.y(), source.z())});
  while (!queue.empty()) {
    const auto [cost, index] = queue.top();
    queue.pop();
    const Eigen::Vector3i a = mask.ijk(index);
    if (cost > result.cost(a))
      continue; // stale
    const double d_a = distance(a);
    for (std::size_t n = 0; n < offsets.size(); ++n) {
      const Eigen::Vector3i b = a + offsets[n];
      if (!mask.contains(b) || !mask(b))
        continue;
      const float through_a = cost + static_cast<float>(model.step(lengths[n], d_a, distance(b)));
      float* cost_b = result.cost.find(b.x(), b.y(), b.z());
      if (through_a < *cost_b) {
        *cost_b = through_a;
        *result.step_back.find(b.x(), b.y(), b.z()) = static_cast<std::uint8_t>(n);
        queue.push({through_a, mask.index(b.x(), b.y(), b.z())});
      }
    }
  }
  return result;
}

/// Among `voxels` (linear indices), the reachable one of largest path cost.
Eigen::Vector3i farthest(const Mask& mask, const ShortestPaths& paths,
                         const std::vector<std::size_t>& voxels)
{
  Eigen::Vector3i best = mask.ijk(voxels.front());
  float best_cost = -1.0f;
  for (std::size_t index : voxels) {
    const Eigen::Vector3i v = mask.ijk(index);
    if (paths.reaches(v) && paths.cost(v) > best_cost) {
      best_cost = paths.cost(v);
      best = v;
    }
  }
  return best;
}

/// The voxels from `voxel` back to the source of `paths`, both included.
std::vector<Eigen::Vector3i> path_to_source(const ShortestPaths& paths, Eigen::Vector3i voxel)
{
  std::vector<Eigen::Vector3i> result{voxel};
  while (voxel != paths.source) {
    voxel -= neighbourhood_26()[paths.step_back(voxel)];
    result.push_back(voxel);
  }
  return result;
}

double segment_cost(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const ScalarGrid& distance,
                    const CostModel& model, bool* leaves_shape = nullptr)
{
  const double length = (b - a).norm();
  const int samples = std::max(1, static_cast<int>(std::ceil(4.0 * length / distance.spacing)));
  double cost = 0.0;
  double d_prev = interpolate(distance, a);
  for (int s = 1; s <= samples; ++s) {
    const double d = interpolate(distance, a + (b - a) * (static_cast<double>(s) / samples));
    if (leaves_shape && d <= 0.0)
      *leaves_shape = true;
    cost += model.step(length / samples, d_prev, d);
    d_prev = d;
  }
  return cost;
}

/// Greedy string pulling: from each kept point, jump to the farthest later point whose straight
/// segment stays inside and costs no more than the path it replaces.
std::vector<Eigen::Vector3d> pull_string(const std::vector<Eigen::Vector3d>& path,
                                         const ScalarGrid& distance, const CostModel& model)
{
  std::vector<double> prefix(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i)
    prefix[i] = prefix[i - 1] + segment_cost(path[i - 1], path[i], distance, model);
  std::vector<Eigen::Vector3d> result{path.front()};
  std::size_t i = 0;
  while (i + 1 < path.size()) {
    std::size_t next = i + 1;
    for (std::size_t j = i + 2; j < path.size(); ++j) {
      bool leaves = false;
      const double cost = segment_cost(path[i], path[j], distance, model, &leaves);
      if (leaves)
        break; // out of sight: farther points are reached through a later corner
      if (cost <= prefix[j] - prefix[i])
        next = j;
    }
    result.push_back(path[next]);
    i = next;
  }
  return result;
}

std::vector<Eigen::Vector3d> resample(const std::vector<Eigen::Vector3d>& line, double step)
{
  std::vector<double> arc(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i)
    arc[i] = arc[i - 1] + (line[i] - line[i - 1]).norm();
  const int count = std::max(2, static_cast<int>(std::round(arc.back() / step)) + 1);
  std::vector<Eigen::Vector3d> result;
  std::size_t segment = 0;
  for (int k = 0; k < count; ++k) {
    const double s = arc.back() * k / (count - 1);
    while (segment + 2 < line.size() && arc[segment + 1] < s)
      ++segment;
    const double span = arc[segment + 1] - arc[segment];
    const double f = span > 0.0 ? std::clamp((s - arc[segment]) / span, 0.0, 1.0) : 0.0;
    result.push_back(line[segment] + f * (line[segment + 1] - line[segment]));
  }
  return result;
}

/// Eq. 25 along a polyline by the midpoint rule.
double line_energy(const std::vector<Eigen::Vector3d>& line, const ScalarGrid& distance,
                   const CostModel& model)
{
  double energy = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    energy += (line[i + 1] - line[i]).norm() *
              model.density(interpolate(distance, 0.5 * (line[i] + line[i + 1])));
  return energy;
}

/// Moves the interior points, perpendicular to the line, downhill on eq. 25 (gradient descent
/// with an adaptive step, ends fixed): the string-pulled path's corners sit on voxel centres;
/// this smooths it towards the ridge of the interpolated distance.
void relax(std::vector<Eigen::Vector3d>& line, const ScalarGrid& distance, const CostModel& model,
           int iterations)
{
  if (line.size() < 3)
    return;
  const double h = 0.1 * distance.spacing; // finite-difference step for grad d
  auto density_gradient = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3d g;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(a);
      g[a] = (model.density(interpolate(distance, p + e)) -
              model.density(interpolate(distance, p - e))) /
             (2 * h);
    }
    return g;
  };
  double energy = line_energy(line, distance, model);
  double step = 0.0;
  for (int it = 0; it < iterations; ++it) {
    std::vector<Eigen::Vector3d> gradient(line.size(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Eigen::Vector3d e = line[i + 1] - line[i];
      const double length = e.norm();
      if (length == 0.0)
        continue;
      const Eigen::Vector3d mid = 0.5 * (line[i] + line[i + 1]);
      const double w = model.density(interpolate(distance, mid));
      const Eigen::Vector3d half_grad_w = 0.5 * length * density_gradient(mid);
      gradient[i] += -w * e / length + half_grad_w;
      gradient[i + 1] += w * e / length + half_grad_w;
    }
    // Only motion across the line counts: sliding along it changes nothing but the spacing.
    double largest = 0.0;
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      const Eigen::Vector3d t = (line[i + 1] - line[i - 1]).normalized();
      gradient[i] -= gradient[i].dot(t) * t;
      largest = std::max(largest, gradient[i].norm());
    }
    if (largest == 0.0)
      return;
    if (step == 0.0)
      step = 0.1 * distance.spacing / largest;
    // Backtrack until the energy drops and every point stays inside.
    for (int tries = 0; tries < 20; ++tries) {
      std::vector<Eigen::Vector3d> trial = line;
      bool inside = true;
      for (std::size_t i = 1; i + 1 < line.size() && inside; ++i) {
        trial[i] -= step * gradient[i];
        inside = interpolate(distance, trial[i]) > 0.0;
      }
      const double trial_energy = inside ? line_energy(trial, distance, model) : energy;
      if (inside && trial_energy < energy) {
        const bool converged = energy - trial_energy < 1e-7 * energy;
        line.swap(trial);
        energy = trial_energy;
        step *= 1.5;
        if (converged)
          return;
        break;
      }
      step *= 0.5;
      if (tries == 19)
        return;
    }
  }
}

/// Extends the line beyond its last point along its end direction until it meets the surface
/// (the zero of the signed distance), in steps of `step`.
void extend_end(std::vector<Eigen::Vector3d>& line, const ScalarGrid& distance, double step)
{
  const std::size_t back = std::min<std::size_t>(3, line.size() - 1);
  const Eigen::Vector3d direction = (line.back() - line[line.size() - 1 - back]).normalized();
  if (!direction.allFinite())
    return;
  const double limit = distance.spacing * distance.dims.cast<double>().norm();
  Eigen::Vector3d p = line.back();
  for (double travelled = 0.0; travelled < limit; travelled += step) {
    const Eigen::Vector3d q = p + step * direction;
    if (interpolate(distance, q) <= 0.0) {
      // Bisect for the crossing between p (inside) and q (outside).
      Eigen::Vector3d inside = p, outside = q;
      for (int i = 0; i < 30; ++i) {
        const Eigen::Vector3d mid = 0.5 * (inside + outside);
        (interpolate(distance, mid) > 0.0 ? inside : outside) = mid;
      }
      if ((inside - line.back()).norm() > 0.25 * step)
        line.push_back(inside);
      return;
    }
    line.push_back(q);
    p = q;
  }
}

} // namespace

Span parse_span(const std::string& name)
{
  if (name == "means")
    return Span::means;
  if (name == "attachments")
    return Span::attachments;
  fail("unknown centerline span '{}' (use 'means' or 'attachments')", name);
}

std::string to_string(Span span)
{
  return span == Span::means ? "means" : "attachments";
}

double path_cost(const Points& points, const ScalarGrid& distance, double alpha)
{
  const CostModel model = cost_model(distance, alpha);
  double cost = 0.0;
  for (Eigen::Index i = 1; i < points.rows(); ++i)
    cost += segment_cost(points.row(i - 1).transpose(), points.row(i).transpose(), distance, model);
  return cost;
}

Centerline extract(const Mask& mask, const ScalarGrid& distance, const Points& start_area,
                   const Points& end_area, const Parameters& parameters)
{
  if (!(parameters.alpha >= 0.0 && parameters.alpha <= 1.0))
    fail("centerline alpha must lie in [0, 1], got {}", parameters.alpha);
  if (start_area.rows() == 0 || end_area.rows() == 0)
    fail("the centerline needs two non-empty attachment areas");
  const CostModel model = cost_model(distance, parameters.alpha);

  Eigen::Vector3i start_voxel = nearest_inside(mask, start_area.colwise().mean().transpose());
  Eigen::Vector3i end_voxel = nearest_inside(mask, end_area.colwise().mean().transpose());
  if (start_voxel == end_voxel)
    fail("the two attachment areas map to the same voxel: no centerline between them");
  Progress progress("centerline (Dijkstra)", parameters.span == Span::attachments ? 4 : 1);
  ShortestPaths from_start = shortest_paths(mask, distance, start_voxel, model);
  progress.advance();
  if (!from_start.reaches(end_voxel)) {
    const Eigen::Vector3d a = mask.point_of(start_voxel), b = mask.point_of(end_voxel);
    fail("the attachment areas cannot be connected inside the ligament: the voxels nearest them, "
         "at ({:.2f}, {:.2f}, {:.2f}) and ({:.2f}, {:.2f}, {:.2f}) mm, lie in different parts of "
         "the voxel image (try a smaller voxel spacing)",
         a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
  }

  // Voxel path from the start to the end, in order.
  std::vector<Eigen::Vector3i> voxels;
  float path_cost = 0.0f;
  if (parameters.span == Span::attachments) {
    // Through the whole areas: the end is the end area's voxel farthest along the shape (path
    // length inside it, alpha = 0: the medial term would favour voxels at the surface) from the
    // start; the start is the start area's voxel farthest from that end.
    from_start = ShortestPaths{}; // one result in memory at a time
    const CostModel length_only{0.0, model.d_max, model.d_min};
    end_voxel = farthest(mask, shortest_paths(mask, distance, start_voxel, length_only),
                         nearest_inside_voxels(mask, end_area));
    progress.advance();
    start_voxel = farthest(mask, shortest_paths(mask, distance, end_voxel, length_only),
                           nearest_inside_voxels(mask, start_area));
    progress.advance();
    const ShortestPaths from_end = shortest_paths(mask, distance, end_voxel, model);
    progress.advance();
    voxels = path_to_source(from_end, start_voxel);
    path_cost = from_end.cost(start_voxel);
  } else {
    voxels = path_to_source(from_start, end_voxel);
    std::reverse(voxels.begin(), voxels.end());
    path_cost = from_start.cost(end_voxel);
  }
  progress.finish();

  Centerline result;
  result.start_voxel = start_voxel;
  result.end_voxel = end_voxel;
  result.path_cost = path_cost;
  result.voxel_path = voxels;
  std::vector<Eigen::Vector3d> path;
  for (const Eigen::Vector3i& voxel : voxels)
    path.push_back(mask.point_of(voxel));

  if (parameters.refine && path.size() > 2)
    path = pull_string(path, distance, model);
  const double step =
      parameters.point_spacing_mm > 0.0 ? parameters.point_spacing_mm : mask.spacing;
  std::vector<Eigen::Vector3d> line = resample(path, step);
  if (parameters.refine)
    relax(line, distance, model, parameters.relax_iterations);
  if (parameters.extend_to_surface) {
    extend_end(line, distance, step);
    std::reverse(line.begin(), line.end());
    extend_end(line, distance, step);
    std::reverse(line.begin(), line.end());
    line = resample(line, step);
  }
  for (int pass = 0; pass < parameters.smoothing_passes; ++pass) {
    std::vector<Eigen::Vector3d> smoothed = line;
    for (std::size_t i = 1; i + 1 < line.size(); ++i)
      smoothed[i] = 0.5 * line[i] + 0.25 * (line[i - 1] + line[i + 1]);
    line.swap(smoothed);
  }

  const auto n = static_cast<Eigen::Index>(line.size());
  result.points.resize(n, 3);
  result.tangents.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    result.points.row(i) = line[i].transpose();
    const Eigen::Vector3d t = line[std::min<std::size_t>(i + 1, line.size() - 1)] -
                              line[std::max<Eigen::Index>(i - 1, 0)];
    result.tangents.row(i) = t.normalized().transpose();
  }
  for (Eigen::Index i = 1; i < n; ++i)
    result.length_mm += (result.points.row(i) - result.points.row(i - 1)).norm();
  return result;
}

} // namespace ligsim::centerline
