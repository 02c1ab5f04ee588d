// The second body kind through the code the splines use, unchanged:
// apps/scenes/framed_chain.json — a FramedChain (points with frames, internal DOFs) held by a
// FixedPointConstraint, resting on a PlaneObstacle through unilateral contact rows, drawn by a
// GeneralizedCylinder skin — run by `filum run --meshes` for 0.6 s (settled: the drag's time
// constant is 0.5 s and the swing is over by 0.3 s).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "filum/geometry/mesh_file.hpp"
#include "filum/run_command.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;

/// Rows (x, y, z) of the last frame of control_points.csv (time,body,index,x,y,z).
Points lastFrame(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, last_time;
  std::vector<Vec3> rows;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string time, body, index, x, y, z;
    std::getline(fields, time, ',');
    std::getline(fields, body, ',');
    std::getline(fields, index, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, z, ',');
    if (time != last_time) rows.clear();
    last_time = time;
    rows.emplace_back(std::stod(x), std::stod(y), std::stod(z));
  }
  Points p(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  return p;
}

TEST(FramedChainScene, IsHeldRestsOnTheTableAndIsDrawn) {
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "framed_chain";
  fs::remove_all(out);
  RunOptions options;
  options.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/framed_chain.json";
  options.out = out.string();
  options.duration = 0.6;
  options.progress = false;
  options.meshes = true;
  std::ostringstream log, progress;
  ASSERT_EQ(runScene(options, log, progress), kRunOk) << log.str();

  const Points x = lastFrame(out / "control_points.csv");
  ASSERT_EQ(x.rows(), 21);
  const double r = 1e-3;
  // Held: node 0 is P(0), kept by a Lagrange row at every step (round-off of its 3 × 3 system).
  EXPECT_LE((x.row(0).transpose() - Vec3(0, 0, 0.03)).norm(), 1e-12);
  // On the table: no node below one radius (the rows are solved to the contact tolerance,
  // ~1e-6 of the radius), and the far end lies on it.
  EXPECT_GE(x.col(2).minCoeff(), r * (1.0 - 1e-6));
  EXPECT_NEAR(x(20, 2), r, 1e-6 * r);
  // Inextensible at this load: the stretch is at most the whole weight over E A,
  // ρ A g L / (E A) = 1150 · 9.81 · 0.2 / 3e7 = 7.5e-5.
  double length = 0.0;
  for (int i = 0; i + 1 < 21; ++i) length += (x.row(i + 1) - x.row(i)).norm();
  EXPECT_NEAR(length, 0.2, 0.2 * 7.5e-5);
  // It bends under its weight: between pin and table, heights fall monotonically.
  // (Two nodes on the table may differ by the contact tolerance, 1e-6 r each.)
  for (int i = 0; i + 1 < 21; ++i) EXPECT_GE(x(i, 2), x(i + 1, 2) - 2e-6 * r) << "node " << i;

  // Drawn: the skin around P(s) spans the rod. Every skin vertex is one radius from the centre
  // line (rings and round caps), and the rings around the end nodes reach past them: the box of
  // the skin lies between the centre line's and that box grown by r. Its lowest vertex is within
  // the sagitta r (1 − cos(π/16)) of the table for the default 16 sides per ring (a ring's
  // vertices are 2π/16 apart, and the resting nodes are at r(1 ± 1e-6)).
  const geometry::PolygonSoup skin = geometry::readMeshFile((out / "meshes" / "final_rod_GeneralizedCylinder.ply").string());
  ASSERT_GT(skin.vertices.rows(), 0);
  const Vec3 low = skin.vertices.colwise().minCoeff().transpose(), high = skin.vertices.colwise().maxCoeff().transpose();
  const double sagitta = r * (1.0 - std::cos(M_PI / 16)), slack = 1e-6 * r;
  EXPECT_GE(low.z(), -slack);
  EXPECT_LE(low.z(), sagitta + slack);
  EXPECT_GE(high.z(), x(0, 2));
  EXPECT_LE(high.z(), x(0, 2) + r + slack);
  EXPECT_LE(low.x(), x(0, 0));
  EXPECT_GE(low.x(), x(0, 0) - r - slack);
  EXPECT_GE(high.x(), x(20, 0));
  EXPECT_LE(high.x(), x(20, 0) + r + slack);
}

}  // namespace
}  // namespace filum::app
