"""A callback that raises is logged and answered; the executor (and so the process) keeps going."""

from __future__ import annotations

from rclpy.node import Node
from std_msgs.msg import String

from cf_commag.guarded import GuardedNode
from cf_interfaces.srv import Lookup, Register


class Faulty(GuardedNode, Node):
    """Every callback raises on its first call, then works."""

    def __init__(self, name, **kwargs):
        super().__init__(name, **kwargs)
        self.calls = {"lookup": 0, "register": 0, "timer": 0, "topic": 0}
        self.create_service(Lookup, f"/{name}/lookup", self._lookup)
        self.create_service(Register, f"/{name}/register", self._register)
        self.create_timer(0.01, self._tick)
        self.create_subscription(String, f"/{name}/topic", self._on_topic, 10)

    def _count(self, what):
        self.calls[what] += 1
        if self.calls[what] == 1:
            raise KeyError("x1")

    def _lookup(self, request, response):
        self._count("lookup")
        response.ok, response.reason = True, "fine"
        return response

    def _register(self, request, response):
        self._count("register")
        response.accepted = True
        return response

    def _tick(self):
        self._count("timer")

    def _on_topic(self, msg):
        self._count("topic")


def test_failing_callbacks_answer_failure_and_the_node_goes_on(ros, unique):
    node = ros.add(Faulty(f"faulty_{unique}", context=ros.context))
    probe = ros.node(f"probe_{unique}")
    lookup = probe.create_client(Lookup, f"/faulty_{unique}/lookup")
    register = probe.create_client(Register, f"/faulty_{unique}/register")
    first = ros.call(lookup, Lookup.Request(service_class="Kick"))
    assert not first.ok and first.reason == "internal error: KeyError: 'x1'"
    assert ros.call(lookup, Lookup.Request(service_class="Kick")).ok  # served again
    refused = ros.call(register, Register.Request())
    assert not refused.accepted and "KeyError" in refused.reason
    assert ros.call(register, Register.Request()).accepted
    ros.spin_until(lambda: node.calls["timer"] >= 3, what="the timer to go on after raising")
    pub = probe.create_publisher(String, f"/faulty_{unique}/topic", 10)

    def publish_until_two():
        pub.publish(String(data="x"))
        return node.calls["topic"] >= 2

    ros.spin_until(publish_until_two, what="the subscription to go on after raising")
