//! One bilinear product of an algebra as a table of its basis products, applied to many pairs
//! of dense coefficient arrays at once.

use super::{AlgebraError, Multivector, Product, Signature};

/// The largest dimension of a [`ProductTable`]: 4⁸ = 65 536 basis products.
pub const PRODUCT_TABLE_MAX_DIM: usize = 8;

/// Elements per block of [`ProductTable::apply_batch`]: each block is turned into one array
/// per blade, so that every entry of the table runs over contiguous lanes.
const BLOCK: usize = 64;

/// A bilinear product of Cl(p, q, r) as the list of its non-zero basis products
/// e_a ∘ e_b = f e_k (f = ±1), made once from the product itself and then applied to dense
/// coefficient arrays (blade bit-mask order) without recomputing a sign.
///
/// The entries are ordered by a, then b, the order of [`Multivector::try_product`]'s own
/// loop, and each adds `f · a_a · b_b`: the answer equals that of the product to the last bit
/// (up to the sign of a zero), except for the regressive product and the inner product,
/// which the multivector sums in another order (through complements, or as three products)
/// and the table agrees with to round-off. [`ProductTable::apply_batch`] runs through many pairs at once,
/// in blocks whose coefficients sit one array per blade, so that the compiler vectorises each
/// entry across the block.
///
/// ```
/// use rotorflow::algebra::{Multivector, Product, ProductTable, Signature};
/// let sig = Signature::new(2, 1, 0)?;
/// let table = ProductTable::new(sig, Product::Geometric)?;
/// let a: Vec<f64> = (0..8).map(|i| i as f64 - 2.5).collect();
/// let b: Vec<f64> = (0..8).map(|i| 0.5 * i as f64).collect();
/// let mut out = [0.0; 8];
/// table.apply(&a, &b, &mut out)?;
/// let (ma, mb) = (Multivector::from_coefficients(sig, &a)?, Multivector::from_coefficients(sig, &b)?);
/// assert_eq!(out, ma.geometric(&mb).as_slice());
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ProductTable {
    sig: Signature,
    /// (a, b, k, f): e_a ∘ e_b = f e_k, ordered by a, then b.
    entries: Vec<(u32, u32, u32, f64)>,
}

impl ProductTable {
    /// The table of `kind` in the algebra `sig`.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] above [`PRODUCT_TABLE_MAX_DIM`].
    pub fn new(sig: Signature, kind: Product) -> Result<Self, AlgebraError> {
        Self::from_basis_products(sig, |a, b| a.try_product(b, kind))
    }

    /// The table of the inner product [`Multivector::inner`] (the operator `|`).
    ///
    /// # Errors
    /// As [`ProductTable::new`].
    pub fn inner(sig: Signature) -> Result<Self, AlgebraError> {
        Self::from_basis_products(sig, |a, b| Ok(a.inner(b)))
    }

    fn from_basis_products(
        sig: Signature,
        product: impl Fn(&Multivector, &Multivector) -> Result<Multivector, AlgebraError>,
    ) -> Result<Self, AlgebraError> {
        let n = sig.dim();
        if n > PRODUCT_TABLE_MAX_DIM {
            return Err(AlgebraError::DimensionTooLarge {
                what: "product table",
                dim: n,
                max: PRODUCT_TABLE_MAX_DIM,
            });
        }
        let size = 1u64 << n;
        let blades: Vec<Multivector> = (0..size)
            .map(|m| Multivector::try_basis_blade(sig, m))
            .collect::<Result<_, _>>()?;
        let mut entries = Vec::new();
        for (a, ea) in blades.iter().enumerate() {
            for (b, eb) in blades.iter().enumerate() {
                for (k, f) in product(ea, eb)?.terms() {
                    entries.push((a as u32, b as u32, k as u32, f));
                }
            }
        }
        Ok(ProductTable { sig, entries })
    }

    /// The algebra of the table.
    pub fn signature(&self) -> Signature {
        self.sig
    }

    /// The number of non-zero basis products.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no basis product is non-zero (a product that vanishes on the whole algebra).
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    fn check(&self, lens: [usize; 3], elements: usize) -> Result<(), AlgebraError> {
        let expected = elements << self.sig.dim();
        for found in lens {
            if found != expected {
                return Err(AlgebraError::WrongComponentCount {
                    what: "coefficients of the product table",
                    expected,
                    found,
                });
            }
        }
        Ok(())
    }

    /// `out` = a ∘ b for the 2ᴺ coefficients of one pair.
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless every slice has 2ᴺ coefficients.
    pub fn apply(&self, a: &[f64], b: &[f64], out: &mut [f64]) -> Result<(), AlgebraError> {
        self.check([a.len(), b.len(), out.len()], 1)?;
        out.fill(0.0);
        for &(i, j, k, f) in &self.entries {
            out[k as usize] += f * a[i as usize] * b[j as usize];
        }
        Ok(())
    }

    /// `out[m]` = `a[m]` ∘ `b[m]` for M pairs stored one after the other (M · 2ᴺ coefficients
    /// in each slice), equal to M calls of [`ProductTable::apply`].
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless the three slices hold the same whole
    /// number of elements.
    pub fn apply_batch(&self, a: &[f64], b: &[f64], out: &mut [f64]) -> Result<(), AlgebraError> {
        let size = 1usize << self.sig.dim();
        let elements = a.len() / size;
        self.check([a.len(), b.len(), out.len()], elements)?;
        // One array of BLOCK lanes per blade for each operand and the result.
        let mut sa = vec![[0.0f64; BLOCK]; size];
        let mut sb = vec![[0.0f64; BLOCK]; size];
        let mut so = vec![[0.0f64; BLOCK]; size];
        let step = BLOCK * size;
        for ((ca, cb), co) in a.chunks(step).zip(b.chunks(step)).zip(out.chunks_mut(step)) {
            let lanes = ca.len() / size;
            for (m, (ea, eb)) in ca.chunks_exact(size).zip(cb.chunks_exact(size)).enumerate() {
                for ((lane_a, lane_b), (&xa, &xb)) in
                    sa.iter_mut().zip(sb.iter_mut()).zip(ea.iter().zip(eb))
                {
                    lane_a[m] = xa;
                    lane_b[m] = xb;
                }
            }
            so.iter_mut().for_each(|lane| lane.fill(0.0));
            for &(i, j, k, f) in &self.entries {
                let (x, y) = (&sa[i as usize], &sb[j as usize]);
                for ((o, xm), ym) in so[k as usize].iter_mut().zip(x).zip(y) {
                    *o += f * xm * ym;
                }
            }
            for (m, eo) in co.chunks_exact_mut(size).take(lanes).enumerate() {
                for (e, lane) in eo.iter_mut().zip(&so) {
                    *e = lane[m];
                }
            }
        }
        Ok(())
    }
}
