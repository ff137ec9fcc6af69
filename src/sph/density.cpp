// h-rho iteration (PL15 eq. 24, 28); see include/mote/sph/density.hpp.
#include "mote/sph/density.hpp"

#include "mote/core/loops.hpp"

namespace mote::sph {

/// Per-pass counters of the h-rho solver, reduced in the density kernel itself
/// (no per-particle scratch): counts and the iteration sum add, the largest
/// iteration count is kept by the same join.
struct DensityCounts {
  int outside_cover = 0, not_converged = 0, max_iterations = 0;
  long long iterations = 0;
  KOKKOS_INLINE_FUNCTION DensityCounts& operator+=(const DensityCounts& o) {
    outside_cover += o.outside_cover;
    not_converged += o.not_converged;
    max_iterations = max_iterations > o.max_iterations ? max_iterations : o.max_iterations;
    iterations += o.iterations;
    return *this;
  }
};

}  // namespace mote::sph

namespace Kokkos {
template <>
struct reduction_identity<mote::sph::DensityCounts> {
  KOKKOS_FORCEINLINE_FUNCTION static mote::sph::DensityCounts sum() { return {}; }
};
}  // namespace Kokkos

namespace mote::sph {

// A named namespace: nvcc requires the functions that enclose extended
// (KOKKOS_LAMBDA) lambdas to have external linkage.
namespace detail {

template <int Dim, class K>
DensityResult density_impl(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg) {
  const int n = p.n;
  const auto x = p.x;
  const auto m = p.m;
  const auto h = p.h;
  const auto rho = p.rho;
  const auto omega = p.omega;
  const auto type = p.type;
  const auto offsets = nl.offsets;
  const auto neigh = nl.neigh;
  const auto image = nl.image;
  const auto h_cover = nl.h_cover;
  const Real hfact = cfg.effective_hfact();
  const Real tol = cfg.h_tol;
  const int max_iter = cfg.h_max_iter;
  const Real huge = 1e300;
  Real f0, df0;
  K::shape(0.0, f0, df0);
  const Real w0 = K::norm() * f0;

  DensityCounts counts;
  par_reduce(
      "sph::density", 0, n,
      KOKKOS_LAMBDA(int a, DensityCounts& acc) {
        const Real ma = m(a);
        const int ta = type(a);
        Real xa[3] = {0, 0, 0};
        for (int d = 0; d < Dim; ++d) xa[d] = x(a, d);
        const int jb = offsets(a), je = offsets(a + 1);
        const Real hcap = h_cover(a);

        Real hh = h(a), hlo = 0.0, hhi = huge;
        int st = 2, it = 0;
        Real rho_s = 0.0, dsum = 0.0, rho_a = 0.0, omega_a = 1.0;
        for (it = 1; it <= max_iter; ++it) {
          const Real hinv = 1.0 / hh;
          const Real hd = ipow<Dim>(hinv);
          // Self contribution: W(0) and dW/dh(0) = -d W(0) / h.
          rho_s = ma * w0 * hd;
          dsum = -Dim * ma * w0 * hd * hinv;
          for (int j = jb; j < je; ++j) {
            const int b = neigh(j);
            if (type(b) != ta) continue;
            Real r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              const Real dx = box.separation(xa[d], x(b, d), image(j), d);
              r2 += dx * dx;
            }
            // No support test: the kernels are branch-free and vanish beyond it.
            const Real q = math::sqrt(r2) * hinv;
            Real f, df;
            K::shape(q, f, df);
            const Real mb = m(b);
            rho_s += mb * K::norm() * hd * f;
            dsum -= mb * K::norm() * hd * hinv * (Dim * f + q * df);
          }
          const Real h_rho = hfact * root_dim<Dim>(ma / rho_s);
          const bool converged = math::fabs(hh - h_rho) < tol * hh;
          const Real rho_h = ma * ipow<Dim>(hfact * hinv);
          const Real fval = rho_s - rho_h;
          if (fval > 0.0) {
            hhi = hh;
          } else {
            hlo = hh;
          }
          const Real dfdh = dsum + Dim * rho_h * hinv;  // d rho_h / dh = -d rho_h / h
          Real hnew = hh - fval / dfdh;
          if (converged) {
            // Converged to tol: take the final (quadratically convergent) Newton
            // step without another pass and set rho = m (h_fact / h)^d, which
            // then matches the density sum to O(tol^2). This keeps the noise of
            // the iteration out of the forces (hydrostatic columns).
            omega_a = 1.0 + hh / (Dim * rho_s) * dsum;
            if (hnew > hlo && hnew < hhi && hnew <= hcap) {
              hh = hnew;
              rho_a = ma * ipow<Dim>(hfact / hh);
            } else {
              rho_a = rho_s;
            }
            st = 0;
            break;
          }
          if (!(hnew > hlo && hnew < hhi)) {
            // Newton left the bracket: bisect (or expand when unbounded above).
            hnew = hhi < huge ? 0.5 * (hlo + hhi) : 2.0 * hh;
          }
          hh = hnew;
          if (hh > hcap) {
            st = 1;
            break;
          }
          rho_a = rho_s;
          omega_a = 1.0 + hh / (Dim * rho_s) * dsum;
        }
        h(a) = hh;
        if (st != 1) {
          rho(a) = rho_a;
          omega(a) = omega_a;
        }
        const int used = it > max_iter ? max_iter : it;
        acc.outside_cover += st == 1 ? 1 : 0;
        acc.not_converged += st == 2 ? 1 : 0;
        acc.max_iterations = acc.max_iterations > used ? acc.max_iterations : used;
        acc.iterations += used;
      },
      counts);

  DensityResult res;
  res.outside_cover = counts.outside_cover;
  res.not_converged = counts.not_converged;
  res.max_iterations = counts.max_iterations;
  res.mean_iterations = n > 0 ? static_cast<double>(counts.iterations) / n : 0.0;
  return res;
}

struct DensityDispatch {
  Particles& p;
  const NeighbourList& nl;
  const Box& box;
  const SphConfig& cfg;
  DensityResult result;
  template <int Dim, class K>
  void operator()() {
    result = density_impl<Dim, K>(p, nl, box, cfg);
  }
};

}  // namespace detail

DensityResult compute_density(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg) {
  detail::DensityDispatch f{p, nl, box, cfg, {}};
  dispatch(p.dim, cfg.kernel, f);
  return f.result;
}

}  // namespace mote::sph
