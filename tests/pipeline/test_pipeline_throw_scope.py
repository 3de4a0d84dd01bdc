"""The typed key of a throw model (fe_crank.throw_scope) and how the check and the
assessment read it."""

from __future__ import annotations

import json

import pytest

from fe_crank.throw_scope import ALL_THROWS, ThrowScope, throws_of

ENGINE = {"1": None, "2": None, "3": None}  # a dict of throw names, as DynamicsResult.throws


def test_all_throws_stands_for_every_throw_in_engine_order():
    assert throws_of(ALL_THROWS, ENGINE) == ["1", "2", "3"]
    assert throws_of("2", ENGINE) == ["2"]


def test_a_key_that_is_no_throw_is_refused_not_read_as_every_throw():
    # the former API read any non-throw key (e.g. "throw") as "every throw"
    for key in ("throw", "all throws", "4"):
        with pytest.raises(ValueError, match="neither a throw of the engine"):
            throws_of(key, ENGINE)


def test_all_throws_is_written_as_before():
    # results.json, notes and provenance keep the text "all throws"
    assert isinstance(ALL_THROWS, ThrowScope) and isinstance(ALL_THROWS, str)
    assert f"mesh {ALL_THROWS}: x" == "mesh all throws: x"
    assert json.dumps({ALL_THROWS: 1, "list": [ALL_THROWS]}) == '{"all throws": 1, "list": ["all throws"]}'
