// SPDX-License-Identifier: GPL-2.0-or-later
// Kernels split into functions (kernel_splitter.*, kanegen generate
// --split-threshold) compute what the unsplit ones do: arm7 generated with
// parts of about 300 operations (arm7_split, double and float) against the
// shipped arm7, kernel by kernel, at random states; each part makes its
// library calls first. (chain20, split by the default threshold, is checked
// against MuJoCo by the consistency tests.)
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "arm7.hpp"
#include "arm7_split.hpp"
#include "arm7_split_float.hpp"

namespace {

namespace whole = kanegen_models::arm7;
namespace split = kanegen_models::arm7_split;
namespace split_float = kanegen_models::arm7_split_float;

/// max|a - b| / max(1, max|b|).
template <class A>
double error(const A* a, const double* b, int n) {
  double difference = 0, size = 1;
  for (int i = 0; i < n; ++i) {
    difference = std::max(difference, std::abs(static_cast<double>(a[i]) - b[i]));
    size = std::max(size, std::abs(b[i]));
  }
  return difference / size;
}

std::string read(const char* path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("arm7_split's kernels are split into functions", "[split]") {
  const std::string header = read(ARM7_SPLIT_HEADER);
  REQUIRE_FALSE(header.empty());
  // The kernels of more than 300 operations: M, f, forward_dynamics, ...
  CHECK(header.find("//   mass_matrix: ") != std::string::npos);
  std::size_t split_kernels = 0;
  for (std::size_t at = header.find("[split in "); at != std::string::npos;
       at = header.find("[split in ", at + 1))
    ++split_kernels;
  CHECK(split_kernels >= 4);
}

TEST_CASE("each part of a split kernel makes its library calls first", "[split]") {
  // A call may overwrite every floating-point register: before a part's
  // last sin or cos come only values loaded from earlier parts, arguments
  // of the inputs alone (q[k] + c), the calls and their stores.
  const std::string header = ARM7_SPLIT_HEADER;  // arm7_split.hpp; the source beside it
  const std::string source = read((header.substr(0, header.size() - 4) + ".cpp").c_str());
  REQUIRE_FALSE(source.empty());
  const std::regex call(R"(= (sin|cos)\(x\d+\);)"), early(R"(= w\[\d+\];|^ *w\[\d+\] = x\d+;$)");
  const std::regex temporary(R"(x\d+)");
  std::istringstream lines(source);
  std::vector<std::string> part;
  int parts_with_calls = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("static void part") != std::string::npos) {
      part.clear();
      continue;
    }
    if (line != "    }") {
      part.push_back(line);
      continue;
    }
    std::size_t last_call = 0;
    for (std::size_t k = 0; k < part.size(); ++k)
      if (std::regex_search(part[k], call)) last_call = k + 1;
    if (last_call == 0) continue;
    ++parts_with_calls;
    for (std::size_t k = 0; k < last_call; ++k) {
      const std::string& l = part[k];
      const std::string rhs = l.substr(l.find(" = ") + 3);
      INFO(l);
      const bool allowed =
          std::regex_search(l, call) || std::regex_search(l, early) || !std::regex_search(rhs, temporary);
      CHECK(allowed);
    }
  }
  CHECK(parts_with_calls > 0);
}

TEST_CASE("split kernels give the numbers of the unsplit ones", "[split]") {
  static_assert(whole::NQ == split::NQ && whole::NU == split::NU && whole::NTAU == split::NTAU);
  constexpr int n = whole::NU;
  std::mt19937 random(17);
  std::uniform_real_distribution<double> angle(-3.14, 3.14), rate(-2, 2);
  const whole::Params pw;
  const split::Params ps;
  const split_float::Params pf;
  for (int sample = 0; sample < 20; ++sample) {
    double q[n], u[n], tau[n], a[n];
    float qf[n], uf[n], tauf[n];
    for (int i = 0; i < n; ++i) {
      q[i] = angle(random);
      u[i] = rate(random);
      tau[i] = rate(random);
      a[i] = rate(random);
      qf[i] = static_cast<float>(q[i]);
      uf[i] = static_cast<float>(u[i]);
      tauf[i] = static_cast<float>(tau[i]);
    }
    const double t = 0.1 * sample;
    double mw[n * n], ms[n * n], fw[n], fs[n], aw[n], as[n], hw[n], hs[n], iw[n], is[n], gw[n], gs[n];
    whole::mass_matrix(pw, q, mw);
    split::mass_matrix(ps, q, ms);
    CHECK(error(ms, mw, n * n) < 1e-13);
    whole::forcing(pw, t, q, u, tau, fw);
    split::forcing(ps, t, q, u, tau, fs);
    CHECK(error(fs, fw, n) < 1e-13);
    REQUIRE(whole::forward_dynamics(pw, t, q, u, tau, aw) == 0);
    REQUIRE(split::forward_dynamics(ps, t, q, u, tau, as) == 0);
    CHECK(error(as, aw, n) < 1e-12);
    whole::generalized_momentum(pw, q, u, hw);
    split::generalized_momentum(ps, q, u, hs);
    CHECK(error(hs, hw, n) < 1e-13);
    whole::inverse_dynamics(pw, t, q, u, a, iw);
    split::inverse_dynamics(ps, t, q, u, a, is);
    CHECK(error(is, iw, n) < 1e-13);
    whole::gravity(pw, q, gw);
    split::gravity(ps, q, gs);
    CHECK(error(gs, gw, n) < 1e-13);
    const double tw = whole::kinetic_energy(pw, q, u), vw = whole::potential_energy(pw, q);
    CHECK(std::abs(split::kinetic_energy(ps, q, u) - tw) <= 1e-13 * std::max(1.0, std::abs(tw)));
    CHECK(std::abs(split::potential_energy(ps, q) - vw) <= 1e-13 * std::max(1.0, std::abs(vw)));

    // float: the same code in single precision, to its rounding.
    float af[n], mf[n * n];
    split_float::mass_matrix(pf, qf, mf);
    CHECK(error(mf, mw, n * n) < 1e-4);
    REQUIRE(split_float::forward_dynamics(pf, static_cast<float>(t), qf, uf, tauf, af) == 0);
    CHECK(error(af, aw, n) < 1e-2);
  }
}
