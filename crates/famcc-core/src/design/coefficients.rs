//! The polynomial coefficients of a design: binomial coefficients (the
//! differentiator's `(s + 2)^n` and the manifold's `(D + lambda)^(n - 1)`).
//! Below both the rules (rules.rs) and the linearized loop (linear.rs).

use super::MAX_ORDER;
use num_traits::Float as F;

/// The binomial coefficient `C(n, k)`, as a float.
pub(super) fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The manifold coefficients of `s = (D + lambda)^(n_law - 1) z1`: slot `j`
/// multiplies `z_(j+1)`.
pub(super) fn manifold(n_law: usize, lambda: f64) -> [f64; MAX_ORDER] {
    let mut c = [0.0; MAX_ORDER];
    for (j, cj) in c.iter_mut().enumerate().take(n_law) {
        *cj = binomial(n_law - 1, j) * F::powi(lambda, (n_law - 1 - j) as i32);
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_manifold_of_order_3_is_d_plus_lambda_squared() {
        // (D + 2)^2 z1 = z3 + 4 z2 + 4 z1.
        let c = manifold(3, 2.0);
        assert_eq!(&c[..3], &[4.0, 4.0, 1.0]);
        assert!(c[3..].iter().all(|&x| x == 0.0));
        assert_eq!(binomial(5, 2), 10.0);
        assert_eq!(manifold(1, 7.0)[0], 1.0);
    }
}
