//! The shared test vectors: one deterministic input sequence, fed open loop
//! to example 1 (order 2) and example 3 (order 3) on the host and on the
//! target; each sample's output is printed as bit patterns and compared.
//!
//! The input is made of f32 additions and multiplications and an integer
//! PRNG only (no libm), so it is bit-identical everywhere by construction:
//! a decaying 1.3 Hz oscillation from -1 (like example 1's initial error,
//! as a damped rotation), a +0.8 pulse between 1.2 s and 1.35 s (after the
//! envelopes have settled: it drives the state outside the nominal bounds and
//! expands the flexible ones), and uniform noise of amplitude 2e-5 (xorshift32).

use crate::out::Sink;
use crate::Digest;
use famcc_core::{Controller, StepError};

/// Samples per order.
pub const SAMPLES: u32 = 2000;

/// The input sequence generator.
#[derive(Clone, Copy, Debug)]
pub struct Input {
    x: f32,
    y: f32,
    rng: u32,
    k: u32,
}

impl Default for Input {
    fn default() -> Self {
        Self {
            x: -1.0,
            y: 0.0,
            rng: 0x2545_f491,
            k: 0,
        }
    }
}

// cos and sin of 2 pi 1.3 Hz * 1 ms, and the per-sample decay exp(-1.5 ms).
const C: f32 = 0.999_966_6;
const S: f32 = 0.008_168_05;
const R: f32 = 0.998_501_1;

impl Iterator for Input {
    type Item = f32;

    fn next(&mut self) -> Option<f32> {
        let k = self.k;
        self.k += 1;
        let pulse = if (1200..1350).contains(&k) { 0.8 } else { 0.0 };
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 17;
        self.rng ^= self.rng << 5;
        let noise = ((self.rng >> 8) as f32 * (1.0 / 16_777_216.0) - 0.5) * 4e-5;
        let e = self.x + pulse + noise;
        let (x, y) = (self.x, self.y);
        self.x = R * (C * x - S * y);
        self.y = R * (S * x + C * y);
        Some(e)
    }
}

fn err_code(e: StepError) -> u32 {
    match e {
        StepError::NonFiniteInput => 1,
        StepError::NonFiniteApplied => 2,
        StepError::InvalidDt => 3,
        StepError::NoDifferentiator => 4,
        StepError::Overflow => 5,
    }
}

/// Feeds the input to `ctrl` and prints one line per sample:
/// `vec <order> <k> <e bits> <v bits> <xi~ bits> <s bits>` (hex), then a
/// `vecsum` line with digests of the inputs and of the outputs.
pub fn dump<const N: usize, S: Sink>(ctrl: &mut Controller<f32, N>, out: &mut S) {
    let mut din = Digest::default();
    let mut dout = Digest::default();
    for (k, e) in Input::default().take(SAMPLES as usize).enumerate() {
        din.f32(e);
        out.s("vec ").u(N as u64).s(" ").u(k as u64).s(" ");
        out.hex(u64::from(e.to_bits()), 8).s(" ");
        match ctrl.step(e) {
            Ok(v) => {
                let d = ctrl.diagnostics();
                dout.f32(v);
                dout.f32(d.xi);
                dout.f32(d.s);
                out.hex(u64::from(v.to_bits()), 8).s(" ");
                out.hex(u64::from(d.xi.to_bits()), 8).s(" ");
                out.hex(u64::from(d.s.to_bits()), 8).nl();
            }
            Err(err) => {
                dout.word(0xdead_0000 | err_code(err));
                out.s("ERR").u(u64::from(err_code(err))).nl();
            }
        }
    }
    out.s("vecsum ")
        .u(N as u64)
        .s(" samples=")
        .u(u64::from(SAMPLES))
        .s(" input=")
        .x64(din.0)
        .s(" output=")
        .x64(dout.0)
        .nl();
}
