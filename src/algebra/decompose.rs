//! The invariant decomposition of a bivector into orthogonal commuting simple planes.
//!
//! Every bivector B of ℝᴺ is a sum B = Σₖ θₖ uₖ∧vₖ of at most ⌊N/2⌋ simple bivectors whose
//! planes (uₖ, vₖ orthonormal) are mutually orthogonal, so the terms commute
//! (Roelfs & De Keninck, "Graded Symmetry Groups: Plane and Simple", Adv. Appl. Clifford Alg.
//! 2023; in matrix terms the real normal form of the skew matrix \[B\]).
//!
//! # Method, and why
//! The closed-form route through the wedge powers of B (the reference `clifford`
//! implementation) divides by differences of the θₖ² and fails for isoclinic input
//! (θ₁ = θ₂), losing digits near it. rotorflow instead works on the skew matrix A = \[B\]:
//! - N ≤ 3: B is simple; the plane comes from the largest column of A.
//! - N = 4: the self-dual / anti-self-dual split so(4) = so(3) ⊕ so(3). With
//!   α, β ∈ ℝ³ the coordinates of B's two halves, θ₁,₂ = |α| ± |β| and the planes are
//!   (F ± G)/2 for the unit isoclinic directions F, G. No division by θ₁ − θ₂ occurs; an
//!   exactly isoclinic B (β = 0) simply takes any G.
//! - N ≥ 5: deflation. Scale A by a power of two (exact), take the top eigenvector w of the
//!   symmetric AᵀA, pair it with u = A w / |A w| (so A w = θ u exactly up to rounding, even
//!   when w mixes nearly equal planes), split off the plane (w, u) with a Householder basis of
//!   its complement, and recurse on the restricted matrix until N ≤ 4. Up to N = 8 the
//!   matrices are inline and the eigenproblem runs on nalgebra's fixed-size matrices, so the
//!   decomposition (and the rotor exponential of N ≤ 6 built on it) never allocates. Taking only the top
//!   plane per level keeps the error at the level of eps·|B|: mixing between nearly equal
//!   planes (error ε/gap) multiplies a residual of size gap.
//!
//! Planes whose magnitude falls below 8·N·ε times the largest are dropped (numerical rank).

use super::bivector::{bivector_len, pairs};
use super::{Bivector, Vector};
use crate::numeric::dense::{self, Mat8, Vec8};
use crate::numeric::{exponent_of, householder_complement, ldexp};
use smallvec::{SmallVec, smallvec};

/// One simple component θ u∧v of a bivector: a magnitude θ > 0 and an orthonormal pair
/// (u, v) spanning its plane, oriented so that \[B\] v = θ u.
#[derive(Clone, Debug, PartialEq)]
pub struct SimplePlane {
    magnitude: f64,
    u: Vector,
    v: Vector,
}

impl SimplePlane {
    /// Returns the magnitude θ > 0 (for an angular velocity, the rate in this plane).
    #[inline]
    pub fn magnitude(&self) -> f64 {
        self.magnitude
    }

    /// Returns the first unit vector u of the plane.
    #[inline]
    pub fn u(&self) -> &Vector {
        &self.u
    }

    /// Returns the second unit vector v of the plane (orthogonal to u).
    #[inline]
    pub fn v(&self) -> &Vector {
        &self.v
    }

    /// Returns the unit simple bivector u∧v.
    pub fn unit_bivector(&self) -> Bivector {
        self.u.wedge(&self.v)
    }

    /// Returns the simple bivector θ u∧v.
    pub fn bivector(&self) -> Bivector {
        self.unit_bivector() * self.magnitude
    }
}

/// The invariant decomposition of a bivector: its simple, mutually orthogonal, commuting
/// components, largest magnitude first. See the module documentation for the method.
#[derive(Clone, Debug, PartialEq)]
pub struct Decomposition {
    dim: usize,
    planes: Vec<SimplePlane>,
}

impl Decomposition {
    /// Returns the dimension N of the space.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the simple components, largest magnitude first.
    pub fn planes(&self) -> &[SimplePlane] {
        &self.planes
    }

    /// Returns the magnitudes θₖ, largest first.
    pub fn magnitudes(&self) -> Vec<f64> {
        self.planes.iter().map(|p| p.magnitude).collect()
    }

    /// Returns the number of planes (half the rank of the skew matrix).
    pub fn len(&self) -> usize {
        self.planes.len()
    }

    /// Returns true for the zero bivector (no planes).
    pub fn is_empty(&self) -> bool {
        self.planes.is_empty()
    }

    /// Returns Σₖ θₖ uₖ∧vₖ, which equals the decomposed bivector up to rounding.
    pub fn reconstruct(&self) -> Bivector {
        let mut b = Bivector::zero(self.dim);
        for p in &self.planes {
            b += &p.bivector();
        }
        b
    }
}

impl Bivector {
    /// Returns the invariant decomposition of B into at most ⌊N/2⌋ orthogonal, commuting simple
    /// bivectors with their magnitudes (exact for isoclinic, near-isoclinic, rank-deficient,
    /// tiny and huge input; see [`crate::algebra::decompose`]).
    ///
    /// ```
    /// use rotorflow::algebra::Bivector;
    /// // The isoclinic double rotation 0.7(e12 + e34): two planes of equal magnitude.
    /// let b = Bivector::from_components(4, &[0.7, 0.0, 0.0, 0.0, 0.0, 0.7])?;
    /// let d = b.decompose();
    /// assert_eq!(d.len(), 2);
    /// for theta in d.magnitudes() {
    ///     assert!((theta - 0.7).abs() < 1e-15);
    /// }
    /// assert!((&d.reconstruct() - &b).norm() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    pub fn decompose(&self) -> Decomposition {
        let n = self.dim();
        let mut raw = decompose_components(n, self.as_slice());
        raw.sort_by(|a, b| b.theta.total_cmp(&a.theta));
        Decomposition {
            dim: n,
            planes: raw
                .into_iter()
                .map(|p| SimplePlane {
                    magnitude: p.theta,
                    u: Vector::from_storage(p.u),
                    v: Vector::from_storage(p.v),
                })
                .collect(),
        }
    }

    /// Returns true if B is simple (a single plane, B ∧ B = 0) to within a relative tolerance:
    /// the second plane's magnitude is at most `tolerance` times the first.
    pub fn is_simple(&self, tolerance: f64) -> bool {
        let m = self.decompose().magnitudes();
        m.len() < 2 || m[1] <= tolerance * m[0]
    }
}

/// The planes of a decomposition, inline up to N = 9 (at most four planes).
pub(crate) type Planes = SmallVec<[RawPlane; 4]>;

/// A plane in raw form: B ⊇ θ u∧v with \[B\] v = θ u.
#[derive(Clone, Debug)]
pub(crate) struct RawPlane {
    pub theta: f64,
    pub u: SmallVec<[f64; 8]>,
    pub v: SmallVec<[f64; 8]>,
}

/// Decomposes packed bivector components of dimension `n`.
pub(crate) fn decompose_components(n: usize, comps: &[f64]) -> Planes {
    debug_assert_eq!(comps.len(), bivector_len(n));
    let scale = comps.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if n < 2 || scale == 0.0 || !scale.is_finite() {
        return Planes::new();
    }
    // Scale exactly by a power of two so that the largest component lies in [1, 2).
    let e = exponent_of(scale);
    let scaled: SmallVec<[f64; 28]> = comps.iter().map(|&c| ldexp(c, -e)).collect();
    let mut planes = match n {
        2 => plane_2d(&scaled),
        3 => plane_3d(&scaled),
        4 => planes_4d(&scaled),
        _ => planes_deflation(n, &scaled),
    };
    let max_theta = planes.iter().fold(0.0f64, |m, p| m.max(p.theta));
    let tol = 8.0 * n as f64 * f64::EPSILON * max_theta;
    planes.retain(|p| p.theta > tol);
    for p in &mut planes {
        p.theta = ldexp(p.theta, e);
    }
    planes
}

fn plane_2d(c: &[f64]) -> Planes {
    let b = c[0];
    if b == 0.0 {
        return Planes::new();
    }
    // θ e1∧e2 with [B] e2 = θ e1: u = e1, v = e2 (swapped for negative b).
    let (u, v) = if b > 0.0 {
        ([1.0, 0.0], [0.0, 1.0])
    } else {
        ([0.0, 1.0], [1.0, 0.0])
    };
    smallvec![RawPlane {
        theta: b.abs(),
        u: SmallVec::from_slice(&u),
        v: SmallVec::from_slice(&v),
    }]
}

fn plane_3d(c: &[f64]) -> Planes {
    let theta = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    if theta == 0.0 {
        return Planes::new();
    }
    let unit: SmallVec<[f64; 28]> = c.iter().map(|x| x / theta).collect();
    let (u, v) = unit_plane_vectors(3, &unit);
    smallvec![RawPlane { theta, u, v }]
}

/// Splits the components (12, 13, 14, 23, 24, 34) of a 4D bivector into its self-dual and
/// anti-self-dual coordinates: B = Σ αₖ fₖ + Σ βₖ gₖ with f = (e12+e34, e13−e24, e14+e23) and
/// g = (e12−e34, e13+e24, e14−e23), the two so(3) halves of so(4).
pub(crate) fn self_dual_split(c: &[f64]) -> ([f64; 3], [f64; 3]) {
    let (b12, b13, b14, b23, b24, b34) = (c[0], c[1], c[2], c[3], c[4], c[5]);
    (
        [0.5 * (b12 + b34), 0.5 * (b13 - b24), 0.5 * (b14 + b23)],
        [0.5 * (b12 - b34), 0.5 * (b13 + b24), 0.5 * (b14 - b23)],
    )
}

/// The inverse of [`self_dual_split`]: the components Σ αₖ fₖ + Σ βₖ gₖ.
pub(crate) fn self_dual_join(a: [f64; 3], b: [f64; 3]) -> [f64; 6] {
    [
        a[0] + b[0],
        a[1] + b[1],
        a[2] + b[2],
        a[2] - b[2],
        -a[1] + b[1],
        a[0] - b[0],
    ]
}

/// The 4D closed form through the self-dual / anti-self-dual split.
fn planes_4d(c: &[f64]) -> Planes {
    let (alpha, beta) = self_dual_split(c);
    // Scaled norms: squaring a part of size ~1e-162 lands in the subnormals, where the norm
    // (and the unit direction built from it) loses most of its bits: an isoclinic pair with a
    // 1e-161 perturbation would give a rotor off by 1e-3.
    let na = crate::numeric::scaled_norm(&alpha);
    let nb = crate::numeric::scaled_norm(&beta);
    // Unit directions; an exactly (anti-)self-dual B leaves the other direction free. Divide
    // by the largest component first: a subnormal norm has too few bits to divide by.
    let unit = |x: [f64; 3], n: f64| {
        if n > 0.0 {
            if (1e-150..=1e150).contains(&n) {
                return [x[0] / n, x[1] / n, x[2] / n];
            }
            let m = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let y = [x[0] / m, x[1] / m, x[2] / m];
            let k = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
            [y[0] / k, y[1] / k, y[2] / k]
        } else {
            [1.0, 0.0, 0.0]
        }
    };
    let a = unit(alpha, na);
    let g = unit(beta, nb);
    let f_comp = self_dual_join(a, [0.0; 3]);
    let g_comp = self_dual_join([0.0; 3], g);
    let p1: [f64; 6] = std::array::from_fn(|k| 0.5 * (f_comp[k] + g_comp[k]));
    let mut p2: [f64; 6] = std::array::from_fn(|k| 0.5 * (f_comp[k] - g_comp[k]));
    let theta1 = na + nb;
    let mut theta2 = na - nb;
    if theta2 < 0.0 {
        theta2 = -theta2;
        p2.iter_mut().for_each(|x| *x = -*x);
    }
    let mut out = Planes::new();
    let (u1, v1) = unit_plane_vectors(4, &p1);
    if theta1 > 0.0 {
        out.push(RawPlane {
            theta: theta1,
            u: u1.clone(),
            v: v1.clone(),
        });
    }
    if theta2 > 0.0 {
        let (mut u2, mut v2) = unit_plane_vectors(4, &p2);
        // Remove the rounding-level overlap with the first plane.
        for w in [&mut u2, &mut v2] {
            for basis in [&u1, &v1] {
                let d: f64 = w.iter().zip(basis.iter()).map(|(a, b)| a * b).sum();
                w.iter_mut()
                    .zip(basis.iter())
                    .for_each(|(x, b)| *x -= d * b);
            }
        }
        let d: f64 = v2.iter().zip(u2.iter()).map(|(a, b)| a * b).sum();
        let nu = normalize_in_place(&mut u2);
        v2.iter_mut()
            .zip(u2.iter())
            .for_each(|(x, b)| *x -= d / nu * b);
        normalize_in_place(&mut v2);
        out.push(RawPlane {
            theta: theta2,
            u: u2,
            v: v2,
        });
    }
    out
}

fn normalize_in_place(x: &mut [f64]) -> f64 {
    // Scale by the largest component first: squares of tiny components underflow, and a
    // subnormal norm has too few bits to divide by.
    let m = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    if (1e-150..=1e150).contains(&m) {
        // The common case: one rounding per component.
        let n = x.iter().map(|a| a * a).sum::<f64>().sqrt();
        x.iter_mut().for_each(|a| *a /= n);
        return n;
    }
    x.iter_mut().for_each(|a| *a /= m);
    let k = x.iter().map(|a| a * a).sum::<f64>().sqrt();
    x.iter_mut().for_each(|a| *a /= k);
    m * k
}

/// Returns an orthonormal pair (u, v) with P = u∧v for a unit simple bivector P: u is the
/// largest column of \[P\] normalised, and v = −\[P\] u.
pub(crate) fn unit_plane_vectors(n: usize, p: &[f64]) -> (SmallVec<[f64; 8]>, SmallVec<[f64; 8]>) {
    let entry = |i: usize, j: usize| -> f64 {
        match i.cmp(&j) {
            std::cmp::Ordering::Less => p[super::bivector::pair_index(n, i, j)],
            std::cmp::Ordering::Greater => -p[super::bivector::pair_index(n, j, i)],
            std::cmp::Ordering::Equal => 0.0,
        }
    };
    let mut best = 0;
    let mut best_norm = -1.0;
    for k in 0..n {
        let s: f64 = (0..n).map(|i| entry(i, k).powi(2)).sum();
        if s > best_norm {
            best_norm = s;
            best = k;
        }
    }
    let mut u: SmallVec<[f64; 8]> = (0..n).map(|i| entry(i, best)).collect();
    normalize_in_place(&mut u);
    let mut v: SmallVec<[f64; 8]> = (0..n)
        .map(|i| -(0..n).map(|j| entry(i, j) * u[j]).sum::<f64>())
        .collect();
    let d: f64 = v.iter().zip(u.iter()).map(|(a, b)| a * b).sum();
    v.iter_mut().zip(u.iter()).for_each(|(x, b)| *x -= d * b);
    normalize_in_place(&mut v);
    (u, v)
}

/// Deflation for N ≥ 5 (see the module documentation), on matrices held inline up to N = 8
/// (they spill to the heap above).
// Kept out of line: its inline matrices would enlarge the stack frame of the small cases.
#[inline(never)]
fn planes_deflation(n: usize, comps: &[f64]) -> Planes {
    let mut a = Mat8::zeros(n, n);
    for ((i, j), &c) in pairs(n).zip(comps.iter()) {
        a[(i, j)] = c;
        a[(j, i)] = -c;
    }
    let mut basis = Mat8::identity(n);
    let mut out = Planes::new();
    let mut level_exp = 0i32; // a = 2^level_exp · (restriction of the scaled input)
    loop {
        let m = a.ncols();
        let scale = a.amax();
        if scale == 0.0 {
            break;
        }
        // Rescale each level so that the small planes keep full relative precision.
        let e = exponent_of(scale);
        if e != 0 {
            a = Mat8::from_fn(m, m, |i, j| ldexp(a[(i, j)], -e));
            level_exp -= e;
        }
        if m <= 4 {
            let packed: SmallVec<[f64; 6]> = pairs(m).map(|(i, j)| a[(i, j)]).collect();
            let local = match m {
                2 => plane_2d(&packed),
                3 => plane_3d(&packed),
                4 => planes_4d(&packed),
                _ => Planes::new(),
            };
            for p in local {
                out.push(lift(&basis, &p, level_exp));
            }
            break;
        }
        let s = a.transpose().mul(&a);
        let (eigenvalues, eigenvectors) = s.symmetric_eigen();
        let top = eigenvalues
            .iter()
            .enumerate()
            .max_by(|x, y| x.1.total_cmp(y.1))
            .map(|(i, _)| i)
            .unwrap_or(0);
        let w: Vec8 = SmallVec::from_slice(eigenvectors.column(top));
        let x = a.mul_vec(&w);
        let theta = dense::norm(&x);
        if theta == 0.0 {
            break;
        }
        let mut u: Vec8 = x.iter().map(|c| c / theta).collect();
        let d = dense::dot(&u, &w);
        u.iter_mut().zip(&w).for_each(|(ui, wi)| *ui -= wi * d);
        let nu = dense::norm(&u);
        u.iter_mut().for_each(|c| *c /= nu);
        out.push(lift(
            &basis,
            &RawPlane {
                theta,
                u: u.clone(),
                v: w.clone(),
            },
            level_exp,
        ));
        let h = householder_complement(&w, &u);
        a = h.transpose().mul(&a).mul(&h);
        basis = basis.mul(&h);
    }
    out
}

/// Maps a plane found in the coordinates of `basis` back to ℝᴺ and undoes the level scaling.
fn lift(basis: &Mat8, p: &RawPlane, level_exp: i32) -> RawPlane {
    RawPlane {
        theta: ldexp(p.theta, -level_exp),
        u: basis.mul_vec(&p.u),
        v: basis.mul_vec(&p.v),
    }
}
