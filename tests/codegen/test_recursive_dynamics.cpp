// SPDX-License-Identifier: GPL-2.0-or-later
// The articulated-body recursion (kane/articulated_body.*) against the
// composite solve of the same equations, M u_dot = f with M and f summed by
// composite bodies and solved by Eigen, on random rigid trees: branches,
// revolute and prismatic joints on frame axes (either way) and oblique axes,
// rotated joint frames, fixed joints, gravity in any direction, joint
// springs, dampers, inputs and efforts, body-fixed and world-fixed forces and a spring between two bodies.
// Both are evaluated from the expression graph the kernels are printed from.
// On the rigid trees also inverse_dynamics (Newton and Euler's recursion in
// the working frames, kane/working_newton_euler.*) against M u_dot - f.
// Flexible models too: the shipped ones (bodies on beam nodes, geometric
// stiffening, modal and nodal coordinates) and a random flexible tree with
// rigid and flexible children on a node, elastic speeds in the recursion.
#include <unistd.h>

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "codegen/expression_graph.hpp"
#include "fem/elastic_model.hpp"
#include "kane/equations.hpp"
#include "model/load.hpp"
#include "symbolic/program.hpp"
#include "symbolic/shape_function.hpp"
#include "symbolic/variables.hpp"

namespace {

using kanegen::codegen::ExpressionGraph;
using kanegen::codegen::Op;

/// The values of every node of the graph, in node order (operands come
/// before the nodes that use them), inputs taken from `input`.
template <class Input>
std::vector<double> node_values(const ExpressionGraph& g, const Input& input) {
  std::vector<double> v(g.size());
  for (std::size_t id = 0; id < g.size(); ++id) {
    const kanegen::codegen::Node& n = g.node(static_cast<int>(id));
    const auto arg = [&](std::size_t i) { return v[n.args[i]]; };
    double x = std::nan("");
    switch (n.op) {
      case Op::number:
        x = n.value;
        break;
      case Op::input:
        x = input(n.name);
        break;
      case Op::add:
        x = 0;
        for (std::size_t i = 0; i < n.args.size(); ++i) x += arg(i);
        break;
      case Op::mul:
        x = 1;
        for (std::size_t i = 0; i < n.args.size(); ++i) x *= arg(i);
        break;
      case Op::power:
        x = std::pow(arg(0), n.value);
        break;
      case Op::sqrt:
        x = std::sqrt(arg(0));
        break;
      case Op::sin:
        x = std::sin(arg(0));
        break;
      case Op::cos:
        x = std::cos(arg(0));
        break;
      case Op::tan:
        x = std::tan(arg(0));
        break;
      case Op::exp:
        x = std::exp(arg(0));
        break;
      case Op::log:
        x = std::log(arg(0));
        break;
      case Op::abs:
        x = std::abs(arg(0));
        break;
    }
    v[id] = x;
  }
  return v;
}

std::string vec(double x, double y, double z) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << x << ", " << y << ", " << z << "]";
  return s.str();
}

/// A random rigid tree as a model file: `bodies` bodies, each hung from the
/// ground or an earlier body.
std::string random_tree(std::mt19937& rng, int bodies) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.5, 1.5);
  const auto any = [&] { return vec(unit(rng), unit(rng), unit(rng)); };
  std::ostringstream m;
  m.precision(17);
  m << "{\"format\": \"kanegen-model\", \"version\": 1, \"name\": \"random_tree\",\n"
    << "\"gravity\": " << vec(2 * unit(rng), 2 * unit(rng), -9.81) << ",\n\"bodies\": [\n";
  for (int b = 0; b < bodies; ++b) {
    // Principal moments that satisfy the triangle inequality, small products.
    const double ixx = 0.1 + 0.03 * unit(rng), iyy = 0.1 + 0.03 * unit(rng), izz = 0.1 + 0.03 * unit(rng);
    m << (b ? ",\n" : "") << "{\"name\": \"b" << b << "\", \"mass\": " << positive(rng)
      << ", \"com\": " << vec(0.3 * unit(rng), 0.3 * unit(rng), 0.3 * unit(rng))
      << ", \"inertia\": {\"ixx\": " << ixx << ", \"iyy\": " << iyy << ", \"izz\": " << izz
      << ", \"ixy\": " << 0.004 * unit(rng) << ", \"ixz\": " << 0.004 * unit(rng)
      << ", \"iyz\": " << 0.004 * unit(rng) << "}}";
  }
  m << "],\n\"joints\": [\n";
  std::vector<std::string> moving;
  for (int b = 0; b < bodies; ++b) {
    const int parent = std::uniform_int_distribution<int>(-1, b - 1)(rng);
    const int kind = std::uniform_int_distribution<int>(0, 5)(rng);  // 0-2 revolute, 3-4 prismatic, 5 fixed
    const std::string type = b == 0 || kind < 3 ? "revolute" : kind < 5 ? "prismatic" : "fixed";
    const std::string name = "j" + std::to_string(b);
    m << (b ? ",\n" : "") << "{\"name\": \"" << name << "\", \"type\": \"" << type << "\", \"parent\": \""
      << (parent < 0 ? std::string("ground") : "b" + std::to_string(parent)) << "\", \"child\": \"b" << b
      << "\", \"origin\": {\"xyz\": " << vec(0.5 * unit(rng), 0.5 * unit(rng), 0.5 * unit(rng))
      << ", \"rpy\": " << any() << "}";
    if (type != "fixed") {
      moving.push_back(name);
      // Two thirds of the axes along a frame axis, either way (the structural
      // zeros, which the recursion sets exactly), one third oblique.
      const int axis = std::uniform_int_distribution<int>(0, 8)(rng);
      const double sign = axis < 3 ? 1.0 : -1.0;
      const auto along = [&](int k) { return axis % 3 == k ? sign : 0.0; };
      m << ", \"axis\": " << (axis < 6 ? vec(along(0), along(1), along(2)) : any());
      if (b % 2 == 0)
        m << ", \"spring\": {\"stiffness\": " << 5 * positive(rng) << ", \"rest\": " << 0.2 * unit(rng)
          << "}, \"damping\": " << 0.5 * positive(rng);
    }
    m << "}";
  }
  m << "],\n\"forces\": [\n"
    << "{\"name\": \"push\", \"body\": \"b" << bodies - 1 << "\", \"point\": " << any()
    << ", \"force\": " << any() << ", \"frame\": \"body\"},\n"
    << "{\"name\": \"wind\", \"body\": \"b0\", \"point\": " << any() << ", \"force\": " << any()
    << ", \"frame\": \"world\"},\n"
    << "{\"name\": \"tether\", \"type\": \"spring\", \"body\": \"b" << bodies - 1
    << "\", \"point\": " << any() << ", \"body2\": \"b0\", \"point2\": " << any()
    << ", \"stiffness\": 20, \"rest_length\": 0.3, \"damping\": 0.7},\n"
    << "{\"name\": \"motor\", \"type\": \"joint_effort\", \"joint\": \"" << moving.back()
    << "\", \"value\": \"0.8*sin(3*t) + 0.1\"}]}\n";
  return m.str();
}

struct Comparison {
  double worst = 0;  ///< largest |recursive - composite| / (1 + |composite|)
  int nu = 0;
  /// Rigid trees: inverse_dynamics (Newton and Euler's recursion) against M
  /// u_dot - f at random u_dot, the same measure; -1 where there is none.
  double worst_inverse = -1;
};

/// q and u drawn in [-2, 2] (`joints` of them, the joints'), elastic ones in
/// [-scale, scale]; the model parameters at their defaults.
Comparison compare(const std::string& path, std::mt19937& rng, double elastic_scale = 0.0) {
  const kanegen::model::Model model = kanegen::model::load_model(path);
  kanegen::kane::FlexibleBodies flexible;
  std::vector<int> elastic_counts(model.bodies.size(), 0);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].flexible) continue;
    kanegen::fem::ElasticModel beam =
        kanegen::fem::build_elastic_model(model.bodies[b], path, kanegen::symbolic::sample_shape);
    elastic_counts[b] = static_cast<int>(beam.reduced.names.size());
    flexible.emplace(static_cast<int>(b), std::move(beam));
  }
  const kanegen::symbolic::Variables vars(model, elastic_counts);
  kanegen::symbolic::Program program;
  kanegen::kane::DerivationContext eq(model, vars, program, kanegen::kane::MassMatrixMethod::body_frames,
                                      flexible);
  INFO(eq.recursion().unavailable);
  REQUIRE(eq.recursion().unavailable.empty());
  const int n = eq.nu();
  REQUIRE(static_cast<int>(eq.recursion().accelerations.size()) == n);
  ExpressionGraph graph(vars, program);
  std::vector<int> mass, forcing, recursive;
  for (const GiNaC::ex& e : eq.mass_matrix()) mass.push_back(graph.add(e));
  for (const GiNaC::ex& e : eq.forcing()) forcing.push_back(graph.add(e));
  for (const GiNaC::ex& e : eq.recursion().accelerations) recursive.push_back(graph.add(e));
  std::vector<int> inverse;
  for (const GiNaC::ex& e : eq.inverse_dynamics().inertial) inverse.push_back(graph.add(e));

  Comparison c;
  c.nu = n;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int state = 0; state < 5; ++state) {
    std::vector<double> q(n), u(n), tau(n), accelerations(n);
    for (int i = 0; i < n; ++i) {
      const double scale = i < vars.joint_coordinates ? 2.0 : elastic_scale;
      q[i] = scale * unit(rng);
      u[i] = scale * unit(rng);
      tau[i] = unit(rng);
      accelerations[i] = 3 * unit(rng);
    }
    const double t = 1 + unit(rng);
    const auto input = [&](const std::string& name) {
      if (name == "t") return t;
      for (const kanegen::model::Parameter& p : model.parameters)
        if (name == "p." + p.name) return p.value;
      const std::size_t open = name.find('[');
      const std::string array = name.substr(0, open);
      const int i = std::stoi(name.substr(open + 1));
      if (array == "q") return q.at(i);
      if (array == "u") return u.at(i);
      if (array == "tau") return tau.at(i);
      if (array == "udot") return accelerations.at(i);
      FAIL("unexpected input " << name);
      return 0.0;
    };
    const std::vector<double> v = node_values(graph, input);
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd f(n), udot(n);
    for (int i = 0; i < n; ++i) {
      f[i] = v[forcing[i]];
      udot[i] = v[recursive[i]];
      for (int j = 0; j < n; ++j) M(i, j) = v[mass[i * n + j]];
    }
    const Eigen::VectorXd reference = M.ldlt().solve(f);
    for (int i = 0; i < n; ++i)
      c.worst = std::max(c.worst, std::abs(udot[i] - reference[i]) / (1 + std::abs(reference[i])));
    if (inverse.empty()) continue;
    const Eigen::VectorXd given = Eigen::Map<const Eigen::VectorXd>(accelerations.data(), n);
    const Eigen::VectorXd balance = M * given - f;
    c.worst_inverse = std::max(c.worst_inverse, 0.0);
    for (int i = 0; i < n; ++i)
      c.worst_inverse =
          std::max(c.worst_inverse, std::abs(v[inverse[i]] - balance[i]) / (1 + std::abs(balance[i])));
  }
  return c;
}

/// compare() on a model given as text, written to a file of this process
/// (ctest runs the cases in parallel) and removed after.
Comparison compare_text(const std::string& name, const std::string& text, std::mt19937& rng,
                        double elastic_scale = 0.0) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("kanegen_" + name + "_" + std::to_string(::getpid()) + ".json"))
                               .string();
  {
    std::ofstream out(path);
    out << text;
  }
  const Comparison c = compare(path, rng, elastic_scale);
  std::filesystem::remove(path);
  return c;
}

}  // namespace

TEST_CASE("recursive forward dynamics equals the composite solve on random trees", "[codegen][recursive]") {
  std::mt19937 rng(1717);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("kanegen_random_tree_" + std::to_string(::getpid()) + ".json"))
                               .string();
  double worst = 0, worst_inverse = 0;
  for (int tree = 0; tree < 12; ++tree) {
    const int bodies = 2 + tree % 6;
    {
      std::ofstream out(path);
      out << random_tree(rng, bodies);
    }
    INFO("tree " << tree << ", model file:\n" << std::ifstream(path).rdbuf());
    const Comparison c = compare(path, rng);
    CHECK(c.worst < 1e-10);
    CHECK(c.worst_inverse >= 0);  // a rigid tree has the recursive inverse dynamics
    CHECK(c.worst_inverse < 1e-10);
    worst = std::max(worst, c.worst);
    worst_inverse = std::max(worst_inverse, c.worst_inverse);
  }
  std::filesystem::remove(path);
  std::printf("recursive vs composite on 12 random trees: max rel. difference of u_dot %.2e\n", worst);
  std::printf("inverse_dynamics vs M u_dot - f on the same trees: max rel. difference %.2e\n", worst_inverse);
}

TEST_CASE("recursive forward dynamics equals the composite solve on the flexible models",
          "[codegen][recursive][flexible]") {
  std::mt19937 rng(1718);
  // Elastic coordinates of the size of the models' deflections (nodal ones in m and rad).
  for (const char* name : {"flexible_arm2", "spatial_arm2", "beam_tip_mass", "cantilever", "l_frame"}) {
    INFO(name);
    const Comparison c = compare(KANEGEN_SOURCE_DIR "/models/" + std::string(name) + ".json", rng, 0.02);
    CHECK(c.worst < 1e-9);
    std::printf("recursive vs composite on %s (%d speeds): max rel. difference of u_dot %.2e\n", name, c.nu,
                c.worst);
  }
}

TEST_CASE("recursive forward dynamics equals the composite solve on a random flexible tree",
          "[codegen][recursive][flexible]") {
  // Two flexible links (modal, nodal), a rigid and a flexible child on a
  // node of the first, a prismatic joint on a node of the second's frame
  // child, a fixed flexible body, oblique axes and rotated frames.
  std::mt19937 rng(1719);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto any = [&] { return vec(unit(rng), unit(rng), unit(rng)); };
  const std::string beam =
      "\"section\": {\"A\": 2e-4, \"Iy\": 2e-9, \"Iz\": 6e-9, \"J\": 5e-9}, "
      "\"material\": {\"E\": 7e10, \"poisson\": 0.33, \"density\": 2700}";
  std::ostringstream m;
  m.precision(17);
  m << "{\"format\": \"kanegen-model\", \"version\": 1, \"name\": \"random_flexible_tree\",\n"
    << "\"gravity\": " << vec(unit(rng), unit(rng), -9.81) << ",\n\"bodies\": [\n"
    << "{\"name\": \"f1\", \"mass\": 0.3, \"com\": " << vec(0.02, 0.01, 0)
    << ", \"inertia\": {\"ixx\": 2e-4, \"iyy\": 3e-4, \"izz\": 2.5e-4}, \"flexible\": {\"formulation\": "
       "\"spatial\", \"length\": 0.7, \"elements\": 3, \"modes\": 4, "
    << beam << "}},\n"
    << "{\"name\": \"r1\", \"mass\": 0.6, \"com\": " << vec(0.05, 0.02, -0.01)
    << ", \"inertia\": {\"ixx\": 3e-4, \"iyy\": 4e-4, \"izz\": 5e-4, \"ixy\": 2e-5}},\n"
    << "{\"name\": \"f2\", \"mass\": 0.2, \"inertia\": {\"ixx\": 1e-4, \"iyy\": 1e-4, \"izz\": 1e-4}, "
       "\"flexible\": {\"formulation\": \"spatial\", \"length\": 0.5, \"elements\": 2, "
    << beam << ", \"damping\": {\"rayleigh\": [0.1, 1e-4]}}},\n"
    << "{\"name\": \"r2\", \"mass\": 0.4, \"com\": " << vec(0.01, 0, 0.02)
    << ", \"inertia\": {\"ixx\": 2e-4, \"iyy\": 2e-4, \"izz\": 3e-4}},\n"
    << "{\"name\": \"f3\", \"mass\": 0.1, \"inertia\": {\"ixx\": 1e-4, \"iyy\": 1e-4, \"izz\": 1e-4}, "
       "\"flexible\": {\"formulation\": \"planar\", \"length\": 0.4, \"elements\": 2, \"modes\": 2, "
    << beam << "}}\n],\n\"joints\": [\n"
    << "{\"name\": \"j1\", \"type\": \"revolute\", \"parent\": \"ground\", \"child\": \"f1\", \"axis\": "
    << any() << ", \"origin\": {\"rpy\": " << any() << "}},\n"
    << "{\"name\": \"j2\", \"type\": \"revolute\", \"parent\": \"f1\", \"child\": \"r1\", \"parent_node\": "
       "\"tip\", \"axis\": "
    << any() << ", \"origin\": {\"xyz\": " << vec(0.02, 0, 0.01) << ", \"rpy\": " << any() << "}},\n"
    << "{\"name\": \"j3\", \"type\": \"revolute\", \"parent\": \"f1\", \"child\": \"f2\", \"parent_node\": "
       "2, "
       "\"axis\": [0, 0, 1], \"origin\": {\"rpy\": "
    << any() << "}, \"spring\": {\"stiffness\": 2}, \"damping\": 0.1},\n"
    << "{\"name\": \"j4\", \"type\": \"prismatic\", \"parent\": \"r1\", \"child\": \"r2\", \"axis\": "
    << any() << ", \"origin\": {\"xyz\": " << any() << "}},\n"
    << "{\"name\": \"j5\", \"type\": \"fixed\", \"parent\": \"r2\", \"child\": \"f3\", \"origin\": {\"rpy\": "
    << any() << "}}\n],\n\"forces\": [\n"
    << "{\"name\": \"push\", \"body\": \"f2\", \"node\": \"tip\", \"force\": " << any()
    << ", \"frame\": \"body\"},\n"
    << "{\"name\": \"motor\", \"type\": \"joint_effort\", \"joint\": \"j2\", \"value\": "
       "\"0.3*sin(2*t)\"}]}\n";
  INFO("model file:\n" << m.str());
  const Comparison c = compare_text("random_flexible_tree", m.str(), rng, 0.02);
  CHECK(c.nu == 4 + 4 + 2 * 6 + 2);
  CHECK(c.worst < 1e-9);
  std::printf(
      "recursive vs composite on a random flexible tree (%d speeds): max rel. difference of u_dot %.2e\n",
      c.nu, c.worst);
}

TEST_CASE("recursive forward dynamics equals the composite solve on rigid bodies off a flexible frame",
          "[codegen][recursive][flexible]") {
  // A rigid chain on a flexible link's own frame (no node): the recursion
  // carries the link's motion to the chain through one general step
  // (kane/working_motion.*), where a chain on the ground or on a node starts
  // from its body frame. A world force on the chain's end, gravity oblique.
  const std::string beam =
      "\"section\": {\"A\": 2e-4, \"Iy\": 2e-9, \"Iz\": 6e-9, \"J\": 5e-9}, "
      "\"material\": {\"E\": 7e10, \"poisson\": 0.33, \"density\": 2700}";
  const std::string model =
      "{\"format\": \"kanegen-model\", \"version\": 1, \"name\": \"rigid_off_flexible\",\n"
      "\"gravity\": [1.5, -2, -9.81],\n\"bodies\": [\n"
      "{\"name\": \"f\", \"mass\": 0.3, \"com\": [0.02, 0.01, 0], \"inertia\": {\"ixx\": 2e-4, "
      "\"iyy\": 3e-4, \"izz\": 2.5e-4}, \"flexible\": {\"formulation\": \"spatial\", \"length\": 0.7, "
      "\"elements\": 3, \"modes\": 4, " +
      beam +
      "}},\n"
      "{\"name\": \"r1\", \"mass\": 0.6, \"com\": [0.05, 0.02, -0.01], \"inertia\": {\"ixx\": 3e-4, "
      "\"iyy\": 4e-4, \"izz\": 5e-4, \"ixy\": 2e-5}},\n"
      "{\"name\": \"r2\", \"mass\": 0.4, \"com\": [0.01, 0, 0.02], \"inertia\": {\"ixx\": 2e-4, "
      "\"iyy\": 2e-4, \"izz\": 3e-4, \"iyz\": -1e-5}},\n"
      "{\"name\": \"r3\", \"mass\": 0.3, \"com\": [0.02, 0.03, 0], \"inertia\": {\"ixx\": 1e-4, "
      "\"iyy\": 2e-4, \"izz\": 2e-4}}\n],\n\"joints\": [\n"
      "{\"name\": \"j1\", \"type\": \"revolute\", \"parent\": \"ground\", \"child\": \"f\", "
      "\"axis\": [0.6, 0, 0.8]},\n"
      "{\"name\": \"j2\", \"type\": \"revolute\", \"parent\": \"f\", \"child\": \"r1\", "
      "\"axis\": [0, 1, 0], \"origin\": {\"xyz\": [0.1, 0.05, -0.02], \"rpy\": [0.3, -0.2, 0.5]}},\n"
      "{\"name\": \"j3\", \"type\": \"prismatic\", \"parent\": \"r1\", \"child\": \"r2\", "
      "\"axis\": [0, 0.6, 0.8], \"origin\": {\"xyz\": [0.2, 0, 0.05], \"rpy\": [0, 0.4, 0]}},\n"
      "{\"name\": \"j4\", \"type\": \"revolute\", \"parent\": \"r2\", \"child\": \"r3\", "
      "\"axis\": [1, 0, 0], \"origin\": {\"xyz\": [0, 0.15, 0.1], \"rpy\": [0.7, 0, 0]}}\n],\n"
      "\"forces\": [{\"name\": \"pull\", \"body\": \"r3\", \"point\": [0.1, 0, 0], \"force\": [0.3, "
      "-0.2, 0.5], \"frame\": \"world\"}]}\n";
  INFO("model file:\n" << model);
  std::mt19937 rng(1721);
  const Comparison c = compare_text("rigid_off_flexible", model, rng, 0.02);
  CHECK(c.nu == 4 + 4);
  CHECK(c.worst < 1e-9);
  std::printf("recursive vs composite on rigid bodies off a flexible frame: max rel. difference %.2e\n",
              c.worst);
}

TEST_CASE("recursive forward dynamics equals the composite solve where the working frames are special",
          "[codegen][recursive]") {
  // The recursion's working frames (kane/working_frames.*) take each joint's
  // constant transform apart into turns about and shifts along coordinate
  // axes; these joints hit its special cases: parallel and antiparallel axes
  // (sin alpha = 0, with and without an offset across them), intersecting
  // axes (a = 0), a prismatic joint with an offset origin along its own
  // axis, a branch (the second child keeps gamma and eps), a fixed joint
  // between moving ones, and a joint origin over a parameter (one general step).
  const std::string body =
      "\"mass\": 0.8, \"com\": [0.05, -0.02, 0.1], \"inertia\": {\"ixx\": 0.02, "
      "\"iyy\": 0.03, \"izz\": 0.025, \"ixy\": 0.001, \"ixz\": -0.002, \"iyz\": 0.0015}";
  const char* joints[][5] = {
      // name, type, parent, axis, origin
      {"j0", "revolute", "ground", "[0, 0, 1]", "{\"xyz\": [0.1, 0, 0]}"},
      {"j1", "revolute", "b0", "[0, 0, 1]", "{\"xyz\": [0.3, 0.1, 0.05]}"},  // parallel
      {"j2", "revolute", "b1", "[0, 0, -1]", "{\"xyz\": [0, 0, 0.2]}"},      // antiparallel, coaxial
      {"j3", "revolute", "b2", "[1, 0, 0]", "{\"xyz\": [0, 0, 0.25]}"},      // intersecting
      {"j4", "prismatic", "b3", "[0, 1, 0]",
       "{\"xyz\": [0, 0.2, 0], \"rpy\": [0.3, 0, 0]}"},  // along its axis
      {"j5", "fixed", "b4", "", "{\"xyz\": [0.1, 0.1, 0.1], \"rpy\": [0.2, -0.4, 0.7]}"},
      {"j6", "revolute", "b5", "[0.6, 0, 0.8]", "{\"xyz\": [0.2, -0.1, 0], \"rpy\": [0, 0.5, 0]}"},
      {"j7", "revolute", "b3", "[0, 1, 0]",
       "{\"xyz\": [0.1, 0.3, -0.2], \"rpy\": [0.1, 0.2, 0.3]}"},                                  // branch
      {"j8", "revolute", "b7", "[0, 0, 1]", "{\"xyz\": [\"l\", 0, 0.1], \"rpy\": [0.5, 0, 0]}"},  // parameter
      {"j9", "prismatic", "b8", "[1, 0, 0]", "{\"xyz\": [0.2, 0, 0], \"rpy\": [0, 0, 1.5707963267948966]}"},
  };
  std::ostringstream m;
  m << "{\"format\": \"kanegen-model\", \"version\": 1, \"name\": \"special_frames\", \"parameters\": "
       "{\"l\": "
       "0.35},\n\"gravity\": [0.5, -1, -9.81],\n\"bodies\": [\n";
  const int count = sizeof joints / sizeof joints[0];
  for (int b = 0; b < count; ++b) m << (b ? ",\n" : "") << "{\"name\": \"b" << b << "\", " << body << "}";
  m << "],\n\"joints\": [\n";
  for (int b = 0; b < count; ++b) {
    const std::string type = joints[b][1];
    m << (b ? ",\n" : "") << "{\"name\": \"" << joints[b][0] << "\", \"type\": \"" << type
      << "\", \"parent\": \"" << joints[b][2] << "\", \"child\": \"b" << b
      << "\", \"origin\": " << joints[b][4];
    if (type != "fixed") m << ", \"axis\": " << joints[b][3] << ", \"damping\": 0.3";
    m << "}";
  }
  m << "]}\n";
  INFO("model file:\n" << m.str());
  std::mt19937 rng(1720);
  const Comparison c = compare_text("special_frames", m.str(), rng);
  CHECK(c.nu == count - 1);
  CHECK(c.worst < 1e-10);
  CHECK(c.worst_inverse >= 0);
  CHECK(c.worst_inverse < 1e-10);
  std::printf("recursive vs composite where the working frames are special: max rel. difference %.2e\n",
              c.worst);
}
