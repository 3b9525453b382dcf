"""Load helper for the no-loss test and benchmark: one agent floods another's inbox.

flood.py receive NAME EXPECTED [--work-us N]   # counts informs, prints a JSON line
flood.py send NAME TO COUNT                     # sends COUNT informs as fast as it can
"""

from __future__ import annotations

import json
import sys
import time

import rclpy

from cf_commag.client import Agent, inbox_topic
from cf_lang.acl import AclMessage, AgentId, Performative


def receive(name: str, expected: int, work_us: float) -> None:
    rclpy.init()
    node = rclpy.create_node(name)
    seen = set()
    state = {"first": None, "last": None}

    def on_message(msg: AclMessage) -> None:
        end = time.perf_counter() + work_us / 1e6
        while time.perf_counter() < end:  # a deliberately slow subscriber
            pass
        seen.add(int(msg.content))
        now = time.monotonic()
        state["first"] = state["first"] or now
        state["last"] = now

    agent = Agent(node, name=name, service_class="Monitoring", register=False, on_message=on_message)
    print("ready", flush=True)
    idle_since = time.monotonic()
    count = 0
    while len(seen) < expected and time.monotonic() - idle_since < 15.0:
        rclpy.spin_once(node, timeout_sec=0.1)
        if len(seen) != count:
            count, idle_since = len(seen), time.monotonic()
    took = (state["last"] or 0) - (state["first"] or 0)
    missing = sorted(set(range(expected)) - seen)
    print(
        json.dumps(
            {
                "received": len(seen),
                "expected": expected,
                "seconds": took,
                "bad": agent.counters["bad"],
                "missing_first": missing[:5],
                "missing_last": missing[-5:],
            }
        ),
        flush=True,
    )
    node.destroy_node()
    rclpy.shutdown()


def send(name: str, to: str, count: int) -> None:
    rclpy.init()
    node = rclpy.create_node(name)
    agent = Agent(node, name=name, service_class="Monitoring", register=False)
    deadline = time.monotonic() + 20
    while node.count_subscribers(inbox_topic(to)) == 0 and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
    receiver = (AgentId(to),)
    start = time.monotonic()
    for i in range(count):
        agent.send(AclMessage(Performative.INFORM, receivers=receiver, content=str(i)))
    sent = time.monotonic() - start
    acked = agent.flush(timeout=60.0)
    print(json.dumps({"sent": count, "seconds": sent, "acked": acked}), flush=True)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    if sys.argv[1] == "receive":
        work = float(sys.argv[sys.argv.index("--work-us") + 1]) if "--work-us" in sys.argv else 0.0
        receive(sys.argv[2], int(sys.argv[3]), work)
    else:
        send(sys.argv[2], sys.argv[3], int(sys.argv[4]))
