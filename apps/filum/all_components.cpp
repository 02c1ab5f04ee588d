#include "filum/all_components.hpp"

#include "filum/collision/register_components.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/mechanics/register_components.hpp"
#include "filum/visual/register_components.hpp"

namespace filum::app {

Factory makeFactory() {
  Factory factory;
  mechanics::register_components(factory);
  constraints::register_components(factory);
  collision::register_components(factory);
  visual::register_components(factory);
  return factory;
}

}  // namespace filum::app
