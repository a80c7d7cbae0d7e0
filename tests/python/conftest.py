"""The granwave package of the build tree (build/python/, or $GRANWAVE_BUILD/python/) comes first,
so that the tests judge the code of this tree; test_installed checks the installed copy."""
import os
import signal
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("GRANWAVE_BUILD", os.path.join(ROOT, "build"))
sys.path.insert(0, os.path.join(BUILD, "python"))

try:   # granwave.crosscheck of this source tree when the build's package predates it (pure Python)
    import granwave
    _src = os.path.join(ROOT, "python", "granwave")
    if _src not in granwave.__path__:
        granwave.__path__.append(_src)
except ImportError:
    pass


def pytest_configure(config):
    config.addinivalue_line("markers", "realcodes: runs real codes (granwave, LAMMPS) through the crosscheck; "
                            "select with -m realcodes, skip with -m 'not realcodes'")


@pytest.fixture(autouse=True)
def python_sigint_handler():
    """Ctrl-C raises KeyboardInterrupt, as in a terminal or a notebook: a process started in the
    background by a non-interactive shell inherits SIGINT ignored, and Python then keeps it ignored,
    which would make the interrupt tests measure the shell instead of the module."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)
