// The grid's VTK file (write_grid_vtu): active cells as lines, quads or hexahedra of positive
// measure, with the nodes' fields.
#include <gtest/gtest.h>
#include <vtkCell.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "tests/writers/vtk_test_support.hpp"
#include "writers/vtk_output.hpp"

namespace unsatmpm {
namespace test_vtk_output {

TEST_F(VtkOutput, GridIn2DKeepsActiveCellsAsCounterClockwiseQuads) {
  const numerics::Grid<2> grid({1.0, 2.0}, {0.5, 0.25}, {3, 2});  // 4 x 3 nodes
  const std::vector<char> active = {1, 1, 0, 0, 0, 1};            // cells (0,0) (1,0) (2,1)
  std::vector<double> mass(12), velocity(24);
  for (int n = 0; n < 12; ++n) mass[n] = 10.0 * n, velocity[2 * n] = n, velocity[2 * n + 1] = -n;
  const std::vector<VtkField> fields = {{"mass", 1, mass}, {"velocity", 2, velocity, true}};
  const fs::path file = dir_ / "grid2.vtu";
  write_grid_vtu<2>(file, grid, active, fields);

  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfCells(), 3);
  ASSERT_EQ(data->GetNumberOfPoints(), 9);  // nodes 0 1 2 4 5 6 7 10 11
  vtkPointData* pd = data->GetPointData();
  vtkDataArray* node_id = pd->GetArray("node_id");
  ASSERT_NE(node_id, nullptr);
  const std::vector<double> expected_ids = {0, 1, 2, 4, 5, 6, 7, 10, 11};
  for (vtkIdType p = 0; p < 9; ++p) {
    const double id = node_id->GetComponent(p, 0);
    EXPECT_EQ(id, expected_ids[p]);
    const auto x = grid.node_position(static_cast<std::int64_t>(id));
    EXPECT_EQ(point(data, p), Vector3d(x[0], x[1], 0.0));
    EXPECT_EQ(pd->GetArray("mass")->GetComponent(p, 0), 10.0 * id);
    EXPECT_EQ(pd->GetArray("velocity")->GetComponent(p, 1), -id);
    EXPECT_EQ(pd->GetArray("velocity")->GetComponent(p, 2), 0.0);
  }
  for (vtkIdType c = 0; c < 3; ++c) {
    ASSERT_EQ(data->GetCellType(c), VTK_QUAD);
    vtkCell* cell = data->GetCell(c);
    double area = 0.0;  // shoelace: positive when counter-clockwise
    for (int k = 0; k < 4; ++k) {
      const Vector3d a = point(data, cell->GetPointId(k));
      const Vector3d b = point(data, cell->GetPointId((k + 1) % 4));
      area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
    }
    EXPECT_NEAR(area, 0.5 * 0.25, 1e-14);
  }
  // The last active cell is (2,1): its first corner is node 6.
  EXPECT_EQ(node_id->GetComponent(data->GetCell(2)->GetPointId(0), 0), 6.0);
}

/// Jacobian determinants at the 8 corners of a VTK hexahedron (edges in right-handed order).
std::array<double, 8> corner_jacobians(vtkUnstructuredGrid* data, vtkCell* hex) {
  static constexpr int edge[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                     {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  std::array<double, 8> det;
  for (int k = 0; k < 8; ++k) {
    const Vector3d x = point(data, hex->GetPointId(k));
    const Vector3d a = point(data, hex->GetPointId(edge[k][0])) - x;
    const Vector3d b = point(data, hex->GetPointId(edge[k][1])) - x;
    const Vector3d c = point(data, hex->GetPointId(edge[k][2])) - x;
    det[k] = a.dot(b.cross(c));
  }
  return det;
}

TEST_F(VtkOutput, GridIn3DWritesHexahedraWithPositiveVolume) {
  const numerics::Grid<3> grid({0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}, {2, 2, 2});
  std::vector<char> active(8, 0);
  active[0] = active[7] = 1;
  const fs::path file = dir_ / "grid3.vtu";
  write_grid_vtu<3>(file, grid, active, {});

  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfCells(), 2);
  EXPECT_EQ(data->GetNumberOfPoints(), 15);  // two hexahedra sharing the centre node
  EXPECT_EQ(array_names(data), std::set<std::string>{"node_id"});
  for (vtkIdType c = 0; c < 2; ++c) {
    ASSERT_EQ(data->GetCellType(c), VTK_HEXAHEDRON);
    for (const double det : corner_jacobians(data, data->GetCell(c))) EXPECT_NEAR(det, 6.0, 1e-12);
  }
  vtkCell* last = data->GetCell(1);
  EXPECT_EQ(point(data, last->GetPointId(0)), Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(point(data, last->GetPointId(6)), Vector3d(2.0, 4.0, 6.0));
}

TEST_F(VtkOutput, GridIn1DWritesLinesAndAnEmptyGridIsValid) {
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.5), {4});
  const fs::path file = dir_ / "grid1.vtu";
  write_grid_vtu<1>(file, grid, std::vector<char>{0, 1, 1, 0}, {});
  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfCells(), 2);
  EXPECT_EQ(data->GetNumberOfPoints(), 3);
  EXPECT_EQ(data->GetCellType(0), VTK_LINE);
  EXPECT_EQ(point(data, data->GetCell(0)->GetPointId(1)), Vector3d(1.0, 0.0, 0.0));

  write_grid_vtu<1>(file, grid, std::vector<char>(4, 0), {});
  const auto empty = read_vtu(file);
  EXPECT_EQ(empty->GetNumberOfCells(), 0);
  EXPECT_EQ(empty->GetNumberOfPoints(), 0);
}

}  // namespace test_vtk_output
}  // namespace unsatmpm
