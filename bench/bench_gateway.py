"""Round trip and throughput through the gateway, side by side with raw rclpy and raw TCP.

- raw TCP echo (asyncio server, 1 client): the floor for anything over a socket;
- raw rclpy ping-pong between two processes (std_msgs/String, reliable);
- TCP agent -> gateway -> ROS agent (another process) -> gateway -> TCP agent;
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
import threading
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


def raw_tcp(rounds: int) -> list[float]:
    loop = asyncio.new_event_loop()

    async def handle(reader, writer):
        while line := await reader.readline():
            writer.write(line)

    server = loop.run_until_complete(asyncio.start_server(handle, "127.0.0.1", 0))
    port = server.sockets[0].getsockname()[1]
    threading.Thread(target=loop.run_forever, daemon=True).start()
    sock = socket.create_connection(("127.0.0.1", port))
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    f = sock.makefile("rwb")
    out = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        f.write(PAYLOAD.encode() + b"\n")
        f.flush()
        f.readline()
        out.append((time.perf_counter() - t0) * 1e6)
    sock.close()
    loop.call_soon_threadsafe(loop.stop)
    return out


def raw_rclpy(rounds: int, kind: str) -> list[float]:
    node = rclpy.create_node(f"bench_pinger_{kind}")
    executor = make_executor(kind)
    executor.add_node(node)
    got = []
    node.create_subscription(String, f"/bench/pong_{kind}", got.append, QOS)
    pub = node.create_publisher(String, f"/bench/ping_{kind}", QOS)
    deadline = time.monotonic() + 20
    while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)
    for _ in range(20):  # warm-up and matching
        pub.publish(String(data=PAYLOAD))
        executor.spin_once(timeout_sec=0.5)
    time.sleep(0.5)
    for _ in range(50):
        executor.spin_once(timeout_sec=0.01)
    got.clear()
    out = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        pub.publish(String(data=PAYLOAD))
        while not got:
            executor.spin_once(timeout_sec=1.0)
        got.pop()
        out.append((time.perf_counter() - t0) * 1e6)
    executor.shutdown()
    node.destroy_node()
    return out


def line_to(receiver: str, i: int) -> bytes:
    return f'(inform :receiver (set (agent-identifier :name {receiver})) :content "{i}")\n'.encode()


def gateway_round_trips(port: int, name: str, echo: str, rounds: int) -> list[float]:
    gw = GatewayClient("127.0.0.1", port, name=name)
    gw.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    for i in range(20):  # warm-up: discovery of the echo agent's inbox
        gw.send_line(line_to(echo, i).decode().strip())
        gw.receive()
    out = []
    for i in range(rounds):
        t0 = time.perf_counter()
        gw.file.write(line_to(echo, i))
        gw.file.flush()
        gw.file.readline()
        out.append((time.perf_counter() - t0) * 1e6)
    gw.close()
    return out


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
    latencies: list[float] = []
    lock = threading.Lock()
    conns = [GatewayClient("127.0.0.1", port, name=f"c{i}_{tag}") for i in range(clients)]
    for c in conns:  # warm-up each inbox
        c.send_line(line_to(echo, 0).decode().strip())
    for c in conns:
        c.receive()
    barrier = threading.Barrier(clients + 1)

    def run(c: GatewayClient) -> None:
        mine = []
        barrier.wait()
        for i in range(rounds):
            t0 = time.perf_counter()
            c.file.write(line_to(echo, i))
            c.file.flush()
            c.file.readline()
            mine.append((time.perf_counter() - t0) * 1e6)
        with lock:
            latencies.extend(mine)

    threads = [threading.Thread(target=run, args=(c,)) for c in conns]
    for t in threads:
        t.start()
    barrier.wait()
    t0 = time.perf_counter()
    for t in threads:
        t.join()
    rate = clients * rounds / (time.perf_counter() - t0)
    for c in conns:
        c.close()
    return rate, latencies


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
        procs.start([sys.executable, helper, "ros-echo", kind], "ros-echo")
        deadline = time.monotonic() + 30
        while not (port_file.exists() and "ready" in procs.log("echo")) and time.monotonic() < deadline:
            time.sleep(0.1)
        port = int(port_file.read_text())
        time.sleep(2.0)  # the echo agent registers; the gateway's registry cache learns it

        tcp = raw_tcp(args.rounds)
        ros = raw_rclpy(args.rounds, kind)
        gw = gateway_round_trips(port, f"rt_{tag}", echo, args.rounds)
        print(f"executor in every ROS process: {kind}\n")
        print("| round trip, 60 B payload | p50 µs | p99 µs | p50 vs raw rclpy |")
        print("|---|---:|---:|---:|")
        base = statistics.median(ros)
        for label, v in (
            ("raw TCP echo (asyncio)", tcp),
            ("raw rclpy ping-pong, 2 processes", ros),
            ("TCP agent -> gateway -> ROS agent -> back", gw),
        ):
            print(f"| {label} | {pct(v, 0.5):.0f} | {pct(v, 0.99):.0f} | {statistics.median(v) / base:.2f}x |")

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
