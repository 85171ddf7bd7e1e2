#include "common/app/run_options.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>

#include "common/app/cli_suggest.h"
#include "common/app/version.h"

namespace cosim::app {

std::optional<int> parse_command_line(int argc, char** argv, const std::string& name, const std::string& description,
                                      const std::string& examples, RunOptions& opt) {
  CLI::App app{name + ": " + description};
  app.footer("Examples:\n" + examples);
  app.add_option("scene", opt.scene_file, "scene file (YAML)")->required();
  app.add_option("--out", opt.out_dir, "output directory (created if missing; required unless --check)");
  app.add_flag("--check", opt.check,
               "validate the scene and the files it names as a run would read them, run nothing, write nothing: "
               "exit 0 when it can run, 2 with the first error");
  app.add_flag("--plan-facts", opt.plan_facts)->group("");  // cosim check's (plan_facts.h): not in --help
  app.add_option("--ranks", opt.check_ranks,
                 "with --check: the plan on this many MPI ranks (the layout, the cells and memory of each rank)")
      ->check(CLI::PositiveNumber);
  app.add_option("--set", opt.overrides, "override a scene key: key.path=value (repeatable)");
  app.add_flag("--quiet,-q", opt.quiet, "no progress line");
  app.add_option("--threads", opt.threads,
                 "OpenMP threads (default: the scene's value, else chosen by the size of the work)");
  app.add_option("--coupler", opt.coupler,
                 "coupled run: the coupler's endpoint (ipc://PATH or tcp://HOST:PORT); the coupler sets time steps "
                 "and output times");
  app.add_option("--token", opt.token,
                 "coupled run: the per-run token the coupler expects (default: $COSIM_TOKEN, which cosim run sets: a "
                 "command line is visible to every user of the machine, an environment only to its owner)");
  app.add_option("--restart", opt.restart,
                 "resume from this checkpoint set (a directory RUN/checkpoints/NNNNNNNNN; cosim run --restart RUN "
                 "chooses it)");
  app.add_option("--checkpoints", opt.checkpoints,
                 "standalone run: the directory of its checkpoint sets (default OUT/checkpoints)");
  app.set_version_flag("--version", version_line(name));
  if (const std::string unknown = unknown_option(app, argc, argv); !unknown.empty()) {
    std::cerr << name << ": " << unknown << "\nRun with --help for more information.\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (opt.out_dir.empty() && !opt.check) {
    std::cerr << name << ": --out is required (the output directory; or --check to validate the scene only)\n"
              << "Run with --help for more information.\n";
    return 2;
  }
  if (opt.token.empty()) opt.token = token_from_environment();
  if (opt.checkpoints.empty() && !opt.out_dir.empty()) opt.checkpoints = opt.out_dir / "checkpoints";
  spdlog::set_default_logger(spdlog::stderr_color_mt(name));  // stdout stays free for data
  spdlog::set_pattern("[" + name + "] %^%l%$: %v");
  if (opt.quiet) spdlog::set_level(spdlog::level::warn);
  return std::nullopt;
}

bool make_output_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    spdlog::error("--out {}: cannot create the output directory ({})", dir.string(), ec.message());
    return false;
  }
  return true;
}

std::string token_from_environment() {
  const char* t = std::getenv("COSIM_TOKEN");
  return t ? t : "";
}

}  // namespace cosim::app
