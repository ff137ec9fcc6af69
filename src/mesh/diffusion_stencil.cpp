// Wu et al. (2012) diffusion stencil on the (R, theta) mesh, RBO24 eq. 21-25
// and app. A (see include/mote/mesh/diffusion_stencil.hpp).
#include "mote/mesh/diffusion_stencil.hpp"

#include "mote/core/loops.hpp"

namespace mote::mesh {

namespace {

struct Vec2 {
  Real x, y;
};
KOKKOS_INLINE_FUNCTION Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
KOKKOS_INLINE_FUNCTION Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
KOKKOS_INLINE_FUNCTION Vec2 operator*(Real s, Vec2 a) { return {s * a.x, s * a.y}; }
KOKKOS_INLINE_FUNCTION Real dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

/// A face: a point on it and its unit normal. Radial faces are lines R = const,
/// theta faces lines through the origin at angle theta.
struct Face {
  Vec2 point, normal;
  KOKKOS_INLINE_FUNCTION Vec2 foot(Vec2 p) const { return p - dot(p - point, normal) * normal; }
  KOKKOS_INLINE_FUNCTION Real distance(Vec2 p) const { return math::fabs(dot(p - point, normal)); }
};

/// Weight of the cell at `p` (diffusion coefficient Dp) on a face shared with
/// the cell at `q` (Dq) in the combination of the one-sided fluxes (eq. 21):
/// w_p = mu_p / (mu_p + mu_q), mu = d / D (eq. 22).
KOKKOS_INLINE_FUNCTION Real weight(const Face& f, Vec2 p, Real Dp, Vec2 q, Real Dq) {
  const Real mp = f.distance(p) / Dp, mq = f.distance(q) / Dq;
  return mp / (mp + mq);
}

/// Weight of the cell at `p` in the interface value u_f = h_p u_p + h_q u_q at
/// the interpolation point x_f = h_p foot(p) + h_q foot(q): the harmonic
/// weights h_p = (D_p/d_p) / (D_p/d_p + D_q/d_q) that make the normal flux
/// continuous for piecewise-linear u (Wu et al. 2012). With them each
/// one-sided flux (eq. 25) is exact for linear u; with the weights of eq. 22
/// in eq. 23/25 it is not (tests/unit/test_mesh_diffusion.cpp).
KOKKOS_INLINE_FUNCTION Real harmonic_weight(const Face& f, Vec2 p, Real Dp, Vec2 q, Real Dq) {
  const Real mp = Dp / f.distance(p), mq = Dq / f.distance(q);
  return mp / (mp + mq);
}

/// Vector from cell centre c to the interpolation point on face f shared with
/// cell centre o (eq. 23): h_c (foot(c) - c) + h_o (foot(o) - c).
KOKKOS_INLINE_FUNCTION Vec2 interpolation_vector(const Face& f, Vec2 c, Real wc, Vec2 o, Real wo) {
  return wc * (f.foot(c) - c) + wo * (f.foot(o) - c);
}

/// Solves c1 v1 + c2 v2 = n for (c1, c2) (eq. 24).
KOKKOS_INLINE_FUNCTION void decompose(Vec2 v1, Vec2 v2, Vec2 n, Real& c1, Real& c2) {
  const Real det = v1.x * v2.y - v1.y * v2.x;
  c1 = (n.x * v2.y - n.y * v2.x) / det;
  c2 = (v1.x * n.y - v1.y * n.x) / det;
}

}  // namespace

DiffusionCoefficients diffusion_coefficients(const Grid& grid, const RealView2& D) {
  DiffusionCoefficients c;
  c.radial = RealView3("mesh::diffusion_radial", grid.nr_total() + 1, grid.nt_total(), 4);
  c.theta = RealView3("mesh::diffusion_theta", grid.nr_total(), grid.nt_total() + 1, 4);
  update_diffusion_coefficients(grid, D, c);
  return c;
}

void update_diffusion_coefficients(const Grid& grid, const RealView2& D, DiffusionCoefficients& coef) {
  const int NI = grid.nr_total(), NJ = grid.nt_total();
  auto Re = grid.Re, Rc = grid.Rc, tan_tc = grid.tan_tc, sin_te = grid.sin_te, cos_te = grid.cos_te;
  auto AR = grid.AR, AZ = grid.AZ;
  auto radial = coef.radial, theta = coef.theta;
  Kokkos::deep_copy(radial, 0.0);
  Kokkos::deep_copy(theta, 0.0);
  auto centre = [=] KOKKOS_FUNCTION(int i, int j) { return Vec2{Rc(i), Rc(i) * tan_tc(j)}; };
  auto radial_face = [=] KOKKOS_FUNCTION(int i) { return Face{Vec2{Re(i), 0.0}, Vec2{1.0, 0.0}}; };
  auto theta_face = [=] KOKKOS_FUNCTION(int j) { return Face{Vec2{0.0, 0.0}, Vec2{-sin_te(j), cos_te(j)}}; };

  // Radial faces i in [1, NI), rows j in [1, NJ - 1): cells k=(i-1,j), l=(i,j), m=(i-1,j-1), p=(i,j+1).
  par_for(
      "mesh::diffusion_radial_coefficients", 1, NI, 1, NJ - 1, KOKKOS_LAMBDA(int i, int j) {
        const Face sigma = radial_face(i), tau = theta_face(j), nu = theta_face(j + 1);
        const Vec2 ck = centre(i - 1, j), cl = centre(i, j), cm = centre(i - 1, j - 1), cp = centre(i, j + 1);
        const Real Dk = D(i - 1, j), Dl = D(i, j), Dm = D(i - 1, j - 1), Dp = D(i, j + 1);
        const Real wk = weight(sigma, ck, Dk, cl, Dl), wl = 1.0 - wk;
        const Real hk = harmonic_weight(sigma, ck, Dk, cl, Dl), hl = 1.0 - hk;
        const Real hk_tau = harmonic_weight(tau, ck, Dk, cm, Dm), hm_tau = 1.0 - hk_tau;
        const Real hl_nu = harmonic_weight(nu, cl, Dl, cp, Dp), hp_nu = 1.0 - hl_nu;
        // One-sided flux out of k (normal +R) through sigma, with the bottom face tau of k.
        Real c_kl, c_km;
        decompose(interpolation_vector(sigma, ck, hk, cl, hl), interpolation_vector(tau, ck, hk_tau, cm, hm_tau),
                  sigma.normal, c_kl, c_km);
        // One-sided flux out of l (normal -R) through sigma, with the top face nu of l.
        Real c_lk, c_lp;
        decompose(interpolation_vector(sigma, cl, hl, ck, hk), interpolation_vector(nu, cl, hl_nu, cp, hp_nu),
                  -1.0 * sigma.normal, c_lk, c_lp);
        // F A = A [w_k F_k - w_l F_l],  F_k = -D_k [h_l c_kl (u_l-u_k) + h_m c_km (u_m-u_k)],
        //                               F_l = -D_l [h_k c_lk (u_k-u_l) + h_p c_lp (u_p-u_l)].
        const Real A = AR(i, j);
        const Real ak = A * wk * Dk, al = A * wl * Dl;
        radial(i, j, 0) = ak * hl * c_kl + ak * hm_tau * c_km + al * hk * c_lk;
        radial(i, j, 1) = -ak * hl * c_kl - al * hk * c_lk - al * hp_nu * c_lp;
        radial(i, j, 2) = -ak * hm_tau * c_km;
        radial(i, j, 3) = al * hp_nu * c_lp;
      });

  // Theta faces j in [1, NJ), columns i in [1, NI - 1): cells a=(i,j-1), l=(i,j), m=(i-1,j-1), b=(i+1,j).
  par_for(
      "mesh::diffusion_theta_coefficients", 1, NI - 1, 1, NJ, KOKKOS_LAMBDA(int i, int j) {
        const Face lambda = theta_face(j), beta = radial_face(i), eps = radial_face(i + 1);
        const Vec2 ca = centre(i, j - 1), cl = centre(i, j), cm = centre(i - 1, j - 1), cb = centre(i + 1, j);
        const Real Da = D(i, j - 1), Dl = D(i, j), Dm = D(i - 1, j - 1), Db = D(i + 1, j);
        const Real wa = weight(lambda, ca, Da, cl, Dl), wl = 1.0 - wa;
        const Real ha = harmonic_weight(lambda, ca, Da, cl, Dl), hl = 1.0 - ha;
        const Real ha_beta = harmonic_weight(beta, ca, Da, cm, Dm), hm_beta = 1.0 - ha_beta;
        const Real hl_eps = harmonic_weight(eps, cl, Dl, cb, Db), hb_eps = 1.0 - hl_eps;
        // Out of a (normal +n) through lambda, with the left face beta of a.
        Real c_al, c_am;
        decompose(interpolation_vector(lambda, ca, ha, cl, hl), interpolation_vector(beta, ca, ha_beta, cm, hm_beta),
                  lambda.normal, c_al, c_am);
        // Out of l (normal -n) through lambda, with the right face eps of l.
        Real c_la, c_lb;
        decompose(interpolation_vector(lambda, cl, hl, ca, ha), interpolation_vector(eps, cl, hl_eps, cb, hb_eps),
                  -1.0 * lambda.normal, c_la, c_lb);
        const Real A = AZ(i, j);
        const Real aa = A * wa * Da, al = A * wl * Dl;
        theta(i, j, 0) = aa * hl * c_al + aa * hm_beta * c_am + al * ha * c_la;
        theta(i, j, 1) = -aa * hl * c_al - al * ha * c_la - al * hb_eps * c_lb;
        theta(i, j, 2) = -aa * hm_beta * c_am;
        theta(i, j, 3) = al * hb_eps * c_lb;
      });
}

}  // namespace mote::mesh
