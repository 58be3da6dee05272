#pragma once
// What the mesh problems' runs tell a user about their result, in every front end: the per-face
// outputs (CSV values, a PLY heat map, an SVG picture), the panel summary line, and the warning
// that the result is far from the input.

#include <optional>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/registry.h"

namespace gproj {

// The outputs "face_values" (the CSV text `csv`), "heatmap" (PLY, a colour per face) and
// "picture" (SVG titled `title`) that `context` asks for, into result->texts. The colours show
// `values` (one per face) on `scale`.
void AddFaceOutputTexts(const PolyMesh& mesh, const std::vector<double>& values,
                        const ColourScale& scale, const std::string& csv, const std::string& title,
                        const RunContext& context, RunResult* result);

// The SVG picture of `mesh` titled `title` as the output `output` when `context` asks for it.
void AddMeshPicture(const RunContext& context, const std::string& output, const PolyMesh& mesh,
                    const std::string& title, RunResult* result);

// "panels: non-convex quads 0 -> 0, smallest corner angle …" from the ShapeValues of the initial
// and final measures, preceded by the gliding line when the final measures have
// max_glide_distance.
std::vector<std::string> PanelSummaryLines(const NamedValues& initial, const NamedValues& final);

// "the input is far from <target>: …" when a corner angle changed by more than the change's
// threshold in over 5% of the quads, or a vertex moved more than 2% of the bbox diagonal.
std::optional<std::string> FarFromInputWarning(const std::string& target, const ShapeChange& change,
                                               double max_displacement);

// PanelSummaryLines of the run's initial and final measures as kInfo messages and, when `mesh`
// (the result) is far from `input` (corner angles changed by more than `threshold_deg`),
// FarFromInputWarning for `target` ("a PQ (conjugate) mesh") as a kWarning.
void AddPanelMessages(const std::string& target, const PolyMesh& input, const PolyMesh& mesh,
                      double threshold_deg, double max_displacement, RunResult* result);

}  // namespace gproj
