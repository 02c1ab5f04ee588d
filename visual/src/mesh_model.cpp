#include "filum/visual/mesh_model.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "filum/geometry/mesh_file.hpp"
#include "filum/geometry/mesh_units.hpp"

namespace filum::visual {

std::unique_ptr<MeshModel> MeshModel::fromParams(const Params& p) {
  const std::string file = p.string("file");
  std::filesystem::path path(file);
  if (path.is_relative()) path = std::filesystem::path(p.file()).parent_path() / path;
  const double scale = geometry::meshScale(p);  // "units" × "scale": metres per unit of the file
  const Vec3 degrees = p.vec3({"rotation", "°"}, Vec3::Zero());
  const Vec3 translation = p.vec3({"translation", "m"}, Vec3::Zero());
  TriangleMesh mesh;
  try {
    mesh = triangleMesh(geometry::readMeshFile(path.string()));
  } catch (const std::runtime_error& e) {
    p.fail("file", "a readable .obj, .off, .ply, .stl or .vtp mesh", std::string("\"") + file + "\" (" + e.what() + ")");
  }
  // x_world = R (scale x) + t, R = Rz Ry Rx; normals turn with R.
  const double k = std::numbers::pi / 180.0;
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(k * degrees.z(), Vec3::UnitZ()) *
                             Eigen::AngleAxisd(k * degrees.y(), Vec3::UnitY()) *
                             Eigen::AngleAxisd(k * degrees.x(), Vec3::UnitX()))
                                .toRotationMatrix();
  mesh.vertices = ((scale * mesh.vertices) * R.transpose()).rowwise() + translation.transpose();
  mesh.normals = mesh.normals * R.transpose();
  auto model = std::make_unique<MeshModel>(std::move(mesh));
  model->setMaterial(Material::fromParams(p, Material{Vec3(0.85, 0.55, 0.5), 1.0}));
  return model;
}

}  // namespace filum::visual
