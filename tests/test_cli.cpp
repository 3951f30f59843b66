// The glossa command as a user runs it: help, the whole path on a generated corpus, and clear
// errors (naming the file) on bad input, with nothing half-written.
#include <gtest/gtest.h>

#include "io/npy.h"
#include "support/fixtures.h"

namespace glossa {
namespace {
namespace fs = std::filesystem;
using testing::run_command;

std::string G() { return testing::cli_path().string(); }

TEST(Cli, HelpListsTheCommands) {
  std::string out;
  ASSERT_EQ(run_command(G() + " --help", &out), 0);
  for (const char* c : {"corpus", "train", "eval", "predict"})
    EXPECT_NE(out.find(c), std::string::npos) << c;
  ASSERT_EQ(run_command(G() + " train --help", &out), 0);
  EXPECT_NE(out.find("--resume"), std::string::npos);
}

TEST(Cli, DemoCorpusTrainEvalPredict) {
  testing::TempDir t;
  const std::string d = t.path().string();
  std::string out;
  ASSERT_EQ(run_command(G() + " corpus demo " + d + "/src --texts 4 --takes 2", &out), 0) << out;
  ASSERT_EQ(run_command(G() + " corpus import " + d + "/src -o " + d + "/c", &out), 0) << out;
  ASSERT_EQ(run_command(G() + " corpus stats " + d + "/c", &out), 0) << out;
  EXPECT_NE(out.find("TT"), std::string::npos);
  ASSERT_EQ(run_command(G() + " train -q -c " + d + "/c -o " + d + "/m.glossa --split text:04 "
                            "--hidden 32 --layers 1 --epochs 2 --threads 1 --no-cache",
                        &out),
            0)
      << out;
  ASSERT_EQ(run_command(G() + " eval -c " + d + "/c -m " + d + "/m.glossa --csv " + d + "/r.csv",
                        &out),
            0)
      << out;
  EXPECT_NE(out.find("mean pose"), std::string::npos);
  EXPECT_NE(out.find("ridge"), std::string::npos);
  EXPECT_TRUE(fs::exists(t / "r.csv"));
  ASSERT_EQ(run_command(G() + " predict " + d + "/src/S01T101.wav -m " + d + "/m.glossa -o " + d +
                            "/p",
                        &out),
            0)
      << out;
  const auto a = io::read_npy(t / "p.npy");
  ASSERT_EQ(a.shape.size(), 3u);
  EXPECT_EQ(a.shape[1], 10u);
  EXPECT_EQ(a.shape[2], 3u);
  EXPECT_GT(a.shape[0], 50u);
}

TEST(Cli, BadInputGivesAClearErrorAndNoOutput) {
  testing::TempDir t;
  const std::string d = t.path().string();
  std::string out;
  // Missing audio file.
  testing::write_bytes(t / "bad.glossa", "GLOSSAMF-but-not-really");
  EXPECT_EQ(run_command(G() + " predict " + d + "/nope.wav -m " + d + "/bad.glossa", &out), 1);
  EXPECT_NE(out.find("bad.glossa"), std::string::npos) << out;  // the model is read first
  // A damaged model file.
  EXPECT_NE(out.find("error"), std::string::npos) << out;
  // Garbage audio with a real-looking name.
  testing::write_bytes(t / "noise.wav", std::string(1000, 'x'));
  ASSERT_EQ(run_command(G() + " corpus demo " + d + "/src --texts 2 --takes 1", &out), 0);
  ASSERT_EQ(run_command(G() + " corpus import " + d + "/src -o " + d + "/c", &out), 0);
  ASSERT_EQ(run_command(G() + " train -q -c " + d + "/c -o " + d + "/m.glossa --split none "
                            "--hidden 8 --layers 1 --epochs 1 --no-cache",
                        &out),
            0)
      << out;
  EXPECT_EQ(run_command(G() + " predict " + d + "/noise.wav -m " + d + "/m.glossa -o " + d + "/o",
                        &out),
            1);
  EXPECT_NE(out.find("noise.wav"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(t / "o.csv"));
  EXPECT_FALSE(fs::exists(t / "o.npy"));
  // Unknown split and decoder values name the problem.
  EXPECT_EQ(run_command(G() + " train -q -c " + d + "/c -o " + d + "/x.glossa --decoder tcn", &out),
            1);
  EXPECT_NE(out.find("tcn"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(t / "x.glossa"));
  // Not a corpus.
  EXPECT_EQ(run_command(G() + " corpus stats " + d + "/src", &out), 1);
  EXPECT_NE(out.find("manifest.json"), std::string::npos) << out;
}

}  // namespace
}  // namespace glossa
