//! The controller side of a run: the controllers of every channel and lane
//! ([`Controllers`]), what a run records of them ([`Diag`]), and famcc-core's
//! controllers as lanes ([`Cores`]).

use famcc_core::{Controller, Real, StepError};

/// The controllers of a run: one per channel and lane.
pub trait Controllers {
    /// What a failed step reports (and stops the run with).
    type Error;
    /// Steps the controller of every channel `c` of every lane `l` with
    /// `live[l]`: error `e[c * lanes + l]`, the input applied at the previous
    /// sample (`None` at the first sample), output into `v`. Other lanes are
    /// not touched.
    fn step(
        &mut self,
        e: &[f64],
        applied: Option<&[f64]>,
        live: &[bool],
        v: &mut [f64],
    ) -> Result<(), Self::Error>;
    /// What the controller of channel `c`, lane `l` did at its last step
    /// (`None` when it reports nothing).
    fn diagnostics(&self, c: usize, l: usize) -> Option<Diag>;
    /// Steps that failed and were held so far (a bank's overflows).
    fn held(&self) -> u64 {
        0
    }
}

/// The diagnostics a run records per sample: famcc-core's
/// [`famcc_core::Diagnostics`] in f64, the estimate without an integral slot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diag {
    /// `xi~`.
    pub xi: f64,
    /// The nominal `xi`.
    pub xi_nominal: f64,
    /// Flexible / nominal bound.
    pub expansion: f64,
    /// `s_n`.
    pub s: f64,
    /// `s_{n-1}`.
    pub s_prev: f64,
    /// `d/dt s_{n-1}`.
    pub ds_prev: f64,
    /// Flexible upper bounds (x, y).
    pub bounds: [f64; 2],
    /// Nominal upper bounds (x, y).
    pub nominal_bounds: [f64; 2],
    /// The bounds were expanded.
    pub expanded: bool,
    /// Clamps so far.
    pub clamp_count: u64,
    /// Expansions with headroom so far (`None`: not counted).
    pub unsaturated_expansions: Option<u64>,
    /// `z_hat_1 .. z_hat_n` (`order` entries used).
    pub z_hat: [f64; famcc_core::config::MAX_ORDER],
    /// `n`.
    pub order: usize,
}

impl Diag {
    /// NaN everywhere, nothing counted.
    pub fn unknown(order: usize) -> Self {
        Self {
            xi: f64::NAN,
            xi_nominal: f64::NAN,
            expansion: f64::NAN,
            s: f64::NAN,
            s_prev: f64::NAN,
            ds_prev: f64::NAN,
            bounds: [f64::NAN; 2],
            nominal_bounds: [f64::NAN; 2],
            expanded: false,
            clamp_count: 0,
            unsaturated_expansions: None,
            z_hat: [f64::NAN; famcc_core::config::MAX_ORDER],
            order,
        }
    }

    /// A famcc-core controller's diagnostics of its last step.
    pub fn of<T: Real, const N: usize>(c: &Controller<T, N>) -> Self {
        let d = c.diagnostics();
        let f = |x: T| x.to_f64_lossless();
        let skip = usize::from(d.integral.is_some());
        let mut z_hat = [f64::NAN; famcc_core::config::MAX_ORDER];
        let mut order = 0;
        for (o, z) in z_hat.iter_mut().zip(d.z_hat.iter().skip(skip)) {
            *o = f(*z);
            order += 1;
        }
        Self {
            xi: f(d.xi),
            xi_nominal: f(d.xi_nominal),
            expansion: f(d.expansion),
            s: f(d.s),
            s_prev: f(d.s_prev),
            ds_prev: f(d.ds_prev),
            bounds: [f(d.bounds.0), f(d.bounds.1)],
            nominal_bounds: [f(d.nominal_bounds.0), f(d.nominal_bounds.1)],
            expanded: d.expanded,
            clamp_count: d.clamp_count,
            unsaturated_expansions: Some(d.unsaturated_expansions),
            z_hat,
            order,
        }
    }
}

/// What a failed core step does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnError {
    /// The run stops with the error (a single controller, as `Controller.step` raises).
    Raise,
    /// The lane repeats its previous output and the failure is counted (a bank).
    Hold,
}

/// One famcc-core step with the binding's float handling: a finite f64 out
/// of the core's range is an overflow.
#[inline]
pub fn step_core<T: Real, const N: usize>(
    c: &mut Controller<T, N>,
    e: f64,
    applied: Option<f64>,
) -> Result<f64, StepError> {
    let (ec, ac) = (T::from_f64(e), applied.map(T::from_f64));
    if (e.is_finite() && !ec.is_finite())
        || applied
            .zip(ac)
            .is_some_and(|(a, ac)| a.is_finite() && !ac.is_finite())
    {
        return Err(StepError::Overflow);
    }
    c.step_applied(ec, ac).map(|v| v.to_f64_lossless())
}

/// famcc-core controllers as the lanes of one channel.
#[derive(Debug)]
pub struct Cores<'a, T: Real, const N: usize> {
    cores: &'a mut [Controller<T, N>],
    on_error: OnError,
    held: u64,
}

impl<'a, T: Real, const N: usize> Cores<'a, T, N> {
    /// Lanes whose first failed step stops the run.
    pub fn raising(cores: &'a mut [Controller<T, N>]) -> Self {
        Self {
            cores,
            on_error: OnError::Raise,
            held: 0,
        }
    }

    /// Lanes that hold their output on a failed step (counted in [`Controllers::held`]).
    pub fn holding(cores: &'a mut [Controller<T, N>]) -> Self {
        Self {
            cores,
            on_error: OnError::Hold,
            held: 0,
        }
    }
}

impl<T: Real, const N: usize> Controllers for Cores<'_, T, N> {
    type Error = StepError;

    fn step(
        &mut self,
        e: &[f64],
        applied: Option<&[f64]>,
        live: &[bool],
        v: &mut [f64],
    ) -> Result<(), StepError> {
        for (l, c) in self.cores.iter_mut().enumerate() {
            if !live.get(l).copied().unwrap_or(false) {
                continue;
            }
            let el = e.get(l).copied().unwrap_or(f64::NAN);
            let al = applied.and_then(|a| a.get(l).copied());
            let out = match step_core(c, el, al) {
                Ok(x) => x,
                Err(err) if self.on_error == OnError::Raise => return Err(err),
                Err(_) => {
                    self.held += 1;
                    c.diagnostics().v.to_f64_lossless()
                }
            };
            if let Some(o) = v.get_mut(l) {
                *o = out;
            }
        }
        Ok(())
    }

    fn diagnostics(&self, c: usize, l: usize) -> Option<Diag> {
        if c != 0 {
            return None;
        }
        self.cores.get(l).map(Diag::of)
    }

    fn held(&self) -> u64 {
        self.held
    }
}
