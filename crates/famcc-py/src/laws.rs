//! Frozen configuration objects: the feedback laws `h_p` (the skews are in
//! `skews.rs`). Each converts to its famcc-core value (and back, for the
//! paper's designs); validation is famcc-core's.

use crate::array::map_float_or_array;
use crate::errors::{config_err, ConfigFault};
use crate::number::Num;
use famcc_core::{Feedback, Real};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

macro_rules! law_class {
    ($(#[doc = $doc:tt])* $name:ident, ($($field:ident),*), $build:expr) => {
        $(#[doc = $doc])*
        #[pyclass(frozen, eq, module = "famcc._core")]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name {
            $(#[pyo3(get)] pub $field: f64,)*
        }

        #[pymethods]
        impl $name {
            #[new]
            #[pyo3(signature = ($($field),*))]
            fn new($($field: Num),*) -> PyResult<Self> {
                let s = Self { $($field: $field.0),* };
                s.feedback::<f64>().validate().map_err(config_err)?;
                Ok(s)
            }

            /// The law's value ``h_p(x)``.
            ///
            /// Parameters
            /// ----------
            /// x : float or array_like
            ///     The stage variable, in its own unit.
            ///
            /// Returns
            /// -------
            /// float or numpy.ndarray
            ///     ``h_p(x)``, unit of ``x`` per s; an array of the shape of
            ///     ``x`` for an array.
            fn __call__<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
                let h = self.feedback::<f64>();
                map_float_or_array(py, x, |v| h.eval(v))
            }

            /// The law's slope ``dh_p/dx``.
            ///
            /// Parameters
            /// ----------
            /// x : float or array_like
            ///     The stage variable, in its own unit.
            ///
            /// Returns
            /// -------
            /// float or numpy.ndarray
            ///     ``dh_p/dx``, 1/s; an array of the shape of ``x`` for an
            ///     array.
            fn slope<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
                let h = self.feedback::<f64>();
                map_float_or_array(py, x, |v| h.slope(v))
            }

            fn __repr__(&self) -> String {
                let parts: Vec<String> = vec![$(format!("{}={:?}", stringify!($field), self.$field)),*];
                format!("{}({})", stringify!($name), parts.join(", "))
            }

            fn __getnewargs__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
                PyTuple::new(py, [$(self.$field),*])
            }

            /// Pickling for every protocol (0 and 1 too): the class and its
            /// constructor arguments.
            fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
                Ok((slf.get_type().into_any(), slf.call_method0("__getnewargs__")?))
            }
        }

        impl $name {
            pub fn feedback<T: Real>(&self) -> Feedback<T> {
                let $name { $($field),* } = *self;
                $(let $field = T::from_f64($field);)*
                $build
            }
        }
    };
}

law_class!(
    /// Linear law ``h(s) = -k s`` (eq. (59) (lfmi)).
    ///
    /// A stage law ``h_p`` of the iterative manifold: it maps a stage value
    /// ``s`` to the desired rate ``ds/dt = h_p(s)``. Callable on floats and
    /// NumPy arrays; frozen, comparable and picklable.
    ///
    /// Parameters
    /// ----------
    /// k : float
    ///     Gain, 1/s, ``k > 0``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     ``k`` not finite and ``> 0``.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.Linear(k=2.0)
    /// >>> h(0.5), h.slope(0.5)
    /// (-1.0, -2.0)
    Linear,
    (k),
    Feedback::Linear { k }
);
law_class!(
    /// Finite-time law ``h(s) = -k |s|^p sign(s)``, ``0 < p < 1`` (eq. (37) (fn)).
    ///
    /// A stage law ``h_p`` (``ds/dt = h_p(s)``) that reaches ``s = 0`` in
    /// finite time (Corollary 1, eq. (42) (fnT)). Callable on floats and NumPy
    /// arrays; frozen, comparable and picklable.
    ///
    /// Parameters
    /// ----------
    /// k : float
    ///     Gain, ``k > 0``, unit of ``s`` per s over unit of ``s`` to the
    ///     power ``p``.
    /// p : float
    ///     Exponent, dimensionless, ``0 < p < 1``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     ``k <= 0`` or ``p`` outside ``(0, 1)``.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.FiniteTime(k=1.0, p=0.5)
    /// >>> h(4.0), h(-4.0)
    /// (-2.0, 2.0)
    FiniteTime,
    (k, p),
    Feedback::FiniteTime { k, p }
);
law_class!(
    /// Fixed-time law ``h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)``, ``0 < p < 1 < q`` (eq. (61) (RFCs)).
    ///
    /// A stage law ``h_p`` (``ds/dt = h_p(s)``) whose settling time is bounded
    /// independently of the initial value (Corollary 3, eq. (63) (fxTho)).
    /// Callable on floats and NumPy arrays; frozen, comparable and picklable.
    ///
    /// Parameters
    /// ----------
    /// alpha : float
    ///     Low-power gain, ``alpha > 0`` (unit of ``s`` per s over unit of
    ///     ``s`` to the power ``p``).
    /// p : float
    ///     Low power, dimensionless, ``0 < p < 1``.
    /// beta : float
    ///     High-power gain, ``beta > 0`` (unit of ``s`` per s over unit of
    ///     ``s`` to the power ``q``).
    /// q : float
    ///     High power, dimensionless, finite and ``q > 1``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A gain ``<= 0``, ``p`` outside ``(0, 1)`` or ``q <= 1``.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0)
    /// >>> h(4.0)
    /// -10.0
    FixedTime,
    (alpha, p, beta, q),
    Feedback::FixedTime { alpha, p, beta, q }
);
law_class!(
    /// Continuous variable-exponent law (eq. (45) (fxe)): exponent r_b at 0, r_1 at |s| = 1, r_t at infinity.
    ///
    /// ``h(s) = -k |s|^r(s) sign(s)`` with ``r(s) = a s^2 / (1 + b s^2) + r_b``,
    /// ``b = (r_1 - r_b) / (r_t - r_1)`` and ``a = (r_t - r_b) b``: a stage law
    /// ``h_p`` (``ds/dt = h_p(s)``) with a settling bound of Corollary 2
    /// (eq. (53) (fxeT)). Callable on floats and NumPy arrays; frozen,
    /// comparable and picklable.
    ///
    /// Parameters
    /// ----------
    /// k : float
    ///     Gain, ``k > 0`` (unit of ``s`` per s at ``|s| = 1``).
    /// r_b : float
    ///     Exponent at ``s = 0``, dimensionless, ``0 < r_b < 1``.
    /// r_1 : float
    ///     Exponent at ``|s| = 1``, dimensionless, ``r_1 > 1``.
    /// r_t : float
    ///     Exponent as ``|s|`` tends to infinity, dimensionless, finite and
    ///     ``r_t > r_1``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A rule above broken, or ``r_b`` too small for ``r_1`` and ``r_t``
    ///     (``h`` must be strictly decreasing, paper Step B1).
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.VariableExponent(k=1.5, r_b=0.5, r_1=2.0, r_t=3.0)
    /// >>> h(1.0), h(-1.0)
    /// (-1.5, 1.5)
    VariableExponent,
    (k, r_b, r_1, r_t),
    Feedback::VariableExponent { k, r_b, r_1, r_t }
);
law_class!(
    /// The discontinuous variable-exponent law of Moulay et al. (eq. (58) (fvec)), for comparison only.
    ///
    /// ``h(s) = -beta |s|^p(s) sign(s)`` with ``p(s) = lambda_ s^2 / (1 + mu s^2)``.
    /// Its exponent is 0 at ``s = 0``, so ``h`` jumps from ``+beta`` to
    /// ``-beta`` across zero. Callable on floats and NumPy arrays; frozen,
    /// comparable and picklable.
    ///
    /// Parameters
    /// ----------
    /// beta : float
    ///     Gain, ``beta > 0`` (unit of ``s`` per s).
    /// lambda_ : float
    ///     Exponent numerator coefficient, ``lambda_ > 0`` (1 over unit of
    ///     ``s`` squared).
    /// mu : float
    ///     Exponent denominator coefficient, finite and ``mu >= 0`` (1 over
    ///     unit of ``s`` squared).
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     ``beta <= 0``, ``lambda_ <= 0`` or ``mu < 0``.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> h = famcc.MoulayDiscontinuous(beta=1.0, lambda_=1.0, mu=0.5)
    /// >>> h(1e-9) < -0.99, h(-1e-9) > 0.99
    /// (True, True)
    MoulayDiscontinuous,
    (beta, lambda_, mu),
    Feedback::MoulayDiscontinuous {
        beta,
        lambda: lambda_,
        mu
    }
);

/// Any feedback law object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Law {
    Linear(Linear),
    FiniteTime(FiniteTime),
    FixedTime(FixedTime),
    VariableExponent(VariableExponent),
    Moulay(MoulayDiscontinuous),
}

impl Law {
    pub fn extract(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::extract_named(obj, "law")
    }

    /// Like `extract`; errors name the argument `name`.
    pub fn extract_named(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Self> {
        if let Ok(l) = obj.cast::<Linear>() {
            return Ok(Law::Linear(*l.get()));
        }
        if let Ok(l) = obj.cast::<FiniteTime>() {
            return Ok(Law::FiniteTime(*l.get()));
        }
        if let Ok(l) = obj.cast::<FixedTime>() {
            return Ok(Law::FixedTime(*l.get()));
        }
        if let Ok(l) = obj.cast::<VariableExponent>() {
            return Ok(Law::VariableExponent(*l.get()));
        }
        if let Ok(l) = obj.cast::<MoulayDiscontinuous>() {
            return Ok(Law::Moulay(*l.get()));
        }
        let rule = format!(
            "must be a law (Linear, FiniteTime, FixedTime, VariableExponent, MoulayDiscontinuous){}",
            if name == "feedback" {
                " or a list of them"
            } else {
                ""
            }
        );
        let message = format!("{name} {rule}, got {}", obj.repr()?);
        Err(ConfigFault::new(name, rule).message(message).into())
    }

    pub fn feedback<T: Real>(&self) -> Feedback<T> {
        match self {
            Law::Linear(l) => l.feedback(),
            Law::FiniteTime(l) => l.feedback(),
            Law::FixedTime(l) => l.feedback(),
            Law::VariableExponent(l) => l.feedback(),
            Law::Moulay(l) => l.feedback(),
        }
    }

    /// The law object of a core law.
    pub fn from_feedback<T: Real>(f: &Feedback<T>) -> Self {
        let x = |v: T| v.to_f64_lossless();
        match *f {
            Feedback::Linear { k } => Law::Linear(Linear { k: x(k) }),
            Feedback::FiniteTime { k, p } => Law::FiniteTime(FiniteTime { k: x(k), p: x(p) }),
            Feedback::FixedTime { alpha, p, beta, q } => Law::FixedTime(FixedTime {
                alpha: x(alpha),
                p: x(p),
                beta: x(beta),
                q: x(q),
            }),
            Feedback::VariableExponent { k, r_b, r_1, r_t } => Law::VariableExponent(VariableExponent {
                k: x(k),
                r_b: x(r_b),
                r_1: x(r_1),
                r_t: x(r_t),
            }),
            Feedback::MoulayDiscontinuous { beta, lambda, mu } => Law::Moulay(MoulayDiscontinuous {
                beta: x(beta),
                lambda_: x(lambda),
                mu: x(mu),
            }),
        }
    }

    /// The Python object.
    pub fn to_object<'py>(self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(match self {
            Law::Linear(l) => l.into_pyobject(py)?.into_any(),
            Law::FiniteTime(l) => l.into_pyobject(py)?.into_any(),
            Law::FixedTime(l) => l.into_pyobject(py)?.into_any(),
            Law::VariableExponent(l) => l.into_pyobject(py)?.into_any(),
            Law::Moulay(l) => l.into_pyobject(py)?.into_any(),
        })
    }
}
