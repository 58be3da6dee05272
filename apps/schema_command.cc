// `gproj schema`: the registry (problems, inputs, outputs, typed options with defaults, ranges,
// units and docs) as JSON, the same document as Python's gproj.schema() and the service's
// GET /api/schema; with --markdown DIR, the reference page of every problem (docs/reference).
#include <cstdio>
#include <iostream>
#include <memory>

#include "apps/commands.h"

namespace gproj {
namespace {

struct SchemaArgs {
  std::string output, markdown;
};

int RunSchema(const SchemaArgs& args) {
  const Registry& registry = Registry::Builtin();
  const std::string text = registry.SchemaJson().dump(2) + "\n";
  if (args.output.empty() && args.markdown.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return kExitOk;
  }
  try {
    OutputFiles files;
    if (!args.output.empty()) {
      CheckOutputPath("--output", args.output);
      files.AddText(args.output, text);
    }
    for (const ProblemSpec& spec : registry.problems()) {
      if (args.markdown.empty()) break;
      const std::string path = args.markdown + "/" + spec.name + ".md";
      CheckOutputPath("--markdown", path);
      files.AddText(path, ReferenceMarkdown(spec));
    }
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj schema: " << e.what() << "\n";
    return kExitInputError;
  }
  return kExitOk;
}

}  // namespace

void RegisterSchemaCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<SchemaArgs>();
  CLI::App* cmd = app->add_subcommand(
      "schema",
      "Print the registry of problems as JSON (or write it with -o): every problem's "
      "inputs, outputs and options with their types, defaults, ranges, units and docs.");
  cmd->add_option("-o,--output", args->output, "Write the JSON here instead of printing it")
      ->type_name("FILE");
  cmd->add_option("--markdown", args->markdown,
                  "Write the reference page of every problem as DIR/NAME.md (docs/reference)")
      ->type_name("DIR");
  cmd->callback([args, exit_code]() { *exit_code = RunSchema(*args); });
}

}  // namespace gproj
