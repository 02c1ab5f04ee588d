// The interaction tool's sphere as a visual model (the tool itself — its push and grasp forces —
// is haptics/tool.hpp, driven by `filum view`'s mouse or by a haptic device): drawn while it
// touches the scene, red when it pushes, green when its jaws hold a point.
#pragma once

#include <memory>

#include "filum/haptics/tool.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class ProbeVisual final : public VisualModel {
 public:
  explicit ProbeVisual(std::shared_ptr<const haptics::ToolState> tool);
  std::string typeName() const override { return "ProbeVisual"; }
  bool needsBody() const override { return false; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  std::shared_ptr<const haptics::ToolState> tool_;
  TriangleMesh unit_, mesh_;
};

}  // namespace filum::visual
