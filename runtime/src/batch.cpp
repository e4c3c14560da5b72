// SPDX-License-Identifier: MIT
#include "batch.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "kanegen/runtime/kernel_thunks.hpp"
#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {
namespace {

// ---------------------------------------------------------------- request

/// A value of the flat request object: a number, an array of numbers, an
/// array of names, a string or a boolean (all the protocol needs; nesting is an error).
struct Value {
  enum Kind { number, array, names, string, boolean } kind = number;
  double x = 0;
  std::vector<double> xs;
  std::vector<std::string> words;
  std::string text;
  bool flag = false;
};

class RequestParser {
 public:
  explicit RequestParser(const std::string& line) : s_(line) {}

  std::map<std::string, Value> object() {
    std::map<std::string, Value> members;
    expect('{');
    if (peek() == '}') {
      ++at_;
    } else {
      for (;;) {
        const std::string key = string();
        expect(':');
        if (!members.emplace(key, value()).second) fail("key \"" + key + "\" given twice");
        if (peek() == ',') {
          ++at_;
          continue;
        }
        expect('}');
        break;
      }
    }
    if (peek() != '\0') fail("text after the object");
    return members;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("malformed request at column " + std::to_string(at_ + 1) + ": " + what);
  }
  char peek() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
    return at_ < s_.size() ? s_[at_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("'") + c + "' expected");
    ++at_;
  }
  std::string string() {
    expect('"');
    std::string text;
    while (at_ < s_.size() && s_[at_] != '"') {
      if (s_[at_] == '\\') fail("escapes are not supported");
      text += s_[at_++];
    }
    if (at_ >= s_.size()) fail("unterminated string");
    ++at_;
    return text;
  }
  double number() {
    const size_t start = at_;
    while (at_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[at_])) || s_[at_] == '-' ||
                               s_[at_] == '+' || s_[at_] == '.' || s_[at_] == 'e' || s_[at_] == 'E'))
      ++at_;
    double x = 0;
    if (!parse_number(std::string_view(s_).substr(start, at_ - start), &x)) {
      at_ = start;
      fail("number expected");
    }
    return x;
  }
  bool word(const char* w) {
    const size_t n = std::char_traits<char>::length(w);
    if (s_.compare(at_, n, w) != 0) return false;
    at_ += n;
    return true;
  }
  Value value() {
    Value v;
    const char c = peek();
    if (c == '"') {
      v.kind = Value::string;
      v.text = string();
    } else if (c == '[') {
      ++at_;
      v.kind = Value::array;
      if (peek() == ']') {
        ++at_;
        return v;
      }
      if (peek() == '"') v.kind = Value::names;
      for (;;) {
        peek();
        if (v.kind == Value::names)
          v.words.push_back(string());
        else
          v.xs.push_back(number());
        if (peek() == ',') {
          ++at_;
          continue;
        }
        expect(']');
        break;
      }
    } else if (word("true")) {
      v.kind = Value::boolean;
      v.flag = true;
    } else if (word("false")) {
      v.kind = Value::boolean;
    } else {
      v.x = number();
    }
    return v;
  }

  const std::string& s_;
  size_t at_ = 0;
};

enum class Selection { all, udot, energy };

struct Request {
  double t = 0;
  std::vector<double> q, u, tau, p;
  bool has_p = false;
  Selection selection = Selection::all;
  bool hessian = false;
  /// The Jacobian kernels, with the fixed vectors of the products they differentiate.
  bool jacobians = false;
  std::vector<double> jacobian_a, jacobian_lambda;
  /// The inverse_dynamics kernel at these accelerations (if given).
  bool inverse_dynamics = false;
  std::vector<double> inverse_dynamics_udot;
  /// The kernels of --controller.
  bool controller = false;
  /// Kernels asked for by name (kernels.def), and their input arrays other
  /// than q, u and tau ("input_<argument>").
  std::vector<Kernel> kernels;
  std::map<std::string, std::vector<double>> inputs;
};

/// A kernel "kernels" can name: one the table binds, taking only arrays and scalars.
bool callable(const KernelSpec& spec) {
  if (spec.binding == KernelBinding::unbound || spec.params == ParamsAccess::write) return false;
  for (std::size_t i = 0; i < spec.argument_count; ++i)
    if (spec.arguments[i].role == ArgumentRole::text || spec.arguments[i].role == ArgumentRole::index)
      return false;
  return true;
}

Kernel callable_kernel(const std::string& name) {
  std::string known;
  for (const KernelSpec& spec : kernel_specs) {
    if (!callable(spec)) continue;
    if (name == spec.name) return spec.kernel;
    known += (known.empty() ? "" : ", ") + std::string(spec.name);
  }
  throw std::invalid_argument("\"kernels\": no kernel \"" + name + "\" to call; known: " + known);
}

/// "kernels": [names] and the "input_<argument>" arrays they take besides q, u and tau.
void parse_kernels(const std::map<std::string, Value>& m, Request& r) {
  if (const auto k = m.find("kernels"); k != m.end()) {
    if (k->second.kind != Value::names && !(k->second.kind == Value::array && k->second.xs.empty()))
      throw std::invalid_argument("\"kernels\" must be an array of kernel names");
    for (const std::string& name : k->second.words) {
      const Kernel kernel = callable_kernel(name);
      if (std::find(r.kernels.begin(), r.kernels.end(), kernel) != r.kernels.end())
        throw std::invalid_argument("\"kernels\": \"" + name + "\" named twice");
      r.kernels.push_back(kernel);
    }
  }
  for (const auto& [key, value] : m)
    if (key.rfind("input_", 0) == 0) {
      if (value.kind != Value::array)
        throw std::invalid_argument("\"" + key + "\" must be an array of numbers");
      r.inputs[key.substr(6)] = value.xs;
    }
}

std::vector<double> numbers(const std::map<std::string, Value>& m, const char* key, int n, bool required) {
  const auto found = m.find(key);
  if (found == m.end()) {
    if (required) throw std::invalid_argument(std::string("missing \"") + key + "\"");
    return std::vector<double>(static_cast<size_t>(n), 0.0);
  }
  if (found->second.kind != Value::array)
    throw std::invalid_argument(std::string("\"") + key + "\" must be an array of numbers");
  if (static_cast<int>(found->second.xs.size()) != n)
    throw std::invalid_argument(std::string("\"") + key + "\" needs " + std::to_string(n) +
                                " value(s), got " + std::to_string(found->second.xs.size()));
  return found->second.xs;
}

/// "jacobians": true asks for the Jacobian kernels, at the fixed vectors
/// "jacobian_a" (nu, required) and "jacobian_lambda" (nc, required with loops).
void parse_jacobians(const std::map<std::string, Value>& m, const ModelInfo& info, Request& r) {
  if (const auto j = m.find("jacobians"); j != m.end()) {
    if (j->second.kind != Value::boolean) throw std::invalid_argument("\"jacobians\" must be true or false");
    r.jacobians = j->second.flag;
  }
  r.jacobian_a = numbers(m, "jacobian_a", info.nu, r.jacobians);
  r.jacobian_lambda = numbers(m, "jacobian_lambda", info.nc, r.jacobians && info.nc > 0);
}

Request parse_request(const std::string& line, const ModelInfo& info) {
  const std::map<std::string, Value> m = RequestParser(line).object();
  for (const auto& member : m) {
    const std::string& key = member.first;
    static const char* const known[] = {"t",
                                        "q",
                                        "u",
                                        "tau",
                                        "p",
                                        "eval",
                                        "kinetic_energy_hessian",
                                        "jacobians",
                                        "jacobian_a",
                                        "jacobian_lambda",
                                        "inverse_dynamics_udot",
                                        "controller",
                                        "kernels"};
    if (std::none_of(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) &&
        key.rfind("input_", 0) != 0)
      throw std::invalid_argument(
          "unknown key \"" + key +
          "\"; known: t, q, u, tau, p, eval, kinetic_energy_hessian, jacobians, jacobian_a, jacobian_lambda, "
          "inverse_dynamics_udot, controller, kernels, input_<argument>");
  }
  Request r;
  if (const auto t = m.find("t"); t != m.end()) {
    if (t->second.kind != Value::number) throw std::invalid_argument("\"t\" must be a number");
    r.t = t->second.x;
  }
  r.q = numbers(m, "q", info.nq, true);
  r.u = numbers(m, "u", info.nu, true);
  r.tau = numbers(m, "tau", info.ntau, false);
  r.has_p = m.count("p") > 0;
  r.p = numbers(m, "p", info.np, false);
  if (const auto e = m.find("eval"); e != m.end()) {
    const std::string& s = e->second.text;
    if (e->second.kind != Value::string || (s != "all" && s != "udot" && s != "energy"))
      throw std::invalid_argument("\"eval\" must be \"all\", \"udot\" or \"energy\"");
    r.selection = s == "udot" ? Selection::udot : s == "energy" ? Selection::energy : Selection::all;
  }
  if (const auto h = m.find("kinetic_energy_hessian"); h != m.end()) {
    if (h->second.kind != Value::boolean)
      throw std::invalid_argument("\"kinetic_energy_hessian\" must be true or false");
    r.hessian = h->second.flag;
  }
  parse_jacobians(m, info, r);
  r.inverse_dynamics = m.count("inverse_dynamics_udot") > 0;
  r.inverse_dynamics_udot = numbers(m, "inverse_dynamics_udot", info.nu, false);
  if (const auto c = m.find("controller"); c != m.end()) {
    if (c->second.kind != Value::boolean) throw std::invalid_argument("\"controller\" must be true or false");
    r.controller = c->second.flag;
  }
  parse_kernels(m, r);
  return r;
}

// ---------------------------------------------------------------- response

std::string numbers_json(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + json_number(v[i]);
  return s + "]";
}

std::string matrix_json(const std::vector<double>& m, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + numbers_json(m.data() + static_cast<size_t>(i) * n, n);
  return s + "]";
}

/// H_rs = T(e_r + e_s) - T(e_r) - T(e_s) + T(0): exact for a quadratic T.
std::vector<double> kinetic_hessian(const Model& model, const double* q, int n) {
  std::vector<double> u(static_cast<size_t>(std::max(n, 1)), 0.0), single(n), h(static_cast<size_t>(n) * n);
  const double t0 = model.kinetic_energy(q, u.data());
  for (int r = 0; r < n; ++r) {
    u[r] = 1.0;
    single[r] = model.kinetic_energy(q, u.data());
    u[r] = 0.0;
  }
  for (int r = 0; r < n; ++r) {
    for (int s = r; s < n; ++s) {
      u[r] += 1.0;
      u[s] += 1.0;
      const double both = model.kinetic_energy(q, u.data());
      u[r] = u[s] = 0.0;
      h[r * n + s] = h[s * n + r] = both - single[r] - single[s] + t0;
    }
  }
  return h;
}

/// The Jacobian kernels' matrices (nu x nq, and nq = nu), or an error if the
/// model was generated without them.
template <class Field>
void add_jacobians(const Model& model, const Request& r, const std::vector<double>& q,
                   const std::vector<double>& u, const std::vector<double>& tau, const Field& field) {
  if (!model.has_jacobians())
    throw std::invalid_argument("the model has no Jacobian kernels; generate it with --jacobians");
  const int n = model.info().nu;
  const size_t m = static_cast<size_t>(std::max(n, 1));
  std::vector<double> dfdq(m * m), dfdu(m * m), dMa(m * m), a = r.jacobian_a, lambda = r.jacobian_lambda;
  a.resize(m);
  lambda.resize(std::max<size_t>(lambda.size(), 1));
  model.forcing_jacobian(r.t, q.data(), u.data(), tau.data(), dfdq.data(), dfdu.data());
  model.mass_matrix_product_jacobian(q.data(), a.data(), dMa.data());
  field("forcing_jacobian_q", matrix_json(dfdq, n));
  field("forcing_jacobian_u", matrix_json(dfdu, n));
  field("mass_matrix_product_jacobian", matrix_json(dMa, n));
  if (model.info().nc > 0) {
    std::vector<double> dCl(m * m);
    model.constraint_force_jacobian(q.data(), lambda.data(), dCl.data());
    field("constraint_force_jacobian", matrix_json(dCl, n));
  }
}

/// A rows x cols row-major matrix as an array of rows.
std::string rows_json(const std::vector<double>& m, int rows, int cols) {
  std::string s = "[";
  for (int i = 0; i < rows; ++i)
    s += (i ? "," : "") + numbers_json(m.data() + static_cast<size_t>(i) * cols, cols);
  return s + "]";
}

/// The kernels of --controller, or an error if the model was generated without them.
template <class Field>
void add_controller(const Model& model, const Request& r, const std::vector<double>& q,
                    const std::vector<double>& u, const std::vector<double>& tau, const Field& field) {
  if (!model.has_controller())
    throw std::invalid_argument("the model has no controller kernels; generate it with --controller");
  const ModelInfo& info = model.info();
  const int n = info.nu;
  const size_t m = static_cast<size_t>(std::max(n, 1)), ny = static_cast<size_t>(std::max(info.ny, 1));
  std::vector<double> C(m * m), J(ny * m), jdot(ny), A(4 * m * m), B(2 * m * std::max(info.ntau, 1));
  model.coriolis_matrix(q.data(), u.data(), C.data());
  model.output_jacobian(r.t, q.data(), J.data());
  model.output_jacobian_rate(r.t, q.data(), u.data(), jdot.data());
  const int status = model.linearize(r.t, q.data(), u.data(), tau.data(), A.data(), B.data());
  field("coriolis_matrix", rows_json(C, n, n));
  field("output_jacobian", rows_json(J, info.ny, n));
  field("output_jacobian_rate", numbers_json(jdot.data(), info.ny));
  field("linearize_A", rows_json(A, 2 * n, 2 * n));
  field("linearize_B", rows_json(B, 2 * n, info.ntau));
  field("linearize_status", std::to_string(status));
}

/// The values of a kernel's input `argument` of `n` numbers: the line's
/// state for q, u and tau, else its "input_<argument>".
std::vector<double> kernel_input(const Request& r, const KernelSpec& spec, const char* argument, int n) {
  const std::string name = argument;
  const std::vector<double>* given = name == "q"     ? &r.q
                                     : name == "u"   ? &r.u
                                     : name == "tau" ? &r.tau
                                                     : nullptr;
  if (!given) {
    const auto found = r.inputs.find(name);
    if (found == r.inputs.end())
      throw std::invalid_argument(std::string("\"kernels\": ") + spec.name + " needs \"input_" + name + "\"");
    given = &found->second;
  }
  if (static_cast<int>(given->size()) != n)
    throw std::invalid_argument(std::string("\"kernels\": ") + spec.name + "'s " + name + " needs " +
                                std::to_string(n) + " value(s), got " + std::to_string(given->size()));
  std::vector<double> values = *given;
  values.resize(static_cast<size_t>(std::max(n, 1)));
  return values;
}

/// Which models have a kernel of this presence (kernels.def), as a fix.
const char* presence_hint(KernelPresence presence) {
  switch (presence) {
    case KernelPresence::always:
      break;
    case KernelPresence::with_loops:
      return "only models with closed loops have it";
    case KernelPresence::with_jacobians:
      return "generate the model with --jacobians";
    case KernelPresence::with_loops_and_jacobians:
      return "only models with closed loops generated with --jacobians have it";
    case KernelPresence::with_controller:
      return "generate the model with --controller";
  }
  return "regenerate the model with this kanegen";
}

/// One kernel called through its spec: {"<output>": values, ..., "returns": x}
/// (a matrix as its rows; "returns" unless the kernel returns nothing).
std::string call_kernel(const Model& model, const Request& r, Kernel kernel) {
  const KernelSpec& spec = kernel_spec(kernel);
  const KernelEntry& entry = kernel_entries[static_cast<std::size_t>(kernel)];
  if (!entry.present(model.table()))
    throw std::invalid_argument(std::string("\"kernels\": the model has no ") + spec.name + " kernel; " +
                                presence_hint(spec.presence));
  std::vector<std::vector<double>> arrays(spec.argument_count);
  std::vector<std::pair<int, int>> shapes(spec.argument_count);
  std::vector<double> scalars(spec.argument_count);
  std::array<void*, 1 + 8> slots{};  // Params, and at most 8 arguments (kernel_spec.hpp)
  const std::size_t first = spec.params == ParamsAccess::none ? 0 : 1;
  if (first) slots[0] = const_cast<void*>(model.parameter_storage());
  for (std::size_t i = 0; i < spec.argument_count; ++i) {
    const KernelArgumentSpec& a = spec.arguments[i];
    const int n = kernel_argument_length(model.table(), a.size, &shapes[i]);
    if (a.role == ArgumentRole::scalar) {
      scalars[i] = std::string(a.name) == "t" ? r.t : kernel_input(r, spec, a.name, 1)[0];
      slots[first + i] = &scalars[i];
      continue;
    }
    arrays[i] = a.role == ArgumentRole::in ? kernel_input(r, spec, a.name, n)
                                           : std::vector<double>(static_cast<size_t>(std::max(n, 1)));
    slots[first + i] = arrays[i].data();
  }
  const double result = entry.call(model.table(), slots.data());
  std::string out = "{";
  for (std::size_t i = 0; i < spec.argument_count; ++i) {
    if (spec.arguments[i].role != ArgumentRole::out) continue;
    const auto [rows, columns] = shapes[i];
    out += (out.size() > 1 ? ",\"" : "\"") + std::string(spec.arguments[i].name) +
           "\":" + (columns > 0 ? rows_json(arrays[i], rows, columns) : numbers_json(arrays[i].data(), rows));
  }
  if (std::string(spec.returns) != "void")
    out += (out.size() > 1 ? "," : "") + std::string("\"returns\":") + json_number(result);
  return out + "}";
}

/// "kernels": each kernel named, by its spec, as {"<kernel>": call_kernel(...), ...}.
std::string kernels_json(const Model& model, const Request& r) {
  std::string out = "{";
  for (Kernel kernel : r.kernels)
    out += (out.size() > 1 ? ",\"" : "\"") + std::string(kernel_spec(kernel).name) +
           "\":" + call_kernel(model, r, kernel);
  return out + "}";
}

std::string respond(Model& model, const Request& r, const std::vector<double>& defaults) {
  const ModelInfo& info = model.info();
  for (int k = 0; k < info.np; ++k)
    model.set_parameter(info.parameter_names[k], r.has_p ? r.p[k] : defaults[k]);
  const int n = info.nu;
  const size_t m = static_cast<size_t>(std::max(n, 1));
  std::vector<double> q = r.q, u = r.u, tau = r.tau;
  q.resize(std::max<size_t>(q.size(), 1));
  u.resize(m);
  tau.resize(std::max<size_t>(tau.size(), 1));
  std::string out = "{";
  const auto field = [&](const char* key, const std::string& value) {
    out += (out.size() > 1 ? ",\"" : "\"") + std::string(key) + "\":" + value;
  };
  if (r.selection != Selection::energy) {
    std::vector<double> udot(m);
    const int pivot = model.forward_dynamics(r.t, q.data(), u.data(), tau.data(), udot.data());
    field("udot", pivot == 0 ? numbers_json(udot.data(), n) : "null");
    field("pivot", std::to_string(pivot));
  }
  if (r.selection == Selection::all) {
    std::vector<double> M(m * m), f(m), y(static_cast<size_t>(std::max(info.ny, 1)));
    model.mass_matrix(q.data(), M.data());
    model.forcing(r.t, q.data(), u.data(), tau.data(), f.data());
    model.outputs(r.t, q.data(), u.data(), y.data());
    field("mass_matrix", matrix_json(M, n));
    field("forcing", numbers_json(f.data(), n));
    field("outputs", numbers_json(y.data(), info.ny));
    if (model.has_inverse_dynamics()) {
      std::vector<double> g(m);
      model.gravity(q.data(), g.data());
      field("gravity", numbers_json(g.data(), n));
    }
    if (model.has_nonconservative_power())
      field("nonconservative_power",
            json_number(model.nonconservative_power(r.t, q.data(), u.data(), tau.data())));
    if (info.nc > 0) {
      // The loop kernels, and lambda of the same solve as udot.
      const size_t nc = static_cast<size_t>(info.nc);
      std::vector<double> phi(nc), C(nc * m), gamma(nc), udot(m), lambda(nc);
      model.constraints(q.data(), phi.data());
      model.constraint_jacobian(q.data(), C.data());
      model.constraint_bias(q.data(), u.data(), gamma.data());
      const bool solved =
          model.constrained_dynamics(r.t, q.data(), u.data(), tau.data(), udot.data(), lambda.data()) == 0;
      std::string rows = "[";
      for (int i = 0; i < info.nc; ++i)
        rows += (i ? "," : "") + numbers_json(C.data() + static_cast<size_t>(i) * n, n);
      field("constraints", numbers_json(phi.data(), info.nc));
      field("constraint_jacobian", rows + "]");
      field("constraint_bias", numbers_json(gamma.data(), info.nc));
      field("lambda", solved ? numbers_json(lambda.data(), info.nc) : "null");
    }
  }
  if (r.selection != Selection::udot) {
    field("kinetic_energy", json_number(model.kinetic_energy(q.data(), u.data())));
    field("potential_energy", json_number(model.potential_energy(q.data())));
  }
  if (r.hessian) field("kinetic_energy_hessian", matrix_json(kinetic_hessian(model, q.data(), n), n));
  if (r.jacobians) add_jacobians(model, r, q, u, tau, field);
  if (r.inverse_dynamics) {
    if (!model.has_inverse_dynamics())
      throw std::invalid_argument(
          "the model has no inverse_dynamics kernel; regenerate it with this kanegen");
    std::vector<double> udot = r.inverse_dynamics_udot, tau_id(m);
    udot.resize(m);
    model.inverse_dynamics(r.t, q.data(), u.data(), udot.data(), tau_id.data());
    field("inverse_dynamics", numbers_json(tau_id.data(), n));
  }
  if (r.controller) add_controller(model, r, q, u, tau, field);
  if (!r.kernels.empty()) field("kernels", kernels_json(model, r));
  return out + "}\n";
}

/// One line without its newline; false at end of input.
bool read_line(std::FILE* in, std::string& line) {
  line.clear();
  char buf[4096];
  while (std::fgets(buf, sizeof buf, in)) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      return true;
    }
  }
  return !line.empty();
}

}  // namespace

int run_batch(Model& model, std::FILE* in, std::FILE* out) {
  const ModelInfo& info = model.info();
  std::vector<double> defaults(static_cast<size_t>(std::max(info.np, 1)));
  for (int k = 0; k < info.np; ++k) defaults[k] = model.parameter(k);
  int code = 0;
  std::string line;
  while (read_line(in, line)) {
    if (std::all_of(line.begin(), line.end(),
                    [](char c) { return std::isspace(static_cast<unsigned char>(c)); }))
      continue;
    std::string reply;
    try {
      reply = respond(model, parse_request(line, info), defaults);
    } catch (const std::exception& e) {
      reply = "{\"error\":" + json_string(e.what()) + "}\n";
      code = 1;
    }
    std::fputs(reply.c_str(), out);
    std::fflush(out);
  }
  return code;
}

}  // namespace kanegen::runtime
