//! The plant side of a run: a right-hand side over every lane at once
//! ([`Plant`]), and the paper's two plants as lanes ([`PaperLanes`]).

use famcc_paper::plants::{self, Clock, Plant as PaperPlant, SecondOrder, ThirdOrder};
use famcc_paper::Variant;

/// `dx/dt` of every lane at once.
///
/// Layouts are state-major, as a NumPy array of shape `(states, lanes)`:
/// state `i` of lane `l` is `x[i * lanes + l]`; input `c` of lane `l` is
/// `u[c * lanes + l]`.
pub trait Plant {
    /// What a failed evaluation reports.
    type Error;
    /// Writes `dx` at time `t` (s), states `x` and held inputs `u`.
    fn rhs(&mut self, t: f64, x: &[f64], u: &[f64], dx: &mut [f64]) -> Result<(), Self::Error>;

    /// A plant that advances itself over a whole sample period (a simulator
    /// with its own integrator, e.g. MuJoCo) overwrites `x` with the states
    /// at `t + dt` under the inputs `u` held from `t`, and returns `true`;
    /// the loop then does not integrate [`Plant::rhs`]. The default returns
    /// `false`: the loop integrates `rhs` with RK4.
    fn advance(&mut self, t: f64, dt: f64, x: &mut [f64], u: &[f64]) -> Result<bool, Self::Error> {
        let _ = (t, dt, x, u);
        Ok(false)
    }
}

/// One of the paper's plants with per-lane input-gain factors and
/// disturbance amplitudes (famcc-paper's [`SecondOrder`] and [`ThirdOrder`]):
/// lane `l` computes exactly what the scalar plant with `gain[l]`, `amp[l]`
/// computes.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperLanes {
    order: usize,
    variant: Variant,
    gain: Vec<f64>,
    amp: Vec<f64>,
}

impl PaperLanes {
    /// The second-order plant (examples 1 and 2), one lane per entry of
    /// `gain` and `amp` (equal lengths).
    pub fn second(variant: Variant, gain: Vec<f64>, amp: Vec<f64>) -> Self {
        Self {
            order: 2,
            variant,
            gain,
            amp,
        }
    }

    /// The third-order plant (example 3).
    pub fn third(variant: Variant, gain: Vec<f64>, amp: Vec<f64>) -> Self {
        Self {
            order: 3,
            variant,
            gain,
            amp,
        }
    }

    /// The plant's order (2 or 3).
    pub fn order(&self) -> usize {
        self.order
    }

    /// The number of lanes.
    pub fn lanes(&self) -> usize {
        self.gain.len().min(self.amp.len())
    }

    /// Lane 0's exact output derivatives `(y, ..., y^(n-1))`, gain `G_a` and
    /// drift `F_a` at time `t` and state `x` (famcc-paper's, as its scalar plant).
    pub fn exact(&self, t: f64, x: &[f64]) -> (Vec<f64>, f64, f64) {
        let (gain, amp) = (
            self.gain.first().copied().unwrap_or(1.0),
            self.amp.first().copied().unwrap_or(0.0),
        );
        if self.order == 2 {
            let p = SecondOrder {
                variant: self.variant,
                gain,
                amp,
                x0: [0.0; 2],
            };
            let x = lane::<2>(x, 1, 0);
            let (g, f) = plants::gain_and_drift(&p, t, &x);
            (plants::output_derivatives(&p, t, &x).to_vec(), g, f)
        } else {
            let p = ThirdOrder {
                variant: self.variant,
                gain,
                amp,
                x0: [0.0; 3],
            };
            let x = lane::<3>(x, 1, 0);
            let (g, f) = plants::gain_and_drift(&p, t, &x);
            (plants::output_derivatives(&p, t, &x).to_vec(), g, f)
        }
    }

    /// The variant's initial state for every lane, state-major.
    pub fn x0(&self) -> Vec<f64> {
        let x0: Vec<f64> = match self.order {
            2 => SecondOrder::new(self.variant).x0.to_vec(),
            _ => ThirdOrder::new(self.variant).x0.to_vec(),
        };
        x0.iter()
            .flat_map(|v| core::iter::repeat_n(*v, self.lanes()))
            .collect()
    }
}

/// Lane `l` of `x` (state-major, `lanes` lanes) as an array.
fn lane<const N: usize>(x: &[f64], lanes: usize, l: usize) -> [f64; N] {
    core::array::from_fn(|i| x.get(i * lanes + l).copied().unwrap_or(f64::NAN))
}

fn put(dx: &mut [f64], lanes: usize, l: usize, rates: &[f64]) {
    for (i, r) in rates.iter().enumerate() {
        if let Some(o) = dx.get_mut(i * lanes + l) {
            *o = *r;
        }
    }
}

impl Plant for PaperLanes {
    type Error = core::convert::Infallible;

    fn rhs(&mut self, t: f64, x: &[f64], u: &[f64], dx: &mut [f64]) -> Result<(), Self::Error> {
        let c = Clock::at(t);
        let n = self.lanes();
        for (l, (gain, amp)) in self.gain.iter().zip(&self.amp).enumerate() {
            let ul = u.get(l).copied().unwrap_or(f64::NAN);
            if self.order == 2 {
                let p = SecondOrder {
                    variant: self.variant,
                    gain: *gain,
                    amp: *amp,
                    x0: [0.0; 2],
                };
                put(dx, n, l, &p.rhs(&c, &lane::<2>(x, n, l), ul));
            } else {
                let p = ThirdOrder {
                    variant: self.variant,
                    gain: *gain,
                    amp: *amp,
                    x0: [0.0; 3],
                };
                put(dx, n, l, &p.rhs(&c, &lane::<3>(x, n, l), ul));
            }
        }
        Ok(())
    }
}
