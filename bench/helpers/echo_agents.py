"""Responders for bench_gateway.py, each in its own process.

echo_agents.py ros-echo       # raw rclpy: /bench/ping -> /bench/pong
echo_agents.py agent NAME     # a framework agent that sends every message's content back to its sender
echo_agents.py tcp-echo FILE  # raw asyncio line echo on a free loopback port, written to FILE
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
from pathlib import Path

import rclpy
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String

from cf_commag.client import Agent, make_executor
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
            ros_echo(sys.argv[2]) if sys.argv[1] == "ros-echo" else agent(sys.argv[2])
