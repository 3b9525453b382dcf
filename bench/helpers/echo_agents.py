"""Responders for bench_gateway.py, each in its own process.

echo_agents.py ros-echo       # raw rclpy: /bench/ping -> /bench/pong
echo_agents.py agent NAME     # a framework agent that sends every message's content back to its sender
echo_agents.py acl-echo NAME  # a bare rclpy node, registered as NAME, answering each ACL line with string work only
echo_agents.py tcp-echo FILE  # raw asyncio line echo on a free loopback port, written to FILE
"""

from __future__ import annotations

import asyncio
import contextlib
import re
import sys
import time
from pathlib import Path

import rclpy
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String

from cf_commag.client import Agent, inbox_topic, make_executor
from cf_commag.convert import to_msg
from cf_commag.records import Record
from cf_commag.transport.qos import INBOX_QOS
from cf_interfaces.srv import Register
from cf_lang.acl import AclMessage, Performative

QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)


def run(node, kind: str) -> None:
    executor = make_executor(kind)
    executor.add_node(node)
    print("ready", flush=True)
    while rclpy.ok():
        executor.spin_once(timeout_sec=0.1)


def ros_echo(kind: str) -> None:
    node = rclpy.create_node(f"bench_ros_echo_{kind}")
    pub = node.create_publisher(String, f"/bench/pong_{kind}", QOS)
    node.create_subscription(String, f"/bench/ping_{kind}", pub.publish, QOS)
    run(node, kind)


def agent(name: str) -> None:
    node = rclpy.create_node(name)
    box = {}

    def echo(msg: AclMessage) -> None:
        box["agent"].send(AclMessage(Performative.INFORM, receivers=(msg.sender,), content=msg.content))

    box["agent"] = Agent(node, name=name, service_class="Monitoring", on_message=echo, commag=sys.argv[3])
    run(node, sys.argv[4])


def acl_echo(name: str) -> None:
    """What raw rclpy ping-pong's echo does, for ACL: the gateway's cost without an agent library's.

    Registered with the ComMAg like any component (the gateway routes only to
    known agents); each line's sender gets an inform back, found with one regex.
    """
    node = rclpy.create_node(name)
    register = node.create_client(Register, f"{sys.argv[3]}/register")
    record = to_msg(Record(name=name, service_class="Monitoring", lease_period=2.0))
    node.create_timer(
        0.5, lambda: register.service_is_ready() and register.call_async(Register.Request(component=record))
    )
    sender = re.compile(r":sender \(agent-identifier :name ([A-Za-z][A-Za-z0-9_]*)\)")
    publishers: dict[str, object] = {}
    me = f"(inform :sender (agent-identifier :name {name}) :receiver (set (agent-identifier :name "

    def on_inbox(msg: String) -> None:
        for line in msg.data.split("\n"):
            to = sender.search(line).group(1)
            pub = publishers.get(to)
            if pub is None:  # a new publisher: what it sends before discovery matches it is lost
                pub = publishers[to] = node.create_publisher(String, inbox_topic(to), INBOX_QOS)
                deadline = time.monotonic() + 5
                while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
                    time.sleep(0.01)
            pub.publish(String(data=me + to + ')) :content "ok")'))

    node.create_subscription(String, inbox_topic(name), on_inbox, INBOX_QOS)
    run(node, sys.argv[4])


async def tcp_echo(port_file: str) -> None:
    class Echo(asyncio.Protocol):
        def connection_made(self, transport):
            self.transport = transport

        def data_received(self, data):
            self.transport.write(data)

    server = await asyncio.get_running_loop().create_server(Echo, "127.0.0.1", 0)
    Path(port_file).write_text(f"{server.sockets[0].getsockname()[1]}\n")
    print("ready", flush=True)
    await server.serve_forever()


if __name__ == "__main__":
    with contextlib.suppress(KeyboardInterrupt):
        if sys.argv[1] == "tcp-echo":
            asyncio.run(tcp_echo(sys.argv[2]))
        else:
            rclpy.init()
            {"ros-echo": ros_echo, "agent": agent, "acl-echo": acl_echo}[sys.argv[1]](sys.argv[2])
