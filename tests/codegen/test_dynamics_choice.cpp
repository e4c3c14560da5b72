// SPDX-License-Identifier: GPL-2.0-or-later
// The generator counts the forward_dynamics it does not print (and the M
// summation it does not keep) instead of printing them. These checks hold the
// counts so obtained to the counts of the kernels when they are printed: the
// method forced by --dynamics prints the other one, whose count must equal
// what the header quoted for it; and the single emission with the Jacobian
// kernels must give the same kernels and choice as the plain one.
#include <catch2/catch.hpp>
#include <string>

#include "pipeline/pipeline.hpp"

namespace {

using kanegen::codegen::DynamicsMethod;
using kanegen::codegen::Kernel;
using kanegen::pipeline::GeneratedModel;

GeneratedModel generate(const std::string& model, DynamicsMethod method, bool jacobians = false) {
  kanegen::pipeline::GenerateOptions options;
  options.dynamics = method;
  options.jacobians = jacobians;
  return kanegen::pipeline::generate(std::string(KANEGEN_SOURCE_DIR) + "/models/" + model, {}, options);
}

}  // namespace

TEST_CASE("the forward_dynamics not printed is counted as it would print", "[codegen][choice]") {
  // double_pendulum: the composite solve wins; arm7 (by a few operations) and chain20: the recursion.
  for (const char* model : {"double_pendulum.json", "arm7.urdf", "chain20.urdf"}) {
    INFO(model);
    const GeneratedModel chosen = generate(model, DynamicsMethod::automatic);
    const GeneratedModel recursive = generate(model, DynamicsMethod::recursive);
    const GeneratedModel composite = generate(model, DynamicsMethod::composite);
    REQUIRE(chosen.dynamics.recursive_operations > 0);
    CHECK(recursive.operations.at(Kernel::forward_dynamics) == chosen.dynamics.recursive_operations);
    CHECK(composite.operations.at(Kernel::forward_dynamics) == chosen.dynamics.composite_operations);
    CHECK(recursive.dynamics.composite_operations == chosen.dynamics.composite_operations);
    CHECK(composite.dynamics.recursive_operations == chosen.dynamics.recursive_operations);
    CHECK(chosen.dynamics.recursive ==
          (chosen.dynamics.recursive_operations < chosen.dynamics.composite_operations));
    CHECK(chosen.operations.at(Kernel::forward_dynamics) == (chosen.dynamics.recursive
                                                                 ? chosen.dynamics.recursive_operations
                                                                 : chosen.dynamics.composite_operations));
  }
  CHECK_FALSE(generate("double_pendulum.json", DynamicsMethod::automatic).dynamics.recursive);
  CHECK(generate("chain20.urdf", DynamicsMethod::automatic).dynamics.recursive);
}

TEST_CASE("emitting once with the Jacobians keeps the plain kernels and choice", "[codegen][choice]") {
  const GeneratedModel plain = generate("arm7.urdf", DynamicsMethod::automatic);
  const GeneratedModel with = generate("arm7.urdf", DynamicsMethod::automatic, true);
  CHECK(with.dynamics.composite_operations == plain.dynamics.composite_operations);
  CHECK(with.dynamics.recursive_operations == plain.dynamics.recursive_operations);
  CHECK(with.intermediates == plain.intermediates);
  for (const auto& [kernel, count] : plain.operations) CHECK(with.operations.at(kernel) == count);
  CHECK(with.operations.size() > plain.operations.size());
}
