"""No node of ours assigns an attribute that rclpy's Node or LifecycleNode uses itself.

rclpy keeps what the executor serves in attributes of the node (``_services``, ``_timers``, ...):
a subclass that assigns one of them silently drops what rclpy made, e.g. the lifecycle services.
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import inspect
import pkgutil
import textwrap

from rclpy.lifecycle import LifecycleNode
from rclpy.node import Node

PACKAGES = ["cf_commag", "cf_sim_backend", "cf_decision"]


def assigned_attributes(cls: type) -> set[str]:
    """Names assigned as ``self.<name>`` anywhere in the class body."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(cls)))
    names = set()
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, ast.AnnAssign | ast.AugAssign):
            targets = [node.target]
        for target in targets:
            for t in ast.walk(target):
                if isinstance(t, ast.Attribute) and isinstance(t.value, ast.Name) and t.value.id == "self":
                    names.add(t.attr)
    return names


def rclpy_attributes() -> set[str]:
    names = set()
    for cls in {*Node.__mro__, *LifecycleNode.__mro__} - {object}:
        names |= {n for n in vars(cls) if not n.startswith("__")}
        with contextlib.suppress(OSError, TypeError):  # a class without Python source
            names |= assigned_attributes(cls)
    return names


def our_node_classes() -> list[type]:
    found = {}
    for package in PACKAGES:
        pkg = importlib.import_module(package)
        for info in pkgutil.walk_packages(pkg.__path__, prefix=f"{package}."):
            module = importlib.import_module(info.name)
            for _, cls in inspect.getmembers(module, inspect.isclass):
                if issubclass(cls, Node) and cls.__module__.split(".")[0] in PACKAGES:
                    found[cls.__qualname__] = cls
    return list(found.values())


def test_rclpy_attribute_names_are_known():
    taken = rclpy_attributes()
    assert {"_services", "_timers", "_clients", "_subscriptions", "_publishers"} <= taken


def test_no_node_of_ours_shadows_an_rclpy_attribute():
    classes = our_node_classes()
    assert len(classes) >= 6, [c.__name__ for c in classes]
    taken = rclpy_attributes()
    clashes = {cls.__name__: sorted(assigned_attributes(cls) & taken) for cls in classes}
    assert not {k: v for k, v in clashes.items() if v}, clashes
