// Logarithmic mass grid of the coagulation solver (RBO24 sec. 5, after
// Brauer et al. 2008): N species with centre masses m_k spaced evenly in
// log m, bin edges at the geometric means of neighbouring centres (the outer
// edges half a bin beyond the first and last centres), and grain sizes
// a_k = (3 m_k / (4 pi rho_m))^(1/3) for an intrinsic (material) density rho_m.
// RBO24 sec. 7 (after Ohtsuki et al. 1990) requires >= 7 bins per mass decade
// for accuracy; coarser grids are accepted with a warning.
#pragma once

#include <string>
#include <vector>

#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

class MassGrid {
 public:
  /// Grid of `species` sizes from a_min to a_max (centres, cm or code length)
  /// for grains of intrinsic density rho_m.
  static MassGrid from_sizes(Real a_min, Real a_max, int species, Real rho_m);
  /// Grid of `species` centre masses from m_min to m_max; sizes use rho_m.
  static MassGrid from_masses(Real m_min, Real m_max, int species, Real rho_m = 1.0);

  int size() const { return static_cast<int>(mass_.size()); }
  Real rho_m() const { return rho_m_; }
  /// Bins per decade of mass, log10(m_{k+1}/m_k)^-1.
  Real bins_per_mass_decade() const;
  /// Centre mass m_k, bin edge m^e_k (k = 0..N, bin k is [m^e_k, m^e_{k+1})), size a_k.
  Real mass(int k) const { return mass_[k]; }
  Real edge(int k) const { return edge_[k]; }
  Real grain_size(int k) const { return size_[k]; }
  const std::vector<Real>& masses() const { return mass_; }
  const std::vector<Real>& edges() const { return edge_; }
  const std::vector<Real>& sizes() const { return size_; }

  /// Device copies (centres, edges, sizes).
  RealView1 mass_view() const { return mass_d_; }
  RealView1 edge_view() const { return edge_d_; }
  RealView1 size_view() const { return size_d_; }

  /// Warning text if the grid is coarser than 7 bins per mass decade, else empty.
  std::string resolution_warning() const;

 private:
  MassGrid(std::vector<Real> masses, Real rho_m);
  std::vector<Real> mass_, edge_, size_;
  Real rho_m_ = 1.0;
  RealView1 mass_d_, edge_d_, size_d_;
};

}  // namespace mote::coagulation
