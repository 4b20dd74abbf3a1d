//! The private `famcc._core` extension module: a thin pyo3 layer over
//! famcc-core (parsing, conversion, errors). It holds no control logic; the
//! public API lives in the Python package `famcc`.

use pyo3::prelude::*;

mod bank;
mod controller;
mod design;
mod errors;
mod functions;
mod laws;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_ORDER", controller::MAX_ORDER)?;
    for ty in [
        py.get_type::<errors::ConfigError>(),
        py.get_type::<errors::StepError>(),
    ] {
        // Importable (and so picklable) as famcc._core.<name>.
        ty.setattr("__module__", "famcc._core")?;
    }
    m.add("ConfigError", py.get_type::<errors::ConfigError>())?;
    m.add("StepError", py.get_type::<errors::StepError>())?;
    m.add_class::<laws::Linear>()?;
    m.add_class::<laws::FiniteTime>()?;
    m.add_class::<laws::FixedTime>()?;
    m.add_class::<laws::VariableExponent>()?;
    m.add_class::<laws::MoulayDiscontinuous>()?;
    m.add_class::<laws::Smooth>()?;
    m.add_class::<laws::Nonsingular>()?;
    m.add_class::<laws::HighGain>()?;
    m.add_class::<controller::PyController>()?;
    m.add_class::<controller::Diagnostics>()?;
    m.add_class::<bank::ControllerBank>()?;
    m.add_class::<functions::Skewed>()?;
    m.add_function(wrap_pyfunction!(controller::_controller_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(functions::transition_t, m)?)?;
    m.add_function(wrap_pyfunction!(functions::transition_s, m)?)?;
    m.add_function(wrap_pyfunction!(functions::transition_u, m)?)?;
    m.add_function(wrap_pyfunction!(functions::rho, m)?)?;
    m.add_function(wrap_pyfunction!(functions::skewed, m)?)?;
    m.add_function(wrap_pyfunction!(functions::manifold_values, m)?)?;
    m.add_function(wrap_pyfunction!(functions::finite_time, m)?)?;
    m.add_function(wrap_pyfunction!(functions::variable_exponent, m)?)?;
    m.add_function(wrap_pyfunction!(functions::fixed_time, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_rules, m)?)?;
    Ok(())
}
