"""The report: the Markdown tables (times and ratios, physics check, memory) and the JSON document."""
from __future__ import annotations

import json
import os
import platform
import statistics
import time

from .cases import CODE_TITLES
from .stats import summarize


def _s(x, fmt="%.2f"):
    return "-" if x is None else fmt % x


def _x(x):
    return "-" if x is None else "%.2fx" % x


def table(results: list, runners: list, codes: list) -> str:
    gw = [r for r in runners if r.code == "granwave"]
    others = [c for c in ("lammps", "liggghts")]
    head = ["case", "particles x steps", "granwave build", "granwave wall / CPU (s)"]
    for c in others:
        head += ["%s wall / CPU (s)" % CODE_TITLES[c], "%s / granwave wall (CPU)" % CODE_TITLES[c]]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        sm = summarize(res, runners)
        t = sm["times"]
        for g in gw:
            row = [res["case"], "%d x %d" % (res["particles"], res["steps"]), g.title,
                   "%s / %s" % (_s(t[g.key]["wall"]), _s(t[g.key]["cpu"]))]
            for c in others:
                if c not in codes:
                    row += ["not run (--codes)", "-"]
                    continue
                if c not in t:
                    row += ["not run (other physics)", "-"]
                    continue
                rt = sm["ratios"]["%s/%s" % (c, g.key)]
                row += ["%s / %s" % (_s(t[c]["wall"]), _s(t[c]["cpu"])), "%s (%s)" % (_x(rt["wall"]), _x(rt["cpu"]))]
            lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def sanity_table(results: list, runners: list) -> str:
    head = ["case"] + ["%s V_half (m/s)" % r.title for r in runners] + \
           ["%s max d(sigma_zz or v_x) / peak" % r.title for r in runners if r.code != "granwave"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        row = [res["case"]]
        for r in runners:
            s = res["sanity"].get(r.key, {})
            if r.key not in res["runs"]:
                row.append("not run")
            elif s.get("v_half") is not None:
                rng = s.get("z_over_l0") or ["?", "?"]
                row.append("%.3f (%sz/l0 %s..%s)" % (s["v_half"], ("%s, " % s["field"]) if s.get("field") else "",
                                                      rng[0], rng[1]))
            else:
                row.append("error: %s" % s.get("error", "?")[:60])
        for r in runners:
            if r.code != "granwave":
                sr = res["sanity"].get(r.key, {})
                if "vz_dev" in sr:   # a packing: v_z, and sigma_zz's change from t = 0 (layers.packing_deviations)
                    row.append("v_z %s; sigma_zz change %s" % (_s(sr.get("vz_dev"), "%.1e"), _s(sr.get("stress_dev"), "%.1e")))
                    continue
                row.append(_s(sr.get("stress_dev"), "%.1e") + (" (printed digits allow %.1e)" % sr["stress_resolution"]
                                                               if sr.get("stress_resolution") is not None else ""))
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def contacts_table(results: list, runners: list) -> str:
    """The packing cases' list builds (the timed runs') and contact counts (the count run's snapshots)."""
    head = ["case", "code", "list builds in the timed runs", "contacts at start / end", "opened / closed between snapshots",
            "opened / closed start to end", "snapshots"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        if "contacts" not in res:
            continue
        for r in runners:
            if r.key not in res["runs"]:
                continue
            key = "contact_list_builds" if r.code == "granwave" else "neighbor_builds"
            builds = sorted(set(str(x.get(key)) for x in res["runs"][r.key]))
            note = " (construction's included)" if r.code == "granwave" else " (after set-up)"
            c = res["contacts"].get(r.key, {})
            if "error" in c:
                lines.append("| %s | %s | %s | error: %s | | | |" % (res["case"], r.title, ", ".join(builds) + note, c["error"][:80]))
                continue
            lines.append("| %s | %s | %s | %s / %s | %s / %s | %s / %s | %s |" % (
                res["case"], r.title, ", ".join(builds) + note, c.get("contacts_start"), c.get("contacts_end"),
                c.get("opened"), c.get("closed"), c.get("opened_net"), c.get("closed_net"), c.get("snapshots")))
    return "\n".join(lines)


def memory_table(results: list, runners: list) -> str:
    head = ["case"] + ["%s peak RSS (MB; kB/particle)" % r.title for r in runners]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        row = [res["case"]]
        for r in runners:
            if r.key not in res["runs"]:
                row.append("not run")
                continue
            kb = max(x["maxrss_kb"] for x in res["runs"][r.key])
            row.append("%.0f; %.2f" % (kb / 1024.0, kb * 1.024 / res["particles"]))
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def write_report(a, argv: list, cpu: dict, load0: dict, load1: dict, t_start: float, gw_facts: dict, versions: dict,
                 notes: list, results: list, runners: list, codes: list) -> None:
    """Print the Markdown report; write it to --out and every run and fact to --json (NAME.tmp, renamed)."""
    md = []
    md.append("side_by_side: %s" % " ".join(["bench/side_by_side.py"] + argv))
    md.append("")
    md.append("- CPU: %s, %d logical CPUs; SIMD flags: %s (AVX2 %s, AVX-512F %s)"
              % (cpu["model"], cpu["cpus"] or 0, " ".join(cpu["simd"]) or "none", "yes" if cpu["avx2"] else "no",
                 "yes" if cpu["avx512f"] else "no"))
    for key, f in gw_facts.items():
        zmm = f["zmm_instructions"]
        md.append("- %s: %s, %s; flags %s%s; %s" % (
            key, f["path"], f["version"], f["flags"],
            " (**built with -mno-avx512f: AVX2 code only**)" if f["no_avx512"] else "",
            "instructions on 512-bit registers: %s" % ("?" if zmm is None else zmm)))
    for c, v in versions.items():
        extra = " (Debian's generic build: no OPENMP/KOKKOS/INTEL package; serial)" if c == "lammps" else ""
        md.append("- %s: %s%s" % (CODE_TITLES[c], v, extra))
    md.append("- one thread (OMP_NUM_THREADS=1), one process each; %d runs per code and case, alternating; "
              "times end to end (start-up included), medians; ratios = median of the paired ratios "
              "(other / granwave, same repetition; > 1: granwave faster)" % a.reps)
    md.append("- machine load: before `%s`; after `%s`; %.0f s in all" % (load0["uptime"], load1["uptime"],
                                                                        time.time() - t_start))
    util = [x["cpu"] / x["wall"] for res in results for runs in res["runs"].values() for x in runs if x["wall"] > 0]
    if util:
        md.append("- CPU time / wall time of the runs: median %.2f, range %.2f-%.2f (1.00: a process never waited; "
                  "lower: it waited for a CPU (a busy machine) or for the disk, and its wall time carries that wait)"
                  % (statistics.median(util), min(util), max(util)))
    md += ["- " + n for n in notes]
    md.append("")
    md.append(table(results, runners, codes))
    md.append("")
    md.append("Physics check (`granwave analyze --json` on every code's output, last run): half-peak speed, and the "
              "largest difference from granwave's trace relative to the wave's peak, of sigma_zz for a P wave and of "
              "the layer velocity v_x for an S wave (the layer files' stress/atom xz is delx fz, not sigma_zx):")
    md.append("")
    md.append(sanity_table(results, runners))
    md.append("")
    if any("contacts" in res for res in results):
        md.append("The packing cases: contact-list builds and the contacts that open and close (bench/side_by_side.py "
                  "says how each is counted); the packing and granwave's build (import and relaxation, not timed):")
        md.append("")
        md.append(contacts_table(results, runners))
        md.append("")
        for res in results:
            if "packing" in res:
                b = res.get("build", {})
                built = ("the system of %s (the same but for name and lever_arm)" % b["reused"] if b.get("reused") else
                         "granwave build %.1f s wall, %.1f s CPU" % (b.get("wall_s", 0), b.get("cpu_s", 0)))
                md.append("- %s: packing %s (%s%s); %s, %s relaxation steps" % (
                    res["case"], res["packing"]["path"], res["packing"]["source"],
                    (", %.1f s of CPU" % res["packing"]["cpu_s"]) if res["packing"].get("cpu_s") else "",
                    built, b.get("relax_steps")))
        md.append("")
    md.append("Peak resident memory of each process (VmHWM polled every 10 ms, the largest of its runs; kB = 1000 bytes):")
    md.append("")
    md.append(memory_table(results, runners))
    text = "\n".join(md) + "\n"
    print(text)
    if a.out:
        with open(a.out + ".tmp", "w") as f:
            f.write(text)
        os.replace(a.out + ".tmp", a.out)
    if a.json:
        doc = dict(schema="granwave-side-by-side/1", argv=argv, cpu=cpu,
                   load_before=load0, load_after=load1, granwave_builds=gw_facts, versions=versions, reps=a.reps,
                   codes=codes, host=platform.node(),
                   cases=[dict(r, summary=summarize(r, runners)) for r in results])
        with open(a.json + ".tmp", "w") as f:
            json.dump(doc, f, indent=1, default=float)
        os.replace(a.json + ".tmp", a.json)
