// SPDX-License-Identifier: GPL-2.0-or-later
#include "pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "codegen/emitter.hpp"
#include "kane/equations.hpp"
#include "model/fnv1a.hpp"
#include "model/model_error.hpp"
#include "symbolic/program.hpp"
#include "symbolic/shape_function.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::pipeline {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The Jacobian and controller kernels exist in double only (linearize's
/// solve and the Jacobians' zero fills are written for it).
void check_precision(const model::Model& model, const GenerateOptions& options) {
  if (options.precision == codegen::Precision::double_precision) return;
  if (options.jacobians || options.controller)
    throw model::ModelError(model.source_file, "",
                            "--precision float cannot be combined with --jacobians or --controller",
                            "generate the Jacobian and controller kernels in double (leave out --precision)");
}

/// The controller kernels linearize and solve the tree's own M: a loop's
/// constraint forces or a prescribed acceleration would make them wrong.
void refuse_controller_kernels(const model::Model& model) {
  const std::string why = "--controller supports trees without prescribed motions (docs/controllers.md)";
  if (!model.loops.empty())
    throw model::ModelError(model.source_file, model.loops.front().where,
                            "the controller kernels are not made for closed loops",
                            "generate without --controller; " + why);
  for (const model::Joint& joint : model.joints)
    if (joint.is_prescribed())
      throw model::ModelError(model.source_file, joint.where + "/prescribed",
                              "the controller kernels are not made for prescribed motions",
                              "generate without --controller; " + why);
}

/// The batched kernels evaluate the scalar kernels' straight-line code over
/// lanes: no time-dependent branch (a prescribed motion's pieces), no
/// saddle-point solve (loops), double only.
void refuse_batch_kernels(const model::Model& model, const GenerateOptions& options) {
  const std::string why =
      "--batch supports double kernels of trees without prescribed motions "
      "(docs/architecture.md#batched-kernels)";
  if (options.batch != 4 && options.batch != 8)
    throw model::ModelError(model.source_file, "",
                            "--batch " + std::to_string(options.batch) + " is not a lane count",
                            "use --batch 4 or --batch 8");
  if (options.precision != codegen::Precision::double_precision)
    throw model::ModelError(model.source_file, "", "--batch cannot be combined with --precision float",
                            "generate the batched kernels in double (leave out --precision)");
  if (!model.loops.empty())
    throw model::ModelError(model.source_file, model.loops.front().where,
                            "the batched kernels are not made for closed loops",
                            "generate without --batch; " + why);
  for (const model::Joint& joint : model.joints)
    if (joint.is_prescribed())
      throw model::ModelError(model.source_file, joint.where + "/prescribed",
                              "the batched kernels are not made for prescribed motions",
                              "generate without --batch; " + why);
}

/// The Jacobian kernels (implicit integration, --controller) are d/dq of
/// kernels, the whole Jacobian only where q_dot = u: not for a quaternion.
void refuse_quaternion_jacobians(const model::Model& model, const GenerateOptions& options) {
  if (!options.jacobians && !options.controller) return;
  for (const model::Joint& joint : model.joints)
    if (joint.type == model::JointType::spherical)
      throw model::ModelError(model.source_file, joint.where + "/type",
                              "the Jacobian kernels (of the implicit integrators and of --controller) need "
                              "coordinates whose rates are the speeds, and joint '" +
                                  joint.name + "' turns by a quaternion",
                              "integrate with an explicit method (--integrator dopri5 or rk4) and generate "
                              "without --jacobians and --controller");
}

/// The articulated-body recursion solves open trees whose every speed is
/// free: `--dynamics recursive` on anything else is refused, naming why.
void refuse_recursive_dynamics(const model::Model& model) {
  const std::string fix = "use --dynamics composite, or auto (the default), which picks composite here";
  if (!model.loops.empty())
    throw model::ModelError(model.source_file, model.loops.front().where,
                            "--dynamics recursive is for open trees, and this model closes " +
                                std::to_string(model.loops.size()) +
                                " loop(s) (their constraint forces need the saddle-point solve)",
                            fix);
  for (const model::Joint& joint : model.joints) {
    if (joint.is_prescribed())
      throw model::ModelError(model.source_file, joint.where + "/prescribed",
                              "--dynamics recursive solves for every speed, and joint '" + joint.name +
                                  "' has a prescribed motion",
                              fix);
    if (joint.type == model::JointType::spherical)
      throw model::ModelError(model.source_file, joint.where + "/type",
                              "--dynamics recursive solves joints of one speed, and joint '" + joint.name +
                                  "' is spherical (three)",
                              fix);
  }
}

}  // namespace

std::string digest(const std::string& bytes) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(model::fnv1a(bytes)));
  return text;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the file; check the path");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

GeneratedModel generate(const std::string& model_path, const model::LoadOptions& options,
                        const GenerateOptions& generate_options) {
  GeneratedModel out;
  auto start = std::chrono::steady_clock::now();
  const model::Model model = model::load_model(model_path, options);
  const std::string hash = digest(read_file(model_path));
  out.seconds.load = seconds_since(start);
  check_precision(model, generate_options);

  if (generate_options.controller) refuse_controller_kernels(model);
  if (generate_options.batch > 0) refuse_batch_kernels(model, generate_options);
  refuse_quaternion_jacobians(model, generate_options);
  if (generate_options.dynamics == codegen::DynamicsMethod::recursive) refuse_recursive_dynamics(model);

  // The finite-element bodies: element matrices, invariants, modal bases.
  kane::FlexibleBodies flexible;
  std::vector<int> elastic_counts(model.bodies.size(), 0);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].flexible) continue;
    fem::ElasticModel beam =
        fem::build_elastic_model(model.bodies[b], model.source_file, symbolic::sample_shape);
    elastic_counts[b] = static_cast<int>(beam.reduced.names.size());
    flexible.emplace(static_cast<int>(b), std::move(beam));
  }

  // A derivation context with each way of summing M; keep the one whose
  // composite forward_dynamics is shorter (the recursion does not use M), by
  // counting alone: that derives M, f and the loops only. The kernels are then
  // derived from the context kept, each asking it for what it needs, and
  // printed on the graph their count filled. The Program lives on the heap:
  // the context and the graph refer to it.
  const symbolic::Variables vars(model, elastic_counts);
  const codegen::EmitOptions emit_options{generate_options.jacobians || generate_options.controller,
                                          generate_options.controller,
                                          generate_options.precision,
                                          generate_options.dynamics,
                                          generate_options.split_threshold,
                                          generate_options.batch};
  const codegen::ScalarType scalar(generate_options.precision);
  long fewest = 0;
  std::unique_ptr<symbolic::Program> chosen_program;
  std::unique_ptr<codegen::ExpressionGraph> chosen_graph;
  std::unique_ptr<kane::DerivationContext> chosen;
  for (kane::MassMatrixMethod method :
       {kane::MassMatrixMethod::body_frames, kane::MassMatrixMethod::world_projection}) {
    // A joint on a beam node makes the context sum in body frames
    // anyway: the second derivation would be the first again.
    if (method == kane::MassMatrixMethod::world_projection &&
        std::any_of(model.joints.begin(), model.joints.end(),
                    [](const model::Joint& joint) { return joint.parent_node >= 0; }))
      continue;
    start = std::chrono::steady_clock::now();
    auto program = std::make_unique<symbolic::Program>();
    auto products = std::make_unique<kane::DerivationContext>(model, vars, *program, method, flexible);
    // What the count asks for, asked first to time the derivation apart.
    products->mass_matrix();
    products->forcing();
    if (products->has_loops()) products->loops();
    out.seconds.derive += seconds_since(start);
    start = std::chrono::steady_clock::now();
    if (generate_options.dynamics == codegen::DynamicsMethod::recursive &&
        !products->recursion().unavailable.empty())
      throw model::ModelError(
          model.source_file, products->recursion().unavailable_place,
          "--dynamics recursive cannot solve this model: " + products->recursion().unavailable,
          "use --dynamics composite, or auto (the default)");
    auto graph = std::make_unique<codegen::ExpressionGraph>(vars, *program);
    const long operations = codegen::composite_operations(*products, *graph, scalar);
    out.seconds.choose += seconds_since(start);
    if (!chosen_program || operations < fewest) {
      fewest = operations;
      chosen_graph = std::move(graph);
      chosen = std::move(products);
      chosen_program = std::move(program);
    }
  }
  start = std::chrono::steady_clock::now();
  codegen::EmittedModel emitted = codegen::emit_model(*chosen, *chosen_graph, hash, emit_options);
  (emit_options.jacobians ? out.seconds.jacobians : out.seconds.emit) += seconds_since(start);

  out.name = model.name;
  out.files = std::move(emitted.files);
  out.operations = std::move(emitted.operations);
  out.dynamics = emitted.dynamics;
  out.intermediates = chosen_program->size();
  out.nq = chosen->nq();
  out.nu = chosen->nu();
  return out;
}

}  // namespace kanegen::pipeline
