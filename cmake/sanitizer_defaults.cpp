// SPDX-License-Identifier: MIT
// Linked into every executable of a KANEGEN_SANITIZE build (see
// KanegenSanitize.cmake): the sanitizers' options, so that kanegen run by the
// build itself (kanegen_add_model) and every test stop at the first finding
// without any environment. ASAN_OPTIONS, UBSAN_OPTIONS and LSAN_OPTIONS in
// the environment are applied on top.
extern "C" {

const char* __asan_default_options() {  // NOLINT(bugprone-reserved-identifier)
  return "halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_init_order=1";
}

const char* __ubsan_default_options() {  // NOLINT(bugprone-reserved-identifier)
  return "halt_on_error=1:print_stacktrace=1";
}

const char* __lsan_default_options() {  // NOLINT(bugprone-reserved-identifier)
  return "print_suppressions=0";
}

// Leaks in uninstrumented system libraries, whose frames have no symbols, so
// only the library can be named; leaks allocated from kanegen's own frames
// are still reported.
//  - CLN (GiNaC's number library) keeps 26 bytes from its start-up for the
//    process lifetime.
//  - GiNaC's parser loses the node it was building when evaluating it throws
//    ("1/0": power::eval(): division by zero), 40 bytes per such error.
//  - urdfdom's parseURDF leaks the links it has read when a later one fails
//    to parse (an inertia value that is not a number; found by the fuzzer,
//    tests/data/fuzz_regressions/urdf/bad_inertia_leak.urdf). The loader
//    checks the joint tree itself to avoid the leaks it can, but cannot
//    pre-parse every attribute urdfdom reads; the error ends the process.
const char* __lsan_default_suppressions() {  // NOLINT(bugprone-reserved-identifier)
  return "leak:libcln.so\n"
         "leak:libginac.so\n"
         "leak:liburdfdom_model.so\n";
}
}
