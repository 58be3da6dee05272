#!/bin/sh
# Quick-start command 1: installs what is missing, builds Release, and planarises the noisy
# 21 x 21 quad grid shipped in examples/data, with a live iteration log.
set -eu
cd "$(dirname "$0")/.."
sh .ci/install-deps
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target gproj
mkdir -p out/demo
echo
echo "== PQ planarisation of examples/data/noisy_grid_21x21.obj (guided projection) =="
./build/gproj planarize examples/data/noisy_grid_21x21.obj -o out/demo/planarized.obj \
  --report out/demo/planarize_report.json --picture out/demo/planarized.svg
echo
echo "== The same problem through the Ceres cross-check path =="
./build/gproj planarize examples/data/noisy_grid_21x21.obj -o out/demo/planarized_ceres.obj \
  --report out/demo/planarize_ceres_report.json --solver ceres --tolerance 1e-6 --max-iterations 200
echo
echo "== H-net: smooth skin of rational bilinear patches from a jittered asymptotic grid of Enneper's surface =="
./build/gproj hnet examples/data/enneper_41x41_jitter3.obj --reference examples/data/enneper_41x41.obj \
  -o out/demo/enneper_hnet.json --surface-mesh out/demo/enneper_hnet_surface.obj --samples 6 \
  --picture out/demo/enneper_hnet.svg --report out/demo/enneper_hnet_report.json
echo
echo "== Marionette mesh: planar quads over a fixed plan view, lifted from two guide curves =="
ROW=$(awk 'BEGIN { for (j = 0; j <= 20; ++j) printf "%s%.4f", (j ? "," : ""), 0.4 * sin(j / 4.0) }')
COLUMN=$(awk 'BEGIN { for (i = 0; i <= 20; ++i) printf "%s%.4f", (i ? "," : ""), 0.3 * (1 - cos(i / 5.0)) }')
./build/gproj marionette examples/data/marionette_plan_21x21.obj -o out/demo/marionette.obj \
  --row "$ROW" --column "$COLUMN" --report out/demo/marionette_report.json
echo
echo "Results in $(pwd)/out/demo (open the .obj files in any mesh viewer, e.g. MeshLab or Blender):"
echo "  planarized.obj                planar-quad mesh (planarized.svg: a picture of it)"
echo "  planarize_report.json         convergence history and final measures"
echo "  planarized_ceres.obj, planarize_ceres_report.json   the Ceres cross-check"
echo "  enneper_hnet.json             H-net: vertices, quads, four corner weights per patch"
echo "  enneper_hnet_surface.obj      the smooth patchwork sampled as a triangle mesh"
echo "  enneper_hnet.svg              a shaded picture of it (open in a web browser)"
echo "  enneper_hnet_report.json      A-net and H-net history, tangent-plane angles, weights"
echo "  marionette.obj                Marionette mesh (planar quads, plan view kept)"
