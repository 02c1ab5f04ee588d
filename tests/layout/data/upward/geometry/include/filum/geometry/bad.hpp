// Fixture for layout.dependency_check_catches_upward_include: geometry must not include mechanics.
#include "filum/mechanics/dynamic_spline.hpp"
