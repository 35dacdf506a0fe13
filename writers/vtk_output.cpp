#include "writers/vtk_output.hpp"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace unsatmpm {
namespace {

/// Keeps VTK's error text for the exception instead of letting VTK print it to stderr.
class ErrorCapture : public vtkCommand {
 public:
  static ErrorCapture* New() { return new ErrorCapture; }
  void Execute(vtkObject*, unsigned long, void* call_data) override {
    if (call_data == nullptr || !message.empty()) return;
    message = static_cast<const char*>(call_data);
    std::replace(message.begin(), message.end(), '\n', ' ');
    message.erase(message.find_last_not_of(' ') + 1);
  }
  std::string message;
};

/// The reason of a failed VTK write in the operating system's words where VTK's error code
/// has one (a full disk: "No space left on device"), else the OS error seen, else VTK's message,
/// else the code.
/// vtkErrorCode's own names live in VTK::CommonMisc, which the build does not link.
std::string vtk_write_reason(unsigned long code, int os_error, const std::string& vtk_message) {
  if (code == vtkErrorCode::OutOfDiskSpaceError) return std::generic_category().message(ENOSPC);
  if (os_error != 0) return std::generic_category().message(os_error);
  if (!vtk_message.empty()) return vtk_message;
  return "VTK error code " + std::to_string(code);
}

void write_vtu(const fs::path& file, vtkUnstructuredGrid* data) {
  write_file_atomically(file, [&](const fs::path& tmp) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    vtkNew<ErrorCapture> errors;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();  // raw binary, not base64
    writer->SetCompressorTypeToNone();
    writer->SetHeaderTypeToUInt64();  // arrays beyond 4 GB stay readable
    errno = 0;
    if (writer->Write() == 0 || writer->GetErrorCode() != vtkErrorCode::NoError) {
      const int os_error = errno;
      throw std::runtime_error(
          "cannot write VTK file " + quoted_path(file) + " (via " + quoted_path(tmp) +
          "): " + vtk_write_reason(writer->GetErrorCode(), os_error, errors->message));
    }
  });
}

/// Checks each field's name and size; returns the components written (D-vectors padded to 3).
template <typename Field>
std::vector<int> checked_output_components(std::span<const Field> fields, std::int64_t n_rows,
                                           int dim) {
  std::vector<int> n_out;
  for (const Field& f : fields) {
    const std::string field = "VTK output: field '" + f.name + "'";
    if (f.name.empty()) throw std::invalid_argument("VTK output: a field has an empty name");
    if (f.n_components < 1) throw std::invalid_argument(field + " needs n_components >= 1");
    if (f.is_vector && f.n_components != dim)
      throw std::invalid_argument(field + " is a vector of " + std::to_string(f.n_components) +
                                  " components, expected " + std::to_string(dim));
    if (f.values.size() != static_cast<std::size_t>(n_rows * f.n_components))
      throw std::invalid_argument(field + " has " + std::to_string(f.values.size()) +
                                  " values, expected " + std::to_string(n_rows) + " x " +
                                  std::to_string(f.n_components));
    n_out.push_back(f.is_vector ? 3 : f.n_components);
  }
  return n_out;
}

vtkSmartPointer<vtkDoubleArray> new_double_array(const std::string& name, int n_components,
                                                 vtkIdType n_tuples) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(n_components);
  array->SetNumberOfTuples(n_tuples);
  return array;
}

/// Adds the rows `rows` of each interleaved field as tuples, padded to n_out[f] components.
template <typename Field>
void add_fields(vtkPointData* point_data, std::span<const Field> fields,
                const std::vector<int>& n_out, std::span<const std::int64_t> rows) {
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const Field& field = fields[f];
    const int n_in = field.n_components;
    if (point_data->HasArray(field.name.c_str()) != 0)
      throw std::invalid_argument("VTK output: field name '" + field.name + "' is used twice");
    auto array = new_double_array(field.name, n_out[f], static_cast<vtkIdType>(rows.size()));
    double* out = array->GetPointer(0);
    for (std::size_t t = 0; t < rows.size(); ++t)
      for (int c = 0; c < n_out[f]; ++c)
        out[t * n_out[f] + c] =
            c < n_in ? field.values[static_cast<std::size_t>(rows[t] * n_in + c)] : 0.0;
    point_data->AddArray(array);
  }
}

template <int D>
void add_vector(vtkPointData* point_data, const char* name,
                const std::vector<numerics::Vec<D>>& v) {
  auto array = new_double_array(name, 3, static_cast<vtkIdType>(v.size()));
  double* out = array->GetPointer(0);
  for (std::size_t p = 0; p < v.size(); ++p)
    for (int c = 0; c < 3; ++c) out[3 * p + c] = c < D ? v[p][c] : 0.0;
  point_data->AddArray(array);
}

void add_voigt(vtkPointData* point_data, const char* name, const std::vector<physics::Vec6>& v) {
  static constexpr std::array<const char*, 6> component = {"xx", "yy", "zz", "xy", "yz", "zx"};
  auto array = new_double_array(name, 6, static_cast<vtkIdType>(v.size()));
  for (int c = 0; c < 6; ++c) array->SetComponentName(c, component[c]);
  double* out = array->GetPointer(0);
  for (std::size_t p = 0; p < v.size(); ++p)
    for (int c = 0; c < 6; ++c) out[6 * p + c] = v[p][c];
  point_data->AddArray(array);
}

void add_scalar(vtkPointData* point_data, const char* name, const std::vector<double>& v) {
  auto array = new_double_array(name, 1, static_cast<vtkIdType>(v.size()));
  std::copy(v.begin(), v.end(), array->GetPointer(0));
  point_data->AddArray(array);
}

template <typename ArrayT, typename T>
void add_integers(vtkPointData* point_data, const char* name, const std::vector<T>& v) {
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), v[i]);
  point_data->AddArray(array);
}

template <int D>
vtkSmartPointer<vtkPoints> padded_points(const std::vector<numerics::Vec<D>>& x) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(x.size()));
  for (std::size_t p = 0; p < x.size(); ++p) {
    double xyz[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < D; ++d) xyz[d] = x[p][d];
    points->SetPoint(static_cast<vtkIdType>(p), xyz);
  }
  return points;
}

/// Cells of one type, `nodes_per_cell` consecutive entries of `connectivity` each.
void set_cells(vtkUnstructuredGrid* data, int cell_type, int nodes_per_cell,
               const std::vector<vtkIdType>& connectivity) {
  vtkNew<vtkIdTypeArray> ids;
  ids->SetNumberOfTuples(static_cast<vtkIdType>(connectivity.size()));
  std::copy(connectivity.begin(), connectivity.end(), ids->GetPointer(0));
  vtkNew<vtkCellArray> cells;
  if (!cells->SetData(nodes_per_cell, ids))
    throw std::logic_error("VTK output: inconsistent cell connectivity");
  data->SetCells(cell_type, cells);
}

template <int D>
void check_point_columns(const numerics::MaterialPoints<D>& mps, const PointFieldSelection& sel) {
  const std::size_t n = mps.size();
  const auto check = [n](const char* name, std::size_t size) {
    if (size != n)
      throw std::invalid_argument("VTK output: material point column '" + std::string(name) +
                                  "' has " + std::to_string(size) + " entries, expected " +
                                  std::to_string(n));
  };
  check("material", mps.material.size()), check("position", mps.position.size());
  check("displacement", mps.displacement.size()), check("velocity", mps.velocity.size());
  check("stress", mps.stress.size()), check("strain", mps.strain.size());
  if (sel.deviatoric_plastic_strain) check("plastic_strain", mps.plastic_strain.size());
  if (sel.mass) check("mass", mps.mass.size());
  if (sel.volume) check("volume", mps.volume.size());
}

/// The corners of a cell in VTK order (line, quad counter-clockwise, hexahedron bottom then top).
template <int D>
constexpr std::array<std::array<int, D>, (1 << D)> vtk_corners() {
  std::array<std::array<int, D>, (1 << D)> corners{};
  for (int n = 0; n < (1 << D); ++n) {
    const int in_plane = n & 3;  // 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1)
    corners[n][0] = (in_plane == 1 || in_plane == 2) ? 1 : 0;
    if constexpr (D >= 2) corners[n][1] = in_plane >= 2 ? 1 : 0;
    if constexpr (D >= 3) corners[n][2] = n >> 2;
  }
  return corners;
}

/// Grid node indices of the active cells' corners, (1 << D) per cell in VTK order.
template <int D>
std::vector<std::int64_t> active_cell_nodes(const numerics::Grid<D>& grid,
                                            std::span<const char> active_cell) {
  constexpr auto corners = vtk_corners<D>();
  std::vector<std::int64_t> nodes;
  for (std::int64_t c = 0; c < grid.n_cells_total(); ++c) {
    if (active_cell[static_cast<std::size_t>(c)] == 0) continue;
    std::int64_t base = 0, rest = c;
    for (int d = 0; d < D; ++d) {
      base += (rest % grid.n_cells[d]) * grid.stride[d];
      rest /= grid.n_cells[d];
    }
    for (const auto& corner : corners) {
      std::int64_t node = base;
      for (int d = 0; d < D; ++d) node += corner[d] * grid.stride[d];
      nodes.push_back(node);
    }
  }
  return nodes;
}

/// The active cells' nodes renumbered compactly, in increasing grid order.
struct ActiveMesh {
  std::vector<std::int64_t> used;       // grid index of each output point
  std::vector<vtkIdType> connectivity;  // output point of each cell corner
};

ActiveMesh compact_mesh(const std::vector<std::int64_t>& cell_nodes, std::int64_t n_nodes) {
  std::vector<std::int64_t> compact(static_cast<std::size_t>(n_nodes), -1);
  for (const std::int64_t node : cell_nodes) compact[static_cast<std::size_t>(node)] = 0;
  ActiveMesh mesh;
  for (std::int64_t node = 0; node < n_nodes; ++node) {
    auto& index = compact[static_cast<std::size_t>(node)];
    if (index < 0) continue;
    index = static_cast<std::int64_t>(mesh.used.size());
    mesh.used.push_back(node);
  }
  mesh.connectivity.reserve(cell_nodes.size());
  for (const std::int64_t node : cell_nodes)
    mesh.connectivity.push_back(static_cast<vtkIdType>(compact[static_cast<std::size_t>(node)]));
  return mesh;
}

/// Text for a double-quoted XML attribute.
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const char* entity = ch == '&'   ? "&amp;"
                         : ch == '<' ? "&lt;"
                         : ch == '>' ? "&gt;"
                         : ch == '"' ? "&quot;"
                                     : nullptr;
    out += entity != nullptr ? std::string_view(entity) : std::string_view(&ch, 1);
  }
  return out;
}

}  // namespace

template <int D>
void write_points_vtu(const fs::path& file, const numerics::MaterialPoints<D>& mps,
                      const PointFieldSelection& sel, std::span<const VtkField> extra) {
  check_point_columns(mps, sel);
  const auto n = static_cast<std::int64_t>(mps.size());
  const std::vector<int> n_out = checked_output_components(extra, n, D);

  vtkNew<vtkUnstructuredGrid> data;
  data->SetPoints(padded_points<D>(mps.position));
  std::vector<vtkIdType> vertices(mps.size());
  std::iota(vertices.begin(), vertices.end(), vtkIdType{0});
  set_cells(data, VTK_VERTEX, 1, vertices);

  vtkPointData* point_data = data->GetPointData();
  add_integers<vtkTypeInt64Array>(point_data, "mp_id", mps.id);
  add_integers<vtkTypeInt32Array>(point_data, "material_id", mps.material);
  add_vector<D>(point_data, "displacement", mps.displacement);
  add_vector<D>(point_data, "velocity_solid", mps.velocity);
  add_voigt(point_data, "net_stress", mps.stress);
  add_voigt(point_data, "strain", mps.strain);
  if (sel.deviatoric_plastic_strain)
    add_scalar(point_data, "deviatoric_plastic_strain", mps.plastic_strain);
  if (sel.mass) add_scalar(point_data, "mass", mps.mass);
  if (sel.volume) add_scalar(point_data, "volume", mps.volume);
  std::vector<std::int64_t> rows(mps.size());
  std::iota(rows.begin(), rows.end(), std::int64_t{0});
  add_fields(point_data, extra, n_out, rows);
  write_vtu(file, data);
}

template <int D>
void write_grid_vtu(const fs::path& file, const numerics::Grid<D>& grid,
                    std::span<const char> active_cell, std::span<const VtkField> fields) {
  if (active_cell.size() != static_cast<std::size_t>(grid.n_cells_total()))
    throw std::invalid_argument("VTK output: active_cell has " +
                                std::to_string(active_cell.size()) + " entries, expected " +
                                std::to_string(grid.n_cells_total()));
  const std::vector<int> n_out = checked_output_components(fields, grid.n_nodes(), D);

  const ActiveMesh mesh = compact_mesh(active_cell_nodes(grid, active_cell), grid.n_nodes());
  std::vector<numerics::Vec<D>> positions;
  for (const std::int64_t node : mesh.used) positions.push_back(grid.node_position(node));
  vtkNew<vtkUnstructuredGrid> data;
  data->SetPoints(padded_points<D>(positions));
  constexpr int cell_type = D == 1 ? VTK_LINE : (D == 2 ? VTK_QUAD : VTK_HEXAHEDRON);
  set_cells(data, cell_type, 1 << D, mesh.connectivity);

  vtkPointData* point_data = data->GetPointData();
  add_integers<vtkTypeInt64Array>(point_data, "node_id", mesh.used);
  add_fields(point_data, fields, n_out, mesh.used);
  write_vtu(file, data);
}

void PvdSeries::add(double time, std::string relative_file) {
  if (!std::isfinite(time))
    throw std::invalid_argument("PvdSeries: time of '" + relative_file + "' is not finite");
  if (relative_file.empty()) throw std::invalid_argument("PvdSeries: empty file name");
  entries_.push_back({time, std::move(relative_file)});
}

std::string PvdSeries::xml() const {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const Entry& e : entries_) {
    char time[32];
    std::snprintf(time, sizeof time, "%.17g", e.time);
    out += "    <DataSet timestep=\"" + std::string(time) + "\" group=\"\" part=\"0\" file=\"" +
           xml_escaped(e.file) + "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

void PvdSeries::write(const fs::path& file) const { write_text_atomically(file, xml()); }

template void write_points_vtu<1>(const fs::path&, const numerics::MaterialPoints<1>&,
                                  const PointFieldSelection&, std::span<const VtkField>);
template void write_points_vtu<2>(const fs::path&, const numerics::MaterialPoints<2>&,
                                  const PointFieldSelection&, std::span<const VtkField>);
template void write_points_vtu<3>(const fs::path&, const numerics::MaterialPoints<3>&,
                                  const PointFieldSelection&, std::span<const VtkField>);
template void write_grid_vtu<1>(const fs::path&, const numerics::Grid<1>&, std::span<const char>,
                                std::span<const VtkField>);
template void write_grid_vtu<2>(const fs::path&, const numerics::Grid<2>&, std::span<const char>,
                                std::span<const VtkField>);
template void write_grid_vtu<3>(const fs::path&, const numerics::Grid<3>&, std::span<const char>,
                                std::span<const VtkField>);

}  // namespace unsatmpm
