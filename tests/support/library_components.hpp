// Every component of the libraries (mechanics, constraints, collision, visual) registered in one
// factory, without the application layer: what the core tests load their scene files with, so
// that they link the libraries only (apps/filum/all_components.cpp gives `filum` the same set).
#pragma once

#include "filum/collision/register_components.hpp"
#include "filum/constraints/register_components.hpp"
#include "filum/core/factory.hpp"
#include "filum/mechanics/register_components.hpp"
#include "filum/visual/register_components.hpp"

namespace filum::test {

inline Factory libraryComponents() {
  Factory factory;
  mechanics::register_components(factory);
  constraints::register_components(factory);
  collision::register_components(factory);
  visual::register_components(factory);
  return factory;
}

}  // namespace filum::test
