//! `famcc._core.ControllerSpec`: a parsed controller configuration (the
//! binding's [`Spec`]) that builds controllers without keyword arguments or
//! text: what `famcc.design` returns besides its numbers, and what
//! `Controller.replace` copies (the class is declared in spec.rs). Also the construction of a
//! [`PyController`] from a spec, with the constructor's warnings.

use crate::array::map_float_or_array;
use crate::controller::PyController;
use crate::dispatch::Core;
use crate::errors::config_err;
use crate::health::design_warning;
use crate::module::module_function;
use crate::names::{DType, DTYPE};
use crate::replace::spec_from_kwargs;
use crate::spec::{ControllerSpec, RhoE, Spec};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

impl PyController {
    /// Builds the controller of `spec`, whose `rho_e` then shows the margin
    /// in effect.
    pub fn from_spec(mut spec: Spec) -> PyResult<Self> {
        let core = Core::build(&spec).map_err(config_err)?;
        spec.rho_e = RhoE::Given(core.rho_e());
        Ok(Self {
            core,
            spec,
            health_warned: false,
        })
    }

    /// [`PyController::from_spec`], then the constructor's warnings: the
    /// legal but risky choices (famcc-core's `Config::lint`), once each.
    pub fn from_spec_warned(py: Python<'_>, spec: Spec) -> PyResult<Self> {
        let c = Self::from_spec(spec)?;
        for finding in c.core.lint() {
            design_warning(py, &finding)?;
        }
        Ok(c)
    }

    pub fn set_state_vec(&mut self, v: &[f64]) -> PyResult<()> {
        self.core.set_state(v)
    }
}

#[pymethods]
impl ControllerSpec {
    /// System order n.
    #[getter]
    fn order(&self) -> usize {
        self.spec.order
    }

    /// Sample period, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.spec.dt
    }

    /// "float64" or "float32".
    #[getter]
    fn dtype(&self) -> &'static str {
        DTYPE.name(self.spec.dtype)
    }

    /// A fresh controller of this configuration.
    ///
    /// Returns
    /// -------
    /// Controller
    ///     Equal to ``Controller(**spec.config())``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A value famcc-core rejects (the message names it).
    ///
    /// Warns
    /// -----
    /// famcc.DesignWarning
    ///     For a legal but risky configuration, as the constructor.
    fn build(&self, py: Python<'_>) -> PyResult<PyController> {
        PyController::from_spec_warned(py, self.spec.clone())
    }

    /// This configuration with the named fields changed.
    ///
    /// Parameters
    /// ----------
    /// **overrides
    ///     Keyword arguments of :class:`Controller` (the types and names of
    ///     :meth:`Controller.replace`; not ``order``, ``constraint`` or
    ///     ``integral``). Checked when the spec is built.
    ///
    /// Returns
    /// -------
    /// ControllerSpec
    ///     The changed configuration.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A value of the wrong shape (a list of the wrong length, a name
    ///     that is not a choice).
    /// TypeError
    ///     An unknown keyword, one of ``order``, ``constraint``,
    ///     ``integral``, or a value of the wrong type.
    #[pyo3(signature = (**overrides))]
    fn replace(&self, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        Ok(Self {
            spec: self.spec.replace(overrides)?,
        })
    }

    /// The spec of a configuration given as keyword arguments.
    ///
    /// Parameters
    /// ----------
    /// config : dict
    ///     Keyword arguments of :class:`Controller` with ``order`` and ``dt``,
    ///     as :meth:`Controller.config` gives them.
    ///
    /// Returns
    /// -------
    /// ControllerSpec
    ///     ``ControllerSpec.from_config(c.config()).build()`` equals ``c``.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError, TypeError
    ///     As the :class:`Controller` constructor.
    #[staticmethod]
    fn from_config(config: &Bound<'_, PyDict>) -> PyResult<Self> {
        Ok(Self {
            spec: spec_from_kwargs(config)?,
        })
    }

    /// The output accuracy ``eps_z`` the configuration presets for ``|z1|``.
    ///
    /// The constraint's half-width at order 1 (``s = z1``) and for LaMC at
    /// order 2 (``eps_x = eps_z``, Corollary 1); otherwise a skewed first
    /// stage's ``eps_z`` (Corollaries 2 and 3); with integral action none.
    ///
    /// Returns
    /// -------
    /// float or None
    ///     None when the configuration presets no accuracy of the output.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A configuration famcc-core rejects.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> famcc.scenarios.paper("finite-time").controller().spec.output_accuracy()
    /// 0.1
    fn output_accuracy(&self) -> PyResult<Option<f64>> {
        Ok(self.exact()?.output_accuracy())
    }

    /// The reaching time ``T'`` of the paper's corollaries, s.
    ///
    /// Every stage ``FixedTime``: ``T_fr'`` (Corollary 3); one
    /// ``VariableExponent`` stage: ``T_fxe'`` (Corollary 2); one
    /// ``FiniteTime`` stage: ``T_fn'`` (Corollary 1), which depends on
    /// ``|z1(0)|``. The bound on reaching ``|z1| < eps_z`` is ``T_s + T'``.
    ///
    /// Parameters
    /// ----------
    /// z1_0 : float or array_like
    ///     The initial error ``z1(0)`` (one per case).
    ///
    /// Returns
    /// -------
    /// float, numpy.ndarray or None
    ///     ``T'`` in the shape of ``z1_0``; None when the laws have no
    ///     corollary bound.
    ///
    /// Examples
    /// --------
    /// >>> import famcc
    /// >>> famcc.scenarios.paper("finite-time").controller().spec.corollary_time(-1.0)
    /// 2.0
    fn corollary_time<'py>(
        &self,
        py: Python<'py>,
        z1_0: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let core = self.exact()?;
        if core.corollary_time(0.0).is_none() {
            return Ok(None);
        }
        map_float_or_array(py, z1_0, |z| core.corollary_time(z).unwrap_or(f64::NAN)).map(Some)
    }

    /// The configuration as keyword arguments of :class:`Controller`.
    ///
    /// Returns
    /// -------
    /// dict
    ///     ``Controller(**spec.config())`` builds the controller of
    ///     :meth:`build`; ``rho_e`` is ``'auto'`` when the spec leaves it to
    ///     famcc-core.
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.spec.kwargs(py)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        self.spec.repr(py, "ControllerSpec")
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let f = module_function(py, "_controller_spec_from_kwargs")?;
        Ok((f, PyTuple::new(py, [self.spec.kwargs(py)?])?))
    }
}

impl ControllerSpec {
    /// The configuration's controller in f64: the guarantees in the
    /// configuration's own numbers, whatever its float type.
    fn exact(&self) -> PyResult<Core> {
        let mut spec = self.spec.clone();
        spec.dtype = DType::F64;
        Core::build(&spec).map_err(config_err)
    }
}

/// Unpickling: the spec of keyword arguments (as `config()` gives them).
#[pyfunction]
pub fn _controller_spec_from_kwargs(kwargs: &Bound<'_, PyDict>) -> PyResult<ControllerSpec> {
    Ok(ControllerSpec {
        spec: spec_from_kwargs(kwargs)?,
    })
}
