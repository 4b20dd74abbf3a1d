//! Frozen configuration objects: the skews of a stage law (SSMD and NSMD,
//! paper eqs. (14) and (15)). Each converts to its famcc-core value (and
//! back, for the paper's designs); validation is famcc-core's.

use crate::errors::{config_err, ConfigFault};
use crate::names::TRANSITION;
use crate::number::{Num, Text};
use famcc_core::{Real, Skew, SkewKind, Transition};
use pyo3::prelude::*;

/// Smooth skewed manifold design (SSMD, eq. (14) (SSMD)).
///
/// Skews a stage law: ``h_m(s) = h_p(s) + T1(s) eps_s`` with
/// ``T1(s) = 1 - 2 S((s + eps_z) / (2 eps_z))``, so ``h_m = h_p +- eps_s``
/// outside ``+-eps_z``. Passed as ``skew=`` to :class:`Controller` or to
/// :func:`skewed`; frozen, comparable and picklable.
///
/// Parameters
/// ----------
/// eps_s : float
///     Vertical offset of the skewed law outside ``+-eps_z``, ``> 0``, rate
///     units (unit of ``s`` per s).
/// eps_z : float
///     Half-width of the transition zone around 0, ``> 0``, unit of ``s``.
/// transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
///     The double-ended transition ``S`` of ``T1``; 'exponential' is the
///     paper's eq. (2) (trnsS).
///
/// Raises
/// ------
/// famcc.ConfigError
///     ``eps_s`` or ``eps_z`` not finite and ``> 0``, or an unknown
///     ``transition``.
///
/// Examples
/// --------
/// >>> import famcc
/// >>> h = famcc.skewed(famcc.Linear(1.0), famcc.Smooth(eps_s=0.2, eps_z=0.1))
/// >>> round(h(-1.0), 12), h(0.0)
/// (1.2, 0.0)
#[pyclass(frozen, eq, module = "famcc._core")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    #[pyo3(get)]
    pub eps_s: f64,
    #[pyo3(get)]
    pub eps_z: f64,
    pub transition: Transition,
}

/// Nonsingular skewed manifold design (NSMD, eq. (15) (NSMD)).
///
/// Skews a stage law: ``h_m(s) = T2(s) (h_p(s) + T1(s) eps_s) - (1 - T2(s)) k_p s``
/// with ``T2(s) = U(s / eps_z)`` and ``k_p = k_pp (eps_s - h_p(eps_z)) / eps_z``.
/// Outside ``+-eps_z`` it equals ``h_p +- eps_s``; near 0 it is the line
/// ``-k_p s``, which removes the infinite slope of power laws below 1. The
/// widths of Corollary 3 are eqs. (62a) (NSMDie), (62b) (NSMDif). Passed as
/// ``skew=`` to :class:`Controller` or to :func:`skewed`; frozen, comparable
/// and picklable.
///
/// Parameters
/// ----------
/// eps_s : float
///     Vertical offset of the skewed law outside ``+-eps_z``, ``> 0``, rate
///     units (unit of ``s`` per s).
/// eps_z : float
///     Half-width of the transition zone around 0, ``> 0``, unit of ``s``.
/// k_pp : float
///     Slope factor, dimensionless, ``> 0``: it sets the slope ``-k_p`` of
///     ``h_m`` at 0.
/// transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
///     The double-ended transition ``S`` of ``T1`` and ``T2``; 'exponential'
///     is the paper's eq. (2) (trnsS).
///
/// Raises
/// ------
/// famcc.ConfigError
///     ``eps_s``, ``eps_z`` or ``k_pp`` not finite and ``> 0``, or an
///     unknown ``transition``.
///
/// Examples
/// --------
/// >>> import famcc
/// >>> h = famcc.skewed(famcc.FiniteTime(1.0, 0.5), famcc.Nonsingular(0.1, 0.1, 0.1))
/// >>> h(1.0), h(-1.0)
/// (-1.1, 1.1)
/// >>> round(h.k_p, 6)
/// 0.416228
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
    ($name:ident, ($($field:ident),*), $sig:tt) => {
        #[pymethods]
        impl $name {
            #[new]
            // The default is famcc-core's; the Python signature spells it out
            // (tests/test_docs.py checks it against the default in effect).
            #[pyo3(signature = ($($field,)* transition = Text(TRANSITION.default_name().into())),
                text_signature = $sig)]
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

skew_methods!(Smooth, (eps_s, eps_z), "(eps_s, eps_z, transition='exponential')");
skew_methods!(
    Nonsingular,
    (eps_s, eps_z, k_pp),
    "(eps_s, eps_z, k_pp, transition='exponential')"
);

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
        const RULE: &str = "must be None, Smooth, Nonsingular, or a list of them";
        let message = format!("skew {RULE}, got {}", obj.repr()?);
        Err(ConfigFault::new("skew", RULE).message(message).into())
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
