// Stellar irradiation by ray tracing (RBO24 eq. 45-46); see irradiation.hpp.
#include "mote/radiation/irradiation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "mote/radiation/planck.hpp"

namespace mote::radiation {

double Star::luminosity(const RadiationConstants& constants) const {
  return 4.0 * math::pi() * radius * radius * constants.sigma * std::pow(T_eff, 4);
}

namespace {

void check_edges(const std::vector<double>& edges, const std::string& what) {
  if (edges.size() < 2) throw std::invalid_argument("radiation: " + what + " need at least two edges");
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (!(edges[k] > 0.0) || !std::isfinite(edges[k]) || (k > 0 && !(edges[k] > edges[k - 1])))
      throw std::invalid_argument("radiation: " + what + " edges must be positive and increasing (edge " +
                                  std::to_string(k) + ")");
}

/// Index of the FLD band holding wavelength lambda (outer bands open-ended).
int band_holding(const std::vector<double>& band_edges, double lambda) {
  const int nb = static_cast<int>(band_edges.size()) - 1;
  int b = 0;
  while (b < nb - 1 && lambda >= band_edges[b + 1]) ++b;
  return b;
}

}  // namespace

StellarIrradiation::StellarIrradiation(const mesh::Grid& grid, Star star, std::vector<double> bin_edges_cm,
                                       std::vector<double> fld_band_edges_cm, const RadiationConstants& constants)
    : grid_(grid), nB_(static_cast<int>(bin_edges_cm.size()) - 1) {
  check_edges(bin_edges_cm, "stellar wavelength bins");
  check_edges(fld_band_edges_cm, "FLD bands");
  if (!(star.radius > 0.0) || !(star.T_eff > 0.0) || !std::isfinite(star.radius) || !std::isfinite(star.T_eff))
    throw std::invalid_argument("radiation: the star needs a positive radius and effective temperature");
  L_ = RealView1("radiation::L_bin", nB_);
  band_of_bin_ = IntView1("radiation::band_of_bin", nB_);
  auto L_host = Kokkos::create_mirror_view(L_);
  auto band_host = Kokkos::create_mirror_view(band_of_bin_);
  const double L = star.luminosity(constants);
  for (int B = 0; B < nB_; ++B) {
    const double lo = B == 0 ? 0.0 : bin_edges_cm[B], hi = B == nB_ - 1 ? 0.0 : bin_edges_cm[B + 1];
    L_host(B) = L * band_fraction(lo, hi, star.T_eff);
    L_h_.push_back(L_host(B));
    band_host(B) = band_holding(fld_band_edges_cm, std::sqrt(bin_edges_cm[B] * bin_edges_cm[B + 1]));
  }
  Kokkos::deep_copy(L_, L_host);
  Kokkos::deep_copy(band_of_bin_, band_host);
  tau_ = RealView3("radiation::tau_star", grid.nr_total(), grid.nt_total(), nB_);
  tau_start_ = RealView2("radiation::tau_star_start", grid.nt_total(), nB_);
  tau_end_ = RealView2("radiation::tau_star_end", grid.nt_total(), nB_);
  tau_start_h_ = Kokkos::create_mirror_view(tau_start_);
  tau_end_h_ = Kokkos::create_mirror_view(tau_end_);
}

namespace {

constexpr int kOpticalDepthTag = 7301;

/// Radial slabs (mesh::Grid): rank r's rays start with the optical depth at
/// which rank r - 1's end, received here (rank 0 starts from 0).
void receive_ray_start(const core::Comm& comm, const RealView2& start, const RealView2::HostMirror& host) {
  if (comm.rank() == 0) return;
  comm.sendrecv(nullptr, 0, -1, host.data(), static_cast<int>(host.size()), comm.rank() - 1, kOpticalDepthTag);
  Kokkos::deep_copy(start, host);
}

/// Sends the optical depth at the outer edge of this rank's slab to rank r + 1.
void send_ray_end(const core::Comm& comm, const RealView2& end, const RealView2::HostMirror& host) {
  if (comm.rank() == comm.size() - 1) return;
  Kokkos::deep_copy(host, end);
  comm.sendrecv(host.data(), static_cast<int>(host.size()), comm.rank() + 1, nullptr, 0, -1, kOpticalDepthTag);
}

}  // namespace

void StellarIrradiation::heat(const RealView3& extinction, const RealView3& absorption, const RealView2& heating,
                              const RealView3& scattering) const {
  const int i0 = grid_.i_begin(), i1 = grid_.i_end(), j0 = grid_.j_begin(), j1 = grid_.j_end();
  const int nB = nB_;
  const auto Re = grid_.Re;
  const auto tc = grid_.tc, te = grid_.te;
  const auto V = grid_.V;
  const auto tau = tau_;
  const auto start = tau_start_, end = tau_end_;
  // tau_B to the inner edge of every cell: a scan along each ray (j, B), over
  // the ranks' slabs in turn (each continues the sum where the inner one ended,
  // so that any number of ranks adds in the same order as one).
  const core::Comm& comm = grid_.comm();
  if (comm.size() > 1) receive_ray_start(comm, start, tau_start_h_);
  par_for(
      "radiation::stellar_optical_depth", j0, j1, 0, nB, KOKKOS_LAMBDA(int j, int B) {
        const Real inv_cos = 1.0 / math::cos(tc(j));
        Real t = start(j, B);
        for (int i = i0; i < i1; ++i) {
          tau(i, j, B) = t;
          t += extinction(i, j, B) * (Re(i + 1) - Re(i)) * inv_cos;
        }
        end(j, B) = t;
      });
  if (comm.size() > 1) send_ray_end(comm, end, tau_end_h_);
  Kokkos::deep_copy(heating, 0.0);
  Kokkos::deep_copy(scattering, 0.0);
  const auto L = L_;
  const auto band = band_of_bin_;
  par_for(
      "radiation::stellar_heating", i0, i1, j0, j1, KOKKOS_LAMBDA(int i, int j) {
        const Real dr = (Re(i + 1) - Re(i)) / math::cos(tc(j));
        const Real per_volume = (math::sin(te(j + 1)) - math::sin(te(j))) / (4.0 * math::pi() * V(i, j));
        Real absorbed = 0.0;
        for (int B = 0; B < nB; ++B) {
          const Real ext = extinction(i, j, B);
          const Real taken = L(B) * per_volume * math::exp(-tau(i, j, B)) * (-math::expm1(-ext * dr));
          const Real albedo = ext > 0.0 ? 1.0 - absorption(i, j, B) / ext : 0.0;
          absorbed += taken * (1.0 - albedo);
          scattering(i, j, band(B)) += taken * albedo;
        }
        heating(i, j) = absorbed;
      });
}

double absorbed_power(const mesh::Grid& grid, const FldFields& fields) {
  const auto V = grid.V;
  const auto S = fields.heating;
  const auto Ss = fields.scattering_source;
  const int nb = static_cast<int>(Ss.extent(2));
  double P = 0.0;
  par_reduce(
      "radiation::absorbed_power", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j, double& sum) {
        Real s = S(i, j);
        for (int b = 0; b < nb; ++b) s += Ss(i, j, b);
        sum += V(i, j) * s;
      },
      P);
  return grid.comm().sum(P);
}

}  // namespace mote::radiation
