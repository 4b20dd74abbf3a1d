//! The table of configuration variants that `tests_variants.rs` runs through
//! the C ABI and the core side by side (`tests_variant_build.rs` builds each
//! case in both worlds).
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use crate::types::*;

/// A law of the table, in both worlds.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Law {
    Linear(f64),
    Finite(f64, f64),
    Fixed(f64, f64, f64, f64),
    Variable(f64, f64, f64, f64),
    Moulay(f64, f64, f64),
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum SkewSpec {
    None,
    Smooth(f64, f64, FamccTransition),
    Nsmd(f64, f64, f64, FamccTransition),
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum Flex {
    Off,
    On(f64),
    Auto,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Case {
    pub(crate) stages: [(Law, SkewSpec); 2],
    pub(crate) constraint: (FamccConstraintKind, f64, f64),
    pub(crate) gamma: FamccGamma,
    pub(crate) flex: Flex,
    pub(crate) transition: FamccTransition,
    pub(crate) latch: FamccLatch,
    pub(crate) discretization: FamccDiscretization,
    /// The differentiator's prefilter time constant, s (0: none).
    pub(crate) prefilter: f64,
    pub(crate) limits: Option<[f64; 3]>,
    pub(crate) init: Option<[f64; 3]>,
    pub(crate) k_u: f64,
}

pub(crate) const BASE: Case = Case {
    stages: [
        (
            Law::Fixed(1.0, 0.5, 0.5, 2.0),
            SkewSpec::Nsmd(0.1, 0.1, 0.1, FamccTransition::Exponential),
        ),
        (Law::Finite(1.0, 0.5), SkewSpec::None),
    ],
    constraint: (FamccConstraintKind::Longitudinal, 0.1, 0.2),
    gamma: FamccGamma::Log,
    flex: Flex::Auto,
    transition: FamccTransition::Exponential,
    latch: FamccLatch::Paper,
    discretization: FamccDiscretization::Exact,
    prefilter: 0.0,
    limits: None,
    init: None,
    k_u: 5.0,
};

/// One factor at a time from [`BASE`], and a few combinations. The first
/// stage law varies at order 2 (its last stage) only where it is singular.
pub(crate) fn variants() -> std::vec::Vec<(usize, Case)> {
    use FamccTransition as Tr;
    let mut out = std::vec::Vec::new();
    let nsmd = SkewSpec::Nsmd(0.1, 0.1, 0.2, Tr::Exponential);
    let laws2 = [
        (Law::Linear(2.0), SkewSpec::None),
        (Law::Finite(1.0, 0.5), SkewSpec::None),
        (Law::Finite(1.5, 0.7), SkewSpec::Smooth(0.15, 0.1, Tr::Cubic)),
        (Law::Fixed(1.0, 0.5, 0.5, 2.0), nsmd),
        (
            Law::Variable(1.5, 0.5, 2.0, 3.0),
            SkewSpec::Smooth(0.225, 0.1, Tr::Exponential),
        ),
        (Law::Moulay(1.0, 2.0, 0.1), SkewSpec::None),
        (Law::Linear(1.0), SkewSpec::Nsmd(0.2, 0.1, 0.5, Tr::Quintic)),
        (Law::Finite(1.0, 0.5), SkewSpec::Nsmd(0.2, 0.1, 0.1, Tr::Sine)),
    ];
    let laws3_first = [
        (Law::Linear(2.0), SkewSpec::None),
        (
            Law::Fixed(1.0, 0.5, 0.5, 2.0),
            SkewSpec::Nsmd(0.1, 0.1, 0.1, Tr::Cubic),
        ),
        (
            Law::Variable(1.5, 0.5, 2.0, 3.0),
            SkewSpec::Nsmd(0.2, 0.1, 0.3, Tr::Sine),
        ),
        (Law::Finite(1.0, 0.6), SkewSpec::Nsmd(0.2, 0.1, 0.3, Tr::Quintic)),
    ];
    let constraints = [
        (FamccConstraintKind::Longitudinal, 0.1, 0.2),
        (FamccConstraintKind::Lateral, 0.1, 0.2),
        (FamccConstraintKind::Oblique, 0.1, 0.2),
    ];
    for order in [2, 3] {
        for c in constraints {
            for gamma in [FamccGamma::Log, FamccGamma::Rational] {
                for flex in [Flex::Off, Flex::On(0.005), Flex::Auto] {
                    out.push((
                        order,
                        Case {
                            constraint: c,
                            gamma,
                            flex,
                            ..BASE
                        },
                    ));
                }
            }
            for discretization in [
                FamccDiscretization::Euler,
                FamccDiscretization::Tustin,
                FamccDiscretization::Foh,
            ] {
                out.push((
                    order,
                    Case {
                        constraint: c,
                        discretization,
                        ..BASE
                    },
                ));
            }
            for discretization in [
                FamccDiscretization::Exact,
                FamccDiscretization::Euler,
                FamccDiscretization::Tustin,
                FamccDiscretization::Foh,
            ] {
                out.push((
                    order,
                    Case {
                        constraint: c,
                        discretization,
                        prefilter: 0.005,
                        ..BASE
                    },
                ));
            }
            for latch in [FamccLatch::Paper, FamccLatch::Authors] {
                for transition in [Tr::Cubic, Tr::Quintic, Tr::Sine] {
                    out.push((
                        order,
                        Case {
                            constraint: c,
                            latch,
                            transition,
                            ..BASE
                        },
                    ));
                }
            }
            out.push((
                order,
                Case {
                    constraint: c,
                    limits: Some([5.0, 3.0, 50.0]),
                    init: Some([0.0, 0.5, -2.0]),
                    ..BASE
                },
            ));
            out.push((
                order,
                Case {
                    constraint: c,
                    gamma: FamccGamma::Rational,
                    flex: Flex::Off,
                    discretization: FamccDiscretization::Tustin,
                    latch: FamccLatch::Authors,
                    limits: Some([f64::INFINITY, 2.0, 10.0]),
                    init: Some([0.0, -0.3, 1.0]),
                    ..BASE
                },
            ));
        }
    }
    for l in laws2 {
        for c in constraints {
            let mut v = Case {
                constraint: c,
                ..BASE
            };
            v.stages[0] = l;
            out.push((2, v));
        }
    }
    for l in laws3_first {
        for last in laws2 {
            let mut v = BASE;
            v.stages = [l, last];
            out.push((3, v));
        }
    }
    out
}
