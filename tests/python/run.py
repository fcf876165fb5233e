# SPDX-License-Identifier: Apache-2.0
"""run.py TEST_FILE... - runs the Python package's tests with pytest, as ctest
does: exit 77 (ctest's "skipped") with the reason when numpy or pytest is
missing from this interpreter, pytest's exit status otherwise. Writes no
cache or bytecode into the source tree."""
import os
import sys

sys.dont_write_bytecode = True
for name, package in (("numpy", "python3-numpy"), ("pytest", "python3-pytest")):
    try:
        __import__(name)
    except ImportError:
        print("skipped: %s has no %s (install %s)" % (sys.executable, name, package))
        sys.exit(77)
import pytest  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "--rootdir", here] + sys.argv[1:]))
