#pragma once
// What the super-canal constructions (Combescure transformations, inversions, canal surfaces;
// 000) share: the measures of a circular mesh, and the report of a construction that takes no
// iterations.

#include <nlohmann/json.hpp>
#include <string>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/mobius.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::circular {

// Planarity and concyclicity of a quad mesh, per mean edge length, as named values (the
// report's keys): max_planarity, mean_planarity (diagonal distance), max_concyclicity,
// mean_concyclicity (distance to the fitted circle), worst_concyclic_face, folded_quads (quads
// that are not convex: crossed or degenerate).
NamedValues MeasureCircularMesh(const PolyMesh& mesh);

// "" when MeasureCircularMesh's `measures` have no folded quads, else "the canal mesh has N
// crossed quads (<hint>)".
std::string CrossedQuadsFault(const NamedValues& measures, const std::string& hint);

// "<label>: max planarity …, max concyclicity … (…)" from MeasureCircularMesh's values, for logs.
std::string CircularMeasuresLine(const std::string& label, const NamedValues& measures);

// The report's "m_revolution" object: t, the centres found, the root used, the image's side
// angle (radians) and diagonals.
nlohmann::json MRevolutionJson(const MRevolutionChoice& choice, double t, int root);

}  // namespace gproj::circular
