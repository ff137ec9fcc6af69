// Dust opacities on the device and the solver's opacity fields (see dust_opacities.hpp).
#include "mote/radiation/dust_opacities.hpp"

#include <algorithm>
#include <stdexcept>

#include "mote/radiation/planck.hpp"

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

/// Bins summed side by side in one pass over the species: independent sums that
/// neither wait on each other's additions nor read the densities once per bin.
constexpr int kBinChunk = 8;

/// out_a(i, j, c0 + c) and out_b for c < Width: the gas term, then the species in order.
template <int Width>
KOKKOS_INLINE_FUNCTION void weighted_chunk(int i, int j, int c0, Real gas, const RealView2& kappa_a,
                                           const RealView2& kappa_b, const RealView3& rho_dust, const RealView3& out_a,
                                           const RealView3& out_b) {
  Real a[Width], b[Width];
  for (int c = 0; c < Width; ++c) a[c] = b[c] = gas;
  for (int s = 0; s < static_cast<int>(rho_dust.extent(2)); ++s) {
    const Real rho = rho_dust(i, j, s);
    for (int c = 0; c < Width; ++c) {
      a[c] += rho * kappa_a(s, c0 + c);
      b[c] += rho * kappa_b(s, c0 + c);
    }
  }
  for (int c = 0; c < Width; ++c) {
    out_a(i, j, c0 + c) = a[c];
    out_b(i, j, c0 + c) = b[c];
  }
}

/// out_a(i, j, c) = sum_s rho_s(i, j) kappa_a(s, c) + rho_g(i, j) kappa_gas over all cells, and
/// out_b from kappa_b likewise (both tables have the same columns).
void weighted_sums(const std::string& name, const RealView2& kappa_a, const RealView2& kappa_b,
                   const RealView3& rho_dust, const RealView2& rho_gas, Real kappa_gas, const RealView3& out_a,
                   const RealView3& out_b) {
  const int ns = static_cast<int>(kappa_a.extent(0)), nc = static_cast<int>(kappa_a.extent(1));
  if (static_cast<int>(rho_dust.extent(2)) != ns || kappa_b.extent(0) != kappa_a.extent(0) ||
      kappa_b.extent(1) != kappa_a.extent(1) || static_cast<int>(out_a.extent(2)) != nc ||
      out_b.extent(0) != out_a.extent(0) || out_b.extent(1) != out_a.extent(1) || out_b.extent(2) != out_a.extent(2))
    throw std::invalid_argument(name + ": species or band counts differ between opacities and fields");
  const int whole = nc - nc % kBinChunk;
  par_for(
      name, 0, static_cast<int>(out_a.extent(0)), 0, static_cast<int>(out_a.extent(1)), KOKKOS_LAMBDA(int i, int j) {
        const Real gas = rho_gas(i, j) * kappa_gas;
        for (int c0 = 0; c0 < whole; c0 += kBinChunk)
          weighted_chunk<kBinChunk>(i, j, c0, gas, kappa_a, kappa_b, rho_dust, out_a, out_b);
        for (int c0 = whole; c0 < nc; ++c0) weighted_chunk<1>(i, j, c0, gas, kappa_a, kappa_b, rho_dust, out_a, out_b);
      });
}

RealView1 edges_on_device(const std::vector<double>& edges_cm) {
  RealView1 v("radiation::bin_edges_cm", edges_cm.size());
  auto h = Kokkos::create_mirror_view(v);
  for (std::size_t k = 0; k < edges_cm.size(); ++k) h(k) = edges_cm[k];
  Kokkos::deep_copy(v, h);
  return v;
}

/// band_first_bin from the band of every bin (non-decreasing, every band holding one).
IntView1 band_ranges(const std::vector<int>& band_of_bin, int bands) {
  IntView1 first("radiation::band_first_bin", bands + 1);
  auto h = Kokkos::create_mirror_view(first);
  const int nl = static_cast<int>(band_of_bin.size());
  for (int b = 0; b <= bands; ++b)
    h(b) = static_cast<int>(std::lower_bound(band_of_bin.begin(), band_of_bin.end(), b) - band_of_bin.begin());
  h(bands) = nl;
  Kokkos::deep_copy(first, h);
  return first;
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
          to_device("radiation::kappa_star_abs", table.absorption, ns, nB, to_code),
          edges_on_device(bin_edges_cm),
          band_ranges(fine_bin_bands(bin_edges_cm, band_edges_cm), nb)};
}

void fill_fld_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                        Real kappa_gas, const FldFields& fields) {
  weighted_sums("radiation::fld_opacities", opacities.planck_absorption, opacities.rosseland_total, rho_dust, rho_gas,
                kappa_gas, fields.absorption, fields.extinction);
}

void fill_fld_opacities_at(const DustOpacities& opacities, const RealView3& extinction_at_bins,
                           const RealView3& absorption_at_bins, const RealView2& T, const mesh::Grid& grid,
                           const FldFields& fields) {
  const int nb = static_cast<int>(opacities.band_first_bin.extent(0)) - 1;
  if (extinction_at_bins.extent(2) != opacities.stellar_absorption.extent(1) ||
      absorption_at_bins.extent(2) != opacities.stellar_absorption.extent(1) ||
      static_cast<int>(fields.absorption.extent(2)) != nb)
    throw std::invalid_argument("radiation: bin or band counts differ between opacities and fields");
  auto k_abs = absorption_at_bins, k_ext = extinction_at_bins;
  auto edges = opacities.bin_edges_cm;
  auto first = opacities.band_first_bin;
  auto absorption = fields.absorption, extinction = fields.extinction;
  const int i0 = grid.i_begin(), i1 = grid.i_end() - 1, j0 = grid.j_begin(), j1 = grid.j_end() - 1;
  par_for(
      "radiation::fld_opacities_at_T", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        const Real t = T(math::min(math::max(i, i0), i1), math::min(math::max(j, j0), j1));
        PlanckEdge short_edge = planck_edge(edges(0), t);  // of the bin
        for (int b = 0; b < nb; ++b) {
          Real wp = 0, sp = 0, wr = 0, sr = 0;  // the weights are > 0 (band_weight_floor)
          for (int l = first(b); l < first(b + 1); ++l) {
            const PlanckEdge long_edge = planck_edge(edges(l + 1), t);
            Real p, r;
            band_mean_weights(short_edge, long_edge, t, p, r);
            short_edge = long_edge;
            wp += p;
            sp += p * k_abs(i, j, l);
            wr += r;
            sr += r / math::max(k_ext(i, j, l), Real(1e-300));
          }
          absorption(i, j, b) = sp / wp;
          extinction(i, j, b) = wr / sr;
        }
      });
}

void fill_stellar_opacities(const DustOpacities& opacities, const RealView3& rho_dust, const RealView2& rho_gas,
                            Real kappa_gas, const RealView3& extinction, const RealView3& absorption) {
  weighted_sums("radiation::stellar_opacities", opacities.stellar_extinction, opacities.stellar_absorption, rho_dust,
                rho_gas, kappa_gas, extinction, absorption);
}

}  // namespace mote::radiation
