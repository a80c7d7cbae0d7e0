"""The machine and the builds: CPU model and SIMD flags, load, a granwave binary's CMake flags and
512-bit instructions, the other codes' versions."""
from __future__ import annotations

import os
import re
import shutil
import subprocess


def cpu_facts(cpuinfo: str | None = None) -> dict:
    if cpuinfo is None:
        try:
            with open("/proc/cpuinfo") as f:
                cpuinfo = f.read()
        except OSError:
            cpuinfo = ""
    model, flags = "unknown", set()
    for ln in cpuinfo.splitlines():
        if ln.startswith("model name") and model == "unknown":
            model = ln.split(":", 1)[1].strip()
        elif ln.startswith("flags") and not flags:
            flags = set(ln.split(":", 1)[1].split())
    simd = [f for f in ("avx2", "fma", "avx512f", "avx512dq", "avx512vl", "avx512bw") if f in flags]
    return dict(model=model, cpus=os.cpu_count(), avx2="avx2" in flags, avx512f="avx512f" in flags, simd=simd)


def load_facts() -> dict:
    la = os.getloadavg()
    up = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip() if shutil.which("uptime") else ""
    return dict(loadavg=[round(x, 2) for x in la], uptime=up)


def cmake_cache(exe: str) -> dict:
    """CMAKE_CXX_FLAGS, build type and GRANWAVE_* options of the build tree a granwave binary sits in."""
    d = os.path.dirname(os.path.abspath(exe))
    for _ in range(3):
        p = os.path.join(d, "CMakeCache.txt")
        if os.path.exists(p):
            out = {"cache": p}
            with open(p) as f:
                for ln in f:
                    m = re.match(r"^(CMAKE_CXX_FLAGS|CMAKE_BUILD_TYPE|GRANWAVE_[A-Z_]+|CMAKE_CXX_COMPILER):[A-Z]+=(.*)$",
                                 ln.rstrip("\n"))
                    if m:
                        out[m.group(1)] = m.group(2)
            return out
        d = os.path.dirname(d)
    return {}


def zmm_instructions(exe: str) -> int | None:
    """How many instructions of the binary use a 512-bit register (None: no objdump)."""
    if not shutil.which("objdump"):
        return None
    p = subprocess.run(["objdump", "-d", "--no-show-raw-insn", exe], capture_output=True, text=True)
    return p.stdout.count("%zmm") if p.returncode == 0 else None


def granwave_build_facts(exe: str) -> dict:
    c = cmake_cache(exe)
    flags = c.get("CMAKE_CXX_FLAGS", "")
    zmm = zmm_instructions(exe)
    ver = subprocess.run([exe, "version"], capture_output=True, text=True).stdout.strip()
    native = c.get("GRANWAVE_NATIVE", "ON").upper() not in ("OFF", "0", "FALSE")
    desc = "-O3%s%s" % (" -march=native" if native else "", (" " + flags) if flags else "")
    if c.get("GRANWAVE_ONE_COPY", "OFF").upper() in ("ON", "1", "TRUE"):
        desc += " -fPIC -fno-semantic-interposition (GRANWAVE_ONE_COPY: the module's copy of the libraries)"
    if not c:
        desc = "unknown (no CMakeCache.txt next to the binary)"
    return dict(path=exe, version=ver, cmake=c, flags=desc, no_avx512="-mno-avx512f" in flags, zmm_instructions=zmm)


def code_version(exe: str, code: str) -> str:
    p = subprocess.run([exe, "-in", "/dev/null", "-log", "none"], capture_output=True, text=True, timeout=120)
    first = (p.stdout.strip().splitlines() or [""])[0]
    return first.strip()
