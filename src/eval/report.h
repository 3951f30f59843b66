#pragma once
// Results tables in the shape of the papers' Table 2, as Markdown and as CSV.
#include <string>
#include <vector>

#include "ema/landmarks.h"
#include "eval/evaluate.h"

namespace glossa::eval {

// `reference` names the row the "x mean pose" column divides by (normally "mean pose").
std::string markdown_table(const std::vector<ResultRow>& rows, const LandmarkSet& set,
                           const std::string& reference = "mean pose");
std::string csv_table(const std::vector<ResultRow>& rows, const LandmarkSet& set,
                      const std::string& reference = "mean pose");

}  // namespace glossa::eval
