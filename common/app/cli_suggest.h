// Command-line words a program does not know, named with the closest one it does. CLI11 reports an unknown option
// only after any missing required one ("--output x" said "--out is required") and an unknown subcommand as a
// missing one ("A subcommand is required"); checking first names the word the user typed.
#pragma once

#include <CLI/CLI.hpp>

#include <set>
#include <string>

#include "common/config/config.h"

namespace cosim::app {

// "" when every "--name" argument from argv[first] on is an option of `app`, else the message for the first that
// is not: "unknown option '--output' (did you mean '--out'?)".
inline std::string unknown_option(const CLI::App& app, int argc, char** argv, int first = 1) {
  std::set<std::string> known{"--help"};
  for (const CLI::Option* o : app.get_options())
    for (const std::string& l : o->get_lnames()) known.insert("--" + l);
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") break;  // the rest are positional
    if (a.rfind("--", 0) != 0) continue;
    const std::string name = a.substr(0, a.find('='));
    if (known.count(name)) continue;
    const std::string best = config::closest(name, known);
    return "unknown option '" + name + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)");
  }
  return "";
}

// "" when `word` names a subcommand of `app`, else "unknown command 'frobnicate' (did you mean 'run'?)".
inline std::string unknown_subcommand(const CLI::App& app, const std::string& word) {
  std::set<std::string> names;
  for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; })) names.insert(s->get_name());
  if (names.count(word)) return "";
  const std::string best = config::closest(word, names);
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  return "unknown command '" + word + "' (" + (best.empty() ? "commands: " + all : "did you mean '" + best + "'?") +
         ")";
}

}  // namespace cosim::app
