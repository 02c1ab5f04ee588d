// Units of a mesh file: the scene says them next to the file, as mesh files carry none (an organ
// segmented in 3D Slicer or exported from CAD is in millimetres, filum works in metres). Read by
// both components that take a mesh file, TriangleMeshObstacle and MeshModel:
//   "units": "m" (default), "cm" or "mm" — the unit of the file's coordinates;
//   "scale": a factor > 0 (default 1) on top of it, e.g. to grow an organ by 10 %.
// The file's coordinates are multiplied by units × scale to give metres: "units": "mm" is the
// same as "scale": 0.001, and both together multiply.
#pragma once

#include "filum/core/params.hpp"

namespace filum::geometry {

/// Metres per unit of the mesh file: the "units" factor times "scale". Throws SceneError naming
/// the JSON path of "units" for an unknown unit, of "scale" for a scale <= 0.
double meshScale(const Params& p);

}  // namespace filum::geometry
