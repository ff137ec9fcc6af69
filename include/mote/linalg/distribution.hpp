// A linear system spread over the ranks of radial slabs: each rank owns a
// contiguous block of rows, and its matrix has, after the owned columns, ghost
// columns that stand for the values of rows its left and right neighbours own
// (the 9-point FLD stencil reaches one cell into the next slab). Before every
// spmv a GhostExchange brings those values across (device pack, host
// sendrecv, device unpack, as mesh::RadialHalo does), and the solver's dot
// products and maxima are reduced over the ranks. The preconditioner works on
// the owned block alone (block Jacobi).
#pragma once

#include <string>

#include "mote/core/comm.hpp"
#include "mote/linalg/crs_pattern.hpp"

namespace mote::linalg {

/// Which rows this rank owns and which values it exchanges with its neighbours.
struct Distribution {
  core::Comm comm = core::Comm::self();
  int owned = 0;                      // rows on this rank (columns [0, owned))
  int left = -1, right = -1;          // neighbour ranks; -1 for none
  int from_left = 0, from_right = 0;  // ghost columns [owned, owned + from_left), then from_right more
  IntView1 to_left, to_right;         // owned rows whose values the left / right neighbour holds as ghosts,
                                      // in the order of that neighbour's ghost columns
  int ghosts() const { return from_left + from_right; }
  int columns() const { return owned + ghosts(); }
  /// More than one rank takes part: reductions and exchanges are needed.
  bool distributed() const { return comm.size() > 1; }
  /// Throws std::invalid_argument, on every rank together (collective), when
  /// a count is negative, ghosts come from a side without a neighbour, a send
  /// list names a row this rank does not own, or the ghosts a rank expects
  /// from a neighbour are not as many as that neighbour sends.
  void validate() const;
};

/// Fills the ghost entries x(owned ..) of a vector of length columns() from
/// the neighbours' owned entries.
class GhostExchange {
 public:
  explicit GhostExchange(const Distribution& distribution);
  void update(const Vector& x);

 private:
  Distribution d_;
  RealView1 send_, recv_;
  HostView<Real*> send_h_, recv_h_;
};

}  // namespace mote::linalg
