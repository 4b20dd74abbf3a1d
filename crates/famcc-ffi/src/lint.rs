//! `Config::lint` through the C ABI: the findings of an initialised
//! controller's configuration, as text in caller-provided structs.

use core::ffi::c_char;
use core::fmt::{self, Write};
use core::ptr;

use crate::reports::{FamccFinding, FAMCC_MAX_FINDINGS};
use crate::storage::slot_config;
use crate::types::FamccStatus;
use famcc_core::Real;

// The header's capacity is the core's number of lints.
const _: () = assert!(FAMCC_MAX_FINDINGS == famcc_core::config::LINT_COUNT);

/// A `fmt::Write` into a fixed C buffer that truncates (keeping a NUL).
struct CBuf<'a> {
    buf: &'a mut [c_char],
    len: usize,
}

impl Write for CBuf<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for b in s.bytes() {
            if self.len + 1 >= self.buf.len() {
                break;
            }
            if let Some(d) = self.buf.get_mut(self.len) {
                *d = b as c_char;
            }
            self.len += 1;
        }
        Ok(())
    }
}

/// Writes at most `capacity` findings to `out` and their number (all of
/// them, even beyond `capacity`) to `count`.
pub(crate) unsafe fn lint<S, T: Real, const N: usize>(
    storage: *const S,
    tag: u64,
    out: *mut FamccFinding,
    capacity: usize,
    count: *mut usize,
) -> FamccStatus {
    if count.is_null() || (out.is_null() && capacity > 0) {
        return FamccStatus::NullPointer;
    }
    let cfg = match slot_config::<S, T, N>(storage, tag) {
        Ok(c) => c,
        Err(st) => return st,
    };
    let findings = cfg.lint();
    let mut n = 0usize;
    for f in findings.iter() {
        if n < capacity {
            let mut r = FamccFinding {
                stage: f.stage.map_or(-1, |s| s as i32),
                parameter: [0; 32],
                message: [0; 480],
            };
            let _ = CBuf {
                buf: &mut r.parameter,
                len: 0,
            }
            .write_str(f.parameter);
            let _ = write!(
                CBuf {
                    buf: &mut r.message,
                    len: 0
                },
                "{f}"
            );
            ptr::write_unaligned(out.add(n), r);
        }
        n += 1;
    }
    ptr::write_unaligned(count, n);
    FamccStatus::Ok
}
