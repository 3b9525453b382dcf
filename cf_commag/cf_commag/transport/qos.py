"""The QoS profiles of the framework's topics and services: one definition each."""

from __future__ import annotations

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

# Agents' inboxes: reliable and KEEP_ALL, so a fast sender is slowed down instead of losing messages.
INBOX_QOS = QoSProfile(
    history=HistoryPolicy.KEEP_ALL,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)
# The ComMAg's registry snapshot: a late joiner gets the latest at once.
SNAPSHOT_QOS = QoSProfile(
    depth=1,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
    history=HistoryPolicy.KEEP_LAST,
)
# The ComMAg's events: a monitor that joins late still gets the last 1000.
EVENTS_QOS = QoSProfile(
    depth=1000,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
    history=HistoryPolicy.KEEP_LAST,
)
# The ComMAg's services, on both sides. ROS's default keeps 10 requests (and 10 responses):
# a burst of registrations (a team starting, the gateway's clients arriving together) lost
# a quarter of them. Requests and answers are small; keep many.
SERVICE_QOS = QoSProfile(
    depth=1000,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
    history=HistoryPolicy.KEEP_LAST,
)
