"""Run every test of the workspace and print one readable summary.

`make test` calls this after `colcon build`. It reserves a ROS_DOMAIN_ID of its
own and keeps DDS discovery on this host, so two runs on one machine never see
each other; runs `colcon test` (each package's pytest suite) and then the
system tests under test/; and fails when any package collected no tests (a
pytest exit code 5 must never pass as green).
"""

from __future__ import annotations

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from domain_coordinator import domain_id

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "test-results"
ALL_PACKAGES = ["cf_lang", "cf_commag", "cf_sim_backend", "cf_decision"]


def _has_code(pkg: str) -> bool:
    """A package counts once it holds a module besides __init__.py; then it must have tests."""
    return any(p.name != "__init__.py" for p in (ROOT / pkg / pkg).glob("*.py"))


PYTHON_PACKAGES = [pkg for pkg in ALL_PACKAGES if _has_code(pkg)]


def _junit_counts(path: Path) -> dict[str, int] | None:
    """Sum tests/failures/errors/skipped over a JUnit XML file."""
    if not path.exists():
        return None
    root = ET.parse(path).getroot()
    suites = [root] if root.tag == "testsuite" else list(root.iter("testsuite"))
    counts = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    for suite in suites:
        for key in counts:
            counts[key] += int(suite.get(key, 0))
    return counts


def _skips(path: Path) -> list[str]:
    if not path.exists():
        return []
    out = []
    for case in ET.parse(path).getroot().iter("testcase"):
        for skipped in case.iter("skipped"):
            out.append(f"{case.get('classname')}.{case.get('name')}: {skipped.get('message', '')}")
    return out


def main() -> int:
    RESULTS.mkdir(exist_ok=True)
    with domain_id() as did:
        env = dict(os.environ, ROS_DOMAIN_ID=str(did), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", PYTHONUNBUFFERED="1")
        print(f"==> tests use ROS_DOMAIN_ID={did}, discovery on localhost only", flush=True)
        colcon = subprocess.run(
            [
                "colcon",
                "--log-base",
                "log",
                "test",
                "--packages-select",
                *PYTHON_PACKAGES,
                "--test-result-base",
                str(RESULTS / "colcon"),
                "--event-handlers",
                "console_direct+",
                "summary+",
                "--return-code-on-test-failure",
                "--pytest-args",
                "-q",
                "-p",
                "no:cacheprovider",
            ],
            cwd=ROOT,
            env=env,
        )
        system_xml = RESULTS / "system.xml"
        system = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", f"--junitxml={system_xml}", "test"],
            cwd=ROOT,
            env=env,
        )

    rows = []
    failed = colcon.returncode != 0
    for pkg in PYTHON_PACKAGES:
        counts = _junit_counts(RESULTS / "colcon" / pkg / "pytest.xml")
        rows.append((pkg, counts, _skips(RESULTS / "colcon" / pkg / "pytest.xml")))
    rows.append(("test/ (system)", _junit_counts(system_xml), _skips(system_xml)))
    if system.returncode == 5:
        print("system tests: pytest collected nothing (exit code 5); that is a failure here")
    failed = failed or system.returncode != 0

    print("\n==================== test summary ====================")
    print(f"{'suite':<18}{'tests':>7}{'failed':>8}{'errors':>8}{'skipped':>9}")
    for name, counts, skips in rows:
        if counts is None or counts["tests"] == 0:
            print(f"{name:<18}  NO TESTS RAN (counted as a failure)")
            failed = True
            continue
        print(f"{name:<18}{counts['tests']:>7}{counts['failures']:>8}{counts['errors']:>8}{counts['skipped']:>9}")
        failed = failed or counts["failures"] > 0 or counts["errors"] > 0
        for skip in skips:
            print(f"    skipped: {skip}")
    print("=======================================================")
    print("RESULT:", "FAILED" if failed else "PASSED")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
