//! Exponents that are integers in the common case: raised by multiplication, in straight-line
//! code that vectorizes, and by `powf` otherwise.

/// The squaring exponent n, with integers (the case in Anjyo & Hiramitsu 2003) raised by
/// multiplication.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exponent {
    /// An integer n from 1 to [`Exponent::MAX_INTEGER`].
    Integer(i32),
    /// Any other n > 0.
    Real(f32),
}

impl Exponent {
    /// The largest n raised by multiplication.
    pub const MAX_INTEGER: i32 = (1 << Self::INTEGER_BITS) - 1;

    /// The bits of an integer n.
    pub(crate) const INTEGER_BITS: u32 = 7;

    /// The exponent `n` (> 0), an [`Exponent::Integer`] where it is one.
    #[must_use]
    pub fn new(n: f32) -> Self {
        if n.fract() == 0.0 && (1.0..=Self::MAX_INTEGER as f32).contains(&n) {
            Exponent::Integer(n as i32)
        } else {
            Exponent::Real(n)
        }
    }

    /// `x^n`: by multiplication for an integer n, else `powf`.
    #[inline(always)]
    #[must_use]
    pub fn pow(self, x: f32) -> f32 {
        let mut x = [x];
        self.pow_each(&mut x);
        x[0]
    }

    /// Each `x` raised to n, as [`pow`](Self::pow) does, with the kind of n matched once: the
    /// loop over `xs` for an integer n vectorizes.
    #[inline(always)]
    pub fn pow_each(self, xs: &mut [f32]) {
        match self {
            // Up to 15, four bits.
            Exponent::Integer(k) if k < 16 => xs.iter_mut().for_each(|x| *x = int_pow::<4>(*x, k)),
            Exponent::Integer(k) => xs
                .iter_mut()
                .for_each(|x| *x = int_pow::<{ Self::INTEGER_BITS }>(*x, k)),
            Exponent::Real(r) => xs.iter_mut().for_each(|x| *x = x.powf(r)),
        }
    }
}

/// `x^n` for an integer `1 ≤ n < 2^BITS`, by binary exponentiation over `BITS` bits
/// (straight-line code, so loops calling it vectorize). Bits of n above them would only square
/// the base further, so any `BITS` that holds n gives the same value.
#[inline(always)]
pub(crate) fn int_pow<const BITS: u32>(x: f32, n: i32) -> f32 {
    let (mut result, mut base) = (1.0, x);
    for bit in 0..BITS {
        if (n >> bit) & 1 == 1 {
            result *= base;
        }
        base *= base;
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_exponent_matches_powf() {
        for n in [1.0_f32, 2.0, 3.0, 7.0, 12.0, 64.0, 127.0] {
            let Exponent::Integer(k) = Exponent::new(n) else {
                panic!("{n} not an integer exponent")
            };
            for x in [0.0_f32, 0.3, 0.9, 1.0] {
                let (got, want) = (int_pow::<{ Exponent::INTEGER_BITS }>(x, k), x.powf(n));
                assert!(
                    (got - want).abs() <= 1e-6 * want.max(1e-30),
                    "{x}^{n}: {got} vs {want}"
                );
                // Over fewer bits that still hold n: the same value, bit for bit.
                if k < 4 {
                    assert_eq!(int_pow::<2>(x, k).to_bits(), got.to_bits(), "{x}^{n}");
                }
                if k < 16 {
                    assert_eq!(int_pow::<4>(x, k).to_bits(), got.to_bits(), "{x}^{n}");
                }
            }
        }
        assert_eq!(Exponent::new(2.5), Exponent::Real(2.5));
        assert_eq!(Exponent::new(128.0), Exponent::Real(128.0));
    }
}
