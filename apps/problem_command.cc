// The subcommands of the registry's problems, generated from their specs: inputs as positional
// paths (required) or --NAME paths, outputs as -o/--output and --NAME paths plus --report, and
// one option per schema entry (--kebab-case; switches as flags, with their negation). The
// handler reads, runs by the one protocol, logs, writes and maps the exit code.
#include <signal.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include "apps/commands.h"
#include "gproj/geometry/io/text_input.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/registry.h"

namespace gproj {
namespace {

std::string Flag(const std::string& name) {
  std::string flag = "--" + name;
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

// The option's help: its doc, unit and range.
std::string HelpOf(const OptionSpec& spec) {
  std::string help = spec.doc;
  if (!spec.unit.empty()) help += " [" + spec.unit + "]";
  if (!spec.RangeText().empty()) help += " (" + spec.RangeText() + ")";
  if (spec.type == OptionType::kBool && spec.default_value.is_boolean())
    help += spec.default_value.get<bool>() ? " (default: on)" : " (default: off)";
  return help;
}

// Ctrl-C during a run: the first SIGINT asks the run to stop (at its next iterate, or between
// the steps of a stage without iterates); the run ends USER_ABORT, writes what it has and the
// command exits 130. The handler is one-shot (SA_RESETHAND): a second Ctrl-C terminates at
// once. Outside the run (reading, writing) SIGINT keeps its default action.
volatile std::sig_atomic_t interrupted = 0;

extern "C" void OnInterrupt(int) { interrupted = 1; }

class InterruptScope {
 public:
  InterruptScope() {
    interrupted = 0;
    struct sigaction action = {};
    action.sa_handler = OnInterrupt;
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigemptyset(&action.sa_mask);
    installed_ = sigaction(SIGINT, &action, &previous_) == 0;
  }
  ~InterruptScope() {
    if (installed_) sigaction(SIGINT, &previous_, nullptr);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
  static bool Requested() { return interrupted != 0; }

 private:
  struct sigaction previous_ = {};
  bool installed_ = false;
};

struct ProblemArgs {
  std::map<std::string, std::string> paths;   // input and output name -> path ("report" too)
  std::map<std::string, std::string> texts;   // option -> its text
  std::map<std::string, bool> switches;       // switch -> its value
  std::map<std::string, CLI::Option*> given;  // option -> CLI11's record of it
  bool weld = false;                          // --weld: merge coincident input vertices
};

// The options given on the command line, as JSON values (checked again by the run protocol).
nlohmann::json GivenOptions(const ProblemSpec& spec, const ProblemArgs& args) {
  nlohmann::json given = nlohmann::json::object();
  for (const OptionSpec& option : spec.options) {
    if (args.given.at(option.name)->count() == 0) continue;
    given[option.name] = option.type == OptionType::kBool
                             ? nlohmann::json(args.switches.at(option.name))
                             : ParseOptionText(option, args.texts.at(option.name));
  }
  return given;
}

// How messages name an input: "input" for the required one, the name of an optional
// positional one ("plan"), else its flag.
std::string InputOption(const InputSpec& input) {
  return input.required ? "input" : input.positional ? input.name : Flag(input.name);
}

// Output paths checked before the work starts, then the inputs read.
RunInputs ReadInputs(const ProblemSpec& spec, const ProblemArgs& args) {
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const InputSpec& input : spec.inputs)
    inputs.emplace_back(InputOption(input), args.paths.at(input.name));
  std::vector<OutputPath> outputs;
  for (const OutputSpec& output : spec.outputs) {
    outputs.push_back({Flag(output.name), args.paths.at(output.name),
                       output.kind == OutputKind::kMesh || output.kind == OutputKind::kPly,
                       OutputExtension(output.kind)});
  }
  outputs.push_back({"--report", args.paths.at("report")});
  CheckOutputPaths(inputs, outputs);

  RunInputs read;
  int num_vertices = -1;
  for (const InputSpec& input : spec.inputs) {
    const std::string& path = args.paths.at(input.name);
    if (path.empty()) continue;
    read.sources[input.name] = path;
    read.files[input.name] = path;
    if (input.kind == InputKind::kVertexIds) {
      read.vertex_ids[input.name] = ReadVertexIds(path, num_vertices);
      continue;
    }
    if (input.kind == InputKind::kCurve) {
      read.curves[input.name] = ReadPoints(path, 2);
      continue;
    }
    if (input.kind == InputKind::kBSpline) {
      read.surfaces[input.name] = ReadBSplineJson(path);
      continue;
    }
    if (input.kind == InputKind::kText || input.kind == InputKind::kJson) {
      read.texts[input.name] = ReadTextFile(path);
      continue;
    }
    std::vector<int> weld_map;
    read.meshes[input.name] =
        ReadMesh(path, MeshRequirements{input.kind == InputKind::kQuadMesh, args.weld}, &weld_map);
    if (args.weld) read.weld_maps[input.name] = std::move(weld_map);
    if (num_vertices < 0) num_vertices = static_cast<int>(read.meshes[input.name].n_vertices());
  }
  return read;
}

// Writes the outputs asked for and the report, all or none; returns the paths written. A run
// that failed, or ended before its result (e.g. an H-net without rounds), writes nothing.
std::vector<std::string> WriteResult(const ProblemSpec& spec, const ProblemArgs& args,
                                     const RunInputs& inputs, const nlohmann::json& options,
                                     const RunResult& result) {
  std::vector<std::string> written;
  bool complete = !result.report.failed;
  for (const OutputSpec& output : spec.outputs)
    if (output.required)
      complete = complete && (result.meshes.count(output.name) || result.texts.count(output.name));
  if (!complete) return written;
  OutputFiles files;
  for (const OutputSpec& output : spec.outputs) {
    const std::string& path = args.paths.at(output.name);
    if (path.empty()) continue;
    if (!result.meshes.count(output.name) && !result.texts.count(output.name)) {
      // Asked for, but this run does not make it (e.g. planarize's diagonal_mesh without net
      // diagonal): said, not silently dropped.
      std::string flag = output.name;
      std::replace(flag.begin(), flag.end(), '_', '-');
      std::fprintf(stderr,
                   "gproj %s: warning: --%s %s was not written: this run does not make it\n",
                   spec.name.c_str(), flag.c_str(), path.c_str());
      continue;
    }
    if (output.kind == OutputKind::kMesh)
      files.AddMesh(result.meshes.at(output.name), path);
    else
      files.AddText(path, result.texts.at(output.name));
    written.push_back(path);
  }
  if (!args.paths.at("report").empty()) {
    const nlohmann::json report = RunResultJson(
        spec, result, options, inputs, args.paths.count("output") ? args.paths.at("output") : "");
    files.AddText(args.paths.at("report"), report.dump(2) + "\n");
    written.push_back(args.paths.at("report"));
  }
  files.Commit();
  return written;
}

int RunProblemCommand(const ProblemSpec& spec, const ProblemArgs& args) {
  const std::string name = "gproj " + spec.name;
  auto log = std::make_unique<IterationLog>(spec.log_measures);
  bool logged = false;
  RunContext context;
  context.on_record = [&](const RunRecord& record) {
    if (!logged) log->PrintHeader(), logged = true;
    log->Print(record);
    return true;
  };
  context.on_columns = [&](const std::vector<std::string>& columns) {
    log = std::make_unique<IterationLog>(columns);
    logged = false;
  };
  context.on_message = [&name](const RunMessage& m) {
    if (m.kind == RunMessage::Kind::kWarning) {
      std::fflush(stdout);
      std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), SpellOptions(m.text, true).c_str());
    } else {
      std::printf("%s%s\n", m.kind == RunMessage::Kind::kHeadline ? (name + ": ").c_str() : "",
                  SpellOptions(m.text, true).c_str());
      std::fflush(stdout);  // progress shows when stdout is a pipe or a log file too
    }
  };
  for (const OutputSpec& output : spec.outputs)
    if (!args.paths.at(output.name).empty()) context.outputs.insert(output.name);
  const nlohmann::json options = GivenOptions(spec, args);
  RunResult result;
  std::vector<std::string> written;
  try {
    const RunInputs inputs = ReadInputs(spec, args);
    {
      InterruptScope scope;
      context.stop_requested = &InterruptScope::Requested;
      result = RunProblem(spec, inputs, options, context);
    }
    result.report.termination = SpellOptions(result.report.termination, true);
    written = WriteResult(spec, args, inputs, options, result);
  } catch (const InputError& e) {
    std::cerr << name << ": " << SpellOptions(e.what(), true) << "\n";
    return kExitInputError;
  }
  if (!result.report.failed)
    for (const RunMessage& message : result.messages) context.on_message(message);
  if (spec.generator) {
    std::printf("wrote %s\n", written.front().c_str());
    return kExitOk;
  }
  const int code = ConcludeRun(spec.name, result.report, result.tolerance_measure, result.tolerance,
                               written, InterruptScope::Requested() && !result.report.converged);
  if (code == kExitNotConverged)
    for (const std::string& shortfall : result.shortfalls)
      std::fprintf(stderr, "%s: %s\n", name.c_str(), SpellOptions(shortfall, true).c_str());
  return code;
}

// The inputs as positional paths (required) or --NAME FILE, the outputs as -o/--output and
// --NAME FILE, and --report.
void AddPaths(CLI::App* cmd, const ProblemSpec& spec, ProblemArgs* args) {
  for (const InputSpec& input : spec.inputs) {
    const std::string format = input.kind == InputKind::kCurve     ? " (text: x y z per line)"
                               : input.kind == InputKind::kBSpline ? " (.json)"
                               : input.kind == InputKind::kJson    ? " (.json)"
                               : input.kind == InputKind::kText    ? " (a text file)"
                               : input.kind == InputKind::kVertexIds
                                   ? ": a text file of ids separated by spaces or newlines, '#' "
                                     "comments"
                                   : " (.obj, .off or .ply)";
    CLI::Option* option = cmd->add_option(input.IsPositional() ? input.name : Flag(input.name),
                                          args->paths[input.name], input.doc + format);
    option->type_name("FILE");
    if (input.required) option->required();
  }
  for (const OutputSpec& output : spec.outputs) {
    const std::string extension =
        output.kind == OutputKind::kMesh ? ".obj, .off or .ply" : OutputExtension(output.kind);
    CLI::Option* option = cmd->add_option(
        output.name == "output" ? "-o,--output" : Flag(output.name), args->paths[output.name],
        "Write " + output.doc + (extension.empty() ? "" : " (" + extension + ")") +
            "; written atomically");
    option->type_name("FILE");
    if (output.required) option->required();
  }
  args->paths["report"];
  if (spec.generator) return;
  if (std::any_of(spec.inputs.begin(), spec.inputs.end(), [](const InputSpec& input) {
        return input.kind == InputKind::kMesh || input.kind == InputKind::kQuadMesh;
      }))
    cmd->add_flag("--weld", args->weld,
                  "Merge the input meshes' coincident vertices (within 1e-9 of the bounding-box "
                  "diagonal), as unwelded exports need (each face with its own corners); "
                  "without it such a mesh is refused");
  cmd->add_option("--report", args->paths["report"],
                  "Write a JSON report: converged, iterations, seconds, variables, per-iteration "
                  "history, the initial and final measures and the options")
      ->type_name("FILE");
}

// A list option: its words (--samples 12 9, or 12,9) joined by commas and checked as one value.
CLI::Option* AddListOption(CLI::App* cmd, const OptionSpec& option, std::string* text) {
  const int words = option.count * (option.type == OptionType::kPoints ? 3 : 1);
  CLI::Option* cli = cmd->add_option_function<std::vector<std::string>>(
      Flag(option.name),
      [option, text](const std::vector<std::string>& given) {
        text->clear();
        for (const std::string& w : given) *text += (text->empty() ? "" : ",") + w;
        try {
          ParseOptionText(option, *text);
        } catch (const OptionError& e) {
          throw CLI::ValidationError(Flag(option.name), e.rule());
        }
      },
      HelpOf(option));
  return cli->expected(1, words > 0 ? words : 1);
}

// One option of the schema: a switch (with its negation), a list, or a value checked by
// ParseOptionText as it is parsed; the schema's default shown.
void AddOption(CLI::App* cmd, const OptionSpec& option, ProblemArgs* args) {
  if (option.type == OptionType::kBool) {
    bool& value = args->switches[option.name];
    value = option.default_value.is_boolean() && option.default_value.get<bool>();
    args->given[option.name] = cmd->add_flag(
        Flag(option.name) + (option.negation.empty() ? "" : ",!" + Flag(option.negation)), value,
        HelpOf(option));
    return;
  }
  std::string& text = args->texts[option.name];
  CLI::Option* cli = nullptr;
  if (option.type == OptionType::kNumbers || option.type == OptionType::kInts ||
      option.type == OptionType::kPoints || option.type == OptionType::kVertexValues) {
    cli = AddListOption(cmd, option, &text);
  } else {
    const CLI::Validator check(
        [option](std::string& value) {
          try {
            ParseOptionText(option, value);
            return std::string();
          } catch (const OptionError& e) {
            return e.rule();
          }
        },
        "");
    cli = cmd->add_option(Flag(option.name), text, HelpOf(option))->check(check);
  }
  if (!option.default_value.is_null()) cli->default_str(OptionText(option.default_value));
  if (option.required) cli->required();
  cli->type_name(option.type == OptionType::kInt            ? "INT"
                 : option.type == OptionType::kVertexValues ? "VERTEX:VALUE,..."
                                                            : "NUMBER");
  if (!option.placeholder.empty()) cli->type_name(option.placeholder);
  if (!option.choices.empty()) {
    std::string choices;
    for (const std::string& c : option.choices) choices += (choices.empty() ? "" : "|") + c;
    cli->type_name(choices);
  }
  args->given[option.name] = cli;
}

}  // namespace

void RegisterProblemCommand(CLI::App* app, const ProblemSpec& spec, int* exit_code) {
  auto args = std::make_shared<ProblemArgs>();
  CLI::App* cmd = app->add_subcommand(
      spec.name,
      spec.summary + (spec.generator ? " Exit codes: 0 written, 1 bad option (nothing written)."
                                     : " Exit codes: 0 converged, 1 bad input or option (nothing "
                                       "written), 3 tolerance not reached (result written), 4 "
                                       "numerical failure (nothing written)."));
  AddPaths(cmd, spec, args.get());
  for (const OptionSpec& option : spec.options) AddOption(cmd, option, args.get());
  cmd->callback([&spec, args, exit_code]() { *exit_code = RunProblemCommand(spec, *args); });
}

}  // namespace gproj
