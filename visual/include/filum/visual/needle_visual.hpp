// NeedleVisual: a curved needle (haptics/needle.hpp) as drawn — its wire as a tube of round-capped
// cylinders along the arc, steel, where the needle is at the last step's start.
#pragma once

#include "filum/haptics/needle.hpp"
#include "filum/visual/generalized_cylinder.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class NeedleVisual final : public VisualModel {
 public:
  explicit NeedleVisual(const haptics::Needle& needle);
  std::string typeName() const override { return "NeedleVisual"; }
  /// X-ray: steel.
  double defaultXrayOpacity() const override { return 0.95; }
  bool needsBody() const override { return false; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return cylinder_.mesh(); }

 private:
  static constexpr int kRings = 24;  // samples along the arc
  const haptics::Needle& needle_;
  GeneralizedCylinder cylinder_;
};

}  // namespace filum::visual
