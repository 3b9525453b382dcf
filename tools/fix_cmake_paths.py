"""Point the ROS wheels' exported CMake files at this interpreter's include dirs.

The wheels were built in a manylinux container and their exported CMake files
name that container's Python and NumPy include paths; CMake's generate step
then fails with "includes non-existent path". Rewriting is idempotent and only
touches files inside the given prefix (the venv).
"""

from __future__ import annotations

import sys
import sysconfig
from pathlib import Path

BUILD_PY_INCLUDE = "/opt/python/cp311-cp311/include/python3.11"
BUILD_NUMPY_INCLUDE = "/opt/python/cp311-cp311/lib/python3.11/site-packages/numpy/_core/include"


def fix(prefix: Path) -> int:
    """Rewrite the build-machine paths under prefix/share; return files changed."""
    import numpy

    replacements = {
        BUILD_PY_INCLUDE: sysconfig.get_paths()["include"],
        BUILD_NUMPY_INCLUDE: numpy.get_include(),
    }
    changed = 0
    for path in (prefix / "share").glob("*/cmake/*.cmake"):
        text = path.read_text(encoding="utf-8")
        new = text
        for old, repl in replacements.items():
            new = new.replace(old, repl)
        if new != text:
            path.write_text(new, encoding="utf-8")
            changed += 1
    return changed


if __name__ == "__main__":
    prefix = Path(sys.argv[1] if len(sys.argv) > 1 else sys.prefix)
    print(f"cmake path fix: {fix(prefix)} file(s) rewritten")
