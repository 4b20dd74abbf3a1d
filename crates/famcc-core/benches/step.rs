//! Cost of one `Controller::step` (issue "Performance: benchmarks").
//!
//! Run with `cargo bench -p famcc-core --bench step` (about 2 minutes on 2 cores).
//!
//! What is measured:
//! - the paper's three designs (tests/suite/common: `example1/2/3`, variant "code"),
//!   f64 and f32, in two phases: `transient` (the first 1000 samples, t < T_s = 1 s,
//!   envelope still shrinking, latch at the first sample) and `settled`
//!   (samples 1000..10000, t >= T_s);
//! - the same designs with the Euler differentiator (`Phi` is precomputed at
//!   construction, so the step costs the same as with the exact one);
//! - a hand-inlined order-2 finite-time LaMC law with the same math as example 1
//!   (`baseline`), checked at start-up to give the controller's outputs;
//! - orders 3..=8 (FixedTime + NSMD at every stage, and all-linear laws) to show
//!   how the cost scales with the order.
//!
//! Inputs are errors recorded from closed-loop runs (plants and RK4 from
//! tests/suite/common, dt = 1 ms, 10 s). One criterion iteration replays one chunk of
//! [`CHUNK`] = 1000 recorded samples from a saved controller state, so criterion's
//! time per iteration in microseconds is the time per step in nanoseconds.
//!
//! `examples/callgrind_step.rs` includes this file as a module to count
//! instructions for exactly the same workloads.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

#[path = "../tests/suite/common/mod.rs"]
pub mod common;
#[cfg(feature = "observer")]
pub use common::observed;

use std::hint::black_box;
use std::time::Duration;

use common::{Second, Third, Variant, UNSAT};
use criterion::{Criterion, Throughput};
use famcc_core::{
    Config, Constraint, Controller, Discretization, Feedback, Gamma, HighGain, Latch, Real, Skew, Transition,
};

/// Sample period of every workload, seconds.
pub const DT: f64 = 1e-3;
/// Length of the recorded closed-loop runs, seconds.
pub const T_END: f64 = 10.0;
/// RK4 substeps per sample when recording.
pub const SUB: usize = 10;
/// Steps per benchmark iteration (1 us per iteration = 1 ns per step).
pub const CHUNK: usize = 1000;

// ---------------------------------------------------------------------------
// Something that steps.

/// One sample in, one control out.
pub trait Stepper<T>: Copy {
    /// One step; NaN on error (never happens on the recorded inputs).
    fn step_once(&mut self, e: T) -> T;
}

impl<T: Real, const N: usize> Stepper<T> for Controller<T, N> {
    #[inline(always)]
    fn step_once(&mut self, e: T) -> T {
        match self.step(e) {
            Ok(v) => v,
            Err(_) => T::nan(),
        }
    }
}

// ---------------------------------------------------------------------------
// The hand-inlined baseline: example 1 (LaMC, finite-time law, no skew,
// exponential flexible boundary, log Gamma) written out as plain code.

/// Example 1's controller as one flat function, no jets, no generic laws.
#[derive(Clone, Copy, Debug)]
pub struct Baseline<T> {
    phi: [[T; 2]; 2],
    gamma: [T; 2],
    /// Finite-time law `h(x) = -k |x|^p sign(x)`: `k` and `1/p`.
    k: T,
    inv_p: T,
    /// `1/p == 2` (the paper's p = 1/2): the inverse is a square, as src does.
    square: bool,
    eps: T,
    settle_time: T,
    k0: T,
    k_u: T,
    rho_e: T,
    dt: T,
    latch: Latch,
    // State.
    started: bool,
    n: u64,
    zhat: [T; 2],
    rho0: T,
}

#[inline(always)]
fn spow<T: Real>(x: T, p: T) -> T {
    if x > T::zero() {
        x.powf(p)
    } else if x < T::zero() {
        -(-x).powf(p)
    } else {
        T::zero()
    }
}

impl<T: Real> Baseline<T> {
    /// Takes the constants from example 1's configuration (and asserts that it
    /// is the design this baseline hand-codes).
    pub fn from_config(cfg: &Config<T, 2>) -> Self {
        let (k, p) = match (cfg.laws()[0].feedback(), cfg.laws()[0].skew()) {
            (Feedback::FiniteTime { k, p }, None) => (*k, *p),
            other => panic!("baseline needs an unskewed finite-time law, got {other:?}"),
        };
        let Constraint::Lateral { eps } = *cfg.constraint() else {
            panic!("baseline needs LaMC");
        };
        assert_eq!(cfg.gamma(), Gamma::Log);
        assert_eq!(cfg.transition(), Transition::Exponential);
        assert!(cfg.initial_derivatives().is_none() && cfg.estimate_limits().is_none());
        let d = cfg.differentiator().unwrap().discretize(cfg.dt()).unwrap();
        Self {
            phi: d.phi,
            gamma: d.gamma,
            k,
            inv_p: T::one() / p,
            square: T::one() / p == T::from_f64(2.0),
            eps,
            settle_time: cfg.settle_time(),
            k0: cfg.k0(),
            k_u: cfg.k_u(),
            rho_e: cfg.rho_e().unwrap(),
            dt: cfg.dt(),
            latch: cfg.latch(),
            started: false,
            n: 0,
            zhat: [T::zero(); 2],
            rho0: eps,
        }
    }
}

impl<T: Real> Stepper<T> for Baseline<T> {
    #[inline(always)]
    fn step_once(&mut self, e: T) -> T {
        let zero = T::zero();
        let one = T::one();
        let two = T::from_f64(2.0);
        if !e.is_finite() {
            return T::nan();
        }
        let z = if self.started { self.zhat } else { [e, zero] };
        // Differentiator: Zhat_{k+1} = Phi Zhat_k + Gamma e_k.
        let next = [
            self.gamma[0] * e + self.phi[0][0] * z[0] + self.phi[0][1] * z[1],
            self.gamma[1] * e + self.phi[1][0] * z[0] + self.phi[1][1] * z[1],
        ];
        // LaMC offset: s_fn = z1 + sign(z2) |z2 / k|^(1/p).
        let y = z[1] / self.k;
        let sigma = z[0]
            + if self.square {
                y * y.abs()
            } else {
                spow(y, self.inv_p)
            };
        if !self.started {
            self.rho0 = self.latch.rho0(sigma, self.k0, self.eps);
        }
        // Envelope x_U = (rho0 - eps) exp((w - 1)/w) + eps, w = (T_s - t)/T_s.
        let t = T::from_f64(self.n as f64) * self.dt;
        let x_u = if t >= self.settle_time {
            self.eps
        } else {
            let w = (self.settle_time - t) / self.settle_time;
            let tr = if w <= zero {
                zero
            } else {
                let a = (w - one) / w;
                if a < T::ln_min_positive() {
                    zero
                } else {
                    a.exp()
                }
            };
            (self.rho0 - self.eps) * tr + self.eps
        };
        // Flexible boundary: expansion factor with the exponential S.
        let xi_nominal = sigma / x_u;
        let d_sc = xi_nominal.abs() * x_u;
        let zs = (d_sc - (x_u - self.rho_e)) / self.rho_e;
        // S(z) = q / (1 + q), q = exp(-(1 - 2z)/(z(1 - z))), for 0 < z <= 1/2,
        // and 1 - S(1 - z) above (the form src/transition.rs uses).
        let rising = |z: T| {
            let w = (one - two * z) / (z * (one - z));
            if -w < T::ln_min_positive() {
                zero
            } else {
                let q = (-w).exp();
                q / (one + q)
            }
        };
        let s = if zs <= zero {
            zero
        } else if zs >= one {
            one
        } else if zs > T::from_f64(0.5) {
            one - rising(one - zs)
        } else {
            rising(zs)
        };
        let factor = if s == zero {
            one
        } else {
            (one - s) + s * (d_sc + self.rho_e) / x_u
        };
        let mut xi = xi_nominal / factor;
        let limit = one - T::epsilon();
        if xi.abs() > limit {
            xi = if xi > zero { limit } else { -limit };
        }
        // Gamma = 2 atanh, evaluated on |xi| (as src/gamma.rs does).
        let g = two * xi.abs().atanh();
        let v = -self.k_u * if xi < zero { -g } else { g };
        self.started = true;
        self.zhat = next;
        self.n += 1;
        v
    }
}

// ---------------------------------------------------------------------------
// Workloads: a recorded error sequence and the stepper's state at the start
// of every chunk of CHUNK samples.

/// A recorded input sequence with saved states at chunk boundaries. Chunk 0
/// is the transient phase (t < T_s = 1 s); chunks 1.. are settled.
pub struct Workload<S, T> {
    /// The recorded errors `e_k`, `k = 0..10000`.
    pub e: Vec<T>,
    /// `starts[j]`: the stepper just before sample `j * CHUNK` (`starts[0]` is fresh).
    pub starts: Vec<S>,
}

impl<T: Copy, S: Stepper<T>> Workload<S, T> {
    /// Steps `fresh` through `e` once, saving the state at each chunk start.
    pub fn new(fresh: S, e: Vec<T>) -> Self {
        let chunks = e.len() / CHUNK;
        let mut s = fresh;
        let mut starts = Vec::with_capacity(chunks);
        for j in 0..chunks {
            starts.push(s);
            for &x in &e[j * CHUNK..(j + 1) * CHUNK] {
                s.step_once(x);
            }
        }
        Self { e, starts }
    }

    /// Runs chunk `j` from its saved state.
    #[inline(always)]
    pub fn run(&self, j: usize) -> T {
        run_chunk(&self.starts[j], &self.e[j * CHUNK..(j + 1) * CHUNK])
    }

    /// The settled chunks' indices.
    pub fn settled(&self) -> std::ops::Range<usize> {
        1..self.starts.len()
    }

    /// Same inputs, another stepper.
    pub fn with<S2: Stepper<T>>(&self, fresh: S2) -> Workload<S2, T> {
        Workload::new(fresh, self.e.clone())
    }
}

/// Replays `e` from a copy of `start`; the unit measured by the benches and
/// counted by callgrind (`--toggle-collect=*run_chunk*`).
#[inline(never)]
pub fn run_chunk<T: Copy, S: Stepper<T>>(start: &S, e: &[T]) -> T {
    let mut s = *start;
    let mut last = e[0];
    for &x in e {
        last = black_box(s.step_once(black_box(x)));
    }
    last
}

/// As [`run_chunk`], in a closed loop: each sample waits for the previous
/// output (`e_k + 0 * v_(k-1)`, the zero hidden from the compiler), as a
/// controller's next measurement follows its last command. The values are
/// those of [`run_chunk`]; the steps can no longer overlap in the CPU.
#[inline(never)]
pub fn run_chunk_closed<T: Real, S: Stepper<T>>(start: &S, e: &[T]) -> T {
    let mut s = *start;
    let zero = black_box(T::zero());
    let mut last = T::zero();
    for &x in e {
        last = black_box(s.step_once(black_box(x + last * zero)));
    }
    last
}

fn to_t<T: Real>(run: &common::Run) -> Vec<T> {
    run.z1.iter().map(|&e| T::from_f64(e)).collect()
}

fn with_disc<T: Real, const N: usize>(c: &Controller<T, N>, disc: Discretization) -> Controller<T, N> {
    let cfg = c.config();
    let h = cfg.differentiator().map(|h| HighGain {
        discretization: disc,
        ..*h
    });
    Controller::new(cfg.to_builder().differentiator(h).build().unwrap())
}

/// Example 1 (LaMC finite-time), closed loop on the second-order plant
/// (variant "code", limits +-100); `disc` replaces the differentiator's
/// discretization for the replay (the inputs stay those of the exact run).
pub fn ex1<T: Real>(disc: Discretization) -> Workload<Controller<T, 2>, T> {
    let c = common::example1::<T>(Variant::Code, DT);
    let mut closed = c; // Controller is Copy: c stays fresh
    let r = common::run(&Second::new(Variant::Code), &mut closed, T_END, UNSAT, SUB);
    Workload::new(with_disc(&c, disc), to_t(&r))
}

/// Example 2 (LoMC variable-exponent with SSMD), as [`ex1`].
pub fn ex2<T: Real>(disc: Discretization) -> Workload<Controller<T, 2>, T> {
    let c = common::example2::<T>(Variant::Code, DT);
    let mut closed = c; // Controller is Copy: c stays fresh
    let r = common::run(&Second::new(Variant::Code), &mut closed, T_END, UNSAT, SUB);
    Workload::new(with_disc(&c, disc), to_t(&r))
}

/// Example 3 (RFC: LoMC, fixed-time laws with NSMD), closed loop on the
/// third-order plant, as [`ex1`].
pub fn ex3<T: Real>(disc: Discretization) -> Workload<Controller<T, 3>, T> {
    let c = common::example3::<T>(Variant::Code, DT);
    let mut closed = c; // Controller is Copy: c stays fresh
    let r = common::run(&Third::new(Variant::Code), &mut closed, T_END, UNSAT, SUB);
    Workload::new(with_disc(&c, disc), to_t(&r))
}

/// The hand-inlined baseline on example 1's inputs.
pub fn baseline<T: Real>() -> Workload<Baseline<T>, T> {
    let w = ex1::<T>(Discretization::Exact);
    w.with(Baseline::from_config(w.starts[0].config()))
}

/// The laws of the order-scaling designs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Every stage FixedTime with NSMD: stages 1..N-2 are example 3's first
    /// stage, the last is example 3's second stage (N = 3 is example 3, code
    /// variant, with the Tustin differentiator).
    Nsmd,
    /// Every stage `h(s) = -2 s` (a pure jet-arithmetic manifold).
    Linear,
}

/// Coefficients of `(s + 2)^N`: `a_i = C(N, i) 2^i`.
pub fn binomial<T: Real, const N: usize>() -> [T; N] {
    let mut a = [T::zero(); N];
    let mut c = 1.0_f64;
    for (i, ai) in a.iter_mut().enumerate() {
        let i = i + 1;
        c = c * (N + 1 - i) as f64 / i as f64;
        *ai = T::from_f64(c * 2f64.powi(i as i32));
    }
    a
}

/// An order-`N` design of `family` (LoMC, eps = 3, k_u = 30, T_s = 1 s,
/// differentiator `(s + 2)^N`, mu = 0.01, Tustin). NSMD: example 3's two
/// stages first and last, the middle ones like its first with `q = 1.5`.
pub fn order_n<T: Real, const N: usize>(family: Family) -> Controller<T, N> {
    let c = T::from_f64;
    let first = (
        Feedback::FixedTime {
            alpha: c(1.0),
            p: c(0.5),
            beta: c(0.5),
            q: c(2.0),
        },
        Some(Skew::nonsingular(c(0.1), c(0.1), c(0.1))),
    );
    // The middle stages with q = 1.5: with q = 2 at every stage the chain
    // grows like |e|^(2^(N-1)) and overflows f64 at moderate errors from
    // order 8 on, which the validation probe rejects (docs/design.md §3.7).
    let middle = (
        Feedback::FixedTime {
            alpha: c(1.0),
            p: c(0.5),
            beta: c(0.5),
            q: c(1.5),
        },
        Some(Skew::nonsingular(c(0.1), c(0.1), c(0.1))),
    );
    let last = (
        Feedback::FixedTime {
            alpha: c(2.0),
            p: c(0.5),
            beta: c(1.0),
            q: c(2.0),
        },
        Some(Skew::nonsingular(c(3.0), c(0.2), c(1.0))),
    );
    let linear = (Feedback::Linear { k: c(2.0) }, None);
    let laws: Vec<_> = (0..N - 1)
        .map(|i| match family {
            Family::Linear => linear,
            Family::Nsmd if i + 2 == N => last,
            Family::Nsmd if i == 0 => first,
            Family::Nsmd => middle,
        })
        .collect();
    let latch = if family == Family::Nsmd {
        Latch::Authors
    } else {
        Latch::Paper
    };
    let cfg = Config::<T, N>::builder(c(DT), &laws, Constraint::Longitudinal { eps: c(3.0) }, c(30.0))
        .differentiator(Some(HighGain::new(
            c(0.01),
            binomial::<T, N>(),
            Discretization::Tustin,
        )))
        .latch(latch)
        .build()
        .unwrap();
    Controller::new(cfg)
}

/// An order-`N` design replaying example 3's recorded closed-loop errors
/// (no closed loop of its own: the recorded signal is a realistic error with
/// a transient and a settled phase).
pub fn scaled<T: Real, const N: usize>(family: Family) -> Workload<Controller<T, N>, T> {
    let c = common::example3::<T>(Variant::Code, DT);
    let mut closed = c; // Controller is Copy: c stays fresh
    let r = common::run(&Third::new(Variant::Code), &mut closed, T_END, UNSAT, SUB);
    Workload::new(order_n::<T, N>(family), to_t(&r))
}

// ---------------------------------------------------------------------------
// Start-up checks: the comparison with the baseline is honest only if both
// compute the same thing.

fn check_replay() {
    // Replaying a recorded input gives the recorded closed-loop outputs.
    let c = common::example1::<f64>(Variant::Code, DT);
    let mut closed = c; // Controller is Copy: c stays fresh
    let r = common::run(&Second::new(Variant::Code), &mut closed, T_END, UNSAT, SUB);
    let mut c2 = c;
    for (e, v) in r.z1.iter().zip(&r.v) {
        assert_eq!(c2.step(*e).unwrap().to_bits(), v.to_bits(), "replay differs");
    }
}

fn check_baseline<T: Real>(tol: f64) -> f64 {
    let w = ex1::<T>(Discretization::Exact);
    let mut ctrl = w.starts[0];
    let mut base = Baseline::from_config(ctrl.config());
    let mut worst = 0.0_f64;
    for (k, &e) in w.e.iter().enumerate() {
        let vc = ctrl.step(e).unwrap().to_f64_lossless();
        let vb = base.step_once(e).to_f64_lossless();
        let err = (vc - vb).abs() / vc.abs().max(1.0);
        assert!(
            err <= tol,
            "baseline differs from the controller at sample {k}: {vb} vs {vc}"
        );
        worst = worst.max(err);
    }
    // Both phases must be present in the recorded run.
    assert!(ctrl.diagnostics().t >= 1.0);
    worst
}

// ---------------------------------------------------------------------------
// The benches.

pub fn bench_phases<S: Stepper<T>, T: Copy>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    w: &Workload<S, T>,
    transient: bool,
) {
    if transient {
        g.bench_function(format!("{name}/transient"), |b| b.iter(|| w.run(0)));
    }
    let settled = w.settled();
    let mut j = settled.start;
    g.bench_function(format!("{name}/settled"), |b| {
        b.iter(|| {
            let out = w.run(j);
            j = if j + 1 == settled.end {
                settled.start
            } else {
                j + 1
            };
            out
        })
    });
}

fn benches(c: &mut Criterion) {
    use Discretization::{Euler, Exact};
    let mut g = c.benchmark_group("step");
    g.throughput(Throughput::Elements(CHUNK as u64));

    // The baseline first, and then the designs it is compared with.
    bench_phases(&mut g, "baseline/f64", &baseline::<f64>(), true);
    bench_phases(&mut g, "ex1/f64", &ex1::<f64>(Exact), true);
    bench_phases(&mut g, "baseline/f32", &baseline::<f32>(), true);
    bench_phases(&mut g, "ex1/f32", &ex1::<f32>(Exact), true);
    bench_phases(&mut g, "ex2/f64", &ex2::<f64>(Exact), true);
    bench_phases(&mut g, "ex2/f32", &ex2::<f32>(Exact), true);
    bench_phases(&mut g, "ex3/f64", &ex3::<f64>(Exact), true);
    bench_phases(&mut g, "ex3/f32", &ex3::<f32>(Exact), true);

    // Euler vs exact differentiator: same cost (Phi is precomputed).
    bench_phases(&mut g, "ex1-euler/f64", &ex1::<f64>(Euler), false);
    bench_phases(&mut g, "ex2-euler/f64", &ex2::<f64>(Euler), false);
    bench_phases(&mut g, "ex3-euler/f64", &ex3::<f64>(Euler), false);

    // Scaling with the order.
    macro_rules! orders {
        ($($n:literal),*) => {$(
            bench_phases(&mut g, concat!("nsmd", $n, "/f64"), &scaled::<f64, $n>(Family::Nsmd), true);
            bench_phases(&mut g, concat!("linear", $n, "/f64"), &scaled::<f64, $n>(Family::Linear), false);
        )*};
    }
    orders!(3, 4, 5, 6, 7, 8);
    g.finish();
}

fn main() {
    check_replay();
    let e64 = check_baseline::<f64>(1e-12);
    let e32 = check_baseline::<f32>(1e-5);
    println!("baseline == controller on example 1's inputs: max rel. diff f64 {e64:.1e}, f32 {e32:.1e}");
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    benches(&mut c);
    c.final_summary();
}
