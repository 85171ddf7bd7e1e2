// cosim run SCENE.yaml [--out DIR] [--set key=value ...] [--tcp [HOST]] [--fluid-exe CMD] [--solid-exe CMD]
//                      [--coupler-exe CMD] [--quiet]
#include <CLI/CLI.hpp>

#include <unistd.h>
#include <filesystem>
#include <iostream>

#include "common/app/cli_suggest.h"
#include "common/app/version.h"
#include "launcher/launch.h"

int main(int argc, char** argv) {
  CLI::App app{"cosim: runs a scene's fluid solver, solid solver and coupler"};
  app.require_subcommand(1);
  app.set_version_flag("--version", cosim::app::version_line("cosim"));
  auto* run = app.add_subcommand("run", "run a scene (fluid alone when it has no solid: section)");
  cosim::launcher::LaunchOptions o;
  std::string out;
  run->add_option("scene", o.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  run->add_option("--out", out, "run directory (default runs/<scene name>)");
  run->add_option("--set", o.overrides, "override a scene value: key.path=value (repeatable)");
  auto* tcp = run->add_option("--tcp", o.tcp_host, "use tcp:// on HOST (default 127.0.0.1) instead of ipc://")
                  ->expected(0, 1)
                  ->default_str("127.0.0.1");
  run->add_option("--fluid-exe", o.fluid_cmd, "fluid command (default: fluid_solver next to cosim)");
  run->add_option("--solid-exe", o.solid_cmd, "solid command (default: solid_solver next to cosim)");
  run->add_option("--coupler-exe", o.coupler_cmd, "coupler command (default: coupler next to cosim)");
  run->add_flag("--quiet", o.quiet, "no progress line");
  run->add_option("--progress-every", o.progress_every,
                  "seconds between progress lines when stderr is not a terminal (a log), default 30")
      ->check(CLI::PositiveNumber);
  if (argc > 1 && argv[1][0] != '-') {
    std::string unknown = cosim::app::unknown_subcommand(app, argv[1]);
    if (unknown.empty()) unknown = cosim::app::unknown_option(*run, argc, argv, 2);
    if (!unknown.empty()) {
      std::cerr << "cosim: " << unknown << "\nRun with --help for more information.\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) { return app.exit(e) == 0 ? 0 : 2; }
  o.tcp = tcp->count() > 0;
  if (o.tcp && o.tcp_host.empty()) o.tcp_host = "127.0.0.1";
  o.out = out;
  std::error_code ec;
  auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  o.bin_dir = ec ? std::filesystem::path(argv[0]).parent_path() : self.parent_path();
  return cosim::launcher::run(o);
}
