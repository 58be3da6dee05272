#pragma once
// The registry of gproj's problems: each problem is registered once with its name, its inputs
// and outputs, its typed options schema and its run. The command line's subcommands, the Python
// functions, `gproj schema` (the registry as JSON, served by the HTTP service) and the docs'
// command reference are all generated from it, so every front end agrees on names, defaults and
// ranges, and a new problem needs no front-end code.
//
// The run protocol is one call: RunProblem(spec, inputs, options, context) checks the options
// against the schema, runs, and returns one RunResult (the solver's RunReport, the problem's own
// report keys, the result meshes and texts, and messages for the user).

#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/option_schema.h"

namespace gproj {

enum class InputKind {
  kQuadMesh,   // a polygon mesh whose faces are all quads
  kMesh,       // any polygon mesh
  kVertexIds,  // 0-based vertex ids of the first mesh input
  kCurve,      // a polyline: at least two points, none repeating the one before (a text file of
               // x y z lines; an (n, 3) array in Python)
  kBSpline,    // a tensor-product B-spline surface (the JSON of docs/formats.md; a dict in Python)
  kText,       // a text document the run parses (a file on the command line; a str in Python),
               // its messages naming the file and line
  kJson,       // a JSON document the run parses, e.g. an H-net (a .json file on the command line;
               // a dict, its JSON text or a path in Python; an object or its text in the
               // service), held as text in RunInputs::texts
};
// "quad_mesh", "mesh", "vertex_ids", "curve", "bspline", "text", "json"
const char* InputKindName(InputKind kind);

struct InputSpec {
  std::string name;  // identifier, e.g. "mesh", "reference", "fixed"
  InputKind kind = InputKind::kMesh;
  std::string doc;
  bool required = false;  // required inputs are positional on the command line and in Python
  // An optional input taken like a required one (positional), e.g. a plan view that another
  // input can replace; at most one per problem, the last of the positional inputs.
  bool positional = false;
  // kMesh: the corners per face a front end assumes when the faces come as one flat list of
  // vertex ids and nothing says how many (Hops' Integer list): 4 where quad meshes are the
  // usual input (planarize), 3 elsewhere.
  int flat_face_corners = 3;

  bool IsPositional() const { return required || positional; }
};

enum class OutputKind {
  kMesh,      // a polygon mesh (.obj, .off or .ply)
  kSvg,       // a picture (.svg)
  kCsv,       // per-element values
  kPly,       // a mesh with colours (.ply)
  kJson,      // a JSON document (.json)
  kSegments,  // line segments as OBJ lines (.obj)
};
const char* OutputKindName(OutputKind kind);  // "mesh", "svg", "csv", "ply", "json", "segments"
// The extension an output of `kind` must have (".svg"); empty for meshes (.obj, .off or .ply)
// and CSV (any).
const char* OutputExtension(OutputKind kind);

struct OutputSpec {
  std::string name;  // identifier, e.g. "output", "picture", "face_values", "heatmap"
  OutputKind kind = OutputKind::kMesh;
  std::string doc;
  bool required = false;
  // The result mesh keeps the input mesh's connectivity (Python returns its vertices alone).
  bool same_connectivity = false;
};

// The inputs of a run, read by a front end (files, numpy arrays, JSON) and named as in the spec.
struct RunInputs {
  std::map<std::string, PolyMesh> meshes;
  std::map<std::string, std::vector<int>> vertex_ids;
  std::map<std::string, std::vector<Eigen::Vector3d>> curves;
  std::map<std::string, BSplineSurface> surfaces;
  std::map<std::string, std::string> texts;  // inputs of kind kText and kJson
  // Meshes welded as read (MeshRequirements::weld): input vertex -> vertex of the mesh.
  std::map<std::string, std::vector<int>> weld_maps;
  // Where each input came from ("in.obj", "V"), for messages.
  std::map<std::string, std::string> sources;
  // The file each input was read from, for those read from one (the report names it).
  std::map<std::string, std::string> files;

  const PolyMesh& Mesh(const std::string& name) const;          // a required mesh input
  const PolyMesh* OptionalMesh(const std::string& name) const;  // null when not given
  std::vector<int> VertexIds(const std::string& name) const;    // empty when not given
  const std::vector<Eigen::Vector3d>& Curve(const std::string& name) const;  // a required curve
  const BSplineSurface& Surface(const std::string& name) const;              // a required B-spline
  const std::string* Text(const std::string& name) const;  // a text input; null when not given
  bool Has(const std::string& name) const;                 // whether the input was given
  std::string Source(const std::string& name) const;
};

struct RunMessage {
  // kHeadline: what is being solved (the command line prefixes "gproj NAME: "); kInfo: progress
  // and measures; kWarning: something the user should look at (Python: warnings.warn).
  enum class Kind { kHeadline, kInfo, kWarning };
  Kind kind = Kind::kInfo;
  std::string text;
};

// What a front end gives a run besides its inputs and options: where progress goes, and which
// outputs are wanted (a run renders only those).
struct RunContext {
  RunCallback on_record;                              // null: no progress; false stops the run
  std::function<void(const RunMessage&)> on_message;  // null: messages only in the result
  // The live log's columns from here on (a stage of the run that measures other things); null:
  // the spec's log_measures throughout.
  std::function<void(const std::vector<std::string>&)> on_columns;
  // The iterate of a record as a mesh (input units, the input's connectivity), after the record,
  // from the problems whose result is a mesh of the input's (planarize, anet): a front end shows
  // the run live (the service's iterate events). Null: none.
  std::function<void(int iteration, const PolyMesh& mesh)> on_iterate;
  std::set<std::string> outputs;  // names of the outputs asked for
  // Polled by the stages that send no records (paneling, long constructions) between their
  // steps, and before every record: true stops the run as a false from on_record does (Ctrl-C
  // on the command line, a signal in Python). Null: never.
  std::function<bool()> stop_requested;
  // The inputs are an earlier result of the same request after a small edit (moved or newly
  // fixed vertices: the service's re-solve). The problems whose result is a mesh of the input's
  // (planarize, anet) then start soft-free, as MeshProblem::Resolve does: closeness and fairness
  // off, so the re-solve pulls only what the edit broke back to the tolerance, in one or two
  // iterations, instead of re-running the fade of the soft terms from the start.
  bool soft_free_start = false;

  bool Wants(const std::string& output) const { return outputs.count(output) > 0; }
  bool StopRequested() const { return stop_requested && stop_requested(); }
  bool Record(const RunRecord& record) const {
    return !StopRequested() && (!on_record || on_record(record));
  }
  void Headline(const std::string& text) const;
  void Columns(const std::vector<std::string>& columns) const {
    if (on_columns) on_columns(columns);
  }
  void Iterate(int iteration, const PolyMesh& mesh) const {
    if (on_iterate) on_iterate(iteration, mesh);
  }
  void Info(const std::string& text) const;
};

struct RunResult {
  RunReport report;
  nlohmann::json facts = nlohmann::json::object();  // the problem's own report keys
  std::map<std::string, PolyMesh> meshes;           // outputs of kind kMesh
  std::map<std::string, std::string> texts;         // outputs of the other kinds
  // Named numeric results (#rows × #columns, documented by the problem), e.g. the directions of
  // a field (#V × 3): numpy arrays in Python.
  std::map<std::string, Eigen::MatrixXd> arrays;
  // Keys added to the report's history entries, one object per record (empty: none), e.g. the
  // level of a multiresolution run.
  std::vector<nlohmann::json> history_facts;
  // Shown after the run, before its conclusion: kInfo lines (the final measures), kWarning
  // (far from the asked net, ...).
  std::vector<RunMessage> messages;
  // The measure the tolerance bounds (empty: the solver's own tolerance) and the tolerance.
  std::string tolerance_measure;
  double tolerance = 0.0;
  // Why the tolerance was missed (quads above it, bounds that hold), shown when not converged.
  std::vector<std::string> shortfalls;

  void Info(std::string text) { messages.push_back({RunMessage::Kind::kInfo, std::move(text)}); }
  void Warn(std::string text) { messages.push_back({RunMessage::Kind::kWarning, std::move(text)}); }
};

// A named numeric result of a run (RunResult::arrays).
struct ArraySpec {
  std::string name;
  std::string doc;  // with its shape, e.g. "#V x 3: ..."
};

struct ProblemSpec {
  std::string name;     // the subcommand and function name, e.g. "planarize"
  std::string summary;  // one paragraph
  std::vector<InputSpec> inputs;
  std::vector<OutputSpec> outputs;
  std::vector<OptionSpec> options;
  std::vector<ArraySpec> arrays;          // the arrays a run returns
  std::vector<std::string> log_measures;  // the live log's columns
  // Makes an input rather than solving one (a test grid): Python returns its one mesh output
  // as (V, F) alone, and the command line writes it without a report or a conclusion.
  bool generator = false;
  // Runs on checked, complete options (CompleteOptions). Throws InputError for bad input.
  std::function<RunResult(const RunInputs&, const nlohmann::json&, const RunContext&)> run;

  const OptionSpec* FindOption(const std::string& name) const;
  const InputSpec* FindInput(const std::string& name) const;
  // The output a warm re-solve starts from (RunContext::soft_free_start): a mesh of the input's
  // connectivity, when the problem also has a "mesh" input and "fixed" vertex ids; null when it
  // has no warm re-solve.
  const OutputSpec* WarmResolveOutput() const;
};

class Registry {
 public:
  // Every problem of gproj (gproj/problems/run/builtin_problems.cc).
  static const Registry& Builtin();

  // Adds a problem; throws std::invalid_argument for a duplicate or malformed entry (a name
  // that is not an identifier, two options of one name, a default outside its range).
  void Add(ProblemSpec spec);
  const ProblemSpec* Find(const std::string& name) const;
  const std::vector<ProblemSpec>& problems() const { return problems_; }

  // The registry as JSON: {"version", "problems": [{name, summary, inputs, outputs, options,
  // log_measures}, ...]}.
  nlohmann::json SchemaJson() const;

 private:
  std::vector<ProblemSpec> problems_;
};

// A warm re-solve's inputs after an edit (a designer dragging or pinning vertices), from a run's
// `inputs` and its `result` (the output spec.WarmResolveOutput() names, numbered as the mesh
// input after any weld): the mesh input becomes `result` with the vertices `moved` put at `to`
// and held, the vertices `fixed` held too, beside those the run held already; the weld maps
// and file names are dropped (the result is numbered as the welded mesh). Run it with
// RunContext::soft_free_start. Throws InputError naming the vertex (out of range, moved twice,
// a non-finite position), or when the problem has no warm re-solve.
void ApplyWarmEdit(const ProblemSpec& spec, PolyMesh result, const std::vector<int>& moved,
                   const std::vector<Eigen::Vector3d>& to, const std::vector<int>& fixed,
                   RunInputs* inputs);

// The one run protocol: options checked and completed against the schema, then spec.run.
// Throws InputError (OptionError for a bad option).
RunResult RunProblem(const ProblemSpec& spec, const RunInputs& inputs,
                     const nlohmann::json& options, const RunContext& context);

// The run's report (gproj/problems/run/report_json.h) with the problem's facts, the complete
// options under "options", "input" (the first input given) and "output", and a key per other input
// given (e.g. "reference"): the file it was read from (RunInputs::files), else null (an input
// given as arrays).
nlohmann::json RunResultJson(const ProblemSpec& spec, const RunResult& result,
                             const nlohmann::json& options, const RunInputs& inputs,
                             const nlohmann::json& output);

// Messages of a run name options as `name` (backquoted); a front end spells them its way: the
// command line as --kebab-case flags, Python as keyword names (without the quotes).
std::string SpellOptions(const std::string& text, bool command_line);

// The reference page of a problem (Markdown): summary, inputs, outputs and a table of its
// options with their command-line flags, Python keywords, types, defaults, ranges and units.
// docs/reference/NAME.md is this page (`gproj schema --markdown docs/reference`; a test keeps
// the checked-in pages current).
std::string ReferenceMarkdown(const ProblemSpec& spec);

// gproj's version ("0.1.0").
const char* GprojVersion();

}  // namespace gproj
