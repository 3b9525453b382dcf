"""The service taxonomy: structure, both search directions, ranking."""

from __future__ import annotations

import pytest

from cf_lang.ontology import PLAYER_METHODS
from cf_lang.taxonomy import SERVICES, Direction, TaxonomyError


def test_tree_shape():
    assert SERVICES.ancestors("Shoot") == ("Kick", "BallAction", "Action", "Service")
    assert set(SERVICES.children("Service")) >= {"Perception", "Action", "Decision"}
    assert "Dribble" in SERVICES.descendants("Action")
    assert SERVICES.is_a("Pass", "Action") and not SERVICES.is_a("Action", "Pass")


def test_general_provider_serves_specific_request():
    assert SERVICES.can_serve("Action", "Dribble")
    assert not SERVICES.can_serve("Dribble", "Action")
    assert SERVICES.match_distance("Shoot", "Kick", Direction.GENERAL) == 1
    assert SERVICES.match_distance("Shoot", "Action", Direction.GENERAL) == 3


def test_specific_direction_finds_descendants():
    assert SERVICES.match_distance("Perception", "BallPerception", Direction.SPECIFIC) == -2
    assert SERVICES.match_distance("Perception", "BallPerception", Direction.GENERAL) is None
    assert SERVICES.match_distance("Kick", "Action", Direction.SPECIFIC) is None


def test_both_and_exact():
    assert SERVICES.match_distance("Kick", "Action", Direction.BOTH) == 2
    assert SERVICES.match_distance("Kick", "Shoot", Direction.BOTH) == -1
    assert SERVICES.match_distance("Kick", "Shoot", Direction.EXACT) is None
    assert SERVICES.match_distance("Kick", "Kick", Direction.EXACT) == 0
    assert SERVICES.match_distance("Kick", "Perception", Direction.BOTH) is None


def test_unknown_class_is_a_clear_error():
    with pytest.raises(TaxonomyError, match="unknown service class 'Juggle'"):
        SERVICES.ancestors("Juggle")


def test_every_action_method_names_a_service_class():
    for method, (_, service) in PLAYER_METHODS.items():
        assert SERVICES.is_a(service, "Action"), method
