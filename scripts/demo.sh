#!/usr/bin/env bash
# The main job on bundled data: installs what is missing, builds the `wavejets` command-line tool
# in Release, then runs it
# - on the Stanford bunny mesh (examples/Wavejets/data/bunny00.off, 37,706 vertices): positions
#   enhanced with gain 2 at the tool's defaults (the README's picture); the paper's Figure 5,
#   positions and normals enhanced with gain 2 at order 6 and Rf = 3% of the bounding-box diagonal;
#   mesh in, mesh out (PLY with the input's faces);
# - on the same bunny with noise: the paper's Figure 12 pipeline (normals filtered first, positions
#   then moved along them) next to the direct enhancement;
# - on the kitten scan (examples/Wavejets/data/kitten.xyz, a point set): curvature, position
#   enhancement (gain 2), flattening (gain 0), inversion (gain -1), normal enhancement (gain 3)
#   and twist (gain 2i);
# - the Python module (python/, built beside the tool): the NumPy example on the kitten.
# Writes the PLY files (open them in MeshLab or CloudCompare) and before/after PNG pictures to the
# folder given as $1 (default: out/). The pictures of the user manual (doc/Wavejets/fig) are the
# same, rendered with --width 560 --height 360.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)"
bash "$root/scripts/install_dependencies.sh"
build="${WAVEJETS_BUILD_DIR:-$root/build/release}"   # another build folder: WAVEJETS_BUILD_DIR=...
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DWAVEJETS_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build "$build" -j2 --target wavejets _wavejets
wavejets="$build/demo/Wavejets/wavejets"
data="$root/examples/Wavejets/data/kitten.xyz"
run() { echo "\$ wavejets $*"; "$wavejets" "$@"; echo; }

bunny="$root/examples/Wavejets/data/bunny00.off"
echo "== The bunny mesh, positions enhanced with gain 2 at the defaults (order 4, 40 nearest neighbors)"
run enhance-positions "$bunny" "$out/bunny_enhanced_positions_defaults.ply" --gain 2
run render --compare "$bunny" "$out/bunny_enhanced_positions_defaults.ply" "$out/bunny_enhanced_positions_defaults.png" --view 0,0.2,1 --width 840 --height 420

# Rf = 3% of the bunny's bounding-box diagonal (1.602): 0.048, about 116 vertices per neighborhood,
# more than the 31 that order 6 needs (28 coefficients x 1.1). --consistent-normals leaves the other
# side of the thin ears out of each neighborhood.
echo "== The paper's Figure 5 on the bunny mesh: positions (gain 2), input left, result right"
run enhance-positions "$bunny" "$out/bunny_enhanced_positions.ply" --gain 2 --order 6 --radius 0.048 --consistent-normals
run render --compare "$bunny" "$out/bunny_enhanced_positions.ply" "$out/bunny_enhanced_positions.png" --view 0,0.2,1 --width 1120 --height 560

echo "== The paper's Figure 5 on the bunny mesh: normals (gain 2), input left, result right"
run enhance-normals "$bunny" "$out/bunny_enhanced_normals.ply" --gain 2 --order 6 --radius 0.048 --consistent-normals
run render --compare "$bunny" "$out/bunny_enhanced_normals.ply" "$out/bunny_enhanced_normals.png" --view 0,0.2,1 --width 1120 --height 560

echo "== The paper's Figure 12 pipeline on a noisy bunny: noisy input, positions (gain 2) moved along"
echo "   their Wavejet normals, and moved along normals filtered first (enhance-normals --gain 0)"
# Gaussian noise of sigma 0.0015 (0.09% of the diagonal) on each coordinate, the same in every run.
awk -v sigma=0.0015 'BEGIN { srand(1) } NR == 1 { print; next } NR == 2 { nv = $1; print; next } NF == 0 { next }
  seen < nv { seen++; for(i = 1; i <= 3; ++i) { u = 1 - rand(); $i += sigma * sqrt(-2 * log(u)) * cos(6.283185307179586 * rand()) }
              printf "%.9g %.9g %.9g\n", $1, $2, $3; next } { print }' "$bunny" > "$out/bunny_noisy.off"
run enhance-positions "$out/bunny_noisy.off" "$out/bunny_noisy_enhanced.ply" --gain 2
run enhance-normals "$out/bunny_noisy.off" "$out/bunny_noisy_filtered_normals.ply" --gain 0
run enhance-positions "$out/bunny_noisy_filtered_normals.ply" "$out/bunny_noisy_enhanced_along_filtered_normals.ply" --gain 2 --along-input-normals
run render --compare "$out/bunny_noisy.off" "$out/bunny_noisy_enhanced.ply" "$out/bunny_noisy_enhanced_along_filtered_normals.ply" \
  "$out/bunny_noisy_pipeline.png" --view 0,0.2,1 --width 1500 --height 500

echo "== Curvature of $data"
run curvature "$data" "$out/kitten_curvature.ply" --order 3
run render "$out/kitten_curvature.ply" "$out/kitten_curvature.png" --color-by mean_curvature

echo "== Position enhancement (gain 2): input left, result right"
run enhance-positions "$data" "$out/kitten_enhanced_positions.ply" --gain 2
run render --compare "$data" "$out/kitten_enhanced_positions.ply" "$out/kitten_enhanced_positions.png"

echo "== Flattening (gain 0): input left, result right"
run enhance-positions "$data" "$out/kitten_flattened_positions.ply" --gain 0
run render --compare "$data" "$out/kitten_flattened_positions.ply" "$out/kitten_flattened_positions.png"

echo "== Inversion (gain -1): input left, result right"
run enhance-positions "$data" "$out/kitten_inverted_positions.ply" --gain -1
run render --compare "$data" "$out/kitten_inverted_positions.ply" "$out/kitten_inverted_positions.png"

echo "== Normal enhancement (gain 3): input left, result right"
run enhance-normals "$data" "$out/kitten_enhanced_normals.ply" --gain 3
run render --compare "$data" "$out/kitten_enhanced_normals.ply" "$out/kitten_enhanced_normals.png"

echo "== Twist of the normals (gain 2i): input left, result right"
run enhance-normals "$data" "$out/kitten_twisted_normals.ply" --gain 0,2
run render --compare "$data" "$out/kitten_twisted_normals.ply" "$out/kitten_twisted_normals.png"

echo "== Python: normals and curvature of the kitten on NumPy arrays (python/examples/numpy_curvature.py)"
echo "\$ PYTHONPATH=$build/python /usr/bin/python3 python/examples/numpy_curvature.py --out $out/python"
PYTHONPATH="$build/python" /usr/bin/python3 "$root/python/examples/numpy_curvature.py" --out "$out/python"
echo

echo "Results in $out:"
ls -l "$out" | tail -n +2
