"""The link between the simulator and its per-player components (the back-end's own wire, like rcssserver's UDP).

``/<sim>/state``: std_msgs/String, one JSON object per cycle (Simulator.snapshot()).
``/<sim>/commands``: std_msgs/String, one JSON object per command, or a list of them (what the
components of one process send in a cycle): ``{"side": "l", "number": 7, "cmd": "dash", "args": [80, 0]}``;
in sync mode ``{"side": "l", "number": 7, "done": <step>}`` says a player has acted on that step.
Components speak the Framework Language to everyone else; only this link is simulator-specific.
"""

from __future__ import annotations

from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy

STATE_QOS = QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)
COMMAND_QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)


def state_topic(sim: str) -> str:
    return f"/{sim}/state"


def command_topic(sim: str) -> str:
    return f"/{sim}/commands"
