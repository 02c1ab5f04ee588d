// ConstraintProblem: what a constraint solver needs to know of the scene besides the rows and the
// operator A⁻¹ (BlockInverse): where each body's points lie in the scene's point vector, how many
// points there are, the state's size and whether bodies carry internal DOFs (a rod's frames), and
// a number that changes when any of it does (refinement, cuts). The solver sees this, never the
// Scene. Scene::constraintProblem() keeps it, rebuilt only when the layout changes (no allocation
// in a steady step).
#pragma once

#include <vector>

#include "filum/core/types.hpp"

namespace filum {

/// One body's block of points: points [offset, offset + pointCount()) of the scene's 3N vector.
struct BodyBlock {
  int first = 0, points = 0;
  int offset() const { return first; }
  int pointCount() const { return points; }
};

struct ConstraintProblem {
  std::vector<BodyBlock> bodies;  // in the scene's body order (rows name bodies by this index)
  int dof_points = 0;             // N: the points of every body
  Eigen::Index state_size = 0;    // q's size: 3N and the internal DOFs
  bool internal_dofs = false;     // some body has DOFs besides its points
  long layout_revision = -1;      // changes whenever the above may have
};

}  // namespace filum
