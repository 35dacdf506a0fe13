// VTK XML output for ParaView (docs/output.md): material points and the active grid as .vtu files
// with appended raw binary data, and the .pvd collection that makes them a time series.
//
// Coordinates and vectors are always written with 3 components (zeros padded for D < 3), so one
// ParaView state works for 1D, 2D and 3D runs. Point-data names are fixed (docs/output.md) and are
// SI: mp_id, material_id, displacement [m], velocity_solid [m/s], net_stress [Pa] (Voigt xx, yy,
// zz, xy, yz, zx, tension positive), strain (engineering shear), deviatoric_plastic_strain, mass
// [kg per out-of-plane measure], volume [m^D]. A field the run does not compute is left out, not
// zeroed.
//
// Every file is written atomically (writers/atomic_file.hpp), so a crash never leaves a truncated
// file. Write failures throw std::runtime_error naming the file; inconsistent
// inputs (field sizes) throw std::invalid_argument naming the field.
//
// VTK itself stays in the .cpp: no VTK header is reachable from here.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "writers/atomic_file.hpp"

namespace unsatmpm {

/// Optional material-point fields. mp_id, material_id, displacement, velocity_solid, net_stress and
/// strain are always written.
struct PointFieldSelection {
  bool deviatoric_plastic_strain = false;  // only when a plastic model is present
  bool mass = true;
  bool volume = true;
};

/// A named array for a .vtu file: per point (an extra point field: liquid_pressure, suction,
/// velocity_liquid, ...) or per grid node (grid.n_nodes() entries). `values` holds n_components
/// doubles per entry, interleaved (entry-major). With `is_vector` and n_components == D, the
/// array is padded to 3 components.
struct VtkField {
  std::string name;
  int n_components = 1;
  std::span<const double> values;
  bool is_vector = false;
};

/// One VTK_VERTEX cell per material point, at its current position.
template <int D>
void write_points_vtu(const std::filesystem::path& file, const numerics::MaterialPoints<D>& mps,
                      const PointFieldSelection& sel, std::span<const VtkField> extra = {});

/// The active cells (active_cell[c] != 0, c lexicographic with x fastest, grid.n_cells_total()
/// entries) as VTK_LINE / VTK_QUAD / VTK_HEXAHEDRON. Only nodes of active cells become points,
/// numbered compactly in increasing grid order; their grid index is the point data `node_id`.
template <int D>
void write_grid_vtu(const std::filesystem::path& file, const numerics::Grid<D>& grid,
                    std::span<const char> active_cell, std::span<const VtkField> fields);

/// The ParaView collection (.pvd) of a time series. VTK 9.1 has no writer for it, so the XML is
/// written here; times [s] with %.17g so they survive a round trip.
class PvdSeries {
 public:
  /// Appends a data set; `relative_file` is relative to the folder of the .pvd. Throws
  /// std::invalid_argument for a non-finite time or an empty file name.
  void add(double time, std::string relative_file);
  std::size_t size() const { return entries_.size(); }
  /// The data sets' times [s] and files, in order (a checkpoint keeps them).
  std::vector<double> times() const {
    std::vector<double> t;
    for (const Entry& e : entries_) t.push_back(e.time);
    return t;
  }
  std::vector<std::string> files() const {
    std::vector<std::string> f;
    for (const Entry& e : entries_) f.push_back(e.file);
    return f;
  }
  /// The collection document.
  std::string xml() const;
  /// Writes xml() to `file` atomically.
  void write(const std::filesystem::path& file) const;

 private:
  struct Entry {
    double time;  // [s]
    std::string file;
  };
  std::vector<Entry> entries_;
};

extern template void write_points_vtu<1>(const std::filesystem::path&,
                                         const numerics::MaterialPoints<1>&,
                                         const PointFieldSelection&, std::span<const VtkField>);
extern template void write_points_vtu<2>(const std::filesystem::path&,
                                         const numerics::MaterialPoints<2>&,
                                         const PointFieldSelection&, std::span<const VtkField>);
extern template void write_points_vtu<3>(const std::filesystem::path&,
                                         const numerics::MaterialPoints<3>&,
                                         const PointFieldSelection&, std::span<const VtkField>);
extern template void write_grid_vtu<1>(const std::filesystem::path&, const numerics::Grid<1>&,
                                       std::span<const char>, std::span<const VtkField>);
extern template void write_grid_vtu<2>(const std::filesystem::path&, const numerics::Grid<2>&,
                                       std::span<const char>, std::span<const VtkField>);
extern template void write_grid_vtu<3>(const std::filesystem::path&, const numerics::Grid<3>&,
                                       std::span<const char>, std::span<const VtkField>);

}  // namespace unsatmpm
