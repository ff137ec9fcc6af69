// Dust opacities on the device and the solver's opacity fields (see dust_opacities.hpp).
#include "mote/radiation/dust_opacities.hpp"

#include <stdexcept>

namespace mote::radiation {

namespace {

/// A (species, column) device array from a host row-major array, times `scale`.
RealView2 to_device(const std::string& name, const std::vector<double>& values, int species, int columns,
                    double scale) {
  RealView2 v(name, species, columns);
  auto h = Kokkos::create_mirror_view(v);
  for (int s = 0; s < species; ++s)
    for (int c = 0; c < columns; ++c) h(s, c) = values[s * columns + c] * scale;
  Kokkos::deep_copy(v, h);
  return v;
}

/// out(i, j, c) = sum_s rho_s(i, j) kappa(s, c) + rho_g(i, j) kappa_gas over all cells.
void weighted_sum(const std::string& name, const RealView2& kappa, const RealView3& rho_dust, const RealView2& rho_gas,
                  Real kappa_gas, const RealView3& out) {
  const int ns = static_cast<int>(kappa.extent(0)), nc = static_cast<int>(kappa.extent(1));
  if (static_cast<int>(rho_dust.extent(2)) != ns || static_cast<int>(out.extent(2)) != nc)
    throw std::invalid_argument(name + ": species or band counts differ between opacities and fields");
  par_for(
      name, 0, static_cast<int>(out.extent(0)), 0, static_cast<int>(out.extent(1)), KOKKOS_LAMBDA(int i, int j) {
        for (int c = 0; c < nc; ++c) {
          Real sum = rho_gas(i, j) * kappa_gas;
          for (int s = 0; s < ns; ++s) sum += rho_dust(i, j, s) * kappa(s, c);
          out(i, j, c) = sum;
        }
      });
}

}  // namespace

DustOpacities DustOpacities::from_table(const OpacityTable& table, const std::vector<double>& bin_edges_cm,
                                        const std::vector<double>& band_edges_cm, double T_binning,
                                        const units::UnitSystem& units) {
  const int ns = table.sizes(), nB = table.wavelengths(), nb = static_cast<int>(band_edges_cm.size()) - 1;
  const auto means = band_means(table, bin_edges_cm, band_edges_cm, T_binning);
  std::vector<double> ext(table.absorption.size());
  for (std::size_t k = 0; k < ext.size(); ++k) ext[k] = table.absorption[k] + table.scattering[k];
  const double to_code = units.mass / (units.length * units.length);  // cm^2 / g -> code
  return {to_device("radiation::kappa_planck", means.planck_absorption, ns, nb, to_code),
          to_device("radiation::kappa_rosseland", means.rosseland_total, ns, nb, to_code),
          to_device("radiation::kappa_star_ext", ext, ns, nB, to_code),
          to_device("radiation::kappa_star_abs", table.absorption, ns, nB, to_code)};
}

void fill_fld_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                        Real kappa_gas, const FldFields& fields) {
  weighted_sum("radiation::fld_absorption", opacities.planck_absorption, rho_dust, rho_gas, kappa_gas,
               fields.absorption);
  weighted_sum("radiation::fld_extinction", opacities.rosseland_total, rho_dust, rho_gas, kappa_gas, fields.extinction);
}

void fill_stellar_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                            Real kappa_gas, const RealView3& extinction, const RealView3& absorption) {
  weighted_sum("radiation::stellar_extinction", opacities.stellar_extinction, rho_dust, rho_gas, kappa_gas, extinction);
  weighted_sum("radiation::stellar_absorption", opacities.stellar_absorption, rho_dust, rho_gas, kappa_gas, absorption);
}

}  // namespace mote::radiation
