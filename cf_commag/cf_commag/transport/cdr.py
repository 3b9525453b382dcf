"""A ``std_msgs/String`` in its serialized (CDR) form, ROS-free.

Inbox samples are published and taken serialized (rclpy's ``publish(bytes)``
and ``raw=True`` subscriptions): that skips building a Python message object
on each side, about 12 µs per publish or take here (bench/bench_gateway.py
and docs/performance.md). What goes on the wire is the same: any ROS tool or
node sees an ordinary ``std_msgs/String``.

The layout is a 4-byte encapsulation header (``00 01 00 00``: plain CDR,
little-endian), the length of the string with its terminating NUL as a
uint32, the UTF-8 bytes, and the NUL. Like rclpy, a string ends at its first
NUL and invalid UTF-8 is read with replacement characters.
"""

from __future__ import annotations

_HEADER_LE = b"\x00\x01\x00\x00"
_from_bytes = int.from_bytes


def to_cdr(text: str) -> bytes:
    """The serialized ``std_msgs/String`` holding ``text``."""
    if "\x00" in text:
        text = text[: text.index("\x00")]
    data = text.encode()
    return _HEADER_LE + (len(data) + 1).to_bytes(4, "little") + data + b"\x00"


def from_cdr(sample: bytes) -> str:
    """The text of a serialized ``std_msgs/String``; ValueError for an encoding this does not read."""
    kind = sample[:2]
    if kind == b"\x00\x01":
        size = _from_bytes(sample[4:8], "little")
    elif kind == b"\x00\x00":
        size = _from_bytes(sample[4:8], "big")
    else:
        raise ValueError(f"encapsulation {kind.hex()} is not plain CDR")
    if size == 0 or len(sample) < 8 + size:
        raise ValueError("truncated std_msgs/String")
    data = sample[8 : 7 + size]
    if b"\x00" in data:
        data = data[: data.index(b"\x00")]
    return data.decode("utf-8", "replace")
