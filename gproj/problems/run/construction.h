#pragma once
// A build without iterations on constraints (an inversion, mirror images, a jet fit, an
// integer-grid map, a linear lift) as a run: a Construction starts its timer when it is made,
// and Finish turns the measures before and after into the RunReport every problem returns.
// Its method comes from one documented set, the report's "method".

#include <chrono>
#include <string>

#include "gproj/common/run_stopped.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj {

enum class ConstructionMethod {
  kClosedForm,      // "closed form": every point from an explicit formula (an inversion, mirror
                    // images, spheres from two curves, a closing circle, a test grid)
  kPropagation,     // "propagation": element by element from the given ones (a Combescure
                    // transform, Marionette's propagation)
  kLinearSystem,    // "linear system": one sparse least-squares solve (Marionette's lifts)
  kJetFit,          // "jet fit": a local polynomial fit at every vertex (a curvature field)
  kIntegerGridMap,  // "integer-grid map": a seamless parametrisation and the quads of its
                    // integer grid (remeshing)
  kBfgs,            // "BFGS": Ceres' BFGS on a smooth energy (a fit of section scales, the
                    // fairing of a cyclidic net); the report's solver is then "ceres"
};
// "closed form", "propagation", "linear system", "jet fit", "integer-grid map", "BFGS"
const char* ConstructionMethodName(ConstructionMethod method);

class Construction {
 public:
  // Starts the timer. `detail` says what is built ("mirror images"); the report's termination
  // reads "constructed directly (<detail>)".
  Construction(ConstructionMethod method, std::string detail);

  // The report now: solver "direct" ("ceres" for kBfgs), the method, iterations 0, the measures
  // `initial` and `final`, converged when `met`, failed when a final measure is not finite.
  RunReport Finish(const NamedValues& initial, const NamedValues& final, bool met) const;
  // The report of a build stopped on request (RunStopped): USER_ABORT, not converged, no
  // measures.
  RunReport Stopped(const RunStopped& stop) const;
  // Stops the timer: the build is done (for a run that builds when it is made, to check its
  // input, and reports later).
  void Stop() { seconds_ = SecondsSince(start_); }
  // Seconds since the start, or until Stop.
  double seconds() const { return seconds_ >= 0.0 ? seconds_ : SecondsSince(start_); }

 private:
  ConstructionMethod method_;
  std::string detail_;
  std::chrono::steady_clock::time_point start_;
  double seconds_ = -1.0;
};

}  // namespace gproj
