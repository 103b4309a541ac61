//! The `polycube` command: parse, set up logging, call one library entry point per subcommand.
#include "cli/app.h"

int main(int argc, char** argv) {
  using namespace polycube::cli;
  keep_freed_memory();
  install_interrupt_handler();
  CLI::App app{
      "polycube: polycube maps, coarse block layouts, hex and quad meshes, fabrication.\n"
      "Run `polycube <subcommand> --help` for the options of each step.",
      "polycube"};  // named, so that usage lines say "polycube", not the path it was started by
  app.set_version_flag("--version", std::string("polycube ") + kVersion);
  for (int i = 0; i < argc; ++i) global_options().command_line += (i ? " " : "") + std::string(argv[i]);
  app.formatter(help_formatter());
  app.footer(
      "Exit codes: 0 done; 1 usage error; 2 bad input (or an output that cannot be written); 3 no valid "
      "result (the stage and reason on stderr and in report.json); 4 internal error; 130 interrupted.");
  app.require_subcommand(1);
  app.fallthrough();
  add_global_flags(app);

  register_info(app);
  register_convert(app);
  register_repair(app);
  register_sample(app);
  register_label(app);
  register_construct(app);
  register_quality(app);
  register_structure(app);
  register_hexmesh(app);
  register_quadmesh(app);
  register_simplify(app);
  register_optimize(app);
  register_pad(app);
  register_run(app);
  register_fabricate(app);
  register_check_fab(app);

  add_config_options(app);
  capture_defaults(app);
  app.parse_complete_callback([&app] {
    setup_logging_and_progress();
    limit_threads();
    save_config_if_asked(app);
  });

  // Subcommand callbacks run inside parse(); library exceptions map to exit codes there.
  int usage = -1;
  const int rc = run_guarded([&] {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      usage = app.exit(e) == 0 ? kOk : kUsage;  // --help and --version exit 0
    }
  });
  return usage >= 0 ? usage : rc;
}
