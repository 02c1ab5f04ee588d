// InstrumentVisual: an instrument (haptics/instrument.hpp) as drawn — its shaft and its two jaws
// (or blades) as round-capped cylinders where they are at the state drawn, opened as its jaws
// are, and the cannula of its trocar if it has one. The shaft is dark (a laparoscopic
// instrument's insulated shaft), the jaws steel; the jaws of bipolar forceps are blue-grey, the
// blades of scissors brass-coloured, a needle holder's jaws gold (as tungsten carbide inserts are
// marked), and the jaws turn green while they hold a thread.
#pragma once

#include "filum/haptics/instrument.hpp"
#include "filum/visual/generalized_cylinder.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class InstrumentVisual final : public VisualModel {
 public:
  enum class Part { kShaft, kJaws };
  /// One part of the instrument (a model has one material: the shaft and the jaws are two models).
  InstrumentVisual(const haptics::Instrument& instrument, Part part);
  std::string typeName() const override { return "InstrumentVisual"; }
  /// X-ray: steel.
  double defaultXrayOpacity() const override { return 0.95; }
  bool needsBody() const override { return false; }
  /// The instrument where its driver has it at s.time.
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  /// The capsule's surface, appended to `out`.
  void appendCapsule(const haptics::Capsule& c, TriangleMesh& out);
  const haptics::Instrument& instrument_;
  Part part_;
  GeneralizedCylinder cylinder_;
  TriangleMesh mesh_;
};

}  // namespace filum::visual
