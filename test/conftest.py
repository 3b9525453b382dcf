"""System-test fixtures (the helpers live in cf_system.py)."""

from __future__ import annotations

import uuid

import pytest

from cf_system import Probe, Processes


@pytest.fixture
def tag():
    return "t" + uuid.uuid4().hex[:8]


@pytest.fixture
def procs(tag, tmp_path):
    p = Processes(tag, tmp_path)
    yield p
    p.kill_all()


@pytest.fixture
def probe(tag):
    p = Probe(f"/commag_{tag}", tag)
    yield p
    p.close()
