// The factory of every component this build has: one explicit register_components call per
// library (DESIGN.md "Libraries and their direction").
#pragma once

#include "filum/core/factory.hpp"

namespace filum::app {

Factory makeFactory();

}  // namespace filum::app
