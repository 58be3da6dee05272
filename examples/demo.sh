#!/bin/sh
# Quick-start command 1: installs what is missing, builds Release, and planarises the noisy
# 21 x 21 quad grid shipped in examples/data, with a live iteration log.
set -eu
cd "$(dirname "$0")/.."
sh .ci/install-deps
sh .ci/install-web
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
echo "== Darboux cyclide skin: that H-net under an inversion (004 §4), now with regions of K > 0 =="
./build/gproj darboux out/demo/enneper_hnet.json -o out/demo/enneper_skin.json \
  --surface out/demo/enneper_skin.obj --samples 4 --picture out/demo/enneper_skin.svg \
  --report out/demo/enneper_skin_report.json
echo
echo "== Curvature field of a shipped triangle mesh (004 §3.1): asymptotic directions, singularities =="
./build/gproj field examples/data/monkey_saddle_tri.obj -o out/demo/monkey_saddle_field.obj \
  --picture out/demo/monkey_saddle_field.svg --report out/demo/monkey_saddle_field_report.json
echo
echo "== From triangles to an H-net (004 Fig. 4): quads along the asymptotic directions, then the H-net =="
./build/gproj remesh examples/data/monkey_saddle_tri.obj --edge-length 0.15 \
  -o out/demo/monkey_saddle_quads.obj --field out/demo/monkey_saddle_frames.obj \
  --picture out/demo/monkey_saddle_quads.svg --report out/demo/monkey_saddle_quads_report.json
./build/gproj hnet out/demo/monkey_saddle_quads.obj --reference examples/data/monkey_saddle_tri.obj \
  -o out/demo/monkey_saddle_hnet.json --surface-mesh out/demo/monkey_saddle_hnet_surface.obj \
  --picture out/demo/monkey_saddle_hnet.svg --report out/demo/monkey_saddle_hnet_report.json
echo
echo "== Marionette mesh: planar quads over a fixed plan view, lifted from two guide curves =="
ROW=$(awk 'BEGIN { for (j = 0; j <= 20; ++j) printf "%s%.4f", (j ? "," : ""), 0.4 * sin(j / 4.0) }')
COLUMN=$(awk 'BEGIN { for (i = 0; i <= 20; ++i) printf "%s%.4f", (i ? "," : ""), 0.3 * (1 - cos(i / 5.0)) }')
./build/gproj marionette examples/data/marionette_plan_21x21.obj -o out/demo/marionette.obj \
  --row "$ROW" --column "$COLUMN" --report out/demo/marionette_report.json
echo
echo "== Marionette mesh with a valence-6 singularity, lifted patch by patch from six guides =="
./build/gproj marionette examples/data/marionette_plan_valence6.obj \
  --guides examples/data/marionette_valence6_guides.txt -o out/demo/marionette_valence6.obj \
  --report out/demo/marionette_valence6_report.json
echo
echo "== Marionette tower: cylindrical projection, guide radii along one row and one column =="
ROW=$(awk 'BEGIN { for (j = 0; j <= 18; ++j) printf "%s%.4f", (j ? "," : ""), 10 + 0.8 * sin(j / 3.0) }')
COLUMN=$(awk 'BEGIN { for (i = 0; i <= 12; ++i) printf "%s%.4f", (i ? "," : ""), 10 - 3 * (i / 12.0)^2 }')
./build/gproj marionette examples/data/marionette_tower_12x18.obj --projection cylindrical \
  --axis 0,0,0,0,0,1 --row "$ROW" --column "$COLUMN" --solver gp \
  -o out/demo/marionette_tower.obj --report out/demo/marionette_tower_report.json
echo
echo "== Marionette mesh over a Kagome plan (triangles and hexagons, 002 §4.2): two guides, three points, fairness =="
./build/gproj marionette examples/data/marionette_kagome.obj -o out/demo/marionette_kagome.obj \
  --hold 0:0.207055,2:0.129410,6:0.353553,10:0.482963,14:0.482963,18:0.353553,22:0.129410,25:0.565685,44:0.772741,63:0.772741,82:0.565685,101:0.207055,40:0.6,70:0.6,100:0.6 \
  --report out/demo/marionette_kagome_report.json
echo
echo "== Marionette closed strip (closure condition of 002 eq. 8) =="
./build/gproj marionette --closed-strip examples/data/marionette_closed_strip.txt \
  -o out/demo/marionette_strip.obj --report out/demo/marionette_strip_report.json
echo
echo "== Marionette closed mesh of three rings (002 Figs. 7-8, eq. 9): each ring closes outward =="
./build/gproj marionette --closed-strip examples/data/marionette_closed_rings.txt \
  -o out/demo/marionette_rings.obj --report out/demo/marionette_rings_report.json
echo
echo "== Canal surface from a circular strip on a shipped curve, smoothed (000 eq. 5, BFGS); its smooth cyclidic surface (§2.2) =="
./build/gproj canal examples/data/canal_curve.txt --first-point -0.5,0.5,2 --length 2 --smooth \
  -o out/demo/canal.obj --strip out/demo/canal_strip.obj --picture out/demo/canal.svg \
  --surface out/demo/canal_smooth.obj --surface-picture out/demo/canal_smooth.svg \
  --report out/demo/canal_report.json
echo
echo "== C-canal surface (000 §5.2): the canal's lengths found by BFGS so that the C-canal's are 2 (eq. 10) =="
./build/gproj canal examples/data/canal_curve.txt --first-point -0.5,0.5,2 --length 2 \
  --section-scales 1.0000,1.0479,1.0841,1.0997,1.0909,1.0598,1.0141,0.9649,0.9243,0.9022,0.9041,0.9294 \
  -o out/demo/c_canal.obj --picture out/demo/c_canal.svg --report out/demo/c_canal_report.json
echo
echo "== Canal surface fitted to two shipped curves (000 §4.1, eq. 6): spheres touching both, circular mesh =="
./build/gproj canal examples/data/canal_curve_fine.txt --second-curve examples/data/canal_second_curve.txt \
  --normal 0,0,1 -o out/demo/canal_two_curves.obj --picture out/demo/canal_two_curves.svg \
  --report out/demo/canal_two_curves_report.json
echo
echo "== Closed canal surface (000 §4.2): the closing circle of a strip on a closed curve on a sphere =="
./build/gproj canal examples/data/canal_closed_curve.txt --closed --first-point 3.2,-0.2,0.5 --length 0.5 \
  --normal 1,0,0 -o out/demo/canal_closed.obj --strip out/demo/canal_closed_strip.obj \
  --picture out/demo/canal_closed.svg --surface out/demo/canal_closed_smooth.obj \
  --surface-picture out/demo/canal_closed_smooth.svg --report out/demo/canal_closed_report.json
echo
echo "== Torsion-free beams of constant height on the canal mesh (000 §4.3): planar beams, parallel offset =="
./build/gproj beams out/demo/canal.obj --height 0.1 -o out/demo/beams.obj \
  --axes out/demo/beam_axes.obj --offset out/demo/beam_offset.obj --picture out/demo/beams.svg \
  --report out/demo/beams_report.json
echo
echo "== Combescure transformation of a circular surface of revolution (edge lengths along row 0 vary) =="
LENGTHS=$(awk 'BEGIN { for (j = 0; j < 16; ++j) printf "%s%.4f", (j ? "," : ""), 0.09 + 0.05 * sin(j / 5.0) }')
./build/gproj combescure examples/data/revolution_13x17.obj --row-lengths "$LENGTHS" \
  --column-scale 0.8 -o out/demo/combescure.obj --picture out/demo/combescure.svg \
  --report out/demo/combescure_report.json
echo
echo "== M-revolution surface: inversion whose centre maps a parallel's quad to an isosceles trapezoid =="
./build/gproj invert examples/data/revolution_13x17.obj --m-revolution 2,0,1,0,2,1,-2,0,1,0,-2,1 --t 0.6 \
  --ratio 40 -o out/demo/m_revolution.obj --picture out/demo/m_revolution.svg \
  --report out/demo/m_revolution_report.json
echo
echo "== M-revolution surface in one step from a shipped planar curve and two points on a circle (000 §5.1) =="
./build/gproj mrevolution examples/data/m_revolution_curve.txt --p2=-0.6840402866513374,1.8793852415718169,0 \
  --p3 1,1.7320508075688772,0 --t 1 -o out/demo/m_revolution_curve.obj \
  --picture out/demo/m_revolution_curve.svg --report out/demo/m_revolution_curve_report.json
echo
echo "== Its smooth cyclidic surface (000 §2.2): a Dupin cyclide patch per circular quad, joined with common tangent planes =="
./build/gproj cyclidic out/demo/m_revolution_curve.obj --segments 4 -o out/demo/m_revolution_smooth.obj \
  --picture out/demo/m_revolution_smooth.svg --report out/demo/m_revolution_smooth_report.json
echo
echo "== Weingarten surface: align the curvature isolines of a shipped bi-degree (4,4) B-spline (003) =="
./build/gproj weingarten examples/data/freeform_10x10.json -o out/demo/weingarten.json \
  --diagram out/demo/weingarten_diagram.svg --curvature out/demo/weingarten_curvature.csv \
  --molds 20 --picture out/demo/weingarten.svg --surface-mesh out/demo/weingarten_surface.obj \
  --panels 10,10 --panel-tolerance 0.003,3 --panel-picture out/demo/weingarten_panels.svg \
  --seam-histograms out/demo/weingarten_seams.svg --report out/demo/weingarten_report.json
echo
echo "== Fig. 3 of 003: the shipped bump, boundary held, driven to constant mean curvature H = -0.1 =="
./build/gproj weingarten examples/data/bump_14x14.json -o out/demo/cmc.json --preset fig3 \
  --linear 1,0,0.1 --diagram out/demo/cmc_diagram.svg --picture out/demo/cmc.svg \
  --surface-mesh out/demo/cmc_surface.obj --report out/demo/cmc_report.json
echo
echo "Results in $(pwd)/out/demo (open the .obj files in any mesh viewer, e.g. MeshLab or Blender):"
echo "  planarized.obj                planar-quad mesh (planarized.svg: a picture of it)"
echo "  planarize_report.json         convergence history and final measures"
echo "  planarized_ceres.obj, planarize_ceres_report.json   the Ceres cross-check"
echo "  enneper_hnet.json             H-net: vertices, quads, four corner weights per patch"
echo "  enneper_hnet_surface.obj      the smooth patchwork sampled as a triangle mesh"
echo "  enneper_hnet.svg              a shaded picture of it (open in a web browser)"
echo "  enneper_hnet_report.json      A-net and H-net history, tangent-plane angles, weights"
echo "  enneper_skin.json, .obj, .svg its image under an inversion: rational biquadratic Darboux"
echo "                                cyclide patches, sampled, and pictured by the sign of K"
echo "  monkey_saddle_field.obj, .svg asymptotic directions of a triangle mesh (OBJ segments); its report"
echo "                                lists the singularities (one, index -1/2, at the flat point)"
echo "  monkey_saddle_quads.obj, .svg  the triangle mesh remeshed into quads along its asymptotic"
echo "                                directions (one valence-6 vertex at the flat point); the frames"
echo "                                followed in monkey_saddle_frames.obj"
echo "  monkey_saddle_hnet.json, monkey_saddle_hnet_surface.obj, .svg   the H-net on those quads"
echo "  marionette.obj                Marionette mesh (planar quads, plan view kept)"
echo "  marionette_valence6.obj, marionette_tower.obj, marionette_strip.obj   and their reports"
echo "  marionette_rings.obj          a closed Marionette mesh of three rings (its report: a, |V| per ring)"
echo "  marionette_kagome.obj         a Kagome plan lifted with planar hexagons (its report: the design"
echo "                                space by eq. 16 and by rank)"
echo "  canal.obj, canal.svg          canal surface meshed by circular quads; canal_strip.obj its strip"
echo "  canal_smooth.obj, .svg        its smooth cyclidic surface: a Dupin cyclide patch per strip quad (000 §2.2)"
echo "  c_canal.obj, .svg             C-canal surface: a planar cross-section, the asked lengths met (000 §5.2)"
echo "  canal_two_curves.obj, .svg    canal surface whose spheres touch two curves (its report: the spheres)"
echo "  canal_closed.obj, .svg        closed canal surface (000 §4.2); canal_closed_strip.obj its closed strip,"
echo "                                canal_closed_smooth.obj, .svg its smooth cyclidic surface, closed"
echo "  beams.obj, beams.svg          torsion-free beams on the canal mesh; beam_axes.obj the node axes,"
echo "                                beam_offset.obj the parallel offset mesh"
echo "  combescure.obj, .svg          parallel mesh of the surface of revolution (still circular)"
echo "  weingarten.json               the optimised B-spline (JSON, docs/formats.md); weingarten_surface.obj sampled"
echo "  weingarten_diagram.svg        curvature diagram (H, K) before and after: a curve after"
echo "  weingarten_curvature.csv      H, K per sample before/after and the mold of each sample"
echo "  weingarten_panels.svg         the result paneled 10 x 10, one colour per mold (003 §4.2)"
echo "  weingarten_seams.svg          gaps and kinks at the seams, input against result (Fig. 13e)"
echo "  cmc.json, cmc_surface.obj     the bump made CMC (H = -0.1); cmc_diagram.svg: H, K before/after"
echo "  m_revolution.obj, .svg        the surface of revolution inverted (000 §5.1; still circular)"
echo "  m_revolution_curve.obj, .svg  M-revolution surface from a planar curve and two points (circular,"
echo "                                planar vertical arches)"
echo "  m_revolution_smooth.obj, .svg its smooth cyclidic surface (000 §2.2, 320 Dupin cyclide patches)"
echo
echo "The web app and the service (started by nothing here): run"
echo "  ./build/gproj serve"
echo "and open http://127.0.0.1:8765/ in a browser: drop a mesh (or pick a shipped example), press Run"
echo "and watch it solve in 3D; http://127.0.0.1:8765/?example=noisy_grid_21x21&run=1 runs the demo's grid."
echo "The same server answers the API (/api) and Grasshopper's Hops components (/hops/planarize, ...;"
echo "docs/service.md). Ctrl-C stops it."
