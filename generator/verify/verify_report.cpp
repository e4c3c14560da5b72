// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_report.hpp"

#include <cmath>

namespace kanegen::verify {
namespace {

std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", x);
  return buf;
}

}  // namespace

void Row::consider(const Worst& candidate) {
  if (candidate.where < 0) return;
  const bool worse = std::isnan(candidate.rel) ? !std::isnan(worst.rel) || worst.where < 0
                                               : worst.where < 0 || candidate.rel > worst.rel;
  if (worse) worst = candidate;
}

double max_abs(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) {
    if (std::isnan(v)) return v;
    m = std::max(m, std::abs(v));
  }
  return m;
}

Worst compare(const std::vector<double>& generated, const std::vector<double>& reference, double scale,
              const EntryName& name, int where) {
  Worst w;
  w.where = where;
  int at = -1;
  for (std::size_t i = 0; i < reference.size() && i < generated.size(); ++i) {
    const double d = std::abs(generated[i] - reference[i]);
    if (at < 0 || std::isnan(d) || d > w.abs) {
      at = static_cast<int>(i);
      w.abs = d;
      if (std::isnan(d)) break;
    }
  }
  if (at < 0) return w;  // nothing to compare: no error
  w.rel = w.abs / scale;
  w.entry = name(at);
  w.generated = generated[at];
  w.numeric = reference[at];
  return w;
}

Worst compare_entries(const std::vector<double>& generated, const std::vector<double>& reference,
                      const std::vector<double>& scale, const EntryName& name, int where) {
  Worst w;
  w.where = where;
  int at = -1;
  for (std::size_t i = 0; i < reference.size() && i < generated.size() && i < scale.size(); ++i) {
    const double d = std::abs(generated[i] - reference[i]), rel = d / scale[i];
    if (at < 0 || std::isnan(rel) || rel > w.rel) {
      at = static_cast<int>(i);
      w.rel = rel;
      w.abs = d;
      if (std::isnan(rel)) break;
    }
  }
  if (at < 0) return w;  // nothing to compare: no error
  w.entry = name(at);
  w.generated = generated[at];
  w.numeric = reference[at];
  return w;
}

void print_table(std::FILE* out, const ReportHeader& h, const std::vector<Row>& rows) {
  std::fprintf(out, "kanegen verify: %s (%d coordinates, %d parameters), %d samples, seed %lu, rtol %g\n",
               h.model.c_str(), h.coordinates, h.parameters, h.samples, h.seed, h.rtol);
  std::fprintf(out, "%-24s %-28s %-10s %-10s %-9s %-6s %s\n", "quantity", "against", "abs error", "rel error",
               "tolerance", "result", "worst at");
  for (const Row& r : rows) {
    if (!r.applicable) {
      std::fprintf(out, "%-24s %-28s %-10s %-10s %-9s %-6s %s\n", r.quantity.c_str(), r.against.c_str(), "-",
                   "-", "-", "n/a", r.note.c_str());
      continue;
    }
    // Where the largest error occurred (nothing to point at if every comparison was exact).
    const bool exact = r.worst.abs == 0 && r.worst.rel == 0;
    std::string at = r.worst.where < 0 || exact ? "-" : r.where_kind + " " + std::to_string(r.worst.where);
    if (!exact && !r.worst.entry.empty()) at += " " + r.worst.entry;
    if (!r.note.empty()) at = exact ? r.note : at + "; " + r.note;
    std::fprintf(out, "%-24s %-28s %-10s %-10s %-9s %-6s %s\n", r.quantity.c_str(), r.against.c_str(),
                 sci(r.worst.abs).c_str(), sci(r.worst.rel).c_str(), sci(r.tolerance).c_str(),
                 r.passed() ? "ok" : "FAIL", at.c_str());
  }
}

nlohmann::json report_json(const ReportHeader& h, const std::vector<Row>& rows,
                           const std::vector<std::string>& failures) {
  nlohmann::json j{{"model", h.model},
                   {"coordinates", h.coordinates},
                   {"parameters", h.parameters},
                   {"samples", h.samples},
                   {"seed", h.seed},
                   {"rtol", h.rtol},
                   {"seconds", h.seconds},
                   {"failures", failures}};
  bool passed = true;
  j["quantities"] = nlohmann::json::array();
  for (const Row& r : rows) {
    passed = passed && r.passed();
    nlohmann::json q{{"quantity", r.quantity}, {"against", r.against},   {"applicable", r.applicable},
                     {"passed", r.passed()},   {"compared", r.compared}, {"note", r.note}};
    if (r.applicable) {
      // JSON has no NaN: a non-finite error is written as null (and has failed).
      const auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
      q["abs_error"] = number(r.worst.abs);
      q["rel_error"] = number(r.worst.rel);
      q["tolerance"] = r.tolerance;
      if (r.worst.where >= 0)
        q["worst"] = {{r.where_kind, r.worst.where},
                      {"entry", r.worst.entry},
                      {"generated", number(r.worst.generated)},
                      {"reference", number(r.worst.numeric)}};
    }
    j["quantities"].push_back(q);
  }
  j["passed"] = passed && failures.empty();
  return j;
}

}  // namespace kanegen::verify
