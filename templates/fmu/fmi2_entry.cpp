// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
// The FMI 2.0 functions (model exchange and co-simulation) over fmu_instance.hpp. No exception leaves an
// FMI function: a failure is logged through the importer's logger and returned as fmi2Error.
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "fmu_instance.hpp"
#include "kanegen_fmi2.h"

namespace {

struct Component {
  std::string name;
  fmi2Type type;
  fmi2CallbackFunctions callbacks;
  bool logging;
  std::unique_ptr<kanegen_fmu::Instance> instance;
  bool in_event_mode = false;
};

Component* component(fmi2Component c) { return static_cast<Component*>(c); }

void log(const Component* c, fmi2Status status, const char* category, const std::string& message) {
  if (c == nullptr || c->callbacks.logger == nullptr) return;
  if (status == fmi2OK && !c->logging) return;
  c->callbacks.logger(c->callbacks.componentEnvironment, c->name.c_str(), status, category, "%s",
                      message.c_str());
}

// Runs `body` on the instance; an exception is logged and becomes fmi2Error.
template <class Body>
fmi2Status guarded(fmi2Component c, const char* function, Body body) {
  Component* self = component(c);
  if (self == nullptr) return fmi2Error;
  try {
    return body(*self, *self->instance) ? fmi2OK : fmi2Error;
  } catch (const std::exception& e) {
    log(self, fmi2Error, "logStatusError", std::string(function) + ": " + e.what());
  } catch (...) {
    log(self, fmi2Error, "logStatusError", std::string(function) + ": unknown error");
  }
  return fmi2Error;
}

fmi2Status unsupported(fmi2Component c, const char* function) {
  log(component(c), fmi2Error, "logStatusError", std::string(function) + " is not supported by this FMU");
  return fmi2Error;
}

}  // namespace

extern "C" {

const char* KANEGEN_FMI2_NAME(fmi2GetTypesPlatform)(void) { return "default"; }
const char* KANEGEN_FMI2_NAME(fmi2GetVersion)(void) { return "2.0"; }

fmi2Status KANEGEN_FMI2_NAME(fmi2SetDebugLogging)(fmi2Component c, fmi2Boolean loggingOn, size_t,
                                                  const fmi2String[]) {
  if (c == nullptr) return fmi2Error;
  component(c)->logging = loggingOn != fmi2False;
  return fmi2OK;
}

fmi2Component KANEGEN_FMI2_NAME(fmi2Instantiate)(fmi2String instanceName, fmi2Type fmuType,
                                                 fmi2String fmuGUID, fmi2String,
                                                 const fmi2CallbackFunctions* functions, fmi2Boolean,
                                                 fmi2Boolean loggingOn) {
  if (functions == nullptr) return nullptr;
  auto self = std::unique_ptr<Component>(new (std::nothrow) Component{
      instanceName ? instanceName : "", fmuType, *functions, loggingOn != fmi2False, nullptr, false});
  if (!self) return nullptr;
  if (fmuGUID == nullptr || std::strcmp(fmuGUID, kanegen_fmu::settings().token) != 0) {
    log(self.get(), fmi2Error, "logStatusError",
        "fmi2Instantiate: the GUID is not this FMU's (a modelDescription.xml of another export?)");
    return nullptr;
  }
  try {
    Component* raw = self.get();
    self->instance = std::make_unique<kanegen_fmu::Instance>([raw](bool error, const std::string& message) {
      log(raw, error ? fmi2Error : fmi2OK, error ? "logStatusError" : "logEvents", message);
    });
  } catch (const std::exception& e) {
    log(self.get(), fmi2Error, "logStatusError", std::string("fmi2Instantiate: ") + e.what());
    return nullptr;
  }
  return self.release();
}

void KANEGEN_FMI2_NAME(fmi2FreeInstance)(fmi2Component c) { delete component(c); }

fmi2Status KANEGEN_FMI2_NAME(fmi2SetupExperiment)(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime,
                                                  fmi2Boolean, fmi2Real) {
  return guarded(c, "fmi2SetupExperiment", [&](Component&, kanegen_fmu::Instance& i) {
    i.enter_initialization(startTime);
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2EnterInitializationMode)(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", [](Component&, kanegen_fmu::Instance&) { return true; });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2ExitInitializationMode)(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", [](Component& self, kanegen_fmu::Instance& i) {
    if (!i.exit_initialization()) return false;
    self.in_event_mode = self.type == fmi2ModelExchange;  // ME continues in event mode
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2Terminate)(fmi2Component c) { return c ? fmi2OK : fmi2Error; }

fmi2Status KANEGEN_FMI2_NAME(fmi2Reset)(fmi2Component c) {
  return guarded(c, "fmi2Reset", [](Component&, kanegen_fmu::Instance& i) {
    i.reset();
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetReal)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                          fmi2Real value[]) {
  return guarded(c, "fmi2GetReal", [&](Component&, kanegen_fmu::Instance& i) {
    for (size_t k = 0; k < nvr; ++k)
      if (!i.get(vr[k], &value[k])) return false;
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2SetReal)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                          const fmi2Real value[]) {
  return guarded(c, "fmi2SetReal", [&](Component&, kanegen_fmu::Instance& i) {
    for (size_t k = 0; k < nvr; ++k)
      if (!i.set(vr[k], value[k])) return false;
    return true;
  });
}

// The FMU has Real variables only: any other type's value reference is unknown (none asked: fine).
#define KANEGEN_FMI2_NO_VALUES(Type, CType)                                                            \
  fmi2Status KANEGEN_FMI2_NAME(fmi2Get##Type)(fmi2Component c, const fmi2ValueReference[], size_t nvr, \
                                              CType[]) {                                               \
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2Get" #Type);                                        \
  }                                                                                                    \
  fmi2Status KANEGEN_FMI2_NAME(fmi2Set##Type)(fmi2Component c, const fmi2ValueReference[], size_t nvr, \
                                              const CType[]) {                                         \
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2Set" #Type);                                        \
  }
KANEGEN_FMI2_NO_VALUES(Integer, fmi2Integer)
KANEGEN_FMI2_NO_VALUES(Boolean, fmi2Boolean)
KANEGEN_FMI2_NO_VALUES(String, fmi2String)
#undef KANEGEN_FMI2_NO_VALUES

fmi2Status KANEGEN_FMI2_NAME(fmi2GetFMUstate)(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2GetFMUstate");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2SetFMUstate)(fmi2Component c, fmi2FMUstate) {
  return unsupported(c, "fmi2SetFMUstate");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2FreeFMUstate)(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2FreeFMUstate");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2SerializedFMUstateSize)(fmi2Component c, fmi2FMUstate, size_t*) {
  return unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2SerializeFMUstate)(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2DeSerializeFMUstate)(fmi2Component c, const fmi2Byte[], size_t,
                                                      fmi2FMUstate*) {
  return unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2GetDirectionalDerivative)(fmi2Component c, const fmi2ValueReference[],
                                                           size_t, const fmi2ValueReference[], size_t,
                                                           const fmi2Real[], fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative");
}

// Model exchange.

fmi2Status KANEGEN_FMI2_NAME(fmi2EnterEventMode)(fmi2Component c) {
  return guarded(c, "fmi2EnterEventMode", [](Component& self, kanegen_fmu::Instance&) {
    self.in_event_mode = true;
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2NewDiscreteStates)(fmi2Component c, fmi2EventInfo* info) {
  return guarded(c, "fmi2NewDiscreteStates", [&](Component&, kanegen_fmu::Instance& i) {
    bool changed = false;
    const bool ok = i.project(&changed);  // the only event: the loops' drift (fmi2CompletedIntegratorStep)
    info->newDiscreteStatesNeeded = fmi2False;
    info->terminateSimulation = ok ? fmi2False : fmi2True;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = changed ? fmi2True : fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0.0;
    return ok;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2EnterContinuousTimeMode)(fmi2Component c) {
  return guarded(c, "fmi2EnterContinuousTimeMode", [](Component& self, kanegen_fmu::Instance&) {
    self.in_event_mode = false;
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2CompletedIntegratorStep)(fmi2Component c, fmi2Boolean,
                                                          fmi2Boolean* enterEventMode,
                                                          fmi2Boolean* terminateSimulation) {
  return guarded(c, "fmi2CompletedIntegratorStep", [&](Component&, kanegen_fmu::Instance& i) {
    *enterEventMode = i.drifted() ? fmi2True : fmi2False;
    *terminateSimulation = fmi2False;
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2SetTime)(fmi2Component c, fmi2Real time) {
  return guarded(c, "fmi2SetTime", [&](Component&, kanegen_fmu::Instance& i) {
    i.set_time(time);
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2SetContinuousStates)(fmi2Component c, const fmi2Real x[], size_t nx) {
  return guarded(c, "fmi2SetContinuousStates", [&](Component&, kanegen_fmu::Instance& i) {
    if (nx != static_cast<size_t>(i.state_count())) return false;
    i.set_states(x);
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetDerivatives)(fmi2Component c, fmi2Real derivatives[], size_t nx) {
  return guarded(c, "fmi2GetDerivatives", [&](Component&, kanegen_fmu::Instance& i) {
    return nx == static_cast<size_t>(i.state_count()) && i.derivatives(derivatives);
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetEventIndicators)(fmi2Component c, fmi2Real[], size_t ni) {
  return ni == 0 && c ? fmi2OK : unsupported(c, "fmi2GetEventIndicators with indicators");
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetContinuousStates)(fmi2Component c, fmi2Real x[], size_t nx) {
  return guarded(c, "fmi2GetContinuousStates", [&](Component&, kanegen_fmu::Instance& i) {
    if (nx != static_cast<size_t>(i.state_count())) return false;
    i.get_states(x);
    return true;
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetNominalsOfContinuousStates)(fmi2Component c, fmi2Real x_nominal[],
                                                                size_t nx) {
  if (c == nullptr) return fmi2Error;
  for (size_t k = 0; k < nx; ++k) x_nominal[k] = 1.0;
  return fmi2OK;
}

// Co-simulation.

fmi2Status KANEGEN_FMI2_NAME(fmi2SetRealInputDerivatives)(fmi2Component c, const fmi2ValueReference[], size_t,
                                                          const fmi2Integer[], const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives");
}

fmi2Status KANEGEN_FMI2_NAME(fmi2GetRealOutputDerivatives)(fmi2Component c, const fmi2ValueReference[],
                                                           size_t, const fmi2Integer[], fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives");
}

fmi2Status KANEGEN_FMI2_NAME(fmi2DoStep)(fmi2Component c, fmi2Real currentCommunicationPoint,
                                         fmi2Real communicationStepSize, fmi2Boolean) {
  return guarded(c, "fmi2DoStep", [&](Component&, kanegen_fmu::Instance& i) {
    return i.do_step(currentCommunicationPoint, communicationStepSize);
  });
}

fmi2Status KANEGEN_FMI2_NAME(fmi2CancelStep)(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

fmi2Status KANEGEN_FMI2_NAME(fmi2GetStatus)(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return unsupported(c, "fmi2GetStatus");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2GetRealStatus)(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  if (c == nullptr || s != fmi2LastSuccessfulTime) return unsupported(c, "fmi2GetRealStatus");
  *value = component(c)->instance->time();
  return fmi2OK;
}
fmi2Status KANEGEN_FMI2_NAME(fmi2GetIntegerStatus)(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2GetBooleanStatus)(fmi2Component c, const fmi2StatusKind, fmi2Boolean*) {
  return unsupported(c, "fmi2GetBooleanStatus");
}
fmi2Status KANEGEN_FMI2_NAME(fmi2GetStringStatus)(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus");
}

}  // extern "C"
