"""The robots shipped with kinegen, one function each: ``kinegen.robots.ur5()``.

``names()`` lists them; each function returns a new ``kinegen.Robot``.
"""

from typing import Callable, List

from ._kinegen import Robot, robot_names


def names() -> List[str]:
    """Names of the shipped robots (``"ur5"``, ``"puma560"``, ...)."""
    return list(robot_names())


def _loader(name: str) -> Callable[[], Robot]:
    def load() -> Robot:
        return Robot.shipped(name)

    load.__name__ = name
    load.__qualname__ = name
    load.__doc__ = f"The shipped robot ``{name}`` (robots/{name}.toml)."
    return load


# One function per shipped robot, from the native module's list, so that the module
# and the engine's robots cannot disagree.
for _name in robot_names():
    globals()[_name] = _loader(_name)

__all__ = ["names"] + list(robot_names())
del _name
