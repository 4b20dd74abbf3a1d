//! Steps one benchmark workload K times, for instruction counts with callgrind.
//!
//! ```text
//! callgrind_step <design> <K> [transient|settled] [--stats]
//! ```
//!
//! `design`: `ex1`, `ex2`, `ex3` (the paper's designs, f64), the same with an
//! `f32` suffix (`ex1f32`) or an `euler` suffix (`ex1euler`, f64, Euler
//! differentiator), `base` / `basef32` (the hand-inlined order-2 baseline), and
//! `nsmd3`..`nsmd8`, `linear3`..`linear8` (order scaling), `ex1obs`, `ex3obs`
//! (the same laws on the observer, benches/observed.rs; `ex1obsfoh`, `ex3obsfoh`
//! with the first-order hold). The workloads are
//! those of `benches/step.rs` (included below): recorded closed-loop errors,
//! replayed in chunks of 1000 samples from saved states. `transient` repeats
//! the first chunk (t < 1 s), `settled` cycles the chunks from t = 1 s on.
//! K must be a multiple of 1000.
//!
//! Instructions per step = Ir / K, either with the stepping loop isolated
//!
//! ```text
//! valgrind --tool=callgrind --toggle-collect='*run_chunk*' \
//!     target/release/examples/callgrind_step ex1 10000 settled
//! ```
//!
//! or as the difference of two whole-program runs with K = 10000 and K = 0.
//! `--stats` prints how often the expensive branches were taken (no stepping
//! is counted then).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

#[allow(dead_code)]
#[path = "../benches/step.rs"]
mod step;

use famcc_core::{Controller, Discretization, Real, SkewKind};
use step::{Family, Stepper, Workload, CHUNK};

#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    Transient,
    Settled,
}

/// Runs `k` steps (k / CHUNK chunks) of `w` in `phase`.
fn go<S: Stepper<T>, T: Copy + std::fmt::Debug>(w: &Workload<S, T>, k: usize, phase: Phase) {
    let settled = w.settled();
    let mut last = None;
    for i in 0..k / CHUNK {
        let j = match phase {
            Phase::Transient => 0,
            Phase::Settled => settled.start + i % settled.len(),
        };
        last = Some(w.run(j));
    }
    println!("{} steps, last output {last:?}", k / CHUNK * CHUNK);
}

/// Branch statistics over the whole recorded run (both phases).
fn stats<T: Real, const N: usize>(w: &Workload<Controller<T, N>, T>) {
    let mut c = w.starts[0];
    let laws = *c.config();
    let mut expanded = [0usize; 2];
    // Per stage: None without NSMD, else steps with |s_i| < eps_z per phase.
    let mut inside = [None::<[usize; 2]>; 8];
    let mut count = [0usize; 2];
    for (k, &e) in w.e.iter().enumerate() {
        c.step(e).unwrap();
        let d = c.diagnostics();
        let ph = usize::from(k >= CHUNK);
        count[ph] += 1;
        expanded[ph] += usize::from(d.expanded);
        for ((law, slot), s) in laws.laws().iter().zip(inside.iter_mut()).zip(d.stages.iter()) {
            if let Some(sk) = law
                .skew()
                .filter(|sk| matches!(sk.kind, SkewKind::Nonsingular { .. }))
            {
                let n = slot.get_or_insert([0; 2]);
                n[ph] += usize::from(s.abs() < sk.eps_z);
            }
        }
    }
    for (ph, name) in ["transient", "settled"].iter().enumerate() {
        let pct = |n: usize| 100.0 * n as f64 / count[ph] as f64;
        print!("{name}: flexible bound expanded {:.1}%", pct(expanded[ph]));
        for (i, v) in inside.iter().enumerate() {
            if let Some(v) = v {
                print!(", |s_{}| < eps_z {:.1}%", i + 1, pct(v[ph]));
            }
        }
        println!();
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: callgrind_step <design> <K> [transient|settled] [--stats]";
    let design = args.get(1).expect(usage).as_str();
    let k: usize = args.get(2).expect(usage).parse().expect("K must be an integer");
    assert!(k % CHUNK == 0, "K must be a multiple of {CHUNK}");
    let phase = match args
        .iter()
        .skip(3)
        .find(|a| !a.starts_with("--"))
        .map(String::as_str)
    {
        None | Some("settled") => Phase::Settled,
        Some("transient") => Phase::Transient,
        Some(other) => panic!("unknown phase {other}; {usage}"),
    };
    let want_stats = args.iter().any(|a| a == "--stats");
    use Discretization::{Euler, Exact};
    macro_rules! run {
        ($w:expr) => {{
            let w = $w;
            if want_stats {
                stats(&w);
            } else {
                go(&w, k, phase);
            }
        }};
    }
    macro_rules! run_plain {
        ($w:expr) => {
            go(&$w, k, phase)
        };
    }
    match design {
        "ex1" => run!(step::ex1::<f64>(Exact)),
        "ex2" => run!(step::ex2::<f64>(Exact)),
        "ex3" => run!(step::ex3::<f64>(Exact)),
        "ex1f32" => run!(step::ex1::<f32>(Exact)),
        "ex2f32" => run!(step::ex2::<f32>(Exact)),
        "ex3f32" => run!(step::ex3::<f32>(Exact)),
        "ex1euler" => run!(step::ex1::<f64>(Euler)),
        "ex2euler" => run!(step::ex2::<f64>(Euler)),
        "ex3euler" => run!(step::ex3::<f64>(Euler)),
        "base" => run_plain!(step::baseline::<f64>()),
        "basef32" => run_plain!(step::baseline::<f32>()),
        "nsmd3" => run!(step::scaled::<f64, 3>(Family::Nsmd)),
        "nsmd4" => run!(step::scaled::<f64, 4>(Family::Nsmd)),
        "nsmd5" => run!(step::scaled::<f64, 5>(Family::Nsmd)),
        "nsmd6" => run!(step::scaled::<f64, 6>(Family::Nsmd)),
        "nsmd7" => run!(step::scaled::<f64, 7>(Family::Nsmd)),
        "nsmd8" => run!(step::scaled::<f64, 8>(Family::Nsmd)),
        "linear3" => run!(step::scaled::<f64, 3>(Family::Linear)),
        "linear4" => run!(step::scaled::<f64, 4>(Family::Linear)),
        "linear5" => run!(step::scaled::<f64, 5>(Family::Linear)),
        "linear6" => run!(step::scaled::<f64, 6>(Family::Linear)),
        "linear7" => run!(step::scaled::<f64, 7>(Family::Linear)),
        "linear8" => run!(step::scaled::<f64, 8>(Family::Linear)),
        #[cfg(feature = "observer")]
        "ex1obs" | "ex3obs" | "ex1obsfoh" | "ex3obsfoh" => {
            let disc = if design.ends_with("foh") {
                Discretization::Foh
            } else {
                Exact
            };
            if design.starts_with("ex1") {
                let w = step::ex1::<f64>(Exact);
                run!(w.with(step::observed(&w.starts[0], disc)))
            } else {
                let w = step::ex3::<f64>(Exact);
                run!(w.with(step::observed(&w.starts[0], disc)))
            }
        }
        other => panic!("unknown design {other}; {usage}"),
    }
}
