#include "numerics/amg_preconditioner.hpp"

#include <mpi.h>
// hypre's headers after MPI's.
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace unsatmpm::numerics {

namespace {

void check_hypre(HYPRE_Int flag, const char* call) {
  if (flag != 0) {
    HYPRE_ClearAllErrors();
    throw std::runtime_error(std::string(call) + " failed with hypre error " +
                             std::to_string(flag));
  }
}

void finalise_parallel_runtime() {
  HYPRE_Finalize();
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (finalised == 0) MPI_Finalize();
}

// MPI (hypre's communicator) and hypre, once per process; finalised at exit.
void initialise_parallel_runtime() {
  static const bool done = [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised == 0 && MPI_Init(nullptr, nullptr) != MPI_SUCCESS)
      throw std::runtime_error("MPI_Init failed (needed by hypre's algebraic multigrid)");
    check_hypre(HYPRE_Init(), "HYPRE_Init");
    std::atexit(finalise_parallel_runtime);
    return true;
  }();
  (void)done;
}

}  // namespace

struct AmgPreconditioner::Impl {
  static constexpr int cycles_per_application = 2;

  std::int64_t n = 0;                  // rows of the matrix set up last
  std::vector<HYPRE_BigInt> rows;      // 0..n-1
  std::vector<HYPRE_Int> row_lengths;  // entries per row
  std::vector<HYPRE_BigInt> columns;   // the pattern's columns in hypre's integer type
  HYPRE_IJMatrix matrix = nullptr;
  HYPRE_IJVector rhs = nullptr, solution = nullptr;
  HYPRE_Solver amg = nullptr;

  ~Impl() { release(); }

  void release() {
    if (amg != nullptr) HYPRE_BoomerAMGDestroy(amg);
    if (matrix != nullptr) HYPRE_IJMatrixDestroy(matrix);
    if (rhs != nullptr) HYPRE_IJVectorDestroy(rhs);
    if (solution != nullptr) HYPRE_IJVectorDestroy(solution);
    amg = nullptr, matrix = nullptr, rhs = nullptr, solution = nullptr;
  }

  // The pattern in hypre's integer types (converted at every setup: a pass over the entries,
  // small beside the hierarchy's construction, and no second copy of the pattern kept).
  void adopt_pattern(const SparsePattern& p) {
    if (p.n > std::numeric_limits<HYPRE_Int>::max() ||
        p.n_nonzeros() > std::numeric_limits<HYPRE_Int>::max())
      throw std::runtime_error("AmgPreconditioner: the matrix exceeds hypre's 32-bit indices");
    n = p.n;
    const auto rows_n = static_cast<std::size_t>(p.n);
    rows.resize(rows_n);
    row_lengths.resize(rows_n);
    for (std::size_t i = 0; i < rows_n; ++i) {
      rows[i] = static_cast<HYPRE_BigInt>(i);
      row_lengths[i] = static_cast<HYPRE_Int>(p.row_ptr[i + 1] - p.row_ptr[i]);
    }
    columns.assign(p.col.begin(), p.col.end());
  }

  HYPRE_IJVector make_vector() const {
    HYPRE_IJVector v = nullptr;
    const auto last = static_cast<HYPRE_BigInt>(n - 1);
    check_hypre(HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, last, &v), "HYPRE_IJVectorCreate");
    check_hypre(HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR), "HYPRE_IJVectorSetObjectType");
    check_hypre(HYPRE_IJVectorInitialize(v), "HYPRE_IJVectorInitialize");
    check_hypre(HYPRE_IJVectorAssemble(v), "HYPRE_IJVectorAssemble");
    return v;
  }

  void build_matrix(std::span<const double> values) {
    const auto last = static_cast<HYPRE_BigInt>(n - 1);
    check_hypre(HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, last, 0, last, &matrix),
                "HYPRE_IJMatrixCreate");
    check_hypre(HYPRE_IJMatrixSetObjectType(matrix, HYPRE_PARCSR), "HYPRE_IJMatrixSetObjectType");
    check_hypre(HYPRE_IJMatrixSetRowSizes(matrix, row_lengths.data()), "HYPRE_IJMatrixSetRowSizes");
    check_hypre(HYPRE_IJMatrixInitialize(matrix), "HYPRE_IJMatrixInitialize");
    std::vector<HYPRE_Int> lengths = row_lengths;  // hypre may write to the counts
    check_hypre(HYPRE_IJMatrixSetValues(matrix, static_cast<HYPRE_Int>(n), lengths.data(),
                                        rows.data(), columns.data(), values.data()),
                "HYPRE_IJMatrixSetValues");
    check_hypre(HYPRE_IJMatrixAssemble(matrix), "HYPRE_IJMatrixAssemble");
  }

  // Settings for the pressure systems' nonsymmetric, diagonally dominant matrices: HMIS
  // coarsening with extended+i interpolation truncated to 4 entries per row (hypre's recommended
  // setting for 2D and 3D problems), hybrid Gauss-Seidel smoothing, two V-cycles per application:
  // on the 2D scaling block with 99,904 unknowns (docs/performance.md) they took GMRES from 1,371
  // to 777 iterations and the flow from 34.1 to 28.9 s (one V-cycle: about 7.7 iterations per
  // Newton iteration at 3e5 unknowns, and growing, with GMRES's orthogonalisation growing as
  // their square). A stronger threshold (0.5), the systems (two-function, nodal) variants and
  // symmetric smoothing changed the iterations by less than 10 %. Not robust yet at 3e5 unknowns
  // and beyond: there the two-cycle run took 892 s with 195 preconditioner setups in 321 steps,
  // a one-cycle run (an earlier binary) 234 s with 55 in 223 (docs/performance.md).
  void create_solver() {
    check_hypre(HYPRE_BoomerAMGCreate(&amg), "HYPRE_BoomerAMGCreate");
    HYPRE_BoomerAMGSetPrintLevel(amg, 0);
    HYPRE_BoomerAMGSetMaxIter(amg, cycles_per_application);
    HYPRE_BoomerAMGSetTol(amg, 0.0);
    HYPRE_BoomerAMGSetCoarsenType(amg, 10);
    HYPRE_BoomerAMGSetInterpType(amg, 6);
    HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
    HYPRE_BoomerAMGSetStrongThreshold(amg, 0.25);
    HYPRE_BoomerAMGSetRelaxType(amg, 3);
    HYPRE_BoomerAMGSetNumSweeps(amg, 1);
  }

  HYPRE_ParCSRMatrix parcsr_matrix() const {
    void* object = nullptr;
    check_hypre(HYPRE_IJMatrixGetObject(matrix, &object), "HYPRE_IJMatrixGetObject");
    return static_cast<HYPRE_ParCSRMatrix>(object);
  }
  static HYPRE_ParVector parcsr_vector(HYPRE_IJVector v) {
    void* object = nullptr;
    check_hypre(HYPRE_IJVectorGetObject(v, &object), "HYPRE_IJVectorGetObject");
    return static_cast<HYPRE_ParVector>(object);
  }
};

AmgPreconditioner::AmgPreconditioner() : impl_(std::make_unique<Impl>()) {
  initialise_parallel_runtime();
}

AmgPreconditioner::~AmgPreconditioner() = default;

void AmgPreconditioner::setup(const SparsePattern& pattern, std::span<const double> values) {
  Impl& s = *impl_;
  if (static_cast<std::int64_t>(values.size()) != pattern.n_nonzeros())
    throw std::invalid_argument("AmgPreconditioner::setup: values and pattern differ in size");
  s.release();
  s.adopt_pattern(pattern);
  s.build_matrix(values);
  s.rhs = s.make_vector();
  s.solution = s.make_vector();
  s.create_solver();
  check_hypre(HYPRE_BoomerAMGSetup(s.amg, s.parcsr_matrix(), s.parcsr_vector(s.rhs),
                                   s.parcsr_vector(s.solution)),
              "HYPRE_BoomerAMGSetup");
}

void AmgPreconditioner::apply(std::span<const double> r, std::span<double> z) {
  Impl& s = *impl_;
  if (s.amg == nullptr) throw std::logic_error("AmgPreconditioner::apply before setup()");
  const auto n = static_cast<HYPRE_Int>(s.n);
  if (static_cast<std::int64_t>(r.size()) != s.n || static_cast<std::int64_t>(z.size()) != s.n)
    throw std::invalid_argument("AmgPreconditioner::apply: vector length differs from n");
  check_hypre(HYPRE_IJVectorSetValues(s.rhs, n, s.rows.data(), r.data()),
              "HYPRE_IJVectorSetValues");
  std::fill(z.begin(), z.end(), 0.0);
  check_hypre(HYPRE_IJVectorSetValues(s.solution, n, s.rows.data(), z.data()),
              "HYPRE_IJVectorSetValues");
  // V-cycles with tolerance 0 stop at their iteration limit, which hypre flags as a
  // convergence error: expected here, so it is cleared rather than reported.
  HYPRE_BoomerAMGSolve(s.amg, s.parcsr_matrix(), s.parcsr_vector(s.rhs),
                       s.parcsr_vector(s.solution));
  const HYPRE_Int other_errors = HYPRE_GetError() & ~HYPRE_ERROR_CONV;
  HYPRE_ClearAllErrors();
  check_hypre(other_errors, "HYPRE_BoomerAMGSolve");
  check_hypre(HYPRE_IJVectorGetValues(s.solution, n, s.rows.data(), z.data()),
              "HYPRE_IJVectorGetValues");
}

}  // namespace unsatmpm::numerics
