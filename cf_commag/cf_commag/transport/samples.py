"""How ACL messages are packed into inbox samples (ROS-free).

An inbox sample (``std_msgs/String`` on ``/cf/agents/<name>/inbox``) carries
one or more ACL messages, one per line. The writer (``cf_lang.dumps``) escapes
newlines inside strings, so a line is always one whole message. Senders pack
what they have ready into one sample because a DDS sample costs tens of
microseconds to publish and to take, whatever it holds.
"""

from __future__ import annotations

from collections.abc import Iterable

SAMPLE_MAX_BYTES = 64 * 1024
# Small enough that the sender, the gateway and the receiver work on different
# samples at once (a pipeline); measured with bench/bench_gateway.py: 16 -> 15.7k,
# 32 -> 19k, 64 -> 18k msg/s with 256 messages in flight.
SAMPLE_MAX_MESSAGES = 32


def pack_lines(texts: list[str]) -> Iterable[str]:
    """Join messages into as few samples as the sample limits allow, in order."""
    return (sample for _, sample in pack_counted(texts))


def pack_counted(texts: list[str]) -> Iterable[tuple[int, str]]:
    """Like :func:`pack_lines`, with how many of the texts each sample holds."""
    start = size = 0
    for i, text in enumerate(texts):
        if i > start and (size + len(text) > SAMPLE_MAX_BYTES or i - start >= SAMPLE_MAX_MESSAGES):
            yield i - start, "\n".join(texts[start:i])
            start, size = i, 0
        size += len(text) + 1
    if start < len(texts):
        yield len(texts) - start, "\n".join(texts[start:])


def sample_messages(data: str) -> list[str]:
    """The ACL message texts in one sample (blank lines skipped)."""
    if "\n" not in data:
        return [data]
    return [line for line in data.split("\n") if line.strip()]
