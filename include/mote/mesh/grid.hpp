// The 2D axisymmetric (R, theta) grid of RBO24 sec. 2: cell edges on constant
// cylindrical radius R and constant angle theta above the mid-plane.
//   V_ij   = (1/3) d(R^3)_i d(tan theta)_j          (eq. 1)
//   A^R_ij = (R^e_i)^2 d(tan theta)_j               (eq. 2)  face at R^e_i
//   A^Z_ij = (1/2) d(R^2)_i / cos(theta^e_j)        (eq. 3)  face at theta^e_j
// written to stay finite as R -> 0. The planar option (2D areas and lengths,
// used by the C1 pulse test) drops one power of R:
//   V_ij = (1/2) d(R^2)_i d(tan theta)_j,  A^R_ij = R^e_i d(tan theta)_j,  A^Z_ij = dR_i / cos(theta^e_j).
// Cell centres: R^c = (R^e_i + R^e_{i+1}) / 2, theta^c likewise, Z^c = R^c tan theta^c.
// Interface normals: radial faces n = R_hat; theta faces n = (-sin theta^e, cos theta^e) in (R, Z).
//
// Radial slabs are distributed over MPI ranks; every array carries `ghosts`
// cells on each side in both directions. Local index i in [0, nr + 2 ng),
// active cells [ng, ng + nr); likewise j.
#pragma once

#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/kokkos_types.hpp"
#include "mote/core/loops.hpp"

namespace mote::mesh {

enum class Geometry { Cylindrical, Planar };

struct GridSpec {
  int nr = 0, ntheta = 0;
  std::vector<double> r_edges;      // nr + 1 global active edges
  std::vector<double> theta_edges;  // ntheta + 1 active edges (radians)
  Geometry geometry = Geometry::Cylindrical;
  bool r_log = true;  // ghost edges continue the boundary spacing geometrically (else arithmetically)
  int ghosts = 2;

  /// Deck table [grid]: R_in, R_out, nr, r_spacing ("log" | "linear" | "log_blocks" | "edges" + r_edges),
  /// theta_min, theta_max, ntheta, theta_spacing ("linear" | "power" | "blocks" | "edges"), geometry.
  static void declare(core::DeckSchema& schema);
  static GridSpec from_deck(const core::Deck& deck);
};

/// Edge generators (global, active edges only).
std::vector<double> log_edges(double lo, double hi, int n);
std::vector<double> linear_edges(double lo, double hi, int n);
/// lo + (hi - lo) (k/n)^p: concentrates cells near lo for p > 1.
std::vector<double> power_edges(double lo, double hi, int n, double p);
/// Two linear blocks: n_inner cells in [lo, split], the rest in [split, hi].
std::vector<double> block_edges(double lo, double split, double hi, int n, int n_inner);
/// Two logarithmic blocks: n_inner cells in [lo, split], the rest in [split, hi]
/// (the refined inner rim of RBO24 sec. 4.3, after Ramsey & Dullemond 2015).
std::vector<double> log_block_edges(double lo, double split, double hi, int n, int n_inner);

class Grid {
 public:
  Grid(const GridSpec& spec, const core::Comm& comm);

  // Sizes: nr and nt are this rank's active cells; totals include ghosts.
  int ng = 2;
  int nr = 0, nt = 0;
  int nr_global = 0;
  int i_offset = 0;  // global index of the first active local cell
  int nr_total() const { return nr + 2 * ng; }
  int nt_total() const { return nt + 2 * ng; }
  int i_begin() const { return ng; }
  int i_end() const { return ng + nr; }
  int j_begin() const { return ng; }
  int j_end() const { return ng + nt; }
  bool has_inner_boundary() const { return rank_ == 0; }
  bool has_outer_boundary() const { return rank_ == size_ - 1; }
  Geometry geometry = Geometry::Cylindrical;

  // 1D geometry (local with ghosts): edges have one more entry than centres.
  RealView1 Re, Rc, dR;              // cylindrical radius: edges, centres, widths
  RealView1 te, tc, tan_te, tan_tc;  // theta: edges, centres and their tangents
  RealView1 sin_te, cos_te;
  // 2D geometry (local with ghosts): V(i,j); AR(i,j) face at Re(i); AZ(i,j) face at te(j).
  RealView2 V, AR, AZ;
  RealView2 Zc;  // Z of cell centres, R^c tan theta^c

  // Host copies of the 1D arrays (I/O, set-up).
  HostView<Real*> Re_h, Rc_h, te_h, tc_h;
  HostView<Real**> V_h;
  /// Global active edges (identical on every rank), for output.
  std::vector<double> r_edges_global, theta_edges_global;

  const core::Comm& comm() const { return comm_; }

 private:
  core::Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace mote::mesh
