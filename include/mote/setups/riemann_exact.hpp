// Exact solution of the Riemann problem for an ideal gas (Toro 2009, ch. 4):
// star-region pressure by Newton-Raphson on the pressure function, then
// self-similar sampling in xi = (x - x0) / t. Host-side; used by the Sod tests
// and reused by the dusty shock (with the effective sound speed).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::sph {

struct RiemannState {
  Real rho = 1.0;
  Real v = 0.0;
  Real p = 1.0;
};

class ExactRiemann {
 public:
  ExactRiemann(const RiemannState& left, const RiemannState& right, Real gamma);

  Real p_star() const { return p_star_; }
  Real v_star() const { return v_star_; }

  /// State at similarity coordinate xi = (x - x0) / t.
  RiemannState sample(Real xi) const;

 private:
  void pressure_function(Real p, const RiemannState& s, Real c, Real& f, Real& df) const;

  RiemannState l_, r_;
  Real gamma_, cl_, cr_;
  Real p_star_ = 0.0, v_star_ = 0.0;
};

}  // namespace mote::sph
