// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
// The FMI 3.0 functions (model exchange and co-simulation) over fmu_instance.hpp. No exception leaves an
// FMI function: a failure is logged through the importer's callback and returned as fmi3Error.
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "fmu_instance.hpp"
#include "kanegen_fmi3.h"

namespace {

struct Component {
  std::string name;
  bool model_exchange;
  fmi3InstanceEnvironment environment;
  fmi3LogMessageCallback logger;
  bool logging;
  std::unique_ptr<kanegen_fmu::Instance> instance;
};

Component* component(fmi3Instance c) { return static_cast<Component*>(c); }

void log(const Component* c, fmi3Status status, const char* category, const std::string& message) {
  if (c == nullptr || c->logger == nullptr) return;
  if (status == fmi3OK && !c->logging) return;
  c->logger(c->environment, status, category, message.c_str());
}

template <class Body>
fmi3Status guarded(fmi3Instance c, const char* function, Body body) {
  Component* self = component(c);
  if (self == nullptr) return fmi3Error;
  try {
    return body(*self->instance) ? fmi3OK : fmi3Error;
  } catch (const std::exception& e) {
    log(self, fmi3Error, "logStatusError", std::string(function) + ": " + e.what());
  } catch (...) {
    log(self, fmi3Error, "logStatusError", std::string(function) + ": unknown error");
  }
  return fmi3Error;
}

fmi3Status unsupported(fmi3Instance c, const char* function) {
  log(component(c), fmi3Error, "logStatusError", std::string(function) + " is not supported by this FMU");
  return fmi3Error;
}

// Every variable is a scalar: as many values as value references.
bool scalars_only(kanegen_fmu::Instance& i) {
  i.log_error("nValues differs from nValueReferences, and every variable of this FMU is a scalar");
  return false;
}

fmi3Instance instantiate(fmi3String instanceName, fmi3String token, bool model_exchange,
                         fmi3Boolean loggingOn, fmi3InstanceEnvironment environment,
                         fmi3LogMessageCallback logger) {
  auto self = std::unique_ptr<Component>(new (std::nothrow) Component{
      instanceName ? instanceName : "", model_exchange, environment, logger, loggingOn, nullptr});
  if (!self) return nullptr;
  if (token == nullptr || std::strcmp(token, kanegen_fmu::settings().token) != 0) {
    log(self.get(), fmi3Error, "logStatusError",
        "instantiate: the instantiationToken is not this FMU's (a modelDescription.xml of another export?)");
    return nullptr;
  }
  try {
    Component* raw = self.get();
    self->instance = std::make_unique<kanegen_fmu::Instance>([raw](bool error, const std::string& message) {
      log(raw, error ? fmi3Error : fmi3OK, error ? "logStatusError" : "logEvents", message);
    });
  } catch (const std::exception& e) {
    log(self.get(), fmi3Error, "logStatusError", std::string("instantiate: ") + e.what());
    return nullptr;
  }
  return self.release();
}

}  // namespace

extern "C" {

const char* KANEGEN_FMI3_NAME(fmi3GetVersion)(void) { return "3.0"; }

fmi3Status KANEGEN_FMI3_NAME(fmi3SetDebugLogging)(fmi3Instance c, fmi3Boolean loggingOn, size_t,
                                                  const fmi3String[]) {
  if (c == nullptr) return fmi3Error;
  component(c)->logging = loggingOn;
  return fmi3OK;
}

fmi3Instance KANEGEN_FMI3_NAME(fmi3InstantiateModelExchange)(fmi3String instanceName,
                                                             fmi3String instantiationToken, fmi3String,
                                                             fmi3Boolean, fmi3Boolean loggingOn,
                                                             fmi3InstanceEnvironment instanceEnvironment,
                                                             fmi3LogMessageCallback logMessage) {
  return instantiate(instanceName, instantiationToken, true, loggingOn, instanceEnvironment, logMessage);
}

fmi3Instance KANEGEN_FMI3_NAME(fmi3InstantiateCoSimulation)(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String, fmi3Boolean, fmi3Boolean loggingOn,
    fmi3Boolean eventModeUsed, fmi3Boolean, const fmi3ValueReference[], size_t,
    fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,
    fmi3IntermediateUpdateCallback) {
  if (eventModeUsed) {  // hasEventMode="false" in modelDescription.xml; the importer should not ask
    if (logMessage)
      logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                 "fmi3InstantiateCoSimulation: this FMU has no event mode in co-simulation");
    return nullptr;
  }
  return instantiate(instanceName, instantiationToken, false, loggingOn, instanceEnvironment, logMessage);
}

fmi3Instance KANEGEN_FMI3_NAME(fmi3InstantiateScheduledExecution)(
    fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean, fmi3InstanceEnvironment,
    fmi3LogMessageCallback, fmi3ClockUpdateCallback, fmi3LockPreemptionCallback,
    fmi3UnlockPreemptionCallback) {
  return nullptr;  // not a scheduled-execution FMU (modelDescription.xml says so)
}

void KANEGEN_FMI3_NAME(fmi3FreeInstance)(fmi3Instance c) { delete component(c); }

fmi3Status KANEGEN_FMI3_NAME(fmi3EnterInitializationMode)(fmi3Instance c, fmi3Boolean, fmi3Float64,
                                                          fmi3Float64 startTime, fmi3Boolean, fmi3Float64) {
  return guarded(c, "fmi3EnterInitializationMode", [&](kanegen_fmu::Instance& i) {
    i.enter_initialization(startTime);
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3ExitInitializationMode)(fmi3Instance c) {
  return guarded(c, "fmi3ExitInitializationMode",
                 [](kanegen_fmu::Instance& i) { return i.exit_initialization(); });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3EnterEventMode)(fmi3Instance c) { return c ? fmi3OK : fmi3Error; }
fmi3Status KANEGEN_FMI3_NAME(fmi3Terminate)(fmi3Instance c) { return c ? fmi3OK : fmi3Error; }

fmi3Status KANEGEN_FMI3_NAME(fmi3Reset)(fmi3Instance c) {
  return guarded(c, "fmi3Reset", [](kanegen_fmu::Instance& i) {
    i.reset();
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetFloat64)(fmi3Instance c, const fmi3ValueReference valueReferences[],
                                             size_t nValueReferences, fmi3Float64 values[], size_t nValues) {
  return guarded(c, "fmi3GetFloat64", [&](kanegen_fmu::Instance& i) {
    if (nValues != nValueReferences) return scalars_only(i);
    for (size_t k = 0; k < nValueReferences; ++k)
      if (!i.get(valueReferences[k], &values[k])) return false;
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3SetFloat64)(fmi3Instance c, const fmi3ValueReference valueReferences[],
                                             size_t nValueReferences, const fmi3Float64 values[],
                                             size_t nValues) {
  return guarded(c, "fmi3SetFloat64", [&](kanegen_fmu::Instance& i) {
    if (nValues != nValueReferences) return scalars_only(i);
    for (size_t k = 0; k < nValueReferences; ++k)
      if (!i.set(valueReferences[k], values[k])) return false;
    return true;
  });
}

// The FMU has Float64 variables only: the other types have no value references (none asked: fine).
#define KANEGEN_FMI3_NO_VALUES(Type, CType)                                                                  \
  fmi3Status KANEGEN_FMI3_NAME(fmi3Get##Type)(fmi3Instance c, const fmi3ValueReference[], size_t n, CType[], \
                                              size_t) {                                                      \
    return n == 0 ? fmi3OK : unsupported(c, "fmi3Get" #Type);                                                \
  }                                                                                                          \
  fmi3Status KANEGEN_FMI3_NAME(fmi3Set##Type)(fmi3Instance c, const fmi3ValueReference[], size_t n,          \
                                              const CType[], size_t) {                                       \
    return n == 0 ? fmi3OK : unsupported(c, "fmi3Set" #Type);                                                \
  }
KANEGEN_FMI3_NO_VALUES(Float32, fmi3Float32)
KANEGEN_FMI3_NO_VALUES(Int8, fmi3Int8)
KANEGEN_FMI3_NO_VALUES(UInt8, fmi3UInt8)
KANEGEN_FMI3_NO_VALUES(Int16, fmi3Int16)
KANEGEN_FMI3_NO_VALUES(UInt16, fmi3UInt16)
KANEGEN_FMI3_NO_VALUES(Int32, fmi3Int32)
KANEGEN_FMI3_NO_VALUES(UInt32, fmi3UInt32)
KANEGEN_FMI3_NO_VALUES(Int64, fmi3Int64)
KANEGEN_FMI3_NO_VALUES(UInt64, fmi3UInt64)
KANEGEN_FMI3_NO_VALUES(Boolean, fmi3Boolean)
KANEGEN_FMI3_NO_VALUES(String, fmi3String)
#undef KANEGEN_FMI3_NO_VALUES

// Functions of capabilities this FMU does not declare: an error, whatever the arguments.
#define KANEGEN_FMI3_UNSUPPORTED(name, parameters) \
  fmi3Status KANEGEN_FMI3_NAME(name) parameters { return unsupported(instance, #name); }
KANEGEN_FMI3_UNSUPPORTED(fmi3GetBinary, (fmi3Instance instance, const fmi3ValueReference[], size_t, size_t[],
                                         fmi3Binary[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetBinary, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                         const size_t[], const fmi3Binary[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetClock,
                         (fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3Clock[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetClock,
                         (fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Clock[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetNumberOfVariableDependencies,
                         (fmi3Instance instance, fmi3ValueReference, size_t*))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetVariableDependencies,
                         (fmi3Instance instance, fmi3ValueReference, size_t[], fmi3ValueReference[], size_t[],
                          fmi3DependencyKind[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetFMUState, (fmi3Instance instance, fmi3FMUState*))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetFMUState, (fmi3Instance instance, fmi3FMUState))
KANEGEN_FMI3_UNSUPPORTED(fmi3FreeFMUState, (fmi3Instance instance, fmi3FMUState*))
KANEGEN_FMI3_UNSUPPORTED(fmi3SerializedFMUStateSize, (fmi3Instance instance, fmi3FMUState, size_t*))
KANEGEN_FMI3_UNSUPPORTED(fmi3SerializeFMUState, (fmi3Instance instance, fmi3FMUState, fmi3Byte[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3DeserializeFMUState,
                         (fmi3Instance instance, const fmi3Byte[], size_t, fmi3FMUState*))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetDirectionalDerivative, (fmi3Instance instance, const fmi3ValueReference[],
                                                        size_t, const fmi3ValueReference[], size_t,
                                                        const fmi3Float64[], size_t, fmi3Float64[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetAdjointDerivative, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                    const fmi3ValueReference[], size_t, const fmi3Float64[],
                                                    size_t, fmi3Float64[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3EnterConfigurationMode, (fmi3Instance instance))
KANEGEN_FMI3_UNSUPPORTED(fmi3ExitConfigurationMode, (fmi3Instance instance))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetIntervalDecimal, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                  fmi3Float64[], fmi3IntervalQualifier[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetIntervalFraction, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                   fmi3UInt64[], fmi3UInt64[], fmi3IntervalQualifier[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetShiftDecimal,
                         (fmi3Instance instance, const fmi3ValueReference[], size_t, fmi3Float64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetShiftFraction, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                fmi3UInt64[], fmi3UInt64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetIntervalDecimal,
                         (fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Float64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetIntervalFraction, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                   const fmi3UInt64[], const fmi3UInt64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetShiftDecimal,
                         (fmi3Instance instance, const fmi3ValueReference[], size_t, const fmi3Float64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3SetShiftFraction, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                const fmi3UInt64[], const fmi3UInt64[]))
KANEGEN_FMI3_UNSUPPORTED(fmi3GetOutputDerivatives, (fmi3Instance instance, const fmi3ValueReference[], size_t,
                                                    const fmi3Int32[], fmi3Float64[], size_t))
KANEGEN_FMI3_UNSUPPORTED(fmi3ActivateModelPartition, (fmi3Instance instance, fmi3ValueReference, fmi3Float64))
#undef KANEGEN_FMI3_UNSUPPORTED

fmi3Status KANEGEN_FMI3_NAME(fmi3EvaluateDiscreteStates)(fmi3Instance c) { return c ? fmi3OK : fmi3Error; }

fmi3Status KANEGEN_FMI3_NAME(fmi3UpdateDiscreteStates)(fmi3Instance c, fmi3Boolean* discreteStatesNeedUpdate,
                                                       fmi3Boolean* terminateSimulation,
                                                       fmi3Boolean* nominalsOfContinuousStatesChanged,
                                                       fmi3Boolean* valuesOfContinuousStatesChanged,
                                                       fmi3Boolean* nextEventTimeDefined,
                                                       fmi3Float64* nextEventTime) {
  return guarded(c, "fmi3UpdateDiscreteStates", [&](kanegen_fmu::Instance& i) {
    bool changed = false;
    const bool ok = i.project(&changed);  // the only event: the loops' drift (fmi3CompletedIntegratorStep)
    *discreteStatesNeedUpdate = false;
    *terminateSimulation = !ok;
    *nominalsOfContinuousStatesChanged = false;
    *valuesOfContinuousStatesChanged = changed;
    *nextEventTimeDefined = false;
    *nextEventTime = 0.0;
    return ok;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3EnterContinuousTimeMode)(fmi3Instance c) { return c ? fmi3OK : fmi3Error; }

fmi3Status KANEGEN_FMI3_NAME(fmi3CompletedIntegratorStep)(fmi3Instance c, fmi3Boolean,
                                                          fmi3Boolean* enterEventMode,
                                                          fmi3Boolean* terminateSimulation) {
  return guarded(c, "fmi3CompletedIntegratorStep", [&](kanegen_fmu::Instance& i) {
    *enterEventMode = i.drifted();
    *terminateSimulation = false;
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3SetTime)(fmi3Instance c, fmi3Float64 time) {
  return guarded(c, "fmi3SetTime", [&](kanegen_fmu::Instance& i) {
    i.set_time(time);
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3SetContinuousStates)(fmi3Instance c, const fmi3Float64 continuousStates[],
                                                      size_t nContinuousStates) {
  return guarded(c, "fmi3SetContinuousStates", [&](kanegen_fmu::Instance& i) {
    if (nContinuousStates != static_cast<size_t>(i.state_count())) return false;
    i.set_states(continuousStates);
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetContinuousStateDerivatives)(fmi3Instance c, fmi3Float64 derivatives[],
                                                                size_t nContinuousStates) {
  return guarded(c, "fmi3GetContinuousStateDerivatives", [&](kanegen_fmu::Instance& i) {
    return nContinuousStates == static_cast<size_t>(i.state_count()) && i.derivatives(derivatives);
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetEventIndicators)(fmi3Instance c, fmi3Float64[], size_t nEventIndicators) {
  return nEventIndicators == 0 && c ? fmi3OK : unsupported(c, "fmi3GetEventIndicators with indicators");
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetContinuousStates)(fmi3Instance c, fmi3Float64 continuousStates[],
                                                      size_t nContinuousStates) {
  return guarded(c, "fmi3GetContinuousStates", [&](kanegen_fmu::Instance& i) {
    if (nContinuousStates != static_cast<size_t>(i.state_count())) return false;
    i.get_states(continuousStates);
    return true;
  });
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetNominalsOfContinuousStates)(fmi3Instance c, fmi3Float64 nominals[],
                                                                size_t nContinuousStates) {
  if (c == nullptr) return fmi3Error;
  for (size_t k = 0; k < nContinuousStates; ++k) nominals[k] = 1.0;
  return fmi3OK;
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetNumberOfEventIndicators)(fmi3Instance c, size_t* nEventIndicators) {
  if (c == nullptr) return fmi3Error;
  *nEventIndicators = 0;
  return fmi3OK;
}

fmi3Status KANEGEN_FMI3_NAME(fmi3GetNumberOfContinuousStates)(fmi3Instance c, size_t* nContinuousStates) {
  if (c == nullptr) return fmi3Error;
  *nContinuousStates = static_cast<size_t>(component(c)->instance->state_count());
  return fmi3OK;
}

fmi3Status KANEGEN_FMI3_NAME(fmi3EnterStepMode)(fmi3Instance c) { return c ? fmi3OK : fmi3Error; }

fmi3Status KANEGEN_FMI3_NAME(fmi3DoStep)(fmi3Instance c, fmi3Float64 currentCommunicationPoint,
                                         fmi3Float64 communicationStepSize, fmi3Boolean,
                                         fmi3Boolean* eventHandlingNeeded, fmi3Boolean* terminateSimulation,
                                         fmi3Boolean* earlyReturn, fmi3Float64* lastSuccessfulTime) {
  return guarded(c, "fmi3DoStep", [&](kanegen_fmu::Instance& i) {
    const bool ok = i.do_step(currentCommunicationPoint, communicationStepSize);
    *eventHandlingNeeded = false;
    *terminateSimulation = !ok;
    *earlyReturn = false;
    *lastSuccessfulTime = i.time();
    return ok;
  });
}

}  // extern "C"
