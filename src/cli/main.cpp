// glossa: speech -> tongue, jaw and lip animation. A thin front end over libglossa.
#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"glossa " GLOSSA_VERSION
               " — speech-driven tongue, jaw and lip animation.\n"
               "Import an EMA corpus, train and evaluate speech-to-articulation models, and "
               "predict landmarks from audio."};
  app.set_version_flag("--version", std::string(GLOSSA_VERSION));
  app.require_subcommand(1);
  std::vector<std::pair<CLI::App*, glossa::cli::Run>> runs;
  glossa::cli::add_corpus_commands(app, runs);
  glossa::cli::add_train_command(app, runs);
  glossa::cli::add_eval_command(app, runs);
  glossa::cli::add_predict_command(app, runs);
  glossa::cli::add_phones_command(app, runs);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (auto& [sub, run] : runs)
      if (sub->parsed()) return run();
  } catch (const glossa::Error& e) {
    std::fprintf(stderr, "glossa: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glossa: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
