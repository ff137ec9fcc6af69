// Opacities (RBO24 sec. 4.2): functional forms, the DSHARP/cuDisc and
// RADMC-3D table formats with their errors (file and line), PCHIP
// (Fritsch & Carlson 1980) interpolation, and Planck / Rosseland band means.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "mote/radiation/opacity.hpp"
#include "mote/radiation/planck.hpp"

namespace {

using namespace mote::radiation;

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// The error message of read(path), or "" if it was accepted.
template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const OpacityFileError& e) {
    return e.what();
  }
  return "";
}

TEST(Pchip, ReproducesCubicsWhereMonotoneAndNeverOvershoots) {
  // Exact on linear data.
  const std::vector<double> x = {0.0, 1.0, 2.5, 3.0, 4.5};
  std::vector<double> y;
  for (double v : x) y.push_back(2.0 - 3.0 * v);
  const auto lin = pchip(x, y, {0.3, 1.7, 4.4});
  EXPECT_NEAR(lin[0], 2.0 - 0.9, 1e-14);
  EXPECT_NEAR(lin[1], 2.0 - 5.1, 1e-14);
  // A step: monotone data give a monotone interpolant within the data range.
  const std::vector<double> xs = {0, 1, 2, 3, 4, 5}, ys = {0, 0, 0, 1, 1, 1};
  std::vector<double> q;
  for (int k = 0; k <= 500; ++k) q.push_back(5.0 * k / 500);
  const auto v = pchip(xs, ys, q);
  for (std::size_t k = 0; k < v.size(); ++k) {
    EXPECT_GE(v[k], 0.0);
    EXPECT_LE(v[k], 1.0);
    if (k > 0) EXPECT_GE(v[k], v[k - 1] - 1e-15);
  }
  EXPECT_THROW(pchip(xs, ys, {5.5}), std::invalid_argument);
}

/// Max error of PCHIP through n equidistant samples of f on [1, 4].
template <class F>
double pchip_error(F f, int n) {
  std::vector<double> x, y, q;
  for (int k = 0; k < n; ++k) x.push_back(1.0 + 3.0 * k / (n - 1));
  for (double v : x) y.push_back(f(v));
  for (int k = 0; k < 301; ++k) q.push_back(1.0 + 3.0 * k / 300);
  const auto p = pchip(x, y, q);
  double worst = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) worst = std::max(worst, std::fabs(p[k] - f(q[k])));
  return worst;
}

TEST(Pchip, ConvergesOnSmoothFunctions) {
  // Monotone data (as opacity curves mostly are) and data through an
  // extremum, where the slope is set to 0 and the method is second order.
  auto power = [](double v) { return std::pow(v, -1.5); };
  auto wave = [](double v) { return std::sin(v); };
  const double p_mono = std::log2(pchip_error(power, 17) / pchip_error(power, 33));
  const double p_wave = std::log2(pchip_error(wave, 17) / pchip_error(wave, 33));
  std::cout << "PCHIP orders: monotone " << p_mono << ", through an extremum " << p_wave << "\n";
  EXPECT_GE(p_mono, 2.4);  // measured 2.61 (piecewise linear would give 2)
  EXPECT_GE(p_wave, 1.7);  // measured 1.81
}

TEST(Opacity, PowerLawHasTheGeometricLimitAndTheCutOff) {
  const auto t = power_law_opacity({1e-4, 1e-1}, {1e-5, 1.0}, 1.6, 1.0);
  EXPECT_NEAR(t.k_abs(0, 0), 3.0 / (4.0 * 1.6 * 1e-4), 1e-9);                      // 2 pi a > lambda: Q = 1
  EXPECT_NEAR(t.k_abs(0, 1), 3.0 / (4.0 * 1.6 * 1e-4) * 2.0 * M_PI * 1e-4, 1e-9);  // Q = 2 pi a / lambda
  EXPECT_NEAR(t.k_abs(1, 0), 3.0 / (4.0 * 1.6 * 1e-1), 1e-12);
}

TEST(Opacity, DsharpTableIsReadWithEffectiveScattering) {
  const auto path = write_file("ok.dat",
                               "2 3\n"
                               "1e-4 1 10 5 0.2\n1e-4 10 4 2 0.2\n1e-4 100 1 0.5 0.2\n"
                               "1e-2 1 2 8 0.5\n1e-2 10 2 4 0.5\n1e-2 100 1.5 2 0.5\n");
  const auto t = read_dsharp_table(path);
  ASSERT_EQ(t.sizes(), 2);
  ASSERT_EQ(t.wavelengths(), 3);
  EXPECT_DOUBLE_EQ(t.wavelengths_cm[1], 10e-4);
  EXPECT_DOUBLE_EQ(t.k_abs(1, 2), 1.5);
  EXPECT_DOUBLE_EQ(t.k_sca(0, 0), 5.0 * 0.8);
  EXPECT_DOUBLE_EQ(t.k_sca(1, 1), 4.0 * 0.5);
}

TEST(Opacity, MalformedDsharpTablesNameFileAndLine) {
  const auto check = [](const std::string& text, const std::string& where, const std::string& words) {
    const auto path = write_file("bad.dat", text);
    const auto message = error_of([&] { read_dsharp_table(path); });
    EXPECT_NE(message.find(path + ":" + where), std::string::npos) << message;
    EXPECT_NE(message.find(words), std::string::npos) << message;
  };
  check("2 2\n1e-4 1 1 1\n1e-4 10 1 1\n1e-2 1 1 1\n", "4:", "announces 2 x 2 rows");
  check("1 2\n1e-4 1 1 x1\n1e-4 10 1 1\n", "2:", "'x1' is not a number");
  check("1 2\n1e-4 1 -1 1\n1e-4 10 1 1\n", "2:", "'-1' must be >= 0");
  check("1 2\n1e-4 1 1 1 -1.5\n1e-4 10 1 1\n", "2:", "g must lie in [-1, 1]");
  check("1 2\n1e-4 1 1 1 inf\n1e-4 10 1 1\n", "2:", "must be finite");
  check("1 2\n1e-4 10 1 1\n1e-4 1 1 1\n", "3:", "wavelengths must increase");
  check("2 1\n1e-2 1 1 1\n1e-4 1 1 1\n", "3:", "grain sizes must increase");
  check("1 2\n1e-4 1 1\n1e-4 10 1 1\n", "2:", "expected 4 to 5 numbers");
  EXPECT_NE(error_of([] { read_dsharp_table("/nonexistent/opacity.dat"); }).find("cannot open"), std::string::npos);
}

// Mie and DSHARP asymmetry factors may be negative (backward scattering, or the
// round-off of isotropic scattering: DSHARP's g dips to -2e-6): read as
// k_sca (1 - g), in both formats.
TEST(Opacity, NegativeAsymmetryFactorsAreRead) {
  const auto dsharp = write_file("negative_g.dat", "1 2\n1e-4 1 1 4 -1e-6\n1e-4 10 1 4 -0.5\n");
  const auto t = read_dsharp_table(dsharp);
  EXPECT_DOUBLE_EQ(t.k_sca(0, 0), 4.0 * (1.0 + 1e-6));
  EXPECT_DOUBLE_EQ(t.k_sca(0, 1), 6.0);
  const auto radmc = write_file("dustkappa_negative_g.inp", "3\n2\n0.1 100 50 -0.25\n1.0 30 10 1.0\n");
  const auto r = read_radmc_dustkappa(radmc, 1e-4);
  EXPECT_DOUBLE_EQ(r.k_sca(0, 0), 62.5);
  EXPECT_DOUBLE_EQ(r.k_sca(0, 1), 0.0);
}

TEST(Opacity, RadmcDustkappaIsRead) {
  const auto path =
      write_file("dustkappa_test.inp", "# a comment\n3\n3\n  0.1 100 50 0.5\n 1.0 30 10 0.25\n10 3 1 0.0\n");
  const auto t = read_radmc_dustkappa(path, 1e-4);
  ASSERT_EQ(t.wavelengths(), 3);
  EXPECT_DOUBLE_EQ(t.k_abs(0, 1), 30.0);
  EXPECT_DOUBLE_EQ(t.k_sca(0, 1), 7.5);
  const auto bad = write_file("dustkappa_bad.inp", "1\n3\n0.1 100\n1.0 30\n");
  EXPECT_NE(error_of([&] { read_radmc_dustkappa(bad, 1e-4); }).find(bad + ":4: n_lambda = 3"), std::string::npos);
  const auto bad2 = write_file("dustkappa_bad2.inp", "2\n2\n0.1 100 1\n0.05 30 1\n");
  EXPECT_NE(error_of([&] { read_radmc_dustkappa(bad2, 1e-4); }).find(":4: wavelengths must be"), std::string::npos);
}

TEST(Opacity, InterpolationIsExactForPowerLawsInLogSpace) {
  // kappa = 7 (lambda / 1 um)^-1.3 (a / 1 um)^-0.5 is linear in log-log space.
  std::vector<double> sizes = {1e-5, 1e-4, 1e-3, 1e-2}, lambdas = {1e-5, 1e-4, 1e-3, 1e-2, 1e-1};
  OpacityTable t = grey_opacity(sizes, lambdas, 0.0, 0.0);
  for (int a = 0; a < 4; ++a)
    for (int l = 0; l < 5; ++l) {
      t.absorption[a * 5 + l] = 7.0 * std::pow(lambdas[l] / 1e-4, -1.3) * std::pow(sizes[a] / 1e-4, -0.5);
      t.scattering[a * 5 + l] = 0.5 * t.absorption[a * 5 + l];
    }
  const auto r = interpolate(t, {3e-5, 2e-3}, {2e-5, 7e-3, 0.1});
  for (int a = 0; a < 2; ++a)
    for (int l = 0; l < 3; ++l) {
      const double exact = 7.0 * std::pow(r.wavelengths_cm[l] / 1e-4, -1.3) * std::pow(r.sizes_cm[a] / 1e-4, -0.5);
      EXPECT_NEAR(r.k_abs(a, l) / exact, 1.0, 1e-12);
      EXPECT_NEAR(r.k_sca(a, l) / (0.5 * exact), 1.0, 1e-12);
    }
  EXPECT_THROW(interpolate(t, {1e-4}, {0.2}), std::invalid_argument);  // wavelength outside the table
  EXPECT_THROW(interpolate(t, {1.0}, {1e-3}), std::invalid_argument);  // size outside the table
}

TEST(Opacity, BandMeansOfAGreyTableAreGreyAndPlanckMeanWeightsByB) {
  std::vector<double> edges;
  for (int k = 0; k <= 100; ++k) edges.push_back(1e-5 * std::pow(3e4, k / 100.0));
  std::vector<double> centres;
  for (int k = 0; k < 100; ++k) centres.push_back(std::sqrt(edges[k] * edges[k + 1]));
  const auto grey = grey_opacity({1e-4}, centres, 3.0, 1.0);
  const std::vector<double> bands = {1e-5, 1e-4, 1e-3, 1e-2, 0.3};
  const auto m = band_means(grey, edges, bands, 100.0);
  for (int b = 0; b < 4; ++b) {
    EXPECT_NEAR(m.planck_absorption[b], 3.0, 1e-12);
    EXPECT_NEAR(m.rosseland_total[b], 4.0, 1e-9);
  }
  // kappa = lambda^-1 over one band holding everything: the Planck mean is
  // sum w kappa / sum w with w the bins' Planck fractions.
  auto t = grey_opacity({1e-4}, centres, 0.0, 0.0);
  double num = 0.0, den = 0.0;
  for (int k = 0; k < 100; ++k) {
    t.absorption[k] = 1e-4 / centres[k];
    const double w = band_fraction(edges[k], edges[k + 1], 300.0);
    num += w * t.absorption[k];
    den += w;
  }
  EXPECT_NEAR(band_means(t, edges, {1e-5, 0.3}, 300.0).planck_absorption[0], num / den, 1e-12 * num / den);
  EXPECT_THROW(band_means(t, edges, {1e-5, 1.06e-5, 1.07e-5, 0.3}, 300.0), std::invalid_argument);  // an empty band
}

// The Rosseland mean of a non-grey table, kappa_tot = 1e-3 / lambda + 0.01 in one
// band holding every bin: sum w / sum (w / kappa), with w the bins' integrals of
// dB_lambda/dT by Simpson's rule here (RBO24 sec. 4.1); an arithmetic mean
// sum w kappa / sum w would be 1.32 times larger.
TEST(Opacity, RosselandBandMeanOfANonGreyTableIsTheHarmonicDbDtMean) {
  std::vector<double> edges, centres;
  for (int k = 0; k <= 100; ++k) edges.push_back(1e-5 * std::pow(3e4, k / 100.0));
  for (int k = 0; k < 100; ++k) centres.push_back(std::sqrt(edges[k] * edges[k + 1]));
  auto t = grey_opacity({1e-4}, centres, 0.0, 0.01);
  for (int k = 0; k < 100; ++k) t.absorption[k] = 1e-3 / centres[k];
  const double T = 300.0, c2 = 1.438776877;  // h c / k_B [cm K]
  const auto dB_dT = [&](double lambda) {    // up to constant factors, which cancel in the mean
    const double x = c2 / (lambda * T), e = std::exp(x);
    return std::pow(lambda, -5) * x * e / ((e - 1.0) * (e - 1.0));
  };
  double weights = 0.0, inverse = 0.0, arithmetic = 0.0;
  for (int k = 0; k < 100; ++k) {
    const int n = 64;  // Simpson in ln(lambda) over the bin
    const double a = std::log(edges[k]), h = (std::log(edges[k + 1]) - a) / n;
    double w = 0.0;
    for (int m = 0; m <= n; ++m) {
      const double lambda = std::exp(a + m * h);
      w += (m == 0 || m == n ? 1.0 : (m % 2 ? 4.0 : 2.0)) * dB_dT(lambda) * lambda;
    }
    w *= h / 3.0;
    const double kappa = t.absorption[k] + t.scattering[k];
    weights += w;
    inverse += w / kappa;
    arithmetic += w * kappa;
  }
  const double expected = weights / inverse;
  EXPECT_NEAR(band_means(t, edges, {1e-5, 0.3}, T).rosseland_total[0] / expected, 1.0, 1e-8);
  EXPECT_GT(arithmetic / weights / expected, 1.3);  // 1.317: the test tells the two means apart
}

}  // namespace
