//! Deterministic mutations of a body's files: bytes flipped, lines cut, dropped or repeated,
//! numbers replaced by NaN, inf, -1, 0, 1e308, huge integers, words or binary junk. One seed
//! gives one mutation, so a case that ever fails is replayed by its seed alone.

/// xorshift64*: a small, fixed generator (no dependency; the same cases on every machine).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        // Never zero; nearby seeds spread apart.
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// What replaces a number: the values readers are most often wrong about.
pub const REPLACEMENTS: [&str; 14] = [
    "NaN",
    "inf",
    "-inf",
    "-1",
    "0",
    "1e308",
    "-1e308",
    "4294967297",
    "18446744073709551615",
    "99999999999999999999999",
    "2147483648",
    "word",
    "1.5",
    "\u{1}\u{ff}\u{0}",
];

/// One mutation of `bytes`, chosen by `rng`, and its description.
pub fn mutate(bytes: &[u8], rng: &mut Rng) -> (Vec<u8>, String) {
    if bytes.is_empty() {
        return (b"junk".to_vec(), "empty file given junk".into());
    }
    let lines = line_starts(bytes);
    match rng.below(8) {
        0 => {
            let mut out = bytes.to_vec();
            let at = rng.below(out.len());
            let mask = 1 + rng.below(255) as u8;
            out[at] ^= mask;
            (out, format!("byte {at} xor {mask:#04x}"))
        }
        1 => {
            let line = rng.below(lines.len());
            let cut = lines[line] + rng.below(line_end(bytes, &lines, line) - lines[line] + 1);
            (
                bytes[..cut].to_vec(),
                format!("cut at byte {cut} (line {})", line + 1),
            )
        }
        2 => {
            let line = rng.below(lines.len());
            let (from, to) = (lines[line], line_end_with_newline(bytes, &lines, line));
            let mut out = bytes[..from].to_vec();
            out.extend_from_slice(&bytes[to..]);
            (out, format!("line {} dropped", line + 1))
        }
        3 => {
            let line = rng.below(lines.len());
            let (from, to) = (lines[line], line_end_with_newline(bytes, &lines, line));
            let times = 1 + rng.below(3);
            let mut out = bytes[..to].to_vec();
            for _ in 0..times {
                out.extend_from_slice(&bytes[from..to]);
            }
            out.extend_from_slice(&bytes[to..]);
            (out, format!("line {} repeated {times}×", line + 1))
        }
        4..=6 => {
            let numbers = number_spans(bytes);
            if numbers.is_empty() {
                return junk(bytes, rng);
            }
            // Early numbers (headers: sizes, counts) more often than their share.
            let pick = if rng.below(2) == 0 {
                rng.below(numbers.len().min(24))
            } else {
                rng.below(numbers.len())
            };
            let (from, to) = numbers[pick];
            let with = REPLACEMENTS[rng.below(REPLACEMENTS.len())];
            let mut out = bytes[..from].to_vec();
            out.extend_from_slice(with.as_bytes());
            out.extend_from_slice(&bytes[to..]);
            (
                out,
                format!(
                    "number `{}` at byte {from} replaced by `{}`",
                    String::from_utf8_lossy(&bytes[from..to]),
                    with.escape_debug()
                ),
            )
        }
        _ => {
            if rng.below(2) == 0 {
                junk(bytes, rng)
            } else {
                binary_integer(bytes, rng)
            }
        }
    }
}

/// Binary junk inserted at a random byte.
fn junk(bytes: &[u8], rng: &mut Rng) -> (Vec<u8>, String) {
    let at = rng.below(bytes.len() + 1);
    let len = 1 + rng.below(16);
    let mut out = bytes[..at].to_vec();
    out.extend((0..len).map(|_| rng.next() as u8));
    out.extend_from_slice(&bytes[at..]);
    (out, format!("{len} junk bytes at byte {at}"))
}

/// A 4-byte little-endian integer of a binary record (OP4's lengths, sizes and indices)
/// overwritten by a huge, negative or zero one.
fn binary_integer(bytes: &[u8], rng: &mut Rng) -> (Vec<u8>, String) {
    if bytes.len() < 4 {
        return junk(bytes, rng);
    }
    let words = bytes.len() / 4;
    let word = if rng.below(2) == 0 {
        rng.below(words.min(16))
    } else {
        rng.below(words)
    };
    let value: u32 = [u32::MAX, 0x7fff_ffff, 0x8000_0000, 0, 1, 0x0100_0000][rng.below(6)];
    let mut out = bytes.to_vec();
    out[4 * word..4 * word + 4].copy_from_slice(&value.to_le_bytes());
    (out, format!("word {word} set to {value:#x}"))
}

/// Byte offsets where each line starts.
fn line_starts(bytes: &[u8]) -> Vec<usize> {
    let mut starts = vec![0];
    starts.extend(
        bytes
            .iter()
            .enumerate()
            .filter(|&(i, &b)| b == b'\n' && i + 1 < bytes.len())
            .map(|(i, _)| i + 1),
    );
    starts
}

/// Where line `line` ends, its newline excluded.
fn line_end(bytes: &[u8], lines: &[usize], line: usize) -> usize {
    let next = lines.get(line + 1).copied().unwrap_or(bytes.len());
    if next > lines[line] && bytes[next - 1] == b'\n' {
        next - 1
    } else {
        next
    }
}

/// Where line `line` ends, its newline included.
fn line_end_with_newline(bytes: &[u8], lines: &[usize], line: usize) -> usize {
    lines.get(line + 1).copied().unwrap_or(bytes.len())
}

/// Byte spans of the numbers in a text: runs of digits with their sign, point and exponent.
fn number_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let mut from = i;
            while from > 0 && matches!(bytes[from - 1], b'-' | b'+' | b'.') {
                from -= 1;
            }
            let mut to = i;
            while to < bytes.len()
                && (bytes[to].is_ascii_digit()
                    || matches!(bytes[to], b'.' | b'e' | b'E' | b'd' | b'D')
                    || (matches!(bytes[to], b'-' | b'+')
                        && matches!(bytes[to - 1], b'e' | b'E' | b'd' | b'D')))
            {
                to += 1;
            }
            spans.push((from, to));
            i = to;
        } else {
            i += 1;
        }
    }
    spans
}
