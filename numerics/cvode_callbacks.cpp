// The functions CVODE calls back (numerics/cvode_impl.hpp): no exception crosses into C; each
// is caught, kept, and rethrown by integrate_to() once CVode has returned. The evaluations poll
// the stop check first, so that a stop request ends the integration at the next one.
#include <exception>
#include <span>
#include <string>

#include "numerics/cvode_impl.hpp"

namespace unsatmpm::numerics {

int CvodeIntegrator::Impl::rhs_callback(realtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto& self = *static_cast<Impl*>(user_data);
  ++self.n_rhs;
  try {
    self.throw_if_stop_requested();
    return self.rhs(t, view(y), view(ydot));
  } catch (...) {
    self.callback_exception = std::current_exception();
    return -1;
  }
}

int CvodeIntegrator::Impl::jacobian_callback(realtype t, N_Vector y, N_Vector fy, SUNMatrix J,
                                             void* user_data, N_Vector, N_Vector, N_Vector) {
  auto& self = *static_cast<Impl*>(user_data);
  ++self.n_jacobian;
  try {
    self.throw_if_stop_requested();
    // CVODE zeroes J (structure included) before this call: restore the pattern.
    const SparsePattern& p = self.pattern;
    const std::int64_t nnz = p.n_nonzeros();
    if (SUNSparseMatrix_NNZ(J) < nnz)
      throw std::logic_error("CvodeIntegrator: Jacobian storage smaller than the pattern");
    std::copy(p.row_ptr.begin(), p.row_ptr.end(), SUNSparseMatrix_IndexPointers(J));
    std::copy(p.col.begin(), p.col.end(), SUNSparseMatrix_IndexValues(J));
    const std::span<double> values(SUNSparseMatrix_Data(J), static_cast<std::size_t>(nnz));
    std::fill(values.begin(), values.end(), 0.0);
    return self.jacobian(t, view(y), view(fy), values);
  } catch (...) {
    self.callback_exception = std::current_exception();
    return -1;
  }
}

int CvodeIntegrator::Impl::preconditioner_setup(realtype t, N_Vector y, N_Vector fy,
                                                booleantype jok, booleantype* fresh, realtype gamma,
                                                void* user_data) {
  auto& self = *static_cast<Impl*>(user_data);
  try {
    self.throw_if_stop_requested();
    bool evaluated = false;
    const int flag = self.krylov->setup(jok != 0, &evaluated, gamma, [&](std::span<double> j) {
      ++self.n_jacobian;
      return self.jacobian(t, view(y), view(fy), j);
    });
    *fresh = evaluated ? SUNTRUE : SUNFALSE;
    return flag;
  } catch (...) {
    self.callback_exception = std::current_exception();
    return -1;
  }
}

int CvodeIntegrator::Impl::preconditioner_solve(realtype, N_Vector, N_Vector, N_Vector r,
                                                N_Vector z, realtype, realtype, int,
                                                void* user_data) {
  auto& self = *static_cast<Impl*>(user_data);
  try {
    self.krylov->precondition(view(r), view(z));
    return 0;
  } catch (...) {
    self.callback_exception = std::current_exception();
    return -1;
  }
}

int CvodeIntegrator::Impl::jacobian_times(N_Vector v, N_Vector jv, realtype, N_Vector, N_Vector,
                                          void* user_data, N_Vector) {
  static_cast<Impl*>(user_data)->krylov->multiply(view(v), view(jv));
  return 0;
}

int CvodeIntegrator::Impl::roots_callback(realtype t, N_Vector y, realtype* g, void* user_data) {
  auto& self = *static_cast<Impl*>(user_data);
  try {
    return self.roots(t, view(y), std::span<double>(g, static_cast<std::size_t>(self.n_roots)));
  } catch (...) {
    self.callback_exception = std::current_exception();
    return -1;
  }
}

void CvodeIntegrator::Impl::error_handler(int error_code, const char* module, const char* function,
                                          char* msg, void* user_data) {
  if (error_code >= 0) return;  // warnings (e.g. t + h == t) are not failures
  auto& self = *static_cast<Impl*>(user_data);
  self.last_cvode_message = std::string(module != nullptr ? module : "?") +
                            "::" + (function != nullptr ? function : "?") + ": " +
                            (msg != nullptr ? msg : "");
}

}  // namespace unsatmpm::numerics
