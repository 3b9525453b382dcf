"""A fuzzer for the gateway over real TCP: generated and mutated lines, many connections.

    python test/helpers/fuzz_gateway.py --port 7700 --lines 1000000 --seed 1 [--concurrency 16]

Every connection sends a batch of lines (random bytes, truncated and unbalanced S-expressions,
invalid UTF-8, NUL bytes, deep nesting, huge numbers, odd Unicode, valid commands with wrong
types, valid commands, ACL messages to itself and to unknown agents), then ``(ping)``, and
reads until ``(pong)``. What it checks, per connection:

- no answer says ``internal error``;
- the connection either answers the final ping (and every non-blank line before it got at
  least one answer line), or the gateway closed it after a final ``(error ...)`` line (a
  framing violation, e.g. a line over the limit) or after ``(bye)``.

It prints the seed and a summary; the exit code is 1 if any connection broke a rule.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import random
import sys
import time
from dataclasses import dataclass, field

CLASSES = ["Kick", "Action", "WorldModel", "PlayerDecision", "Shoot", "Service", "Nope", "kick"]
ODD = ["\u202e", "\u200b", "\u2028", "\u0301", "\U0001f600", "\ufeff", "\uffff", "é", "\x7f", "\t"]
NUMBERS = ["0", "-1", "1e999", "-1e999", "nan", "1" + "0" * 400, "99999999999999999999", "3.5", "+7", ".5", "0x10"]
TEAMS = ["blue", "a", '""', "7"]
VALUES = [*NUMBERS, '"x"', '""', "true", "t", "nil", "(a b)", "()", '"\\u0000"', '"\\ud800"', '"a\\"b"', "blue"]


@dataclass
class Outcome:
    connections: int = 0
    lines: int = 0
    answered: int = 0  # connections whose final ping was answered
    closed_with_error: int = 0  # closed by the gateway after a final (error ...) line
    closed_after_bye: int = 0
    violations: list[str] = field(default_factory=list)
    internal_errors: int = 0
    answers: int = 0


def _name(rng: random.Random, serial: int) -> str:
    return f"fz{serial}_{rng.randrange(10**6)}"


def valid_lines(rng: random.Random, me: str) -> list[str]:
    """Commands as a foreign agent writes them, some with wrong values."""
    cls = rng.choice(CLASSES)
    other = rng.choice([me, "nobody_here", "x" * 120, "a__b"])
    lines = [
        f"(register :service-class {cls} :team {rng.choice(TEAMS)} :player {rng.choice(VALUES)})",
        f"(register :service-class {cls} :lease {rng.choice(VALUES)} :port {rng.choice(VALUES)})",
        f"(register :service-class {cls} :team {rng.choice(VALUES)} :address {rng.choice(VALUES)})",
        f"(lookup :service-class {cls} :direction {rng.choice(['general', 'specific', 'both', 'exact', 'up', '7'])})",
        f"(lookup :service-class {cls} :player {rng.choice(VALUES)} :max {rng.choice(VALUES)} "
        f":include-suspect {rng.choice(VALUES)} :team {rng.choice(VALUES)})",
        f"(events :on {rng.choice(['true', 'false', '1'])})",
        f'(request :receiver (set (agent-identifier :name {other})) :content "(val Game time)" '
        f":protocol fipa-query :conversation-id c{rng.randrange(100)} :reply-by {rng.choice(['20261122T101010123Z', 'x', '0'])})",
        f"(inform :receiver (set (agent-identifier :name {me})) :content {rng.choice(VALUES)})",
        f'(query-ref :sender (agent-identifier :name {rng.choice([me, "someone"])}) :receiver {other} :content "(val Ball)")',
        f"(hello :name {me})",
        "(frobnicate :x 1)",
        '(register :service-class Kick :launch-command (set "/bin/sh" "-c" "true"))',
    ]
    return rng.sample(lines, rng.randint(1, len(lines)))


def mutate(rng: random.Random, line: str) -> bytes:
    """One mutation of a line, as bytes (may be invalid UTF-8)."""
    data = line.encode()
    kind = rng.randrange(12)
    if kind == 0 and data:  # truncate
        return data[: rng.randrange(len(data))]
    if kind == 1:  # unbalanced
        return data + b")" * rng.randint(1, 5) if rng.random() < 0.5 else b"(" * rng.randint(1, 5) + data
    if kind == 2 and data:  # a random byte somewhere
        i = rng.randrange(len(data))
        return data[:i] + bytes([rng.randrange(256)]) + data[i + 1 :]
    if kind == 3:  # invalid UTF-8
        return data + rng.choice([b"\xff", b"\xc3", b"\xed\xa0\x80", b"\x80\x80", b"\xf8\x88\x80\x80\x80"])
    if kind == 4:  # NUL bytes
        return data.replace(b" ", b"\0", rng.randint(1, 3))
    if kind == 5:  # deep nesting
        depth = rng.choice([31, 33, 100, 5000])
        return b"(" * depth + b"x" + b")" * depth
    if kind == 6:  # odd Unicode in the middle
        i = rng.randrange(len(line) + 1)
        return (line[:i] + rng.choice(ODD) + line[i:]).encode("utf-8", "surrogatepass")
    if kind == 7:  # random bytes
        return bytes(rng.randrange(1, 256) for _ in range(rng.randint(1, 200))).replace(b"\n", b" ")
    if kind == 8:  # a string left open
        return data + b' "unterminated'
    if kind == 9:  # escapes
        return data + rng.choice([b' "\\', b' "\\x"', b' "\\u12"', b' "\\uDFFF"'])
    if kind == 10:  # a carriage return or a lone colon
        return data.replace(b" :", b" \r:", 1) if rng.random() < 0.5 else data + b" :"
    return data


def connection_lines(rng: random.Random, serial: int, size: int) -> tuple[list[bytes], str]:
    me = _name(rng, serial)
    out: list[bytes] = []
    if rng.random() < 0.9:
        out.append(f"(hello :name {me})".encode())
    while len(out) < size:
        for line in valid_lines(rng, me):
            if rng.random() < 0.6:
                out.append(mutate(rng, line))
            elif "bye" not in line:
                out.append(line.encode())
    if rng.random() < 0.02:  # a framing violation: a line over the limit
        out.insert(rng.randrange(len(out) + 1), b"(" + b"x" * 70_000 + b")")
    if rng.random() < 0.05:
        out.append(b"(bye)")
    return out[: size + 2], me


async def run_connection(host: str, port: int, lines: list[bytes], me: str, timeout: float, outcome: Outcome) -> None:
    outcome.connections += 1
    outcome.lines += len(lines)
    reader, writer = await asyncio.open_connection(host, port, limit=1 << 20)
    received: list[str] = []
    try:
        writer.write(b"".join(line.replace(b"\n", b" ") + b"\n" for line in lines) + b"(ping)\n")
        await writer.drain()
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                outcome.violations.append(f"no (pong) and no close within {timeout} s; last: {received[-1:]}")
                return
            raw = await asyncio.wait_for(reader.readline(), left)
            if not raw:  # closed by the gateway
                last = received[-1] if received else ""
                if last.startswith("(error"):
                    outcome.closed_with_error += 1
                elif last.startswith("(bye"):
                    outcome.closed_after_bye += 1
                else:
                    outcome.violations.append(f"closed without a final error line; last: {last[:200]!r}")
                return
            text = raw.decode("utf-8", "replace").rstrip("\n")
            received.append(text)
            outcome.answers += 1
            if "internal error" in text:
                outcome.internal_errors += 1
                outcome.violations.append(f"internal error: {text[:200]}")
            if text == "(pong)":
                outcome.answered += 1
                # Messages to itself are relayed through DDS and may come back after the pong.
                asked = sum(1 for line in lines if line.strip(b" \t\r") and me.encode() + b")" not in line)
                asked -= sum(1 for line in lines if b":receiver " + me.encode() in line)
                if len(received) - 1 < asked:
                    outcome.violations.append(f"{asked} lines, {len(received) - 1} answers")
                return
    except ConnectionResetError as exc:
        # The gateway half-closes after its final line and drops what still comes, so that
        # no reset destroys that line. A reset after the line was read is still a close.
        if received and received[-1].startswith("(error"):
            outcome.closed_with_error += 1
        else:
            outcome.violations.append(f"{type(exc).__name__}: {exc}; last: {received[-1:]}")
    except (ConnectionError, TimeoutError) as exc:
        outcome.violations.append(f"{type(exc).__name__}: {exc}; last: {received[-1:]}")
    finally:
        writer.close()
        with contextlib.suppress(ConnectionError, OSError):
            await writer.wait_closed()


async def fuzz(
    host: str, port: int, total_lines: int, seed: int, concurrency: int = 16, timeout: float = 60.0
) -> Outcome:
    rng = random.Random(seed)
    outcome = Outcome()
    serial = 0
    pending: set[asyncio.Task] = set()
    while outcome.lines < total_lines or pending:
        while outcome.lines < total_lines and len(pending) < concurrency:
            serial += 1
            lines, me = connection_lines(rng, serial, rng.choice([5, 20, 80, 200]))
            pending.add(asyncio.ensure_future(run_connection(host, port, lines, me, timeout, outcome)))
        done, pending = await asyncio.wait(pending, return_when=asyncio.FIRST_COMPLETED)
        for task in done:
            if task.exception() is not None:
                outcome.violations.append(f"client error: {task.exception()!r}")
    return outcome


async def churn(host: str, port: int, count: int, seed: int, concurrency: int = 16) -> int:
    """``count`` agents that come and go: hello, register, lookup, then bye or a dropped connection.

    Returns how many of them went through without a failure answer.
    """
    rng = random.Random(seed)
    ok = 0

    async def one(serial: int) -> None:
        nonlocal ok
        reader, writer = await asyncio.open_connection(host, port, limit=1 << 20)
        name = f"ch{seed}_{serial}"
        lines = [
            f"(hello :name {name})",
            "(register :service-class Kick :team churn :lease 0.5)",
            "(lookup :service-class Kick)",
        ]
        writer.write("".join(f"{line}\n" for line in lines).encode())
        answers = [await asyncio.wait_for(reader.readline(), 30) for _ in lines]
        if all(a.startswith((b"(welcome", b"(registered", b"(providers")) for a in answers):
            ok += 1
        if rng.random() < 0.5:
            writer.write(b"(bye)\n")
            await writer.drain()
            await asyncio.wait_for(reader.readline(), 30)
        writer.close()
        with contextlib.suppress(ConnectionError, OSError):
            await writer.wait_closed()

    pending: set[asyncio.Task] = set()
    for serial in range(count):
        if len(pending) >= concurrency:
            _, pending = await asyncio.wait(pending, return_when=asyncio.FIRST_COMPLETED)
        pending.add(asyncio.ensure_future(one(serial)))
    for result in await asyncio.gather(*pending, return_exceptions=True):
        if isinstance(result, BaseException):
            print(f"churn client failed: {result!r}", flush=True)
    return ok


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--lines", type=int, default=100_000)
    ap.add_argument("--seed", type=int, default=int(time.time()))
    ap.add_argument("--concurrency", type=int, default=16)
    ap.add_argument("--churn", type=int, default=0, help="instead: this many agents that come and go")
    args = ap.parse_args()
    if args.churn:
        done = asyncio.run(churn(args.host, args.port, args.churn, args.seed, args.concurrency))
        print(json.dumps({"churned": args.churn, "ok": done}))
        return 0 if done == args.churn else 1
    print(f"fuzzing {args.host}:{args.port} with {args.lines} lines, seed {args.seed}", flush=True)
    started = time.monotonic()
    outcome = asyncio.run(fuzz(args.host, args.port, args.lines, args.seed, args.concurrency))
    summary = {k: v for k, v in vars(outcome).items() if k != "violations"}
    summary["violations"] = len(outcome.violations)
    summary["seconds"] = round(time.monotonic() - started, 1)
    print(json.dumps(summary))
    for v in outcome.violations[:20]:
        print("  ", v[:300])
    return 1 if outcome.violations else 0


if __name__ == "__main__":
    sys.exit(main())
