// SUNDIALS handles owned by unique_ptrs whose deleters are the matching SUNDIALS destructors, for
// the CVODE wrapper's files (numerics/cvode_*, numerics/klu_keeper.*, numerics/umfpack_keeper.*,
// numerics/krylov_keeper.*) only: no other file includes a SUNDIALS header.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics::sundials {

/// v's dot product, N_VDotProd, becomes numerics::dot, for v and every vector cloned from it
/// (clones take the operations table): a GMRES made on v orthogonalises with it.
inline void use_blocked_dot(N_Vector v) {
  v->ops->nvdotprod = [](N_Vector x, N_Vector y) -> realtype {
    const auto n = static_cast<std::size_t>(N_VGetLength(x));
    return dot(std::span<const double>(N_VGetArrayPointer(x), n),
               std::span<const double>(N_VGetArrayPointer(y), n));
  };
}

struct ContextDeleter {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
// A forwarding solver does not own its content: detach it, free ops and struct.
struct ForwardingSolverDeleter {
  void operator()(SUNLinearSolver s) const {
    s->content = nullptr;
    SUNLinSolFreeEmpty(s);
  }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using ForwardingSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, ForwardingSolverDeleter>;

template <class T>
T check_created(T handle, const char* call) {
  if (handle == nullptr) throw std::runtime_error(std::string(call) + " returned NULL");
  return handle;
}

/// A custom matrix-based (direct) linear solver whose content is `owner` (not owned) and whose
/// setup, solve and last flag are the owner's; its initialize is a no-op, so that CVodeReInit
/// keeps the owner's symbolic analysis (numerics/umfpack_keeper.hpp, numerics/klu_keeper.hpp).
inline ForwardingSolverPtr direct_solver(SUNContext context, void* owner,
                                         int (*setup)(SUNLinearSolver, SUNMatrix),
                                         int (*solve)(SUNLinearSolver, SUNMatrix, N_Vector,
                                                      N_Vector, realtype),
                                         sunindextype (*last_flag)(SUNLinearSolver)) {
  ForwardingSolverPtr s(check_created(SUNLinSolNewEmpty(context), "SUNLinSolNewEmpty"));
  s->content = owner;
  s->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  s->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  s->ops->initialize = [](SUNLinearSolver) { return SUNLS_SUCCESS; };
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = last_flag;
  return s;
}

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace unsatmpm::numerics::sundials
