// PressureSystem::jacobian (numerics/pressure/pressure_system.hpp, which includes this file at
// its end; include that header, not this one): the exact derivative of y' = M^-1 F,
//   dy'_i/dP_j = M_i^-1 (dF_i/dP_j - (dM_i/dP_j) P'_i),
// assembled point by point over the stencil nodes each point keeps (PointQuadrature), checked
// against finite differences in tests/numerics/test_pressure_system.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

namespace unsatmpm::numerics {

template <int D, class K>
int PressureSystem<D, K>::jacobian(double t, std::span<const double> y, std::span<double> values) {
  evaluate(t, y);
  std::fill(values.begin(), values.end(), 0.0);
  const bool simplified = form_ == MassBalance::simplified;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const auto& st = points_.stencil[p];
    const double volume = points_.volume[p];
    const PointFlow<D> f = flow_at(p, Pass::jacobian);
    const auto kept = points_.jacobian_nodes[p];
    for (int a = 0; a < st.n; ++a) {
      if (!(kept >> a & 1u)) continue;
      const auto i = st.node[a];
      for (int al = 0; al < 2; ++al) {
        // A prescribed balance feeds the inflow integral's row, with the opposite sign.
        const bool inflow_row = prescribed_active(al, i);
        const auto row = inflow_row ? unknowns_.inflow(al) : unknowns_(al, i);
        const double sign = inflow_row ? -1.0 / inflow_scale_[al] : 1.0;
        if (unknowns_(al, i) < 0 && !inflow_row) continue;
        const double pl = rate_[0][i], pg = rate_[1][i];
        for (int b = 0; b < st.n; ++b) {
          if (!(kept >> b & 1u)) continue;
          const auto j = st.node[b];
          const double nn = st.w[a] * st.w[b];
          for (int be = 0; be < 2; ++be) {
            const auto col = unknowns_(be, j);
            if (col < 0) continue;
            const auto& da = f.d_storage[be];
            const double dm = al == 0 ? da.ll * pl + da.lg * pg : da.gl * pl + da.gg * pg;
            double k =
                st.grad[a].dot(f.d_flux[al][be]) * st.w[b] - f.d_source[al][be] * nn - dm * nn;
            if (al == be) k -= f.conductivity[al] * st.grad[a].dot(st.grad[b]);
            if (simplified)
              k += st.w[a] *
                   (f.d_advective[al][be] * st.w[b] + f.d_advective_d_grad[al][be].dot(st.grad[b]));
            values[pattern_.position(row, col)] += sign * volume * k;
          }
        }
      }
    }
  }
  // Left-multiply each node's rows by M_UU^-1 (U: its unknown, not held, fluids).
  for (const auto i : unknowns_.nodes()) {
    const auto rl = unknowns_(0, i), rg = unknowns_(1, i);
    const auto& m = storage_[i];
    const bool gas_held = held(i);
    if (rl >= 0 && rg >= 0 && !gas_held) {
      const double det = m.ll * m.gg - m.lg * m.gl;
      for (auto q = pattern_.row_ptr[rl], r = pattern_.row_ptr[rg]; q < pattern_.row_ptr[rl + 1];
           ++q, ++r) {
        const double kl = values[q], kg = values[r];
        values[q] = (m.gg * kl - m.lg * kg) / det;
        values[r] = (m.ll * kg - m.gl * kl) / det;
      }
    } else {
      if (rl >= 0)
        for (auto q = pattern_.row_ptr[rl]; q < pattern_.row_ptr[rl + 1]; ++q) values[q] /= m.ll;
      if (rg >= 0)
        for (auto q = pattern_.row_ptr[rg]; q < pattern_.row_ptr[rg + 1]; ++q)
          values[q] = gas_held ? 0.0 : values[q] / m.gg;
    }
  }
  // A node with one fluid prescribed and the other free: its inflow also moves with the free
  // fluid's rate, M_aU dP'_U/dP_j.
  for (const auto i : unknowns_.nodes())
    for (int al = 0; al < 2; ++al) {
      const int other = 1 - al;
      const auto r = unknowns_(other, i);
      if (!prescribed_active(al, i) || r < 0 || (other == 1 && held(i))) continue;
      const auto& m = storage_[i];
      const double coupling = (al == 0 ? m.lg : m.gl) / inflow_scale_[al];
      for (auto q = pattern_.row_ptr[r]; q < pattern_.row_ptr[r + 1]; ++q)
        values[pattern_.position(unknowns_.inflow(al), pattern_.col[q])] += coupling * values[q];
    }
  for (const double v : values)
    if (!std::isfinite(v)) return 1;
  return 0;
}

}  // namespace unsatmpm::numerics
