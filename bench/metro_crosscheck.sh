#!/usr/bin/env bash
# Cross-check of `prm compare` (our Metro-style distance, common/src/metro_distance.cpp) against MeshLab's
# "Hausdorff Distance" filter, an independent implementation (vcglib), on real meshes and modified copies:
#   horse   vs its QEM-decimated copy (MeshLab, 20,000 faces)
#   horse   vs a randomly displaced copy (MeshLab "Random Vertex Displacement")
#   venus   vs its Draco round trip (draco_encoder -qp 12 -cl 10, draco_decoder)
#   rocker-arm vs its QEM-decimated copy (10,000 faces)
#   bunny_zipper (5 holes) vs its QEM-decimated copy (20,000 faces)
# Both tools sample the same way (every vertex, N samples along the edges by length, N on the faces by area;
# `prm compare --sampling meshlab`), so the one-sided mean, RMS and maximum must agree up to sampling noise.
# MeshLab prints six decimals, so every pair is first scaled (by MeshLab) to a bounding-box diagonal of 1000 and
# cleaned of unreferenced vertices; both tools then read the same PLY files.
#
# Needs: a built `prm` (default build/tools/prm/prm), meshlab, xvfb, xauth (apt-get install -y meshlab xvfb xauth),
# the draco tools (package `draco`, for the venus pair), python3. MeshLab is needed by this script only, never by
# the build or the tests.
#
#   bench/metro_crosscheck.sh [PRM_BINARY] [SAMPLES]      (defaults: build/tools/prm/prm, 200000)
# Exit status 1 if a mean or RMS differs by more than 3%, or a maximum by more than 5%.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
prm="${1:-$root/build/tools/prm/prm}"
samples="${2:-200000}"
meshes="$(cd "$root/.." && pwd)/shared/meshes"

for tool in meshlabserver xvfb-run python3; do
  command -v "$tool" >/dev/null || { echo "metro_crosscheck: $tool not found (apt-get install -y meshlab xvfb xauth python3)" >&2; exit 2; }
done
[ -x "$prm" ] || { echo "metro_crosscheck: $prm is not built" >&2; exit 2; }
prm="$(cd "$(dirname "$prm")" && pwd)/$(basename "$prm")"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

meshlab() {  # meshlab LOG -i IN [-i IN2] [-o OUT] -s SCRIPT: meshlabserver under a virtual X server (it needs GL)
  local log="$1"; shift
  xvfb-run -a -s "-screen 0 640x480x24" meshlabserver "$@" -l "$log" > "$log.out" 2>&1 || {
    echo "metro_crosscheck: meshlabserver failed ($*):" >&2; tail -5 "$log.out" >&2; exit 3; }
}

cat > decimate.mlx.in <<'EOF'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Simplification: Quadric Edge Collapse Decimation">
  <Param type="RichInt" value="@FACES@" name="TargetFaceNum"/>
  <Param type="RichFloat" value="0" name="TargetPerc"/>
  <Param type="RichFloat" value="0.3" name="QualityThr"/>
  <Param type="RichBool" value="false" name="PreserveBoundary"/>
  <Param type="RichFloat" value="1" name="BoundaryWeight"/>
  <Param type="RichBool" value="false" name="PreserveNormal"/>
  <Param type="RichBool" value="true" name="PreserveTopology"/>
  <Param type="RichBool" value="true" name="OptimalPlacement"/>
  <Param type="RichBool" value="false" name="PlanarQuadric"/>
  <Param type="RichFloat" value="0.001" name="PlanarWeight"/>
  <Param type="RichBool" value="false" name="QualityWeight"/>
  <Param type="RichBool" value="true" name="AutoClean"/>
  <Param type="RichBool" value="false" name="Selected"/>
 </filter>
</FilterScript>
EOF

cat > displace.mlx.in <<'EOF'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Random Vertex Displacement">
  <Param type="RichBool" value="false" name="UpdateNormals"/>
  <Param type="RichAbsPerc" value="@AMOUNT@" min="0" max="1000" name="Displacement"/>
 </filter>
</FilterScript>
EOF

# Uniform scaling about the origin, applied to the coordinates; unreferenced vertices removed (MeshLab samples
# every vertex it holds, prm only referenced ones).
cat > scale.mlx.in <<'EOF'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Remove Unreferenced Vertices"/>
 <filter name="Transform: Scale, Normalize">
  <Param type="RichFloat" value="@S@" name="axisX"/>
  <Param type="RichFloat" value="@S@" name="axisY"/>
  <Param type="RichFloat" value="@S@" name="axisZ"/>
  <Param type="RichBool" value="true" name="uniformFlag"/>
  <Param type="RichEnum" value="0" enum_cardinality="3" enum_val0="origin" enum_val1="barycenter" enum_val2="custom point" name="scaleCenter"/>
  <Param type="RichPoint3f" x="0" y="0" z="0" name="customCenter"/>
  <Param type="RichBool" value="false" name="unitFlag"/>
  <Param type="RichBool" value="true" name="Freeze"/>
  <Param type="RichBool" value="false" name="allLayers"/>
 </filter>
</FilterScript>
EOF

cat > haus.mlx.in <<EOF
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Hausdorff Distance">
  <Param type="RichMesh" value="@SAMPLED@" name="SampledMesh"/>
  <Param type="RichMesh" value="@TARGET@" name="TargetMesh"/>
  <Param type="RichBool" value="false" name="SaveSample"/>
  <Param type="RichBool" value="true" name="SampleVert"/>
  <Param type="RichBool" value="true" name="SampleEdge"/>
  <Param type="RichBool" value="false" name="SampleFauxEdge"/>
  <Param type="RichBool" value="true" name="SampleFace"/>
  <Param type="RichInt" value="$samples" name="SampleNum"/>
  <Param type="RichAbsPerc" value="100000" min="0" max="1000000" name="MaxDist"/>
 </filter>
</FilterScript>
EOF

diagonal() { "$prm" compare "$1" "$1" --json --samples 1000 | python3 -c 'import json,sys; print(json.load(sys.stdin)["diagonal"])'; }

to_ply() {  # to_ply IN OUT: any format MeshLab reads (not OBJ: vcglib asserts on it) to PLY
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n</FilterScript>\n' > noop.mlx
  meshlab "conv_$2.log" -i "$1" -o "$2" -s noop.mlx
}

decimate() { sed "s/@FACES@/$3/" decimate.mlx.in > dec.mlx; meshlab "dec_$2.log" -i "$1" -o "$2" -s dec.mlx; }
displace() { sed "s/@AMOUNT@/$3/" displace.mlx.in > disp.mlx; meshlab "disp_$2.log" -i "$1" -o "$2" -s disp.mlx; }
draco_round_trip() {
  draco_encoder -i "$1" -o "$2.drc" -qp 12 -cl 10 > /dev/null
  draco_decoder -i "$2.drc" -o "$2" > /dev/null
}

printf 'pair,direction,figure,meshlab,prm,relative difference\n' > results.csv

# check NAME A B: scale both by 1000 / diagonal(A), then measure both ways with both tools.
check() {
  local name="$1" a="$2" b="$3"
  local s
  s="$(python3 -c "print(1000.0 / $(diagonal "$a"))")"
  sed "s/@S@/$s/g" scale.mlx.in > scale.mlx
  meshlab "scale_a_$name.log" -i "$a" -o "${name}_a.ply" -s scale.mlx
  meshlab "scale_b_$name.log" -i "$b" -o "${name}_b.ply" -s scale.mlx
  for dir in ab ba; do
    if [ $dir = ab ]; then sampled=0; target=1; else sampled=1; target=0; fi
    sed "s/@SAMPLED@/$sampled/; s/@TARGET@/$target/" haus.mlx.in > haus.mlx
    meshlab "haus_${name}_$dir.log" -i "${name}_a.ply" -i "${name}_b.ply" -s haus.mlx
  done
  "$prm" compare "${name}_a.ply" "${name}_b.ply" --json --samples "$samples" --sampling meshlab > "prm_$name.json"
  python3 - "$name" "haus_${name}_ab.log" "haus_${name}_ba.log" "prm_$name.json" >> results.csv <<'EOF'
import json, re, sys
name, log_ab, log_ba, prm_json = sys.argv[1:5]
j = json.load(open(prm_json))
for direction, log, key in (("A->B", log_ab, "a_to_b"), ("B->A", log_ba, "b_to_a")):
    text = open(log).read()
    m = re.search(r"Sampled (\d+) pts.*?\n\s*min : \S+\s+max (\S+)\s+mean : (\S+)\s+RMS : (\S+)", text, re.S)
    if not m:
        sys.exit("cannot parse " + log)
    ml = {"samples": int(m.group(1)), "max": float(m.group(2)), "mean": float(m.group(3)), "rms": float(m.group(4))}
    ours = j[key]
    for fig in ("samples", "mean", "rms", "max"):
        a, b = ml[fig], ours[fig]
        rel = abs(b - a) / abs(a) if a else (0.0 if b == 0 else float("inf"))
        print(f"{name},{direction},{fig},{a:.6g},{b:.6g},{rel:.4%}")
EOF
}

echo "metro_crosscheck: preparing the meshes (MeshLab, Draco)" >&2
to_ply "$meshes/venus.off" venus.ply
to_ply "$meshes/rocker-arm.off" rocker.ply
decimate "$meshes/horse.ply" horse_dec.ply 20000
displace "$meshes/horse.ply" horse_noise.ply 0.0003
draco_round_trip venus.ply venus_draco.ply
decimate rocker.ply rocker_dec.ply 10000
decimate "$meshes/bunny_zipper.ply" bunny_dec.ply 20000

echo "metro_crosscheck: measuring ($samples edge and $samples face samples per direction)" >&2
check horse-decimated "$meshes/horse.ply" horse_dec.ply
check horse-displaced "$meshes/horse.ply" horse_noise.ply
check venus-draco12 venus.ply venus_draco.ply
check rocker-decimated rocker.ply rocker_dec.ply
check bunny-decimated "$meshes/bunny_zipper.ply" bunny_dec.ply

python3 - results.csv <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| pair | direction | figure | MeshLab | prm compare | rel. difference |")
print("|---|---|---|---:|---:|---:|")
worst = {"mean": 0.0, "rms": 0.0, "max": 0.0}
for r in rows:
    print(f"| {r['pair']} | {r['direction']} | {r['figure']} | {r['meshlab']} | {r['prm']} | {r['relative difference']} |")
    if r["figure"] in worst:
        worst[r["figure"]] = max(worst[r["figure"]], float(r["relative difference"].rstrip("%")) / 100)
print()
print("largest relative difference: mean %.3f%%, RMS %.3f%%, max %.3f%% (units: the pair scaled to a diagonal of 1000)"
      % (100 * worst["mean"], 100 * worst["rms"], 100 * worst["max"]))
sys.exit(1 if worst["mean"] > 0.03 or worst["rms"] > 0.03 or worst["max"] > 0.05 else 0)
EOF
