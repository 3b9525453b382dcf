"""The standing hostile suite: generated and mutated lines through the installed gateway to a real ComMAg.

At least 100,000 lines (seeds printed; CF_FUZZ_SEED repeats a run, CF_FUZZ_LINES sets the size),
then 3,000 agents that come and go. Afterwards: both processes alive, no ``internal error``,
every connection answered its final ping or was closed after a final ``(error ...)`` line,
memory back near the baseline, and a normal session works.
"""

from __future__ import annotations

import asyncio
import os
import random
import socket
import statistics
import sys
import time
from pathlib import Path

from cf_system import HELPERS, start_commag, start_component, start_gateway

sys.path.insert(0, str(HELPERS))
from fuzz_gateway import churn, fuzz

LINES = int(os.environ.get("CF_FUZZ_LINES", "100000"))


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError(f"no VmRSS for {pid}")


class Line:
    """A plain blocking client, as a foreign agent would be."""

    def __init__(self, port: int):
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=30)
        self.file = self.sock.makefile("rb")

    def ask(self, text: str, until: str = "") -> str:
        self.sock.sendall(text.encode() + b"\n")
        while True:
            line = self.file.readline().decode().rstrip("\n")
            assert line, f"closed after {text}"
            if line.startswith(until):
                return line

    def close(self) -> None:
        self.sock.close()


def round_trips(port: int, name: str, provider: str, count: int = 200) -> list[float]:
    """A normal session: hello, register, lookup, then fipa-requests to a ROS provider; their times (s)."""
    client = Line(port)
    assert client.ask(f"(hello :name {name})").startswith("(welcome")
    assert client.ask("(register :service-class PlayerDecision :team blue :player 9)").startswith("(registered")
    assert provider in client.ask("(lookup :service-class Kick :team blue)")
    times = []
    for i in range(count):
        started = time.perf_counter()
        answer = client.ask(
            f"(request :receiver (set (agent-identifier :name {provider})) :content "
            f'"(exec Player kick :playerNumber 9 :whichTeam our :power 70 :direction 0)" '
            f":protocol fipa-request :conversation-id {name}{i})",
            until="(inform",
        )
        times.append(time.perf_counter() - started)
        assert f":conversation-id {name}{i}" in answer
    client.ask("(bye)", until="(bye")
    client.close()
    return times


def test_a_fuzz_run_and_thousands_of_agents_leave_both_processes_well(procs, probe, tag, tmp_path):
    seed = int(os.environ.get("CF_FUZZ_SEED", random.randrange(10**6)))
    print(f"fuzz seed {seed}, {LINES} lines (CF_FUZZ_SEED={seed} repeats it)", flush=True)
    commag = start_commag(procs, tag, tmp_path, "forget_after:=3.0")
    port_file = tmp_path / "gateway.port"
    gateway = start_gateway(procs, tag, port_file)
    provider = f"blue_9_kick_{tag}"
    start_component(procs, tag, provider, "--service-class", "Kick", "--team", "blue", "--player", "9")
    probe.wait_kind(provider, "registered", timeout=60)
    probe.spin_until(port_file.exists, 60, "the gateway's port")
    port = int(port_file.read_text())

    # Warm up (caches, DDS endpoints, allocator), then take the baseline.
    warm = asyncio.run(fuzz("127.0.0.1", port, 20_000, seed + 1))
    assert asyncio.run(churn("127.0.0.1", port, 300, seed + 2)) == 300
    before = round_trips(port, f"before_{tag}", provider)
    probe.spin_for(8.0)  # churned agents withdrawn and forgotten
    baseline = {"gateway": rss_mb(gateway.pid), "commag": rss_mb(commag.pid)}

    outcome = asyncio.run(fuzz("127.0.0.1", port, LINES, seed))
    churned = asyncio.run(churn("127.0.0.1", port, 3000, seed + 3))
    # Every agent that vanished is withdrawn, then forgotten: the registry is back to what it was.
    probe.spin_until(
        lambda: probe.snapshot is not None and len(probe.snapshot.records) <= 3, 120, "vanished agents forgotten"
    )
    after = {"gateway": rss_mb(gateway.pid), "commag": rss_mb(commag.pid)}
    later = round_trips(port, f"after_{tag}", provider)
    print(
        f"fuzz: {vars(outcome) | {'violations': len(outcome.violations)}}\n"
        f"warm-up violations {len(warm.violations)}; churned ok {churned}/3000\n"
        f"RSS MB before {baseline} after {after}\n"
        f"round trip p50 before {statistics.median(before) * 1e3:.2f} ms, after {statistics.median(later) * 1e3:.2f} ms",
        flush=True,
    )
    assert gateway.poll() is None and commag.poll() is None, "a process died"
    assert outcome.lines >= LINES and outcome.connections > LINES // 200  # about 80 lines per connection
    assert outcome.internal_errors == 0 and not outcome.violations, outcome.violations[:5]
    assert not warm.violations, warm.violations[:5]
    assert outcome.answered + outcome.closed_with_error + outcome.closed_after_bye == outcome.connections
    assert churned == 3000
    # Bounded: the parse caches fill once (a few MB); nothing is kept per connection or per agent.
    assert after["gateway"] - baseline["gateway"] < 25, (baseline, after)
    assert after["commag"] - baseline["commag"] < 15, (baseline, after)
    assert "Traceback" not in procs.log("gateway") and "Traceback" not in procs.log("commag")
