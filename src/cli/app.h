#pragma once
//! \file app.h
//! \brief Shared plumbing of the `polycube` subcommands: global flags, logging, progress,
//! output, exit codes (ARCHITECTURE §4: 0 ok, 1 usage, 2 bad input, 3 no valid result,
//! 4 internal error).

#include "core/progress.h"
#include "core/types.h"
#include "repair/repair.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <utility>
#include <string>
#include <vector>

namespace polycube::mesh {
enum class GridSizing;
}
namespace polycube::quality {
struct ScaledJacobianSummary;
}
namespace polycube::construct {
struct ConstructOptions;
struct Attempt;
}
namespace polycube::optimize {
struct FoldoverReport;
}

namespace polycube::cli {

enum ExitCode : int { kOk = 0, kUsage = 1, kBadInput = 2, kNoResult = 3, kInternal = 4 };

//! Validators for numeric options, in place of CLI11's PositiveNumber, NonNegativeNumber and
//! Range: theirs print the largest double in full for an open bound ("not in range 0.000000 to
//! 17976931348623157...") and let nan through a range (every comparison with nan is false).
//! These refuse nan and infinities and say the bound in plain words.
CLI::Validator positive();                        //!< finite and > 0
CLI::Validator non_negative();                    //!< finite and >= 0
CLI::Validator auto_or_non_negative();            //!< 'auto', or finite and >= 0
CLI::Validator in_range(double lo, double hi);    //!< finite and within [lo, hi]

//! Flags every subcommand understands.
struct GlobalOptions {
  int verbose = 0;     //!< -v: info, -vv: debug
  bool quiet = false;  //!< -q: errors only, no progress
  bool json = false;   //!< --json: machine-readable summary on stdout
  //! The command line as given (argv joined by spaces), recorded in reports.
  std::string command_line;
  std::string log_file;     //!< --log FILE: every message also goes there, with its time
  std::string save_config;  //!< --save-config FILE: the command's settings written there (TOML)
  int threads = 0;          //!< --threads N: worker threads at most (0: every core)
};

//! The program's version, as --version prints it and reports record it.
inline constexpr const char* kVersion = "0.1.0";

//! The options of the running process (set once by main).
GlobalOptions& global_options();

//! Add -v/-q/--json to a (sub)command.
void add_global_flags(CLI::App& app);

//! Install the stderr logger and, when stderr is a terminal and not quiet, the progress bar.
void setup_logging_and_progress();

//! Apply --threads for the rest of the process (call once, after parsing).
void limit_threads();

//! Let the allocator keep freed memory for reuse instead of returning it to the system and
//! faulting it in again (call first in main).
void keep_freed_memory();

//! `--config FILE` (read settings from a TOML file, as --save-config writes them; the command
//! line wins) and `--save-config FILE` on the top app.
void add_config_options(CLI::App& app);

//! After parsing: write the settings of the command as given (and every default) to the file
//! of --save-config, if any; the command then runs as usual.
void save_config_if_asked(const CLI::App& app);

//! A line of news on stderr (a stage starts, an attempt fails), clearing the progress bar first
//! on a terminal.
void print_status(const std::string& line);

//! Print a summary: `json` as JSON on stdout when --json was given, else `text` (unless empty).
void print_result(const nlohmann::json& json, const std::string& text);

//! A scaled-Jacobian summary as JSON, so that every command reporting one gives it the same shape:
//! `{"min", "average", "max", "inverted", "invalid", "histogram": [{"lower", "upper", "count"}, ...]}`.
nlohmann::json scaled_jacobian_json(const quality::ScaledJacobianSummary& summary);

//! Progress lines of construct's attempts on stderr (unless -q or --json): which attempt starts
//! and how long the construction has run (construct::ConstructOptions::on_attempt).
std::function<void(int, int, const construct::Attempt&, double)> attempt_progress();

//! A target surface as triangles: a surface file's triangles (quads split), or a volume mesh's
//! boundary. \throw core::InputError when the file has neither
core::TriMesh read_target_surface(const std::string& path);

//! `--target SURFACE` of the commands that keep a mesh's boundary on a surface, and how far the
//! mesh may start from it.
struct TargetOption {
  std::string path;
  //! Largest Hausdorff distance between the input mesh's boundary and the target before any
  //! work, as a fraction of the target's bounding-box diagonal: a gridded mesh starts within a
  //! few percent, a mesh of another shape or another placement much farther.
  double max_start_distance = 0.1;
};

//! Add the required `--target SURFACE` and `--max-start-distance`.
void add_target_option(CLI::App& sub, TargetOption& target);

//! Read the target and check that the hex mesh read from `mesh_file` starts near it.
//! \throw core::InputError naming both files and the distance when it is beyond the bound
core::TriMesh read_fitting_target(const TargetOption& target, const core::HexMesh& mesh, const std::string& mesh_file);

//! The global fold-over check as JSON: `{"ok", "reason", "inverted_hexes",
//! "nonpositive_scaled_jacobian", "boundary_self_intersections", "crossings": [[x, y, z], ...]}`.
nlohmann::json foldover_json(const optimize::FoldoverReport& check);

//! Help that says choices and defaults in words: `--sizing uniform|map ... (default: uniform)`,
//! `--hexes N ... (a positive number; default: 20000)`, where CLI11's own formatter prints
//! `ENUM:value in {map->1,uniform->0} OR {1,0}=0`. Install on the top app before subcommands.
std::shared_ptr<CLI::FormatterBase> help_formatter();

//! The progress client used off a terminal: a line to `out` at most every `interval`.
std::shared_ptr<core::ProgressClient> line_progress(std::FILE* out, std::chrono::milliseconds interval);

//! A validator for one of `names`, in any case: turns it into the name as listed, refuses
//! anything else with the list of names.
CLI::Validator one_of(const std::vector<std::string>& names);

//! Add `--name a|b|c` storing an enum: `choices` in the order the help lists them; the current
//! value of `value` is shown as the default by its name, and reports record the name given.
template <class Enum>
CLI::Option* add_choice(CLI::App& sub, const std::string& name, Enum& value,
                        const std::vector<std::pair<std::string, Enum>>& choices, const std::string& help) {
  std::vector<std::string> names;
  std::string default_name, type;
  for (const auto& [n, v] : choices) {
    names.push_back(n);
    if (v == value) default_name = n;
    type += (type.empty() ? "" : "|") + n;
  }
  auto set = [&value, choices](const std::string& given) {
    for (const auto& [n, v] : choices)
      if (n == given) value = v;
  };
  return sub.add_option_function<std::string>(name, set, help)
      ->transform(one_of(names))
      ->type_name(type)
      ->default_str(default_name);
}

//! Add `--sizing uniform|map` (mesh/grid.h) to a subcommand.
CLI::Option* add_sizing_option(CLI::App& sub, mesh::GridSizing& sizing, const std::string& help);

//! Add `--chamber X Y Z` (fabrication's build volume) to a subcommand.
CLI::Option* add_chamber_option(CLI::App& sub, std::vector<double>& chamber);

//! Hide `expert` from the subcommand's --help and add `--help-expert`, which lists them too.
void add_expert_options(CLI::App& sub, const std::vector<CLI::Option*>& expert);

//! The repairs that change the geometry (repair/repair.h), for the commands that read a
//! surface: `--repair holes|wrap` (repeatable or comma-separated), `--largest-component`, and
//! their settings (`--max-hole`, `--wrap-alpha`, `--wrap-offset`). Returns the options of the
//! settings, for add_expert_options.
std::vector<CLI::Option*> add_repair_options(CLI::App& sub, repair::RepairOptions& o);

//! --coarse-edge-ratio of construct and run (an expert option: the caller groups it).
CLI::Option* add_coarse_edge_option(CLI::App& sub, construct::ConstructOptions& o);

//! --max-triangles of construct and run; returns the expert options --decimate-to and
//! --decimation-tolerance, which the caller groups.
std::vector<CLI::Option*> add_decimation_options(CLI::App& sub, construct::ConstructOptions& o);

//! Run the parsed application, mapping exceptions to exit codes and one-line messages (and,
//! with --json, a JSON object `{"status": "failed", "exit_code", "error"}` on stdout unless the
//! command already printed its own).
int run_guarded(const std::function<void()>& body);

//! Ctrl-C (SIGINT, unless the shell started us ignoring it) and SIGTERM: run the action set by
//! on_interrupt (`run` writes its report with status "interrupted"), say "interrupted" and exit
//! with code 130. Call first in main.
void install_interrupt_handler();

//! What to do on an interrupt before exiting (replaces the previous action; empty: nothing).
void on_interrupt(std::function<void()> action);

//! Every option of a subcommand with its value as given, or its default (null when it has
//! none), flags as true/false; for reports. Hidden options are left out.
nlohmann::json options_json(const CLI::App& sub);

//! Let every option of the app and its subcommands show its default in --help and in
//! options_json (CLI11 only keeps the defaults it was asked to capture).
void capture_defaults(CLI::App& app);

// --- subcommands: each file cli/cmd_<name>.cpp defines one register function ----------------
void register_info(CLI::App& app);
void register_convert(CLI::App& app);
void register_sample(CLI::App& app);
void register_label(CLI::App& app);
void register_construct(CLI::App& app);
void register_quality(CLI::App& app);
void register_structure(CLI::App& app);
void register_hexmesh(CLI::App& app);
void register_quadmesh(CLI::App& app);
void register_simplify(CLI::App& app);
void register_optimize(CLI::App& app);
void register_pad(CLI::App& app);
void register_run(CLI::App& app);
void register_fabricate(CLI::App& app);
void register_check_fab(CLI::App& app);
void register_repair(CLI::App& app);

}  // namespace polycube::cli
