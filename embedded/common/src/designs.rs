//! The paper's controller designs in famcc terms (docs/design.md §6.2; the same
//! values as `example1`/`example3` in `crates/famcc-core/tests/common`).

use crate::plant::Variant;
use famcc_core::{
    Config, ConfigError, Constraint, Controller, Discretization, Feedback, HighGain, Latch, Skew,
};

/// Example 1: LaMC, FiniteTime(k = 1, p = 0.5), eps_x = 0.1, T_s = 1, k_u = 5,
/// HGD mu = 0.01, a = (4, 4) (exact discretization).
pub fn example1_config(variant: Variant, dt: f32) -> Result<Config<f32, 2>, ConfigError> {
    let mut cfg = Config::<f32, 2>::new(
        dt,
        &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
        Constraint::Lateral { eps: 0.1 },
        1.0,
        5.0,
    )?;
    cfg.differentiator = Some(HighGain::new(0.01, [4.0, 4.0], Discretization::Exact));
    if variant == Variant::Code {
        cfg.latch = Latch::Authors;
    }
    Ok(cfg)
}

/// Example 3: LoMC, two fixed-time NSMD stages, k_u = 30, HGD a = (4, 6, 4).
/// Variant "code": eps_s1 = 0.1, eps_y = 3 and the authors' latch; "paper":
/// eps_s1 = 0.2, eps_y = 5.
pub fn example3_config(variant: Variant, dt: f32) -> Result<Config<f32, 3>, ConfigError> {
    let (eps_s1, eps_y) = if variant == Variant::Paper {
        (0.2, 5.0)
    } else {
        (0.1, 3.0)
    };
    let mut cfg = Config::<f32, 3>::new(
        dt,
        &[
            (
                Feedback::FixedTime {
                    alpha: 1.0,
                    p: 0.5,
                    beta: 0.5,
                    q: 2.0,
                },
                Some(Skew::nonsingular(eps_s1, 0.1, 0.1)),
            ),
            (
                Feedback::FixedTime {
                    alpha: 2.0,
                    p: 0.5,
                    beta: 1.0,
                    q: 2.0,
                },
                Some(Skew::nonsingular(eps_y, 0.2, 1.0)),
            ),
        ],
        Constraint::Longitudinal { eps: eps_y },
        1.0,
        30.0,
    )?;
    cfg.differentiator = Some(HighGain::new(0.01, [4.0, 6.0, 4.0], Discretization::Exact));
    if variant == Variant::Code {
        cfg.latch = Latch::Authors;
    }
    Ok(cfg)
}

/// Example 1's controller.
pub fn example1(variant: Variant, dt: f32) -> Result<Controller<f32, 2>, ConfigError> {
    Controller::new(example1_config(variant, dt)?)
}

/// Example 3's controller.
pub fn example3(variant: Variant, dt: f32) -> Result<Controller<f32, 3>, ConfigError> {
    Controller::new(example3_config(variant, dt)?)
}
