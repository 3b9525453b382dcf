"""Renewing registrations with the ComMAg: three times per lease, one request in flight per name.

Every Agent renews its own record with it, and the gateway renews the records of the TCP
agents that showed life within their lease. A renewal still unanswered when the next one is
due is given up and asked again: the ComMAg restarted (a restarted service loses its first
answers while discovery settles), or the request was lost. Waiting longer would cost the lease.
"""

from __future__ import annotations

from collections.abc import Callable

from rclpy.client import Client
from rclpy.task import Future

RENEWALS_PER_LEASE = 3  # one late or lost renewal is not a missed lease
_EARLY = 0.9  # a timer may fire a little early: still due


class Renewer:
    """When each name is due for renewal, and the renewal requests in flight."""

    def __init__(self, client: Client):
        self._client = client
        self._sent: dict[str, float] = {}  # name -> when its last renewal was sent (or registered)
        self._pending: dict[str, tuple[Future, float]] = {}

    def due(self, name: str, lease: float, now: float) -> bool:
        """Whether ``name`` should be renewed now."""
        last = self._sent.get(name)  # answered or not: the next one is due a third of a lease later
        return last is None or now - last >= _EARLY * lease / RENEWALS_PER_LEASE

    def send(self, name: str, request, now: float, on_answer: Callable[[Future], None] | None = None) -> Future | None:
        """Send a Register request for ``name`` (replacing one still in flight); None if the ComMAg is not there."""
        pending = self._pending.pop(name, None)
        if pending is not None and not pending[0].done():
            self._client.remove_pending_request(pending[0])
            pending[0].cancel()
        if not self._client.service_is_ready():
            return None
        future = self._client.call_async(request)
        self._pending[name] = (future, now)
        self._sent[name] = now
        if on_answer is not None:
            future.add_done_callback(on_answer)
        return future

    def registered(self, name: str, now: float) -> None:
        """``name`` was just registered (by a call of its own): the next renewal is a third of a lease away."""
        self._sent[name] = now

    def pending(self, name: str) -> Future | None:
        """The renewal of ``name`` still in flight, if any."""
        pending = self._pending.get(name)
        return pending[0] if pending is not None and not pending[0].done() else None

    def forget(self, name: str) -> None:
        """Stop renewing ``name`` (it left)."""
        self._sent.pop(name, None)
        self._pending.pop(name, None)
