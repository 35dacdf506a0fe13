// Between the points and the nodes of the pressure system: the nodal start values of an
// integration, fitted to the points' pressures, and the nodal increments of an integration
// returned to the points.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "numerics/fluid_points.hpp"
#include "numerics/pressure/quadrature.hpp"

namespace unsatmpm::numerics {

/// The least spread, in grid spacings, that the points around a node must have in every direction
/// for their pressures to be fitted linearly there (else their mean). With 2 points per cell and
/// direction, a node on the body's edge sees a spread of 0.22 h across it; a single row of
/// points, 0.
inline constexpr double min_fit_spread = 0.1;

/// The nodal values of the points' pressures. The volume-weighted mean is biased wherever a
/// node's support is one-sided — on the body's boundary: a linear field P = rho g depth
/// projects to rho g h/4 instead of 0 at the surface node, and the flow would start from that
/// error (a spurious flux toward the node, a jump where a prescribed value switches on). So each
/// node takes the value of a weighted least-squares linear fit to the points around it (exact
/// for linear fields, equal to the mean for a symmetric support). The mean stays where the
/// points cannot carry a fit: too few of them, or spread less than min_fit_spread h (weighted
/// standard deviation of their offsets) in some direction. Such a cloud is nearly a line, and
/// the fit's slope across it, extrapolated to the node, is noise: on the embankment a crest
/// squeezed into one column of points (offsets from the node 0.084-0.11 m in x, 0.2 m cells)
/// gave a fitted 3.59 MPa where the points held -71 to +8 kPa (mean -12.3 kPa); the flow
/// started from it and threw the crest out of the grid (t = 138.6 s).
/// Fills `nodal` (liquid, gas; every node, 0 where inactive) [Pa].
template <int D, class K>
void fit_pressures_to_nodes(const Grid<D>& grid, const PointQuadrature<D, K>& q,
                            const FluidPoints<D>& fp, std::array<std::vector<double>, 2>& nodal) {
  for (auto& v : nodal) v.assign(grid.n_nodes(), 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    const double v = q.volume[p];
    for (int a = 0; a < st.n; ++a) {
      nodal[liquid_phase][st.node[a]] += st.w[a] * v * fp.liquid_pressure[p];
      nodal[gas_phase][st.node[a]] += st.w[a] * v * fp.gas_pressure[p];
    }
  }
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    for (int a = 0; a < 2; ++a)
      if (q.active(i)) nodal[a][i] /= q.node_volume[i];

  using Row = Eigen::Matrix<double, D + 1, 1>;
  using Normal = Eigen::Matrix<double, D + 1, D + 1>;
  std::vector<std::int64_t> fitted;
  std::vector<std::int64_t> slot(grid.n_nodes(), -1);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    if (q.active(i)) slot[i] = static_cast<std::int64_t>(fitted.size()), fitted.push_back(i);
  std::vector<Normal> normal(fitted.size(), Normal::Zero());
  std::vector<std::array<Row, 2>> rhs(fitted.size(), {Row::Zero(), Row::Zero()});
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a) {
      const auto k = slot[st.node[a]];
      if (k < 0 || st.w[a] <= 0.0) continue;
      Row r;
      r[0] = 1.0;
      r.template tail<D>() = q.position[p] - grid.node_position(st.node[a]);
      const double w = st.w[a] * q.volume[p];
      normal[k] += w * r * r.transpose();
      rhs[k][0] += w * fp.liquid_pressure[p] * r;
      rhs[k][1] += w * fp.gas_pressure[p] * r;
    }
  }
  const double min_variance = std::pow(min_fit_spread * grid.spacing.minCoeff(), 2);
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    // Weighted covariance of the offsets, sum w d d^T / sum w - mean mean^T; at least
    // min_variance in every direction also makes the normal matrix invertible (too few points
    // fail here too).
    const double w = normal[k](0, 0);
    const Vec<D> mean = normal[k].template block<D, 1>(1, 0) / w;
    const Eigen::Matrix<double, D, D> cov =
        normal[k].template block<D, D>(1, 1) / w - mean * mean.transpose();
    if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>>(cov, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .minCoeff() < min_variance)
      continue;
    const Eigen::FullPivLU<Normal> lu(normal[k]);
    for (int a = 0; a < 2; ++a) nodal[a][fitted[k]] = lu.solve(rhs[k][a])[0];
  }
}

/// A nodal field at the points: P_p = sum_i N_i P_i, per fluid.
template <int D, class K>
void interpolate_nodal(const PointQuadrature<D, K>& q,
                       const std::array<std::vector<double>, 2>& nodal,
                       std::array<std::vector<double>, 2>& at_points) {
  for (auto& v : at_points) v.assign(q.size(), 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) at_points[f][p] += st.w[a] * nodal[f][st.node[a]];
  }
}

/// The points' pressures moved by the nodal increments between two nodal fields:
/// dP_p = sum_i N_i (P_i,end - P_i,start).
template <int D, class K>
void add_nodal_increments(const PointQuadrature<D, K>& q,
                          const std::array<std::vector<double>, 2>& start,
                          const std::array<std::vector<double>, 2>& end, FluidPoints<D>& fp) {
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    double dl = 0.0, dg = 0.0;
    for (int a = 0; a < st.n; ++a) {
      const auto i = st.node[a];
      dl += st.w[a] * (end[liquid_phase][i] - start[liquid_phase][i]);
      dg += st.w[a] * (end[gas_phase][i] - start[gas_phase][i]);
    }
    fp.liquid_pressure[p] += dl;
    fp.gas_pressure[p] += dg;
  }
}

}  // namespace unsatmpm::numerics
