// The subcommands of the registry's problems, generated from their specs: inputs as positional
// paths (required) or --NAME paths, outputs as -o/--output and --NAME paths plus --report, and
// one option per schema entry (--kebab-case; switches as flags, with their negation). The
// handler reads, runs by the one protocol, logs, writes and maps the exit code.
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include "apps/commands.h"
#include "geometry/text_input.h"
#include "problems/run/registry.h"

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

struct ProblemArgs {
  std::map<std::string, std::string> paths;   // input and output name -> path ("report" too)
  std::map<std::string, std::string> texts;   // option -> its text
  std::map<std::string, bool> switches;       // switch -> its value
  std::map<std::string, CLI::Option*> given;  // option -> CLI11's record of it
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

std::string InputOption(const InputSpec& input) {
  return input.required ? "input" : Flag(input.name);
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
    if (input.kind == InputKind::kVertexIds) {
      read.vertex_ids[input.name] = ReadVertexIds(path, num_vertices);
      continue;
    }
    if (input.kind == InputKind::kCurve) {
      read.curves[input.name] = ReadPoints(path, 2);
      continue;
    }
    read.meshes[input.name] = ReadMesh(path, MeshRequirements{input.kind == InputKind::kQuadMesh});
    if (num_vertices < 0) num_vertices = static_cast<int>(read.meshes[input.name].n_vertices());
  }
  return read;
}

int RunProblemCommand(const ProblemSpec& spec, const ProblemArgs& args) {
  const std::string name = "gproj " + spec.name;
  const IterationLog log(spec.log_measures);
  bool logged = false;
  RunContext context;
  context.on_record = [&](const RunRecord& record) {
    if (!logged) log.PrintHeader(), logged = true;
    log.Print(record);
    return true;
  };
  context.on_message = [&name](const RunMessage& m) {
    if (m.kind == RunMessage::Kind::kWarning) {
      std::fflush(stdout);
      std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), SpellOptions(m.text, true).c_str());
    } else {
      std::printf("%s%s\n", m.kind == RunMessage::Kind::kHeadline ? (name + ": ").c_str() : "",
                  SpellOptions(m.text, true).c_str());
    }
  };
  for (const OutputSpec& output : spec.outputs)
    if (!args.paths.at(output.name).empty()) context.outputs.insert(output.name);
  const nlohmann::json options = GivenOptions(spec, args);
  RunResult result;
  std::vector<std::string> written;
  try {
    const RunInputs inputs = ReadInputs(spec, args);
    result = RunProblem(spec, inputs, options, context);
    OutputFiles files;
    // A run that failed, or ended before its result (e.g. an H-net without rounds), writes
    // nothing.
    bool complete = !result.report.failed;
    for (const OutputSpec& output : spec.outputs)
      if (output.required)
        complete =
            complete && (result.meshes.count(output.name) || result.texts.count(output.name));
    if (complete) {
      for (const OutputSpec& output : spec.outputs) {
        const std::string& path = args.paths.at(output.name);
        if (path.empty()) continue;
        if (!result.meshes.count(output.name) && !result.texts.count(output.name)) continue;
        if (output.kind == OutputKind::kMesh)
          files.AddMesh(result.meshes.at(output.name), path);
        else
          files.AddText(path, result.texts.at(output.name));
        written.push_back(path);
      }
      if (!args.paths.at("report").empty()) {
        const nlohmann::json report =
            RunResultJson(spec, result, options, args.paths.at(spec.inputs.front().name),
                          args.paths.count("output") ? args.paths.at("output") : "");
        files.AddText(args.paths.at("report"), report.dump(2) + "\n");
        written.push_back(args.paths.at("report"));
      }
    }
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << name << ": " << SpellOptions(e.what(), true) << "\n";
    return kExitInputError;
  }
  if (!result.report.failed)
    for (const RunMessage& message : result.messages) context.on_message(message);
  const int code =
      ConcludeRun(spec.name, result.report, result.tolerance_measure, result.tolerance, written);
  if (code == kExitNotConverged)
    for (const std::string& shortfall : result.shortfalls)
      std::fprintf(stderr, "%s: %s\n", name.c_str(), SpellOptions(shortfall, true).c_str());
  return code;
}

}  // namespace

void RegisterProblemCommand(CLI::App* app, const ProblemSpec& spec, int* exit_code) {
  auto args = std::make_shared<ProblemArgs>();
  CLI::App* cmd = app->add_subcommand(
      spec.name, spec.summary +
                     " Exit codes: 0 converged, 1 bad input or option (nothing written), 3 "
                     "tolerance not reached (result written), 4 numerical failure (nothing "
                     "written).");
  for (const InputSpec& input : spec.inputs) {
    std::string& path = args->paths[input.name];
    if (input.required)
      cmd->add_option(
             input.name, path,
             input.doc + (input.kind == InputKind::kCurve ? std::string(" (text: x y z per line)")
                                                          : std::string(" (.obj, .off or .ply)")))
          ->required()
          ->type_name("FILE");
    else if (input.kind == InputKind::kVertexIds)
      cmd->add_option(Flag(input.name), path,
                      input.doc +
                          ": a text file of ids separated by spaces or newlines, '#' "
                          "comments")
          ->type_name("FILE");
    else
      cmd->add_option(Flag(input.name), path, input.doc + " (.obj, .off or .ply)")
          ->type_name("FILE");
  }
  for (const OutputSpec& output : spec.outputs) {
    const std::string flag = output.name == "output" ? "-o,--output" : Flag(output.name);
    CLI::Option* option =
        cmd->add_option(flag, args->paths[output.name],
                        "Write " + output.doc +
                            (output.kind == OutputKind::kMesh ? std::string(" (.obj, .off or .ply)")
                             : *OutputExtension(output.kind)
                                 ? " (" + std::string(OutputExtension(output.kind)) + ")"
                                 : std::string()) +
                            "; written atomically");
    option->type_name("FILE");
    if (output.required) option->required();
  }
  cmd->add_option("--report", args->paths["report"],
                  "Write a JSON report: converged, iterations, seconds, variables, per-iteration "
                  "history, the initial and final measures and the options")
      ->type_name("FILE");
  for (const OptionSpec& option : spec.options) {
    if (option.type == OptionType::kBool) {
      const std::string flags =
          Flag(option.name) + (option.negation.empty() ? "" : ",!" + Flag(option.negation));
      bool& value = args->switches[option.name];
      value = option.default_value.is_boolean() && option.default_value.get<bool>();
      args->given[option.name] = cmd->add_flag(flags, value, HelpOf(option));
      continue;
    }
    const OptionSpec spec_copy = option;
    CLI::Validator check(
        [spec_copy](std::string& text) {
          try {
            ParseOptionText(spec_copy, text);
            return std::string();
          } catch (const OptionError& e) {
            return e.rule();
          }
        },
        "");
    CLI::Option* cli =
        cmd->add_option(Flag(option.name), args->texts[option.name], HelpOf(option))->check(check);
    if (!option.default_value.is_null()) cli->default_str(OptionText(option.default_value));
    if (option.required) cli->required();
    cli->type_name(option.type == OptionType::kInt ? "INT" : "NUMBER");
    if (!option.placeholder.empty()) cli->type_name(option.placeholder);
    if (!option.choices.empty()) {
      std::string choices;
      for (const std::string& c : option.choices) choices += (choices.empty() ? "" : "|") + c;
      cli->type_name(choices);
    }
    args->given[option.name] = cli;
  }
  cmd->callback([&spec, args, exit_code]() { *exit_code = RunProblemCommand(spec, *args); });
}

}  // namespace gproj
