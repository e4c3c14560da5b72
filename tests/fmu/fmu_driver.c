/* SPDX-License-Identifier: GPL-2.0-or-later */
/* An FMU importer of our own for the tests (tests/fmu/check_fmu.py): loads an FMU's binary, follows FMI's
   calling sequence (instantiate, initialization mode, then model exchange integrated by its own fixed-step
   RK4, or co-simulation stepped by fmi2DoStep/fmi3DoStep) and writes the variables asked for as a CSV. The
   function types are written here from the FMI 2.0 and 3.0 standards' signatures, not taken from kanegen's
   wrapper, so that a wrong signature there shows.

   usage: fmu_driver BINARY 2|3 me|cs PLAN OUT.csv
   PLAN: lines "token TEXT", "states N", "stop T", "interval DT", "substeps K", "set VR VALUE" (before
   initialization: parameters, start values, inputs) and "out VR" (the columns after t, in order). */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_VARS 4096

typedef struct {
  char token[256];
  int states, substeps, nset, nout;
  double stop, interval;
  unsigned set_vr[MAX_VARS], out_vr[MAX_VARS];
  double set_value[MAX_VARS];
} Plan;

static void fail(const char* what) {
  fprintf(stderr, "fmu_driver: %s\n", what);
  exit(1);
}

static void read_plan(const char* path, Plan* p) {
  FILE* f = fopen(path, "r");
  char key[32];
  if (!f) fail("cannot open the plan");
  memset(p, 0, sizeof *p);
  p->substeps = 1;
  while (fscanf(f, "%31s", key) == 1) {
    if (!strcmp(key, "token") && fscanf(f, "%255s", p->token) == 1) continue;
    if (!strcmp(key, "states") && fscanf(f, "%d", &p->states) == 1) continue;
    if (!strcmp(key, "stop") && fscanf(f, "%lf", &p->stop) == 1) continue;
    if (!strcmp(key, "interval") && fscanf(f, "%lf", &p->interval) == 1) continue;
    if (!strcmp(key, "substeps") && fscanf(f, "%d", &p->substeps) == 1) continue;
    if (!strcmp(key, "set") && p->nset < MAX_VARS &&
        fscanf(f, "%u %lf", &p->set_vr[p->nset], &p->set_value[p->nset]) == 2) {
      ++p->nset;
      continue;
    }
    if (!strcmp(key, "out") && p->nout < MAX_VARS && fscanf(f, "%u", &p->out_vr[p->nout]) == 1) {
      ++p->nout;
      continue;
    }
    fail("bad plan line");
  }
  fclose(f);
}

static void* symbol(void* library, const char* name) {
  void* s = dlsym(library, name);
  if (!s) {
    fprintf(stderr, "fmu_driver: the binary does not export %s\n", name);
    exit(1);
  }
  return s;
}

/* ---- the interface of one version, as function pointers over void* instances ---- */
typedef struct {
  void* instance;
  int (*set_real)(void*, const unsigned*, size_t, const double*);
  int (*get_real)(void*, const unsigned*, size_t, double*);
  int (*set_time)(void*, double);
  int (*set_states)(void*, const double*, size_t);
  int (*get_states)(void*, double*, size_t);
  int (*derivatives)(void*, double*, size_t);
  int (*completed_step)(void*, bool* event);                    /* ME: after an accepted step */
  int (*handle_event)(void*, bool enter, bool* states_changed); /* enter: not yet in event mode */
  int (*do_step)(void*, double t, double h);
} Fmu;

/* ---- FMI 2.0 ---- */
typedef struct {
  void (*logger)(void*, const char*, int, const char*, const char*, ...);
  void* (*allocate)(size_t, size_t);
  void (*free)(void*);
  void (*step_finished)(void*, int);
  void* environment;
} Fmi2Callbacks;
typedef struct {
  int new_discrete_states_needed, terminate, nominals_changed, values_changed, next_event_time_defined;
  double next_event_time;
} Fmi2EventInfo;

static void fmi2_logger(void* env, const char* name, int status, const char* category, const char* message,
                        ...) {
  va_list args;
  (void)env;
  va_start(args, message);
  fprintf(stderr, "[%s %d %s] ", name, status, category);
  vfprintf(stderr, message, args);
  fputc('\n', stderr);
  va_end(args);
}

static void* g_library;
static long g_events, g_moved; /* step events, and those that moved the states */
#define FMI2(name, type) ((type)symbol(g_library, #name))

static int fmi2_completed(void* c, bool* event) {
  int enter = 0, terminate = 0;
  int s = FMI2(fmi2CompletedIntegratorStep, int (*)(void*, int, int*, int*))(c, 1, &enter, &terminate);
  *event = enter != 0;
  return s;
}

static int fmi2_event(void* c, bool enter, bool* changed) {
  Fmi2EventInfo info;
  int s = enter ? FMI2(fmi2EnterEventMode, int (*)(void*))(c) : 0;
  *changed = false;
  do {
    s = s ? s : FMI2(fmi2NewDiscreteStates, int (*)(void*, Fmi2EventInfo*))(c, &info);
    if (info.values_changed) *changed = true;
  } while (s == 0 && info.new_discrete_states_needed);
  return s ? s : FMI2(fmi2EnterContinuousTimeMode, int (*)(void*))(c);
}

static int fmi2_do_step(void* c, double t, double h) {
  return FMI2(fmi2DoStep, int (*)(void*, double, double, int))(c, t, h, 1);
}

static void fmi2_open(Fmu* f, const Plan* p, bool me) {
  static Fmi2Callbacks callbacks = {fmi2_logger, calloc, free, NULL, NULL};
  typedef void* (*Instantiate)(const char*, int, const char*, const char*, const Fmi2Callbacks*, int, int);
  f->instance = FMI2(fmi2Instantiate, Instantiate)("driver", me ? 0 : 1, p->token, "", &callbacks, 0, 0);
  if (!f->instance) fail("fmi2Instantiate failed");
  f->set_real = FMI2(fmi2SetReal, int (*)(void*, const unsigned*, size_t, const double*));
  f->get_real = FMI2(fmi2GetReal, int (*)(void*, const unsigned*, size_t, double*));
  f->set_time = FMI2(fmi2SetTime, int (*)(void*, double));
  f->set_states = FMI2(fmi2SetContinuousStates, int (*)(void*, const double*, size_t));
  f->get_states = FMI2(fmi2GetContinuousStates, int (*)(void*, double*, size_t));
  f->derivatives = FMI2(fmi2GetDerivatives, int (*)(void*, double*, size_t));
  f->completed_step = fmi2_completed;
  f->handle_event = fmi2_event;
  f->do_step = fmi2_do_step;
  if (FMI2(fmi2SetupExperiment, int (*)(void*, int, double, double, int, double))(f->instance, 0, 0, 0, 1,
                                                                                  p->stop))
    fail("fmi2SetupExperiment failed");
  if (FMI2(fmi2EnterInitializationMode, int (*)(void*))(f->instance))
    fail("fmi2EnterInitializationMode failed");
  if (p->nset && f->set_real(f->instance, p->set_vr, (size_t)p->nset, p->set_value))
    fail("fmi2SetReal failed");
  if (FMI2(fmi2ExitInitializationMode, int (*)(void*))(f->instance))
    fail("fmi2ExitInitializationMode failed");
}

/* ---- FMI 3.0 ---- */
static void fmi3_logger(void* env, int status, const char* category, const char* message) {
  (void)env;
  fprintf(stderr, "[%d %s] %s\n", status, category, message);
}
#define FMI3(name, type) ((type)symbol(g_library, #name))

static int fmi3_set(void* c, const unsigned* vr, size_t n, const double* v) {
  return FMI3(fmi3SetFloat64, int (*)(void*, const uint32_t*, size_t, const double*, size_t))(c, vr, n, v, n);
}
static int fmi3_get(void* c, const unsigned* vr, size_t n, double* v) {
  return FMI3(fmi3GetFloat64, int (*)(void*, const uint32_t*, size_t, double*, size_t))(c, vr, n, v, n);
}
static int fmi3_completed(void* c, bool* event) {
  bool terminate = false;
  return FMI3(fmi3CompletedIntegratorStep, int (*)(void*, bool, bool*, bool*))(c, true, event, &terminate);
}
static int fmi3_event(void* c, bool enter, bool* changed) {
  bool need = false, terminate = false, nominals = false, values = false, defined = false;
  double next = 0;
  int s = enter ? FMI3(fmi3EnterEventMode, int (*)(void*))(c) : 0;
  *changed = false;
  do {
    s = s ? s
          : FMI3(fmi3UpdateDiscreteStates, int (*)(void*, bool*, bool*, bool*, bool*, bool*, double*))(
                c, &need, &terminate, &nominals, &values, &defined, &next);
    if (values) *changed = true;
  } while (s == 0 && need);
  return s ? s : FMI3(fmi3EnterContinuousTimeMode, int (*)(void*))(c);
}
static int fmi3_do_step(void* c, double t, double h) {
  bool event = false, terminate = false, early = false;
  double last = 0;
  return FMI3(fmi3DoStep, int (*)(void*, double, double, bool, bool*, bool*, bool*, double*))(
      c, t, h, true, &event, &terminate, &early, &last);
}

static void fmi3_open(Fmu* f, const Plan* p, bool me) {
  if (me) {
    typedef void* (*Instantiate)(const char*, const char*, const char*, bool, bool, void*, void*);
    f->instance = FMI3(fmi3InstantiateModelExchange, Instantiate)("driver", p->token, NULL, false, false,
                                                                  NULL, (void*)fmi3_logger);
  } else {
    typedef void* (*Instantiate)(const char*, const char*, const char*, bool, bool, bool, bool,
                                 const uint32_t*, size_t, void*, void*, void*);
    f->instance = FMI3(fmi3InstantiateCoSimulation, Instantiate)(
        "driver", p->token, NULL, false, false, false, false, NULL, 0, NULL, (void*)fmi3_logger, NULL);
  }
  if (!f->instance) fail("fmi3Instantiate failed");
  f->set_real = fmi3_set;
  f->get_real = fmi3_get;
  f->set_time = FMI3(fmi3SetTime, int (*)(void*, double));
  f->set_states = FMI3(fmi3SetContinuousStates, int (*)(void*, const double*, size_t));
  f->get_states = FMI3(fmi3GetContinuousStates, int (*)(void*, double*, size_t));
  f->derivatives = FMI3(fmi3GetContinuousStateDerivatives, int (*)(void*, double*, size_t));
  f->completed_step = fmi3_completed;
  f->handle_event = fmi3_event;
  f->do_step = fmi3_do_step;
  if (FMI3(fmi3EnterInitializationMode, int (*)(void*, bool, double, double, bool, double))(
          f->instance, false, 0, 0, true, p->stop))
    fail("fmi3EnterInitializationMode failed");
  if (p->nset && f->set_real(f->instance, p->set_vr, (size_t)p->nset, p->set_value))
    fail("fmi3SetFloat64 failed");
  if (FMI3(fmi3ExitInitializationMode, int (*)(void*))(f->instance))
    fail("fmi3ExitInitializationMode failed");
  if (!me && FMI3(fmi3EnterStepMode, int (*)(void*))(f->instance)) fail("fmi3EnterStepMode failed");
}

/* ---- the run ---- */
static void record(FILE* out, const Fmu* f, const Plan* p, double t) {
  double values[MAX_VARS];
  int i;
  if (p->nout && f->get_real(f->instance, p->out_vr, (size_t)p->nout, values))
    fail("getting the outputs failed");
  fprintf(out, "%.17g", t);
  for (i = 0; i < p->nout; ++i) fprintf(out, ",%.17g", values[i]);
  fputc('\n', out);
}

/* The derivatives at (t, x). */
static void rhs(const Fmu* f, double t, const double* x, double* dx, int n) {
  if (f->set_time(f->instance, t) || f->set_states(f->instance, x, (size_t)n) ||
      f->derivatives(f->instance, dx, (size_t)n))
    fail("evaluating the derivatives failed");
}

/* One classical RK4 step of size h from (t, x); then the FMU is told the step is complete. */
static void rk4_step(const Fmu* f, double t, double h, double* x, int n) {
  double k1[MAX_VARS], k2[MAX_VARS], k3[MAX_VARS], k4[MAX_VARS], y[MAX_VARS];
  bool event = false, changed = false;
  int i;
  rhs(f, t, x, k1, n);
  for (i = 0; i < n; ++i) y[i] = x[i] + h / 2 * k1[i];
  rhs(f, t + h / 2, y, k2, n);
  for (i = 0; i < n; ++i) y[i] = x[i] + h / 2 * k2[i];
  rhs(f, t + h / 2, y, k3, n);
  for (i = 0; i < n; ++i) y[i] = x[i] + h * k3[i];
  rhs(f, t + h, y, k4, n);
  for (i = 0; i < n; ++i) x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  if (f->set_time(f->instance, t + h) || f->set_states(f->instance, x, (size_t)n))
    fail("setting the state failed");
  if (f->completed_step(f->instance, &event)) fail("completed integrator step failed");
  if (event) {
    ++g_events;
    if (f->handle_event(f->instance, true, &changed)) fail("the step event failed");
    g_moved += changed;
    if (changed && f->get_states(f->instance, x, (size_t)n))
      fail("getting the states after the event failed");
  }
}

int main(int argc, char** argv) {
  Plan plan;
  Fmu f;
  double x[MAX_VARS];
  bool me, changed = false;
  long k, intervals;
  int j;
  FILE* out;
  if (argc != 6) fail("usage: fmu_driver BINARY 2|3 me|cs PLAN OUT.csv");
  read_plan(argv[4], &plan);
  me = !strcmp(argv[3], "me");
  g_library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!g_library) fail(dlerror());
  if (!strcmp(argv[2], "2"))
    fmi2_open(&f, &plan, me);
  else
    fmi3_open(&f, &plan, me);
  out = fopen(argv[5], "w");
  if (!out || plan.states > MAX_VARS || plan.interval <= 0) fail("bad output file or plan");
  if (me) { /* event mode after initialization, then continuous time */
    if (f.handle_event(f.instance, false, &changed)) fail("the initial event failed");
    if (f.get_states(f.instance, x, (size_t)plan.states)) fail("getting the states failed");
  }
  fprintf(out, "t");
  for (j = 0; j < plan.nout; ++j) fprintf(out, ",%u", plan.out_vr[j]);
  fputc('\n', out);
  intervals = (long)(plan.stop / plan.interval + 0.5);
  for (k = 0; k <= intervals; ++k) {
    const double t = k * plan.interval;
    record(out, &f, &plan, t);
    if (k == intervals) break;
    if (!me) {
      if (f.do_step(f.instance, t, plan.interval)) fail("the co-simulation step failed");
      continue;
    }
    for (j = 0; j < plan.substeps; ++j)
      rk4_step(&f, t + j * plan.interval / plan.substeps, plan.interval / plan.substeps, x, plan.states);
  }
  fclose(out);
  printf("step events: %ld, states moved: %ld\n", g_events, g_moved);
  if (!strcmp(argv[2], "2"))
    FMI2(fmi2FreeInstance, void (*)(void*))(f.instance);
  else
    FMI3(fmi3FreeInstance, void (*)(void*))(f.instance);
  dlclose(g_library);
  return 0;
}
