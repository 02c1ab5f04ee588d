// WoundVisual: a wound's lips (haptics/wound.hpp) as drawn — each lip the slab beside its edge
// curve that the wound's geometry uses, P + (u − r_e) ô − (v − r_e) n̂ for u ∈ [0, width] and
// v ∈ [0, thickness], at 32 stations
// along the edge, flat-shaded faces (top, far side, bottom, the cut face, the two ends), skin-coloured.
#pragma once

#include "filum/haptics/wound.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class WoundVisual final : public VisualModel {
 public:
  /// lip: 0 or 1.
  WoundVisual(const haptics::Wound& wound, int lip);
  std::string typeName() const override { return "WoundVisual"; }
  bool needsBody() const override { return false; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  static constexpr int kStations = 32;
  const haptics::Wound& wound_;
  int lip_;
  TriangleMesh mesh_;
};

}  // namespace filum::visual
