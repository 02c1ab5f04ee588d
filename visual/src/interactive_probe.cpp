#include "filum/visual/interactive_probe.hpp"

#include "filum/visual/sphere_mesh.hpp"

namespace filum::visual {

ProbeVisual::ProbeVisual(std::shared_ptr<const haptics::ToolState> tool) : tool_(std::move(tool)), unit_(unitSphere(12)) {
  setName("probe");
}

void ProbeVisual::update(const SceneState&) {
  mesh_ = TriangleMesh{};
  mesh_.vertices.resize(0, 3);
  mesh_.normals.resize(0, 3);
  mesh_.triangles.resize(0, 3);
  if (!tool_->touching && !tool_->grasping) return;
  setMaterial(Material{tool_->grasping ? Vec3(0.2, 0.75, 0.3) : Vec3(0.9, 0.2, 0.15), 0.6});
  appendSphere(unit_, tool_->position, tool_->radius, mesh_);
}

}  // namespace filum::visual
