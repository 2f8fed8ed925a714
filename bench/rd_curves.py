#!/usr/bin/env python3
"""Rate-distortion curves (issue 23 item 3; bench/README.md, "Rate-distortion curves").

Per mesh, RMS and max error against stream bytes for:
  * PRM curves, one per --curve "LABEL:PRM_BINARY:EXTRA PACK ARGS" (default "PRM uniform:build/tools/prm/prm:"):
    `prm pack MESH --target-error E EXTRA -o s.prm --json` for every E of --errors; bytes and errors from --json,
    checked against an independent `prm compare MESH s.prm` of the decoded stream;
  * simplify + Draco at each PRM stream's bytes B (every PRM curve's points, so that points line up at equal bytes):
    for each -qp of --sd-qp (cl 10), the largest triangle count whose Draco stream is at most B (meshopt_simplify
    through prm_bench_simplify, searched by interpolation/bisection on the count), then the -qp with the lowest RMS;
  * Draco alone: draco_encoder -qp Q -cl 10 of the whole mesh, Q in --draco-qp;
  * gltfpack -si R -cc (default -vp 14) at each budget B like simplify + Draco (R searched so that the .glb is at most
    B bytes), when --gltfpack names an existing program.
Every error is `prm compare ORIGINAL DECODED --json` (symmetric Metro RMS and max, fractions of the original's
bounding-box diagonal), the decoded mesh being the PRM stream itself, draco_decoder's PLY or `prm unpack`'s glTF.

Results are cached per mesh in OUT/<mesh>/ (results.json; the PRM streams as <curve>/<E>.prm with pack's JSON, CPU
time and exit code), so a re-run with one more --curve only packs that curve and the new budgets. --report writes
OUT/rd_table.md (per PRM point: the issue-23 comparison) and, with --plot DIR, one PNG per mesh (gnuplot, log bytes
against RMS and against max).

Usage (from the repository root, after building prm and prm_bench_simplify, and `npm ci` in bench/gltf):
  nice -n 10 python3 bench/rd_curves.py MESH... [--curve "PRM uniform:build/tools/prm/prm:"] [--curve ...]
      [--errors 2e-5,5e-5,1e-4,2e-4,5e-4,1e-3] [--out build/rd] [--report] [--plot bench/rd]
Exit codes: 0 done (points that failed are named in the table and on stderr), 2 usage (argparse's), 3 a needed
program missing, 1 a tool failed unexpectedly (the traceback names the command).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def slug(label):
    return re.sub(r"[^a-z0-9]+", "_", label.lower()).strip("_")


def stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


class Ctx:
    def __init__(self, a):
        self.a = a
        self.prm = a.prm
        self.tmp = tempfile.mkdtemp(prefix="rd_")

    def compare(self, original, decoded, prm=None):
        """prm compare ORIGINAL DECODED: (rms_rel, max_rel) of the symmetric distance (a .prm stream is compared
        by the prm that wrote it, which reads its format version)."""
        r = run([prm or self.prm, "compare", "--json", original, decoded])
        if r.returncode != 0:
            raise RuntimeError(f"prm compare {original} {decoded}: {r.stderr.strip()[-300:]}")
        s = json.loads(r.stdout)["symmetric"]
        return s["rms_rel"], s["max_rel"]


def parse_curve(spec):
    parts = spec.split(":", 2)
    if len(parts) < 2 or not parts[0] or not parts[1]:
        raise argparse.ArgumentTypeError(f"curve '{spec}' is not LABEL:PRM_BINARY[:EXTRA PACK ARGS]")
    return {"label": parts[0], "prm": parts[1], "extra": parts[2].split() if len(parts) > 2 else []}


# ---------------------------------------------------------------------------------------------------------- PRM ---
def prm_point(ctx, mesh, mdir, curve, e):
    d = os.path.join(mdir, slug(curve["label"]))
    os.makedirs(d, exist_ok=True)
    base = os.path.join(d, e)
    if not os.path.exists(base + ".rc"):
        cmd = ["/usr/bin/time", "-f", "%U %S %M %e", "-o", base + ".time", "timeout", str(ctx.a.pack_timeout),
               curve["prm"], "pack", mesh, "--target-error", e] + curve["extra"] + ["-o", base + ".prm", "--json"]
        with open(base + ".json", "w") as out, open(base + ".err", "w") as err:
            rc = subprocess.run(cmd, stdout=out, stderr=err).returncode
        with open(base + ".rc", "w") as f:
            f.write(f"{rc}\n")
    rc = int(open(base + ".rc").read().split()[0])
    point = {"target": float(e), "rc": rc}
    try:
        t = open(base + ".time").read().split()[-4:]
        point["cpu_s"] = float(t[0]) + float(t[1])
        point["max_rss_kb"] = int(t[2])
    except (OSError, ValueError, IndexError):
        pass
    if rc != 0:
        why = "timeout after %ss" % ctx.a.pack_timeout if rc == 124 else open(base + ".err").read().strip()[-200:]
        point["failed"] = f"exit {rc}: {why}"
        return point
    j = json.load(open(base + ".json"))
    point["bytes"] = j["bytes"]["total"]
    point["rms"], point["max"] = j["distance"]["rms_rel"], j["distance"]["max_rel"]
    # independent check: prm compare of the decoded stream against the original
    point["check_rms"], point["check_max"] = ctx.compare(mesh, base + ".prm", curve["prm"])
    point["stream_bytes"] = os.path.getsize(base + ".prm")
    point["mode"] = j.get("mode")
    return point


# -------------------------------------------------------------------------------------------------------- Draco ---
def draco_encode(ctx, ply, qp, out):
    r = run(["draco_encoder", "-i", ply, "-o", out, "-qp", str(qp), "-cl", "10"])
    if r.returncode != 0:
        raise RuntimeError(f"draco_encoder {ply}: {r.stderr.strip()[-300:]}")
    return os.path.getsize(out)


def draco_error(ctx, mesh, drc):
    dec = drc + ".ply"
    r = run(["draco_decoder", "-i", drc, "-o", dec])
    if r.returncode != 0:
        raise RuntimeError(f"draco_decoder {drc}: {r.stderr.strip()[-300:]}")
    return ctx.compare(mesh, dec)


def search_count(size_of, full, budget, max_evals=12):
    """The largest triangle count T in [16, full] with size_of(T) <= budget (sizes grow with T, roughly linearly),
    by interpolation then bisection. Returns (T, size) or None when even 16 triangles exceed the budget."""
    lo, hi = None, None  # (T, size) with size <= budget / size > budget
    s_full = size_of(full)
    if s_full <= budget:
        return full, s_full
    hi = (full, s_full)
    t = max(16, min(full - 1, int(full * budget / s_full)))
    for _ in range(max_evals):
        s = size_of(t)
        if s <= budget:
            lo = (t, s)
        else:
            hi = (t, s)
        if lo is None:
            if t == 16:
                return None
            t = max(16, int(t * budget / s * 0.97))
            continue
        if hi[0] - lo[0] <= max(1, lo[0] // 200):  # within 0.5% of the count
            break
        # interpolate in the bracket, kept off its ends so that the bracket shrinks
        frac = (budget - lo[1]) / max(1, hi[1] - lo[1])
        t = lo[0] + int((hi[0] - lo[0]) * min(0.9, max(0.1, frac)))
        t = min(hi[0] - 1, max(lo[0] + 1, t))
    return lo


class Simplified:
    """meshopt_simplify results by triangle count, shared across -qp and methods for one mesh."""

    def __init__(self, ctx, mesh, ext):
        self.ctx, self.mesh, self.ext, self.files, self.sloppy = ctx, mesh, ext, {}, set()

    def get(self, t):
        if t not in self.files:
            path = os.path.join(self.ctx.tmp, f"{stem(self.mesh)}_{t}{self.ext}")
            r = run([self.ctx.a.simplify, self.mesh, str(t), path])
            if r.returncode != 0:
                raise RuntimeError(f"prm_bench_simplify {self.mesh} {t}: {r.stderr.strip()}")
            if "sloppy=1" in r.stdout:
                self.sloppy.add(t)
            self.files[t] = path
        return self.files[t]


def sd_point(ctx, mesh, full, simp, budget):
    """simplify + Draco at most `budget` bytes: every -qp searched, the lowest RMS kept."""
    per_qp = []
    for qp in ctx.a.sd_qp:
        cache = {}

        def size_of(t):
            if t not in cache:
                cache[t] = draco_encode(ctx, simp.get(t), qp, os.path.join(ctx.tmp, f"sd_{qp}_{t}.drc"))
            return cache[t]

        found = search_count(size_of, full, budget)
        if found is None:
            per_qp.append({"qp": qp, "failed": "16 triangles exceed the budget"})
            continue
        t, size = found
        rms, mx = draco_error(ctx, mesh, os.path.join(ctx.tmp, f"sd_{qp}_{t}.drc"))
        per_qp.append({"qp": qp, "triangles": t, "bytes": size, "rms": rms, "max": mx, "encodes": len(cache),
                       "sloppy": t in simp.sloppy})
    ok = [p for p in per_qp if "rms" in p]
    best = min(ok, key=lambda p: p["rms"]) if ok else {"failed": "no -qp fits"}
    return dict(best, budget=budget, per_qp=per_qp)


def gltfpack_point(ctx, mesh, full, obj, budget):
    cache = {}

    def size_of(t):
        if t not in cache:
            out = os.path.join(ctx.tmp, f"g_{t}.glb")
            ratio = "%.6f" % (t / full)
            r = run([ctx.a.gltfpack, "-i", obj, "-o", out, "-si", ratio, "-cc"])
            if r.returncode != 0:
                raise RuntimeError(f"gltfpack -si {ratio}: {r.stderr.strip()[-300:]}")
            cache[t] = os.path.getsize(out)
        return cache[t]

    found = search_count(size_of, full, budget, max_evals=10)
    if found is None:
        return {"budget": budget, "failed": "the smallest -si exceeds the budget"}
    t, size = found
    glb = os.path.join(ctx.tmp, f"g_{t}.glb")
    plain = glb + ".plain.glb"
    r = run([ctx.prm, "unpack", glb, "-o", plain])
    if r.returncode != 0:
        raise RuntimeError(f"prm unpack {glb}: {r.stderr.strip()[-300:]}")
    rms, mx = ctx.compare(mesh, plain)
    return {"budget": budget, "si": t / full, "bytes": size, "rms": rms, "max": mx, "encodes": len(cache)}


# --------------------------------------------------------------------------------------------------------- mesh ---
def do_mesh(ctx, mesh):
    a = ctx.a
    mdir = os.path.join(a.out, stem(mesh))
    os.makedirs(mdir, exist_ok=True)
    rpath = os.path.join(mdir, "results.json")
    res = json.load(open(rpath)) if os.path.exists(rpath) else {}
    res["mesh"] = mesh

    def save():
        with open(rpath + ".tmp", "w") as f:
            json.dump(res, f, indent=1)
        os.replace(rpath + ".tmp", rpath)

    plain = os.path.join(ctx.tmp, stem(mesh) + "_full.ply")
    r = run([a.simplify, mesh, "1000000000", plain])  # a plain PLY of the input for Draco and gltfpack
    if r.returncode != 0:
        raise RuntimeError(f"prm_bench_simplify {mesh}: {r.stderr.strip()}")
    full = int(re.search(r"output_triangles=(\d+)", r.stdout).group(1))
    res["triangles"] = full

    curves = res.setdefault("prm", {})
    for c in a.curve:
        pts = curves.setdefault(c["label"], {})
        for e in a.errors:
            if e in pts and "rc" in pts[e]:
                continue
            print(f"[rd] {stem(mesh)}: {c['label']} at {e}", file=sys.stderr, flush=True)
            pts[e] = prm_point(ctx, mesh, mdir, c, e)
            if "failed" in pts[e]:
                print(f"[rd] {stem(mesh)}: {c['label']} at {e} failed: {pts[e]['failed']}", file=sys.stderr)
            save()
    budgets = sorted({p["bytes"] for pts in curves.values() for p in pts.values() if "bytes" in p})

    if not a.no_draco:
        dra = res.setdefault("draco", {})
        for qp in a.draco_qp:
            if str(qp) in dra:
                continue
            drc = os.path.join(ctx.tmp, f"full_{qp}.drc")
            size = draco_encode(ctx, plain, qp, drc)
            rms, mx = draco_error(ctx, mesh, drc)
            dra[str(qp)] = {"qp": qp, "bytes": size, "rms": rms, "max": mx}
            save()

    def per_budget(key, what, point_at):  # one point of a baseline at each PRM stream's bytes, cached
        done = res.setdefault(key, {})
        for b in budgets:
            if str(b) not in done:
                print(f"[rd] {stem(mesh)}: {what} at {b} B", file=sys.stderr, flush=True)
                done[str(b)] = point_at(b)
                save()

    if not a.no_sd:
        simp = Simplified(ctx, mesh, ".ply")
        per_budget("sd", "simplify + Draco", lambda b: sd_point(ctx, mesh, full, simp, b))
    if a.gltfpack and os.path.exists(a.gltfpack):
        obj = os.path.join(ctx.tmp, stem(mesh) + "_full.obj")
        run([a.simplify, mesh, "1000000000", obj])
        per_budget("gltfpack", "gltfpack", lambda b: gltfpack_point(ctx, mesh, full, obj, b))
    elif a.gltfpack:
        print(f"[rd] gltfpack {a.gltfpack} not found: no gltfpack points (npm ci in bench/gltf)", file=sys.stderr)
    save()
    return res


# ------------------------------------------------------------------------------------------------------- report ---
def fmt(x):
    return "%.2e" % x


def pack_mode(a, mesh, label, e):
    """pack's mode of a cached point ("prm", or "general" where no piecewise regular mesh was made)."""
    try:
        return json.load(open(os.path.join(a.out, stem(mesh), slug(label), e + ".json"))).get("mode")
    except (OSError, ValueError):
        return None


def report(a, results):
    lines = ["| mesh | PRM curve | E | bytes | PRM RMS | PRM max | S+D -qp / tris | S+D bytes | S+D RMS | S+D max "
             "| RMS ratio (<= 0.70) | max no worse | gltfpack RMS / max | Draco alone at PRM's RMS |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    missing = []
    for res in results:
        name = stem(res["mesh"])
        dra = sorted(res.get("draco", {}).values(), key=lambda p: p["qp"])
        for label, pts in res.get("prm", {}).items():
            for e, p in sorted(pts.items(), key=lambda kv: float(kv[0])):
                if "bytes" not in p:
                    missing.append(f"{name} {label} E={e}: {p.get('failed')}")
                    continue
                sd = res.get("sd", {}).get(str(p["bytes"]), {})
                gp = res.get("gltfpack", {}).get(str(p["bytes"]), {})
                mode = p.get("mode") or pack_mode(a, res["mesh"], label, e)
                row = [name, label, e + ("" if mode in ("prm", None) else f" ({mode})"), str(p["bytes"]),
                       fmt(p["rms"]), fmt(p["max"])]
                if "rms" in sd:
                    row += [f"{sd['qp']} / {sd['triangles']}" + (" sloppy" if sd.get("sloppy") else ""),
                            str(sd["bytes"]), fmt(sd["rms"]), fmt(sd["max"]), "%.2f" % (p["rms"] / sd["rms"]),
                            "yes" if p["max"] <= sd["max"] else "no (%.2fx)" % (p["max"] / sd["max"])]
                else:
                    row += [sd.get("failed", "not run"), "", "", "", "", ""]
                row.append(f"{fmt(gp['rms'])} / {fmt(gp['max'])} ({gp['bytes']} B)" if "rms" in gp
                           else gp.get("failed", "not run"))
                fit = sorted((d for d in dra if d["rms"] <= p["rms"]), key=lambda d: d["bytes"])  # the smallest
                row.append(f"-qp {fit[0]['qp']}: {fit[0]['bytes']} B ({fit[0]['bytes'] / p['bytes']:.1f}x)" if fit
                           else "none of -qp %s" % ",".join(str(d["qp"]) for d in dra))
                lines.append("| " + " | ".join(row) + " |")
    lines += ["", "Issue 23's first target per mesh and PRM curve, over the points with 5e-5 <= E <= 5e-4 (RMS ratio at most "
              "0.70 at every point; max no worse than simplify + Draco's at every point):", ""]
    for res in results:
        name = stem(res["mesh"])
        for label, pts in res.get("prm", {}).items():
            ratios, max_ok, n = [], 0, 0
            for e, p in pts.items():
                sd = res.get("sd", {}).get(str(p.get("bytes")), {})
                if not 5e-5 <= float(e) <= 5e-4 or "rms" not in sd or "bytes" not in p:
                    continue
                n += 1
                ratios.append(p["rms"] / sd["rms"])
                max_ok += p["max"] <= sd["max"]
            if n:
                lines.append(f"- {name}, {label}: RMS ratio {min(ratios):.2f}..{max(ratios):.2f} over {n} points "
                             f"({'met' if max(ratios) <= 0.70 else 'missed'}); max no worse at {max_ok} of {n} "
                             f"({'met' if max_ok == n else 'missed'})")
    lines.append("")
    lines.append("Draco alone (-cl 10) on each whole mesh:")
    lines.append("")
    lines.append("| mesh | " + " | ".join(f"-qp {q}" for q in a.draco_qp) + " |")
    lines.append("|---|" + "---:|" * len(a.draco_qp))
    for res in results:
        d = res.get("draco", {})
        lines.append(f"| {stem(res['mesh'])} | " + " | ".join(
            f"{d[str(q)]['bytes']} B, {fmt(d[str(q)]['rms'])} / {fmt(d[str(q)]['max'])}" if str(q) in d else ""
            for q in a.draco_qp) + " |")
    if missing:
        lines += ["", "PRM points that do not exist:", ""] + [f"- {m}" for m in missing]
    return "\n".join(lines) + "\n"


def plot(a, res, pdir):
    name = stem(res["mesh"])
    dat = os.path.join(a.out, stem(res["mesh"]), "plot")
    os.makedirs(dat, exist_ok=True)
    series = []  # (title, file)

    def write(title, pts):
        pts = sorted(p for p in pts if p)
        if not pts:
            return
        f = os.path.join(dat, slug(title) + ".dat")
        with open(f, "w") as out:
            for b, r, m in pts:
                out.write(f"{b} {r} {m}\n")
        series.append((title, f))

    for label, pts in res.get("prm", {}).items():
        write(label, [(p["bytes"], p["rms"], p["max"]) for p in pts.values() if "bytes" in p])
    write("simplify + Draco (best -qp 9-14)", [(p["bytes"], p["rms"], p["max"]) for p in res.get("sd", {}).values()
                                               if "rms" in p])
    write("Draco alone (-qp 8-14)", [(p["bytes"], p["rms"], p["max"]) for p in res.get("draco", {}).values()])
    write("gltfpack -si R -cc", [(p["bytes"], p["rms"], p["max"]) for p in res.get("gltfpack", {}).values()
                                 if "rms" in p])
    png = os.path.join(pdir, name + ".png")
    gp = [f"set terminal pngcairo size 1200,480 font ',10'", f"set output '{png}'", "set multiplot layout 1,2",
          "set logscale xy", "set grid", "set key top right", "set xlabel 'stream bytes'", "set format y '%.0e'"]
    for col, what in ((2, "RMS"), (3, "max")):
        gp.append(f"set title '{name}: {what} error (fraction of the diagonal) against bytes'")
        gp.append(f"set ylabel '{what} / diagonal'")
        gp.append("plot " + ", ".join(f"'{f}' using 1:{col} with linespoints title '{t}'" for t, f in series))
    gp.append("unset multiplot")
    r = subprocess.run(["gnuplot"], input="\n".join(gp) + "\n", text=True, stderr=subprocess.PIPE)
    if r.returncode != 0:
        print(f"[rd] gnuplot {png}: {r.stderr.strip()}", file=sys.stderr)
    return png


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("meshes", nargs="*", help="input meshes (the ORIGINAL every error is measured against)")
    p.add_argument("--curve", action="append", type=parse_curve,
                   help='PRM curve "LABEL:PRM_BINARY:EXTRA PACK ARGS" (repeatable; default "PRM uniform:'
                        'build/tools/prm/prm:")')
    p.add_argument("--errors", default="2e-5,5e-5,1e-4,2e-4,5e-4,1e-3", help="pack --target-error values")
    p.add_argument("--prm", default="build/tools/prm/prm", help="the prm that compares and unpacks")
    p.add_argument("--simplify", default="build/bench/prm_bench_simplify")
    p.add_argument("--gltfpack", default="bench/gltf/node_modules/.bin/gltfpack", help="'' for no gltfpack curve")
    p.add_argument("--sd-qp", default="9,10,11,12,13,14", help="Draco -qp tried by simplify + Draco")
    p.add_argument("--draco-qp", default="8,9,10,11,12,13,14", help="Draco alone -qp")
    p.add_argument("--pack-timeout", type=int, default=900, help="wall seconds a pack may take")
    p.add_argument("--out", default="build/rd", help="cache and results directory")
    p.add_argument("--no-sd", action="store_true")
    p.add_argument("--no-draco", action="store_true")
    p.add_argument("--report", action="store_true", help="write OUT/rd_table.md from every mesh given")
    p.add_argument("--report-only", action="store_true",
                   help="run nothing: the table and plots from the cached OUT/<mesh>/results.json")
    p.add_argument("--plot", metavar="DIR", help="one PNG per mesh into DIR")
    a = p.parse_args()
    if not a.meshes:
        p.error("no mesh given")
    a.curve = a.curve or [parse_curve("PRM uniform:build/tools/prm/prm:")]
    a.errors = [e.strip() for e in a.errors.split(",") if e.strip()]
    a.sd_qp = [int(q) for q in a.sd_qp.split(",")]
    a.draco_qp = [int(q) for q in a.draco_qp.split(",")]
    for prog in [a.prm, a.simplify] + [c["prm"] for c in a.curve]:
        if not os.path.exists(prog):
            print(f"rd_curves: {prog} not found (build it first)", file=sys.stderr)
            return 3
    for prog in ("draco_encoder", "draco_decoder") + (("gnuplot",) if a.plot else ()):
        if not shutil.which(prog):
            print(f"rd_curves: {prog} not found (apt-get install draco gnuplot-nox)", file=sys.stderr)
            return 3
    ctx = Ctx(a)
    results = []
    try:
        for m in a.meshes:
            if a.report_only:
                rpath = os.path.join(a.out, stem(m), "results.json")
                if not os.path.exists(rpath):
                    print(f"[rd] {m}: no {rpath}, left out", file=sys.stderr)
                    continue
                results.append(json.load(open(rpath)))
            else:
                results.append(do_mesh(ctx, m))
            if a.plot:
                os.makedirs(a.plot, exist_ok=True)
                print(f"[rd] {plot(a, results[-1], a.plot)}", file=sys.stderr)
    finally:
        shutil.rmtree(ctx.tmp, ignore_errors=True)
    if a.report or a.report_only:
        table = report(a, results)
        with open(os.path.join(a.out, "rd_table.md"), "w") as f:
            f.write(table)
        sys.stdout.write(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
