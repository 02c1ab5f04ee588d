// Basic numeric types of filum: the scalar is double, vectors are Eigen.
//
// Points of a body (control points, sampled points) are stored as rows of an n×3 row-major
// matrix, so that a body's block of the global state vector (x0 y0 z0 x1 y1 z1 ...) can be
// viewed as points without copying.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace filum {

using Vec3 = Eigen::Vector3d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

/// n points, one per row (x, y, z), row-major so that it maps a flat x0 y0 z0 x1 ... vector.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using PointsMap = Eigen::Map<Points>;
using ConstPointsMap = Eigen::Map<const Points>;
using PointsRef = Eigen::Ref<Points>;
using ConstPointsRef = Eigen::Ref<const Points>;

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// Entries (row, column, value) of a sparse matrix over the scene's 3N coordinates, as force
/// Jacobians and mass matrices are assembled (duplicates add up).
using Triplet = Eigen::Triplet<double>;
using Triplets = std::vector<Triplet>;

}  // namespace filum
