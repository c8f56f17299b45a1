//! Fast text output for the ASCII writers: numbers formatted straight into byte buffers
//! (`zmij`'s shortest round-trip digits for floats, laid out exactly as Rust's `{:?}` lays
//! them out; `itoa` for integers), and records formatted chunk by chunk in parallel (rayon)
//! then written in order, so that a file's bytes do not depend on the number of threads, and
//! are the bytes `write!(w, "{:?}", x)` wrote before.

use std::io::{self, Write};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

/// Appends `x` as `format!("{x:?}")` would: the shortest digits that read back as `x`, in
/// decimal form with at least one fractional digit (`1.0`, `0.0001`, `-0.0`) when
/// 1e-4 ≤ |x| < 1e16 or x = 0, else in exponent form without padding or `+` (`1e-5`,
/// `1.5e16`, `5e-324`).
pub(crate) fn push_f64(out: &mut Vec<u8>, x: f64) {
    if !x.is_finite() {
        out.extend_from_slice(format!("{x:?}").as_bytes());
        return;
    }
    if x.is_sign_negative() {
        out.push(b'-');
    }
    if x == 0.0 {
        out.extend_from_slice(b"0.0");
        return;
    }
    let mut buffer = zmij::Buffer::new();
    let abs = x.abs();
    let text = buffer.format_finite(abs).as_bytes();
    let tie = may_tie(abs);
    // an exponent (`e-7`, `e+300`) is among the last five bytes when there is one
    let exponent = text[text.len().saturating_sub(5)..].contains(&b'e');
    if !tie && (1e-4..1e16).contains(&abs) && !exponent {
        // zmij's plain form is std's there (`12.5`, `0.00125`, `100.0`)
        out.extend_from_slice(text);
        return;
    }
    let (mut decimal, point) = Decimal::parse(text);
    if tie {
        decimal.tie_up(abs, point);
    }
    let digits = decimal.as_slice();
    if !(1e-4..1e16).contains(&abs) {
        // d.ddd e exp, the exponent of the first digit
        out.push(digits[0]);
        if digits.len() > 1 {
            out.push(b'.');
            out.extend_from_slice(&digits[1..]);
        }
        out.push(b'e');
        push_int(out, point - 1);
    } else if point <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', (-point) as usize));
        out.extend_from_slice(digits);
    } else {
        let point = point as usize;
        if point < digits.len() {
            out.extend_from_slice(&digits[..point]);
            out.push(b'.');
            out.extend_from_slice(&digits[point..]);
        } else {
            out.extend_from_slice(digits);
            out.extend(std::iter::repeat_n(b'0', point - digits.len()));
            out.extend_from_slice(b".0");
        }
    }
}

/// The significant digits of a positive decimal number and where its point goes: the value
/// is `0.d₁d₂…dₙ × 10^point`, d₁ and dₙ not zero.
struct Decimal {
    digits: [u8; 32],
    len: usize,
}

impl Decimal {
    /// Reads any plain decimal text `zmij` prints (`12.5`, `0.00125`, `1.25e-7`, `1e+300`).
    fn parse(text: &[u8]) -> (Decimal, i32) {
        let mut d = Decimal {
            digits: [0; 32],
            len: 0,
        };
        let (mut point, mut exponent) = (None, 0i32);
        let mut leading = 0i32;
        let mut i = 0;
        while i < text.len() {
            match text[i] {
                b'.' => point = Some(d.len as i32 + leading),
                b'e' | b'E' => {
                    exponent = parse_exponent(&text[i + 1..]);
                    break;
                }
                b'0' if d.len == 0 => leading += 1,
                c @ b'0'..=b'9' => {
                    d.digits[d.len] = c;
                    d.len += 1;
                }
                _ => {}
            }
            i += 1;
        }
        while d.len > 1 && d.digits[d.len - 1] == b'0' {
            d.len -= 1;
        }
        // the integer digits (leading zeros counted) then the exponent, less the leading zeros
        let integer = point.unwrap_or_else(|| {
            let all = text.iter().take(i).filter(|c| c.is_ascii_digit()).count();
            all as i32
        });
        (d, integer - leading + exponent)
    }

    /// Where `x` lies exactly halfway between these digits and the next ones up (two
    /// shortest forms equally close), takes the one up as Rust's `{:?}` does; `zmij` takes
    /// the one with an even last digit.
    fn tie_up(&mut self, x: f64, point: i32) {
        let Some(&last) = self.as_slice().last() else {
            return;
        };
        if last == b'9' {
            return; // never the lower of a tie: the digit up would carry
        }
        // the halfway value: these digits then a 5, times 10^k
        let half = self
            .as_slice()
            .iter()
            .fold(0u128, |m, &c| m * 10 + u128::from(c - b'0'))
            * 10
            + 5;
        let k = point - self.len as i32 - 1;
        if equals_decimal(x, half, k) {
            self.digits[self.len - 1] = last + 1;
        }
    }

    fn as_slice(&self) -> &[u8] {
        &self.digits[..self.len]
    }
}

/// Whether the shortest forms of a positive finite `x` may tie (`x` exactly halfway between
/// two of them): its exact decimal form then has at most 18 significant digits (the 17 of a
/// shortest form at most, then a 5). With `x = b·2^e`, `b` odd, that form is `b·5^-e` for
/// `e < 0`, hence `-e ≤ 25`; an integer `x` (`e ≥ 0`) never ties: either it has at most 16
/// digits and is its own shortest form, or it is ≥ 2^53 and halfway points are not integers.
fn may_tie(x: f64) -> bool {
    let (b, e) = dyadic_of_f64(x);
    (-25..0).contains(&e) && b * 5u128.pow(e.unsigned_abs()) < 1_000_000_000_000_000_000
}

/// A positive finite `x` as (odd integer, power of two).
fn dyadic_of_f64(x: f64) -> (u128, i32) {
    let bits = x.to_bits();
    let (exponent, fraction) = ((bits >> 52) as i32 & 0x7ff, bits & ((1 << 52) - 1));
    let (m, e) = if exponent == 0 {
        (fraction, -1074)
    } else {
        (fraction | 1 << 52, exponent - 1075)
    };
    let tz = m.trailing_zeros();
    (u128::from(m >> tz), e + tz as i32)
}

/// Whether `m × 10^k` equals `x` (positive, finite) exactly: `m·2^k·5^k = b·2^e` with
/// `x = b·2^e`, each side multiplied up to integers; a side that overflows a `u128` cannot
/// equal the other (which fits: `m` < 10^19, `b` < 2^53, and each power goes to one side).
fn equals_decimal(x: f64, m: u128, k: i32) -> bool {
    let (b, e) = dyadic_of_f64(x);
    let times = |v: Option<u128>, base: u128, p: i32| v?.checked_mul(base.checked_pow(p as u32)?);
    let (mut lhs, mut rhs) = (Some(m), Some(b));
    if k >= e {
        lhs = times(lhs, 2, k - e);
    } else {
        rhs = times(rhs, 2, e - k);
    }
    if k >= 0 {
        lhs = times(lhs, 5, k);
    } else {
        rhs = times(rhs, 5, -k);
    }
    lhs.is_some() && lhs == rhs
}

fn parse_exponent(text: &[u8]) -> i32 {
    let (negative, digits) = match text.first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    let e = digits
        .iter()
        .fold(0i32, |e, &c| e * 10 + i32::from(c - b'0'));
    if negative { -e } else { e }
}

/// Appends an integer in decimal, as `{}` would.
pub(crate) fn push_int(out: &mut Vec<u8>, n: impl itoa::Integer) {
    let mut buffer = itoa::Buffer::new();
    out.extend_from_slice(buffer.format(n).as_bytes());
}

/// Writes every node as a line `x y z` (as `{:?}` prints each coordinate).
pub(crate) fn write_points(w: &mut dyn Write, nodes: &[[f64; 3]]) -> io::Result<()> {
    write_records(w, nodes.len(), |i, b| {
        let p = nodes[i];
        push_f64(b, p[0]);
        b.push(b' ');
        push_f64(b, p[1]);
        b.push(b' ');
        push_f64(b, p[2]);
        b.push(b'\n');
    })
}

/// Records per chunk of [`write_records`].
const CHUNK: usize = 8192;
/// Chunks formatted ahead of the one being written: enough that the threads never wait on
/// one another at the end of a group of chunks (with batches of 16 formatted while the last
/// batch was written, a thread idled for the rest of each write, 2–3 ms a batch of P3
/// cells), few enough that the buffers (about 0.5 MiB a chunk of P3 cells, up to twice that
/// in capacity: 16–32 MiB in all) stay small next to the mesh (at 1M cells the writer runs
/// at the memory peak).
const AHEAD: usize = 32;

/// Writes records `0..n`, each formatted by `record(i, buffer)`: chunks of records are
/// formatted into their own buffers by jobs of the thread pool, up to [`AHEAD`] chunks ahead
/// of the one being written, and written in order. A writing thread of the pool formats the
/// chunks no other thread has taken yet (the oldest first) while it waits for the next one,
/// so a pool of one thread formats and writes each chunk in turn; a thread outside the pool
/// sleeps until the pool has formatted it.
pub(crate) fn write_records<F>(w: &mut dyn Write, n: usize, record: F) -> io::Result<()>
where
    F: Fn(usize, &mut Vec<u8>) + Sync,
{
    let chunks = n.div_ceil(CHUNK);
    // chunk c's buffer, once formatted, waits in slot c % AHEAD until it is written; the
    // job for chunk c + AHEAD is spawned only then, with the same buffer
    let slots = Slots {
        slots: Mutex::new((0..AHEAD.min(chunks)).map(|_| Slot::Empty).collect()),
        filled: Condvar::new(),
    };
    let format = |c: usize, mut buffer: Vec<u8>| {
        let mut fill = Fill {
            slots: &slots,
            at: c % AHEAD,
            buffer: None,
        };
        buffer.clear();
        for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
            record(i, &mut buffer);
        }
        fill.buffer = Some(buffer);
    };
    let in_pool = rayon::current_thread_index().is_some();
    rayon::in_place_scope_fifo(|s| {
        for c in 0..AHEAD.min(chunks) {
            s.spawn_fifo(move |_| format(c, Vec::new()));
        }
        for c in 0..chunks {
            // (None: a job panicked, which the scope raises once its jobs have ended)
            let Some(buffer) = slots.take(c % AHEAD, in_pool) else {
                return Ok(());
            };
            w.write_all(&buffer)?;
            if c + AHEAD < chunks {
                s.spawn_fifo(move |_| format(c + AHEAD, buffer));
            }
        }
        Ok(())
    })
}

/// The chunks formatted and not yet written, by slot, and the signal that one was filled.
struct Slots {
    slots: Mutex<Vec<Slot>>,
    filled: Condvar,
}

/// A slot of [`Slots`].
enum Slot {
    Empty,
    Ready(Vec<u8>),
    /// The job formatting its chunk panicked.
    Failed,
}

impl Slots {
    fn lock(&self) -> MutexGuard<'_, Vec<Slot>> {
        // (poisoned only by a panic between a lock and its release, none of which formats)
        self.slots.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The buffer of slot `at`, when it is filled: in the pool, meanwhile running the pool's
    /// jobs (the oldest first: the chunk itself when no other thread has taken it); outside,
    /// asleep. `None` when its job panicked.
    fn take(&self, at: usize, in_pool: bool) -> Option<Vec<u8>> {
        let mut slots = self.lock();
        loop {
            match std::mem::replace(&mut slots[at], Slot::Empty) {
                Slot::Ready(buffer) => return Some(buffer),
                Slot::Failed => return None,
                Slot::Empty => {}
            }
            if in_pool {
                drop(slots);
                if rayon::yield_now() != Some(rayon::Yield::Executed) {
                    std::thread::yield_now();
                }
                slots = self.lock();
            } else {
                slots = self
                    .filled
                    .wait(slots)
                    .unwrap_or_else(PoisonError::into_inner);
            }
        }
    }
}

/// Fills a slot with its formatted buffer when dropped, or marks it failed when the buffer
/// is missing (a panic while formatting), and signals it.
struct Fill<'a> {
    slots: &'a Slots,
    at: usize,
    buffer: Option<Vec<u8>>,
}

impl Drop for Fill<'_> {
    fn drop(&mut self) {
        let slot = self.buffer.take().map_or(Slot::Failed, Slot::Ready);
        self.slots.lock()[self.at] = slot;
        self.slots.filled.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn fast(x: f64) -> String {
        let mut out = Vec::new();
        push_f64(&mut out, x);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_layout_is_that_of_debug_at_the_edges() {
        let edges = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1e-4,
            9.999999999999999e-5,
            1e-5,
            1.5e-5,
            1e16,
            9999999999999998.0,
            1e15,
            123456789012345680.0,
            1e300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            5e-324,
            -5e-324,
            f64::from_bits(0x000f_ffff_ffff_ffff), // the largest subnormal
            0.3,
            2.0f64.powi(60),
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in edges {
            assert_eq!(fast(x), format!("{x:?}"), "bits {:#x}", x.to_bits());
        }
    }

    /// (Run once with 200 million in release while this was written: no difference.)
    #[test]
    fn a_million_random_doubles_print_as_debug_does() {
        random_doubles_print_as_debug_does(1_000_000, 0x9e37_79b9_7f4a_7c15);
    }

    fn random_doubles_print_as_debug_does(n: usize, mut seed: u64) {
        for _ in 0..n {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let x = f64::from_bits(seed);
            assert_eq!(fast(x), format!("{x:?}"), "bits {seed:#x}");
        }
    }

    /// In pools of one to three threads (the writer a thread of the pool) and from a thread
    /// outside any pool, whatever the number of chunks and of chunks ahead.
    #[test]
    fn records_are_written_in_order_whatever_the_chunks() {
        let write = |n: usize| {
            let mut fast = Vec::new();
            write_records(&mut fast, n, |i, b| {
                push_int(b, i);
                b.push(b'\n');
            })
            .unwrap();
            fast
        };
        for n in [
            0,
            1,
            CHUNK - 1,
            CHUNK,
            CHUNK * AHEAD + 3,
            3 * CHUNK * AHEAD - 1,
        ] {
            let slow: String = (0..n).map(|i| format!("{i}\n")).collect();
            for threads in 1..=3 {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let fast = pool.install(|| write(n));
                assert_eq!(fast, slow.as_bytes(), "{n} records, {threads} threads");
            }
            assert_eq!(write(n), slow.as_bytes(), "{n} records, outside a pool");
        }
    }

    /// A panic while formatting a record reaches the caller, in a pool or outside one (the
    /// writer does not wait for the chunk for ever).
    #[test]
    fn a_panic_while_formatting_is_raised() {
        let write = || {
            let mut out = Vec::new();
            let _ = write_records(&mut out, 5 * CHUNK, |i, b| {
                assert!(i != 3 * CHUNK + 7, "record {i}");
                push_int(b, i);
            });
        };
        for threads in 1..=2 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let caught =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| pool.install(write)));
            assert!(caught.is_err(), "{threads} threads");
        }
        assert!(std::panic::catch_unwind(write).is_err(), "outside a pool");
    }

    /// A failed write is the error returned, after the jobs already spawned have ended.
    #[test]
    fn a_failed_write_is_returned() {
        struct Full(usize);
        impl Write for Full {
            fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
                if self.0 == 0 {
                    return Err(io::Error::other("disk full"));
                }
                self.0 -= 1;
                Ok(buf.len())
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let mut w = Full(3);
        let e = write_records(&mut w, 10 * CHUNK, |i, b| push_int(b, i)).unwrap_err();
        assert_eq!(e.to_string(), "disk full");
    }

    #[test]
    fn halfway_doubles_print_as_debug_does() {
        // fractions of a quarter above 2^50 and of a half above 2^51: 17 significant digits,
        // where the shortest forms tie
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let base = (1u64 << 50) + (seed >> 13) % (1u64 << 52);
            for q in 0..4 {
                let x = base as f64 + f64::from(q) * 0.25;
                assert_eq!(fast(x), format!("{x:?}"), "bits {:#x}", x.to_bits());
            }
            // b·2^e with an exact decimal form of up to 18 digits, where `may_tie` looks
            let e = -1 - (seed % 25) as i32;
            let b =
                1 + 2 * (seed >> 20) % (1_000_000_000_000_000_000 / 5u64.pow(e.unsigned_abs()) / 2);
            let x = b as f64 * 2f64.powi(e);
            assert_eq!(fast(x), format!("{x:?}"), "bits {:#x}", x.to_bits());
        }
    }

    fn doubles() -> impl Strategy<Value = f64> {
        prop_oneof![
            any::<u64>().prop_map(f64::from_bits),
            (0u64..1 << 52).prop_map(f64::from_bits), // subnormals
            (-1e20f64..1e20),
            (-400i32..400, 1u64..100_000).prop_map(|(e, m)| m as f64 * 10f64.powi(e)),
            (-60i32..60).prop_map(|e| 2f64.powi(e)),
            Just(-0.0),
            Just(f64::MAX),
        ]
    }

    proptest! {
        #[test]
        fn every_double_prints_as_debug_does(x in doubles()) {
            prop_assert_eq!(fast(x), format!("{x:?}"));
            prop_assert_eq!(fast(-x), format!("{:?}", -x));
        }

        #[test]
        fn integers_print_as_display_does(n in any::<u64>(), m in any::<i64>()) {
            let mut out = Vec::new();
            push_int(&mut out, n);
            push_int(&mut out, m);
            prop_assert_eq!(out, format!("{n}{m}").into_bytes());
        }
    }
}
