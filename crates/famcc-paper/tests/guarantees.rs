//! The paper's numbers agree with famcc-core's rules: each example's design
//! presets the paper's accuracy (`Config::output_accuracy`) and has the
//! corollary bound of `corollary_bound` (`Config::corollary_time` from the
//! plants' initial error), in both variants and in f64 and f32.

use famcc_paper::designs::{self, Design, Example, Variant, ACCURACY, SAMPLE_PERIOD};
use famcc_paper::plants::SECOND_ORDER_X0;

fn guarantees<T: famcc_core::Real>(example: Example, variant: Variant) -> (Option<T>, Option<T>) {
    let dt = T::from_f64(SAMPLE_PERIOD);
    // Examples 1 and 2 start from x1(0) = -1 against y_d(0) = sin 0 = 0 (Corollary 1's
    // bound depends on it; example 3's does not).
    let z1_0 = T::from_f64(SECOND_ORDER_X0[0]);
    match designs::design::<T>(example, variant, dt).expect("the paper's design is valid") {
        Design::Order2(c) => (c.output_accuracy(), c.corollary_time(z1_0)),
        Design::Order3(c) => (c.output_accuracy(), c.corollary_time(z1_0)),
    }
}

#[test]
fn every_example_presets_the_papers_accuracy_and_bound() {
    for example in Example::ALL {
        for variant in Variant::ALL {
            let (eps, t_prime) = guarantees::<f64>(example, variant);
            assert_eq!(eps, Some(ACCURACY), "{example:?} {variant:?}");
            assert_eq!(
                t_prime,
                Some(designs::corollary_bound::<f64>(example)),
                "{example:?} {variant:?}"
            );
            let (eps, t_prime) = guarantees::<f32>(example, variant);
            assert_eq!(eps, Some(ACCURACY as f32), "{example:?} {variant:?} f32");
            let bound = designs::corollary_bound::<f32>(example);
            let t_prime = t_prime.expect("a bound in f32");
            assert!(
                (t_prime - bound).abs() <= 1e-5 * bound,
                "{example:?} {variant:?} f32"
            );
        }
    }
}
