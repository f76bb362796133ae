"""Fixtures shared by the test files."""

import pytest

import kinegen


@pytest.fixture(scope="session")
def shipped():
    """Every shipped robot, derived once for the whole session."""
    return {name: getattr(kinegen.robots, name)() for name in kinegen.robots.names()}
