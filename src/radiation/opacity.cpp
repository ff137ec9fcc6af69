// Dust opacities: functional forms, table readers, PCHIP interpolation and
// band means (see opacity.hpp).
#include "mote/radiation/opacity.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "mote/radiation/planck.hpp"

namespace mote::radiation {

namespace {

constexpr double cm_per_um = 1e-4;

OpacityTable empty_table(const std::vector<double>& sizes, const std::vector<double>& wavelengths) {
  OpacityTable t;
  t.sizes_cm = sizes;
  t.wavelengths_cm = wavelengths;
  t.absorption.assign(sizes.size() * wavelengths.size(), 0.0);
  t.scattering.assign(sizes.size() * wavelengths.size(), 0.0);
  return t;
}

/// Reads a file's lines, keeping their numbers (1-based); skips blank lines
/// and, if `comments`, lines starting with '#'.
struct Line {
  int number;
  std::string text;
};
std::vector<Line> read_lines(const std::string& path, bool comments) {
  std::ifstream in(path);
  if (!in) throw OpacityFileError(path + ": cannot open the opacity file");
  std::vector<Line> lines;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || (comments && text[first] == '#')) continue;
    lines.push_back({n, text});
  }
  return lines;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw OpacityFileError(path + ":" + std::to_string(line) + ": " + what);
}

constexpr std::size_t kNoSignedColumn = ~std::size_t(0);

/// The numbers of a line: between `least` and `most` of them, finite, >= 0 but
/// the one in column `signed_column` (an asymmetry factor g), which may be negative.
std::vector<double> numbers(const std::string& path, const Line& line, std::size_t least, std::size_t most,
                            std::size_t signed_column = kNoSignedColumn) {
  std::istringstream in(line.text);
  std::vector<double> v;
  std::string word;
  while (in >> word) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.size()) fail(path, line.number, "'" + word + "' is not a number");
    if (!std::isfinite(x)) fail(path, line.number, "'" + word + "' must be finite");
    if (x < 0.0 && v.size() != signed_column) fail(path, line.number, "'" + word + "' must be >= 0");
    v.push_back(x);
  }
  if (v.size() < least || v.size() > most)
    fail(path, line.number,
         "expected " + std::to_string(least) + (most > least ? " to " + std::to_string(most) : std::string()) +
             " numbers, found " + std::to_string(v.size()));
  return v;
}

int count(const std::string& path, const Line& line, double x, const std::string& what) {
  if (x < 1.0 || x != std::floor(x) || x > 1e8) fail(path, line.number, what + " must be a positive integer");
  return static_cast<int>(x);
}

}  // namespace

OpacityTable grey_opacity(const std::vector<double>& sizes_cm, const std::vector<double>& wavelengths_cm,
                          double kappa_abs, double kappa_sca) {
  if (!(kappa_abs >= 0.0 && kappa_sca >= 0.0 && std::isfinite(kappa_abs) && std::isfinite(kappa_sca)))
    throw std::invalid_argument("radiation: grey opacities must be finite and >= 0");
  auto t = empty_table(sizes_cm, wavelengths_cm);
  std::fill(t.absorption.begin(), t.absorption.end(), kappa_abs);
  std::fill(t.scattering.begin(), t.scattering.end(), kappa_sca);
  return t;
}

OpacityTable power_law_opacity(const std::vector<double>& sizes_cm, const std::vector<double>& wavelengths_cm,
                               double rho_grain, double beta) {
  if (!(rho_grain > 0.0) || !(beta >= 0.0))
    throw std::invalid_argument("radiation: power-law opacity needs rho_grain > 0 and beta >= 0");
  auto t = empty_table(sizes_cm, wavelengths_cm);
  for (int a = 0; a < t.sizes(); ++a)
    for (int l = 0; l < t.wavelengths(); ++l) {
      const double size = sizes_cm[a], x = 2.0 * M_PI * size / wavelengths_cm[l];
      t.absorption[a * t.wavelengths() + l] = 3.0 / (4.0 * rho_grain * size) * std::min(1.0, std::pow(x, beta));
    }
  return t;
}

OpacityTable read_dsharp_table(const std::string& path) {
  const auto lines = read_lines(path, false);
  if (lines.empty()) throw OpacityFileError(path + ": the opacity file is empty");
  const auto header = numbers(path, lines[0], 2, 2);
  const int na = count(path, lines[0], header[0], "n_a"), nl = count(path, lines[0], header[1], "n_lambda");
  if (static_cast<long>(lines.size()) - 1 != static_cast<long>(na) * nl)
    fail(path, lines.back().number,
         "the header announces " + std::to_string(na) + " x " + std::to_string(nl) + " rows, the file holds " +
             std::to_string(lines.size() - 1));
  OpacityTable t = empty_table(std::vector<double>(na), std::vector<double>(nl));
  for (int a = 0; a < na; ++a)
    for (int l = 0; l < nl; ++l) {
      const Line& line = lines[1 + a * nl + l];
      const auto v = numbers(path, line, 4, 5, 4);
      const double size = v[0], lambda = v[1] * cm_per_um, g = v.size() == 5 ? v[4] : 0.0;
      if (std::fabs(g) > 1.0) fail(path, line.number, "the asymmetry factor g must lie in [-1, 1]");
      if (l == 0 && a > 0 && !(size > t.sizes_cm[a - 1])) fail(path, line.number, "grain sizes must increase");
      if (l > 0 && size != t.sizes_cm[a]) fail(path, line.number, "the grain size changes inside its block");
      if (l > 0 && !(lambda > t.wavelengths_cm[l - 1])) fail(path, line.number, "wavelengths must increase");
      if (a > 0 && lambda != t.wavelengths_cm[l])
        fail(path, line.number, "the wavelength differs from the first size's block");
      if (!(size > 0.0) || !(lambda > 0.0)) fail(path, line.number, "sizes and wavelengths must be > 0");
      t.sizes_cm[a] = size;
      t.wavelengths_cm[l] = lambda;
      t.absorption[a * nl + l] = v[2];
      t.scattering[a * nl + l] = v[3] * (1.0 - g);
    }
  return t;
}

OpacityTable read_radmc_dustkappa(const std::string& path, double size_cm) {
  const auto lines = read_lines(path, true);
  if (lines.size() < 2) throw OpacityFileError(path + ": expected iformat and n_lambda before the table");
  const int iformat = count(path, lines[0], numbers(path, lines[0], 1, 1)[0], "iformat");
  if (iformat > 3) fail(path, lines[0].number, "iformat must be 1, 2 or 3");
  const int nl = count(path, lines[1], numbers(path, lines[1], 1, 1)[0], "n_lambda");
  if (static_cast<int>(lines.size()) - 2 != nl)
    fail(path, lines.back().number,
         "n_lambda = " + std::to_string(nl) + " but the file holds " + std::to_string(lines.size() - 2) + " rows");
  OpacityTable t = empty_table({size_cm}, std::vector<double>(nl));
  for (int l = 0; l < nl; ++l) {
    const Line& line = lines[2 + l];
    const auto v = numbers(path, line, 1 + iformat, 1 + iformat, 3);
    const double lambda = v[0] * cm_per_um;
    if (!(lambda > 0.0) || (l > 0 && !(lambda > t.wavelengths_cm[l - 1])))
      fail(path, line.number, "wavelengths must be > 0 and increase");
    const double g = iformat == 3 ? v[3] : 0.0;
    if (std::fabs(g) > 1.0) fail(path, line.number, "the asymmetry factor g must lie in [-1, 1]");
    t.wavelengths_cm[l] = lambda;
    t.absorption[l] = v[1];
    t.scattering[l] = iformat >= 2 ? v[2] * (1.0 - g) : 0.0;
  }
  return t;
}

std::vector<double> pchip(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& xq) {
  const int n = static_cast<int>(x.size());
  if (n < 2 || y.size() != x.size()) throw std::invalid_argument("pchip: needs two or more points");
  std::vector<double> h(n - 1), delta(n - 1), d(n, 0.0);
  for (int k = 0; k + 1 < n; ++k) {
    h[k] = x[k + 1] - x[k];
    if (!(h[k] > 0.0)) throw std::invalid_argument("pchip: x must increase");
    delta[k] = (y[k + 1] - y[k]) / h[k];
  }
  // Interior slopes: weighted harmonic mean where the data are monotone, else 0.
  for (int k = 1; k + 1 < n; ++k) {
    if (delta[k - 1] * delta[k] <= 0.0) continue;
    const double w1 = 2.0 * h[k] + h[k - 1], w2 = h[k] + 2.0 * h[k - 1];
    d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
  }
  // End slopes: the shape-preserving three-point formula.
  auto end_slope = [](double h0, double h1, double d0, double d1) {
    double s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (s * d0 <= 0.0) return 0.0;
    if (d0 * d1 <= 0.0 && std::fabs(s) > std::fabs(3.0 * d0)) return 3.0 * d0;
    return s;
  };
  if (n == 2) {
    d[0] = d[1] = delta[0];
  } else {
    d[0] = end_slope(h[0], h[1], delta[0], delta[1]);
    d[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
  }
  std::vector<double> out;
  for (double q : xq) {
    if (q < x.front() || q > x.back()) throw std::invalid_argument("pchip: point outside the data");
    const int k = std::min<int>(static_cast<int>(std::upper_bound(x.begin(), x.end(), q) - x.begin()) - 1, n - 2);
    const double t = (q - x[k]) / h[k], t2 = t * t, t3 = t2 * t;
    out.push_back((2 * t3 - 3 * t2 + 1) * y[k] + (t3 - 2 * t2 + t) * h[k] * d[k] + (-2 * t3 + 3 * t2) * y[k + 1] +
                  (t3 - t2) * h[k] * d[k + 1]);
  }
  return out;
}

namespace {

std::vector<double> logs(const std::vector<double>& v) {
  std::vector<double> out;
  for (double x : v) out.push_back(std::log(std::max(x, 1e-300)));
  return out;
}

/// One opacity array (size-major) interpolated in log-log space.
std::vector<double> interpolate_values(const OpacityTable& t, const std::vector<double>& values,
                                       const std::vector<double>& sizes, const std::vector<double>& wavelengths) {
  const auto lq = logs(wavelengths), lx = logs(t.wavelengths_cm);
  // In wavelength at every table size.
  std::vector<std::vector<double>> by_size;
  for (int a = 0; a < t.sizes(); ++a) {
    const std::vector<double> row(values.begin() + a * t.wavelengths(), values.begin() + (a + 1) * t.wavelengths());
    by_size.push_back(pchip(lx, logs(row), lq));
  }
  std::vector<double> out(sizes.size() * wavelengths.size());
  const auto aq = logs(sizes), ax = logs(t.sizes_cm);
  for (std::size_t l = 0; l < wavelengths.size(); ++l) {
    std::vector<double> column;
    for (int a = 0; a < t.sizes(); ++a) column.push_back(by_size[a][l]);
    const auto at_sizes = t.sizes() == 1 ? std::vector<double>(sizes.size(), column[0]) : pchip(ax, column, aq);
    for (std::size_t a = 0; a < sizes.size(); ++a) out[a * wavelengths.size() + l] = std::exp(at_sizes[a]);
  }
  return out;
}

void check_inside(const std::vector<double>& table, const std::vector<double>& wanted, const std::string& what) {
  for (double x : wanted)
    if (x < table.front() * (1 - 1e-12) || x > table.back() * (1 + 1e-12)) {
      std::ostringstream out;
      out << "radiation: " << what << " " << x << " cm lies outside the table (" << table.front() << " - "
          << table.back() << " cm)";
      throw std::invalid_argument(out.str());
    }
}

std::vector<double> clamp_to(const std::vector<double>& table, std::vector<double> wanted) {
  for (double& x : wanted) x = std::min(std::max(x, table.front()), table.back());
  return wanted;
}

}  // namespace

OpacityTable interpolate(const OpacityTable& table, const std::vector<double>& sizes_cm,
                         const std::vector<double>& wavelengths_cm) {
  check_inside(table.wavelengths_cm, wavelengths_cm, "wavelength");
  if (table.sizes() > 1) check_inside(table.sizes_cm, sizes_cm, "grain size");
  const auto lambda = clamp_to(table.wavelengths_cm, wavelengths_cm);
  const auto a = table.sizes() > 1 ? clamp_to(table.sizes_cm, sizes_cm) : sizes_cm;
  OpacityTable out = empty_table(sizes_cm, wavelengths_cm);
  out.absorption = interpolate_values(table, table.absorption, a, lambda);
  out.scattering = interpolate_values(table, table.scattering, a, lambda);
  return out;
}

std::vector<int> fine_bin_bands(const std::vector<double>& fine_edges_cm, const std::vector<double>& band_edges_cm) {
  const int nl = static_cast<int>(fine_edges_cm.size()) - 1, nb = static_cast<int>(band_edges_cm.size()) - 1;
  if (nb < 1) throw std::invalid_argument("radiation: at least one band is needed");
  std::vector<int> band(nl);
  std::vector<int> members(nb, 0);
  for (int l = 0; l < nl; ++l) {
    const double centre = std::sqrt(fine_edges_cm[l] * fine_edges_cm[l + 1]);
    int b = 0;
    while (b < nb - 1 && centre >= band_edges_cm[b + 1]) ++b;
    band[l] = b;
    ++members[b];
  }
  for (int b = 0; b < nb; ++b)
    if (members[b] == 0)
      throw std::invalid_argument("radiation: band " + std::to_string(b) + " holds no fine wavelength bin");
  return band;
}

BandMeans band_means(const OpacityTable& fine, const std::vector<double>& fine_edges_cm,
                     const std::vector<double>& band_edges_cm, double T) {
  const int nl = fine.wavelengths(), nb = static_cast<int>(band_edges_cm.size()) - 1;
  if (static_cast<int>(fine_edges_cm.size()) != nl + 1)
    throw std::invalid_argument("radiation: the fine bins need one more edge than the table has wavelengths");
  if (!(T > 0.0)) throw std::invalid_argument("radiation: band means need T > 0");
  const std::vector<int> band = fine_bin_bands(fine_edges_cm, band_edges_cm);
  BandMeans m;
  m.planck_absorption.assign(fine.sizes() * nb, 0.0);
  m.rosseland_total.assign(fine.sizes() * nb, 0.0);
  for (int a = 0; a < fine.sizes(); ++a) {
    std::vector<double> wp(nb, 0.0), sp(nb, 0.0), wr(nb, 0.0), sr(nb, 0.0);  // weights > 0 (band_weight_floor)
    for (int l = 0; l < nl; ++l) {
      double p, r;
      band_mean_weights(planck_edge(fine_edges_cm[l], T), planck_edge(fine_edges_cm[l + 1], T), T, p, r);
      const double total = fine.k_abs(a, l) + fine.k_sca(a, l);
      wp[band[l]] += p;
      sp[band[l]] += p * fine.k_abs(a, l);
      wr[band[l]] += r;
      sr[band[l]] += r / std::max(total, 1e-300);
    }
    for (int b = 0; b < nb; ++b) {
      m.planck_absorption[a * nb + b] = sp[b] / wp[b];
      m.rosseland_total[a * nb + b] = wr[b] / sr[b];
    }
  }
  return m;
}

}  // namespace mote::radiation
