// cosim run SCENE.yaml [--out DIR] [--set key=value ...] [--tcp [HOST]] [--fluid-exe CMD] [--solid-exe CMD]
//                      [--coupler-exe CMD] [--quiet]
// cosim check SCENE.yaml [--set key=value ...]
// cosim view RUN_DIR [--write]
#include <CLI/CLI.hpp>

#include <unistd.h>
#include <filesystem>
#include <iostream>
#include <string>

#include "common/app/cli_suggest.h"
#include "common/app/version.h"
#include "launcher/launch.h"
#include "launcher/view_command.h"

int main(int argc, char** argv) {
  CLI::App app{"cosim: runs a scene's fluid solver, solid solver and coupler"};
  app.require_subcommand(1);
  app.set_version_flag("--version", cosim::app::version_line("cosim"));
  auto* run = app.add_subcommand("run", "run a scene (fluid alone when it has no solid: section)");
  run->set_version_flag("--version", cosim::app::version_line("cosim"));
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
  run->add_option("--fluid-ranks", o.fluid_ranks,
                  "MPI ranks of the fluid (default: the scene's launcher.fluid_ranks, else 1)")
      ->check(CLI::PositiveNumber);
  run->add_option("--solid-ranks", o.solid_ranks,
                  "MPI ranks of the solid (solid-only or coupled; default: the scene's launcher.solid_ranks, else 1)")
      ->check(CLI::PositiveNumber);
  run->add_flag("--quiet", o.quiet, "no progress line");
  run->add_option("--restart", o.restart,
                  "resume the run in this run directory from its newest complete checkpoint set (the scene may "
                  "change only its end time, checkpoint settings, timeouts and threads)")
      ->check(CLI::ExistingDirectory);
  run->add_option("--from", o.restart_from, "with --restart: the checkpoint set of this cycle instead of the newest")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--progress-every", o.progress_every,
                  "seconds between progress lines when stderr is not a terminal (a log), default 30")
      ->check(CLI::PositiveNumber);
  auto* chk = app.add_subcommand("check", "check a scene as a run would read it, without running or writing anything");
  cosim::launcher::LaunchOptions co;
  chk->add_option("scene", co.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  chk->add_option("--set", co.overrides, "override a scene value: key.path=value (repeatable)");
  chk->add_option("--fluid-ranks", co.fluid_ranks,
                  "the fluid's MPI ranks, as cosim run --fluid-ranks: the plan states their layout, cells and memory")
      ->check(CLI::PositiveNumber);
  chk->add_option("--solid-ranks", co.solid_ranks,
                  "the solid's MPI ranks, as cosim run --solid-ranks: the plan states their parts, elements and memory")
      ->check(CLI::PositiveNumber);
  chk->footer(
      "Examples:\n"
      "  cosim check configs/shock_panel_2d.yaml           every section as its program reads it; exit 0 or 2\n"
      "  cosim check configs/particle_blast_2d.yaml --fluid-ranks 8   the layout of 8 ranks, cells and memory of each\n"
      "  cosim check configs/piston_2d.yaml --set coupling.time.end=1e-3");
  auto* view = app.add_subcommand("view", "open a run in ParaView with its state RUN/view.py");
  std::string view_dir;
  bool view_write = false;
  view->add_option("run", view_dir, "run directory")->required();
  view->add_flag("--write", view_write, "write RUN/view.py anew (from the run as it is now) and open nothing");
  view->footer(
      "Runs paraview --state=RUN/view.py: the fluid coloured by pressure (a 3D fluid on its mid-plane), the solid\n"
      "by von Mises stress, the interface faces, at the last time step. Without a display:\n"
      "  COSIM_VIEW_SCREENSHOT=view.png pvbatch RUN/view.py   a picture of it\n"
      "Examples:\n"
      "  cosim view runs/piston_2d\n"
      "  cosim view runs/piston_2d --write                 view.py written again, nothing opened");
  app.footer(
      "Examples:\n"
      "  cosim run configs/piston_2d.yaml                  coupled run into runs/<scene name>\n"
      "  cosim run configs/sod.yaml --out runs/sod_800 --set 'fluid.mesh.cells=[800]'\n"
      "  cosim check configs/piston_2d.yaml                the scene checked, nothing run\n"
      "  cosim view runs/piston_2d                         the run in ParaView\n"
      "  cosim run --help                                  the options of a run");
  run->footer(
      "Examples:\n"
      "  cosim run configs/shock_panel_2d.yaml             fluid, solid and coupler; results in "
      "runs/shock_panel_2d\n"
      "  cosim run configs/sod.yaml --out runs/sod_800 --set 'fluid.mesh.cells=[800]'\n"
      "  cosim run configs/piston_2d.yaml --set coupling.time.end=1e-3 --quiet\n"
      "  cosim run configs/piston_2d.yaml --tcp             over tcp://127.0.0.1 (processes on one host)\n"
      "  cosim run configs/piston_2d.yaml --restart runs/piston_2d          resume from the newest checkpoint\n"
      "  cosim run configs/piston_2d.yaml --restart runs/piston_2d --from 400 --set coupling.time.end=2.0");
  // The word the user typed is named, before CLI11's "A subcommand is required" or "--out is required".
  std::string unknown;
  if (argc == 1) {
    unknown = "a command is required: cosim run SCENE.yaml [options] (cosim --help for more)";
  } else if (argv[1][0] != '-') {
    unknown = cosim::app::unknown_subcommand(app, argv[1]);
    if (unknown.empty())
      unknown = cosim::app::unknown_option(argv[1] == std::string("view") ? *view : *run, argc, argv, 2);
  } else if (const std::string w = std::string(argv[1]).substr(0, std::string(argv[1]).find('='));
             w != "--version" && w != "--help" && w != "-h") {
    // an option before the command (cosim has none but --help and --version): named with run's closest
    const std::string of_run = cosim::app::unknown_option(*run, 2, argv, 1);
    unknown = of_run.empty() ? "'" + w + "' is an option of 'run': cosim run SCENE.yaml " + w + " ..."
                             : of_run + "; options follow the command: cosim run SCENE.yaml [options]";
  }
  if (!unknown.empty()) {
    std::cerr << "cosim: " << unknown << "\nRun with --help for more information.\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) { return app.exit(e) == 0 ? 0 : 2; }
  std::error_code ec;
  auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path bin_dir = ec ? std::filesystem::path(argv[0]).parent_path() : self.parent_path();
  if (view->parsed()) return cosim::launcher::view(view_dir, view_write);
  if (chk->parsed()) {
    co.bin_dir = bin_dir;
    return cosim::launcher::check(co);
  }
  o.tcp = tcp->count() > 0;
  if (o.tcp && o.tcp_host.empty()) o.tcp_host = "127.0.0.1";
  o.out = out;
  o.bin_dir = bin_dir;
  return cosim::launcher::run(o);
}
