//! `famcc.Observer`: the extended high-gain differentiator's parameters
//! (beyond the paper; docs/observer.md). The rules and the default
//! coefficients are famcc-core's (`ExtendedHighGain`).

use crate::errors::{config_err, ConfigFault};
use crate::names::DISCRETIZATION;
use crate::number::{Num, Text};
use crate::orders::{to_array, with_order};
use famcc_core::config::check_order;
use famcc_core::{Discretization, ExtendedHighGain, Real};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// The extended high-gain observer: disturbance estimation (beyond the paper).
///
/// Estimates the error's derivatives and the lumped term ``L`` of
/// ``z1^(n) = L + b0 u`` (everything the nominal input gain ``b0`` does not
/// explain: the plant's own dynamics, loads, the gain error) from the error
/// samples and the applied input. Passed as ``observer=`` to
/// :class:`Controller`, it replaces the differentiator, and the command
/// becomes ``u = v - clip(Lhat / b0, -delta, delta)``: the law's ``v`` on the
/// same manifold and envelope holds only what the cancellation does not,
/// which removes the steady error of a holding input. Frozen, comparable
/// and picklable.
///
/// Parameters
/// ----------
/// mu : float
///     The time constant ``mu``, s (``> 0``): smaller is faster and
///     amplifies noise more (about 20 sample periods is a start).
/// b0 : float
///     The nominal input gain, output units per input unit per s^n
///     (nonzero; its sign is the control direction). A 20 % error is
///     lumped into ``L`` and cancelled with it.
/// a : sequence of float, default None
///     The coefficients ``(a1, ..., an, a(n+1))`` of
///     ``s^(n+1) + a1 s^n + ... + a(n+1)``, Hurwitz, one more than the
///     order; None: the binomial ``(s + 2)^(n+1)`` at the controller's order.
/// discretization : {'exact', 'foh'}, default 'exact'
///     How the measurement is sampled: held ('exact') or the straight line
///     through the samples ('foh': no lag from the hold on a moving error).
///
/// Raises
/// ------
/// famcc.ConfigError
///     ``mu <= 0``, ``b0 == 0``, coefficients that are not Hurwitz or of a
///     length outside ``2..MAX_ORDER + 1``, or another discretization
///     (naming ``observer_mu``, ``b0``, ``observer_a``,
///     ``observer_discretization``).
///
/// Examples
/// --------
/// >>> import famcc
/// >>> obs = famcc.Observer(0.02, 1.5)
/// >>> obs.mu, obs.b0, obs.a, obs.discretization
/// (0.02, 1.5, None, 'exact')
/// >>> c = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.7), constraint="lateral",
/// ...                      eps=0.1, k_u=5.0, observer=obs, cancellation_limit=4.0)
/// >>> c.config()["observer"] == obs, c.config()["differentiator"] is None
/// (True, True)
#[pyclass(frozen, module = "famcc._core", name = "Observer")]
#[derive(Clone, Debug, PartialEq)]
pub struct Observer {
    /// The time constant, s.
    #[pyo3(get)]
    pub mu: f64,
    /// The nominal input gain.
    #[pyo3(get)]
    pub b0: f64,
    /// `(a_1, ..., a_(n+1))`, or `None`: the binomial default at the order.
    pub a: Option<Vec<f64>>,
    pub discretization: Discretization,
}

impl Observer {
    /// famcc-core's observer of order `N` (`a`, when given, must have
    /// `N + 1` entries).
    pub fn core<T: Real, const N: usize>(&self) -> Option<ExtendedHighGain<T, N>> {
        let t = T::from_f64;
        let obs = match &self.a {
            None => ExtendedHighGain::binomial(t(self.mu), t(self.b0)),
            Some(a) => {
                let (last, head) = a.split_last()?;
                ExtendedHighGain::new(t(self.mu), to_array::<T, N>(head)?, t(*last), t(self.b0))
            }
        };
        Some(obs.with_discretization(self.discretization))
    }

    /// The Python observer of famcc-core's (`a` kept as `None` when it is
    /// the binomial default).
    pub fn from_core<T: Real, const N: usize>(obs: &ExtendedHighGain<T, N>) -> Self {
        let f = |x: T| x.to_f64_lossless();
        let default = ExtendedHighGain::<T, N>::binomial(obs.mu, obs.b0);
        let a = (obs.a != default.a || obs.a_ext != default.a_ext)
            .then(|| obs.a.iter().map(|x| f(*x)).chain([f(obs.a_ext)]).collect());
        Self {
            mu: f(obs.mu),
            b0: f(obs.b0),
            a,
            discretization: obs.discretization,
        }
    }

    /// The checks famcc-core makes of the values alone (at order 1 when the
    /// coefficients are the default, else at theirs).
    fn validate(&self) -> PyResult<()> {
        let order = self.a.as_ref().map_or(1, |a| a.len().saturating_sub(1));
        check_order(order).map_err(|e| {
            let message = format!(
                "observer_a must have order + 1 coefficients: {e} (got {})",
                self.a.as_ref().map_or(0, Vec::len)
            );
            PyErr::from(ConfigFault::new("observer_a", "must have order + 1 coefficients").message(message))
        })?;
        with_order!(order, N => match self.core::<f64, N>() {
            Some(core) => core.validate().map_err(config_err),
            None => Err(ConfigFault::new("observer_a", "must have order + 1 coefficients").into()),
        }, _ => Err(ConfigFault::new("observer_a", "must have order + 1 coefficients").into()))
    }
}

#[pymethods]
impl Observer {
    #[new]
    #[pyo3(signature = (mu, b0, a = None, discretization = Text(DISCRETIZATION.default_name().into())),
        text_signature = "(mu, b0, a=None, discretization='exact')")]
    fn new(mu: Num, b0: Num, a: Option<Vec<Num>>, discretization: Text) -> PyResult<Self> {
        let obs = Self {
            mu: mu.0,
            b0: b0.0,
            a: a.map(|a| a.into_iter().map(|x| x.0).collect()),
            discretization: DISCRETIZATION.parse(&discretization.0, "observer_discretization")?,
        };
        obs.validate()?;
        Ok(obs)
    }

    /// The coefficients ``(a1, ..., a(n+1))``, or None (the binomial default).
    #[getter]
    fn a<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyTuple>>> {
        self.a.as_ref().map(|a| PyTuple::new(py, a)).transpose()
    }

    /// 'exact' or 'foh'.
    #[getter(discretization)]
    fn get_discretization(&self) -> &'static str {
        DISCRETIZATION.name(self.discretization)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Observer>().is_ok_and(|o| o.get() == self)
    }

    fn __repr__(&self) -> String {
        let mut s = format!("Observer(mu={:?}, b0={:?}", self.mu, self.b0);
        if let Some(a) = &self.a {
            s.push_str(&format!(", a={a:?}"));
        }
        if self.discretization != Discretization::Exact {
            s.push_str(&format!(
                ", discretization='{}'",
                DISCRETIZATION.name(self.discretization)
            ));
        }
        s.push(')');
        s
    }

    #[allow(clippy::type_complexity)]
    /// Pickling for every protocol (0 and 1 too).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        Ok((slf.get_type().into_any(), slf.call_method0("__getnewargs__")?))
    }

    fn __getnewargs__(&self) -> (f64, f64, Option<Vec<f64>>, &'static str) {
        (
            self.mu,
            self.b0,
            self.a.clone(),
            DISCRETIZATION.name(self.discretization),
        )
    }
}
