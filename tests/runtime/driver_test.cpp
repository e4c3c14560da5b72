// SPDX-License-Identifier: GPL-2.0-or-later
// The runner, in-process, on a hand-written 1-DOF pendulum that satisfies
// system.hpp: simulate (CSV), eval (JSON), info and the error paths.
#include "kanegen/runtime/driver.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/model.hpp"
#include "kanegen/runtime/text.hpp"

namespace mock {

// Pendulum of mass m on a massless rod of length l: M = m l^2,
// f = -m g l sin(theta) + tau. Two test hooks: the mass matrix "loses rank"
// beyond |theta| > q_limit, and udot is NaN for t > nan_after.
struct Params {
  double m = 2.0;
  double l = 0.5;
  double g = 9.81;
  double q_limit = 1e9;
  double nan_after = 1e9;
};

struct System {
  using Params = mock::Params;
  static constexpr int nq = 1, nu = 1, ntau = 1, ny = 2, np = 5;
  static constexpr const char* name = "pendulum";
  static const char* const* coordinate_names() {
    static const char* const names[] = {"theta"};
    return names;
  }
  static const char* const* speed_names() {
    static const char* const names[] = {"omega"};
    return names;
  }
  static const char* const* input_names() {
    static const char* const names[] = {"torque"};
    return names;
  }
  static const char* const* output_names() {
    static const char* const names[] = {"tip_x", "tip_y"};
    return names;
  }
  static const char* const* parameter_names() {
    static const char* const names[] = {"m", "l", "g", "q_limit", "nan_after"};
    return names;
  }
  static const char* const* coordinate_joints() {
    static const char* const names[] = {"theta"};
    return names;
  }
  static const int* moved_bodies_first() {
    static const int first[] = {0, 1};
    return first;
  }
  static const char* const* moved_bodies() {
    static const char* const names[] = {"bob"};
    return names;
  }
  static const double* q0() {
    static const double v[] = {0.3};
    return v;
  }
  static const double* u0() {
    static const double v[] = {0.0};
    return v;
  }
  static double* field(Params& p, int i) {
    double* fields[] = {&p.m, &p.l, &p.g, &p.q_limit, &p.nan_after};
    return fields[i];
  }
  static bool set_parameter(Params& p, const char* name, double value) {
    for (int i = 0; i < np; ++i) {
      if (std::strcmp(name, parameter_names()[i]) == 0) {
        *field(p, i) = value;
        return true;
      }
    }
    return false;
  }
  static double get_parameter(const Params& p, int i) { return *field(const_cast<Params&>(p), i); }
  static void mass_matrix(const Params& p, const double*, double* M) { M[0] = p.m * p.l * p.l; }
  static void forcing(const Params& p, double, const double* q, const double*, const double* tau, double* f) {
    f[0] = -p.m * p.g * p.l * std::sin(q[0]) + tau[0];
  }
  static int forward_dynamics(const Params& p, double t, const double* q, const double* u, const double* tau,
                              double* udot) {
    double M, f;
    mass_matrix(p, q, &M);
    if (!(M > 0) || std::abs(q[0]) > p.q_limit) return 1;
    forcing(p, t, q, u, tau, &f);
    udot[0] = t > p.nan_after ? std::nan("") : f / M;
    return 0;
  }
  static void coordinate_rates(const double*, const double* u, double* qdot) { qdot[0] = u[0]; }
  static double kinetic_energy(const Params& p, const double*, const double* u) {
    return 0.5 * p.m * p.l * p.l * u[0] * u[0];
  }
  static double potential_energy(const Params& p, const double* q) {
    return -p.m * p.g * p.l * std::cos(q[0]);
  }
  static void outputs(const Params& p, double, const double* q, const double*, double* y) {
    y[0] = p.l * std::sin(q[0]);
    y[1] = -p.l * std::cos(q[0]);
  }
  static void initial_state(const Params&, double* q, double* u) {
    q[0] = q0()[0];
    u[0] = u0()[0];
  }
  // As a generated header writes it (templates/model.hpp.in).
  template <class Table>
  static Table kernel_table() {
    Table t{};
    t.name = name;
    t.nq = nq, t.nu = nu, t.ntau = ntau, t.ny = ny, t.np = np;
    t.coordinate_names = coordinate_names(), t.speed_names = speed_names(), t.input_names = input_names();
    t.output_names = output_names(), t.parameter_names = parameter_names(), t.q0 = q0(), t.u0 = u0();
    t.coordinate_joints = coordinate_joints(), t.moved_bodies_first = moved_bodies_first();
    t.moved_bodies = moved_bodies();
    t.parameters_size = sizeof(Params);
    t.default_parameters = [](void* p) { new (p) Params(); };
    t.set_parameter = [](void* p, const char* n, double v) {
      return set_parameter(*static_cast<Params*>(p), n, v);
    };
    t.get_parameter = [](const void* p, int i) { return get_parameter(*static_cast<const Params*>(p), i); };
    t.initial_state = [](const void* p, double* q, double* u) {
      initial_state(*static_cast<const Params*>(p), q, u);
    };
    t.mass_matrix = [](const void* p, const double* q, double* M) {
      mass_matrix(*static_cast<const Params*>(p), q, M);
    };
    t.forcing = [](const void* p, double t, const double* q, const double* u, const double* tau, double* f) {
      forcing(*static_cast<const Params*>(p), t, q, u, tau, f);
    };
    t.forward_dynamics = [](const void* p, double t, const double* q, const double* u, const double* tau,
                            double* udot) {
      return forward_dynamics(*static_cast<const Params*>(p), t, q, u, tau, udot);
    };
    t.coordinate_rates = coordinate_rates;
    t.kinetic_energy = [](const void* p, const double* q, const double* u) {
      return kinetic_energy(*static_cast<const Params*>(p), q, u);
    };
    t.potential_energy = [](const void* p, const double* q) {
      return potential_energy(*static_cast<const Params*>(p), q);
    };
    t.outputs = [](const void* p, double t, const double* q, const double* u, double* y) {
      outputs(*static_cast<const Params*>(p), t, q, u, y);
    };
    return t;
  }
};

}  // namespace mock

namespace {

using kanegen::runtime::run_model;
using nlohmann::json;

// The registry's names (methods.hpp) as the unknown-integrator message lists
// them: a new method changes the message, not this test.
std::string known_integrators() {
  std::string known;
  for (const std::string& name : kanegen::runtime::method_names())
    known += (known.empty() ? "" : ", ") + name;
  return known;
}

std::string read_all(std::FILE* f) {
  std::string s;
  std::rewind(f);
  char buf[4096];
  for (size_t got; (got = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, got);
  std::fclose(f);
  return s;
}

struct Outcome {
  int code;
  std::string out, err;
};

Outcome run(std::vector<std::string> args) {
  args.insert(args.begin(), "/some/dir/pendulum_runner");
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  REQUIRE(out);
  REQUIRE(err);
  const int code = run_model<mock::System>(args, out, err);
  return {code, read_all(out), read_all(err)};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A failing command: non-zero code, nothing on stdout, one "error:" line on stderr.
void check_one_line_error(const Outcome& o) {
  INFO(o.err);
  CHECK(o.code != 0);
  CHECK(o.err.rfind("error: ", 0) == 0);
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<double> numbers(const std::string& line) {
  std::vector<double> v;
  REQUIRE(kanegen::runtime::parse_number_list(line, &v));
  return v;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("kanegen_runtime_" + name)).string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("simulate: header, rows and the analytic free rotation", "[driver]") {
  // With g = 0 the pendulum turns uniformly: theta = theta0 + omega0 t.
  const std::string path = temp_path("free.csv");
  for (const char* integrator : {"dopri5", "rk4"}) {
    const Outcome o = run({"simulate", "--t-end", "1", "--dt", "0.1", "--integrator", integrator, "--set",
                           "g=0", "--q0", "theta=0.1", "--u0", "omega=2", "-o", path});
    INFO(o.err);
    REQUIRE(o.code == 0);
    CHECK(o.out.empty());
    CHECK(o.err.empty());
    const std::vector<std::string> rows = lines(slurp(path));
    REQUIRE(rows.size() == 12);
    CHECK(rows[0] == "t,theta,omega,tip_x,tip_y");
    for (size_t k = 1; k < rows.size(); ++k) {
      const std::vector<double> v = numbers(rows[k]);
      REQUIRE(v.size() == 5);
      CHECK(v[0] == Approx(0.1 * (k - 1)).margin(1e-15));
      CHECK(v[1] == Approx(0.1 + 2 * v[0]).margin(1e-12));
      CHECK(v[2] == Approx(2.0).margin(1e-12));
      CHECK(v[3] == Approx(0.5 * std::sin(v[1])).margin(1e-12));
      CHECK(v[4] == Approx(-0.5 * std::cos(v[1])).margin(1e-12));
    }
    CHECK(numbers(rows.back())[0] == 1.0);
  }
  std::filesystem::remove(path);
}

TEST_CASE("simulate: energy is conserved at tight tolerance, CSV to stdout", "[driver]") {
  const Outcome o = run({"simulate", "--t-end=5", "--dt=0.05", "--rtol", "1e-11", "--atol", "1e-11", "--q0",
                         "theta=2.5", "--stats"});
  INFO(o.err);
  REQUIRE(o.code == 0);
  CHECK(o.err.rfind("stats: integrator=dopri5 accepted=", 0) == 0);
  const std::vector<std::string> rows = lines(o.out);
  REQUIRE(rows.size() == 102);
  const auto energy = [](const std::vector<double>& v) {
    return 0.5 * 2.0 * 0.25 * v[2] * v[2] - 2.0 * 9.81 * 0.5 * std::cos(v[1]);
  };
  const double e0 = energy(numbers(rows[1]));
  CHECK(e0 == Approx(-9.81 * std::cos(2.5)));
  double drift = 0;
  for (size_t k = 1; k < rows.size(); ++k) drift = std::max(drift, std::abs(energy(numbers(rows[k])) - e0));
  INFO("energy drift " << drift);
  CHECK(drift < 1e-8);
}

TEST_CASE("simulate: singular mass matrix stops the run, keeps the rows", "[driver]") {
  const std::string path = temp_path("singular.csv");
  // theta = t; the "mass matrix" fails beyond theta = 0.53, first met by the
  // RK4 stage at t = 0.55 in the step from 0.5.
  const Outcome o = run({"simulate", "--t-end", "1", "--dt", "0.1", "--integrator", "rk4", "--set", "g=0",
                         "--set", "q_limit=0.53", "--q0", "theta=0", "--u0", "omega=1", "-o", path});
  check_one_line_error(o);
  CHECK(o.code == 1);
  CHECK(contains(o.err,
                 "mass matrix is not positive definite at coordinate 'theta' (pivot 1 of its LDL^T "
                 "factorisation is not positive): joint 'theta' moves body 'bob', which has a zero or "
                 "negative mass or an invalid inertia at these parameters (or no mass moves along this "
                 "coordinate); check its mass and inertia and the --set values"));
  CHECK(contains(o.err, "at t=0.55, state [theta=0.55, omega=1]"));
  const std::vector<std::string> rows = lines(slurp(path));
  REQUIRE(rows.size() == 7);  // header and t = 0 .. 0.5
  CHECK(numbers(rows.back())[0] == 0.5);

  SECTION("zero mass: fails at the first evaluation, after the t = 0 row") {
    const Outcome z = run({"simulate", "--t-end", "1", "--set", "m=0", "-o", path});
    check_one_line_error(z);
    CHECK(contains(z.err, "at t=0,"));
    CHECK(lines(slurp(path)).size() == 2);
  }
  SECTION("dopri5: rows up to the last accepted step") {
    const Outcome d = run({"simulate", "--t-end", "1", "--dt", "0.1", "--set", "g=0", "--set", "q_limit=0.53",
                           "--q0", "theta=0", "--u0", "omega=1", "-o", path});
    check_one_line_error(d);
    const std::vector<std::string> r = lines(slurp(path));
    REQUIRE(r.size() >= 2);
    CHECK(numbers(r.back())[0] < 0.53);
  }
  std::filesystem::remove(path);
}

TEST_CASE("simulate: NaN accelerations stop the run with the time", "[driver]") {
  const Outcome o =
      run({"simulate", "--t-end", "1", "--integrator", "rk4", "--dt", "0.1", "--set", "nan_after=0.32"});
  check_one_line_error(o);
  CHECK(contains(o.err, "d(omega)/dt = nan at t=0.35"));
  CHECK(lines(o.out).size() == 5);  // header and t = 0 .. 0.3, the step from 0.3 fails at its midpoint
}

TEST_CASE("simulate: max steps is a clean failure", "[driver]") {
  const Outcome o = run({"simulate", "--t-end", "100", "--max-steps", "10"});
  check_one_line_error(o);
  CHECK(contains(o.err, "max_steps = 10"));
}

TEST_CASE("eval prints the equations at one state as JSON", "[driver]") {
  const Outcome o = run({"eval", "--q", "0.3", "--u", "-0.7", "--set", "l=2"});
  INFO(o.err);
  REQUIRE(o.code == 0);
  const json j = json::parse(o.out);
  CHECK(j.size() == 6);
  CHECK(j["coordinates"] == json::array({"theta"}));
  const double m = 2.0, l = 2.0, g = 9.81, q = 0.3, u = -0.7;
  CHECK(j["mass_matrix"] == json::array({json::array({m * l * l})}));
  // Round-trip printing: the same doubles as computed here.
  CHECK(j["forcing"][0].get<double>() == -m * g * l * std::sin(q));
  CHECK(j["udot"][0].get<double>() == -m * g * l * std::sin(q) / (m * l * l));
  CHECK(j["kinetic_energy"].get<double>() == 0.5 * m * l * l * u * u);
  CHECK(j["potential_energy"].get<double>() == -m * g * l * std::cos(q));
  CHECK(o.out.rfind("{\"coordinates\": [\"theta\"], \"mass_matrix\": [[8]], \"forcing\": [", 0) == 0);
}

TEST_CASE("eval defaults to q0, u0 and reports singular mass matrices", "[driver]") {
  const Outcome o = run({"eval"});
  REQUIRE(o.code == 0);
  CHECK(json::parse(o.out)["kinetic_energy"] == 0.0);
  const Outcome bad = run({"eval", "--set", "m=0"});
  check_one_line_error(bad);
  CHECK(contains(bad.err, "not positive definite"));
  CHECK(bad.out.empty());
}

TEST_CASE("Command-line errors name what is expected", "[driver]") {
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"eval", "--q", "1,2"}, "--q expects 1 value(s), got 2; known coordinates: theta"},
      {{"eval", "--u", "1,x"}, "invalid list '1,x' for --u"},
      {{"eval", "--set", "mass=1"},
       "unknown parameter 'mass' in --set; known parameters: m, l, g, q_limit, nan_after"},
      {{"simulate", "--t-end", "1", "--set", "k=1"}, "unknown parameter 'k'"},
      {{"simulate", "--t-end", "1", "--q0", "phi=1"}, "unknown name 'phi' in --q0; known coordinates: theta"},
      {{"simulate", "--t-end", "1", "--u0", "theta=1"}, "known speeds: omega"},
      {{"simulate", "--t-end", "1.2x"}, "invalid number '1.2x' for --t-end"},
      {{"simulate", "--t-end", "1", "--set", "m=nan"}, "invalid number 'nan' for --set"},
      {{"simulate", "--t-end", "1", "--set", "m"}, "--set expects NAME=VALUE"},
      {{"simulate"}, "simulate needs --t-end"},
      {{"simulate", "--t-end", "1", "--dt", "0"}, "--dt must be positive"},
      {{"simulate", "--t-end", "1", "--rtol", "-1"}, "--rtol must be >= 0"},
      {{"simulate", "--t-end", "1", "--rtol", "0", "--atol", "0"}, "--rtol and --atol cannot both be zero"},
      {{"simulate", "--t-end", "1", "--h-min", "-1"}, "--h-min must be >= 0"},
      {{"simulate", "--t-end", "1", "--stats=yes"}, "option --stats takes no value"},
      {{"simulate", "--t-end", "1", "--t-end", "2"}, "--t-end given more than once"},
      {{"simulate", "--t-end", "1", "--integrator", "euler"},
       "unknown integrator 'euler'; known: " + known_integrators()},
      {{"simulate", "--t-end", "1", "--max-steps", "1.5"}, "--max-steps needs a positive integer"},
      {{"simulate", "--t-end"}, "option --t-end needs a value"},
      {{"simulate", "--t-end", "1", "--bogus"}, "unknown option '--bogus' for pendulum_runner simulate"},
      {{"simulate", "--t-end", "1", "extra"}, "unexpected argument 'extra'"},
      {{"simulate", "--t-end", "1", "-o", "/nonexistent-dir/x.csv"}, "cannot open /nonexistent-dir/x.csv"},
      {{"info", "--verbose"}, "unknown option '--verbose'"},
      {{"fly"}, "unknown command 'fly'"},
  };
  for (const Case& c : cases) {
    const Outcome o = run(c.args);
    INFO(c.args[0] << " ... -> " << o.err);
    check_one_line_error(o);
    CHECK(contains(o.err, c.message));
    CHECK(o.out.empty());
  }
}

TEST_CASE("info describes the model", "[driver]") {
  const Outcome o = run({"info"});
  REQUIRE(o.code == 0);
  const json j = json::parse(o.out);
  CHECK(j["name"] == "pendulum");
  CHECK(j["nq"] == 1);
  CHECK(j["nu"] == 1);
  CHECK(j["ntau"] == 1);
  CHECK(j["ny"] == 2);
  CHECK(j["np"] == 5);
  CHECK(j["coordinates"] == json::array({"theta"}));
  CHECK(j["speeds"] == json::array({"omega"}));
  CHECK(j["inputs"] == json::array({"torque"}));
  CHECK(j["outputs"] == json::array({"tip_x", "tip_y"}));
  CHECK(j["parameters"] == json::array({"m", "l", "g", "q_limit", "nan_after"}));
  CHECK(j["parameter_defaults"] == json::array({2.0, 0.5, 9.81, 1e9, 1e9}));
  CHECK(j["q0"] == json::array({0.3}));
  CHECK(j["u0"] == json::array({0.0}));
  // The kernels its table holds, in spec order: not the loop kernels of an open tree, not an unbound one.
  const std::vector<std::string> kernels = j["kernels"].get<std::vector<std::string>>();
  CHECK(std::find(kernels.begin(), kernels.end(), "mass_matrix") != kernels.end());
  CHECK(std::find(kernels.begin(), kernels.end(), "forward_dynamics") != kernels.end());
  CHECK(std::find(kernels.begin(), kernels.end(), "constraints") == kernels.end());
  CHECK(std::find(kernels.begin(), kernels.end(), "generalized_momentum") == kernels.end());
}

// The Model and its table are instantiated from kernels.def: the methods
// forward, the ones that may be absent say so, and a table that lacks a
// kernel the spec requires of its kind is refused.
TEST_CASE("Model over the kernel spec: forwarding, absent kernels, completeness", "[driver][spec]") {
  using kanegen::runtime::Kernel;
  using kanegen::runtime::kernel_specs;
  using kanegen::runtime::ModelTable;
  for (std::size_t k = 0; k < kanegen::runtime::kernel_count; ++k)
    CHECK(static_cast<std::size_t>(kernel_specs[k].kernel) == k);
  const ModelTable table = mock::System::kernel_table<ModelTable>();
  kanegen::runtime::Model model(table);
  const double q[1] = {0.3}, u[1] = {2.0}, tau[1] = {0.0};
  double M = 0, phi = 7.0;
  model.mass_matrix(q, &M);
  CHECK(M == Approx(2.0 * 0.25));
  CHECK(model.kinetic_energy(q, u) == Approx(0.5 * 0.5 * 4.0));
  CHECK(model.has(Kernel::mass_matrix));
  CHECK_FALSE(model.has(Kernel::constraints));
  CHECK_FALSE(model.has(Kernel::generalized_momentum));  // unbound: System only
  model.constraints(q, &phi);                            // call_or_zero: nothing for an open tree
  CHECK(phi == 7.0);
  CHECK(model.nonconservative_power(0.0, q, u, tau) == 0.0);  // absent: 0
  CHECK_FALSE(model.has_jacobians());
  CHECK_FALSE(model.has_controller());

  ModelTable with_jacobians = table;
  with_jacobians.forcing_jacobian = [](const void*, double, const double*, const double*, const double*,
                                       double*, double*) {};
  CHECK_FALSE(kanegen::runtime::Model(with_jacobians).has_jacobians());
  with_jacobians.mass_matrix_product_jacobian = [](const void*, const double*, const double*, double*) {};
  CHECK(kanegen::runtime::Model(with_jacobians).has_jacobians());

  ModelTable incomplete = table;
  incomplete.forcing = nullptr;
  CHECK_THROWS_WITH(kanegen::runtime::Model(incomplete), Catch::Contains("lacks a kernel"));
  ModelTable loops = table;  // a table of a model with loops needs the loop kernels
  loops.nc = 1;
  CHECK_THROWS_WITH(kanegen::runtime::Model(loops), Catch::Contains("lacks a kernel"));
}

TEST_CASE("--help for the runner and each command", "[driver]") {
  const Outcome top = run({"--help"});
  CHECK(top.code == 0);
  CHECK(contains(top.out, "usage: pendulum_runner <command>"));
  CHECK(contains(top.out, "Runs the compiled model pendulum."));
  const Outcome sim = run({"simulate", "--help"});
  CHECK(sim.code == 0);
  CHECK(contains(sim.out, "--t-end T"));
  CHECK(contains(run({"eval", "-h"}).out, "--q v1,v2,..."));
  CHECK(contains(run({"info", "--help"}).out, "usage: pendulum_runner info"));
  const Outcome none = run({});
  CHECK(none.code == 2);
  CHECK(contains(none.err, "usage:"));
}

TEST_CASE("run_model(argc, argv) as called from a generated main", "[driver]") {
  const std::string path = temp_path("argv.csv");
  std::vector<std::string> storage = {"runner", "simulate", "--t-end", "0.5", "-o", path};
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  REQUIRE(run_model<mock::System>(static_cast<int>(argv.size()), argv.data()) == 0);
  CHECK(lines(slurp(path)).size() == 52);
  std::filesystem::remove(path);
}
