"""The shipped config file names exactly the node's parameters, with the same defaults."""

from __future__ import annotations

from pathlib import Path

import yaml

from cf_commag.commag_node import CommagConfig

CONFIG = Path(__file__).resolve().parents[1] / "config" / "commag.yaml"


def test_config_file_matches_the_parameters():
    params = yaml.safe_load(CONFIG.read_text())["commag"]["ros__parameters"]
    assert set(params) == set(CommagConfig.model_fields) | {"autostart"}
    for name, info in CommagConfig.model_fields.items():
        value = params[name]
        if isinstance(info.default, tuple):
            assert [v for v in value if v] == list(info.default)
        else:
            assert value == info.default, name
