"""The agent runtime, as components import it: ``from cf_commag.client import Agent, run``.

It gathers three modules: the agent (agent.py: Agent, Responder, Reply, Refuse, Failure), the
process runtime (runtime.py: init, spin, run, make_executor, own_launch_command) and the inbox
transport (transport/: topic names, QoS profiles, sample packing, Outbox).

    node = rclpy.create_node("blue_7_action")
    agent = Agent(node, name="blue_7_action", service_class="Action", team="blue", player_number=7)
    agent.serve("fipa-request", on_request)        # answer requests
    future = agent.request("blue_7_perception", "(val Game time)", protocol="fipa-query")
"""

from .agent import Agent, Failure, Handler, Refuse, Reply, Responder
from .runtime import init, make_executor, own_launch_command, run, spin
from .transport.outbox import Outbox, inbox_topic, sample_text
from .transport.qos import EVENTS_QOS, INBOX_QOS, SERVICE_QOS, SNAPSHOT_QOS

__all__ = [
    "EVENTS_QOS",
    "INBOX_QOS",
    "SERVICE_QOS",
    "SNAPSHOT_QOS",
    "Agent",
    "Failure",
    "Handler",
    "Outbox",
    "Refuse",
    "Reply",
    "Responder",
    "inbox_topic",
    "init",
    "make_executor",
    "own_launch_command",
    "run",
    "sample_text",
    "spin",
]
