#include "gcode/cli/tool.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <csignal>

#include "gcode/cli/completion.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/version.hpp"

namespace gcode::cli {

namespace {

CLI::Validator number_validator(bool (*ok)(double), const char* rule, const char* type) {
  return CLI::Validator(
      [ok, rule](std::string& text) {
        double v = 0;
        if (parse_number(text, v) && std::isfinite(v) && ok(v)) return std::string();
        return std::string("must be a number ") + rule + ", not '" + text + "'";
      },
      type);
}

}  // namespace

const char* version() { return kVersion; }

const CLI::Validator& positive() {
  static const CLI::Validator v = number_validator([](double d) { return d > 0; }, "> 0", "NUMBER>0");
  return v;
}

const CLI::Validator& non_negative() {
  static const CLI::Validator v = number_validator([](double d) { return d >= 0; }, ">= 0", "NUMBER>=0");
  return v;
}

// A pattern that does not compile is the caller's mistake: a usage error
// now, not a failure once the input is open.
const CLI::Validator& layer_marker_pattern() {
  static const CLI::Validator v(
      [](std::string& pattern) {
        try {
          LayerMarkers markers(pattern);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "REGEX");
  return v;
}

std::vector<double> option_numbers(const std::string& text, const char* option) {
  std::vector<double> list;
  if (!parse_number_list(text, list)) throw UsageError(std::string(option) + ": '" + text + "' is not a list of numbers");
  return list;
}

LayerMarkers FilterOptions::markers() const {
  return layer_marker.empty() ? LayerMarkers() : LayerMarkers(layer_marker);
}

Tool::~Tool() = default;

Tool::Tool(std::string name, std::string description) : name_(std::move(name)), app_(std::make_unique<CLI::App>(std::move(description), name_)) {
  app_->set_version_flag("--version", name_ + " " + kVersion, "Print the version and exit");
  app_->get_formatter()->column_width(34);
  // Hidden (no group): the build runs it to write the tool's bash completion.
  // It answers at parse time, when every option of the tool is defined.
  app_->add_flag_callback("--bash-completion", [this] {
        std::fputs(bash_completion(name_, completion_entries(*app_)).c_str(), stdout);
        throw CLI::Success();
      })
      ->group("")
      ->configurable(false);
}

void Tool::add_filter_options(FilterOptions& o, unsigned parts) {
  filter_ = &o;
  parts_ = parts;
  o.tool = name_;
  if (parts & kInput) app_->add_option("FILE", o.file, "G-code file; - or absent: standard input")->type_name("FILE");
  CLI::Option* out = nullptr;
  if (parts & kOutput) out = app_->add_option("-o,--output", o.output, "Write to FILE instead of standard output")->type_name("FILE");
  if (parts & kInPlace) {
    CLI::Option* in_place =
        app_->add_flag("-i,--in-place", o.in_place, "Rewrite FILE in place, atomically, only when everything succeeded");
    if (out != nullptr) in_place->excludes(out);
  }
  if (parts & kLayerMarker)
    app_->add_option("--layer-marker", o.layer_marker,
                    "RE2 pattern that marks a layer start in a comment (first group: the slicer's number)")
        ->type_name("REGEX")
        ->check(layer_marker_pattern());
  if (parts & kEMode)
    app_->add_option("--e-mode", o.e_mode,
                    "E values of a file that never says M82/M83: relative, absolute, or auto (guessed, with a warning)")
        ->type_name("MODE")
        ->check(CLI::IsMember({"auto", "relative", "absolute"}));
  if (parts & kVerbosity) {
    app_->add_flag("-q,--quiet", o.quiet, "Only errors on standard error");
    app_->add_flag("-v,--verbose", o.verbose, "More messages on standard error");
  }
}

void Tool::add_selection(SelectionText& text, const std::string& verb) {
  CLI::Option* options[] = {
      app_->add_option("--layers", text.layers,
                      verb + " these layers (5, 5-9, 5-, -3 = the last three, 5,7,9-12; first layer = 1)")
          ->type_name("RANGE"),
      app_->add_option("--z-range", text.z_range, verb + " layers whose Z lies in Z1:Z2 (either side may be empty)")
          ->type_name("Z1:Z2"),
      app_->add_option("--types", text.types,
                      verb + " these ;TYPE: features, comma-separated, any slicer's spelling (WALL-OUTER, \"External perimeter\")")
          ->type_name("LIST")};
  check([&text, options] {
    // "--layers ''" (an unset shell variable) is a mistake, not "everything".
    for (CLI::Option* option : options)
      if (option->count() > 0 && option->as<std::string>().empty()) throw UsageError(option->get_name() + ": empty");
    LayerSelection::parse(text);
  });
}

int Tool::usage_error(const std::string& message) const {
  std::fprintf(stderr, "%s: %s (see %s --help)\n", name_.c_str(), message.c_str(), name_.c_str());
  return 2;
}

int Tool::run(int argc, char** argv, const std::function<int()>& body) {
  try {
    app_->parse(argc, argv);
    if (filter_ != nullptr && (parts_ & kInPlace) && filter_->in_place && (filter_->file.empty() || filter_->file == "-"))
      throw UsageError("-i/--in-place needs a FILE to rewrite, not standard input");
    for (const auto& rule : checks_) rule();
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app_->exit(e);  // --help, --version
    return usage_error(e.what());
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  }
  try {
    return body();
  } catch (const UsageError& e) {
    return usage_error(e.what());
  } catch (const BrokenPipe&) {
    // Die the way cat does when `| head` closes the pipe: by SIGPIPE.
    std::signal(SIGPIPE, SIG_DFL);
    std::raise(SIGPIPE);
    return 141;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name_.c_str(), e.what());
    return 1;
  }
}

}  // namespace gcode::cli
