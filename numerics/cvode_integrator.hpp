// Implicit time integration of dy/dt = f(t, y), y in R^n, with SUNDIALS CVODE: variable-order
// (1..5), variable-step BDF, Newton iteration, each Newton system (I - gamma J) on a fixed CSR
// sparsity pattern solved either by a sparse direct solver, UMFPACK (Davis, ACM TOMS 30 (2004) 196)
// or KLU (Davis & Palamadai Natarajan, ACM TOMS 37 (2010) 36), or by GMRES preconditioned with
// algebraic multigrid (numerics/krylov_keeper.hpp); CVODE after Hindmarsh et al., ACM TOMS 31
// (2005) 363. Local error control: the weighted RMS norm
// with weights 1 / (rtol |y_i| + atol) stays below 1 per step.
//
// This is the project's one wrapper around SUNDIALS (STYLE.md, "SUNDIALS behind one RAII
// wrapper"): only its own files (numerics/cvode_*.cpp and the solver keepers) include SUNDIALS
// headers, this one none. One object owns the context, the state vector, the sparse matrix and
// the sparse LU or the GMRES solver and its preconditioner, and the CVODE memory; the destructor is
// the only cleanup path.
//
// Callback contract (rhs and Jacobian): return 0 on success; > 0 for a recoverable failure (e.g.
// a saturation out of range): CVODE then retries the step with a smaller step size (a Newton
// convergence failure; after 10 in one step, or on the very first rhs call at t0, the integration
// fails with CV_REPTD_RHSFUNC_ERR / CV_FIRST_RHSFUNC_ERR); < 0 for an unrecoverable failure.
// Exceptions thrown by a callback never cross into C: they are caught, the callback returns -1,
// and integrate_to() rethrows the original exception once CVode has returned.
//
// Units are the caller's: t in the units of the rhs (s in the cycles), y as the unknowns are.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

/// Scalar local error tolerances: relative [-] and absolute [units of y]; both > 0 and finite.
struct CvodeTolerances {
  double relative;
  double absolute;
};

/// The linear solver of the Newton systems: a sparse LU (`direct`), GMRES with algebraic multigrid
/// (`iterative`), or chosen by the number of unknowns at each reset (`automatic`).
enum class LinearSolverChoice { automatic, direct, iterative };
/// The sparse LU of `direct`: UMFPACK (multifrontal, the default; numerics/umfpack_keeper.hpp) or
/// KLU (numerics/klu_keeper.hpp).
enum class DirectSolverChoice { umfpack, klu };

/// Counters cumulative over the object's life (all resets); last_step and current_time are those
/// of the current CVODE run.
struct CvodeStatistics {
  long steps = 0;
  long rhs_evaluations = 0;  // calls of the rhs callback
  long newton_iterations = 0;
  long jacobian_evaluations = 0;  // calls of the Jacobian callback
  long error_test_failures = 0;
  long convergence_failures = 0;  // Newton convergence failures (incl. recoverable callback errors)
  DirectSolverChoice direct_solver = DirectSolverChoice::umfpack;  // the sparse LU set
  long lu_analyses = 0;            // the sparse LU's symbolic analyses actually performed
  long lu_factorisations = 0;      // linear-solver setups: numeric (re)factorisations
  double lu_seconds = 0.0;         // wall time in the sparse LU: factorisations and solves [s]
  double lu_setup_seconds = 0.0;   // of which in the factorisations [s]
  long lu_ordering_trials = 0;     // matrices factorised with both orderings to choose one
  int lu_ordering = -1;            // the last analysis's: 0 AMD, 1 COLAMD (-1: none yet)
  long lu_ordering_tried_on = 0;   // the unknowns of the matrix that ordering was chosen on
  long linear_iterations = 0;      // GMRES iterations (0 with a sparse LU)
  long linear_failures = 0;        // GMRES solves that ended short of their tolerance (0 with LU)
  long preconditioner_setups = 0;  // multigrid hierarchies built (0 with a sparse LU)
  double preconditioner_seconds = 0.0;  // wall time in their setups and V-cycles [s]
  double last_step = 0.0;               // size of the last successful internal step
  double current_time = 0.0;            // time reached by the internal integrator
};

/// A failed CVode call: the return flag, the time reached and the component with the largest
/// weighted local error estimate |e_i| w_i (-1 when CVODE had not attempted a step).
class CvodeError : public std::runtime_error {
 public:
  CvodeError(const std::string& message, int flag, std::string flag_name, double time,
             std::int64_t worst_component);
  int flag() const { return flag_; }
  const std::string& flag_name() const { return flag_name_; }
  double time() const { return time_; }
  std::int64_t worst_component() const { return worst_component_; }

 private:
  int flag_;
  std::string flag_name_;
  double time_;
  std::int64_t worst_component_;
};

/// Thrown out of integrate_to() when the stop check (set_stop_check) asked to end the
/// integration: a request from outside, such as a signal, not a numerical failure.
class StopRequested : public std::runtime_error {
 public:
  explicit StopRequested(const std::string& what, std::int64_t worst_component = -1,
                         std::string where = {})
      : std::runtime_error(what), worst_component_(worst_component), where_(std::move(where)) {}
  /// The component with the largest weighted local error in CVODE's last step attempt (-1 if
  /// none was estimated yet): where a stalled integration struggles.
  std::int64_t worst_component() const { return worst_component_; }
  /// Where the integration stood, in the words of the integrator's user (empty: not said).
  const std::string& where() const { return where_; }

 private:
  std::int64_t worst_component_;
  std::string where_;
};

class CvodeIntegrator {
 public:
  /// ydot = f(t, y). Spans have length n; y is CVODE's work vector, not state().
  using Rhs = std::function<int(double t, std::span<const double> y, std::span<double> ydot)>;
  /// Fill values (length nnz, already zeroed) with df/dy in the order of the pattern's entries;
  /// f = f(t, y) is passed for reuse.
  using Jacobian = std::function<int(double t, std::span<const double> y, std::span<const double> f,
                                     std::span<double> values)>;
  /// Fill g (length n) with the root functions at (t, y); return 0, or non-zero to fail.
  using Roots = std::function<int(double t, std::span<const double> y, std::span<double> g)>;
  /// True once the integration should end (polled before each rhs and Jacobian evaluation).
  using StopCheck = std::function<bool()>;

  /// Throws std::invalid_argument if a tolerance is not positive and finite, or a callback is
  /// empty.
  CvodeIntegrator(Rhs rhs, Jacobian jacobian, CvodeTolerances tolerances);
  ~CvodeIntegrator();
  /// Moves keep CVODE's pointers valid (they point at the heap-held Impl); a moved-from object may
  /// only be destroyed or assigned to.
  CvodeIntegrator(CvodeIntegrator&&) noexcept;
  CvodeIntegrator& operator=(CvodeIntegrator&&) noexcept;
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  /// Start a new problem at (t0, y0). A pattern equal to the current one keeps the matrix, the
  /// sparse LU and its symbolic analysis (CVodeReInit only); a different one re-creates the
  /// vector, matrix, linear solver and CVODE memory. Throws std::invalid_argument on a malformed
  /// pattern or size mismatch; options (max step, max steps) carry over.
  void reset(const SparsePattern& pattern, double t0, std::span<const double> y0);

  /// Integrate to t_out (CVODE's CV_NORMAL: internal steps may pass t_out, the solution is
  /// interpolated there, or stops at the stop time if one is set). Returns the time reached.
  /// On failure throws CvodeError (or the callback's own exception) and state() holds the last
  /// successful internal step. t_out equal to the current time returns at once. Throws
  /// std::logic_error before the first reset().
  double integrate_to(double t_out);

  /// The unknowns: one contiguous buffer that CVODE's N_Vector wraps without copying. Writing to it
  /// does not change the integration until the next reset(), which may take state() as y0.
  std::span<const double> state() const;
  std::span<double> state();

  const CvodeStatistics& statistics() const;
  /// Takes the sparse LU's ordering as chosen on a matrix of `tried_on` unknowns (statistics()'s
  /// lu_ordering and lu_ordering_tried_on of a saved run), so that a resumed run factorises as
  /// the saved one would have; ordering -1 leaves the choice to the next analysis's trial.
  void set_lu_ordering(int ordering, long tried_on);
  /// Where the integration stands now, read from CVODE itself (also from inside a callback,
  /// where statistics() still holds the last call's): the time its last successful internal
  /// step reached [s] and that step's size [s]; {0, 0} before the first reset().
  std::pair<double, double> position() const;

  /// Upper bound on the internal step size (> 0; infinity = no bound, the default).
  void set_max_step(double max_step);
  /// CVODE's rootfinding from the next reset() on: integrate_to() stops at the first t where one
  /// of the n functions falls through zero (rising crossings are ignored) and returns that t,
  /// below t_out. n = 0 (or an empty callback) turns it off.
  void set_roots(int n, Roots roots);
  /// After integrate_to() stopped at a root: the indices of the functions that fell through zero.
  std::vector<int> roots_found() const;
  /// The linear solver from the next reset() on (default: direct); `automatic` takes the
  /// iterative one for patterns of `iterative_from` unknowns or more (ignored otherwise; > 0). A
  /// reset whose choice resolves to another solver than the live one re-creates the solver
  /// objects.
  void set_linear_solver(LinearSolverChoice choice, std::int64_t iterative_from = 1);
  /// The sparse LU of `direct` from the next reset() on (default: UMFPACK); a reset after a change
  /// re-creates the solver objects.
  void set_direct_solver(DirectSolverChoice choice);
  /// Whether the live solver is GMRES with multigrid (false before the first reset).
  bool iterative() const;
  /// Maximum number of internal steps per integrate_to() call (> 0; CVODE's default is 500).
  void set_max_num_steps(long max_num_steps);
  /// A check polled before every rhs and Jacobian evaluation (and preconditioner setup): once it
  /// returns true, the evaluation fails, CVODE returns, and integrate_to() throws StopRequested
  /// with state() at the last successful internal step. So a request from outside ends even an
  /// integration that crawls within milliseconds. Empty (the default): never stops.
  void set_stop_check(StopCheck check);
  /// Never step past t_stop (CVodeSetStopTime). One-shot, as in CVODE: cleared once reached and
  /// by reset(). Needs a reset() first.
  void set_stop_time(double t_stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace unsatmpm::numerics
