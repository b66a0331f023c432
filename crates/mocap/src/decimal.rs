//! Reading the decimals motion files are made of (`-17.3198`, `0.0000`, `5`),
//! shared by the BVH and AMC readers: a fast path that gives the same f32 as a
//! general parser (`fast_float2`) for the forms it accepts, and declines the rest.

use crate::text::is_blank;

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

/// Fast path for the numbers mocap files are made of: `[+-]digits[.digits]` with a
/// digit string below 2^24 and no exponent. Then the value is `m / 10^e` with `m < 2^24` and
/// `10^e` both exact in f32, so one IEEE division gives the correctly rounded result
/// (one multiplication in f64 for up to 7 decimals: see [`TENTHS`]).
/// Anything else (`None`) goes to the general parser.
#[inline]
pub(crate) fn parse_short(s: &[u8]) -> Option<(f32, usize)> {
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
        while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|&d| d < 10) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
            i += 1;
        }
        fraction_digits = i - fraction_start;
    }
    let ends_cleanly = s.get(i).is_none_or(|&b| is_blank(b) || b == b'\n' || b == b'\r');
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

#[cfg(test)]
mod tests {
    use super::parse_short;

    #[test]
    fn short_decimals_match_the_general_parser_bit_for_bit() {
        let cases = ["0", "-0", "+1.5", "17.8693", "-17.3198", ".0083333", "5.", "-0.000000", "9999999", "0.1234567", "123.4567", "-.5", "16777215", "1.6777215", "0.0000000001"];
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
        for c in ["1e5", "123456789", "1.23456789", "16777216", ".", "-", "1.2.3", "nan", "1x", "0.00000000001", "00000000000000000000001"] {
            assert!(parse_short(c.as_bytes()).is_none(), "{c}");
        }
    }
}
