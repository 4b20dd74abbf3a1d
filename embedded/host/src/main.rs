//! Host twin of the famcc firmware.
//!
//! - `famcc-fw-host run`: the same closed loops and test vectors as the
//!   firmware's `check` mode, same code (embedded/common), same output
//!   format; exit status = number of failed checks.
//! - `famcc-fw-host compare HOST.txt TARGET.txt`: compares the `loop`,
//!   `check`, `vec` and `vecsum` lines of the two outputs; for `vec` lines
//!   it reports the largest difference in units in the last place (ulp) per
//!   field. The tolerance is 0 ulp (see embedded/README.md for why bit
//!   equality is expected); exit status 1 on any difference.
use std::io::Write;
use std::process::ExitCode;

use famcc_fw_common::out::Sink;
use famcc_fw_common::suite;

struct Stdout(std::io::BufWriter<std::io::Stdout>);

impl Sink for Stdout {
    fn bytes(&mut self, b: &[u8]) {
        // A closed pipe only loses output; the exit status still reports.
        let _ = self.0.write_all(b);
    }
}

fn run() -> ExitCode {
    let mut out = Stdout(std::io::BufWriter::new(std::io::stdout()));
    out.s("famcc-fw-host: famcc-core f32 on the host").nl();
    let mut fails = suite::loops(&mut out, &mut |_, _, _| {}, &mut |_, _, _| {});
    fails += suite::vectors(&mut out);
    fails += precomputed(&mut out);
    out.s("result: ").u(u64::from(fails)).s(" failure(s)").nl();
    let _ = out.0.flush();
    ExitCode::from(fails.min(255) as u8)
}

/// The firmware's configurations (a recursion precomputed by build.rs, then
/// `build_discretized`) against the configurations `build` makes on the
/// host with its own discretization: they must be equal, recursion and all.
fn precomputed(out: &mut Stdout) -> u32 {
    use famcc_paper::designs::{self, Variant, SAMPLE_PERIOD};
    let dt = SAMPLE_PERIOD as f32;
    let same = [
        suite::example1().ok().map(|c| *c.config()) == designs::example1(Variant::Code, dt).ok(),
        suite::example3().ok().map(|c| *c.config()) == designs::example3(Variant::Code, dt).ok(),
    ];
    let fails = same.iter().filter(|s| !**s).count() as u32;
    if fails == 0 {
        out.s("precomputed: examples 1 and 3 equal the host's own build")
            .nl();
    } else {
        out.s("FAIL precomputed: ")
            .u(u64::from(fails))
            .s(" configuration(s) differ from the host's build")
            .nl();
    }
    fails
}

/// Distance in ulps between two f32 bit patterns (monotone integer mapping;
/// +0 and -0 are 0 apart; NaNs compare by bits only).
fn ulps(a: u32, b: u32) -> u64 {
    fn key(x: u32) -> i64 {
        if x & 0x8000_0000 != 0 {
            -i64::from(x & 0x7fff_ffff)
        } else {
            i64::from(x)
        }
    }
    (key(a) - key(b)).unsigned_abs()
}

fn keep(line: &str) -> bool {
    ["loop ", "check ", "vec ", "vecsum ", "FAIL "]
        .iter()
        .any(|p| line.starts_with(p))
}

fn compare(host: &str, target: &str) -> ExitCode {
    let read = |p: &str| match std::fs::read_to_string(p) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("compare: cannot read {p}: {e}");
            std::process::exit(2);
        }
    };
    let (h, t) = (read(host), read(target));
    let hl: Vec<&str> = h.lines().filter(|l| keep(l)).collect();
    let tl: Vec<&str> = t.lines().filter(|l| keep(l)).collect();
    let mut vec_lines = 0usize;
    let mut vec_equal = 0usize;
    let mut max_ulp = [0u64; 3];
    let mut other_diff = 0usize;
    let mut first_diff: Option<(String, String)> = None;
    if hl.len() != tl.len() {
        eprintln!(
            "compare: {} lines on the host, {} on the target",
            hl.len(),
            tl.len()
        );
    }
    for (a, b) in hl.iter().zip(tl.iter()) {
        if a.starts_with("vec ") {
            vec_lines += 1;
            if a == b {
                vec_equal += 1;
                continue;
            }
            let fa: Vec<&str> = a.split(' ').collect();
            let fb: Vec<&str> = b.split(' ').collect();
            // vec <order> <k> <e> <v> <xi> <s>
            if fa.len() == 7 && fb.len() == 7 && fa[..4] == fb[..4] {
                for i in 0..3 {
                    let pa = u32::from_str_radix(fa[4 + i], 16);
                    let pb = u32::from_str_radix(fb[4 + i], 16);
                    match (pa, pb) {
                        (Ok(x), Ok(y)) => max_ulp[i] = max_ulp[i].max(ulps(x, y)),
                        _ => max_ulp[i] = u64::MAX,
                    }
                }
            } else {
                max_ulp = [u64::MAX; 3];
            }
        } else if a != b {
            other_diff += 1;
        }
        if first_diff.is_none() && a != b {
            first_diff = Some((a.to_string(), b.to_string()));
        }
    }
    println!(
        "vectors: {vec_lines} samples compared, {vec_equal} bit-identical; max ulp difference v={} xi={} s={} (tolerance 0)",
        max_ulp[0], max_ulp[1], max_ulp[2]
    );
    println!(
        "loops/digests: {} lines compared, {} differ",
        hl.len() - vec_lines.min(hl.len()),
        other_diff
    );
    if let Some((a, b)) = &first_diff {
        println!("first difference:\n  host:   {a}\n  target: {b}");
    }
    let ok = hl.len() == tl.len() && vec_lines > 0 && vec_equal == vec_lines && other_diff == 0;
    println!("compare: {}", if ok { "IDENTICAL" } else { "DIFFERENT" });
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("run") | None => run(),
        Some("compare") if args.len() == 4 => compare(&args[2], &args[3]),
        _ => {
            eprintln!("usage: famcc-fw-host run | compare HOST.txt TARGET.txt");
            ExitCode::from(64)
        }
    }
}
