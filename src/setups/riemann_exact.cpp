// Exact Riemann solver for an ideal gas (Toro 2009, sec. 4.2-4.5).
#include "mote/setups/riemann_exact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mote::sph {

ExactRiemann::ExactRiemann(const RiemannState& left, const RiemannState& right, Real gamma)
    : l_(left), r_(right), gamma_(gamma) {
  cl_ = std::sqrt(gamma * l_.p / l_.rho);
  cr_ = std::sqrt(gamma * r_.p / r_.rho);
  const Real g = gamma_;
  if (2.0 / (g - 1.0) * (cl_ + cr_) <= r_.v - l_.v) throw std::runtime_error("ExactRiemann: vacuum is generated");
  // Initial guess: primitive-variable (PVRS) estimate, Toro eq. 4.47.
  Real p = 0.5 * (l_.p + r_.p) - 0.125 * (r_.v - l_.v) * (l_.rho + r_.rho) * (cl_ + cr_);
  p = std::max(p, 1e-8 * std::min(l_.p, r_.p));
  for (int it = 0; it < 100; ++it) {
    Real fl, dfl, fr, dfr;
    pressure_function(p, l_, cl_, fl, dfl);
    pressure_function(p, r_, cr_, fr, dfr);
    Real pn = p - (fl + fr + r_.v - l_.v) / (dfl + dfr);
    if (pn <= 0.0) pn = 0.5 * p;
    const Real change = 2.0 * std::fabs(pn - p) / (pn + p);
    p = pn;
    if (change < 1e-14) break;
  }
  Real fl, dfl, fr, dfr;
  pressure_function(p, l_, cl_, fl, dfl);
  pressure_function(p, r_, cr_, fr, dfr);
  p_star_ = p;
  v_star_ = 0.5 * (l_.v + r_.v) + 0.5 * (fr - fl);
}

// Toro eq. 4.6-4.7 (f_K) and 4.37 (derivatives).
void ExactRiemann::pressure_function(Real p, const RiemannState& s, Real c, Real& f, Real& df) const {
  const Real g = gamma_;
  if (p > s.p) {
    const Real A = 2.0 / ((g + 1.0) * s.rho);
    const Real B = (g - 1.0) / (g + 1.0) * s.p;
    const Real q = std::sqrt(A / (p + B));
    f = (p - s.p) * q;
    df = q * (1.0 - 0.5 * (p - s.p) / (B + p));
  } else {
    const Real pr = p / s.p;
    f = 2.0 * c / (g - 1.0) * (std::pow(pr, (g - 1.0) / (2.0 * g)) - 1.0);
    df = 1.0 / (s.rho * c) * std::pow(pr, -(g + 1.0) / (2.0 * g));
  }
}

// Toro sec. 4.5, sampling at xi = x / t.
RiemannState ExactRiemann::sample(Real xi) const {
  const Real g = gamma_;
  const Real gm = (g - 1.0) / (g + 1.0);
  const Real ps = p_star_, us = v_star_;
  if (xi <= us) {
    const RiemannState& s = l_;
    const Real c = cl_;
    if (ps > s.p) {  // left shock
      const Real sl = s.v - c * std::sqrt((g + 1.0) / (2.0 * g) * ps / s.p + (g - 1.0) / (2.0 * g));
      if (xi <= sl) return s;
      return {s.rho * (ps / s.p + gm) / (gm * ps / s.p + 1.0), us, ps};
    }
    const Real shl = s.v - c;  // left rarefaction head
    if (xi <= shl) return s;
    const Real cs = c * std::pow(ps / s.p, (g - 1.0) / (2.0 * g));
    const Real stl = us - cs;
    if (xi > stl) return {s.rho * std::pow(ps / s.p, 1.0 / g), us, ps};
    const Real f = 2.0 / (g + 1.0) + gm / c * (s.v - xi);
    return {s.rho * std::pow(f, 2.0 / (g - 1.0)), 2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * s.v + xi),
            s.p * std::pow(f, 2.0 * g / (g - 1.0))};
  }
  const RiemannState& s = r_;
  const Real c = cr_;
  if (ps > s.p) {  // right shock
    const Real sr = s.v + c * std::sqrt((g + 1.0) / (2.0 * g) * ps / s.p + (g - 1.0) / (2.0 * g));
    if (xi >= sr) return s;
    return {s.rho * (ps / s.p + gm) / (gm * ps / s.p + 1.0), us, ps};
  }
  const Real shr = s.v + c;  // right rarefaction head
  if (xi >= shr) return s;
  const Real cs = c * std::pow(ps / s.p, (g - 1.0) / (2.0 * g));
  const Real str = us + cs;
  if (xi < str) return {s.rho * std::pow(ps / s.p, 1.0 / g), us, ps};
  const Real f = 2.0 / (g + 1.0) - gm / c * (s.v - xi);
  return {s.rho * std::pow(f, 2.0 / (g - 1.0)), 2.0 / (g + 1.0) * (-c + 0.5 * (g - 1.0) * s.v + xi),
          s.p * std::pow(f, 2.0 * g / (g - 1.0))};
}

}  // namespace mote::sph
