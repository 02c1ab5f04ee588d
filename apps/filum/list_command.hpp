// `filum list [TYPE]`: the component types this build knows, one line each; with a TYPE, that
// type's parameters — key, required or its default, and what it must be — read off the
// component's own fromParams (ParameterRecorder, core/params.hpp), so that the listing is the
// code's and cannot drift from it. A mistyped TYPE gets the scene loader's suggestion.
#pragma once

#include <iosfwd>
#include <string>

#include "filum/core/factory.hpp"

namespace filum::app {

/// Every type with its one-line summary; 0.
int listTypes(const Factory& factory, std::ostream& out);
/// One type's parameters; 0, or 2 with "error: ..." (naming the closest type) for an unknown one.
int listParameters(const Factory& factory, const std::string& type, std::ostream& out, std::ostream& err);

}  // namespace filum::app
