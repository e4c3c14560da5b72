// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/ccx_matrices.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

using model::ModelError;

// Longer lines are not CalculiX's: refused before they are parsed.
constexpr std::size_t kMaxLine = 200;

[[noreturn]] void fail(const std::string& path, int line, const std::string& problem,
                       const std::string& fix) {
  throw ModelError(path, "line " + std::to_string(line), problem, fix);
}

std::ifstream open(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in)
    throw ModelError(path, "file", "cannot open the " + what + " file",
                     "write it with CalculiX's *FREQUENCY, SOLVER=MATRIXSTORAGE (jobname.sti, jobname.mas, "
                     "jobname.dof) and give its path relative to the model file");
  return in;
}

/// Reads the lines of the file, with the line-length check; trailing blank
/// lines dropped.
std::vector<std::string> lines_of(std::ifstream& in, const std::string& path) {
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() > kMaxLine)
      fail(path, static_cast<int>(lines.size()) + 1,
           "the line is longer than " + std::to_string(kMaxLine) +
               " characters, which CalculiX does not write",
           "give the file CalculiX wrote, unchanged");
    lines.push_back(line);
  }
  while (!lines.empty() && lines.back().find_first_not_of(" \t") == std::string::npos) lines.pop_back();
  return lines;
}

/// A positive integer of at most 9 digits, or -1.
int positive_integer(const std::string& s) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return -1;
  const int v = std::stoi(s);
  return v > 0 ? v : -1;
}

/// A finite number written completely, or false.
bool finite_number(const std::string& s, double& value) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && errno != ERANGE && std::isfinite(value);
}

std::vector<std::string> fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string f;
  while (in >> f && out.size() < 4) out.push_back(f);
  return out;
}

}  // namespace

std::vector<CcxDof> read_ccx_dofs(const std::string& path) {
  std::ifstream in = open(path, "dof map (.dof)");
  const std::vector<std::string> lines = lines_of(in, path);
  if (lines.empty())
    throw ModelError(path, "file", "the dof map is empty",
                     "give the jobname.dof file of the same CalculiX job");
  const std::string fix = "each line is node.direction (as 12.3), as CalculiX writes jobname.dof";
  std::vector<CcxDof> dofs;
  std::set<std::pair<int, int>> seen;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line = static_cast<int>(k) + 1;
    const std::vector<std::string> f = fields(lines[k]);
    const std::size_t dot = f.size() == 1 ? f[0].find('.') : std::string::npos;
    if (dot == std::string::npos) fail(path, line, "not a dof node.direction", fix);
    const int node = positive_integer(f[0].substr(0, dot));
    const int direction = positive_integer(f[0].substr(dot + 1));
    if (node < 0 || direction < 0) fail(path, line, "not a dof node.direction", fix);
    if (direction > 3)
      fail(path, line,
           "direction " + std::to_string(direction) + " of node " + std::to_string(node) +
               " is not a translation (1, 2 or 3)",
           "export a mesh of plane or solid elements, whose nodes have translations only");
    if (!seen.insert({node, direction}).second)
      fail(path, line,
           "node " + std::to_string(node) + " direction " + std::to_string(direction) + " is listed twice",
           "give the jobname.dof file CalculiX wrote, unchanged");
    dofs.push_back({node, direction});
  }
  return dofs;
}

Eigen::SparseMatrix<double> read_ccx_matrix(const std::string& path, int n) {
  std::ifstream in = open(path, "matrix (.sti, .mas)");
  const std::vector<std::string> lines = lines_of(in, path);
  if (lines.empty())
    throw ModelError(path, "file", "the matrix file is empty",
                     "give the file CalculiX wrote for the same job");
  struct Entry {
    double value;
    int line;
    bool upper;
  };
  std::map<std::pair<int, int>, Entry> entries;  // (min, max) index
  const std::string range = std::to_string(n);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line = static_cast<int>(k) + 1;
    const std::vector<std::string> f = fields(lines[k]);
    double value = 0.0;
    if (f.size() != 3 || !finite_number(f[2], value))
      fail(path, line, "not an entry 'row column value' (two integers and a finite number)",
           "give the file CalculiX wrote, unchanged");
    const int i = positive_integer(f[0]), j = positive_integer(f[1]);
    if (i < 0 || j < 0 || i > n || j > n)
      fail(path, line, "the row or column is not in 1.." + range + ", the dofs of the dof map",
           "give the matrices and the .dof file of the same CalculiX job");
    const std::pair<int, int> key{std::min(i, j) - 1, std::max(i, j) - 1};
    const bool upper = i <= j;
    const auto [it, inserted] = entries.insert({key, {value, line, upper}});
    if (inserted) continue;
    if (it->second.upper == upper || i == j)
      fail(path, line,
           "entry (" + f[0] + ", " + f[1] + ") is given twice (first on line " +
               std::to_string(it->second.line) + ")",
           "give the file CalculiX wrote, unchanged");
    const double a = it->second.value;
    if (std::abs(a - value) > 1e-9 * std::max(std::abs(a), std::abs(value)))
      fail(path, line,
           "the matrix is not symmetric: entry (" + f[0] + ", " + f[1] +
               ") differs from its mirror on line " + std::to_string(it->second.line),
           "give a symmetric matrix (CalculiX writes one triangle of its symmetric K and M)");
  }
  // A stiffness or mass matrix has a positive diagonal; a file cut short
  // (or one for fewer dofs than the .dof file lists) lacks the last ones.
  const int end = static_cast<int>(lines.size());
  for (int d = 0; d < n; ++d) {
    const auto it = entries.find({d, d});
    if (it == entries.end())
      fail(path, end,
           "the file ends without the diagonal entry (" + std::to_string(d + 1) + ", " +
               std::to_string(d + 1) + ") of the " + range + " dofs of the dof map (cut short?)",
           "give the complete file CalculiX wrote, with the .dof file of the same job");
    if (!(it->second.value > 0.0))
      fail(path, it->second.line,
           "the diagonal entry (" + std::to_string(d + 1) + ", " + std::to_string(d + 1) +
               ") is not positive, which no stiffness or mass matrix of a body has",
           "give the file CalculiX wrote, unchanged");
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(2 * entries.size());
  for (const auto& [key, e] : entries) {
    triplets.emplace_back(key.first, key.second, e.value);
    if (key.first != key.second) triplets.emplace_back(key.second, key.first, e.value);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

}  // namespace kanegen::fem
