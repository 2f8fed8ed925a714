#!/usr/bin/env python3
# Issue 21, h21fast9 (bench/README.md, "Twelfth round"): can effort 0's first grid be predicted from the input surface?
# For each mesh: `prm pack MESH --target-error E --effort 0 --mode prm --json` gives the grid the pack needs (its search
# round nearest the target, scaled by the RMS ~ g^2 model: g x sqrt(E / rms)), and prm_bench_first_grid the input's
# statistics. Each predictor's constant is fitted on the four paper models (least squares in log) and checked on the
# others: the table gives predicted / needed grid per mesh (> 1: the first grid misses the target and the pack remeshes
# again; < 1: finer than needed, more vertices), and the spread (RMS of the log ratio) on each set. Then the
# two-statistic model fitted on all meshes, leave-one-out.
# Usage (from the checkout's root): bench/first_grid_study.py OUTDIR [PRM [FIRST_GRID_TOOL]]
# Exit code 1 on a bad command line, 3 when a pack or the tool fails.
import json, math, os, subprocess, sys

if len(sys.argv) < 2 or len(sys.argv) > 4:
    sys.stderr.write(open(__file__).read().split('\nimport')[0] + '\n')
    sys.exit(1)
out = sys.argv[1]
prm = sys.argv[2] if len(sys.argv) > 2 else 'build/tools/prm/prm'
tool = sys.argv[3] if len(sys.argv) > 3 else 'build/bench/prm_bench_first_grid'
S, C = '../shared/meshes', '/usr/share/doc/libcgal-demo/examples/data/meshes'
C = os.environ.get('CGAL_MESHES', C)  # the folder of CGAL's data/meshes (libcgal-demo's examples.tar.gz)
PAPER = [('horse', S + '/horse.ply', 2e-4), ('venus', S + '/venus.off', 1.3e-4), ('feline', S + '/feline.off', 2.6e-4),
         ('bunny_zipper', S + '/bunny_zipper.ply', 2e-4)]
OTHERS = [(n, S + '/' + f, 2e-4) for n, f in [('spot', 'spot.obj'), ('feline_5k', 'feline_5k.obj'), ('igea', 'igea.ply'),
                                              ('rocker', 'rocker-arm.off')]]
OTHERS += [(n, C + '/' + n + '.off', 2e-4) for n in ['armadillo', 'camel', 'bunny00', 'elephant', 'man', 'dino', 'bull', 'cow']]
os.makedirs(out, exist_ok=True)
rows = []
for name, mesh, e in PAPER + OTHERS:
    js = os.path.join(out, name + '.json')
    if not os.path.exists(js):  # a rerun reuses the packs
        r = subprocess.run(['nice', '-n', '10', prm, 'pack', mesh, '--target-error', repr(e), '--effort', '0', '--mode',
                            'prm', '-o', os.path.join(out, name + '.prm'), '--json'], capture_output=True, text=True)
        if r.returncode != 0:
            sys.stderr.write(f'{name}: pack failed ({r.returncode}): {r.stderr}\n')
            sys.exit(3)
        open(js, 'w').write(r.stdout)
    d = json.load(open(js))
    t = subprocess.run([tool, mesh, repr(e)], capture_output=True, text=True)
    if t.returncode != 0:
        sys.stderr.write(f'{name}: {tool} failed ({t.returncode}): {t.stderr}\n')
        sys.exit(3)
    st = json.loads(t.stdout)
    unit = e * st['diagonal']
    best = min(d['search'], key=lambda s: abs(math.log(s['rms'] / e)))
    need = best['grid_steps'] * d['step'] * math.sqrt(e / best['rms']) / unit
    first = d['search'][0]
    rows.append(dict(name=name, paper=name in dict((p[0], 1) for p in PAPER), need=need,
                     first=first['grid_steps'] * d['step'] / unit, first_rms=first['rms'] / e, rounds=len(d['search']),
                     kr=st['kappa_rms'], ka=st['kappa_abs'], h=st['edge_mean'], gm=st['model_grid']))


def solve(X, y):  # least squares by the normal equations
    m = len(X[0])
    A = [[sum(x[i] * x[j] for x in X) for j in range(m)] + [sum(x[i] * t for x, t in zip(X, y))] for i in range(m)]
    for i in range(m):
        for j in range(i + 1, m):
            f = A[j][i] / A[i][i]
            A[j] = [a - f * c for a, c in zip(A[j], A[i])]
    x = [0.0] * m
    for i in reversed(range(m)):
        x[i] = (A[i][m] - sum(A[i][j] * x[j] for j in range(i + 1, m))) / A[i][i]
    return x


def spread(v):
    return math.sqrt(sum(math.log(t) ** 2 for t in v) / len(v)) if v else 0.0


# Predictors: log g = c + log f(mesh); c fitted on the paper models.
PRED = [('constant', lambda r: 1.0), ('kappa_rms^-1/2', lambda r: r['kr'] ** -0.5),
        ('kappa_abs^-1/2', lambda r: r['ka'] ** -0.5), ('model_grid', lambda r: r['gm'])]
print('%-13s %5s %6s %7s %6s %8s %8s %8s %6s' % ('mesh', 'rnds', 'first', 'rms1/E', 'need', 'kap_rms', 'kap_abs',
                                                'edge/Ed', 'model'))
for r in rows:
    print('%-13s %5d %6.1f %7.3f %6.1f %8.1f %8.1f %8.1f %6.2f' % (r['name'], r['rounds'], r['first'], r['first_rms'],
                                                                  r['need'], r['kr'], r['ka'], r['h'], r['gm']))
print('\npredicted / needed grid, each constant fitted on the paper models (first four)')
for label, f in PRED:
    c = sum(math.log(r['need'] / f(r)) for r in rows if r['paper']) / sum(r['paper'] for r in rows)
    ratio = [math.exp(c) * f(r) / r['need'] for r in rows]
    p = [v for v, r in zip(ratio, rows) if r['paper']]
    o = [v for v, r in zip(ratio, rows) if not r['paper']]
    print('%-15s const %7.3g  paper spread %.3f  others spread %.3f  others %.2f..%.2f' %
          (label, math.exp(c), spread(p), spread(o), min(o), max(o)))
    print('   ' + ' '.join('%s %.2f' % (r['name'], v) for r, v in zip(rows, ratio)))
# Two statistics: log g = a + b log model_grid + c log edge_mean.
feat = lambda r: [1.0, math.log(r['gm']), math.log(r['h'])]
for label, train in [('fitted on the paper models', [r for r in rows if r['paper']]), ('fitted on all', rows)]:
    c = solve([feat(r) for r in train], [math.log(r['need']) for r in train])
    ratio = [math.exp(sum(a * b for a, b in zip(c, feat(r)))) / r['need'] for r in rows]
    o = [v for v, r in zip(ratio, rows) if not r['paper']]
    print('\nmodel_grid + edge_mean, %s: coefficients %s; others spread %.3f' %
          (label, ' '.join('%.3f' % x for x in c), spread(o)))
    print('   ' + ' '.join('%s %.2f' % (r['name'], v) for r, v in zip(rows, ratio)))
loo = []
for i, r in enumerate(rows):
    train = rows[:i] + rows[i + 1:]
    c = solve([feat(t) for t in train], [math.log(t['need']) for t in train])
    loo.append(math.exp(sum(a * b for a, b in zip(c, feat(r)))) / r['need'])
print('\nmodel_grid + edge_mean, leave-one-out over all: spread %.3f, %.2f..%.2f' % (spread(loo), min(loo), max(loo)))
print('   ' + ' '.join('%s %.2f' % (r['name'], v) for r, v in zip(rows, loo)))
