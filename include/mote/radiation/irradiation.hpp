// Heating by the star, RBO24 sec. 4.1 eq. 45-46: ray tracing along the grid's
// constant-theta rays from a blackbody star at the origin, in stellar
// wavelength bins B (finer than the FLD bands). Along each ray the optical
// depth tau_B is a scan over the cells in R of rho kappa_B dr, with the
// spherical path dr = dR / cos(theta_c) through each cell. The power a cell
// takes from bin B, per radian of azimuth, is
//   (L_B / 4 pi) exp(-tau_B) (1 - exp(-rho kappa_B dr)) (sin theta_top - sin theta_bottom),
// the part (1 - a_B) of it heating the grains (S_*, eq. 45) and the part a_B
// (albedo = scattering / extinction) scattered into the FLD band that holds
// the bin's central wavelength (S_sca, eq. 46). Divided by the cell volume this
// is eq. 45 with the solid angle of the cell written out, so that the
// absorbed power equals the attenuated stellar power exactly. The medium
// inside R_in is empty. Under MPI (radial slabs) each rank's rays continue
// from the optical depth at which the inner rank's end: the ranks scan in
// turn, and the sums are the one-rank sums, in the same order.
#pragma once

#include <vector>

#include "mote/mesh/grid.hpp"
#include "mote/radiation/fld.hpp"

namespace mote::radiation {

/// A blackbody star: radius (code length) and effective temperature (K).
struct Star {
  double radius = 0.0;
  double T_eff = 0.0;
  /// 4 pi R^2 sigma T^4 in code units.
  double luminosity(const RadiationConstants& constants) const;
};

class StellarIrradiation {
 public:
  /// `bin_edges_cm`: stellar wavelength bins (the outer two stand for 0 and
  /// infinity); `fld_band_edges_cm`: the FLD bands the scattered light goes to.
  StellarIrradiation(const mesh::Grid& grid, Star star, std::vector<double> bin_edges_cm,
                     std::vector<double> fld_band_edges_cm, const RadiationConstants& constants);

  int bins() const { return nB_; }
  /// L_B per bin (code units), summing to the stellar luminosity.
  const std::vector<double>& bin_luminosities() const { return L_h_; }

  /// heating(i, j) = S_* and scattering(i, j, b) = S_sca^b (energy / volume /
  /// time) from extinction(i, j, B) = rho kappa_ext,B and absorption(i, j, B) =
  /// rho kappa_abs,B (1 / length) at the active cells; ghost cells are 0.
  void heat(const RealView3& extinction, const RealView3& absorption, const RealView2& heating,
            const RealView3& scattering) const;

 private:
  const mesh::Grid& grid_;
  int nB_;
  std::vector<double> L_h_;
  RealView1 L_;                                    // (nB)
  IntView1 band_of_bin_;                           // (nB): FLD band of each bin's central wavelength
  RealView3 tau_;                                  // (nr_total, nt_total, nB): optical depth to the cell's inner edge
  RealView2 tau_start_;                            // (nt_total, nB): at this rank's inner edge (0 on rank 0)
  RealView2 tau_end_;                              // (nt_total, nB): at its outer edge, for the next rank
  RealView2::HostMirror tau_start_h_, tau_end_h_;  // their host copies for MPI, made once
};

/// Stellar power the grid takes per radian of azimuth: the sum over the active
/// cells of V (S_* + sum_b S_sca^b) from the fields StellarIrradiation::heat
/// filled, over all ranks.
double absorbed_power(const mesh::Grid& grid, const FldFields& fields);

}  // namespace mote::radiation
