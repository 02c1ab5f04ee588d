#include "filum/visual/instrument_visual.hpp"

namespace filum::visual {

namespace {

Vec3 jawColor(haptics::InstrumentKind kind) {
  switch (kind) {
    case haptics::InstrumentKind::kScissors: return {0.78, 0.62, 0.30};
    case haptics::InstrumentKind::kBipolarForceps: return {0.45, 0.55, 0.75};
    case haptics::InstrumentKind::kNeedleHolder: return {0.85, 0.72, 0.25};  // gold handles: tungsten carbide jaws
    case haptics::InstrumentKind::kGrasper: break;
  }
  return {0.75, 0.76, 0.78};
}

}  // namespace

InstrumentVisual::InstrumentVisual(const haptics::Instrument& instrument, Part part)
    : instrument_(instrument), part_(part), cylinder_(2, 20, CapStyle::kRound) {
  setName(instrument.name() + (part == Part::kShaft ? " shaft" : " jaws"));
  setMaterial(Material{part == Part::kShaft ? Vec3(0.18, 0.18, 0.2) : jawColor(instrument.kind()), 1.0});
}

void InstrumentVisual::appendCapsule(const haptics::Capsule& c, TriangleMesh& out) {
  const Vec3 axis = c.b - c.a;
  if (!(axis.norm() > 0.0)) return;
  Points ends(2, 3), tangents(2, 3), curvatures(0, 3);
  ends.row(0) = c.a.transpose();
  ends.row(1) = c.b.transpose();
  tangents.row(0) = tangents.row(1) = axis.normalized().transpose();
  const VecX radii = VecX::Constant(2, c.radius), slopes = VecX::Zero(2);
  const Vec3 any = std::abs(axis.normalized().z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  cylinder_.update(ends, tangents, curvatures, radii, slopes, any);
  const TriangleMesh& part = cylinder_.mesh();
  const int v = out.vertexCount(), f = out.triangleCount();
  out.vertices.conservativeResize(v + part.vertexCount(), 3);
  out.normals.conservativeResize(v + part.vertexCount(), 3);
  out.triangles.conservativeResize(f + part.triangleCount(), 3);
  out.vertices.bottomRows(part.vertexCount()) = part.vertices;
  out.normals.bottomRows(part.vertexCount()) = part.normals;
  out.triangles.bottomRows(part.triangleCount()) = part.triangles.array() + v;
}

void InstrumentVisual::update(const SceneState& s) {
  const haptics::InstrumentSettings& settings = instrument_.settings();
  const haptics::InstrumentPose pose = instrument_.poseAt(s.time);
  const double opening = instrument_.jawAt(s.time);
  mesh_.vertices.resize(0, 3);
  mesh_.normals.resize(0, 3);
  mesh_.triangles.resize(0, 3);
  if (part_ == Part::kShaft) {
    appendCapsule(settings.shape.shaft(pose), mesh_);
    // The trocar's cannula: 3 cm of a sleeve 1.6 times the shaft's radius, centred on the port.
    if (settings.trocar) {
      const Vec3 half = 0.015 * pose.axis();
      appendCapsule({*settings.trocar - half, *settings.trocar + half, 1.6 * settings.shape.shaft_radius}, mesh_);
    }
    return;
  }
  appendCapsule(settings.shape.jaw(pose, opening, 1), mesh_);
  appendCapsule(settings.shape.jaw(pose, opening, -1), mesh_);
  setMaterial(Material{instrument_.holding() ? Vec3(0.3, 0.75, 0.35) : jawColor(instrument_.kind()), 1.0});
}

}  // namespace filum::visual
