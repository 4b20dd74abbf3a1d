//! Frozen configuration objects: the feedback laws and the skews. Each
//! converts to its famcc-core value (and back, for the paper's designs);
//! validation is famcc-core's.

use crate::array::map_float_or_array;
use crate::errors::{config_err, ConfigError};
use crate::names::TRANSITION;
use crate::number::{Num, Text};
use famcc_core::{Feedback, Real, Skew, SkewKind, Transition};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

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
            fn new($($field: Num),*) -> PyResult<Self> {
                let s = Self { $($field: $field.0),* };
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
    Linear,
    "Linear law `h(s) = -k s` (eq. (59) (lfmi)).",
    (k),
    Feedback::Linear { k }
);
law_class!(
    FiniteTime,
    "Finite-time law `h(s) = -k |s|^p sign(s)`, `0 < p < 1` (eq. (37) (fn)).",
    (k, p),
    Feedback::FiniteTime { k, p }
);
law_class!(
    FixedTime,
    "Fixed-time law `h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)`, `0 < p < 1 < q` (eq. (61) (RFCs)).",
    (alpha, p, beta, q),
    Feedback::FixedTime { alpha, p, beta, q }
);
law_class!(
    VariableExponent,
    "Continuous variable-exponent law (eq. (45) (fxe)): exponent r_b at 0, r_1 at |s| = 1, r_t at infinity.",
    (k, r_b, r_1, r_t),
    Feedback::VariableExponent { k, r_b, r_1, r_t }
);
law_class!(
    MoulayDiscontinuous,
    "The discontinuous variable-exponent law of Moulay et al. (eq. (58) (fvec)), for comparison only.",
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
        Err(ConfigError::new_err(format!(
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

/// Smooth skewed manifold design (SSMD, eq. (14)).
#[pyclass(frozen, eq, module = "famcc._core")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    #[pyo3(get)]
    pub eps_s: f64,
    #[pyo3(get)]
    pub eps_z: f64,
    pub transition: Transition,
}

/// Nonsingular skewed manifold design (NSMD, eq. (15)).
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

/// The Python methods shared by the skew classes: construction with
/// validation, the transition's name, `repr` and pickling.
macro_rules! skew_methods {
    ($name:ident, ($($field:ident),*)) => {
        #[pymethods]
        impl $name {
            #[new]
            #[pyo3(signature = ($($field,)* transition = Text(TRANSITION.default_name().into())))]
            fn new($($field: Num,)* transition: Text) -> PyResult<Self> {
                let s = Self { $($field: $field.0,)* transition: TRANSITION.parse(&transition.0, "transition")? };
                s.skew::<f64>().validate().map_err(config_err)?;
                Ok(s)
            }
            #[getter(transition)]
            fn get_transition(&self) -> &'static str {
                TRANSITION.name(self.transition)
            }
            fn __repr__(&self) -> String {
                let parts: Vec<String> = vec![$(format!("{}={:?}", stringify!($field), self.$field)),*];
                format!("{}({}, transition='{}')", stringify!($name), parts.join(", "), TRANSITION.name(self.transition))
            }
            fn __getnewargs__(&self) -> ($(skew_methods!(@f64 $field),)* &'static str) {
                ($(self.$field,)* TRANSITION.name(self.transition))
            }

            /// Pickling for every protocol (0 and 1 too): the class and its
            /// constructor arguments.
            fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
                Ok((slf.get_type().into_any(), slf.call_method0("__getnewargs__")?))
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
            eps_s: T::from_f64(self.eps_s),
            eps_z: T::from_f64(self.eps_z),
            kind: SkewKind::Smooth,
            transition: self.transition,
        }
    }
}

impl Nonsingular {
    pub fn skew<T: Real>(&self) -> Skew<T> {
        Skew {
            eps_s: T::from_f64(self.eps_s),
            eps_z: T::from_f64(self.eps_z),
            kind: SkewKind::Nonsingular {
                k_pp: T::from_f64(self.k_pp),
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
        Err(ConfigError::new_err(format!(
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

    /// The skew object of a core skew.
    pub fn from_skew<T: Real>(s: &Skew<T>) -> Self {
        let (eps_s, eps_z) = (s.eps_s.to_f64_lossless(), s.eps_z.to_f64_lossless());
        let transition = s.transition;
        match s.kind {
            SkewKind::Smooth => SkewSpec::Smooth(Smooth {
                eps_s,
                eps_z,
                transition,
            }),
            SkewKind::Nonsingular { k_pp } => SkewSpec::Nonsingular(Nonsingular {
                eps_s,
                eps_z,
                k_pp: k_pp.to_f64_lossless(),
                transition,
            }),
        }
    }

    /// The Python object.
    pub fn to_object<'py>(self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(match self {
            SkewSpec::Smooth(s) => s.into_pyobject(py)?.into_any(),
            SkewSpec::Nonsingular(s) => s.into_pyobject(py)?.into_any(),
        })
    }
}
