// SPDX-License-Identifier: MIT
#include "batch.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
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
/// array of names, or a string or boolean (read so that a key the protocol
/// does not know, such as an old "eval", is named as unknown; nesting is an error).
struct Value {
  enum Kind { number, array, names, other } kind = number;
  double x = 0;
  std::vector<double> xs;
  std::vector<std::string> words;
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
      v.kind = Value::other;
      string();
    } else if (word("true") || word("false")) {
      v.kind = Value::other;
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
    } else {
      v.x = number();
    }
    return v;
  }

  const std::string& s_;
  size_t at_ = 0;
};

struct Request {
  double t = 0;
  std::vector<double> q, u, tau, p;
  bool has_p = false;
  /// The kernels asked for by name (kernels.def), and their input arrays
  /// other than q, u and tau ("input_<argument>").
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
  const auto k = m.find("kernels");
  if (k == m.end())
    throw std::invalid_argument(
        "missing \"kernels\": name the kernels to call, e.g. \"kernels\": [\"mass_matrix\"]");
  if (k->second.kind != Value::names)
    throw std::invalid_argument("\"kernels\" must be a non-empty array of kernel names");
  for (const std::string& name : k->second.words) {
    const Kernel kernel = callable_kernel(name);
    if (std::find(r.kernels.begin(), r.kernels.end(), kernel) != r.kernels.end())
      throw std::invalid_argument("\"kernels\": \"" + name + "\" named twice");
    r.kernels.push_back(kernel);
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

Request parse_request(const std::string& line, const ModelInfo& info) {
  const std::map<std::string, Value> m = RequestParser(line).object();
  for (const auto& member : m) {
    const std::string& key = member.first;
    static const char* const known[] = {"t", "q", "u", "tau", "p", "kernels"};
    if (std::none_of(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) &&
        key.rfind("input_", 0) != 0)
      throw std::invalid_argument("unknown key \"" + key +
                                  "\"; known: t, q, u, tau, p, kernels, input_<argument>");
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
  parse_kernels(m, r);
  return r;
}

// ---------------------------------------------------------------- response

std::string numbers_json(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + json_number(v[i]);
  return s + "]";
}

/// A rows x cols row-major matrix as an array of rows.
std::string rows_json(const std::vector<double>& m, int rows, int cols) {
  std::string s = "[";
  for (int i = 0; i < rows; ++i)
    s += (i ? "," : "") + numbers_json(m.data() + static_cast<size_t>(i) * cols, cols);
  return s + "]";
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
    // A matrix (a size with a factor, "NU*NU") as its rows, even of no columns ("2*NU*NTAU", NTAU = 0).
    const bool matrix = std::strchr(spec.arguments[i].size, '*') != nullptr;
    const auto [rows, columns] = shapes[i];
    out += (out.size() > 1 ? ",\"" : "\"") + std::string(spec.arguments[i].name) +
           "\":" + (matrix ? rows_json(arrays[i], rows, columns) : numbers_json(arrays[i].data(), rows));
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
  return "{\"kernels\":" + kernels_json(model, r) + "}\n";
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
