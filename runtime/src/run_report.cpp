// SPDX-License-Identifier: MIT
#include "run_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {

void EnergyColumns::add_header(std::vector<std::string>& header) const {
  if (enabled_) header.insert(header.end(), {"kinetic_energy", "potential_energy", "total_energy"});
}

void EnergyColumns::fill(const double* q, const double* u, double* out) {
  const double kinetic = model_.kinetic_energy(q, u), potential = model_.potential_energy(q);
  const double total = kinetic + potential;
  if (first_) initial_ = total;
  first_ = false;
  largest_change_ = std::max(largest_change_, std::abs(total - initial_));
  if (!enabled_) return;
  out[0] = kinetic;
  out[1] = potential;
  out[2] = total;
}

Progress::Progress(std::FILE* err, double t_end)
    : err_(err),
      t_end_(t_end),
      terminal_(err != nullptr && isatty(fileno(err)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void Progress::on_rhs(double t) {
  ++calls_;
  if (!terminal_ || calls_ % 64 != 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - start_).count();
  // Quiet for short runs, then at most ten updates a second.
  if (wall < 1.0 || std::chrono::duration<double>(now - last_).count() < 0.1) return;
  last_ = now;
  shown_ = true;
  std::fprintf(err_, "\r\033[Ksimulate: t = %.6g of %.6g s, wall %.1f s, %ld rhs evaluations", t, t_end_, wall,
               calls_);
  std::fflush(err_);
}

void Progress::finish() {
  if (!shown_) return;
  shown_ = false;
  std::fputs("\r\033[K", err_);  // the messages after it start on a clean line
  std::fflush(err_);
}

std::string run_summary(long steps, double t_final, const EnergyColumns& energy, bool loops,
                        double largest_loop_residual) {
  const double scale = std::max(std::abs(energy.initial()), 1e-300);
  char text[320];
  // T + V is conserved only without damping, forces, inputs or prescribed
  // motion, which the runner cannot tell: the change is named for what it is.
  std::snprintf(
      text, sizeof text,
      "summary: %ld steps to t=%s; T+V changed by at most %.3g (%.3g relative to (T+V)(0)), the energy "
      "drift if the model is conservative",
      steps, format_double(t_final).c_str(), energy.largest_change(), energy.largest_change() / scale);
  std::string s = text;
  if (loops) {
    std::snprintf(text, sizeof text, "; largest loop residual |phi| %.3g", largest_loop_residual);
    s += text;
  }
  return s + "\n";
}

}  // namespace kanegen::runtime
