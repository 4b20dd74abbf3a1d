//! Which of the paper's printed numbers, or the authors' code's, a design or
//! a plant uses: below both designs.rs and plants.rs.
//!
//! ```
//! use famcc_paper::Variant;
//! assert_eq!(Variant::Code.latch(), famcc_core::Latch::Authors);
//! ```

use famcc_core::Latch;

/// Which printed numbers a design or plant uses (docs/design.md §6.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// As printed in the paper.
    Paper,
    /// As in the authors' MATLAB code (the default of famcc's scenarios).
    Code,
}

impl Variant {
    /// Both variants.
    pub const ALL: [Variant; 2] = [Variant::Paper, Variant::Code];

    /// The envelope latch of this variant (docs/design.md §3.4).
    pub fn latch(self) -> Latch {
        match self {
            Variant::Paper => Latch::Paper,
            Variant::Code => Latch::Authors,
        }
    }
}
