// The main cycle's sections of a checkpoint (checkpoint/checkpoint_file.hpp) besides the points:
// what the flow's next start carries over from the last interval, and the counters of the run so
// far (cycles/implicit_solver.hpp saves and restores them).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "cycles/implicit_diagnostics.hpp"
#include "numerics/cvode_integrator.hpp"
#include "numerics/pressure/pressure_system.hpp"

namespace unsatmpm {

/// CVODE's counts of two parts of a run added (the times and step of the later part).
inline numerics::CvodeStatistics add_counts(const numerics::CvodeStatistics& a,
                                            const numerics::CvodeStatistics& b) {
  numerics::CvodeStatistics s = b;
  s.steps += a.steps, s.rhs_evaluations += a.rhs_evaluations;
  s.newton_iterations += a.newton_iterations, s.jacobian_evaluations += a.jacobian_evaluations;
  s.error_test_failures += a.error_test_failures;
  s.convergence_failures += a.convergence_failures;
  s.lu_analyses += a.lu_analyses, s.lu_factorisations += a.lu_factorisations;
  s.lu_seconds += a.lu_seconds, s.lu_setup_seconds += a.lu_setup_seconds;
  s.linear_iterations += a.linear_iterations, s.preconditioner_setups += a.preconditioner_setups;
  s.linear_failures += a.linear_failures;
  s.preconditioner_seconds += a.preconditioner_seconds;
  return s;
}

/// The nodal pressures of the last update [Pa], the inflows [kg] and the pressure system's
/// carried flags.
inline void save_flow_carry(CheckpointWriter& w, const std::array<std::vector<double>, 2>& nodal,
                            const std::array<double, 2>& inflow_done,
                            const std::array<double, 2>& inflow_now,
                            const numerics::PrepareCarry& carried) {
  w.put("flow.nodal_liquid", nodal[0]);
  w.put("flow.nodal_gas", nodal[1]);
  for (int a = 0; a < 2; ++a) w.value("flow.inflow_done", inflow_done[a]);
  for (int a = 0; a < 2; ++a) w.value("flow.inflow_now", inflow_now[a]);
  w.put("flow.active", carried.active);
  w.put("flow.surface", carried.surface);
  for (int a = 0; a < 2; ++a) w.put("flow.prescribed", carried.prescribed[a]);
  for (int a = 0; a < 2; ++a) w.put("flow.exempt", carried.exempt[a]);
}

/// Reads what save_flow_carry wrote; every nodal column holds `n_nodes` values or none.
inline numerics::PrepareCarry restore_flow_carry(CheckpointReader& r, std::int64_t n_nodes,
                                                 std::array<std::vector<double>, 2>& nodal,
                                                 std::array<double, 2>& inflow_done,
                                                 std::array<double, 2>& inflow_now) {
  const auto nodes = [&](const char* name, auto& column) {
    r.get(name, column);
    if (!column.empty() && static_cast<std::int64_t>(column.size()) != n_nodes)
      r.fail(std::string("section '") + name + "' holds " + std::to_string(column.size()) +
             " nodes where the grid has " + std::to_string(n_nodes));
  };
  nodes("flow.nodal_liquid", nodal[0]);
  nodes("flow.nodal_gas", nodal[1]);
  for (int a = 0; a < 2; ++a) inflow_done[a] = r.value<double>("flow.inflow_done");
  for (int a = 0; a < 2; ++a) inflow_now[a] = r.value<double>("flow.inflow_now");
  numerics::PrepareCarry c;
  nodes("flow.active", c.active);
  nodes("flow.surface", c.surface);
  for (int a = 0; a < 2; ++a) nodes("flow.prescribed", c.prescribed[a]);
  for (int a = 0; a < 2; ++a) nodes("flow.exempt", c.exempt[a]);
  return c;
}

/// The cycle's counters and CVODE's counts of the run so far.
inline void save_counters(CheckpointWriter& w, const FlowCounters& c,
                          const numerics::CvodeStatistics& s) {
  for (const std::int64_t n :
       {c.coupling_intervals, c.mechanics_substeps, c.correction_factorisations,
        c.correction_iterations, c.correction_direct_solves})
    w.value("counters.count", n);
  for (const double x : {c.correction_seconds, c.flow_seconds, c.rhs_seconds, c.jacobian_seconds,
                         c.mechanics_seconds})
    w.value("counters.seconds", x);
  for (const long n :
       {s.steps, s.rhs_evaluations, s.newton_iterations, s.jacobian_evaluations,
        s.error_test_failures, s.convergence_failures, s.lu_analyses, s.lu_factorisations,
        s.linear_iterations, s.preconditioner_setups, s.linear_failures})
    w.value("cvode.count", static_cast<std::int64_t>(n));
  for (const double x : {s.lu_seconds, s.lu_setup_seconds, s.preconditioner_seconds})
    w.value("cvode.seconds", x);
  for (const long n : {static_cast<long>(s.lu_ordering), s.lu_ordering_tried_on})
    w.value("cvode.lu_ordering", static_cast<std::int64_t>(n));
}

/// Reads what save_counters wrote, and hands CVODE the saved run's sparse-LU ordering.
inline void restore_counters(CheckpointReader& r, FlowCounters& c, numerics::CvodeStatistics& s,
                             numerics::CvodeIntegrator& cvode) {
  for (std::int64_t* n :
       {&c.coupling_intervals, &c.mechanics_substeps, &c.correction_factorisations,
        &c.correction_iterations, &c.correction_direct_solves})
    *n = r.value<std::int64_t>("counters.count");
  for (double* x : {&c.correction_seconds, &c.flow_seconds, &c.rhs_seconds, &c.jacobian_seconds,
                    &c.mechanics_seconds})
    *x = r.value<double>("counters.seconds");
  for (long* n :
       {&s.steps, &s.rhs_evaluations, &s.newton_iterations, &s.jacobian_evaluations,
        &s.error_test_failures, &s.convergence_failures, &s.lu_analyses, &s.lu_factorisations,
        &s.linear_iterations, &s.preconditioner_setups, &s.linear_failures})
    *n = static_cast<long>(r.value<std::int64_t>("cvode.count"));
  for (double* x : {&s.lu_seconds, &s.lu_setup_seconds, &s.preconditioner_seconds})
    *x = r.value<double>("cvode.seconds");
  const auto ordering = r.value<std::int64_t>("cvode.lu_ordering");
  const auto tried_on = r.value<std::int64_t>("cvode.lu_ordering");
  cvode.set_lu_ordering(static_cast<int>(ordering), static_cast<long>(tried_on));
}

}  // namespace unsatmpm
