// Boundary kinds and their deck keys (see include/mote/mesh/boundaries.hpp).
#include "mote/mesh/boundaries.hpp"

#include <stdexcept>

namespace mote::mesh {

BoundaryKind boundary_kind(const std::string& name) {
  if (name == "outflow") return BoundaryKind::Outflow;
  if (name == "zero") return BoundaryKind::Zero;
  if (name == "closed") return BoundaryKind::Closed;
  throw std::invalid_argument("unknown boundary kind '" + name + "'");
}

void Boundaries::declare(core::DeckSchema& s) {
  s.table("boundaries", "Boundary conditions per side of the (R, theta) grid (RBO24 sec. 2).");
  const std::vector<std::string> kinds = {"outflow", "zero", "closed"};
  s.string("boundaries.inner").default_value(std::string("outflow")).one_of(kinds).doc("At R_in.");
  s.string("boundaries.outer").default_value(std::string("outflow")).one_of(kinds).doc("At R_out.");
  s.string("boundaries.lower")
      .default_value(std::string("closed"))
      .one_of(kinds)
      .doc("At theta_min (closed = mid-plane symmetry).");
  s.string("boundaries.upper").default_value(std::string("outflow")).one_of(kinds).doc("At theta_max.");
}

Boundaries Boundaries::from_deck(const core::Deck& d) {
  Boundaries b;
  b.inner = boundary_kind(d.string("boundaries.inner"));
  b.outer = boundary_kind(d.string("boundaries.outer"));
  b.lower = boundary_kind(d.string("boundaries.lower"));
  b.upper = boundary_kind(d.string("boundaries.upper"));
  return b;
}

}  // namespace mote::mesh
