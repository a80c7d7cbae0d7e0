#!/usr/bin/python3
"""The contact passes and the particle pass against the processor's ceilings (issue #41 item 1): for
each pass, the time per contact (per particle) that each ceiling allows, from bench/ceilings' measured
rates and bench/count_pass_ops.py's counts, beside the achieved time (bench_crystal --passes); the
binding ceiling and the fraction achieved. Prints a Markdown table and draws docs/figures/ceilings.png.

Usage: /usr/bin/python3 bench/ceilings_figure.py CEILINGS.json PASS_OPS.json BENCH_PASSES.txt [--out PNG]
  CEILINGS.json: build/ceilings --json; PASS_OPS.json: bench/count_pass_ops.py BUILD --ceilings CEILINGS.json
  --mca --json; BENCH_PASSES.txt: the output of build/bench_crystal --passes.
"""
import json
import re
import sys
from pathlib import Path

# Each pass, its bench_crystal row and its particle pass (count_pass_ops.py's names).
PASSES = [
    ("frictionless (Hooke)", "4x4x200, frictionless", "particle pass, 1 row (frictionless)"),
    ("friction, radius arm", "4x4x200, kt = k (friction)", "particle pass, 2 rows (radius arm, Hertz-Mindlin)"),
    ("friction, contact-point arm", "4x4x200, kt = k, contact-point arm", "particle pass, 3 rows (contact-point arm)"),
    ("Hertz-Mindlin", "4x4x200, Hertz-Mindlin", "particle pass, 2 rows (radius arm, Hertz-Mindlin)"),
    ("rolling and torsion", "4x4x200, rolling and torsion", "particle pass, 2 rows and couples (rolling)"),
]
CONTACTS_PER_PARTICLE = 18880 / 3200  # the bench crystal (bench_crystal prints both)

# Bytes a pass moves per contact, counted from crystal/kernel.hpp (ListColumns) and the rows: the contact
# list's i, j (8), images (2), the overlap written (8), the law's history columns read and written (16 each:
# Hooke 0, Luding's spring 3, Mindlin's 4 (spring, a), with rolling and torsion 8 (spring, flag, rolling,
# torsion)), the frictionless pass's forces written (24); per particle (divided by the contacts per
# particle): the particle data read (Hooke: x, y, z, v, a, 56; the gathered laws: 3 rows of 4, 96) and the
# contact sums' rows read and written (32 + 32 each: 1, 2, 3 rows, rolling 3). The vector sweep of an
# undamped frictional law leaves the losses alone (contact::LosslessSweep). STREAM's convention: no
# write-allocate read.
BYTES = {
    "frictionless (Hooke)": 10 + 8 + 0 + 24 + (56 + 64 * 1) / CONTACTS_PER_PARTICLE,
    "friction, radius arm": 10 + 8 + 3 * 16 + (96 + 64 * 2) / CONTACTS_PER_PARTICLE,
    "friction, contact-point arm": 10 + 8 + 3 * 16 + (96 + 64 * 3) / CONTACTS_PER_PARTICLE,
    "Hertz-Mindlin": 10 + 8 + 4 * 16 + (96 + 64 * 2) / CONTACTS_PER_PARTICLE,
    "rolling and torsion": 10 + 8 + 8 * 16 + (96 + 64 * 3) / CONTACTS_PER_PARTICLE,
}
# Loads at random particle indices per contact (the gathers' ceiling, at the measured random-load rate in
# L1): Hooke reads x, y, z, v, a of i and j one double at a time (14); the laws with torques load whole
# rows of four (x y z a | v | w of i and j: 6) and transpose them (crystal/kernel_gather.hpp).
RANDOM_LOADS = {"frictionless (Hooke)": 14}


def dispatch_width(cpu):
    """Macro-ops dispatched a cycle: Zen 3 and Zen 4 (AMD family 25) 6, Zen 5 (family 26) 8 (AMD's
    guides); Golden Cove (Sapphire Rapids) allocates 6 a cycle (Intel's optimisation manual). A probe
    file from before the family was recorded counts 6."""
    return 8 if cpu.get("vendor") == "AuthenticAMD" and cpu.get("family", 0) >= 26 else 6


CEILINGS = ["divider", "FP pipes", "L1 ports", "dispatch", "execution ports", "gathers", "memory (L2)", "memory (L3)",
            "memory (DRAM)", "chain"]
# Floors: the time the pass cannot go below while that resource alone limits it (the pass's arrays do
# not fit in L1, so they come at L2's rate at best). Not floors: L3 and DRAM (the bench crystal's few MB
# live in L2 and L3: what the pass would take if they came from there), and the chain (one iteration's
# critical path per contact: the time if successive iterations did not overlap; the out-of-order window
# overlaps them).
# Execution ports: each loop's instructions on the ports that can take them, the busiest port's load (llvm-mca's
# block reciprocal throughput, from its model of the core: at 512 bits an Intel core has two vector ports, 0
# and 5, and port 5 alone shuffles), so a floor of today's instructions, not of the law's arithmetic; 0 when
# count_pass_ops ran without --mca.
FLOORS = ["divider", "FP pipes", "L1 ports", "dispatch", "execution ports", "gathers", "memory (L2)"]


def achieved(text):
    """{bench row: (contact pass ns/contact, particle pass ns/particle)} from bench_crystal --passes: the
    phases of a run's steps (the fastest of many advances of 20 steps, phase by phase)."""
    out, last = {}, None
    for line in text.splitlines():
        m = re.match(r"^(4x4x200, .*?)\s{2,}(\d+)\s+([\d.]+)\s+([\d.]+)\s+([-\d.]+)\s+([\d.]+)\s*$", line)
        if m:
            last = m.group(1)
            out[last] = [float(m.group(6)), None]
            continue
        if line.startswith("4x4x"):  # another table's row (the crystal beyond the L3): not these passes
            last = None
        m = re.search(r"contact pass ([\d.]+) ns/contact, particle pass \(kick, drift, finish\) ([\d.]+) ns/particle",
                      line)
        if m and last:
            out[last] = [float(m.group(1)), float(m.group(2))]
    return out


def fp_time(p, key, op, tput):
    """ns of one kind of arithmetic per contact: its instructions by width at each width's rate (counts from
    count_pass_ops' add_sub_insns_<lanes>; older counts without them: the flops at 4 lanes)."""
    by_width = {int(k.rsplit("_", 1)[1]): v for k, v in p.items() if k.startswith(key + "_insns_")}
    if not by_width:
        return p[key] / 4 * tput(op, 4)
    return sum(v * tput(op, lanes) for lanes, v in by_width.items())


def bounds(ops, ceil, name, per):
    """ns per contact (particle) that each ceiling allows for a pass."""
    ns_cycle = 1.0 / ceil["core_ghz"]
    by_lanes = {r["lanes"]: r for r in ceil["arithmetic"]}
    # packed xmm (2 lanes) at the scalar rate (the probe times scalar, ymm and zmm); a width it has not, at ymm's
    tput = lambda op, lanes: by_lanes[1 if lanes == 2 else lanes if lanes in by_lanes else 4][op]["throughput_ns"]
    div = chain = ports = 0.0
    for L in ops["loops"]:
        n = L["per_iteration"]
        ports += ((L.get("mca") or {}).get("block_rthroughput") or 0.0) * ns_cycle / n
        for lanes, k in L["div_by_lanes"].items():
            div += k * tput("div", int(lanes)) / n
        for lanes, k in L["sqrt_by_lanes"].items():
            div += k * tput("sqrt", int(lanes)) / n
        chain += L["critical_path_cycles"] * ns_cycle / n
    p = ops["per_" + per]
    b = {
        "divider": div,  # one unit for both (ceilings' mix: div + sqrt interleaved cost their sum)
        # each add and multiply instruction at its width's measured rate (a zmm one is one instruction)
        "FP pipes": max(fp_time(p, "add_sub", "add", tput) + p["minmax"] / 4 * tput("add", 4),
                        fp_time(p, "mul", "mul", tput)),
        "L1 ports": max(p["loads"] * ceil["l1_ymm"]["load_ns"], p["stores"] * ceil["l1_ymm"]["store_ns"]),
        "dispatch": p["instructions"] / dispatch_width(ceil["cpu"]) * ns_cycle,
        "execution ports": ports,
        "chain": chain,
    }
    l1 = next(g for g in ceil["gathers"] if g["table"].startswith("L1"))
    # the probe's random scalar read is two loads (the index, the value): a load at a random index costs
    # half of it; the hardware gathers (vgatherdpd) cost more per double on this machine
    per_load = l1["scalar_ns_per_double"] / 2
    # the triad's real traffic: 32 bytes per element (b and c in, a out and its write-allocate read in),
    # where STREAM counts 24; the passes' bytes count every line in and out the same way
    tri = {(t["where"], t["threads"]): t["gb_per_s"] * 32 / 24 for t in ceil["triad"]}
    if per == "contact":
        b["gathers"] = (RANDOM_LOADS.get(name, 6) + 2) * per_load  # and i, j
        byt = BYTES[name]
    else:  # the particle pass streams its arrays: the loop's own array bytes
        byt = sum((L["counts"]["load_bytes"] + L["counts"]["store_bytes"]) / L["per_iteration"] for L in ops["loops"])
        b["gathers"] = 0.0
    b["memory (L2)"] = byt / tri[("L2", 1)]
    b["memory (L3)"] = byt / tri[("L3", 1)]
    b["memory (DRAM)"] = byt / tri[("memory", 1)]
    return b, byt


def main():
    args = sys.argv[1:]
    if len(args) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    def read(path, what):
        try:
            text = Path(path).read_text()
            return json.loads(text) if what != "text" else text
        except (OSError, ValueError) as e:
            print(f"ceilings_figure: {path}: cannot read it as {what} ({e})", file=sys.stderr)
            sys.exit(2)
    ceil = read(args[0], "JSON (build/ceilings --json)")
    ops = {p["pass"]: p for p in read(args[1], "JSON (bench/count_pass_ops.py --json)")["passes"]}
    got = achieved(read(args[2], "text"))
    out = Path(args[args.index("--out") + 1]) if "--out" in args else None
    rows = []
    for name, bench, particle in PASSES:
        if bench not in got:
            print(f"ceilings_figure: no row '{bench}' in {args[2]} (bench_crystal --passes output)", file=sys.stderr)
            sys.exit(2)
        for what, per, t in ((name, "contact", got[bench][0]), (particle, "particle", got[bench][1])):
            o = ops[what]
            b, byt = bounds(o, ceil, what, per)
            cyc = [(L["kind"], (L.get("mca") or {}).get("cycles_per_iteration") or 0.0, L["per_iteration"])
                   for L in o["loops"]]
            mca = sum(c / n for _, c, n in cyc) / ceil["core_ghz"]
            largest = max(cyc, key=lambda r: r[1] / r[2])
            share = (largest[1] / largest[2]) / max(1e-12, sum(c / n for _, c, n in cyc))
            note = next((L.get("mca") or {}).get("bottleneck", "") for L in o["loops"] if L["kind"] == largest[0])
            dep = re.search(r"Register Dependencies \[\s*([\d.]+)%", note)
            why = f", llvm-mca: register dependencies {float(dep.group(1)):.0f} % of its cycles" if dep else ""
            rows.append({"pass": what if per == "contact" else f"{what} [{name}]", "per": per, "achieved": t,
                         "bounds": b, "bytes": byt, "mca": mca, "largest": f"{largest[0]} loop ({share:.0%} by llvm-mca{why})",
                         "counts": o["per_" + per]})
    # the Markdown table
    print("| pass | per | achieved ns | " + " | ".join(CEILINGS) + " (no overlap) | binding (fraction) | llvm-mca ns | largest cost |")
    print("|---|---|---:|" + "---:|" * len(CEILINGS) + "---|---:|---|")
    seen_particle = set()
    for r in rows:
        if r["per"] == "particle":
            key = r["pass"].split(" [")[0]
            if key in seen_particle:
                continue
            seen_particle.add(key)
        cached = {k: r["bounds"][k] for k in FLOORS}
        bind = max(cached, key=cached.get)
        frac = cached[bind] / r["achieved"] if r["achieved"] and r["achieved"] > 0 else float("nan")
        print(f"| {r['pass']} | {r['per']} | {r['achieved']:.2f} | "
              + " | ".join(f"{r['bounds'][c]:.2f}" for c in CEILINGS)
              + f" | {bind} ({frac:.0%}) | {r['mca']:.2f} | {r['largest']} |")
    print("\nfraction: the binding floor's time / the achieved time; chain: the critical path of one iteration per "
          "contact (not a floor: the window overlaps iterations, chain / achieved of them on average)")
    print()
    print("| pass | per | instructions | div | sqrt | flops (add/sub, mul) | loads (stack) | stores (stack) | shuffles | bytes |")
    print("|---|---|---:|---:|---:|---|---|---|---:|---:|")
    for r in rows:
        c = r["counts"]
        print(f"| {r['pass']} | {r['per']} | {c['instructions']:.1f} | {c['div_lanes']:.2f} | {c['sqrt_lanes']:.2f} | "
              f"{c['flops']:.0f} ({c['add_sub']:.0f}, {c['mul']:.0f}) | {c['loads']:.1f} ({c['stack_loads']:.1f}) | "
              f"{c['stores']:.1f} ({c['stack_stores']:.1f}) | {c['shuffles']:.1f} | {r['bytes']:.0f} |")
    if out:
        draw(rows, out, ceil)


def draw(rows, out, ceil):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    groups = [("contact", "ns per contact"), ("particle", "ns per particle")]
    fig, axes = plt.subplots(1, 2, figsize=(13, 6.5), gridspec_kw={"width_ratios": [5, 4]})
    labels = ["achieved"] + CEILINGS
    colors = ["black", "tab:red", "tab:orange", "tab:olive", "tab:purple", "tab:blue", "tab:cyan", "tab:green",
              "tab:gray", "tab:brown", "tab:pink"]
    for ax, (per, unit) in zip(axes, groups):
        rs = [r for r in rows if r["per"] == per]
        if per == "particle":  # one bar group per distinct particle pass
            uniq = {}
            for r in rs:
                uniq.setdefault(r["pass"].split(" [")[0], r)
            rs = list(uniq.values())
        y = np.arange(len(rs))
        h = 0.85 / len(labels)
        for k, (lab, col) in enumerate(zip(labels, colors)):
            vals = [r["achieved"] if lab == "achieved" else r["bounds"][lab] for r in rs]
            floor = lab == "achieved" or lab in FLOORS  # hatched: not a floor (see FLOORS)
            ax.barh(y + (k - len(labels) / 2) * h, vals, height=h, color=col, hatch=None if floor else "///",
                    edgecolor="white" if not floor else None, label=lab if floor else f"{lab} (not a floor)")
        ax.set_yticks(y)
        ax.set_yticklabels([r["pass"].split(" [")[0].replace("particle pass, ", "") for r in rs])
        ax.invert_yaxis()
        ax.set_xlabel(unit)
        ax.set_title(f"{per} pass (one thread)")
        ax.grid(axis="x", alpha=0.3)
    handles, labs = axes[0].get_legend_handles_labels()
    fig.legend(handles, labs, loc="lower center", ncol=5, fontsize=8)
    fig.suptitle(f"granwave's passes against the ceilings of {ceil['cpu']['model']} "
                 f"({ceil['core_ghz']:.2f} GHz, {ceil['build']}): a bar is the time a ceiling alone allows")
    fig.tight_layout(rect=(0, 0.08, 1, 0.95))
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    main()
