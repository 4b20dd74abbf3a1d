"""Type stubs for the compiled extension ``famcc._core`` (crates/famcc-py).

Parameter names, defaults and keyword-only markers follow the
``#[pyo3(signature = ...)]`` attributes of the bindings; ``tests/test_stubs.py``
checks them against the runtime with ``mypy.stubtest``.
"""

from collections.abc import Sequence
from typing import Any, Callable, ClassVar, Final, Literal, final, overload

import numpy as np
from numpy.typing import NDArray
from typing_extensions import TypeAlias

__all__ = [
    "MAX_ORDER",
    "STATE_FIELDS",
    "ConfigError",
    "Controller",
    "ControllerBank",
    "Diagnostics",
    "FiniteTime",
    "FixedTime",
    "HighGain",
    "Linear",
    "MoulayDiscontinuous",
    "Nonsingular",
    "PaperPlant",
    "Skewed",
    "Smooth",
    "StepError",
    "VariableExponent",
    "_CallFloor",
    "__version__",
    "_controller_from_state",
    "design_rules",
    "finite_time",
    "fixed_time",
    "manifold",
    "paper_corollary_bound",
    "paper_design",
    "paper_input_limits",
    "rho",
    "skewed",
    "transition_s",
    "transition_t",
    "transition_u",
    "variable_exponent",
]

__version__: Final[str]
MAX_ORDER: Final[int]
#: Names of the leading entries of ``Controller.state()``; ``z_hat[0..order]`` follows.
STATE_FIELDS: Final[tuple[str, ...]]

_F64Array: TypeAlias = NDArray[np.float64]
# Scalars the element-wise functions return a float for.
_Scalar: TypeAlias = float | np.floating[Any] | np.integer[Any]
# What the element-wise functions accept besides a plain float: anything
# ``numpy.asarray(x, "float64")`` converts; the result has the same shape.
_ArrayIn: TypeAlias = NDArray[Any] | Sequence[float] | Sequence[Sequence[float]]

_Transition: TypeAlias = Literal["exponential", "cubic", "quintic", "sine"]
_Discretization: TypeAlias = Literal["exact", "euler", "tustin"]
_Constraint: TypeAlias = Literal["longitudinal", "lateral", "oblique"]
_Gamma: TypeAlias = Literal["log", "rational"]
_Latch: TypeAlias = Literal["paper", "authors"]
_DType: TypeAlias = Literal["float64", "float32"]

# Defaults written ``= ...`` are famcc-core's (the binding names them, it does not
# repeat them): k0 = 2, settle_time = 1 s, gamma "log", latch "paper", transition
# "exponential", discretization "exact", mu = 0.01, dtype "float64", constraint
# "longitudinal".

class ConfigError(ValueError):
    """An invalid configuration value; the message names the parameter and the rule."""

class StepError(ValueError):
    """A step that could not be taken (non-finite input, bad ``dt``, overflow).

    The state is unchanged, except after an internal overflow past the first
    step: the valid sample is then consumed (hold the previous output).
    """

# -- feedback laws -------------------------------------------------------------

@final
class Linear:
    """Linear law ``h(s) = -k s``."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, k: float) -> Linear: ...
    @property
    def k(self) -> float: ...
    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def slope(self, x: _Scalar) -> float: ...
    @overload
    def slope(self, x: _ArrayIn) -> _F64Array: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float]: ...

@final
class FiniteTime:
    """Finite-time law ``h(s) = -k |s|^p sign(s)``, ``0 < p < 1``."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, k: float, p: float) -> FiniteTime: ...
    @property
    def k(self) -> float: ...
    @property
    def p(self) -> float: ...
    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def slope(self, x: _Scalar) -> float: ...
    @overload
    def slope(self, x: _ArrayIn) -> _F64Array: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float]: ...

@final
class FixedTime:
    """Fixed-time law ``h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)``."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, alpha: float, p: float, beta: float, q: float) -> FixedTime: ...
    @property
    def alpha(self) -> float: ...
    @property
    def p(self) -> float: ...
    @property
    def beta(self) -> float: ...
    @property
    def q(self) -> float: ...
    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def slope(self, x: _Scalar) -> float: ...
    @overload
    def slope(self, x: _ArrayIn) -> _F64Array: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, float, float]: ...

@final
class VariableExponent:
    """Continuous variable-exponent law: exponent r_b at 0, r_1 at 1, r_t at infinity."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, k: float, r_b: float, r_1: float, r_t: float) -> VariableExponent: ...
    @property
    def k(self) -> float: ...
    @property
    def r_b(self) -> float: ...
    @property
    def r_1(self) -> float: ...
    @property
    def r_t(self) -> float: ...
    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def slope(self, x: _Scalar) -> float: ...
    @overload
    def slope(self, x: _ArrayIn) -> _F64Array: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, float, float]: ...

@final
class MoulayDiscontinuous:
    """The discontinuous variable-exponent law of Moulay et al. (comparison only)."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, beta: float, lambda_: float, mu: float) -> MoulayDiscontinuous: ...
    @property
    def beta(self) -> float: ...
    @property
    def lambda_(self) -> float: ...
    @property
    def mu(self) -> float: ...
    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def slope(self, x: _Scalar) -> float: ...
    @overload
    def slope(self, x: _ArrayIn) -> _F64Array: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, float]: ...

_Law: TypeAlias = Linear | FiniteTime | FixedTime | VariableExponent | MoulayDiscontinuous

# -- skews -----------------------------------------------------------------------

@final
class Smooth:
    """Smooth skewed manifold design (SSMD)."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(cls, eps_s: float, eps_z: float, transition: _Transition = ...) -> Smooth: ...
    @property
    def eps_s(self) -> float: ...
    @property
    def eps_z(self) -> float: ...
    @property
    def transition(self) -> _Transition: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, str]: ...

@final
class Nonsingular:
    """Nonsingular skewed manifold design (NSMD)."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls, eps_s: float, eps_z: float, k_pp: float, transition: _Transition = ...
    ) -> Nonsingular: ...
    @property
    def eps_s(self) -> float: ...
    @property
    def eps_z(self) -> float: ...
    @property
    def k_pp(self) -> float: ...
    @property
    def transition(self) -> _Transition: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, float, str]: ...

_Skew: TypeAlias = Smooth | Nonsingular

@final
class Skewed:
    """A skewed law h_m (built by :func:`skewed`; not constructible directly)."""

    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def inverse(self, y: _Scalar) -> float: ...
    @overload
    def inverse(self, y: _ArrayIn) -> _F64Array: ...
    @property
    def k_p(self) -> float: ...

# -- differentiator --------------------------------------------------------------

@final
class HighGain:
    """The high-gain differentiator (eq. HGD)."""

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls,
        mu: float,
        a: Sequence[float],
        discretization: _Discretization = ...,
        limits: Sequence[float] | None = None,
    ) -> HighGain: ...
    @staticmethod
    def default(order: int, mu: float = ..., discretization: _Discretization = ...) -> HighGain: ...
    @staticmethod
    def for_rate(order: int, dt: float) -> HighGain: ...
    @property
    def mu(self) -> float: ...
    @property
    def a(self) -> tuple[float, ...]: ...
    @property
    def discretization(self) -> _Discretization: ...
    @property
    def limits(self) -> tuple[float, ...] | None: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, list[float], str, list[float] | None]: ...

# -- controller ------------------------------------------------------------------

@final
class Diagnostics:
    """What the last step did (read-only)."""

    @property
    def t(self) -> float: ...
    @property
    def xi(self) -> float: ...
    @property
    def xi_nominal(self) -> float: ...
    @property
    def s(self) -> float: ...
    @property
    def stages(self) -> _F64Array: ...
    @property
    def s_prev(self) -> float: ...
    @property
    def ds_prev(self) -> float: ...
    @property
    def bounds(self) -> tuple[float, float]: ...
    @property
    def nominal_bounds(self) -> tuple[float, float]: ...
    @property
    def z_hat(self) -> _F64Array: ...
    @property
    def expanded(self) -> bool: ...
    @property
    def expansion(self) -> float: ...
    @property
    def saturation_gap(self) -> float | None: ...
    @property
    def clamp_count(self) -> int: ...
    @property
    def v_unlimited(self) -> float: ...
    @property
    def integral(self) -> float | None: ...
    @property
    def integrating(self) -> bool: ...
    @property
    def unsaturated_expansions(self) -> int: ...
    @property
    def v(self) -> float: ...

@final
class Controller:
    """The FAMCC controller.

    The sign convention of every step method is ``e = y - y_d`` (the output minus
    the reference: the opposite of a PID's ``setpoint - y``); :meth:`step_output`
    takes ``y`` and ``y_d`` and forms it.

    Parameters
    ----------
    order : int
        The plant's order n (the relative degree of the output).
    integral : bool, optional
        Integral action (default False; docs/design.md §3.8). The law of order
        ``n + 1`` acts on ``(I, e, e', ..., e^(n-1))`` with ``I`` the exact integral
        of the measured error (rectangle rule), so a constant load is carried by
        ``I`` and the error tends to 0. ``feedback`` and ``skew`` then have ``order``
        entries (one per stage of the order ``n + 1`` law), the differentiator keeps
        ``order`` coefficients (it runs on ``e``), ``initial_derivatives`` stay the
        plant's ``(z2..zn)``. The integral is separated (anti-windup): ``e`` is
        integrated only while ``|s| <= eps`` (the final band) and not while the
        output is beyond a known limit with ``e`` pushing it further. Needs
        ``order < MAX_ORDER``.
    output_limits : (float, float), optional
        Magnitude limits ``(lo, hi)`` of the output, ``lo < hi``, input units
        (default None). :meth:`step` returns the limited output; it counts as the
        applied input for the integral separation and the health count, and
        ``diagnostics.v_unlimited`` keeps the law's own output.
    rate_limit : float, optional
        The output's largest rate of change, input units per second (default
        None).
    initial_output : float, optional
        Bumpless start (default None): the first step's output equals
        ``initial_output`` when that is feasible (with integral action by the
        choice of ``I_0``; without, by rescaling the latched widths), else the
        nearest feasible output.

    Warns
    -----
    famcc.DesignWarning
        At construction, once per legal but risky choice (``lint()``): dt too
        coarse for mu, a last-stage law that chatters when sampled, rho_e too
        large for eps, no estimate limits at differentiator order >= 4, the
        exact ZOH at order >= 4. While stepping with the applied input known
        (``applied`` passed or ``output_limits`` set), once, when the bounds
        were expanded although the actuator had headroom for half the envelope's
        settling time in total (``diagnostics.unsaturated_expansions >=
        0.5 settle_time / dt``: persistent, not a start-up transient or the
        recovery after a saturation): ``k_u`` too small for the plant.
    """

    def __new__(
        cls,
        order: int,
        dt: float,
        feedback: _Law | Sequence[_Law] | None = None,
        *,
        skew: _Skew | Sequence[_Skew | None] | None = None,
        constraint: _Constraint = ...,
        eps: float | tuple[float, float],
        settle_time: float = ...,
        k0: float = ...,
        k_u: float,
        gamma: _Gamma = ...,
        rho_e: float | Literal["auto"] | None = ...,  # "auto": min(0.01, eps/10); None: off
        # "auto": the paper's (exact) up to order 3, HighGain.default(order, discretization="tustin") above
        differentiator: HighGain | Literal["auto"] | None = ...,
        latch: _Latch = ...,
        transition: _Transition = ...,
        initial_derivatives: Sequence[float] | None = None,
        dtype: _DType = ...,
        integral: bool = False,
        output_limits: tuple[float, float] | None = None,
        rate_limit: float | None = None,
        initial_output: float | None = None,
    ) -> Controller: ...
    @property
    def dt(self) -> float: ...
    @property
    def order(self) -> int: ...
    @property
    def dtype(self) -> _DType: ...
    @property
    def time(self) -> float: ...
    @property
    def diagnostics(self) -> Diagnostics: ...
    @property
    def estimate(self) -> _F64Array: ...
    @property
    def integral(self) -> bool: ...
    def step(self, e: float, applied: float | None = None) -> float: ...
    def step_output(self, y: float, y_d: float, applied: float | None = None) -> float: ...
    def lint(self) -> list[str]: ...
    def step_dt(self, e: float, dt: float, applied: float | None = None) -> float: ...
    def step_state(
        self, z: Sequence[float] | NDArray[np.floating[Any]], applied: float | None = None
    ) -> float: ...
    def reset(self) -> None: ...
    def state(self) -> _F64Array: ...
    def set_state(self, state: _F64Array) -> None: ...
    def config(self) -> dict[str, Any]: ...
    def __copy__(self) -> Controller: ...
    def __deepcopy__(self, _memo: Any) -> Controller: ...
    def __reduce__(self) -> tuple[_Rebuild, tuple[dict[str, Any], list[float]]]: ...

_Rebuild: TypeAlias = Callable[[dict[str, Any], list[float]], Controller]

@final
class ControllerBank:
    """n independent copies of a configured controller."""

    def __new__(cls, controller: Controller, n: int) -> ControllerBank: ...
    def __len__(self) -> int: ...
    def step(self, e: _F64Array, on_nonfinite: Literal["raise", "hold"] = "raise") -> _F64Array: ...
    def step_output(self, y: _F64Array, y_d: _F64Array) -> _F64Array: ...
    @property
    def overflows(self) -> int: ...
    @property
    def held(self) -> tuple[int, ...]: ...
    @property
    def xi(self) -> _F64Array: ...
    @property
    def xi_nominal(self) -> _F64Array: ...
    @property
    def expansion(self) -> _F64Array: ...
    def reset(self) -> None: ...
    def controller(self, i: int) -> Controller: ...

@final
class _CallFloor:
    """The floor of a Python-to-Rust method call (benchmarks)."""

    def __new__(cls) -> _CallFloor: ...
    def step(self, e: float) -> float: ...

# -- the paper's designs and plants (famcc-paper) ---------------------------------

@final
class PaperPlant:
    """One of the paper's plants: order 2 (examples 1-2) or 3 (example 3)."""

    def __new__(
        cls,
        order: int,
        variant: str,
        gain: float = 1.0,
        amp: float | None = None,
        x0: Sequence[float] | None = None,
    ) -> PaperPlant: ...
    @property
    def x0(self) -> tuple[float, ...]: ...
    def rhs(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]], u: float
    ) -> tuple[float, ...]: ...
    def output_derivatives(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]]
    ) -> tuple[float, ...]: ...
    def gain_and_drift(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]]
    ) -> tuple[float, float]: ...

def paper_design(example: int, variant: str) -> dict[str, Any]: ...
def paper_corollary_bound(example: int) -> float: ...
def paper_input_limits(example: int, saturated: bool) -> tuple[float, float]: ...

# -- functions -------------------------------------------------------------------

def _controller_from_state(kwargs: dict[str, Any], state: Sequence[float]) -> Controller: ...
@overload
def transition_t(z: _Scalar) -> float: ...
@overload
def transition_t(z: _ArrayIn) -> _F64Array: ...
@overload
def transition_s(z: _Scalar, kind: _Transition = ...) -> float: ...
@overload
def transition_s(z: _ArrayIn, kind: _Transition = ...) -> _F64Array: ...
@overload
def transition_u(z: _Scalar, kind: _Transition = ...) -> float: ...
@overload
def transition_u(z: _ArrayIn, kind: _Transition = ...) -> _F64Array: ...
@overload
def rho(rho0: float, eps: float, settle_time: float, t: _Scalar) -> float: ...
@overload
def rho(rho0: float, eps: float, settle_time: float, t: _ArrayIn) -> _F64Array: ...
def skewed(law: _Law, skew: _Skew | None = None) -> Skewed: ...
def manifold(
    z: Sequence[float] | NDArray[np.floating[Any]],
    feedback: _Law | Sequence[_Law],
    skew: _Skew | Sequence[_Skew | None] | None = None,
) -> _F64Array: ...
def finite_time(k: float, p: float, z1_0: float) -> float: ...
def variable_exponent(k: float, r_b: float, r_1: float, r_t: float) -> float: ...
def fixed_time(stages: Sequence[tuple[float, float, float, float]]) -> float: ...
def design_rules(
    order: int,
    dt: float,
    u_limits: tuple[float, float],
    eps: float,
    settle_time: float,
    hold_input: float,
    gain: float | None = None,
    noise_std: float = 0.0,
    integral: bool | None = None,
    phase_budget: float | None = None,
    mu_per_dt: float | None = None,
    settle_fraction: float | None = None,
    max_error: float | None = None,
) -> dict[str, Any]:
    """The design rules of famcc-core (see :func:`famcc.design`)."""
