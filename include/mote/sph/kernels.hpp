// SPH smoothing kernels W(r, h) = C_d / h^d f(q), q = r / h, in 1, 2 and 3
// dimensions: the M4 cubic spline (support 2h), the M6 quintic spline (support
// 3h, PL15 sec. 3.4.4 and 4.4) and the Wendland C4 kernel (support 2h, Dehnen &
// Aly 2012, table 1). The kernel gradient is written as grad_a W_ab = F_ab r_hat_ab
// (PL15 sec. 3.2.2, eq. 34), with F_ab = C_d / h^(d+1) f'(q), and the derivative
// with respect to h (needed for Omega, PL15 eq. 28) is
// dW/dh = -C_d / h^(d+1) (d f(q) + q f'(q)).
//
// Kernels are stateless structs templated on the dimension; a run-time choice
// (KernelType) is dispatched once, outside every Kokkos kernel.
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>

#include "mote/core/kokkos_types.hpp"

namespace mote::sph {

enum class KernelType { M4 = 0, M6 = 1, WendlandC4 = 2 };

/// Integer power x^N for small compile-time N.
template <int N>
KOKKOS_INLINE_FUNCTION constexpr Real ipow(Real x) {
  if constexpr (N == 0) {
    return Real(1);
  } else {
    return x * ipow<N - 1>(x);
  }
}

/// Branch-free max(x, 0): neighbour loops evaluate kernels on pairs at
/// random q, where branches on the spline pieces would be mispredicted.
KOKKOS_INLINE_FUNCTION Real pos(Real x) { return x > 0.0 ? x : 0.0; }

/// M4 cubic spline (Monaghan & Lattanzio 1985), support q < 2:
/// f = (2-q)_+^3 / 4 - (1-q)_+^3, i.e. 1 - 3/2 q^2 + 3/4 q^3 (q < 1), (2-q)^3 / 4 (1 <= q < 2).
template <int Dim>
struct KernelM4 {
  static constexpr int dim = Dim;
  KOKKOS_INLINE_FUNCTION static constexpr Real radius() { return 2.0; }
  KOKKOS_INLINE_FUNCTION static constexpr Real norm() {
    return Dim == 1 ? 2.0 / 3.0 : (Dim == 2 ? 10.0 / (7.0 * math::pi()) : 1.0 / math::pi());
  }
  /// f(q) and f'(q); both zero for q >= 2.
  KOKKOS_INLINE_FUNCTION static void shape(Real q, Real& f, Real& df) {
    const Real t2 = pos(2.0 - q), t1 = pos(1.0 - q);
    f = 0.25 * t2 * t2 * t2 - t1 * t1 * t1;
    df = -0.75 * t2 * t2 + 3.0 * t1 * t1;
  }
};

/// M6 quintic spline (Schoenberg 1946), support q < 3:
/// f = (3-q)_+^5 - 6 (2-q)_+^5 + 15 (1-q)_+^5.
template <int Dim>
struct KernelM6 {
  static constexpr int dim = Dim;
  KOKKOS_INLINE_FUNCTION static constexpr Real radius() { return 3.0; }
  KOKKOS_INLINE_FUNCTION static constexpr Real norm() {
    return Dim == 1 ? 1.0 / 120.0 : (Dim == 2 ? 7.0 / (478.0 * math::pi()) : 1.0 / (120.0 * math::pi()));
  }
  KOKKOS_INLINE_FUNCTION static void shape(Real q, Real& f, Real& df) {
    const Real t3 = pos(3.0 - q), t2 = pos(2.0 - q), t1 = pos(1.0 - q);
    const Real t3_4 = (t3 * t3) * (t3 * t3), t2_4 = (t2 * t2) * (t2 * t2), t1_4 = (t1 * t1) * (t1 * t1);
    f = t3_4 * t3 - 6.0 * t2_4 * t2 + 15.0 * t1_4 * t1;
    df = -5.0 * t3_4 + 30.0 * t2_4 - 75.0 * t1_4;
  }
};

/// Wendland C4 (Dehnen & Aly 2012), support q < 2 (x = q/2 in [0, 1]).
/// 1D: (1-x)^5 (1 + 5x + 8x^2); 2D and 3D: (1-x)^6 (1 + 6x + 35/3 x^2).
template <int Dim>
struct KernelWendlandC4 {
  static constexpr int dim = Dim;
  KOKKOS_INLINE_FUNCTION static constexpr Real radius() { return 2.0; }
  KOKKOS_INLINE_FUNCTION static constexpr Real norm() {
    // Dehnen & Aly normalisations for unit support, divided by 2^d.
    return Dim == 1 ? 1.5 / 2.0 : (Dim == 2 ? 9.0 / (4.0 * math::pi()) : 495.0 / (256.0 * math::pi()));
  }
  KOKKOS_INLINE_FUNCTION static void shape(Real q, Real& f, Real& df) {
    const Real t = pos(1.0 - 0.5 * q);
    const Real x = 1.0 - t;  // = q/2 inside the support
    const Real t4 = (t * t) * (t * t);
    if constexpr (Dim == 1) {
      f = t4 * t * (1.0 + 5.0 * x + 8.0 * x * x);
      df = 0.5 * (-14.0 * x * (1.0 + 4.0 * x) * t4);
    } else {
      f = t4 * t * t * (1.0 + 6.0 * x + 35.0 / 3.0 * x * x);
      df = 0.5 * (-56.0 / 3.0 * x * (1.0 + 5.0 * x) * t4 * t);
    }
  }
};

/// W(r, h) for kernel K.
template <class K>
KOKKOS_INLINE_FUNCTION Real kernel_w(Real r, Real h) {
  const Real hinv = 1.0 / h;
  Real f, df;
  K::shape(r * hinv, f, df);
  return K::norm() * ipow<K::dim>(hinv) * f;
}

/// F_ab such that grad W = F r_hat (PL15 eq. 34).
template <class K>
KOKKOS_INLINE_FUNCTION Real kernel_f(Real r, Real h) {
  const Real hinv = 1.0 / h;
  Real f, df;
  K::shape(r * hinv, f, df);
  return K::norm() * ipow<K::dim + 1>(hinv) * df;
}

/// dW/dh (used in Omega, PL15 eq. 28).
template <class K>
KOKKOS_INLINE_FUNCTION Real kernel_dwdh(Real r, Real h) {
  const Real hinv = 1.0 / h;
  const Real q = r * hinv;
  Real f, df;
  K::shape(q, f, df);
  return -K::norm() * ipow<K::dim + 1>(hinv) * (K::dim * f + q * df);
}

/// Support radius in units of h.
inline Real kernel_radius(KernelType k) {
  switch (k) {
    case KernelType::M4:
      return 2.0;
    case KernelType::M6:
      return 3.0;
    case KernelType::WendlandC4:
      return 2.0;
  }
  return 2.0;
}

/// Default h_fact = h / particle spacing: 1.2 (M4, PL15 sec. 3.1), 1.0 (M6,
/// PL15 sec. 4.4), 1.3 (Wendland C4, needs more neighbours; Dehnen & Aly 2012).
inline Real default_hfact(KernelType k) {
  switch (k) {
    case KernelType::M4:
      return 1.2;
    case KernelType::M6:
      return 1.0;
    case KernelType::WendlandC4:
      return 1.3;
  }
  return 1.2;
}

inline KernelType kernel_from_string(const std::string& s) {
  if (s == "m4" || s == "cubic") return KernelType::M4;
  if (s == "m6" || s == "quintic") return KernelType::M6;
  if (s == "wendland_c4" || s == "c4") return KernelType::WendlandC4;
  throw std::invalid_argument("sph: unknown kernel '" + s + "' (expected m4, m6 or wendland_c4)");
}

/// Calls f.template operator()<Dim, Kernel>() for the run-time (dim, kernel):
/// the single place where the 9 instantiations are chosen.
template <class F>
void dispatch(int dim, KernelType k, F&& f) {
  auto by_kernel = [&](auto dimc) {
    constexpr int D = decltype(dimc)::value;
    switch (k) {
      case KernelType::M4:
        f.template operator()<D, KernelM4<D>>();
        return;
      case KernelType::M6:
        f.template operator()<D, KernelM6<D>>();
        return;
      case KernelType::WendlandC4:
        f.template operator()<D, KernelWendlandC4<D>>();
        return;
    }
  };
  switch (dim) {
    case 1:
      by_kernel(std::integral_constant<int, 1>{});
      return;
    case 2:
      by_kernel(std::integral_constant<int, 2>{});
      return;
    case 3:
      by_kernel(std::integral_constant<int, 3>{});
      return;
    default:
      throw std::invalid_argument("sph: dimension must be 1, 2 or 3");
  }
}

}  // namespace mote::sph
