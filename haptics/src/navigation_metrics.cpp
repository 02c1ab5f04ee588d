#include "filum/haptics/navigation_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/node.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/mechanics/rod_end_frame.hpp"

namespace filum::haptics {

namespace {

/// The node at `path` of the scene, refused at p[key] otherwise.
Node* nodeAt(const Scene& scene, const Params& p, const std::string& key, const std::string& path) {
  Node* node = const_cast<Scene&>(scene).root().find(path);
  if (!node) p.fail(key, "the path of a node of the scene", "\"" + path + "\"");
  return node;
}

/// The names of the tree's branches, for an error that lists them.
std::string branchNames(const geometry::VesselTree& tree) {
  std::string known;
  for (int b = 0; b < tree.branchCount(); ++b) known += (b ? ", " : "") + tree.branch(b).name;
  return known;
}

template <class T>
const T* componentOf(const Node& node) {
  for (const auto& c : node.components())
    if (const auto* found = dynamic_cast<const T*>(c.get())) return found;
  return nullptr;
}

}  // namespace

std::unique_ptr<NavigationMetrics> NavigationMetrics::fromScene(const nlohmann::json& document, const std::string& source,
                                                                const Scene& scene) {
  if (!document.is_object() || !document.contains("navigation")) return nullptr;
  const Params top(document, source, "");
  const Params p = top.object("navigation").withOwner("navigation");
  std::unique_ptr<NavigationMetrics> metrics(new NavigationMetrics());
  metrics->pedal_ = FluoroscopyPedal::fromScene(document, source);
  std::vector<std::string> names;
  if (p.has("instrument")) names.push_back(p.string("instrument"));
  if (p.has("instruments")) {
    const nlohmann::json& list = p.raw("instruments");
    if (!list.is_array() || list.empty() || list.size() > 16)
      p.fail("instruments", "a list of 1 to 16 node paths of instruments (curve bodies)");
    for (const nlohmann::json& name : list) {
      if (!name.is_string()) p.fail("instruments", "node paths (strings)", describeJson(name));
      names.push_back(name.get<std::string>());
    }
  }
  if (names.empty() && !p.has("aneurysm"))
    p.fail("instruments", "the instruments to score: \"instruments\": [node paths] or \"instrument\" (or an \"aneurysm\")");
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const std::string key = i == 0 && p.has("instrument") ? "instrument" : "instruments";
    Node* node = nodeAt(scene, p, key, name);
    const MechanicalState* body = node->mechanicalState();
    if (!body || !body->curve())
      p.fail(key, "instruments that are curve bodies (a rod, a spline)",
             "\"" + name + "\" (no curve body)");
    Instrument m;
    m.name = name;
    m.body = body->curve();
    m.hub_frame = mechanics::RodEndFrame::atStartOf(*node);  // the hub's, not a held tip's
    metrics->instruments_.push_back(m);
  }
  Node* vessels = nodeAt(scene, p, "vessels", p.string("vessels"));
  metrics->lumen_ = componentOf<collision::VesselLumenObstacle>(*vessels);
  if (!metrics->lumen_)
    p.fail("vessels", "the node holding the VesselLumenObstacle", "\"" + p.string("vessels") + "\" (it has none)");
  if (const auto* pipeline = dynamic_cast<const collision::ContactPipeline*>(scene.collisionPipeline()))
    for (std::size_t o = 0; o < pipeline->obstacles().size(); ++o)
      if (pipeline->obstacles()[o] == metrics->lumen_) metrics->lumen_index_ = static_cast<int>(o);
  if (metrics->lumen_index_ < 0)
    p.fail("vessels", "a lumen the scene's ContactPipeline touches (the wall force is measured on its contacts)",
           "\"" + p.string("vessels") + "\" without a \"collision\": {\"type\": \"ContactPipeline\"} block");
  if (p.has("target")) metrics->target_ = p.vec3({"target", "m"});
  if (p.has("target_branch")) {
    const std::string branch = p.string("target_branch");
    metrics->target_branch_ = metrics->lumen_->tree().branchIndex(branch);
    if (metrics->target_branch_ < 0) {
      p.fail("target_branch", "a branch of the vessel tree (" + branchNames(metrics->lumen_->tree()) + ")",
             "\"" + branch + "\"");
    }
  }
  metrics->force_limit_ = p.positive({"force_limit", "N"}, 0.5);
  if (p.has("aneurysm")) metrics->readAneurysm(scene, p.object("aneurysm"));
  if (p.has("device")) p.raw("device");  // the hand's device at the hub: read by HubDevice
  p.finish();
  return metrics;
}

void NavigationMetrics::readAneurysm(const Scene& scene, const Params& a) {
  const geometry::VesselTree& tree = lumen_->tree();
  std::vector<int> branches;
  const auto names = [&](const std::string& key, const std::string& what) {
    const nlohmann::json& list = a.raw(key);
    if (!list.is_array() || list.empty() || list.size() > 64) a.fail(key, "a list of 1 to 64 " + what);
    std::vector<std::string> out;
    for (const nlohmann::json& name : list) {
      if (!name.is_string()) a.fail(key, what, describeJson(name));
      if (std::find(out.begin(), out.end(), name.get<std::string>()) != out.end())
        a.fail(key, what + ", each once", "\"" + name.get<std::string>() + "\" twice");
      out.push_back(name.get<std::string>());
    }
    return out;
  };
  for (const std::string& name : names("branches", "names of the vessel tree's branches (the sac, its neck)")) {
    const int b = tree.branchIndex(name);
    if (b < 0) a.fail("branches", "branches of the vessel tree (" + branchNames(tree) + ")", "\"" + name + "\"");
    if (tree.branch(b).open_start || tree.branch(b).open_end)
      a.fail("branches", "closed branches (a sac, its neck): an open end goes on without end",
             "\"" + name + "\", open at an end");
    branches.push_back(b);
  }
  for (const std::string& name : names("coils", "node paths of the coils (curve bodies)")) {
    const MechanicalState* body = nodeAt(scene, a, "coils", name)->mechanicalState();
    if (!body || !body->curve()) a.fail("coils", "coils that are curve bodies (a rod, a spline)", "\"" + name + "\" (no curve body)");
    coils_.push_back({name, body->curve(), 0.0});
  }
  const double spacing = a.has("spacing") ? a.positive({"spacing", "m"}) : 0.0;
  try {
    packing_ = std::make_unique<CoilPacking>(tree, branches, spacing);
  } catch (const std::invalid_argument& e) {
    // A spacing too coarse or too fine for the grid, or no cell in the aneurysm (its branches lie
    // under the others').
    a.fail(a.has("spacing") ? "spacing" : "branches", "an aneurysm the volume grid can measure", e.what());
  }
  a.finish();
}

void NavigationMetrics::measurePacking(const Scene& scene) {
  if (!packing_) return;
  packing_density_ = 0.0;
  for (Coil& c : coils_) {
    const CoilPacking::Inside inside = packing_->inside(*c.body, scene.state().q);
    c.length_inside = inside.length;
    packing_density_ += packing_->density(inside.volume);
  }
  max_packing_density_ = std::max(max_packing_density_, packing_density_);
}

void NavigationMetrics::measure(const Scene& scene, Instrument& m) const {
  const VecX& q = scene.state().q;
  const Vec3 hub = m.body->position(q, 0.0);
  m.inserted = (hub - m.hub_start).dot(m.axis);
  m.roll = m.hub_frame ? m.hub_frame->roll(scene.state().time) : 0.0;
  m.tip = m.body->position(q, 1.0);
  m.branch = lumen_->tree().branchAt(m.tip, lumen_->tree().maxRadius());
  if (target_) m.target_distance = (m.tip - *target_).norm();
  // Σ |F_c| over this instrument's contacts with the lumen (the last solve's multipliers).
  m.wall_force = m.max_contact_force = 0.0;
  const auto* pipeline = dynamic_cast<const collision::ContactPipeline*>(scene.collisionPipeline());
  if (!pipeline || lumen_index_ < 0) return;
  const collision::ContactSet& contacts = pipeline->contacts();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const collision::Contact& c = contacts[i];
    if (c.obstacle != lumen_index_ || &pipeline->models()[c.model_a]->curve() != m.body) continue;
    const double f = pipeline->contactForce(static_cast<int>(i), scene.state()).norm();
    m.wall_force += f;
    m.max_contact_force = std::max(m.max_contact_force, f);
  }
}

void NavigationMetrics::start(const Scene& scene) {
  for (Instrument& m : instruments_) {
    const VecX& q = scene.state().q;
    m.hub_start = m.body->position(q, 0.0);
    const Vec3 tangent = m.body->tangent(q, 0.0);
    m.axis = tangent.norm() > 0.0 ? Vec3(tangent.normalized()) : Vec3::UnitZ();
    measure(scene, m);
    m.min_target_distance = m.target_distance;
    m.max_inserted = m.inserted;
  }
  measurePacking(scene);
  time_ = scene.state().time;
  writeRow(time_);
}

void NavigationMetrics::afterStep(const Scene& scene, double h) {
  time_ = scene.state().time;
  for (Instrument& m : instruments_) {
    const Vec3 previous_tip = m.tip;
    measure(scene, m);
    m.tip_path += (m.tip - previous_tip).norm();
    m.max_inserted = std::max(m.max_inserted, m.inserted);
    m.max_wall_force = std::max(m.max_wall_force, m.wall_force);
    if (m.wall_force > force_limit_) m.time_above_limit += h;
    if (target_) m.min_target_distance = std::min(m.min_target_distance, m.target_distance);
    if (target_branch_ >= 0 && m.reached_time < 0.0 && m.branch == target_branch_) m.reached_time = time_;
  }
  measurePacking(scene);
  writeRow(time_);
}

void NavigationMetrics::openCsv(const std::string& path) {
  csv_.open(path);
  if (!csv_) throw std::runtime_error(path + ": cannot open for writing");
  csv_ << std::setprecision(9) << "time";
  for (const Instrument& m : instruments_)
    for (const char* column : {"inserted", "roll", "tip_x", "tip_y", "tip_z", "branch", "target_distance", "wall_force",
                               "max_contact_force"})
      csv_ << ',' << m.name << '_' << column;
  if (packing_) {
    for (const Coil& c : coils_) csv_ << ',' << c.name << "_in_aneurysm";
    csv_ << ",packing_density";
  }
  csv_ << '\n';
}

void NavigationMetrics::writeRow(double t) {
  if (!csv_.is_open() || csv_failed_) return;
  csv_ << t;
  const geometry::VesselTree& tree = lumen_->tree();
  static const std::string outside = "outside";
  for (const Instrument& m : instruments_) {
    const std::string& branch = m.branch >= 0 ? tree.branch(m.branch).name : outside;  // no copy in a step
    csv_ << ',' << m.inserted << ',' << m.roll << ',' << m.tip.x() << ',' << m.tip.y() << ',' << m.tip.z() << ','
         << branch << ',' << m.target_distance << ',' << m.wall_force << ',' << m.max_contact_force;
  }
  if (packing_) {
    for (const Coil& c : coils_) csv_ << ',' << c.length_inside;
    csv_ << ',' << packing_density_;
  }
  csv_ << '\n';
  if (!csv_) csv_failed_ = true;
}

nlohmann::json NavigationMetrics::summary() const {
  nlohmann::json out = {{"duration", time_}, {"force_limit", force_limit_}};
  const geometry::VesselTree& tree = lumen_->tree();
  if (target_branch_ >= 0) out["target_branch"] = tree.branch(target_branch_).name;
  if (target_) out["target"] = {target_->x(), target_->y(), target_->z()};
  if (pedal_) out["fluoroscopy_time"] = pedal_->time(time_);
  for (const Instrument& m : instruments_) {
    nlohmann::json i = {{"inserted_length", m.inserted},
                        {"max_inserted_length", m.max_inserted},
                        {"roll", m.roll},
                        {"tip", {m.tip.x(), m.tip.y(), m.tip.z()}},
                        {"tip_branch", m.branch >= 0 ? tree.branch(m.branch).name : std::string("outside")},
                        {"tip_path_length", m.tip_path},
                        {"max_wall_force", m.max_wall_force},
                        {"time_above_force_limit", m.time_above_limit}};
    if (target_) {
      i["target_distance"] = m.target_distance;
      i["min_target_distance"] = m.min_target_distance;
    }
    if (target_branch_ >= 0) {
      i["reached_target_branch"] = m.reached_time >= 0.0;
      if (m.reached_time >= 0.0) i["time_to_target_branch"] = m.reached_time;
    }
    out["instruments"][m.name] = i;
  }
  if (packing_) {
    nlohmann::json a = {{"volume", packing_->volume()},
                        {"packing_density", packing_density_},
                        {"max_packing_density", max_packing_density_}};
    for (const int b : packing_->branches()) a["branches"].push_back(tree.branch(b).name);
    for (const Coil& c : coils_) a["coil_length_inside"][c.name] = c.length_inside;
    out["aneurysm"] = a;
  }
  return out;
}

void NavigationMetrics::writeSummary(const std::string& path) const {
  std::ofstream out(path);
  out << summary().dump(2) << '\n';
  if (!out) throw std::runtime_error(path + ": write failed");
}

std::string NavigationMetrics::text() const {
  std::ostringstream s;
  s << std::setprecision(3);
  const geometry::VesselTree& tree = lumen_->tree();
  for (const Instrument& m : instruments_) {
    s << "  " << m.name << ": inserted " << 1e3 * m.inserted << " mm, roll " << m.roll * 180.0 / M_PI
      << "°, tip in " << (m.branch >= 0 ? tree.branch(m.branch).name : std::string("no branch"));
    if (target_) s << ", " << 1e3 * m.target_distance << " mm from the target";
    if (target_branch_ >= 0)
      s << (m.reached_time >= 0.0 ? ", reached " + tree.branch(target_branch_).name + " at t = " + [&] {
              std::ostringstream t;
              t << std::setprecision(3) << m.reached_time;
              return t.str();
            }() + " s"
                                  : ", did not reach " + tree.branch(target_branch_).name);
    s << "; wall force max " << m.max_wall_force << " N, " << m.time_above_limit << " s above " << force_limit_
      << " N; tip path " << 1e3 * m.tip_path << " mm\n";
  }
  if (pedal_) s << "  fluoroscopy time " << pedal_->time(time_) << " s of " << time_ << " s\n";
  if (packing_) {
    double inside = 0.0;
    for (const Coil& c : coils_) inside += c.length_inside;
    s << "  aneurysm " << 1e9 * packing_->volume() << " mm³: coil inside " << 1e3 * inside << " mm, packing density "
      << 100.0 * packing_density_ << " % (largest " << 100.0 * max_packing_density_ << " %)\n";
  }
  return s.str();
}

}  // namespace filum::haptics
