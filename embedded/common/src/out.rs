//! A byte sink and a tiny formatter for integers, hex words and fixed-point
//! numbers. No `core::fmt` anywhere (it would pull ~15 KB of flash into the
//! firmware and into the code under measurement).

/// Where text goes (semihosting on the target, stdout on the host).
pub trait Sink {
    /// Writes raw bytes.
    fn bytes(&mut self, b: &[u8]);

    /// Writes a string.
    fn s(&mut self, s: &str) -> &mut Self
    where
        Self: Sized,
    {
        self.bytes(s.as_bytes());
        self
    }

    /// Writes an unsigned decimal.
    fn u(&mut self, v: u64) -> &mut Self
    where
        Self: Sized,
    {
        let mut buf = [0u8; 20];
        let mut i = buf.len();
        let mut v = v;
        loop {
            i -= 1;
            buf[i] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        self.bytes(&buf[i..]);
        self
    }

    /// Writes a signed decimal.
    fn i(&mut self, v: i64) -> &mut Self
    where
        Self: Sized,
    {
        if v < 0 {
            self.bytes(b"-");
        }
        self.u(v.unsigned_abs())
    }

    /// Writes `0x` and eight hex digits.
    fn x32(&mut self, v: u32) -> &mut Self
    where
        Self: Sized,
    {
        self.bytes(b"0x");
        self.hex(u64::from(v), 8)
    }

    /// Writes `0x` and sixteen hex digits.
    fn x64(&mut self, v: u64) -> &mut Self
    where
        Self: Sized,
    {
        self.bytes(b"0x");
        self.hex(v, 16)
    }

    /// Writes `digits` hex digits of `v` (no prefix).
    fn hex(&mut self, v: u64, digits: usize) -> &mut Self
    where
        Self: Sized,
    {
        const H: &[u8; 16] = b"0123456789abcdef";
        let mut buf = [0u8; 16];
        let n = digits.min(16);
        for (k, slot) in buf[..n].iter_mut().enumerate() {
            let shift = 4 * (n - 1 - k);
            *slot = H[((v >> shift) & 0xf) as usize];
        }
        self.bytes(&buf[..n]);
        self
    }

    /// Writes `x` rounded to `decimals` decimals (|x| < 9.2e18 / 10^decimals;
    /// NaN and infinities by name). For humans only: the comparisons use
    /// bit patterns.
    fn fx(&mut self, x: f32, decimals: u32) -> &mut Self
    where
        Self: Sized,
    {
        if x.is_nan() {
            return self.s("NaN");
        }
        if x.is_infinite() {
            return self.s(if x > 0.0 { "inf" } else { "-inf" });
        }
        let scale = 10u64.pow(decimals);
        let xd = f64::from(x);
        let neg = xd < 0.0;
        let m = if neg { -xd } else { xd };
        let q = (m * scale as f64 + 0.5) as u64;
        if neg && q != 0 {
            self.bytes(b"-");
        }
        self.u(q / scale);
        if decimals > 0 {
            self.bytes(b".");
            let mut frac = [b'0'; 19];
            let mut r = q % scale;
            for k in (0..decimals as usize).rev() {
                frac[k] = b'0' + (r % 10) as u8;
                r /= 10;
            }
            self.bytes(&frac[..decimals as usize]);
        }
        self
    }

    /// Ends the line.
    fn nl(&mut self) -> &mut Self
    where
        Self: Sized,
    {
        self.bytes(b"\n");
        self
    }
}
