// Analytic solutions of the Smoluchowski equation for the test kernels
// (VALIDATION E1/E2), in x = m / m0 for an initial number density
// f(m, 0) = (N0 / m0) e^-x (constant, additive) or (N0 / m0) e^-x / x (product):
//   constant K0:        f = (N0/m0) g^2 e^(-g x),               g = 2 / (2 + K0 N0 t)
//   additive K0(m+m'):  f = (N0/m0) (1 - tau) e^(-(1+tau) x) I1(2 x sqrt(tau)) / (x sqrt(tau)),
//                       tau = 1 - exp(-K0 N0 m0 t)              (Golovin 1963)
//   product K0 m m':    f = (N0/m0) e^(-(1+T) x) I1(2 x sqrt(T)) / (x^2 sqrt(T)),
//                       T = K0 N0 m0^2 t < 1 (before gelation)  (e.g. Ohtsuki et al. 1990)
// and their mass in a bin, integrated numerically (host code, for checks).
#pragma once

#include <cmath>
#include <string>

namespace mote::coagulation::analytic {

/// log(I1(z)) for z > 0, overflow-free (series/libstdc++ below 500, asymptotic above).
inline double log_bessel_i1(double z) {
  if (z < 500.0) return std::log(std::cyl_bessel_i(1.0, z));
  const double s = 1.0 - 3.0 / (8.0 * z) - 15.0 / (128.0 * z * z) - 315.0 / (3072.0 * z * z * z);
  return z - 0.5 * std::log(2.0 * M_PI * z) + std::log(s);
}

/// Mass density per unit x, x f(x) * m0 / (N0 m0) = x f(x) m0 / N0 (dimensionless), at time t.
inline double mass_density(const std::string& kernel, double x, double t, double K0, double N0, double m0) {
  if (kernel == "constant") {
    const double g = 2.0 / (2.0 + K0 * N0 * t);
    return x * g * g * std::exp(-g * x);
  }
  if (kernel == "additive") {
    const double tau = -std::expm1(-K0 * N0 * m0 * t);
    if (tau <= 0) return x * std::exp(-x);
    const double s = std::sqrt(tau);
    return (1.0 - tau) / s * std::exp(-(1.0 + tau) * x + log_bessel_i1(2.0 * x * s));
  }
  const double T = K0 * N0 * m0 * m0 * t;  // product
  if (T <= 0) return std::exp(-x);
  const double s = std::sqrt(T);
  return std::exp(-(1.0 + T) * x + log_bessel_i1(2.0 * x * s)) / (x * s);
}

/// Mass (per volume, in units of N0 m0) between x_lo and x_hi (Simpson in log x).
inline double bin_mass(const std::string& kernel, double x_lo, double x_hi, double t, double K0, double N0, double m0,
                       int intervals = 64) {
  const double a = std::log(x_lo), b = std::log(x_hi), h = (b - a) / intervals;
  double sum = 0;
  for (int i = 0; i <= intervals; ++i) {
    const double x = std::exp(a + i * h);
    const double w = (i == 0 || i == intervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * x * mass_density(kernel, x, t, K0, N0, m0);
  }
  return sum * h / 3.0;
}

}  // namespace mote::coagulation::analytic
