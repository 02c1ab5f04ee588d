// InstrumentCapsule: one rigid part of an instrument (its shaft, a jaw, a blade) as an obstacle
// of the collision pipeline, so that a shaft pushes a thread aside with the same contact rows,
// friction and solver as any other obstacle. The instrument sets where the part is at the start
// and at the end of the coming step; in between the part moves linearly, with the velocity
// (end − start) / h at every point of its axis (the surface velocity of the contacts).
#pragma once

#include "filum/collision/obstacle.hpp"
#include "filum/haptics/instrument_shape.hpp"

namespace filum::haptics {

class InstrumentCapsule final : public collision::Obstacle {
 public:
  std::string typeName() const override { return "InstrumentCapsule"; }

  /// The part at time t0 (`start`) and at t0 + h (`end`), h > 0; the radius is start's.
  void setMotion(const Capsule& start, const Capsule& end, double t0, double h);
  /// A part that does not collide (jaws closed on what they let go of, scissors' blades).
  void setEnabled(bool enabled) { enabled_ = enabled; }
  bool enabled() const { return enabled_; }
  /// The span [from, to] of abscissas of `body` that this part lets through: the piece of a
  /// thread its jaws hold (the hold is that piece's contact; the rest of the thread, and every
  /// other thread, is pushed). Null body: none.
  void setPassage(const CurveBody* body, double from, double to) {
    passage_body_ = body;
    passage_from_ = from;
    passage_to_ = to;
  }
  bool passesThrough(const CurveBody& body, double s) const override {
    return &body == passage_body_ && s >= passage_from_ && s <= passage_to_;
  }

  void moveTo(double t) override;
  bool sample(const Vec3& x, double max_distance, collision::SurfaceSample& out) const override;
  double speed() const override { return enabled_ ? std::max(velocity_a_.norm(), velocity_b_.norm()) : 0.0; }

  /// Where the part is (at the last moveTo).
  const Capsule& capsule() const { return now_; }

 private:
  Capsule start_, end_, now_;
  Vec3 velocity_a_ = Vec3::Zero(), velocity_b_ = Vec3::Zero();
  double t0_ = 0.0, h_ = 1.0;
  bool enabled_ = true;
  const CurveBody* passage_body_ = nullptr;
  double passage_from_ = 0.0, passage_to_ = 0.0;
};

}  // namespace filum::haptics
