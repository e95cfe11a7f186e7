//! The loops of the batched rotations on numpy arrays of vectors (M rows of N entries),
//! written so that the compiler vectorises them across rows, and compiled a second and third
//! time for AVX2 and AVX-512, used where the processor has them. No fused multiply-add: each
//! entry is the sum of the same products in the same order on every processor.

use crate::arrays::all_finite;
use rotorflow::algebra::Rotor3;

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
    rotate_lanes::<2>(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn rotate_each3_avx2(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_lanes::<4>(rotors, input, out, inverse)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn rotate_each3_avx512(rotors: &[Rotor3], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
    rotate_lanes::<8>(rotors, input, out, inverse)
}

/// [`rotate_each3`] L rotors at a time, each quaternion and vector component in an array of L
/// lanes: the formula of `Rotor3::rotate_vector`, v + 2w (u × v) + 2 u × (u × v), term for
/// term, so the same result to the last bit.
#[inline(always)]
fn rotate_lanes<const L: usize>(
    rotors: &[Rotor3],
    input: &[f64],
    out: &mut [f64],
    inverse: bool,
) -> bool {
    let step = usize::from(input.len() > 3);
    let mut ok = true;
    for (b, (rb, ob)) in rotors.chunks(L).zip(out.chunks_mut(3 * L)).enumerate() {
        let (mut w, mut ux, mut uy, mut uz) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        let (mut x, mut y, mut z) = ([0.0; L], [0.0; L], [0.0; L]);
        for (l, r) in rb.iter().enumerate() {
            let r = if inverse { r.inverse() } else { *r };
            [w[l], ux[l], uy[l], uz[l]] = r.to_quaternion();
            let i = 3 * (b * L + l) * step;
            [x[l], y[l], z[l]] = [input[i], input[i + 1], input[i + 2]];
        }
        ok &= all_finite(&x) & all_finite(&y) & all_finite(&z);
        let (mut ox, mut oy, mut oz) = ([0.0; L], [0.0; L], [0.0; L]);
        for l in 0..L {
            let tx = 2.0 * (uy[l] * z[l] - uz[l] * y[l]);
            let ty = 2.0 * (uz[l] * x[l] - ux[l] * z[l]);
            let tz = 2.0 * (ux[l] * y[l] - uy[l] * x[l]);
            ox[l] = x[l] + w[l] * tx + (uy[l] * tz - uz[l] * ty);
            oy[l] = y[l] + w[l] * ty + (uz[l] * tx - ux[l] * tz);
            oz[l] = z[l] + w[l] * tz + (ux[l] * ty - uy[l] * tx);
        }
        for (l, o) in ob.chunks_exact_mut(3).enumerate() {
            o.copy_from_slice(&[ox[l], oy[l], oz[l]]);
        }
    }
    ok
}
