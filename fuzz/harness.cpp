// SPDX-License-Identifier: GPL-2.0-or-later
#include "fuzz/harness.hpp"

#include <ginac/ginac.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "model/expression_check.hpp"
#include "model/expression_eval.hpp"
#include "model/json_loader.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"
#include "model/urdf_loader.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::fuzz {
namespace {

using model::Model;
using model::ModelError;
using model::Scalar;

[[noreturn]] void failure(const std::string& what) { throw HarnessFailure(what); }

/// One in-memory file, rewritten for each input: the loaders take a path,
/// and /proc/self/fd/N is one without touching the disk.
class MemoryFile {
 public:
  MemoryFile() : fd_(::memfd_create("kanegen-fuzz", 0)) {
    if (fd_ < 0) failure(std::string("memfd_create: ") + std::strerror(errno));
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  ~MemoryFile() { ::close(fd_); }

  const std::string& hold(const std::uint8_t* data, std::size_t size) {
    if (::ftruncate(fd_, 0) != 0) failure(std::string("ftruncate: ") + std::strerror(errno));
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = ::pwrite(fd_, data + done, size - done, static_cast<off_t>(done));
      if (n <= 0) failure(std::string("pwrite: ") + std::strerror(errno));
      done += static_cast<std::size_t>(n);
    }
    return path_;
  }

 private:
  int fd_;
  std::string path_;
};

void for_each_scalar(const Model& m, const std::function<void(const Scalar&)>& visit) {
  for (const Scalar& s : m.gravity) visit(s);
  for (const auto& b : m.bodies) {
    visit(b.mass);
    for (const Scalar& s : b.com) visit(s);
    for (const Scalar& s : b.inertia) visit(s);
  }
  for (const auto& j : m.joints) {
    for (const Scalar& s : j.origin_xyz) visit(s);
    for (const Scalar& s : j.origin_rpy) visit(s);
    visit(j.spring_stiffness);
    visit(j.spring_rest);
    visit(j.damping);
  }
  for (const auto& f : m.forces) {
    for (const Scalar& s : f.point) visit(s);
    for (const Scalar& s : f.force) visit(s);
  }
  for (const auto& sp : m.springs) {
    for (const Scalar& s : sp.point) visit(s);
    for (const Scalar& s : sp.point2) visit(s);
    visit(sp.stiffness);
    visit(sp.rest_length);
    visit(sp.damping);
  }
  for (const auto& e : m.joint_efforts)  // an expression may use t: read in load()
    if (e.value.is_literal) visit(e.value);
  for (const auto& o : m.outputs)
    if (o.kind == model::OutputKind::point_position)
      for (const Scalar& s : o.point) visit(s);
}

/// What every loaded model guarantees to the symbolic stages.
void check_invariants(const Model& m) {
  const auto finite = [](double v, const std::string& what) {
    if (!std::isfinite(v)) failure("accepted model has a non-finite " + what);
  };
  for (const auto& p : m.parameters) finite(p.value, "parameter '" + p.name + "'");
  for_each_scalar(m, [&](const Scalar& s) {
    if (s.is_literal) finite(s.value, "number at " + s.where);
  });
  if (!model::is_identifier(m.name) || model::is_cpp_keyword(m.name))
    failure("accepted model name '" + m.name + "' is not a usable identifier");
  std::map<std::string, const model::Joint*> parent_of;  // body -> the joint carrying it
  bool moving = false;
  for (const auto& j : m.joints) {
    finite(j.q0, "initial q of joint '" + j.name + "'");
    finite(j.u0, "initial u of joint '" + j.name + "'");
    if (j.moves()) {
      moving = true;
      const double norm = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
      if (!(std::abs(norm - 1) < 1e-12)) failure("accepted joint '" + j.name + "' has no unit axis");
    }
    if (!parent_of.emplace(j.child, &j).second) failure("accepted body '" + j.child + "' has two parents");
  }
  // Something must move: a joint, or the elastic coordinates of a flexible body.
  const bool flexible =
      std::any_of(m.bodies.begin(), m.bodies.end(), [](const auto& b) { return b.flexible; });
  if (!moving && !flexible) failure("accepted model has no moving joint and no flexible body");
  for (const auto& b : m.bodies) {
    if (b.mass.is_literal && b.mass.value < 0) failure("accepted body '" + b.name + "' has a negative mass");
    // Every chain of parents ends at the ground, in at most one step per body.
    std::string at = b.name;
    for (std::size_t steps = 0; at != m.ground; ++steps) {
      const auto up = parent_of.find(at);
      if (up == parent_of.end() || steps > m.bodies.size())
        failure("accepted body '" + b.name + "' does not hang from the ground");
      at = up->second->parent;
    }
  }
}

GiNaC::symtab ginac_table(const std::vector<std::string>& parameters) {
  GiNaC::symtab table;
  for (const std::string& p : parameters) table[p] = GiNaC::symbol(p);
  table["pi"] = GiNaC::Pi;
  return table;
}

/// Reads an expression the load-time check accepted through Variables::scalar.
/// A ModelError is fine when GiNaC parsed the text and only its arithmetic
/// failed (1/0); a parse error means the check let through text GiNaC does
/// not read, which the check exists to prevent.
void read_with_ginac(const symbolic::Variables& variables, const Scalar& s,
                     const std::vector<std::string>& parameters) {
  try {
    (void)variables.scalar(s);
  } catch (const ModelError&) {
    GiNaC::parser reader(ginac_table(parameters), /*strict=*/true);
    try {
      (void)reader(s.text);
    } catch (const GiNaC::parse_error& p) {
      failure("the load-time check accepts '" + s.text + "' but GiNaC cannot parse it: " + p.what());
    } catch (const std::exception&) {
    }
  }
}

template <class Load>
void load(const std::uint8_t* data, std::size_t size, MemoryFile& file, Load&& load_model) {
  const std::string& path = file.hold(data, size);
  Model m;
  try {
    m = load_model(path);
  } catch (const ModelError& e) {
    check_error(e, path);
    return;
  } catch (const std::exception& e) {
    failure(std::string("loader threw something other than a ModelError: ") + e.what());
  }
  check_invariants(m);
  std::vector<std::string> parameters;
  for (const auto& p : m.parameters) parameters.push_back(p.name);
  const symbolic::Variables variables(m);
  for_each_scalar(m, [&](const Scalar& s) {
    if (!s.is_literal) read_with_ginac(variables, s, parameters);
  });
  parameters.push_back("t");
  for (const auto& e : m.joint_efforts)
    if (!e.value.is_literal) read_with_ginac(variables, e.value, parameters);
}

}  // namespace

void check_error(const ModelError& e, const std::string& file) {
  const std::string message = e.what();
  if (e.file() != file) failure("ModelError names file '" + e.file() + "', not '" + file + "': " + message);
  // The message shows the file's control characters escaped (ModelError::printable).
  const std::string shown_file = ModelError::printable(file);
  if (message.rfind(shown_file + ": ", 0) != 0)
    failure("ModelError does not start with the file: " + message);
  const std::string rest = message.substr(shown_file.size() + 2);
  const auto colon = rest.find(": ");
  if (colon == std::string::npos || colon == 0 || rest.size() <= colon + 2)
    failure("ModelError has no place or no problem: " + message);
  // One line, or three for an expression shown with a caret under the
  // culprit: "problem\n  TEXT\n  <spaces>^[; fix]".
  const auto first = message.find('\n');
  if (first == std::string::npos) return;
  const auto second = message.find('\n', first + 1);
  const bool caret_layout = second != std::string::npos &&
                            message.find('\n', second + 1) == std::string::npos &&
                            message.compare(first + 1, 2, "  ") == 0 &&
                            message.find_first_not_of(' ', second + 1) != std::string::npos &&
                            message[message.find_first_not_of(' ', second + 1)] == '^' &&
                            message.find_first_not_of(' ', second + 1) >= second + 3;
  if (!caret_layout)
    failure("ModelError takes more than one line, and not as an expression with a caret: " + message);
}

void json_model(const std::uint8_t* data, std::size_t size) {
  static MemoryFile file;
  load(data, size, file, [](const std::string& path) { return model::load_json_model(path); });
}

void urdf_model(const std::uint8_t* data, std::size_t size) {
  static MemoryFile file;
  load(data, size, file, [](const std::string& path) { return model::load_urdf_model(path, {}); });
}

void expression(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto newline = input.find('\n');
  const std::string names = newline == std::string::npos ? std::string() : input.substr(0, newline);
  const std::string text = newline == std::string::npos ? input : input.substr(newline + 1);
  std::vector<std::string> parameters;
  std::set<std::string> seen;
  std::string name;
  for (std::size_t i = 0; i <= names.size(); ++i) {
    const char c = i < names.size() ? names[i] : ' ';
    if (c != ' ' && c != ',' && c != '\t' && c != '\r') {
      name += c;
      continue;
    }
    if (name.empty()) continue;
    if (!model::is_identifier(name) || model::is_cpp_keyword(name) || model::is_reserved_parameter_name(name))
      return;  // the loaders refuse such a parameter before any expression is read
    if (seen.insert(name).second) parameters.push_back(name);
    name.clear();
  }

  const auto issue = model::check_expression(text, parameters);
  if (issue) {
    if (issue->column > text.size()) failure("caret column past the end of '" + text + "'");
    if (issue->problem.empty() || issue->fix.empty())
      failure("issue without problem or fix for '" + text + "'");
    const std::string described = model::describe_with_caret(text, *issue);
    if (described.rfind(issue->problem, 0) != 0) failure("caret description does not start with the problem");
    return;
  }
  // The loaders refuse an expression that is not finite at the parameters'
  // defaults (model_check.cpp, with the numeric evaluator); GiNaC reads the rest.
  Model m;
  m.source_file = "expression";
  double value = 0.5;
  for (const std::string& p : parameters) m.parameters.push_back({p, value += 0.25, "/parameters/" + p});
  const model::ParameterValues defaults = model::default_parameter_values(m);
  double expected = 0;
  try {
    expected = model::evaluate_expression(text, defaults);
  } catch (const std::exception& e) {
    failure("the load-time check accepts '" + text + "' but the evaluator cannot read it: " + e.what());
  }
  if (!std::isfinite(expected)) return;
  const symbolic::Variables variables(m);
  // Values are not compared with GiNaC's: it folds numbers in its own order
  // and precision (1e51 - 1e51 - 5 is 0 for it, -5 in doubles), so only
  // the grammar is checked to agree.
  read_with_ginac(variables, Scalar::expression(text, "/expression"), parameters);
}

int run_or_abort(void (*check)(const std::uint8_t*, std::size_t), const std::uint8_t* data,
                 std::size_t size) {
  try {
    check(data, size);
  } catch (const HarnessFailure& e) {
    std::fprintf(stderr, "kanegen fuzz harness: %s\n", e.what());
    std::fflush(stderr);
    std::abort();
  }
  return 0;
}

}  // namespace kanegen::fuzz
