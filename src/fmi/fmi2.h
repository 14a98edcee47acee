/* fmi2.h - the C interface of FMI 2.0 (Functional Mock-up Interface 2.0.x, Modelica
 * Association, fmi-standard.org): its types and the functions an FMU exports, declared here
 * from the signatures the specification documents (sections 2.1 and 3.2, 4.2).
 *
 * Why our own header and not the standard's fmi2Functions.h, fmi2FunctionTypes.h and
 * fmi2TypesPlatform.h: those files are not packaged - not by Debian 12 (apt-cache search fmi
 * finds none) nor by the npm registry - and lvsim takes its dependencies from packages only.
 * The declarations below follow the documented ones: the same names, types, enumerator order
 * and structure layouts, so an FMU built with them is called correctly by any importer built
 * with the standard's headers. The platform is "default": fmi2Boolean is int, fmi2Byte char.
 * Used by the FMU (src/fmi/fmu.c) and by the test suite's importer (tests/unit/test_fmu.c).
 */
#ifndef LV_FMI_FMI2_H
#define LV_FMI_FMI2_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define fmi2TypesPlatform "default"
#define fmi2Version "2.0"

typedef void *fmi2Component;            /* an FMU instance */
typedef void *fmi2ComponentEnvironment; /* the importer's pointer, passed back to callbacks */
typedef void *fmi2FMUstate;             /* a saved state of an instance */
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
typedef char fmi2Byte;

#define fmi2True 1
#define fmi2False 0

typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;

typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;

typedef enum {
    fmi2DoStepStatus,
    fmi2PendingStatus,
    fmi2LastSuccessfulTime,
    fmi2Terminated
} fmi2StatusKind;

typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment componentEnvironment,
                                   fmi2String instanceName, fmi2Status status,
                                   fmi2String category, fmi2String message, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t nobj, size_t size);
typedef void (*fmi2CallbackFreeMemory)(void *obj);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment componentEnvironment,
                                 fmi2Status status);

typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef struct {
    fmi2Boolean newDiscreteStatesNeeded;
    fmi2Boolean terminateSimulation;
    fmi2Boolean nominalsOfContinuousStatesChanged;
    fmi2Boolean valuesOfContinuousStatesChanged;
    fmi2Boolean nextEventTimeDefined;
    fmi2Real nextEventTime;
} fmi2EventInfo;

/* The FMU's functions. FMI2_EXPORT gives them default visibility in the FMU (built with
 * -fvisibility=hidden); an importer includes this header only for the types and the
 * function-pointer typedefs below. */
#ifndef FMI2_EXPORT
#define FMI2_EXPORT
#endif

/* Each function F has the pointer type F##TYPE (as the standard's fmi2FunctionTypes.h). */
#define LV_FMI2_FUNCTIONS(X)                                                                   \
    X(const char *, fmi2GetTypesPlatform, (void))                                             \
    X(const char *, fmi2GetVersion, (void))                                                   \
    X(fmi2Status, fmi2SetDebugLogging,                                                        \
      (fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,                            \
       const fmi2String categories[]))                                                        \
    X(fmi2Component, fmi2Instantiate,                                                         \
      (fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,                         \
       fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,                \
       fmi2Boolean visible, fmi2Boolean loggingOn))                                           \
    X(void, fmi2FreeInstance, (fmi2Component c))                                              \
    X(fmi2Status, fmi2SetupExperiment,                                                        \
      (fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime, \
       fmi2Boolean stopTimeDefined, fmi2Real stopTime))                                       \
    X(fmi2Status, fmi2EnterInitializationMode, (fmi2Component c))                             \
    X(fmi2Status, fmi2ExitInitializationMode, (fmi2Component c))                              \
    X(fmi2Status, fmi2Terminate, (fmi2Component c))                                           \
    X(fmi2Status, fmi2Reset, (fmi2Component c))                                               \
    X(fmi2Status, fmi2GetReal,                                                                \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]))         \
    X(fmi2Status, fmi2GetInteger,                                                             \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]))      \
    X(fmi2Status, fmi2GetBoolean,                                                             \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]))      \
    X(fmi2Status, fmi2GetString,                                                              \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]))      \
    X(fmi2Status, fmi2SetReal,                                                                \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]))   \
    X(fmi2Status, fmi2SetInteger,                                                             \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr,                            \
       const fmi2Integer value[]))                                                            \
    X(fmi2Status, fmi2SetBoolean,                                                             \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr,                            \
       const fmi2Boolean value[]))                                                            \
    X(fmi2Status, fmi2SetString,                                                              \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])) \
    X(fmi2Status, fmi2GetFMUstate, (fmi2Component c, fmi2FMUstate *FMUstate))                 \
    X(fmi2Status, fmi2SetFMUstate, (fmi2Component c, fmi2FMUstate FMUstate))                  \
    X(fmi2Status, fmi2FreeFMUstate, (fmi2Component c, fmi2FMUstate *FMUstate))                \
    X(fmi2Status, fmi2SerializedFMUstateSize,                                                 \
      (fmi2Component c, fmi2FMUstate FMUstate, size_t *size))                                 \
    X(fmi2Status, fmi2SerializeFMUstate,                                                      \
      (fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size))      \
    X(fmi2Status, fmi2DeSerializeFMUstate,                                                    \
      (fmi2Component c, const fmi2Byte serializedState[], size_t size,                        \
       fmi2FMUstate *FMUstate))                                                               \
    X(fmi2Status, fmi2GetDirectionalDerivative,                                               \
      (fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,             \
       const fmi2ValueReference vKnown_ref[], size_t nKnown, const fmi2Real dvKnown[],        \
       fmi2Real dvUnknown[]))                                                                 \
    /* Model Exchange */                                                                      \
    X(fmi2Status, fmi2EnterEventMode, (fmi2Component c))                                      \
    X(fmi2Status, fmi2NewDiscreteStates, (fmi2Component c, fmi2EventInfo * eventInfo))        \
    X(fmi2Status, fmi2EnterContinuousTimeMode, (fmi2Component c))                             \
    X(fmi2Status, fmi2CompletedIntegratorStep,                                                \
      (fmi2Component c, fmi2Boolean noSetFMUStatePriorToCurrentPoint,                         \
       fmi2Boolean * enterEventMode, fmi2Boolean * terminateSimulation))                      \
    X(fmi2Status, fmi2SetTime, (fmi2Component c, fmi2Real time))                              \
    X(fmi2Status, fmi2SetContinuousStates, (fmi2Component c, const fmi2Real x[], size_t nx))  \
    X(fmi2Status, fmi2GetDerivatives,                                                         \
      (fmi2Component c, fmi2Real derivatives[], size_t nx))                                   \
    X(fmi2Status, fmi2GetEventIndicators,                                                     \
      (fmi2Component c, fmi2Real eventIndicators[], size_t ni))                               \
    X(fmi2Status, fmi2GetContinuousStates, (fmi2Component c, fmi2Real x[], size_t nx))        \
    X(fmi2Status, fmi2GetNominalsOfContinuousStates,                                          \
      (fmi2Component c, fmi2Real x_nominal[], size_t nx))                                     \
    /* Co-Simulation */                                                                       \
    X(fmi2Status, fmi2SetRealInputDerivatives,                                                \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[], \
       const fmi2Real value[]))                                                               \
    X(fmi2Status, fmi2GetRealOutputDerivatives,                                               \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[], \
       fmi2Real value[]))                                                                     \
    X(fmi2Status, fmi2DoStep,                                                                 \
      (fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,    \
       fmi2Boolean noSetFMUStatePriorToCurrentPoint))                                         \
    X(fmi2Status, fmi2CancelStep, (fmi2Component c))                                          \
    X(fmi2Status, fmi2GetStatus,                                                              \
      (fmi2Component c, const fmi2StatusKind s, fmi2Status * value))                          \
    X(fmi2Status, fmi2GetRealStatus,                                                          \
      (fmi2Component c, const fmi2StatusKind s, fmi2Real * value))                            \
    X(fmi2Status, fmi2GetIntegerStatus,                                                       \
      (fmi2Component c, const fmi2StatusKind s, fmi2Integer * value))                         \
    X(fmi2Status, fmi2GetBooleanStatus,                                                       \
      (fmi2Component c, const fmi2StatusKind s, fmi2Boolean * value))                         \
    X(fmi2Status, fmi2GetStringStatus,                                                        \
      (fmi2Component c, const fmi2StatusKind s, fmi2String * value))

#define LV_FMI2_TYPEDEF(ret, name, args) typedef ret name##TYPE args;
LV_FMI2_FUNCTIONS(LV_FMI2_TYPEDEF)
#undef LV_FMI2_TYPEDEF

#ifdef LV_FMI2_DECLARE_FUNCTIONS /* the FMU itself */
#define LV_FMI2_DECLARE(ret, name, args) FMI2_EXPORT ret name args;
LV_FMI2_FUNCTIONS(LV_FMI2_DECLARE)
#undef LV_FMI2_DECLARE
#endif

#ifdef __cplusplus
}
#endif
#endif
