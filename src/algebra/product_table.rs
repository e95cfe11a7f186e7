//! One bilinear product of an algebra as a table of its basis products, applied to many pairs
//! of dense coefficient arrays at once.

use super::{AlgebraError, Multivector, Product, Signature, blade};

/// The largest dimension of a [`ProductTable`]: 4⁸ = 65 536 basis products.
pub const PRODUCT_TABLE_MAX_DIM: usize = 8;

/// Elements per block of [`ProductTable::apply_batch`]: each block is turned into one array
/// per blade, so that every entry of the table runs over contiguous lanes.
const BLOCK: usize = 64;

/// The largest dimension whose products also come as a dense sign matrix, applied by a kernel
/// whose sizes are known at compile time (2ᴺ ≤ 16 coefficients).
const DENSE_MAX_DIM: usize = 4;

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
/// entry across the block. Up to N = 4 the same basis products are also kept as a dense
/// 2ᴺ × 2ᴺ matrix of signs (every product of blades tabulated here sends e_a, e_b to the
/// blade a ⊕ b ⊕ c for one mask c), applied by kernels whose sizes are known at compile time;
/// they add the same terms in the same order.
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
    /// The same products as dense signs, up to [`DENSE_MAX_DIM`].
    dense: Option<Dense>,
    /// Whether the product is the geometric product, whose sandwiches of an even element
    /// with a vector are vectors (see [`ProductTable::sandwich_batch`]).
    geometric: bool,
}

/// A product whose basis products all send (e_a, e_b) to the blade k = a ⊕ b ⊕ `offset`:
/// e_i ∘ e_(i ⊕ k ⊕ offset) = `signs[i · 2ᴺ + k]` e_k, zero where the product vanishes.
#[derive(Clone, Debug, PartialEq)]
struct Dense {
    offset: usize,
    signs: Vec<f64>,
}

impl Dense {
    /// The dense form of `entries`, when the algebra is small enough and every entry has the
    /// same offset.
    fn new(dim: usize, entries: &[(u32, u32, u32, f64)]) -> Option<Self> {
        if dim > DENSE_MAX_DIM {
            return None;
        }
        let size = 1usize << dim;
        let offset = entries
            .first()
            .map_or(0, |&(a, b, k, _)| (a ^ b ^ k) as usize);
        let mut signs = vec![0.0; size * size];
        for &(a, b, k, f) in entries {
            if (a ^ b ^ k) as usize != offset {
                return None;
            }
            signs[a as usize * size + k as usize] = f;
        }
        Some(Dense { offset, signs })
    }
}

impl ProductTable {
    /// The table of `kind` in the algebra `sig`.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] above [`PRODUCT_TABLE_MAX_DIM`].
    pub fn new(sig: Signature, kind: Product) -> Result<Self, AlgebraError> {
        let mut table = Self::from_basis_products(sig, |a, b| a.try_product(b, kind))?;
        table.geometric = kind == Product::Geometric;
        Ok(table)
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
        let dense = Dense::new(n, &entries);
        Ok(ProductTable {
            sig,
            entries,
            dense,
            geometric: false,
        })
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
    /// Inlined, so that a caller compiled for wider vector instructions (a function with
    /// `#[target_feature]`) gets the kernels compiled for them too.
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless the three slices hold the same whole
    /// number of elements.
    #[inline]
    pub fn apply_batch(&self, a: &[f64], b: &[f64], out: &mut [f64]) -> Result<(), AlgebraError> {
        let size = 1usize << self.sig.dim();
        let elements = a.len() / size;
        self.check([a.len(), b.len(), out.len()], elements)?;
        match &self.dense {
            Some(d) => match size {
                1 => dense_batch::<1, 1>(d, a, b, out),
                2 => dense_batch::<2, 2>(d, a, b, out),
                4 => dense_batch::<4, 4>(d, a, b, out),
                8 => dense_batch::<8, 8>(d, a, b, out),
                _ => dense_batch::<16, 4>(d, a, b, out),
            },
            None => self.table_batch(a, b, out),
        }
        Ok(())
    }

    /// `out[m]` = (`a[m]` ∘ `x[m]`) ∘ ã`[m]`, ã the reverse of a: with the geometric product's
    /// table, the sandwiches V X Ṽ of M versors V with M elements X, summed as
    /// [`Multivector`]'s `Versor::apply` sums them (V X first).
    ///
    /// In 3D and 4D, the geometric product's table runs each block of 64 elements whose
    /// versors are even (every odd coefficient exactly zero) and whose operands are vectors
    /// (every coefficient outside grade 1 exactly zero) through a kernel that reads and adds
    /// only the non-zero terms: a rotor on a vector. V X Ṽ is then odd and equal to its own
    /// reverse, so a vector (its grade-3 part vanishes exactly and is written as zero, where
    /// the dense sums leave round-off). With finite coefficients its vector part is the dense
    /// sums' to the last bit (up to the sign of a zero): the same non-zero terms, added in
    /// the same order. Other blocks keep the dense kernels.
    ///
    /// # Errors
    /// As [`ProductTable::apply_batch`].
    #[inline]
    pub fn sandwich_batch(
        &self,
        a: &[f64],
        x: &[f64],
        out: &mut [f64],
    ) -> Result<(), AlgebraError> {
        let size = 1usize << self.sig.dim();
        let elements = a.len() / size;
        self.check([a.len(), x.len(), out.len()], elements)?;
        match &self.dense {
            Some(d) => match size {
                8 if self.geometric => {
                    even_on_vector_batch::<8, 8, VEC3_TERMS, VEC3_TERMS>(d, a, x, out)
                }
                16 if self.geometric => {
                    even_on_vector_batch::<16, 4, VEC4_TERMS, VEC4_TERMS>(d, a, x, out)
                }
                1 => dense_sandwich::<1, 1>(d, a, x, out),
                2 => dense_sandwich::<2, 2>(d, a, x, out),
                4 => dense_sandwich::<4, 4>(d, a, x, out),
                8 => dense_sandwich::<8, 8>(d, a, x, out),
                _ => dense_sandwich::<16, 4>(d, a, x, out),
            },
            None => {
                let step = BLOCK * size;
                let mut ax = vec![0.0; step];
                let mut reversed = vec![0.0; step];
                for ((ca, cx), co) in a.chunks(step).zip(x.chunks(step)).zip(out.chunks_mut(step)) {
                    let n = ca.len();
                    self.table_batch(ca, cx, &mut ax[..n]);
                    for (r, (blade, c)) in reversed[..n].iter_mut().zip(ca.iter().enumerate()) {
                        *r = c * blade::reverse_sign(blade::grade((blade % size) as u64));
                    }
                    self.table_batch(&ax[..n], &reversed[..n], co);
                }
            }
        }
        Ok(())
    }

    /// The batch through the list of entries, in blocks of [`BLOCK`] elements.
    fn table_batch(&self, a: &[f64], b: &[f64], out: &mut [f64]) {
        let size = 1usize << self.sig.dim();
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
    }
}

/// `out[k]` = Σᵢ `signs[i][k]` · `x[i]` · `y[i ⊕ k]` for one element, i in increasing order
/// (the order of the table's entries for this k), `y` already read with the table's offset.
/// The K × K terms go by tiles of T × T, whose loops the compiler unrolls, so that the
/// coefficients stay in registers and each row of signs is one vector.
#[inline(always)]
fn dense_element<const K: usize, const T: usize>(
    signs: &[[f64; K]; K],
    x: &[f64; K],
    y: &[f64; K],
    out: &mut [f64; K],
) {
    let tile = |v: &[f64; K], h: usize| -> [f64; T] {
        v[h * T..h * T + T].try_into().expect("T divides K")
    };
    for kh in 0..K / T {
        let mut acc = [0.0; T];
        for ih in 0..K / T {
            // i ⊕ k = (ih ⊕ kh) T + (il ⊕ kl): the tile of y that this tile of x meets.
            let (xh, yh) = (tile(x, ih), tile(y, ih ^ kh));
            for (il, &xi) in xh.iter().enumerate() {
                let s = tile(&signs[ih * T + il], kh);
                for kl in 0..T {
                    acc[kl] += s[kl] * xi * yh[il ^ kl];
                }
            }
        }
        out[kh * T..kh * T + T].copy_from_slice(&acc);
    }
}

/// The signs of a dense table of 2ᴺ = K coefficients as a K × K array.
#[inline(always)]
fn dense_signs<const K: usize>(d: &Dense) -> &[[f64; K]; K] {
    d.signs
        .as_chunks::<K>()
        .0
        .try_into()
        .expect("a dense table holds 2ᴺ × 2ᴺ signs")
}

/// One element of K coefficients of a batch, read with a blade offset.
#[inline(always)]
fn element<const K: usize>(row: &[f64], offset: usize) -> [f64; K] {
    let row: &[f64; K] = row.try_into().expect("rows of K coefficients");
    if offset == 0 {
        *row
    } else {
        std::array::from_fn(|j| row[j ^ offset])
    }
}

#[inline(always)]
fn dense_batch<const K: usize, const T: usize>(d: &Dense, a: &[f64], b: &[f64], out: &mut [f64]) {
    let signs = dense_signs::<K>(d);
    for ((ra, rb), ro) in a
        .chunks_exact(K)
        .zip(b.chunks_exact(K))
        .zip(out.chunks_exact_mut(K))
    {
        let o: &mut [f64; K] = ro.try_into().expect("rows of K coefficients");
        dense_element::<K, T>(signs, &element(ra, 0), &element(rb, d.offset), o);
    }
}

#[inline(always)]
fn dense_sandwich<const K: usize, const T: usize>(
    d: &Dense,
    a: &[f64],
    x: &[f64],
    out: &mut [f64],
) {
    let signs = dense_signs::<K>(d);
    // The reverse's sign of each blade, in the order in which the right operand is read.
    let reverse: [f64; K] =
        std::array::from_fn(|j| blade::reverse_sign(blade::grade((j ^ d.offset) as u64)));
    let mut ax = [0.0; K];
    for ((ra, rx), ro) in a
        .chunks_exact(K)
        .zip(x.chunks_exact(K))
        .zip(out.chunks_exact_mut(K))
    {
        let o: &mut [f64; K] = ro.try_into().expect("rows of K coefficients");
        let va = element::<K>(ra, 0);
        dense_element::<K, T>(signs, &va, &element(rx, d.offset), &mut ax);
        let mut reversed = element::<K>(ra, d.offset);
        for (c, r) in reversed.iter_mut().zip(reverse) {
            *c *= r;
        }
        dense_element::<K, T>(signs, &ax, &reversed, o);
    }
}

/// `$body` once for each `$t` = 0, 1, …, 31 (a constant in each copy): the terms of a
/// sandwich are indices known at compile time, and written out one by one they keep every
/// coefficient in a register, which a loop of 32 terms (more than the compiler unrolls by
/// itself) would not.
macro_rules! unrolled {
    ($t:ident $body:block) => {
        unrolled!(@ $t $body [0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15
            16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31])
    };
    (@ $t:ident $body:block [$($n:literal)*]) => {
        $({
            let $t: usize = $n;
            $body
        })*
    };
}

/// The terms of V X and of (V X) Ṽ for V even and X a vector in 3D (4 even blades times 3
/// vectors; 3 vectors out, 4 odd blades each) and in 4D (8 × 4; 4 × 8).
const VEC3_TERMS: usize = 12;
const VEC4_TERMS: usize = 32;

/// The basis products (i, j, k), e_i e_j ∝ e_k = e_(i ⊕ j), of a sandwich of an even element
/// with a vector in 2ᴺ = K coefficients, ordered by k, then i (the order of the dense sums):
/// with `first`, those of V X (i even, j of grade 1); otherwise those of (V X) Ṽ that land
/// on a vector (i odd, j even, k of grade 1).
const fn even_on_vector_terms<const K: usize, const L: usize>(
    first: bool,
) -> [(usize, usize, usize); L] {
    let mut terms = [(0, 0, 0); L];
    let mut n = 0;
    let mut k = 0;
    while k < K {
        let mut i = 0;
        while i < K {
            let j = i ^ k;
            let (gi, gj, gk) = (i.count_ones(), j.count_ones(), k.count_ones());
            let wanted = if first {
                gi % 2 == 0 && gj == 1
            } else {
                gi % 2 == 1 && gj % 2 == 0 && gk == 1
            };
            if wanted {
                terms[n] = (i, j, k);
                n += 1;
            }
            i += 1;
        }
        k += 1;
    }
    assert!(n == L, "the count of terms of the sandwich");
    terms
}

/// Whether every element of a block is an even versor and a vector (exact zeros elsewhere).
#[inline(always)]
fn even_and_vector<const K: usize>(a: &[f64], x: &[f64]) -> bool {
    a.chunks_exact(K).zip(x.chunks_exact(K)).all(|(ra, rx)| {
        (0..K).all(|j| {
            let g = j.count_ones();
            (g % 2 == 0 || ra[j] == 0.0) && (g == 1 || rx[j] == 0.0)
        })
    })
}

/// [`ProductTable::sandwich_batch`] of the geometric product with K = 2ᴺ coefficients, in
/// blocks of [`BLOCK`] elements: through the terms of a rotor on a vector where a block is
/// one, through [`dense_sandwich`] otherwise.
#[inline(always)]
fn even_on_vector_batch<const K: usize, const T: usize, const L1: usize, const L2: usize>(
    d: &Dense,
    a: &[f64],
    x: &[f64],
    out: &mut [f64],
) {
    const { assert!(L1 <= 32 && L2 <= 32, "unrolled! writes out 32 terms") };
    let first: [(usize, usize, usize); L1] = const { even_on_vector_terms::<K, L1>(true) };
    let second: [(usize, usize, usize); L2] = const { even_on_vector_terms::<K, L2>(false) };
    let signs = dense_signs::<K>(d);
    // The geometric product has offset 0: e_i e_j = signs[i][k] e_k with k = i ⊕ j. The
    // reverse's sign of Ṽ's blade j goes into the sign of each term of the second product.
    let s1: [f64; L1] = std::array::from_fn(|t| {
        let (i, _, k) = first[t];
        signs[i][k]
    });
    let s2: [f64; L2] = std::array::from_fn(|t| {
        let (i, j, k) = second[t];
        signs[i][k] * blade::reverse_sign(blade::grade(j as u64))
    });
    let step = BLOCK * K;
    for ((ca, cx), co) in a.chunks(step).zip(x.chunks(step)).zip(out.chunks_mut(step)) {
        if !even_and_vector::<K>(ca, cx) {
            dense_sandwich::<K, T>(d, ca, cx, co);
            continue;
        }
        for ((ra, rx), ro) in ca
            .chunks_exact(K)
            .zip(cx.chunks_exact(K))
            .zip(co.chunks_exact_mut(K))
        {
            let va: &[f64; K] = ra.try_into().expect("rows of K coefficients");
            let vx: &[f64; K] = rx.try_into().expect("rows of K coefficients");
            let mut ax = [0.0; K];
            unrolled!(t {
                if t < L1 {
                    let (i, j, k) = first[t];
                    ax[k] += s1[t] * va[i] * vx[j];
                }
            });
            let mut o = [0.0; K];
            unrolled!(t {
                if t < L2 {
                    let (i, j, k) = second[t];
                    o[k] += s2[t] * ax[i] * va[j];
                }
            });
            ro.copy_from_slice(&o);
        }
    }
}
