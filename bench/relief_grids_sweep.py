#!/usr/bin/env python3
# Issue 23: bytes at equal RMS, one grid against a grid per relief. Around the grid that `prm pack MESH
# --target-error TARGET --json` chose (UNIFORM_JSON, its output), pack at four fixed grids (0.92 to 1.17 times it,
# the same bits, step scale and height lambda) with one grid ('u'), with --adaptive's curvature model at each
# exponent ('aX') and with its measured model ('m', --adaptive-model measured), then
# interpolate log(bytes) against log(RMS) between the two points around TARGET.
# Usage: PRM_BIN=build/tools/prm/prm bench/relief_grids_sweep.py NAME MESH TARGET UNIFORM_JSON [u m a0.1667 ...]
import json, subprocess, sys, math, os
P = os.environ.get('PRM_BIN', 'build/tools/prm/prm')
name, mesh, target = sys.argv[1], sys.argv[2], float(sys.argv[3])
variants = sys.argv[5:] if len(sys.argv) > 5 else ['u', 'm', 'a0.1667']
u = json.load(open(sys.argv[4]))
G, S, B, L = u['grid_size'], u['step_scale'], u['bits'], u.get('height_lambda', 0)
factors = [0.92, 1.0, 1.08, 1.17]
out = {}
for v in variants:
    pts = []
    for f in factors:
        cmd = ['/usr/bin/time', '-f', '%U %S', 'nice', '-n', '10', P, 'pack', mesh, '--grid', repr(G * f), '--bits', str(B),
               '--step-scale', repr(S), '--height-lambda', repr(L), '--json', '-o', f'sweep_{name}.prm']
        if v.startswith('a'):
            cmd += ['--adaptive', '--adaptive-model', 'curvature', '--adaptive-exponent', v[1:]]
        if v == 'm':
            cmd += ['--adaptive', '--adaptive-model', 'measured']
        r = subprocess.run(cmd, capture_output=True, text=True)
        try:
            j = json.loads(r.stdout)
        except Exception:
            print(name, v, f, 'FAILED', r.stderr[-300:]); continue
        cpu = sum(float(x) for x in r.stderr.strip().split('\n')[-1].split())
        pts.append((j['distance']['rms_rel'], j['bytes']['total'], j['grid_steps'], j.get('grid_sizes'), cpu))
        print(f'{name} {v:8s} f {f:.2f} grid {j["grid_steps"]:3d} sizes {j.get("grid_sizes")} bytes {j["bytes"]["total"]:7d} rms {j["distance"]["rms_rel"]:.4e} max {j["distance"]["max_rel"]:.4e} cpu {cpu:.1f}', flush=True)
    # interpolate log(bytes) against log(rms) at the target, between the bracketing points (sorted by rms)
    pts.sort()
    est = None
    for a, b in zip(pts, pts[1:]):
        if a[0] <= target <= b[0] and b[0] > a[0]:
            t = (math.log(target) - math.log(a[0])) / (math.log(b[0]) - math.log(a[0]))
            est = math.exp(math.log(a[1]) + t * (math.log(b[1]) - math.log(a[1])))
    out[v] = est
    print(f'{name} {v:8s} bytes at rms {target:g}: {est if est is None else round(est)}', flush=True)
base = out.get('u')
for v, e in out.items():
    if base and e:
        print(f'SUMMARY {name} {v:8s} {round(e)} bytes at rms {target:g}: {100 * (e / base - 1):+.1f}% vs uniform')
