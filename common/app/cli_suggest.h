// Command-line words a program does not know, named with the closest one it does. CLI11 reports an unknown option
// only after any missing required one ("--output x" said "--out is required") and an unknown subcommand as a
// missing one ("A subcommand is required"); checking first names the word the user typed.
#pragma once

#include <CLI/CLI.hpp>

#include <cctype>
#include <set>
#include <string>

#include "common/config/config.h"

namespace cosim::app {

// "" when every option word from argv[first] on ("--name", "--name=value", "-x") is an option of `app`, else the
// message for the first that is not: "unknown option '--output' (did you mean '--out'?)". A single-dash word is
// matched by its letters against the long names too ("-o", "-out": '--out'); a negative number is a value.
inline std::string unknown_option(const CLI::App& app, int argc, char** argv, int first = 1) {
  std::set<std::string> known{"--help", "-h"}, longs{"--help"};
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) {
      known.insert("--" + l);
      longs.insert("--" + l);
    }
    for (const std::string& s : o->get_snames()) known.insert("-" + s);
  }
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") break;  // the rest are positional
    if (a.size() < 2 || a[0] != '-' || std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.') continue;
    const std::string name = a.substr(0, a.find('='));
    if (known.count(name)) continue;
    std::string best;
    if (name[1] != '-') {  // "-o": the one long option starting with "--o"; "-out": else the closest to "--out"
      const std::string as_long = "-" + name;
      for (const std::string& l : longs)
        if (l.rfind(as_long, 0) == 0) best = best.empty() ? l : "-";
      if (best == "-") best.clear();
      if (best.empty() && name.size() > 2) best = config::closest(as_long, longs);
    } else {
      best = config::closest(name, longs);
    }
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
