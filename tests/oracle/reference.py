"""A pure-Python reference implementation of the FAMCC control law (a test oracle).

:class:`ReferenceController` computes the same discrete-time controller as the
compiled :class:`famcc.Controller` (docs/design.md §3), written independently from
the paper's definitions with the ``math`` module only: no call into
``famcc._core`` and no NumPy anywhere. It exists to
check the compiled core (``tests/test_reference.py``) and as a readable
statement of the law (it lives with the tests and is not shipped); it is 50-100 times slower than the compiled step.

Scope: float64, orders 1-3, every feedback law (Linear, FiniteTime, FixedTime,
VariableExponent, MoulayDiscontinuous), both skews (SSMD, NSMD), the three
constraint types (LoMC, LaMC, OMC), both Gamma maps, the four transitions, the
flexible boundary on or off, both latches, the exact/Euler/Tustin/first-order-hold
differentiator with optional estimate limits and prefilter, initial derivative
estimates and the ``applied`` argument.

Discrete-time semantics (docs/design.md §3.2), in the order of ``step(e_k)``:

1. at ``k = 0`` the estimate is ``Zhat_0 = (e_0, d_2, ..., d_n)`` (``d_i`` the
   initial derivatives, zeros by default); otherwise the stored ``Zhat_k``,
   built from samples up to ``k - 1``;
2. the output is computed from ``Zhat_k`` (clipped to the estimate limits when
   given) at time ``t_k = k dt``: manifold ``s_1 .. s_n`` (eq. IS), the
   constraint offset along the gradient line (eqs. gradient, xyc, xi), at
   ``k = 0`` the envelope latch (text after eq. yUyL; ``latch="paper"``:
   ``rho_0 = k0 max(|s_0|, eps)``, ``"authors"``: ``max(k0 |s_0|, eps)``), the
   flexible boundary (eqs. WxyUxyL, Wxi), the clamp ``|xi| <= 1 - 2^-53`` when
   the flexible boundary is off, and ``v = -k_u Gamma(xi)`` (eqs. uT, WuT, uOF);
3. the estimate advances: ``Zhat_{k+1} = Phi Zhat_k + Gamma f_k`` (eq. HGD,
   zero-order hold, ``Phi``/``Gamma`` computed at construction; ``f_k`` the
   sample ``e_k``, or its low-pass value with a prefilter).

With the first-order hold (``discretization="foh"``) ``Phi`` and ``Gamma`` are
the exact hold's, the stored vector is ``V_k`` and step 1 uses
``Zhat_k = V_k + D (f_k - f_(k-1))`` at every step after the first (``D`` the
feedthrough of the input's increment, see :func:`discretize_hgd`; the first
step's ``Zhat_0`` has none); step 3 stores ``V_{k+1} = Phi Zhat_k + Gamma f_k``
from the unlimited ``Zhat_k`` (the estimate limits only clip what the law
sees). ``step_state`` runs the differentiator the same way. The restart of the
recovery rule advances its seed as the exact hold does, and the sample after it
adds no feedthrough (its clock starts a run at count 0, as the core's does).

A rejected step (non-finite ``e`` or ``applied``, overflow) raises ``ValueError``
and changes nothing, except an overflow after the first step (the recovery rule
of design.md §3.7): the clock advances and the estimate restarts, from this
sample when the law overflowed, from a zero error when the update would leave
the estimate's range ``|z| <= 2^512``.
``rho_e="auto"`` (the default) is ``min(0.01, eps/10)`` with ``eps`` the smallest
final half-width.

Derivatives (order 3): ``s_2 = z_2 - h_1(z_1)`` and
``ds_2/dt = z_3 - h_1'(z_1) z_2``; every ``h`` below comes with its slope
``h'`` written out analytically (SSMD/NSMD by the product rule on the
transitions). At ``s = 0`` the NSMD blend ``T_2 = U(s/eps_z)`` and its slope are
exactly zero, so only the linear branch ``-k_p s`` is evaluated (docs/design.md §4.2).

The differentiator's ``Phi``/``Gamma`` are the exact zero-order-hold
discretization (``Phi = exp(M dt)``, ``M = A - H C``; ``Gamma`` from the unit DC
gain, see :func:`discretize_hgd`), computed once at construction by scaling
and squaring of a Taylor series in 60-digit ``decimal`` arithmetic, in
balanced coordinates ``w_i = mu^(i-1) Zhat_i`` (time in units of ``mu``, every
entry ``O(a_i)`` whatever ``mu`` is), then rounded once to float: in practice
the nearest floats to the exact values. (The core uses a degree-13 Pade
approximant of the augmented matrix in float64; the two agree to a few ulps
while ``dt <~ mu``.)

>>> import famcc
>>> from oracle.reference import ReferenceController
>>> sc = famcc.scenarios.paper("finite-time")
>>> ref = ReferenceController.from_kwargs(dt=1e-3, **sc.controller_kwargs)
>>> ctrl = sc.controller(1e-3)
>>> abs(ref.step(-1.0) - ctrl.step(-1.0)) < 1e-12
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from decimal import Decimal, getcontext, localcontext
from typing import Any

__all__ = [
    "CLAMP_LIMIT",
    "ReferenceController",
    "ReferenceDiagnostics",
    "discretize_hgd",
    "transition_s",
    "transition_t",
]

#: The largest float below 1 (docs/design.md §3.6: ``xi`` is clamped to the largest
#: floating-point number below 1; both Gamma maps are finite there).
#: The estimate's range (design.md §3.7): the square root of the largest f64.
ESTIMATE_RANGE = 2.0**512
CLAMP_LIMIT = 1.0 - 2.0**-53

_INF = math.inf
_HALF_PI = 0.5 * math.pi


# ---------------------------------------------------------------------------
# Transitions (paper Definitions 1-3)


def transition_t(z: float) -> float:
    """Single-ended ``T(z)`` (eq. trnsT): 0 for ``z <= 0``, ``exp((z - 1)/z)`` above."""
    if z <= 0.0:
        return 0.0
    return math.exp((z - 1.0) / z)  # underflows to 0.0 quietly


def _s_exponential(z: float) -> float:
    # eq. trnsS: 1 / (exp((1-2z)/(z(1-z))) + 1), evaluated without overflow
    w = (1.0 - 2.0 * z) / (z * (1.0 - z))
    if w >= 0.0:
        q = math.exp(-w)
        return q / (1.0 + q)
    return 1.0 / (1.0 + math.exp(w))


def _ds_exponential(z: float) -> tuple[float, float]:
    zz = z * (1.0 - z)
    w = (1.0 - 2.0 * z) / zz
    q = math.exp(-abs(w))
    s = q / (1.0 + q) if w >= 0.0 else 1.0 / (1.0 + q)
    # dS/dz = S (1 - S) (-dw/dz), S (1 - S) = q / (1 + q)^2, -dw/dz = (2z^2 - 2z + 1)/(z(1-z))^2
    return s, q / ((1.0 + q) * (1.0 + q)) * (2.0 * z * z - 2.0 * z + 1.0) / (zz * zz)


def _s_cubic(z: float) -> float:
    return z * z * (3.0 - 2.0 * z)


def _ds_cubic(z: float) -> tuple[float, float]:
    return z * z * (3.0 - 2.0 * z), 6.0 * z * (1.0 - z)


def _s_quintic(z: float) -> float:
    return z * z * z * (10.0 - 15.0 * z + 6.0 * z * z)


def _ds_quintic(z: float) -> tuple[float, float]:
    zz = z * (1.0 - z)
    return z * z * z * (10.0 - 15.0 * z + 6.0 * z * z), 30.0 * zz * zz


def _s_sine(z: float) -> float:
    s = math.sin(_HALF_PI * z)
    return s * s


def _ds_sine(z: float) -> tuple[float, float]:
    s = math.sin(_HALF_PI * z)
    return s * s, _HALF_PI * math.sin(math.pi * z)


_S_INNER = {
    "exponential": (_s_exponential, _ds_exponential),
    "cubic": (_s_cubic, _ds_cubic),
    "quintic": (_s_quintic, _ds_quintic),
    "sine": (_s_sine, _ds_sine),
}


def _double(kind: str):
    """``S`` and ``(S, S')`` of a double-ended transition (0 below 0, 1 above 1)."""
    inner, dinner = _S_INNER[kind]

    def s(z: float) -> float:
        if z <= 0.0:
            return 0.0
        if z >= 1.0:
            return 1.0
        return inner(z)

    def ds(z: float) -> tuple[float, float]:
        if z <= 0.0:
            return 0.0, 0.0
        if z >= 1.0:
            return 1.0, 0.0
        return dinner(z)

    return s, ds


def transition_s(z: float, kind: str = "exponential") -> float:
    """Double-ended ``S(z)`` (eq. trnsS for ``kind="exponential"``)."""
    return _double(kind)[0](z)


# ---------------------------------------------------------------------------
# Feedback laws h_p (paper eqs. lfmi, fn, RFCs, fxe, fvec) with their slopes


def _spow(x: float, p: float) -> float:
    """``|x|^p sign(x)``; +-inf where the power overflows."""
    if x > 0.0:
        try:
            return x**p
        except OverflowError:
            return _INF
    if x < 0.0:
        try:
            return -((-x) ** p)
        except OverflowError:
            return -_INF
    return 0.0


def _dspow(x: float, p: float) -> float:
    """``d/dx |x|^p sign(x) = p |x|^(p-1)`` (inf at 0 for p < 1)."""
    ax = abs(x)
    if ax == 0.0:
        return _INF if p < 1.0 else (1.0 if p == 1.0 else 0.0)
    try:
        return p * ax ** (p - 1.0)
    except OverflowError:
        return _INF


class _Law:
    singular = True

    def value(self, s: float) -> float:
        raise NotImplementedError

    def value_slope(self, s: float) -> tuple[float, float]:
        raise NotImplementedError

    def closed_inverse(self, y: float) -> float | None:
        return None


class _Linear(_Law):
    singular = False

    def __init__(self, k: float) -> None:
        self.k = k

    def value(self, s: float) -> float:
        return -self.k * s

    def value_slope(self, s: float) -> tuple[float, float]:
        return -self.k * s, -self.k

    def closed_inverse(self, y: float) -> float | None:
        return -y / self.k


class _FiniteTime(_Law):
    def __init__(self, k: float, p: float) -> None:
        self.k, self.p = k, p

    def value(self, s: float) -> float:
        return -self.k * _spow(s, self.p)

    def value_slope(self, s: float) -> tuple[float, float]:
        return -self.k * _spow(s, self.p), -self.k * _dspow(s, self.p)

    def closed_inverse(self, y: float) -> float | None:
        # Erratum (docs/errata.md, eq. nfn): h^-1(y) = -sign(y) |y/k|^(1/p)
        return -_spow(y / self.k, 1.0 / self.p)


class _FixedTime(_Law):
    def __init__(self, alpha: float, p: float, beta: float, q: float) -> None:
        self.alpha, self.p, self.beta, self.q = alpha, p, beta, q

    def value(self, s: float) -> float:
        return -(self.alpha * _spow(s, self.p) + self.beta * _spow(s, self.q))

    def value_slope(self, s: float) -> tuple[float, float]:
        return (self.value(s), -(self.alpha * _dspow(s, self.p) + self.beta * _dspow(s, self.q)))


class _VarExponent(_Law):
    """``-k |s|^{r(s)} sign(s)``, ``r(s) = a s^2/(1 + b s^2) + r0`` (eqs. fxe, fvec)."""

    def __init__(self, k: float, a: float, b: float, r0: float) -> None:
        self.k, self.a, self.b, self.r0 = k, a, b, r0

    def _r(self, s: float) -> float:
        if abs(s) <= 1.0:
            s2 = s * s
            return self.a * s2 / (1.0 + self.b * s2) + self.r0
        w = 1.0 / s
        return self.a / (self.b + w * w) + self.r0

    def value(self, s: float) -> float:
        return -self.k * _spow(s, self._r(s))

    def value_slope(self, s: float) -> tuple[float, float]:
        if s == 0.0:
            return 0.0, (-_INF if self.r0 < 1.0 else (-self.k if self.r0 == 1.0 else 0.0))
        r = self._r(s)
        m = abs(s)
        g = _spow(s, r)
        d = 1.0 + self.b * s * s
        dr = 2.0 * self.a * s / (d * d)
        # d/ds sign(s)|s|^r(s) = |s|^r (r'(s) ln|s| sign(s) + r/|s|)
        slope = abs(g) * (dr * math.log(m) * (1.0 if s > 0.0 else -1.0) + r / m)
        return -self.k * g, -self.k * slope


def _law_from(obj: Any) -> _Law:
    name = type(obj).__name__
    if name == "Linear":
        return _Linear(float(obj.k))
    if name == "FiniteTime":
        return _FiniteTime(float(obj.k), float(obj.p))
    if name == "FixedTime":
        return _FixedTime(float(obj.alpha), float(obj.p), float(obj.beta), float(obj.q))
    if name == "VariableExponent":
        r_b, r_1, r_t = float(obj.r_b), float(obj.r_1), float(obj.r_t)
        b = (r_1 - r_b) / (r_t - r_1)
        return _VarExponent(float(obj.k), (r_t - r_b) * b, b, r_b)
    if name == "MoulayDiscontinuous":
        return _VarExponent(float(obj.beta), float(obj.lambda_), float(obj.mu), 0.0)
    raise ValueError(f"feedback must be a famcc feedback law, got {obj!r}")


# ---------------------------------------------------------------------------
# Skewed laws h_m (eqs. SSMD, NSMD)


class _SkewedLaw:
    """``h_m``: a law with an optional SSMD/NSMD skew; ``value`` and ``value_slope``."""

    def __init__(self, law: _Law, skew: Any) -> None:
        self.law = law
        self.kind = None
        self.closed_inverse = law.closed_inverse
        self.value = law.value
        self.value_slope = law.value_slope
        self.singular = law.singular
        if skew is None:
            return
        name = type(skew).__name__
        self.eps_s = float(skew.eps_s)
        self.eps_z = float(skew.eps_z)
        self._s, self._ds = _double(getattr(skew, "transition", "exponential"))
        self.closed_inverse = lambda y: None
        if name == "Smooth":
            self.kind = "smooth"
            self.value = self._ssmd
            self.value_slope = self._ssmd_slope
        elif name == "Nonsingular":
            self.kind = "nonsingular"
            self.singular = False
            # k_p = k_pp (eps_s - h_p(eps_z)) / eps_z
            self.k_p = float(skew.k_pp) * (self.eps_s - law.value(self.eps_z)) / self.eps_z
            self.value = self._nsmd
            self.value_slope = self._nsmd_slope
        else:
            raise ValueError(f"skew must be None, famcc.Smooth or famcc.Nonsingular, got {skew!r}")

    # T1 = 1 - 2 S((s + eps_z)/(2 eps_z)); T2 = U(s/eps_z) = S(|s|/eps_z)
    def _ssmd(self, s: float) -> float:
        t1 = 1.0 - 2.0 * self._s((s + self.eps_z) / (2.0 * self.eps_z))
        return self.law.value(s) + t1 * self.eps_s

    def _ssmd_slope(self, s: float) -> tuple[float, float]:
        sv, sd = self._ds((s + self.eps_z) / (2.0 * self.eps_z))
        h, dh = self.law.value_slope(s)
        return h + (1.0 - 2.0 * sv) * self.eps_s, dh - sd / self.eps_z * self.eps_s

    def _nsmd(self, s: float) -> float:
        t2 = self._s(abs(s) / self.eps_z)
        lin = -(1.0 - t2) * self.k_p * s
        if t2 == 0.0:
            return lin
        t1 = 1.0 - 2.0 * self._s((s + self.eps_z) / (2.0 * self.eps_z))
        return t2 * (self.law.value(s) + t1 * self.eps_s) + lin

    def _nsmd_slope(self, s: float) -> tuple[float, float]:
        a = abs(s)
        t2, dt2 = self._ds(a / self.eps_z)
        dt2 = dt2 / self.eps_z * (1.0 if s > 0.0 else -1.0)  # d/ds U(s/eps_z)
        kp = self.k_p
        if t2 == 0.0 and dt2 == 0.0:
            # every derivative of T2 vanishes: skip the (possibly singular) h_p branch
            return -kp * s, -kp
        sv, sd = self._ds((s + self.eps_z) / (2.0 * self.eps_z))
        h, dh = self.law.value_slope(s)
        inner = h + (1.0 - 2.0 * sv) * self.eps_s
        dinner = dh - sd / self.eps_z * self.eps_s
        if t2 == 1.0 and dt2 == 0.0:
            return inner, dinner
        value = t2 * inner - (1.0 - t2) * kp * s
        slope = dt2 * inner + t2 * dinner + dt2 * kp * s - (1.0 - t2) * kp
        return value, slope


def _decreasing_root(f, x0: float) -> float:
    """Root of a strictly decreasing ``f`` near ``x0``: doubling bracket, then bisection
    down to adjacent floats (the best float, not a tolerance)."""
    f0 = f(x0)
    if f0 == 0.0 or not math.isfinite(f0):
        return x0
    pos0 = f0 > 0.0
    direction = 1.0 if pos0 else -1.0
    step = max(abs(x0), 1.0)
    a, fa = x0, f0
    b = fb = None
    for _ in range(1100):
        x = x0 + direction * step
        if not math.isfinite(x):
            break
        fx = f(x)
        if not math.isfinite(fx):
            break
        if fx == 0.0:
            return x
        if (fx > 0.0) != pos0:
            b, fb = x, fx
            break
        a, fa = x, fx
        step *= 2.0
    if b is None:
        return a
    for _ in range(2200):
        m = a + (b - a) * 0.5
        if m == a or m == b:
            break
        fm = f(m)
        if fm == 0.0:
            return m
        if (fm > 0.0) == pos0:
            a, fa = m, fm
        else:
            b, fb = m, fm
    return a if abs(fa) < abs(fb) else b


# ---------------------------------------------------------------------------
# The differentiator (eq. HGD), discretized at construction


def _mat_mul(x, y):
    n, m, p = len(x), len(y), len(y[0])
    return [[sum(x[i][k] * y[k][j] for k in range(m)) for j in range(p)] for i in range(n)]


def _expm(x):
    """Matrix exponential of a small Decimal matrix: scaling and squaring of a Taylor
    series, in the current (high) Decimal precision."""
    n = len(x)
    one, zero = Decimal(1), Decimal(0)
    eye = [[one if i == j else zero for j in range(n)] for i in range(n)]
    norm = max(sum(abs(x[i][j]) for i in range(n)) for j in range(n))
    squarings = 0
    while norm > Decimal("0.5"):
        norm /= 2
        squarings += 1
    scale = Decimal(2) ** squarings
    y = [[v / scale for v in row] for row in x]
    out = [row[:] for row in eye]
    term = [row[:] for row in eye]
    tiny = Decimal(10) ** (-getcontext().prec - 5)
    for k in range(1, 400):
        term = [[v / k for v in row] for row in _mat_mul(term, y)]
        out = [[a + b for a, b in zip(ra, rb)] for ra, rb in zip(out, term)]
        if max(abs(v) for row in term for v in row) <= tiny:
            break
    for _ in range(squarings):
        out = _mat_mul(out, out)
    return out


def _solve(a, b):
    """``a^-1 b`` for small Decimal matrices (Gauss-Jordan, partial pivoting)."""
    n = len(a)
    m = [list(ra) + list(rb) for ra, rb in zip(a, b)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        piv = m[c][c]
        m[c] = [v / piv for v in m[c]]
        for r in range(n):
            if r != c and m[r][c] != 0:
                f = m[r][c]
                m[r] = [v - f * w for v, w in zip(m[r], m[c])]
    return [row[n:] for row in m]


def discretize_hgd(
    mu: float, a: Sequence[float], dt: float, method: str = "exact", *, feedthrough: bool = False
):
    """``(Phi, Gamma)`` of eq. HGD sampled at ``dt`` as tuples of floats, and with
    ``feedthrough=True`` ``(Phi, Gamma, D)`` (``D`` zeros except for ``"foh"``).

    ``method``: ``"exact"`` (zero-order hold, ``Phi = exp(M dt)``), ``"euler"``
    (``I + M dt``), ``"tustin"`` (``(I - M dt/2)^-1 (I + M dt/2)``) or ``"foh"``
    (first-order hold), ``M = A - H C``.

    Computed in 60-digit decimal arithmetic, in balanced coordinates
    ``w_i = mu^(i-1) Zhat_i`` over ``tau = dt/mu`` (where ``M0 = A - a C`` has ``O(1)``
    entries), mapped back with ``Phi_ij = Phi0_ij mu^(j-i)``, ``Gamma_i = Gamma0_i mu^-i``
    (0-based) and rounded once: in practice the floats nearest the exact values.

    ``Gamma`` comes from the unit DC gain instead of the last column of the augmented
    exponential ``exp([[M0, a], [0, 0]] tau)``: ``M0 e1 = -a``, so a held input ``e``
    has the fixed point ``w = e e1`` and ``Gamma0 = e1 - Phi0 e1`` exactly, for all three
    methods (ZOH: ``Gamma0 = (Phi0 - I) M0^-1 a``; Euler: ``tau a``; Tustin:
    ``(I - M0 tau/2)^-1 tau a``). Unlike the augmented column, whose entries lose all
    relative accuracy when they are tiny (``dt >> mu``), this keeps every entry of
    ``Gamma`` as accurate as ``Phi``'s first column.

    ``"foh"``: the input is the straight line through the samples,
    ``e(t_k + s) = e_k + (e_{k+1} - e_k) s/dt``, so
    ``Zhat_{k+1} = Phi Zhat_k + Gamma_zoh e_k + D (e_{k+1} - e_k)`` with ``Phi`` and
    ``Gamma_zoh`` those of ``"exact"`` and
    ``D = (1/dt) integral_0^dt exp(M s) (dt - s) ds H``; the returned ``Gamma`` is
    ``Gamma_zoh``, and ``D`` multiplies the increment ``e_{k+1} - e_k``. ``D0``
    (balanced) is read from the exponential of the augmented
    ``[[M0, a, 0], [0, 0, 1], [0, 0, 0]] tau``, whose state ``(w, u, v)`` with
    ``u' = v``, ``v' = 0`` from ``(0, 0, 1)`` is driven by the ramp ``u = s``: its last
    column's top block is ``integral_0^tau exp(M0 (tau - s)) s ds a = tau D0``
    (substitute ``s -> tau - s``); the column before it, the unit step's response,
    must reproduce ``Gamma_zoh`` (checked to 1e-40). ``D`` maps back like ``Gamma``.
    (The core solves ``M0 D0 = (Gamma_zoh - tau a)/tau`` instead, or sums its series
    for small ``tau``.)
    """
    with localcontext() as ctx:
        ctx.prec = 60
        av = [Decimal(float(x)) for x in a]
        n = len(av)
        mu_d = Decimal(float(mu))
        tau = Decimal(float(dt)) / mu_d
        zero, one, half = Decimal(0), Decimal(1), Decimal("0.5")
        m0 = [[-av[i] if j == 0 else zero for j in range(n)] for i in range(n)]
        for i in range(n - 1):
            m0[i][i + 1] += one
        eye = [[one if i == j else zero for j in range(n)] for i in range(n)]
        if method == "exact":
            phi0 = _expm([[v * tau for v in row] for row in m0])
        elif method == "euler":
            phi0 = [[eye[i][j] + tau * m0[i][j] for j in range(n)] for i in range(n)]
        elif method == "tustin":
            lhs = [[eye[i][j] - half * tau * m0[i][j] for j in range(n)] for i in range(n)]
            rhs = [[eye[i][j] + half * tau * m0[i][j] for j in range(n)] for i in range(n)]
            phi0 = _solve(lhs, rhs)
        elif method == "foh":
            phi0 = _expm([[v * tau for v in row] for row in m0])
        else:
            raise ValueError(
                f"discretization must be 'exact', 'euler', 'tustin' or 'foh', got {method!r}"
            )
        g0 = [eye[i][0] - phi0[i][0] for i in range(n)]
        d0 = [zero] * n
        if method == "foh":
            aug = [[v * tau for v in row] + [av[i] * tau, zero] for i, row in enumerate(m0)]
            aug.append([zero] * (n + 1) + [tau])
            aug.append([zero] * (n + 2))
            big = _expm(aug)
            if max(abs(big[i][n] - g0[i]) for i in range(n)) > Decimal("1e-40"):
                raise ArithmeticError("the augmented exponential disagrees with Gamma_zoh")
            d0 = [big[i][n + 1] / tau for i in range(n)]
        phi = tuple(tuple(float(phi0[i][j] * mu_d ** (j - i)) for j in range(n)) for i in range(n))
        gamma = tuple(float(g0[i] * mu_d ** (-i)) for i in range(n))
        feed = tuple(float(d0[i] * mu_d ** (-i)) for i in range(n))
    if feedthrough:
        return phi, gamma, feed
    return phi, gamma


# ---------------------------------------------------------------------------
# Diagnostics


class ReferenceDiagnostics:
    """What the last step did (same attribute names as ``famcc.Controller.diagnostics``)."""

    __slots__ = (
        "bounds",
        "clamp_count",
        "ds_prev",
        "expanded",
        "nominal_bounds",
        "s",
        "s_prev",
        "saturation_gap",
        "stages",
        "t",
        "v",
        "xi",
        "xi_nominal",
        "z_hat",
    )

    def __init__(self, **kw: Any) -> None:
        for k in self.__slots__:
            setattr(self, k, kw[k])

    def __repr__(self) -> str:
        return (
            "ReferenceDiagnostics("
            + ", ".join(f"{k}={getattr(self, k)!r}" for k in self.__slots__)
            + ")"
        )


# ---------------------------------------------------------------------------
# The controller

_DEFAULT_A = {2: (4.0, 4.0), 3: (4.0, 6.0, 4.0)}


class ReferenceController:
    """Pure-Python FAMCC controller with the semantics of ``famcc.Controller``.

    Same constructor arguments as :class:`famcc.Controller` (``dtype`` must be
    ``"float64"``); law and skew objects are famcc's (their parameters are read
    once, here). ``step(e, applied=None) -> float`` uses ``math`` only.

    Attributes: ``order``, ``dt``, ``k_u``, ``phi``/``gamma_vec``/``feedthrough``
    (the sampled differentiator; ``feedthrough`` is ``D`` of the first-order hold,
    else None), ``xi`` (of the last step), ``diagnostics``, ``time``,
    ``estimate``.
    """

    def __init__(
        self,
        order: int,
        dt: float,
        feedback: Any = None,
        *,
        skew: Any = None,
        constraint: str = "longitudinal",
        eps: Any,
        settle_time: float = 1.0,
        k0: float = 2.0,
        k_u: float,
        gamma: str = "log",
        rho_e: Any = "auto",
        differentiator: Any = "auto",
        latch: str = "paper",
        transition: str = "exponential",
        initial_derivatives: Sequence[float] | None = None,
        dtype: str = "float64",
    ) -> None:
        if order not in (1, 2, 3):
            raise ValueError(f"order must be 1, 2 or 3 in the reference (got {order})")
        if dtype != "float64":
            raise ValueError("the reference computes in float64 only")
        dt = float(dt)
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be finite and > 0 (got {dt})")
        self.order = order
        self.dt = dt
        n = order - 1
        # -- stage laws h_m1 .. h_m(n-1) --
        laws = feedback if isinstance(feedback, (list, tuple)) else [feedback] * n
        skews = skew if isinstance(skew, (list, tuple)) else [skew] * n
        if len(laws) != n or len(skews) != n or (n and feedback is None):
            raise ValueError(f"feedback and skew must have order - 1 = {n} entries")
        self.laws = [_SkewedLaw(_law_from(h), sk) for h, sk in zip(laws, skews)]
        if order == 3 and self.laws[0].singular:
            raise ValueError(
                "stage 1: skew must be Nonsingular (NSMD) for a power law "
                "below 1 at order 3 (its derivative is needed)"
            )
        # -- constraint and envelopes --
        if constraint not in ("longitudinal", "lateral", "oblique"):
            raise ValueError(
                f"constraint must be longitudinal, lateral or oblique (got {constraint!r})"
            )
        if order == 1 and constraint != "longitudinal":
            raise ValueError("constraint must be longitudinal at order 1")
        self.constraint = constraint
        if constraint == "oblique":
            eps_x, eps_y = (float(v) for v in eps)
        elif constraint == "lateral":
            eps_x, eps_y = float(eps), 0.0
        else:
            eps_x, eps_y = 0.0, float(eps)
        self.eps_x, self.eps_y = eps_x, eps_y
        self.settle_time = float(settle_time)
        self.k0 = float(k0)
        self.k_u = float(k_u)
        for name, val in (("settle_time", self.settle_time), ("k_u", self.k_u)):
            if not (math.isfinite(val) and val > 0.0):
                raise ValueError(f"{name} must be finite and > 0 (got {val})")
        if not (math.isfinite(self.k0) and self.k0 > 1.0):
            raise ValueError(f"k0 must be finite and > 1 (got {self.k0})")
        if gamma not in ("log", "rational"):
            raise ValueError(f"gamma must be 'log' or 'rational' (got {gamma!r})")
        self.gamma = gamma
        if isinstance(rho_e, str):
            if rho_e != "auto":
                raise ValueError(f"rho_e must be a float, 'auto' or None (got {rho_e!r})")
            # 0.01, or a tenth of the smallest final width when that is smaller
            smallest = {"longitudinal": eps_y, "lateral": eps_x}.get(constraint, min(eps_x, eps_y))
            rho_e = min(0.01, 0.1 * smallest)
        self.rho_e = None if rho_e is None else float(rho_e)
        if latch not in ("paper", "authors"):
            raise ValueError(f"latch must be 'paper' or 'authors' (got {latch!r})")
        self.latch = latch
        self.transition = transition
        self._flex_s = _double(transition)[0]
        # -- differentiator --
        self.limits = None
        # the prefilter's gain per period (1: none): f_k = f + b (e_k - f)
        self.prefilter_gain = 1.0
        if differentiator == "auto":
            differentiator = None if order == 1 else ("auto",)
        self.feedthrough = None
        if differentiator is None:
            self.phi = self.gamma_vec = None
        else:
            if isinstance(differentiator, tuple):
                mu, a, method = 0.01, _DEFAULT_A[order], "exact"
            else:
                mu = float(differentiator.mu)
                a = tuple(float(x) for x in differentiator.a)
                method = getattr(differentiator, "discretization", "exact")
                lim = getattr(differentiator, "limits", None)
                self.limits = None if lim is None else tuple(float(x) for x in lim)
                tau = float(getattr(differentiator, "prefilter", 0.0))
                if tau > 0.0:
                    self.prefilter_gain = -math.expm1(-dt / tau)
            if len(a) != order:
                raise ValueError(f"differentiator.a must have {order} coefficients")
            self.phi, self.gamma_vec, feed = discretize_hgd(mu, a, dt, method, feedthrough=True)
            if method == "foh":
                self.feedthrough = feed
        if initial_derivatives is not None:
            d = [float(x) for x in initial_derivatives]
            if len(d) != n:
                raise ValueError(f"initial_derivatives must have order - 1 = {n} entries")
            self.initial_derivatives = d
        else:
            self.initial_derivatives = [0.0] * n
        self._last = self.laws[-1] if self.laws else None
        self.reset()

    @classmethod
    def from_kwargs(cls, order: int, dt: float, **kwargs: Any) -> ReferenceController:
        """The same as the constructor (mirrors ``famcc.Controller(order, dt, **kwargs)``)."""
        return cls(order, dt, **kwargs)

    @classmethod
    def from_controller(cls, ctrl: Any) -> ReferenceController:
        """A reference with the configuration of a ``famcc.Controller`` (its ``config()``)."""
        kw = dict(ctrl.config())
        return cls(kw.pop("order"), kw.pop("dt"), **kw)

    # -- state ---------------------------------------------------------------

    def reset(self) -> None:
        """Back to the state before the first step."""
        self._started = False
        self._t_base = 0.0
        self._k = 0
        self._zhat = [0.0] * self.order
        self._filtered = 0.0
        self._rho0_x, self._rho0_y = self.eps_x, self.eps_y
        self._clamps = 0
        self._last_v = 0.0
        self.xi = 0.0
        self._diag: dict | None = None

    @property
    def time(self) -> float:
        """Time of the next sample, s."""
        return self._t_base + float(self._k) * self.dt

    @property
    def estimate(self) -> list:
        """The estimate the next step will use (the stored ``V`` with the
        first-order hold, before the feedthrough of the next increment)."""
        return list(self._zhat)

    def state(self) -> list:
        """``[started, t_base, k, rho0_x, rho0_y, clamp_count, last_v, period,
        config, filtered, lhat, zhat...]`` (the layout of ``famcc.Controller.state()``;
        the compiled core's configuration fingerprint is not known here: 0; this
        oracle has no observer, so ``lhat`` is 0)."""
        return [
            1.0 if self._started else 0.0,
            self._t_base,
            float(self._k),
            self._rho0_x,
            self._rho0_y,
            float(self._clamps),
            self._last_v,
            self.dt,
            0.0,
            self._filtered,
            0.0,
            *self._zhat,
        ]

    def set_state(self, v: Sequence[float]) -> None:
        """Continues from a vector returned by ``state()`` (either implementation's)."""
        v = [float(x) for x in v]
        if len(v) != 11 + self.order:
            raise ValueError(f"state must have {11 + self.order} entries")
        self.reset()
        self._started = v[0] != 0.0
        self._t_base, self._k = v[1], int(v[2])
        self._rho0_x, self._rho0_y = v[3], v[4]
        self._clamps, self._last_v = int(v[5]), v[6]
        self._filtered = v[9]
        self._zhat = v[11:]

    @property
    def diagnostics(self) -> ReferenceDiagnostics:
        """What the last step did."""
        d = self._diag
        if d is None:
            z = [0.0] * self.order
            d = {
                "t": 0.0,
                "xi": 0.0,
                "xi_nominal": 0.0,
                "s": 0.0,
                "stages": z,
                "s_prev": 0.0,
                "ds_prev": 0.0,
                "bounds": (0.0, 0.0),
                "nominal_bounds": (0.0, 0.0),
                "z_hat": z,
                "expanded": False,
                "saturation_gap": None,
                "clamp_count": self._clamps,
                "v": self._last_v,
            }
        return ReferenceDiagnostics(**d)

    # -- the law ----------------------------------------------------------------

    def _manifold(self, z: Sequence[float]) -> tuple[list, float, float]:
        """``(stages, s_prev, ds_prev)`` of eq. IS for ``Z = z``."""
        order = self.order
        if order == 1:
            return [z[0]], 0.0, 0.0
        if order == 2:
            z1, z2 = z
            return [z1, z2 - self.laws[0].value(z1)], z1, z2
        z1, z2, z3 = z
        h1, dh1 = self.laws[0].value_slope(z1)
        s2 = z2 - h1
        ds2 = z3 - dh1 * z2  # d/dt (z2 - h_m1(z1))
        return [z1, s2, ds2 - self.laws[1].value(s2)], s2, ds2

    def _x_c(self, s_prev: float, ds_prev: float, m: float | None) -> float:
        """Abscissa of the gradient line's intersection with the zero manifold."""
        law = self._last
        if m is None:  # lateral: x_c = h_v(ds) = h^-1(ds)
            x = law.closed_inverse(ds_prev)
            if x is not None:
                return x
            guess = law.law.closed_inverse(ds_prev)
            if guess is None or not math.isfinite(guess):
                guess = 0.0
            return _decreasing_root(lambda x: law.value(x) - ds_prev, guess)
        # oblique, eq. (xyc): x_U (h(x) - ds) = y_U (x - s_prev)
        return _decreasing_root(lambda x: law.value(x) - ds_prev - m * (x - s_prev), s_prev)

    def _envelope(self, rho0: float, eps: float, t: float) -> float:
        ts = self.settle_time
        if t >= ts:
            return eps
        return (rho0 - eps) * transition_t((ts - t) / ts) + eps

    def _rho0(self, s0: float, eps: float) -> float:
        if self.latch == "paper":
            return self.k0 * max(abs(s0), eps)
        return max(self.k0 * abs(s0), eps)

    def _law(self, z: Sequence[float], t: float, latch: bool) -> dict:
        stages, s_prev, ds_prev = self._manifold(z)
        s = stages[-1]
        kind = self.constraint
        if latch:
            if kind != "longitudinal":
                # s_x0 = |h_v(ds_{n-1}) - s_{n-1}|
                self._new_rho0_x = self._rho0(s_prev - self._x_c(s_prev, ds_prev, None), self.eps_x)
            else:
                self._new_rho0_x = self._rho0_x
            self._new_rho0_y = self._rho0(s, self.eps_y) if kind != "lateral" else self._rho0_y
            rho0_x, rho0_y = self._new_rho0_x, self._new_rho0_y
        else:
            rho0_x, rho0_y = self._rho0_x, self._rho0_y
        x_u = 0.0 if kind == "longitudinal" else self._envelope(rho0_x, self.eps_x, t)
        y_u = 0.0 if kind == "lateral" else self._envelope(rho0_y, self.eps_y, t)
        # eq. (xi) with symmetric bounds; d_sc, d_U of eq. (WxyUxyL)
        if kind == "longitudinal" or self._last is None:
            sigma, width, d_u, d_sc = s, y_u, y_u, abs(s)
        elif kind == "lateral":
            sigma = s_prev - self._x_c(s_prev, ds_prev, None)
            width = d_u = x_u
            d_sc = abs(sigma)
        else:
            x_c = self._x_c(s_prev, ds_prev, y_u / x_u)
            sigma, width = s_prev - x_c, x_u
            d_u = math.sqrt(x_u * x_u + y_u * y_u)
            d_sc = math.hypot(sigma, ds_prev - self._last.value(x_c))
        xi_nominal = sigma / width
        factor = 1.0
        if self.rho_e is not None:
            rho_e = self.rho_e
            ts = self._flex_s((d_sc - (d_u - rho_e)) / rho_e)
            if ts != 0.0:
                factor = (1.0 - ts) + ts * (d_sc + rho_e) / d_u
        xi = xi_nominal / factor
        clamps = 0
        if abs(xi) > CLAMP_LIMIT:
            xi = CLAMP_LIMIT if xi > 0.0 else -CLAMP_LIMIT
            clamps = 1
        if self.gamma == "log":
            g = 2.0 * math.atanh(abs(xi))  # ln((1 + xi)/(1 - xi)), exactly odd
            g = -g if xi < 0.0 else g
        else:
            g = xi / ((1.0 + xi) * (1.0 - xi))
        v = -self.k_u * g
        return {
            "t": t,
            "xi": xi,
            "xi_nominal": xi_nominal,
            "s": s,
            "stages": stages,
            "s_prev": s_prev,
            "ds_prev": ds_prev,
            "bounds": (factor * x_u, factor * y_u),
            "nominal_bounds": (x_u, y_u),
            "z_hat": list(z),
            "expanded": factor > 1.0,
            "saturation_gap": None,
            "clamp_count": clamps,
            "v": v,
        }

    # -- stepping ---------------------------------------------------------------

    def _input(self, e: float) -> float:
        """The differentiator's input for the sample ``e``: ``e`` itself at the
        first step or without a prefilter, else ``f + b (e - f)``."""
        if not self._started or self.prefilter_gain == 1.0:
            return e
        return self._filtered + self.prefilter_gain * (e - self._filtered)

    def _advance(self, zhat: Sequence[float], e: float) -> list:
        """``Phi zhat + Gamma e``, each row summed left to right from ``Gamma_i e``."""
        out = []
        for row, g in zip(self.phi, self.gamma_vec):
            acc = g * e
            for p, z in zip(row, zhat):
                acc += p * z
            out.append(acc)
        return out

    def _current(self, v: Sequence[float], f: float) -> list:
        """The estimate of the sample whose differentiator input is ``f`` from the
        stored ``v``: ``v + D (f - f_prev)`` with the first-order hold, else ``v``
        itself, and ``v`` itself on the sample after a restart (count 0)."""
        if self.feedthrough is None or self._k == 0:
            return list(v)
        df = f - self._filtered
        return [x + d * df for x, d in zip(v, self.feedthrough)]

    def step(self, e: float, applied: float | None = None) -> float:
        """One output-feedback step: error sample ``e`` in, control ``v`` out."""
        e = float(e)
        if not math.isfinite(e):
            raise ValueError(f"e must be finite (got {e})")
        f = self._input(e)
        if self.phi is None:
            if self.order != 1:
                raise ValueError("output feedback at order >= 2 needs a differentiator")
            zhat = [e]
            nxt = [e]
        else:
            if self._started:
                zhat = self._current(self._zhat, f)
            else:
                zhat = [e, *self.initial_derivatives]
            nxt = self._advance(zhat, f)
        if self.limits is not None:
            zhat = [max(-lim, min(lim, z)) for z, lim in zip(zhat, self.limits)]
        return self._finish(zhat, nxt, applied, [e, *self.initial_derivatives], e, f)

    def step_state(self, z: Sequence[float], applied: float | None = None) -> float:
        """One state-feedback step with the measured error vector ``z = (z1..zn)``."""
        z = [float(x) for x in z]
        if len(z) != self.order or not all(math.isfinite(x) for x in z):
            raise ValueError(f"z must be {self.order} finite floats")
        f = self._input(z[0])
        if self.phi is None:
            nxt = z
        else:
            nxt = self._advance(self._current(self._zhat, f) if self._started else z, f)
        return self._finish(z, nxt, applied, z, z[0], f)

    def _restart(self, seed: list, e: float, law_failed: bool) -> None:
        """The recovery rule: the estimate restarts from ``seed`` (the first
        step's estimate for this sample) when the law failed, else (or when that
        is out of range) from a zero error."""
        zero = [0.0, *self.initial_derivatives]
        for s, x in ([(seed, e)] if law_failed else []) + [(zero, 0.0)]:
            nxt = s if self.phi is None else self._advance(s, x)
            if all(abs(v) <= ESTIMATE_RANGE for v in nxt):
                self._zhat, self._filtered = nxt, x
                break
        self._k += 1
        if self.feedthrough is not None:
            # the next sample starts a run: no feedthrough onto the restart
            self._t_base, self._k = self._t_base + float(self._k) * self.dt, 0

    def _finish(
        self, z: list, nxt: list, applied: float | None, seed: list, e: float, filtered: float
    ) -> float:
        if applied is not None:
            applied = float(applied)
            if not math.isfinite(applied):
                raise ValueError(f"applied must be finite (got {applied})")
        if self.phi is not None and not all(abs(x) <= ESTIMATE_RANGE for x in nxt):
            if self._started:
                self._restart(seed, e, law_failed=False)
            raise ValueError("the differentiator's estimate overflowed")
        t = self._t_base + float(self._k) * self.dt
        latch = not self._started
        d = self._law(z, t, latch)
        if latch and not (math.isfinite(self._new_rho0_x) and math.isfinite(self._new_rho0_y)):
            raise ValueError("the envelope's initial width overflowed")
        v = d["v"]
        if not (math.isfinite(v) and math.isfinite(d["xi"])):
            if self._started:
                # a valid sample on which the law overflowed: consumed, the
                # estimate restarts from it (the recovery rule)
                self._restart(seed, e, law_failed=True)
            raise ValueError("an internal value overflowed")
        if applied is not None:
            d["saturation_gap"] = self._last_v - applied
        self._clamps += d["clamp_count"]
        d["clamp_count"] = self._clamps
        if latch:
            self._rho0_x, self._rho0_y = self._new_rho0_x, self._new_rho0_y
        self._started = True
        self._zhat = nxt
        self._filtered = filtered
        self._k += 1
        self._last_v = v
        self.xi = d["xi"]
        self._diag = d
        return v

    def __repr__(self) -> str:
        return (
            f"ReferenceController(order={self.order}, dt={self.dt!r}, "
            f"constraint={self.constraint!r}, k_u={self.k_u!r})"
        )
