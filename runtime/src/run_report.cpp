// SPDX-License-Identifier: MIT
#include "run_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {

void EnergyColumns::add_header(std::vector<std::string>& header) const {
  if (enabled_) header.insert(header.end(), {"kinetic_energy", "potential_energy", "total_energy"});
  if (with_work_) header.push_back("nonconservative_work");
}

void EnergyColumns::fill(const double* q, const double* u, double work, double* out) {
  const double kinetic = model_.kinetic_energy(q, u), potential = model_.potential_energy(q);
  const double total = kinetic + potential;
  if (first_) initial_ = total;
  first_ = false;
  largest_change_ = std::max(largest_change_, std::abs(total - work - initial_));
  scale_ = std::max(scale_, kinetic + std::abs(potential));
  if (!enabled_) return;
  out[0] = kinetic;
  out[1] = potential;
  out[2] = total;
  if (with_work_) out[3] = work;
}

Progress::Progress(std::FILE* err, double t_end)
    : err_(err),
      t_end_(t_end),
      terminal_(err != nullptr && isatty(fileno(err)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {
  // The quiet start, 1 s; KANEGEN_PROGRESS_AFTER (seconds) changes it, so
  // that a test can see the line without depending on the machine's speed.
  if (const char* after = std::getenv("KANEGEN_PROGRESS_AFTER")) {
    char* end = nullptr;
    const double seconds = std::strtod(after, &end);
    if (end != after && *end == '\0' && seconds >= 0) quiet_for_ = seconds;
  }
}

void Progress::on_step(double t, long steps) {
  steps_ = steps;
  update(t);  // a step costs several right-hand sides: the clock is cheap beside it
}

void Progress::on_rhs(double t) {
  ++rhs_evals_;
  if (steps_ == 0 && rhs_evals_ % 64 == 0) update(t);
}

void Progress::update(double t) {
  if (!terminal_) return;
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - start_).count();
  // Quiet for short runs, then the line at once (a run shorter than 0.1 s
  // after the quiet start would show none otherwise), then at most ten updates a second.
  if (wall < quiet_for_ || (shown_ && std::chrono::duration<double>(now - last_).count() < 0.1)) return;
  last_ = now;
  shown_ = true;
  std::fprintf(err_, "\r\033[Ksimulate: t = %.6g of %.6g s, wall %.1f s, %ld %s", t, t_end_, wall,
               steps_ > 0 ? steps_ : rhs_evals_, steps_ > 0 ? "steps" : "rhs evaluations");
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
  // Relative to the largest T + |V| of the run: (T + V)(0) can be 0 (a
  // potential's zero at the start, a body at rest) and is no measure then.
  const double scale = energy.scale() > 0 ? energy.scale() : 1.0;
  char text[480];
  // T + V is conserved only without dampers, efforts, body-fixed forces or
  // prescribed motions (the generated `nonconservative`; simulate's inputs
  // are 0): the change is named for what it is.
  const char* meaning = energy.with_work() ? "the error of the energy balance"
                        : energy.nonconservative()
                            ? "not a drift: the model has dampers, efforts, body-fixed "
                              "forces or prescribed motions (--energies adds their "
                              "work W_nc for the energy balance)"
                            : "the energy drift";
  std::snprintf(text, sizeof text,
                "summary: %ld steps to t=%s; %s changed by at most %.3g (%.3g relative to the largest "
                "T+|V|), %s",
                steps, format_double(t_final).c_str(), energy.with_work() ? "T+V-W_nc" : "T+V",
                energy.largest_change(), energy.largest_change() / scale, meaning);
  std::string s = text;
  if (loops) {
    std::snprintf(text, sizeof text, "; largest loop residual |phi| %.3g of the rows written",
                  largest_loop_residual);
    s += text;
  }
  return s + "\n";
}

}  // namespace kanegen::runtime
