//! Reading the decimals motion files are made of (`-17.3198`, `0.0000`, `5`),
//! shared by the BVH and AMC readers: a fast path that gives the same f32 as a
//! general parser (`fast_float2`) for the forms it accepts, and declines the rest.

use crate::formats::text::{is_blank, is_eol};

/// `10^-e` for `e` up to 7, as the nearest f64s.
///
/// For `m < 2^24` and `e <= 7`, `(m as f64 * TENTHS[e]) as f32` is the correctly
/// rounded f32 of `m / 10^e`, as `m as f32 / 10^e as f32` is: the product is
/// within 2^-52 of the quotient (relative), and a quotient that is not an f32
/// lies at least `1 / (10^e · 2^25)` > 2^-49 (relative) from every point halfway
/// between two f32s, so both round the same way. (Checked for every `m` and `e`
/// once; a test checks a sample.) A multiplication instead of a division, which
/// takes several times as long.
const TENTHS: [f64; 8] = [1e0, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7];
/// Powers of ten exactly representable in f32.
const POW10: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// `0x01` in every byte of a word.
const ONES: u64 = 0x0101_0101_0101_0101;

/// Powers of ten below 10^8 as integers.
const POW10_INT: [u64; 8] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000];

/// How many of the eight bytes of `word` (first byte lowest) are ASCII digits
/// before the first one that is not (8 if all are).
#[inline]
fn digit_run(word: u64) -> usize {
    // Bit 7 of each byte set where the byte is in b'0'..=b'9'; the high bit is
    // cleared first so that no byte's addition carries into the next.
    let low7 = word & (ONES * 0x7f);
    let at_least_zero = low7.wrapping_add(ONES * (0x80 - u64::from(b'0')));
    let above_nine = low7.wrapping_add(ONES * (0x7f - u64::from(b'9')));
    let digits = at_least_zero & !above_nine & !word & (ONES * 0x80);
    ((!digits & (ONES * 0x80)).trailing_zeros() / 8) as usize
}

/// The value of the first `n` (below 8) bytes of `word` (first byte lowest),
/// which are ASCII digits.
#[inline]
fn digits_value(word: u64, n: usize) -> u64 {
    // Digit values in the first n bytes (a digit byte never borrows), moved up
    // so that the bytes after them fall off and zeros lead: eight digits.
    let v = word.wrapping_sub(ONES * u64::from(b'0')).checked_shl(((8 - n.min(8)) * 8) as u32).unwrap_or(0);
    // Pairs, then fours, then all eight; no lane overflows into the next.
    let pairs = v.wrapping_mul(10).wrapping_add(v >> 8) & 0x00ff_00ff_00ff_00ff;
    let fours = pairs.wrapping_mul(100).wrapping_add(pairs >> 16) & 0x0000_ffff_0000_ffff;
    fours.wrapping_mul(10_000).wrapping_add(fours >> 32) & 0xffff_ffff
}

/// Fast path for the numbers mocap files are made of: `[+-]digits[.digits]` with a
/// digit string below 2^24 and no exponent. Then the value is `m / 10^e` with `m < 2^24` and
/// `10^e` both exact in f32, so one IEEE division gives the correctly rounded result
/// (one multiplication in f64 for up to 7 decimals: see [`TENTHS`]).
/// Anything else (`None`) goes to the general parser.
///
/// With `words`, up to seven fraction digits are read from one 8-byte word
/// (see [`Decimals`]). Always inlined: called for every value, and the
/// WebAssembly build left it a call.
#[inline(always)]
fn parse_short_with(s: &[u8], words: bool) -> Option<(f32, usize)> {
    // The sign without a branch: signs vary from number to number.
    let first = s.first().copied();
    let negative = first == Some(b'-');
    let mut i = usize::from(negative || first == Some(b'+'));
    // Integer digits, then fraction digits, each in a tight loop.
    let mut mantissa: u64 = 0;
    let int_start = i;
    while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|&d| d < 10) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
        i += 1;
    }
    let int_digits = i - int_start;
    let mut fraction_digits = 0;
    if s.get(i) == Some(&b'.') {
        i += 1;
        let fraction_start = i;
        let word = if words {
            s.get(i..i + 8).and_then(|w| <[u8; 8]>::try_from(w).ok()).map(u64::from_le_bytes)
        } else {
            None
        };
        let run = word.map_or(8, digit_run);
        if let (Some(word), true) = (word, run < 8) {
            mantissa = mantissa.wrapping_mul(POW10_INT[run]).wrapping_add(digits_value(word, run));
            i += run;
        } else {
            while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|&d| d < 10) {
                mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
                i += 1;
            }
        }
        fraction_digits = i - fraction_start;
    }
    let ends_cleanly = s.get(i).is_none_or(|&b| is_blank(b) || is_eol(b));
    // 19 digits cannot overflow u64; m < 2^24 is exact in f32.
    let total = int_digits + fraction_digits;
    if total == 0 || total > 19 || mantissa >= 1 << 24 || !ends_cleanly {
        return None;
    }
    let magnitude = match TENTHS.get(fraction_digits) {
        Some(tenths) => (mantissa as f64 * tenths) as f32,
        None => mantissa as f32 / *POW10.get(fraction_digits)?,
    };
    Some((f32::from_bits(magnitude.to_bits() | (u32::from(negative) << 31)), i))
}

/// How a file's short decimals are read: the fraction digits byte by byte, or
/// up to seven of them from one 8-byte word.
///
/// A byte loop over the digits ends with a branch on how many there are. Where
/// every number has as many decimals (`%.4f`, as most BVH exporters write) the
/// processor predicts it and runs ahead to the next number; where the count
/// varies (`%g`, six significant digits, as in CMU's AMC files) it mispredicts
/// at nearly every number, and the word with bit arithmetic is faster
/// (01_06.amc: 6.3-6.7 -> 5.6-6.1 ms on one thread). The word makes the first kind
/// slower (the 27 MB BVH take: 37.7 -> 46.9 ms): the next number's start then
/// waits for that arithmetic. So the way is chosen from a sample of the text
/// ([`Decimals::for_text`]); both give the same values.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Decimals {
    words: bool,
}

impl Decimals {
    /// Bytes looked at to choose.
    const SAMPLE_BYTES: usize = 4096;

    /// The way for the numbers of `text`, from its first few thousand bytes:
    /// the word where the number of decimals changes from one number to the
    /// next for more than a quarter of them. Words that are not numbers (AMC's
    /// bone names) are passed over.
    pub(crate) fn for_text(text: &[u8]) -> Decimals {
        let sample = text.get(..Self::SAMPLE_BYTES).unwrap_or(text);
        let numbers = sample
            .split(|&b| is_blank(b) || is_eol(b))
            .filter(|t| t.first().is_some_and(|&b| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'.')));
        let (mut count, mut changes, mut last) = (0usize, 0usize, None);
        for token in numbers {
            let decimals = token
                .iter()
                .position(|&b| b == b'.')
                .map_or(0, |p| token.iter().skip(p + 1).take_while(|b| b.is_ascii_digit()).count());
            changes += usize::from(last.is_some_and(|l| l != decimals));
            last = Some(decimals);
            count += 1;
        }
        Decimals { words: changes * 4 > count }
    }

    /// The short decimal at the start of `s` ([`parse_short_with`]), the
    /// fraction digits read this way; `None` for anything else.
    #[inline]
    pub(crate) fn read(self, s: &[u8]) -> Option<(f32, usize)> {
        parse_short_with(s, self.words)
    }
}

#[cfg(test)]
mod tests {
    use super::{Decimals, parse_short_with};

    /// A short decimal read byte by byte (the default way).
    fn parse_short(s: &[u8]) -> Option<(f32, usize)> {
        Decimals::default().read(s)
    }

    #[test]
    fn short_decimals_match_the_general_parser_bit_for_bit() {
        let cases = [
            "0",
            "-0",
            "+1.5",
            "17.8693",
            "-17.3198",
            ".0083333",
            "5.",
            "-0.000000",
            "9999999",
            "0.1234567",
            "123.4567",
            "-.5",
            "16777215",
            "1.6777215",
            "0.0000000001",
        ];
        for c in cases {
            let (v, used) = parse_short(c.as_bytes()).unwrap_or_else(|| panic!("{c}"));
            let expected: f32 = c.parse().unwrap();
            assert_eq!((v.to_bits(), used), (expected.to_bits(), c.len()), "{c}");
        }
        // Exhaustive over short patterns: every 4-digit value with each dot position.
        for n in 0..10_000u32 {
            for dot in 0..=4 {
                let digits = format!("{n:04}");
                let text = format!("{}.{}", &digits[..dot], &digits[dot..]);
                let (v, _) = parse_short(text.as_bytes()).unwrap();
                assert_eq!(v.to_bits(), text.parse::<f32>().unwrap().to_bits(), "{text}");
            }
        }
    }

    proptest::proptest! {
        #[test]
        fn short_decimals_agree_with_std(sign in "[-+]?", int in "[0-9]{0,9}", frac in proptest::option::of("[0-9]{0,11}")) {
            let text = format!("{sign}{int}{}", frac.as_ref().map(|f| format!(".{f}")).unwrap_or_default());
            if let Some((v, used)) = parse_short(text.as_bytes()) {
                let expected: f32 = text.parse().unwrap();
                proptest::prop_assert_eq!((v.to_bits(), used), (expected.to_bits(), text.len()), "{}", text);
            }
        }
    }

    #[test]
    fn tenths_round_like_a_division() {
        for (e, tenths) in super::TENTHS.iter().enumerate() {
            for m in (0..1u64 << 24).step_by(61).chain(0..30_000) {
                let by_division = m as f32 / super::POW10[e];
                assert_eq!(((m as f64 * tenths) as f32).to_bits(), by_division.to_bits(), "{m}e-{e}");
            }
        }
    }

    #[test]
    fn long_or_exponent_forms_fall_back() {
        for c in [
            "1e5",
            "123456789",
            "1.23456789",
            "16777216",
            ".",
            "-",
            "1.2.3",
            "nan",
            "1x",
            "0.00000000001",
            "00000000000000000000001",
        ] {
            assert!(parse_short(c.as_bytes()).is_none(), "{c}");
        }
    }

    /// Both ways of reading fraction digits, with bytes enough after the number
    /// for the word, against std.
    fn both_ways_match_std(text: &str) {
        let expected: f32 = text.parse().unwrap();
        for tail in ["", " 1.5 -2.25 0.125", "\n7", "\t0.0000001 9"] {
            let padded = format!("{text}{tail}");
            for words in [false, true] {
                let (v, used) =
                    parse_short_with(padded.as_bytes(), words).unwrap_or_else(|| panic!("{text:?} words {words}"));
                assert_eq!((v.to_bits(), used), (expected.to_bits(), text.len()), "{text:?} words {words}");
            }
        }
    }

    #[test]
    fn fraction_words_read_like_the_loop() {
        for c in [
            "0",
            "-0",
            "+1.5",
            "17.8693",
            "-17.3198",
            ".0083333",
            "5.",
            "-0.000000",
            "0.1234567",
            "123.4567",
            "-.5",
            "1.6777215",
            "0.0000000001",
            "1677721.5",
        ] {
            both_ways_match_std(c);
        }
        for n in 0..10_000u32 {
            for dot in 0..=4 {
                let digits = format!("{n:04}");
                both_ways_match_std(&format!("-{}.{}", &digits[..dot], &digits[dot..]));
            }
        }
        // Eight or more decimals go to the loop; a non-digit ends the run.
        for words in [false, true] {
            assert!(
                parse_short_with(b"0.12345678 1 2 3", words).is_some_and(|(v, used)| v == 0.123_456_78 && used == 10)
            );
            assert!(parse_short_with(b"1.25x 1 2 3 4 5", words).is_none());
            assert!(parse_short_with(b"1.5e3 1 2 3 4 5", words).is_none());
        }
    }

    proptest::proptest! {
        #[test]
        fn fraction_words_agree_with_std(sign in "[-+]?", int in "[0-9]{0,7}", frac in "[0-9]{0,9}", tail in "[ \t\n][0-9 .]{0,12}") {
            let text = format!("{sign}{int}.{frac}");
            let padded = format!("{text}{tail}");
            let by_loop = parse_short_with(padded.as_bytes(), false);
            let by_words = parse_short_with(padded.as_bytes(), true);
            proptest::prop_assert_eq!(by_loop.map(|(v, u)| (v.to_bits(), u)), by_words.map(|(v, u)| (v.to_bits(), u)), "{}", padded);
            if let Some((v, used)) = by_words {
                let expected: f32 = text.parse().unwrap();
                proptest::prop_assert_eq!((v.to_bits(), used), (expected.to_bits(), text.len()));
            }
        }
    }

    #[test]
    fn the_way_follows_the_decimals() {
        let fixed = b"9.3722 17.8693 -17.3198 -3.2316 -7.5970 -2.0168 0.0000 0.0000\n9.3728 17.8666 -17.3192 -3.1009";
        assert!(!Decimals::for_text(fixed).words);
        let varying = b"root 9.37216 17.0763 -17.3198 -0.90059 6.61511 -0.0813\nlowerback 1.41797 1.15581 -3.4\nupperback 2.94419 2.06517 2.07727 -8.8994 16.7239 2.80366";
        assert!(Decimals::for_text(varying).words);
        assert!(!Decimals::for_text(b"").words);
    }
}
