"""The granwave package of the build tree (build/python/, or $GRANWAVE_BUILD/python/) comes first,
so that the tests judge the code of this tree; test_installed checks the installed copy."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("GRANWAVE_BUILD", os.path.join(ROOT, "build"))
sys.path.insert(0, os.path.join(BUILD, "python"))
