"""The record of a closed-loop run (:class:`SimResult`): its data, and views of
it (summary text, figure, HTML, data frame). The metrics are
:mod:`famcc.metrics`' functions; the methods of the same names call them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from famcc import metrics
from famcc._common import Signal
from famcc.sim import views
from famcc.summary import Summary, describe_controller, summarize

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["SimResult"]

#: The per-sample arrays of a result (cut together by :meth:`SimResult.truncated`).
PER_SAMPLE = (
    "t",
    "y",
    "y_d",
    "x",
    "z",
    "v",
    "u",
    "z_hat",
    "xi",
    "s",
    "s_prev",
    "ds_prev",
    "bounds",
    "nominal_bounds",
    "expanded",
    "neg_f_over_g",
    "xi_nominal",
    "expansion",
    "z1_measured",
    "disturbance",
)


@dataclass
class SimResult:
    """Recorded closed loop, one row per controller sample.

    Attributes
    ----------
    t : ndarray, shape (K,)
        Sample times ``k dt``.
    y, y_d : ndarray, shape (K,)
        Plant output and reference at the samples.
    x : ndarray, shape (K, n)
        Plant state at the samples.
    z : ndarray, shape (K, n)
        True error vector ``z_i = y^(i-1) - y_d^(i-1)``; columns after the first are
        NaN when the plant cannot report its output derivatives.
    v, u : ndarray, shape (K,)
        Controller output and applied (saturated) input, held over ``[t_k, t_k + dt)``.
    dt : float
        Sample period.
    u_limits : (float, float) or None
        Actuator limits, None when unsaturated.
    z_hat, xi, s, s_prev, ds_prev, bounds, nominal_bounds, expanded : ndarray or None
        Controller diagnostics read after each step (None when not recorded).
        ``bounds`` and ``nominal_bounds`` have shape (K, 2): flexible / nominal upper
        bounds in the x and y directions.
    xi_nominal : ndarray or None
        The nominal constraint variable ``xi`` (before the flexible expansion). Unlike
        ``xi`` (= ``xi~``, which stays below 1 by construction once the bounds expand),
        it shows how far the state really left the nominal constraint set.
    expansion : ndarray or None
        The flexible boundary's expansion factor (flexible / nominal bound, 1.0 while
        the bounds are nominal).
    clamp_count : int
        The controller's final clamp count.
    unsaturated_expansions : int or None
        Steps at which the controller's bounds were expanded while the actuator had
        headroom (famcc's controllers count them because :func:`simulate` passes
        ``applied``): nonzero means the preset accuracy was given up without
        saturation, ``k_u`` too small for the plant or ``rho_e`` too large. None when
        not recorded or the controller does not count them.
    neg_f_over_g : ndarray or None
        ``-F/G`` (the input that holds ``dz_n/dt = 0``), None when unknown; then
        ``neg_f_over_g_error`` says why.
    output, input : famcc.Signal
        Names and units of the plant's output and input (from the plant or from
        :func:`simulate`'s ``output=`` / ``input=``); figures and reports use them.
    controller_repr : str or None
        ``repr`` of the controller at the start of the run (its configuration).
    controller_config : dict or None
        ``controller.config()`` when the controller has one (famcc's
        :class:`famcc.Controller` does): constraint, eps, settle_time, laws, ...
    reference_repr : str or None
        What the reference was (``"Sine(...)"``, ``"constant 0.0"``, ...).
    neg_f_over_g_error, derivatives_error : str or None
        Why ``-F/G``, or the error's derivatives ``z_2..z_n``, are unknown (the
        plant's own error text, or the missing ingredient); None when known.
    z1_measured : ndarray or None
        The error the controller was given, ``y + n - y_d`` (output unit), when
        :func:`simulate` added measurement noise ``n``; None without noise.
        ``z`` stays the true, noise-free error.
    disturbance : ndarray or None
        The input disturbance ``d`` added to the applied input (input unit),
        held over each sample period like ``u``; None without one. The plant
        receives ``u + d``.
    diverged_at : float or None
        Time (s) at which :func:`simulate` stopped the run because it diverged
        (``|z1|`` beyond ``diverge_at``, or a non-finite state or controller
        output); the arrays end with that sample. None when the run completed.

    Examples
    --------
    >>> t = np.array([0.0, 0.1, 0.2, 0.3, 0.4])
    >>> z1 = np.array([1.0, 0.05, 0.2, 0.01, 0.0])
    >>> r = SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None],
    ...               v=0 * t, u=0 * t, dt=0.1)
    >>> r.first_entry(0.1), r.settling_time(0.1)
    (0.1, 0.3)
    >>> for part in r.summary(eps=0.1).text.split("; "):
    ...     print(part)
    settled to |z1| < 0.1 at 0.3 s (first entry 0.1 s)
    steady RMS 0.00707
    u ripple after settling 0 (peak-to-peak)
    IAE 0.076 s
    RMS u 0
    TV(u) 0/s
    no controller diagnostics recorded (no xi, no bounds)
    no actuator limits
    """

    t: np.ndarray
    y: np.ndarray
    y_d: np.ndarray
    x: np.ndarray
    z: np.ndarray
    v: np.ndarray
    u: np.ndarray
    dt: float
    u_limits: tuple[float, float] | None = None
    z_hat: np.ndarray | None = None
    xi: np.ndarray | None = None
    s: np.ndarray | None = None
    s_prev: np.ndarray | None = None
    ds_prev: np.ndarray | None = None
    bounds: np.ndarray | None = None
    nominal_bounds: np.ndarray | None = None
    expanded: np.ndarray | None = None
    clamp_count: int = 0
    unsaturated_expansions: int | None = None
    neg_f_over_g: np.ndarray | None = None
    xi_nominal: np.ndarray | None = None
    expansion: np.ndarray | None = None
    output: Signal = field(default_factory=lambda: Signal("y"))
    input: Signal = field(default_factory=lambda: Signal("u"))
    controller_repr: str | None = None
    controller_config: dict[str, Any] | None = field(default=None, repr=False)
    reference_repr: str | None = None
    neg_f_over_g_error: str | None = None
    derivatives_error: str | None = None
    z1_measured: np.ndarray | None = None
    disturbance: np.ndarray | None = None
    diverged_at: float | None = None
    _png: bytes | None = field(default=None, init=False, repr=False, compare=False)

    # -- what the run was --------------------------------------------------------
    @property
    def constraint(self) -> str | None:
        """The controller's constraint (``"lateral"``, ``"longitudinal"``, ``"oblique"``).

        None when the controller has no famcc configuration (a duck-typed one).
        """
        kind = (self.controller_config or {}).get("constraint")
        return str(kind) if kind is not None else None

    @property
    def settle_time(self) -> float | None:
        """The envelope's preset time ``T_s`` (s) from the configuration, or None."""
        return metrics.as_float((self.controller_config or {}).get("settle_time"))

    @property
    def accuracy(self) -> float | None:
        """The output accuracy ``eps_z`` that the configuration presets, or None
        (:func:`famcc.metrics.preset_accuracy`): then give ``eps`` to
        :meth:`summary`, :meth:`plot` or :func:`famcc.report` yourself."""
        return metrics.preset_accuracy(self.controller_config)

    @property
    def controller_description(self) -> str:
        """One line: constraint, laws, eps, ``T_s``, ``k_u`` (or the controller's type)."""
        return describe_controller(self.controller_config, self.controller_repr)

    @property
    def diverged(self) -> bool:
        """True when :func:`famcc.simulate` stopped the run as diverged (see ``diverged_at``)."""
        return self.diverged_at is not None

    def truncated(self, k: int) -> None:
        """Keeps the first ``k`` samples of every per-sample array (in place)."""
        for name in PER_SAMPLE:
            arr = getattr(self, name)
            if arr is not None:
                setattr(self, name, arr[:k])

    # -- metrics (famcc.metrics) ---------------------------------------------------
    @property
    def z1(self) -> np.ndarray:
        """Tracking error ``y - y_d``."""
        return metrics.z1(self)

    def settling_time(self, eps: float) -> float | None:
        """:func:`famcc.metrics.settling_time`."""
        return metrics.settling_time(self, eps)

    def first_entry(self, eps: float) -> float | None:
        """:func:`famcc.metrics.first_entry`."""
        return metrics.first_entry(self, eps)

    def steady_rms(self, eps: float) -> float | None:
        """:func:`famcc.metrics.steady_rms`."""
        return metrics.steady_rms(self, eps)

    def ripple(self, eps: float) -> float | None:
        """:func:`famcc.metrics.ripple`."""
        return metrics.ripple(self, eps)

    def z1_ripple(self, eps: float) -> float | None:
        """:func:`famcc.metrics.z1_ripple`."""
        return metrics.z1_ripple(self, eps)

    def never_settled(self, eps: float) -> bool:
        """:func:`famcc.metrics.never_settled`."""
        return metrics.never_settled(self, eps)

    def saturation_episodes(self) -> list[tuple[float, float]]:
        """:func:`famcc.metrics.saturation_episodes`."""
        return metrics.saturation_episodes(self)

    @property
    def max_abs_xi(self) -> float | None:
        """:func:`famcc.metrics.max_abs_xi`."""
        return metrics.max_abs_xi(self)

    @property
    def max_abs_xi_nominal(self) -> float | None:
        """:func:`famcc.metrics.max_abs_xi_nominal`."""
        return metrics.max_abs_xi_nominal(self)

    @property
    def expanded_fraction(self) -> float | None:
        """:func:`famcc.metrics.expanded_fraction`."""
        return metrics.expanded_fraction(self)

    @property
    def expanded_unsaturated_fraction(self) -> float | None:
        """:func:`famcc.metrics.expanded_unsaturated_fraction`."""
        return metrics.expanded_unsaturated_fraction(self)

    @property
    def u_min(self) -> float:
        """Smallest applied input."""
        return float(np.min(self.u))

    @property
    def u_max(self) -> float:
        """Largest applied input."""
        return float(np.max(self.u))

    @property
    def saturated(self) -> np.ndarray:
        """:func:`famcc.metrics.saturated`."""
        return metrics.saturated(self)

    @property
    def saturated_fraction(self) -> float:
        """:func:`famcc.metrics.saturated_fraction`."""
        return metrics.saturated_fraction(self)

    @property
    def last_saturation_end(self) -> float | None:
        """:func:`famcc.metrics.last_saturation_end`."""
        return metrics.last_saturation_end(self)

    @property
    def largest_expansion(self) -> float | None:
        """:func:`famcc.metrics.largest_expansion`."""
        return metrics.largest_expansion(self)

    @property
    def nominal_return_time(self) -> float | None:
        """:func:`famcc.metrics.nominal_return_time`."""
        return metrics.nominal_return_time(self)

    @property
    def iae(self) -> float:
        """:func:`famcc.metrics.iae`."""
        return metrics.iae(self)

    @property
    def rms_u(self) -> float:
        """:func:`famcc.metrics.rms_u`."""
        return metrics.rms_u(self)

    @property
    def tv_u_per_s(self) -> float:
        """:func:`famcc.metrics.tv_u_per_s`."""
        return metrics.tv_u_per_s(self)

    # -- views -------------------------------------------------------------------
    def summary(self, eps: float | None = None) -> Summary:
        """The run's metrics as a dict, with a short text (:func:`famcc.summary.summarize`).

        Parameters
        ----------
        eps : float, optional
            Accuracy for the settling time, steady RMS and ripple. Default: the
            accuracy the controller's configuration presets (:attr:`accuracy`);
            when there is none, those metrics are None and the text says so.

        Examples
        --------
        >>> t = np.arange(0.0, 2.001, 0.5)
        >>> r = SimResult(t=t, y=t, y_d=0 * t, x=t[:, None],
        ...               z=np.array([[1.0], [0.5], [0.05], [0.02], [0.0]]),
        ...               v=np.array([4.0, 2.0, 1.0, 0.0, 1.0]),
        ...               u=np.array([3.0, 2.0, 1.0, 0.0, 1.0]), dt=0.5, u_limits=(-3, 3))
        >>> s = r.summary(eps=0.1)
        >>> s["settling_time"], s["ripple"], s["saturated_fraction"]
        (1.0, 1.0, 0.2)
        >>> s.text.splitlines()[1]
        'no controller diagnostics recorded (no xi, no bounds); saturated 20 % of the samples'
        """
        return summarize(self, eps)

    def __repr__(self) -> str:
        return views.text_view(self)

    def plot(
        self,
        panels: Sequence[str] | None = None,
        *,
        window: tuple[float, float] | None = None,
        eps: float | None = None,
        title: str | None = None,
    ) -> Figure:
        """The ``famcc reproduce`` figure of this run; returns the matplotlib Figure.

        Parameters
        ----------
        panels : sequence of str, optional
            Which panels, in order, from ``"error"`` (``z`` and its estimate),
            ``"accuracy"`` (``z1`` with the eps band and the settling time),
            ``"constraint"`` (the constrained value with its nominal and flexible
            bounds), ``"input"`` (``u``, the limits, saturation, ``-F/G``) and
            ``"xi"`` (the nominal ``xi`` and ``xi~``). Default: all that the run
            recorded.
        window : (t0, t1), optional
            Time window in seconds (default: the whole run; the accuracy panel
            then starts at ``T_s``).
        eps : float, optional
            Accuracy band (default: :attr:`accuracy`).
        title : str, optional
            Figure title (default: the plant's output, the controller, ``dt``).

        See Also
        --------
        famcc.plot.figure : the same figure from a function; docs/figures.md explains it.
        """
        from famcc.plot import figure  # deferred: famcc.plot loads matplotlib

        return figure(self, panels, window=window, eps=eps, title=title)

    def _repr_png_(self) -> bytes:
        """The figure as PNG (Jupyter); drawn once per result."""
        if self._png is None:
            self._png = views.png(self)
        return self._png

    def _repr_html_(self) -> str:
        """The summary as a table and the figure (Jupyter)."""
        return views.html_view(self)

    def to_dataframe(self) -> Any:
        """The recorded arrays as a :class:`pandas.DataFrame` indexed by time.

        One column per recorded signal, ``df.attrs`` the names and units
        (:func:`famcc.sim.views.dataframe` lists them). Needs pandas (optional).
        """
        return views.dataframe(self)
