"""Agents' inboxes on DDS: topic names, sample text, and the Outbox that publishes to them.

An inbox is ``/cf/agents/<name>/inbox``: ``std_msgs/String`` samples holding FIPA-ACL text, one
message per line (several per sample: see samples.py), published and taken serialized (cdr.py).
"""

from __future__ import annotations

import contextlib
import threading
import time

from rclpy._rclpy_pybind11 import InvalidHandle, RCLError
from rclpy.duration import Duration
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.node import Node
from rclpy.serialization import deserialize_message
from std_msgs.msg import String

from .cdr import from_cdr, to_cdr
from .qos import INBOX_QOS
from .samples import pack_counted, pack_lines


def sample_text(sample: bytes) -> str:
    """The text of an inbox sample taken serialized (``raw=True``)."""
    try:
        return from_cdr(sample)
    except ValueError:  # an encapsulation string_cdr does not read: rclpy does
        return deserialize_message(sample, String).data


def inbox_topic(name: str) -> str:
    """The topic on which agent ``name`` receives its ACL messages."""
    return f"/cf/agents/{name}/inbox"


class Outbox:
    """Publishers to agents' inboxes, one per receiver.

    A new publisher is not matched with the receiver's subscription at once
    (DDS discovery takes a moment) and what it publishes before that is lost.
    So messages for a receiver are held until its inbox is matched, then sent
    in order by :meth:`flush` (call it from a timer). Messages held longer
    than ``hold_seconds`` are dropped and counted in ``undeliverable``.

    A receiver that is alive but takes nothing (hung, stopped) fills its
    queue in DDS; then a publish blocks for 100 ms and fails. Its messages
    are held the same way, and only one publish per ``retry_seconds`` is
    tried for it, so that the sender's thread is not stalled message after
    message.
    """

    def __init__(self, node: Node, *, hold_seconds: float = 10.0, retry_seconds: float = 0.5):
        self._node = node
        self._hold = hold_seconds
        self._retry = retry_seconds
        self._stalled: dict[str, float] = {}  # receiver -> when to try publishing to it again
        self._publishers: dict[str, object] = {}
        self._held: dict[str, list[tuple[float, str]]] = {}
        self._matched: dict[str, object] = {}  # receivers whose inbox was seen matched: publish at once
        self._lock = threading.Lock()  # send() may run on another thread than flush()
        self._batch: dict[str, list[str]] | None = None
        self.undeliverable = 0

    def send(self, receiver: str, text: str) -> None:
        """Publish ``text`` (one or more ACL messages, one per line) to ``receiver``'s inbox.

        Inside :meth:`batch`, messages for the same receiver are collected and
        go out together as one sample when the batch ends.
        """
        if self._batch is not None:
            with self._lock:
                if self._batch is not None:
                    self._batch.setdefault(receiver, []).append(text)
                    return
        self._send(receiver, text)

    @contextlib.contextmanager
    def batch(self):
        """Collect what is sent inside the block; publish one sample per receiver at its end.

        Each DDS sample costs tens of microseconds to publish and to take, whatever
        its size, so a burst of replies goes out as one sample per receiver.
        Blocks may nest; the outermost one publishes.
        """
        with self._lock:
            outer = self._batch is None
            if outer:
                self._batch = {}
        try:
            yield self
        finally:
            if outer:
                with self._lock:
                    collected, self._batch = self._batch, None
                for receiver, texts in collected.items():
                    for chunk in pack_lines(texts):
                        self._send(receiver, chunk)

    def _send(self, receiver: str, text: str) -> None:
        pub = self._matched.get(receiver)
        if pub is not None:
            try:
                pub.publish(to_cdr(text))
                return
            except RCLError:
                self._stall(receiver, [(time.monotonic(), text)])
                return
            except InvalidHandle:  # released by retain() meanwhile: make a new one below
                pass
        with self._lock:
            pub = self._publishers.get(receiver)
            if pub is None:
                # The matched event tells when the receiver's inbox goes away (the
                # receiver died): later messages are held then. Asking DDS for the
                # match count on every message instead costs a lock on its side.
                events = PublisherEventCallbacks(matched=lambda status: self._on_matched(receiver, status))
                pub = self._node.create_publisher(String, inbox_topic(receiver), INBOX_QOS, event_callbacks=events)
                self._publishers[receiver] = pub
            held = self._held.get(receiver)
            if held is None and pub.get_subscription_count() > 0:  # (again) matched: send at once
                try:
                    pub.publish(to_cdr(text))
                except RCLError:
                    self._stall_locked(receiver, [(time.monotonic(), text)])
                    return
                self._matched[receiver] = pub
                return
            # Not matched (yet, or any more: the receiver died and may be relaunched): hold it.
            self._matched.pop(receiver, None)
            self._held.setdefault(receiver, []).append((time.monotonic(), text))

    def retain(self, receivers: set[str] | frozenset[str]) -> None:
        """Release the publishers of receivers not in ``receivers`` (and with nothing held for them).

        A gateway relays to whoever registers; without this, every agent that ever came and
        went would keep a publisher (and its DDS writer) in the gateway for ever.
        """
        with self._lock:
            gone = [r for r in self._publishers if r not in receivers and r not in self._held]
            for receiver in gone:
                self._matched.pop(receiver, None)
                self._stalled.pop(receiver, None)
                self._node.destroy_publisher(self._publishers.pop(receiver))

    def _stall(self, receiver: str, messages: list[tuple[float, str]]) -> None:
        with self._lock:
            self._stall_locked(receiver, messages)

    def _stall_locked(self, receiver: str, messages: list[tuple[float, str]]) -> None:
        """The receiver's queue is full: hold these (in order, after what waits) and retry later."""
        self._matched.pop(receiver, None)
        self._held.setdefault(receiver, []).extend(messages)
        self._stalled[receiver] = time.monotonic() + self._retry
        self._node.get_logger().warning(
            f"{receiver} takes no messages (hung?): holding them for up to {self._hold:.0f} s",
            throttle_duration_sec=5.0,
        )

    def _on_matched(self, receiver: str, status) -> None:
        if status.current_count == 0:
            self._matched.pop(receiver, None)

    def flush(self) -> None:
        """Send held messages whose receiver is now matched; drop the ones held too long."""
        if not self._held:
            return
        with self._lock:
            self._flush_locked()

    def _flush_locked(self) -> None:
        now = time.monotonic()
        for receiver, held in list(self._held.items()):
            pub = self._publishers[receiver]
            if self._stalled.get(receiver, 0.0) <= now and pub.get_subscription_count() > 0:
                self._stalled.pop(receiver, None)
                sent = 0
                try:
                    for count, text in pack_counted([text for _, text in held]):
                        pub.publish(to_cdr(text))
                        sent += count
                except RCLError:  # still full: keep the rest, in order
                    del self._held[receiver]
                    self._stall_locked(receiver, held[sent:])
                    continue
                del self._held[receiver]
                self._matched[receiver] = pub
            elif now - held[0][0] > self._hold:
                fresh = [(t, m) for t, m in held if now - t <= self._hold]
                dropped = sum(m.count("\n") + 1 for t, m in held if now - t > self._hold)
                self.undeliverable += dropped
                self._node.get_logger().warning(
                    f"{receiver!r} took no messages for {self._hold:.0f} s (no inbox, or hung):"
                    f" {dropped} message(s) dropped",
                    throttle_duration_sec=5.0,
                )
                if fresh:
                    self._held[receiver] = fresh
                else:
                    del self._held[receiver]

    @property
    def held(self) -> int:
        """Messages waiting for their receiver's inbox to appear."""
        return sum(m.count("\n") + 1 for h in self._held.values() for _, m in h)

    def wait_acked(self, timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        for pub in self._publishers.values():
            left = max(0.0, deadline - time.monotonic())
            if not pub.wait_for_all_acked(Duration(nanoseconds=int(left * 1e9))):
                return False
        return True
