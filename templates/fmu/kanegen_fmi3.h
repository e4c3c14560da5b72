// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
// The FMI 3.0 types and functions that kanegen's FMU wrapper implements, written for kanegen from the
// function signatures in the FMI 3.0 standard's text (section 2.2 and chapters 3 to 5); not the Modelica
// Association's headers. With FMI3_FUNCTION_PREFIX defined (a source FMU compiled into an importer), each
// function is named PREFIX##name, as the standard asks of source code FMUs.
#ifndef KANEGEN_FMI3_H
#define KANEGEN_FMI3_H

#include <stddef.h>
#include <stdint.h>
#ifndef __cplusplus
#include <stdbool.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef void* fmi3Instance;
typedef void* fmi3InstanceEnvironment;
typedef void* fmi3FMUState;
typedef uint32_t fmi3ValueReference;
typedef float fmi3Float32;
typedef double fmi3Float64;
typedef int8_t fmi3Int8;
typedef uint8_t fmi3UInt8;
typedef int16_t fmi3Int16;
typedef uint16_t fmi3UInt16;
typedef int32_t fmi3Int32;
typedef uint32_t fmi3UInt32;
typedef int64_t fmi3Int64;
typedef uint64_t fmi3UInt64;
typedef bool fmi3Boolean;
typedef char fmi3Char;
typedef const fmi3Char* fmi3String;
typedef uint8_t fmi3Byte;
typedef const fmi3Byte* fmi3Binary;
typedef bool fmi3Clock;

#define fmi3True true
#define fmi3False false

typedef enum { fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal } fmi3Status;
typedef enum {
  fmi3Independent,
  fmi3Constant,
  fmi3Fixed,
  fmi3Tunable,
  fmi3Discrete,
  fmi3Continuous
} fmi3DependencyKind;
typedef enum { fmi3IntervalNotYetKnown, fmi3IntervalUnchanged, fmi3IntervalChanged } fmi3IntervalQualifier;

typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment instanceEnvironment, fmi3Status status,
                                       fmi3String category, fmi3String message);
typedef void (*fmi3ClockUpdateCallback)(fmi3InstanceEnvironment instanceEnvironment);
typedef void (*fmi3IntermediateUpdateCallback)(fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3Float64 intermediateUpdateTime,
                                               fmi3Boolean intermediateVariableSetRequested,
                                               fmi3Boolean intermediateVariableGetAllowed,
                                               fmi3Boolean intermediateStepFinished,
                                               fmi3Boolean canReturnEarly, fmi3Boolean* earlyReturnRequested,
                                               fmi3Float64* earlyReturnTime);
typedef void (*fmi3LockPreemptionCallback)(void);
typedef void (*fmi3UnlockPreemptionCallback)(void);

#ifdef FMI3_FUNCTION_PREFIX
#define KANEGEN_FMI3_PASTE(a, b) a##b
#define KANEGEN_FMI3_JOIN(a, b) KANEGEN_FMI3_PASTE(a, b)
#define KANEGEN_FMI3_NAME(name) KANEGEN_FMI3_JOIN(FMI3_FUNCTION_PREFIX, name)
#else
#define KANEGEN_FMI3_NAME(name) name
#endif

#if defined(_WIN32)
#define KANEGEN_FMI3_EXPORT __declspec(dllexport)
#else
#define KANEGEN_FMI3_EXPORT __attribute__((visibility("default")))
#endif

// The getters and setters of one type: X(type name, C type).
#define KANEGEN_FMI3_VALUE_TYPES(X) \
  X(Float32, fmi3Float32)           \
  X(Float64, fmi3Float64)           \
  X(Int8, fmi3Int8)                 \
  X(UInt8, fmi3UInt8)               \
  X(Int16, fmi3Int16)               \
  X(UInt16, fmi3UInt16)             \
  X(Int32, fmi3Int32)               \
  X(UInt32, fmi3UInt32)             \
  X(Int64, fmi3Int64)               \
  X(UInt64, fmi3UInt64)             \
  X(Boolean, fmi3Boolean)           \
  X(String, fmi3String)

#define KANEGEN_FMI3_DECLARE_VALUES(type, ctype)                                                  \
  KANEGEN_FMI3_EXPORT fmi3Status KANEGEN_FMI3_NAME(fmi3Get##type)(                                \
      fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, \
      ctype values[], size_t nValues);                                                            \
  KANEGEN_FMI3_EXPORT fmi3Status KANEGEN_FMI3_NAME(fmi3Set##type)(                                \
      fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, \
      const ctype values[], size_t nValues);
KANEGEN_FMI3_VALUE_TYPES(KANEGEN_FMI3_DECLARE_VALUES)
#undef KANEGEN_FMI3_DECLARE_VALUES

// KANEGEN_FMI3_FUNCTIONS(X): X(return type, name, (parameters)) for the other functions of the standard.
#define KANEGEN_FMI3_FUNCTIONS(X)                                                                            \
  X(const char*, fmi3GetVersion, (void))                                                                     \
  X(fmi3Status, fmi3SetDebugLogging,                                                                         \
    (fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories, const fmi3String categories[]))       \
  X(fmi3Instance, fmi3InstantiateModelExchange,                                                              \
    (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,   \
     fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage)) \
  X(fmi3Instance, fmi3InstantiateCoSimulation,                                                               \
    (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,   \
     fmi3Boolean loggingOn, fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,                       \
     const fmi3ValueReference requiredIntermediateVariables[], size_t nRequiredIntermediateVariables,        \
     fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,                         \
     fmi3IntermediateUpdateCallback intermediateUpdate))                                                     \
  X(fmi3Instance, fmi3InstantiateScheduledExecution,                                                         \
    (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,   \
     fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,  \
     fmi3ClockUpdateCallback clockUpdate, fmi3LockPreemptionCallback lockPreemption,                         \
     fmi3UnlockPreemptionCallback unlockPreemption))                                                         \
  X(void, fmi3FreeInstance, (fmi3Instance instance))                                                         \
  X(fmi3Status, fmi3EnterInitializationMode,                                                                 \
    (fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance, fmi3Float64 startTime,      \
     fmi3Boolean stopTimeDefined, fmi3Float64 stopTime))                                                     \
  X(fmi3Status, fmi3ExitInitializationMode, (fmi3Instance instance))                                         \
  X(fmi3Status, fmi3EnterEventMode, (fmi3Instance instance))                                                 \
  X(fmi3Status, fmi3Terminate, (fmi3Instance instance))                                                      \
  X(fmi3Status, fmi3Reset, (fmi3Instance instance))                                                          \
  X(fmi3Status, fmi3GetBinary,                                                                               \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     size_t valueSizes[], fmi3Binary values[], size_t nValues))                                              \
  X(fmi3Status, fmi3SetBinary,                                                                               \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const size_t valueSizes[], const fmi3Binary values[], size_t nValues))                                  \
  X(fmi3Status, fmi3GetClock,                                                                                \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     fmi3Clock values[]))                                                                                    \
  X(fmi3Status, fmi3SetClock,                                                                                \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3Clock values[]))                                                                              \
  X(fmi3Status, fmi3GetNumberOfVariableDependencies,                                                         \
    (fmi3Instance instance, fmi3ValueReference valueReference, size_t * nDependencies))                      \
  X(fmi3Status, fmi3GetVariableDependencies,                                                                 \
    (fmi3Instance instance, fmi3ValueReference dependent, size_t elementIndicesOfDependent[],                \
     fmi3ValueReference independents[], size_t elementIndicesOfIndependents[],                               \
     fmi3DependencyKind dependencyKinds[], size_t nDependencies))                                            \
  X(fmi3Status, fmi3GetFMUState, (fmi3Instance instance, fmi3FMUState * FMUState))                           \
  X(fmi3Status, fmi3SetFMUState, (fmi3Instance instance, fmi3FMUState FMUState))                             \
  X(fmi3Status, fmi3FreeFMUState, (fmi3Instance instance, fmi3FMUState * FMUState))                          \
  X(fmi3Status, fmi3SerializedFMUStateSize, (fmi3Instance instance, fmi3FMUState FMUState, size_t * size))   \
  X(fmi3Status, fmi3SerializeFMUState,                                                                       \
    (fmi3Instance instance, fmi3FMUState FMUState, fmi3Byte serializedState[], size_t size))                 \
  X(fmi3Status, fmi3DeserializeFMUState,                                                                     \
    (fmi3Instance instance, const fmi3Byte serializedState[], size_t size, fmi3FMUState* FMUState))          \
  X(fmi3Status, fmi3GetDirectionalDerivative,                                                                \
    (fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,                           \
     const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,              \
     fmi3Float64 sensitivity[], size_t nSensitivity))                                                        \
  X(fmi3Status, fmi3GetAdjointDerivative,                                                                    \
    (fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,                           \
     const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,              \
     fmi3Float64 sensitivity[], size_t nSensitivity))                                                        \
  X(fmi3Status, fmi3EnterConfigurationMode, (fmi3Instance instance))                                         \
  X(fmi3Status, fmi3ExitConfigurationMode, (fmi3Instance instance))                                          \
  X(fmi3Status, fmi3GetIntervalDecimal,                                                                      \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[]))                                           \
  X(fmi3Status, fmi3GetIntervalFraction,                                                                     \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     fmi3UInt64 counters[], fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[]))                   \
  X(fmi3Status, fmi3GetShiftDecimal,                                                                         \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     fmi3Float64 shifts[]))                                                                                  \
  X(fmi3Status, fmi3GetShiftFraction,                                                                        \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     fmi3UInt64 counters[], fmi3UInt64 resolutions[]))                                                       \
  X(fmi3Status, fmi3SetIntervalDecimal,                                                                      \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3Float64 intervals[]))                                                                         \
  X(fmi3Status, fmi3SetIntervalFraction,                                                                     \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]))                                           \
  X(fmi3Status, fmi3SetShiftDecimal,                                                                         \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3Float64 shifts[]))                                                                            \
  X(fmi3Status, fmi3SetShiftFraction,                                                                        \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]))                                           \
  X(fmi3Status, fmi3EvaluateDiscreteStates, (fmi3Instance instance))                                         \
  X(fmi3Status, fmi3UpdateDiscreteStates,                                                                    \
    (fmi3Instance instance, fmi3Boolean * discreteStatesNeedUpdate, fmi3Boolean * terminateSimulation,       \
     fmi3Boolean * nominalsOfContinuousStatesChanged, fmi3Boolean * valuesOfContinuousStatesChanged,         \
     fmi3Boolean * nextEventTimeDefined, fmi3Float64 * nextEventTime))                                       \
  X(fmi3Status, fmi3EnterContinuousTimeMode, (fmi3Instance instance))                                        \
  X(fmi3Status, fmi3CompletedIntegratorStep,                                                                 \
    (fmi3Instance instance, fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean * enterEventMode,      \
     fmi3Boolean * terminateSimulation))                                                                     \
  X(fmi3Status, fmi3SetTime, (fmi3Instance instance, fmi3Float64 time))                                      \
  X(fmi3Status, fmi3SetContinuousStates,                                                                     \
    (fmi3Instance instance, const fmi3Float64 continuousStates[], size_t nContinuousStates))                 \
  X(fmi3Status, fmi3GetContinuousStateDerivatives,                                                           \
    (fmi3Instance instance, fmi3Float64 derivatives[], size_t nContinuousStates))                            \
  X(fmi3Status, fmi3GetEventIndicators,                                                                      \
    (fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators))                         \
  X(fmi3Status, fmi3GetContinuousStates,                                                                     \
    (fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates))                       \
  X(fmi3Status, fmi3GetNominalsOfContinuousStates,                                                           \
    (fmi3Instance instance, fmi3Float64 nominals[], size_t nContinuousStates))                               \
  X(fmi3Status, fmi3GetNumberOfEventIndicators, (fmi3Instance instance, size_t * nEventIndicators))          \
  X(fmi3Status, fmi3GetNumberOfContinuousStates, (fmi3Instance instance, size_t * nContinuousStates))        \
  X(fmi3Status, fmi3EnterStepMode, (fmi3Instance instance))                                                  \
  X(fmi3Status, fmi3GetOutputDerivatives,                                                                    \
    (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,             \
     const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues))                                        \
  X(fmi3Status, fmi3DoStep,                                                                                  \
    (fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,        \
     fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean * eventHandlingNeeded,                        \
     fmi3Boolean * terminateSimulation, fmi3Boolean * earlyReturn, fmi3Float64 * lastSuccessfulTime))        \
  X(fmi3Status, fmi3ActivateModelPartition,                                                                  \
    (fmi3Instance instance, fmi3ValueReference clockReference, fmi3Float64 activationTime))

#define KANEGEN_FMI3_DECLARE(returns, name, parameters) \
  KANEGEN_FMI3_EXPORT returns KANEGEN_FMI3_NAME(name) parameters;
KANEGEN_FMI3_FUNCTIONS(KANEGEN_FMI3_DECLARE)
#undef KANEGEN_FMI3_DECLARE

#ifdef __cplusplus
}
#endif

#endif  // KANEGEN_FMI3_H
