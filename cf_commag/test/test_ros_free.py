"""The ComMAg's cores import without ROS: what the design promises and the gateway's core relies on."""

from __future__ import annotations

import subprocess
import sys

CORES = [
    "cf_commag.records",
    "cf_commag.registry",
    "cf_commag.launcher",
    "cf_commag.store",
    "cf_commag.gateway",
    "cf_commag.transport.samples",
    "cf_commag.transport.cdr",
]


def test_the_cores_import_without_rclpy():
    code = f"import sys; import {', '.join(CORES)}; print(sorted(m for m in sys.modules if m.startswith('rclpy')))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]", out
