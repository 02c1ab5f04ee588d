#include "filum/visual/obstacle_model.hpp"

#include <algorithm>

#include <Eigen/Geometry>

#include "filum/collision/triangle_mesh_surface.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/visual/sphere_mesh.hpp"

namespace filum::visual {

using Kind = collision::ObstacleShape::Kind;

ObstacleModel::ObstacleModel(Options options) : options_(std::move(options)), unit_(unitSphere(options_.resolution)) {}

ObstacleModel::ObstacleModel(const collision::Obstacle& obstacle) : ObstacleModel(Options{}) {
  obstacle_ = &obstacle;
  setMaterial(defaultMaterial(obstacle.shape()));
}

std::unique_ptr<ObstacleModel> ObstacleModel::fromParams(const Params& p) {
  Options o;
  o.obstacle = p.string("obstacle", "");
  // Even: a ring on the equator, where a capsule's cylinder joins its two caps.
  o.resolution = 2 * (p.integer("resolution", 2, 256, o.resolution, "latitude rings: 256 are finer than any pixel") / 2);
  auto model = std::make_unique<ObstacleModel>(o);
  // The kind's default is not known before init (the obstacle is found then): a colour given
  // here is kept, a missing one takes the kind's default at init.
  // An X-ray opacity given alone keeps the kind's colours (and is kept over them at init).
  const Material given = Material::fromParams(p, Material{});
  if (p.has("color") || p.has("opacity")) model->setMaterial(given);
  model->explicit_material_ = p.has("color") || p.has("opacity");
  model->xray_opacity_ = given.xray_opacity;
  return model;
}

Material ObstacleModel::defaultMaterial(const collision::ObstacleShape& shape) {
  switch (shape.kind) {
    case Kind::kPlane: return Material{Vec3(0.80, 0.78, 0.72), 1.0};
    case Kind::kSphere:
    case Kind::kCapsule: return Material{Vec3(0.70, 0.70, 0.75), 1.0};
    case Kind::kMesh: return Material{Vec3(0.85, 0.55, 0.50), shape.cavity ? 0.3 : 1.0};
    case Kind::kNone: break;
  }
  return Material{};
}

void ObstacleModel::init(const Scene& scene) {
  scene_ = &scene;
  if (!obstacle_) {
    const Node* owner = node();
    std::vector<collision::Obstacle*> candidates;
    if (owner) owner->collect(candidates, false);
    std::string names;
    for (const collision::Obstacle* o : candidates) {
      names += (names.empty() ? "" : ", ") + ("\"" + o->name() + "\"");
      if (options_.obstacle.empty() ? candidates.size() == 1 : o->name() == options_.obstacle) obstacle_ = o;
    }
    if (!obstacle_)
      throw SceneError(origin() + "/obstacle",
                       options_.obstacle.empty() ? "exactly one obstacle in the node (or \"obstacle\": its name)"
                                                 : "the name of an obstacle of the same node",
                       (options_.obstacle.empty() ? "" : "\"" + options_.obstacle + "\"; ") +
                           (names.empty() ? std::string("the node has no obstacle") : "its obstacles: " + names));
    if (!explicit_material_) {
      Material m = defaultMaterial(obstacle_->shape());
      m.xray_opacity = xray_opacity_;
      setMaterial(m);
    }
  }
  build(obstacle_->shapeAt(scene.state().time), scene.state());
}

void ObstacleModel::update(const SceneState& s) {
  const collision::ObstacleShape shape = obstacle_->shapeAt(s.time);
  // Only a moving primitive changes; a plane's patch and a mesh are built once.
  const bool moved = shape.kind != drawn_.kind || shape.a != drawn_.a || shape.b != drawn_.b ||
                     shape.radius != drawn_.radius || shape.normal != drawn_.normal || shape.mesh != drawn_.mesh;
  if (moved || !built_) build(shape, s);
}

void ObstacleModel::build(const collision::ObstacleShape& shape, const SceneState& s) {
  drawn_ = shape;
  built_ = true;
  mesh_ = TriangleMesh{};
  switch (shape.kind) {
    case Kind::kPlane: buildPlane(shape, s); break;
    case Kind::kSphere: appendSphere(unit_, shape.a, shape.radius, mesh_); break;
    case Kind::kCapsule: {
      // The unit sphere's southern half at a, its northern half at b, in a frame whose z is the
      // axis: the band between the equator ring and the ring below it becomes the cylinder.
      // Normals are the sphere's (radial on the cylinder's rings, exact on the caps).
      const Vec3 axis = shape.b - shape.a;
      const Eigen::Matrix3d R =
          axis.norm() > 0.0 ? Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix()
                            : Eigen::Matrix3d::Identity();
      mesh_ = unit_;
      for (int i = 0; i < mesh_.vertexCount(); ++i) {
        const Vec3 n = R * unit_.normals.row(i).transpose();
        const Vec3 end = unit_.vertices(i, 2) >= 0.0 ? shape.b : shape.a;
        mesh_.vertices.row(i) = (end + shape.radius * n).transpose();
        mesh_.normals.row(i) = n.transpose();
      }
      break;
    }
    case Kind::kMesh: {
      const auto& triangles = shape.mesh->triangles();
      mesh_.vertices = shape.mesh->vertices();
      mesh_.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
      for (std::size_t f = 0; f < triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) mesh_.triangles(static_cast<Eigen::Index>(f), k) = triangles[f][k];
      computeVertexNormals(mesh_);
      break;
    }
    case Kind::kNone: break;
  }
}

void ObstacleModel::buildPlane(const collision::ObstacleShape& shape, const SceneState& s) {
  // The bodies' points: the first 3N entries of q, N the points of every body.
  Vec3 lower = shape.a, upper = shape.a;
  bool any = false;
  for (const MechanicalState* body : scene_->bodies())
    for (int i = 0; i < body->pointCount(); ++i) {
      const int k = 3 * (body->offset() + i);
      if (k + 2 >= s.q.size()) break;
      const Vec3 x = s.q.segment<3>(k);
      lower = any ? Vec3(lower.cwiseMin(x)) : x;
      upper = any ? Vec3(upper.cwiseMax(x)) : x;
      any = true;
    }
  const Vec3 n = shape.normal.normalized();
  const Vec3 middle = 0.5 * (lower + upper);
  const Vec3 centre = middle - n.dot(middle - shape.a) * n;  // projected onto the plane
  // Half the side: the bodies' extent (at least 5 cm, a hand's width of table around a suture).
  const double half = std::max((upper - lower).norm(), 0.05);
  const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
  mesh_.vertices.resize(4, 3);
  mesh_.normals.resize(4, 3);
  const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int i = 0; i < 4; ++i) {
    mesh_.vertices.row(i) = (centre + half * (corners[i][0] * u + corners[i][1] * w)).transpose();
    mesh_.normals.row(i) = n.transpose();
  }
  mesh_.triangles.resize(2, 3);
  mesh_.triangles << 0, 1, 2, 0, 2, 3;  // counter-clockwise seen from the normal's side (u × w = n)
}

}  // namespace filum::visual
