"""Round trip and throughput through the gateway, side by side with raw rclpy and raw TCP.

- raw TCP echo (asyncio server, 1 client): the floor for anything over a socket;
- raw rclpy ping-pong between two processes (std_msgs/String, reliable);
- TCP agent -> gateway -> ROS agent (another process) -> gateway -> TCP agent, with two ROS agents:
  a bare rclpy node answering with string work only (like the raw echo: the gateway's own cost)
  and a framework Agent (cf_commag.client: reads, dispatches and writes every message);
- sustained throughput through the gateway with many messages in flight, every one counted;
- 200 concurrent TCP clients doing round trips.

    python bench/bench_gateway.py [--rounds 2000] [--executor events|single]
"""

from __future__ import annotations

import argparse
import asyncio
import socket
import statistics
import sys
import tempfile
import time
import uuid
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "test"))
import rclpy  # noqa: E402
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy  # noqa: E402
from std_msgs.msg import String  # noqa: E402

from cf_commag.client import make_executor  # noqa: E402
from cf_commag.gateway_client import GatewayClient  # noqa: E402
from cf_system import Processes, start_commag, start_gateway  # noqa: E402

QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)
PAYLOAD = "x" * 60


def pct(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


class RawTcp:
    """A line echo in another process (asyncio protocol) and one blocking client: the socket floor."""

    def __init__(self, port: int):
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.file = self.sock.makefile("rwb")

    def rounds(self, n: int) -> list[float]:
        out = []
        for _ in range(n):
            t0 = time.perf_counter()
            self.file.write(PAYLOAD.encode() + b"\n")
            self.file.flush()
            self.file.readline()
            out.append((time.perf_counter() - t0) * 1e6)
        return out

    def close(self) -> None:
        self.sock.close()


class RawRclpy:
    """Ping-pong with the raw rclpy echo process (std_msgs/String, reliable)."""

    def __init__(self, kind: str):
        self.node = rclpy.create_node(f"bench_pinger_{kind}")
        self.executor = make_executor(kind)
        self.executor.add_node(self.node)
        self.got: list = []
        self.node.create_subscription(String, f"/bench/pong_{kind}", self.got.append, QOS)
        self.pub = self.node.create_publisher(String, f"/bench/ping_{kind}", QOS)
        deadline = time.monotonic() + 20
        while self.pub.get_subscription_count() == 0 and time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.05)
        for _ in range(20):  # warm-up and matching
            self.pub.publish(String(data=PAYLOAD))
            self.executor.spin_once(timeout_sec=0.5)
        time.sleep(0.5)
        for _ in range(50):
            self.executor.spin_once(timeout_sec=0.01)
        self.got.clear()

    def rounds(self, n: int) -> list[float]:
        out = []
        for _ in range(n):
            t0 = time.perf_counter()
            self.pub.publish(String(data=PAYLOAD))
            while not self.got:
                self.executor.spin_once(timeout_sec=1.0)
            self.got.pop()
            out.append((time.perf_counter() - t0) * 1e6)
        return out

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def line_to(receiver: str, i: int) -> bytes:
    return f'(inform :receiver (set (agent-identifier :name {receiver})) :content "{i}")\n'.encode()


class ThroughGateway:
    """Round trips TCP agent -> gateway -> ROS agent -> gateway -> TCP agent."""

    def __init__(self, port: int, name: str, echo: str):
        self.echo = echo
        self.gw = GatewayClient("127.0.0.1", port, name=name)
        self.gw.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        for i in range(20):  # warm-up: discovery of the echo agent's inbox
            self.gw.send_line(line_to(echo, i).decode().strip())
            self.gw.receive()

    def rounds(self, n: int) -> list[float]:
        out = []
        f, read_line = self.gw.file, self.gw.read_line
        for i in range(n):
            t0 = time.perf_counter()
            f.write(line_to(self.echo, i))
            f.flush()
            read_line()
            out.append((time.perf_counter() - t0) * 1e6)
        return out

    def close(self) -> None:
        self.gw.close()


def gateway_throughput(port: int, name: str, echo: str, total: int, in_flight: int) -> tuple[float, int]:
    gw = GatewayClient("127.0.0.1", port, name=name)
    for i in range(20):
        gw.send_line(line_to(echo, i).decode().strip())
        gw.receive()
    sock = gw.sock
    received = 0
    buf = b""
    sent = 0
    t0 = time.perf_counter()
    while received < total:
        if sent < total and sent - received < in_flight:
            burst = min(total, received + in_flight) - sent  # pipelined: one send for the whole window
            sock.sendall(b"".join(line_to(echo, i) for i in range(sent, sent + burst)))
            sent += burst
        chunk = sock.recv(1 << 20)
        if not chunk:
            break
        buf += chunk
        received += buf.count(b"\n")
        buf = buf[buf.rfind(b"\n") + 1 :]
    rate = received / (time.perf_counter() - t0)
    gw.close()
    return rate, total - received


def many_clients(port: int, tag: str, echo: str, clients: int, rounds: int) -> tuple[float, list[float]]:
    """``clients`` connections, each doing ``rounds`` round trips one after the other, all at once.

    The clients share one asyncio thread, so the benchmark process is not the
    bottleneck (200 blocking threads contending for one GIL were).
    """

    async def run() -> tuple[float, list[float]]:
        conns = []
        for i in range(clients):
            reader, writer = await asyncio.open_connection("127.0.0.1", port)
            writer.write(f"(hello :name c{i}_{tag})\n".encode())
            assert (await reader.readline()).startswith(b"(welcome")
            conns.append((reader, writer))
        for _, writer in conns:  # warm-up: each inbox is matched
            writer.write(line_to(echo, 0))
        for reader, _ in conns:
            await asyncio.wait_for(reader.readline(), 30)
        latencies: list[float] = []

        async def client(reader, writer) -> None:
            for i in range(rounds):
                t0 = time.perf_counter()
                writer.write(line_to(echo, i))
                await reader.readline()
                latencies.append((time.perf_counter() - t0) * 1e6)

        t0 = time.perf_counter()
        await asyncio.gather(*(client(r, w) for r, w in conns))
        rate = clients * rounds / (time.perf_counter() - t0)
        for _, writer in conns:
            writer.write(b"(bye)\n")
            writer.close()
        return rate, latencies

    return asyncio.run(run())


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=2000)
    parser.add_argument(
        "--executor",
        choices=["events", "single"],
        default="events",
        help="the rclpy executor of every ROS process in the run (gateway, agents, baseline)",
    )
    args = parser.parse_args()
    tag = "g" + uuid.uuid4().hex[:8]
    tmp = Path(tempfile.mkdtemp(prefix="cf-bench-gw-"))
    procs = Processes(tag, tmp)
    rclpy.init()
    try:
        start_commag(procs, tag, tmp)
        port_file = tmp / "port"
        kind = args.executor
        start_gateway(procs, tag, port_file, f"executor:={kind}")
        echo = f"echo_{tag}"
        helper = str(HERE / "helpers/echo_agents.py")
        procs.start([sys.executable, helper, "agent", echo, f"/commag_{tag}", kind], "echo")
        bare = f"bare_{tag}"
        procs.start([sys.executable, helper, "acl-echo", bare, f"/commag_{tag}", kind], "acl-echo")
        procs.start([sys.executable, helper, "ros-echo", kind], "ros-echo")
        tcp_port_file = tmp / "tcp-echo-port"
        procs.start([sys.executable, helper, "tcp-echo", str(tcp_port_file)], "tcp-echo")
        deadline = time.monotonic() + 30
        while not (port_file.exists() and all("ready" in procs.log(n) for n in ("echo", "acl-echo", "tcp-echo"))):
            if time.monotonic() > deadline:
                raise RuntimeError("the gateway, an echo agent or the TCP echo did not start")
            time.sleep(0.1)
        port = int(port_file.read_text())
        time.sleep(2.0)  # the echo agent registers; the gateway's registry cache learns it

        # The three round trips in turns, block by block, so that the machine's
        # drift (2 shared cores) falls on all of them alike.
        variants = {
            "raw TCP echo, 2 processes (asyncio)": RawTcp(int(tcp_port_file.read_text())),
            "raw rclpy ping-pong, 2 processes": RawRclpy(kind),
            "TCP agent -> gateway -> bare rclpy ACL echo -> back": ThroughGateway(port, f"rtb_{tag}", bare),
            "TCP agent -> gateway -> framework Agent -> back": ThroughGateway(port, f"rt_{tag}", echo),
        }
        samples: dict[str, list[float]] = {label: [] for label in variants}
        block_medians: dict[str, list[float]] = {label: [] for label in variants}
        blocks = 30
        for _ in range(blocks):
            for label, variant in variants.items():
                block = variant.rounds(args.rounds // blocks)
                samples[label] += block
                block_medians[label].append(statistics.median(block))
        for variant in variants.values():
            variant.close()
        # The ratio is taken block by block (each variant's median against raw rclpy's
        # in the same block, seconds apart), then the median of those: the shared
        # machine's drift over the run falls out of it.
        raw = block_medians["raw rclpy ping-pong, 2 processes"]
        print(f"executor in every ROS process: {kind}\n")
        print("| round trip, 60 B payload | p50 µs | p99 µs | p50 vs raw rclpy (median of 30 blocks) |")
        print("|---|---:|---:|---:|")
        for label, v in samples.items():
            ratio = statistics.median(m / r for m, r in zip(block_medians[label], raw, strict=True))
            print(f"| {label} | {pct(v, 0.5):.0f} | {pct(v, 0.99):.0f} | {ratio:.2f}x |")

        print("\n| sustained, through the gateway | messages | in flight | msg/s | lost |")
        print("|---|---:|---:|---:|---:|")
        for in_flight in (32, 256):
            rate, lost = gateway_throughput(port, f"tp{in_flight}_{tag}", echo, 20_000, in_flight)
            print(f"| TCP -> ROS agent -> TCP | 20000 | {in_flight} | {rate:,.0f} | {lost} |")

        rate, lat = many_clients(port, tag, echo, 200, 50)
        print("\n| concurrent clients | round trips each | total msg/s | p50 µs | p99 µs |")
        print("|---:|---:|---:|---:|---:|")
        print(f"| 200 | 50 | {rate:,.0f} | {pct(lat, 0.5):.0f} | {pct(lat, 0.99):.0f} |")
    finally:
        rclpy.try_shutdown()
        procs.kill_all()


if __name__ == "__main__":
    main()
