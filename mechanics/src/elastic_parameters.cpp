#include "filum/mechanics/elastic_parameters.hpp"

#include "filum/core/mechanical_state.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

ElasticParameters ElasticParameters::fromParams(const Params& p) {
  ElasticParameters e;
  e.youngs_modulus = p.positive({"youngs_modulus", "Pa"});
  if (p.has("rest_length")) e.rest_length = p.positive({"rest_length", "m"});
  if (p.has("quadrature_nodes")) e.quadrature_nodes = p.integer("quadrature_nodes", 1);
  return e;
}

const DynamicSpline& splineBody(const BodyComponent& component) {
  const auto* spline = dynamic_cast<const DynamicSpline*>(&component.body());
  if (!spline)
    throw SceneError(component.origin(), "a DynamicSpline body for " + component.describe(),
                     component.body().describe());
  return *spline;
}

}  // namespace filum::mechanics
