#include "cli/app.h"

#include "construct/construct.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "mesh/grid.h"
#include "optimize/foldover_check.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/global_control.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <malloc.h>
#include <semaphore.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <mutex>
#include <thread>

namespace polycube::cli {

namespace {

//! A one-line progress bar on stderr, redrawn in place, with the elapsed time and an estimate
//! of what is left. It only moves forward: a task that runs again (the untangling restarts
//! within one optimization) continues its bar instead of starting from 0 %.
class TerminalProgress : public core::ProgressClient {
 public:
  void begin(const std::string& task) override {
    if (task != task_) {
      task_ = task;
      start_ = std::chrono::steady_clock::now();
      shown_ = 0.0;
    }
    draw();
  }
  void progress(const std::string& task, double fraction, bool total_known) override {
    if (task == task_) shown_ = std::max(shown_, fraction);
    total_known_ = total_known;
    draw();
  }
  void end(const std::string& task, bool ok) override {
    (void)task;
    (void)ok;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }

 private:
  void draw() const {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(shown_ * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string left;
    if (total_known_ && shown_ >= 0.05 && shown_ < 1.0)
      left = fmt::format(", ~{:.0f} s left", elapsed * (1.0 - shown_) / shown_);
    std::fprintf(stderr, "\r\033[K%-24.24s [%s] %3d%% %.0f s%s", task_.c_str(), bar.c_str(),
                 static_cast<int>(shown_ * 100.0), elapsed, left.c_str());
    std::fflush(stderr);
  }

  std::string task_;
  std::chrono::steady_clock::time_point start_;
  double shown_ = 0.0;
  bool total_known_ = true;
};

//! CLI11's formatter with the option's type and its constraints and default moved into words:
//! the type column keeps the bare type (`N`, `X`, `TEXT` or the choices), the description ends
//! with "(a positive number; default: 20000)".
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    if (opt->get_type_size() == 0) return {};
    std::string out = " " + bare_type(*opt);
    if (opt->get_expected_max() == CLI::detail::expected_max_vector_size)
      out += " ...";
    else if (opt->get_expected_min() > 1)
      out += " x " + std::to_string(opt->get_expected());
    if (opt->get_required()) out += " (required)";
    return out;
  }

  std::string make_option_desc(const CLI::Option* opt) const override {
    std::vector<std::string> notes;
    const std::string full = opt->get_type_name();
    const std::size_t colon = full.find(':');
    if (colon != std::string::npos) notes.push_back(full.substr(colon + 1));
    if (!opt->get_default_str().empty() && opt->get_default_str() != "[]")  // "[]": an empty list, no default
      notes.push_back("default: " + opt->get_default_str());
    std::string desc = opt->get_description();
    if (!notes.empty()) desc += " (" + fmt::format("{}", fmt::join(notes, "; ")) + ")";
    return desc;
  }

 private:
  static std::string bare_type(const CLI::Option& opt) {
    std::string t = opt.get_type_name();
    t = t.substr(0, t.find(':'));
    if (t == "INT" || t == "UINT") return "N";
    if (t == "FLOAT") return "X";
    return t;
  }
};

//! Progress off a terminal (a batch log): a line at most every `interval`, with the task's
//! elapsed time and, where the total is known, an estimate of what is left.
class LineProgress : public core::ProgressClient {
 public:
  LineProgress(std::FILE* out, std::chrono::milliseconds interval) : out_(out), interval_(interval) {}
  void begin(const std::string& task) override {
    if (task == task_) return;  // the same task again: its time goes on
    task_ = task;
    start_ = last_ = std::chrono::steady_clock::now();
  }
  void progress(const std::string& task, double f, bool total_known) override {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < interval_) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::string left;
    if (total_known && f >= 0.05 && f < 1.0) left = fmt::format(", ~{:.0f} s left", elapsed * (1.0 - f) / f);
    std::fprintf(out_, "      %s: %d%% (%.0f s%s)\n", task.c_str(), static_cast<int>(f * 100.0), elapsed,
                 left.c_str());
    std::fflush(out_);
  }
  void end(const std::string& task, bool ok) override {
    (void)task;
    (void)ok;
  }

 private:
  std::FILE* out_;
  std::chrono::milliseconds interval_;
  std::string task_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace

std::shared_ptr<CLI::FormatterBase> help_formatter() { return std::make_shared<HelpFormatter>(); }

std::shared_ptr<core::ProgressClient> line_progress(std::FILE* out, std::chrono::milliseconds interval) {
  return std::make_shared<LineProgress>(out, interval);
}

CLI::Validator one_of(const std::vector<std::string>& names) {
  return CLI::Validator(
      [names](std::string& text) -> std::string {
        std::string lower = text;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        for (std::size_t i = 0; i < names.size(); ++i)
          if (lower == names[i]) {
            text = names[i];
            return {};
          }
        return fmt::format("must be one of {}, got '{}'", fmt::join(names, ", "), text);
      },
      "", "ONE_OF");
}

GlobalOptions& global_options() {
  static GlobalOptions g;
  return g;
}

namespace {
bool g_json_printed = false;  // print_result printed the command's JSON: no error object after it
std::mutex g_interrupt_mutex;
std::function<void()> g_on_interrupt;
}  // namespace

namespace {
sem_t g_interrupt_signal;  // posted by the signal handler (sem_post is async-signal-safe)

extern "C" void post_interrupt(int /*sig*/) { sem_post(&g_interrupt_signal); }
}  // namespace

void install_interrupt_handler() {
  // The handler only posts a semaphore; a thread of our own waits on it and does the work,
  // whichever thread the signal lands on (libraries start threads we do not control).
  sem_init(&g_interrupt_signal, 0, 0);
  std::thread([] {
    while (sem_wait(&g_interrupt_signal) != 0) {
    }
    {
      std::lock_guard lock(g_interrupt_mutex);
      try {
        if (g_on_interrupt) g_on_interrupt();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "polycube: could not write the report: %s\n", e.what());
      }
    }
    std::fputs("\npolycube: interrupted\n", stderr);
    std::_Exit(130);
  }).detach();
  struct sigaction action {};
  action.sa_handler = post_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGTERM, &action, nullptr);
  struct sigaction old {};
  // A shell starts background jobs with SIGINT ignored; keep it so (it is not meant for them).
  if (sigaction(SIGINT, nullptr, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(SIGINT, &action, nullptr);
}

void on_interrupt(std::function<void()> action) {
  std::lock_guard lock(g_interrupt_mutex);
  g_on_interrupt = std::move(action);
}

nlohmann::json options_json(const CLI::App& sub) {
  nlohmann::json j = nlohmann::json::object();
  for (const CLI::Option* o : sub.get_options()) {
    if (o->get_group().empty()) continue;  // hidden (testing only)
    std::string name = o->get_lnames().empty() ? o->get_name() : o->get_lnames().front();
    if (name == "help" || name == "help-expert") continue;
    if (o->get_items_expected_max() == 0) {  // a flag: given as such, or "=false" in a config file
      j[name] = o->count() > 0 && o->as<bool>();
    } else if (o->count() > 0) {
      const std::vector<std::string>& given = o->results();
      j[name] = given.size() == 1 ? nlohmann::json(given.front()) : nlohmann::json(given);
    } else if (!o->get_default_str().empty() && o->get_default_str() != "[]") {
      j[name] = o->get_default_str();
    } else {
      j[name] = nullptr;
    }
  }
  return j;
}

void capture_defaults(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (o->get_items_expected_max() != 0 && o->get_default_str().empty()) o->capture_default_str();
  for (CLI::App* sub : app.get_subcommands({})) capture_defaults(*sub);
}

nlohmann::json scaled_jacobian_json(const quality::ScaledJacobianSummary& s) {
  nlohmann::json bins = nlohmann::json::array();
  for (int i = 0; i < quality::kHistogramBins; ++i)
    bins.push_back({{"lower", quality::histogram_bin_lower(i)},
                    {"upper", quality::histogram_bin_upper(i)},
                    {"count", s.histogram[i]}});
  return {{"min", s.min},           {"average", s.average}, {"max", s.max},
          {"inverted", s.inverted}, {"invalid", s.invalid}, {"histogram", bins}};
}

CLI::Option* add_sizing_option(CLI::App& sub, mesh::GridSizing& sizing, const std::string& help) {
  return add_choice<mesh::GridSizing>(sub, "--sizing", sizing,
                                      {{"uniform", mesh::GridSizing::Uniform}, {"map", mesh::GridSizing::Map}}, help);
}

void add_target_option(CLI::App& sub, TargetOption& target) {
  sub.add_option("--target", target.path, "Target surface (.obj .off .ply .stl .mesh; a volume mesh stands for its boundary)")
      ->required();
  sub.add_option("--max-start-distance", target.max_start_distance,
                 "Refuse a mesh whose boundary is farther than this from the target before any work (Hausdorff "
                 "distance, as a fraction of the target's bounding-box diagonal): a gridded mesh starts within a "
                 "few percent, a mesh of another shape or placement does not")
      ->check(positive())
      ->capture_default_str();
}

core::TriMesh read_fitting_target(const TargetOption& target, const core::HexMesh& mesh, const std::string& mesh_file) {
  core::TriMesh surface = read_target_surface(target.path);
  // A coarse bound is enough to tell a wrong target from the right one.
  const quality::SurfaceDistance d = quality::hausdorff_distance(mesh, surface, {.tolerance = 1e-2});
  if (d.relative > target.max_start_distance)
    throw core::InputError(fmt::format(
        "{} is {:.3g}% of the target's diagonal away from {} (Hausdorff distance {:.6g}; at most {:.3g}% allowed): "
        "is this the mesh's target, in the same units and position? (--max-start-distance to allow more)",
        mesh_file, 100.0 * d.relative, target.path, d.hausdorff, 100.0 * target.max_start_distance));
  return surface;
}

nlohmann::json foldover_json(const optimize::FoldoverReport& check) {
  nlohmann::json j = {{"ok", check.ok()},
                      {"reason", check.reason()},
                      {"inverted_hexes", check.inverted_hexes},
                      {"nonpositive_scaled_jacobian", check.nonpositive_scaled_jacobian},
                      {"boundary_self_intersections", check.boundary_self_intersections},
                      {"crossings", nlohmann::json::array()}};
  for (const core::Vec3& c : check.crossings) j["crossings"].push_back({c.x(), c.y(), c.z()});
  return j;
}

core::TriMesh read_target_surface(const std::string& path) {
  const core::MeshData d = io::read_mesh(path);
  if (!d.triangles.empty() || !d.quads.empty()) return io::read_surface(path);
  if (!d.hexes.empty()) return quality::triangulate(core::boundary(core::hexes_of(d)).surface);
  if (!d.tets.empty()) return core::boundary(core::tets_of(d)).surface;
  throw core::InputError(path + ": no surface or volume elements to use as target");
}

void add_global_flags(CLI::App& app) {
  GlobalOptions& g = global_options();
  app.add_flag("-v,--verbose", g.verbose, "More messages on stderr (-vv for debug)");
  app.add_flag("-q,--quiet", g.quiet, "Only errors on stderr, no progress");
  app.add_flag("--json", g.json, "Print a machine-readable JSON summary on stdout");
  app.add_option("--log", g.log_file, "Also write every message, with its time, to this file (info level; debug with -vv)");
  app.add_option("--threads", g.threads,
                 "Worker threads at most (0: every core); the results are the same whatever the number")
      ->check(CLI::NonNegativeNumber);
}

void keep_freed_memory() {
  // The solvers allocate and free arrays of tens of MiB every iteration (a Hessian's values,
  // element derivatives). glibc serves blocks above its mmap threshold (at most 32 MiB, however
  // it adapts) with fresh pages and gives them back on free, so each iteration faulted them in
  // again, and it trims freed memory at the heap's top likewise: a tenth to a fifth of an
  // optimization's time. Blocks up to 256 MiB now come from the heap, which keeps up to 512 MiB
  // of freed memory for the next iteration; larger ones are still mapped and returned.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

void limit_threads() {
  // Held for the whole process: TBB's parallel loops (optimizer, untangler, distances) use at
  // most this many threads. The fabrication's ray casting and CHOLMOD's BLAS already run on one
  // (solve/sparse_solver.cpp).
  static std::unique_ptr<tbb::global_control> limit;
  const int n = global_options().threads;
  if (n <= 0) return;
  limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                static_cast<std::size_t>(n));
}

void setup_logging_and_progress() {
  const GlobalOptions& g = global_options();
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  // On a terminal, a message first clears the progress bar's line.
  sink->set_pattern(isatty(STDERR_FILENO) ? "\r\033[K%^%l%$: %v" : "%^%l%$: %v");
  const spdlog::level::level_enum screen = g.quiet          ? spdlog::level::err
                                           : g.verbose >= 2 ? spdlog::level::debug
                                           : g.verbose == 1 ? spdlog::level::info
                                                            : spdlog::level::warn;
  sink->set_level(screen);
  std::vector<spdlog::sink_ptr> sinks{sink};
  if (!g.log_file.empty()) {
    // The log file gets the info messages too (debug with -vv), with the time of each.
    try {
      auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(g.log_file, true);
      file->set_pattern("%Y-%m-%d %H:%M:%S.%e %l: %v");
      file->set_level(g.verbose >= 2 ? spdlog::level::debug : spdlog::level::info);
      sinks.push_back(file);
    } catch (const spdlog::spdlog_ex& e) {
      throw core::OutputError(g.log_file, 0, std::string("cannot write the log: ") + e.what());
    }
  }
  auto l = std::make_shared<spdlog::logger>("polycube", sinks.begin(), sinks.end());
  l->set_level(std::min(screen, g.log_file.empty() ? screen : (g.verbose >= 2 ? spdlog::level::debug : spdlog::level::info)));
  l->flush_on(spdlog::level::info);
  core::set_logger(l);
  if (g.quiet || g.json) return;
  if (isatty(STDERR_FILENO))
    core::set_progress_client(std::make_shared<TerminalProgress>());
  else
    core::set_progress_client(line_progress(stderr, std::chrono::seconds(10)));
}

void add_config_options(CLI::App& app) {
  app.set_config("--config", "", "Read the settings from this TOML file (as --save-config writes it; what the command line gives wins)");
  app.add_option("--save-config", global_options().save_config,
                 "Write the settings of this command (every option, the defaults included) to this TOML file, "
                 "then run it; --config reads them back");
}

void save_config_if_asked(const CLI::App& app) {
  const std::string& path = global_options().save_config;
  if (path.empty()) return;
  // Only the subcommand's section: the global flags (-v, --json, ...) are not settings.
  std::string text = "# polycube " + std::string(kVersion) + " settings: polycube --config FILE <subcommand> ...\n";
  for (const CLI::App* sub : app.get_subcommands()) {
    text += "[" + sub->get_name() + "]\n";
    std::istringstream lines(sub->config_to_str(true, false));
    // Left out: options without a value (an empty list or text: nothing to restore).
    for (std::string line; std::getline(lines, line);)
      if (!line.ends_with("=\"\"") && !line.ends_with("=\"[]\"")) text += line + "\n";
  }
  io::write_text_atomic(path, text);
}

void print_status(const std::string& line) {
  // On a terminal, over the progress bar's line (it is drawn again at its next move).
  std::fprintf(stderr, "%s%s\n", isatty(STDERR_FILENO) ? "\r\033[K" : "", line.c_str());
  std::fflush(stderr);
}

void print_result(const nlohmann::json& json, const std::string& text) {
  if (global_options().json) {
    std::cout << json.dump(2) << '\n';
    g_json_printed = true;
  }
  else if (!text.empty())
    std::cout << text << (text.back() == '\n' ? "" : "\n");
}

std::function<void(int, int, const construct::Attempt&, double)> attempt_progress() {
  const bool show = !global_options().quiet && !global_options().json;
  return [show](int i, int n, const construct::Attempt& attempt, double seconds) {
    if (show) print_status(fmt::format("      construct attempt {}/{}: {} ({:.0f} s so far)", i, n, attempt.name(), seconds));
  };
}

CLI::Option* add_coarse_edge_option(CLI::App& sub, construct::ConstructOptions& o) {
  return sub
      .add_option("--coarse-edge-ratio", o.coarse_edge_ratio,
                  "When no labeling is valid and an edge of the surface is longer than the bounding-box diagonal "
                  "over this, split every triangle into four at its edges' midpoints until none is (the surface "
                  "does not move) and construct again: a tetrahedron, a wedge or a pyramid has too few triangles "
                  "to label (0: never)")
      ->capture_default_str()
      ->check(cli::non_negative());
}

std::vector<CLI::Option*> add_decimation_options(CLI::App& sub, construct::ConstructOptions& o) {
  sub.add_option("--max-triangles", o.max_triangles,
                 "A surface of more triangles is decimated to --decimate-to triangles before the construction, no "
                 "vertex moved farther than --decimation-tolerance: the construction's time grows with the triangles; "
                 "the map is of the decimated solid, and run still fits the hex mesh to the full surface (0: never "
                 "decimate)")
      ->capture_default_str()
      ->check(cli::non_negative());
  return {sub.add_option("--decimate-to", o.decimate_to, "Triangles a surface over --max-triangles is decimated to")
              ->capture_default_str()
              ->check(CLI::PositiveNumber),
          sub.add_option("--decimation-tolerance", o.decimation_tolerance,
                         "How far a vertex of the decimated surface may be from the input, as a fraction of the "
                         "bounding-box diagonal")
              ->capture_default_str()
              ->check(CLI::Range(1e-6, 0.05))};
}

void add_expert_options(CLI::App& sub, const std::vector<CLI::Option*>& expert) {
  for (CLI::Option* o : expert) o->group("");
  sub.add_flag_callback(
      "--help-expert",
      [&sub, expert] {
        for (CLI::Option* o : expert) o->group("Expert options");
        sub.footer("");
        throw CLI::CallForHelp();
      },
      "Show the expert options too (settings of the algorithm's steps; the defaults are tuned)");
  sub.footer("Expert options: see --help-expert.");
}

int run_guarded(const std::function<void()>& body) {
  auto fail = [](int code, const std::string& what) {
    std::cerr << "polycube: error: " << what << '\n';
    if (global_options().json && !g_json_printed)
      std::cout << nlohmann::json{{"status", "failed"}, {"exit_code", code}, {"error", what}}.dump(2) << '\n';
    return code;
  };
  try {
    body();
    return kOk;
  } catch (const core::InputError& e) {
    return fail(kBadInput, e.what());
  } catch (const core::GeometryError& e) {
    return fail(kNoResult, e.what());
  } catch (const core::SolverError& e) {
    return fail(kNoResult, e.what());
  } catch (const core::Cancelled& e) {
    return fail(kNoResult, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kInternal, "out of memory");
  } catch (const std::exception& e) {
    return fail(kInternal, std::string("internal error: ") + e.what());
  }
}

namespace {

//! A numeric validator: `ok` on the parsed value, `wanted` completing "must be ...".
CLI::Validator number_check(std::function<bool(double)> ok, const std::string& wanted, const std::string& name) {
  return CLI::Validator(
      [ok = std::move(ok), wanted](std::string& text) -> std::string {
        double v = 0.0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (used != text.size()) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || !ok(v)) return "must be " + wanted + ", got " + text;
        return {};
      },
      wanted, name);
}

}  // namespace

std::vector<CLI::Option*> add_repair_options(CLI::App& sub, repair::RepairOptions& o) {
  sub.add_option_function<std::vector<std::string>>(
         "--repair",
         [&o](const std::vector<std::string>& kinds) {
           for (const std::string& k : kinds) {
             o.fill_holes = o.fill_holes || k == "holes";
             o.wrap = o.wrap || k == "wrap";
           }
         },
         "Repairs that change the surface, on request: holes (close holes up to --max-hole edges with refined, "
         "faired patches), wrap (replace the surface by its alpha wrap: watertight, manifold, without "
         "self-intersections, within --wrap-offset of the input; for soups, self-intersections, touching or "
         "overlapping solids). The repairs that never move the surface are always on")
      ->delimiter(',')
      ->transform(one_of({"holes", "wrap"}))
      ->type_name("holes|wrap");
  sub.add_flag("--largest-component", o.largest_component,
               "Keep only the component of largest area (drops loose parts and debris)");
  return {
      sub.add_option("--max-hole", o.max_hole_edges, "--repair holes: the largest hole closed, in boundary edges")
          ->check(positive())
          ->capture_default_str(),
      sub.add_option("--wrap-alpha", o.wrap_alpha,
                     "--repair wrap: the wrapping ball's radius, a fraction of the bounding-box diagonal (smaller: "
                     "finer details, more triangles)")
          ->check(in_range(1e-4, 1.0))
          ->capture_default_str(),
      sub.add_option("--wrap-offset", o.wrap_offset,
                     "--repair wrap: the wrap's distance from the input, a fraction of the bounding-box diagonal")
          ->check(in_range(1e-5, 0.1))
          ->capture_default_str(),
  };
}

CLI::Validator positive() {
  return number_check([](double v) { return v > 0.0; }, "a positive number", "POSITIVE");
}

CLI::Validator non_negative() {
  return number_check([](double v) { return v >= 0.0; }, "a number >= 0", "NONNEGATIVE");
}

CLI::Validator auto_or_non_negative() {
  const CLI::Validator number = non_negative();
  return CLI::Validator(
      [number](std::string& text) { return text == "auto" ? std::string() : number(text); }, "auto or a number >= 0",
      "AUTO_OR_NONNEGATIVE");
}

CLI::Validator in_range(double lo, double hi) {
  return number_check([lo, hi](double v) { return v >= lo && v <= hi; },
                      fmt::format("a number from {:g} to {:g}", lo, hi), "RANGE");
}

}  // namespace polycube::cli
