// The factory of every component this build has: one explicit register_components call per
// library (docs/architecture.md, "Libraries, top to bottom").
#pragma once

#include "filum/core/factory.hpp"

namespace filum::app {

Factory makeFactory();

}  // namespace filum::app
