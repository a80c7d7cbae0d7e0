import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "crosscheck"))
sys.path.insert(0, os.path.join(REPO, "liggghts_inputs"))


def pytest_configure(config):
    config.addinivalue_line("markers", "realcodes: runs real YADE/LIGGGHTS/granwave (a few minutes); "
                            "select with -m realcodes, skip with -m 'not realcodes'")
    config.addinivalue_line("markers", "fullsize: a paper-size run in every code (about 10 minutes on one core); "
                            "not in CI (scripts/test-all.sh deselects it), select with -m fullsize")


@pytest.fixture
def cases_dir():
    return os.path.join(HERE, "cases")
