"""What every reading option of `granwave analyze` (--period, --wavenumber-speed) must refuse: a
value it does not know, and any value on a chain trace (exit 2, naming the option)."""
import os
import subprocess
import sys


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run(*cmd):
    return subprocess.run(list(cmd), capture_output=True, text=True)


def check_refusals(gw, trace, chain_case, work, flag, unknown, known):
    bad = run(gw, "analyze", trace, flag, unknown)
    if bad.returncode != 2 or "%s %s" % (flag, unknown) not in bad.stderr:
        fail("%s %s: exit %d, %r" % (flag, unknown, bad.returncode, bad.stderr))
    ctrace = os.path.join(work, "chain.h5")
    if run(gw, "run", chain_case, "-o", ctrace, "--quiet").returncode != 0:
        fail("chain run failed")
    c = run(gw, "analyze", ctrace, flag, known)
    if c.returncode != 2 or "crystal traces" not in c.stderr:
        fail("%s on a chain trace: exit %d, %r" % (flag, c.returncode, c.stderr))


def check_each_greater(smaller, larger, what):
    """larger[i] > smaller[i] in every layer where both exist (what: '%r not after %r' style)."""
    for s, g in zip(smaller, larger):
        if s is not None and g is not None and not g > s:
            fail(what % (g, s))


def check_text_says(gw, trace, phrase, what):
    if phrase not in run(gw, "analyze", trace).stdout:
        fail("analyze's text does not say " + what)
