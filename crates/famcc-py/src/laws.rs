//! Frozen configuration objects: feedback laws, skews, the differentiator.
//! Each converts to its famcc-core value; validation is famcc-core's.

use crate::errors::config_err;
use famcc_core::{Discretization, Feedback, Real, Skew, SkewKind, SkewedLaw, Transition};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// Evaluates `f` on a float (returns a float) or on an array-like (returns
/// a float64 array of the same length).
pub fn map_float_or_array<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    if let Ok(v) = x.extract::<f64>() {
        return Ok(f(v).into_pyobject(py)?.into_any());
    }
    let np = py.import("numpy")?;
    let arr = np.call_method1("asarray", (x, "float64"))?;
    let flat: PyReadonlyArray1<f64> = arr.call_method0("ravel")?.extract()?;
    let out: Vec<f64> = flat.as_array().iter().map(|v| f(*v)).collect();
    let res = PyArray1::from_vec(py, out);
    Ok(res
        .reshape(arr.getattr("shape")?.extract::<Vec<usize>>()?)?
        .into_any())
}

macro_rules! law_class {
    ($name:ident, $doc:literal, ($($field:ident),*), $build:expr) => {
        #[doc = $doc]
        #[pyclass(frozen, eq, module = "famcc._core")]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name {
            $(#[pyo3(get)] pub $field: f64,)*
        }

        #[pymethods]
        impl $name {
            #[new]
            #[pyo3(signature = ($($field),*))]
            fn new($($field: f64),*) -> PyResult<Self> {
                let s = Self { $($field),* };
                s.feedback::<f64>().validate().map_err(config_err)?;
                Ok(s)
            }

            /// `h_p(x)` on a float or an array.
            fn __call__<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
                let h = self.feedback::<f64>();
                map_float_or_array(py, x, |v| h.eval(v))
            }

            /// `dh_p/dx` on a float or an array.
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
        }

        impl $name {
            pub fn feedback<T: Real>(&self) -> Feedback<T> {
                let $name { $($field),* } = *self;
                $(let $field = T::c($field);)*
                $build
            }
        }
    };
}

law_class!(
    Linear,
    "Linear law `h(s) = -k s` (eq. lfmi).",
    (k),
    Feedback::Linear { k }
);
law_class!(
    FiniteTime,
    "Finite-time law `h(s) = -k |s|^p sign(s)`, `0 < p < 1` (eq. fn).",
    (k, p),
    Feedback::FiniteTime { k, p }
);
law_class!(
    FixedTime,
    "Fixed-time law `h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)`, `0 < p < 1 < q` (eq. RFCs).",
    (alpha, p, beta, q),
    Feedback::FixedTime { alpha, p, beta, q }
);
law_class!(
    VariableExponent,
    "Continuous variable-exponent law (eq. fxe): exponent r_b at 0, r_1 at |s| = 1, r_t at infinity.",
    (k, r_b, r_1, r_t),
    Feedback::VariableExponent { k, r_b, r_1, r_t }
);
law_class!(
    MoulayDiscontinuous,
    "The discontinuous variable-exponent law of Moulay et al. (eq. fvec), for comparison only.",
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
        Err(crate::errors::ConfigError::new_err(format!(
            "{name} must be a law (Linear, FiniteTime, FixedTime, VariableExponent, \
             MoulayDiscontinuous){}, got {}",
            if name == "feedback" {
                " or a list of them"
            } else {
                ""
            },
            obj.repr()?
        )))
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
}

/// Parses a transition name; errors name the argument `arg`.
pub fn parse_transition(name: &str, arg: &str) -> PyResult<Transition> {
    match name {
        "exponential" => Ok(Transition::Exponential),
        "cubic" => Ok(Transition::Cubic),
        "quintic" => Ok(Transition::Quintic),
        "sine" => Ok(Transition::Sine),
        other => Err(crate::errors::ConfigError::new_err(format!(
            "{arg} must be one of 'exponential', 'cubic', 'quintic', 'sine' (got {other:?})"
        ))),
    }
}

pub fn transition_name(t: Transition) -> &'static str {
    match t {
        Transition::Exponential => "exponential",
        Transition::Cubic => "cubic",
        Transition::Quintic => "quintic",
        Transition::Sine => "sine",
    }
}

/// Smooth skewed manifold design (SSMD, eq. SSMD).
#[pyclass(frozen, eq, module = "famcc._core")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    #[pyo3(get)]
    pub eps_s: f64,
    #[pyo3(get)]
    pub eps_z: f64,
    pub transition: Transition,
}

/// Nonsingular skewed manifold design (NSMD, eq. NSMD).
#[pyclass(frozen, eq, module = "famcc._core")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nonsingular {
    #[pyo3(get)]
    pub eps_s: f64,
    #[pyo3(get)]
    pub eps_z: f64,
    #[pyo3(get)]
    pub k_pp: f64,
    pub transition: Transition,
}

fn check_skew<T: Real>(s: Skew<T>) -> PyResult<()> {
    SkewedLaw::new(Feedback::Linear { k: T::one() }, Some(s))
        .map(|_| ())
        .map_err(config_err)
}

/// The Python methods shared by the skew classes: construction with
/// validation, the transition's name, `repr` and pickling.
macro_rules! skew_methods {
    ($name:ident, ($($field:ident),*)) => {
        #[pymethods]
        impl $name {
            #[new]
            #[pyo3(signature = ($($field,)* transition = "exponential"))]
            fn new($($field: f64,)* transition: &str) -> PyResult<Self> {
                let s = Self { $($field,)* transition: parse_transition(transition, "transition")? };
                check_skew(s.skew::<f64>())?;
                Ok(s)
            }
            #[getter(transition)]
            fn get_transition(&self) -> &'static str {
                transition_name(self.transition)
            }
            fn __repr__(&self) -> String {
                let parts: Vec<String> = vec![$(format!("{}={:?}", stringify!($field), self.$field)),*];
                format!("{}({}, transition='{}')", stringify!($name), parts.join(", "), transition_name(self.transition))
            }
            fn __getnewargs__(&self) -> ($(skew_methods!(@f64 $field),)* &'static str) {
                ($(self.$field,)* transition_name(self.transition))
            }
        }
    };
    (@f64 $field:ident) => { f64 };
}

skew_methods!(Smooth, (eps_s, eps_z));
skew_methods!(Nonsingular, (eps_s, eps_z, k_pp));

impl Smooth {
    pub fn skew<T: Real>(&self) -> Skew<T> {
        Skew {
            eps_s: T::c(self.eps_s),
            eps_z: T::c(self.eps_z),
            kind: SkewKind::Smooth,
            transition: self.transition,
        }
    }
}

impl Nonsingular {
    pub fn skew<T: Real>(&self) -> Skew<T> {
        Skew {
            eps_s: T::c(self.eps_s),
            eps_z: T::c(self.eps_z),
            kind: SkewKind::Nonsingular {
                k_pp: T::c(self.k_pp),
            },
            transition: self.transition,
        }
    }
}

/// Any skew object, or none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkewSpec {
    Smooth(Smooth),
    Nonsingular(Nonsingular),
}

impl SkewSpec {
    pub fn extract(obj: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        if obj.is_none() {
            return Ok(None);
        }
        if let Ok(s) = obj.cast::<Smooth>() {
            return Ok(Some(SkewSpec::Smooth(*s.get())));
        }
        if let Ok(s) = obj.cast::<Nonsingular>() {
            return Ok(Some(SkewSpec::Nonsingular(*s.get())));
        }
        Err(crate::errors::ConfigError::new_err(format!(
            "skew must be None, Smooth, Nonsingular, or a list of them, got {}",
            obj.repr()?
        )))
    }

    pub fn skew<T: Real>(&self) -> Skew<T> {
        match self {
            SkewSpec::Smooth(s) => s.skew(),
            SkewSpec::Nonsingular(s) => s.skew(),
        }
    }
}

/// The high-gain differentiator (eq. HGD): gain `mu` (s), Hurwitz
/// coefficients `a`, discretization "exact" (zero-order hold), "euler" or
/// "tustin", and an optional saturation `limits` of the estimates fed to
/// the law.
#[pyclass(frozen, module = "famcc._core")]
#[derive(Clone, Debug)]
pub struct HighGain {
    #[pyo3(get)]
    pub mu: f64,
    pub a: Vec<f64>,
    pub discretization: Discretization,
    pub limits: Option<Vec<f64>>,
}

fn parse_discretization(name: &str) -> PyResult<Discretization> {
    match name {
        "exact" => Ok(Discretization::Exact),
        "euler" => Ok(Discretization::Euler),
        "tustin" => Ok(Discretization::Tustin),
        other => Err(crate::errors::ConfigError::new_err(format!(
            "discretization must be one of 'exact', 'euler', 'tustin' (got {other:?})"
        ))),
    }
}

pub fn discretization_name(d: Discretization) -> &'static str {
    match d {
        Discretization::Exact => "exact",
        Discretization::Euler => "euler",
        Discretization::Tustin => "tustin",
    }
}

fn finite_list(name: &str, v: &[f64]) -> PyResult<()> {
    if v.iter().any(|x| !x.is_finite()) && name == "a" {
        return Err(crate::errors::ConfigError::new_err(format!(
            "{name} must be finite"
        )));
    }
    Ok(())
}

#[pymethods]
impl HighGain {
    #[new]
    #[pyo3(signature = (mu, a, discretization = "exact", limits = None))]
    fn new(mu: f64, a: Vec<f64>, discretization: &str, limits: Option<Vec<f64>>) -> PyResult<Self> {
        if a.is_empty() || a.len() > crate::controller::MAX_ORDER {
            return Err(crate::errors::ConfigError::new_err(format!(
                "a must have between 1 and {} coefficients (one per order), got {}",
                crate::controller::MAX_ORDER,
                a.len()
            )));
        }
        finite_list("a", &a)?;
        if let Some(l) = &limits {
            if l.len() != a.len() {
                return Err(crate::errors::ConfigError::new_err(format!(
                    "limits must have one entry per order ({}), got {}",
                    a.len(),
                    l.len()
                )));
            }
            if l.iter().any(|v| v.is_nan() || *v <= 0.0) {
                return Err(crate::errors::ConfigError::new_err(
                    "limits must all be > 0 (inf allowed)",
                ));
            }
        }
        let h = Self {
            mu,
            a,
            discretization: parse_discretization(discretization)?,
            limits,
        };
        crate::controller::validate_high_gain(&h)?;
        Ok(h)
    }

    /// The paper's default for an order: mu = 0.01, a = (4, 4) at order 2,
    /// (4, 6, 4) at order 3, binomial (s + 2)^n otherwise.
    #[staticmethod]
    #[pyo3(signature = (order, mu = 0.01, discretization = "exact"))]
    fn default(order: usize, mu: f64, discretization: &str) -> PyResult<Self> {
        Self::new(mu, default_coefficients(order)?, discretization, None)
    }

    #[getter]
    fn a<'py>(&self, py: Python<'py>) -> Bound<'py, PyTuple> {
        PyTuple::new(py, &self.a).unwrap_or_else(|_| PyTuple::empty(py))
    }
    #[getter(discretization)]
    fn get_discretization(&self) -> &'static str {
        discretization_name(self.discretization)
    }
    #[getter(limits)]
    fn get_limits<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyTuple>> {
        self.limits.as_ref().and_then(|l| PyTuple::new(py, l).ok())
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
            })
            .unwrap_or(false)
    }
    fn __repr__(&self) -> String {
        let mut s = format!(
            "HighGain(mu={:?}, a={:?}, discretization='{}'",
            self.mu,
            self.a,
            discretization_name(self.discretization)
        );
        if let Some(l) = &self.limits {
            s.push_str(&format!(", limits={l:?}"));
        }
        s.push(')');
        s
    }
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(&self) -> (f64, Vec<f64>, &'static str, Option<Vec<f64>>) {
        (
            self.mu,
            self.a.clone(),
            discretization_name(self.discretization),
            self.limits.clone(),
        )
    }
}

pub fn default_coefficients(order: usize) -> PyResult<Vec<f64>> {
    match order {
        2 => Ok(vec![4.0, 4.0]),
        3 => Ok(vec![4.0, 6.0, 4.0]),
        n if (1..=crate::controller::MAX_ORDER).contains(&n) => {
            // binomial coefficients of (s + 2)^n
            let mut c = vec![1.0_f64];
            for _ in 0..n {
                let mut next = vec![0.0; c.len() + 1];
                for (i, v) in c.iter().enumerate() {
                    next[i] += v;
                    next[i + 1] += 2.0 * v;
                }
                c = next;
            }
            Ok(c[1..].to_vec())
        }
        n => Err(crate::errors::ConfigError::new_err(format!(
            "order must be between 1 and {} (got {n})",
            crate::controller::MAX_ORDER
        ))),
    }
}
