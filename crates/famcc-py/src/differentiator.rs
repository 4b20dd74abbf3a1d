//! `famcc.HighGain`: the high-gain differentiator's parameters. The rules
//! and the paper's choice of them are famcc-core's.

use crate::errors::{config_err, config_err_got, ConfigFault};
use crate::names::DISCRETIZATION;
use crate::number::{Num, Text};
use crate::orders::{to_array, with_order};
use famcc_core::config::{check_estimate_limits, check_order};
use famcc_core::differentiator::{auto_discretization, paper_coefficients, PAPER_MU};
use famcc_core::{Discretization, Real};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// The high-gain differentiator (eq. (34) (HGD)).
///
/// Estimates the error's derivatives ``e', ..., e^(n-1)`` from its samples
/// for the output-feedback controller (eq. (35) (uOF)): passed as
/// ``differentiator=`` to :class:`Controller`. Frozen, comparable and
/// picklable; :meth:`default` builds the paper's.
///
/// Parameters
/// ----------
/// mu : float
///     The gain's time constant ``mu``, s (``> 0``): smaller is faster and
///     amplifies noise more.
/// a : sequence of float
///     The coefficients ``(a1, ..., an)``, one per order (``1..MAX_ORDER``
///     entries), all ``> 0``, with ``s^n + a1 s^(n-1) + ... + an`` Hurwitz;
///     dimensionless.
/// discretization : {'exact', 'euler', 'tustin', 'foh'}, default 'exact'
///     How the continuous differentiator is discretized for the sample
///     period: 'exact' (zero-order hold), 'euler' (forward), 'tustin'
///     (bilinear) or 'foh' (first-order hold: the measurement is the
///     straight line through the samples, and the estimate of a sample
///     uses that sample; famcc's choice below 1 kHz, see ``for_rate``).
/// limits : sequence of float, default None
///     Saturation ``|z_hat_i| <= limit_i`` of the estimates fed to the law,
///     one per order, in the unit of each estimate (``z_k`` in the unit of
///     ``e`` per s^(k-1)), all ``> 0`` (``inf``: no limit for that
///     estimate); None: no limits.
/// prefilter : float, default 0.0
///     Time constant ``tau`` of a first-order low-pass stage on the measured
///     error in front of the differentiator, s (``>= 0``; 0: none, the
///     paper's differentiator). Against measurement noise: it rolls the
///     noise off by one more order above ``1/tau`` for a lag of about
///     ``tau``; :func:`famcc.design` with ``noise_std`` sets ``mu / 2``. Not
///     in the paper.
///
/// Raises
/// ------
/// famcc.ConfigError
///     ``mu <= 0``, coefficients that are not Hurwitz, ``limits`` of the
///     wrong length or not ``> 0``, or ``prefilter < 0``.
///
/// Examples
/// --------
/// >>> import famcc
/// >>> h = famcc.HighGain(0.01, [4.0, 4.0])
/// >>> h.a, h.discretization, h.limits, h.prefilter
/// ((4.0, 4.0), 'exact', None, 0.0)
/// >>> famcc.HighGain.default(2) == h
/// True
/// >>> famcc.HighGain(0.02, [4.0, 6.0, 4.0], prefilter=0.01)
/// HighGain(mu=0.02, a=[4.0, 6.0, 4.0], discretization='exact', prefilter=0.01)
#[pyclass(frozen, module = "famcc._core")]
#[derive(Clone, Debug)]
pub struct HighGain {
    /// The gain's time constant, s.
    #[pyo3(get)]
    pub mu: f64,
    pub a: Vec<f64>,
    pub discretization: Discretization,
    pub limits: Option<Vec<f64>>,
    /// The prefilter's time constant, s (0: none).
    #[pyo3(get)]
    pub prefilter: f64,
}

impl HighGain {
    /// The paper's differentiator for `order` (famcc-core's
    /// `HighGain::paper`), with the discretization's default.
    pub fn paper(order: usize) -> PyResult<Self> {
        Self::default(order, PAPER_MU, DISCRETIZATION.default_name())
    }

    /// famcc's default differentiator ("auto", famcc-core's
    /// `HighGain::auto_for`): the paper's up to order 3, Tustin with the
    /// binomial `(s + 2)^n` and `mu = 0.01` from order 4 on.
    pub fn auto(order: usize) -> PyResult<Self> {
        let name = DISCRETIZATION.name(auto_discretization(order));
        Self::default(order, PAPER_MU, name)
    }

    /// The core's differentiator of order `N` (`a` must have `N` entries).
    pub fn core<T: Real, const N: usize>(&self) -> Option<famcc_core::HighGain<T, N>> {
        self.core_padded(0)
    }

    /// The core's differentiator in an `N`-sized array with `pad` trailing
    /// zero coefficients (`a` must have `N - pad` entries): with integral
    /// action (`pad = 1`) the core runs it at order `N - 1`.
    pub fn core_padded<T: Real, const N: usize>(&self, pad: usize) -> Option<famcc_core::HighGain<T, N>> {
        let full: Vec<f64> = self
            .a
            .iter()
            .copied()
            .chain(core::iter::repeat_n(0.0, pad))
            .collect();
        let a = to_array::<T, N>(&full)?;
        Some(
            famcc_core::HighGain::new(T::from_f64(self.mu), a, self.discretization)
                .with_prefilter(T::from_f64(self.prefilter)),
        )
    }

    /// The estimate limits in an `N`-sized array after `shift` leading
    /// unlimited slots (the integral's, with integral action), if any.
    pub fn core_limits_shifted<T: Real, const N: usize>(&self, shift: usize) -> Option<[T; N]> {
        let l = self.limits.as_deref()?;
        let full: Vec<f64> = core::iter::repeat_n(f64::INFINITY, shift)
            .chain(l.iter().copied())
            .collect();
        to_array::<T, N>(&full)
    }

    /// The object of a core differentiator and its estimate limits, whose
    /// plant's entries start at slot `off` (1 with integral action).
    pub fn from_core<T: Real, const N: usize>(
        h: &famcc_core::HighGain<T, N>,
        limits: Option<&[T; N]>,
        off: usize,
    ) -> Self {
        let v = |x: &[T], skip: usize, take: usize| {
            x.iter()
                .skip(skip)
                .take(take)
                .map(|x| x.to_f64_lossless())
                .collect::<Vec<_>>()
        };
        let order = N - off;
        Self {
            mu: h.mu.to_f64_lossless(),
            a: v(&h.a, 0, order),
            discretization: h.discretization,
            limits: limits.map(|l| v(l, off, order)),
            prefilter: h.prefilter.to_f64_lossless(),
        }
    }
}

#[pymethods]
impl HighGain {
    #[new]
    // The defaults are famcc-core's; the Python signatures spell them out
    // (tests/test_docs.py checks each against the default in effect).
    #[pyo3(signature = (mu, a, discretization = Text(DISCRETIZATION.default_name().into()), limits = None, prefilter = Num(0.0)),
        text_signature = "(mu, a, discretization='exact', limits=None, prefilter=0.0)")]
    fn new(
        mu: Num,
        a: Vec<Num>,
        discretization: Text,
        limits: Option<Vec<Num>>,
        prefilter: Num,
    ) -> PyResult<Self> {
        let (mu, discretization) = (mu.0, discretization.0.as_str());
        let a: Vec<f64> = a.into_iter().map(|x| x.0).collect();
        let limits: Option<Vec<f64>> = limits.map(|l| l.into_iter().map(|x| x.0).collect());
        check_order(a.len()).map_err(|e| {
            let message = format!("a must have one coefficient per order: {e} (got {})", a.len());
            PyErr::from(ConfigFault::new("a", "must have one coefficient per order").message(message))
        })?;
        if let Some(l) = &limits {
            if l.len() != a.len() {
                let rule = format!("must have one entry per order ({})", a.len());
                let message = format!("limits {rule}, got {}", l.len());
                return Err(ConfigFault::new("limits", rule).message(message).into());
            }
            check_estimate_limits(l).map_err(|e| PyErr::from(ConfigFault::new("limits", e.rule)))?;
        }
        let h = Self {
            mu,
            a,
            discretization: DISCRETIZATION.parse(discretization, "discretization")?,
            limits,
            prefilter: prefilter.0,
        };
        with_order!(h.a.len(), N => match h.core::<f64, N>() {
            Some(core) => core.validate().map_err(config_err)?,
            None => unreachable_length()?,
        }, _ => unreachable_length()?);
        Ok(h)
    }

    /// The paper's differentiator for an order (famcc-core's ``HighGain::paper``).
    ///
    /// Parameters
    /// ----------
    /// order : int
    ///     The order n, ``1 <= order <= MAX_ORDER``.
    /// mu : float, default 0.01
    ///     The gain's time constant, s (the paper's).
    /// discretization : {'exact', 'euler', 'tustin'}, default 'exact'
    ///     As for the constructor.
    ///
    /// Returns
    /// -------
    /// HighGain
    ///     ``a = (4, 4)`` at order 2, ``(4, 6, 4)`` at order 3, the binomial
    ///     ``(s + 2)^n`` otherwise; no limits.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     An order outside ``1..MAX_ORDER`` or ``mu <= 0``.
    #[staticmethod]
    #[pyo3(signature = (order, mu = PAPER_MU, discretization = DISCRETIZATION.default_name()),
        text_signature = "(order, mu=0.01, discretization='exact')")]
    fn default(order: usize, mu: f64, discretization: &str) -> PyResult<Self> {
        check_order(order).map_err(|e| config_err_got(e, order))?;
        let mut a = vec![0.0; order];
        paper_coefficients(&mut a);
        Self::new(
            Num(mu),
            a.into_iter().map(Num).collect(),
            Text(discretization.into()),
            None,
            Num(0.0),
        )
    }

    /// famcc's default differentiator for an order and a sample period.
    ///
    /// famcc-core's ``HighGain::auto_at``: the paper's differentiator at
    /// ``dt <= 1 ms`` (up to order 3); at slower rates a faster ``mu`` that
    /// keeps the loop's delay. Up to order 3: the exact hold while
    /// ``mu >= 10 dt`` (the paper's: 1 kHz and faster), else the first-order hold
    /// ('foh'), whose estimate uses the current sample, with
    /// ``mu = 0.01 - (dt - 3 ms) / order`` (at most 0.01, at least
    /// ``dt / 2``). From order 4 on Tustin, with
    /// ``mu = 0.01 - (3 / order) (dt - 1 ms)`` (at least ``min(dt, 0.01)``).
    ///
    /// Parameters
    /// ----------
    /// order : int
    ///     The differentiator's order (the plant's order), 1 to 8.
    /// dt : float
    ///     The sample period, s.
    ///
    /// Returns
    /// -------
    /// HighGain
    ///     The differentiator famcc picks for that rate.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     If ``order`` is out of range or ``dt`` is not finite and > 0.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.HighGain.for_rate(3, 5e-3)   # 200 Hz
    /// >>> round(h.mu, 6), h.discretization
    /// (0.009333, 'foh')
    #[staticmethod]
    #[pyo3(text_signature = "(order, dt)")]
    fn for_rate(order: usize, dt: Num) -> PyResult<Self> {
        let dt = dt.0;
        check_order(order).map_err(|e| config_err_got(e, order))?;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ConfigFault::new("dt", "must be finite and > 0").got(dt).into());
        }
        let h = famcc_core::HighGain::<f64, { famcc_core::config::MAX_ORDER }>::auto_at(order, dt);
        let a = h.a.get(..order).map(<[f64]>::to_vec).unwrap_or_default();
        Self::new(
            Num(h.mu),
            a.into_iter().map(Num).collect(),
            Text(DISCRETIZATION.name(h.discretization).into()),
            None,
            Num(0.0),
        )
    }

    /// The discretization famcc picks for a differentiator sampled at ``dt``.
    ///
    /// famcc-core's ``auto_discretization_at`` (also ``famcc.design``'s and
    /// :meth:`for_rate`'s): up to order 3 'exact' while ``mu >= 10 dt`` (the
    /// paper's ratio), 'foh' (first-order hold) at coarser sampling; 'tustin'
    /// from order 4 on.
    ///
    /// Parameters
    /// ----------
    /// order : int
    ///     The differentiator's order (the plant's order), 1 to 8.
    /// dt : float
    ///     The sample period, s.
    /// mu : float
    ///     The differentiator's time constant, s.
    ///
    /// Returns
    /// -------
    /// str
    ///     'exact', 'foh' or 'tustin'.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     If ``order`` is out of range, or ``dt`` or ``mu`` is not finite and > 0.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> H = famcc.HighGain
    /// >>> H.discretization_for(2, 1e-3, 0.01), H.discretization_for(2, 5e-3, 0.01)
    /// ('exact', 'foh')
    #[staticmethod]
    #[pyo3(text_signature = "(order, dt, mu)")]
    fn discretization_for(order: usize, dt: Num, mu: Num) -> PyResult<&'static str> {
        check_order(order).map_err(|e| config_err_got(e, order))?;
        for (name, v) in [("dt", dt.0), ("mu", mu.0)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ConfigFault::new(name, "must be finite and > 0").got(v).into());
            }
        }
        Ok(
            DISCRETIZATION.name(famcc_core::differentiator::auto_discretization_at(
                order, dt.0, mu.0,
            )),
        )
    }

    /// The coefficients ``(a1, ..., an)``.
    #[getter]
    fn a<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, &self.a)
    }
    /// 'exact', 'euler', 'tustin' or 'foh'.
    #[getter(discretization)]
    fn get_discretization(&self) -> &'static str {
        DISCRETIZATION.name(self.discretization)
    }
    /// The estimates' limits, or None.
    #[getter(limits)]
    fn get_limits<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyTuple>>> {
        self.limits.as_ref().map(|l| PyTuple::new(py, l)).transpose()
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<HighGain>()
            .map(|o| {
                let o = o.get();
                o.mu == self.mu
                    && o.a == self.a
                    && o.discretization == self.discretization
                    && o.limits == self.limits
                    && o.prefilter == self.prefilter
            })
            .unwrap_or(false)
    }
    fn __repr__(&self) -> String {
        let mut s = format!(
            "HighGain(mu={:?}, a={:?}, discretization='{}'",
            self.mu,
            self.a,
            DISCRETIZATION.name(self.discretization)
        );
        if let Some(l) = &self.limits {
            s.push_str(&format!(", limits={l:?}"));
        }
        if self.prefilter != 0.0 {
            s.push_str(&format!(", prefilter={:?}", self.prefilter));
        }
        s.push(')');
        s
    }
    #[allow(clippy::type_complexity)]
    /// Pickling for every protocol (0 and 1 too).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        Ok((slf.get_type().into_any(), slf.call_method0("__getnewargs__")?))
    }

    fn __getnewargs__(&self) -> (f64, Vec<f64>, &'static str, Option<Vec<f64>>, f64) {
        (
            self.mu,
            self.a.clone(),
            DISCRETIZATION.name(self.discretization),
            self.limits.clone(),
            self.prefilter,
        )
    }
}

/// The length was checked by `check_order`; this is never reached.
fn unreachable_length() -> PyResult<()> {
    Err(ConfigFault::new("a", "must have one coefficient per order").into())
}
