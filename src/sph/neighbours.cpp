// Cell binning (a counting sort on cell keys) and symmetric CSR neighbour list
// with count-then-fill; see include/mote/sph/neighbours.hpp for the method.
#include "mote/sph/neighbours.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "mote/core/device_sort.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"

namespace mote::sph {

// A named namespace: nvcc requires the functions that enclose extended
// (KOKKOS_LAMBDA) lambdas to have external linkage.
namespace detail {

/// An uninitialised View of n entries (at least n with slack, for the list
/// arrays whose length varies between builds): the storage of `kept` when it
/// is large enough and no copy of the list shares it, otherwise new storage.
template <class V>
V reuse(V& kept, std::size_t n, const std::string& label, bool slack = false) {
  const bool fits = slack ? kept.extent(0) >= n : kept.extent(0) == n;
  if (!fits || kept.use_count() != 1) {
    kept = V();
    kept = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), slack ? n + n / 16 : n);
  }
  return kept;
}

RealView2 reuse(RealView2& kept, int n, int dim, const std::string& label) {
  if (kept.extent(0) != static_cast<std::size_t>(n) || kept.extent(1) != static_cast<std::size_t>(dim) ||
      kept.use_count() != 1) {
    kept = RealView2();
    kept = RealView2(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), n, dim);
  }
  return kept;
}

/// Stable counting sort of the particles by cell key: cell_start(c) is the
/// first slot of cell c (cell_start(ncell) = n) and cell_particles holds the
/// particles of each cell in index order, so the list is identical on every
/// backend. `fill` (ncell entries) is work space. Allocates nothing.
void sort_by_cell(const IntView1& keys, int n, int ncell, const View<int*>& fill, const View<int*>& cell_start,
                  const View<int*>& cell_particles) {
  par_for(
      "sph::neighbour_cell_zero", 0, ncell, KOKKOS_LAMBDA(int c) { fill(c) = 0; });
  par_for(
      "sph::neighbour_cell_count", 0, n, KOKKOS_LAMBDA(int i) { Kokkos::atomic_add(&fill(keys(i)), 1); });
  Kokkos::parallel_scan(
      "sph::neighbour_cell_start", Kokkos::RangePolicy<ExecSpace>(0, ncell + 1),
      KOKKOS_LAMBDA(int c, int& acc, bool final) {
        if (final) cell_start(c) = acc;
        if (c < ncell) acc += fill(c);
      });
  par_for(
      "sph::neighbour_cell_zero", 0, ncell, KOKKOS_LAMBDA(int c) { fill(c) = 0; });
  par_for(
      "sph::neighbour_cell_fill", 0, n, KOKKOS_LAMBDA(int i) {
        const int c = keys(i);
        cell_particles(cell_start(c) + Kokkos::atomic_fetch_add(&fill(c), 1)) = i;
      });
  // Parallel fills arrive in any order: insertion sort of each cell (a few particles).
  par_for(
      "sph::neighbour_cell_sort", 0, ncell,
      KOKKOS_LAMBDA(int c) { insertion_sort(cell_particles, cell_start(c), cell_start(c + 1)); });
}

KOKKOS_INLINE_FUNCTION int ifloor(Real v) {
  int i = static_cast<int>(v);
  return i > v ? i - 1 : i;
}

/// Calls f(begin, end, image, shift) for every range [begin, end) of
/// cell_particles whose cells intersect the ball of radius `search` around xa.
/// In a periodic direction the cells are visited with their image shift (-2 ..
/// +2 box lengths), so a particle (also a itself) can appear with several
/// images when the search radius exceeds half the box. Along x the cells of a
/// row that meet the ball have consecutive keys, so their particles are one
/// range per image (no per-cell work there); shift[d] =
/// Box::image_shift(image, d). The caller loops over a range with its own
/// local state, which the compiler keeps in registers.
template <int Dim, class F>
KOKKOS_INLINE_FUNCTION void visit_ranges(const CellGrid& g, const Box& box, const Real* xa, Real search, F&& f) {
  int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  Real rel[3] = {0, 0, 0};  // xa relative to the grid origin
  for (int d = 0; d < Dim; ++d) {
    rel[d] = xa[d] - g.origin[d];
    lo[d] = ifloor((rel[d] - search) / g.width[d]);
    hi[d] = ifloor((rel[d] + search) / g.width[d]);
    if (box.periodic[d]) {
      if (lo[d] < -2 * g.nc[d]) lo[d] = -2 * g.nc[d];
      if (hi[d] > 3 * g.nc[d] - 1) hi[d] = 3 * g.nc[d] - 1;
    } else {
      if (lo[d] < 0) lo[d] = 0;
      if (hi[d] > g.nc[d] - 1) hi[d] = g.nc[d] - 1;
    }
  }
  const Real s2 = search * search;
  // Squared distance from xa to the slab of cell i along d (0 inside).
  auto gap2 = [&](int i, int d) {
    const Real clo = i * g.width[d] - rel[d];
    const Real chi = clo + g.width[d];
    const Real gap = clo > 0.0 ? clo : (chi < 0.0 ? -chi : 0.0);
    return gap * gap;
  };
  auto image_of = [&](int i, int d) {
    // floor(i / nc) for i in [-2 nc, 3 nc), no division inside the box
    if (i >= 0 && i < g.nc[d]) return 0;
    return i < 0 ? -((-i + g.nc[d] - 1) / g.nc[d]) : i / g.nc[d];
  };
  const Real inv_width0 = 1.0 / g.width[0];
  for (int i2 = lo[2]; i2 <= hi[2]; ++i2) {
    const Real g2 = Dim > 2 ? gap2(i2, 2) : 0.0;
    if (g2 >= s2) continue;
    const int sh2 = Dim > 2 ? image_of(i2, 2) : 0;
    const int c2 = i2 - sh2 * g.nc[2];
    for (int i1 = lo[1]; i1 <= hi[1]; ++i1) {
      const Real g1 = g2 + (Dim > 1 ? gap2(i1, 1) : 0.0);
      if (g1 >= s2) continue;
      const int sh1 = Dim > 1 ? image_of(i1, 1) : 0;
      const int c1 = i1 - sh1 * g.nc[1];
      const int row = g.nc[0] * (c1 + g.nc[1] * c2);
      // The cells of the row within reach of the ball, one image at a time.
      const Real reach = math::sqrt(s2 - g1);
      int a0 = ifloor((rel[0] - reach) * inv_width0), b0 = ifloor((rel[0] + reach) * inv_width0);
      if (a0 < lo[0]) a0 = lo[0];
      if (b0 > hi[0]) b0 = hi[0];
      while (a0 <= b0) {
        const int sh0 = image_of(a0, 0);
        const int e0 = b0 < (sh0 + 1) * g.nc[0] - 1 ? b0 : (sh0 + 1) * g.nc[0] - 1;
        const int code = (sh0 + 2) + 5 * (sh1 + 2) + 25 * (sh2 + 2);
        const int sh[3] = {sh0, sh1, sh2};
        Real shift[3] = {0, 0, 0};
        for (int d = 0; d < Dim; ++d) shift[d] = sh[d] * (box.hi[d] - box.lo[d]);  // Box::image_shift
        f(g.cell_start(row + a0 - sh0 * g.nc[0]), g.cell_start(row + e0 - sh0 * g.nc[0] + 1), code,
          static_cast<const Real*>(shift));
        a0 = e0 + 1;
      }
    }
  }
}

/// Calls f(b, image, shift) for every particle image in the ranges of
/// visit_ranges (the exact count-then-fill path, run on first builds only).
template <int Dim, class F>
KOKKOS_INLINE_FUNCTION void visit_cells(const CellGrid& g, const Box& box, const Real* xa, Real search, F&& f) {
  visit_ranges<Dim>(g, box, xa, search, [&](int begin, int end, int code, const Real* shift) {
    for (int s = begin; s < end; ++s) f(g.cell_particles(s), code, shift);
  });
}

/// Stride of the packed candidate records: x, y, z and the squared search
/// radius (R h (1 + skin) + delta)^2 of each particle, in cell order.
constexpr int kPack = 4;

/// The candidate loop of the single-traversal build over one range of
/// cell_particles: the entries of a go to its slack segment [begin, begin +
/// cap), reverse entries (pairs that b's own, smaller, search misses) to the
/// back of b's. The candidates are read from packed records in cell order (one
/// stream). Branch-free on the accept test (about half the candidates pass):
/// every candidate is written to the next free slot, which a hit keeps; at the
/// cap the last slot is reused and the overflow test redoes the build.
/// Everything the loop reads is copied into locals first: its byte stores may
/// alias any memory, so a value behind a pointer would be reloaded each time.
/// Ranges of the particles' own cells (no periodic image, the common case)
/// skip the shift; the separation is Box::separation's (x_a - x_b) - shift.
template <int Dim>
struct GatherScan {
  const Real* pack;  ///< kPack values per slot of cell_particles
  const int* cell_particles;
  int* out;
  unsigned char* out_image;
  View<int*> nreverse;
  View<int*> slack;

  KOKKOS_INLINE_FUNCTION int unshifted(int a, int s0, int s1, const Real* xa, Real sa2, int begin, int cap,
                                       int c) const {
    const Real zero[3] = {0, 0, 0};
    return run<false>(a, s0, s1, no_image(), xa, zero, sa2, begin, cap, c);
  }
  KOKKOS_INLINE_FUNCTION int shifted(int a, int s0, int s1, int code, const Real* xa, const Real* shift, Real sa2,
                                     int begin, int cap, int c) const {
    return run<true>(a, s0, s1, code, xa, shift, sa2, begin, cap, c);
  }

  template <bool Shifted>
  KOKKOS_INLINE_FUNCTION int run(int a, int s0, int s1, int code, const Real* xa, const Real* shift, Real sa2,
                                 int begin, int cap, int c) const {
    const Real* const rec = pack;
    const int* const cp = cell_particles;
    int* const dst = out + begin;
    unsigned char* const dst_image = out_image + begin;
    const unsigned char img = static_cast<unsigned char>(code);
    Real xl[3] = {0, 0, 0}, sh[3] = {0, 0, 0};
    for (int d = 0; d < Dim; ++d) {
      xl[d] = xa[d];
      sh[d] = shift[d];
    }
    const int self = Shifted ? -1 : a;  // a meets itself only through an image
    const int last = cap - 1;
    const Real reach2 = sa2;
    for (int s = s0; s < s1; ++s) {
      const Real* const r = rec + kPack * s;
      Real r2 = 0.0;
      for (int d = 0; d < Dim; ++d) {
        const Real dx = Shifted ? (xl[d] - r[d]) - sh[d] : xl[d] - r[d];
        r2 += dx * dx;
      }
      const int b = cp[s];
      const bool hit = (r2 < reach2) & (b != self);
      const int slot = c < last ? c : last;
      dst[slot] = b;
      dst_image[slot] = img;
      c += hit ? 1 : 0;
      if (hit & (r2 >= r[3])) add_reverse(a, b, code);
    }
    return c;
  }

  KOKKOS_INLINE_FUNCTION void add_reverse(int a, int b, int code) const {
    const int k = Kokkos::atomic_fetch_add(&nreverse(b), 1);
    const int e = slack(b + 1) - 1 - k;
    if (e >= slack(b)) {
      out[e] = a;
      out_image[e] = static_cast<unsigned char>(mirror_image(code));
    }
  }
};

/// A core::NumericalError naming the first particle whose position or smoothing length is not finite,
/// or whose h is not positive: a cell index cannot be formed from it. One reduction; the offending
/// particle's values are copied to the host only to report them.
template <int Dim>
void refuse_unusable_particles(const Particles& p) {
  auto x = p.x;
  auto h = p.h;
  const int n = p.n;
  int first = 0;
  par_reduce(
      "sph::neighbour_unusable", 0, n,
      KOKKOS_LAMBDA(int i, int& r) {
        bool usable = math::isfinite(h(i)) && h(i) > 0.0;
        for (int d = 0; d < Dim; ++d) usable = usable && math::isfinite(x(i, d));
        if (!usable && i < r) r = i;
      },
      Kokkos::Min<int>(first));
  if (first >= n) return;  // the reducer starts from the largest int
  const auto xi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(x, first, Kokkos::ALL));
  const auto hi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(h, first));
  std::string where;
  for (int d = 0; d < Dim; ++d) where += (d ? ", " : "") + logging::format("%.17g", xi(d));
  throw core::NumericalError(logging::cat("sph: particle ", first, " (in memory order) has position (", where,
                                          ") and h = ", logging::format("%.17g", hi()),
                                          " at a neighbour rebuild; positions and h must be finite, h > 0"));
}

/// Returns true when the exact count-then-fill path was taken.
template <int Dim>
bool build_impl(NeighbourList& nl, Particles& p, const Box& box, Real radius, Real skin, View<int*> prev_counts,
                const ReorderParticles& reorder) {
  const int n = p.n;
  auto x = p.x;
  auto h = p.h;
  refuse_unusable_particles<Dim>(p);
  par_for(
      "sph::neighbour_wrap", 0, n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < Dim; ++d) x(i, d) = box.wrap(x(i, d), d);
      });

  Real hmin = 0.0, hmax = 0.0;
  par_reduce(
      "sph::neighbour_hmin", 0, n, KOKKOS_LAMBDA(int i, Real& r) { r = h(i) < r ? h(i) : r; }, Kokkos::Min<Real>(hmin));
  par_reduce(
      "sph::neighbour_hmax", 0, n, KOKKOS_LAMBDA(int i, Real& r) { r = h(i) > r ? h(i) : r; }, Kokkos::Max<Real>(hmax));

  const Real eps = skin;
  const Real delta = skin * radius * hmin;
  const Real s_min = radius * hmin * (1.0 + eps) + delta;
  const Real s_max = radius * hmax * (1.0 + eps) + delta;

  Real xmin[3] = {0, 0, 0}, xmax[3] = {0, 0, 0}, vol = 1.0;
  for (int d = 0; d < Dim; ++d) {
    if (box.periodic[d]) {
      if (s_max >= 2.0 * box.length(d)) {
        throw std::runtime_error("sph::NeighbourList: kernel support " + std::to_string(s_max) +
                                 " exceeds twice the periodic box length in direction " + std::to_string(d));
      }
      xmin[d] = box.lo[d];
      xmax[d] = box.hi[d];
    } else {
      Real lo = 0.0, hi = 0.0;
      par_reduce(
          "sph::neighbour_xmin", 0, n, KOKKOS_LAMBDA(int i, Real& r) { r = x(i, d) < r ? x(i, d) : r; },
          Kokkos::Min<Real>(lo));
      par_reduce(
          "sph::neighbour_xmax", 0, n, KOKKOS_LAMBDA(int i, Real& r) { r = x(i, d) > r ? x(i, d) : r; },
          Kokkos::Max<Real>(hi));
      xmin[d] = lo;
      xmax[d] = hi;
    }
    vol *= std::max(xmax[d] - xmin[d], s_min);
  }
  // Across the rows, cells of two thirds of the smallest support (not smaller
  // than the particle spacing), so that a search meets about four rows per
  // direction: a row costs about as much as five candidates (its reach and
  // range bounds), and these rows measured fastest on the 3D settling column
  // (perf/README.md). Along the rows (x) kRowSplit times finer, a twelfth of
  // the support, which costs nothing in the search (a row segment is one
  // range) and trims the candidates beyond the ball at the ends of each one.
  constexpr int kRowSplit = 8;
  const Real across = std::max(s_min / 1.5, std::pow(vol / std::max(n, 1), 1.0 / Dim));
  CellGrid g;
  long long ncell = 1;
  for (int d = 0; d < Dim; ++d) {
    const Real ext = xmax[d] - xmin[d];
    const Real target = d == 0 ? across / kRowSplit : across;
    if (box.periodic[d]) {
      g.nc[d] = std::max(1, static_cast<int>(std::floor(ext / target)));
      g.width[d] = ext / g.nc[d];
    } else {
      g.nc[d] = static_cast<int>(std::floor(ext / target)) + 1;
      g.width[d] = target;
    }
    g.origin[d] = xmin[d];
    ncell *= g.nc[d];
  }
  if (ncell > (1LL << 30)) throw std::runtime_error("sph::NeighbourList: too many cells");
  const int nc_total = static_cast<int>(ncell);

  // Bin particles by cell key.
  const IntView1 keys = reuse(nl.work.keys, n, "sph::cell_key");
  par_for(
      "sph::neighbour_keys", 0, n, KOKKOS_LAMBDA(int i) {
        int key = 0, stride = 1;
        for (int d = 0; d < Dim; ++d) {
          key += stride * g.coord(x(i, d), d);
          stride *= g.nc[d];
        }
        keys(i) = key;
      });
  g.cell_start = reuse(nl.grid.cell_start, nc_total + 1, "sph::cell_start", true);
  g.cell_particles = reuse(nl.grid.cell_particles, n, "sph::cell_particles");
  const auto cell_start = g.cell_start;
  const auto cell_particles = g.cell_particles;
  sort_by_cell(keys, n, nc_total, reuse(nl.work.cell_fill, nc_total, "sph::cell_fill", true), cell_start,
               cell_particles);
  if (reorder) {
    // Cell order: particle i of the sorted set was cell_particles(i); the
    // previous list sizes move with their particles.
    reorder(cell_particles);
    x = p.x;
    h = p.h;
    if (prev_counts.extent(0) == static_cast<std::size_t>(n)) {
      const View<int*> moved = reuse(nl.work.moved_counts, n, "sph::neighbour_prev_counts");
      par_for(
          "sph::neighbour_prev_counts", 0, n, KOKKOS_LAMBDA(int i) { moved(i) = prev_counts(cell_particles(i)); });
      prev_counts = moved;
    }
    par_for(
        "sph::neighbour_cells_sorted", 0, n, KOKKOS_LAMBDA(int i) { cell_particles(i) = i; });
  }

  const Real rfac = radius * (1.0 + eps);
  const IntView1 ngather = reuse(nl.work.ngather, n, "sph::ngather");
  const IntView1 nreverse = reuse(nl.work.nreverse, n, "sph::nreverse");
  Kokkos::deep_copy(nreverse, 0);
  const View<int*> offsets = reuse(nl.offsets, n + 1, "sph::neighbour_offsets");
  if (nl.work.scan_total.data() == nullptr) nl.work.scan_total = View<long long>("sph::neighbour_scan_total");
  const View<long long> scan_total = nl.work.scan_total;
  View<int*> neigh;
  View<unsigned char*> image;
  bool built = false;

  if (prev_counts.extent(0) == static_cast<std::size_t>(n)) {
    // Single traversal into segments sized from the previous list (+25% + 8):
    // gather entries fill a segment from the front, reverse entries from the
    // back; a segment that overflows sends the whole build to the exact
    // count-then-fill path below. The segments are then compacted.
    const View<int*> slack = reuse(nl.work.slack, n + 1, "sph::neighbour_slack");
    const int total_slack = scan_offsets(
        "sph::neighbour_slack", n, slack, scan_total,
        KOKKOS_LAMBDA(int i) { return static_cast<long long>(prev_counts(i)) + prev_counts(i) / 4 + 8; });
    const View<int*> sneigh = reuse(nl.work.slack_neigh, total_slack, "sph::neighbour_slack_list", true);
    const View<unsigned char*> simage = reuse(nl.work.slack_image, total_slack, "sph::neighbour_slack_images", true);
    const RealView1 pack = reuse(nl.work.cell_pack, static_cast<std::size_t>(kPack) * n, "sph::neighbour_cell_pack");
    par_for(
        "sph::neighbour_cell_pack", 0, n, KOKKOS_LAMBDA(int slot) {
          const int i = cell_particles(slot);
          for (int d = 0; d < Dim; ++d) pack(kPack * slot + d) = x(i, d);
          for (int d = Dim; d < 3; ++d) pack(kPack * slot + d) = 0.0;
          const Real si = rfac * h(i) + delta;
          pack(kPack * slot + 3) = si * si;
        });
    const GatherScan<Dim> scan{pack.data(), cell_particles.data(), sneigh.data(), simage.data(), nreverse, slack};
    par_for(
        "sph::neighbour_gather", 0, n, KOKKOS_LAMBDA(int a) {
          Real xa[3] = {0, 0, 0};
          for (int d = 0; d < Dim; ++d) xa[d] = x(a, d);
          const Real sa = rfac * h(a) + delta;
          const Real sa2 = sa * sa;
          const int begin = slack(a), cap = slack(a + 1) - slack(a);
          int count = 0;
          visit_ranges<Dim>(g, box, xa, sa, [&](int s0, int s1, int code, const Real* shift) {
            count = code == no_image() ? scan.unshifted(a, s0, s1, xa, sa2, begin, cap, count)
                                       : scan.shifted(a, s0, s1, code, xa, shift, sa2, begin, cap, count);
          });
          ngather(a) = count;
        });
    int overflow = 0;
    par_reduce(
        "sph::neighbour_overflow", 0, n,
        KOKKOS_LAMBDA(int a, int& c) { c += ngather(a) + nreverse(a) >= slack(a + 1) - slack(a) ? 1 : 0; }, overflow);
    if (overflow == 0) {
      const int total = scan_offsets(
          "sph::neighbour_offsets", n, offsets, scan_total,
          KOKKOS_LAMBDA(int i) { return static_cast<long long>(ngather(i)) + nreverse(i); });
      neigh = reuse(nl.neigh, std::max(total, 1), "sph::neighbours", true);
      image = reuse(nl.image, std::max(total, 1), "sph::neighbour_images", true);
      const auto nb = neigh;
      const auto im = image;
      par_for(
          "sph::neighbour_compact", 0, n, KOKKOS_LAMBDA(int a) {
            // Raw pointers in locals, as in GatherScan (byte stores alias).
            int* const dst = nb.data() + offsets(a);
            unsigned char* const dst_image = im.data() + offsets(a);
            const int* const src = sneigh.data() + slack(a);
            const unsigned char* const src_image = simage.data() + slack(a);
            const int gathered = ngather(a), segment = slack(a + 1) - slack(a), reversed = nreverse(a);
            for (int k = 0; k < gathered; ++k) {
              dst[k] = src[k];
              dst_image[k] = src_image[k];
            }
            // In arrival order (the k-th went to the segment's end - 1 - k): in Serial that is
            // already the sorted order, which the insertion sort below then only checks.
            for (int k = 0; k < reversed; ++k) {
              dst[gathered + k] = src[segment - 1 - k];
              dst_image[gathered + k] = src_image[segment - 1 - k];
            }
          });
      built = true;
    } else {
      Kokkos::deep_copy(nreverse, 0);
    }
  }

  if (!built) {
    // Exact count-then-fill: gather entries of a, and reverse entries for
    // pairs that only the particle with the larger search radius finds.
    par_for(
        "sph::neighbour_count", 0, n, KOKKOS_LAMBDA(int a) {
          Real xa[3] = {0, 0, 0};
          for (int d = 0; d < Dim; ++d) xa[d] = x(a, d);
          const Real sa = rfac * h(a) + delta;
          const Real sa2 = sa * sa;
          int count = 0;
          visit_cells<Dim>(g, box, xa, sa, [&](int b, int code, const Real* shift) {
            if (b == a && code == no_image()) return;
            Real r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              const Real dx = (xa[d] - x(b, d)) - shift[d];  // Box::separation
              r2 += dx * dx;
            }
            if (r2 < sa2) {
              ++count;
              const Real sb = rfac * h(b) + delta;
              if (r2 >= sb * sb) Kokkos::atomic_add(&nreverse(b), 1);
            }
          });
          ngather(a) = count;
        });
    const int total = scan_offsets(
        "sph::neighbour_offsets", n, offsets, scan_total,
        KOKKOS_LAMBDA(int i) { return static_cast<long long>(ngather(i)) + nreverse(i); });
    neigh = reuse(nl.neigh, std::max(total, 1), "sph::neighbours", true);
    image = reuse(nl.image, std::max(total, 1), "sph::neighbour_images", true);
    const auto nb = neigh;
    const auto im = image;
    const IntView1 rfill = reuse(nl.work.rfill, n, "sph::rfill");
    Kokkos::deep_copy(rfill, 0);
    par_for(
        "sph::neighbour_fill", 0, n, KOKKOS_LAMBDA(int a) {
          Real xa[3] = {0, 0, 0};
          for (int d = 0; d < Dim; ++d) xa[d] = x(a, d);
          const Real sa = rfac * h(a) + delta;
          const Real sa2 = sa * sa;
          int pos = offsets(a);
          visit_cells<Dim>(g, box, xa, sa, [&](int b, int code, const Real* shift) {
            if (b == a && code == no_image()) return;
            Real r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              const Real dx = (xa[d] - x(b, d)) - shift[d];  // Box::separation
              r2 += dx * dx;
            }
            if (r2 < sa2) {
              im(pos) = static_cast<unsigned char>(code);
              nb(pos++) = b;
              const Real sb = rfac * h(b) + delta;
              if (r2 >= sb * sb) {
                const int k = Kokkos::atomic_fetch_add(&rfill(b), 1);
                const int e = offsets(b) + ngather(b) + k;
                nb(e) = a;
                im(e) = static_cast<unsigned char>(mirror_image(code));
              }
            }
          });
        });
  }
  // Reverse entries arrive in any order on parallel backends: sort them.
  par_for(
      "sph::neighbour_sort_reverse", 0, n, KOKKOS_LAMBDA(int a) {
        // Raw pointers in locals, as in GatherScan (byte stores alias).
        int* const nb = neigh.data() + offsets(a) + ngather(a);
        unsigned char* const im = image.data() + offsets(a) + ngather(a);
        const int m = offsets(a + 1) - offsets(a) - ngather(a);
        for (int i = 1; i < m; ++i) {
          const int key = nb[i];
          const unsigned char img = im[i];
          int j = i - 1;
          while (j >= 0 && (nb[j] > key || (nb[j] == key && im[j] > img))) {
            nb[j + 1] = nb[j];
            im[j + 1] = im[j];
            --j;
          }
          nb[j + 1] = key;
          im[j + 1] = img;
        }
      });

  const RealView1 h_cover = reuse(nl.h_cover, n, "sph::h_cover");
  const RealView1 h_build = reuse(nl.h_build, n, "sph::h_build");
  const RealView2 x_build = reuse(nl.x_build, n, Dim, "sph::x_build");
  par_for(
      "sph::neighbour_save", 0, n, KOKKOS_LAMBDA(int a) {
        h_cover(a) = h(a) * (1.0 + eps);
        h_build(a) = h(a);
        for (int d = 0; d < Dim; ++d) x_build(a, d) = x(a, d);
      });

  // The counts of this build go to the spare buffer: the previous counts
  // (prev_counts) are still referenced; the two swap on every build.
  const View<int*> counts = reuse(nl.work.spare_counts, n, "sph::neighbour_counts");
  par_for(
      "sph::neighbour_counts", 0, n, KOKKOS_LAMBDA(int a) { counts(a) = offsets(a + 1) - offsets(a); });
  nl.work.spare_counts = nl.counts;
  nl.counts = counts;
  nl.offsets = offsets;
  nl.neigh = neigh;
  nl.image = image;
  nl.h_cover = h_cover;
  nl.x_build = x_build;
  nl.h_build = h_build;
  nl.delta = delta;
  nl.grid = g;
  return !built;
}

}  // namespace detail

void NeighbourList::build(Particles& p, const Box& box, KernelType kernel, Real skin, const ReorderParticles& reorder) {
  if (p.n <= 0) throw std::runtime_error("sph::NeighbourList: no particles");
  const Real radius = kernel_radius(kernel);
  // Previous per-particle list sizes size the single-traversal build.
  const View<int*> prev = (n_ == p.n && dim_ == p.dim) ? counts : View<int*>();
  bool exact = true;
  switch (p.dim) {
    case 1:
      exact = detail::build_impl<1>(*this, p, box, radius, skin, prev, reorder);
      break;
    case 2:
      exact = detail::build_impl<2>(*this, p, box, radius, skin, prev, reorder);
      break;
    case 3:
      exact = detail::build_impl<3>(*this, p, box, radius, skin, prev, reorder);
      break;
    default:
      throw std::invalid_argument("sph::NeighbourList: dimension must be 1, 2 or 3");
  }
  n_ = p.n;
  dim_ = p.dim;
  int total = 0;
  Kokkos::deep_copy(total, Kokkos::subview(offsets, n_));
  entries_ = total;
  ++builds_;
  if (exact) ++exact_builds_;
}

bool NeighbourList::needs_rebuild(const Particles& p, const Box& /*box*/) const {
  if (!built() || p.n != n_ || p.dim != dim_) return true;
  const auto x = p.x;
  const auto h = p.h;
  const auto xb = x_build;
  const auto hc = h_cover;
  const int dim = dim_;
  const Real lim2 = 0.25 * delta * delta;
  int bad = 0;
  par_reduce(
      "sph::neighbour_check", 0, n_,
      KOKKOS_LAMBDA(int a, int& cnt) {
        Real r2 = 0.0;
        for (int d = 0; d < dim; ++d) {
          const Real dx = x(a, d) - xb(a, d);  // positions are not wrapped between builds
          r2 += dx * dx;
        }
        if (r2 > lim2 || h(a) > hc(a)) ++cnt;
      },
      bad);
  return bad > 0;
}

std::size_t NeighbourList::bytes() const {
  return image.extent(0) +
         sizeof(int) * (offsets.extent(0) + neigh.extent(0) + counts.extent(0) + grid.cell_start.extent(0) +
                        grid.cell_particles.extent(0)) +
         sizeof(Real) * (h_cover.extent(0) + h_build.extent(0) + x_build.extent(0) * x_build.extent(1));
}

}  // namespace mote::sph
