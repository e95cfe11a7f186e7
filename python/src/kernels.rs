//! The loops of the batched rotations on numpy arrays of vectors (M rows of N entries),
//! written so that the compiler vectorises them across rows, and compiled a second and third
//! time for AVX2 and AVX-512, used where the processor has them. No fused multiply-add: each
//! entry is the sum of the same products in the same order on every processor.

use rotorflow::algebra::{Rotor3, Rotor4};

/// `out` = Q v for every vector v of `input` (N entries each, as many in `out`); `false` if an
/// entry of `input` is NaN or infinite.
pub fn turn_all<const N: usize>(q: &[[f64; N]; N], input: &[f64], out: &mut [f64]) -> bool {
    assert_eq!(input.len(), out.len(), "one output per vector");
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, the only requirement.
            return unsafe { turn_all_avx512::<N>(q, input, out) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, the only requirement.
            return unsafe { turn_all_avx2::<N>(q, input, out) };
        }
    }
    turn_rows::<N>(q, input, out)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn turn_all_avx2<const N: usize>(q: &[[f64; N]; N], input: &[f64], out: &mut [f64]) -> bool {
    turn_rows::<N>(q, input, out)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn turn_all_avx512<const N: usize>(q: &[[f64; N]; N], input: &[f64], out: &mut [f64]) -> bool {
    turn_rows::<N>(q, input, out)
}

/// [`turn_all`] row by row: each entry the sum of Q[i][j] · x[j] in the order j = 0, 1, …,
/// N − 1; the compiler vectorises the loop across rows, with the finiteness check in the same
/// pass, so that the vectors are read from memory once.
#[inline(always)]
fn turn_rows<const N: usize>(q: &[[f64; N]; N], input: &[f64], out: &mut [f64]) -> bool {
    let (rows, _) = input.as_chunks::<N>();
    let (outs, _) = out.as_chunks_mut::<N>();
    let mut ok = true;
    for (o, x) in outs.iter_mut().zip(rows) {
        for c in x {
            ok &= c.is_finite();
        }
        for i in 0..N {
            let mut acc = 0.0;
            for j in 0..N {
                acc += q[i][j] * x[j];
            }
            o[i] = acc;
        }
    }
    ok
}

/// `out[i]` = Rᵢ vᵢ R̃ᵢ (R̃ᵢ vᵢ Rᵢ with `inverse`) for 3D rotors, `input` holding as many
/// vectors or one for all; `false` if an entry of `input` is NaN or infinite.
pub fn rotate_each3(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, the only requirement.
            return unsafe { rotate_each3_avx512(rotors, input, out, inverse) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, the only requirement.
            return unsafe { rotate_each3_avx2(rotors, input, out, inverse) };
        }
    }
    rotate_rows(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn rotate_each3_avx2(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_rows(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn rotate_each3_avx512(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_rows(rotors, input, out, inverse)
}

/// [`rotate_each3`] rotor by rotor, in a loop that the compiler vectorises across rotors:
/// the formula of `Rotor3::rotate_vector`, v + 2w (u × v) + 2 u × (u × v), term for term.
#[inline(always)]
fn rotate_rows(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    let (vectors, _) = input.as_chunks::<3>();
    let (outs, _) = out.as_chunks_mut::<3>();
    let one = vectors.len() == 1;
    let mut ok = true;
    let mut from = 0;
    #[cfg(target_arch = "x86_64")]
    if !one && !inverse && std::arch::is_x86_feature_detected!("avx512f") {
        let blocks = rotors.len().min(outs.len()) / ROWS3;
        for k in 0..blocks {
            let rows = k * ROWS3..(k + 1) * ROWS3;
            // SAFETY: the processor supports AVX-512F; the block holds 8 rotors, 8 vectors
            // and 8 outputs.
            ok &= unsafe {
                rotate_block3_avx512(
                    rotors[rows.clone()]
                        .try_into()
                        .expect("a block of 8 rotors"),
                    vectors[rows.clone()].try_into().expect("8 vectors"),
                    (&mut outs[rows]).try_into().expect("8 outputs"),
                )
            };
        }
        from = blocks * ROWS3;
    }
    for (i, (r, o)) in rotors.iter().zip(outs).enumerate().skip(from) {
        let v = &vectors[if one { 0 } else { i }];
        ok &= v[0].is_finite() & v[1].is_finite() & v[2].is_finite();
        let r = if inverse { r.inverse() } else { *r };
        let [w, ux, uy, uz] = r.to_quaternion();
        let [x, y, z] = *v;
        let tx = 2.0 * (uy * z - uz * y);
        let ty = 2.0 * (uz * x - ux * z);
        let tz = 2.0 * (ux * y - uy * x);
        *o = [
            x + w * tx + (uy * tz - uz * ty),
            y + w * ty + (uz * tx - ux * tz),
            z + w * tz + (ux * ty - uy * tx),
        ];
    }
    ok
}

/// Rows per block of [`rotate_block3_avx512`]: one AVX-512 register of each coordinate.
const ROWS3: usize = 8;

/// Eight rows of [`rotate_rows`] with AVX-512, one register per coordinate: the quaternions
/// turned from rows to coordinates by permutations (a `Rotor3` is its quaternion (w, x, y,
/// z)), the vectors gathered, the results put back in rows by permutations. Each lane does
/// the operations of the row formula in its order (no fused multiply-add), so the same
/// results to the last bit; `false` if a vector's entry is NaN or infinite.
///
/// # Safety
/// The processor must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn rotate_block3_avx512(
    rotors: &[Rotor3; ROWS3],
    vectors: &[[f64; 3]; ROWS3],
    outs: &mut [[f64; 3]; ROWS3],
) -> bool {
    use std::arch::x86_64::*;
    const _: () = assert!(size_of::<Rotor3>() == 4 * size_of::<f64>());
    // SAFETY: 8 rotors of 4 f64 are 32 f64.
    let [w, ux, uy, uz] = unsafe { load_columns4(rotors.as_ptr().cast::<f64>()) };
    let vp = vectors.as_ptr().cast::<f64>();
    let stride = _mm512_set_epi64(21, 18, 15, 12, 9, 6, 3, 0);
    // SAFETY: lane l reads coordinate c of vector l, inside the block of 8 vectors of 3 f64.
    let g = |c: usize| unsafe { _mm512_i64gather_pd::<8>(stride, vp.add(c)) };
    let (x, y, z) = (g(0), g(1), g(2));
    let finite = finite_lanes(x) & finite_lanes(y) & finite_lanes(z);
    let (m, add, sub) = (_mm512_mul_pd, _mm512_add_pd, _mm512_sub_pd);
    let two = _mm512_set1_pd(2.0);
    let tx = m(two, sub(m(uy, z), m(uz, y)));
    let ty = m(two, sub(m(uz, x), m(ux, z)));
    let tz = m(two, sub(m(ux, y), m(uy, x)));
    let ox = add(add(x, m(w, tx)), sub(m(uy, tz), m(uz, ty)));
    let oy = add(add(y, m(w, ty)), sub(m(uz, tx), m(ux, tz)));
    let oz = add(add(z, m(w, tz)), sub(m(ux, ty), m(uy, tx)));
    // Coordinates back to rows of 3: lane j of output register k is coordinate (8k + j) mod 3
    // of row (8k + j) / 3; first x and y, then z.
    let op = outs.as_mut_ptr().cast::<f64>();
    for k in 0..3 {
        let mut from_xy = [0i64; 8];
        let mut with_z = [0i64; 8];
        for j in 0..8 {
            let (row, c) = ((8 * k + j) / 3, (8 * k + j) % 3);
            from_xy[j] = match c {
                0 => row as i64,
                1 => 8 + row as i64,
                _ => 0,
            };
            with_z[j] = if c == 2 { 8 + row as i64 } else { j as i64 };
        }
        // SAFETY: each index array holds eight i64.
        let (ixy, iz) = unsafe {
            (
                _mm512_loadu_si512(from_xy.as_ptr().cast()),
                _mm512_loadu_si512(with_z.as_ptr().cast()),
            )
        };
        let t = _mm512_permutex2var_pd(ox, ixy, oy);
        // SAFETY: 8 outputs of 3 f64 are 24 f64, register k the eight from 8k.
        unsafe { _mm512_storeu_pd(op.add(8 * k), _mm512_permutex2var_pd(t, iz, oz)) };
    }
    finite == 0xff
}

/// The basis products of a product of 2ᴺ = K coefficients that sends every (e_i, e_j) to
/// e_(i ⊕ j ⊕ `offset`): e_i ∘ e_(i ⊕ k ⊕ offset) = `signs[i][k]` e_k (0 where it vanishes).
pub struct DenseSigns<const K: usize> {
    signs: [[f64; K]; K],
    offset: usize,
}

impl<const K: usize> DenseSigns<K> {
    /// The signs of `product` (a ∘ b into `out` for K coefficients each), read off its basis
    /// products; `None` unless each lands on one blade with sign ±1 and one offset serves all.
    pub fn new(product: impl Fn(&[f64], &[f64], &mut [f64])) -> Option<Self> {
        let mut signs = [[0.0; K]; K];
        let mut offset = None;
        let (mut ea, mut eb, mut out) = ([0.0; K], [0.0; K], [0.0; K]);
        for i in 0..K {
            for j in 0..K {
                ea[i] = 1.0;
                eb[j] = 1.0;
                product(&ea, &eb, &mut out);
                ea[i] = 0.0;
                eb[j] = 0.0;
                let terms: Vec<usize> = (0..K).filter(|&k| out[k] != 0.0).collect();
                let k = match terms[..] {
                    [] => continue,
                    [k] if out[k].abs() == 1.0 => k,
                    _ => return None,
                };
                if *offset.get_or_insert(i ^ j ^ k) != i ^ j ^ k {
                    return None;
                }
                signs[i][k] = out[k];
            }
        }
        Some(DenseSigns {
            signs,
            offset: offset.unwrap_or(0),
        })
    }
}

/// [`dense_product`] of 8 coefficients through [`dense_product8_avx512`] where the processor
/// has AVX-512 (the same results to the last bit), which also tells whether every operand
/// was finite; None (and nothing written) elsewhere, for the caller to check the operands
/// and run [`dense_product`].
#[inline(always)]
pub fn product8(d: &DenseSigns<8>, a: &[f64], b: &[f64], out: &mut [f64]) -> Option<bool> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        // SAFETY: the processor supports AVX-512F, the only requirement.
        return Some(unsafe { dense_product8_avx512(d, a, b, out) });
    }
    let _ = (d, a, b, out);
    None
}

/// [`product8`] for 16 coefficients, through [`dense_product16_avx512`].
#[inline(always)]
pub fn product16(d: &DenseSigns<16>, a: &[f64], b: &[f64], out: &mut [f64]) -> Option<bool> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        // SAFETY: the processor supports AVX-512F, the only requirement.
        return Some(unsafe { dense_product16_avx512(d, a, b, out) });
    }
    let _ = (d, a, b, out);
    None
}

/// Elements per block of [`dense_product`]: two AVX-512 registers per coefficient.
const LANES: usize = 16;

/// `out[m]` = `a[m]` ∘ `b[m]` for M pairs of K coefficients, the product of `d`: each block
/// of [`LANES`] elements turned into one array of lanes per coefficient, so that every basis
/// product is a multiplication and an addition of whole registers. Each `out[k]` is the sum
/// over i = 0, 1, …, K − 1 of (signs[i][k] · a_i) · b_(i ⊕ k ⊕ offset), the order and the
/// operations of the crate's product table, so its result to the last bit (up to the sign of
/// a zero).
#[inline(always)]
pub fn dense_product<const K: usize>(d: &DenseSigns<K>, a: &[f64], b: &[f64], out: &mut [f64]) {
    const { assert!(K <= 16, "blocks of at most 16 coefficients") };
    let step = LANES * K;
    let mut pad = [[0.0; LANES * 16]; 3];
    for ((ca, cb), co) in a.chunks(step).zip(b.chunks(step)).zip(out.chunks_mut(step)) {
        if co.len() == step {
            dense_block(d, ca, cb, co);
        } else {
            let n = co.len();
            let [pa, pb, po] = &mut pad;
            pa[..n].copy_from_slice(ca);
            pb[..n].copy_from_slice(cb);
            dense_block(d, &pa[..step], &pb[..step], &mut po[..step]);
            co.copy_from_slice(&po[..n]);
        }
    }
}

#[inline(always)]
fn dense_block<const K: usize>(d: &DenseSigns<K>, a: &[f64], b: &[f64], out: &mut [f64]) {
    let (a, b) = (&a[..LANES * K], &b[..LANES * K]);
    let out = &mut out[..LANES * K];
    let mut x = [[0.0; LANES]; K];
    let mut y = [[0.0; LANES]; K];
    for l in 0..LANES {
        for c in 0..K {
            x[c][l] = a[l * K + c];
            // b read with the offset: the operand of e_i for e_k is y[i ⊕ k].
            y[c][l] = b[l * K + (c ^ d.offset)];
        }
    }
    for k in 0..K {
        let mut acc = [0.0; LANES];
        for (i, xi) in x.iter().enumerate() {
            let s = d.signs[i][k];
            let yi = &y[i ^ k];
            for l in 0..LANES {
                acc[l] += s * xi[l] * yi[l];
            }
        }
        for l in 0..LANES {
            out[l * K + k] = acc[l];
        }
    }
}

/// [`dense_product`] for 16 coefficients with AVX-512: each element in two registers (blades
/// 0–7 and 8–15), no change of layout. The operand of e_i for the blades k of a half,
/// b_(i ⊕ k ⊕ offset), is a permutation of one half of b (i ⊕ k keeps the high bit of i
/// ⊕ k's half), and the same eight permutations of each half serve all sixteen i. Each
/// `out[k]` adds (signs[i][k] · a_i) · b_(i ⊕ k ⊕ offset) for i = 0, 1, …, 15 in turn, the
/// terms of [`dense_product`] in its order, so the same result to the last bit.
///
/// # Safety
/// The processor must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn dense_product16_avx512(
    d: &DenseSigns<16>,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
) -> bool {
    // In Euclidean algebras (and wherever the highest basis vector squares to +1) every row
    // of signs is the same on both halves: one multiplication serves them.
    let halves_alike = d.signs.iter().all(|row| row[..8] == row[8..]);
    // SAFETY: the processor supports AVX-512F, as the caller's.
    unsafe {
        if halves_alike {
            dense_product16_avx512_in::<true>(d, a, b, out)
        } else {
            dense_product16_avx512_in::<false>(d, a, b, out)
        }
    }
}

/// [`dense_product16_avx512`], the sign of e_i on the high half taken from the low half's
/// when `ALIKE`.
///
/// # Safety
/// The processor must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn dense_product16_avx512_in<const ALIKE: bool>(
    d: &DenseSigns<16>,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
) -> bool {
    use std::arch::x86_64::*;
    let idx = xor_permutations();
    let signs: [[__m512d; 2]; 16] = std::array::from_fn(|i| {
        let row = &d.signs[i];
        // SAFETY: each half of a row holds eight f64.
        unsafe {
            [
                _mm512_loadu_pd(row.as_ptr()),
                _mm512_loadu_pd(row.as_ptr().add(8)),
            ]
        }
    });
    let off = d.offset;
    let (a, _) = a.as_chunks::<16>();
    let (b, _) = b.as_chunks::<16>();
    let (out, _) = out.as_chunks_mut::<16>();
    let mut finite = 0xffu8;
    for ((ra, rb), ro) in a.iter().zip(b).zip(out) {
        // SAFETY: every row holds sixteen f64.
        let (blo, bhi, alo, ahi) = unsafe {
            (
                _mm512_loadu_pd(rb.as_ptr()),
                _mm512_loadu_pd(rb.as_ptr().add(8)),
                _mm512_loadu_pd(ra.as_ptr()),
                _mm512_loadu_pd(ra.as_ptr().add(8)),
            )
        };
        finite &= finite_lanes(blo) & finite_lanes(bhi) & finite_lanes(alo) & finite_lanes(ahi);
        // y[c] = b[c ⊕ offset]: the halves swapped by the offset's high bit, permuted by the rest.
        let (ylo, yhi) = if off & 8 == 0 { (blo, bhi) } else { (bhi, blo) };
        let (ylo, yhi) = (
            _mm512_permutexvar_pd(idx[off & 7], ylo),
            _mm512_permutexvar_pd(idx[off & 7], yhi),
        );
        let mut lo = _mm512_setzero_pd();
        let mut hi = _mm512_setzero_pd();
        for i in 0..16 {
            let c = i & 7;
            let (from_lo, from_hi) = if i < 8 { (ylo, yhi) } else { (yhi, ylo) };
            let w_lo = _mm512_permutexvar_pd(idx[c], from_lo);
            let w_hi = _mm512_permutexvar_pd(idx[c], from_hi);
            let x = _mm512_set1_pd(ra[i]);
            let sx_lo = _mm512_mul_pd(signs[i][0], x);
            let sx_hi = if ALIKE {
                sx_lo
            } else {
                _mm512_mul_pd(signs[i][1], x)
            };
            lo = _mm512_add_pd(lo, _mm512_mul_pd(sx_lo, w_lo));
            hi = _mm512_add_pd(hi, _mm512_mul_pd(sx_hi, w_hi));
        }
        // SAFETY: every row holds sixteen f64.
        unsafe {
            _mm512_storeu_pd(ro.as_mut_ptr(), lo);
            _mm512_storeu_pd(ro.as_mut_ptr().add(8), hi);
        }
    }
    finite == 0xff
}

/// The lanes of `x` that hold a finite number (x − x is 0 for them, NaN for ±∞ and NaN).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn finite_lanes(x: std::arch::x86_64::__m512d) -> u8 {
    use std::arch::x86_64::*;
    _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(_mm512_sub_pd(x, x), _mm512_setzero_pd())
}

/// [`dense_product`] for 8 coefficients with AVX-512: each element in one register, the
/// operand of e_i for every blade k, b_(i ⊕ k ⊕ offset), one permutation of it; the terms of
/// [`dense_product`] in its order, so the same result to the last bit.
///
/// # Safety
/// The processor must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn dense_product8_avx512(d: &DenseSigns<8>, a: &[f64], b: &[f64], out: &mut [f64]) -> bool {
    use std::arch::x86_64::*;
    let idx = xor_permutations();
    // SAFETY: each row of signs holds eight f64.
    let signs: [__m512d; 8] =
        std::array::from_fn(|i| unsafe { _mm512_loadu_pd(d.signs[i].as_ptr()) });
    let (a, _) = a.as_chunks::<8>();
    let (b, _) = b.as_chunks::<8>();
    let (out, _) = out.as_chunks_mut::<8>();
    let mut finite = 0xffu8;
    for ((ra, rb), ro) in a.iter().zip(b).zip(out) {
        // SAFETY: every row holds eight f64.
        let (xa, xb) = unsafe { (_mm512_loadu_pd(ra.as_ptr()), _mm512_loadu_pd(rb.as_ptr())) };
        finite &= finite_lanes(xa) & finite_lanes(xb);
        let y = _mm512_permutexvar_pd(idx[d.offset], xb);
        let mut acc = _mm512_setzero_pd();
        for (i, s) in signs.iter().enumerate() {
            let w = _mm512_permutexvar_pd(idx[i], y);
            acc = _mm512_add_pd(
                acc,
                _mm512_mul_pd(_mm512_mul_pd(*s, _mm512_set1_pd(ra[i])), w),
            );
        }
        // SAFETY: every row holds eight f64.
        unsafe { _mm512_storeu_pd(ro.as_mut_ptr(), acc) };
    }
    finite == 0xff
}

/// The permutations that turn eight rows of four numbers, held two rows to a register,
/// into four registers of one column each (`ROWS_LO`/`ROWS_HI` pair the rows' entries,
/// `HALF_LO`/`HALF_HI` join the halves); a transpose undoes itself, so the same four turn
/// columns back into rows.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn transpose_indices() -> [std::arch::x86_64::__m512i; 4] {
    use std::arch::x86_64::_mm512_set_epi64;
    [
        _mm512_set_epi64(13, 9, 5, 1, 12, 8, 4, 0),
        _mm512_set_epi64(15, 11, 7, 3, 14, 10, 6, 2),
        _mm512_set_epi64(11, 10, 9, 8, 3, 2, 1, 0),
        _mm512_set_epi64(15, 14, 13, 12, 7, 6, 5, 4),
    ]
}

/// Eight rows of four numbers (32 f64 from `p`, row-major) as four registers, one column
/// each: lane l of register c is entry c of row l.
///
/// # Safety
/// The processor must support AVX-512F, and `p` must point to 32 readable f64.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn load_columns4(p: *const f64) -> [std::arch::x86_64::__m512d; 4] {
    use std::arch::x86_64::*;
    let [lo, hi, first, second] = transpose_indices();
    // SAFETY: 32 readable f64, the caller's promise.
    let [r01, r23, r45, r67] = std::array::from_fn(|k| unsafe { _mm512_loadu_pd(p.add(8 * k)) });
    let (s0, s1) = (
        _mm512_permutex2var_pd(r01, lo, r23),
        _mm512_permutex2var_pd(r01, hi, r23),
    );
    let (s2, s3) = (
        _mm512_permutex2var_pd(r45, lo, r67),
        _mm512_permutex2var_pd(r45, hi, r67),
    );
    [
        _mm512_permutex2var_pd(s0, first, s2),
        _mm512_permutex2var_pd(s0, second, s2),
        _mm512_permutex2var_pd(s1, first, s3),
        _mm512_permutex2var_pd(s1, second, s3),
    ]
}

/// [`load_columns4`] undone: the four column registers stored as eight rows of four at `p`.
///
/// # Safety
/// The processor must support AVX-512F, and `p` must point to 32 writable f64.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn store_columns4(columns: [std::arch::x86_64::__m512d; 4], p: *mut f64) {
    use std::arch::x86_64::*;
    let [lo, hi, first, second] = transpose_indices();
    let [o0, o1, o2, o3] = columns;
    let (t0, t2) = (
        _mm512_permutex2var_pd(o0, first, o1),
        _mm512_permutex2var_pd(o0, second, o1),
    );
    let (t1, t3) = (
        _mm512_permutex2var_pd(o2, first, o3),
        _mm512_permutex2var_pd(o2, second, o3),
    );
    let rows = [
        _mm512_permutex2var_pd(t0, lo, t1),
        _mm512_permutex2var_pd(t0, hi, t1),
        _mm512_permutex2var_pd(t2, lo, t3),
        _mm512_permutex2var_pd(t2, hi, t3),
    ];
    for (k, r) in rows.iter().enumerate() {
        // SAFETY: 32 writable f64, the caller's promise.
        unsafe { _mm512_storeu_pd(p.add(8 * k), *r) };
    }
}

/// The permutations of eight lanes whose lane k reads lane k ⊕ c, c = 0, 1, …, 7.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn xor_permutations() -> [std::arch::x86_64::__m512i; 8] {
    std::array::from_fn(|c| {
        let c = c as i64;
        std::arch::x86_64::_mm512_set_epi64(7 ^ c, 6 ^ c, 5 ^ c, 4 ^ c, 3 ^ c, 2 ^ c, 1 ^ c, c)
    })
}

/// `out[i]` = Rᵢ vᵢ R̃ᵢ (R̃ᵢ vᵢ Rᵢ with `inverse`) for 4D rotors, `input` holding as many
/// vectors or one for all; `false` if an entry of `input` is NaN or infinite.
pub fn rotate_each4(rotors: &[Rotor4], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, the only requirement.
            return unsafe { rotate_each4_avx512(rotors, input, out, inverse) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, the only requirement.
            return unsafe { rotate_each4_avx2(rotors, input, out, inverse) };
        }
    }
    rotate_rows4(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn rotate_each4_avx2(rotors: &[Rotor4], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_rows4(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn rotate_each4_avx512(rotors: &[Rotor4], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_rows4(rotors, input, out, inverse)
}

/// Hamilton's product of two quaternions, the formula of the crate's scalar quaternion
/// product term for term.
#[inline(always)]
fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    let [w1, x1, y1, z1] = a;
    let [w2, x2, y2, z2] = b;
    [
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ]
}

/// Rows per block of [`rotate_rows4`]: one AVX-512 register of each coordinate.
const ROWS4: usize = 8;

/// [`rotate_each4`] rotor by rotor: `Rotor4::rotate_vector`'s two quaternion products
/// (a x) b, a = (m₀, −m₁, −m₂, m₃) and b = Q̄₊ of the pair (Q₊, Q₋), term for term. Blocks of
/// [`ROWS4`] rows are first laid out one array per coordinate, so that the compiler runs the
/// products on whole registers (a row of 8 + 4 numbers does not fit the lanes otherwise); each
/// lane does the scalar formula's operations in its order, so the same results to the last bit.
#[inline(always)]
fn rotate_rows4(rotors: &[Rotor4], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    // One loop for each case, without a test per row.
    match (inverse, input.len() == 4) {
        (false, false) => rotate_rows4_in::<false, false>(rotors, input, out),
        (false, true) => rotate_rows4_in::<false, true>(rotors, input, out),
        (true, false) => rotate_rows4_in::<true, false>(rotors, input, out),
        (true, true) => rotate_rows4_in::<true, true>(rotors, input, out),
    }
}

#[inline(always)]
fn rotate_rows4_in<const INVERSE: bool, const ONE: bool>(
    rotors: &[Rotor4],
    input: &[f64],
    out: &mut [f64],
) -> bool {
    let (vectors, _) = input.as_chunks::<4>();
    let (outs, _) = out.as_chunks_mut::<4>();
    let vector = |i: usize| &vectors[if ONE { 0 } else { i }];
    let factors = factors4::<INVERSE>;
    let mut ok = true;
    let blocks = rotors.len().min(outs.len()) / ROWS4;
    #[cfg(target_arch = "x86_64")]
    if !ONE && !INVERSE && std::arch::is_x86_feature_detected!("avx512f") {
        for k in 0..blocks {
            let rows = &rotors[k * ROWS4..(k + 1) * ROWS4];
            let (xs, os) = (&vectors[k * ROWS4..], &mut outs[k * ROWS4..]);
            // SAFETY: the processor supports AVX-512F; the block holds 8 rotors, 8 vectors and 8 outputs.
            ok &= unsafe {
                rotate_block4_avx512(
                    rows.try_into().expect("a block of 8 rotors"),
                    xs[..ROWS4].try_into().expect("8 vectors"),
                    (&mut os[..ROWS4]).try_into().expect("8 outputs"),
                )
            };
        }
        return rotate_rest4::<INVERSE, ONE>(rotors, vectors, outs, blocks * ROWS4) & ok;
    }
    for k in 0..blocks {
        let base = k * ROWS4;
        let mut a = [[0.0; ROWS4]; 4];
        let mut b = [[0.0; ROWS4]; 4];
        let mut x = [[0.0; ROWS4]; 4];
        for l in 0..ROWS4 {
            let (fa, fb) = factors(&rotors[base + l]);
            let v = vector(base + l);
            for c in 0..4 {
                a[c][l] = fa[c];
                b[c][l] = fb[c];
                x[c][l] = v[c];
                ok &= v[c].is_finite();
            }
        }
        let mut o = [[0.0; ROWS4]; 4];
        for l in 0..ROWS4 {
            let ax = quat_mul(
                [a[0][l], a[1][l], a[2][l], a[3][l]],
                [x[0][l], x[1][l], x[2][l], x[3][l]],
            );
            let r = quat_mul(ax, [b[0][l], b[1][l], b[2][l], b[3][l]]);
            for c in 0..4 {
                o[c][l] = r[c];
            }
        }
        for l in 0..ROWS4 {
            outs[base + l] = [o[0][l], o[1][l], o[2][l], o[3][l]];
        }
    }
    rotate_rest4::<INVERSE, ONE>(rotors, vectors, outs, blocks * ROWS4) & ok
}

/// The factors (a, b) of `Rotor4::rotate_vector`'s (a x) b for R (R⁻¹ with `INVERSE`).
#[inline(always)]
fn factors4<const INVERSE: bool>(r: &Rotor4) -> ([f64; 4], [f64; 4]) {
    let r = if INVERSE { r.inverse() } else { *r };
    let (p, m) = r.to_quaternion_pair();
    ([m[0], -m[1], -m[2], m[3]], [p[0], -p[1], -p[2], -p[3]])
}

/// The rows of [`rotate_rows4_in`] from `from` on, one at a time.
#[inline(always)]
fn rotate_rest4<const INVERSE: bool, const ONE: bool>(
    rotors: &[Rotor4],
    vectors: &[[f64; 4]],
    outs: &mut [[f64; 4]],
    from: usize,
) -> bool {
    let mut ok = true;
    for (i, (r, o)) in rotors.iter().zip(outs.iter_mut()).enumerate().skip(from) {
        let v = &vectors[if ONE { 0 } else { i }];
        ok &= v.iter().fold(true, |ok, c| ok & c.is_finite());
        let (a, b) = factors4::<INVERSE>(r);
        *o = quat_mul(quat_mul(a, *v), b);
    }
    ok
}

/// Eight rows of [`rotate_rows4`] with AVX-512, one register per coordinate: the rotors'
/// coordinates gathered (a `Rotor4` is Q₊ then Q₋), the vectors and results turned between
/// rows and coordinates by permutations. Each lane does the operations of [`quat_mul`] in
/// its order (no fused multiply-add), so the same results to the last bit; `false` if a
/// vector's entry is NaN or infinite.
///
/// # Safety
/// The processor must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn rotate_block4_avx512(
    rotors: &[Rotor4; ROWS4],
    vectors: &[[f64; 4]; ROWS4],
    outs: &mut [[f64; 4]; ROWS4],
) -> bool {
    use std::arch::x86_64::*;
    const _: () = assert!(size_of::<Rotor4>() == 8 * size_of::<f64>());
    let base = rotors.as_ptr().cast::<f64>();
    let stride = _mm512_set_epi64(56, 48, 40, 32, 24, 16, 8, 0);
    // SAFETY: lane l reads coordinate c of rotor l, inside the block of 8 rotors of 8 f64.
    let g = |c: usize| unsafe { _mm512_i64gather_pd::<8>(stride, base.add(c)) };
    let neg = _mm512_set1_pd(-1.0);
    let (p0, p1, p2, p3) = (g(0), g(1), g(2), g(3));
    let (m0, m1, m2, m3) = (g(4), g(5), g(6), g(7));
    let a = [m0, _mm512_mul_pd(neg, m1), _mm512_mul_pd(neg, m2), m3];
    let b = [
        p0,
        _mm512_mul_pd(neg, p1),
        _mm512_mul_pd(neg, p2),
        _mm512_mul_pd(neg, p3),
    ];
    // SAFETY: 8 vectors of 4 f64 are 32 f64.
    let x = unsafe { load_columns4(vectors.as_ptr().cast::<f64>()) };
    let finite = x.iter().fold(0xff, |ok, c| ok & finite_lanes(*c));
    let mul = |u: [__m512d; 4], v: [__m512d; 4]| {
        let [w1, x1, y1, z1] = u;
        let [w2, x2, y2, z2] = v;
        let m = _mm512_mul_pd;
        let (add, sub) = (_mm512_add_pd, _mm512_sub_pd);
        [
            sub(sub(sub(m(w1, w2), m(x1, x2)), m(y1, y2)), m(z1, z2)),
            sub(add(add(m(w1, x2), m(x1, w2)), m(y1, z2)), m(z1, y2)),
            add(add(sub(m(w1, y2), m(x1, z2)), m(y1, w2)), m(z1, x2)),
            add(sub(add(m(w1, z2), m(x1, y2)), m(y1, x2)), m(z1, w2)),
        ]
    };
    // SAFETY: 8 outputs of 4 f64 are 32 f64.
    unsafe { store_columns4(mul(mul(a, x), b), outs.as_mut_ptr().cast::<f64>()) };
    finite == 0xff
}
