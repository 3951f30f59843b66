// Inference speed of features + decoder on one core, per second of audio. Trains nothing: the
// models are built with random weights of the configured size (speed does not depend on the
// values) and saved/loaded through the real model-file path.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "features/encoder.h"
#include "nn/decoder_config.h"
#include "nn/model.h"
#include "nn/model_file.h"
#include "nn/torch_decoder.h"

namespace {
using namespace glossa;

Audio ten_seconds() {
  Audio a;
  std::mt19937 rng(1);
  std::normal_distribution<float> n(0, 0.1f);
  a.samples.resize(16000 * 10);
  for (size_t i = 0; i < a.samples.size(); ++i)
    a.samples[i] = 0.3f * std::sin(2 * M_PI * 150 * i / 16000.0) + n(rng);
  return a;
}

std::filesystem::path make_model(const std::string& type, int layers, int hidden, bool bi,
                                 int window) {
  nn::DecoderConfig d;
  d.type = type;
  d.layers = layers;
  d.hidden = hidden;
  d.bidirectional = bi;
  d.inference_window = window;
  const auto enc = features::make_encoder("mfcc");
  const int out = 21;
  nn::DecoderNet net(d, enc->dims(), out);
  nn::ModelFile mf;
  nn::export_tensors(net, mf.tensors);
  std::vector<float> zeros_in(enc->dims(), 0.f), ones_in(enc->dims(), 1.f);
  std::vector<float> zeros_out(out, 0.f), ones_out(out, 1.f);
  nlohmann::json& h = mf.header;
  h["kind"] = "glossa-landmark-model";
  h["landmark_set"] = std::vector<std::string>{"UL", "LL", "LLC", "RLC", "TR", "TM", "TT"};
  h["encoder"] = enc->config();
  h["feature_norm"]["mean"] = zeros_in;
  h["feature_norm"]["std"] = ones_in;
  h["target_norm"]["mean"] = zeros_out;
  h["target_norm"]["std"] = ones_out;
  h["decoder"] = d.to_json();
  h["neutral"]["default"] = zeros_out;
  const auto p = std::filesystem::temp_directory_path() /
                 ("glossa-bench-" + d.label() + std::to_string(hidden) + "w" +
                  std::to_string(window) + ".glossa");
  mf.write(p);
  return p;
}

// window: RNN inference window in frames (0 = the whole utterance in one pass).
void BM_Predict(benchmark::State& st, std::string type, int layers, bool bi, int window) {
  nn::set_threads(1);
  const int hidden = static_cast<int>(st.range(0));
  const auto model = nn::Model::load(make_model(type, layers, hidden, bi, window));
  const Audio audio = ten_seconds();
  for (auto _ : st) benchmark::DoNotOptimize(model.predict(audio));
  // Items = seconds of audio, so items_per_second is the real-time factor.
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations()) * 10);
  st.counters["hidden"] = hidden;
}

void BM_Mfcc(benchmark::State& st) {
  const auto enc = features::make_encoder("mfcc");
  const Audio audio = ten_seconds();
  for (auto _ : st) benchmark::DoNotOptimize(enc->encode(audio));
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations()) * 10);
}

}  // namespace

BENCHMARK(BM_Mfcc)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Predict, gru2, std::string("gru"), 2, false, 0)
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Predict, bigru2, std::string("gru"), 2, true, 0)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Predict, bigru2_window15, std::string("gru"), 2, true, 15)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Predict, mlp, std::string("mlp"), 2, false, 0)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
