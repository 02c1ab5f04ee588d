// Fixture: mechanics may include geometry and core.
#include "filum/geometry/spline_basis.hpp"
