#pragma once
#include <Eigen/Core>

namespace glossa {

// Row-major float matrix: rows are frames, so a row is one contiguous frame, laid out as NumPy
// (C order) lays out [frames, dims].
using MatrixRM = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowVec = Eigen::Matrix<float, 1, Eigen::Dynamic>;

}  // namespace glossa
