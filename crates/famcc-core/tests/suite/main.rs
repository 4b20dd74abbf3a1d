//! The integration tests of famcc-core, in one test binary: the generic core
//! is compiled once for all of them rather than once per file, which is what
//! a build (and a mutant, docs/mutation.md) costs. Each module is one subject;
//! `cargo test -p famcc-core --test suite -- step_values::` runs one of them.

mod common;

mod auto_high_order;
mod clock_restore;
mod closed_loop;
mod closed_loop_outcomes;
mod closed_loop_random;
mod design;
mod differentiator;
mod direction;
mod estimate_saturation;
#[cfg(feature = "observer")]
mod extended;
mod f32_vs_f64;
mod fast_path;
mod fuzz;
mod golden;
mod guarantees;
mod latch;
mod no_alloc;
mod no_flexible_clamp;
#[cfg(feature = "observer")]
mod observed;
#[cfg(feature = "observer")]
mod observed_state;
mod options;
mod options_proptest;
mod precomputed;
mod prefilter;
mod properties;
mod rate_rules;
mod recovery;
mod step_proptest;
mod step_values;
mod worst_case;
