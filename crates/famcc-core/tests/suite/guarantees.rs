//! `Config::output_accuracy` and `Config::corollary_time`: which configurations
//! preset an accuracy of `|z1|` (and which do not), and the corollaries'
//! reaching time picked by the stage laws, against the bounds written out.

use famcc_core::{bounds, Config, Constraint, Feedback, Skew};
use proptest::prelude::*;

const DT: f64 = 1e-3;
const K_U: f64 = 5.0;

fn config<const N: usize>(
    stages: &[(Feedback<f64>, Option<Skew<f64>>)],
    constraint: Constraint<f64>,
) -> Config<f64, N> {
    Config::<f64, N>::builder(DT, stages, constraint, K_U)
        .build()
        .expect("a valid configuration")
}

const LINEAR: Feedback<f64> = Feedback::Linear { k: 2.0 };

#[test]
fn the_constraint_presets_the_accuracy_only_where_it_bounds_z1() {
    let lon = Constraint::Longitudinal { eps: 0.1 };
    let lat = Constraint::Lateral { eps: 0.2 };
    let obl = Constraint::Oblique {
        eps_x: 0.3,
        eps_y: 0.4,
    };
    // Order 1: s = z1, so the vertical half-width is the accuracy.
    assert_eq!(config::<1>(&[], lon).output_accuracy(), Some(0.1));
    // Order 2: LaMC bounds s_1 = z1 (Corollary 1); LoMC and OMC bound s.
    assert_eq!(config::<2>(&[(LINEAR, None)], lat).output_accuracy(), Some(0.2));
    assert_eq!(config::<2>(&[(LINEAR, None)], lon).output_accuracy(), None);
    assert_eq!(config::<2>(&[(LINEAR, None)], obl).output_accuracy(), None);
    // Order 3: LaMC bounds s_2, not z1.
    assert_eq!(
        config::<3>(&[(LINEAR, None), (LINEAR, None)], lat).output_accuracy(),
        None
    );
}

#[test]
fn a_skewed_first_stage_presets_its_eps_z() {
    let lon = Constraint::Longitudinal { eps: 0.1 };
    let ssmd = Skew::smooth(0.05, 0.02);
    let nsmd = Skew::nonsingular(0.05, 0.03, 1.0);
    assert_eq!(
        config::<2>(&[(LINEAR, Some(ssmd))], lon).output_accuracy(),
        Some(0.02)
    );
    let c = config::<3>(&[(LINEAR, Some(nsmd)), (LINEAR, Some(ssmd))], lon);
    assert_eq!(c.output_accuracy(), Some(0.03));
    // A skew on a later stage only: no accuracy of z1.
    assert_eq!(
        config::<3>(&[(LINEAR, None), (LINEAR, Some(ssmd))], lon).output_accuracy(),
        None
    );
    // With LaMC at order 2 the constraint decides, not the skew.
    let lat = Constraint::Lateral { eps: 0.2 };
    assert_eq!(
        config::<2>(&[(LINEAR, Some(ssmd))], lat).output_accuracy(),
        Some(0.2)
    );
}

#[cfg(feature = "integral")]
#[test]
fn integral_action_presets_no_output_accuracy() {
    let lat = Constraint::Lateral { eps: 0.2 };
    let ssmd = Skew::smooth(0.05, 0.02);
    let c = Config::<f64, 2>::builder(DT, &[(LINEAR, Some(ssmd))], lat, K_U)
        .integral(true)
        .build();
    let c = c.expect("a valid configuration");
    assert!(c.integral());
    assert_eq!(c.output_accuracy(), None);
}

#[test]
fn laws_without_a_corollary_have_no_reaching_time() {
    let lat = Constraint::Lateral { eps: 0.1 };
    let fin = Feedback::FiniteTime { k: 1.0, p: 0.5 };
    let fixed = Feedback::FixedTime {
        alpha: 1.0,
        p: 0.5,
        beta: 0.5,
        q: 2.0,
    };
    let nsmd = Some(Skew::nonsingular(0.05, 0.02, 1.0));
    let lon = Constraint::Longitudinal { eps: 0.1 };
    assert_eq!(config::<1>(&[], lon).corollary_time(1.0), None);
    assert_eq!(config::<2>(&[(LINEAR, None)], lat).corollary_time(1.0), None);
    // Two finite-time stages, or a fixed-time stage beside a linear one: no corollary.
    assert_eq!(
        config::<3>(&[(fin, nsmd), (fin, None)], lat).corollary_time(1.0),
        None
    );
    assert_eq!(
        config::<3>(&[(fixed, nsmd), (LINEAR, None)], lat).corollary_time(1.0),
        None
    );
    // ... while fixed-time stages throughout have one (Corollary 3).
    let t = config::<3>(&[(fixed, nsmd), (fixed, None)], lat).corollary_time(1.0);
    assert_eq!(
        t,
        Some(bounds::fixed_time(&[(1.0, 0.5, 0.5, 2.0), (1.0, 0.5, 0.5, 2.0)]))
    );
}

proptest! {
    #[test]
    fn finite_time_is_corollary_1(k in 0.1..10.0f64, p in 0.05..0.95f64, z in -10.0..10.0f64) {
        let c = config::<2>(&[(Feedback::FiniteTime { k, p }, None)], Constraint::Lateral { eps: 0.1 });
        prop_assert_eq!(c.corollary_time(z), Some(bounds::finite_time(k, p, z)));
    }

    #[test]
    fn variable_exponent_is_corollary_2(
        k in 0.1..10.0f64, r_b in 0.05..0.95f64, r_1 in 1.05..2.0f64, dr in 0.05..2.0f64, z in -10.0..10.0f64,
    ) {
        let law = Feedback::VariableExponent { k, r_b, r_1, r_t: r_1 + dr };
        let lon = Constraint::Longitudinal { eps: 0.1 };
        let c = Config::<f64, 2>::builder(DT, &[(law, None)], lon, K_U).build();
        prop_assume!(c.is_ok()); // h strictly decreasing (Step B1) rules some out
        let c = c.expect("checked");
        prop_assert_eq!(c.corollary_time(z), Some(bounds::variable_exponent(k, r_b, r_1, r_1 + dr)));
    }

    #[test]
    fn fixed_time_stages_are_corollary_3(
        stages in prop::collection::vec((0.1..5.0f64, 0.05..0.95f64, 0.1..5.0f64, 1.05..3.0f64), 2..=3),
        z in -10.0..10.0f64,
    ) {
        // Every stage but the last needs NSMD at order >= 3 (its derivatives are used).
        let last = stages.len() - 1;
        let laws: Vec<_> = stages
            .iter()
            .enumerate()
            .map(|(i, &(alpha, p, beta, q))| {
                let skew = (i < last).then(|| Skew::nonsingular(0.05, 0.02, 1.0));
                (Feedback::FixedTime { alpha, p, beta, q }, skew)
            })
            .collect();
        let lon = Constraint::Longitudinal { eps: 0.1 };
        let t = match laws.len() {
            2 => config::<3>(&laws, lon).corollary_time(z),
            _ => config::<4>(&laws, lon).corollary_time(z),
        };
        prop_assert_eq!(t, Some(bounds::fixed_time(&stages)));
    }
}
