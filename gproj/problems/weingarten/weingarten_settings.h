#pragma once
// What a user sets for a Weingarten run: a preset and overrides of its options
// (WeingartenSettings), and their conversion to WeingartenOptions.

#include <optional>
#include <string>
#include <vector>

#include "gproj/problems/weingarten/weingarten_options.h"

namespace gproj::weingarten {

// A preset with what a user overrides (unset: the preset's value); the command line and the
// Python module fill one of these.
struct WeingartenSettings {
  std::string preset = "fig1";
  // "none", "linear" (fitted every iteration) or "bspline"; empty: the preset's.
  std::string relation;
  // A fixed linear relation a H + b K + c = 0 (input units): {a, b, c}, or empty. It replaces
  // the relation.
  std::vector<double> linear;
  std::string relation_on;  // "surface" or "auxiliaries"; empty: the preset's
  std::string steps;        // "plain", "monotone" or "projected"; empty: the preset's
  bool no_auxiliaries = false;
  bool allow_folds = false;  // keep steps that fold the surface (WeingartenOptions::prevent_folds)
  std::vector<int> samples;  // {NU, NV}, or empty: the preset's density
  std::optional<int> max_iterations;
  std::optional<double> alignment, closeness, shape, geodesic_parallel, boundary, epsilon, fairness,
      definitions, soft_start, tolerance;
  int refine_levels = 0;
  std::string refine_method = "insert";  // "insert" (knot insertion) or "refit" (least squares)
  int molds = 0;  // cluster the result's samples into at most this many molds (0: none)

  // The preset with the overrides applied; throws InputError naming the rule broken.
  WeingartenOptions ToOptions() const;
};

}  // namespace gproj::weingarten
