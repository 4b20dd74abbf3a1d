//! Shared closed-loop test support: the paper's plants (docs/design.md §6.3),
//! RK4 integration between samples, and the paper's controller designs.
#![allow(dead_code, clippy::indexing_slicing, clippy::unwrap_used)]

use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain, Latch, Real, Skew};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    Paper,
    Code,
}

/// A strict-feedback plant x' = f(t, x, u) with y = x1.
pub trait Plant<const N: usize> {
    fn x0(&self) -> [f64; N];
    fn rhs(&self, t: f64, x: &[f64; N], u: f64) -> [f64; N];
}

/// Example 1/2 plant (eq. System_sim); variant "code" has disturbance amplitude 3.
pub struct Second(pub Variant);

impl Plant<2> for Second {
    fn x0(&self) -> [f64; 2] {
        [-1.0, 0.5]
    }
    fn rhs(&self, t: f64, x: &[f64; 2], u: f64) -> [f64; 2] {
        let amp = if self.0 == Variant::Code { 3.0 } else { 1.0 };
        let (x1, x2) = (x[0], x[1]);
        [
            (1.0 + 0.1 * x1.cos() + 0.1 * t.sin()) * x2 - x1 + t.sin(),
            (2.0 + 0.2 * (x1 * x2).sin() + 0.1 * t.cos()) * u - (x1 * x1 - 1.0) * x2
                + amp * (t.sin() + (2.0 * t).cos()),
        ]
    }
}

/// Example 3 plant (eq. System_sim3) with the factor x2 restored in x1'.
pub struct Third(pub Variant);

impl Plant<3> for Third {
    fn x0(&self) -> [f64; 3] {
        match self.0 {
            Variant::Paper => [1.0, -0.2, 0.4],
            Variant::Code => [1.0, 0.5, 4.0],
        }
    }
    fn rhs(&self, t: f64, x: &[f64; 3], u: f64) -> [f64; 3] {
        let (x1, x2, x3) = (x[0], x[1], x[2]);
        [
            (1.0 + 0.1 * x1.sin() + 0.1 * t.cos()) * x2 - x1 + t.cos(),
            (1.0 + 0.1 * (x1 * x2).cos() + 0.1 * t.sin()) * x3 - (x1 * x1 - 1.0) * x2 + t.sin(),
            (2.0 + 0.2 * (x1 * x2 * x3).sin() + 0.1 * t.cos()) * u - (x1 * x1 + x2) * x3
                + 10.0 * t.sin()
                + 10.0 * (2.0 * t).cos(),
        ]
    }
}

fn axpy<const N: usize>(x: &[f64; N], a: f64, k: &[f64; N]) -> [f64; N] {
    let mut out = *x;
    for i in 0..N {
        out[i] += a * k[i];
    }
    out
}

/// Classical RK4 over [t, t + h] with the input held.
pub fn rk4<const N: usize, P: Plant<N>>(p: &P, t: f64, x: &[f64; N], u: f64, h: f64) -> [f64; N] {
    let k1 = p.rhs(t, x, u);
    let k2 = p.rhs(t + h / 2.0, &axpy(x, h / 2.0, &k1), u);
    let k3 = p.rhs(t + h / 2.0, &axpy(x, h / 2.0, &k2), u);
    let k4 = p.rhs(t + h, &axpy(x, h, &k3), u);
    let mut out = *x;
    for i in 0..N {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}

/// One closed-loop run's record.
#[derive(Default, Debug, Clone)]
pub struct Run {
    pub t: Vec<f64>,
    pub z1: Vec<f64>,
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    pub xi: Vec<f64>,
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
    pub fn u_range(&self) -> (f64, f64) {
        self.u
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), u| {
                (a.min(*u), b.max(*u))
            })
    }
}

/// Runs a sampled loop: controller at `dt`, plant by RK4 with `sub` substeps.
pub fn run<T: Real, const N: usize, P: Plant<N>>(
    plant: &P,
    ctrl: &mut Controller<T, N>,
    t_end: f64,
    limits: (f64, f64),
    sub: usize,
) -> Run {
    let dt = ctrl.config().dt.to_f64_lossless();
    let steps = (t_end / dt).round() as usize;
    let mut x = plant.x0();
    let mut r = Run::default();
    for k in 0..=steps {
        let t = k as f64 * dt;
        let e = x[0] - t.sin();
        let v = match ctrl.step(T::c(e)) {
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

pub const UNSAT: (f64, f64) = (-100.0, 100.0);

/// Example 1: LaMC, FiniteTime(1, 0.5), eps_x = 0.1, k_u = 5.
pub fn example1<T: Real>(variant: Variant, dt: f64) -> Controller<T, 2> {
    let mut cfg = Config::<T, 2>::new(
        T::c(dt),
        &[(
            Feedback::FiniteTime {
                k: T::c(1.0),
                p: T::c(0.5),
            },
            None,
        )],
        Constraint::Lateral { eps: T::c(0.1) },
        T::c(1.0),
        T::c(5.0),
    )
    .unwrap();
    finish(&mut cfg, variant, [T::c(4.0), T::c(4.0)]);
    Controller::new(cfg).unwrap()
}

/// Example 2: LoMC, VariableExponent(1.5, 0.5, 2, 3) with SSMD, eps_y = 0.15, k_u = 2.
pub fn example2<T: Real>(variant: Variant, dt: f64) -> Controller<T, 2> {
    let eps_s = if variant == Variant::Paper { 0.15 } else { 0.225 };
    let mut cfg = Config::<T, 2>::new(
        T::c(dt),
        &[(
            Feedback::VariableExponent {
                k: T::c(1.5),
                r_b: T::c(0.5),
                r_1: T::c(2.0),
                r_t: T::c(3.0),
            },
            Some(Skew::smooth(T::c(eps_s), T::c(0.1))),
        )],
        Constraint::Longitudinal { eps: T::c(0.15) },
        T::c(1.0),
        T::c(2.0),
    )
    .unwrap();
    finish(&mut cfg, variant, [T::c(4.0), T::c(4.0)]);
    Controller::new(cfg).unwrap()
}

/// Example 3: LoMC, two fixed-time NSMD stages, k_u = 30.
pub fn example3<T: Real>(variant: Variant, dt: f64) -> Controller<T, 3> {
    example3_cfg(variant, dt)
        .map(|c| Controller::new(c).unwrap())
        .unwrap()
}

pub fn example3_cfg<T: Real>(variant: Variant, dt: f64) -> Option<Config<T, 3>> {
    let (eps_s1, eps_y) = if variant == Variant::Paper {
        (0.2, 5.0)
    } else {
        (0.1, 3.0)
    };
    let mut cfg = Config::<T, 3>::new(
        T::c(dt),
        &[
            (
                Feedback::FixedTime {
                    alpha: T::c(1.0),
                    p: T::c(0.5),
                    beta: T::c(0.5),
                    q: T::c(2.0),
                },
                Some(Skew::nonsingular(T::c(eps_s1), T::c(0.1), T::c(0.1))),
            ),
            (
                Feedback::FixedTime {
                    alpha: T::c(2.0),
                    p: T::c(0.5),
                    beta: T::c(1.0),
                    q: T::c(2.0),
                },
                Some(Skew::nonsingular(T::c(eps_y), T::c(0.2), T::c(1.0))),
            ),
        ],
        Constraint::Longitudinal { eps: T::c(eps_y) },
        T::c(1.0),
        T::c(30.0),
    )
    .ok()?;
    finish(&mut cfg, variant, [T::c(4.0), T::c(6.0), T::c(4.0)]);
    Some(cfg)
}

fn finish<T: Real, const N: usize>(cfg: &mut Config<T, N>, variant: Variant, a: [T; N]) {
    cfg.differentiator = Some(HighGain::new(T::c(0.01), a, Discretization::Exact));
    if variant == Variant::Code {
        cfg.latch = Latch::Authors;
    }
}
