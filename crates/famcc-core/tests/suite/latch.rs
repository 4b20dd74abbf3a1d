//! The envelopes' latch at the first sample (text after eqs. (21)-(22)):
//! `x_U` starts from `s_x0 = |h_v(ds_{n-1}) - s_{n-1}|`, the horizontal
//! offset, for every constraint type that uses `x` (LaMC and OMC), and `y_U`
//! from `s_y0 = |h(s_{n-1}) - ds_{n-1}| = |s|` (LoMC and OMC). For OMC the
//! paper defines `s_x0` once, not along the oblique gradient line; this pins
//! that reading (docs/design.md §3.4).
#![allow(clippy::unwrap_used)]

use famcc_core::constraint::inverse;
use famcc_core::{Config, Constraint, Controller, Feedback, Latch, SkewedLaw};

const Z: [f64; 2] = [0.5, -1.0];

fn first_step(constraint: Constraint<f64>, latch: Latch) -> (f64, f64) {
    let law = Feedback::FiniteTime { k: 2.0, p: 0.5 };
    let cfg = Config::<f64, 2>::builder(1e-3, &[(law, None)], constraint, 5.0)
        .latch(latch)
        .build()
        .unwrap();
    let mut c = Controller::new(cfg);
    c.step_state(Z).unwrap();
    let snap = c.snapshot();
    (snap.rho0_x, snap.rho0_y)
}

#[test]
fn every_type_latches_x_from_the_horizontal_offset_and_y_from_s() {
    let h = SkewedLaw::new(Feedback::FiniteTime { k: 2.0, p: 0.5 }, None).unwrap();
    let s_x0 = Z[0] - inverse(&h, Z[1]);
    let s_y0 = Z[1] - h.eval(Z[0]);
    let (eps_x, eps_y) = (0.1, 0.2);
    let oblique = Constraint::Oblique { eps_x, eps_y };
    for latch in [Latch::Paper, Latch::Authors] {
        let (x, y) = first_step(oblique, latch);
        assert_eq!(x, latch.rho0(s_x0, 2.0, eps_x), "{latch:?}");
        assert_eq!(y, latch.rho0(s_y0, 2.0, eps_y), "{latch:?}");
        let (x, y) = first_step(Constraint::Lateral { eps: eps_x }, latch);
        assert_eq!((x, y), (latch.rho0(s_x0, 2.0, eps_x), 0.0));
        let (x, y) = first_step(Constraint::Longitudinal { eps: eps_y }, latch);
        assert_eq!((x, y), (0.0, latch.rho0(s_y0, 2.0, eps_y)));
    }
    // The reading matters: the offset along OMC's own gradient line (at the
    // initial widths) is another number.
    let (x_u, y_u) = first_step(oblique, Latch::Paper);
    let along = oblique.offset(&h, Z[0], Z[1], x_u, y_u).sigma;
    assert!((along.abs() - s_x0.abs()).abs() > 0.1, "{along} vs {s_x0}");
}
