// The VTK writers' tests' shared set-up: a fresh folder per test, and readers of what was written.
#pragma once

#include <gtest/gtest.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <Eigen/Core>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

namespace unsatmpm {
namespace test_vtk_output {

namespace fs = std::filesystem;
using Eigen::Vector3d;

class VtkOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() /
           ("unsatmpm_vtk_" + test + "_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

inline vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& file) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

inline std::set<std::string> array_names(vtkUnstructuredGrid* data) {
  std::set<std::string> names;
  vtkPointData* pd = data->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a) names.insert(pd->GetArrayName(a));
  return names;
}

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline int count_tmp_files(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().extension() == ".tmp") ++n;
  return n;
}

template <typename E, typename F>
void expect_throw_containing(F&& f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no exception thrown, expected one mentioning " << text;
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

inline Vector3d point(vtkUnstructuredGrid* data, vtkIdType i) {
  Vector3d x;
  data->GetPoint(i, x.data());
  return x;
}

}  // namespace test_vtk_output
}  // namespace unsatmpm
