// SPDX-License-Identifier: GPL-2.0-or-later
#include "runner/generation_interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>

namespace kanegen::runner {
namespace {

constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
constexpr const char* kNames[3] = {"SIGINT", "SIGTERM", "SIGHUP"};

// Formatted before the signal can come: a handler may only write and exit.
char g_message[3][1024];

int index_of(int signal_number) { return signal_number == SIGINT ? 0 : signal_number == SIGTERM ? 1 : 2; }

extern "C" void stop_generating(int signal_number) {
  const char* message = g_message[index_of(signal_number)];
  if (write(STDERR_FILENO, message, std::strlen(message)) < 0) {
  }
  _exit(128 + signal_number);
}

}  // namespace

StopWhileGenerating::StopWhileGenerating(const std::string& model, const char* what) {
  for (int k = 0; k < 3; ++k) {
    std::snprintf(g_message[k], sizeof g_message[k],
                  "error: interrupted by %s while generating %s; nothing was %s\n", kNames[k], model.c_str(),
                  what);
    previous_[k] = std::signal(kSignals[k], stop_generating);
  }
}

StopWhileGenerating::~StopWhileGenerating() {
  for (int k = 0; k < 3; ++k) std::signal(kSignals[k], previous_[k]);
}

}  // namespace kanegen::runner
