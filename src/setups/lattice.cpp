// Lattices, stretch mapping (PL15 eq. 54-55) and equal masses; see lattice.hpp.
#include "mote/setups/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mote::sph {

namespace {

/// Number of lattice rows of spacing s in length len; even if periodic.
int row_count(Real len, Real s, bool periodic, int multiple) {
  int n = std::max(1, static_cast<int>(std::lround(len / s)));
  if (periodic && n % multiple != 0) n += multiple - n % multiple;
  return n;
}

/// Periodic direction: the box is resized (about its centre) to n s;
/// free direction: the box is kept and the spacing becomes len / n.
Real fit_direction(Box& box, int d, int n, Real s) {
  if (box.periodic[d]) {
    const Real c = 0.5 * (box.lo[d] + box.hi[d]);
    box.lo[d] = c - 0.5 * n * s;
    box.hi[d] = c + 0.5 * n * s;
    return s;
  }
  return box.length(d) / n;
}

}  // namespace

Lattice cubic_lattice(const Box& box, Real dx) {
  Lattice lat;
  lat.dim = box.dim;
  lat.box = box;
  const int dim = box.dim;
  int n[3] = {1, 1, 1};
  Real s[3] = {0, 0, 0};
  n[0] = std::max(1, static_cast<int>(std::lround(box.length(0) / dx)));
  s[0] = box.length(0) / n[0];
  for (int d = 1; d < dim; ++d) {
    n[d] = row_count(box.length(d), s[0], box.periodic[d], 1);
    s[d] = fit_direction(lat.box, d, n[d], s[0]);
  }
  lat.dx = s[0];
  lat.x.reserve(static_cast<std::size_t>(n[0]) * n[1] * n[2] * dim);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const int idx[3] = {i, j, k};
        for (int d = 0; d < dim; ++d) lat.x.push_back(lat.box.lo[d] + (idx[d] + 0.5) * s[d]);
      }
  return lat;
}

Lattice hexagonal_lattice(const Box& box, Real dx) {
  if (box.dim != 2) throw std::invalid_argument("sph::hexagonal_lattice: 2D only");
  Lattice lat;
  lat.dim = 2;
  lat.box = box;
  const int nx = std::max(1, static_cast<int>(std::lround(box.length(0) / dx)));
  const Real sx = box.length(0) / nx;
  const int ny = row_count(box.length(1), sx * std::sqrt(3.0) / 2.0, box.periodic[1], 2);
  const Real sy = fit_direction(lat.box, 1, ny, sx * std::sqrt(3.0) / 2.0);
  lat.dx = sx;
  lat.x.reserve(static_cast<std::size_t>(nx) * ny * 2);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      lat.x.push_back(lat.box.lo[0] + (i + 0.25 + 0.5 * (j % 2)) * sx);
      lat.x.push_back(lat.box.lo[1] + (j + 0.5) * sy);
    }
  return lat;
}

Lattice close_packed_lattice(const Box& box, Real dx) {
  if (box.dim != 3) throw std::invalid_argument("sph::close_packed_lattice: 3D only");
  if (!box.periodic[0])  // rows and layers shift by up to 1.25 spacings in x, which only a periodic x wraps
    throw std::invalid_argument("sph::close_packed_lattice: x must be periodic");
  Lattice lat;
  lat.dim = 3;
  lat.box = box;
  const int nx = std::max(1, static_cast<int>(std::lround(box.length(0) / dx)));
  const Real sx = box.length(0) / nx;
  const int ny = row_count(box.length(1), sx * std::sqrt(3.0) / 2.0, box.periodic[1], 2);
  const Real sy = fit_direction(lat.box, 1, ny, sx * std::sqrt(3.0) / 2.0);
  const int nz = row_count(box.length(2), sx * std::sqrt(2.0 / 3.0), box.periodic[2], 2);
  const Real sz = fit_direction(lat.box, 2, nz, sx * std::sqrt(2.0 / 3.0));
  lat.dx = sx;
  lat.x.reserve(static_cast<std::size_t>(nx) * ny * nz * 3);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        // Layer B (odd k) sits over the holes of layer A: shift (dx/2, dy/3).
        lat.x.push_back(lat.box.lo[0] + (i + 0.25 + 0.5 * (j % 2) + 0.5 * (k % 2)) * sx);
        lat.x.push_back(lat.box.lo[1] + (j + 0.25 + (k % 2) / 3.0) * sy);
        lat.x.push_back(lat.box.lo[2] + (k + 0.5) * sz);
      }
  for (std::size_t i = 0; i < lat.x.size(); ++i) lat.x[i] = lat.box.wrap(lat.x[i], static_cast<int>(i % 3));
  return lat;
}

Real integrate_profile(const std::function<Real(Real)>& rho, Real lo, Real hi, int n) {
  if (n % 2) ++n;
  const Real ds = (hi - lo) / n;
  Real s = rho(lo) + rho(hi);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * rho(lo + i * ds);
  return s * ds / 3.0;
}

void stretch_map(Lattice& lat, int axis, Real lo, Real hi, const std::function<Real(Real)>& rho) {
  // Cumulative mass on a fine grid (Simpson per pair of half intervals).
  const int ncell = 20000;
  const Real ds = (hi - lo) / ncell;
  std::vector<Real> cum(ncell + 1, 0.0);
  for (int i = 0; i < ncell; ++i) {
    const Real s0 = lo + i * ds;
    cum[i + 1] = cum[i] + ds / 6.0 * (rho(s0) + 4.0 * rho(s0 + 0.5 * ds) + rho(s0 + ds));
  }
  const Real mtot = cum[ncell];
  const int dim = lat.dim;
  for (int p = 0; p < lat.size(); ++p) {
    Real& s = lat.x[p * dim + axis];
    const Real target = (s - lo) / (hi - lo) * mtot;  // PL15 eq. 54
    const auto it = std::upper_bound(cum.begin(), cum.end(), target);
    const int i = std::clamp(static_cast<int>(it - cum.begin()) - 1, 0, ncell - 1);
    // Newton inside the cell on M(s) = cum[i] + int_{s_i}^{s} rho (trapezoid).
    Real z = lo + i * ds;
    const Real zi = z;
    Real mz = cum[i];
    for (int k = 0; k < 20; ++k) {
      const Real r = rho(z);
      if (!(r > 0.0)) break;
      const Real dz = (target - mz) / r;
      z += dz;
      z = std::clamp(z, zi, zi + ds);
      mz = cum[i] + 0.5 * (rho(zi) + rho(z)) * (z - zi);
      if (std::fabs(dz) < 1e-14 * (hi - lo)) break;
    }
    s = z;
  }
}

std::vector<Real> equal_masses(int n, Real total_mass) { return std::vector<Real>(n, total_mass / n); }

}  // namespace mote::sph
