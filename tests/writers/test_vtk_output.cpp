#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "tests/writers/vtk_test_support.hpp"
#include "writers/vtk_output.hpp"

namespace unsatmpm {
namespace test_vtk_output {

numerics::MaterialPoints<2> three_points_2d() {
  numerics::MaterialPoints<2> mps;
  const numerics::Vec<2> half(0.25, 0.25);
  mps.push_back(0, numerics::Vec<2>(0.5, 1.5), half, 2.0, 0.25);
  mps.push_back(1, numerics::Vec<2>(1.0, 2.0), half, 3.0, 0.25);
  mps.push_back(1, numerics::Vec<2>(1.5, 2.5), half, 4.0, 0.25);
  mps.displacement[1] = numerics::Vec<2>(0.1, -0.2);
  mps.velocity[2] = numerics::Vec<2>(1.0, 2.0);
  mps.stress[1] << -1e5, -2e5, -3e5, 4e3, 5e3, 6e3;
  mps.strain[1] << 1e-3, 2e-3, 0.0, 4e-3, 0.0, 0.0;
  return mps;
}

TEST_F(VtkOutput, PointsIn2DHaveTheSpecNamesPaddedVectorsAndAppendedRawData) {
  const auto mps = three_points_2d();
  const std::vector<double> suction = {10.0, 20.0, 30.0};
  const std::vector<double> velocity_liquid = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  const std::vector<VtkField> extra = {{"suction", 1, suction},
                                       {"velocity_liquid", 2, velocity_liquid, true}};
  const fs::path file = dir_ / "points.vtu";
  write_points_vtu<2>(file, mps, {.deviatoric_plastic_strain = false, .volume = false}, extra);

  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfPoints(), 3);
  ASSERT_EQ(data->GetNumberOfCells(), 3);
  for (vtkIdType c = 0; c < 3; ++c) EXPECT_EQ(data->GetCellType(c), VTK_VERTEX);
  EXPECT_EQ(point(data, 1), Vector3d(1.0, 2.0, 0.0));
  const std::set<std::string> expected = {"mp_id",          "material_id", "displacement",
                                          "velocity_solid", "net_stress",  "strain",
                                          "mass",           "suction",     "velocity_liquid"};
  EXPECT_EQ(array_names(data), expected);  // no deviatoric_plastic_strain, no volume

  vtkPointData* pd = data->GetPointData();
  EXPECT_EQ(pd->GetArray("mp_id")->GetDataType(), VTK_TYPE_INT64);
  EXPECT_EQ(pd->GetArray("material_id")->GetDataType(), VTK_TYPE_INT32);
  EXPECT_EQ(pd->GetArray("material_id")->GetComponent(1, 0), 1.0);
  vtkDataArray* stress = pd->GetArray("net_stress");
  ASSERT_EQ(stress->GetNumberOfComponents(), 6);
  const std::array<std::string, 6> component = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c) {
    ASSERT_NE(stress->GetComponentName(c), nullptr);
    EXPECT_EQ(stress->GetComponentName(c), component[c]);
    EXPECT_EQ(stress->GetComponent(1, c), mps.stress[1][c]);
    EXPECT_EQ(stress->GetComponent(0, c), 0.0);
  }
  EXPECT_EQ(pd->GetArray("strain")->GetComponent(1, 3), 4e-3);
  vtkDataArray* u = pd->GetArray("displacement");
  ASSERT_EQ(u->GetNumberOfComponents(), 3);
  EXPECT_EQ(u->GetComponent(1, 0), 0.1);
  EXPECT_EQ(u->GetComponent(1, 1), -0.2);
  EXPECT_EQ(u->GetComponent(1, 2), 0.0);
  EXPECT_EQ(pd->GetArray("velocity_solid")->GetComponent(2, 1), 2.0);
  EXPECT_EQ(pd->GetArray("mass")->GetComponent(2, 0), 4.0);
  EXPECT_EQ(pd->GetArray("suction")->GetComponent(2, 0), 30.0);
  vtkDataArray* v_l = pd->GetArray("velocity_liquid");
  ASSERT_EQ(v_l->GetNumberOfComponents(), 3);
  EXPECT_EQ(v_l->GetComponent(2, 0), 5.0);
  EXPECT_EQ(v_l->GetComponent(2, 1), 6.0);
  EXPECT_EQ(v_l->GetComponent(2, 2), 0.0);

  const std::string text = read_text(file);
  EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);
  EXPECT_EQ(text.find("format=\"ascii\""), std::string::npos);
  EXPECT_EQ(text.find("format=\"binary\""), std::string::npos);
}

TEST_F(VtkOutput, PointsIn3DWritePlasticStrainAndVolumeWhenSelected) {
  numerics::MaterialPoints<3> mps;
  const numerics::Vec<3> half(0.5, 0.5, 0.5);
  mps.push_back(2, numerics::Vec<3>(1.0, 2.0, 3.0), half, 5.0, 1.0);
  mps.push_back(0, numerics::Vec<3>(4.0, 5.0, 6.0), half, 6.0, 1.5);
  mps.plastic_strain[1] = 0.02;
  mps.displacement[0] = numerics::Vec<3>(0.1, 0.2, 0.3);
  mps.id[1] = 41;
  const fs::path file = dir_ / "points3.vtu";
  write_points_vtu<3>(file, mps, {.deviatoric_plastic_strain = true});

  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfPoints(), 2);
  EXPECT_EQ(point(data, 1), Vector3d(4.0, 5.0, 6.0));
  const auto names = array_names(data);
  EXPECT_EQ(names.size(), 9u);
  vtkPointData* pd = data->GetPointData();
  ASSERT_TRUE(names.contains("deviatoric_plastic_strain"));
  EXPECT_EQ(pd->GetArray("deviatoric_plastic_strain")->GetComponent(1, 0), 0.02);
  EXPECT_EQ(pd->GetArray("volume")->GetComponent(1, 0), 1.5);
  EXPECT_EQ(pd->GetArray("mp_id")->GetComponent(1, 0), 41.0);
  EXPECT_EQ(pd->GetArray("displacement")->GetComponent(0, 2), 0.3);
}

TEST_F(VtkOutput, PointsIn1DPadCoordinatesWithZeros) {
  numerics::MaterialPoints<1> mps;
  mps.push_back(0, numerics::Vec<1>(0.75), numerics::Vec<1>(0.25), 1.0, 0.5);
  mps.velocity[0] = numerics::Vec<1>(-3.0);
  const fs::path file = dir_ / "points1.vtu";
  write_points_vtu<1>(file, mps, {});
  const auto data = read_vtu(file);
  ASSERT_EQ(data->GetNumberOfPoints(), 1);
  EXPECT_EQ(point(data, 0), Vector3d(0.75, 0.0, 0.0));
  vtkDataArray* v = data->GetPointData()->GetArray("velocity_solid");
  EXPECT_EQ(v->GetComponent(0, 0), -3.0);
  EXPECT_EQ(v->GetComponent(0, 1), 0.0);
  EXPECT_EQ(v->GetComponent(0, 2), 0.0);
}

TEST_F(VtkOutput, PvdListsEveryDataSetWithItsExactTime) {
  PvdSeries series;
  const std::vector<double> times = {0.0, 0.1, 1.0 / 3.0};
  series.add(times[0], "points_0000.vtu");
  series.add(times[1], "points_0001.vtu");
  series.add(times[2], "a&b.vtu");
  EXPECT_EQ(series.size(), 3u);
  const fs::path file = dir_ / "points.pvd";
  series.write(file);

  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(file.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* root = parser->GetRootElement();
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  ASSERT_NE(collection, nullptr);
  ASSERT_EQ(collection->GetNumberOfNestedElements(), 3);
  for (int i = 0; i < 3; ++i) {
    vtkXMLDataElement* set = collection->GetNestedElement(i);
    EXPECT_STREQ(set->GetName(), "DataSet");
    ASSERT_NE(set->GetAttribute("timestep"), nullptr);
    EXPECT_EQ(std::stod(set->GetAttribute("timestep")), times[i]);  // bit-exact round trip
    EXPECT_STREQ(set->GetAttribute("part"), "0");
  }
  EXPECT_STREQ(collection->GetNestedElement(2)->GetAttribute("file"), "a&b.vtu");
  EXPECT_THROW(series.add(std::numeric_limits<double>::quiet_NaN(), "x.vtu"),
               std::invalid_argument);
}

TEST_F(VtkOutput, SuccessfulWritesLeaveNoTemporaryFiles) {
  const auto mps = three_points_2d();
  const numerics::Grid<2> grid({0.0, 0.0}, {1.0, 1.0}, {2, 2});
  for (int round = 0; round < 2; ++round) {  // the second round overwrites
    write_points_vtu<2>(dir_ / "points.vtu", mps, {});
    write_grid_vtu<2>(dir_ / "grid.vtu", grid, std::vector<char>{1, 0, 0, 1}, {});
    PvdSeries series;
    series.add(round, "points.vtu");
    series.write(dir_ / "points.pvd");
  }
  EXPECT_EQ(count_tmp_files(dir_), 0);
  EXPECT_NE(read_text(dir_ / "points.pvd").find("timestep=\"1\""), std::string::npos);
  EXPECT_EQ(read_vtu(dir_ / "grid.vtu")->GetNumberOfCells(), 2);
}

TEST_F(VtkOutput, AFailedWriteKeepsThePreviousFile) {
  const fs::path file = dir_ / "summary.json";
  write_text_atomically(file, "old");
  EXPECT_THROW(write_file_atomically(file,
                                     [](const fs::path& tmp) {
                                       std::ofstream(tmp) << "partial";
                                       throw std::runtime_error("crash while writing");
                                     }),
               std::runtime_error);
  EXPECT_EQ(read_text(file), "old");
  EXPECT_EQ(count_tmp_files(dir_), 0);
}

TEST_F(VtkOutput, AFullDiskIsNamedInTheOperatingSystemsWords) {
  // /dev/full takes no byte: every write to it fails with ENOSPC, as on a full disk.
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const auto mps = three_points_2d();
  const fs::path points = dir_ / "points.vtu", text = dir_ / "summary.json";
  fs::create_symlink("/dev/full", dir_ / "points.vtu.tmp");
  fs::create_symlink("/dev/full", dir_ / "summary.json.tmp");
  expect_throw_containing<std::runtime_error>([&] { write_points_vtu<2>(points, mps, {}); },
                                              "points.vtu.tmp'): No space left on device");
  expect_throw_containing<std::runtime_error>([&] { write_text_atomically(text, "x"); },
                                              "summary.json.tmp'): No space left on device");
  EXPECT_FALSE(fs::exists(points));
  EXPECT_FALSE(fs::exists(text));
}

TEST_F(VtkOutput, WritingIntoAMissingFolderThrowsNamingTheFile) {
  const fs::path missing = dir_ / "missing";
  const auto mps = three_points_2d();
  const numerics::Grid<2> grid({0.0, 0.0}, {1.0, 1.0}, {1, 1});
  const fs::path points = missing / "points.vtu", cells = missing / "grid.vtu";
  expect_throw_containing<std::runtime_error>([&] { write_points_vtu<2>(points, mps, {}); },
                                              points.string());
  expect_throw_containing<std::runtime_error>(
      [&] { write_grid_vtu<2>(cells, grid, std::vector<char>{1}, {}); }, cells.string());
  expect_throw_containing<std::runtime_error>([&] { PvdSeries{}.write(missing / "a.pvd"); },
                                              (missing / "a.pvd").string());
  write_text_atomically(dir_ / "plain_file", "x");  // a file used as a folder
  const fs::path under_file = dir_ / "plain_file" / "out.csv";
  expect_throw_containing<std::runtime_error>([&] { write_text_atomically(under_file, "x"); },
                                              under_file.string());
  EXPECT_FALSE(fs::exists(missing));
}

TEST_F(VtkOutput, AVtkWriterFailureThrowsNamingTheFile) {
  const fs::path file = dir_ / "points.vtu";
  fs::create_directory(dir_ / "points.vtu.tmp");  // VTK cannot open its temporary
  expect_throw_containing<std::runtime_error>(
      [&] { write_points_vtu<2>(file, three_points_2d(), {}); }, file.string());
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(VtkOutput, InconsistentFieldsAreRejectedWithTheirName) {
  const numerics::Grid<2> grid({0.0, 0.0}, {1.0, 1.0}, {2, 1});  // 6 nodes
  const std::vector<char> active = {1, 1};
  const std::vector<double> five(5), twelve(12);
  const fs::path file = dir_ / "grid.vtu";
  const std::vector<VtkField> short_field = {{"pressure", 1, five}};
  expect_throw_containing<std::invalid_argument>(
      [&] { write_grid_vtu<2>(file, grid, active, short_field); }, "pressure");
  EXPECT_NO_THROW(write_grid_vtu<2>(file, grid, active, std::vector<VtkField>{{"m", 2, twelve}}));
  const std::vector<VtkField> wrong_dim = {{"flux", 1, std::span(twelve).first(6), true}};
  expect_throw_containing<std::invalid_argument>(
      [&] { write_grid_vtu<2>(file, grid, active, wrong_dim); }, "flux");
  expect_throw_containing<std::invalid_argument>(
      [&] { write_grid_vtu<2>(file, grid, std::vector<char>{1}, {}); }, "active_cell");
  const std::vector<double> three(3);
  const std::vector<VtkField> clash = {{"mp_id", 1, three}};
  expect_throw_containing<std::invalid_argument>(
      [&] { write_points_vtu<2>(dir_ / "p.vtu", three_points_2d(), {}, clash); }, "mp_id");
  EXPECT_EQ(count_tmp_files(dir_), 0);
}

}  // namespace test_vtk_output
}  // namespace unsatmpm
