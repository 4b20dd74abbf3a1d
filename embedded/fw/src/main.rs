//! The famcc firmware check program (QEMU mps2-an386, Cortex-M4F, f32).
//!
//! Command line (semihosting, `-semihosting-config ...,arg=famcc-fw,arg=MODE,...`):
//!
//! - `check` (default): the closed loops with their checks, a bit-exact
//!   replay of the recorded error through the measured step wrappers, and the
//!   test vectors. Exit status = number of failures (0 = pass).
//! - `bench2 K` / `bench3 K`: the order-2 / order-3 closed loop (recording
//!   its error signal), then `K` replayed steps through `famcc_fw_step_o2/3`,
//!   no output. Run with `K = 10001` and `K = 0` under `-icount` with an
//!   instruction-counting plugin: (total(K) - total(0)) / K is the mean
//!   number of instructions per controller step (with ~6 loop instructions).
//! - `worst2` / `worst3`: the same replay timed per step by SysTick (under
//!   `-icount shift=0`: 1 instruction = 1 ns, 40 per 25 MHz tick); prints
//!   the largest and the summed ticks.
//! - `adversarial2` / `adversarial3`: the worst and the median step over the
//!   replay with adversarial samples injected (`adversarial.rs`).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod adversarial;

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!("famcc-fw runs on thumbv7em-none-eabihf under QEMU; see embedded/README.md");
    std::process::exit(2);
}

#[cfg(target_os = "none")]
mod app {
    use core::hint::black_box;
    use famcc_core::Controller;
    use famcc_fw::{
        cmdline, exit, famcc_fw_step_o2, famcc_fw_step_o3, systick_now, systick_start, ticks, Out,
    };
    use famcc_fw_common::out::Sink;
    use famcc_fw_common::suite::{self, STEPS};
    use famcc_fw_common::Digest;

    const N: usize = STEPS as usize;

    /// The error signals and output digests of the unsaturated closed loops.
    struct Recorded {
        e2: [f32; N],
        e3: [f32; N],
        v2: Digest,
        v3: Digest,
    }

    fn record_loops(out: &mut Out, rec: &mut Recorded) -> u32 {
        let (e2, e3) = (&mut rec.e2, &mut rec.e3);
        let (v2, v3) = (&mut rec.v2, &mut rec.v3);
        suite::loops(
            out,
            &mut |k, e, v| {
                e2[k as usize] = e;
                v2.f32(v);
            },
            &mut |k, e, v| {
                e3[k as usize] = e;
                v3.f32(v);
            },
        )
    }

    fn parse_u32(s: &[u8]) -> Option<u32> {
        if s.is_empty() {
            return None;
        }
        let mut v: u32 = 0;
        for &c in s {
            if !c.is_ascii_digit() {
                return None;
            }
            v = v.checked_mul(10)?.checked_add(u32::from(c - b'0'))?;
        }
        Some(v)
    }

    fn controllers() -> (Controller<f32, 2>, Controller<f32, 3>) {
        match (suite::example1(), suite::example3()) {
            (Ok(a), Ok(b)) => (a, b),
            _ => {
                Out::new().s("FAIL: example config rejected").nl();
                exit(1)
            }
        }
    }

    /// Replays `k` recorded samples through the measured wrapper.
    #[inline(never)]
    fn replay2(c: &mut Controller<f32, 2>, e: &[f32], d: &mut Digest) {
        for &x in e {
            d.f32(famcc_fw_step_o2(c, black_box(x)));
        }
    }

    #[inline(never)]
    fn replay3(c: &mut Controller<f32, 3>, e: &[f32], d: &mut Digest) {
        for &x in e {
            d.f32(famcc_fw_step_o3(c, black_box(x)));
        }
    }

    #[inline(never)]
    fn bench2(c: &mut Controller<f32, 2>, e: &[f32]) {
        for &x in e {
            black_box(famcc_fw_step_o2(c, black_box(x)));
        }
    }

    #[inline(never)]
    fn bench3(c: &mut Controller<f32, 3>, e: &[f32]) {
        for &x in e {
            black_box(famcc_fw_step_o3(c, black_box(x)));
        }
    }

    /// Largest and summed SysTick ticks per step, and the sample of the largest.
    fn worst<const M: usize>(
        c: &mut Controller<f32, M>,
        e: &[f32],
        step: fn(&mut Controller<f32, M>, f32) -> f32,
    ) -> (u32, u64, usize) {
        systick_start();
        let (mut max, mut sum, mut at) = (0u32, 0u64, 0usize);
        for (k, &x) in e.iter().enumerate() {
            let t0 = systick_now();
            black_box(step(c, black_box(x)));
            let t1 = systick_now();
            let d = ticks(t0, t1);
            sum += u64::from(d);
            if d > max {
                max = d;
                at = k;
            }
        }
        (max, sum, at)
    }

    #[no_mangle]
    extern "C" fn famcc_fw_main() -> ! {
        let mut buf = [0u8; 128];
        let line = cmdline(&mut buf);
        let mut args = line.split(|&c| c == b' ').filter(|a| !a.is_empty()).skip(1);
        let mode = args.next().unwrap_or(b"check");
        let count = args.next().and_then(parse_u32);

        // ~80 KB on the stack (4 MiB of RAM).
        let mut rec = Recorded {
            e2: [0.0; N],
            e3: [0.0; N],
            v2: Digest::default(),
            v3: Digest::default(),
        };
        let mut out = Out::new();

        match (mode, count) {
            (b"bench2", Some(k)) | (b"bench3", Some(k)) => {
                // No output in this mode: the K = 0 run must differ from the
                // K > 0 run by the replayed steps only.
                let k = (k as usize).min(N);
                let (mut c2, mut c3) = controllers();
                if mode == b"bench2" {
                    suite::example1_loop(false, &mut Quiet, &mut |i, e, _| rec.e2[i as usize] = e);
                    bench2(&mut c2, &rec.e2[..k]);
                } else {
                    suite::example3_loop(false, &mut Quiet, &mut |i, e, _| rec.e3[i as usize] = e);
                    bench3(&mut c3, &rec.e3[..k]);
                }
                exit(0)
            }
            (b"worst2", _) | (b"worst3", _) => {
                let (mut c2, mut c3) = controllers();
                let (max, sum, at) = if mode == b"worst2" {
                    suite::example1_loop(false, &mut Quiet, &mut |i, e, _| rec.e2[i as usize] = e);
                    worst(&mut c2, &rec.e2, famcc_fw_step_o2)
                } else {
                    suite::example3_loop(false, &mut Quiet, &mut |i, e, _| rec.e3[i as usize] = e);
                    worst(&mut c3, &rec.e3, famcc_fw_step_o3)
                };
                out.s("worst ")
                    .s(if mode == b"worst2" { "o2" } else { "o3" })
                    .s(" steps=")
                    .u(N as u64)
                    .s(" max_ticks=")
                    .u(u64::from(max))
                    .s(" at_k=")
                    .u(at as u64)
                    .s(" sum_ticks=")
                    .u(sum)
                    .nl();
                drop(out);
                exit(0)
            }
            (b"adversarial2", _) | (b"adversarial3", _) => {
                let (mut c2, mut c3) = controllers();
                if mode == b"adversarial2" {
                    suite::example1_loop(false, &mut Quiet, &mut |i, e, _| rec.e2[i as usize] = e);
                    crate::adversarial::order2(&mut out, &mut c2, &rec.e2);
                } else {
                    suite::example3_loop(false, &mut Quiet, &mut |i, e, _| rec.e3[i as usize] = e);
                    crate::adversarial::order3(&mut out, &mut c3, &rec.e3);
                }
                drop(out);
                exit(0)
            }
            (b"check", _) => {}
            _ => {
                out.s("usage: famcc-fw [check | bench2 K | bench3 K | worst2 | worst3 | adversarial2 | adversarial3]")
                    .nl();
                drop(out);
                exit(64)
            }
        }

        out.s("famcc-fw: famcc-core f32 on thumbv7em-none-eabihf (QEMU mps2-an386)")
            .nl();
        let mut fails = record_loops(&mut out, &mut rec);

        // The measured wrappers must reproduce the closed loops bit for bit.
        let (mut c2, mut c3) = controllers();
        let mut d2 = Digest::default();
        let mut d3 = Digest::default();
        replay2(&mut c2, &rec.e2, &mut d2);
        replay3(&mut c3, &rec.e3, &mut d3);
        for (name, got, want) in [("o2", d2, rec.v2), ("o3", d3, rec.v3)] {
            let same = got.0 == want.0;
            out.s("replay ")
                .s(name)
                .s(" steps=")
                .u(N as u64)
                .s(" digest=")
                .x64(got.0)
                .s(if same { " identical" } else { " DIFFERS" })
                .nl();
            if !same {
                fails += 1;
            }
        }
        // reset() must restore the initial state: replay again after it.
        c2.reset();
        let mut again = Digest::default();
        replay2(&mut c2, &rec.e2, &mut again);
        if again.0 != d2.0 {
            out.s("FAIL reset: replay after reset() differs").nl();
            fails += 1;
        }

        fails += suite::vectors(&mut out);
        out.s("result: ").u(u64::from(fails)).s(" failure(s)").nl();
        drop(out);
        exit(fails.min(255))
    }

    /// Discards text.
    struct Quiet;

    impl Sink for Quiet {
        fn bytes(&mut self, _: &[u8]) {}
    }
}
