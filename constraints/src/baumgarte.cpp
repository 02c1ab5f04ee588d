#include "filum/constraints/baumgarte.hpp"

#include "filum/core/scene.hpp"

namespace filum::constraints {

Baumgarte Baumgarte::fromParams(const Params& p) {
  if (!p.has("stabilization")) return Baumgarte();
  return Baumgarte(p.nonNegative({"stabilization", "1/s"}, 0.0));
}

void Baumgarte::init(const Scene& scene) {
  if (!omega_) omega_ = 0.1 / scene.settings().dt;
}

}  // namespace filum::constraints
