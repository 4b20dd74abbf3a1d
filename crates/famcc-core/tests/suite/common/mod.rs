//! Shared closed-loop test support: a sampled loop over the paper's plants
//! and designs, which come from famcc-paper (docs/design.md §6.2-6.3).
#![allow(dead_code, unused_imports, clippy::indexing_slicing, clippy::unwrap_used)]

use famcc_core::{Config, Controller, Real};
pub use famcc_paper::designs::Variant;
use famcc_paper::designs::{self, UNSATURATED_LIMITS};
use famcc_paper::plants::{self, Clock, Instant};
pub use famcc_paper::plants::{output_derivatives, Plant, SecondOrder as Second, ThirdOrder as Third};

/// A plant `x' = f(t, x, u)` with `y = x1`: the paper's plants (any
/// [`Plant`]) and the tests' own (random or scaled) ones.
pub trait TimePlant<const N: usize> {
    fn initial_state(&self) -> [f64; N];
    fn rate(&self, t: f64, x: &[f64; N], u: f64) -> [f64; N];
}

impl<const N: usize, P: Plant<f64, N>> TimePlant<N> for P {
    fn initial_state(&self) -> [f64; N] {
        self.x0()
    }
    fn rate(&self, t: f64, x: &[f64; N], u: f64) -> [f64; N] {
        self.rhs(&Clock::at(t), x, u)
    }
}

/// Classical RK4 over [t, t + h] with the input held.
pub fn rk4<const N: usize, P: TimePlant<N>>(p: &P, t: f64, x: &[f64; N], u: f64, h: f64) -> [f64; N] {
    let at = |i: Instant| match i {
        Instant::Start => t,
        Instant::Middle => t + h / 2.0,
        Instant::End => t + h,
    };
    plants::rk4_with(|i, x| p.rate(at(i), x, u), x, h)
}

/// One closed-loop run's record.
#[derive(Default, Debug, Clone)]
pub struct Run {
    pub t: Vec<f64>,
    pub z1: Vec<f64>,
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    pub xi: Vec<f64>,
    /// The nominal xi of eq. (28) (before the flexible expansion and the clamp).
    pub xi_nominal: Vec<f64>,
    pub expanded: Vec<bool>,
    pub bounds: Vec<(f64, f64)>,
    pub nominal: Vec<(f64, f64)>,
    pub clamp_count: u64,
    pub nonfinite: bool,
}

impl Run {
    /// First time after which |z1| < eps to the end (None if the end is outside).
    pub fn settling_time(&self, eps: f64) -> Option<f64> {
        match self.z1.iter().rposition(|z| z.abs() >= eps) {
            None => Some(0.0),
            Some(i) if i + 1 < self.t.len() => Some(self.t[i + 1]),
            Some(_) => None,
        }
    }
    /// End of the last saturation episode (None if never saturated).
    pub fn last_saturation_end(&self) -> Option<f64> {
        let i = self.v.iter().zip(&self.u).rposition(|(v, u)| v != u)?;
        Some(self.t.get(i + 1).copied().unwrap_or(self.t[i]))
    }
    pub fn max_abs_xi(&self) -> f64 {
        self.xi.iter().fold(0.0, |m, x| m.max(x.abs()))
    }
    pub fn max_abs_xi_nominal(&self) -> f64 {
        self.xi_nominal.iter().fold(0.0, |m, x| m.max(x.abs()))
    }
    /// First time with |z1| < eps (None if never).
    pub fn first_entry(&self, eps: f64) -> Option<f64> {
        self.z1.iter().position(|z| z.abs() < eps).map(|i| self.t[i])
    }
    /// max |z1| over the last `window` seconds of the run.
    pub fn final_abs_z1(&self, window: f64) -> f64 {
        let end = self.t.last().copied().unwrap_or(0.0);
        self.t
            .iter()
            .zip(&self.z1)
            .filter(|(t, _)| **t >= end - window - 1e-12)
            .fold(0.0, |m, (_, z)| m.max(z.abs()))
    }
    /// Fraction of samples at which the input was clipped.
    pub fn saturated_fraction(&self) -> f64 {
        let n = self.v.iter().zip(&self.u).filter(|(v, u)| v != u).count();
        n as f64 / self.v.len().max(1) as f64
    }
    pub fn u_range(&self) -> (f64, f64) {
        self.u
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), u| {
                (a.min(*u), b.max(*u))
            })
    }
}

/// Runs a sampled loop: controller at `dt`, plant by RK4 with `sub` substeps.
pub fn run<T: Real, const N: usize, P: TimePlant<N>>(
    plant: &P,
    ctrl: &mut Controller<T, N>,
    t_end: f64,
    limits: (f64, f64),
    sub: usize,
) -> Run {
    let dt = ctrl.config().dt().to_f64_lossless();
    let steps = (t_end / dt).round() as usize;
    let mut x = plant.initial_state();
    let mut r = Run::default();
    for k in 0..=steps {
        let t = k as f64 * dt;
        let e = x[0] - t.sin();
        let v = match ctrl.step(T::from_f64(e)) {
            Ok(v) => v.to_f64_lossless(),
            Err(_) => {
                r.nonfinite = true;
                break;
            }
        };
        let u = v.clamp(limits.0, limits.1);
        let d = ctrl.diagnostics();
        r.t.push(t);
        r.z1.push(e);
        r.v.push(v);
        r.u.push(u);
        r.xi.push(d.xi.to_f64_lossless());
        r.xi_nominal.push(d.xi_nominal.to_f64_lossless());
        r.expanded.push(d.expanded);
        r.bounds
            .push((d.bounds.0.to_f64_lossless(), d.bounds.1.to_f64_lossless()));
        r.nominal.push((
            d.nominal_bounds.0.to_f64_lossless(),
            d.nominal_bounds.1.to_f64_lossless(),
        ));
        r.clamp_count = d.clamp_count;
        let h = dt / sub as f64;
        for j in 0..sub {
            x = rk4(plant, t + j as f64 * h, &x, u, h);
        }
        if x.iter().any(|v| !v.is_finite()) || !v.is_finite() {
            r.nonfinite = true;
            break;
        }
    }
    r
}

pub const UNSAT: (f64, f64) = UNSATURATED_LIMITS;

/// Example 1: LaMC, FiniteTime(1, 0.5), eps_x = 0.1, k_u = 5.
pub fn example1<T: Real>(variant: Variant, dt: f64) -> Controller<T, 2> {
    Controller::new(designs::example1(variant, T::from_f64(dt)).unwrap())
}

/// Example 2: LoMC, VariableExponent(1.5, 0.5, 2, 3) with SSMD, eps_y = 0.15, k_u = 2.
pub fn example2<T: Real>(variant: Variant, dt: f64) -> Controller<T, 2> {
    Controller::new(designs::example2(variant, T::from_f64(dt)).unwrap())
}

/// Example 3: LoMC, two fixed-time NSMD stages, k_u = 30.
pub fn example3<T: Real>(variant: Variant, dt: f64) -> Controller<T, 3> {
    Controller::new(example3_cfg(variant, dt).unwrap())
}

pub fn example3_cfg<T: Real>(variant: Variant, dt: f64) -> Option<Config<T, 3>> {
    designs::example3(variant, T::from_f64(dt)).ok()
}

/// The paper's example `example` (1, 2, 3) in `variant` over 10 s at 1 kHz
/// with the input limits `limits`, the plant by RK4 with 10 substeps.
pub fn paper_loop(example: u8, variant: Variant, limits: (f64, f64)) -> Run {
    const DT: f64 = 1e-3;
    const T_END: f64 = 10.0;
    match example {
        1 => run(
            &Second::new(variant),
            &mut example1::<f64>(variant, DT),
            T_END,
            limits,
            10,
        ),
        2 => run(
            &Second::new(variant),
            &mut example2::<f64>(variant, DT),
            T_END,
            limits,
            10,
        ),
        _ => run(
            &Third::new(variant),
            &mut example3::<f64>(variant, DT),
            T_END,
            limits,
            10,
        ),
    }
}

/// The law of `plain` without its differentiator, on the observer (`mu = 0.02`,
/// `b0 = 1`, `delta = 10`): tests/suite/fast_path.rs, benches/observed.rs,
/// examples/callgrind_step.rs.
#[cfg(feature = "observer")]
pub fn observed<T: Real, const N: usize>(
    plain: &Controller<T, N>,
    hold: famcc_core::Discretization,
) -> Controller<T, N> {
    let obs = famcc_core::ExtendedHighGain::binomial(T::from_f64(0.02), T::one()).with_discretization(hold);
    let cfg = plain
        .config()
        .to_builder()
        .differentiator(None)
        .observer(Some(obs))
        .cancellation_limit(Some(T::from_f64(10.0)))
        .build()
        .unwrap();
    Controller::new(cfg)
}
