// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/model_description.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "fmu/xml_text.hpp"

namespace kanegen::fmu {

namespace {

const char* causality_name(Causality c) {
  switch (c) {
    case Causality::independent:
      return "independent";
    case Causality::parameter:
      return "parameter";
    case Causality::local:
      return "local";
    case Causality::input:
      return "input";
    case Causality::output:
      return "output";
  }
  return "local";
}

/// A start value that reads back as the same double; non-finite values have no place in the XML.
std::string number(double value, const std::string& what) {
  if (!std::isfinite(value))
    throw std::runtime_error(what + " is " + std::to_string(value) +
                             "; an FMU's start values must be finite");
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string attribute(const char* name, const std::string& escaped) {
  return std::string(" ") + name + "=\"" + escaped + "\"";
}

std::string what(const Variable& v) { return "the " + v.description + " name '" + v.name + "'"; }

// The attributes a variable has in both versions (name, valueReference, causality, variability, initial).
std::string common_attributes(const Variable& v) {
  std::string out = attribute("name", xml_attribute(v.name, what(v))) +
                    attribute("valueReference", std::to_string(v.value_reference)) +
                    attribute("causality", causality_name(v.causality)) +
                    attribute("variability", v.variability);
  if (*v.initial) out += attribute("initial", v.initial);
  return out;
}

// The attributes of FMI 2.0's <Real> or of FMI 3.0's <Float64>: unit, start, derivative (an index in FMI
// 2.0, 1-based; a value reference in FMI 3.0).
std::string value_attributes(const FmuVariables& variables, const Variable& v, int fmi_version) {
  std::string out;
  if (!v.unit.empty()) out += attribute("unit", v.unit);
  if (v.derivative_of >= 0) {
    const Variable& state = variables.all[static_cast<std::size_t>(v.derivative_of)];
    out += attribute(
        "derivative",
        std::to_string(fmi_version == 2 ? v.derivative_of + 1 : static_cast<int>(state.value_reference)));
  }
  if (v.has_start) out += attribute("start", number(v.start, "the start value of " + what(v)));
  return out;
}

std::string unit_definitions(const FmuVariables& variables) {
  const std::vector<UnitDefinition> units = units_used(variables);
  if (units.empty()) return "";
  std::string out = "  <UnitDefinitions>\n";
  for (const UnitDefinition& u : units) {
    out += "    <Unit name=\"" + std::string(u.name) + "\"><BaseUnit";
    const std::pair<const char*, int> exponents[] = {{"kg", u.kg}, {"m", u.m}, {"s", u.s}, {"rad", u.rad}};
    for (const auto& [base, exponent] : exponents)
      if (exponent != 0) out += attribute(base, std::to_string(exponent));
    out += "/></Unit>\n";
  }
  return out + "  </UnitDefinitions>\n";
}

// The parts after the interfaces, the same in both versions but for the variables.
std::string common_parts(const FmuVariables& variables) {
  return unit_definitions(variables) +
         "  <LogCategories>\n"
         "    <Category name=\"logEvents\" description=\"what the FMU did (loops assembled)\"/>\n"
         "    <Category name=\"logStatusError\" description=\"why a call failed\"/>\n"
         "  </LogCategories>\n"
         "  <DefaultExperiment startTime=\"0\" stopTime=\"1\" stepSize=\"0.01\"/>\n";
}

// Which variables FMI lists as initial unknowns (FMI 2.0 3.3.1 / 3.0 2.4.8.3): the outputs, and the
// states and derivatives whose initial is approx or calculated.
std::vector<int> initial_unknowns(const FmuVariables& variables) {
  std::vector<int> out;
  for (std::size_t i = 0; i < variables.all.size(); ++i) {
    const Variable& v = variables.all[i];
    const bool computed = std::string(v.initial) == "approx" || std::string(v.initial) == "calculated";
    if (v.causality == Causality::output || (v.causality == Causality::local && computed))
      out.push_back(static_cast<int>(i));
  }
  return out;
}

std::string header(const ModelFacts& facts, const DescriptionOptions& o, const char* token_attribute) {
  const std::string description = "kanegen model " + facts.identifier +
                                  ": equations of motion by Kane's method" +
                                  (o.co_simulation ? "; co-simulation by " + o.integrator : std::string());
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription" +
         attribute("fmiVersion", o.fmi_version == 2 ? "2.0" : "3.0") +
         attribute("modelName", xml_attribute(facts.identifier, "the model name")) +
         attribute(token_attribute, xml_attribute(o.token, "the token")) +
         attribute("description", xml_attribute(description, "the description")) +
         attribute("generationTool", xml_attribute(o.generation_tool, "the generation tool")) +
         attribute("variableNamingConvention", "flat");
}

std::string fmi2_source_files(const DescriptionOptions& o) {
  std::string out = "    <SourceFiles>\n";
  for (const std::string& file : o.source_files)
    out += "      <File" + attribute("name", xml_attribute(file, "a source file")) + "/>\n";
  return out + "    </SourceFiles>\n";
}

std::string fmi2(const ModelFacts& facts, const FmuVariables& variables, const DescriptionOptions& o) {
  const std::string id =
      attribute("modelIdentifier", xml_attribute(facts.identifier, "the model identifier"));
  const std::string capabilities =
      " canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\""
      " canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"";
  std::string out = header(facts, o, "guid") + " numberOfEventIndicators=\"0\">\n";
  if (o.model_exchange)
    out += "  <ModelExchange" + id + capabilities + " completedIntegratorStepNotNeeded=\"false\">\n" +
           fmi2_source_files(o) + "  </ModelExchange>\n";
  if (o.co_simulation)
    out += "  <CoSimulation" + id + capabilities + " canHandleVariableCommunicationStepSize=\"true\">\n" +
           fmi2_source_files(o) + "  </CoSimulation>\n";
  out += common_parts(variables) + "  <ModelVariables>\n";
  for (std::size_t i = 0; i < variables.all.size(); ++i) {
    const Variable& v = variables.all[i];
    out += "    <!-- index " + std::to_string(i + 1) + " -->\n    <ScalarVariable" + common_attributes(v) +
           ">\n      <Real" + value_attributes(variables, v, 2) + "/>\n    </ScalarVariable>\n";
  }
  out += "  </ModelVariables>\n  <ModelStructure>\n";
  const auto unknowns = [&](const char* element, const std::vector<int>& indices) {
    if (indices.empty()) return;
    out += std::string("    <") + element + ">\n";
    for (int index : indices) out += "      <Unknown index=\"" + std::to_string(index + 1) + "\"/>\n";
    out += std::string("    </") + element + ">\n";
  };
  unknowns("Outputs", variables.outputs);
  unknowns("Derivatives", variables.derivatives);
  unknowns("InitialUnknowns", initial_unknowns(variables));
  return out + "  </ModelStructure>\n</fmiModelDescription>\n";
}

std::string fmi3(const ModelFacts& facts, const FmuVariables& variables, const DescriptionOptions& o) {
  const std::string id =
      attribute("modelIdentifier", xml_attribute(facts.identifier, "the model identifier"));
  const std::string capabilities =
      " canGetAndSetFMUState=\"false\" canSerializeFMUState=\"false\""
      " providesDirectionalDerivatives=\"false\"";
  std::string out = header(facts, o, "instantiationToken") + ">\n";
  if (o.model_exchange)
    out += "  <ModelExchange" + id + capabilities + " needsCompletedIntegratorStep=\"true\"/>\n";
  if (o.co_simulation)
    out += "  <CoSimulation" + id + capabilities +
           " canHandleVariableCommunicationStepSize=\"true\" hasEventMode=\"false\"/>\n";
  out += common_parts(variables) + "  <ModelVariables>\n";
  for (const Variable& v : variables.all)
    out += "    <Float64" + common_attributes(v) + value_attributes(variables, v, 3) + "/>\n";
  out += "  </ModelVariables>\n  <ModelStructure>\n";
  const auto unknowns = [&](const char* element, const std::vector<int>& indices) {
    for (int index : indices)
      out += std::string("    <") + element + " valueReference=\"" +
             std::to_string(variables.all[static_cast<std::size_t>(index)].value_reference) + "\"/>\n";
  };
  unknowns("Output", variables.outputs);
  unknowns("ContinuousStateDerivative", variables.derivatives);
  unknowns("InitialUnknown", initial_unknowns(variables));
  return out + "  </ModelStructure>\n</fmiModelDescription>\n";
}

}  // namespace

std::string model_description(const ModelFacts& facts, const FmuVariables& variables,
                              const DescriptionOptions& options) {
  if (options.fmi_version != 2 && options.fmi_version != 3)
    throw std::invalid_argument("FMI version " + std::to_string(options.fmi_version) + ": 2 or 3");
  return options.fmi_version == 2 ? fmi2(facts, variables, options) : fmi3(facts, variables, options);
}

std::string build_description(const ModelFacts& facts, const DescriptionOptions& options) {
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiBuildDescription fmiVersion=\"3.0\">\n  "
      "<BuildConfiguration" +
      attribute("modelIdentifier", xml_attribute(facts.identifier, "the model identifier")) +
      " description=\"the model's kernels, the kanegen runtime and the FMI wrapper, C++17\">\n"
      "    <SourceFileSet language=\"C++17\">\n";
  for (const std::string& file : options.source_files)
    out += "      <SourceFile" + attribute("name", xml_attribute(file, "a source file")) + "/>\n";
  return out +
         "      <IncludeDirectory name=\".\"/>\n    </SourceFileSet>\n  "
         "</BuildConfiguration>\n</fmiBuildDescription>\n";
}

}  // namespace kanegen::fmu
