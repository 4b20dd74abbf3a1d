"""Type stubs for the compiled extension ``famcc._core`` (crates/famcc-py).

Parameter names, defaults and keyword-only markers follow the
``#[pyo3(signature = ...)]`` attributes of the bindings; ``tests/test_stubs.py``
checks them against the runtime with ``mypy.stubtest``.
"""

from collections.abc import Callable, Sequence
from typing import Any, ClassVar, Final, Literal, TypeAlias, final, overload

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "MAX_ORDER",
    "STATE_FIELDS",
    "ArgumentTypeError",
    "ConfigError",
    "Controller",
    "ControllerBank",
    "ControllerSpec",
    "DesignWarning",
    "Diagnostics",
    "FamccWarning",
    "FiniteTime",
    "FixedTime",
    "HighGain",
    "Linear",
    "Lockstep",
    "MoulayDiscontinuous",
    "Nonsingular",
    "Observer",
    "PaperLanes",
    "PaperPlant",
    "Skewed",
    "Smooth",
    "StepError",
    "VariableExponent",
    "_CallFloor",
    "__version__",
    "_controller_from_state",
    "_controller_spec_from_kwargs",
    "design_rules",
    "finite_time",
    "fixed_time",
    "manifold",
    "paper_corollary_bound",
    "paper_design",
    "paper_input_limits",
    "paper_nominal_gain",
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
_Discretization: TypeAlias = Literal["exact", "euler", "tustin", "foh"]
_Constraint: TypeAlias = Literal["longitudinal", "lateral", "oblique"]
_Gamma: TypeAlias = Literal["log", "rational"]
_Latch: TypeAlias = Literal["paper", "authors"]
_DType: TypeAlias = Literal["float64", "float32"]

# The constructors' defaults are famcc-core's: the binding passes the core's values
# and its text signatures spell them out (tests/test_docs.py checks that they agree).

class ConfigError(ValueError):
    """An invalid configuration value; the message names the parameter and the rule.

    A ``ValueError``: ``str(error)`` is the message; the fields say the same for a program.

    Parameters
    ----------
    *args
        The message, as for any exception.
    parameter : str, optional
        The parameter's name.
    stage : int, optional
        The stage of a per-stage parameter, from 1.
    rule : str, optional
        The rule the value broke.

    Attributes
    ----------
    parameter : str or None
        The parameter's name as in the API (``'eps'``, ``'k_u'``, ``'feedback'``,
        ``'differentiator.a'``); None when no single parameter is at fault.
    stage : int or None
        For a per-stage parameter (``feedback``, ``skew``, a stage's own values), the
        stage, counted from 1 as in the message ``'stage 1: ...'``; None otherwise.
    rule : str or None
        The rule the value broke, e.g. ``'must be finite and > 0'``; None when the
        message has no separate rule.

    Examples
    --------
    >>> import famcc
    >>> try:
    ...     famcc.Linear(0.0)
    ... except famcc.ConfigError as error:
    ...     print(error, '|', error.parameter, '|', error.rule)
    k must be finite and > 0 | k | must be finite and > 0
    """

    parameter: str | None
    stage: int | None
    rule: str | None
    def __init__(
        self,
        *args: object,
        parameter: str | None = None,
        stage: int | None = None,
        rule: str | None = None,
    ) -> None: ...

class StepError(ValueError):
    """A step that could not be taken (non-finite input, bad ``dt``, overflow).

    For a non-finite ``e``, ``applied`` or ``dt`` the state is unchanged; an overflow on a valid sample after the first step consumes the sample (hold the previous output).

    Parameters
    ----------
    *args
        The message, as for any exception.
    kind : str, optional
        What went wrong (see ``kind`` below).
    parameter : str, optional
        The input at fault.

    Attributes
    ----------
    kind : str or None
        One stable name per cause: ``'non-finite-input'``, ``'non-finite-applied'``,
        ``'invalid-dt'``, ``'no-differentiator'``, ``'overflow'`` (famcc-core's ``StepError``),
        ``'wrong-length'`` (a vector of the wrong length) and ``'wrong-type'`` (an input that is
        not a float vector).
    parameter : str or None
        The input at fault (``'e'``, ``'y'``, ``'y_d'``, ``'z'``, ``'applied'``, ``'dt'``,
        ``'differentiator'``); None when no single input is (an overflow).

    Examples
    --------
    >>> import famcc
    >>> ctrl = famcc.Controller(1, 1e-3, constraint='longitudinal', eps=0.1, k_u=1.0)
    >>> try:
    ...     ctrl.step(float('nan'))
    ... except famcc.StepError as error:
    ...     print(error.kind, error.parameter)
    non-finite-input e
    """

    kind: str | None
    parameter: str | None
    def __init__(
        self, *args: object, kind: str | None = None, parameter: str | None = None
    ) -> None: ...

class FamccWarning(UserWarning):
    """Base class of the warnings famcc itself emits.

    The test suite turns every one of them into an error, so that a warning that famcc's own code triggers is either fixed or expected explicitly.
    """

class DesignWarning(FamccWarning):
    """A legal but risky choice (or a requirement a design cannot meet).

    Emitted by :func:`famcc.design` for every finding that is not ok, and by :class:`famcc.Controller` for risky configurations; the message names the parameter, the rule and a suggested value.
    """

class ArgumentTypeError(TypeError):
    """A ``TypeError`` whose message names the argument.

    The compiled constructors raise it for an argument of the wrong type (a ``bool`` where a number is meant, a ``str`` for a float, ...): ``str(error)`` reads ``argument 'dt': must be a real number, not bool``.
    """

    def add_note(self, note: str, /) -> None:
        """A method of a class made at run time (binds the instance on access)."""

# -- feedback laws -------------------------------------------------------------

@final
class Linear:
    """Linear law ``h(s) = -k s`` (eq. (59) (lfmi)).

    A stage law ``h_p`` of the iterative manifold: it maps a stage value
    ``s`` to the desired rate ``ds/dt = h_p(s)``. Callable on floats and
    NumPy arrays; frozen, comparable and picklable.

    Parameters
    ----------
    k : float
        Gain, 1/s, ``k > 0``.

    Raises
    ------
    famcc.ConfigError
        ``k`` not finite and ``> 0``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.Linear(k=2.0)
    >>> h(0.5), h.slope(0.5)
    (-1.0, -2.0)
    """

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
    """Finite-time law ``h(s) = -k |s|^p sign(s)``, ``0 < p < 1`` (eq. (37) (fn)).

    A stage law ``h_p`` (``ds/dt = h_p(s)``) that reaches ``s = 0`` in
    finite time (Corollary 1, eq. (42) (fnT)). Callable on floats and NumPy
    arrays; frozen, comparable and picklable.

    Parameters
    ----------
    k : float
        Gain, ``k > 0``, unit of ``s`` per s over unit of ``s`` to the
        power ``p``.
    p : float
        Exponent, dimensionless, ``0 < p < 1``.

    Raises
    ------
    famcc.ConfigError
        ``k <= 0`` or ``p`` outside ``(0, 1)``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.FiniteTime(k=1.0, p=0.5)
    >>> h(4.0), h(-4.0)
    (-2.0, 2.0)
    """

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
    """Fixed-time law ``h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)``, ``0 < p < 1 < q`` (eq. (61) (RFCs)).

    A stage law ``h_p`` (``ds/dt = h_p(s)``) whose settling time is bounded
    independently of the initial value (Corollary 3, eq. (63) (fxTho)).
    Callable on floats and NumPy arrays; frozen, comparable and picklable.

    Parameters
    ----------
    alpha : float
        Low-power gain, ``alpha > 0`` (unit of ``s`` per s over unit of
        ``s`` to the power ``p``).
    p : float
        Low power, dimensionless, ``0 < p < 1``.
    beta : float
        High-power gain, ``beta > 0`` (unit of ``s`` per s over unit of
        ``s`` to the power ``q``).
    q : float
        High power, dimensionless, finite and ``q > 1``.

    Raises
    ------
    famcc.ConfigError
        A gain ``<= 0``, ``p`` outside ``(0, 1)`` or ``q <= 1``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0)
    >>> h(4.0)
    -10.0
    """

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
    """Continuous variable-exponent law (eq. (45) (fxe)): exponent r_b at 0, r_1 at |s| = 1, r_t at infinity.

    ``h(s) = -k |s|^r(s) sign(s)`` with ``r(s) = a s^2 / (1 + b s^2) + r_b``,
    ``b = (r_1 - r_b) / (r_t - r_1)`` and ``a = (r_t - r_b) b``: a stage law
    ``h_p`` (``ds/dt = h_p(s)``) with a settling bound of Corollary 2
    (eq. (53) (fxeT)). Callable on floats and NumPy arrays; frozen,
    comparable and picklable.

    Parameters
    ----------
    k : float
        Gain, ``k > 0`` (unit of ``s`` per s at ``|s| = 1``).
    r_b : float
        Exponent at ``s = 0``, dimensionless, ``0 < r_b < 1``.
    r_1 : float
        Exponent at ``|s| = 1``, dimensionless, ``r_1 > 1``.
    r_t : float
        Exponent as ``|s|`` tends to infinity, dimensionless, finite and
        ``r_t > r_1``.

    Raises
    ------
    famcc.ConfigError
        A rule above broken, or ``r_b`` too small for ``r_1`` and ``r_t``
        (``h`` must be strictly decreasing, paper Step B1).

    Examples
    --------
    >>> import famcc
    >>> h = famcc.VariableExponent(k=1.5, r_b=0.5, r_1=2.0, r_t=3.0)
    >>> h(1.0), h(-1.0)
    (-1.5, 1.5)
    """

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
    """The discontinuous variable-exponent law of Moulay et al. (eq. (58) (fvec)), for comparison only.

    ``h(s) = -beta |s|^p(s) sign(s)`` with ``p(s) = lambda_ s^2 / (1 + mu s^2)``.
    Its exponent is 0 at ``s = 0``, so ``h`` jumps from ``+beta`` to
    ``-beta`` across zero. Callable on floats and NumPy arrays; frozen,
    comparable and picklable.

    Parameters
    ----------
    beta : float
        Gain, ``beta > 0`` (unit of ``s`` per s).
    lambda_ : float
        Exponent numerator coefficient, ``lambda_ > 0`` (1 over unit of
        ``s`` squared).
    mu : float
        Exponent denominator coefficient, finite and ``mu >= 0`` (1 over
        unit of ``s`` squared).

    Raises
    ------
    famcc.ConfigError
        ``beta <= 0``, ``lambda_ <= 0`` or ``mu < 0``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.MoulayDiscontinuous(beta=1.0, lambda_=1.0, mu=0.5)
    >>> h(1e-9) < -0.99, h(-1e-9) > 0.99
    (True, True)
    """

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
    """Smooth skewed manifold design (SSMD, eq. (14) (SSMD)).

    Skews a stage law: ``h_m(s) = h_p(s) + T1(s) eps_s`` with
    ``T1(s) = 1 - 2 S((s + eps_z) / (2 eps_z))``, so ``h_m = h_p +- eps_s``
    outside ``+-eps_z``. Passed as ``skew=`` to :class:`Controller` or to
    :func:`skewed`; frozen, comparable and picklable.

    Parameters
    ----------
    eps_s : float
        Vertical offset of the skewed law outside ``+-eps_z``, ``> 0``, rate
        units (unit of ``s`` per s).
    eps_z : float
        Half-width of the transition zone around 0, ``> 0``, unit of ``s``.
    transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
        The double-ended transition ``S`` of ``T1``; 'exponential' is the
        paper's eq. (2) (trnsS).

    Raises
    ------
    famcc.ConfigError
        ``eps_s`` or ``eps_z`` not finite and ``> 0``, or an unknown
        ``transition``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.skewed(famcc.Linear(1.0), famcc.Smooth(eps_s=0.2, eps_z=0.1))
    >>> round(h(-1.0), 12), h(0.0)
    (1.2, 0.0)
    """

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls, eps_s: float, eps_z: float, transition: _Transition = "exponential"
    ) -> Smooth: ...
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
    """Nonsingular skewed manifold design (NSMD, eq. (15) (NSMD)).

    Skews a stage law: ``h_m(s) = T2(s) (h_p(s) + T1(s) eps_s) - (1 - T2(s)) k_p s``
    with ``T2(s) = U(s / eps_z)`` and ``k_p = k_pp (eps_s - h_p(eps_z)) / eps_z``.
    Outside ``+-eps_z`` it equals ``h_p +- eps_s``; near 0 it is the line
    ``-k_p s``, which removes the infinite slope of power laws below 1. The
    widths of Corollary 3 are eqs. (62a) (NSMDie), (62b) (NSMDif). Passed as
    ``skew=`` to :class:`Controller` or to :func:`skewed`; frozen, comparable
    and picklable.

    Parameters
    ----------
    eps_s : float
        Vertical offset of the skewed law outside ``+-eps_z``, ``> 0``, rate
        units (unit of ``s`` per s).
    eps_z : float
        Half-width of the transition zone around 0, ``> 0``, unit of ``s``.
    k_pp : float
        Slope factor, dimensionless, ``> 0``: it sets the slope ``-k_p`` of
        ``h_m`` at 0.
    transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
        The double-ended transition ``S`` of ``T1`` and ``T2``; 'exponential'
        is the paper's eq. (2) (trnsS).

    Raises
    ------
    famcc.ConfigError
        ``eps_s``, ``eps_z`` or ``k_pp`` not finite and ``> 0``, or an
        unknown ``transition``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.skewed(famcc.FiniteTime(1.0, 0.5), famcc.Nonsingular(0.1, 0.1, 0.1))
    >>> h(1.0), h(-1.0)
    (-1.1, 1.1)
    >>> round(h.k_p, 6)
    0.416228
    """

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls, eps_s: float, eps_z: float, k_pp: float, transition: _Transition = "exponential"
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
    """A skewed law h_m (eqs. (14) (SSMD), (15) (NSMD)), callable on floats and arrays.

    Built by :func:`skewed` from a law and an optional skew; not
    constructible directly. ``h_m(x)`` is the skewed law, :meth:`inverse`
    its inverse ``h_v``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.skewed(famcc.Linear(1.0), famcc.Smooth(eps_s=0.2, eps_z=0.1))
    >>> y = h(-1.0)
    >>> round(h.inverse(y), 9)
    -1.0
    >>> h.k_p
    0.0
    """

    @overload
    def __call__(self, x: _Scalar) -> float: ...
    @overload
    def __call__(self, x: _ArrayIn) -> _F64Array: ...
    @overload
    def inverse(self, y: _Scalar) -> float: ...
    @overload
    def inverse(self, y: _ArrayIn) -> _F64Array: ...
    @property
    def k_p(self) -> float:
        """The NSMD slope k_p (0 for other designs)."""

# -- differentiator --------------------------------------------------------------

@final
class HighGain:
    """The high-gain differentiator (eq. (34) (HGD)).

    Estimates the error's derivatives ``e', ..., e^(n-1)`` from its samples
    for the output-feedback controller (eq. (35) (uOF)): passed as
    ``differentiator=`` to :class:`Controller`. Frozen, comparable and
    picklable; :meth:`default` builds the paper's.

    Parameters
    ----------
    mu : float
        The gain's time constant ``mu``, s (``> 0``): smaller is faster and
        amplifies noise more.
    a : sequence of float
        The coefficients ``(a1, ..., an)``, one per order (``1..MAX_ORDER``
        entries), all ``> 0``, with ``s^n + a1 s^(n-1) + ... + an`` Hurwitz;
        dimensionless.
    discretization : {'exact', 'euler', 'tustin', 'foh'}, default 'exact'
        How the continuous differentiator is discretized for the sample
        period: 'exact' (zero-order hold), 'euler' (forward), 'tustin'
        (bilinear) or 'foh' (first-order hold: the measurement is the
        straight line through the samples, and the estimate of a sample
        uses that sample; famcc's choice below 1 kHz, see ``for_rate``).
    limits : sequence of float, default None
        Saturation ``|z_hat_i| <= limit_i`` of the estimates fed to the law,
        one per order, in the unit of each estimate (``z_k`` in the unit of
        ``e`` per s^(k-1)), all ``> 0`` (``inf``: no limit for that
        estimate); None: no limits.
    prefilter : float, default 0.0
        Time constant ``tau`` of a first-order low-pass stage on the measured
        error in front of the differentiator, s (``>= 0``; 0: none, the
        paper's differentiator). Against measurement noise: it rolls the
        noise off by one more order above ``1/tau`` for a lag of about
        ``tau``; :func:`famcc.design` with ``noise_std`` sets ``mu / 2``. Not
        in the paper.

    Raises
    ------
    famcc.ConfigError
        ``mu <= 0``, coefficients that are not Hurwitz, ``limits`` of the
        wrong length or not ``> 0``, or ``prefilter < 0``.

    Examples
    --------
    >>> import famcc
    >>> h = famcc.HighGain(0.01, [4.0, 4.0])
    >>> h.a, h.discretization, h.limits, h.prefilter
    ((4.0, 4.0), 'exact', None, 0.0)
    >>> famcc.HighGain.default(2) == h
    True
    >>> famcc.HighGain(0.02, [4.0, 6.0, 4.0], prefilter=0.01)
    HighGain(mu=0.02, a=[4.0, 6.0, 4.0], discretization='exact', prefilter=0.01)
    """

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls,
        mu: float,
        a: Sequence[float],
        discretization: _Discretization = "exact",
        limits: Sequence[float] | None = None,
        prefilter: float = 0.0,
    ) -> HighGain: ...
    @staticmethod
    def default(
        order: int, mu: float = 0.01, discretization: _Discretization = "exact"
    ) -> HighGain:
        """The paper's differentiator for an order (famcc-core's ``HighGain::paper``).

        Parameters
        ----------
        order : int
            The order n, ``1 <= order <= MAX_ORDER``.
        mu : float, default 0.01
            The gain's time constant, s (the paper's).
        discretization : {'exact', 'euler', 'tustin'}, default 'exact'
            As for the constructor.

        Returns
        -------
        HighGain
            ``a = (4, 4)`` at order 2, ``(4, 6, 4)`` at order 3, the binomial
            ``(s + 2)^n`` otherwise; no limits.

        Raises
        ------
        famcc.ConfigError
            An order outside ``1..MAX_ORDER`` or ``mu <= 0``.
        """
    @staticmethod
    def for_rate(order: int, dt: float) -> HighGain:
        """famcc's default differentiator for an order and a sample period.

        famcc-core's ``HighGain::auto_at``: the paper's differentiator at
        ``dt <= 1 ms`` (up to order 3); at slower rates a faster ``mu`` that
        keeps the loop's delay. Up to order 3: the exact hold while
        ``mu >= 10 dt`` (the paper's: 1 kHz and faster), else the first-order hold
        ('foh'), whose estimate uses the current sample, with
        ``mu = 0.01 - (dt - 3 ms) / order`` (at most 0.01, at least
        ``dt / 2``). From order 4 on Tustin, with
        ``mu = 0.01 - (3 / order) (dt - 1 ms)`` (at least ``min(dt, 0.01)``).

        Parameters
        ----------
        order : int
            The differentiator's order (the plant's order), 1 to 8.
        dt : float
            The sample period, s.

        Returns
        -------
        HighGain
            The differentiator famcc picks for that rate.

        Raises
        ------
        famcc.ConfigError
            If ``order`` is out of range or ``dt`` is not finite and > 0.

        Examples
        --------
        >>> import famcc
        >>> h = famcc.HighGain.for_rate(3, 5e-3)   # 200 Hz
        >>> round(h.mu, 6), h.discretization
        (0.009333, 'foh')
        """
    @staticmethod
    def discretization_for(order: int, dt: float, mu: float) -> _Discretization:
        """The discretization famcc picks for a differentiator sampled at ``dt``.

        famcc-core's ``auto_discretization_at`` (also ``famcc.design``'s and
        :meth:`for_rate`'s): up to order 3 'exact' while ``mu >= 10 dt`` (the
        paper's ratio), 'foh' (first-order hold) at coarser sampling; 'tustin'
        from order 4 on.

        Parameters
        ----------
        order : int
            The differentiator's order (the plant's order), 1 to 8.
        dt : float
            The sample period, s.
        mu : float
            The differentiator's time constant, s.

        Returns
        -------
        str
            'exact', 'foh' or 'tustin'.

        Raises
        ------
        famcc.ConfigError
            If ``order`` is out of range, or ``dt`` or ``mu`` is not finite and > 0.

        Examples
        --------
        >>> import famcc
        >>> H = famcc.HighGain
        >>> H.discretization_for(2, 1e-3, 0.01), H.discretization_for(2, 5e-3, 0.01)
        ('exact', 'foh')
        """
    @property
    def mu(self) -> float:
        """The gain's time constant, s."""
    @property
    def a(self) -> tuple[float, ...]:
        """The coefficients ``(a1, ..., an)``."""
    @property
    def discretization(self) -> _Discretization:
        """'exact', 'euler', 'tustin' or 'foh'."""
    @property
    def limits(self) -> tuple[float, ...] | None:
        """The estimates' limits, or None."""
    def __eq__(self, value: object, /) -> bool: ...
    @property
    def prefilter(self) -> float:
        """The prefilter's time constant, s (0: none)."""
    def __getnewargs__(self) -> tuple[float, list[float], str, list[float] | None, float]: ...

@final
class Observer:
    """The extended high-gain observer: disturbance estimation (beyond the paper).

    Estimates the error's derivatives and the lumped term ``L`` of
    ``z1^(n) = L + b0 u`` (everything the nominal input gain ``b0`` does not
    explain: the plant's own dynamics, loads, the gain error) from the error
    samples and the applied input. Passed as ``observer=`` to
    :class:`Controller`, it replaces the differentiator, and the command
    becomes ``u = v - clip(Lhat / b0, -delta, delta)``: the law's ``v`` on the
    same manifold and envelope holds only what the cancellation does not,
    which removes the steady error of a holding input. Frozen, comparable
    and picklable.

    Parameters
    ----------
    mu : float
        The time constant ``mu``, s (``> 0``): smaller is faster and
        amplifies noise more (about 20 sample periods is a start).
    b0 : float
        The nominal input gain, output units per input unit per s^n
        (nonzero; its sign is the control direction). A 20 % error is
        lumped into ``L`` and cancelled with it.
    a : sequence of float, default None
        The coefficients ``(a1, ..., an, a(n+1))`` of
        ``s^(n+1) + a1 s^n + ... + a(n+1)``, Hurwitz, one more than the
        order; None: the binomial ``(s + 2)^(n+1)`` at the controller's order.
    discretization : {'exact', 'foh'}, default 'exact'
        How the measurement is sampled: held ('exact') or the straight line
        through the samples ('foh': no lag from the hold on a moving error).

    Raises
    ------
    famcc.ConfigError
        ``mu <= 0``, ``b0 == 0``, coefficients that are not Hurwitz or of a
        length outside ``2..MAX_ORDER + 1``, or another discretization
        (naming ``observer_mu``, ``b0``, ``observer_a``,
        ``observer_discretization``).

    Examples
    --------
    >>> import famcc
    >>> obs = famcc.Observer(0.02, 1.5)
    >>> obs.mu, obs.b0, obs.a, obs.discretization
    (0.02, 1.5, None, 'exact')
    >>> c = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.7), constraint="lateral",
    ...                      eps=0.1, k_u=5.0, observer=obs, cancellation_limit=4.0)
    >>> c.config()["observer"] == obs, c.config()["differentiator"] is None
    (True, True)
    """

    __hash__: ClassVar[None]  # type: ignore[assignment]
    def __new__(
        cls,
        mu: float,
        b0: float,
        a: Sequence[float] | None = None,
        discretization: Literal["exact", "foh"] = "exact",
    ) -> Observer: ...
    @property
    def mu(self) -> float:
        """The time constant, s."""
    @property
    def b0(self) -> float:
        """The nominal input gain."""
    @property
    def a(self) -> tuple[float, ...] | None:
        """The coefficients ``(a1, ..., a(n+1))``, or None (the binomial default)."""
    @property
    def discretization(self) -> str:
        """'exact' or 'foh'."""
    def __eq__(self, value: object, /) -> bool: ...
    def __getnewargs__(self) -> tuple[float, float, list[float] | None, str]: ...

# -- controller ------------------------------------------------------------------

@final
class Diagnostics:
    """What a controller's last step did (read-only).

    Returned by ``Controller.diagnostics``; not constructed directly. A
    snapshot: it does not change when the controller steps again. The
    attributes are the quantities of the step in the paper's notation:
    the constraint variables ``xi`` (eq. (28) (xi)) and ``xi~`` (eq. (31)
    (Wxi)), the manifold ``s`` (eq. (11) (IS)), the envelopes' bounds
    (eqs. (21) (xUxL), (22) (yUyL)) and their flexible expansion (eq. (30)
    (WxyUxyL)), and the estimate ``z_hat`` of the differentiator (eq. (34)
    (HGD)).

    Examples
    --------
    >>> import famcc
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
    ...                         constraint="lateral", eps=0.1, k_u=5.0)
    >>> v = ctrl.step(-1.0)
    >>> d = ctrl.diagnostics
    >>> d.v == v, d.t, d.expanded, d.saturation_gap is None
    (True, 0.0, False, True)
    >>> abs(d.xi) < 1.0
    True
    """

    @property
    def t(self) -> float:
        """Time of the last sample, s."""
    @property
    def xi(self) -> float:
        """Constraint variable used for the output (flexible xi~)."""
    @property
    def xi_nominal(self) -> float:
        """Nominal constraint variable xi (eq. (28))."""
    @property
    def s(self) -> float:
        """Manifold value s = s_n."""
    @property
    def stages(self) -> _F64Array:
        """s_1..s_n (NumPy array)."""
    @property
    def s_prev(self) -> float:
        """s_{n-1}."""
    @property
    def ds_prev(self) -> float:
        """d/dt s_{n-1}."""
    @property
    def bounds(self) -> tuple[float, float]:
        """Flexible upper bounds (x~_U, y~_U)."""
    @property
    def nominal_bounds(self) -> tuple[float, float]:
        """Nominal upper bounds (x_U, y_U)."""
    @property
    def z_hat(self) -> _F64Array:
        """The estimate of the error vector (z_1..z_n) the output was computed from
        (NumPy array; with integral action the integral is `integral`).
        """
    @property
    def expanded(self) -> bool:
        """True when the flexible bounds were expanded."""
    @property
    def expansion(self) -> float:
        """Expansion factor of the flexible bounds (flexible / nominal, 1.0 when nominal)."""
    @property
    def saturation_gap(self) -> float | None:
        """v_{k-1} - applied, when `applied` was passed."""
    @property
    def clamp_count(self) -> int:
        """Steps at which |xi| had to be clamped below 1."""
    @property
    def v_unlimited(self) -> float:
        """The law's output -k_u Gamma(xi) - cancellation before the output limits."""
    @property
    def cancellation(self) -> float:
        """The observer's cancellation clip(Lhat / b0, -delta, delta) in the
        output (0.0 without an observer).
        """
    @property
    def integral(self) -> float | None:
        """The integral I of the error the output used (integral=True), else None."""
    @property
    def integrating(self) -> bool:
        """True when this step added its sample to I (False while the integral
        separation froze it, and without integral action).
        """
    @property
    def unsaturated_expansions(self) -> int:
        """Steps so far at which the bounds were expanded while the actuator was
        known to have headroom (`applied` passed or output limits set).
        """
    @property
    def v(self) -> float:
        """The output returned (after the output limits, when configured)."""

@final
class Controller:
    """The FAMCC controller: fully actuated manifold constraint control.

    A model-free output-feedback controller for an unknown strict-feedback
    plant of order n (eq. (5) (SFS)). It drives the tracking error to the
    preset accuracy ``eps`` within the preset time ``settle_time`` and keeps
    working when the actuator saturates. The sign convention of every step
    method is ``e = y - y_d`` (the output minus the reference: the opposite of
    a PID's ``setpoint - y``); :meth:`step_output` takes ``y`` and ``y_d`` and
    forms it.

    Parameters
    ----------
    order : int
        The plant's order n (the relative degree of the output),
        ``1 <= order <= MAX_ORDER``.
    dt : float
        Sample period, s (``> 0``); :meth:`step_dt` takes a one-off period.
    feedback : Linear, FiniteTime, FixedTime, VariableExponent, MoulayDiscontinuous or a sequence of them, default None
        The stage laws ``h_p`` of the iterative manifold (eq. (11) (IS)): one
        law for every stage, or a list of ``order - 1`` (``order`` with
        integral action), first stage first. Required at order >= 2; omitted
        (or empty) at order 1, which has no stages.
    skew : Smooth, Nonsingular, None or a sequence of them, default None
        The skews of the stage laws (eqs. (14) (SSMD), (15) (NSMD)): one for
        every stage, or one per stage (a None entry: that stage unskewed).
        None: no stage is skewed.
    constraint : {'longitudinal', 'lateral', 'oblique'}, default 'longitudinal'
        The manifold constraint (paper Step C1): LoMC constrains ``s``
        itself, LaMC ``s_{n-1} - h_v(ds_{n-1})``, OMC the oblique combination
        of both (eq. (27) (xyc)).
    eps : float or (float, float)
        Final half-widths of the constraint (required): ``eps_y`` (unit of
        ``s``) for 'longitudinal', ``eps_x`` (unit of ``s_{n-1}``) for
        'lateral', the pair ``(eps_x, eps_y)`` for 'oblique'. With the
        paper's choice ``eps_x = eps_z`` at order 2 it is the output accuracy,
        in the unit of ``y``.
    settle_time : float, default 1.0
        Preset settling time ``T_s`` of the envelopes (eqs. (21) (xUxL),
        (22) (yUyL)), s (``> 0``).
    k0 : float, default 2.0
        Initial-width factor of the envelopes, dimensionless, ``k0 > 1``
        (eqs. (21)-(22)).
    k_u : float
        Control gain ``k_u > 0`` (required), input units: the output is
        ``v = -k_u Gamma(xi)`` (eq. (29) (uT)).
    gamma : {'log', 'rational'}, default 'log'
        The map ``Gamma`` of eq. (29) (uT): 'log' is
        ``ln((1 + xi)/(1 - xi)) = 2 atanh(xi)``, 'rational' is
        ``xi / ((1 + xi)(1 - xi))``.
    rho_e : float, 'auto' or None, default 'auto'
        The flexible-boundary margin ``rho_e`` of eq. (30) (WxyUxyL), in the
        unit of the constrained variable: 'auto' is ``min(0.01, eps / 10)``
        (the smallest final width), None turns the flexible boundary off.
        :meth:`config` shows the margin in effect.
    differentiator : HighGain, 'auto' or None, default 'auto'
        The high-gain differentiator (eq. (34) (HGD)) that estimates
        ``e', ..., e^(n-1)`` from ``e`` (eq. (35) (uOF)): 'auto' is the
        paper's (exact) up to order 3 and
        ``HighGain.default(order, discretization="tustin")`` above, none at
        order 1 (which needs none); None: state feedback only
        (:meth:`step_state`).
    latch : {'paper', 'authors'}, default 'paper'
        How the envelopes' initial width is latched from the first sample's
        offset ``s0``: 'paper' (text after eq. (22) (yUyL))
        ``rho0 = k0 max(|s0|, eps)``, 'authors' (the authors' code)
        ``rho0 = max(k0 |s0|, eps)``.
    transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
        The transition ``S`` of the flexible boundary: 'exponential' is the
        paper's eq. (2) (trnsS), C-infinity; 'cubic' ``3z^2 - 2z^3``;
        'quintic' ``10z^3 - 15z^4 + 6z^5``; 'sine' ``(1 - cos(pi z)) / 2``.
    initial_derivatives : sequence of float, default None
        The differentiator's initial estimates of ``(z2, ..., zn)``
        (``order - 1`` entries, ``z_k`` in the unit of ``e`` per s^(k-1));
        None: zeros.
    dtype : {'float64', 'float32'}, default 'float64'
        The float type of the core's arithmetic (the API takes and returns
        Python floats either way).
    integral : bool, default False
        Integral action (docs/design.md §3.8). The law of order
        ``n + 1`` acts on ``(I, e, e', ..., e^(n-1))`` with ``I`` the exact integral
        of the measured error (rectangle rule), so a constant load is carried by
        ``I`` and the error tends to 0. ``feedback`` and ``skew`` then have ``order``
        entries (one per stage of the order ``n + 1`` law), the differentiator keeps
        ``order`` coefficients (it runs on ``e``), ``initial_derivatives`` stay the
        plant's ``(z2..zn)``. The integral is separated (anti-windup): ``e`` is
        integrated only while ``|s| <= eps`` (the final band) and not while the
        output is beyond a known limit with ``e`` pushing it further. Needs
        ``order < MAX_ORDER``.
    output_limits : (float, float), default None
        Magnitude limits ``(lo, hi)`` of the output, ``lo < hi``, input units.
        :meth:`step` returns the limited output; it counts as the
        applied input for the integral separation and the health count, and
        ``diagnostics.v_unlimited`` keeps the law's own output.
    rate_limit : float, default None
        The output's largest rate of change, input units per second.
    initial_output : float, default None
        Bumpless start, input units: the first step's output equals
        ``initial_output`` when that is feasible (with integral action by the
        choice of ``I_0``; without, by rescaling the latched widths), else the
        nearest feasible output.
    observer : Observer, default None
        Disturbance estimation (beyond the paper, docs/observer.md): the
        extended observer replaces the differentiator (``differentiator`` must
        be 'auto', which then means none, or None) and the output becomes
        ``u = v - clip(Lhat / b0, -delta, delta)``, ``v`` the same law on the
        observer's estimates; the output limits apply to ``u``. Needs
        ``integral=False`` (the estimate of the lumped term removes the steady
        error instead). None: the paper's controller.
    cancellation_limit : float, default None
        The bound ``delta > 0`` of the observer's cancellation, input units.
        None: half the range of ``output_limits`` (``U`` for ``(-U, U)``);
        required with an observer and no finite ``output_limits``.
    direction : {'positive', 'negative'}, default 'positive'
        The control direction, the sign of the plant's input gain ``G`` in
        ``y^(n) = F + G u`` (beyond the paper, which assumes ``G > 0``): with
        'negative' the law's sign is reversed, ``v = +k_u Gamma(xi)``, for a
        plant whose output falls when its input rises (a cooler, a magnetic
        levitation, a reversed actuator). Limits, ``initial_output`` and the
        applied input stay in the actuator's units; an observer's ``b0`` must
        have the same sign.

    Raises
    ------
    famcc.ConfigError
        An invalid value or combination; the message names the parameter
        and the rule.

    Warns
    -----
    famcc.DesignWarning
        At construction, once per legal but risky choice (:meth:`lint`): dt too
        coarse for mu, a last-stage law that chatters when sampled, rho_e too
        large for eps, no estimate limits at differentiator order >= 4, the
        exact ZOH at order >= 4. While stepping with the applied input known
        (``applied`` passed or ``output_limits`` set), once, when the bounds
        were expanded although the actuator had headroom for half the envelope's
        settling time in total (``diagnostics.unsaturated_expansions >=
        0.5 settle_time / dt``: persistent, not a start-up transient or the
        recovery after a saturation): ``k_u`` too small for the plant.

    See Also
    --------
    ControllerBank : n copies stepped together from an array.
    famcc.design : a design from the plant's limits and the wanted accuracy.

    Notes
    -----
    The output is the flexible manifold constraint controller
    ``v = -k_u Gamma(xi~)`` (eqs. (31) (Wxi), (32) (WuT)) on the iterative
    manifold ``s = s_n`` (eq. (11) (IS)), fed by the differentiator's
    estimate (eq. (35) (uOF)). The defaults are famcc-core's (every example
    of the paper). A controller can be copied, pickled, and continued from
    :meth:`state`.

    Examples
    --------
    Example 1 of the paper (LaMC, finite-time law):

    >>> import famcc
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
    ...                         constraint="lateral", eps=0.1, k_u=5.0)
    >>> round(ctrl.step(-1.0), 4)
    5.4931
    >>> ctrl.config()["settle_time"], ctrl.config()["k0"]
    (1.0, 2.0)
    """

    def __new__(
        cls,
        order: int,
        dt: float,
        feedback: _Law | Sequence[_Law] | None = None,
        *,
        skew: _Skew | Sequence[_Skew | None] | None = None,
        constraint: _Constraint = "longitudinal",
        eps: float | tuple[float, float],
        settle_time: float = 1.0,
        k0: float = 2.0,
        k_u: float,
        gamma: _Gamma = "log",
        rho_e: float | Literal["auto"] | None = "auto",
        differentiator: HighGain | Literal["auto"] | None = "auto",
        latch: _Latch = "paper",
        transition: _Transition = "exponential",
        initial_derivatives: Sequence[float] | None = None,
        dtype: _DType = "float64",
        integral: bool = False,
        output_limits: tuple[float, float] | None = None,
        rate_limit: float | None = None,
        initial_output: float | None = None,
        observer: Observer | None = None,
        cancellation_limit: float | None = None,
        direction: Literal["positive", "negative"] = "positive",
    ) -> Controller: ...
    @property
    def dt(self) -> float:
        """Sample period, s."""
    @property
    def order(self) -> int:
        """System order n."""
    @property
    def dtype(self) -> _DType:
        """ "float64" or "float32"."""
    @property
    def time(self) -> float:
        """Time of the next sample, s."""
    @property
    def diagnostics(self) -> Diagnostics:
        """What the last step did."""
    @property
    def lumped(self) -> float:
        """The observer's estimate ``Lhat`` of the lumped term, output units
        per s^n (0.0 without an observer; ``Lhat / b0`` is what it cancels).
        """
    @property
    def estimate(self) -> _F64Array:
        """The estimate the next step will use (NumPy array; with integral
        action the integral `I` first, then the plant's `z1..zn`).
        """
    @property
    def spec(self) -> ControllerSpec:
        """The configuration (a :class:`ControllerSpec`): what the controller
        guarantees (``spec.output_accuracy()``, ``spec.corollary_time(z1_0)``)
        and copies of it (``spec.replace(...).build()``).
        """
    @property
    def integral(self) -> bool:
        """True with integral action."""
    def step(self, e: float, applied: float | None = None) -> float:
        """One output-feedback step: the error sample in, the control out.

        Parameters
        ----------
        e : float
            The error sample ``e = y - y_d`` (output minus reference, the
            opposite of a PID's ``setpoint - y``), unit of ``y``.
        applied : float, default None
            The input the actuator really gave at the previous sample, input
            units, when known (``diagnostics.saturation_gap`` then reports the
            gap, and the health warning can fire).

        Returns
        -------
        float
            The control ``v`` (input units), after ``output_limits`` and
            ``rate_limit`` when configured.

        Raises
        ------
        famcc.StepError
            A non-finite ``e`` or ``applied`` (the state is unchanged), or an
            overflow of the law.

        Warns
        -----
        famcc.DesignWarning
            Once, when the bounds keep expanding while the actuator has
            headroom: ``k_u`` too small for the plant.
        """
    def step_output(self, y: float, y_d: float, applied: float | None = None) -> float:
        """One step from the measured output and the reference.

        The error is ``e = y - y_d`` (the opposite of a PID's
        ``setpoint - y``); otherwise as :meth:`step`.

        Parameters
        ----------
        y : float
            The measured output.
        y_d : float
            The reference, unit of ``y``.
        applied : float, default None
            The input the actuator really gave at the previous sample, input
            units, when known.

        Returns
        -------
        float
            The control ``v``, input units.

        Raises
        ------
        famcc.StepError
            A non-finite input (the state is unchanged), or an overflow.
        """
    def lint(self) -> list[str]:
        """The legal but risky choices of this configuration.

        Returns
        -------
        list of str
            One message per finding (each was emitted as a
            ``famcc.DesignWarning`` at construction); empty when none.
        """
    def step_dt(self, e: float, dt: float, applied: float | None = None) -> float:
        """One step with a one-off sample period.

        Parameters
        ----------
        e : float
            The error sample ``e = y - y_d``, unit of ``y``.
        dt : float
            The time since the previous sample, s (``> 0``); the configured
            ``dt`` is unchanged.
        applied : float, default None
            The input the actuator really gave at the previous sample, input
            units, when known.

        Returns
        -------
        float
            The control ``v``, input units.

        Raises
        ------
        famcc.StepError
            A non-finite input or a bad ``dt`` (the state is unchanged), or an
            overflow.
        """
    def step_state(
        self, z: Sequence[float] | NDArray[np.floating[Any]], applied: float | None = None
    ) -> float:
        """One state-feedback step with the measured error vector.

        Parameters
        ----------
        z : sequence of float or numpy.ndarray
            The error vector ``z = (z1, ..., zn)``, ``order`` entries,
            ``z1 = y - y_d`` and ``z_k`` its (k-1)-th derivative (unit of ``y``
            per s^(k-1)). With integral action the controller prepends its own
            integral.
        applied : float, default None
            The input the actuator really gave at the previous sample, input
            units, when known.

        Returns
        -------
        float
            The control ``v``, input units.

        Raises
        ------
        famcc.StepError
            ``z`` not a float sequence of the right length, a non-finite
            input, or an overflow.
        """
    def reset(self) -> None:
        """Back to the state before the first step (the configuration is kept)."""
    def state(self) -> _F64Array:
        """The state as a float vector.

        Returns
        -------
        numpy.ndarray
            float64, laid out as ``STATE_FIELDS`` followed by the estimate
            ``z_hat[0..order]`` (with integral action ``order + 1`` entries:
            the integral ``I`` first). :meth:`set_state` continues from it.
        """
    def set_state(self, state: _F64Array) -> None:
        """Continues from a vector returned by :meth:`state`.

        Parameters
        ----------
        state : numpy.ndarray
            A contiguous float64 vector from :meth:`state` of a controller
            with the same configuration.

        Raises
        ------
        famcc.ConfigError
            A vector of the wrong length or layout.
        """
    def config(self) -> dict[str, Any]:
        """The configuration as keyword arguments of the constructor.

        Returns
        -------
        dict
            ``Controller(**ctrl.config())`` builds an equal controller; 'auto'
            values appear resolved (``rho_e`` the margin in effect,
            ``differentiator`` a :class:`HighGain` or None).
        """
    def __copy__(self) -> Controller: ...
    def __deepcopy__(self, _memo: Any) -> Controller: ...
    def replace(
        self,
        *,
        dt: float = ...,
        feedback: _Law | Sequence[_Law] | None = ...,
        skew: _Skew | Sequence[_Skew | None] | None = ...,
        eps: float | tuple[float, float] = ...,
        settle_time: float = ...,
        k0: float = ...,
        k_u: float = ...,
        gamma: _Gamma = ...,
        rho_e: float | Literal["auto"] | None = ...,
        differentiator: HighGain | Literal["auto"] | None = ...,
        latch: _Latch = ...,
        transition: _Transition = ...,
        initial_derivatives: Sequence[float] | None = ...,
        dtype: _DType = ...,
        output_limits: tuple[float, float] | None = ...,
        rate_limit: float | None = ...,
        initial_output: float | None = ...,
        observer: Observer | None = ...,
        cancellation_limit: float | None = ...,
        direction: Literal["positive", "negative"] = ...,
    ) -> Controller:
        """A fresh controller with this configuration and the named fields changed.

        The configuration is copied as parsed (no keyword arguments, no text):
        ``ctrl.replace(k_u=8.0)`` equals
        ``Controller(**{**ctrl.config(), 'k_u': 8.0})`` and is cheaper. The
        new controller starts from the beginning (no state is copied); its
        values are checked by famcc-core as in the constructor, and its risky
        choices warn as there.

        Parameters
        ----------
        **overrides
            Keyword arguments of :class:`Controller`, with the same types and
            meanings: ``dt``, ``feedback``, ``skew``, ``eps``, ``settle_time``,
            ``k0``, ``k_u``, ``gamma``, ``rho_e``, ``differentiator``, ``latch``,
            ``transition``, ``initial_derivatives``, ``dtype``, ``output_limits``,
            ``rate_limit``, ``initial_output``, ``observer``, ``cancellation_limit``,
            ``direction``. Not ``order``, ``constraint`` or
            ``integral``, which set the shape of the configuration (build a new
            controller for those). ``rho_e`` keeps the margin in effect (as
            ``config()`` shows it) unless given; ``rho_e='auto'`` derives it
            anew from ``eps``.

        Returns
        -------
        Controller
            The new controller.

        Raises
        ------
        famcc.ConfigError
            A value the constructor would reject (the message names it).
        TypeError
            An unknown keyword, one of ``order``, ``constraint``, ``integral``,
            or a value of the wrong type.

        Warns
        -----
        famcc.DesignWarning
            For a legal but risky configuration, as the constructor.

        Examples
        --------
        >>> import famcc
        >>> ctrl = famcc.Controller(2, 1e-3, famcc.Linear(2.0), constraint="lateral", eps=0.1, k_u=5.0)
        >>> faster = ctrl.replace(k_u=8.0)
        >>> faster.config()["k_u"], ctrl.config()["k_u"]
        (8.0, 5.0)
        """
    def __reduce__(self) -> tuple[_Rebuild, tuple[dict[str, Any], list[float]]]: ...

_Rebuild: TypeAlias = Callable[[dict[str, Any], list[float]], Controller]

@final
class ControllerSpec:
    """A controller's configuration, parsed and typed; :meth:`build` makes the
    controller.

    Returned by :func:`famcc.design` (``Design.spec``): the design's
    configuration, built into a :class:`Controller` without keyword
    arguments or text. Frozen and picklable. Its values are checked when a
    controller is built (by famcc-core, as in the :class:`Controller`
    constructor).

    Examples
    --------
    >>> import famcc
    >>> d = famcc.design(2, 1e-3, u_limits=(-12, 12), eps=0.01, settle_time=2.0,
    ...                  hold_input=4.0, gain=25.0)
    >>> spec = d.spec
    >>> spec.order, spec.dt
    (2, 0.001)
    >>> spec.build().config() == d.controller().config()
    True
    >>> spec.replace(k_u=10.0).config()["k_u"]
    10.0
    """

    @property
    def order(self) -> int:
        """System order n."""
    @property
    def dt(self) -> float:
        """Sample period, s."""
    @property
    def dtype(self) -> _DType:
        """ "float64" or "float32"."""
    def build(self) -> Controller:
        """A fresh controller of this configuration.

        Returns
        -------
        Controller
            Equal to ``Controller(**spec.config())``.

        Raises
        ------
        famcc.ConfigError
            A value famcc-core rejects (the message names it).

        Warns
        -----
        famcc.DesignWarning
            For a legal but risky configuration, as the constructor.
        """
    def replace(
        self,
        *,
        dt: float = ...,
        feedback: _Law | Sequence[_Law] | None = ...,
        skew: _Skew | Sequence[_Skew | None] | None = ...,
        eps: float | tuple[float, float] = ...,
        settle_time: float = ...,
        k0: float = ...,
        k_u: float = ...,
        gamma: _Gamma = ...,
        rho_e: float | Literal["auto"] | None = ...,
        differentiator: HighGain | Literal["auto"] | None = ...,
        latch: _Latch = ...,
        transition: _Transition = ...,
        initial_derivatives: Sequence[float] | None = ...,
        dtype: _DType = ...,
        output_limits: tuple[float, float] | None = ...,
        rate_limit: float | None = ...,
        initial_output: float | None = ...,
        observer: Observer | None = ...,
        cancellation_limit: float | None = ...,
        direction: Literal["positive", "negative"] = ...,
    ) -> ControllerSpec:
        """This configuration with the named fields changed.

        Parameters
        ----------
        **overrides
            Keyword arguments of :class:`Controller` (the types and names of
            :meth:`Controller.replace`; not ``order``, ``constraint`` or
            ``integral``). Checked when the spec is built.

        Returns
        -------
        ControllerSpec
            The changed configuration.

        Raises
        ------
        famcc.ConfigError
            A value of the wrong shape (a list of the wrong length, a name
            that is not a choice).
        TypeError
            An unknown keyword, one of ``order``, ``constraint``,
            ``integral``, or a value of the wrong type.
        """
    @staticmethod
    def from_config(config: dict[str, Any]) -> ControllerSpec:
        """The spec of a configuration given as keyword arguments.

        Parameters
        ----------
        config : dict
            Keyword arguments of :class:`Controller` with ``order`` and ``dt``,
            as :meth:`Controller.config` gives them.

        Returns
        -------
        ControllerSpec
            ``ControllerSpec.from_config(c.config()).build()`` equals ``c``.

        Raises
        ------
        famcc.ConfigError, TypeError
            As the :class:`Controller` constructor.
        """
    def output_accuracy(self) -> float | None:
        """The output accuracy ``eps_z`` the configuration presets for ``|z1|``.

        The constraint's half-width at order 1 (``s = z1``) and for LaMC at
        order 2 (``eps_x = eps_z``, Corollary 1); otherwise a skewed first
        stage's ``eps_z`` (Corollaries 2 and 3); with integral action none.

        Returns
        -------
        float or None
            None when the configuration presets no accuracy of the output.

        Raises
        ------
        famcc.ConfigError
            A configuration famcc-core rejects.

        Examples
        --------
        >>> import famcc
        >>> famcc.scenarios.paper("finite-time").controller().spec.output_accuracy()
        0.1
        """
    def corollary_time(
        self, z1_0: float | Sequence[float] | NDArray[np.float64]
    ) -> float | NDArray[np.float64] | None:
        """The reaching time ``T'`` of the paper's corollaries, s.

        Every stage ``FixedTime``: ``T_fr'`` (Corollary 3); one
        ``VariableExponent`` stage: ``T_fxe'`` (Corollary 2); one
        ``FiniteTime`` stage: ``T_fn'`` (Corollary 1), which depends on
        ``|z1(0)|``. The bound on reaching ``|z1| < eps_z`` is ``T_s + T'``.

        Parameters
        ----------
        z1_0 : float or array_like
            The initial error ``z1(0)`` (one per case).

        Returns
        -------
        float, numpy.ndarray or None
            ``T'`` in the shape of ``z1_0``; None when the laws have no
            corollary bound.

        Examples
        --------
        >>> import famcc
        >>> famcc.scenarios.paper("finite-time").controller().spec.corollary_time(-1.0)
        2.0
        """
    def config(self) -> dict[str, Any]:
        """The configuration as keyword arguments of :class:`Controller`.

        Returns
        -------
        dict
            ``Controller(**spec.config())`` builds the controller of
            :meth:`build`; ``rho_e`` is ``'auto'`` when the spec leaves it to
            famcc-core.
        """
    def __reduce__(
        self,
    ) -> tuple[Callable[[dict[str, Any]], ControllerSpec], tuple[dict[str, Any]]]: ...

@final
class ControllerBank:
    """n independent copies of a configured controller, stepped together.

    Every copy starts from the controller's configuration and state; each
    then runs on its own error sample. For Monte Carlo work: one call steps
    all copies from a NumPy array, large batches release the GIL and are
    split across threads, and the result equals stepping the copies one by
    one.

    Parameters
    ----------
    controller : Controller
        The configuration and the state every copy starts from (copied; the
        controller itself is not changed).
    n : int
        The number of copies, ``n >= 1``.

    Raises
    ------
    famcc.ConfigError
        ``n < 1``.

    Examples
    --------
    >>> import famcc, numpy as np
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
    ...                         constraint="lateral", eps=0.1, k_u=5.0)
    >>> bank = famcc.ControllerBank(ctrl, 3)
    >>> len(bank)
    3
    >>> v = bank.step(np.array([-1.0, -1.0, 0.5]))
    >>> bool(v[0] == v[1] == ctrl.step(-1.0))
    True
    """

    def __new__(cls, controller: Controller, n: int) -> ControllerBank: ...
    def __len__(self) -> int: ...
    def step(self, e: _F64Array, on_nonfinite: Literal["raise", "hold"] = "raise") -> _F64Array:
        """Steps controller i with ``e[i]``; returns the outputs.

        Equal to stepping the copies one by one. Large batches release the
        GIL and are split across threads. A controller whose law overflows on
        a valid sample consumes it and repeats its previous output (counted in
        ``overflows``).

        Parameters
        ----------
        e : numpy.ndarray
            The error samples ``e = y - y_d`` (output minus reference, the
            opposite of a PID's ``setpoint - y``), a contiguous float64 array
            of length ``n``, unit of ``y``.
        on_nonfinite : {'raise', 'hold'}, default 'raise'
            'raise': a NaN or infinite entry raises ``StepError`` before any
            controller moves. 'hold': such a lane keeps its state and repeats
            its output, the others step, and ``held`` lists the held lanes.

        Returns
        -------
        numpy.ndarray
            The outputs ``v``, float64, length ``n``, input units.

        Raises
        ------
        famcc.StepError
            ``e`` of the wrong length or not contiguous, or a non-finite entry
            with ``on_nonfinite='raise'``.
        famcc.ConfigError
            An unknown ``on_nonfinite``.
        """
    def step_output(self, y: _F64Array, y_d: _F64Array) -> _F64Array:
        """Steps controller i with the error ``e[i] = y[i] - y_d[i]``; as :meth:`step`.

        Parameters
        ----------
        y : numpy.ndarray
            The measured outputs, float64, length ``n``.
        y_d : numpy.ndarray
            The references, float64, length ``n``, unit of ``y``.

        Returns
        -------
        numpy.ndarray
            The outputs ``v``, float64, length ``n``, input units.

        Raises
        ------
        famcc.StepError
            Arrays of different or wrong length, or a non-finite entry.
        """
    @property
    def overflows(self) -> int:
        """Overflowed steps in the last call of `step`."""
    @property
    def held(self) -> tuple[int, ...]:
        """The lanes held by the last `step`, in order (empty unless
        `on_nonfinite="hold"` met non-finite entries).
        """
    @property
    def xi(self) -> _F64Array:
        """The constraint variables xi~ of the last step (NumPy array)."""
    @property
    def xi_nominal(self) -> _F64Array:
        """The nominal constraint variables xi of the last step, before the
        flexible expansion and the clamp (NumPy array). Above 1 a controller's
        state left the nominal constraint set (docs/design.md §8).
        """
    @property
    def expansion(self) -> _F64Array:
        """The flexible boundaries' expansion factors of the last step (NumPy
        array): 1.0 while a controller's bounds are nominal, > 1 while expanded.
        """
    def reset(self) -> None:
        """Resets every controller to the state before its first step."""
    def controller(self, i: int) -> Controller:
        """A copy of controller i, with its configuration and current state.

        Parameters
        ----------
        i : int
            The index; negative indices count from the end, as Python's.

        Returns
        -------
        Controller
            An independent copy (stepping it does not move the bank).

        Raises
        ------
        IndexError
            ``i`` out of range.
        """

@final
class _CallFloor:
    """The floor of a Python-to-Rust method call, for the benchmarks
    (`benches/bench_step.py`): a `&mut self` method that takes and returns a
    float, like `Controller.step`, and does nothing else.
    """

    def __new__(cls) -> _CallFloor: ...
    def step(self, e: float) -> float:
        """Returns `e`."""

# -- the paper's designs and plants (famcc-paper) ---------------------------------

@final
class PaperPlant:
    """One of the paper's plants: order 2 (examples 1-2) or 3 (example 3).

    The second-order plant of eq. (44) (System_sim) or the third-order plant
    of eq. (68) (System_sim3), in variant 'paper' (as printed) or 'code' (as
    the authors ran it; docs/errata.md): right-hand side, exact output
    derivatives, gain and drift. ``famcc.plants`` builds on it.

    Parameters
    ----------
    order : int
        2 or 3.
    variant : {'paper', 'code'}
        The paper's printed plant or the authors' code.
    gain : float, default 1.0
        Factor on the input gain, dimensionless, finite and ``> 0``.
    amp : float, default None
        The disturbance amplitude, in the unit of the state's last entry per
        s; None: the variant's.
    x0 : sequence of float, default None
        The initial state, ``order`` finite entries; None: the variant's.

    Raises
    ------
    famcc.ConfigError
        An order other than 2 or 3, an unknown variant, or a value above out
        of range.

    Examples
    --------
    >>> from famcc import _core
    >>> plant = _core.PaperPlant(2, "paper")
    >>> len(plant.x0), len(plant.rhs(0.0, plant.x0, 0.0))
    (2, 2)
    """

    def __new__(
        cls,
        order: int,
        variant: str,
        gain: float = 1.0,
        amp: float | None = None,
        x0: Sequence[float] | None = None,
    ) -> PaperPlant: ...
    @property
    def x0(self) -> tuple[float, ...]:
        """The initial state."""
    def rhs(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]], u: float
    ) -> tuple[float, ...]:
        """The right-hand side ``dx/dt``.

        Parameters
        ----------
        t : float
            Time, s.
        x : sequence of float
            The state, ``order`` entries.
        u : float
            The input (after any saturation), input units.

        Returns
        -------
        tuple of float
            ``dx/dt``, ``order`` entries.
        """
    def output_derivatives(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]]
    ) -> tuple[float, ...]:
        """The output and its derivatives, exactly.

        Parameters
        ----------
        t : float
            Time, s.
        x : sequence of float
            The state, ``order`` entries.

        Returns
        -------
        tuple of float
            ``(y, y', ..., y^(n-1))``.
        """
    def gain_and_drift(
        self, t: float, x: Sequence[float] | NDArray[np.floating[Any]]
    ) -> tuple[float, float]:
        """The gain and drift of the fully actuated form (eq. (7) (FAS)).

        Parameters
        ----------
        t : float
            Time, s.
        x : sequence of float
            The state, ``order`` entries.

        Returns
        -------
        (float, float)
            ``(G_a, F_a)`` with ``y^(n) = G_a u + F_a``.
        """

# -- the simulator (famcc-sim): the private engine of famcc.sim -------------------

@final
class PaperLanes:
    """The paper's second- or third-order plant for many lanes at once, each
    with its own input-gain factor and disturbance amplitude; lane ``l``
    computes exactly what ``PaperPlant(order, variant, gain[l], amp[l])``
    computes.

    Parameters
    ----------
    order : int
        2 or 3.
    variant : {'paper', 'code'}
    gain, amp : numpy.ndarray
        One finite value per lane (``gain > 0``).
    """
    def __new__(cls, order: int, variant: str, gain: _F64Array, amp: _F64Array) -> PaperLanes: ...
    def __len__(self) -> int: ...
    def table(
        self, t: _F64Array, x: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], _F64Array, _F64Array]:
        """Lane 0's exact output derivatives, gain and drift at every sample.

        Parameters
        ----------
        t : numpy.ndarray
            Times, shape ``(K,)``.
        x : numpy.ndarray
            States, shape ``(K, order)``.

        Returns
        -------
        (numpy.ndarray, numpy.ndarray, numpy.ndarray)
            ``(y, ..., y^(n-1))`` per sample ``(K, order)``, and ``G_a``, ``F_a``
            of ``y^(n) = G_a u + F_a`` ``(K,)``: what ``PaperPlant``'s
            ``output_derivatives`` and ``gain_and_drift`` give sample by sample.
        """
    def rhs(self, t: float, x: _ArrayIn, u: _ArrayIn) -> NDArray[np.float64]:
        """``dx/dt`` of every lane.

        Parameters
        ----------
        t : float
            Time, s.
        x : numpy.ndarray
            The states, shape ``(order, lanes)``.
        u : numpy.ndarray
            The inputs, shape ``(lanes,)``.

        Returns
        -------
        numpy.ndarray
            Shape ``(order, lanes)``.
        """

@final
class Lockstep:
    """A closed loop run sample by sample (famcc-sim's ``Lockstep``): ``lanes``
    copies of a plant, ``channels`` controllers per copy; the private engine
    of :func:`famcc.simulate`, :func:`famcc.joints.simulate_joints` and
    :func:`famcc.campaign`.

    Parameters
    ----------
    plant : PaperLanes or (kind, callable)
        The paper's plant as lanes, or a Python right-hand side with kind
        ``'list'`` or ``'array'`` (one lane) or ``'lanes'`` (all at once).
    controllers : list
        One ``Controller`` (or duck-typed object with ``step(e, applied=)``)
        per channel for one lane; or ``ControllerBank`` objects whose lengths
        add up to ``lanes`` (one channel), lanes in order.
    dt : float
    samples, substeps, states : int
    x0 : sequence of float
        ``states * lanes`` values, state-major.
    outputs : list of int
        Per channel, the index of its output state.
    limits : list of (float, float) or None
        Per channel.
    diverge_at, state_bound : float, optional
    detail : {'full', 'campaign', 'none'}
    keep_states : bool
    """
    def __new__(
        cls,
        plant: PaperLanes | tuple[str, Callable[..., Any]],
        controllers: Sequence[Any],
        *,
        dt: float,
        samples: int,
        substeps: int,
        states: int,
        x0: Sequence[float],
        outputs: Sequence[int],
        limits: Sequence[tuple[float, float] | None],
        diverge_at: float | None = None,
        state_bound: float | None = None,
        detail: str = "full",
        keep_states: bool = True,
    ) -> Lockstep: ...
    @property
    def diag_columns(self) -> tuple[str, ...]:
        """The diagnostics columns per channel and lane of ``run``'s ``'diag'``."""
    @property
    def sample(self) -> int:
        """The next sample's index."""
    @property
    def done(self) -> bool:
        """True when the run is over (every lane stopped, or the last sample done)."""
    @property
    def held(self) -> int:
        """Failed steps held so far (banks)."""
    @property
    def state(self) -> _F64Array:
        """The plant's states now, state-major."""
    @property
    def stops(self) -> list[tuple[int, str] | None]:
        """Per lane, ``(samples_kept, reason)`` of a lane that stopped, else None."""
    def counts(self) -> list[tuple[int, int | None] | None]:
        """Per channel and lane, the last diagnostics' ``(clamp_count,
        unsaturated_expansions)`` (None when the controller reports none).
        """
    def run(
        self,
        yd: _F64Array,
        noise: _F64Array | None = None,
        disturbance: _F64Array | None = None,
    ) -> dict[str, Any]:
        """Runs the next ``len(yd) / (channels * lanes)`` samples.

        Parameters
        ----------
        yd, noise, disturbance : numpy.ndarray
            Contiguous float64, ``[row][channel][lane]``; noise and disturbance
            may be None.

        Returns
        -------
        dict
            ``rows`` and float64 vectors ``e``, ``e_measured``, ``v``, ``u``,
            ``d`` (``rows * channels * lanes``), ``x`` (``rows * states *
            lanes``, when kept), ``diag`` (``rows * channels * lanes * width``)
            and ``width``; ``plant_error`` (the exception) when the plant's
            right-hand side raised: the block ends there.
        """

def paper_design(example: int, variant: str) -> dict[str, Any]: ...
def paper_corollary_bound(example: int) -> float: ...
def paper_input_limits(example: int, saturated: bool) -> tuple[float, float]: ...
def paper_nominal_gain(example: int) -> float: ...

# -- functions -------------------------------------------------------------------

def _controller_from_state(kwargs: dict[str, Any], state: Sequence[float]) -> Controller: ...
def _controller_spec_from_kwargs(kwargs: dict[str, Any]) -> ControllerSpec: ...
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
