// Logarithmic mass grid (RBO24 sec. 5 and 7; Brauer et al. 2008).
#include "mote/coagulation/mass_grid.hpp"

#include <cmath>
#include <stdexcept>

#include "mote/core/log.hpp"

namespace mote::coagulation {

namespace {
constexpr double kFourThirdsPi = 4.0 * M_PI / 3.0;

RealView1 to_device(const std::vector<Real>& v, const char* name) {
  RealView1 d(std::string(name), v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < v.size(); ++i) h(i) = v[i];
  Kokkos::deep_copy(d, h);
  return d;
}
}  // namespace

MassGrid MassGrid::from_sizes(Real a_min, Real a_max, int species, Real rho_m) {
  if (!(a_min > 0) || !(a_max > a_min) || species < 2 || !(rho_m > 0))
    throw std::invalid_argument(
        logging::cat("coagulation mass grid: need 0 < a_min < a_max, species >= 2, rho_m > 0 (got a_min = ", a_min,
                     ", a_max = ", a_max, ", species = ", species, ", rho_m = ", rho_m, ")"));
  return from_masses(kFourThirdsPi * rho_m * a_min * a_min * a_min, kFourThirdsPi * rho_m * a_max * a_max * a_max,
                     species, rho_m);
}

MassGrid MassGrid::from_masses(Real m_min, Real m_max, int species, Real rho_m) {
  if (!(m_min > 0) || !(m_max > m_min) || species < 2 || !(rho_m > 0))
    throw std::invalid_argument(
        logging::cat("coagulation mass grid: need 0 < m_min < m_max, species >= 2, rho_m > 0 (got m_min = ", m_min,
                     ", m_max = ", m_max, ", species = ", species, ")"));
  std::vector<Real> m(species);
  const double step = std::log(m_max / m_min) / (species - 1);
  for (int k = 0; k < species; ++k) m[k] = m_min * std::exp(step * k);
  m.back() = m_max;
  return MassGrid(std::move(m), rho_m);
}

MassGrid::MassGrid(std::vector<Real> masses, Real rho_m) : mass_(std::move(masses)), rho_m_(rho_m) {
  const int n = size();
  edge_.resize(n + 1);
  const double ratio = mass_[1] / mass_[0];
  edge_[0] = mass_[0] / std::sqrt(ratio);
  for (int k = 1; k < n; ++k) edge_[k] = std::sqrt(mass_[k - 1] * mass_[k]);
  edge_[n] = mass_[n - 1] * std::sqrt(ratio);
  size_.resize(n);
  for (int k = 0; k < n; ++k) size_[k] = std::cbrt(mass_[k] / (kFourThirdsPi * rho_m_));
  mass_d_ = to_device(mass_, "coagulation::mass");
  edge_d_ = to_device(edge_, "coagulation::mass_edges");
  size_d_ = to_device(size_, "coagulation::grain_size");
}

Real MassGrid::bins_per_mass_decade() const { return 1.0 / std::log10(mass_[1] / mass_[0]); }

std::string MassGrid::resolution_warning() const {
  const double bpd = bins_per_mass_decade();
  if (bpd >= 7.0 - 1e-9) return {};
  return logging::format(
      "coagulation mass grid has %.2f bins per mass decade (m_{k+1}/m_k = %.3f); "
      "RBO24 (after Ohtsuki et al. 1990) needs >= 7 for accurate growth rates",
      bpd, mass_[1] / mass_[0]);
}

}  // namespace mote::coagulation
