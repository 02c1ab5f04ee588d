// The units of parameters whose key means the same quantity in every component that reads it
// (a radius is in metres wherever it is read), for `filum list`. A type whose key means
// something else, or whose other quantities have units, says so with Factory::addUnits in its
// library's register_components. Scene files are in SI units throughout (README, "Scene files");
// "1" marks a pure number (a ratio, a friction coefficient, an abscissa in [0, 1]).
#pragma once

#include <string>

namespace filum {

/// The common unit of `key`, or "" when the key has none (its meaning depends on the type).
std::string commonParameterUnit(const std::string& key);

}  // namespace filum
