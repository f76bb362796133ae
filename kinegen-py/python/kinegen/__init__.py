"""Closed-form robot kinematics on NumPy arrays.

``Robot.from_urdf``, ``Robot.from_toml``, ``Robot.from_dh`` and ``kinegen.robots.ur5()``
(and every robot shipped with kinegen) load a robot; its methods take one joint vector
(shape ``(N,)``) or a batch ``(M, N)``. A file that does not load raises
``kinegen.LoadError`` (with the file and line); bad arrays raise ``ValueError``.
"""

from ._kinegen import LoadError, Robot, robot_names
from . import robots

__all__ = ["LoadError", "Robot", "robots", "robot_names"]
