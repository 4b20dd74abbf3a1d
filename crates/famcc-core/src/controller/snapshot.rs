//! The controller's state as plain values, and its flat layout: the one
//! definition of the vector every binding exchanges (Python `state()` /
//! `set_state()`, pickling), and the one check of a state to restore.
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, Snapshot, SNAPSHOT_FIELDS};
//! assert_eq!(SNAPSHOT_FIELDS[0], "started");
//! assert_eq!(Snapshot::<f64, 3>::LEN, SNAPSHOT_FIELDS.len() + 3);
//! let cfg = Config::<f32, 1>::builder(1e-3, &[], Constraint::Longitudinal { eps: 0.1 }, 5.0)
//!     .build().unwrap();
//! let mut c = Controller::new(cfg);
//! c.step(0.5).unwrap();
//! let s = c.snapshot();
//! let mut flat = [0.0; Snapshot::<f32, 1>::LEN];
//! s.to_array(&mut flat).unwrap();
//! assert_eq!(flat[..3], [1.0, 0.0, 1.0]);               // started, t_base, k
//! assert_eq!(flat[7], f64::from(1e-3_f32));             // period
//! assert_eq!(flat[8], cfg.fingerprint() as f64);        // config
//! assert_eq!(Snapshot::<f32, 1>::from_array(&flat), Ok(s));
//! let mut twin = Controller::new(cfg);
//! twin.restore(&s).unwrap();
//! assert_eq!(twin.step(0.25), c.step(0.25));
//! ```

use super::clock::Clock;
use super::recover::{in_range, width_in_range};
use super::Controller;
use crate::{Config, ConfigError, Real};

/// The names of the leading entries of the flat layout, in order; the
/// estimate `z_hat[0..N]` ([`Snapshot::ESTIMATE`]) follows them.
pub const SNAPSHOT_FIELDS: [&str; 11] = [
    "started",
    "t_base",
    "k",
    "rho0_x",
    "rho0_y",
    "clamp_count",
    "last_v",
    "period",
    "config",
    "filtered",
    "lhat",
];

/// Everything a controller needs to continue bit-identically, as plain
/// values (for checkpoints, pickling and hand-over between processes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snapshot<T, const N: usize> {
    /// False before the first step.
    pub started: bool,
    /// Time of sample 0 of the clock's current run, seconds.
    pub t_base: f64,
    /// Samples taken in the current run.
    pub k: u64,
    /// The estimate the next step uses.
    pub zhat: [T; N],
    /// Latched initial width of the lateral envelope.
    pub rho0_x: T,
    /// Latched initial width of the vertical envelope.
    pub rho0_y: T,
    /// Clamp events so far.
    pub clamp_count: u64,
    /// The last output (for the saturation gap and the rate limit).
    pub last_v: T,
    /// The period of the clock's current run, seconds.
    pub period: T,
    /// [`Config::fingerprint`] of the controller's configuration.
    pub config: u64,
    /// The differentiator's last input: the prefiltered error
    /// ([`crate::HighGain::with_prefilter`]; the error itself without one).
    pub filtered: T,
    /// The observer's estimate of the lumped term `Lhat` (0 without an
    /// observer; config/observer.rs).
    pub lhat: T,
}

const _: () = assert!(SNAPSHOT_FIELDS.len() == 11, "update split() and length_error()");

/// The largest integer every `f64` below it represents exactly (`2^53`).
const EXACT_INTEGERS: f64 = 9_007_199_254_740_992.0;

fn count(x: f64, name: &'static str) -> Result<u64, ConfigError> {
    if x.is_finite() && x >= 0.0 && num_traits::Float::fract(x) == 0.0 && x <= EXACT_INTEGERS {
        Ok(x as u64)
    } else {
        Err(ConfigError::new(
            name,
            "must be a non-negative integer below 2^53",
        ))
    }
}

/// `x` as a `T` (rounded to nearest), when it is finite as a `T`.
fn value<T: Real>(x: f64, name: &'static str) -> Result<T, ConfigError> {
    let v = T::from_f64(x);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ConfigError::new(
            name,
            "must be finite (in the controller's float type)",
        ))
    }
}

fn rule(ok: bool, name: &'static str, rule: &'static str) -> Result<(), ConfigError> {
    if ok {
        Ok(())
    } else {
        Err(ConfigError::new(name, rule))
    }
}

impl<T: Real, const N: usize> Snapshot<T, N> {
    /// [`SNAPSHOT_FIELDS`].
    pub const FIELDS: [&'static str; 11] = SNAPSHOT_FIELDS;
    /// The name of the trailing estimate entries (`z_hat[0]`, `z_hat[1]`, ...).
    pub const ESTIMATE: &'static str = "z_hat";
    /// Length of the flat layout: the fields, then the estimate.
    pub const LEN: usize = SNAPSHOT_FIELDS.len() + N;

    /// Writes the flat layout `[started, t_base, k, rho0_x, rho0_y,
    /// clamp_count, last_v, period, config, filtered, lhat, z_hat...]` into `out` (exactly
    /// [`Self::LEN`] entries; `started` as 1 or 0, the counts as exact
    /// integers, saturating at `2^53`).
    pub fn to_array(&self, out: &mut [f64]) -> Result<(), ConfigError> {
        if out.len() != Self::LEN {
            return Err(length_error());
        }
        let f = |x: T| x.to_f64_lossless();
        let n = |k: u64| (k as f64).min(EXACT_INTEGERS);
        let head = [
            if self.started { 1.0 } else { 0.0 },
            self.t_base,
            n(self.k),
            f(self.rho0_x),
            f(self.rho0_y),
            n(self.clamp_count),
            f(self.last_v),
            f(self.period),
            n(self.config),
            f(self.filtered),
            f(self.lhat),
        ];
        let estimate = self.zhat.iter().map(|z| f(*z));
        out.iter_mut()
            .zip(head.into_iter().chain(estimate))
            .for_each(|(o, x)| *o = x);
        Ok(())
    }

    /// Reads the flat layout of [`Snapshot::to_array`]. Rejects a wrong
    /// length, a `started` other than 0 or 1, counts that are not exact
    /// non-negative integers and values that are not finite in `T`;
    /// the rest is checked by [`crate::Controller::restore`].
    pub fn from_array(v: &[f64]) -> Result<Self, ConfigError> {
        let (
            [started, t_base, k, rho0_x, rho0_y, clamp_count, last_v, period, config, filtered, lhat],
            estimate,
        ) = split::<N>(v)?;
        rule(
            *started == 0.0 || *started == 1.0,
            "state.started",
            "must be 0 or 1",
        )?;
        rule(t_base.is_finite(), "state.t_base", "must be finite and >= 0")?;
        let mut zhat = [T::zero(); N];
        for (z, x) in zhat.iter_mut().zip(estimate.iter()) {
            *z = value(*x, "state.z_hat")?;
        }
        Ok(Self {
            started: *started == 1.0,
            t_base: *t_base,
            k: count(*k, "state.k")?,
            zhat,
            rho0_x: value(*rho0_x, "state.rho0_x")?,
            rho0_y: value(*rho0_y, "state.rho0_y")?,
            clamp_count: count(*clamp_count, "state.clamp_count")?,
            last_v: value(*last_v, "state.last_v")?,
            period: value(*period, "state.period")?,
            config: count(*config, "state.config")?,
            filtered: value(*filtered, "state.filtered")?,
            lhat: value(*lhat, "state.lhat")?,
        })
    }

    /// Checks every value against the configuration `c` the state is
    /// restored into: the same fingerprint; a finite time `>= 0` and a
    /// period `> 0`; an estimate in range (docs/design.md §3.7) and a finite
    /// prefilter state; widths
    /// finite and at least the final ones; a finite last output within the
    /// output limits; and before the first step, the initial state itself.
    pub(crate) fn check(&self, c: &Config<T, N>) -> Result<(), ConfigError> {
        rule(
            self.config == c.fingerprint(),
            "state.config",
            "was taken from a controller with another configuration",
        )?;
        let time = self.t_base + self.k as f64 * self.period.to_f64_lossless();
        rule(
            self.t_base.is_finite() && self.t_base >= 0.0 && time.is_finite(),
            "state.t_base",
            "must be finite and >= 0 (and the time t_base + k period finite)",
        )?;
        rule(
            self.period.is_finite() && self.period > T::zero(),
            "state.period",
            "must be finite and > 0",
        )?;
        if !crate::compiled::period_allowed(self.period, c.dt()) {
            return Err(crate::compiled::PERIOD_COMPILED_OUT);
        }
        // The differentiator's estimate is kept in range (recover.rs);
        // without one only the integral is carried, the rest is measured.
        let carried = if c.recursion().is_some() || c.observing() {
            N
        } else {
            c.estimate_offset()
        };
        let mut head = [T::zero(); N];
        head.iter_mut()
            .zip(self.zhat.iter())
            .take(carried)
            .for_each(|(h, z)| *h = *z);
        rule(
            in_range(&head) && self.zhat.iter().all(|z| z.is_finite()),
            "state.z_hat",
            "must be finite and within the estimate range (2^512 in f64, 2^64 in f32)",
        )?;
        rule(self.filtered.is_finite(), "state.filtered", "must be finite")?;
        rule(
            in_range(&[self.lhat]) && (c.observing() || self.lhat == T::zero()),
            "state.lhat",
            "must be within the estimate range with an observer, and 0 without one",
        )?;
        let (ex, ey) = c.constraint().eps();
        let widths = self.rho0_x >= ex && self.rho0_y >= ey;
        rule(
            widths && width_in_range(self.rho0_x) && width_in_range(self.rho0_y),
            "state.rho0_x",
            "and state.rho0_y must be finite and >= eps",
        )?;
        let within = c
            .output_limits()
            .is_none_or(|(lo, hi)| self.last_v >= lo && self.last_v <= hi);
        rule(
            self.last_v.is_finite() && within,
            "state.last_v",
            "must be finite (and within output_limits)",
        )?;
        if !self.started {
            let fresh = Controller::new(*c).snapshot();
            rule(
                *self == fresh,
                "state.started",
                "is 0, but the other values are not those of a controller before its first step",
            )?;
        }
        Ok(())
    }
}

impl<T: Real, const N: usize> Controller<T, N> {
    /// The state as plain values; [`Controller::restore`] continues from it.
    pub fn snapshot(&self) -> Snapshot<T, N> {
        let st = &self.state;
        Snapshot {
            started: st.started,
            t_base: st.clock.base,
            k: st.clock.k,
            zhat: st.zhat,
            rho0_x: st.envelopes.x.rho0,
            rho0_y: st.envelopes.y.rho0,
            clamp_count: st.diag.clamp_count,
            last_v: st.diag.v,
            period: st.clock.period,
            config: self.config.fingerprint(),
            filtered: st.filtered,
            #[cfg(feature = "observer")]
            lhat: st.lhat,
            #[cfg(not(feature = "observer"))]
            lhat: T::zero(),
        }
    }

    /// Continues from a [`Controller::snapshot`] of a controller with the
    /// same configuration. Checks every field ([`Snapshot`]'s rules); on
    /// error nothing changes. The diagnostics keep only the clamp count and
    /// the last output (the count of expansions with headroom restarts at
    /// 0). The estimate carries the integral (slot 0) with integral action.
    pub fn restore(&mut self, snap: &Snapshot<T, N>) -> Result<(), ConfigError> {
        snap.check(&self.config)?;
        let mut st = Self::initial_state(&self.config);
        st.started = snap.started;
        st.clock = Clock::at(snap.t_base, snap.k, snap.period, self.config.settle_time());
        st.zhat = snap.zhat;
        st.filtered = snap.filtered;
        #[cfg(feature = "observer")]
        {
            st.lhat = snap.lhat;
        }
        st.envelopes.x.rho0 = snap.rho0_x;
        st.envelopes.y.rho0 = snap.rho0_y;
        st.diag.clamp_count = snap.clamp_count;
        st.diag.v = snap.last_v;
        self.state = st;
        Ok(())
    }
}

fn length_error() -> ConfigError {
    ConfigError::new(
        "state",
        "must be a float vector of length 11 + order (the fields, then z_hat)",
    )
}

/// The fields and the estimate of a flat vector of the right length.
#[allow(clippy::type_complexity)]
fn split<const N: usize>(v: &[f64]) -> Result<(&[f64; 11], &[f64]), ConfigError> {
    match v.split_first_chunk::<11>() {
        Some((head, estimate)) if estimate.len() == N => Ok((head, estimate)),
        _ => Err(length_error()),
    }
}
