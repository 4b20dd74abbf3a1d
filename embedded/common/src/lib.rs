//! Shared by the famcc firmware (thumbv7em-none-eabihf) and its host twin
//! (x86_64): the same f32 code runs on both, so their outputs can be
//! compared bit for bit.
//!
//! - [`closed_loop`]: the sampled loop over the paper's plants (famcc-paper,
//!   in f32, RK4 with substeps), its record and its checks;
//! - [`suite`]: the runs both builds make, with the paper's example 1 and
//!   example 3 designs (famcc-paper) in f32;
//! - [`vectors`]: the deterministic test-vector input sequence;
//! - [`out`]: a tiny integer/hex formatter (no `core::fmt`: it costs ~15 KB
//!   of flash and must stay out of the measured code).
#![no_std]

pub mod closed_loop;
pub mod out;
pub mod suite;
pub mod vectors;

/// FNV-1a (64 bit) over 32-bit words: a digest of a run's bit patterns.
#[derive(Clone, Copy, Debug)]
pub struct Digest(pub u64);

impl Default for Digest {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Digest {
    /// Folds one word in (little-endian bytes).
    #[inline]
    pub fn word(&mut self, w: u32) {
        for b in w.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Folds an f32's bit pattern in.
    #[inline]
    pub fn f32(&mut self, x: f32) {
        self.word(x.to_bits());
    }
}
