#pragma once
// Per-dimension standardisation statistics (mean, std), computed once over a training set and
// stored in the model file so that inference applies exactly the same transform.
#include <nlohmann/json.hpp>
#include <vector>

#include "core/matrix.h"

namespace glossa::features {

struct Normalizer {
  RowVec mean;
  RowVec std;

  bool empty() const { return mean.size() == 0; }
  // Statistics over the rows of all matrices; std is floored at `min_std`.
  static Normalizer fit(const std::vector<const MatrixRM*>& data, float min_std = 1e-3f);
  MatrixRM apply(const MatrixRM& x) const;
  MatrixRM invert(const MatrixRM& z) const;
  nlohmann::json to_json() const;
  static Normalizer from_json(const nlohmann::json& j);
};

}  // namespace glossa::features
