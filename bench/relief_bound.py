#!/usr/bin/env python3
# Issue 23: how much can a grid per relief save at all? (bench/README.md "The bound (h23bound)")
#
# 1. `prm pack MESH --target-error TARGET --json --relief-costs`: the uniform stream at the target, and per relief
#    the patch bits charged to it, its lattice vertices, area and mean squared distance to the input (msq).
#    Where the bytes go: reliefs sorted by patch bits per lattice vertex, cut into quartiles of lattice vertices;
#    per quartile its share of the area, of the patch bits and of the squared error (area x msq).
# 2. The same at fixed grids G x FACTORS (G the uniform run's grid; its bits, step scale and height lambda), one grid
#    for every relief. Per relief, least-squares fits log bits_r = a_r + b_r log g and log msq_r = c_r + d_r log g.
# 3. The oracle: per relief a continuous grid g_r in [LO, HI] x G minimising sum bits_r(g_r) subject to
#    sum area_r msq_r(g_r) = the uniform grid's (equal slope, b_r bits_r / g = -lambda d_r area_r msq_r / g, with
#    reliefs at a bound clamped: the problem is separable and convex in log g). No table rounding (2^(k/4)), no seam
#    cost, the areas held at the uniform grid's: an upper bound on what per-relief grids can save. Two accountings:
#    (a) patch bits only, the other sections (connectivity, irregular triangles, positions, header) held fixed;
#    (b) the other sections charged to the reliefs by their share of lattice vertices at each grid (so they shrink
#    with the relief's vertices: generous to the oracle).
#    Also with the fitted exponents clamped to b in [-3, -1], d in [1, 6] (noise in three points).
# Usage: PRM_BIN=build/tools/prm/prm bench/relief_bound.py NAME MESH TARGET [FACTORS, default 1,1.2,1.44]
#        [--no-split] (without the split bound: each relief cut into halves and quarters along its faces' error)
#        SPLIT_BIN=build/bench/prm_bench_relief_split: also the split with classes from a third grid (no noise ranking)
import json, math, os, subprocess, sys

P = os.environ.get('PRM_BIN', 'build/tools/prm/prm')
OUT = os.environ.get('OUT_DIR', '.')
name, mesh, target = sys.argv[1], sys.argv[2], float(sys.argv[3])
factors = [float(x) for x in sys.argv[4].split(',')] if len(sys.argv) > 4 else [1.0, 1.2, 1.44]
LO, HI = 0.5, 2.0  # the oracle's grid range around G (format 1.5's table spans 2^(-3/4)..2 of the search's grid)


def pack(extra, tag):
    path = os.path.join(OUT, f'bound_{name}_{tag}.json')
    cmd = ['/usr/bin/time', '-f', '%U %S', 'nice', '-n', '10', P, 'pack', mesh, '--json', '--relief-costs',
           '-o', os.path.join(OUT, f'bound_{name}.prm')] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{name}: {" ".join(cmd)} failed: {r.stderr[-400:]}')
    open(path, 'w').write(r.stdout)
    j = json.loads(r.stdout)
    cpu = sum(float(x) for x in r.stderr.strip().split('\n')[-1].split())
    print(f'# {" ".join(cmd[5:])}  -> {j["bytes"]["total"]} B, grid {j["grid_steps"]} steps, rms {j["distance"]["rms_rel"]:.4e}, '
          f'{cpu:.1f} s CPU', flush=True)
    return j


def stream_parts(j):
    c = j['relief_costs']
    patch_bits = sum(r['bits'] for r in c['reliefs'])
    other_bits = 8 * j['bytes']['total'] - patch_bits  # prologue, termination, unattributed and every other section
    return patch_bits, other_bits


u = pack(['--target-error', repr(target)], 'target')
G, B, S, L = u['grid_size'], u['bits'], u['step_scale'], u.get('height_lambda', 0)
rel = u['relief_costs']['reliefs']
tot_area = sum(r['area'] for r in rel)
tot_err = sum(r['area'] * r['msq'] for r in rel)
tot_bits = sum(r['bits'] for r in rel)
tot_lat = sum(r['lattice_vertices'] for r in rel)
pb, ob = stream_parts(u)
print(f'\n## {name} at {target:g}: {u["bytes"]["total"]} B (patch bits {pb / 8:.0f} B = {100 * pb / (8 * u["bytes"]["total"]):.1f}%), '
      f'{len(rel)} reliefs, {tot_lat} lattice vertices, {tot_bits / max(tot_lat, 1):.3f} patch bits / lattice vertex')
print('\nWhere the bytes go (reliefs by patch bits per lattice vertex, quartiles of lattice vertices):\n')
print('| quartile | reliefs | bits/vertex | area | patch bits | squared error |')
print('|---|---|---|---|---|---|')
order = sorted((r for r in rel if r['lattice_vertices'] > 0), key=lambda r: r['bits'] / r['lattice_vertices'])
q, acc, groups = 0, 0, [[] for _ in range(4)]
for r in order:
    groups[min(3, int(4 * (acc + r['lattice_vertices'] / 2) / tot_lat))].append(r)
    acc += r['lattice_vertices']
for k, g in enumerate(groups):
    if not g:
        continue
    lat = sum(r['lattice_vertices'] for r in g)
    bits = sum(r['bits'] for r in g)
    print(f'| Q{k + 1} | {len(g)} | {bits / lat:.2f} | {100 * sum(r["area"] for r in g) / tot_area:.0f}% | '
          f'{100 * bits / tot_bits:.0f}% | {100 * sum(r["area"] * r["msq"] for r in g) / tot_err:.0f}% |')

runs = [pack(['--grid', repr(G * f), '--bits', str(B), '--step-scale', repr(S), '--height-lambda', repr(L)], f'g{f:g}')
        for f in factors]
gs = [j['grid_size'] for j in runs]
n = len(rel)


def fit(xs, ys):
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return my - b * mx, b


def relief_models(charge_other):
    models = []  # (area, a, b, c, d) in log g
    for i in range(n):
        xs, yb, ym = [], [], []
        for j in runs:
            rr = j['relief_costs']['reliefs']
            if i >= len(rr) or rr[i]['bits'] <= 0 or rr[i]['msq'] <= 0:
                break
            bits = rr[i]['bits']
            if charge_other:
                pbj, obj = stream_parts(j)
                lat = sum(r['lattice_vertices'] for r in rr)
                bits += obj * rr[i]['lattice_vertices'] / lat
            xs.append(math.log(j['grid_size']))
            yb.append(math.log(bits))
            ym.append(math.log(rr[i]['msq']))
        else:
            a, b = fit(xs, yb)
            c, d = fit(xs, ym)
            models.append((rel[i]['area'], a, b, c, d))
            continue
        models.append(None)  # not measured at every grid: held at G
    return models


def oracle(models, clamp_exponents):
    lo, hi = math.log(G * LO), math.log(G * HI)
    x0 = math.log(G)
    fixed_bits = fixed_err = 0.0
    live = []
    for m in models:
        if m is None:
            continue
        A, a, b, c, d = m
        if clamp_exponents:
            b, d = min(-1.0, max(-3.0, b)), min(6.0, max(1.0, d))
            a = (a + m[2] * x0) - b * x0  # same value at G
            c = (c + m[4] * x0) - d * x0
        live.append((A, a, b, c, d))
    bits_at = lambda m, x: math.exp(m[1] + m[2] * x)
    err_at = lambda m, x: m[0] * math.exp(m[3] + m[4] * x)
    target_err = sum(err_at(m, x0) for m in live)
    uniform_bits = sum(bits_at(m, x0) for m in live)

    def choose(loglam):
        xs = []
        for m in live:
            A, a, b, c, d = m
            # minimise exp(a + b x) + lambda A exp(c + d x) over x in [lo, hi] (convex in x when b <= 0 <= d).
            f = lambda x: bits_at(m, x) + math.exp(loglam) * err_at(m, x)
            if b < 0 < d:
                x = (loglam + math.log(d * A) + c - math.log(-b) - a) / (b - d)
                x = min(hi, max(lo, x))
            else:
                x = min((lo, hi, x0), key=f)
            xs.append(x)
        return xs

    a_lo, a_hi = -60.0, 60.0
    for _ in range(200):  # more lambda: finer grids, less error
        mid = (a_lo + a_hi) / 2
        e = sum(err_at(m, x) for m, x in zip(live, choose(mid)))
        if e > target_err:
            a_lo = mid
        else:
            a_hi = mid
    xs = choose(a_hi)
    best_bits = sum(bits_at(m, x) for m, x in zip(live, xs))
    scales = sorted(math.exp(x) / G for x in xs)
    return uniform_bits, best_bits, scales


def oracle_rows(prefix, make_models):
    # One table row per accounting and exponent choice: make_models(charge_other) gives the units' models.
    pbits, obits = stream_parts(runs[0])
    for charge_other, label in ((False, 'patch bits only, rest fixed'), (True, 'rest charged by lattice vertices')):
        models = make_models(charge_other)
        for clamp in (False, True):
            ub, bb, sc = oracle(models, clamp)
            fixed = 0 if charge_other else obits  # the sections the oracle does not move
            print(f'| {prefix}{label} | {"clamped b -3..-1, d 1..6" if clamp else "as fitted"} | {(ub + fixed) / 8:,.0f} | '
                  f'{(bb + fixed) / 8:,.0f} | {100 * (ub - bb) / (ub + fixed):.1f}% | '
                  f'{sc[0]:.2f} / {sc[len(sc) // 2]:.2f} / {sc[-1]:.2f} |')


print(f'\nFixed grids {", ".join(f"{g:.5g}" for g in gs)} (x {", ".join(map(str, factors))}): '
      + ', '.join(f'{j["bytes"]["total"]} B / rms {j["distance"]["rms_rel"]:.4e}' for j in runs))
print('\nThe oracle (continuous per-relief grids in [%g, %g] x G, equal slope, no seams, no table rounding):\n' % (LO, HI))
print('| accounting | exponents | model bytes at G | oracle bytes | saving of the stream | scales (min / median / max) |')
print('|---|---|---|---|---|---|')
oracle_rows('', relief_models)

def split_models(models, parts):
    # Each relief cut into `parts` (2: halves, 4: quarters) of equal area by its faces' own squared error at G
    # (msq_quarters of the G run); each part with the relief's bits per area (generous to the split: a flat part's
    # heights cost less than the relief's mean) and its exponents; its msq at G measured. Ranking faces by their own
    # error at one grid also ranks noise, so the parts differ more than a split made beforehand could: an upper bound.
    out = []
    x0 = math.log(G)
    for i, m in enumerate(models):
        if m is None:
            continue
        A, a, b, c, d = m
        q = runs[0]['relief_costs']['reliefs'][i]['msq_quarters']
        per = len(q) // parts
        for k in range(parts):
            msq = sum(q[k * per:(k + 1) * per]) / per
            if msq <= 0:
                continue
            out.append((A / parts, a - math.log(parts), b, math.log(msq) - d * x0, d))
    return out


if len(sys.argv) <= 5 or sys.argv[5] != '--no-split':
    print('\nSplit along the detail (each relief in parts of equal area by its faces\' own error at G; bits per area '
          'as the relief\'s):\n')
    print('| parts | accounting | exponents | model bytes at G | oracle bytes | saving of the stream | scales (min / median / max) |')
    print('|---|---|---|---|---|---|---|')
    for parts in (2, 4):
        oracle_rows(f'{parts} | ', lambda charge_other: split_models(relief_models(charge_other), parts))

def class_models(models, split):
    # The split with classes from a third grid (prm_bench_relief_split): per relief and class its area share of the
    # relief's bits (bits per area as the relief's: generous) and its own msq exponent from the two measured grids.
    g0, g1 = split['runs'][0], split['runs'][1]
    x0, x1 = math.log(g0['grid_size']), math.log(g1['grid_size'])
    out = []
    for i, m in enumerate(models):
        if m is None or i >= len(g0['reliefs']):
            continue
        A, a, b, c, d = m
        r0, r1 = g0['reliefs'][i], g1['reliefs'][i]
        ks = [k for k in range(len(r0['area'])) if r0['msq'][k] > 0 and r1['msq'][k] > 0]
        area = sum(r0['area'][k] for k in ks)
        for k in ks:
            share = r0['area'][k] / area
            dk = (math.log(r1['msq'][k]) - math.log(r0['msq'][k])) / (x1 - x0)
            out.append((A * share, a + math.log(share), b, math.log(r0['msq'][k]) - dk * x0, dk))
    return out


if os.environ.get('SPLIT_BIN'):
    cmd = ['nice', '-n', '10', os.environ['SPLIT_BIN'], mesh, repr(G), str(B), repr(S), repr(L)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{" ".join(cmd)} failed: {r.stderr[-400:]}')
    open(os.path.join(OUT, f'bound_{name}_split.json'), 'w').write(r.stdout)
    split = json.loads(r.stdout)
    print(f'\nSplit along the detail, classes from a third grid (`{" ".join(cmd[3:])}`: class grid '
          f'{split["class_grid"]:.5g}, measured at {split["runs"][0]["grid_size"]:.5g} and '
          f'{split["runs"][1]["grid_size"]:.5g}; unclassified area '
          f'{100 * split["runs"][0]["unclassified_area"] / split["runs"][0]["area"]:.1f}% / '
          f'{100 * split["runs"][1]["unclassified_area"] / split["runs"][1]["area"]:.1f}%):\n')
    print('| parts | accounting | exponents | model bytes at G | oracle bytes | saving of the stream | scales (min / median / max) |')
    print('|---|---|---|---|---|---|---|')
    oracle_rows('4 (third grid) | ', lambda charge_other: class_models(relief_models(charge_other), split))
bs = [m for m in relief_models(False) if m]
print(f'\nFitted exponents (patch bits, per relief): bits ~ g^b, b median {sorted(m[2] for m in bs)[len(bs) // 2]:.2f} '
      f'[{min(m[2] for m in bs):.2f}, {max(m[2] for m in bs):.2f}]; msq ~ g^d, d median '
      f'{sorted(m[4] for m in bs)[len(bs) // 2]:.2f} [{min(m[4] for m in bs):.2f}, {max(m[4] for m in bs):.2f}]')
