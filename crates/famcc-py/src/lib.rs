//! The private `famcc._core` extension module: a thin pyo3 layer over
//! famcc-core (and the paper's designs and plants of famcc-paper). It holds
//! no control logic, no rule and no default of its own; the public API lives
//! in the Python package `famcc`.
//!
//! | module | concern |
//! |---|---|
//! | `errors`, `bind` | the exception and warning classes, and their methods |
//! | `names` | Python names of the core's enumerations |
//! | `args` | the constructor's arguments, parsed into a typed `spec` |
//! | `spec` | a controller's configuration, fed to the core's builder; the `ControllerSpec` class |
//! | `module` | `famcc._core` kept for pickling (`module_function`) |
//! | `controller_spec`, `replace` | `ControllerSpec`; specs changed or read without text |
//! | `kwargs` | a spec as keyword arguments (`config()`, `repr`, pickling) |
//! | `orders`, `dispatch` | run-time order and float type to the core's generics |
//! | `state` | the state codec (the core's `Snapshot` layout) |
//! | `diagnostics` | `Diagnostics` |
//! | `controller` | `Controller`'s Python methods |
//! | `bank` | `ControllerBank` |
//! | `laws`, `differentiator` | laws, skews, `HighGain` |
//! | `functions`, `array` | building blocks as functions |
//! | `paper` | the paper's designs and plants |
//! | `sim`, `sim_plants`, `sim_ctrls` | famcc-sim's loop (`Lockstep`), its plants and controllers |

use pyo3::prelude::*;
use pyo3::types::PyTuple;

mod args;
mod array;
mod bank;
mod bind;
mod call_floor;
mod controller;
mod controller_spec;
mod design;
mod diagnostics;
mod differentiator;
mod dispatch;
mod errors;
mod exception_methods;
mod functions;
mod health;
mod kwargs;
mod laws;
mod module;
mod names;
mod number;
mod observer;
mod orders;
mod paper;
mod replace;
mod sim;
mod sim_ctrls;
mod sim_plants;
mod skews;
mod spec;
mod state;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_ORDER", famcc_core::config::MAX_ORDER)?;
    m.add("STATE_FIELDS", PyTuple::new(py, famcc_core::SNAPSHOT_FIELDS)?)?;
    // ConfigError, StepError, the warnings and ArgumentTypeError.
    exception_methods::install(m)?;
    m.add_class::<laws::Linear>()?;
    m.add_class::<laws::FiniteTime>()?;
    m.add_class::<laws::FixedTime>()?;
    m.add_class::<laws::VariableExponent>()?;
    m.add_class::<laws::MoulayDiscontinuous>()?;
    m.add_class::<skews::Smooth>()?;
    m.add_class::<skews::Nonsingular>()?;
    m.add_class::<differentiator::HighGain>()?;
    m.add_class::<observer::Observer>()?;
    m.add_class::<controller::PyController>()?;
    m.add_class::<call_floor::CallFloor>()?;
    m.add_class::<diagnostics::Diagnostics>()?;
    m.add_class::<bank::ControllerBank>()?;
    m.add_class::<functions::Skewed>()?;
    m.add_class::<paper::PaperPlant>()?;
    m.add_class::<sim::Lockstep>()?;
    m.add_class::<sim_plants::PaperLanes>()?;
    m.add_function(wrap_pyfunction!(kwargs::_controller_from_state, m)?)?;
    m.add_class::<spec::ControllerSpec>()?;
    m.add_function(wrap_pyfunction!(
        controller_spec::_controller_spec_from_kwargs,
        m
    )?)?;
    module::remember_module(m);
    m.add_function(wrap_pyfunction!(functions::transition_t, m)?)?;
    m.add_function(wrap_pyfunction!(functions::transition_s, m)?)?;
    m.add_function(wrap_pyfunction!(functions::transition_u, m)?)?;
    m.add_function(wrap_pyfunction!(functions::rho, m)?)?;
    m.add_function(wrap_pyfunction!(functions::skewed, m)?)?;
    m.add_function(wrap_pyfunction!(functions::manifold, m)?)?;
    m.add_function(wrap_pyfunction!(functions::finite_time, m)?)?;
    m.add_function(wrap_pyfunction!(functions::variable_exponent, m)?)?;
    m.add_function(wrap_pyfunction!(functions::fixed_time, m)?)?;
    m.add_function(wrap_pyfunction!(paper::paper_design, m)?)?;
    m.add_function(wrap_pyfunction!(paper::paper_corollary_bound, m)?)?;
    m.add_function(wrap_pyfunction!(paper::paper_input_limits, m)?)?;
    m.add_function(wrap_pyfunction!(paper::paper_nominal_gain, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_rules, m)?)?;
    Ok(())
}
