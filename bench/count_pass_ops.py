#!/usr/bin/python3
"""Counts, from the compiled code, what each contact pass and the particle pass execute per contact
(per particle): divisions, square roots, flops, loads, stores, gathers (issue #41 item 1).

How: `objdump -d` of the kernel's objects (build/CMakeFiles/granwave_crystal.dir/src/crystal/
law_model_*.cpp.o, passes.cpp.o), the function of each pass found by its demangled name, its loops
found by their backward jumps, the hot loops picked by what they hold (the evaluation: the packed
root; the gather: the row transposes; the scatter: the row sums), each instruction classified by
mnemonic and operand (xmm/ymm/zmm lanes of doubles, a memory source or destination, %rsp: the stack).
A loop's counts are divided by the contacts (particles) an iteration walks (the table PASSES, read by
hand and checked against the loop's induction where the script can read it). The scatter's change
of particle i (its sums stored and the next i's loaded), once per run of equal i, is a block that a
forward jump skips when i is unchanged (or placed out of line): it is counted once per I_RUN contacts
(the crystals' 6: twelve neighbours, half of them as i), the rest of the loop every time. Each loop's
critical path (one iteration's longest register dependency chain: the measured latencies of div,
sqrt, add, mul with --ceilings, else Zen 4's published ones). With --mca, each loop
is also handed to llvm-mca-14 for its cycles per iteration and the bottleneck it names: -mcpu=znver3 on
AMD (LLVM 14 has no Zen 4 model; it reads AVX-512VL instructions on ymm as their Zen 3 forms),
-mcpu=sapphirerapids on an Intel core with AVX512-FP16 (LLVM 14 schedules it with its Ice Lake server
model), icelake-server on other Intel cores with AVX-512, skylake on Intel cores without; --mcpu NAME sets it.

Usage: /usr/bin/python3 bench/count_pass_ops.py BUILD_DIR [--ceilings CEILINGS.json] [--mca [--mcpu NAME]] [--json FILE]
       /usr/bin/python3 bench/count_pass_ops.py BUILD_DIR --list FUNCTION_SUBSTRING   (every loop of it)
"""
import json
import re
import subprocess
import sys
from pathlib import Path

# The passes bench_crystal times (its cases), with the instantiation each case runs on one thread
# (contact/*_case.hpp's model(): crystal_p has gamma_n = 0, kt = 0 -> HookeLaw<false>, not dissipative;
# kt = k, mu_static = mu_dynamic, no dashpots -> LinearLudingLaw<false, false>, either arm (the arm is a
# run-time value: scatter<2> or scatter<3>); crystal_hertz.toml, undamped, displacement history ->
# HertzMindlinLaw<false, 1, false>; bench/cases/crystal_rolling.toml -> WithRollingTorsion<
# LinearLudingLaw<false, false>, false, false>), and the loops that make the pass, with the contacts
# (particles) each iteration walks, read by hand from this build's loops (GCC 12 -O3 -march=native,
# 256-bit vectors, except law_model_*_wide.cpp's friction forms without couples at 512) and checked where
# the script can see the induction: the evaluation is unrolled twice (8 contacts at 256 bits, 16 at 512:
# pass() doubles the step where the loop's root or division is a zmm one; its column pointer steps 64
# bytes; the frictionless one, two ymm roots for Hooke's one root per contact), the gather and the scatter take 4
# (their index steps 4, ymm in either unit), the frictionless pass's image offsets 32 (16 ymm stores of
# shx, shy), the particle pass 4. The one-thread route: the gathered passes' own function, the direct
# pass's lambda #4 (kernel::in_parts' body without stored end arms, a run's step).
# divisions_roots: the packed divisions and roots a contact the pass's loops hold (the gather's 1/r and r,
# R* for Hertz-Mindlin, the laws' own); loops picked with other counts are refused.
PASSES = [
    {"name": "frictionless (Hooke)", "object": "law_model_linear.cpp.o",
     "function": "direct_contact_pass<granwave::contact::HookeLaw<false>, false>(granwave::crystal::Dynamics&, granwave::contact::HookeLaw<false> const&, granwave::crystal::ContactPassPlan const&)::{lambda(long, long)#4}::operator()",
     "loops": ["images", "evaluation", "scatter1"], "step": {"images": 32, "evaluation": 8, "scatter1": 4},
     "per": "contact", "divisions_roots": (1, 1)},
    {"name": "friction, radius arm", "object": "law_model_linear_wide.cpp.o",
     "function": "granwave::crystal::ContactSums granwave::crystal::kernel::gathered_contact_pass<granwave::contact::LinearLudingLaw<false, false>, true, false>(",
     "loops": ["gather", "evaluation", "scatter2"], "step": {"gather": 4, "evaluation": 8, "scatter2": 4},
     "per": "contact", "divisions_roots": (2, 1)},
    {"name": "friction, contact-point arm", "object": "law_model_linear_wide.cpp.o",
     "function": "granwave::crystal::ContactSums granwave::crystal::kernel::gathered_contact_pass<granwave::contact::LinearLudingLaw<false, false>, true, false>(",
     "loops": ["gather", "evaluation", "scatter3"], "step": {"gather": 4, "evaluation": 8, "scatter3": 4},
     "per": "contact", "divisions_roots": (2, 1)},
    {"name": "Hertz-Mindlin", "object": "law_model_hertz_mindlin_wide.cpp.o",
     "function": "granwave::crystal::ContactSums granwave::crystal::kernel::gathered_contact_pass<granwave::contact::HertzMindlinLaw<false, (granwave::contact::MindlinHistory)1, false>, true, false>(",
     "loops": ["gather", "evaluation", "scatter2"], "step": {"gather": 4, "evaluation": 8, "scatter2": 4},
     "per": "contact", "divisions_roots": (3, 2)},
    {"name": "rolling and torsion", "object": "law_model_linear.cpp.o",
     "function": "granwave::crystal::ContactSums granwave::crystal::kernel::gathered_contact_pass<granwave::contact::WithRollingTorsion<granwave::contact::LinearLudingLaw<false, false>, false, false>, true, false>(",
     "loops": ["gather", "evaluation", "scatter2c"], "step": {"gather": 4, "evaluation": 8, "scatter2c": 4},
     "per": "contact", "divisions_roots": (4, 1)},
]

# The particle pass of each (one thread, a run's step): Dynamics::finish_kick_drift<Rows, Couples>(q0, q1)
# (crystal/passes.cpp), the contact sums' rows finished, kicked, drifted and the gather rows refilled.
PARTICLE = [
    {"name": "particle pass, 1 row (frictionless)", "object": "passes.cpp.o",
     "function": "granwave::crystal::Dynamics::finish_kick_drift<1, false>(long, long)", "loops": ["fkd"], "step": {"fkd": 4}, "per": "particle"},
    {"name": "particle pass, 2 rows (radius arm, Hertz-Mindlin)", "object": "passes.cpp.o",
     "function": "granwave::crystal::Dynamics::finish_kick_drift<2, false>(long, long)", "loops": ["fkd"], "step": {"fkd": 4}, "per": "particle"},
    {"name": "particle pass, 3 rows (contact-point arm)", "object": "passes.cpp.o",
     "function": "granwave::crystal::Dynamics::finish_kick_drift<3, false>(long, long)", "loops": ["fkd"], "step": {"fkd": 4}, "per": "particle"},
    {"name": "particle pass, 2 rows and couples (rolling)", "object": "passes.cpp.o",
     "function": "granwave::crystal::Dynamics::finish_kick_drift<2, true>(long, long)", "loops": ["fkd"], "step": {"fkd": 4}, "per": "particle"},
]

INSN = re.compile(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$")
FUNC = re.compile(r"^([0-9a-f]+) <(.*)>:$")


def disassemble(obj):
    """{function name: [(address, mnemonic, operands)]} of an object file."""
    out = subprocess.run(["objdump", "-d", "-C", "--no-show-raw-insn", str(obj)], check=True,
                         capture_output=True, text=True).stdout
    funcs, cur = {}, None
    for line in out.splitlines():
        m = FUNC.match(line)
        if m:
            cur = funcs.setdefault(m.group(2), [])
            continue
        m = INSN.match(line)
        if m and cur is not None:
            ops = m.group(3).split("#")[0].strip()
            cur.append((int(m.group(1), 16), m.group(2), ops))
    return funcs


def loops(insns):
    """The loops of a function: (first index, last index) of each backward jump's range, innermost first."""
    index = {a: k for k, (a, _, _) in enumerate(insns)}
    found = []
    for k, (a, mn, ops) in enumerate(insns):
        if not mn.startswith("j"):
            continue
        t = re.match(r"([0-9a-f]+)\b", ops)
        if t and int(t.group(1), 16) <= a and int(t.group(1), 16) in index:
            found.append((index[int(t.group(1), 16)], k))
    return sorted(found, key=lambda r: r[1] - r[0])


def lanes(ops, mn):
    """Doubles an arithmetic instruction works on."""
    if mn.endswith("sd") or mn.endswith("ss"):
        return 1
    if "%zmm" in ops:
        return 8
    if "%ymm" in ops:
        return 4
    return 2


ARITH = re.compile(r"^v?(add|sub|mul|div|sqrt|min|max|fmadd\w*|fmsub\w*|fnmadd\w*)(pd|sd)$")


def width(ops, mn):
    """Bytes a memory operand moves (from the register it pairs with, or the mnemonic)."""
    if "gather" in mn:
        return 0
    if "%zmm" in ops:
        return 64
    if "%ymm" in ops or "256" in mn or mn.endswith("x4") or mn.startswith("vbroadcastf128"):
        return 32
    if mn in ("vmovsd", "movsd", "vbroadcastsd", "vmovq", "movq") or mn.endswith("sd") or mn.endswith("q"):
        return 8
    if mn.endswith("l") or mn.startswith("movsl") or mn == "vmovd" or mn == "vpbroadcastd":
        return 4
    if mn.startswith("movsb") or mn.startswith("movzb") or mn.endswith("b"):
        return 1
    if "%xmm" in ops:
        return 16
    return 8


def classify(body):
    """Counts of one loop body."""
    c = {"instructions": len(body), "div": 0, "sqrt": 0, "div_lanes": 0, "sqrt_lanes": 0, "flops": 0,
         "add_sub": 0, "mul": 0, "minmax": 0, "compare_select": 0, "shuffles": 0, "loads": 0, "stores": 0,
         "load_bytes": 0, "store_bytes": 0, "stack_loads": 0, "stack_stores": 0, "gathers": 0, "scalar_arith": 0,
         "branches": 0}
    for _, mn, ops in body:
        parts = [p.strip() for p in re.split(r",(?![^(]*\))", ops)] if ops else []
        mem = [p for p in parts if "(" in p]
        if mn.startswith("j"):
            c["branches"] += 1
        m = ARITH.match(mn)
        if m:
            n = lanes(ops, mn)
            kind = m.group(1)
            if kind == "div":
                c["div"] += 1
                c["div_lanes"] += n
            elif kind == "sqrt":
                c["sqrt"] += 1
                c["sqrt_lanes"] += n
            elif kind in ("add", "sub"):
                c["add_sub"] += n
                c[f"add_sub_insns_{n}"] = c.get(f"add_sub_insns_{n}", 0) + 1
            elif kind == "mul":
                c["mul"] += n
                c[f"mul_insns_{n}"] = c.get(f"mul_insns_{n}", 0) + 1
            else:
                c["minmax"] += n
            c["flops"] += n
            if n == 1:
                c["scalar_arith"] += 1
        elif mn.startswith(("vcmp", "vblend", "vpblend", "vandpd", "vandnpd", "vorpd", "vxorpd", "vpand", "vpor",
                            "vpxor", "vpternlog", "vmovapd %", "kand", "kor", "kmov", "vpcmp")) and not mem:
            c["compare_select"] += 1
        elif mn.startswith(("vperm", "vunpck", "vshuf", "vinsert", "vextract", "vbroadcast", "vmovddup", "vpshuf")):
            c["shuffles"] += 1
        if "gather" in mn:
            c["gathers"] += 1
        if mem and not mn.startswith(("lea", "nop", "prefetch")) and not mn.startswith("j"):
            dest = parts[-1]
            store = "(" in dest and not mn.startswith(("cmp", "test", "vcmp", "vucomi", "ucomi")) \
                and len(parts) <= 2 or (mn.startswith("vextract") and "(" in dest)
            stack = any("%rsp" in p or "%rbp" in p for p in mem)
            w = width(ops, mn)
            # bytes: the arrays' only (ceilings_figure.py's memory floors); a spill or a base pointer
            # reloaded from the stack stays in the L1
            if store:
                c["stores"] += 1
                c["store_bytes"] += 0 if stack else w
                c["stack_stores"] += stack
            else:
                c["loads"] += 1
                c["load_bytes"] += 0 if stack else w
                c["stack_loads"] += stack
    return c


def signature(body):
    text = [mn + " " + ops for _, mn, ops in body]
    c = classify(body)
    return {
        "sqrt_ymm": any(t.startswith("vsqrtpd") and ("%ymm" in t or "%zmm" in t) for t in text),
        "zmm_loop": any(t.startswith(("vsqrtpd", "vdivpd")) and "%zmm" in t for t in text),  # a 512-bit loop
        "div_ymm": any(t.startswith("vdivpd") and ("%ymm" in t or "%zmm" in t) for t in text),
        "perm": sum(t.startswith(("vperm2f128", "vinsertf128", "vshuff64x2", "vunpck", "vpermt2pd", "vpermi2pd"))
                    for t in text),
        "int8": any(t.startswith(("movsbl", "movsbq", "vpmovsxbd", "vpmovsxbq", "vpmovsxbw")) for t in text),
        "counts": c,
    }


def is_inner(insns, lo, hi):
    return not any(l2 >= lo and h2 <= hi and (l2, h2) != (lo, hi) for l2, h2 in loops(insns))


# Contacts in a run of equal i (the FCC crystal: 6 of its 12 neighbours have the larger index).
I_RUN = 6


def rare_blocks(body):
    """Indices of the instructions a forward conditional jump inside the loop skips where the skipped
    range stores vector rows: the scatter's change of particle i, not on the common path."""
    index = {a: k for k, (a, _, _) in enumerate(body)}
    rare = set()
    for k, (a, mn, ops) in enumerate(body):
        if not mn.startswith("j") or mn == "jmp":
            continue
        t = re.match(r"([0-9a-f]+)\b", ops)
        if not t or int(t.group(1), 16) <= a or int(t.group(1), 16) not in index:
            continue
        skipped = range(k + 1, index[int(t.group(1), 16)])
        if any(body[q][1].startswith("vmov") and re.search(r"%[yz]mm\d+,\s*-?(0x[0-9a-f]+)?\(", body[q][2])
               for q in skipped):
            rare.update(skipped)
    return rare


def weighted_counts(body, rare):
    """classify() of the common path plus the rare blocks' counts / I_RUN (floats)."""
    common = classify([x for q, x in enumerate(body) if q not in rare])
    if not rare:
        return common
    r = classify([x for q, x in enumerate(body) if q in rare])
    return {k: common.get(k, 0) + r.get(k, 0) / I_RUN for k in set(common) | set(r)}


# What each kind of loop holds (per iteration of 4 contacts): scatter<K, Couples>'s row sums.
SCATTER = {"scatter1": (32, 0), "scatter2": (64, 0), "scatter3": (96, 16), "scatter2c": (96, 0)}


def pick(insns, kind):
    """The hot loop of a kind, as (first, last) indices: the smallest loop with the kind's content (the
    evaluation: the largest innermost one)."""
    best = None
    for lo, hi in loops(insns):
        body = insns[lo:hi + 1]
        sg = signature(body)
        c = sg["counts"]
        ok = False
        gathers = sg["perm"] >= 8 and sg["int8"]  # row transposes and j's image bytes
        if kind == "evaluation":  # the largest innermost loop with a packed root or division, not the
            # gather (which takes the contact's length) nor the end arms' loop of 32
            ok = (sg["sqrt_ymm"] or sg["div_ymm"]) and not gathers and is_inner(insns, lo, hi)
            if ok and (best is None or hi - lo > best[1] - best[0]):
                best = (lo, hi)
            continue
        elif kind == "gather":
            ok = gathers and is_inner(insns, lo, hi)
        elif kind == "images":
            ok = not sg["sqrt_ymm"] and sg["int8"] and sg["perm"] < 8 and is_inner(insns, lo, hi)
        elif kind == "fkd":
            ok = c["mul"] > 0 and c["add_sub"] > 0 and not sg["sqrt_ymm"]
        elif kind in SCATTER:
            ok = not sg["sqrt_ymm"] and not sg["int8"] and (c["add_sub"], c["mul"]) == SCATTER[kind] \
                and c["div"] == 0
        if ok and (best is None or hi - lo < best[1] - best[0]):
            best = (lo, hi)
    if best is None:
        raise SystemExit(f"count_pass_ops: no {kind} loop found (has the kernel changed? --list FUNCTION shows its loops)")
    return best


def elements_per_iteration(body):
    """Elements (contacts, particles) an iteration walks: the induction register's step, as an index
    (scaled: the step is elements) or as a pointer to doubles (the step / 8)."""
    best = (0, None)
    for _, mn, ops in body:
        m = re.match(r"^\$0x([0-9a-f]+),(%r\w+)$", ops)
        if mn not in ("add", "addq") or not m:
            continue
        step, reg = int(m.group(1), 16), m.group(2)
        as_index = sum(len(re.findall(r"\(%r\w*," + re.escape(reg) + r",", o)) for _, _, o in body)
        as_base = sum(len(re.findall(r"\(" + re.escape(reg) + r"[,)]", o)) for _, mn2, o in body
                      if "%ymm" in o or "%xmm" in o or mn2.endswith("pd") or mn2.endswith("sd"))
        uses, n = (as_index, step) if as_index >= as_base else (as_base, step // 8)
        if uses > best[0]:
            best = (uses, n)
    return best[1]


def default_mcpu():
    """llvm-mca-14's model nearest this machine's core (/proc/cpuinfo)."""
    try:
        info = Path("/proc/cpuinfo").read_text()
    except OSError:
        return "znver3"
    flags = set(re.search(r"^flags\s*:(.*)$", info, re.M).group(1).split()) if "flags" in info else set()
    if "GenuineIntel" not in info:
        return "znver3"
    if "avx512_fp16" in flags:
        return "sapphirerapids"
    return "icelake-server" if "avx512f" in flags else "skylake"


def mca(body, mcpu="znver3"):
    """llvm-mca-14's cycles per iteration and its bottleneck note for a loop body, or None."""
    lines = ["L0:"]
    for _, mn, ops in body:
        if mn.startswith("j"):
            lines.append(f"{mn} L0")
        else:
            lines.append(f"{mn} {re.sub(r'<.*', '', ops)}".strip())
    try:
        out = subprocess.run(["llvm-mca-14", f"-mcpu={mcpu}", "-iterations=200", "-bottleneck-analysis"],
                             input="\n".join(lines) + "\n", capture_output=True, text=True, timeout=120).stdout
    except (OSError, subprocess.TimeoutExpired):
        return None
    cyc = re.search(r"Total Cycles:\s+(\d+)", out)
    rt = re.search(r"Block RThroughput:\s+([\d.]+)", out)
    note = []
    for key in ("Cycles with backend pressure increase", "Throughput Bottlenecks", "- Resource Pressure",
                "- Data Dependencies", "- Register Dependencies", "- Memory Dependencies"):
        m = re.search(re.escape(key) + r".*", out)
        if m:
            note.append(m.group(0).strip())
    return {"cycles_per_iteration": int(cyc.group(1)) / 200 if cyc else None,
            "block_rthroughput": float(rt.group(1)) if rt else None, "bottleneck": "; ".join(note)}


# Latencies (cycles) for the dependency path: div, sqrt, add, mul from bench/ceilings (passed in);
# the rest Zen 4's published figures (AMD's software optimisation guide for family 19h): an L1 load
# 7 (FP), a lane shuffle across halves 3, within 1, a conversion 3, a compare into a mask 3 (approximate).
def latency_of(mn, ops, lat):
    z = "_zmm" if "%zmm" in ops and lat.get("div_zmm") else ""  # a 512-bit instruction's own latency
    if mn.startswith(("vdivpd", "vdivsd")):
        return lat["div" + z]
    if mn.startswith(("vsqrtpd", "vsqrtsd")):
        return lat["sqrt" + z]
    if mn.startswith(("vmul",)):
        return lat["mul" + z]
    if re.match(r"^v(add|sub|min|max)(pd|sd)$", mn):
        return lat["add" + z]
    if mn.startswith(("vperm2", "vinsertf", "vextractf", "vshuff", "vpermt", "vpermi")):
        return 3
    if mn.startswith(("vcvt", "vcmp", "vpcmp")):
        return 3
    return 1


def critical_path(body, lat):
    """The longest register dependency path through one iteration (cycles), loads adding 7 (L1)."""
    ready = {}
    longest = 0.0
    for _, mn, ops in body:
        if mn.startswith("j") or not ops:
            continue
        parts = [p.strip() for p in re.split(r",(?![^(]*\))", ops)]
        regs_in = []
        mem_load = False
        dest = None
        if len(parts) >= 2 and not parts[-1].startswith("(") and "(" not in parts[-1]:
            dest = parts[-1].split("{")[0]
            srcs = parts[:-1]
        else:
            srcs = parts  # a store or compare: no register result
        for p in srcs:
            if "(" in p:
                mem_load = True
                regs_in += re.findall(r"%\w+", p)
            else:
                regs_in += re.findall(r"%\w+", p)
        start = max([ready.get(r, 0.0) for r in regs_in] + [0.0])
        t = start + latency_of(mn, ops, lat) + (7 if mem_load else 0)
        if dest:
            ready[dest] = t
            ready[dest.replace("%ymm", "%zmm").replace("%xmm", "%zmm")] = t
        longest = max(longest, t)
    return longest


def pass_counts(objdir, spec, lat, with_mca, cache):
    # the table's unit first; a form CMake moved to the other width's unit (GRANWAVE_COUPLES_512: the
    # rolling forms in law_model_<law>_wide.cpp) is found in it
    stem = spec["object"].replace("_wide.cpp.o", ".cpp.o")
    for obj in dict.fromkeys((objdir / spec["object"], objdir / stem, objdir / stem.replace(".cpp.o", "_wide.cpp.o"))):
        if obj not in cache:
            cache[obj] = disassemble(obj) if obj.exists() else {}
        funcs = cache[obj]
        names = [n for n in funcs if spec["function"] in n]
        if names:
            break
    else:
        raise SystemExit(f"count_pass_ops: no function with {spec['function']!r} in {objdir / spec['object']} "
                         "or its other width's unit")
    name = min(names, key=len)
    insns = funcs[name]
    out = {"pass": spec["name"], "object": obj.name, "function": name[:160], "loops": []}
    total = {}
    for kind in spec["loops"]:
        lo, hi = pick(insns, kind)
        body = insns[lo:hi + 1]
        n = spec["step"][kind]
        if kind == "evaluation" and signature(body)["zmm_loop"]:
            n *= 2  # 512-bit vectors: the same loop unrolled twice walks 16 contacts
        seen = elements_per_iteration(body)
        if seen and seen != n:
            print(f"count_pass_ops: note: {spec['name']}, {kind}: the induction reads {seen} per iteration, "
                  f"the table says {n} (a byte-offset index or a second pointer; checked by hand)", file=sys.stderr)
        rare = rare_blocks(body) if kind in SCATTER else set()
        c = weighted_counts(body, rare)
        row = {"kind": kind, "range": [hex(body[0][0]), hex(body[-1][0])], "per_iteration": n,
               "instructions": c["instructions"], "instructions_in_loop": len(body), "rare_instructions": len(rare),
               "counts": c, "induction_seen": seen, "critical_path_cycles": critical_path(body, lat)}
        # division and root instructions by width, for the divider's time
        row["div_by_lanes"] = {}
        row["sqrt_by_lanes"] = {}
        for _, mn, ops in body:
            if ARITH.match(mn) and ARITH.match(mn).group(1) in ("div", "sqrt"):
                d = row["div_by_lanes" if "div" in mn else "sqrt_by_lanes"]
                k = str(lanes(ops, mn))
                d[k] = d.get(k, 0) + 1
        if with_mca:
            row["mca"] = mca([x for q, x in enumerate(body) if q not in rare], with_mca)  # the common path
        out["loops"].append(row)
        for k, v in c.items():
            if isinstance(v, (int, float)) and v is not None:
                total[k] = total.get(k, 0.0) + v / n
    out["per_" + spec["per"]] = total
    # The loops picked must hold the pass's divisions and roots a contact: a build with other arithmetic
    # (a scratch bound without them) makes pick() take another loop, whose counts would be wrong silently.
    if "divisions_roots" in spec and any(abs(total.get(k, 0.0) - want) > 1e-9 for k, want in
                                         zip(("div_lanes", "sqrt_lanes"), spec["divisions_roots"])):
        print(f"count_pass_ops: {spec['name']}: the loops picked in {obj.name} hold {total.get('div_lanes', 0):g} divisions "
              f"and {total.get('sqrt_lanes', 0):g} roots a contact where the pass has {spec['divisions_roots'][0]} and "
              f"{spec['divisions_roots'][1]}: a build with other arithmetic, or the kernel changed "
              "(--list FUNCTION shows its loops; PASSES names what each pass holds)", file=sys.stderr)
        sys.exit(2)
    return out


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith("-"):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    build = Path(args[0])
    objdir = build / "CMakeFiles/granwave_crystal.dir/src/crystal"
    if not objdir.is_dir():
        print(f"count_pass_ops: {objdir} is not a directory (BUILD_DIR: a Release build of granwave)", file=sys.stderr)
        sys.exit(2)
    if "--list" in args:
        want = args[args.index("--list") + 1]
        for obj in sorted(objdir.glob("*.o")):
            for name, insns in disassemble(obj).items():
                if want in name:
                    print(f"== {obj.name}: {name[:200]}")
                    for lo, hi in loops(insns):
                        c = classify(insns[lo:hi + 1])
                        print(f"  loop [{insns[lo][0]:x}, {insns[hi][0]:x}] {hi - lo + 1} insns, step "
                              f"{elements_per_iteration(insns[lo:hi + 1])}: "
                              + ", ".join(f"{k} {v}" for k, v in c.items() if v))
        return
    lat = {"div": 13.0, "sqrt": 21.0, "add": 3.0, "mul": 3.0}
    if "--ceilings" in args:  # the measured latencies (bench/ceilings --json)
        cj = json.loads(Path(args[args.index("--ceilings") + 1]).read_text())
        ymm = next(r for r in cj["arithmetic"] if r["lanes"] == 4)
        lat = {k: ymm[k]["latency_cycles"] for k in ("div", "sqrt", "add", "mul")}
        zmm = next((r for r in cj["arithmetic"] if r["lanes"] == 8), None)
        if zmm:
            lat.update({k + "_zmm": zmm[k]["latency_cycles"] for k in ("div", "sqrt", "add", "mul")})
    with_mca = ("--mca" in args) and (args[args.index("--mcpu") + 1] if "--mcpu" in args else default_mcpu())
    cache = {}
    result = {"format": "granwave-pass-ops/1", "latencies_cycles": lat, "passes": []}
    for spec in PASSES + PARTICLE:
        r = pass_counts(objdir, spec, lat, with_mca, cache)
        result["passes"].append(r)
        per = r["per_" + spec["per"]]
        print(f"{spec['name']:<50} per {spec['per']}: {per['instructions']:.1f} instructions, div {per['div_lanes']:.2f}, "
              f"sqrt {per['sqrt_lanes']:.2f}, flops {per['flops']:.1f} (add/sub {per['add_sub']:.1f}, mul {per['mul']:.1f}), "
              f"loads {per['loads']:.1f} ({per['stack_loads']:.1f} stack), stores {per['stores']:.1f} "
              f"({per['stack_stores']:.1f} stack), shuffles {per['shuffles']:.1f}")
        for L in r["loops"]:
            m = L.get("mca") or {}
            rare = f" ({L['rare_instructions']} of {L['instructions_in_loop']} once per {I_RUN} contacts)" \
                if L["rare_instructions"] else ""
            print(f"    {L['kind']:<11} {L['instructions']:6.1f} insns / {L['per_iteration']} {spec['per']}s{rare}, critical path "
                  f"{L['critical_path_cycles']:.0f} cycles" + (f"; llvm-mca {m.get('cycles_per_iteration')} cycles/iteration "
                                                                 f"(rthroughput {m.get('block_rthroughput')})" if m else ""))
    if "--json" in args:
        Path(args[args.index("--json") + 1]).write_text(json.dumps(result, indent=1) + "\n")


if __name__ == "__main__":
    main()
