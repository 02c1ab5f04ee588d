#include "filum/haptics/coil_packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace filum::haptics {

CoilPacking::CoilPacking(const geometry::VesselTree& tree, std::vector<int> branches, double spacing)
    : tree_(tree), branches_(std::move(branches)) {
  if (branches_.empty()) throw std::invalid_argument("an aneurysm needs at least one branch of the vessel tree");
  Eigen::AlignedBox3d box;
  double smallest = std::numeric_limits<double>::infinity();
  for (const int b : branches_) {
    if (b < 0 || b >= tree.branchCount())
      throw std::invalid_argument("branch " + std::to_string(b) + " is not a branch of the vessel tree (" +
                                  std::to_string(tree.branchCount()) + " branches)");
    const geometry::VesselTree::Branch& branch = tree.branch(b);
    const double grow = branch.radii.maxCoeff() + tree.blend();  // the fillet reaches k/4 beyond
    for (Eigen::Index i = 0; i < branch.points.rows(); ++i) {
      const Vec3 p = branch.points.row(i).transpose();
      box.extend(Vec3(p.array() - grow));
      box.extend(Vec3(p.array() + grow));
    }
    smallest = std::min(smallest, branch.radii.minCoeff());
  }
  if (spacing > 0.25 * smallest) {
    std::ostringstream message;
    message << "a grid spacing of " << spacing << " m, above a quarter of the aneurysm's smallest radius ("
            << 0.25 * smallest << " m): the grid would not see its shape";
    throw std::invalid_argument(message.str());
  }
  spacing_ = spacing > 0.0 ? spacing : smallest / 25.0;
  const Vec3 size = box.sizes();
  const Eigen::Array3d cells_per_axis = (size / spacing_).array().ceil();
  if ((cells_per_axis > 1e6).any() || cells_per_axis.prod() > static_cast<double>(kMaxCells)) {
    std::ostringstream message;
    message << "the aneurysm's volume grid of spacing " << spacing_ << " m over a box of " << size.x() << " x "
            << size.y() << " x " << size.z() << " m would have more than " << kMaxCells << " cells";
    throw std::invalid_argument(message.str());
  }
  const Eigen::Array3i n = cells_per_axis.cast<int>();
  // Midpoint rule: V = h³ · #{cell centres in the aneurysm} (header).
  long inside = 0;
  for (int i = 0; i < n.x(); ++i)
    for (int j = 0; j < n.y(); ++j)
      for (int k = 0; k < n.z(); ++k)
        if (contains(box.min() + spacing_ * Vec3(i + 0.5, j + 0.5, k + 0.5))) ++inside;
  volume_ = static_cast<double>(inside) * spacing_ * spacing_ * spacing_;
  if (inside == 0)
    throw std::invalid_argument("no cell of the volume grid lies in the aneurysm (its branches lie under the others')");
}

bool CoilPacking::contains(const Vec3& x) const {
  const geometry::VesselTree::Sample sample = tree_.sample(x, 0.0);
  return sample.value > 0.0 && std::find(branches_.begin(), branches_.end(), sample.branch) != branches_.end();
}

CoilPacking::Inside CoilPacking::inside(const CurveBody& body, const VecX& q, int pieces) const {
  Inside in;
  const bool varies = body.radiusVaries();
  const double r = body.radius();
  Vec3 previous = body.position(q, 0.0);
  for (int i = 1; i <= pieces; ++i) {
    const Vec3 next = body.position(q, static_cast<double>(i) / pieces);
    if (contains(0.5 * (previous + next))) {
      const double length = (next - previous).norm();
      in.length += length;
      if (varies) {  // π r² dℓ with the radius at the piece's middle abscissa (header)
        const double middle = body.radiusAt((i - 0.5) / pieces);
        in.volume += M_PI * middle * middle * length;
      }
    }
    previous = next;
  }
  if (!varies) in.volume = M_PI * r * r * in.length;  // one radius: π r² L
  return in;
}

}  // namespace filum::haptics
