//! The step itself: the control from the current estimate (or the measured
//! state), then the estimate and the clock advanced, committed as one
//! transaction (docs/design.md §3.2-3.8). The steady step of a
//! configuration with nothing to limit or integrate is compiled apart, inline;
//! every other step (the first one, with its latch and bumpless start, and
//! the steady one with limits) is one out-of-line function.

use super::output::{Limited, Limits};
use super::recover::{in_range, width_in_range, Cause};
use super::{Controller, Measured};
use crate::differentiator::{self, Recursion};
use crate::error::StepError;
use crate::{manifold, Real};

impl<T: Real, const N: usize> Controller<T, N> {
    /// Every step: computes the control from the current estimate (or the
    /// measured state), then advances the estimate and the clock by `dt`
    /// (`None`: the nominal period) and commits, or changes nothing on an
    /// error (except a law overflow after the first step, see the module docs).
    #[inline(always)]
    pub(super) fn control_then_advance(
        &mut self,
        measured: Measured<T, N>,
        one_off_dt: Option<T>,
        applied: Option<T>,
    ) -> Result<T, StepError> {
        if !self.state.started {
            return self.control_then_advance_general(measured, one_off_dt, applied);
        }
        // Without output limits, integral action, a told input or the
        // first-order hold's feedthrough, the limits, the integral separation,
        // the health count and the feedthrough are known to do nothing: that
        // steady step is compiled apart (the observer's its own copy, dead code
        // without the feature), so they cost it nothing.
        if applied.is_none() && self.config.steady_fast() {
            if self.config.observing() {
                self.control_then_advance_from::<true, true>(false, measured, one_off_dt, None)
            } else {
                self.control_then_advance_from::<true, false>(false, measured, one_off_dt, None)
            }
        } else {
            self.control_then_advance_general(measured, one_off_dt, applied)
        }
    }

    /// Every other step: the first one (latch, bumpless start) and the
    /// steady one with limits, integral action or a told input. Out of line
    /// and one copy for both, so that they cost the unlimited steady step
    /// nothing and a program (a microcontroller's flash) holds the general
    /// step once (the validation probe uses it too). Cold, as the first
    /// step alone was: measured, it keeps the unlimited steady step 2-8
    /// Ir cheaper (benches/README.md).
    #[cold]
    #[inline(never)]
    pub(super) fn control_then_advance_general(
        &mut self,
        measured: Measured<T, N>,
        one_off_dt: Option<T>,
        applied: Option<T>,
    ) -> Result<T, StepError> {
        let first = !self.state.started;
        self.control_then_advance_from::<false, true>(first, measured, one_off_dt, applied)
    }

    /// [`Self::control_then_advance`] for a first step (`first`) or a later
    /// one, and for a configuration with nothing to limit or integrate and
    /// no told input (`UNLIMITED`, see [`crate::Config::unlimited`]; never
    /// a first step); `OBSERVED`: that step may have an observer (observe.rs).
    #[inline(always)]
    fn control_then_advance_from<const UNLIMITED: bool, const OBSERVED: bool>(
        &mut self,
        first: bool,
        measured: Measured<T, N>,
        one_off_dt: Option<T>,
        applied: Option<T>,
    ) -> Result<T, StepError> {
        let c = &self.config;
        let off = c.estimate_offset();
        let finite = match &measured {
            Measured::Error(e) => e.is_finite(),
            Measured::State(z) => z.iter().skip(off).all(|v| v.is_finite()),
        };
        if !finite {
            return Err(StepError::NonFiniteInput);
        }
        let dt = match one_off_dt {
            Some(dt) if !(dt.is_finite() && dt > T::zero()) => return Err(StepError::InvalidDt),
            // Compiled out (src/compiled.rs): the nominal period only.
            Some(dt) if !crate::compiled::period_allowed(dt, c.dt()) => return Err(StepError::InvalidDt),
            Some(dt) => dt,
            None => c.dt(),
        };
        let settle_time = c.settle_time();
        // This step's discretization (a one-off period is rediscretized).
        let one_off;
        let rediscretized = one_off_dt.filter(|_| crate::compiled::ONE_OFF_PERIOD);
        let hgd = match rediscretized.and_then(|dt| c.recursion_at(dt)) {
            Some(d) => {
                one_off = d.map_err(|_| StepError::InvalidDt)?;
                Some(&one_off)
            }
            None => c.recursion(),
        };
        // The measured sample, the vector the law uses, and the estimate the
        // next step will use (all in the law's coordinates). The
        // differentiator's update of this step's estimate is computed after
        // the law, so that its values need not live through the law's calls.
        // Without a differentiator the next step measures its own vector.
        let carried = hgd.is_some();
        // With an observer its estimate replaces the differentiator's (observe.rs;
        // `OBSERVED` is false on the plain steady step only).
        let mut lumped = T::zero();
        let plain = UNLIMITED && !OBSERVED;
        let observed = if plain {
            None
        } else {
            self.observe(first, &measured, applied)
        };
        let (e, mut z, plan) = match (measured, observed) {
            (_, Some(o)) => {
                lumped = o.lumped;
                (o.e, o.law, Next::Known((o.next, o.e)))
            }
            (Measured::Error(e), None) => match hgd {
                Some(d) => {
                    let z =
                        self.current_estimate::<UNLIMITED>(first, d, e, || d.filter(self.state.filtered, e));
                    (e, self.limited(z), Next::Update(d))
                }
                // Order 1 needs no differentiator: Z = (e) (or (I, e)) is measured.
                None if !differentiator::needed_at(c.plant_order()) => {
                    let mut z = [e; N];
                    if let (1, Some(i)) = (off, z.first_mut()) {
                        *i = self.state.zhat.first().copied().unwrap_or_else(T::zero);
                    }
                    (e, z, Next::Known((z, e)))
                }
                None => return Err(StepError::NoDifferentiator),
            },
            (Measured::State(mut z), None) => {
                let e = z.get(off).copied().unwrap_or_else(T::zero);
                if let (1, Some(i)) = (off, z.first_mut()) {
                    *i = self.state.zhat.first().copied().unwrap_or_else(T::zero);
                }
                let (zhat, last) = if self.state.started {
                    (self.state.zhat, self.state.filtered)
                } else {
                    (z, e)
                };
                let next = match c.recursion() {
                    Some(d) => {
                        let f = d.filter(last, e);
                        let zhat = if self.state.started && d.has_feedthrough() {
                            self.held(f)
                        } else {
                            zhat
                        };
                        (d.advance(&zhat, f), f)
                    }
                    None => (z, e),
                };
                (e, z, Next::Known(next))
            }
        };
        if applied.is_some_and(|a| !a.is_finite()) {
            return Err(StepError::NonFiniteApplied);
        }
        // A one-off period within the scale range of §3.9 (the clock then
        // stays finite for any number of samples).
        let in_scale = one_off_dt.is_none() || crate::error::scale(dt, "dt").is_ok();
        let Some((t, clock_next)) = self.state.clock.sample(dt, settle_time).filter(|_| in_scale) else {
            return Err(StepError::InvalidDt);
        };
        // Beyond this point a failure after the first step consumes the
        // sample and restarts the estimate (the recovery rule, recover.rs):
        // an update out of range is the cause whatever the law gave.
        // Bumpless start with integral action: the I_0 whose output is u0.
        if let (true, 1, Some(u0)) = (first, off, c.initial_output()) {
            let i0 = self.initial_integral(&z, u0, t);
            if let Some(z0) = z.first_mut() {
                *z0 = i0;
            }
        }

        // The law (eqs. (11), (28)-(32)), with the envelopes latched from
        // this very state at the first step.
        let c = &self.config;
        let constraint = c.constraint();
        let m = if constraint.needs_s(first) {
            manifold::evaluate(&z, c.laws())
        } else {
            manifold::evaluate_prev(&z, c.laws())
        };
        // A failed first step leaves the envelopes as they were.
        let unlatched = if first { Some(self.state.envelopes) } else { None };
        let flexible = c.rho_e().map(|rho_e| (rho_e, c.transition()));
        let mut eval = constraint.evaluate(
            c.last_law(),
            &m,
            &mut self.state.envelopes,
            first.then(|| (c.latch(), c.k0())),
            t,
            flexible,
        );
        // Bumpless start without integral action: the latch for u0.
        if let (true, 0, Some(u0)) = (first, off, c.initial_output()) {
            let env = self.bumpless_envelopes(&z, self.state.envelopes, u0, t);
            self.state.envelopes = env;
            eval = constraint.evaluate(c.last_law(), &m, &mut self.state.envelopes, None, t, flexible);
        }
        // With an observer the command is u = v - c (config/observer.rs).
        let cancel = if plain {
            T::zero()
        } else {
            self.cancellation(lumped)
        };
        let v = -c.direction().apply(c.k_u()) * c.gamma().eval(eval.xi) - cancel;
        let env = &self.state.envelopes;
        let latched = !first || (width_in_range(env.x.rho0) && width_in_range(env.y.rho0));
        let (mut next, filtered) = self.next_estimate::<UNLIMITED>(first, plan, e);
        let updated = !carried || in_range(&next);
        if !(updated & latched & v.is_finite() & eval.xi.is_finite()) {
            if let Some(envelopes) = unlatched {
                self.state.envelopes = envelopes;
            }
            let cause = if updated { Cause::Law } else { Cause::Update };
            return Err(self.state.consume(c, &measured, hgd, clock_next, cause));
        }

        // The output limits, what is known of the actuator, the integral
        // separation and the health count (docs/design.md §3.8).
        let limited = if UNLIMITED {
            Limited::unlimited(v)
        } else {
            let previous = if first {
                c.initial_output()
            } else {
                Some(self.state.diag.v)
            };
            Limits {
                magnitude: c.output_limits(),
                rate: c.rate_limit().map(|r| (r, dt)),
                previous,
                applied: if first { None } else { applied },
                k_u: c.k_u(),
            }
            .apply(v)
        };
        let integral = z.first().copied().filter(|_| !UNLIMITED && off == 1);
        let mut integrating = false;
        if let (Some(i), Some(n0)) = (integral, next.first_mut()) {
            let (width, eps) = match constraint {
                crate::Constraint::Longitudinal { eps } => (eval.nominal.1, *eps),
                crate::Constraint::Lateral { eps } => (eval.nominal.0, *eps),
                crate::Constraint::Oblique { eps_x, .. } => (eval.nominal.0, *eps_x),
            };
            integrating = limited.integrates(c.direction().apply(e), eval.xi_nominal.abs() * width <= eps);
            let i_next = if integrating { i + dt * e } else { i };
            if !in_range(&[i_next]) {
                if let Some(envelopes) = unlatched {
                    self.state.envelopes = envelopes;
                }
                return Err(self.state.consume(c, &measured, hgd, clock_next, Cause::Update));
            }
            *n0 = i_next;
        }

        let (x_u, y_u) = eval.nominal;
        let factor = eval.expansion;
        let expanded = factor > T::one();
        let st = &mut self.state;
        // Field by field: the manifold values, the flexible bounds and the
        // time are never stored (`diagnostics()` computes them), so they are
        // not written either.
        let d = &mut st.diag;
        d.saturation_gap = applied.map(|a| d.v - a);
        d.xi = eval.xi;
        d.xi_nominal = eval.xi_nominal;
        // The flexible bounds and `expanded` follow from these two
        // (`diagnostics()` computes them).
        d.nominal_bounds = (x_u, y_u);
        d.z_hat = z;
        d.expansion = factor;
        d.clamp_count = d.clamp_count.saturating_add(u64::from(eval.clamped));
        d.v = limited.u;
        d.v_unlimited = v;
        #[cfg(feature = "observer")]
        {
            d.cancellation = cancel;
        }
        d.integral = integral;
        d.integrating = integrating;
        d.unsaturated_expansions = d
            .unsaturated_expansions
            .saturating_add(u64::from(expanded && limited.headroom()));
        st.started = true;
        st.zhat = next;
        st.filtered = filtered;
        #[cfg(feature = "observer")]
        {
            st.lhat = lumped;
        }
        st.sampled = st.clock;
        st.clock = clock_next;
        Ok(limited.u)
    }

    /// The estimate the next step uses, and the differentiator's input of
    /// this sample (the prefiltered `e`, or `e`).
    #[inline(always)]
    fn next_estimate<const PLAIN: bool>(&self, first: bool, plan: Next<'_, T, N>, e: T) -> ([T; N], T) {
        match plan {
            Next::Known(next) => next,
            Next::Update(d) => {
                // Only the first step comes before anything started.
                let last = if first { e } else { self.state.filtered };
                let f = d.filter(last, e);
                (
                    d.advance(&self.current_estimate::<PLAIN>(first, d, e, || f), f),
                    f,
                )
            }
        }
    }

    /// The estimate for this step: the initial one at the first step, else
    /// the stored one, with the first-order hold's feedthrough of this
    /// sample's differentiator input `f()` ([`Self::held`]; `f` is evaluated
    /// only then). `d` is this step's recursion (its discretization is the
    /// configuration's). `PLAIN`: known to have no feedthrough (the steady
    /// fast path, [`crate::Config::steady_fast`]).
    #[inline(always)]
    fn current_estimate<const PLAIN: bool>(
        &self,
        first: bool,
        d: &Recursion<T, N>,
        e: T,
        f: impl FnOnce() -> T,
    ) -> [T; N] {
        if first {
            return self.config.initial_estimate(e);
        }
        if PLAIN || !d.has_feedthrough() {
            return self.state.zhat;
        }
        self.held(f())
    }

    /// The stored estimate plus the first-order hold's feedthrough
    /// `D (f - f_prev)` ([`crate::Discretization::Foh`]) of the increment of
    /// the sample's differentiator input `f` over the stored last input,
    /// under the recursion of the period that just elapsed (the previous
    /// step's: a one-off period is rediscretized). Out of line: the other
    /// discretizations never call it.
    #[inline(never)]
    fn held(&self, f: T) -> [T; N] {
        let c = &self.config;
        let v = &self.state.zhat;
        let Some(d) = c.recursion() else {
            return *v;
        };
        if self.state.clock.k == 0 {
            // The last sample restarted the estimate (State::consume): the
            // next one uses it as the exact hold would, the estimate the
            // validation probe stepped from (recover.rs).
            return *v;
        }
        let df = f - self.state.filtered;
        let period = self.state.clock.period;
        if crate::compiled::continues_run(c.dt(), period) {
            return d.current(v, df);
        }
        match c.recursion_at(period) {
            Some(Ok(r)) => r.current(v, df),
            _ => d.current(v, df),
        }
    }

    /// The estimate after the optional saturation `|z_hat_i| <= limit_i`
    /// (the integral, slot 0 with integral action, is not limited).
    #[inline]
    pub(super) fn limited(&self, mut z: [T; N]) -> [T; N] {
        if let Some(limits) = self.config.estimate_limits() {
            z.iter_mut()
                .zip(limits.iter())
                .skip(self.config.estimate_offset())
                .for_each(|(z, l)| *z = z.max(-*l).min(*l));
        }
        z
    }
}

/// The estimate the next step uses (with the differentiator's input of this
/// sample): known, or the differentiator's update of this step's estimate
/// (stored or initial, before its limits) with the (prefiltered) sample.
#[derive(Clone, Copy)]
enum Next<'a, T, const N: usize> {
    Known(([T; N], T)),
    Update(&'a Recursion<T, N>),
}
