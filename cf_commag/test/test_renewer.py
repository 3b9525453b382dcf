"""When a registration is due for renewal: three times per lease, one request in flight, lost ones asked again."""

from __future__ import annotations

from rclpy.task import Future

from cf_commag.renewer import Renewer


class Client:
    """Stands in for an rclpy service client: records the calls (a side effect), answers nothing itself."""

    def __init__(self, ready=True):
        self.ready, self.calls, self.removed = ready, [], []

    def service_is_ready(self):
        return self.ready

    def call_async(self, request):
        future = Future()
        self.calls.append((request, future))
        return future

    def remove_pending_request(self, future):
        self.removed.append(future)


def test_three_renewals_per_lease_and_one_in_flight():
    client = Client()
    renewer = Renewer(client)
    assert renewer.due("a", 3.0, now=0.0)
    renewer.send("a", "req", now=0.0)
    assert not renewer.due("a", 3.0, now=0.5)  # in flight
    client.calls[0][1].set_result("ok")
    assert not renewer.due("a", 3.0, now=0.8)
    assert renewer.due("a", 3.0, now=0.95)  # a third of the lease (a timer may fire a little early)


def test_an_unanswered_renewal_is_given_up_and_asked_again_when_the_next_is_due():
    """A restarted ComMAg loses its first answers: waiting a whole lease for one would cost the lease."""
    client = Client()
    renewer = Renewer(client)
    renewer.send("a", "req", now=0.0)
    assert renewer.pending("a") is client.calls[0][1]
    assert not renewer.due("a", 1.0, now=0.2) and renewer.due("a", 1.0, now=0.31)
    renewer.send("a", "req", now=0.31)
    assert client.removed == [client.calls[0][1]] and client.calls[0][1].cancelled()


def test_nothing_is_sent_before_the_commag_is_there_and_forgotten_names_start_over():
    client = Client(ready=False)
    renewer = Renewer(client)
    assert renewer.send("a", "req", now=0.0) is None and renewer.due("a", 1.0, now=0.01)
    client.ready = True
    renewer.registered("a", now=1.0)
    assert not renewer.due("a", 3.0, now=1.5)
    renewer.forget("a")
    assert renewer.due("a", 3.0, now=1.5) and renewer.pending("a") is None
