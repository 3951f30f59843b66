#include "eval/report.h"

#include <cmath>

#include <fmt/format.h>

namespace glossa::eval {

namespace {

double reference_error(const std::vector<ResultRow>& rows, const std::string& ref) {
  for (const auto& r : rows)
    if (r.name == ref) return r.metrics.mean_error_mm;
  return NAN;
}

std::string num(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, digits) : "–";
}

std::string params(int64_t n) {
  if (n <= 0) return "0";
  if (n < 1000) return std::to_string(n);
  return fmt::format("{:.2e}", double(n));
}

}  // namespace

std::string markdown_table(const std::vector<ResultRow>& rows, const LandmarkSet& set,
                           const std::string& reference) {
  const double ref = reference_error(rows, reference);
  std::string out = "| Model | Mean error [mm] | × mean pose |";
  std::string rule = "|---|---|---|";
  for (const auto& n : set.names) {
    out += " " + n + " |";
    rule += "---|";
  }
  out += " RMSE [mm] | Pearson r | Params | Train [min] | Inference [ms/s] |\n";
  rule += "---|---|---|---|---|\n";
  out += rule;
  for (const auto& r : rows) {
    out += fmt::format("| {} | {} | {} |", r.name, num(r.metrics.mean_error_mm, 3),
                       num(r.metrics.mean_error_mm / ref, 3));
    for (double e : r.metrics.per_landmark_mm) out += " " + num(e, 2) + " |";
    out += fmt::format(" {} | {} | {} | {} | {} |\n", num(r.metrics.rmse_mm, 3),
                       num(r.metrics.pearson, 3), params(r.parameters), num(r.train_minutes, 2),
                       num(r.infer_ms_per_s, 3));
  }
  return out;
}

std::string csv_table(const std::vector<ResultRow>& rows, const LandmarkSet& set,
                      const std::string& reference) {
  const double ref = reference_error(rows, reference);
  std::string out = "model,mean_error_mm,ratio_to_mean_pose";
  for (const auto& n : set.names) out += "," + n + "_mm";
  out += ",rmse_mm,pearson_r,parameters,train_minutes,inference_ms_per_s,utterances,frames\n";
  for (const auto& r : rows) {
    out += fmt::format("\"{}\",{:.6f},{:.6f}", r.name, r.metrics.mean_error_mm,
                       r.metrics.mean_error_mm / ref);
    for (double e : r.metrics.per_landmark_mm) out += fmt::format(",{:.6f}", e);
    out += fmt::format(",{:.6f},{:.6f},{},{:.4f},{:.4f},{},{}\n", r.metrics.rmse_mm,
                       r.metrics.pearson, r.parameters, r.train_minutes, r.infer_ms_per_s,
                       r.metrics.utterances, r.metrics.frames);
  }
  return out;
}

}  // namespace glossa::eval
