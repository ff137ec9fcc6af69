// O(N) neighbour finding for SPH. Particles are binned on the device into cells
// of about the smallest kernel support (two thirds of it across the x rows, a
// twelfth along them; a stable counting sort of cell keys); each particle a
// gathers the candidates within S_a = R h_a (1 + skin) + delta, read from a
// cell-ordered copy of the positions and search radii in a loop without a
// branch on the accept test, and the list is made symmetric by adding, for
// every pair found only from the larger-h side, the reverse entry. The list of
// a therefore holds every b with |r_ab| < max(S_a, S_b): exactly what the
// density (gather, h_a) and the symmetric force sums of PL15 eq. 25, 27, 34
// (h_a and h_b) need, for h varying by any factor between particles. Every
// entry carries the periodic image of b it refers to (supports up to two box
// lengths; a particle may then also neighbour its own images). The list stays
// valid while every particle moved less than delta/2 and no h grew beyond
// h_build (1 + skin); positions are wrapped into the box only at a rebuild,
// so that the stored images stay correct in between. A rebuild traverses the
// cells once, into per-particle segments sized from the previous list, and
// compacts them; the first build (or an overflowing segment) uses an exact
// count-then-fill pair of traversals. The list and work arrays are reused
// between builds (the list arrays hold at least, not exactly, the entries).
// A build may reorder the particles into cell order (spatial locality for
// every later particle loop): the sorted cell keys give the order, a
// caller-supplied function permutes all the per-particle state (SphSystem:
// ParticleReorder), and the list is then built on the reordered particles;
// inside a cell the particles keep their previous order, so the order is
// reproducible from the stored state alone.
#pragma once

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/kernels.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

/// Uniform cell grid over the particles (device-copyable).
struct CellGrid {
  int nc[3] = {1, 1, 1};
  Real width[3] = {1.0, 1.0, 1.0};
  Real origin[3] = {0.0, 0.0, 0.0};
  View<int*> cell_start;      ///< ncell + 1 offsets into cell_particles
  View<int*> cell_particles;  ///< particle indices sorted by cell

  KOKKOS_INLINE_FUNCTION int coord(Real x, int d) const {
    int c = static_cast<int>((x - origin[d]) / width[d]);
    if (c < 0) c = 0;
    if (c >= nc[d]) c = nc[d] - 1;
    return c;
  }
};

/// Permutes every per-particle View into order: new index i takes the
/// particle at old index order(i).
using ReorderParticles = std::function<void(const View<int*>& order)>;

class NeighbourList {
 public:
  /// Wraps the positions into the box and builds the list for them and the
  /// current smoothing lengths; with reorder, first moves the particles into
  /// cell order through it (the list then indexes the reordered particles).
  void build(Particles& p, const Box& box, KernelType kernel, Real skin, const ReorderParticles& reorder = {});

  /// True if the list no longer covers all pairs within the kernel support:
  /// a particle moved more than delta/2 or an h grew past its cover.
  bool needs_rebuild(const Particles& p, const Box& box) const;

  bool built() const { return n_ == 0 ? false : offsets.extent(0) == static_cast<std::size_t>(n_ + 1); }
  int size() const { return n_; }
  long long entries() const { return entries_; }
  int builds() const { return builds_; }
  /// Builds that took the exact two-traversal path (first build, overflow).
  int exact_builds() const { return exact_builds_; }
  std::size_t bytes() const;

  View<int*> offsets;          ///< n + 1 CSR offsets
  View<int*> neigh;            ///< neighbour indices (self only through a periodic image)
  View<unsigned char*> image;  ///< image code of each entry (Box::image_shift)
  View<int*> counts;           ///< list length per particle (sizes the next build)
  RealView1 h_cover;           ///< largest h each particle's list stays valid for
  RealView2 x_build;           ///< positions at build time (wrapped into the box)
  RealView1 h_build;           ///< smoothing lengths at build time
  Real delta = 0.0;            ///< absolute displacement skin
  CellGrid grid;

  /// Work arrays of a build, kept (like the list arrays, unless a copy of the
  /// list shares them) so that a rebuild allocates nothing once sizes settle.
  struct Work {
    View<int*> keys, ngather, nreverse, rfill, slack, moved_counts, slack_neigh, cell_fill, spare_counts;
    View<unsigned char*> slack_image;
    RealView1 cell_pack;         ///< x and squared search radius per cell slot
    View<long long> scan_total;  ///< a scan's total, summed in 64 bits
  } work;

 private:
  int n_ = 0;
  int dim_ = 0;
  long long entries_ = 0;
  int builds_ = 0;
  int exact_builds_ = 0;
};

namespace detail {
/// offsets(i) = sum_{k < i} count(k) for i = 0 .. n (n + 1 entries): the
/// exclusive scan of a list's segment sizes. Returns the total; throws
/// std::length_error where it exceeds the int index range of the lists (about
/// 10^7 particles with the 3D M6 kernel): summed in 64 bits, so it is found
/// before any entry is written.
template <class Count>
int scan_offsets(const char* name, int n, const View<int*>& offsets, const View<long long>& total, Count count) {
  Kokkos::parallel_scan(
      name, Kokkos::RangePolicy<ExecSpace>(0, n + 1), KOKKOS_LAMBDA(int i, long long& acc, bool final) {
        if (final) {
          offsets(i) = static_cast<int>(acc);  // meaningful only if the total fits
          if (i == n) total() = acc;
        }
        if (i < n) acc += count(i);
      });
  long long sum = 0;
  Kokkos::deep_copy(sum, total);
  if (sum > std::numeric_limits<int>::max())
    throw std::length_error(std::string(name) + ": a neighbour list of " + std::to_string(sum) +
                            " entries exceeds the 32-bit index range (2^31 - 1): fewer particles per device");
  return static_cast<int>(sum);
}
}  // namespace detail

}  // namespace mote::sph
