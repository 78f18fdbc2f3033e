#!/usr/bin/env bash
# End-to-end tests of the `wavejets` tool, one case per CTest test. Each case is a function
# cli_case_NAME below; CMake registers every one of them (`--list` prints their names):
#   cli_test.sh CASE WAVEJETS WAVEJETS_CHECK KITTEN_XYZ WORK_DIR
#   cli_test.sh --list
set -uo pipefail
failures=0
fail() { echo "FAIL [$case_name]: $*"; failures=$((failures + 1)); }
run() { echo "+ wavejets $*"; "$wj" "$@"; }

# A command must succeed and write OUT with the input's points, in order, and the properties.
expect_ok() { # IN OUT TOLERANCE PROPS -- COMMAND ARGS...
  local in=$1 out=$2 tol=$3 props=$4; shift 5
  run "$@" || { fail "exit status $? for: $*"; return; }
  [ -f "$out" ] || { fail "no output $out"; return; }
  # shellcheck disable=SC2086
  "$check" points "$in" "$out" "$tol" $props || fail "output check of $out"
}

# A command must fail with a one-line error naming FILE, and leave no output nor temporary file.
expect_error() { # FILE OUT -- COMMAND ARGS...
  local file=$1 out=$2; shift 3
  "$wj" "$@" > stdout.txt 2> stderr.txt
  local status=$?
  echo "+ wavejets $* -> exit $status: $(cat stderr.txt)"
  [ $status -ne 0 ] || fail "exit status 0 for: $*"
  [ "$(wc -l < stderr.txt)" -eq 1 ] || fail "error is not one line for: $* ($(cat stderr.txt))"
  grep -q "error" stderr.txt || fail "no error message for: $*"
  grep -qF -- "$file" stderr.txt || fail "the error does not name $file"
  [ ! -e "$out" ] || fail "$out was written by: $*"
  [ -z "$(ls -A | grep -F '.tmp-')" ] || fail "temporary file left by: $*"
}

kitten_props="fitted"
cli_case_help() {
  run --help | tee help.txt
  for c in normals curvature enhance-positions enhance-normals render; do
    grep -q "$c" help.txt || fail "global help misses $c"
    run "$c" --help > "help_$c.txt" || fail "$c --help failed"
    grep -q -- "--help" "help_$c.txt" || fail "$c --help lists no flags"
  done
  grep -q -- "--max-displacement" help_enhance-positions.txt || fail "enhance-positions --help misses --max-displacement"
  grep -q -- "--gain" help_enhance-normals.txt || fail "enhance-normals --help misses --gain"
  grep -q -- "--compare" help_render.txt || fail "render --help misses --compare"
}

cli_case_normals() {
  expect_ok "$kitten" n.ply 0 "fitted" -- normals "$kitten" n.ply --k 30
  expect_ok "$kitten" n_ascii.ply 1e-12 "fitted" -- normals "$kitten" n_ascii.ply --radius 0.05 --k 60 --ascii
  head -c 3 n_ascii.ply | grep -q ply || fail "not a PLY"
  grep -aq "format ascii" n_ascii.ply || fail "--ascii did not write ASCII"
  grep -aq "format binary_little_endian" n.ply || fail "default PLY is not binary"
  # PLY input (the previous output), and OFF input (the kitten's vertices).
  expect_ok n.ply n2.ply 0 "fitted" -- normals n.ply n2.ply
  awk 'BEGIN { } { p[NR] = $1 " " $2 " " $3 } END { print "OFF"; print NR " 0 0"; for(i = 1; i <= NR; ++i) print p[i] }' "$kitten" > kitten.off
  expect_ok "$kitten" n_off.ply 0 "fitted" -- normals kitten.off n_off.ply
}

cli_case_normals_without_input_normals() {
  awk '{ print $1, $2, $3 }' "$kitten" > bare.xyz
  expect_ok bare.xyz n.ply 0 "fitted" -- normals bare.xyz n.ply
  # The estimated normals must be oriented like the scan's (outward): most agree with the input's.
  expect_ok "$kitten" n_ref.ply 0 "fitted" -- normals "$kitten" n_ref.ply
  "$check" agree n.ply n_ref.ply 0.95 || fail "the estimated normals are not oriented like the scan's"
}

cli_case_curvature() {
  expect_ok "$kitten" c.ply 0 "fitted mean_curvature gaussian_curvature k1 k2 k1_dir_x k1_dir_y k1_dir_z k2_dir_x k2_dir_y k2_dir_z quality" \
    -- curvature "$kitten" c.ply --order 3 | tee summary.txt
  grep -q "not fitted" summary.txt || fail "the summary does not count unfitted points"
}

cli_case_enhance_positions() {
  expect_ok "$kitten" p.ply 0.00100001 "fitted" -- enhance-positions "$kitten" p.ply --gain 3 --max-displacement 0.001 | tee summary.txt
  grep -q "clamped" summary.txt || fail "the summary does not count clamped points"
  # Without the clamp (default evaluation radius s = Rf, gain 2), a point moves by
  #   |f00 - 2 pi (gain - 1) a0(s) / Rf^2|,  2 pi a0(s) = the signed volume between the Wavejet and
  # its tangent plane over the disc of radius s <= Rf. Where the Wavejet stays within the ball of
  # radius Rf holding its neighbors (the height-field assumption), |f00| <= Rf and
  # |2 pi a0(s)| <= pi s^2 Rf, so the motion is at most (1 + pi (gain - 1)) Rf = 4.15 Rf. Where the
  # assumption breaks (which is why the clamp exists) the fit can overshoot without bound; measured on the kitten: 12 of the 5210 points (0.23%) beyond 4.15 Rf, the worst 9.6 Rf.
  # The check allows 1%: a lost point order, a wrong scaling (a0/Rf^3 instead of a0/Rf^2 is 15 times
  # larger here) or a general blow-up fails it. It also needs some point beyond Rf/2, which the
  # default clamp would have cut (measured: 770 points): the clamp is really off.
  # (The distance checked by `points` is unbounded here: `motion` checks it per point.)
  expect_ok "$kitten" p_none.ply inf "fitted" -- enhance-positions "$kitten" p_none.ply --k 40 --max-displacement none
  "$check" motion "$kitten" p_none.ply 40 0.5 4.15 0.01 || fail "unclamped motion out of bounds"
  # With the default clamp, no point moves by more than Rf/2 (plus rounding), and many reach it.
  expect_ok "$kitten" p_clamp.ply inf "fitted" -- enhance-positions "$kitten" p_clamp.ply --k 40
  "$check" motion "$kitten" p_clamp.ply 40 0.499999 0.500001 0 || fail "the default clamp Rf/2 is not applied"
}

cli_case_enhance_normals() {
  expect_ok "$kitten" en.ply 0 "fitted" -- enhance-normals "$kitten" en.ply --gain 3
  expect_ok "$kitten" twist.ply 0 "fitted" -- enhance-normals "$kitten" twist.ply --gain 0,2 --k 40 --order 5
}

cli_case_threads_identical() {
  expect_ok "$kitten" t1.ply 0 "fitted" -- enhance-normals "$kitten" t1.ply --threads 1 --quiet
  expect_ok "$kitten" t2.ply 0 "fitted" -- enhance-normals "$kitten" t2.ply --threads 2 --quiet
  "$check" same t1.ply t2.ply || fail "--threads 1 and 2 differ"
}

cli_case_malformed() {
  : > empty.xyz
  : > empty.ply
  printf 'hello, this is not a point set\n' > garbage.xyz
  printf 'hello, this is not a point set\n' > garbage.ply
  printf 'OFF\nhello\n' > garbage.off
  printf '1 2 3\n4 5\n' > short_line.xyz
  printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > no_points.ply
  "$wj" normals "$kitten" full.ply --quiet || fail "cannot make a full PLY"
  size=$(wc -c < full.ply)
  head -c $((size / 2)) full.ply > truncated.ply
  head -c $((size - 5)) full.ply > truncated_end.ply
  printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n' > truncated_ascii.ply
  printf '0 0 0\n1 0 0\nnan 1 0\n0 1 1\n' > nan.xyz
  printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\nnan 1 0\n0 1 1\n' > nan_ascii.ply
  { printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n'
    printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00'   # 0 0 0
    printf '\x00\x00\xc0\x7f\x00\x00\x80\x3f\x00\x00\x00\x00'   # NaN 1 0
    printf '\x00\x00\x80\x7f\x00\x00\x80\x3f\x00\x00\x80\x3f'   # inf 1 1
  } > nan_binary.ply
  for f in empty.xyz empty.ply garbage.xyz garbage.ply garbage.off short_line.xyz no_points.ply truncated.ply \
           truncated_end.ply truncated_ascii.ply nan.xyz nan_ascii.ply nan_binary.ply missing.xyz; do
    for c in normals curvature enhance-positions enhance-normals; do
      expect_error "$f" out.ply -- "$c" "$f" out.ply
    done
    expect_error "$f" out.png -- render "$f" out.png
  done
  grep -q "NaN" <("$wj" normals nan_binary.ply out.ply 2>&1) || fail "the NaN error does not say NaN"
  # CGAL 5.5's PLY reader gives no reason for these: the tool says "malformed or truncated", or
  # "truncated PLY (...)" when the reader stops early without an error.
  for f in truncated.ply truncated_end.ply truncated_ascii.ply; do
    grep -q "$f: .*truncated" <("$wj" normals "$f" out.ply 2>&1) || fail "the error for $f does not say truncated"
  done
  # An existing output is left untouched by a failing run.
  echo keep > keep.ply
  "$wj" normals garbage.xyz keep.ply 2> /dev/null && fail "garbage accepted"
  [ "$(cat keep.ply)" = keep ] || fail "a failing run replaced an existing output"
  # Unwritable output folder.
  expect_error "no_such_dir" no_such_dir/out.ply -- normals "$kitten" no_such_dir/out.ply
}

cli_case_coincident() {
  # Points that all coincide have no surface: every command fails, naming the file, writing nothing.
  printf '0.1 0.2 0.3\n0.1 0.2 0.3\n0.1 0.2 0.3\n0.1 0.2 0.3\n0.1 0.2 0.3\n' > same.xyz
  printf '0.1 0.2 0.3 0 0 1\n' > single.pwn
  for f in same.xyz single.pwn; do
    for c in normals curvature enhance-positions enhance-normals; do
      expect_error "$f" out.ply -- "$c" "$f" out.ply
      expect_error "$f" out.ply -- "$c" "$f" out.ply --k 3
      expect_error "$f" out.ply -- "$c" "$f" out.ply --radius 0.1
    done
    expect_error "$f" out.png -- render "$f" out.png
  done
  grep -q "all 5 points coincide" <("$wj" normals same.xyz out.ply 2>&1) || fail "the error does not say that the points coincide"
  grep -q "single point" <("$wj" normals single.pwn out.ply 2>&1) || fail "the error does not say single point"
  # Two groups of 7 coincident points: not all equal, but every point's 6 nearest neighbors
  # coincide with it, so a radius of 4 x the average spacing cannot be chosen.
  for i in 1 2 3 4 5 6 7; do echo "0 0 0"; echo "1 1 1"; done > clusters.xyz
  expect_error clusters.xyz out.ply -- normals clusters.xyz out.ply --radius-factor 4
  grep -q "coincides with its nearest neighbors" <("$wj" normals clusters.xyz out.ply --radius-factor 4 2>&1) || fail "clusters: wrong message"
  # Two points: too few to estimate normals for shading.
  printf '0 0 0\n1 0 0\n' > two.xyz
  expect_error two.xyz out.png -- render two.xyz out.png
}

cli_case_library_errors() {
  # Checks of the library (std::invalid_argument) that the command line does not make itself:
  # a bad command line (exit status 2), one line naming the input file, no output.
  for args in "enhance-positions --gain 1e101" "enhance-normals --gain 0,1e101" "enhance-normals --gain 1e101,0"; do
    # shellcheck disable=SC2086
    set -- $args
    expect_error "$kitten" out.ply -- "$1" "$kitten" out.ply "${@:2}"
    "$wj" "$1" "$kitten" out.ply "${@:2}" 2> stderr.txt; status=$?
    [ $status -eq 2 ] || fail "exit status $status (expected 2) for: $args"
    grep -q "the gain must be finite" stderr.txt || fail "the library's message is missing for: $args"
  done
}

cli_case_pwn() {
  # A .pwn file ("x y z nx ny nz" per line) is read with its normals, like the same .xyz.
  cp "$kitten" kitten.pwn
  expect_ok kitten.pwn n_pwn.ply 0 "fitted" -- normals kitten.pwn n_pwn.ply | tee summary.txt
  grep -q "(XYZ, with normals)" summary.txt || fail "the .pwn normals were not read"
  expect_ok "$kitten" n_xyz.ply 0 "fitted" -- normals "$kitten" n_xyz.ply --quiet
  "$check" same n_pwn.ply n_xyz.ply || fail ".pwn and .xyz give different results"
}

cli_case_bad_flags() {
  # (--k abc names a property of the input: cli_case_scale_columns)
  for args in "normals" "nosuchcommand a b" "normals $kitten out.ply --k" "normals $kitten out.ply --k 4x" \
              "normals $kitten out.ply --order 0" "normals $kitten out.xyz" "enhance-positions $kitten out.ply --gain 0,2" \
              "normals $kitten out.ply --gain 2" "enhance-positions $kitten out.ply --max-displacement -1" \
              "normals $kitten out.ply --bogus" "render $kitten out.ply" "normals $kitten out.ply --k 1" \
              "normals $kitten out.ply --radius 0.1 --radius-factor 4"; do
    # shellcheck disable=SC2086
    "$wj" $args > /dev/null 2> stderr.txt; status=$?
    echo "+ wavejets $args -> exit $status: $(cat stderr.txt)"
    [ $status -eq 2 ] || fail "exit status $status (expected 2) for: $args"
    [ "$(wc -l < stderr.txt)" -eq 1 ] || fail "error is not one line for: $args"
    [ ! -e out.ply ] && [ ! -e out.xyz ] || fail "output written for: $args"
  done
}

cli_case_render() {
  run render "$kitten" k.png --width 320 --height 240 --view 0,0,1 || fail "render failed"
  "$check" png k.png 320 240 || fail "render check"
  awk '{ print $1, $2, $3 }' "$kitten" > bare.xyz   # no normals: estimated for shading
  run render bare.xyz bare.png --width 200 --height 200 --view 1,1,1 || fail "render without normals failed"
  "$check" png bare.png 200 200 || fail "render check (no normals)"
  "$wj" curvature "$kitten" c.ply --quiet || fail "curvature for color"
  run render c.ply c.png --width 256 --height 256 --color-by mean_curvature || fail "render --color-by failed"
  "$check" png c.png 256 256 || fail "render check (color)"
}

cli_case_compare() {
  "$wj" enhance-positions "$kitten" p.ply --quiet || fail "enhance-positions"
  run render --compare "$kitten" p.ply cmp.png --width 640 --height 320 || fail "compare failed"
  "$check" png cmp.png 640 320 || fail "compare check"
}

cli_case_mesh_off() {
  # Mesh in, mesh out: every command that writes points keeps the vertex order and the faces,
  # as a PLY with a face element by default, as OFF or OBJ when OUT says so.
  props_of() { case $1 in curvature) echo "fitted mean_curvature quality";; *) echo "fitted";; esac; }
  for c in normals curvature enhance-positions enhance-normals; do
    tol=0; [ "$c" = enhance-positions ] && tol=inf
    # shellcheck disable=SC2046
    expect_ok "$mesh" "m_$c.ply" "$tol" "$(props_of $c)" -- "$c" "$mesh" "m_$c.ply" | tee "summary_$c.txt"
    "$check" faces "$mesh" "m_$c.ply" || fail "$c: the PLY output does not have the input's faces"
    grep -q "read a mesh of 3793 vertices and 7598 faces" "summary_$c.txt" || fail "$c: the summary does not say mesh"
    grep -q "PLY mesh, 3793 vertices in input order and the 7598 input faces" "summary_$c.txt" || fail "$c: the summary does not describe the mesh output"
    grep -q "normals of its faces" "summary_$c.txt" || fail "$c: the input normals do not come from the faces"
    for ext in off obj; do
      run "$c" "$mesh" "m_$c.$ext" --quiet || fail "$c: .$ext output failed"
      "$check" faces "$mesh" "m_$c.$ext" || fail "$c: the .$ext output does not have the input's faces"
    done
  done
  # The OFF output carries the same positions and normals as the PLY output.
  "$check" same m_enhance-positions.ply m_enhance-positions.off || fail "the OFF and PLY outputs differ"
  grep -q "normals of the moved mesh from its faces" summary_enhance-positions.txt || fail "the moved mesh's normals are not its faces'"
  # ASCII PLY output keeps the faces too.
  run enhance-normals "$mesh" m_ascii.ply --ascii --quiet && "$check" faces "$mesh" m_ascii.ply || fail "ASCII PLY mesh output"
  # A point set (the kitten) still gives a point set, and cannot be written as OFF.
  expect_ok "$kitten" p.ply 0 "fitted" -- normals "$kitten" p.ply --quiet
  "$check" no_faces p.ply || fail "a point set got faces"
  "$wj" normals "$kitten" p.off 2> stderr.txt; status=$?
  [ $status -eq 2 ] && grep -q "point set" stderr.txt && [ ! -e p.off ] || fail "OFF output of a point set: exit $status, $(cat stderr.txt)"
}

cli_case_mesh_ply() {
  # A PLY mesh (binary, with a face element) in: PLY mesh out with the same faces and vertex order.
  "$wj" normals "$mesh" in.ply --quiet || fail "cannot make a PLY mesh"
  "$check" faces "$mesh" in.ply || fail "the PLY mesh has other faces"
  expect_ok in.ply out.ply inf "fitted" -- enhance-positions in.ply out.ply --gain 2 | tee summary.txt
  "$check" faces in.ply out.ply || fail "enhance-positions of a PLY mesh lost its faces"
  grep -q "read a mesh of" summary.txt || fail "the summary does not say mesh"
  "$wj" normals "$mesh" in_ascii.ply --ascii --quiet || fail "cannot make an ASCII PLY mesh"
  expect_ok in_ascii.ply out2.ply 0 "fitted" -- enhance-normals in_ascii.ply out2.ply --gain 3 --quiet
  "$check" faces "$mesh" out2.ply || fail "enhance-normals of an ASCII PLY mesh lost its faces"
  # Same results from the OFF and the PLY of the same mesh (the PLY has the OFF's face normals:
  # run both with normals).
  expect_ok "$mesh" a.ply 0 "fitted" -- enhance-normals in.ply a.ply --quiet
  expect_ok "$mesh" b.ply 0 "fitted" -- enhance-normals in.ply b.ply --quiet --threads 1
  "$check" same a.ply b.ply || fail "threads change the results on a mesh"
}

cli_case_mesh_soup() {
  # Polygon soups and non-manifold meshes: faces are copied as they are (here a non-manifold
  # edge, a duplicated face, a quad, a pentagon and an isolated vertex), OBJ input too.
  # (anchor_dense.off: "OFF", then "V F 0", V vertex lines, F face lines; its first face is 3596 2693 27.)
  awk 'NR == 2 { n = $1; print $1 + 1, $2 + 4, 0; next }
       { print }
       NR == n + 2 { print "0.3 0.3 0.3" }
       END { print "3 3596 2693 100"; print "3 3596 2693 27"; print "4 0 1 2 3"; print "5 4 5 6 7 8" }' "$mesh" > soup.off
  head -n 2 soup.off | tail -n 1 | grep -q "^3794 7602 0" || fail "soup.off header: $(head -n 2 soup.off | tail -n 1)"
  expect_ok soup.off soup_out.ply inf "fitted" -- enhance-positions soup.off soup_out.ply | tee summary.txt
  "$check" faces soup.off soup_out.ply || fail "the soup's faces were not copied as they are"
  grep -q "3794 vertices and 7602 faces" summary.txt || fail "the soup summary"
  run enhance-positions soup.off soup_out.off --quiet && "$check" faces soup.off soup_out.off || fail "soup to OFF"
  # OBJ input (v / f lines, 1-based).
  awk 'NR == 2 { n = $1; next } NR > 2 && NR <= n + 2 { print "v", $1, $2, $3; next } NR > n + 2 && NF > 1 { printf "f"; for(i = 2; i <= NF; ++i) printf " %d", $i + 1; print "" }' "$mesh" > m.obj
  expect_ok "$mesh" obj_out.ply inf "fitted" -- enhance-positions m.obj obj_out.ply | tee summary.txt
  "$check" faces "$mesh" obj_out.ply || fail "the OBJ's faces were not kept"
  grep -q "(OBJ, without normals)" summary.txt || fail "the OBJ summary"
  run enhance-positions m.obj obj_out.obj --quiet && "$check" faces "$mesh" obj_out.obj || fail "OBJ to OBJ"
  # A face that refers to a vertex that does not exist: an error naming the file, nothing written.
  awk 'NR == 2 { print $1, $2 + 1, 0; next } { print } END { print "3 0 1 99999" }' "$mesh" > bad_face.off
  expect_error bad_face.off out.ply -- enhance-positions bad_face.off out.ply
}

cli_case_along_input_normals() {
  # The paper's pipeline for noisy inputs (Figure 12): normals filtered at gain 0, then positions
  # moved along them. With --along-input-normals every moved point moves along its input normal;
  # without, along its Wavejet normal, which differs from the filtered one at most points.
  expect_ok "$kitten" n0.ply 0 "fitted" -- enhance-normals "$kitten" n0.ply --gain 0 --quiet
  expect_ok n0.ply along.ply inf "fitted" -- enhance-positions n0.ply along.ply --along-input-normals | tee summary.txt
  grep -q "along the input normals" summary.txt || fail "the summary does not say along the input normals"
  "$check" along n0.ply along.ply 1.0 || fail "--along-input-normals: a point did not move along its input normal"
  expect_ok n0.ply plain.ply inf "fitted" -- enhance-positions n0.ply plain.ply --quiet
  "$check" along n0.ply plain.ply 0.5 && fail "without the flag the points also move along the input normals (the check cannot fail)"
  # Meshes too (input normals from the faces).
  expect_ok "$mesh" m_along.ply inf "fitted" -- enhance-positions "$mesh" m_along.ply --along-input-normals --quiet
  "$check" faces "$mesh" m_along.ply || fail "mesh faces with --along-input-normals"
  # --consistent-normals (neighbors on the other side of a thin part left out): runs, says so, and
  # changes the result on the anchor (which has thin parts).
  expect_ok "$mesh" m_cons.ply inf "fitted" -- enhance-positions "$mesh" m_cons.ply --consistent-normals | tee summary.txt
  grep -q "neighbors with consistent normals" summary.txt || fail "the summary does not say consistent normals"
  expect_ok "$mesh" m_all.ply inf "fitted" -- enhance-positions "$mesh" m_all.ply --all-neighbors | tee summary.txt
  grep -q "neighbors with consistent normals" summary.txt && fail "--all-neighbors: the summary says consistent normals"
  "$check" same m_cons.ply m_all.ply > /dev/null && fail "--consistent-normals changes nothing on the anchor"
  # The default for a mesh (normals from its oriented faces) is --consistent-normals; for a point
  # set (normals possibly unoriented), --all-neighbors.
  expect_ok "$mesh" m_default.ply inf "fitted" -- enhance-positions "$mesh" m_default.ply --quiet
  "$check" same m_cons.ply m_default.ply || fail "a mesh's default is not --consistent-normals"
  expect_ok "$kitten" k_default.ply inf "fitted" -- enhance-normals "$kitten" k_default.ply --quiet
  expect_ok "$kitten" k_all.ply inf "fitted" -- enhance-normals "$kitten" k_all.ply --all-neighbors --quiet
  "$check" same k_all.ply k_default.ply || fail "a point set's default is not --all-neighbors"
}

cli_case_default_neighborhood() {
  # A non-uniform sampling (a bumpy square, 10x denser in one half, as scans and CAD tessellations
  # are): the default neighborhood (the 40 nearest) fits every point at full order, where one radius
  # from the average spacing (dominated by the dense half) leaves the sparse half unfitted.
  awk 'BEGIN { for(i = 0; i <= 100; ++i) for(j = 0; j <= 50; ++j) { x = i / 100; y = j / 100; print x, y, 0.02 * sin(6 * x) * cos(5 * y) }
               for(i = 0; i <= 20; ++i) for(j = 11; j <= 20; ++j) { x = i / 20; y = j / 20; print x, y, 0.02 * sin(6 * x) * cos(5 * y) } }' > nonuniform.xyz
  for c in normals curvature enhance-positions enhance-normals; do
    expect_ok nonuniform.xyz d.ply inf "fitted" -- "$c" nonuniform.xyz d.ply | tee summary.txt
    grep -q "neighborhoods: 40 nearest neighbors (default)" summary.txt || fail "$c: the summary does not give the default neighborhood"
    # The normals estimated first (every command: the input has none) and the command's own fit.
    grep -q "estimated them (order 2; 0 not fitted)" summary.txt || fail "$c: normals left unfitted by the default neighborhood"
    if [ "$c" != normals ]; then
      grep -q ": 5361 points fitted, 0 not fitted (left unchanged), 0 at reduced order" summary.txt ||
        fail "$c: points unfitted or at reduced order with the default neighborhood"
    fi
    expect_ok nonuniform.xyz r.ply inf "fitted" -- "$c" nonuniform.xyz r.ply --radius-factor 4 | tee summary.txt
    grep -q "estimated them (order 2; 0 not fitted)" summary.txt &&
      fail "$c: --radius-factor 4 fits the sparse half too (the checks above cannot fail)"
  done
  # Orders above 6 take 1.5 x their coefficients (order 8: 45 coefficients, 67 neighbors).
  run curvature nonuniform.xyz o8.ply --order 8 | grep -q "67 nearest neighbors (default)" || fail "order 8: not 67 neighbors by default"
}

cli_case_render_mesh() {
  "$check" renderer || fail "renderer self-checks"
  run render "$mesh" m.png --width 320 --height 240 --view 1,1,1 | tee summary.txt || fail "render of a mesh failed"
  "$check" png m.png 320 240 || fail "render check (mesh)"
  grep -q "a mesh of 7598 faces" summary.txt || fail "the mesh was not drawn as a mesh"
  "$wj" curvature "$mesh" mc.ply --quiet || fail "curvature of a mesh"
  run render mc.ply mc.png --width 256 --height 256 --color-by mean_curvature || fail "render --color-by of a mesh failed"
  "$check" png mc.png 256 256 || fail "render check (mesh, color)"
  "$wj" enhance-positions "$mesh" mp.ply --quiet || fail "enhance-positions of a mesh"
  run render --compare "$mesh" mp.ply mcmp.png --width 640 --height 320 | tee summary.txt || fail "compare of meshes failed"
  "$check" png mcmp.png 640 320 || fail "compare check (mesh)"
  grep -q "(left, a mesh of 7598 faces) with mp.ply (right, a mesh of 7598 faces)" summary.txt || fail "compare summary"
  # Three panels, one camera (the paper's gain series).
  run render --compare "$mesh" mp.ply "$mesh" m3.png --width 600 --height 200 | tee summary.txt || fail "compare of three failed"
  "$check" png m3.png 600 200 || fail "compare check (three)"
  grep -q "compared, left to right," summary.txt || fail "compare summary (three)"
}

# Streamed runs (--tile-size, --max-memory) write the bytes of the in-core run.
same_as_in_core() { # NAME TILE_SIZE -- COMMAND ARGS...
  local name=$1 tile=$2; shift 3
  "$wj" "$@" "in_$name.ply" -q || { fail "in-core run failed: $*"; return; }
  run "$@" "st_$name.ply" -q --tile-size "$tile" || { fail "streamed run failed: $* --tile-size $tile"; return; }
  cmp -s "in_$name.ply" "st_$name.ply" || fail "streamed output differs from the in-core one: $* --tile-size $tile"
}

cli_case_streamed_identical() {
  awk '{ print $1, $2, $3 }' "$kitten" > bare.xyz
  for c in normals curvature enhance-positions enhance-normals; do same_as_in_core "kitten_$c" 300 -- "$c" "$kitten"; done
  # k larger than a tile's population; a radius; PLY in (binary and ASCII) and ASCII out.
  same_as_in_core k100 20 -- curvature "$kitten" --k 100
  same_as_in_core radius 50 -- enhance-positions "$kitten" --radius 0.03
  same_as_in_core twist 50 -- enhance-normals "$kitten" --radius 0.05 --k 12 --gain 0,2
  "$wj" normals "$kitten" k.ply -q && "$wj" normals "$kitten" k_ascii.ply -q --ascii
  same_as_in_core ply 100 -- enhance-positions k.ply --gain 3 --max-displacement none
  same_as_in_core ply_ascii 100 -- enhance-normals k_ascii.ply --ascii --consistent-normals
  # Binary PLY as scanners write it: float or int coordinates, either byte order, another column
  # between them and the normals, or no normals (read directly or by CGAL's reader: the same values).
  for variant in "float little" "double big" "float big"; do
    set -- $variant
    "$check" binary_ply "$kitten" "bin_$1_$2.ply" "$1" "$2" > /dev/null || fail "binary_ply $variant"
    same_as_in_core "bin_$1_$2" 200 -- curvature "bin_$1_$2.ply"
  done
  "$check" binary_ply bare.xyz bare_float.ply float little > /dev/null || fail "binary_ply bare"
  same_as_in_core bare_float 150 -- normals bare_float.ply --orient-toward 0,0,5
  # --max-memory: one tile here; the summary says how the run went.
  "$wj" curvature "$kitten" mm.ply --max-memory 1G > summary.txt || fail "--max-memory run failed"
  cmp -s mm.ply in_kitten_curvature.ply || fail "--max-memory output differs from the in-core one"
  grep -q "5210 points in input order, 5210 of them fitted" summary.txt || fail "no streamed summary: $(cat summary.txt)"
  grep -q "the same bytes" summary.txt && fail "the summary claims the same bytes unchecked: $(cat summary.txt)"
  # --verify: the in-memory run too, and the claim only then.
  "$wj" curvature "$kitten" verified.ply --tile-size 700 --verify > summary.txt || fail "--verify run failed"
  cmp -s verified.ply in_kitten_curvature.ply || fail "--verify output differs from the in-core one"
  grep -q "verified: the same bytes as the in-memory run" summary.txt || fail "no verified summary: $(cat summary.txt)"
  ls -a | grep -q '\.tmp-' && fail "--verify left a temporary file: $(ls -a)"
  expect_error --verify out.ply -- curvature "$kitten" out.ply --verify --job job --stage prepare
}

cli_case_auto_scales() {
  # --k auto: a size per point (column scale_k, one of the ladder's), every point fitted; curvature
  # also writes |f_2| at each size; in memory only, and only with numbers of neighbors.
  run normals "$kitten" auto.ply --k auto > auto.txt || fail "normals --k auto failed"
  cat auto.txt
  grep -q "Scales chosen per point" auto.txt || fail "no summary of the scales"
  "$check" points "$kitten" auto.ply 0 fitted || fail "output check of auto.ply"
  grep -aq "property int scale_k" auto.ply || fail "no scale_k column"
  "$wj" curvature "$mesh" auto_c.ply --k auto -q || fail "curvature --k auto failed"
  for c in scale_k f2_k10 f2_k160 mean_curvature; do grep -aq "property [a-z]* $c\$" auto_c.ply || fail "curvature: no $c column"; done
  expect_error "--k auto" out.ply -- normals "$kitten" out.ply --k auto --tile-size 1000
  expect_error "--k auto" out.ply -- normals "$kitten" out.ply --k auto --radius 0.1
}

# The vertex lines of the ASCII PLY MIXED equal those of A where its field FIELD is VA, of B where it
# is VB (the whole line: 17 digits, so the same doubles); both kinds of points are numerous.
same_per_point() { # MIXED FIELD VA A VB B
  paste -d'|' <(sed '1,/^end_header/d' "$1") <(sed '1,/^end_header/d' "$4") <(sed '1,/^end_header/d' "$6") |
    awk -F'|' -v c="$2" -v a="$3" -v b="$5" '{ split($1, f, " ");
      if(f[c] == a) { na++; bad += ($1 != $2) } else if(f[c] == b) { nb++; bad += ($1 != $3) } else bad++ }
      END { print "  " na " points at " a ", " nb " at " b ", " bad + 0 " differ"; exit !(bad == 0 && na > 1000 && nb > 1000) }'
}

cli_case_scale_columns() {
  # --k, --radius, --order COLUMN: each point's own value from a property of the input (any PLY
  # type); each point gets what a run with its value as the flag gives it. In memory only; a
  # missing column or a bad value is an error naming the file and the property.
  local n; n=$(wc -l < "$kitten")
  { printf "ply\nformat ascii 1.0\nelement vertex %d\n" "$n"
    for p in x y z nx ny nz; do echo "property float $p"; done
    printf "property uchar kk\nproperty float rr\nproperty short oo\nproperty float half\nend_header\n"
    # k 12 or 30 by the side of x; radius 1/16 or 3/32 (floats exactly) by y; order 3 or 0 (the default) by z.
    awk '{ print $0, ($1 < 0 ? 12 : 30), ($2 < 0 ? 0.0625 : 0.09375), ($3 < 0 ? 3 : 0), 12.5 }' "$kitten"; } > col.ply
  run normals col.ply k.ply --k kk --ascii -q || fail "normals --k kk failed"
  run normals col.ply k12.ply --k 12 --ascii -q && run normals col.ply k30.ply --k 30 --ascii -q || fail "normals --k N failed"
  same_per_point k.ply 4 12 k12.ply 30 k30.ply || fail "--k kk: a point differs from the run at its k"
  run normals col.ply r.ply --radius rr --k 0 --ascii -q || fail "normals --radius rr failed"
  run normals col.ply r1.ply --radius 0.0625 --k 0 --ascii -q && run normals col.ply r2.ply --radius 0.09375 --k 0 --ascii -q ||
    fail "normals --radius R failed"
  same_per_point r.ply 5 0.0625 r1.ply 0.09375 r2.ply || fail "--radius rr: a point differs from the run at its radius"
  run curvature col.ply o.ply --order oo --ascii -q || fail "curvature --order oo failed"
  run curvature col.ply o3.ply --order 3 --ascii -q && run curvature col.ply o2.ply --ascii -q || fail "curvature --order K failed"
  same_per_point o.ply 6 3 o3.ply 0 o2.ply || fail "--order oo: a point differs from the run at its order"
  run enhance-positions col.ply e.ply --k kk --order oo --radius rr -q > /dev/null || fail "enhance-positions with three columns failed"
  expect_error "nope" out.ply -- normals col.ply out.ply --k nope
  expect_error "half" out.ply -- normals col.ply out.ply --k half
  expect_error "--k" out.ply -- normals col.ply out.ply --k kk --tile-size 1000
  expect_error "--k auto" out.ply -- normals col.ply out.ply --k auto --order oo
  awk 'NR == 11 { $0 = "property float zr" } { print }' col.ply | sed 's/ 0.0625 / 0 /' > zero.ply
  expect_error "zr" out.ply -- normals zero.ply out.ply --radius zr
}

cli_case_streamed_write_in_parts() {
  # 300,000 points in binary PLY: the output in two parts, written by two threads at their places
  # in the file, directly (the tool's own PLY: x y z nx ny nz fitted) or by CGAL's writer (float
  # coordinates, another column between them and the normals).
  awk 'BEGIN { srand(5); for(i = 0; i < 300000; ++i) { x = rand(); y = rand(); printf "%.9f %.9f %.9f 0 0 1\n", x, y, 0.05 * sin(9 * x) * cos(7 * y) } }' > wave.xyz
  "$wj" normals wave.xyz wave.ply -q --k 12 --threads 2 || fail "normals of wave.xyz failed"
  "$check" binary_ply wave.xyz wave_column.ply float little > /dev/null || fail "binary_ply float little"
  same_as_in_core parts_direct 100000 -- enhance-positions wave.ply --k 12 --threads 2
  same_as_in_core parts_cgal 100000 -- curvature wave_column.ply --k 12 --threads 2
}

cli_case_streamed_hard_input() {
  # The kitten with 40 points repeated 50 times each and a cluster of 5000 points (10^-3 apart)
  # straddling the middle of the model: duplicates, and a density 1000x the rest across tiles.
  awk 'BEGIN { srand(7) } { print; line[NR] = $0 }
       END { for(i = 1; i <= 40; ++i) for(j = 0; j < 50; ++j) print line[i * 100];
             for(i = 0; i < 5000; ++i) printf "%.17g %.17g %.17g 0 0 1\n", (rand() - 0.5) * 0.01, (rand() - 0.5) * 0.01, (rand() - 0.5) * 0.001 }' \
      "$kitten" > hard.xyz
  for c in normals curvature enhance-positions enhance-normals; do same_as_in_core "hard_$c" 300 -- "$c" hard.xyz --k 18; done
  same_as_in_core hard_k40 16 -- enhance-positions hard.xyz --k 40
  # Without normals: estimated and oriented toward a viewpoint, the same way in core and streamed.
  awk '{ print $1, $2, $3 }' "$kitten" > bare.xyz
  same_as_in_core bare_normals 100 -- normals bare.xyz --orient-toward 0,0,5
  same_as_in_core bare_enhance 100 -- enhance-positions bare.xyz --orient-toward 0,0,5
  "$check" points "$kitten" in_bare_normals.ply 0 fitted || fail "--orient-toward output check"
}

cli_case_streamed_errors() {
  awk '{ print $1, $2, $3 }' "$kitten" > bare.xyz
  expect_error bare.xyz out.ply -- normals bare.xyz out.ply --tile-size 100
  grep -q -- "--orient-toward" stderr.txt || fail "no hint at --orient-toward: $(cat stderr.txt)"
  expect_error "$mesh" out.ply -- normals "$mesh" out.ply --tile-size 100
  expect_error --radius-factor out.ply -- normals "$kitten" out.ply --tile-size 100 --radius-factor 3
  expect_error --max-memory out.ply -- normals "$kitten" out.ply --tile-size 100 --max-memory 1G
  sed '100s/.*/nan 0 0 0 0 1/' "$kitten" > nan.xyz
  expect_error nan.xyz out.ply -- normals nan.xyz out.ply --tile-size 100
  "$wj" normals "$kitten" k.ply -q
  head -c 30000 k.ply > truncated.ply
  expect_error truncated.ply out.ply -- normals truncated.ply out.ply --tile-size 100
  # Integer coordinates (CGAL's reader would crash on them): a clear error, in memory and streamed.
  "$check" binary_ply "$kitten" int.ply int little > /dev/null || fail "binary_ply int"
  expect_error "int x" out.ply -- normals int.ply out.ply
  expect_error "int x" out.ply -- normals int.ply out.ply --tile-size 100
  # A full disk (here a file size limit: writes fail with EFBIG) fails the run, leaves an existing
  # OUT as it was, and no scratch file.
  echo "previous" > kept.ply
  (trap '' XFSZ; ulimit -f 200; "$wj" curvature "$kitten" kept.ply --tile-size 300 > stdout.txt 2> stderr.txt)
  local status=$?
  echo "+ (ulimit -f 200) wavejets curvature --tile-size 300 -> exit $status: $(cat stderr.txt)"
  [ $status -eq 1 ] || fail "disk full: exit status $status"
  [ "$(cat kept.ply)" = previous ] || fail "disk full: OUT was changed"
  [ -z "$(ls -A | grep -e '.tmp-' -e scratch)" ] || fail "disk full: temporary files left: $(ls -A)"
}

# The steps of a streamed run by hand, sharing the job folder $1 (the tasks of wavejets.distributed):
# the tiles in reverse order and one of them twice, then OUT in one step ($2 = 0) or in $2 parts
# (in reverse order, one twice, then finish). The other arguments: the command's.
staged_run() {
  local job=$1 parts=$2 p t c tiles passes
  shift 2
  local flags=("$@" -q --job "$job")
  mkdir -p "$job"
  run "${flags[@]}" --stage prepare || fail "prepare failed"
  passes=$(awk '$1 == "passes" { print $2 }' "$job/run")
  for p in $(seq 0 $((passes - 1))); do
    [ "$p" -eq 0 ] || run "${flags[@]}" --stage "bin:$p" || fail "bin:$p failed"
    tiles=$(head -1 "$job/pass-$p.tiles")
    [ "$tiles" -gt 3 ] || fail "pass $p: $tiles tiles"
    for t in $(seq $((tiles - 1)) -1 0); do run "${flags[@]}" --stage "tile:$p:$t" || fail "tile:$p:$t failed"; done
    run "${flags[@]}" --stage "tile:$p:1" || fail "tile:$p:1 run again failed"
  done
  if [ "$parts" -eq 0 ]; then
    run "${flags[@]}" --stage write || fail "write failed"
    return
  fi
  for c in $(seq $((parts - 1)) -1 0); do run "${flags[@]}" --stage "write:$c:$parts" || fail "write:$c:$parts failed"; done
  run "${flags[@]}" --stage "write:0:$parts" || fail "write:0:$parts run again failed"
  run "${flags[@]}" --stage "finish:$parts" || fail "finish:$parts failed"
}

cli_case_streamed_staged() {
  # An XYZ input: OUT in one step.
  "$wj" enhance-positions "$kitten" in_staged.ply -q --k 24 || fail "in-core run failed"
  staged_run job 0 enhance-positions "$kitten" st_staged.ply --k 24 --tile-size 700
  [ "$(awk '$1 == "passes" { print $2 }' job/run)" = 2 ] || fail "enhance-positions on a point set with normals: not 2 passes"
  cmp -s in_staged.ply st_staged.ply || fail "staged output differs from the in-core one"
  # Binary PLY in and out: OUT in parts, written directly (x y z nx ny nz fitted) or by CGAL's
  # writer (a uchar column between the coordinates and the normals).
  "$wj" normals "$kitten" k.ply -q || fail "normals of the kitten failed"
  "$wj" enhance-positions k.ply in_parts.ply -q --k 24 || fail "in-core run failed"
  staged_run job_parts 3 enhance-positions k.ply st_parts.ply --k 24 --tile-size 700
  cmp -s in_parts.ply st_parts.ply || fail "output in parts differs from the in-core one"
  "$check" binary_ply "$kitten" bin_float_little.ply float little > /dev/null || fail "binary_ply float little"
  "$wj" curvature bin_float_little.ply in_column.ply -q || fail "in-core run failed"
  staged_run job_column 2 curvature bin_float_little.ply st_column.ply --tile-size 700
  cmp -s in_column.ply st_column.ply || fail "output in parts (another column) differs from the in-core one"
  # Steps whose inputs are missing, steps that do not exist or do not apply: clear errors.
  expect_error "part 0 of 4 of the output is not written" st_bad.ply -- curvature bin_float_little.ply st_bad.ply --job job_column --stage finish:4
  expect_error "in parts only in binary" st_bad.ply -- enhance-positions "$kitten" st_bad.ply --k 24 --job job --stage write:0:2
  mkdir -p empty_job
  expect_error empty_job st_empty.ply -- normals "$kitten" st_empty.ply --job empty_job --stage write
  expect_error "tile:0" st_bad.ply -- normals "$kitten" st_bad.ply --job job --stage tile:0
  expect_error "--stage" st_bad.ply -- normals "$kitten" st_bad.ply --job job
}

cli_case_streamed_interrupted() {
  # A streamed run of a few seconds (300,000 points, one thread), interrupted: no output, no
  # temporary files, exit status 130.
  awk 'BEGIN { srand(3); for(i = 0; i < 300000; ++i) { x = rand(); y = rand(); printf "%.9f %.9f %.9f 0 0 1\n", x, y, 0.05 * sin(9 * x) * cos(7 * y) } }' > big.xyz
  echo "previous" > kept.ply
  "$wj" enhance-positions big.xyz kept.ply --tile-size 20000 --threads 1 --k 40 > stdout.txt 2> stderr.txt &
  local pid=$!
  sleep 1.5
  kill -INT $pid
  wait $pid
  local status=$?
  echo "+ wavejets enhance-positions big.xyz kept.ply --tile-size 20000, SIGINT after 1.5 s -> exit $status: $(cat stderr.txt)"
  [ $status -eq 130 ] || fail "interrupted run: exit status $status (did it end before the signal?)"
  [ "$(cat kept.ply)" = previous ] || fail "interrupted run: OUT was changed"
  [ -z "$(ls -A | grep -e '.tmp-' -e scratch)" ] || fail "interrupted run: temporary files left: $(ls -A)"
}

if [ "${1:-}" = --list ]; then
  declare -F | sed -n 's/^declare -f cli_case_//p'
  exit 0
fi
case_name=$1 wj=$2 check=$3 kitten=$4 work=$5
declare -F "cli_case_$case_name" > /dev/null || { echo "FAIL: unknown case $case_name (--list prints them)"; exit 1; }
# A small triangle mesh next to the kitten (examples/Wavejets/data/anchor_dense.off).
mesh="$(dirname "$kitten")/anchor_dense.off"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"cli_case_$case_name"
[ $failures -eq 0 ] && echo "PASS [$case_name]" || { echo "$failures failure(s) [$case_name]"; exit 1; }
