#include "filum/geometry/vessel_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/mesh_units.hpp"

namespace filum::geometry {

namespace {

/// The polynomial smooth maximum of blend width k and its weight on a (header).
double smoothMax(double a, double b, double k, double& weight_a) {
  if (!(k > 0.0) || std::abs(a - b) >= k) {
    weight_a = a >= b ? 1.0 : 0.0;
    return std::max(a, b);
  }
  const double h = (k - std::abs(a - b)) / k;
  weight_a = std::clamp(0.5 + (a - b) / (2.0 * k), 0.0, 1.0);
  return std::max(a, b) + h * h * k / 4.0;
}

}  // namespace

VesselTree::VesselTree(std::vector<Branch> branches, double blend) : branches_(std::move(branches)), blend_(blend) {
  if (!(blend >= 0.0) || !std::isfinite(blend)) throw std::invalid_argument("the blend width must be >= 0");
  if (branches_.empty()) throw std::invalid_argument("a vessel tree needs at least one branch");
  branch_first_.push_back(0);
  for (int b = 0; b < branchCount(); ++b) {
    const Branch& branch = branches_[b];
    const int m = static_cast<int>(branch.points.rows());
    const std::string name = "branch " + std::to_string(b) + " (\"" + branch.name + "\")";
    if (m < 2 || branch.radii.size() != m)
      throw std::invalid_argument(name + ": expected at least 2 points, each with a radius");
    for (int i = 0; i < m; ++i) {
      if (!(branch.radii[i] > 0.0) || !std::isfinite(branch.radii[i]) || !branch.points.row(i).allFinite())
        throw std::invalid_argument(name + ", point " + std::to_string(i) + ": expected finite coordinates and a radius > 0");
      max_radius_ = std::max(max_radius_, branch.radii[i]);
      bounds_.extend(Vec3(branch.points.row(i).transpose()));
    }
    for (int i = 0; i + 1 < m; ++i) {
      Segment s;
      s.a = branch.points.row(i).transpose();
      s.d = branch.points.row(i + 1).transpose() - s.a;
      const double length2 = s.d.squaredNorm();
      if (!(length2 > 0.0))
        throw std::invalid_argument(name + ", points " + std::to_string(i) + " and " + std::to_string(i + 1) +
                                    ": expected distinct consecutive points, found the same point twice");
      s.inv_length2 = 1.0 / length2;
      s.ra = branch.radii[i];
      s.dr = branch.radii[i + 1] - branch.radii[i];
      s.open_before = i == 0 && branch.open_start;
      s.open_after = i + 2 == m && branch.open_end;
      s.centre = s.a + 0.5 * s.d;
      s.cull_radius = 0.5 * std::sqrt(length2) + std::max(branch.radii[i], branch.radii[i + 1]);
      segments_.push_back(s);
    }
    branch_first_.push_back(static_cast<int>(segments_.size()));
  }
  bounds_.min().array() -= max_radius_;
  bounds_.max().array() += max_radius_;
}

double VesselTree::segmentValue(const Segment& s, const Vec3& x, bool capped, Vec3& gradient) {
  // t of the axis point nearest x, clamped to the segment except across an open end.
  const double raw = (x - s.a).dot(s.d) * s.inv_length2;
  const double t = std::clamp(raw, s.open_before ? -std::numeric_limits<double>::infinity() : 0.0,
                              s.open_after ? std::numeric_limits<double>::infinity() : 1.0);
  const Vec3 away = x - (s.a + t * s.d);
  const double distance = away.norm();
  // Beyond an open end the tube keeps the end's radius.
  const double along = std::clamp(t, 0.0, 1.0);
  const double radius = s.ra + along * s.dr;
  // ∇φ_k = r'(t) ∇t − (x − c)/|x − c|, ∇t = d/|d|² while t is inside the segment (0 where clamped).
  gradient = distance > 0.0 ? Vec3(-away / distance) : Vec3::Zero();
  if (t > 0.0 && t < 1.0) gradient += (s.dr * s.inv_length2) * s.d;
  double value = radius - distance;
  // Capped: an open end cut flat by its end plane, φ = min(φ, distance to the plane on the inner side).
  if (capped && ((s.open_after && raw > 0.5) || (s.open_before && raw <= 0.5))) {
    const double length = 1.0 / std::sqrt(s.inv_length2);
    const bool after = s.open_after && raw > 0.5;
    const double plane = after ? (1.0 - raw) * length : raw * length;
    if (plane < value) {
      value = plane;
      gradient = (after ? -1.0 : 1.0) * s.d / length;
    }
  }
  return value;
}

bool VesselTree::branchField(int b, const Vec3& x, double cull, bool capped, double& value, Vec3& gradient) const {
  bool any = false;
  for (int k = branch_first_[b]; k < branch_first_[b + 1]; ++k) {
    const Segment& s = segments_[k];
    // φ_k <= cull_radius − |x − centre| for a closed segment: skip it when that is below −cull.
    if (!s.open_before && !s.open_after && (x - s.centre).norm() > s.cull_radius + cull) continue;
    Vec3 g;
    const double v = segmentValue(s, x, capped, g);
    if (!any || v > value) {
      value = v;
      gradient = g;
      any = true;
    }
  }
  return any;
}

VesselTree::Sample VesselTree::sample(const Vec3& x, double reach, bool capped) const {
  // The smooth maximum of the largest two branch fields (header): symmetric in the branches, at
  // most k/4 above the plain maximum, and exact to cull — a branch below −(reach + k) is more than
  // k below any field above −reach, so it is neither of the largest two where φ > −reach matters,
  // or, if it is the second, more than k below the first and adds no bump.
  const double cull = std::max(reach, 0.0) + blend_;
  double first = -std::numeric_limits<double>::infinity(), second = first;
  Vec3 first_gradient = Vec3::Zero(), second_gradient = Vec3::Zero();
  Sample out;
  for (int b = 0; b < branchCount(); ++b) {
    double v;
    Vec3 g;
    if (!branchField(b, x, cull, capped, v, g) || v < -cull) continue;
    if (v > first) {
      second = first;
      second_gradient = first_gradient;
      first = v;
      first_gradient = g;
      out.branch = b;
    } else if (v > second) {
      second = v;
      second_gradient = g;
    }
  }
  if (out.branch < 0) {
    out.value = -cull;
    return out;
  }
  double w = 1.0;
  out.value = second > -std::numeric_limits<double>::infinity() ? smoothMax(first, second, blend_, w) : first;
  out.gradient = w * first_gradient + (1.0 - w) * second_gradient;
  return out;
}

double VesselTree::branchValue(int b, const Vec3& x) const {
  double v = -std::numeric_limits<double>::infinity();
  Vec3 g;
  branchField(b, x, std::numeric_limits<double>::infinity(), false, v, g);
  return v;
}

int VesselTree::branchAt(const Vec3& x, double reach) const { return sample(x, reach).branch; }

int VesselTree::branchIndex(const std::string& name) const {
  for (int b = 0; b < branchCount(); ++b)
    if (branches_[b].name == name) return b;
  return -1;
}

VesselTree VesselTree::fromParams(const Params& p) {
  const double scale = meshScale(p);  // "units" (and "scale"): metres per unit of the points
  const double blend = scale * p.nonNegative({"blend", "as units"}, 0.0);
  const nlohmann::json& list = p.raw({"branches", "as units"});
  if (!list.is_array() || list.empty())
    p.fail("branches", "a non-empty list of branches {\"name\", \"points\": [[x, y, z, r], ...], \"open\"}");
  if (list.size() > static_cast<std::size_t>(kMaxBranches))
    p.fail("branches", "at most " + std::to_string(kMaxBranches) + " branches (a vessel tree, not a capillary bed)",
           std::to_string(list.size()) + " branches");
  std::vector<Params> items = p.objects("branches");
  std::vector<Branch> branches;
  long total = 0;
  for (const Params& item : items) {
    Branch branch;
    branch.name = item.string("name", "branch " + std::to_string(branches.size()));
    const nlohmann::json& points = item.raw({"points", "as units"});
    if (!points.is_array() || points.size() < 2)
      item.fail("points", "a list of at least 2 centre points [x, y, z, r]");
    total += static_cast<long>(points.size());
    if (total > kMaxPoints)
      item.fail("points", "at most " + std::to_string(kMaxPoints) + " centre points in the whole tree (memory)",
                std::to_string(total) + " so far");
    const int m = static_cast<int>(points.size());
    branch.points.resize(m, 3);
    branch.radii.resize(m);
    for (int i = 0; i < m; ++i) {
      const nlohmann::json& row = points[static_cast<std::size_t>(i)];
      const std::string point = " at point " + std::to_string(i);
      if (!row.is_array() || row.size() != 4)
        item.fail("points", "[x, y, z, r] (a centre point and the lumen's radius there)" + point, describeJson(row));
      for (int c = 0; c < 4; ++c)
        if (!row[static_cast<std::size_t>(c)].is_number() || !std::isfinite(row[static_cast<std::size_t>(c)].get<double>()))
          item.fail("points", "[x, y, z, r] of finite numbers" + point, describeJson(row));
      for (int c = 0; c < 3; ++c) branch.points(i, c) = scale * row[static_cast<std::size_t>(c)].get<double>();
      branch.radii[i] = scale * row[3].get<double>();
      if (!(branch.radii[i] > 0.0)) item.fail("points", "a radius r > 0 (the fourth number)" + point, describeJson(row));
      if (i > 0 && branch.points.row(i) == branch.points.row(i - 1))
        item.fail("points", "a point distinct from the one before it" + point, describeJson(row));
    }
    if (item.has("open")) {
      const nlohmann::json& open = item.raw("open");
      if (!open.is_array()) item.fail("open", "a list of the ends that are open: [\"start\"], [\"end\"] or both");
      for (const nlohmann::json& end : open) {
        if (end == "start") branch.open_start = true;
        else if (end == "end") branch.open_end = true;
        else item.fail("open", "ends named \"start\" or \"end\"", end.dump());
      }
    }
    item.finish();
    branches.push_back(std::move(branch));
  }
  return VesselTree(std::move(branches), blend);
}

VesselTree VesselTree::read(const std::string& path) {
  const nlohmann::json document = readJsonFile(path);
  if (!document.is_object()) throw SceneError(path, "a JSON object {\"units\", \"blend\", \"branches\"}", describeJson(document));
  const Params p(document, path, "", "vessel tree");
  VesselTree tree = fromParams(p);
  p.finish();
  return tree;
}

}  // namespace filum::geometry
