"""No ACL message is silently lost when a fast sender floods a slow agent (counted, between processes)."""

from __future__ import annotations

import json

from cf_system import python_helper


def test_fast_sender_slow_receiver_loses_nothing(procs, tag, probe):
    count = 10_000
    receiver = python_helper(procs, "flood.py", "receive", f"rx_{tag}", str(count), "--work-us", "50", log_name="rx")
    probe.spin_until(lambda: "ready" in procs.log("rx"), what="receiver ready")
    sender = python_helper(procs, "flood.py", "send", f"tx_{tag}", f"rx_{tag}", str(count), log_name="tx")
    assert sender.wait(timeout=240) == 0, procs.log("tx")
    assert receiver.wait(timeout=240) == 0, procs.log("rx")
    sent = json.loads(procs.log("tx").strip().splitlines()[-1])
    got = json.loads(procs.log("rx").strip().splitlines()[-1])
    assert sent["sent"] == count and sent["acked"]
    assert got["received"] == count, got
    assert got["bad"] == 0
