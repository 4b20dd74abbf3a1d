//! The unlimited steady step (`Config::unlimited`, no told input) is a
//! specialization of the general step: telling the controller the input it
//! applied, equal to its own previous output, takes the general step and
//! must give the same outputs and estimates bit for bit. The validation probe
//! relies on it: it checks every configuration through the general step.
//! The same holds with the observer (its steady step is compiled apart too).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

#[cfg(feature = "observer")]
use super::common::observed;
use super::common::{example1, example2, example3};
use famcc_core::{Controller, Real};
use famcc_paper::designs::Variant;
use proptest::prelude::*;

fn same<T: Real, const N: usize>(mut fast: Controller<T, N>, errors: &[f64]) -> Result<(), TestCaseError> {
    prop_assert!(fast.config().unlimited());
    let mut general = fast;
    let mut told = None;
    for (k, e) in errors.iter().enumerate() {
        let e = T::from_f64(*e);
        let a = fast.step(e);
        let b = general.step_applied(e, told);
        let bits = |r: &Result<T, _>| r.map(|v: T| v.to_f64_lossless().to_bits());
        prop_assert_eq!(bits(&a), bits(&b), "sample {}", k);
        let est = |c: &Controller<T, N>| c.estimate().map(|v| v.to_f64_lossless().to_bits());
        prop_assert_eq!(est(&fast), est(&general), "sample {}", k);
        if let Ok(u) = b {
            told = Some(u);
        }
    }
    Ok(())
}

/// A decaying oscillation with arbitrary samples spliced in.
fn errors() -> impl Strategy<Value = Vec<f64>> {
    let odd = prop_oneof![
        -1e3_f64..1e3,
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(1e30),
        Just(-1e-300)
    ];
    (0.1_f64..3.0, prop::collection::vec((0_usize..400, odd), 0..6)).prop_map(|(a, odd)| {
        let mut e: Vec<f64> = (0..400)
            .map(|k| a * (-(k as f64) * 2e-3).exp() * (k as f64 * 8e-3).cos())
            .collect();
        for (k, v) in odd {
            e[k] = v;
        }
        e
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn the_unlimited_step_equals_the_general_one(e in errors(), variant in any::<bool>()) {
        let v = if variant { Variant::Code } else { Variant::Paper };
        same(example1::<f64>(v, 1e-3), &e)?;
        same(example1::<f32>(v, 1e-3), &e)?;
        same(example2::<f64>(v, 1e-3), &e)?;
        same(example3::<f64>(v, 1e-3), &e)?;
        same(example3::<f32>(v, 1e-3), &e)?;
        // the observer's steady step is compiled apart too (common::observed)
        #[cfg(feature = "observer")]
        {
            same(observed(&example1::<f64>(v, 1e-3), famcc_core::Discretization::Foh), &e)?;
            same(observed(&example1::<f32>(v, 1e-3), famcc_core::Discretization::Exact), &e)?;
            same(observed(&example3::<f64>(v, 1e-3), famcc_core::Discretization::Exact), &e)?;
        }
    }
}
