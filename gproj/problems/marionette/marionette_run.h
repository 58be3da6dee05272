#pragma once
// The modes of Marionette meshes (002) behind one call, for `gproj marionette` and any other
// front end: the inputs are read and checked (InputError of one line naming the file, line,
// option or rule), then the mode runs and reports in the shared RunReport, so that the front
// end only logs, writes and maps exit codes. Modes solved directly (propagation, the normal
// equations of a fit, the closing lift of a strip) report as solver "direct" with no
// iterations; the others run a GuidedProblem. Nothing is printed: descriptions are returned.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/marionette/marionette_mesh.h"
#include "gproj/problems/marionette/marionette_mesh_problem.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/report_json.h"

namespace gproj::marionette {

// What a Marionette run takes; the mode follows from what is given:
//   closed_strip                 a closed strip (002 §2.5) lifted by its closing condition (eq. 8);
//   guides, or a projection      a plan of any connectivity lifted on the lines of the projection
//   other than vertical          (MarionetteMeshProblem), guides from the file or row / column;
//   otherwise                    a grid plan lifted from row and column, or fitted to the heights
//                                of the mesh `fit` or of the vertices in `fit_heights`, with the
//                                hard constraints if any (MarionetteGridProblem).
struct MarionetteRunOptions {
  std::string plan;    // plan view: a quad mesh file
  std::string guides;  // guide file (ReadMarionetteGuides)
  std::string fit;     // target mesh with the plan's vertex order
  // A partial target: lines "VERTEX HEIGHT" ('#' comments); the fit follows only these.
  std::string fit_heights;
  // Hard linear constraints of the fit (002 §3.3), met exactly (direct solver).
  MarionetteConstraints constraints;
  std::string closed_strip;  // closed strip file (ReadClosedStrip) instead of a plan
  // The plan, the fit target and the texts of the guide, fit-heights and closed-strip files held
  // in memory (the registry's front ends): when set, each replaces reading its file, and `plan`,
  // `fit`, `guides`, `fit_heights`, `closed_strip` are only the names used in messages and in
  // Facts(). The meshes are validated like a file.
  std::optional<PolyMesh> plan_mesh, fit_mesh;
  std::optional<std::string> guides_text, fit_heights_text, closed_strip_text;
  std::vector<double> row, column;      // guide values of a grid plan's row 0 and column 0
  std::string projection = "vertical";  // vertical, cylindrical or central
  std::vector<double> axis = {0, 0, 0, 0, 0, 1};  // cylindrical: point and direction
  std::vector<double> centre = {0, 0, 0};         // central: the centre
  // direct, gp (guided projection) or ceres (Levenberg–Marquardt on the same rows)
  SolverKind solver = SolverKind::kDirect;
  double outer_height = 0.0;  // closed strip with a = 1: height of outer vertex 0
  // A vertical plan view whose quads overlap or are not convex is refused unless this is set;
  // then it is lifted with a warning naming the faces.
  bool allow_folded_plan = false;
  // The tolerance of every mode, and guided projection's options on non-vertical lines.
  MarionetteMeshOptions lift;
};

class MarionetteRun {
 public:
  virtual ~MarionetteRun() = default;
  // What was read, for the log: lines ending in '\n'.
  virtual std::string Description() const = 0;
  // Solves; guided projection passes every record to `callback`.
  virtual RunReport Run(const RunCallback& callback) = 0;
  // The lifted mesh (after a run that did not fail).
  virtual PolyMesh Result() const = 0;
  // The mode's own report keys (input files, decomposition, closing condition, ...).
  virtual nlohmann::json Facts() const = 0;
  // The measure the tolerance bounds first (named in a message when it is missed).
  virtual std::string ToleranceMeasure() const = 0;
};

// Reads and checks the inputs of the mode `options` asks for. Throws InputError.
std::unique_ptr<MarionetteRun> MakeMarionetteRun(const MarionetteRunOptions& options);

}  // namespace gproj::marionette
