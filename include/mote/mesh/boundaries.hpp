// Boundary conditions of the (R, theta) grid (RBO24 sec. 2), set per side:
//   outflow: ghost cells copy the adjacent active cell; what moves out leaves, and
//            nothing flows in (the dust ghost mirrors an inward velocity, as
//            cuDisc's open boundaries do);
//   zero:    ghost densities are set to the floor (velocities copied);
//   closed:  a mirror: no mass crosses the face (the dust ghost holds the edge
//            cell with its normal velocity reversed, and dust moving into the
//            face exchanges normal momentum with its mirror image).
// The default (RBO24) is closed at theta_min (mid-plane symmetry) and outflow elsewhere.
#pragma once

#include <string>

#include "mote/core/deck.hpp"

namespace mote::mesh {

enum class BoundaryKind { Outflow, Zero, Closed };

struct Boundaries {
  BoundaryKind inner = BoundaryKind::Outflow;  // R_in
  BoundaryKind outer = BoundaryKind::Outflow;  // R_out
  BoundaryKind lower = BoundaryKind::Closed;   // theta_min
  BoundaryKind upper = BoundaryKind::Outflow;  // theta_max

  /// Deck table [boundaries]: inner, outer, lower, upper = "outflow" | "zero" | "closed".
  static void declare(core::DeckSchema& schema);
  static Boundaries from_deck(const core::Deck& deck);
};

BoundaryKind boundary_kind(const std::string& name);

}  // namespace mote::mesh
