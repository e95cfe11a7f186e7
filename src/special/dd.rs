//! Minimal double-double arithmetic (an unevaluated sum `hi + lo` with
//! `|lo| <= ulp(hi) / 2`), used only to know the quarter period K(m) and
//! π to about 106 bits so that large arguments can be reduced exactly.
//!
//! The algorithms are the classical error-free transformations (Knuth's
//! two-sum, FMA two-product) and the Dekker/Bailey double-double operations.

/// A double-double number `hi + lo`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dd {
    pub hi: f64,
    pub lo: f64,
}

/// π/2 as a double-double.
pub(crate) const FRAC_PI_2: Dd = Dd {
    hi: core::f64::consts::FRAC_PI_2,
    lo: 6.123_233_995_736_766e-17,
};

/// π as a double-double.
pub(crate) const PI: Dd = Dd {
    hi: core::f64::consts::PI,
    lo: 1.224_646_799_147_353_2e-16,
};

/// Exact `a + b = s + e`.
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Exact `a + b = s + e`, valid when `|a| >= |b|` (or `a == 0`).
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let e = b - (s - a);
    (s, e)
}

/// Exact `a * b = p + e` (needs a correctly rounded FMA, which `mul_add` is).
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let e = a.mul_add(b, -p);
    (p, e)
}

impl Dd {
    /// The double-double equal to `x`.
    #[inline]
    pub(crate) const fn from_f64(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }

    /// `self + other`.
    #[inline]
    pub(crate) fn add(self, other: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, other.hi);
        let (t, f) = two_sum(self.lo, other.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        Dd { hi, lo }
    }

    /// `self - other`.
    #[inline]
    pub(crate) fn sub(self, other: Dd) -> Dd {
        self.add(Dd {
            hi: -other.hi,
            lo: -other.lo,
        })
    }

    /// `self * other`.
    #[inline]
    pub(crate) fn mul(self, other: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, other.hi);
        let e = e + (self.hi * other.lo + self.lo * other.hi);
        let (hi, lo) = quick_two_sum(p, e);
        Dd { hi, lo }
    }

    /// `self * x` for an `f64` factor.
    #[inline]
    pub(crate) fn mul_f64(self, x: f64) -> Dd {
        let (p, e) = two_prod(self.hi, x);
        let e = e + self.lo * x;
        let (hi, lo) = quick_two_sum(p, e);
        Dd { hi, lo }
    }

    /// `self / other` (one Newton correction of the `f64` quotient).
    #[inline]
    pub(crate) fn div(self, other: Dd) -> Dd {
        let q1 = self.hi / other.hi;
        let r = self.sub(other.mul_f64(q1));
        let q2 = r.hi / other.hi;
        let r = r.sub(other.mul_f64(q2));
        let q3 = r.hi / other.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Dd { hi, lo }.add(Dd::from_f64(q3))
    }

    /// `sqrt(self)` for `self >= 0` (one Newton correction of the `f64` root).
    #[inline]
    pub(crate) fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::from_f64(0.0);
        }
        // Keep the squared residual out of the subnormal range (and away
        // from overflow): scale by an even power of two, exactly.
        const TINY: f64 = 1.0e-200;
        const HUGE: f64 = 1.0e200;
        if self.hi < TINY || self.hi > HUGE {
            let e = (self.hi.log2() / 2.0).round() as i32;
            let down = 2f64.powi(-e);
            let scaled = Dd {
                hi: self.hi * down * down,
                lo: self.lo * down * down,
            };
            let r = scaled.sqrt();
            let up = 2f64.powi(e);
            return Dd {
                hi: r.hi * up,
                lo: r.lo * up,
            };
        }
        let s = self.hi.sqrt();
        let (p, e) = two_prod(s, s);
        // residual = self - s^2, computed exactly enough
        let r = ((self.hi - p) - e) + self.lo;
        let (hi, lo) = quick_two_sum(s, r / (2.0 * s));
        Dd { hi, lo }
    }

    /// `self / 2` (exact).
    #[inline]
    pub(crate) fn half(self) -> Dd {
        Dd {
            hi: 0.5 * self.hi,
            lo: 0.5 * self.lo,
        }
    }
}

/// The complementary parameter 1 − m as an exact double-double.
pub(crate) fn one_minus(m: f64) -> Dd {
    let (hi, lo) = two_sum(1.0, -m);
    Dd { hi, lo }
}

/// Arithmetic-geometric mean M(1, √m₁) in double-double arithmetic
/// (DLMF 19.8.1). Converges quadratically; returns 0 when `m1 == 0`.
pub(crate) fn agm_one_sqrt(m1: Dd) -> Dd {
    if m1.hi <= 0.0 {
        return Dd::from_f64(0.0);
    }
    let mut a = Dd::from_f64(1.0);
    let mut b = m1.sqrt();
    // 64 iterations cover m1 down to the smallest subnormal many times over.
    for _ in 0..64 {
        let diff = a.sub(b);
        let next_a = a.add(b).half();
        if diff.hi.abs() <= 1e-17 * a.hi {
            // |(a + b)/2 - M| <= (a - b)^2 / (8 a): below 1e-34 relative.
            return next_a;
        }
        b = a.mul(b).sqrt();
        a = next_a;
    }
    a.add(b).half()
}

/// K(m) = π / (2 M(1, √(1−m))) as a double-double (DLMF 19.8.5),
/// for a complementary parameter `0 < m1 <= 1` given as a double-double.
pub(crate) fn complete_k_dd(m1: Dd) -> Dd {
    FRAC_PI_2.div(agm_one_sqrt(m1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dd_sqrt_two_squares_back() {
        let s = Dd::from_f64(2.0).sqrt();
        let back = s.mul(s).sub(Dd::from_f64(2.0));
        assert!(back.hi.abs() < 1e-30, "{back:?}");
    }

    #[test]
    fn dd_sqrt_tiny_keeps_precision() {
        // sqrt(1e-300): the squared residual would be subnormal without the
        // internal rescaling; check sqrt(x)^2 = x after scaling up by 2^1000
        let x = Dd::from_f64(1e-300);
        let s = x.sqrt();
        let up = Dd {
            hi: s.hi * 2f64.powi(500),
            lo: s.lo * 2f64.powi(500),
        };
        let back = up.mul(up).sub(Dd::from_f64(1e-300 * 2f64.powi(1000)));
        assert!(back.hi.abs() < 1e-31, "{back:?}");
        let k = complete_k_dd(x);
        // mpmath, 400 digits: K(1 - 1e-300) = 346.77405831022674 + 8.106670740906309e-15
        assert_eq!(k.hi, 346.774_058_310_226_74);
        assert!((k.lo - 8.106_670_740_906_309e-15).abs() < 1e-29, "{k:?}");
    }

    #[test]
    fn dd_div_third() {
        let t = Dd::from_f64(1.0).div(Dd::from_f64(3.0));
        let back = t.mul_f64(3.0).sub(Dd::from_f64(1.0));
        assert!(back.hi.abs() < 1e-31, "{back:?}");
    }

    #[test]
    fn k_half_lemniscatic_dd() {
        // K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi)) = 1.854074677301371918433850347195260...
        let k = complete_k_dd(one_minus(0.5));
        let exact = Dd {
            hi: 1.854_074_677_301_371_9,
            lo: 4.220_810_632_962_078_7e-17,
        };
        let d = k.sub(exact);
        assert!(d.hi.abs() < 1e-30, "{k:?} {d:?}");
    }
}
