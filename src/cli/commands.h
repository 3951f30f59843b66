#pragma once
// Each subcommand registers its options on the app and returns the function that runs it.
#include <functional>

#include <CLI/CLI.hpp>

namespace glossa::cli {

using Run = std::function<int()>;

void add_corpus_commands(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs);
void add_train_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs);
void add_eval_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs);
void add_predict_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs);
void add_phones_command(CLI::App& app, std::vector<std::pair<CLI::App*, Run>>& runs);

}  // namespace glossa::cli
