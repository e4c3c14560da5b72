// SPDX-License-Identifier: GPL-2.0-or-later
// One test per kind of bad input (tests/data/bad_models): each fails with one
// ModelError naming the file, the exact place and a fix.
#include <catch2/catch.hpp>

#include "model/expression_eval.hpp"
#include "model/model_check.hpp"
#include "test_support.hpp"

using kanegen::model::joint_type_list;
using kanegen::model::joint_type_names;
using kanegen::model::JointKinds;
using kanegen::model::test::bad_model;
using kanegen::model::test::expect_model_error;

namespace {

/// The joint table's names as the schema's message lists them: "a, b, c".
/// Built from the table, so a new joint type needs no edit here.
std::string all_joint_types() {
  std::string out;
  for (const std::string& name : joint_type_names()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

// ---- JSON syntax and schema ----

TEST_CASE("bad JSON: malformed, with line and column", "[bad][json]") {
  expect_model_error(bad_model("malformed.json"), "line 5, column 10", "malformed JSON: syntax error",
                     "fix the JSON syntax");
}

TEST_CASE("bad JSON: unknown key suggests the nearest known key", "[bad][json]") {
  expect_model_error(bad_model("unknown_key.json"), "/joints/0/axes", "unknown key 'axes'",
                     "did you mean 'axis'?");
}

TEST_CASE("bad JSON: missing required key", "[bad][json]") {
  expect_model_error(bad_model("missing_key.json"), "/bodies/1", "missing required key 'mass'",
                     "add \"mass\": the mass in kg");
}

TEST_CASE("bad JSON: wrong type", "[bad][json]") {
  expect_model_error(bad_model("wrong_type.json"), "/bodies/1/mass",
                     "wrong type: expected a number or an expression string, found an array",
                     "write a number or an expression string");
}

TEST_CASE("bad JSON: value not among the allowed ones", "[bad][json]") {
  expect_model_error(bad_model("bad_enum.json"), "/joints/0/type", "invalid value \"hinge\"",
                     "use one of " + all_joint_types());
}

TEST_CASE("bad JSON: unsupported version", "[bad][json]") {
  expect_model_error(bad_model("bad_version.json"), "/version", "expected 1, found 2", "set it to 1");
}

TEST_CASE("bad JSON: invalid name", "[bad][json]") {
  expect_model_error(bad_model("bad_name.json"), "/joints/0/name", "'1st' is not a valid name",
                     "starting with a letter");
}

TEST_CASE("bad JSON: invalid parameter name", "[bad][json]") {
  expect_model_error(bad_model("bad_parameter_name.json"), "/parameters/2m", "'2m' is not a valid name",
                     "starting with a letter");
}

TEST_CASE("bad JSON: vector of the wrong length", "[bad][json]") {
  expect_model_error(bad_model("short_vector.json"), "/bodies/0/com", "expected 3 entries, found 2",
                     "an array of 3 numbers or expressions");
}

TEST_CASE("bad JSON: number that is not finite", "[bad][json]") {
  expect_model_error(bad_model("nonfinite.json"), "line 5, column 36",
                     "number 1e999 is too large for a double", "use a finite value");
}

// ---- names ----

TEST_CASE("bad model: duplicate body", "[bad][json]") {
  expect_model_error(bad_model("duplicate_body.json"), "/bodies/1/name",
                     "duplicate body name 'a' (also at /bodies/0)", "rename one of them");
}

TEST_CASE("bad model: duplicate joint", "[bad][json]") {
  expect_model_error(bad_model("duplicate_joint.json"), "/joints/1/name", "duplicate joint name 'j1'",
                     "rename one of them");
}

TEST_CASE("bad model: duplicate parameter (a key given twice)", "[bad][json]") {
  expect_model_error(bad_model("duplicate_parameter.json"), "/parameters/m", "key 'm' appears twice",
                     "keep only one of them");
}

TEST_CASE("bad model: duplicate output", "[bad][json]") {
  expect_model_error(bad_model("duplicate_output.json"), "/outputs/1/name", "duplicate output name 'tip'",
                     "rename one of them");
}

TEST_CASE("bad model: duplicate force", "[bad][json]") {
  expect_model_error(bad_model("duplicate_force.json"), "/forces/1/name", "duplicate force name 'push'",
                     "rename one of them");
}

TEST_CASE("bad model: reserved parameter name", "[bad][json]") {
  expect_model_error(bad_model("reserved_parameter.json"), "/parameters/q", "parameter name 'q' is reserved",
                     "rename it");
}

TEST_CASE("bad model: C++ keyword as model name", "[bad][json]") {
  expect_model_error(bad_model("keyword_name.json"), "/name", "model name 'class' is a C++ keyword",
                     "choose another name");
}

TEST_CASE("bad model: library macro as model or parameter name", "[bad][json]") {
  // The preprocessor would replace them in the generated code (namespace errno).
  expect_model_error(bad_model("macro_model_name.json"), "/name",
                     "model name 'errno' is a macro of the C library headers that generated code includes",
                     "choose another name, e.g. 'errno_'");
  expect_model_error(bad_model("macro_parameter_name.json"), "/parameters/EOF",
                     "parameter name 'EOF' is a macro of the C library headers", "choose another name");
}

TEST_CASE("bad model: body named like the ground", "[bad][json]") {
  expect_model_error(bad_model("body_named_ground.json"), "/bodies/1/name", "names the fixed ground",
                     "rename the body");
}

// ---- expressions ----

TEST_CASE("bad model: unknown name in an expression, with a caret", "[bad][json][expression]") {
  expect_model_error(bad_model("expression_unknown_name.json"), "/bodies/0/mass",
                     "unknown name 'm2' in expression\n  m1 + m2\n       ^",
                     "did you mean 'm1'? otherwise define it under /parameters");
}

TEST_CASE("bad model: unclosed parenthesis in an expression", "[bad][json][expression]") {
  expect_model_error(bad_model("expression_syntax.json"), "/bodies/0/com/2",
                     "unclosed '(' in expression\n  -(l1 + 1\n   ^", "add the matching ')'");
}

TEST_CASE("bad model: sign after an operator in an expression", "[bad][json][expression]") {
  expect_model_error(bad_model("expression_sign.json"), "/joints/1/origin/xyz/2",
                     "sign right after an operator in expression\n  l1*-2\n     ^",
                     "put the signed operand in parentheses");
}

// ---- mass properties ----

TEST_CASE("bad model: zero mass with inertia", "[bad][json]") {
  expect_model_error(bad_model("zero_mass_inertia.json"), "/bodies/0/mass",
                     "zero mass with a nonzero inertia", "set all inertia entries to 0 for a massless frame");
}

TEST_CASE("bad model: negative mass", "[bad][json]") {
  expect_model_error(bad_model("negative_mass.json"), "/bodies/1/mass", "negative mass",
                     "give a positive mass");
}

TEST_CASE("bad model: negative principal moment", "[bad][json]") {
  expect_model_error(bad_model("negative_inertia.json"), "/bodies/0/inertia", "negative principal moment",
                     "check the entries");
}

TEST_CASE("bad model: inertia violates the triangle inequality", "[bad][json]") {
  expect_model_error(bad_model("triangle_inertia.json"), "/bodies/0/inertia",
                     "violates the triangle inequality (principal moments 0.1, 0.1, 0.5: 0.1 + 0.1 < 0.5)",
                     "must be at least the third");
}

TEST_CASE("bad model: moving joint carrying only massless bodies", "[bad][json]") {
  expect_model_error(bad_model("massless_moving.json"), "/joints/1", "moves only massless bodies",
                     "make the joint fixed");
}

// ---- joints and tree ----

TEST_CASE("bad model: zero-length axis", "[bad][json]") {
  expect_model_error(bad_model("zero_axis.json"), "/joints/0/axis", "zero-length axis",
                     "give the axis a direction");
}

TEST_CASE("bad model: negative damping", "[bad][json]") {
  expect_model_error(bad_model("negative_damping.json"), "/joints/0/damping", "negative damping", ">= 0");
}

TEST_CASE("bad model: fields of a coordinate on a fixed joint", "[bad][json]") {
  expect_model_error(bad_model("fixed_joint_spring.json"), "/joints/1/spring", "has no coordinate",
                     "make the joint " + joint_type_list(JointKinds::moving, "or"));
}

TEST_CASE("bad model: unknown parent", "[bad][json]") {
  expect_model_error(bad_model("unknown_parent.json"), "/joints/1/parent", "unknown body 'aa'",
                     "did you mean 'a'?");
}

TEST_CASE("bad model: unknown child", "[bad][json]") {
  expect_model_error(bad_model("unknown_child.json"), "/joints/1/child", "unknown body 'c'",
                     "use the name of a body");
}

TEST_CASE("bad model: body that is the child of two joints", "[bad][json]") {
  expect_model_error(bad_model("two_parents.json"), "/joints/2/child",
                     "body 'b' is already the child of joint 'j2' (/joints/1)", "remove one of the joints");
}

TEST_CASE("bad model: cycle", "[bad][json]") {
  expect_model_error(bad_model("cycle.json"), "/joints/1/parent", "joints form a cycle: a -> b -> a",
                     "must end at 'ground'");
}

TEST_CASE("bad model: body not connected to the ground", "[bad][json]") {
  expect_model_error(bad_model("not_connected.json"), "/bodies/0", "body 'c' is not connected to the ground",
                     "attach the chain to 'ground'");
}

TEST_CASE("bad model: body with no joint", "[bad][json]") {
  expect_model_error(bad_model("no_joint.json"), "/bodies/2", "body 'd' is not the child of any joint",
                     "attach it with a joint");
}

// ---- outputs and forces ----

TEST_CASE("bad model: output naming an unknown body", "[bad][json]") {
  expect_model_error(bad_model("output_unknown_body.json"), "/outputs/0/body", "unknown body 'bb'",
                     "did you mean 'b'?");
}

TEST_CASE("bad model: output naming an unknown joint", "[bad][json]") {
  expect_model_error(bad_model("output_unknown_joint.json"), "/outputs/1/joint", "unknown joint 'j9'",
                     "did you mean 'j1'?");
}

TEST_CASE("bad model: joint output on a fixed joint", "[bad][json]") {
  expect_model_error(bad_model("output_fixed_joint.json"), "/outputs/1/joint", "fixed joint 'j2'",
                     "name a " + joint_type_list(JointKinds::one_coordinate, "or") + " joint");
}

TEST_CASE("bad model: point output without a point", "[bad][json]") {
  expect_model_error(bad_model("output_missing_point.json"), "/outputs/0",
                     "missing required key 'point' for a 'point' output", "add \"point\"");
}

TEST_CASE("bad model: force on an unknown body", "[bad][json]") {
  expect_model_error(bad_model("force_unknown_body.json"), "/forces/0/body", "names unknown body 'ground'",
                     "use the name of a body");
}

// ---- springs and joint efforts ----

TEST_CASE("bad spring: an unknown body, the ground as its first end, both ends on one body",
          "[bad][json][spring]") {
  expect_model_error(bad_model("spring_unknown_body.json"), "/forces/0/body2",
                     "spring 'tether' names unknown body 'grund'", "did you mean 'ground'?");
  expect_model_error(bad_model("spring_on_ground.json"), "/forces/0/body",
                     "spring 'tether' has its first point on the ground", "swap the ends");
  expect_model_error(bad_model("spring_same_body.json"), "/forces/0/body2",
                     "spring 'tether' has both points on body 'slider'",
                     "attach its second point to another body");
}

TEST_CASE("bad spring: a negative stiffness, a missing stiffness, a key of another force type",
          "[bad][json][spring]") {
  expect_model_error(bad_model("spring_negative_stiffness.json"), "/forces/0/stiffness",
                     "negative stiffness (-5) of spring 'tether'", "give a stiffness >= 0, in N/m");
  expect_model_error(bad_model("spring_missing_stiffness.json"), "/forces/0",
                     "missing required key 'stiffness' for a 'spring' force", "add \"stiffness\": k in N/m");
  expect_model_error(bad_model("spring_with_force_key.json"), "/forces/0/force",
                     "'force' does not apply to a 'spring' force", "remove it");
  expect_model_error(bad_model("force_bad_type.json"), "/forces/0/type", "invalid value \"sprung\"",
                     "did you mean \"spring\"? use one of constant, spring, joint_effort");
}

TEST_CASE("bad force: a spring and a joint effort with the same name", "[bad][json][spring]") {
  expect_model_error(bad_model("force_duplicate_across_types.json"), "/forces/1/name",
                     "duplicate force name 'tether' (also at /forces/0)", "rename one of them");
}

TEST_CASE("bad joint effort: a fixed, unknown or prescribed joint, an unknown name", "[bad][json][effort]") {
  expect_model_error(bad_model("effort_fixed_joint.json"), "/forces/0/joint",
                     "joint effort 'motor' acts on fixed joint 'mount', which has no coordinate",
                     "name a " + joint_type_list(JointKinds::one_coordinate, "or") + " joint");
  expect_model_error(bad_model("effort_unknown_joint.json"), "/forces/0/joint",
                     "joint effort 'motor' names unknown joint 'spn'", "did you mean 'spin'?");
  expect_model_error(bad_model("effort_prescribed_joint.json"), "/forces/0/joint",
                     "joint effort 'motor' acts on prescribed joint 'spin'", "remove it");
  expect_model_error(bad_model("effort_unknown_name.json"), "/forces/0/value",
                     "unknown name 'tau1' in expression\n  tau1*t\n  ^", "(and t, the time)");
}

// ---- files ----

TEST_CASE("bad file: unsupported extension", "[bad]") {
  expect_model_error(bad_model("unsupported.yaml"), "file", "unknown model file type '.yaml'", "use a .json");
}

TEST_CASE("bad file: missing file", "[bad]") {
  expect_model_error(bad_model("does_not_exist.json"), "file", "cannot open it", "check the path");
}

// ---- URDF ----

TEST_CASE("bad URDF: malformed XML", "[bad][urdf]") {
  // tinyxml2 points at the element left open.
  expect_model_error(bad_model("malformed.urdf"), "line 4", "malformed XML: an element is not closed",
                     "fix the XML syntax");
}

TEST_CASE("bad URDF: unknown joint type", "[bad][urdf]") {
  expect_model_error(bad_model("unknown_type.urdf"), "line 10: <joint name=\"j1\">",
                     "unknown URDF joint type 'hinge'", "use type=\"revolute\"");
}

TEST_CASE("bad URDF: mimic joint", "[bad][urdf]") {
  expect_model_error(bad_model("mimic.urdf"), "line 20: <joint name=\"j2\">/mimic",
                     "mimic joints are not supported", "remove <mimic>");
}

TEST_CASE("bad URDF: urdfdom failure (revolute without limit)", "[bad][urdf]") {
  expect_model_error(bad_model("no_limit.urdf"), "line 10: <joint name=\"j1\">",
                     "urdfdom cannot read the robot", "add <limit");
}

TEST_CASE("bad URDF: joint naming a missing link", "[bad][urdf]") {
  expect_model_error(bad_model("missing_link.urdf"), "line 14: <joint name=\"j2\">",
                     "urdfdom cannot read the robot", "fix the URDF");
}

TEST_CASE("bad URDF: duplicate link", "[bad][urdf]") {
  expect_model_error(bad_model("duplicate_link.urdf"), "line 10: <link name=\"base\">",
                     "duplicate link name 'base' (also at line 4)", "rename one of them");
}

TEST_CASE("bad URDF: zero-length axis", "[bad][urdf]") {
  expect_model_error(bad_model("zero_axis.urdf"), "line 10: <joint name=\"j1\">/axis", "zero-length axis",
                     "give the axis a direction");
}

TEST_CASE("bad URDF: negative principal moment", "[bad][urdf]") {
  expect_model_error(bad_model("negative_inertia.urdf"), "line 4: <link name=\"base\">/inertial/inertia",
                     "negative principal moment", "check the entries");
}

TEST_CASE("bad URDF: moving joint carrying only a link without inertial", "[bad][urdf]") {
  expect_model_error(bad_model("massless_moving.urdf"), "line 15: <joint name=\"spin\">",
                     "moves only massless bodies", "make the joint fixed");
}

// ---- flexible bodies and prescribed motion ----

TEST_CASE("bad flexible body: zero elements, and a billion, are refused with the limit", "[bad][flexible]") {
  expect_model_error(bad_model("flex_zero_elements.json"), "/bodies/0/flexible/elements",
                     "value 0 is below the smallest allowed, 1", "give a value >= 1");
  expect_model_error(bad_model("flex_billion_elements.json"), "/bodies/0/flexible/elements",
                     "value 1000000000 is above the largest allowed, 200", "give a value <= 200");
}

TEST_CASE("bad flexible body: more modes than the beam has coordinates", "[bad][flexible]") {
  expect_model_error(
      bad_model("flex_too_many_modes.json"), "/bodies/0/flexible/modes",
      "50 modes asked, but the supported beam of body 'beam' has only 9 coordinates (the limit)",
      "ask for at most 9 modes");
}

TEST_CASE("bad flexible body: a node that does not exist, a node of the ground", "[bad][flexible]") {
  expect_model_error(bad_model("flex_node_out_of_range.json"), "/joints/1/parent_node",
                     "node 7 of body 'beam' does not exist", "give a node from 0");
  expect_model_error(bad_model("flex_node_on_ground.json"), "/joints/1/parent_node",
                     "the ground has no nodes", "remove \"parent_node\"");
}

TEST_CASE("bad flexible body: missing section data, a zero-length segment", "[bad][flexible]") {
  expect_model_error(bad_model("flex_spatial_without_J.json"), "/bodies/0/flexible/section",
                     "missing 'J' of the spatial beam of body 'beam'", "give \"J\"");
  expect_model_error(bad_model("flex_zero_length_segment.json"), "/bodies/0/flexible/segments/1",
                     "zero-length beam segment in body 'beam'", "give a positive length");
}

TEST_CASE("bad assumed modes: an expression that does not read, an undefined name, a name that clashes",
          "[bad][flexible][assumed]") {
  expect_model_error(bad_model("flex_assumed_syntax.json"), "/bodies/0/flexible/assumed_modes/0/v",
                     "unclosed '(' in expression\n  sin(pi*x/L\n     ^", "add the matching ')'");
  expect_model_error(bad_model("flex_assumed_unknown_name.json"), "/bodies/0/flexible/assumed_modes/1/v",
                     "unknown name 'y' in expression\n  (y/L)^3\n   ^",
                     "(shape functions also know x, the beam coordinate, and L, the beam length)");
  expect_model_error(bad_model("flex_assumed_parameter_x.json"), "/parameters/x",
                     "parameter 'x' clashes with the beam coordinate x of the assumed modes of body 'beam'",
                     "rename the parameter");
  expect_model_error(bad_model("flex_assumed_not_finite.json"), "/bodies/0/flexible/assumed_modes/1/v",
                     "'v' of assumed mode 2 (beam.mode2) is not a real number (NaN) at x = 0",
                     "make the shape finite on the whole beam");
  expect_model_error(bad_model("flex_assumed_planar_w.json"), "/bodies/0/flexible/assumed_modes/1/w",
                     "a planar beam has no 'w'", "use \"formulation\": \"spatial\"");
}

TEST_CASE("bad elastic initial values: unknown name, body prefix, not a number, unknown key",
          "[bad][flexible][initial]") {
  expect_model_error(
      bad_model("flex_initial_unknown_name.json"), "/bodies/0/flexible/initial/q/n2.theta",
      "body 'beam' has no elastic coordinate 'n2.theta'",
      "did you mean 'n2.theta_z'? Its coordinates are n1.u, n1.v, ..., n3.theta_z (n<node>.<u|v|theta_z> "
      "for each dof the support leaves free)");
  expect_model_error(bad_model("flex_initial_body_prefix.json"), "/bodies/0/flexible/initial/u/beam.mode2",
                     "body 'beam' has no elastic coordinate 'beam.mode2'",
                     "write it without the body prefix: 'mode2'. Its coordinates are mode1, mode2");
  expect_model_error(bad_model("flex_initial_not_a_number.json"), "/bodies/0/flexible/initial/q/n1.v",
                     "wrong type: expected a number, found a string", "write a number");
  expect_model_error(bad_model("flex_initial_unknown_key.json"), "/bodies/0/flexible/initial/speed",
                     "unknown key 'speed'", "");
}

TEST_CASE("bad assumed modes: zero, rigid, dependent, too many", "[bad][flexible][assumed]") {
  expect_model_error(bad_model("flex_assumed_zero.json"), "/bodies/0/flexible/assumed_modes/1",
                     "assumed mode 2 (beam.mode2) is zero at every node of the beam", "or remove it");
  expect_model_error(bad_model("flex_assumed_rigid.json"), "/bodies/0/flexible/assumed_modes/0",
                     "assumed mode 1 (beam.mode1) does not deform the beam (constant u, straight v): it is a "
                     "rigid motion",
                     "bends, stretches or twists the beam (the joints carry the rigid motion)");
  expect_model_error(bad_model("flex_assumed_dependent.json"), "/bodies/0/flexible/assumed_modes/2",
                     "assumed mode 3 (beam.mode3) is linearly dependent on the modes before it: at the nodes "
                     "it is 2 * mode 1 - 0.5 * mode 2",
                     "remove it or change it (the shapes are sampled at the 101 nodes of a mesh of 100");
  expect_model_error(bad_model("flex_assumed_too_many.json"), "/bodies/0/flexible/assumed_modes",
                     "31 assumed modes in body 'beam', more than the limit of 30", "keep the 30");
}

TEST_CASE("bad assumed modes: 'support', 'modes', 'segments' and modal damping do not apply",
          "[bad][flexible][assumed]") {
  expect_model_error(bad_model("flex_assumed_segments.json"), "/bodies/0/flexible/segments",
                     "assumed modes need a straight beam along the body x axis", "give \"length\"");
  expect_model_error(bad_model("flex_assumed_modal_damping.json"), "/bodies/0/flexible/damping",
                     "a modal damping ratio needs the beam's own modes, which assumed modes are not",
                     "use \"rayleigh\": [alpha, beta]");
  expect_model_error(bad_model("flex_assumed_with_support.json"), "/bodies/0/flexible/support",
                     "'support' does not apply with 'assumed_modes'",
                     "remove \"support\": the shape functions carry the boundary conditions");
  expect_model_error(bad_model("flex_assumed_with_modes.json"), "/bodies/0/flexible/modes",
                     "'modes' does not apply with 'assumed_modes'",
                     "remove \"modes\": the amplitudes of the assumed modes are the coordinates");
}

TEST_CASE("bad prescribed motion: an undefined name, a damping that cannot apply", "[bad][prescribed]") {
  expect_model_error(bad_model("prescribed_undefined_name.json"), "/joints/0/prescribed",
                     "unknown name 'Omega'", "define it under /parameters");
  expect_model_error(bad_model("prescribed_with_damping.json"), "/joints/0/damping",
                     "'damping' does not apply to prescribed joint 'hub'", "remove it");
}

// ---- Closed loops ----

TEST_CASE("bad loop: unknown body suggests the nearest", "[bad][loops]") {
  expect_model_error(bad_model("loop_unknown_body.json"), "/loops/0/body2",
                     "loop 'E' names unknown body 'slidr'", "did you mean 'slider'?");
}

TEST_CASE("bad loop: a body tied to itself", "[bad][loops]") {
  expect_model_error(bad_model("loop_self.json"), "/loops/0/body2", "loop 'E' ties body 'rod' to itself",
                     "give two different bodies");
}

TEST_CASE("bad loop: a slider needs its axis", "[bad][loops]") {
  expect_model_error(bad_model("loop_slider_without_axis.json"), "/loops/0",
                     "missing required key 'axis' for a slider",
                     "add \"axis\": the sliding direction in the frame of 'rod'");
}

TEST_CASE("bad loop: a spherical loop joint cannot be planar", "[bad][loops]") {
  expect_model_error(bad_model("loop_spherical_planar.json"), "/loops/0/planar",
                     "a spherical loop joint cannot be planar",
                     "use \"type\": \"revolute\" with \"planar\": true for a hinge of a planar mechanism");
}

TEST_CASE("bad loop: a reaction output of an unknown loop", "[bad][loops]") {
  expect_model_error(bad_model("loop_unknown_reaction.json"), "/outputs/5/loop",
                     "output 'E_reaction' names unknown loop 'e'", "did you mean 'E'?");
}

// ---- URDF read as strictly as JSON: a typo must not change the physics silently ----

TEST_CASE("bad URDF: a misspelt inertia attribute (it zeroed the whole inertia)", "[bad][urdf]") {
  expect_model_error(bad_model("misspelt_inertia_attribute.urdf"),
                     "line 8: <link name=\"arm\">/inertial/inertia", "unknown attribute 'ixxx' of <inertia>",
                     "did you mean 'ixx'?");
}

TEST_CASE("bad URDF: the inertia written as text", "[bad][urdf]") {
  expect_model_error(bad_model("inertia_as_text.urdf"), "line 8: <link name=\"arm\">/inertial/inertia",
                     "<inertia> holds text, which URDF ignores",
                     "give the values as attributes: <inertia ixx=");
}

TEST_CASE("bad URDF: a misspelt <inertial> (it made the link massless)", "[bad][urdf]") {
  expect_model_error(bad_model("misspelt_inertial.urdf"), "line 5: <link name=\"arm\">/inertal",
                     "unknown element <inertal> in <link>", "did you mean 'inertial'?");
}

TEST_CASE("bad URDF: an inertia entry that is not a number", "[bad][urdf]") {
  expect_model_error(bad_model("inertia_not_a_number.urdf"),
                     "line 7: <link name=\"arm\">/inertial/inertia/ixx", "'0,1' is not a number",
                     "as a number");
}

TEST_CASE("bad URDF: an unknown element in a joint", "[bad][urdf]") {
  expect_model_error(bad_model("misspelt_joint_child.urdf"), "line 13: <joint name=\"j1\">/axsi",
                     "unknown element <axsi> in <joint>", "origin, parent, child, axis");
}

// ---- physical conditions of values given by expressions, at load and for other values ----

TEST_CASE("bad parameter: a negative mass through a parameter is refused at load", "[bad][parameters]") {
  expect_model_error(bad_model("negative_mass_expression.json"), "/bodies/0/mass",
                     "negative mass (m1 = -1.2) of body 'a'", "check m1 under /parameters");
}

TEST_CASE("bad parameter: a negative izz written as an expression is refused at load", "[bad][parameters]") {
  expect_model_error(
      bad_model("negative_izz_expression.json"), "/bodies/0/inertia",
      "inertia of body 'a' has a negative principal moment (principal moments -0.0416667, "
      "0.0416667, 0.0416667; ixx = m1*l1^2/12, iyy = m1*l1^2/12, izz = k*m1*l1^2/12 with m1 = 2, "
      "l1 = 0.5, k = -1)",
      "ixx, iyy, izz are positive");
}

TEST_CASE("check_parameter_values: other values of a valid model, as --set gives them", "[bad][parameters]") {
  const std::string file = kanegen::model::test::source_path("models/double_pendulum.json");
  const kanegen::model::Model m = kanegen::model::load_model(file);
  kanegen::model::ParameterValues values = kanegen::model::default_parameter_values(m);
  CHECK_NOTHROW(kanegen::model::check_parameter_values(m, values, "from --set"));
  values["m2"] = -0.5;
  try {
    kanegen::model::check_parameter_values(m, values, "from --set");
    FAIL("no error for m2 = -0.5");
  } catch (const kanegen::model::ModelError& e) {
    CHECK(e.file() == file);
    CHECK(e.place() == "/bodies/1/mass");
    CHECK_THAT(e.what(), Catch::Contains("negative mass (m2 = -0.5 from --set) of body 'link2'") &&
                             Catch::Contains("check m2 in --set"));
  }
}

TEST_CASE("check_parameter_values: the triangle inequality of the principal moments", "[bad][parameters]") {
  kanegen::model::Model m;
  m.source_file = "made.json";
  m.parameters = {{"a", 1.0, "/parameters/a"}};
  kanegen::model::Body b;
  b.name = "plate";
  b.where = "/bodies/0";
  b.mass = kanegen::model::Scalar::number(1.0, "/bodies/0/mass");
  const char* entries[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
  for (int k = 0; k < 6; ++k)
    b.inertia[k] = kanegen::model::Scalar::number(0.0, "/bodies/0/inertia/" + std::string(entries[k]));
  b.inertia[0] = kanegen::model::Scalar::number(1.0, "/bodies/0/inertia/ixx");
  b.inertia[1] = kanegen::model::Scalar::number(1.0, "/bodies/0/inertia/iyy");
  b.inertia[2] = kanegen::model::Scalar::expression("a", "/bodies/0/inertia/izz");
  m.bodies.push_back(b);
  CHECK_NOTHROW(
      kanegen::model::check_parameter_values(m, {{"a", 2.0}}, "from --set"));  // 1 + 1 = 2: a flat plate
  try {
    kanegen::model::check_parameter_values(m, {{"a", 2.5}}, "from --set");
    FAIL("no error for izz = 2.5 > ixx + iyy");
  } catch (const kanegen::model::ModelError& e) {
    CHECK(e.place() == "/bodies/0/inertia");
    CHECK_THAT(e.what(), Catch::Contains("violates the triangle inequality") &&
                             Catch::Contains("izz = a with a = 2.5 from --set"));
  }
}
