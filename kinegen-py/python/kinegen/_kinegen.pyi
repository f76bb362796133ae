"""Type stubs of the native module (src/lib.rs)."""

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_F64 = npt.NDArray[np.float64]
_Path = Union[str, "os.PathLike[str]"]

class LoadError(Exception):
    """A robot file did not load: one line per problem, ``file:line: path: message``."""

def robot_names() -> List[str]:
    """Names of the robots shipped with kinegen."""

class Robot:
    """A robot with its closed-form kinematics.

    Methods taking ``q`` accept one joint vector ``(N,)`` or a batch ``(M, N)`` and
    return one result or a leading axis of M. Non-finite values or a wrong shape raise
    ``ValueError``.
    """

    @staticmethod
    def from_urdf(
        path: _Path,
        base: Optional[str] = None,
        tip: Optional[str] = None,
        snap: float = 1e-4,
        symbolic: bool = False,
        task: Optional[Sequence[str]] = None,
    ) -> "Robot":
        """The chain of a URDF file from ``base`` (default: the root link) to ``tip``
        (default: the only leaf after a moving joint, or the one before a parallel
        gripper's fingers); values within ``snap`` of an exact one are snapped; ``task``
        the rows an arm with fewer than six joints solves (a SCARA: ``["x", "y", "z",
        "rz"]``)."""
    @staticmethod
    def from_toml(path: _Path) -> "Robot":
        """A robot file in kinegen's TOML format."""
    @staticmethod
    def from_dh(
        rows: Sequence[Union[Mapping[str, Any], Sequence[Union[float, str]]]],
        convention: str = "standard",
        params: Optional[Mapping[str, Union[float, str]]] = None,
        name: str = "DH robot",
    ) -> "Robot":
        """A DH table: dicts of the TOML columns, or tuples ``(a, alpha, d[, offset])``."""
    @staticmethod
    def shipped(name: str) -> "Robot":
        """A robot shipped with kinegen, by name (``"ur5"``)."""
    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def limits(self) -> _F64:
        """(N, 2) ``[min, max]`` per joint, +-inf where none is known."""
    @property
    def has_det(self) -> bool:
        """Whether the robot has a closed-form det J (a 6x6 Jacobian)."""
    @property
    def det_factors(self) -> List[Tuple[str, int, List[int]]]:
        """The factors of det J as (text, power, joints 1-based); empty without one."""
    @property
    def ik_family(self) -> Optional[str]:
        """The closed-form IK family, or None."""
    @property
    def formulas(self) -> List[Dict[str, str]]:
        """The generated code's FORMULAS: dicts of function, name, text, latex (the first 10 000)."""
    @property
    def det(self) -> str:
        """det J as ``kinegen show --what det`` prints it."""
    def fk(self, q: npt.ArrayLike) -> _F64:
        """Tool pose, (4, 4) or (M, 4, 4)."""
    def frames(self, q: npt.ArrayLike) -> _F64:
        """Every link's frame (without the tool), (N, 4, 4) or (M, N, 4, 4)."""
    def jacobian(self, q: npt.ArrayLike) -> _F64:
        """World-frame geometric Jacobian, (6, N) or (M, 6, N)."""
    def jacobian_ee(self, q: npt.ArrayLike) -> _F64:
        """Tool-frame geometric Jacobian, (6, N) or (M, 6, N)."""
    def jacobian_det(self, q: npt.ArrayLike) -> Union[float, _F64]:
        """det J from its closed form: a float or (M,)."""
    def task_jacobian_det(self, q: npt.ArrayLike) -> Union[float, _F64]:
        """The square task Jacobian's determinant: a float or (M,)."""
    def singular_factors(self, q: npt.ArrayLike) -> Tuple[List[str], _F64]:
        """The factors of det J: names and values (K,) or (M, K)."""
    def manipulability(self, q: npt.ArrayLike) -> Union[float, _F64]:
        """Yoshikawa's sqrt(det(J J^T)): a float or (M,)."""
    def hessian(self, q: npt.ArrayLike) -> _F64:
        """dJ/dq_k, (N, 6, N) or (M, N, 6, N)."""
    def jdot_qdot(self, q: npt.ArrayLike, qd: npt.ArrayLike) -> _F64:
        """dJ/dt qd, (6,) or (M, 6)."""
    def ik(
        self,
        pose: npt.ArrayLike,
        locked: Optional[float] = None,
        residuals: bool = True,
    ) -> Dict[str, Any]:
        """Every closed-form solution: ``q``, masks ``valid``, ``exact``, ``singular``
        (flagged as the generated ``ik`` flags it), ``within_limits``, and ``residual``
        (NaN with ``residuals=False``; a batch of poses adds a leading axis)."""
    def ik_near(
        self, pose: npt.ArrayLike, q: npt.ArrayLike
    ) -> Union[Optional[_F64], Tuple[_F64, npt.NDArray[np.bool_]]]:
        """The exact solution nearest to ``q``: (N,) or None; a batch gives (q, found)."""
    def latex(self, what: str = "all") -> str:
        """The closed forms as a LaTeX body (``kinegen show --latex``)."""
    def rust(self) -> str:
        """The generated Rust code (``kinegen rust``)."""
    def _repr_latex_(self) -> str: ...
    def _repr_html_(self) -> str:
        """det J and its singular factors as MathML (the report's printer)."""
    def _reference(self, which: str, q: npt.ArrayLike) -> _F64:
        """fk, jacobian or jacobian_ee at one q by walking the engine's graph (flat)."""
