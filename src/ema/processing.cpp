#include "ema/processing.h"

#include <Eigen/Dense>
#include <cmath>

#include "audio/resample.h"
#include "core/error.h"
#include "ema/source.h"

namespace glossa::ema {

bool is_reference_sensor(const std::string& name) { return name.rfind("REF", 0) == 0; }

namespace {

using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;

// Rigid transform (R, t) minimising sum |R * src_i + t - dst_i|^2.
void kabsch(const Mat3X& src, const Mat3X& dst, Eigen::Matrix3d& R, Eigen::Vector3d& t) {
  const Eigen::Vector3d cs = src.rowwise().mean();
  const Eigen::Vector3d cd = dst.rowwise().mean();
  const Eigen::Matrix3d H = (src.colwise() - cs) * (dst.colwise() - cd).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) D(2, 2) = -1;
  R = svd.matrixV() * D * svd.matrixU().transpose();
  t = cd - R * cs;
}

Eigen::Vector3d point(const LandmarkSeq& s, Eigen::Index f, int l) {
  return s.positions.block(f, 3 * l, 1, 3).transpose().cast<double>();
}

bool finite_row(const LandmarkSeq& s, Eigen::Index f, const std::vector<int>& idx) {
  for (int l : idx)
    if (!point(s, f, l).allFinite()) return false;
  return true;
}

}  // namespace

LandmarkSeq stabilise_head(const LandmarkSeq& seq) {
  std::vector<int> refs, keep;
  for (size_t i = 0; i < seq.set.size(); ++i)
    (is_reference_sensor(seq.set.names[i]) ? refs : keep).push_back(static_cast<int>(i));
  if (refs.size() < 3)
    throw Error("head stabilisation needs at least 3 reference sensors (REF-...), found " +
                std::to_string(refs.size()));

  const Eigen::Index frames = seq.positions.rows();
  Eigen::Index first = -1;
  for (Eigen::Index f = 0; f < frames && first < 0; ++f)
    if (finite_row(seq, f, refs)) first = f;
  if (first < 0) throw Error("head stabilisation: no frame has all reference sensors");

  // Template: the references of the first complete frame, moved into the head frame when the
  // three standard references are present.
  Mat3X tmpl(3, refs.size());
  for (size_t k = 0; k < refs.size(); ++k) tmpl.col(k) = point(seq, first, refs[k]);
  const int ui = seq.set.index_of("REF-UI"), lm = seq.set.index_of("REF-LM"),
            rm = seq.set.index_of("REF-RM");
  if (ui >= 0 && lm >= 0 && rm >= 0) {
    const Eigen::Vector3d pui = point(seq, first, ui), plm = point(seq, first, lm),
                          prm = point(seq, first, rm);
    const Eigen::Vector3d y = (plm - prm).normalized();
    Eigen::Vector3d x = pui - 0.5 * (plm + prm);
    x = (x - x.dot(y) * y).normalized();
    const Eigen::Vector3d z = x.cross(y);
    Eigen::Matrix3d basis;
    basis.row(0) = x.transpose();
    basis.row(1) = y.transpose();
    basis.row(2) = z.transpose();
    tmpl = basis * (tmpl.colwise() - pui);
  }

  LandmarkSeq out;
  out.rate = seq.rate;
  for (int k : keep) out.set.names.push_back(seq.set.names[k]);
  out.positions.setConstant(frames, 3 * static_cast<Eigen::Index>(keep.size()), NAN);
  Mat3X src(3, refs.size());
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  for (Eigen::Index f = 0; f < frames; ++f) {
    if (!finite_row(seq, f, refs)) continue;
    for (size_t k = 0; k < refs.size(); ++k) src.col(k) = point(seq, f, refs[k]);
    kabsch(src, tmpl, R, t);
    for (size_t k = 0; k < keep.size(); ++k) {
      const Eigen::Vector3d p = R * point(seq, f, keep[k]) + t;
      out.positions.block(f, 3 * k, 1, 3) = p.transpose().cast<float>();
    }
  }
  return out;
}

GapReport fill_gaps(LandmarkSeq& seq, double max_gap_s) {
  GapReport report;
  const Eigen::Index n = seq.positions.rows();
  const double rate = seq.rate;
  // First pass: measure, so that nothing changes when the utterance must be skipped.
  for (Eigen::Index c = 0; c < seq.positions.cols(); ++c) {
    Eigen::Index run = 0, valid = 0;
    for (Eigen::Index f = 0; f <= n; ++f) {
      if (f < n && !std::isfinite(seq.positions(f, c))) {
        ++run;
        continue;
      }
      if (f < n) ++valid;
      if (run > 0 && run / rate > report.longest_gap_s) {
        report.longest_gap_s = run / rate;
        report.worst_sensor = seq.set.names[static_cast<size_t>(c / 3)];
      }
      run = 0;
    }
    if (valid == 0 && n > 0) {
      report.ok = false;
      report.longest_gap_s = n / rate;
      report.worst_sensor = seq.set.names[static_cast<size_t>(c / 3)];
      return report;
    }
  }
  if (report.longest_gap_s > max_gap_s) {
    report.ok = false;
    return report;
  }
  for (Eigen::Index c = 0; c < seq.positions.cols(); ++c) {
    Eigen::Index f = 0;
    while (f < n) {
      if (std::isfinite(seq.positions(f, c))) {
        ++f;
        continue;
      }
      Eigen::Index end = f;
      while (end < n && !std::isfinite(seq.positions(end, c))) ++end;
      const bool has_before = f > 0, has_after = end < n;
      const float a = has_before ? seq.positions(f - 1, c) : seq.positions(end, c);
      const float b = has_after ? seq.positions(end, c) : a;
      for (Eigen::Index k = f; k < end; ++k) {
        const float w = static_cast<float>(k - f + 1) / static_cast<float>(end - f + 1);
        seq.positions(k, c) = has_before && has_after ? a + (b - a) * w : (has_before ? a : b);
      }
      if (c % 3 == 0) ++report.filled_runs;
      f = end;
    }
  }
  return report;
}

LandmarkSeq resample(const LandmarkSeq& seq, double out_rate, Resampling method) {
  if (seq.rate <= 0 || out_rate <= 0) throw Error("landmark resampling: rates must be positive");
  LandmarkSeq out;
  out.set = seq.set;
  out.rate = out_rate;
  const Eigen::Index n = seq.positions.rows();
  if (n == 0) {
    out.positions.resize(0, seq.positions.cols());
    return out;
  }
  const auto m = static_cast<Eigen::Index>(std::floor((n - 1) * out_rate / seq.rate + 1e-9)) + 1;
  if (method == Resampling::kNearest || seq.rate == out_rate) {
    out.positions.resize(m, seq.positions.cols());
    for (Eigen::Index k = 0; k < m; ++k) {
      auto src = static_cast<Eigen::Index>(std::llround(k * seq.rate / out_rate));
      out.positions.row(k) = seq.positions.row(std::min(src, n - 1));
    }
    return out;
  }
  const int ch = static_cast<int>(seq.positions.cols());
  // soxr works best on zero-mean signals: remove each channel's mean, then add it back.
  const RowVec mean = seq.positions.colwise().mean();
  std::vector<float> interleaved(seq.positions.size());
  for (Eigen::Index f = 0; f < n; ++f)
    for (int c = 0; c < ch; ++c) interleaved[f * ch + c] = seq.positions(f, c) - mean(c);
  std::vector<float> res = audio::resample(interleaved, ch, seq.rate, out_rate);
  const Eigen::Index got = static_cast<Eigen::Index>(res.size()) / ch;
  if (got == 0) return resample(seq, out_rate, Resampling::kNearest);  // too short to filter
  out.positions.resize(m, ch);
  for (Eigen::Index k = 0; k < m; ++k)
    for (int c = 0; c < ch; ++c)
      out.positions(k, c) = res[std::min(k, got - 1) * ch + c] + mean(c);
  return out;
}

Resampling parse_resampling(const std::string& name) {
  if (name == "nearest") return Resampling::kNearest;
  if (name == "antialiased" || name == "soxr") return Resampling::kAntialiased;
  throw Error("unknown resampling method '" + name + "' (use nearest or antialiased)");
}

}  // namespace glossa::ema
