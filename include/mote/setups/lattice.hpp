// Particle set-up helpers (host side): cubic (1D/2D/3D), hexagonal (2D) and
// close-packed (3D, hcp) lattices whose box lengths in periodic directions are
// adjusted to hold a whole number of lattice periods, the stretch mapping of a
// lattice to a density profile (Price 2004; PL15 eq. 54-55) and equal particle
// masses.
#pragma once

#include <functional>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"

namespace mote::sph {

struct Lattice {
  int dim = 3;
  std::vector<Real> x;  ///< positions, n x dim row-major
  Real dx = 0.0;        ///< nearest-neighbour spacing along the first direction
  Box box;              ///< the box, adjusted in periodic directions
  int size() const { return dim > 0 ? static_cast<int>(x.size()) / dim : 0; }
};

/// Cubic lattice of spacing ~dx (exactly L_x / n_x) in `box` (box.dim = 1, 2, 3).
/// Periodic directions other than x are resized to a whole number of cells.
Lattice cubic_lattice(const Box& box, Real dx);

/// 2D hexagonal lattice: rows spaced dx sqrt(3)/2, alternate rows shifted by
/// dx/2; an even number of rows in a periodic y direction.
Lattice hexagonal_lattice(const Box& box, Real dx);

/// 3D close-packed (hcp, ABAB) lattice; even numbers of rows and layers in
/// periodic y and z; x must be periodic (its rows shift by up to 1.25 spacings).
Lattice close_packed_lattice(const Box& box, Real dx);

/// Mass in [lo, hi] of the 1D profile rho(s) (composite Simpson, n intervals).
Real integrate_profile(const std::function<Real(Real)>& rho, Real lo, Real hi, int n = 20000);

/// Stretch mapping along `axis` (PL15 eq. 54): moves every coordinate s0 in
/// [lo, hi] to s with M(s) / M(hi) = (s0 - lo) / (hi - lo), M(s) = int_lo^s rho.
void stretch_map(Lattice& lat, int axis, Real lo, Real hi, const std::function<Real(Real)>& rho);

/// Equal masses m = total_mass / n.
std::vector<Real> equal_masses(int n, Real total_mass);

}  // namespace mote::sph
