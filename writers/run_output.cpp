#include "writers/run_output.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "input/case_parser.hpp"
#include "numerics/shape_functions.hpp"
#include "physics/unsaturated_state.hpp"

#include <algorithm>

namespace unsatmpm {

namespace fs = std::filesystem;

namespace {

const char* axis_name(int d) { return d == 0 ? "x" : (d == 1 ? "y" : "z"); }
constexpr const char* voigt_names[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};

/// A CSV field as RFC 4180 writes it: quoted, with its quotes doubled, if it holds a comma, a
/// quote or a line break (a control point's name can).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out(1, '"');
  for (const char ch : s) {
    out.push_back(ch);
    if (ch == '"') out.push_back('"');
  }
  out.push_back('"');
  return out;
}

std::string csv(const std::vector<std::string>& header,
                const std::vector<std::vector<double>>& rows) {
  std::string out;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i) out += ',';
    out += csv_field(header[i]);
  }
  out += '\n';
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i)
      out += fmt::format("{}{:.10g}", i ? "," : "", row[i]);
    out += '\n';
  }
  return out;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\')
      out += '\\', out += ch;
    else if (ch == '\n')
      out += "\\n";
    else if (static_cast<unsigned char>(ch) < 0x20)
      out += ' ';
    else
      out += ch;
  }
  return out + "\"";
}

/// A number for JSON, which has no infinities or NaNs: null for those (a run that failed at its
/// first step has no step size, `inf`, which JSON readers refuse), else x in fmt's `spec`.
std::string json_number(double x, const char* spec) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(spec), x) : std::string("null");
}

/// The same for an object of numbers and fixed names built elsewhere (the gravity loading's, the
/// flow's statistics): fmt's inf and nan after a key become null. Its strings are names, so no
/// ": inf" stands inside one.
std::string json_numbers_finite(std::string object) {
  for (const char* bad : {": -inf", ": inf", ": -nan", ": nan"})
    for (std::size_t at = object.find(bad); at != std::string::npos; at = object.find(bad, at))
      object.replace(at, std::strlen(bad), ": null");
  return object;
}

}  // namespace

template <int D>
RunOutput<D>::RunOutput(const Case& c, OutputFolder& folder, const numerics::MaterialPoints<D>& mp,
                        bool plastic_fields)
    : case_(c), folder_(folder) {
  selection_.deviatoric_plastic_strain = plastic_fields;
  write_text_atomically(folder_.file("effective_case.yaml"), effective_configuration(c));
  for (const ControlPoint& cp : c.output.control_points) {
    std::int64_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < mp.size(); ++p) {
      double d2 = 0.0;
      for (int d = 0; d < D; ++d) d2 += std::pow(mp.position[p][d] - cp.position[d], 2);
      if (d2 < best_d2) best_d2 = d2, best = static_cast<std::int64_t>(p);
    }
    control_index_.push_back(best);
  }
}

template <int D>
void RunOutput<D>::write_fields(double t, const numerics::Grid<D>& grid,
                                std::span<const VtkField> nodal,
                                const numerics::MaterialPoints<D>& mp,
                                std::span<const VtkField> extra, const std::string& tag) {
  const std::string stem = tag.empty() ? fmt::format("{:04d}", frame_++) : tag;
  const std::string points_file = fmt::format("points_{}.vtu", stem);
  write_points_vtu<D>(folder_.file(points_file), mp, selection_, extra);
  if (!tag.empty()) return;  // not a frame of the series: its time is in run_summary.json
  points_series_.add(t, points_file);
  points_series_.write(folder_.file("points.pvd"));
  if (!case_.output.write_grid || nodal.empty()) return;

  std::vector<char> active(grid.n_cells_total(), 0);
  for (const auto& x : mp.position) {
    std::int64_t cell = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      const int i = numerics::clamped_floor((x[d] - grid.origin[d]) / grid.spacing[d], 0,
                                            grid.n_cells[d] - 1);
      cell += i * stride;
      stride *= grid.n_cells[d];
    }
    active[cell] = 1;
  }
  const std::string grid_file = fmt::format("grid_{}.vtu", stem);
  write_grid_vtu<D>(folder_.file(grid_file), grid, active, nodal);
  grid_series_.add(t, grid_file);
  grid_series_.write(folder_.file("grid.pvd"));
}

template <int D>
void RunOutput<D>::record_history(double t, const numerics::MaterialPoints<D>& mp,
                                  const numerics::FluidPoints<D>& fp) {
  fluid_columns_ = fp.size() > 0;
  std::vector<double> row{t};
  for (const auto p : control_index_) {
    for (int d = 0; d < D; ++d) row.push_back(mp.displacement[p][d]);
    for (int d = 0; d < D; ++d) row.push_back(mp.velocity[p][d]);
    for (int k = 0; k < 6; ++k) row.push_back(mp.stress[p][k]);
    if (!fluid_columns_) continue;
    row.push_back(fp.liquid_pressure[p]);
    row.push_back(fp.gas_pressure[p]);
    row.push_back(physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]));
    row.push_back(fp.saturation[p]);
  }
  control_rows_.push_back(std::move(row));

  double kinetic = 0.0, mass = 0.0;
  numerics::Vec<D> momentum = numerics::Vec<D>::Zero();
  numerics::Vec<D> lo = mp.position[0], hi = mp.position[0];
  for (std::size_t p = 0; p < mp.size(); ++p) {
    kinetic += 0.5 * mp.mass[p] * mp.velocity[p].squaredNorm();
    mass += mp.mass[p];
    momentum += mp.mass[p] * mp.velocity[p];
    lo = lo.cwiseMin(mp.position[p]);
    hi = hi.cwiseMax(mp.position[p]);
  }
  std::vector<double> g{t, kinetic, mass};
  for (int d = 0; d < D; ++d) g.push_back(momentum[d]);
  // The points' extent: the front of a slide is max x (the toe of a slope facing +x).
  for (int d = 0; d < D; ++d) g.push_back(lo[d]), g.push_back(hi[d]);
  global_rows_.push_back(std::move(g));
}

template <int D>
void RunOutput<D>::record_balance(double t, const numerics::FluidBalance& b) {
  if (balance_rows_.empty()) initial_ = b;
  // Relative to the initial mass; a fluid absent at the start (the gas of a saturated soil) is
  // measured against its initial capacity, the mass that would fill the pores (docs/output.md).
  const auto relative = [](double mass, double initial, double inflow, double capacity) {
    return (mass - initial - inflow) / (initial > 0.0 ? initial : capacity);
  };
  const double ml =
      relative(b.liquid_mass, initial_.liquid_mass, b.liquid_inflow, initial_.liquid_capacity);
  const double mg = relative(b.gas_mass, initial_.gas_mass, b.gas_inflow, initial_.gas_capacity);
  balance_rows_.push_back({t, b.liquid_mass, b.liquid_inflow, ml, b.gas_mass, b.gas_inflow, mg});
  max_mismatch_[0] = std::max(max_mismatch_[0], std::abs(ml));
  max_mismatch_[1] = std::max(max_mismatch_[1], std::abs(mg));
}

template <int D>
void RunOutput<D>::flush(const RunSummary& s) const {
  std::vector<std::string> header{"time"};
  for (std::size_t i = 0; i < control_index_.size(); ++i) {
    const std::string& name = case_.output.control_points[i].name;
    for (int d = 0; d < D; ++d)
      header.push_back(fmt::format("{}_displacement_{}", name, axis_name(d)));
    for (int d = 0; d < D; ++d) header.push_back(fmt::format("{}_velocity_{}", name, axis_name(d)));
    for (const char* v : voigt_names) header.push_back(fmt::format("{}_net_stress_{}", name, v));
    if (fluid_columns_)
      for (const char* f : {"liquid_pressure", "gas_pressure", "suction", "degree_of_saturation"})
        header.push_back(fmt::format("{}_{}", name, f));
  }
  if (!control_index_.empty())
    write_text_atomically(folder_.file("control_points.csv"), csv(header, control_rows_));
  std::vector<std::string> gheader{"time", "kinetic_energy", "mass"};
  for (int d = 0; d < D; ++d) gheader.push_back(fmt::format("momentum_{}", axis_name(d)));
  for (int d = 0; d < D; ++d) {
    gheader.push_back(fmt::format("min_{}", axis_name(d)));
    gheader.push_back(fmt::format("max_{}", axis_name(d)));
  }
  write_text_atomically(folder_.file("globals.csv"), csv(gheader, global_rows_));
  if (!balance_rows_.empty())
    write_text_atomically(folder_.file("conservation.csv"),
                          csv({"time", "liquid_mass", "liquid_inflow", "liquid_mismatch",
                               "gas_mass", "gas_inflow", "gas_mismatch"},
                              balance_rows_));

  std::string cps = "{";
  for (std::size_t i = 0; i < control_index_.size(); ++i)
    cps += fmt::format("{}{}: {}", i ? ", " : "", json_string(case_.output.control_points[i].name),
                       control_index_[i]);
  cps += "}";
  const double mp_steps = double(s.steps) * double(s.n_points);
  const std::string json = fmt::format(
      "{{\n  \"case\": {},\n  \"case_file\": {},\n  \"status\": {},\n  \"message\": {},\n"
      "  \"dimension\": {},\n  \"cycle\": {},\n"
      "  \"material_points\": {},\n  \"grid_nodes\": {},\n  \"threads\": {},\n  \"steps\": {},\n"
      "  \"simulated_time_s\": {},\n  \"last_time_step_s\": {},\n"
      "  \"wall_time_s\": {},\n  \"ns_per_mp_step\": {},\n"
      "  \"control_point_mp_ids\": {}{}{}{}{}{}\n}}\n",
      json_string(case_.name), json_string(case_.file), json_string(s.status),
      json_string(s.message), D, json_string(s.cycle), s.n_points, s.n_nodes, s.n_threads, s.steps,
      json_number(s.simulated_time, "{:.17g}"), json_number(s.last_time_step, "{:.17g}"),
      json_number(s.wall_time, "{:.6f}"),
      json_number(mp_steps > 0 ? 1e9 * s.wall_time / mp_steps : 0.0, "{:.3f}"), cps,
      balance_rows_.empty() ? std::string()
                            : fmt::format(",\n  \"max_relative_mismatch_liquid\": {},\n"
                                          "  \"max_relative_mismatch_gas\": {}",
                                          json_number(max_mismatch_[0], "{:.6e}"),
                                          json_number(max_mismatch_[1], "{:.6e}")),
      s.solver_statistics.empty()
          ? std::string()
          : ",\n  \"solver_statistics\": " + json_numbers_finite(s.solver_statistics),
      s.gravity_loading.empty()
          ? std::string()
          : ",\n  \"gravity_loading\": " + json_numbers_finite(s.gravity_loading),
      s.failure_step == 0 ? std::string()
                          : fmt::format(",\n  \"failure_step\": {},\n  \"failure_time_s\": {},\n"
                                        "  \"last_good_time_s\": {},\n  \"last_good_file\": "
                                        "\"points_last_good.vtu\"",
                                        s.failure_step, json_number(s.failure_time, "{:.17g}"),
                                        json_number(s.last_good_time, "{:.17g}")),
      s.resumes == 0 ? std::string()
                     : fmt::format(",\n  \"resumes\": {},\n  \"resumed_from_s\": {}", s.resumes,
                                   json_number(s.resumed_from, "{:.17g}")));
  write_text_atomically(folder_.file("run_summary.json"), json);
}

namespace {

void save_rows(CheckpointWriter& w, const std::string& name,
               const std::vector<std::vector<double>>& rows) {
  std::vector<std::int64_t> lengths;
  std::vector<double> values;
  for (const auto& row : rows) {
    lengths.push_back(static_cast<std::int64_t>(row.size()));
    values.insert(values.end(), row.begin(), row.end());
  }
  w.put(name + ".lengths", lengths);
  w.put(name + ".values", values);
}

std::vector<std::vector<double>> restore_rows(CheckpointReader& r, const std::string& name) {
  std::vector<std::int64_t> lengths;
  std::vector<double> values;
  r.get(name + ".lengths", lengths);
  r.get(name + ".values", values);
  std::vector<std::vector<double>> rows;
  std::size_t at = 0;
  for (const auto n : lengths) {
    if (n < 0 || static_cast<std::size_t>(n) > values.size() - at)
      r.fail("section '" + name + ".lengths' does not match its values");
    rows.emplace_back(values.begin() + static_cast<std::ptrdiff_t>(at),
                      values.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += static_cast<std::size_t>(n);
  }
  if (at != values.size()) r.fail("section '" + name + ".values' holds more than its rows");
  return rows;
}

void save_series(CheckpointWriter& w, const std::string& name, const PvdSeries& series) {
  w.put(name + ".times", series.times());
  std::string files;
  for (const auto& f : series.files()) files += f + '\n';
  w.text(name + ".files", files);
}

PvdSeries restore_series(CheckpointReader& r, const std::string& name) {
  std::vector<double> times;
  r.get(name + ".times", times);
  const std::string files = r.text(name + ".files");
  PvdSeries series;
  std::size_t at = 0;
  for (const double t : times) {
    const auto end = files.find('\n', at);
    if (end == std::string::npos) r.fail("section '" + name + ".files' lists too few files");
    series.add(t, files.substr(at, end - at));
    at = end + 1;
  }
  if (at != files.size()) r.fail("section '" + name + ".files' lists too many files");
  return series;
}

}  // namespace

template <int D>
void RunOutput<D>::save(CheckpointWriter& w) const {
  w.put("output.control_index", control_index_);
  save_rows(w, "output.control_rows", control_rows_);
  save_rows(w, "output.global_rows", global_rows_);
  save_rows(w, "output.balance_rows", balance_rows_);
  w.value("output.fluid_columns", std::uint8_t{fluid_columns_});
  for (const double x :
       {initial_.liquid_mass, initial_.gas_mass, initial_.liquid_inflow, initial_.gas_inflow,
        initial_.liquid_capacity, initial_.gas_capacity, max_mismatch_[0], max_mismatch_[1]})
    w.value("output.balance", x);
  save_series(w, "output.points_series", points_series_);
  save_series(w, "output.grid_series", grid_series_);
  w.value("output.frame", std::int64_t{frame_});
}

template <int D>
void RunOutput<D>::restore(CheckpointReader& r) {
  r.get_sized("output.control_index", control_index_, control_index_.size());
  control_rows_ = restore_rows(r, "output.control_rows");
  global_rows_ = restore_rows(r, "output.global_rows");
  balance_rows_ = restore_rows(r, "output.balance_rows");
  fluid_columns_ = r.value<std::uint8_t>("output.fluid_columns") != 0;
  for (double* x :
       {&initial_.liquid_mass, &initial_.gas_mass, &initial_.liquid_inflow, &initial_.gas_inflow,
        &initial_.liquid_capacity, &initial_.gas_capacity, &max_mismatch_[0], &max_mismatch_[1]})
    *x = r.value<double>("output.balance");
  points_series_ = restore_series(r, "output.points_series");
  grid_series_ = restore_series(r, "output.grid_series");
  frame_ = static_cast<int>(r.value<std::int64_t>("output.frame"));
}

template class RunOutput<1>;
template class RunOutput<2>;
template class RunOutput<3>;

}  // namespace unsatmpm
