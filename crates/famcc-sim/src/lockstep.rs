//! The one sample-and-hold loop ([`Lockstep`]).

use crate::control::Controllers;
use crate::options::{Options, Reason, Stop};
use crate::plant::Plant;
use crate::record::Record;
use famcc_paper::rk4::{rk4_in_place, Stages};

/// `v[i]`, NaN past the end.
#[inline(always)]
fn at(v: &[f64], i: usize) -> f64 {
    v.get(i).copied().unwrap_or(f64::NAN)
}

/// `!(|a| <= bound)`: beyond it, or NaN.
#[inline(always)]
fn beyond(a: f64, bound: f64) -> bool {
    !matches!(
        a.abs().partial_cmp(&bound),
        Some(core::cmp::Ordering::Less | core::cmp::Ordering::Equal)
    )
}

/// `v[i] = x` (nothing past the end).
#[inline(always)]
fn set(v: &mut [f64], i: usize, x: f64) {
    if let Some(o) = v.get_mut(i) {
        *o = x;
    }
}

/// `v[i]` of a flag vector, false past the end.
#[inline(always)]
fn flag(v: &[bool], i: usize) -> bool {
    v.get(i).copied().unwrap_or(false)
}

/// Why [`Lockstep::run`] returned early with an error.
#[derive(Debug, PartialEq)]
pub enum Failure<P, C> {
    /// The block's arrays do not fit the options (the message says how).
    Shape(&'static str),
    /// A controller's step failed at sample `k` (that sample is not recorded).
    Controller(usize, C),
    /// The plant's right-hand side failed integrating from sample `k` (that
    /// sample is recorded; the live lanes stop with [`Reason::PlantError`]).
    Plant(usize, P),
}

/// A closed loop of `lanes x channels` controllers and a plant, run sample
/// by sample in blocks ([`Lockstep::run`]); it keeps the plant state, the
/// held inputs and the clock between blocks.
#[derive(Clone, Debug)]
pub struct Lockstep {
    opts: Options,
    k: usize,
    x: Vec<f64>,
    u_prev: Vec<f64>,
    stops: Vec<Option<Stop>>,
    live: Vec<bool>,
    scratch: Vec<f64>,
    order: Vec<usize>,
}

impl Lockstep {
    /// A run from the states `x0` (state-major, `states * lanes` values).
    pub fn new(opts: Options, x0: Vec<f64>) -> Result<Self, &'static str> {
        opts.check()?;
        if x0.len() != opts.states * opts.lanes || x0.iter().any(|v| !v.is_finite()) {
            return Err("x0 must hold states * lanes finite values");
        }
        let (c, l, s) = (opts.channels(), opts.lanes, opts.states);
        // The estimate's length per channel: the states up to the next output.
        let mut order: Vec<usize> = opts
            .outputs
            .iter()
            .map(|&o| {
                opts.outputs
                    .iter()
                    .filter(|&&p| p > o)
                    .min()
                    .copied()
                    .unwrap_or(s)
                    - o
            })
            .collect();
        order
            .iter_mut()
            .for_each(|n| *n = (*n).clamp(1, famcc_core::config::MAX_ORDER));
        Ok(Self {
            k: 0,
            x: x0,
            u_prev: vec![0.0; c * l],
            stops: vec![None; l],
            live: vec![true; l],
            scratch: vec![0.0; 5 * s * l],
            order,
            opts,
        })
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    /// The next sample's index.
    pub fn sample(&self) -> usize {
        self.k
    }

    /// The plant states now (state-major).
    pub fn state(&self) -> &[f64] {
        &self.x
    }

    /// Per lane, where and why it stopped (None: still running or finished).
    pub fn stops(&self) -> &[Option<Stop>] {
        &self.stops
    }

    /// True when every lane stopped or the run reached its last sample.
    pub fn done(&self) -> bool {
        self.k >= self.opts.samples || !self.live.iter().any(|l| *l)
    }

    #[inline]
    fn stop(&mut self, l: usize, samples: usize, reason: Reason) {
        if let (Some(s), Some(live)) = (self.stops.get_mut(l), self.live.get_mut(l)) {
            *s = Some(Stop { samples, reason });
            *live = false;
        }
    }

    /// Runs the next `rows` samples, `rows = yd.len() / (channels * lanes)`
    /// (at most the samples left): the reference `yd`, the measurement noise
    /// and the input disturbance of those samples, each `[row][channel][lane]`.
    /// Rows are appended to `rec`; the block ends early when every lane has
    /// stopped.
    #[allow(clippy::too_many_arguments)]
    pub fn run<P: Plant, C: Controllers + ?Sized>(
        &mut self,
        plant: &mut P,
        ctrls: &mut C,
        yd: &[f64],
        noise: Option<&[f64]>,
        dist: Option<&[f64]>,
        rec: &mut Record,
    ) -> Result<(), Failure<P::Error, C::Error>> {
        let (nc, nl) = (self.opts.channels(), self.opts.lanes);
        let width = nc * nl;
        if yd.len() % width != 0
            || noise.is_some_and(|n| n.len() != yd.len())
            || dist.is_some_and(|d| d.len() != yd.len())
        {
            return Err(Failure::Shape(
                "yd, noise and disturbance need channels * lanes values per row, equally many rows",
            ));
        }
        let rows = (yd.len() / width).min(self.opts.samples.saturating_sub(self.k));
        let (mut e, mut em, mut v, mut u, mut up) = (
            vec![0.0; width],
            vec![0.0; width],
            vec![0.0; width],
            vec![0.0; width],
            vec![0.0; width],
        );
        for b in 0..rows {
            if !self.live.iter().any(|l| *l) {
                break;
            }
            let k = self.k;
            let given =
                |a: Option<&[f64]>, i: usize| a.and_then(|a| a.get(b * width + i)).copied().unwrap_or(0.0);
            let mut partial = vec![None; nl];
            for i in 0..width {
                let (c, l) = (i / nl, i % nl);
                let out = self.opts.outputs.get(c).copied().unwrap_or(0);
                let ei = at(&self.x, out * nl + l) - given(Some(yd), i);
                set(&mut e, i, ei);
                set(&mut em, i, ei + given(noise, i));
            }
            if let Some(bound) = self.opts.diverge_at {
                for l in 0..nl {
                    if flag(&self.live, l) && (0..nc).any(|c| beyond(at(&e, c * nl + l), bound)) {
                        self.stop(l, k + 1, Reason::Diverged);
                        set_reason(&mut partial, l, Reason::Diverged);
                    }
                }
            }
            let applied = if k == 0 {
                None
            } else {
                Some(self.u_prev.as_slice())
            };
            ctrls
                .step(&em, applied, &self.live, &mut v)
                .map_err(|err| Failure::Controller(k, err))?;
            for l in 0..nl {
                if flag(&self.live, l) && (0..nc).any(|c| !at(&v, c * nl + l).is_finite()) {
                    self.stop(l, k + 1, Reason::NonFiniteOutput);
                    set_reason(&mut partial, l, Reason::NonFiniteOutput);
                }
            }
            for i in 0..width {
                let (c, l) = (i / nl, i % nl);
                let vi = at(&v, i);
                let ui = match self.opts.limits.get(c).copied().flatten() {
                    Some((lo, hi)) => vi.max(lo).min(hi),
                    None => vi,
                };
                set(&mut u, i, ui);
                set(
                    &mut up,
                    i,
                    if flag(&self.live, l) {
                        ui + given(dist, i)
                    } else {
                        0.0
                    },
                );
            }
            self.push_row(ctrls, rec, &partial, &e, &em, &v, &u, b, dist);
            if k + 1 < self.opts.samples && self.live.iter().any(|l| *l) {
                self.integrate(plant, k, &up)
                    .map_err(|err| Failure::Plant(k, err))?;
            }
            for (i, (p, ui)) in self.u_prev.iter_mut().zip(&u).enumerate() {
                if flag(&self.live, i % nl) {
                    *p = *ui;
                }
            }
            self.k += 1;
        }
        Ok(())
    }

    /// Appends sample `b` of the block: live lanes fully, lanes that stopped
    /// at it partially, lanes stopped before as NaN.
    #[allow(clippy::too_many_arguments)]
    fn push_row<C: Controllers + ?Sized>(
        &self,
        ctrls: &C,
        rec: &mut Record,
        partial: &[Option<Reason>],
        e: &[f64],
        em: &[f64],
        v: &[f64],
        u: &[f64],
        b: usize,
        dist: Option<&[f64]>,
    ) {
        let (nc, nl) = (self.opts.channels(), self.opts.lanes);
        let first = self.k == 0;
        for i in 0..nc * nl {
            let (c, l) = (i / nl, i % nl);
            let (live, stopped_here) = (flag(&self.live, l), partial.get(l).copied().flatten());
            let kept = live || stopped_here.is_some();
            let nan = |x: f64| if kept { x } else { f64::NAN };
            rec.e.push(nan(at(e, i)));
            if stopped_here == Some(Reason::Diverged) {
                rec.e_measured.push(f64::NAN);
                rec.v.push(f64::NAN);
            } else {
                rec.e_measured.push(nan(at(em, i)));
                rec.v.push(nan(at(v, i)));
            }
            let held = if first { 0.0 } else { at(&self.u_prev, i) };
            rec.u.push(if stopped_here.is_some() {
                held
            } else {
                nan(at(u, i))
            });
            let d = dist.and_then(|d| d.get(b * nc * nl + i)).copied().unwrap_or(0.0);
            rec.d.push(if stopped_here.is_some() { 0.0 } else { nan(d) });
            let n = self.order.get(c).copied().unwrap_or(1);
            let diag = if live { ctrls.diagnostics(c, l) } else { None };
            rec.width = rec.width_for(n);
            rec.push_diag(diag.as_ref(), n);
        }
        if rec.keep_states {
            for (j, x) in self.x.iter().enumerate() {
                let kept = flag(&self.live, j % nl) || partial.get(j % nl).copied().flatten().is_some();
                rec.x.push(if kept { *x } else { f64::NAN });
            }
        }
        rec.rows += 1;
    }

    /// Integrates the plant over one sample period from sample `k` with the
    /// inputs `up` held; stops the lanes whose state leaves the bounds.
    fn integrate<P: Plant>(&mut self, plant: &mut P, k: usize, up: &[f64]) -> Result<(), P::Error> {
        let (s, nl) = (self.opts.states, self.opts.lanes);
        let t = k as f64 * self.opts.dt;
        let h = self.opts.dt / self.opts.substeps as f64;
        let len = s * nl;
        // Stopped lanes integrate from rest (their values are never used).
        for l in (0..nl).filter(|&l| !flag(&self.live, l)) {
            for i in 0..s {
                if let Some(x) = self.x.get_mut(i * nl + l) {
                    *x = 0.0;
                }
            }
        }
        let failed = (|| {
            if plant.advance(t, self.opts.dt, &mut self.x, up)? {
                return Ok(());
            }
            for j in 0..self.opts.substeps {
                let tj = t + j as f64 * h;
                let (k1, rest) = self.scratch.split_at_mut(len);
                let (k2, rest) = rest.split_at_mut(len);
                let (k3, rest) = rest.split_at_mut(len);
                let (k4, trial) = rest.split_at_mut(len);
                let stages = Stages {
                    k: [k1, k2, k3, k4],
                    trial,
                };
                rk4_in_place(
                    |i, x, dx| plant.rhs(i.time(tj, h), x, up, dx),
                    &mut self.x,
                    h,
                    stages,
                )?;
            }
            Ok(())
        })();
        if let Err(err) = failed {
            for l in 0..nl {
                if flag(&self.live, l) {
                    self.stop(l, k + 1, Reason::PlantError);
                }
            }
            return Err(err);
        }
        for l in 0..nl {
            if !flag(&self.live, l) {
                continue;
            }
            let lane = (0..s).filter_map(|i| self.x.get(i * nl + l).copied());
            let mut finite = true;
            let mut inside = true;
            for xi in lane {
                finite &= xi.is_finite();
                inside &= self.opts.state_bound.is_none_or(|b| !beyond(xi, b));
            }
            if !finite {
                self.stop(l, k + 1, Reason::NonFiniteState);
            } else if !inside {
                self.stop(l, k + 1, Reason::StateBound);
            }
        }
        Ok(())
    }
}

/// `partial[l] = Some(reason)`.
fn set_reason(partial: &mut [Option<Reason>], l: usize, reason: Reason) {
    if let Some(p) = partial.get_mut(l) {
        *p = Some(reason);
    }
}
