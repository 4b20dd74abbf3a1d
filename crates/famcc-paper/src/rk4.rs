//! The one RK4 of famcc: the classical fourth-order Runge-Kutta step with
//! the input held, over a state of any length.
//!
//! Every integration in the project goes through [`rk4_in_place`]: the
//! firmware's and the tests' closed loops ([`rk4_with`], [`crate::plants::rk4`]),
//! and the Python package's simulator (famcc-sim, for the paper's plants, the
//! plant families and plants written in Python). Its rounding is fixed here
//! once: the trial states are `x_i + (h/2) k_i` and `x_i + h k_i`, the update is
//! `x_i + (h/6) (k1 + 2 (k2 + k3) + k4)`.
//!
//! ```
//! use famcc_paper::rk4::{rk4_in_place, Instant, Stages};
//! // x' = -x over one step of 0.1 from x = 1.
//! let (mut x, mut k, mut trial) = ([1.0_f64], [[0.0; 1]; 4], [0.0; 1]);
//! let [k1, k2, k3, k4] = &mut k;
//! let stages = Stages { k: [k1, k2, k3, k4], trial: &mut trial };
//! rk4_in_place(|_: Instant, x: &[f64], dx: &mut [f64]| {
//!     dx[0] = -x[0];
//!     Ok::<(), ()>(())
//! }, &mut x, 0.1, stages).unwrap();
//! assert!((x[0] - (-0.1_f64).exp()).abs() < 1e-7);
//! ```

use famcc_core::Real;

/// The three instants of an RK4 step over `[t, t + h]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instant {
    /// `t`.
    Start,
    /// `t + h/2`.
    Middle,
    /// `t + h`.
    End,
}

impl Instant {
    /// The instant's time for a step of length `h` from `t`: `t`, `t + h/2`
    /// (`h/2` as `0.5 h`) or `t + h`.
    #[inline]
    pub fn time<T: Real>(self, t: T, h: T) -> T {
        match self {
            Instant::Start => t,
            Instant::Middle => t + T::from_f64(0.5) * h,
            Instant::End => t + h,
        }
    }
}

/// The scratch of one step: the four stage rates and the trial state, each
/// as long as the state (a longer slice is used up to the state's length).
#[derive(Debug)]
pub struct Stages<'a, T> {
    /// `k1 .. k4`.
    pub k: [&'a mut [T]; 4],
    /// The trial state of stages 2-4.
    pub trial: &'a mut [T],
}

/// `trial_i = x_i + a k_i`.
#[inline(always)]
fn axpy<T: Real>(trial: &mut [T], x: &[T], a: T, k: &[T]) {
    for (o, (xi, ki)) in trial.iter_mut().zip(x.iter().zip(k)) {
        *o = *xi + a * *ki;
    }
}

/// One classical RK4 step of length `h` of `x' = f(x)` in place; `f(instant,
/// x, dx)` writes the rates at the state `x` and the given instant of the
/// step (the caller maps it to a time, [`Instant::time`]). An error of `f`
/// stops the step and leaves `x` unchanged.
#[inline]
pub fn rk4_in_place<T: Real, E>(
    mut f: impl FnMut(Instant, &[T], &mut [T]) -> Result<(), E>,
    x: &mut [T],
    h: T,
    stages: Stages<'_, T>,
) -> Result<(), E> {
    let Stages {
        k: [k1, k2, k3, k4],
        trial,
    } = stages;
    let half = T::from_f64(0.5) * h;
    f(Instant::Start, x, k1)?;
    axpy(trial, x, half, k1);
    f(Instant::Middle, trial, k2)?;
    axpy(trial, x, half, k2);
    f(Instant::Middle, trial, k3)?;
    axpy(trial, x, h, k3);
    f(Instant::End, trial, k4)?;
    let two = T::from_f64(2.0);
    let sixth = h / T::from_f64(6.0);
    for (xi, (((a, b), c), d)) in x
        .iter_mut()
        .zip(k1.iter().zip(k2.iter()).zip(k3.iter()).zip(k4.iter()))
    {
        *xi = *xi + sixth * (*a + two * (*b + *c) + *d);
    }
    Ok(())
}

/// [`rk4_in_place`] for a state of `N` values and a right-hand side that
/// returns the rates, `f(instant, x)`.
pub fn rk4_with<T: Real, const N: usize>(f: impl Fn(Instant, &[T; N]) -> [T; N], x: &[T; N], h: T) -> [T; N] {
    let mut out = *x;
    let (mut k, mut trial) = ([[T::zero(); N]; 4], [T::zero(); N]);
    let [k1, k2, k3, k4] = &mut k;
    let stages = Stages {
        k: [k1, k2, k3, k4],
        trial: &mut trial,
    };
    let rates = |i: Instant, s: &[T], dx: &mut [T]| {
        let mut a = [T::zero(); N];
        a.iter_mut().zip(s).for_each(|(o, v)| *o = *v);
        dx.iter_mut().zip(f(i, &a)).for_each(|(o, v)| *o = v);
        Ok::<(), core::convert::Infallible>(())
    };
    match rk4_in_place(rates, &mut out, h, stages) {
        Ok(()) => out,
        Err(never) => match never {},
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_as_documented() {
        // x' = (1, x1): the update must be x + h/6 (k1 + 2 (k2 + k3) + k4) exactly.
        let h = 0.3_f64;
        let x = [0.7_f64, -0.2];
        let got = rk4_with(|_, s| [1.0, s[0]], &x, h);
        let half = 0.5 * h;
        let k1 = [1.0, x[0]];
        let k2 = [1.0, x[0] + half * k1[0]];
        let k3 = [1.0, x[0] + half * k2[0]];
        let k4 = [1.0, x[0] + h * k3[0]];
        let sixth = h / 6.0;
        for i in 0..2 {
            let want = x[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
            assert_eq!(got[i].to_bits(), want.to_bits());
        }
    }

    #[test]
    fn fourth_order_accurate() {
        // x' = x from 1 over 1 s: halving the step cuts the error about 16-fold.
        let run = |n: usize| {
            let h = 1.0 / n as f64;
            (0..n).fold([1.0_f64], |x, _| rk4_with(|_, s| [s[0]], &x, h))[0] - 1.0_f64.exp()
        };
        let ratio = run(10) / run(20);
        assert!((14.0..18.0).contains(&ratio), "{ratio}");
    }

    #[test]
    fn an_error_leaves_the_state_unchanged() {
        let mut x = [1.0_f64, 2.0];
        let (mut k, mut trial) = ([[0.0; 2]; 4], [0.0; 2]);
        let [k1, k2, k3, k4] = &mut k;
        let stages = Stages {
            k: [k1, k2, k3, k4],
            trial: &mut trial,
        };
        let mut calls = 0;
        let r = rk4_in_place(
            |i, _, dx: &mut [f64]| {
                calls += 1;
                dx.fill(1.0);
                if i == Instant::End {
                    Err("stop")
                } else {
                    Ok(())
                }
            },
            &mut x,
            0.1,
            stages,
        );
        assert_eq!((r, calls, x), (Err("stop"), 4, [1.0, 2.0]));
    }
}
