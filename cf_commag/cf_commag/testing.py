"""Helpers for in-process ROS tests of the framework's nodes: one rclpy Context per test, deadline-based waits.

from cf_commag.testing import Ros
ros = Ros(); node = ros.add(MyNode(context=ros.context)); ros.spin_until(lambda: ..., what="...")
"""

from __future__ import annotations

import time
import uuid

import pytest
import rclpy
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor


class Ros:
    """One rclpy context, its executor and the nodes in it."""

    def __init__(self) -> None:
        self.context = Context()
        rclpy.init(context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.nodes = []

    def node(self, name: str, **kwargs):
        node = rclpy.create_node(name, context=self.context, **kwargs)
        return self.add(node)

    def add(self, node):
        self.nodes.append(node)
        self.executor.add_node(node)
        return node

    def spin_until(self, predicate, timeout: float = 30.0, what: str = "condition"):
        """Spin until ``predicate()`` is true, and return its value; AssertionError after ``timeout``."""
        deadline = time.monotonic() + timeout
        while True:
            value = predicate()
            if value:
                return value
            if time.monotonic() > deadline:
                raise AssertionError(f"timed out after {timeout} s waiting for {what}")
            self.executor.spin_once(timeout_sec=0.02)

    def spin_for(self, seconds: float) -> None:
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.02)

    def call(self, client, request, timeout: float = 10.0):
        self.spin_until(client.service_is_ready, timeout, f"service {client.srv_name}")
        future = client.call_async(request)
        self.spin_until(future.done, timeout, f"answer from {client.srv_name}")
        return future.result()

    def close(self) -> None:
        for node in self.nodes:
            self.executor.remove_node(node)
            node.destroy_node()
        self.executor.shutdown()
        rclpy.try_shutdown(context=self.context)


@pytest.fixture
def ros():
    """An own rclpy context and executor for the test; its nodes are destroyed at the end."""
    helper = Ros()
    yield helper
    helper.close()


@pytest.fixture
def unique():
    """A short unique suffix, so tests in one ROS domain never share names."""
    return "t" + uuid.uuid4().hex[:8]
